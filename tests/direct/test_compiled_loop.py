"""The whole time loop in one compiled call: results bit-identical to the per-chunk kernel it replaced (kept
here, frozen, as the baseline), independent of what is recorded, and every recorded quantity equal to the numpy
reference path and to direct definitions."""

import sys
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct import recording as recording_module
from rodimpact.direct.result import junction_events_from_history

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from _old_loop import old_simulate  # noqa: E402  (the loop before this change, frozen)

DT = 1e-6


def busy_system():
    """Contact with a gap, a bonded joint, a spring-dashpot and a bit-rock end, a nodal load and bearings, and an
    initial force field in the middle rod."""
    striker = ri.Rod.from_impedance(np.r_[np.full(30, 60e3), np.linspace(20e3, 90e3, 25)], dt=DT)
    middle = ri.Rod.from_impedance(np.linspace(40e3, 80e3, 40), dt=DT)
    bar = ri.Rod.from_impedance(np.full(60, 50e3), dt=DT)
    return ri.System([striker, middle, bar], velocities=[6.0, 0.0, -1.0],
                     junctions=[ri.Contact(gap=1e-6), ri.Bonded()], left=ri.SpringEnd(2e8, 50.0),
                     right=ri.BitRockEnd(3e8, 9e8),
                     loads=(ri.NodalForce(1, 0.1, lambda t: 300 * np.sin(1e4 * t)),
                            ri.Bearings(2, [(0.05, 0.2)], friction_coefficient=0.3)),
                     initial=[None, ri.InitialState(force=lambda x: -2e4 * np.sin(30.0 * x)), None])


def thesis_system():
    """The README's thesis-scale impact: two-part striker 51.0e3/28.7e3 N s/m x 50 elements, bar 51.0e3 x 400."""
    striker = ri.Rod.from_impedance([51.0e3] * 50 + [28.7e3] * 50, dt=DT)
    bar = ri.Rod.from_impedance([51.0e3] * 400, dt=DT)
    return ri.System([striker, bar], velocities=[5.0, 0.0], right="nonreflecting")


def resting_struck_system():
    """Struck rods at rest behind the striker with a passive (fixed) far end: the compiled loop skips the
    elements the wave has not reached (the quiet front); a late nodal load in the last rod and bearings in the
    middle one sit beyond the front."""
    striker = ri.Rod.from_impedance(np.linspace(30e3, 70e3, 20), dt=DT)
    middle = ri.Rod.from_impedance(np.r_[np.full(30, 45e3), np.full(30, 80e3)], dt=DT)
    bar = ri.Rod.from_impedance(np.linspace(60e3, 20e3, 90), dt=DT)
    late = ri.NodalForce(2, 0.4, lambda t: np.where(t > 60e-6, 500.0 * np.sin(2e4 * t), 0.0))
    return ri.System([striker, middle, bar], velocities=[7.0, 0.0, 0.0], junctions=[ri.Contact(), ri.Contact()],
                     right="fixed", loads=(late, ri.Bearings(1, [(0.02, 0.2)], friction_coefficient=0.3)))


BUSY_PROBES = (ri.Probe("a", 1, 0.05), ri.Probe("b", 2, 0.1), ri.Probe("c", 0, 0.0))


@pytest.mark.parametrize("make, steps, probes", [(busy_system, 1500, BUSY_PROBES),
                                                 (thesis_system, 600, (ri.Probe("bar", 1, 0.2),)),
                                                 (resting_struck_system, 700, (ri.Probe("far", 2, 0.3),))])
