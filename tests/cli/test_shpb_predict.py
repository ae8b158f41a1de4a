"""`rodimpact shpb predict SPEC.toml` and `rodimpact init shpb` (issue 22): the template runs as written, the folder
holds the predicted signals (CSV with units, NetCDF), the plots and the summary of the same numbers as the Python
API; existing folders are refused without --force; bad specs exit with 2 naming the key (docs/cli.md)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from rodimpact import cli
from rodimpact.io.shpb_spec import TEMPLATE, loads_spec, run, spec_reference_markdown, summarize_run

ROOT = Path(__file__).resolve().parents[2]
HEADER = ["time [s]", "incident [-]", "reflected [-]", "incident_gauge [-]", "transmitted [-]", "force [N]",
          "strain [-]", "strain_rate [1/s]", "true_strain [-]", "stress [Pa]", "true_stress [Pa]",
          "incident_gauge_volts [V]", "transmitted_gauge_volts [V]"]


@pytest.fixture(scope="module")
def python_run():
    """The template's prediction and summary through the Python API."""
    spec = loads_spec(TEMPLATE)
    r = run(spec)
    return r.prediction, summarize_run(r, spec)


def test_init_shpb_then_predict_writes_the_signals_plots_and_summary(tmp_path, capsys, monkeypatch, python_run):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["init", "shpb"]) == 0
    assert capsys.readouterr().out == "wrote shpb.toml; edit it, then run:  rodimpact shpb predict shpb.toml\n"
    assert (tmp_path / "shpb.toml").read_text() == TEMPLATE
    assert cli.main(["shpb", "predict", "shpb.toml", "-o", "out"]) == 0
    printed = capsys.readouterr()
    assert printed.out.splitlines()[:2] == ["LANL-like copper shot",
                                            "Kolsky bar: striker at 10 m/s; dt 0.2 us, 2154 steps"]
    assert "specimen (compression positive): max strain 0.02992" in printed.out
    assert printed.out.rstrip().endswith("results written to out")
    assert printed.err.count("warning: specimen: its elastic transit time L0 / c = 0.887 us") == 1
    out = tmp_path / "out"
    assert sorted(f.name for f in out.iterdir()) == [".rodimpact-output", "plots", "prediction.nc", "signals.csv",
                                                    "spec.toml", "summary.json"]
    assert sorted(f.name for f in (out / "plots").iterdir()) == ["signals.png", "strain-rate.png",
                                                                "stress-strain.png"]
    prediction, summary = python_run
    lines = (out / "signals.csv").read_text().splitlines()
    assert lines[0].split(",") == HEADER
    table = np.loadtxt(out / "signals.csv", delimiter=",", skiprows=1)
    columns = [prediction.time] + [getattr(prediction, h.split(" ")[0]) for h in HEADER[1:11]] \
        + [prediction.volts["incident_gauge"], prediction.volts["transmitted_gauge"]]
    for j, expected in enumerate(columns):
        assert np.array_equal(table[:, j], expected), HEADER[j]
    with xr.open_dataset(out / "prediction.nc") as ds:
        assert np.array_equal(ds["transmitted"].values, prediction.transmitted)
        assert ds["stress"].attrs["units"] == "Pa" and ds.attrs["title"] == "LANL-like copper shot"
    written = json.loads((out / "summary.json").read_text())
    assert {k: v for k, v in written.items() if k != "files"} == json.loads(json.dumps(summary))
    assert written["files"] == ["spec.toml", "signals.csv", "prediction.nc", "plots/signals.png",
                                "plots/stress-strain.png", "plots/strain-rate.png", "summary.json"]
    assert written["peak_incident_strain"] == pytest.approx(-1.005e-3, rel=1e-3)     # rho c v / 2 / (rho c^2)
    assert written["strain_rate_plateau"]["start_s"] < written["strain_rate_plateau"]["end_s"]


