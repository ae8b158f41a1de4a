"""Verification of the direct solver against closed-form results (exact for piecewise-constant impedance)."""

import numpy as np
import pytest

import rodimpact as ri

DT = 1e-6
C = ri.STEEL.wave_speed


def rect_bar(z, n):
    return ri.Rod.from_impedance(np.full(n, z), dt=DT)


def test_equal_impedance_rectangular_pulse_exact():
    """Uniform striker on a uniform rod of equal impedance: N = -Z v / 2 for 2 L / c, then separation."""
    z, v, n = 51.0e3, 5.0, 50
    res = ri.simulate(ri.System([rect_bar(z, n), rect_bar(z, 400)], [v, 0.0], right="nonreflecting"), duration=300e-6)
    expected = np.where(res.time < 2 * n * DT - 0.5 * DT, -z * v / 2, 0.0)
    np.testing.assert_allclose(res.contact_force, expected, rtol=0, atol=1e-12 * z * v)
    np.testing.assert_allclose(res.separation_times(), [2 * n * DT], rtol=1e-12)
    # the striker is left at rest, the bar carries all momentum and energy
    np.testing.assert_allclose(res.rigid_body_velocity[0], 0.0, atol=1e-12 * v)
    assert res.efficiency == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("z1, z2", [(30e3, 60e3), (60e3, 30e3), (51e3, 79.7e3)])
def test_unequal_impedance_staircase(z1, z2):
    """Uniform striker Z1 (n elements) on a semi-infinite bar Z2: window k of length 2T carries
    N1 r^k, r = (Z1 - Z2)/(Z1 + Z2), while compressive; for Z1 < Z2 the rods separate at 2T."""
    v, n = 4.0, 40
    res = ri.simulate(ri.System([rect_bar(z1, n), rect_bar(z2, 50)], [v, 0.0], right="nonreflecting"), steps=8 * n)
    n1 = -z1 * z2 * v / (z1 + z2)
    r = (z1 - z2) / (z1 + z2)
    k = np.arange(res.time.size) // (2 * n)
    expected = n1 * r**k
    if r < 0:
        expected = np.where(k == 0, n1, 0.0)
        np.testing.assert_allclose(res.separation_times(), [2 * n * DT], rtol=1e-12)
        # rebound velocity of the striker: v (Z1 - Z2)/(Z1 + Z2)
        np.testing.assert_allclose(res.rigid_body_velocity[0], v * r, rtol=1e-12)
    else:
        assert res.separation_times().size == 0
    np.testing.assert_allclose(res.contact_force, expected, rtol=0, atol=1e-12 * abs(n1))


def test_stepped_striker_first_stairs_and_separation():
    """Thesis setup 2 type (Tab. 3.1): striker listed left to right [Z0]*50 + [Z1]*50 (Z1 at the impact face)
    on a uniform rod Z0. Stair 1: N1 = -Z1 Z0 v/(Z1+Z0); stair 2 adds the wave reflected at the step
    (R = (Z0-Z1)/(Z0+Z1)) and transmitted into the bar (T = 2 Z0/(Z0+Z1)): N2 = N1 (1 + R T)."""
    z0, z1, v = 51.0e3, 28.7e3, 5.0
    striker = ri.Rod.from_impedance([z0] * 50 + [z1] * 50, dt=DT)
    res = ri.simulate(ri.System([striker, rect_bar(z0, 400)], [v, 0.0], right="nonreflecting"), duration=400e-6)
    n1 = -z1 * z0 * v / (z1 + z0)
    big_r = (z0 - z1) / (z0 + z1)
    big_t = 2 * z0 / (z0 + z1)
    np.testing.assert_allclose(res.contact_force[:100], n1, rtol=1e-12)
    np.testing.assert_allclose(res.contact_force[100:102], n1 * (1 + big_r * big_t), rtol=1e-12)
    # momentum: everything the striker lost is in the bar (free striker, nonreflecting bar end has not
    # been reached by t = 400 us -> momentum of both rods is conserved exactly)
    m = res.energy.momentum
    np.testing.assert_allclose(m.sum(axis=0), m.sum(axis=0)[0], rtol=1e-12)
    assert res.separation_times().size == 1


