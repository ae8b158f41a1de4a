"""The compiled (numba) kernel and the numpy reference path agree."""

import numpy as np

import rodimpact as ri

DT = 1e-6


def test_numba_and_numpy_paths_agree_on_a_busy_system():
    striker = ri.Rod.from_impedance(np.r_[np.full(30, 60e3), np.linspace(20e3, 90e3, 25)], dt=DT)
    middle = ri.Rod.from_impedance(np.linspace(40e3, 80e3, 40), dt=DT)
    bar = ri.Rod.from_impedance(np.full(60, 50e3), dt=DT)
    system = ri.System(
        [striker, middle, bar], [6.0, 0.0, -1.0], junctions=[ri.Contact(gap=1e-6), ri.Bonded()],
        left=ri.SpringEnd(2e8, 50.0), right=ri.BitRockEnd(3e8, 9e8),
        loads=[ri.NodalForce(1, 0.1, lambda t: 300 * np.sin(1e4 * t)),
               ri.Bearings(2, [(0.05, 0.2)], friction_coefficient=0.3)])
    common = dict(steps=1500, outputs=ri.Outputs(probes=[ri.Probe("a", 1, 0.05), ri.Probe("b", 2, 0.1)],
                                                 snapshot_every=250))
    fast = ri.simulate(system, backend="numba", **common)
    ref = ri.simulate(system, backend="numpy", **common)
    scale = 60e3 * 6.0
    np.testing.assert_allclose(fast.junction_force, ref.junction_force, rtol=0, atol=1e-12 * scale)
    np.testing.assert_array_equal(fast.junction_contact, ref.junction_contact)
    np.testing.assert_allclose(fast.snapshots.force, ref.snapshots.force, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(fast.snapshots.velocity, ref.snapshots.velocity, rtol=0, atol=1e-12 * 6.0)
    for name in ("a", "b"):
        np.testing.assert_allclose(fast.probe(name).force, ref.probe(name).force, rtol=0, atol=1e-12 * scale)
    assert fast.junction_contact.any() and not fast.junction_contact.all()
