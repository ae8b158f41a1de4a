"""rodimpact.simulate_batch: every design equals the simulate() run of the same system bit for bit."""

import dataclasses
import operator
from concurrent.futures import Future, ThreadPoolExecutor

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct.batch import gather

DT = 1e-6
C = ri.STEEL.wave_speed


def alone(system, striker, velocity, steps, **outputs):
    """The reference: simulate() with the design in the striker slot (``outputs``: fields of its Outputs)."""
    s = dataclasses.replace(system, rods=(striker, *system.rods[1:]), velocities=(velocity, *system.velocities[1:]))
    return ri.simulate(s, steps=steps, dt=DT, outputs=ri.Outputs(**outputs) if outputs else None)


def assert_design_equals_run(res, d, run):
    """Every quantity of design d equals the stand-alone run exactly."""
    assert np.array_equal(res.contact_force[d], run.junction_force[0])
    np.testing.assert_array_equal(res.time, run.time)
    assert np.array_equal(res.kinetic[d], run.energy.kinetic[:, [0, -1]])
    assert np.array_equal(res.strain[d], run.energy.strain[:, [0, -1]])
    for side in ("left", "right", "loads", "friction"):
        assert getattr(res, f"work_{side}")[d] == getattr(run.energy, f"work_{side}")[-1]
    assert res.efficiency[d] == run.efficiency
    assert res.rigid_body_velocity[d] == run.rigid_body_velocity[0]
    n_s = res.impedance.shape[1]
    assert np.array_equal(res.final_force[d], run.final_force[:n_s])
    assert np.array_equal(res.final_velocity[d], run.final_velocity[:n_s])
    for got, want in zip(res.junction_events(d), run.junction_events, strict=True):
        for f in dataclasses.fields(want):
            assert np.array_equal(getattr(got, f.name), getattr(want, f.name)), f.name
    assert np.array_equal(res.contact_duration[d], [run.contact_duration(j) for j in range(len(run.junction_events))])
    np.testing.assert_array_equal(res.separation_times(d), run.separation_times(0))
    np.testing.assert_array_equal(res.contact_times(d), run.contact_times(0))


def random_strikers(n_designs, n_elements, seed):
    """Impedance profiles with steps everywhere: many reflections, separation and re-contact."""
    return np.random.default_rng(seed).uniform(1.5e4, 8e4, (n_designs, n_elements))


def bar(n):
    return ri.Rod.from_impedance(np.full(n, 4e4), DT)


@pytest.mark.parametrize("right", ["nonreflecting", "free", ri.BitRockEnd(2e8, 1e9)],
                         ids=["nonreflecting", "free", "bitrock"])
def test_random_strikers_equal_simulate(right):
    zs = random_strikers(6, 30, seed=1)
    velocities = np.linspace(2.0, 9.0, 6)
    system = ri.System([bar(1), bar(300)], [0.0, 0.0], right=right)
    res = ri.simulate_batch(system, zs, velocities, ri.TimeGrid(DT, 400), threads=2)
    phases = []
    for d in range(6):
        run = alone(system, ri.Rod.from_impedance(zs[d], DT), velocities[d], steps=400)
        assert_design_equals_run(res, d, run)
        phases.append(res.n_phases[d, 0])
    assert max(phases) >= 2              # the set covers separation and re-contact


@pytest.mark.parametrize("right, moving", [(ri.ForceEnd(lambda t: -2e3 * np.sin(3e4 * t)), False), ("fixed", True)],
                         ids=["forced-end", "moving-part"])
def test_struck_rod_moving_at_first_or_forced_far_end(right, moving):
    """A part of the struck rod moves before the impact, or the far end pushes by itself: the batch may not
    treat the struck rod as at rest ahead of the wave."""
    zs = random_strikers(3, 25, seed=3)
    initial = [None, ri.InitialState(velocity=lambda x: np.where((x > 0.2) & (x < 0.3), -0.5, 0.0))] if moving else None
    system = ri.System([bar(1), bar(100)], [0.0, 0.0], right=right, initial=initial)
    res = ri.simulate_batch(system, zs, [3.0, 4.0, 5.0], ri.TimeGrid(DT, 350))
    for d in range(3):
        assert_design_equals_run(res, d, alone(system, ri.Rod.from_impedance(zs[d], DT), [3.0, 4.0, 5.0][d],
                                               steps=350))


