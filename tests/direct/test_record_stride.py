"""Recording stride: ``simulate(..., outputs=Outputs(record_every=s))`` keeps every s-th step of the histories, bit
for bit the samples of the full run, while contact events and the peak contact force are still taken at every
step."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import rodimpact as ri
from rodimpact.direct import simulate as simulate_module
from rodimpact.direct.result import EventTracker, junction_events_from_history
from rodimpact.io import load, save
from rodimpact.io.results import summarize

DT = 1e-6


def recontact_run(record_every=1):
    """Rod A driven +V0 / -V0 / +V0 at its left end hits rod B, separates and hits again (a hand-checked case in
    test_closed_forms.py), with a probe in each rod."""
    z, v0 = 40e3, 2.0
    drive = ri.VelocityEnd(lambda t: np.where(t < 20 * DT, v0, np.where(t < 35 * DT, -v0, v0)))
    rods = [ri.Rod.from_impedance(np.full(60, z), dt=DT), ri.Rod.from_impedance(np.full(400, z), dt=DT)]
    return ri.simulate(ri.System(rods, [0.0, 0.0], left=drive, right="nonreflecting"), steps=400,
                       outputs=ri.Outputs(probes=[ri.Probe("a", 0, 0.05), ri.Probe("b", 1, 0.3)],
                                          record_every=record_every))


def assert_same_events(a, b):
    assert len(a.junction_events) == len(b.junction_events)
    for ea, eb in zip(a.junction_events, b.junction_events):
        assert np.array_equal(ea.start, eb.start) and np.array_equal(ea.stop, eb.stop)
        assert np.array_equal(ea.max_abs_force, eb.max_abs_force)
        assert (ea.min_force, ea.min_force_step, ea.max_abs_force_run) == \
            (eb.min_force, eb.min_force_step, eb.max_abs_force_run)


@pytest.mark.parametrize("stride", [1, 3, 7, 64, 399, 1000])
def test_strided_histories_are_the_samples_of_the_full_run(stride):
    full, strided = recontact_run(), recontact_run(record_every=stride)
    assert strided.record_every == stride and strided.n_steps == full.n_steps == 400
    assert np.array_equal(strided.time, full.time[::stride])
    assert np.array_equal(strided.junction_force, full.junction_force[:, ::stride])
    assert np.array_equal(strided.junction_contact, full.junction_contact[:, ::stride])
    for side in ("left", "right"):
        assert np.array_equal(strided.end_force[side], full.end_force[side][::stride])
        assert np.array_equal(strided.end_velocity[side], full.end_velocity[side][::stride])
    for name in full.probes:
        for q in ("force", "velocity", "displacement", "strain"):
            assert np.array_equal(getattr(strided.probes[name], q), getattr(full.probes[name], q)[::stride])
    assert np.array_equal(strided.final_force, full.final_force)
    assert np.array_equal(strided.energy.total, full.energy.total)


@pytest.mark.parametrize("stride", [7, 1000])
def test_contact_events_do_not_depend_on_the_stride(stride):
    full, strided = recontact_run(), recontact_run(record_every=stride)
    assert full.contact_times().size >= 2           # re-contacts: the events are not trivial
    assert_same_events(full, strided)
    np.testing.assert_array_equal(strided.contact_times(), full.contact_times())
    np.testing.assert_array_equal(strided.separation_times(), full.separation_times())
    assert strided.contact_duration() == full.contact_duration()
    a, b = summarize(full), summarize(strided)
    assert a["junctions"] == b["junctions"] and (a["steps"], b["record_every"]) == (400, stride)
    # the full-resolution peak, even where the samples miss it
    assert b["junctions"][0]["peak_compressive_force_N"] == full.contact_force.min()


def test_chunk_boundaries(monkeypatch):
    """Kernel chunks of 37 steps against strides that do not divide them: the same samples and events."""
    full = recontact_run()
    monkeypatch.setattr(simulate_module, "_MAX_CHUNK", 37)
    for stride in (1, 5, 37, 50):
        res = recontact_run(record_every=stride)
        assert np.array_equal(res.junction_force, full.junction_force[:, ::stride])
        assert np.array_equal(res.probes["b"].displacement, full.probes["b"].displacement[::stride])
        assert_same_events(full, res)


def test_events_of_the_simulation_equal_those_of_its_histories():
    res = recontact_run()
    assert_same_events(res, type("R", (), {"junction_events": junction_events_from_history(
        res.junction_force, res.junction_contact)})())


def reference_phases(force, contact):
    """Contact phases by the direct definition: maximal runs of consecutive steps in contact."""
    phases, k, n = [], 0, contact.size
    while k < n:
        if contact[k]:
            m = k
            while m < n and contact[m]:
                m += 1
            phases.append((k, m, float(np.max(np.abs(force[k:m])))))
            k = m
        else:
            k += 1
    return phases


@given(st.lists(st.tuples(st.booleans(), st.floats(-1e3, 1e3)), min_size=1, max_size=60),
       st.lists(st.integers(1, 9), min_size=1, max_size=20))
def test_event_tracker_is_independent_of_the_chunking(steps, chunks):
    contact = np.array([c for c, _ in steps])
    force = np.array([f if c else 0.0 for c, f in steps])
    tracker, first = EventTracker(1), 0
    for size in chunks * 10:
        if first >= contact.size:
            break
        tracker.feed(first, force[None, first:first + size], contact[None, first:first + size].astype(float))
        first += size
    tracker.feed(first, force[None, first:], contact[None, first:].astype(float))
    (ev,) = tracker.finish(contact.size)
    expected = reference_phases(force, contact)
    assert [(int(a), int(b), float(m)) for a, b, m in zip(ev.start, ev.stop, ev.max_abs_force)] == expected
    assert ev.min_force == force.min() and ev.min_force_step == int(np.argmin(force))
    assert ev.max_abs_force_run == float(np.max(np.abs(force)))


def test_save_and_load_keep_the_stride_and_the_events(tmp_path):
    res = recontact_run(record_every=9)
    save(res, tmp_path / "out")
    back = load(tmp_path / "out")
    assert (back.record_every, back.n_steps, back.time.size) == (9, 400, 45)
    assert np.array_equal(back.junction_force, res.junction_force)
    assert_same_events(res, back)
    assert summarize(back)["junctions"] == summarize(res)["junctions"]


def test_model_file_record_every(tmp_path):
    from rodimpact.io.model import dump_model, load_model, loads_model, model_from_result

    text = """