def test_default_run_is_bit_identical_to_the_frozen_loop(make, steps, probes):
    """Against the old loop run as one compiled call (energy only at the ends): the same numbers, bit for bit.
    With its default energy sampling the old loop rebuilt its waves at every sample, which moves the last bits."""
    system = make()
    ref = old_simulate(system, steps, DT, probes, energy_every=steps)
    res = ri.simulate(system, steps=steps, dt=DT, outputs=ri.Outputs(probes=probes))   # default energy sampling (~256)
    assert np.array_equal(res.junction_force, ref.junction_force)
    assert np.array_equal(res.junction_contact, ref.junction_contact)
    for side in ("left", "right"):
        assert np.array_equal(res.end_force[side], ref.end_force[side])
        assert np.array_equal(res.end_velocity[side], ref.end_velocity[side])
    for p in probes:
        for q in ("force", "velocity", "displacement", "strain"):
            assert np.array_equal(getattr(res.probe(p.name), q), getattr(ref.probe(p.name), q))
    assert np.array_equal(res.final_force, ref.final_force) and np.array_equal(res.final_velocity, ref.final_velocity)
    for q in ("work_left", "work_right", "work_loads", "work_friction", "impulse"):
        assert np.array_equal(getattr(res.energy, q)[[0, -1]], getattr(ref.energy, q))
    for q in ("kinetic", "strain", "momentum"):       # sums in another order (numpy's reduceat before)
        np.testing.assert_allclose(getattr(res.energy, q)[:, [0, -1]], getattr(ref.energy, q), rtol=1e-14,
                                   atol=1e-14 * ref.energy.total[0])
    assert res.junction_contact.any() and not res.junction_contact.all()
    old_default = old_simulate(system, steps, DT, probes)
    scale = np.abs(ref.junction_force).max()
    np.testing.assert_allclose(old_default.junction_force, res.junction_force, rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_lattices_are_bit_identical_to_the_frozen_loop(seed):
    """Rods of 1 to 300 elements with random impedances (every vector length and remainder of the interior
    sweep), random velocities and loads at random nodes."""
    rng = np.random.default_rng(seed)
    sizes = rng.integers(1, 300, 4)
    rods = [ri.Rod.from_impedance(rng.uniform(2e4, 9e4, int(n)), dt=DT) for n in sizes]
    loads = tuple(ri.NodalForce(r, float(rng.uniform(0.2, 0.8)) * rods[r].length, lambda t: 200.0 * np.cos(3e4 * t))
                  for r in range(4) if sizes[r] > 3)
    system = ri.System(rods, velocities=list(rng.uniform(-3, 3, 4)), junctions=[ri.Contact(), ri.Bonded(),
                       ri.Contact(gap=2e-6)], right="nonreflecting", loads=loads)
    ref = old_simulate(system, 2000, DT, energy_every=2000)
    res = ri.simulate(system, steps=2000, dt=DT)
    assert np.array_equal(res.junction_force, ref.junction_force)
    assert np.array_equal(res.final_force, ref.final_force) and np.array_equal(res.final_velocity, ref.final_velocity)
    assert np.any(res.junction_force != 0.0)


def test_results_do_not_depend_on_what_is_recorded():
    """Energy samples and snapshots at every step leave the motion untouched, bit for bit (the kernel no longer
    stops and rebuilds its wave variables at each sample)."""
    system = busy_system()
    plain = ri.simulate(system, steps=700, dt=DT, outputs=ri.Outputs(energy_every=700))
    dense = ri.simulate(system, steps=700, dt=DT,
                        outputs=ri.Outputs(probes=BUSY_PROBES, snapshot_every=1, energy_every=1, record_every=3))
    assert np.array_equal(dense.junction_force, plain.junction_force[:, ::3])
    assert np.array_equal(dense.final_force, plain.final_force)
    assert np.array_equal(dense.final_velocity, plain.final_velocity)
    assert dense.energy.time.size == 701 and dense.snapshots.time.size == 701
    assert np.array_equal(dense.snapshots.force[:, -1], plain.final_force)
    assert np.array_equal(dense.energy.total[[0, -1]], plain.energy.total)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_recorded_samples_follow_their_definitions(backend):
    """Energy and momentum per rod are the sums of thesis eq. 3.25 over the snapshot fields; the snapshot
    displacement at a node equals the probe's displacement there (accumulated V dt) to rounding."""
    system = busy_system()
    res = ri.simulate(system, steps=400, dt=DT,
                      outputs=ri.Outputs(probes=BUSY_PROBES, snapshot_every=40, energy_every=40), backend=backend)
    s, e, lat = res.snapshots, res.energy, res.lattice
    assert np.array_equal(s.time, e.time) and np.allclose(s.time, np.arange(0, 401, 40) * DT, rtol=0, atol=1e-18)
    z, rs = lat.impedance[:, None], lat.rod_start
    kin = 0.5 * DT * z * s.velocity ** 2
    pot = 0.5 * DT * s.force ** 2 / z
    for r in range(3):
        a, b = rs[r], rs[r + 1]
        np.testing.assert_allclose(e.kinetic[r], kin[a:b].sum(axis=0), rtol=1e-13, atol=1e-300)
        np.testing.assert_allclose(e.strain[r], pot[a:b].sum(axis=0), rtol=1e-13, atol=1e-12 * e.total.max())
        np.testing.assert_allclose(e.momentum[r], (DT * z * s.velocity)[a:b].sum(axis=0), rtol=0,
                                   atol=1e-13 * 60e3 * 6.0 * 55 * DT)
    assert e.kinetic[0, 0] == pytest.approx(0.5 * DT * lat.impedance[:55].sum() * 36.0, rel=1e-14)
    node = lat.rod_start[1] + 1 + int(round(0.05 / lat.element_length[rs[1]]))    # probe "a": rod 1, 0.05 m
    probe = res.probe("a")
    assert lat.node_x[node] - lat.node_x[rs[1] + 1] == pytest.approx(probe.node_position, abs=1e-12)
    np.testing.assert_allclose(s.displacement[node, :-1], probe.displacement[::40], rtol=0,
                               atol=1e-12 * np.abs(probe.displacement).max())


def test_numba_and_numpy_record_the_same():
    system = busy_system()
    kw = dict(steps=900, dt=DT, outputs=ri.Outputs(energy_every=13, snapshot_times=[1e-4, 3.3e-4], snapshot_every=300,
                                                   record_every=7, probes=BUSY_PROBES))
    fast, ref = ri.simulate(system, backend="numba", **kw), ri.simulate(system, backend="numpy", **kw)
    for q in ("kinetic", "strain", "momentum", "work_left", "work_right", "work_loads", "work_friction", "impulse"):
        a, b = getattr(fast.energy, q), getattr(ref.energy, q)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-11 * max(np.abs(b).max(), 1e-300))
    np.testing.assert_array_equal(fast.snapshots.time, ref.snapshots.time)
    for q, scale in (("force", 60e3 * 6.0), ("velocity", 6.0), ("displacement", 6.0 * 900 * DT)):
        np.testing.assert_allclose(getattr(fast.snapshots, q), getattr(ref.snapshots, q), rtol=0, atol=1e-12 * scale)
    for ea, eb in zip(fast.junction_events, ref.junction_events):
        np.testing.assert_array_equal(ea.start, eb.start)
        np.testing.assert_array_equal(ea.stop, eb.stop)
        np.testing.assert_allclose(ea.max_abs_force, eb.max_abs_force, rtol=1e-12)
        assert ea.min_force_step == eb.min_force_step
    np.testing.assert_allclose(fast.junction_force, ref.junction_force, rtol=0, atol=1e-12 * 60e3 * 6.0)


