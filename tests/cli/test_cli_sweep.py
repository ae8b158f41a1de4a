"""Everyday use from the shell (issue 14, item 5): ``rodimpact sweep`` writes one table, ``--set`` overrides keys on
every command, ``--no-output`` writes nothing, and ``--json`` without ``-o`` only prints (so the user guide's
sequence works: a JSON summary after the results folder exists)."""

import csv
import json
import os

import pytest

from rodimpact import cli
from rodimpact.io import load_model
from rodimpact.io.model_sweep import parse_grid, split_values
from rodimpact.io.synthesis_spec import TEMPLATE as SYNTHESIS

MODEL = """
title = "striker on a bar"
[[rods]]
name = "striker"
velocity = "5 m/s"
[[rods.segments]]
shape = "cylinder"
length = "0.2 m"
diameter = "40 mm"
[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "0.6 m"
diameter = "40 mm"
[[probes]]
name = "SG1"
rod = "bar"
position = "0.5 m"
[simulation]
duration = "0.4 ms"
dt = "0.9661 us"               # 5 mm elements
"""


def main(args, cwd, capsys, monkeypatch):
    """``rodimpact ARGS`` in this process (the console script's entry point); returns (code, stdout, stderr)."""
    monkeypatch.chdir(cwd)
    monkeypatch.delenv("RODIMPACT_DEBUG", raising=False)
    try:
        code = cli.main(list(args))
    except SystemExit as exc:               # argparse usage errors
        code = exc.code
    cap = capsys.readouterr()
    return code, cap.out, cap.err


@pytest.fixture
def model(tmp_path):
    (tmp_path / "m.toml").write_text(MODEL, encoding="utf-8")
    return tmp_path