def test_stepped_striker_separates_and_recontacts_on_a_loaded_chain():
    """Rods given as geometry, three rods (two contact junctions), a nodal load and bearings on the struck
    rods, a gap at the impact face, a non-reflecting left end (its parameters depend on each striker)."""
    strikers = [ri.Rod([ri.Cylinder(0.05, d1), ri.Cylinder(0.05, d2)]) for d1, d2 in
                [(0.06, 0.02), (0.02, 0.06), (0.04, 0.04), (0.05, 0.03)]]
    adapter = ri.Rod([ri.Cylinder(0.08, 0.035)])
    rod = ri.Rod([ri.Cylinder(0.4, 0.03)])
    dt = 0.005 / C
    system = ri.System([strikers[0], adapter, rod], [0.0, 0.0, 0.0], junctions=[ri.Contact(gap=1e-5), "contact"],
                       left="nonreflecting", right=ri.SpringEnd(3e8, 50.0),
                       loads=[ri.NodalForce(2, 0.2, lambda t: -2e3 * np.sin(2e4 * t)),
                              ri.Bearings(1, [(0.01, 0.07)], 0.2)])
    velocities = [4.0, 6.0, 8.0, 10.0]
    res = ri.simulate_batch(system, strikers, velocities, ri.TimeGrid.of(duration=1.2e-3, dt=dt),
                            outputs=ri.BatchOutputs(record_every=3, max_phases=64))
    for d, striker in enumerate(strikers):
        s = dataclasses.replace(system, rods=(striker, adapter, rod), velocities=(velocities[d], 0.0, 0.0))
        run = ri.simulate(s, duration=1.2e-3, dt=dt, outputs=ri.Outputs(record_every=3))
        assert_design_equals_run(res, d, run)
    assert res.n_phases[:, 0].max() >= 2 and res.n_phases[:, 1].max() >= 1
    assert np.all(res.work_loads != 0.0) and np.all(res.work_friction < 0.0)


def test_energy_stride_and_threads_and_executor_do_not_change_the_numbers():
    """simulate's energy stride changes nothing (its waves persist between compiled calls), nor do threads."""
    zs = random_strikers(5, 20, seed=2)
    system = ri.System([bar(1), bar(60)], [0.0, 0.0], right="nonreflecting")
    res = ri.simulate_batch(system, zs, 5.0, ri.TimeGrid(DT, 300), threads=1)
    for d in range(5):
        assert_design_equals_run(res, d, alone(system, ri.Rod.from_impedance(zs[d], DT), 5.0, steps=300,
                                               energy_every=7))
    two = ri.simulate_batch(system, zs, 5.0, ri.TimeGrid(DT, 300), threads=2)
    with ThreadPoolExecutor(2) as pool:
        pooled = ri.simulate_batch(system, zs, 5.0, ri.TimeGrid(DT, 300), executor=pool, chunk_size=2)
    for other in (two, pooled):
        for f in dataclasses.fields(res):
            if f.name not in ("system", "diagnostics"):
                assert np.array_equal(getattr(res, f.name), getattr(other, f.name)), f.name


