"""When contact starts: first contact after an initial gap and re-contact after a separation, against
kinematics done by hand.

The lattice resolves contact to step boundaries: a pair that closes its gap at time t* inside step k
(t* in [k dt, (k+1) dt)) is in contact from step k if the gap closes within the first half of the step, else
from step k + 1, i.e. from the step boundary nearest to t*. So |t_contact - t*| <= dt / 2, and the tests put
t* a quarter or three quarters into a step, where a rule that looked a whole step ahead (or a gap of the wrong
size) is off by more than dt / 2.
"""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri

DT = 1e-6
Z = 40.0e3


def bar(n: int, z: float = Z) -> ri.Rod:
    return ri.Rod.from_impedance(np.full(n, z), dt=DT)


@pytest.mark.parametrize("fraction", [0.25, 0.75])
@pytest.mark.parametrize("v_target", [0.0, -1.5, 2.0])
def test_first_contact_after_an_initial_gap_at_gap_over_closing_speed(fraction, v_target):
    """Striker at 5 m/s, target at v_target, both stress-free: the faces move uniformly, so the gap g closes
    at t* = g / (5 - v_target). At contact the force is that of two equal impedances meeting at the relative
    velocity: -Z (5 - v_target) / 2, exactly."""
    v_striker = 5.0
    closing = v_striker - v_target
    steps_to_contact = 20 + fraction
    gap = steps_to_contact * DT * closing
    res = ri.simulate(ri.System([bar(30), bar(200)], [v_striker, v_target], right="nonreflecting",
                                junctions=[ri.Contact(gap=gap)]), steps=60)
    t_star = gap / closing
    contact = res.contact_times()
    assert contact.size == 1
    assert abs(contact[0] - t_star) <= 0.5 * DT * (1 + 1e-9)
    assert contact[0] == pytest.approx(round(steps_to_contact) * DT, rel=1e-12)   # the nearest boundary
    k = int(round(contact[0] / DT))
    assert np.all(res.contact_force[:k] == 0.0)
    np.testing.assert_allclose(res.contact_force[k:k + 60 - k], -Z * closing / 2, rtol=1e-12)


@pytest.mark.parametrize("fraction", [0.25, 0.75])
def test_recontact_after_separation_at_the_hand_calculated_time(fraction):
    """Rod A's left end is driven at +V0 on [0, t1), -V0 on [t1, t2) and +V1 afterwards; rod B (same Z) is at
    rest with a non-reflecting right end. D'Alembert with equal impedances (no reflection at the contact):

    * the +V0 wave reaches the face at T_A and passes into B: N = -Z V0 on [T_A, T_A + t1);
    * the -V0 wave would pull: separation at T_A + t1. A's face is free and moves at twice the drive,
      -2 V0; B's face is at rest (the pulse left). The gap grows to 2 V0 (t2 - t1) at T_A + t2;
    * from T_A + t2 A's face moves at +2 V1 and closes the gap at t* = T_A + t2 + V0 (t2 - t1) / V1,
      where the force is -Z V1 (characteristics N - Z v = -2 Z V1 from A, N + Z v = 0 from B).
    """
    v0 = 2.0
    n_a, k1, k2 = 40, 15, 30
    t1, t2 = k1 * DT, k2 * DT
    closing_steps = 10 + fraction
    v1 = v0 * (k2 - k1) / closing_steps
    drive = ri.VelocityEnd(lambda t: np.where(t < t1, v0, np.where(t < t2, -v0, v1)))
    res = ri.simulate(ri.System([bar(n_a), bar(300)], [0.0, 0.0], left=drive, right="nonreflecting"), steps=n_a + 60)
    t_a = n_a * DT
    t_star = t_a + t2 + v0 * (t2 - t1) / v1
    np.testing.assert_allclose(res.separation_times(), [t_a + t1], rtol=1e-12)
    contact = res.contact_times()
    assert contact.size == 2
    assert contact[0] == pytest.approx(t_a, rel=1e-12)
    assert abs(contact[1] - t_star) <= 0.5 * DT * (1 + 1e-9)
    k = int(round(contact[1] / DT))
    assert np.all(res.contact_force[int(round((t_a + t1) / DT)):k] == 0.0)
    np.testing.assert_allclose(res.contact_force[k:], -Z * v1, rtol=1e-12)
