"""Transformation of a force prescribed inside the struck system into the impact force (thesis Sec. 4.1.2)."""

import numpy as np
import pytest
from scipy.linalg import solve_triangular, toeplitz

import rodimpact as ri
from rodimpact.inverse import transform_force
from rodimpact.inverse._toeplitz import solve_lower_toeplitz
from rodimpact.inverse.struck import driven

DT = 1e-6
C = ri.STEEL.wave_speed


def test_toeplitz_solvers_against_dense_triangular_solve():
    rng = np.random.default_rng(0)
    n = 300
    k = np.arange(n)
    g = np.exp(-k / 40.0) * np.cos(k / 5.0)
    g[0] = 1.3
    y = rng.standard_normal(n)
    dense = solve_triangular(toeplitz(g, np.zeros(n)), y, lower=True)
    np.testing.assert_allclose(solve_lower_toeplitz(g, y, "substitution"), dense, rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(solve_lower_toeplitz(g, y, "fft"), dense, rtol=1e-11, atol=1e-12)


def test_fft_solver_large_n_residual():
    rng = np.random.default_rng(1)
    n = 20000
    g = 0.4 * np.exp(-np.arange(n) / 300.0) * np.sin(np.arange(n) / 17.0)
    g[0] = 1.0
    x = rng.standard_normal(n)
    y = np.convolve(g, x)[:n]
    np.testing.assert_allclose(solve_lower_toeplitz(g, y, "fft"), x, atol=1e-10)
    np.testing.assert_allclose(solve_lower_toeplitz(g[:3000], y[:3000], "substitution"), x[:3000], atol=1e-10)


def _stepped_struck():
    return [ri.Rod.from_impedance([6e4] * 6 + [1.1e5] * 4, DT), ri.Rod.from_impedance([8e4] * 12, DT)]


def _forward(system, x_windows, location, steps, quantity):
    """Quantity at the node from a direct simulation driven by x_windows (independent of the transform)."""
    sim = ri.simulate(driven(system, x_windows, DT), steps=steps, dt=DT,
                      outputs=ri.Outputs(probes=[ri.Probe("p", location[0], location[1])], snapshot_times=[0.0]))
    p = sim.probe("p")
    if quantity == "force":
        return p.force
    a = location[2]
    n0, v0 = sim.snapshots.force[a, 0], sim.snapshots.velocity[a, 0]
    return 0.5 * ((p.force - n0) - sim.lattice.impedance[a] * (p.velocity - v0))


@pytest.mark.parametrize("quantity", ["force", "incident"])
@pytest.mark.parametrize("moving", [False, True])
def test_round_trip_through_the_struck_system(quantity, moving):
    """X -> direct solver -> quantity at p (window starts after the dead time) -> transform -> X."""
    rng = np.random.default_rng(2)
    n = 40
    x = -1e5 * (1 + 0.3 * rng.random(n))
    kw = dict(far_end=ri.SpringEnd(4e8), velocity=0.0)
    if moving:
        kw.update(far_end="fixed", velocity=[0.3, -0.2],
                  loads=[ri.NodalForce(1, 4 * C * DT, lambda t: -3e4 * (t > 5e-6))])
    system = ri.System.struck(_stepped_struck(), **kw)
    p_node = 14                                      # node 4 of rod 1: 14 elements from the impact face
    loc = (1, 4 * C * DT, 13)
    q = _forward(system, x, loc, p_node + 2 * n, quantity)
    y = q[p_node + 2 * np.arange(n)]
    tr = transform_force(y, system, position=14 * C * DT, dt=DT, quantity=quantity)
    assert tr.location.node == p_node and tr.dead_time == pytest.approx(14 * DT)
    np.testing.assert_allclose(tr.impact_force, x, rtol=1e-11)
    assert tr.residual < 1e-13
    assert np.any(tr.free_response != 0) == moving


def test_position_snaps_to_the_nearest_node():
    tr = transform_force(-np.ones(5) * 1e5, _stepped_struck(), position=14.3 * C * DT, dt=DT)
    assert tr.location.node == 14
    assert tr.location.used == pytest.approx(14 * C * DT)
    assert tr.location.requested == pytest.approx(14.3 * C * DT)


def test_transform_errors():
    with pytest.raises(ValueError, match="quantity: must be one of"):
        transform_force(-np.ones(5), _stepped_struck(), position=0.05, dt=DT, quantity="stress")
    with pytest.raises(ValueError, match="position: must lie within the struck system"):
        transform_force(-np.ones(5), _stepped_struck(), position=1.0, dt=DT)
    with pytest.raises(ValueError, match="position = 0 is the impact face"):
        transform_force(-np.ones(5), _stepped_struck(), position=0.0, dt=DT, quantity="incident")
    with pytest.raises(ValueError, match="position: must be >= 0"):
        transform_force(-np.ones(5), _stepped_struck(), position=-0.1, dt=DT)