@pytest.mark.parametrize("pooled", [False, True], ids=["in-process", "executor"])
def test_without_the_final_state_only_the_final_fields_are_left_out(pooled):
    """final_state=False drops the striker's final forces and velocities and keeps the rest, including the
    rigid-body velocity taken from them, bit for bit."""
    zs = random_strikers(5, 20, seed=3)
    system = ri.System([bar(1), bar(60)], [0.0, 0.0], right="free")
    full = ri.simulate_batch(system, zs, np.linspace(3.0, 8.0, 5), ri.TimeGrid(DT, 300))
    with ThreadPoolExecutor(2) as pool:
        slim = ri.simulate_batch(system, zs, np.linspace(3.0, 8.0, 5), ri.TimeGrid(DT, 300),
                                 outputs=ri.BatchOutputs(final_state=False), executor=pool if pooled else None,
                                 chunk_size=2)
    assert slim.final_force is None and slim.final_velocity is None
    assert np.all(np.abs(full.rigid_body_velocity) > 0.0)
    for f in dataclasses.fields(full):
        if f.name not in ("system", "diagnostics", "final_force", "final_velocity"):
            assert np.array_equal(getattr(full, f.name), getattr(slim, f.name)), f.name


class _Future(Future):
    """A finished future that remembers whether it was asked to cancel."""

    asked_to_cancel = False

    def cancel(self):
        self.asked_to_cancel = True
        return super().cancel()


class _RecordingExecutor:
    """Runs each task when submitted and keeps its future."""

    def __init__(self):
        self.futures = []

    def submit(self, fn, *args):
        fut = _Future()
        try:
            fut.set_result(fn(*args))
        except Exception as exc:
            fut.set_exception(exc)
        self.futures.append(fut)
        return fut


def test_gather_cancels_the_tasks_only_when_it_stops_early():
    """Finished tasks are left alone (dask names a task after its arguments: cancelling the first call's
    finished tasks cancelled the identical tasks of the next call); a failure cancels all."""
    pool = _RecordingExecutor()
    assert list(gather(pool, operator.truediv, [(1.0, 2.0), (3.0, 4.0)])) == [0.5, 0.75]
    assert not any(f.asked_to_cancel for f in pool.futures)
    pool = _RecordingExecutor()
    with pytest.raises(ZeroDivisionError):
        list(gather(pool, operator.truediv, [(1.0, 2.0), (1.0, 0.0), (3.0, 4.0)]))
    assert all(f.asked_to_cancel for f in pool.futures)