def test_an_existing_folder_is_refused_and_replaced_with_force(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shot.toml").write_text(TEMPLATE)
    assert cli.main(["shpb", "predict", "shot.toml", "--no-plots", "--quiet"]) == 0
    assert capsys.readouterr().out == ""
    folder = tmp_path / "results" / "shot"                   # the default output folder: results/<spec name>
    assert not (folder / "plots").exists()
    assert cli.main(["shpb", "predict", "shot.toml", "--quiet"]) == 2
    assert "results/shot: exists and is not empty" in capsys.readouterr().err
    assert cli.main(["shpb", "predict", "shot.toml", "--quiet", "--force"]) == 0
    assert (folder / "plots" / "signals.png").is_file()


def test_json_and_overrides_without_an_output_folder(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shot.toml").write_text(TEMPLATE.replace("plots = true", "plots = false"))
    assert cli.main(["shpb", "predict", "shot.toml", "--json", "--set", "input.striker_velocity=12 m/s"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["input"] == {"striker_velocity_m_s": 12.0} and "files" not in summary
    assert not (tmp_path / "results").exists()
    assert cli.main(["shpb", "predict", "shot.toml", "-o", "out", "--quiet"]) == 0
    assert not (tmp_path / "out" / "plots").exists()             # [output] plots = false


def test_the_specimen_inertia_key_gives_the_specimen_its_mass(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shot.toml").write_text(TEMPLATE.replace("plots = true", "plots = false"))
    inertia = ["--set", "simulation.specimen_inertia=true"]
    assert cli.main(["shpb", "predict", "shot.toml", *inertia]) == 2            # the template's dt = 0.2 us
    assert "simulation.dt: rod 2 (specimen): its travel time is represented with a 9.77 % error" \
        in capsys.readouterr().err                                              # cannot resolve the specimen rod
    finer = ["--set", "simulation.dt=0.178195 us"]                              # the step the message proposes
    assert cli.main(["shpb", "predict", "shot.toml", "--json", *inertia, *finer]) == 0
    printed = capsys.readouterr()
    assert "elastic transit time" not in printed.err          # the ring-up is resolved: no equilibrium warning
    assert json.loads(printed.out)["input"] == {"striker_velocity_m_s": 10.0}
    (tmp_path / "light.toml").write_text(TEMPLATE.replace('density = "8960 kg/m^3"', "# no density"))
    assert cli.main(["shpb", "predict", "light.toml", *inertia, *finer]) == 2
    assert capsys.readouterr().err.startswith("rodimpact: error: specimen.density: needed with specimen_inertia")


@pytest.mark.parametrize("change, message", [
    (('b = "292 MPa"', 'b = "-292 MPa"'), "rodimpact: error: specimen.law.b: must be >= 0, got -292 MPa"),
    (('type = "johnson-cook"', 'type = "jonson-cook"'),
     "rodimpact: error: specimen.law.type: unknown type 'jonson-cook' (did you mean 'johnson-cook'?)"),
    (('diameter = "6.34 mm"', 'diameter = "10 mm"'), "rodimpact: error: specimen.diameter: the specimen (10 mm"),
    (('striker_velocity = "10 m/s"', ''), "rodimpact: error: input: give exactly one of striker_velocity"),
])
def test_a_bad_spec_exits_2_naming_the_key_and_writes_nothing(tmp_path, capsys, monkeypatch, change, message):
    monkeypatch.chdir(tmp_path)
    assert change[0] in TEMPLATE
    (tmp_path / "bad.toml").write_text(TEMPLATE.replace(*change))
    assert cli.main(["shpb", "predict", "bad.toml", "-o", "out"]) == 2
    assert capsys.readouterr().err.startswith(message)
    assert not (tmp_path / "out").exists()


def test_the_shpb_group_needs_a_verb_and_documents_its_spec(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["shpb"])
    assert exc.value.code == 2 and "the following arguments are required: VERB" in capsys.readouterr().err
    assert cli.main(["docs", "shpb"]) == 0
    assert capsys.readouterr().out == spec_reference_markdown()


def test_spec_reference_is_in_the_cli_docs():
    page = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    assert spec_reference_markdown() in page, "docs/cli.md: regenerate the Kolsky-bar spec reference section"
