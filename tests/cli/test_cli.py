"""End-to-end tests of the ``rodimpact`` command (subprocess), including bad input and the no-overwrite rule."""

import argparse
import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import cli

RODIMPACT = [sys.executable, "-m", "rodimpact"]
C = ri.STEEL.wave_speed

GOOD = """
[[rods]]
name = "striker"
velocity = "5 m/s"
[[rods.segments]]
shape = "cylinder"
length = "0.4 m"
diameter = "50 mm"

[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "1.2 m"
diameter = "50 mm"

[[probes]]
name = "SG1"
rod = "bar"
position = "0.2 m"

[simulation]
duration = "0.5 ms"
dt = "2 us"
"""


def run(*args, cwd, check_code=None):
    env = dict(os.environ)
    env.pop("RODIMPACT_DEBUG", None)
    proc = subprocess.run(RODIMPACT + list(args), cwd=cwd, capture_output=True, text=True, timeout=300, env=env)
    if check_code is not None:
        assert proc.returncode == check_code, (proc.stdout, proc.stderr)
    return proc


def main_in_process(args, cwd, capsys, monkeypatch):
    """The same entry point as the console script, called in this process (fast); returns (code, out, err)."""
    monkeypatch.chdir(cwd)
    try:
        code = cli.main(list(args))
    except SystemExit as exc:               # argparse usage errors and --version
        code = exc.code
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_version_and_help(tmp_path, capsys, monkeypatch):
    p = run("--version", cwd=tmp_path, check_code=0)
    assert p.stdout.strip() == f"rodimpact {ri.__version__}"
    code, out, _ = main_in_process([], tmp_path, capsys, monkeypatch)
    assert code == 2 and "simulate" in out and "examples" in out
    code, _, err = main_in_process(["simulate", "--frobnicate", "m.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "unrecognized arguments" in err


def test_init_writes_a_template_that_runs_and_never_overwrites(tmp_path, capsys, monkeypatch):
    p = run("init", cwd=tmp_path, check_code=0)
    assert "wrote model.toml" in p.stdout
    text = (tmp_path / "model.toml").read_text()
    code, _, err = main_in_process(["init", "simulate"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "model.toml: exists" in err
    assert (tmp_path / "model.toml").read_text() == text
    code, out, _ = main_in_process(["init", "simulate", "--force", "--quiet"], tmp_path, capsys, monkeypatch)
    assert code == 0 and out == ""
    p = run("simulate", "model.toml", "-o", "out", "--json", "--no-plots", cwd=tmp_path, check_code=0)
    summary = json.loads(p.stdout)
    assert summary["junctions"][0]["peak_compressive_force_N"] < 0
    assert {pr["name"] for pr in summary["probes"]} == {"SG1", "SG2", "SG3"}
    code, _, err = main_in_process(["init", "bogus"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "no template 'bogus'" in err


def test_simulate_writes_results_plots_and_a_summary(tmp_path):
    (tmp_path / "m.toml").write_text(GOOD)
    p = run("simulate", "m.toml", cwd=tmp_path, check_code=0)
    out = tmp_path / "results" / "m"                      # default output folder
    assert "peak contact force    -" in p.stdout and f"results written to {Path('results') / 'm'}" in p.stdout
    names = {f.name for f in out.iterdir()}
    assert names == {"model.toml", "summary.json", "signals.csv", "energy.csv", "result.nc", "plots",
                     ".rodimpact-output"}                 # the marker that lets --force replace this folder later
    assert {f.name for f in (out / "plots").iterdir()} == {"forces.png", "profile.png", "snapshots.png", "xt.png",
                                                           "energy.png"}
    summary = json.loads((out / "summary.json").read_text())
    z = ri.STEEL.impedance(np.pi / 4 * 0.05**2)
    j = summary["junctions"][0]
    assert j["peak_compressive_force_N"] == pytest.approx(-z * 5.0 / 2, rel=1e-12)       # equal impedances
    assert j["contact_duration_s"] == pytest.approx(0.8 / C, abs=2.1e-6)
    from rodimpact.io import load
    back = load(out)
    assert np.array_equal(back.probe("SG1").force, json_free_probe(out))
    again = tomllib.loads((out / "model.toml").read_text())
    assert again["rods"][0]["velocity"] == 5.0


def json_free_probe(out):
    rows = (out / "signals.csv").read_text().splitlines()
    header = rows[0].split(",")
    i = header.index("SG1.force [N]")
    return np.array([float(r.split(",")[i]) for r in rows[1:]])


def test_quiet_and_json_outputs(tmp_path, capsys, monkeypatch):
    (tmp_path / "m.toml").write_text(GOOD)
    code, out, err = main_in_process(["simulate", "m.toml", "-o", "a", "--quiet", "--no-plots"], tmp_path, capsys,
                                     monkeypatch)
    assert code == 0 and out == "" and err == ""
    code, out, _ = main_in_process(["simulate", "m.toml", "-o", "b", "--json", "--no-plots"], tmp_path, capsys,
                                   monkeypatch)
    data = json.loads(out)
    assert code == 0 and data["steps"] == 250 and data["dt_s"] == 2e-6 and "files" in data


def test_bad_model_exits_2_with_the_key_path_and_writes_nothing(tmp_path, capsys, monkeypatch):
    (tmp_path / "bad.toml").write_text(GOOD.replace('diameter = "50 mm"', 'diameter = "-5 mm"', 1))
    p = run("simulate", "bad.toml", "-o", "out", cwd=tmp_path, check_code=2)
    assert p.stderr.strip() == "rodimpact: error: rods[0].segments[0].diameter: must be > 0, got -5 mm"
    assert p.stdout == "" and not (tmp_path / "out").exists()
    (tmp_path / "unknown.toml").write_text(GOOD.replace('name = "bar"', 'name = "bar"\nvelocty = 1', 1))
    code, _, err = main_in_process(["simulate", "unknown.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rods[1].velocty: unknown key (did you mean 'velocity'?)" in err
    code, _, err = main_in_process(["simulate", "missing.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "missing.toml: no such model file" in err
    (tmp_path / "dt.toml").write_text(GOOD.replace('dt = "2 us"', 'dt = "1 ms"'))
    code, _, err = main_in_process(["simulate", "dt.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "dt: the time step" in err                    # caught by the solver, still input
    assert list(tmp_path.glob("results/*")) == [] and list(tmp_path.glob(".*")) == []


def test_existing_output_is_refused_unless_force(tmp_path, capsys, monkeypatch):
    (tmp_path / "m.toml").write_text(GOOD)
    code, _, _ = main_in_process(["simulate", "m.toml", "-o", "out", "--quiet", "--no-plots"], tmp_path, capsys,
                                 monkeypatch)
    assert code == 0
    before = {f.name: f.read_bytes() for f in (tmp_path / "out").iterdir() if f.is_file()}
    (tmp_path / "m.toml").write_text(GOOD.replace('"5 m/s"', '"7 m/s"'))
    p = run("simulate", "m.toml", "-o", "out", "--no-plots", cwd=tmp_path, check_code=2)
    assert "out: exists and is not empty" in p.stderr and "--force" in p.stderr
    assert {f.name: f.read_bytes() for f in (tmp_path / "out").iterdir() if f.is_file()} == before
    code, _, _ = main_in_process(["simulate", "m.toml", "-o", "out", "--force", "--quiet", "--no-plots"], tmp_path,
                                 capsys, monkeypatch)
    assert code == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["rods"][0]["initial_velocity_m_s"] == 7.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.toml", "out"]       # no temporary folders left


def test_examples_list_show_copy(tmp_path, capsys, monkeypatch):
    p = run("examples", cwd=tmp_path, check_code=0)
    for name in ("first-example", "complex-example", "complex-example-energy", "test-rig", "percussion-drilling"):
        assert name in p.stdout
    code, out, _ = main_in_process(["examples", "list", "--json"], tmp_path, capsys, monkeypatch)
    assert code == 0 and [e["name"] for e in json.loads(out)][0] == "first-example"
    code, shown, _ = main_in_process(["examples", "show", "test-rig"], tmp_path, capsys, monkeypatch)
    assert code == 0 and tomllib.loads(shown)["rods"][1]["name"] == "rod"
    code, _, _ = main_in_process(["examples", "copy", "test-rig", "-o", "rig.toml", "--quiet"], tmp_path, capsys,
                                 monkeypatch)
    assert code == 0 and (tmp_path / "rig.toml").read_text() + "\n" == shown
    code, _, err = main_in_process(["examples", "copy", "test-rig", "-o", "rig.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rig.toml: exists" in err
    p = run("examples", "run", "nope", cwd=tmp_path, check_code=2)
    assert "no example named 'nope'; available: first-example" in p.stderr
    code, _, err = main_in_process(["examples", "run"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "give an example name" in err


def test_readme_first_command_writes_results_and_plots(tmp_path, capsys, monkeypatch):
    """The README's first command ends with `rodimpact examples run first-example -o results/first-example`."""
    p = run("examples", "run", "first-example", "-o", "results/first-example", cwd=tmp_path, check_code=0)
    out = tmp_path / "results" / "first-example"
    assert {"model.toml", "summary.json", "signals.csv", "energy.csv", "result.nc"} <= {f.name for f in out.iterdir()}
    assert {"snapshots.png", "xt.png", "forces.png", "profile.png", "energy.png"} <= \
        {f.name for f in (out / "plots").iterdir()}
    assert "separation at         0.2705 ms" in p.stdout
    from rodimpact.io import load
    res = load(out)
    assert res.contact_force[0] == pytest.approx(-255e3, rel=1e-12)        # -Z0 v / 2 (Tab. 3.1, v = 10 m/s)
    code, _, err = main_in_process(["examples", "run", "first-example", "-o", "results/first-example"], tmp_path,
                                   capsys, monkeypatch)
    assert code == 2 and "exists and is not empty" in err


def test_multi_model_example_writes_subfolders_and_comparison(tmp_path, monkeypatch):
    """complex-example-energy runs two models; run in-process with a coarse time step to stay fast."""
    import dataclasses

    import rodimpact.examples as ex

    original = ex.load_example
    monkeypatch.setattr(ex, "load_example", lambda name, i=0, overrides=None: dataclasses.replace(
        original(name, i, overrides), dt=4e-6, duration=2e-3))
    runs = ex.run_example("complex-example-energy", tmp_path / "e")
    assert [f for f, _, _ in runs] == ["complex-example-friction.toml", "complex-example-no-friction.toml"]
    assert (tmp_path / "e" / "energy-comparison.png").is_file()
    for sub in ("complex-example-friction", "complex-example-no-friction"):
        assert (tmp_path / "e" / sub / "result.nc").is_file()
    ex.run_example("complex-example-energy", tmp_path / "e", overwrite=True, plots=False)   # its own results
    assert not (tmp_path / "e" / "energy-comparison.png").exists()


def test_internal_errors_exit_1_and_say_it_is_a_bug(tmp_path, monkeypatch, capsys):
    (tmp_path / "m.toml").write_text(GOOD)

    def broken(*a, **k):
        raise ZeroDivisionError("oops")

    monkeypatch.setattr("rodimpact.io.results.summarize", broken)
    code = cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(tmp_path / "out"), "--no-plots"])
    assert code == 1
    err = capsys.readouterr().err
    assert "internal error: ZeroDivisionError: oops" in err and "this is a bug" in err
    assert not (tmp_path / "out").exists()


def test_progress_left_to_the_solver_also_without_a_terminal(monkeypatch):
    """Long runs report progress on stderr even when it is no terminal (issue 13); only --quiet silences it."""
    args = argparse.Namespace(quiet=False, json=False)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: False)
    assert cli._progress(args) is None                   # the solver reports long runs (lines without a terminal)
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    assert cli._progress(args) is None                   # ... and a bar on a terminal
    assert cli._progress(argparse.Namespace(quiet=True, json=False)) is False
    assert cli._progress(argparse.Namespace(quiet=False, json=True)) is None     # JSON goes to stdout