def test_many_contact_phases_outgrow_the_event_buffer(monkeypatch):
    """A striker driven back and forth hits the bar again and again: the compiled loop returns to have its phase
    buffer enlarged (here from 1), and the phases equal those taken from the full histories."""
    monkeypatch.setattr(recording_module, "_PHASES", 1)
    z, v0 = 40e3, 2.0
    drive = ri.VelocityEnd(lambda t: v0 * (0.5 + np.sign(np.sin(2 * np.pi * t / (60 * DT)))))
    rods = [ri.Rod.from_impedance(np.full(20, z), dt=DT), ri.Rod.from_impedance(np.full(50, z), dt=DT)]
    for backend in ("numba", "numpy"):
        res = ri.simulate(ri.System(rods, [0.0, 0.0], left=drive, right="nonreflecting",
                                    junctions=[ri.Contact(gap=1e-5)]), steps=1200, backend=backend)
        (ev,) = res.junction_events
        (expected,) = junction_events_from_history(res.junction_force, res.junction_contact)
        assert ev.start.size >= 8, ev.start
        np.testing.assert_array_equal(ev.start, expected.start)
        np.testing.assert_array_equal(ev.stop, expected.stop)
        np.testing.assert_array_equal(ev.max_abs_force, expected.max_abs_force)
        assert (ev.min_force, ev.min_force_step, ev.max_abs_force_run) == \
            (expected.min_force, expected.min_force_step, expected.max_abs_force_run)
