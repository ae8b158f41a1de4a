"""Discretisation of geometry-based rods: reports, exactness of impedance-level rods and measured convergence
order of a continuous taper against the closed-form solution of the non-dispersive quadratic horn."""

import math

import numpy as np
import pytest

import rodimpact as ri

E, RHO = 210e9, 7840.0
C = math.sqrt(E / RHO)


def test_impedance_rods_are_taken_exactly_and_refined_by_integer_factors():
    z = np.array([3e4, 5e4, 4e4])
    rod = ri.Rod.from_impedance(z, dt=2e-6)
    sys1 = ri.System([rod], velocities=[0.0])
    lat = ri.build_lattice(sys1, 1e-6)
    np.testing.assert_array_equal(lat.impedance, np.repeat(z, 2))
    assert lat.rods[0].exact


def test_report_states_length_mass_and_time_errors():
    rod = ri.Rod([ri.Cylinder(0.3, 0.05), ri.Cone(0.2, 0.05, 0.04)])
    dt = rod.total_travel_time / 37.4
    lat = ri.build_lattice(ri.System([rod], velocities=[0.0]), dt)
    r = lat.rods[0]
    assert r.n_elements == 37
    assert r.time_scale == pytest.approx(37 / 37.4, rel=1e-12)
    assert lat.element_length.sum() == pytest.approx(rod.length, rel=1e-14)
    # element impedances are travel-time averages of Z: the true mass is conserved exactly
    assert np.sum(lat.impedance * rod.total_travel_time / 37) == pytest.approx(rod.mass, rel=1e-12)
    text = lat.report()
    assert "37 elements" in text and "mass" in text and "time scale" in text


def _cone_errors(n_list, xp=0.5, length=1.0, d0=0.03, d1=0.06, v0=2.0):
    """Max relative error of the end force and of the force at xp for a cone (A = A0 (1 + xi x)^2, the
    non-dispersive family of thesis Tab. 2.1) pulled at its left end with a velocity step -v0.

    Closed form (outgoing wave u = f(t - x/c)/(1 + xi x), f' = -v0):
    N(x, t) = E A0 v0 [(1 + xi x)/c + xi (t - x/c)] for t > x/c, valid until the reflection from the far end.
    """
    a0 = math.pi / 4 * d0**2
    xi = (d1 / d0 - 1) / length
    rod = ri.Rod([ri.Cone(length, d0, d1)])
    t_rod = length / C
    errs = []
    for n in n_list:
        dt = t_rod / n
        res = ri.simulate(ri.System([rod], [0.0], left=ri.VelocityEnd(-v0)), steps=int(1.8 * n), dt=dt,
                          outputs=ri.Outputs(probes=[ri.Probe("p", 0, xp)]))
        t = res.time + 0.5 * dt
        exact_end = E * a0 * v0 * (1 / C + xi * t)
        tau = t - xp / C
        ok = (tau > 2 * dt) & (t < (2 * length - xp) / C - dt)
        exact_p = E * a0 * v0 * ((1 + xi * xp) / C + xi * tau[ok])
        errs.append((np.max(np.abs(res.end_force["left"] - exact_end)) / np.max(exact_end),
                     np.max(np.abs(res.probe("p").force[ok] - exact_p)) / np.max(exact_p)))
    return np.array(errs)


def test_continuous_taper_converges_first_order():
    n_list = np.array([50, 100, 200, 400, 800])
    errs = _cone_errors(n_list)
    for col in range(2):
        order = -np.polyfit(np.log(n_list), np.log(errs[:, col]), 1)[0]
        assert 0.9 < order < 1.1, (col, order, errs[:, col])
    assert errs[-1, 0] < 3e-4 and errs[-1, 1] < 3e-4


def test_time_step_from_elements_or_resolution():
    rod = ri.Rod([ri.Cylinder(0.5, 0.05)])
    striker = ri.Rod([ri.Cylinder(0.2, 0.04)])
    res = ri.simulate(ri.Problem.of([striker, rod], [1.0, 0.0], steps=5, elements=(1, 100)))
    assert res.dt == pytest.approx(0.5 / C / 100, rel=1e-14)
    assert res.lattice.rods[1].n_elements == 100 and res.lattice.rods[0].n_elements == 40
    res = ri.simulate(ri.Problem.of([striker, rod], [1.0, 0.0], steps=5, resolution=2e-3))
    assert res.dt == pytest.approx(2e-3 / C, rel=1e-14)
    assert np.max(res.lattice.element_length) <= 2e-3 * (1 + 1e-12)
    with pytest.raises(ValueError, match="give only one of"):
        ri.simulate(ri.Problem.of([rod], [1.0], steps=5, dt=1e-6, resolution=1e-3))
