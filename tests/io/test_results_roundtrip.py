"""Results on disk: save -> load gives identical arrays; CSV files hold the same numbers with units in the
headers; the summary against hand calculations; no silent overwrite; atomic writes."""

import csv
import importlib.util
import json
import os

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.model import Model, OutputSpec
from rodimpact.io import load, save
from rodimpact.io.results import OutputExistsError, summarize

C = ri.STEEL.wave_speed
ENGINES = ["scipy"] + [e for e, mod in (("netcdf4", "netCDF4"), ("h5netcdf", "h5py")) if importlib.util.find_spec(mod)]


def three_rod_result():
    rods = [ri.Rod([ri.Cylinder(0.3, 0.04)], name="striker"), ri.Rod([ri.Cylinder(0.4, 0.05)], name="adapter"),
            ri.Rod([ri.Cone(0.6, 0.05, 0.04)], name="bar")]
    return ri.simulate(ri.System(rods, [5.0, 0.0, 0.0], right=ri.SpringEnd(1e8), junctions=[ri.Contact(), ri.Bonded()],
                                 loads=[ri.Bearings(2, [(0.1, 0.3)], 0.3)]), duration=1e-3, dt=1e-6,
                       outputs=ri.Outputs(probes=[ri.Probe("SG 1", 2, 0.1), ri.Probe("a,b", 1, 0.2)],
                                          snapshot_times=[1e-4, 5e-4], snapshot_every=50))


def assert_identical(a, b):
    for name in ("time", "junction_force", "junction_contact", "final_force", "final_velocity"):
        x, y = getattr(a, name), getattr(b, name)
        assert x.dtype == y.dtype and np.array_equal(x, y), name
    for side in ("left", "right"):
        assert np.array_equal(a.end_force[side], b.end_force[side])
        assert np.array_equal(a.end_velocity[side], b.end_velocity[side])
    assert list(a.probes) == list(b.probes)
    for k in a.probes:
        pa, pb = a.probes[k], b.probes[k]
        assert pa.probe == pb.probe and pa.node_position == pb.node_position
        for q in ("force", "velocity", "displacement", "strain"):
            assert np.array_equal(getattr(pa, q), getattr(pb, q)), (k, q)
    for q in ("time", "kinetic", "strain", "momentum", "work_left", "work_right", "work_loads", "work_friction",
              "impulse"):
        assert np.array_equal(getattr(a.energy, q), getattr(b.energy, q)), q
    if a.snapshots is None:
        assert b.snapshots is None
    else:
        for q in ("time", "element_x", "node_x", "element_rod", "node_rod", "force", "velocity", "displacement"):
            assert np.array_equal(getattr(a.snapshots, q), getattr(b.snapshots, q)), q
    la, lb = a.lattice, b.lattice
    assert la.dt == lb.dt
    for q in ("impedance", "element_length", "rod_start", "node_x", "element_x"):
        assert np.array_equal(getattr(la, q), getattr(lb, q)), q
    assert la.rods[0].method == lb.rods[0].method
    for ra, rb in zip(la.rods, lb.rods):
        for q in ("n_elements", "time_scale", "true_length", "true_mass", "lattice_mass", "true_travel_time", "exact",
                  "max_boundary_offset"):
            assert getattr(ra, q) == getattr(rb, q), q
    assert a.diagnostics["steps"] == b.diagnostics["steps"]
    assert a.diagnostics["lattice_report"] == b.diagnostics["lattice_report"]
    assert (a.record_every, a.n_steps) == (b.record_every, b.n_steps)
    assert len(a.junction_events) == len(b.junction_events)
    for ea, eb in zip(a.junction_events, b.junction_events):
        for q in ("start", "stop", "max_abs_force"):
            x, y = getattr(ea, q), getattr(eb, q)
            assert x.dtype == y.dtype and np.array_equal(x, y), q
        assert (ea.min_force, ea.min_force_step, ea.max_abs_force_run) == \
            (eb.min_force, eb.min_force_step, eb.max_abs_force_run)


@pytest.mark.parametrize("engine", ENGINES)
def test_save_load_gives_identical_arrays(tmp_path, engine):
    res = three_rod_result()
    save(res, tmp_path / "out", engine=engine)
    back = load(tmp_path / "out")
    assert_identical(res, back)
    assert [r.name for r in back.system.rods] == ["striker", "adapter", "bar"]
    assert back.system.velocities == (5.0, 0.0, 0.0)
    assert back.contact_duration(0) == res.contact_duration(0)


def test_single_rod_without_junction_or_probes_round_trips(tmp_path):
    res = ri.simulate(ri.System([ri.Rod([ri.Cylinder(1.0, 0.05)])], [0.0],
                                left=ri.ForceEnd((np.array([0.0, 5e-5, 1e-4]), np.array([0.0, -1e3, 0.0])))), steps=300,
                      dt=1e-6)
    save(res, tmp_path / "one")
    back = load(tmp_path / "one")
    assert back.junction_force.shape == (0, 300) and back.snapshots is None
    assert_identical(res, back)