def test_free_end_reflects_with_sign_change_fixed_end_without():
    """A compressive rectangular pulse applied at the left end of a bar travels to the right end and comes back
    inverted (free end) or unchanged in sign with doubled end force (fixed end)."""
    n, width, p = 200, 20, -1000.0
    pulse = ri.ForceEnd(lambda t: np.where(t < width * DT, p, 0.0))
    probe = ri.Probe("mid", 0, rect_bar(40e3, n).length / 2)
    for right, sign in (("free", -1.0), ("fixed", 1.0)):
        res = ri.simulate(ri.System([rect_bar(40e3, n)], [0.0], left=pulse, right=right), steps=2 * n,
                          outputs=ri.Outputs(probes=[probe]))
        f = res.probe("mid").force
        first = f[n // 2: n // 2 + width]
        back = f[3 * n // 2: 3 * n // 2 + width]
        np.testing.assert_allclose(first, p, rtol=1e-12)
        np.testing.assert_allclose(back, sign * p, rtol=1e-12)
        end = res.end_force["right"][n: n + width]
        np.testing.assert_allclose(end, 0.0 if right == "free" else 2 * p, atol=1e-12 * abs(p))


def test_nonreflecting_end_absorbs_completely():
    n, width, p = 100, 30, -2500.0
    pulse = ri.ForceEnd(lambda t: np.where(t < width * DT, p, 0.0))
    res = ri.simulate(ri.System([rect_bar(40e3, n)], [0.0], left=pulse, right="nonreflecting"), steps=3 * n,
                      outputs=ri.Outputs(energy_every=1))
    assert np.max(np.abs(res.final_force)) <= 1e-12 * abs(p)
    assert np.max(np.abs(res.final_velocity)) <= 1e-12 * abs(p) / 40e3
    # energy that came in through the left end all left through the right end
    e = res.energy
    assert e.work_left[-1] > 0
    np.testing.assert_allclose(e.work_right[-1], -e.work_left[-1], rtol=1e-12)


def test_recontact_hand_calculation():
    """Hand calculation (d'Alembert, equal impedances, no reflections): rod A's left end is driven with
    velocity +V0 on [0, t1), -V0 on [t1, t2), +V0 afterwards; rod B (same Z) ends non-reflecting.

    Contact transmits the incoming wave unchanged: N = -Z V0 on [T_A, T_A + t1). The unloading wave would
    pull, so the rods separate at T_A + t1; A's face is then free (velocity doubled: -2 V0), B's face is at
    rest, so the gap grows as 2 V0 (t - T_A - t1). From T_A + t2 A's face moves at +2 V0 and the gap closes
    at T_A + 2 t2 - t1, where the force is -Z V0 again (characteristics N - Z v = -2 Z V0 from A,
    N + Z v = 0 from B).
    """
    z, v0, na = 40e3, 2.0, 60
    t1, t2 = 20 * DT, 35 * DT
    drive = ri.VelocityEnd(lambda t: np.where(t < t1, v0, np.where(t < t2, -v0, v0)))
    res = ri.simulate(ri.System([rect_bar(z, na), rect_bar(z, 400)], [0.0, 0.0], left=drive, right="nonreflecting"),
                      steps=na + 100)
    ta = na * DT
    np.testing.assert_allclose(res.separation_times(), [ta + t1], rtol=1e-12)
    np.testing.assert_allclose(res.contact_times(), [ta, ta + 2 * t2 - t1], rtol=1e-12)
    t = res.time
    loaded = ((t >= ta - 1e-12) & (t < ta + t1 - 1e-12)) | (t >= ta + 2 * t2 - t1 - 1e-12)
    np.testing.assert_allclose(res.contact_force, np.where(loaded, -z * v0, 0.0), atol=1e-12 * z * v0)


def test_thesis_setup2_full_staircase_and_separation_time():
    """Thesis first example (Tab. 3.1): the whole contact-force staircase and the separation time against
    the independent exact wave-train superposition of the reference layer (no shared code with the lattice)."""
    from rodimpact import reference as rr

    z0, z1, v = 51.0e3, 28.7e3, 5.0
    striker = ri.Rod.from_impedance([z0] * 50 + [z1] * 50, dt=DT)
    res = ri.simulate(ri.System([striker, rect_bar(z0, 400)], [v, 0.0], right="nonreflecting"), duration=600e-6)
    exact = rr.solve_wave_trains([rr.UniformPiece(z0, 50 * DT), rr.UniformPiece(z1, 50 * DT)],
                                 [rr.UniformPiece(z0, 2.0)], v, 600e-6)
    mid = res.time + 0.5 * DT
    np.testing.assert_allclose(res.contact_force, exact.contact_force(mid), rtol=0, atol=1e-12 * z0 * v)
    np.testing.assert_allclose(res.separation_times(), exact.separations, rtol=1e-12)
    assert exact.recontacts.size == 1          # the first contact only: no re-contact in this example


def test_no_spurious_recontact_after_separation_at_rest():
    """Equal cylinders: after separation the striker face is at rest and the gap stays zero to rounding; the
    rods must not be re-contacted by rounding noise (exactly one contact phase)."""
    rods = [ri.Rod([ri.Cylinder(0.4, 0.05)]), ri.Rod([ri.Cylinder(1.6, 0.05)])]
    res = ri.simulate(ri.Problem.of(rods, [3.0, 0.0], steps=400, elements=(0, 40)))
    np.testing.assert_allclose(res.separation_times(), [80 * res.dt], rtol=1e-12)
    assert res.contact_times().size == 1


def test_prescribed_histories_are_applied_at_every_step_of_a_long_run():
    """End and nodal-force histories are evaluated chunk by chunk (bounded memory): across chunk boundaries
    (every 65536 steps and at energy samples) the end force equals the history at the step midpoints."""
    rod = rect_bar(3e4, 6)
    hist = lambda t: -100.0 * np.sin(2e3 * t) - 50.0      # noqa: E731
    res = ri.simulate(ri.System([rod], [0.0], left=ri.ForceEnd(hist), right="fixed",
                                loads=[ri.NodalForce(0, rod.length / 2, lambda t: 10.0 * np.cos(1e3 * t))]),
                      steps=140_000, outputs=ri.Outputs(energy_every=999))
    np.testing.assert_allclose(res.end_force["left"], hist((np.arange(140_000) + 0.5) * DT), rtol=0, atol=1e-12 * 150)
    e = res.energy
    assert e.balance_error < 1e-10