def test_equal_impedances_give_the_closed_form():
    """A striker of the bar's impedance Z at v on a non-reflecting bar: -Z v / 2 during 2 L / c, then 0;
    all the energy goes into the bar (thesis Sec. 2.3)."""
    n, z = 40, 4e4
    zs = np.full((3, n), z)
    velocities = np.array([1.0, 2.5, 7.0])
    res = ri.simulate_batch(ri.System([bar(1), bar(100)], [0.0, 0.0], right="nonreflecting"), zs, velocities,
                            ri.TimeGrid(DT, 150))
    expected = np.where(np.arange(150) < 2 * n, -z * velocities[:, None] / 2, 0.0)
    np.testing.assert_allclose(res.contact_force, expected, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(res.contact_duration[:, 0], 2 * n * DT, rtol=1e-12)
    np.testing.assert_allclose(res.efficiency, 1.0, rtol=1e-12)
    np.testing.assert_allclose(res.kinetic[:, 0, 0], 0.5 * n * z * DT * velocities**2, rtol=1e-12)


def test_to_xarray_and_truncated_phases():
    zs = random_strikers(4, 30, seed=1)
    system = ri.System([bar(1), bar(120)], [0.0, 0.0], right="free")
    res = ri.simulate_batch(system, zs, np.linspace(2.0, 9.0, 4), ri.TimeGrid(DT, 400),
                            outputs=ri.BatchOutputs(contact_force=False, max_phases=1))
    assert res.contact_force is None and res.time.size == 0
    ds = res.to_xarray()
    assert ds["peak_force"].dims == ("design", "junction") and ds["kinetic_energy"].dims == ("design", "rod",
                                                                                            "energy_time")
    assert "contact_force" not in ds and ds.sizes["phase"] == 1
    many = int(np.argmax(res.n_phases[:, 0]))
    assert res.n_phases[many, 0] >= 2
    with pytest.raises(ValueError, match=rf"design {many}, junction 0: \d+ contact phases, only 1 kept"):
        res.junction_events(many)


SYSTEM = ri.System([bar(1), bar(20)], [0.0, 0.0])


@pytest.mark.parametrize("args, kwargs, error, match", [
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10), ValueError, "dt: required"),
    ((bar(3), np.ones((2, 5)), 1.0), dict(steps=10, dt=DT), TypeError, "system: must be a System"),
    ((ri.System([bar(3)], [0.0]), np.ones((2, 5)), 1.0), dict(steps=10, dt=DT), ValueError, "a single rod"),
    ((ri.System([bar(3), bar(3)], [0.0, 0.0], loads=[ri.NodalForce(0, 1e-3, 1.0)]), np.ones((2, 5)), 1.0),
     dict(steps=10, dt=DT), ValueError, r"system.loads: rod 0 is the striker slot"),
    ((ri.System([bar(3), bar(3)], [0.0, 0.0], initial=[ri.InitialState(force=1.0), None]), np.ones((2, 5)), 1.0),
     dict(steps=10, dt=DT), ValueError, r"system.initial\[0\]"),
    ((SYSTEM, np.ones(5), 1.0), dict(steps=10, dt=DT), ValueError, "strikers: must be 2-dimensional"),
    ((SYSTEM, -np.ones((2, 5)), 1.0), dict(steps=10, dt=DT), ValueError, "design 0 element 0 is -1.0"),
    ((SYSTEM, [[1.0, np.nan]], 1.0), dict(steps=10, dt=DT), ValueError, "strikers: must be finite"),
    ((SYSTEM, [bar(3), bar(4)], 1.0), dict(steps=10, dt=DT), ValueError, r"same number of elements.*\[3, 4\]"),
    ((SYSTEM, [bar(3), [1.0]], 1.0), dict(steps=10, dt=DT), TypeError, "either Rods only"),
    ((SYSTEM, np.ones((2, 5)), [1.0, 2.0, 3.0]), dict(steps=10, dt=DT), ValueError, r"velocities: need one .* \(2\)"),
    ((SYSTEM, np.ones((2, 5)), [1.0, np.inf]), dict(steps=10, dt=DT), ValueError, "velocities: .*finite"),
    ((SYSTEM, np.ones((2, 5)), "fast"), dict(steps=10, dt=DT), TypeError, "velocities: impact velocities"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(dt=DT), ValueError, "duration: give exactly one"),
    ((SYSTEM, np.ones((10**6, 5)), 1.0), dict(steps=10**6, dt=DT), ValueError,
     r"strikers: the results of 1000000 designs would need .* GiB, more than this machine's memory"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, max_phases=0), ValueError, "max_phases: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, contact_force="yes"), TypeError, "contact_force: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, threads=0), ValueError, "threads: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, final_state=None), TypeError, "final_state: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, executor="pool"), TypeError, "executor: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0), dict(steps=10, dt=DT, executor=ThreadPoolExecutor(1), chunk_size=0),
     ValueError, "chunk_size: must be"),
    ((SYSTEM, np.ones((2, 5)), 1.0, (DT, 10)), dict(), TypeError, r"time: must be a TimeGrid, e.g. ri.TimeGrid\(dt, "),
    ((SYSTEM, np.ones((2, 5)), 1.0, ri.TimeGrid(DT, 10)), dict(outputs={"max_phases": 2}), TypeError,
     r"outputs: must be a BatchOutputs\(record_every="),
])
def test_bad_input(args, kwargs, error, match):
    """The time given as ``TimeGrid.of(steps= / duration=, dt=)``, the recording options as ``BatchOutputs``: their
    fields are checked when made and name the field."""
    time = {key: kwargs.pop(key) for key in ("duration", "steps", "dt") if key in kwargs}
    out = {key: kwargs.pop(key) for key in ("record_every", "contact_force", "final_state", "max_phases")
           if key in kwargs}
    with pytest.raises(error, match=match):
        ri.simulate_batch(*args, *([ri.TimeGrid.of(**time)] if time else []),
                          **({"outputs": ri.BatchOutputs(**out)} if out else {}), **kwargs)
