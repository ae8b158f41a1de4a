"""Bit-rock end (BitRockEnd): second-order convergence against Lundberg's closed form, single steps against hand
calculations, work consistent with the continuous bilinear law, compiled and numpy paths agree.

Closed form (rectangular wave into a bilinear rock; derived here, Lundberg's drilling efficiency). A rod of
impedance Z carries an incident compressive wave of force F_I < 0 and duration T towards a right end pressed
against rock: the end force is N = 2 F_I + Z w (w = outward end velocity = penetration rate, the element side
of the end, eqs. 3.17/3.19 with a = N - Z v = 2 F_I) and N = -k1 delta while loading. Hence
Z delta' + k1 delta = -2 F_I, delta(t) = (2 |F_I| / k1) (1 - exp(-k1 t / Z)), and delta keeps growing until
t = T, when the incident wave ends: delta_max = (2 |F_I| / k1) (1 - exp(-x)), x = k1 T / Z. Afterwards a = 0,
Z w = -F < 0: the rock unloads along slope k2 to the release point and gives back (k1 delta_max)^2 / (2 k2).
Energy into the rock k1 delta_max^2 / 2 (1 - k1/k2); incident energy F_I^2 T / Z. Efficiency

    eta(x) = 2 (1 - exp(-x))^2 / x * (1 - k1 / k2),

which for k2 >> k1 is the usual 2 (1 - exp(-x))^2 / x (maximum 0.8145 at x = 1.2564).
"""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct.boundary import BITROCK, end_solve

Z = 4e4          # N s/m
F_I = -1e5       # N, incident force
T = 1e-4         # s, pulse duration


def closed_form(x, k2_over_k1):
    return 2.0 * (1.0 - np.exp(-x)) ** 2 / x * (1.0 - 1.0 / k2_over_k1)


def pulse_into_rock(x, k2_over_k1, n, backend="numba"):
    """A uniform rod of 1.5 n + 5 elements (dt = T / n), the rectangular wave F_I for T entering at the left end
    (prescribed force, free afterwards), rock at the right end; simulated until the rock has unloaded and
    before the wave reflected at the rock comes back to it."""
    dt = T / n
    k1 = x * Z / T
    n_el = int(1.5 * n) + 5
    rod = ri.Rod.from_impedance(np.full(n_el, Z), dt=dt)
    return ri.simulate(ri.System([rod], [0.0], left=ri.ForceEnd(lambda t: np.where(t < T, F_I, 0.0)),
                                 right=ri.BitRockEnd(k1, k2_over_k1 * k1)), steps=n_el + 3 * n, backend=backend)


@pytest.mark.parametrize("x", [0.5, 1.2564, 2.0])
@pytest.mark.parametrize("k2_over_k1", [20.0, 1e4])
def test_efficiency_converges_at_second_order(x, k2_over_k1):
    ns = np.array([100, 200, 400, 800])
    errors = []
    for n in ns:
        r = pulse_into_rock(x, k2_over_k1, int(n))
        into_rock = -r.energy.work_right[-1]
        eta = into_rock / (F_I ** 2 * T / Z)
        errors.append(abs(eta / closed_form(x, k2_over_k1) - 1.0))
    order = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert order >= 1.9
    assert errors[0] < 1e-4          # the first-order scheme was 0.1-1 % off at 100 elements per pulse


def bilinear_work(delta, delta_max, k1, k2):
    """Work done on a bilinear rock that has reached delta_max and now sits at delta (a state function): the
    virgin work k1 delta_max^2 / 2 minus the energy the unloading line gives back from delta_max to the
    present force F, (k1 delta_max)^2 / (2 k2) - F^2 / (2 k2)."""
    force = max(k1 * delta_max + k2 * (delta - delta_max), 0.0)
    return 0.5 * k1 * delta_max ** 2 - (k1 * delta_max) ** 2 / (2.0 * k2) + force ** 2 / (2.0 * k2)


@pytest.mark.parametrize("n", [7, 40])
def test_work_at_the_rock_is_that_of_the_continuous_law(n):
    """A striker hitting a drill rod on rock (load, unload, release, reload several times, reversals inside
    steps): the work the end does on the rods equals minus the work of the bilinear law along the end's
    piecewise-linear path, to rounding, at any resolution; and the energy balance closes."""
    dt = T / n
    k1, k2 = 1.5 * Z / T, 4.5 * Z / T
    striker = ri.Rod.from_impedance(np.full(n, 2.0 * Z), dt=dt)
    rod = ri.Rod.from_impedance(np.full(3 * n, Z), dt=dt)
    r = ri.simulate(ri.System([striker, rod], [8.0, 0.0], right=ri.BitRockEnd(k1, k2), junctions=[ri.Bonded()]),
                    steps=40 * n)
    w = r.end_velocity["right"]
    delta = np.concatenate([[0.0], np.cumsum(w * dt)])
    delta_max = float(np.max(delta))
    assert np.sum(np.diff(np.sign(w[np.abs(w) > 1e-9 * np.max(np.abs(w))])) != 0) >= 3   # several reversals
    expected = bilinear_work(delta[-1], delta_max, k1, k2)
    work = -float(np.sum(r.end_force["right"] * w) * dt)
    assert work == pytest.approx(expected, rel=1e-11)
    assert -r.energy.work_right[-1] == pytest.approx(expected, rel=1e-11)
    assert r.energy.balance_error < 1e-12


