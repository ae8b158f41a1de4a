"""``Outputs``: the outputs of a run declared as one object, equivalent to the keywords of a sweep point's dict
(which ``simulate`` took before, issue 21)."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct._sweep_keywords import problem_of

DT = 1e-6


def point(**kw):
    """A sweep point's dict of keywords: the impact of :func:`impact` with ``kw``."""
    rods = [ri.Rod.from_impedance(np.full(30, 40e3), dt=DT, name="striker"),
            ri.Rod.from_impedance(np.full(90, 40e3), dt=DT, name="bar")]
    return dict(rods=rods, velocities=[3.0, 0.0], steps=200, right="nonreflecting", **kw)


def impact(outputs=None, **kw):
    rods = [ri.Rod.from_impedance(np.full(30, 40e3), dt=DT, name="striker"),
            ri.Rod.from_impedance(np.full(90, 40e3), dt=DT, name="bar")]
    return ri.simulate(ri.System(rods, [3.0, 0.0], right="nonreflecting"), steps=200, outputs=outputs, **kw)


def test_a_recording_gives_the_run_of_its_keywords():
    fields = dict(probes=[ri.Probe("g", "bar", 0.01)], snapshot_times=[5e-5], snapshot_every=50, energy_every=3,
                  record_every=2)
    by_keywords, by_object = ri.simulate(problem_of(point(**fields))[0]), impact(outputs=ri.Outputs(**fields))
    assert np.array_equal(by_object.junction_force, by_keywords.junction_force)
    assert np.array_equal(by_object.probe("g").strain, by_keywords.probe("g").strain)
    assert np.array_equal(by_object.snapshots.time, by_keywords.snapshots.time)
    assert np.allclose(by_object.snapshots.time, [0, 50e-6, 100e-6, 150e-6, 200e-6], rtol=0, atol=1e-18)
    assert np.array_equal(by_object.energy.total, by_keywords.energy.total)
    assert by_object.energy.time.size == 68 and by_object.time.size == 100 and by_object.record_every == 2


def test_the_default_recording_samples_energy_about_256_times():
    res = impact(outputs=ri.Outputs())
    assert res.energy.time.size == 201 and res.snapshots is None and not res.probes  # 200 steps: every step
    rods = [ri.Rod.from_impedance(np.full(10, 40e3), dt=DT)] * 2
    long = ri.simulate(rods, velocities=[1.0, 0.0], steps=1000)
    assert np.array_equal(np.round(long.energy.time / DT), np.r_[np.arange(0, 1000, 4), 1000])


def test_recording_is_frozen_and_normalised():
    rec = ri.Outputs(probes=[ri.Probe("g", 1, 0.0)], snapshot_times=np.array([1e-5, 0.0]), record_every=np.int64(3))
    assert rec.probes == (ri.Probe("g", 1, 0.0),) and rec.snapshot_times == (1e-5, 0.0)
    assert type(rec.record_every) is int
    with pytest.raises(AttributeError):
        rec.record_every = 4


@pytest.mark.parametrize("kw, error, match", [
    (dict(record_every=0), ValueError, "record_every: must be an integer number of steps >= 1"),
    (dict(energy_every=2.5), ValueError, "energy_every: must be an integer number of steps >= 1"),
    (dict(snapshot_every=True), ValueError, "snapshot_every: must be an integer number of steps >= 1"),
    (dict(snapshot_times=[np.nan]), ValueError, "snapshot_times"),
    (dict(snapshot_times=[-1e-6]), ValueError, r"snapshot_times: must lie in \[0, "),
    (dict(probes=["g"]), TypeError, r"probes\[0\]: must be a Probe"),
    (dict(probes=ri.Probe("g", 1, 0.0)), TypeError, "probes: must be a sequence of Probe"),
    (dict(probes=[ri.Probe("g", 1, 0.0), ri.Probe("g", 0, 0.0)]), ValueError, r"probes\[1\].name: 'g' is used twice"),
])
def test_bad_recordings_name_the_field(kw, error, match):
    with pytest.raises(error, match=match):
        ri.Outputs(**kw)
    with pytest.raises(error, match=match):        # the same through the keywords of a sweep point
        problem_of(point(**kw))


def test_recording_and_keywords_together_are_refused():
    with pytest.raises(ValueError, match="outputs: give the outputs either as outputs=Outputs.*energy_every="):
        problem_of(point(outputs=ri.Outputs(), energy_every=5))
    with pytest.raises(TypeError, match=r"energy_every: give the outputs as one Outputs: .*"
                                        r"outputs=ri.Outputs\(energy_every="):
        impact(outputs=ri.Outputs(), energy_every=5)
    with pytest.raises(TypeError, match="outputs: must be an Outputs"):
        impact(outputs={"energy_every": 5})


def test_snapshot_limits_are_checked_against_the_run():
    with pytest.raises(ValueError, match=r"snapshot_times: must lie in \[0, 0.0002\] s"):
        impact(outputs=ri.Outputs(snapshot_times=[1.0]))
    with pytest.raises(ValueError, match="snapshot_every: 1 gives 200001 snapshots; use a larger stride"):
        rods = [ri.Rod.from_impedance(np.full(3, 40e3), dt=DT)]
        ri.simulate(rods, [1.0], steps=200_000, outputs=ri.Outputs(snapshot_every=1))


def test_snapshots_that_do_not_fit_in_memory_are_refused_before_the_run(monkeypatch):
    """Snapshots are preallocated: on a machine with 4 MB, 501 snapshots of 1200 elements (N, v, u: about 14 MB, held twice while
    they are stacked at the end)
    are refused up front, naming the request; 50 of them (1.4 MB) run."""
    from rodimpact.direct import guards

    monkeypatch.setattr(guards, "available_memory", lambda: 4e6)
    rods = [ri.Rod.from_impedance(np.full(200, 40e3), dt=DT), ri.Rod.from_impedance(np.full(1000, 40e3), dt=DT)]
    with pytest.raises(ValueError, match=r"snapshot_every: the run would need about 27\.7 MiB of memory \(snapshots "
                                         r"27\.5 MiB\), more than the 3\.81 MiB available now"):
        ri.simulate(rods, [1.0, 0.0], steps=500, outputs=ri.Outputs(snapshot_every=1))
    assert ri.simulate(rods, [1.0, 0.0], steps=500, outputs=ri.Outputs(snapshot_every=10)).snapshots.time.size == 51
