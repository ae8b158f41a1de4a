"""Displacements (probes and field snapshots) against kinematics done by hand.

Probe displacements are reported at the start of each step, u(t_k) with t_k = k dt, and snapshot
displacements at the snapshot time; both are exact on the lattice for these piecewise-constant motions.
"""

from __future__ import annotations

import numpy as np

import rodimpact as ri

DT = 1e-6
Z = 40.0e3
N_EL = 50


def test_probe_displacement_of_a_rigidly_moving_rod_is_v_t():
    rod = ri.Rod.from_impedance(np.full(N_EL, Z), dt=DT)
    probes = [ri.Probe(name, 0, x) for name, x in (("left", 0.0), ("mid", rod.length / 2), ("right", rod.length))]
    res = ri.simulate([rod], [2.0], steps=80, outputs=ri.Outputs(probes=probes))
    for p in probes:
        np.testing.assert_allclose(res.probe(p.name).displacement, 2.0 * np.arange(80) * DT, rtol=1e-12, atol=0)


def test_probe_and_snapshot_displacements_behind_a_wave_front():
    """A constant compressive force -F at the left end of a rod at rest launches a wave: behind the front the
    particle velocity is F / Z (+x), so the node at travel time m dt from the left end has moved
    u = (F / Z)(t - m dt) once the front has passed (t > m dt), and not at all before. The right end is
    reached at N_EL dt; the test stops before that."""
    force = 1000.0
    rod = ri.Rod.from_impedance(np.full(N_EL, Z), dt=DT)
    m = 20
    x_probe = m / N_EL * rod.length
    steps = N_EL - 5
    res = ri.simulate(ri.System([rod], [0.0], left=ri.ForceEnd(-force)), steps=steps,
                      outputs=ri.Outputs(probes=[ri.Probe("p", 0, x_probe)], snapshot_times=[30 * DT]))
    k = np.arange(steps)
    expected = force / Z * np.maximum(k - m, 0) * DT
    np.testing.assert_allclose(res.probe("p").displacement, expected, rtol=0, atol=1e-12 * force / Z * steps * DT)
    snap = res.snapshots
    j = np.arange(N_EL + 1)                                      # node j at travel time j dt
    expected_field = force / Z * np.maximum(30 - j, 0) * DT
    np.testing.assert_allclose(snap.displacement[:, 0], expected_field, rtol=0, atol=1e-12 * force / Z * 30 * DT)