def _files(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_sweep_writes_one_table_of_the_runs_simulate_would_do(model, capsys, monkeypatch):
    code, out, err = main(["sweep", "m.toml", "--grid", "rods.striker.velocity=4 m/s,6",
                           "--grid", "rods[1].segments[0].length=0.5 m,0.8 m", "--set", "simulation.dt=0.48305 us"],
                          model, capsys, monkeypatch)
    assert code == 0, err
    folder = model / "results" / "m-sweep"
    assert _files(folder) == [".rodimpact-output", "summary.json", "sweep.csv", "sweep.nc", "sweep.png"]
    with open(folder / "sweep.csv", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    # the grid values in SI units, the unit in the header (as for the quantities)
    assert [(r["rods.striker.velocity [m/s]"], r["rods[1].segments[0].length [m]"]) for r in rows] == [
        ("4.0", "0.5"), ("4.0", "0.8"), ("6.0", "0.5"), ("6.0", "0.8")]
    alone = load_model(model / "m.toml", {"rods.striker.velocity": 6, "rods[1].segments[0].length": "0.8 m",
                                          "simulation.dt": "0.48305 us"}).simulate()
    assert float(rows[3]["peak_contact_force [N]"]) == alone.junction_events[0].min_force
    assert float(rows[3]["striker_final_velocity [m/s]"]) == pytest.approx(alone.rigid_body_velocity[0], abs=1e-12)
    assert "peak contact force [kN]" in out and "table written to" in out
    assert any(line.split()[:2] == ["6", "0.8"] for line in out.splitlines())
    assert "rods.striker.velocity [m/s]" in out
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["overrides"] == {"simulation.dt": "0.48305 us"} and summary["points"] == 4 and len(summary["rows"]) == 4


def test_a_sweep_over_the_striker_velocity_runs_as_one_batch(model, capsys, monkeypatch):
    code, out, err = main(["sweep", "m.toml", "--grid", "rods.striker.velocity=3,4,5", "--json"],
                          model, capsys, monkeypatch)
    assert code == 0, err
    summary = json.loads(out)
    assert summary["runner"] == "simulate_batch" and not (model / "results").exists()
    assert [r["rods.striker.velocity"] for r in summary["rows"]] == [3, 4, 5]


def test_nothing_a_user_saved_is_overwritten(model, capsys, monkeypatch):
    args = ["sweep", "m.toml", "--grid", "rods.striker.velocity=3,4", "-o", "study"]
    assert main(args, model, capsys, monkeypatch)[0] == 0
    code, _, err = main(args, model, capsys, monkeypatch)
    assert code == 2 and "study: exists and is not empty" in err
    (model / "study" / "notes.txt").write_text("mine")
    code, _, err = main(args + ["--force"], model, capsys, monkeypatch)
    assert code == 2 and "holds files rodimpact did not write (notes.txt)" in err
    os.remove(model / "study" / "notes.txt")
    assert main(args + ["--force"], model, capsys, monkeypatch)[0] == 0


@pytest.mark.parametrize("args, message", [
    (["--grid", "rods.striker.velocty=3,4"], r"rods[0].velocty: unknown key (did you mean 'velocity'?)"),
    (["--grid", "rods.hammer.velocity=3,4"], "rods.hammer.velocity: rods has no entry named 'hammer' (names: "
                                             "striker, bar; or give an index, e.g. rods[0])"),
    (["--grid", "rods.striker.velocity=3,4 kg"], "rods[0].velocity: expected a velocity"),
    (["--grid", "rods.striker.velocity=3,,4"], "--grid rods.striker.velocity: an empty value"),
    (["--grid", "rods.striker.velocity"], "--grid 'rods.striker.velocity': expected KEY=VALUE"),
    (["--grid", "rods.striker.velocity=3,3"], "rods.striker.velocity: the values [3, 3] repeat"),
    (["--grid", "rods.striker.velocity=3", "--set", "rods.striker.velocity=4"], "rods.striker.velocity: both swept "
                                                                                "and set"),
    (["--grid", "rods.striker.velocity=3", "--set", "simulation.dt=-1 us"], "simulation.dt: must be > 0"),
    (["--grid", "rods.striker.velocity=3", "--grid", "rods.striker.velocity=4"], "given twice"),
])
def test_bad_grids_name_the_key(model, capsys, monkeypatch, args, message):
    code, out, err = main(["sweep", "m.toml", "--no-output", *args], model, capsys, monkeypatch)
    assert code == 2 and message in err and "Traceback" not in err, err
    assert _files(model) == ["m.toml"]


def test_probes_do_not_limit_a_sweep(model, capsys, monkeypatch):
    """A sweep records no probes: a bar shortened to end before the probe (0.5 m) is no error."""
    code, out, err = main(["sweep", "m.toml", "--no-output", "--grid", "rods[1].segments[0].length=0.1 m,1 m"],
                          model, capsys, monkeypatch)
    assert code == 0 and err == "", err


def test_grid_values_are_split_at_top_level_commas():
    assert split_values('4 m/s, 5 m/s,"a,b", [1, 2], { x = 1, y = 2 }') == [
        "4 m/s", "5 m/s", '"a,b"', "[1, 2]", "{ x = 1, y = 2 }"]
    assert parse_grid(["ends.right=free,fixed", "simulation.allow_discretization_error=true,false"]) == {
        "ends.right": ["free", "fixed"], "simulation.allow_discretization_error": [True, False]}


def test_set_overrides_keys_on_simulate_synthesize_and_design(model, capsys, monkeypatch):
    code, out, err = main(["simulate", "m.toml", "--set", "rods.striker.velocity=7 m/s", "--set",
                           "probes.SG1.position=0.1 m", "--json"], model, capsys, monkeypatch)
    assert code == 0, err
    summary = json.loads(out)
    assert summary["rods"][0]["initial_velocity_m_s"] == 7.0 and summary["probes"][0]["position_m"] == 0.1
    code, _, err = main(["simulate", "m.toml", "--no-output", "--set", "rods.striker.velocity=7 kg"],
                        model, capsys, monkeypatch)
    assert code == 2 and "rods[0].velocity: expected a velocity" in err and 'rods.striker.velocity = "7 kg"' in err
    code, _, err = main(["simulate", "m.toml", "--no-output", "--set", "simulation.dt"], model, capsys, monkeypatch)
    assert code == 2 and "--set 'simulation.dt': expected KEY=VALUE" in err
    (model / "s.toml").write_text(SYNTHESIS, encoding="utf-8")
    code, out, err = main(["synthesize", "s.toml", "--set", "striker.velocity=7 m/s", "--set", "striker.elements=20",
                           "--set", "synthesis.verify=false", "-o", "syn", "--json"], model, capsys, monkeypatch)
    assert code == 0, err
    assert json.loads(out)["striker_velocity_m_s"] == 7.0 and json.loads(out)["n_requested"] == 20
    spec = (model / "syn" / "spec.toml").read_text()
    assert 'striker.velocity = "7 m/s"' in spec.splitlines()[0]      # the spec as it ran
    code, out, err = main(["init", "design", "-o", "d.toml"], model, capsys, monkeypatch)
    code, out, err = main(["design", "d.toml", "--no-output", "--json", "--set", "design.elements=12", "--set",
                           "design.starts=1", "--set", "design.max_iterations=3"], model, capsys, monkeypatch)
    assert code == 0, err
    assert json.loads(out)["elements"] == 12


def test_no_output_writes_nothing_and_json_without_o_only_prints(model, capsys, monkeypatch):
    """The user guide's sequence: results exist, then --json prints the summary (it was refused with rc 2)."""
    assert main(["simulate", "m.toml", "-o", "results/m", "--no-plots"], model, capsys, monkeypatch)[0] == 0
    before = _files(model)
    code, out, err = main(["simulate", "m.toml", "-o", "results/m"], model, capsys, monkeypatch)
    assert code == 2 and "exists and is not empty" in err
    code, out, err = main(["simulate", "m.toml", "--json", "--no-plots"], model, capsys, monkeypatch)
    assert code == 0 and json.loads(out)["junctions"][0]["peak_compressive_force_N"] < 0, err
    code, out, err = main(["simulate", "m.toml", "--no-output"], model, capsys, monkeypatch)
    assert code == 0 and "peak contact force" in out and "results written" not in out, err
    for args in (["examples", "run", "first-example", "--no-output"], ["examples", "run", "first-example", "--json"]):
        code, out, err = main(args, model, capsys, monkeypatch)
        assert code == 0 and "255" in out, err
    assert _files(model) == before
    code, out, err = main(["simulate", "m.toml", "--json", "-o", "again", "--no-plots"], model, capsys, monkeypatch)
    assert code == 0 and json.loads(out)["files"] and (model / "again" / "summary.json").is_file()
    code, _, err = main(["simulate", "m.toml", "--no-output", "-o", "x"], model, capsys, monkeypatch)
    assert code == 2 and "not allowed with argument" in err


def test_set_on_examples_run(model, capsys, monkeypatch):
    """--set on 'examples run': the first example at 5 m/s instead of 10 m/s; the first contact force between
    equal impedances Z0 = 51.0 kN s/m is Z0 v / 2 = 127.5 kN (compressive)."""
    code, out, err = main(["examples", "run", "first-example", "--json", "--set", "rods[0].velocity=5 m/s"], model,
                          capsys, monkeypatch)
    assert code == 0, err
    assert json.loads(out)["junctions"][0]["peak_compressive_force_N"] == pytest.approx(-127.5e3, rel=1e-12)
    code, _, err = main(["examples", "run", "first-example", "--no-output", "--set", "rods[0].velocty=5 m/s"],
                        model, capsys, monkeypatch)
    assert code == 2 and "rods[0].velocty" in err
    code, _, err = main(["examples", "show", "first-example", "--set", "rods[0].velocity=5 m/s"], model, capsys,
                        monkeypatch)
    assert code == 2 and "only with 'examples run'" in err


def test_a_drilling_sweep_reports_the_rock(model, capsys, monkeypatch):
    """A model with a bit-rock end: the sweep's table adds the energy into the rock, the drilling efficiency and the
    penetration per blow, equal to a simulate run of the same point; a model without one does not."""
    assert main(["examples", "copy", "percussion-drilling", "-o", "drill.toml"], model, capsys, monkeypatch)[0] == 0
    code, out, err = main(["sweep", "drill.toml", "--grid", "rods[0].velocity=8 m/s,10 m/s", "--json"], model,
                          capsys, monkeypatch)
    assert code == 0, err
    rows = json.loads(out)["rows"]
    rock = load_model(model / "drill.toml", {"rods[0].velocity": "10 m/s"}).simulate().bit_rock[0]
    assert rows[1]["rock_energy"] == pytest.approx(rock.energy, rel=1e-12) and rock.energy > 0
    assert rows[1]["drilling_efficiency"] == pytest.approx(rock.efficiency, rel=1e-12)
    assert rows[1]["penetration_per_blow"] == pytest.approx(rock.penetration, rel=1e-12)
    code, out, err = main(["sweep", "drill.toml", "--grid", "rods[0].velocity=8 m/s,10 m/s", "--no-output"], model,
                          capsys, monkeypatch)
    assert code == 0 and "energy into the rock [J]" in out and "penetration per blow [mm]" in out, err
    code, out, err = main(["sweep", "m.toml", "--grid", "rods[0].velocity=4,5", "--no-output"], model, capsys,
                          monkeypatch)
    assert code == 0 and "energy into the rock" not in out, err


# ---- issue 20, item 13 -------------------------------------------------------------------------------------------
def test_sweep_nc_holds_numbers_in_si_units_with_their_units(model, capsys, monkeypatch):
    """sweep.nc stored the grid values as text ("6 m/s"); now numbers in SI units with a units attribute (a plain
    number is SI in a model file: its unit is the key's), text values such as end names stay text."""
    import xarray as xr

    code, out, err = main(["sweep", "m.toml", "--grid", "rods.striker.velocity=4 m/s,6000 mm/s",
                           "--grid", "rods[1].segments[0].length=0.5,800 mm", "--grid", "ends.right=free,fixed",
                           "-o", "study"], model, capsys, monkeypatch)
    assert code == 0, err
    with xr.open_dataset(model / "study" / "sweep.nc") as ds:
        v, length, end = ds["rods.striker.velocity"], ds["rods[1].segments[0].length"], ds["ends.right"]
        assert v.dtype.kind == "f" and v.values.tolist() == [4.0, 6.0] and v.attrs["units"] == "m/s"
        assert length.dtype.kind == "f" and length.values.tolist() == [0.5, 0.8] and length.attrs["units"] == "m"
        assert end.values.tolist() == ["free", "fixed"]
        # selecting by number works, and the point is the run at 6 m/s on a 0.8 m bar
        peak = float(ds["peak_contact_force"].sel({"rods.striker.velocity": 6.0, "rods[1].segments[0].length": 0.8,
                                                   "ends.right": "fixed"}))
    alone = load_model(model / "m.toml", {"rods.striker.velocity": "6 m/s", "rods[1].segments[0].length": "0.8 m",
                                          "ends.right": "fixed", "probes": []}).simulate()
    assert peak == alone.junction_events[0].min_force
    summary = json.loads((model / "study" / "summary.json").read_text())
    assert summary["grid_units"] == {"rods.striker.velocity": "m/s", "rods[1].segments[0].length": "m",
                                     "ends.right": ""}
    assert "sweep.png" in summary["files"] and (model / "study" / "sweep.png").stat().st_size > 0


def test_no_plots_writes_no_sweep_png(model, capsys, monkeypatch):
    code, out, err = main(["sweep", "m.toml", "--grid", "rods.striker.velocity=3,4", "-o", "study", "--no-plots"],
                          model, capsys, monkeypatch)
    assert code == 0, err
    assert not (model / "study" / "sweep.png").exists() and (model / "study" / "sweep.csv").is_file()


def test_a_grid_too_large_is_refused_before_anything_runs(model, capsys, monkeypatch):
    """A 1e4 x 1e4 grid ran for over a minute, then died with MemoryError; now refused up front, exit status 2."""
    from rodimpact.io.model_sweep import MAX_MODEL_SWEEP_POINTS

    values = ",".join(str(3 + i / 1e4) for i in range(10_000))
    lengths = ",".join(str(0.2 + i / 1e5) for i in range(10_000))
    code, out, err = main(["sweep", "m.toml", "--grid", f"rods.striker.velocity={values}",
                           "--grid", f"rods[1].segments[0].length={lengths}"], model, capsys, monkeypatch)
    assert code == 2 and "Traceback" not in err, err
    assert "--grid: 10,000 x 10,000 values make 100,000,000 points" in err
    assert f"more than the {MAX_MODEL_SWEEP_POINTS:,} one sweep runs" in err
    assert _files(model) == ["m.toml"]