def test_csv_files_hold_the_arrays_with_units_in_the_headers(tmp_path):
    res = three_rod_result()
    save(res, tmp_path / "out")
    with open(tmp_path / "out" / "signals.csv") as fh:
        rows = list(csv.reader(fh))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    assert header[:3] == ["time [s]", "contact_force_0 [N]", "in_contact_0 [-]"]
    assert "SG 1.force [N]" in header and "a,b.strain [-]" in header
    assert np.array_equal(data[:, 0], res.time)
    assert np.array_equal(data[:, header.index("contact_force_0 [N]")], res.junction_force[0])
    assert np.array_equal(data[:, header.index("contact_force_1 [N]")], res.junction_force[1])
    assert np.array_equal(data[:, header.index("right_end_velocity [m/s]")], res.end_velocity["right"])
    assert np.array_equal(data[:, header.index("a,b.displacement [m]")], res.probe("a,b").displacement)
    with open(tmp_path / "out" / "energy.csv") as fh:
        rows = list(csv.reader(fh))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    assert np.array_equal(data[:, header.index("total_energy [J]")], res.energy.total)
    assert np.array_equal(data[:, header.index("bar.kinetic_energy [J]")], res.energy.kinetic[2])
    assert np.array_equal(data[:, header.index("work_friction [J]")], res.energy.work_friction)


def test_summary_against_hand_calculation_for_equal_impedance_rods(tmp_path):
    """Equal impedances Z, striker L1 < bar L2 at v: contact force -Z v / 2 for 2 L1 / c, then separation;
    the striker stops and the bar carries all momentum: rigid-body velocity v L1 / L2, energy transfer 1."""
    L1, L2, v, d = 0.4, 1.6, 3.0, 0.05
    z = ri.STEEL.impedance(np.pi / 4 * d**2)
    dt = L1 / C / 40
    rods = [ri.Rod([ri.Cylinder(L1, d)], name="striker"), ri.Rod([ri.Cylinder(L2, d)], name="bar")]
    model = Model(ri.System(rods, [v, 0.0]), duration=1.9 * L2 / C, dt=dt, output=OutputSpec(snapshot_count=None))
    s = summarize(model.simulate())
    j = s["junctions"][0]
    assert j["peak_compressive_force_N"] == pytest.approx(-z * v / 2, rel=1e-12)
    assert j["contact_duration_s"] == pytest.approx(2 * L1 / C, rel=1e-9)
    assert j["separation_times_s"] == pytest.approx([2 * L1 / C], rel=1e-9) and j["recontact_times_s"] == []
    assert s["rods"][0]["final_rigid_body_velocity_m_s"] == pytest.approx(0.0, abs=1e-9)
    assert s["rods"][1]["final_rigid_body_velocity_m_s"] == pytest.approx(v * L1 / L2, rel=1e-9)
    assert s["energy_transfer"] == pytest.approx(1.0, rel=1e-9)
    assert s["energy_balance_error"] < 1e-12
    assert json.loads(json.dumps(s)) == s


def test_existing_output_is_never_silently_overwritten(tmp_path):
    res = three_rod_result()
    out = tmp_path / "out"
    out.mkdir()
    (out / "precious.txt").write_text("keep me")
    with pytest.raises(OutputExistsError, match="exists and is not empty"):
        save(res, out)
    assert os.listdir(out) == ["precious.txt"]
    with pytest.raises(OutputExistsError, match="holds files rodimpact did not write"):
        save(res, out, overwrite=True)     # overwrite only replaces folders rodimpact wrote
    assert os.listdir(out) == ["precious.txt"]
    (out / "precious.txt").unlink()
    save(res, out)
    (out / "result.nc").write_bytes(b"old")
    save(res, out, overwrite=True)         # earlier results are replaced
    assert (out / "result.nc").read_bytes() != b"old" and load(out).n_steps == res.n_steps
    assert [p for p in os.listdir(tmp_path) if p.startswith(".")] == []     # no temporary folders left
    empty = tmp_path / "empty"
    empty.mkdir()
    save(res, empty)                     # an empty folder holds nothing to overwrite
    assert (empty / "summary.json").is_file()


def test_failed_save_leaves_nothing_behind(tmp_path, monkeypatch):
    import rodimpact.io.results as results

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(results, "_write_csv", boom)
    with pytest.raises(RuntimeError, match="disk full"):
        save(three_rod_result(), tmp_path / "out")
    assert os.listdir(tmp_path) == []
    monkeypatch.undo()
    out = tmp_path / "old"
    save(three_rod_result(), out)
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    monkeypatch.setattr(results, "_write_csv", boom)
    with pytest.raises(RuntimeError):
        save(three_rod_result(), out, overwrite=True)
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before
    assert sorted(os.listdir(tmp_path)) == ["old"]


def test_python_callables_give_results_without_model_file(tmp_path):
    rod = ri.Rod([ri.AreaFunction(1.0, lambda s: 1e-3 * (1 + 0 * s))])
    res = ri.simulate([rod, ri.Rod([ri.Cylinder(1.0, 0.04)])], [2.0, 0.0], steps=100, dt=2e-6)
    save(res, tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert "model.toml" not in summary["files"] and "model.toml not written" in summary["notes"][0]
    back = load(tmp_path / "out")
    assert back.system is None
    assert np.array_equal(back.contact_force, res.contact_force)


def test_load_of_a_folder_without_results_says_so(tmp_path):
    with pytest.raises(FileNotFoundError, match=r"no result here \(none of result.nc, synthesis.nc, design.nc"):
        load(tmp_path)


def test_save_writes_data_only_and_says_where_the_figures_went(tmp_path):
    """io never draws (issue 21): the figures of a results folder come from rodimpact.output_folders."""
    res = three_rod_result()
    with pytest.raises(TypeError, match=r"plots: .*rodimpact.output_folders.write_simulation\(result, outdir"):
        save(res, tmp_path / "out", plots=["forces"])
    with pytest.raises(TypeError, match="snapshot_times: a setting of the snapshot plot"):
        save(res, tmp_path / "out", snapshot_times=[1e-4])
    assert not (tmp_path / "out").exists()
    save(res, tmp_path / "out")
    assert not (tmp_path / "out" / "plots").exists()