[[rods]]
name = "striker"
velocity = "5 m/s"
segments = [{shape = "cylinder", length = "0.2 m", diameter = "40 mm"}]
[[rods]]
name = "bar"
segments = [{shape = "cylinder", length = "1 m", diameter = "40 mm"}]
[simulation]
duration = "0.4 ms"
dt = "1 us"
[output]
record_every = 4
"""
    (tmp_path / "m.toml").write_text(text)
    model = load_model(tmp_path / "m.toml")
    res = model.simulate()
    assert (res.record_every, res.n_steps, res.time.size) == (4, 400, 100)
    assert loads_model(dump_model(model)).output.record_every == 4          # written back to a file
    assert model_from_result(res).output.record_every == 4                 # model.toml of a saved result
    (tmp_path / "bad.toml").write_text(text.replace("record_every = 4", "record_every = 0"))
    with pytest.raises(ValueError, match=r"output\.record_every"):
        load_model(tmp_path / "bad.toml")


@pytest.mark.parametrize("bad", [0, -2, 2.5, True, "3"])
def test_bad_stride_is_refused_with_its_name(bad):
    with pytest.raises(ValueError, match="record_every"):
        recontact_run(record_every=bad)


def test_results_of_format_1_still_load(tmp_path):
    """Folders written before the stride existed (format 1: every step, no stored events) load, and their
    contact events are rebuilt from the histories."""
    import xarray as xr

    res = recontact_run()
    save(res, tmp_path / "out", csv=False)
    nc = tmp_path / "out" / "result.nc"
    ds = xr.load_dataset(nc)
    ds = ds.drop_vars([k for k in ds.variables if k.startswith(("phase_", "junction_min", "junction_max"))])
    for key in ("steps", "record_every"):
        del ds.attrs[key]
    ds.attrs["format_version"] = 1
    ds.attrs["probe_names"] = "[]"                 # formats 1 and 2 named the probes in this attribute
    ds.to_netcdf(nc)
    back = load(tmp_path / "out")
    assert (back.record_every, back.n_steps) == (1, 400)
    assert_same_events(res, back)


def test_the_printed_summary_uses_the_full_resolution_peak():
    full, strided = recontact_run(), recontact_run(record_every=1000)
    assert strided.junction_force.min() != full.contact_force.min()        # the samples miss the peak
    assert f"peak force {full.contact_force.min():.6g} N" in repr(strided)