# single steps, z = 1 N s/m, k1 = 1 N/m, k2 = 4 N/m, largest penetration 1 m: release point r = 1 - 1/4 = 0.75 m.
# Each case prescribes the path delta -> delta + s (dt = 1 s unless given), integrates the bilinear force F by
# hand over it (J = int F), and sets a = -z s/dt - J/s so that a + z w + J/s = 0 with w = s/dt; expected N = -J/s.
HAND = {
    # virgin loading 1 -> 5 with dt = 2: J = (25 - 1)/2 = 12, mean 3, a = -2 - 3
    "virgin loading": dict(a=-5.0, delta=1.0, dt=2.0, w=2.0, n=-3.0, dmax=5.0),
    # reloading 0.5 -> 3: released to 0.75, k2 line to 1 (J = 4 * 0.25^2 / 2 = 0.125), virgin to 3 (J = 4);
    # mean 4.125 / 2.5 = 1.65, a = -2.5 - 1.65
    "released, reloading, virgin in one step": dict(a=-4.15, delta=0.5, dt=1.0, w=2.5, n=-1.65, dmax=3.0),
    # reloading 0.5 -> 0.9: J = 4 * 0.15^2 / 2 = 0.045, mean 0.1125, a = -0.4 - 0.1125
    "released then reloading": dict(a=-0.5125, delta=0.5, dt=1.0, w=0.4, n=-0.1125, dmax=1.0),
    # unloading 1 -> 0.9 along k2: F from 1 to 0.6, mean 0.8, a = 0.1 - 0.8
    "unloading": dict(a=-0.7, delta=1.0, dt=1.0, w=-0.1, n=-0.8, dmax=1.0),
    # unloading 1 -> 0.5 through the release point: J = -0.125, mean 0.25, a = 0.5 - 0.25
    "unloading and release": dict(a=0.25, delta=1.0, dt=1.0, w=-0.5, n=-0.25, dmax=1.0),
    # released, moving out 0.5 -> 0.2 and in 0.5 -> 0.6: no force, w = -a / z
    "released moving out": dict(a=0.3, delta=0.5, dt=1.0, w=-0.3, n=0.0, dmax=1.0),
    "released moving in": dict(a=-0.1, delta=0.5, dt=1.0, w=0.1, n=0.0, dmax=1.0),
}


@pytest.mark.parametrize("case", sorted(HAND))
@pytest.mark.parametrize("compiled", [True, False])
def test_single_step_against_hand_calculation(case, compiled):
    c = HAND[case]
    solve = end_solve if compiled else end_solve.py_func
    w, n, dmax = solve(BITROCK, c["a"], 1.0, 0.0, 1.0, 4.0, c["delta"], 1.0, c["dt"])
    assert w == pytest.approx(c["w"], rel=1e-12, abs=1e-15)
    assert n == pytest.approx(c["n"], rel=1e-12, abs=1e-15)
    assert dmax == pytest.approx(c["dmax"], rel=1e-15)


def test_numba_and_numpy_agree():
    """Bit-rock at both ends (the left end moves outwards to the left), reversals inside steps."""
    dt = T / 30
    k1 = 1.2 * Z / T
    striker = ri.Rod.from_impedance(np.full(30, 1.5 * Z), dt=dt)
    rod = ri.Rod.from_impedance(np.linspace(Z, 2 * Z, 70), dt=dt)
    system = ri.System([striker, rod], [6.0, -1.0], left=ri.BitRockEnd(0.3 * k1, 2 * k1),
                       right=ri.BitRockEnd(k1, 3 * k1), junctions=[ri.Contact()])
    fast = ri.simulate(system, steps=1500, backend="numba")
    ref = ri.simulate(system, steps=1500, backend="numpy")
    scale = 2 * Z * 6.0
    for side in ("left", "right"):
        assert np.max(np.abs(fast.end_force[side])) > 0.05 * scale          # both rocks are loaded
        np.testing.assert_allclose(fast.end_force[side], ref.end_force[side], rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(fast.end_velocity[side], ref.end_velocity[side], rtol=0, atol=1e-12 * 6.0)
    np.testing.assert_allclose(fast.junction_force, ref.junction_force, rtol=0, atol=1e-12 * scale)
    assert fast.energy.balance_error < 1e-12
