"""The spring-and-dashpot joint between two rods (``SpringDashpot``, issue 21): closed forms, measured
convergence order, energy balance, compression only, the numpy twin, model files and refusals.

Closed forms (two identical semi-infinite bars of impedance Z joined by the joint, a rectangular incident force
F_i arriving at t = 0; mu = 2/Z, s0 = -2 F_i / Z the closing rate of the free faces):
  spring k:            N(t) = F_i (1 - exp(-2 k t / Z))
  spring k, dashpot c: N(t) = -(k delta + c s), delta = (s0 / (k mu)) (1 - exp(-lambda t)),
                       s = d delta/dt, lambda = k mu / (1 + c mu)
  dashpot c alone:     N = -c s0 / (1 + c mu), constant (the scheme is exact: to rounding)
"""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri

Z, C, F_I, L = 40e3, 5000.0, -10e3, 0.2


def _run(joint, n: int, backend: str = "numba", force: float = F_I):
    """Incident bar (force end F_i, the wave reaches the joint after n steps), joint, transmitted bar
    (non-reflecting): two semi-infinite bars for 2 n steps."""
    dt = L / C / n
    bars = [ri.Rod.from_impedance(np.full(n, Z), dt=dt, wave_speed=C, name=name) for name in ("in", "out")]
    system = ri.System(bars, [0.0, 0.0], [joint], ri.ForceEnd(force), "nonreflecting")
    res = ri.simulate(ri.Problem.of(system, steps=2 * n, dt=dt), backend=backend)
    t = res.time - n * dt + 0.5 * dt       # the force of step k acts at its midpoint (trapezoidal law)
    after = t > 0
    return t[after], res.contact_force[after], res


def _spring_dashpot(t: np.ndarray, k: float, c: float, f: float = F_I) -> np.ndarray:
    mu, s0 = 2.0 / Z, -2.0 * f / Z
    lam = k * mu / (1.0 + c * mu)
    delta = s0 / (k * mu) * (1.0 - np.exp(-lam * t))
    rate = s0 / (k * mu) * lam * np.exp(-lam * t)
    return -(k * delta + c * rate)


@pytest.mark.parametrize("k, c", [(2e8, 0.0), (3e8, 15e3)])
def test_closed_form_with_second_order_convergence(k: float, c: float) -> None:
    errors = []
    for n in (50, 100, 200, 400):
        t, force, _ = _run(ri.SpringDashpot(k, c), n)
        errors.append(np.abs(force - _spring_dashpot(t, k, c)).max() / abs(F_I))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 1.95), (errors, orders)       # measured: 1.995 .. 1.9994 (trapezoidal rule)
    assert errors[-1] < 2e-6


def test_the_spring_only_form_is_the_textbook_one() -> None:
    # the SHPB closed form of an elastic specimen, N = F_i (1 - exp(-2 k t / Z)), independently of the helper
    t, force, _ = _run(ri.SpringDashpot(2e8), 400)
    assert np.abs(force - F_I * (1.0 - np.exp(-2 * 2e8 * t / Z))).max() < 2e-6 * abs(F_I)


def test_a_dashpot_alone_is_exact() -> None:
    c = 25e3
    _, force, _ = _run(ri.SpringDashpot(0.0, c), 60)
    expected = -c * (-2.0 * F_I / Z) / (1.0 + 2.0 * c / Z)
    assert np.abs(force - expected).max() <= 1e-12 * abs(expected)


def test_energy_balance_closes_and_the_joint_absorbs() -> None:
    k, c = 3e8, 15e3
    *_, res = _run(ri.SpringDashpot(k, c), 200)
    e = res.energy
    assert e.balance_error < 1e-13
    assert e.work_joints[-1] < 0.0                       # a passive joint takes energy out of the rods
    # what it took is its spring energy k delta^2 / 2 plus the dashpot's dissipation, step by step
    n = 200
    dt = L / C / n
    s = -np.diff(np.concatenate([[0.0], _gap(res)]))
    delta = np.cumsum(s)
    rate = s / dt
    dissipated = c * np.sum(rate * rate) * dt
    assert -e.work_joints[-1] == pytest.approx(0.5 * k * delta[-1] ** 2 + dissipated, rel=1e-10)


def _gap(res) -> np.ndarray:
    """The joint's closing per step from the two face velocities (u_end of the rods is not recorded per step):
    shortening increments s dt with s = V_right face of rod 0 - V_left face of rod 1, from the node forces."""
    n = res.lattice.rod_start[1]
    force = res.junction_force[0]
    # V_a = va_free + N / Z, V_b = vb_free - N / Z with va_free = -2 F_i / Z once the wave is there, vb_free = 0
    arrived = np.arange(force.size) >= n
    s = np.where(arrived, -2.0 * F_I / Z + 2.0 * force / Z, 0.0)
    return -np.cumsum(s * res.dt)


def test_compression_only_joint_does_not_pull() -> None:
    _, pulled, res = _run(ri.SpringDashpot(2e8, compression_only=True), 100, force=-F_I)
    assert np.all(pulled == 0.0)
    assert np.all(res.junction_contact[0] == 0.0)
    _, pushed, _ = _run(ri.SpringDashpot(2e8, compression_only=True), 100)
    _, bidirectional, _ = _run(ri.SpringDashpot(2e8), 100)
    assert np.array_equal(pushed, bidirectional)         # in compression it is the same law
    _, pulled_both, _ = _run(ri.SpringDashpot(2e8), 100, force=-F_I)
    assert np.allclose(pulled_both, -bidirectional, rtol=1e-14, atol=0.0)   # the bidirectional joint pulls


def test_numpy_twin_agrees() -> None:
    joint = ri.SpringDashpot(3e8, 15e3)
    _, a, _ = _run(joint, 100, "numba")
    _, b, _ = _run(joint, 100, "numpy")
    assert np.abs(a - b).max() <= 1e-12 * abs(F_I)


@pytest.mark.parametrize("kwargs, message", [
    ({"stiffness": -1.0}, "SpringDashpot.stiffness: must be >= 0"),
    ({"stiffness": 1e8, "damping": -5.0}, "SpringDashpot.damping: must be >= 0"),
    ({"stiffness": float("nan")}, "SpringDashpot.stiffness: must be finite"),
])
def test_physically_impossible_joints_are_refused(kwargs: dict, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        ri.SpringDashpot(**kwargs)


def test_compression_only_must_be_a_bool() -> None:
    with pytest.raises(TypeError, match="SpringDashpot.compression_only: must be True or False"):
        ri.SpringDashpot(1e8, compression_only="yes")


def test_design_refuses_a_joint_it_cannot_differentiate() -> None:
    from rodimpact.design._adjoint import ImpactProblem

    dt = 1e-6
    bars = [ri.Rod.from_impedance(np.full(50, Z), dt=dt), ri.Rod.from_impedance(np.full(50, Z), dt=dt)]
    struck = ri.System(bars, [0.0, 0.0], [ri.SpringDashpot(1e8)], "free", "nonreflecting")
    with pytest.raises(ValueError, match=r"junctions\[0\].*SpringDashpot"):
        ImpactProblem(struck, dt, 20, 100)
