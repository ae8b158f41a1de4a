"""Energy and momentum bookkeeping, linearity and time reversal (property-based where it is cheap)."""

import numpy as np
import pytest
from hypothesis import given, strategies as st

import rodimpact as ri

DT = 1e-6


def random_rod(draw_z):
    return ri.Rod.from_impedance(draw_z, dt=DT)


impedances = st.lists(st.floats(5e3, 2e5), min_size=3, max_size=40)


def test_energy_conserved_over_1e5_steps():
    """Free-free impact with repeated contact phases, a bonded joint and a spring end that stores energy
    without loss: total energy constant to 1e-12 relative over 10^5 steps (spring energy accounted as work)."""
    striker = ri.Rod.from_impedance([60e3] * 30 + [20e3] * 30 + [90e3] * 20, dt=DT)
    middle = ri.Rod.from_impedance(np.linspace(40e3, 80e3, 70), dt=DT)
    bar = ri.Rod.from_impedance([50e3] * 150, dt=DT)
    res = ri.simulate(ri.System([striker, middle, bar], [6.0, 0.0, -1.0], junctions=[ri.Contact(), ri.Bonded()]),
                      steps=100_000, outputs=ri.Outputs(energy_every=97))
    assert res.energy.balance_error < 1e-12
    free = ri.simulate([striker, bar], velocities=[6.0, 0.0], steps=100_000)
    total = free.energy.total
    assert np.max(np.abs(total - total[0])) / total[0] < 1e-12


def test_momentum_balance_with_end_force_loads_and_friction():
    bar = ri.Rod.from_impedance(np.linspace(30e3, 70e3, 120), dt=DT)
    striker = ri.Rod.from_impedance([45e3] * 40, dt=DT)
    res = ri.simulate(ri.System(
        [striker, bar], [3.0, 0.0],
        right=ri.ForceEnd(lambda t: -2e3 * np.sin(2e4 * t)),
        loads=[ri.NodalForce(1, 0.2, lambda t: 500.0 * np.cos(3e4 * t)),
               ri.Bearings(1, [(0.05, 0.15), (0.3, 0.5)], friction_coefficient=0.3, normal_load=2e4)]),
        steps=3000, outputs=ri.Outputs(energy_every=7))
    e = res.energy
    p = e.momentum.sum(axis=0)
    scale = 45e3 * 40 * DT * 3.0
    np.testing.assert_allclose(p - p[0], e.impulse, rtol=0, atol=1e-12 * scale)
    assert e.balance_error < 1e-12
    assert np.all(np.diff(e.work_friction) <= 1e-15)     # friction never gives energy back


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_momentum_balance_with_the_left_end_loaded(backend):
    """The impulse of a force on the left end (issue 20, item 22: every other momentum balance loads only the
    right end, and a flipped sign of the left end's impulse survived). The end face's outward normal is -x, so the
    force on the rod is -N: a push N = -1 kN on a free rod at rest gives it the momentum 1 kN * t (Newton)."""
    bar = ri.Rod.from_impedance(np.linspace(30e3, 70e3, 60), dt=DT)
    every7 = ri.Outputs(energy_every=7)
    e = ri.simulate(ri.System([bar], [0.0], left=ri.ForceEnd(-1e3)), steps=400, outputs=every7,
                    backend=backend).energy
    assert e.time[-1] > 0.3e-3
    np.testing.assert_allclose(e.impulse, 1e3 * e.time, rtol=0, atol=1e-12)
    np.testing.assert_allclose(e.momentum.sum(axis=0), 1e3 * e.time, rtol=0, atol=1e-12)
    # both ends loaded by varying forces, a striker on the bar
    striker = ri.Rod.from_impedance([45e3] * 40, dt=DT)
    system = ri.System([striker, bar], [3.0, 0.0], left=ri.ForceEnd(lambda t: -4e3 * np.sin(1.3e4 * t) ** 2),
                       right=ri.ForceEnd(lambda t: -2e3 * np.sin(2e4 * t)))
    res = ri.simulate(system, steps=900, outputs=every7, backend=backend)
    p = res.energy.momentum.sum(axis=0)
    scale = 45e3 * 40 * DT * 3.0
    assert np.ptp(res.energy.impulse) > 0.1 * scale
    np.testing.assert_allclose(p - p[0], res.energy.impulse, rtol=0, atol=1e-12 * scale)
    assert res.energy.balance_error < 1e-12


@given(z1=impedances, z2=impedances, v=st.floats(0.1, 20.0), a=st.floats(-5.0, 5.0).filter(lambda x: abs(x) > 0.05))
def test_linear_scaling_with_velocity(z1, z2, v, a):
    """Without friction the response is linear in the impact velocity (as long as a > 0 keeps the same
    contact pattern; for a < 0 the rods move apart and never touch)."""
    rods = [random_rod(z1), random_rod(z2)]
    r1 = ri.simulate(ri.System(rods, [v, 0.0], right="nonreflecting"), steps=300)
    r2 = ri.simulate(ri.System(rods, [a * v, 0.0], right="nonreflecting"), steps=300)
    if a > 0:
        np.testing.assert_allclose(r2.contact_force, a * r1.contact_force, rtol=0,
                                   atol=1e-11 * np.max(np.abs(r1.contact_force)))
    else:
        assert not r2.junction_contact.any()
        assert np.all(r2.contact_force == 0.0)


