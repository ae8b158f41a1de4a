"""`rodimpact drive SPEC.toml`, `rodimpact init drive`, `rodimpact docs drive`: the template, the reference page and
bad specs refused with exit code 2 naming the key path."""

from __future__ import annotations

import pytest

from rodimpact import cli
from rodimpact.io.pile_spec import TEMPLATE, loads_spec, spec_reference_markdown
from rodimpact.io.quantities import ModelError


def test_init_drive_writes_the_template(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["init", "drive"]) == 0
    assert capsys.readouterr().out == "wrote drive.toml; edit it, then run:  rodimpact drive drive.toml\n"
    assert (tmp_path / "drive.toml").read_text() == TEMPLATE


def test_docs_drive_prints_the_generated_reference(capsys):
    assert cli.main(["docs", "drive"]) == 0
    out = capsys.readouterr().out
    assert out.rstrip("\n") == spec_reference_markdown().rstrip("\n")
    for key in ("`efficiency`", "`shaft_share`", "`unit_shaft_resistance`", "`capacities`", "`units`"):
        assert key in out


def test_template_builds_its_objects():
    spec = loads_spec(TEMPLATE)
    assert spec.driving.impact_velocity == pytest.approx((2 * 9.80665 * 0.8 * 1.0) ** 0.5, rel=1e-15)
    assert spec.penetration == 15.0 and spec.soil.capacity == 1.5e6 and spec.gauges == {"gauges": 0.6}


@pytest.mark.parametrize("old, new, message", [
    ("efficiency = 0.8\n", "", "driving.efficiency: missing; a drop_height needs the hammer efficiency"),
    ('shaft_quake = "2.54 mm"', 'shaft_quake = "-2.54 mm"', "soil.shaft_quake: must be > 0, got -2.54 mm"),
    ('toe_quake = "2.54 mm"', 'toe_quake = "0 mm"', "soil.toe_quake: must be > 0"),
    ("restitution = 0.8", "restitution = 1.5", r"driving.hammer_cushion.restitution: must (lie|be) in \(0, 1\]"),
    ('penetration = "15 m"', 'penetration = "25 m"', r"soil.penetration: 25 m is deeper than the pile \(20 m long\)"),
    ("shaft_share = 0.5", "shaft_share = 1.5", r"soil.shaft_share: must lie in \[0, 1\]"),
    ('distribution = "triangular"', 'distribution = "custom"\ndepths = ["0 m", "15 m"]\n'
                                    'shaft_resistances = ["0.7 MN"]',
     r"soil.shaft_resistances: must sum to shaft_share x capacity = 750000 N, got 700000 N"),
    ('distribution = "triangular"', 'distribution = "trapezoid"', "soil.top_ratio: needed by the trapezoid"),
    ('ram_mass = "3000 kg"', 'ram_mass = "3000 kg"\nhammer = "vulcan-010"',
     "driving: give exactly one of hammer, ram_mass or \\[driving.ram\\], not hammer and ram_mass"),
])
def test_bad_specs_name_the_key(old, new, message):
    assert old in TEMPLATE
    with pytest.raises(ModelError, match=message):
        loads_spec(TEMPLATE.replace(old, new, 1))


def test_layered_profile_deeper_than_the_pile_names_the_layer():
    with pytest.raises(ModelError, match=r"soil.layers\[1\].bottom: the profile reaches 24 m, deeper than the pile "
                                         r"\(20 m long\)"):
        loads_spec(_layers_spec("24 m"))


def _layers_spec(bottom: str) -> str:
    """The template with a two-layer profile (its second layer down to ``bottom``) instead of a capacity."""
    soil = ('[soil]\npenetration = "15 m"\nperimeter = "1.02 m"\ntoe_area = "0.0824 m^2"\nshaft_quake = "2.54 mm"\n'
            'toe_quake = "2.54 mm"\nshaft_damping = 0.164\ntoe_damping = 0.492\n\n'
            '[[soil.layers]]\nbottom = "10 m"\nunit_shaft_resistance = "20 kPa"\nsetup_factor = 2.0\n\n'
            f'[[soil.layers]]\nbottom = "{bottom}"\nunit_shaft_resistance = "60 kPa"\nunit_toe_resistance = "4 MPa"\n')
    start = TEMPLATE.index("[soil]")
    end = TEMPLATE.index("# Gauge stations")
    return TEMPLATE[:start] + soil + "\n" + TEMPLATE[end:]