@given(z=st.lists(st.floats(5e3, 2e5), min_size=4, max_size=60), steps=st.integers(1, 400),
       left=st.sampled_from(["free", "fixed"]), right=st.sampled_from(["free", "fixed"]))
def test_time_reversal_of_lossless_lattice(z, steps, left, right):
    """Run forward, reverse all velocities, run the same number of steps: the initial state returns."""
    rod = ri.Rod.from_impedance(z, dt=DT)
    rng = np.random.default_rng(len(z) + steps)
    n0 = rng.normal(size=len(z)) * 1e3
    v0 = rng.normal(size=len(z))
    fwd = ri.simulate(ri.System([rod], [0.0], left=left, right=right, initial=[ri.InitialState(force=n0, velocity=v0)]),
                      steps=steps)
    back = ri.simulate(ri.System([rod], [0.0], left=left, right=right,
                                 initial=[ri.InitialState(force=fwd.final_force, velocity=-fwd.final_velocity)]),
                       steps=steps)
    np.testing.assert_allclose(back.final_force, n0, rtol=0, atol=1e-9 * np.max(np.abs(n0)))
    np.testing.assert_allclose(-back.final_velocity, v0, rtol=0, atol=1e-9 * np.max(np.abs(v0)))


def test_friction_linear_energy_decay_over_100_round_trips():
    """Thesis Fig. 3.9: with bearing friction the total energy decays (nearly) linearly over 100 round trips;
    without friction it stays constant. Friction work matches the energy loss exactly."""
    a0, a1 = 1.26e-3, 1.96e-3
    d0, d1 = np.sqrt(4 * a0 / np.pi), np.sqrt(4 * a1 / np.pi)
    rod1 = ri.Rod([ri.Cylinder(0.4, d0)])
    rod2 = ri.Rod([ri.Cylinder(0.1, d0), ri.LinearAreaTaper(0.1, a0, a1), ri.Cylinder(0.3, d1),
                   ri.Cylinder(0.6, d1), ri.Cylinder(0.3, d1), ri.LinearAreaTaper(0.1, a1, a0)])
    t_rod2 = rod2.total_travel_time
    duration = 100 * 2 * t_rod2
    bearings = ri.Bearings(1, [(0.2, 0.5), (1.1, 1.4)], friction_coefficient=0.3)
    kw = dict(duration=duration, dt=t_rod2 / 300, outputs=ri.Outputs(energy_every=200))
    with_f = ri.simulate(ri.System([rod1, rod2], [3.0, -3.0], loads=[bearings]), **kw)
    without = ri.simulate([rod1, rod2], [3.0, -3.0], **kw)
    e0 = without.energy.total
    assert np.max(np.abs(e0 - e0[0])) / e0[0] < 1e-12
    e = with_f.energy
    assert e.balance_error < 1e-12
    total = e.total
    loss = total[0] - total[-1]
    assert loss > 0.01 * total[0]                        # friction matters in the long run (thesis Fig. 3.9)
    assert np.all(np.diff(total) <= 1e-12 * total[0])    # and never gives energy back
    # linear decay: a straight-line fit follows the curve to within 5 % of the total loss
    fit = np.polyval(np.polyfit(e.time, total, 1), e.time)
    assert np.max(np.abs(fit - total)) < 0.05 * loss


def test_friction_stops_a_sliding_rod_without_chatter_or_energy_gain():
    """A free rod sliding at v0 in a bearing over its whole length: while every node slides, the momentum falls
    exactly as m v0 - F_R t (Coulomb, thesis eqs. 3.22-3.23); the rod stops at t = m v0 / F_R and then stays
    at rest: nodes stick (no sign chatter), the energy never increases and stays constant once stuck."""
    rod = ri.Rod.from_impedance([4e4] * 50, dt=DT)
    m, v0, f_r = 4e4 * 50 * DT, 0.3, 0.5 * 2e4
    res = ri.simulate(ri.System([rod], [v0],
                                loads=[ri.Bearings(0, [(0.0, rod.length)], friction_coefficient=0.5, normal_load=2e4)]),
                      steps=3000, outputs=ri.Outputs(energy_every=1))
    e = res.energy
    p, t, total = e.momentum[0], e.time, e.total
    t_stop = m * v0 / f_r
    sliding = t < 0.9 * t_stop
    np.testing.assert_allclose(p[sliding], m * v0 - f_r * t[sliding], rtol=0, atol=1e-12 * m * v0)
    assert np.all(np.diff(total) <= 1e-15 * total[0])
    stuck = t > 1.5 * t_stop
    assert np.max(np.abs(p[stuck])) < 1e-3 * m * v0
    assert np.max(np.abs(total[stuck] - total[-1])) <= 1e-12 * total[0]