def test_layered_spec_builds_the_profile():
    spec = loads_spec(_layers_spec("20 m"))
    r = spec.soil.resistance(15.0)
    assert r.unit_shaft == pytest.approx([20e3 * 1.02 / 2.0, 60e3 * 1.02], rel=1e-15)
    assert r.toe == pytest.approx(4e6 * 0.0824, rel=1e-15)


def test_drive_exits_2_naming_the_key(tmp_path, capsys):
    spec = tmp_path / "drive.toml"
    spec.write_text(TEMPLATE.replace("efficiency = 0.8\n", ""))
    assert cli.main(["drive", str(spec)]) == 2
    assert "rodimpact: error: driving.efficiency: missing" in capsys.readouterr().err


def test_docs_page_holds_the_generated_reference():
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "pile-driving.md").read_text(encoding="utf-8")
    assert spec_reference_markdown() in page, "docs/pile-driving.md: regenerate the spec reference section"


def test_successive_blows_from_the_spec():
    from rodimpact.io.pile_spec import run, summarize_run

    spec = loads_spec(TEMPLATE.replace('kind = "blow"', 'kind = "blow"\nblows = 2'))
    summary = summarize_run(run(spec), spec)
    assert summary["blows"] == 2 and len(summary["permanent_sets_m"]) == 2
    assert summary["permanent_set_m"] == summary["permanent_sets_m"][-1] > 0


def test_successive_blows_only_for_the_blow_analysis():
    text = TEMPLATE.replace('kind = "blow"', 'kind = "bearing-graph"\nblows = 2\ncapacities = ["1 MN"]')
    with pytest.raises(ModelError, match="analysis.blows: successive blows belong to the blow analysis"):
        loads_spec(text)


def test_drive_writes_the_folder_with_the_apis_numbers(tmp_path, capsys, monkeypatch):
    import json

    import numpy as np

    from rodimpact.io.pile_spec import run, summarize_run

    monkeypatch.chdir(tmp_path)
    (tmp_path / "drive.toml").write_text(TEMPLATE)
    assert cli.main(["drive", "drive.toml", "-o", "out"]) == 0
    printed = capsys.readouterr().out
    assert "permanent set" in printed and "blows/0.25 m" in printed and printed.rstrip().endswith("written to out")
    out = tmp_path / "out"
    assert sorted(f.name for f in out.iterdir()) == [".rodimpact-output", "envelope.csv", "head.csv", "plots",
                                                    "spec.toml", "summary.json"]
    assert sorted(f.name for f in (out / "plots").iterdir()) == ["head-force.png", "stress-envelope.png"]
    spec = loads_spec(TEMPLATE)
    r = run(spec)
    written = json.loads((out / "summary.json").read_text())
    assert {k: v for k, v in written.items() if k != "files"} == json.loads(json.dumps(summarize_run(r, spec)))
    head = np.loadtxt(out / "head.csv", delimiter=",", skiprows=1)
    assert np.array_equal(head[:, 1], r.blow.head.force) and np.array_equal(head[:, 3], r.blow.enthru)


def test_bearing_graph_from_the_command_line_in_us_units(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "drive.toml").write_text(TEMPLATE.replace('kind = "blow"', 'kind = "bearing-graph"\n'
                                                          'capacities = ["0.5 MN", "1.5 MN"]'))
    assert cli.main(["drive", "drive.toml", "-o", "out", "--units", "us"]) == 0
    lines = capsys.readouterr().out.splitlines()
    header = next(line for line in lines if "blows/ft" in line)
    assert header.split("|")[0].strip() == "capacity"
    assert any(line.strip().startswith("112.4 kips") for line in lines)      # 0.5 MN = 112.404 kips
    assert sorted(f.name for f in (tmp_path / "out" / "plots").iterdir()) == ["bearing-graph.png"]
    assert (tmp_path / "out" / "table.csv").read_text().splitlines()[0].startswith("capacity [N],permanent_set [m]")
