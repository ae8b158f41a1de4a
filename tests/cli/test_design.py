"""`rodimpact design SPEC.toml` and `rodimpact init design`: end to end and bad input with key paths."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.io.design_spec import TEMPLATE, loads_spec

RODIMPACT = [sys.executable, "-m", "rodimpact"]


def run_cli(*args, cwd, code):
    env = {k: v for k, v in os.environ.items() if k != "RODIMPACT_DEBUG"}
    p = subprocess.run(RODIMPACT + list(args), cwd=cwd, capture_output=True, text=True, timeout=900, env=env)
    assert p.returncode == code, (p.stdout, p.stderr)
    return p


def test_init_design_runs_as_it_is_and_beats_every_uniform_striker(tmp_path):
    """The template (half-sine 80 kN / 100 us on a 20 mm steel bar, 5-60 mm steel striker at 12 m/s): the
    designed striker matches better than the best uniform striker of any allowed diameter (scanned with
    simulate), says why no exact striker exists, and writes the profile, plots and summary."""
    run_cli("init", "design", cwd=tmp_path, code=0)
    p = run_cli("design", "design.toml", "-o", "out", "--json", cwd=tmp_path, code=0)
    s = json.loads(p.stdout)
    out = tmp_path / "out"
    assert {"spec.toml", "striker.csv", "design.nc", "summary.json", "plots", "verification"} <= \
        {f.name for f in out.iterdir()}
    assert {"force.png", "profile.png", "convergence.png"} <= {f.name for f in (out / "plots").iterdir()}
    assert "cannot be produced" in " ".join(s["bounds_diagnosis"]) + s["existence"]
    assert s["verification"]["max_deviation"] < 1e-12
    # independent baseline: uniform strikers of 5..60 mm, 25 elements of 2 us, misfit over the 100 us
    dt, n = 2e-6, 25
    t = dt * np.arange(2 * n)
    target = np.repeat(-80e3 * np.sin(np.pi * (2 * dt * np.arange(n) + dt) / 100e-6), 2)
    bar = ri.Rod([ri.Cylinder(1.0, 0.02)], ri.STEEL)
    best = np.inf
    for d in np.linspace(0.005, 0.06, 56):
        z = ri.STEEL.impedance(np.pi / 4 * d * d)
        sim = ri.simulate(ri.System([ri.Rod.from_impedance([z] * n, dt), bar], [12.0, 0.0], right="nonreflecting"),
                          steps=t.size, dt=dt)
        best = min(best, np.linalg.norm(sim.junction_force[0] - target) / np.linalg.norm(target))
    assert s["misfit"] < 0.8 * best
    assert 0.005 - 1e-12 <= s["outer_diameter_min_m"] and s["outer_diameter_max_m"] <= 0.06 + 1e-12
    # the verification model runs the designed striker
    m = ri.load_model(out / "verification" / "model.toml")
    assert m.system.rods[0].name == "striker" and m.system.velocities[0] == 12.0


SMALL = TEMPLATE.replace("elements = 25", "elements = 6").replace("max_iterations = 50", "max_iterations = 3") \
    .replace('duration = "100 us"', 'duration = "24 us"').replace("100e-6", "24e-6").replace("starts = 2", "starts = 1")


def test_small_spec_options(tmp_path):
    """Velocity bounds, a mass and at most 2 steps from a file spec."""
    spec = loads_spec(SMALL.replace('velocity = "12 m/s"', 'velocity = "12 m/s"\nvelocity_min = "8 m/s"\n'
                                                           'velocity_max = "14 m/s"\nmass = "0.05 kg"')
                      .replace("# max_steps = 3", "max_steps = 2"))
    limits = spec.kwargs["limits"]
    assert limits.velocity_bounds == (8.0, 14.0) and limits.mass == pytest.approx(0.05) and limits.max_steps == 2
    d = spec.design()
    assert d.mass == pytest.approx(0.05, rel=1e-12) and d.steps <= 2 and 8.0 <= d.striker_velocity <= 14.0


@pytest.mark.parametrize("edit, message", [
    (('diameter_min = "5 mm"', 'diameter_min = "-5 mm"'), "striker.diameter_min: must be > 0"),
    (('diameter_max = "60 mm"', ''),
     "striker.diameter_max: missing; give striker.diameter_min and striker.diameter_max together"),
    (('diameter_max = "60 mm"', 'diameter_max = "3 mm"'), "striker.diameter_min: the lower bound exceeds"),
    (('# mass = "0.2 kg"', 'mass = "90 kg"'), "striker.mass: no striker of 6 elements"),
    (('objective = "match"', 'objective = "efficiency"'), "target: the objective 'efficiency' takes no [target]"),
    (('objective = "match"', 'objective = "speed"'), "design.objective"),
    (('elements = 6', 'element = 6'), "design.element: unknown key"),
    (('max_iterations = 3', 'max_iterations = 3\nimprovement = 2'), "design.improvement: must be"),
    (('max_iterations = 3', 'max_iterations = 3\nreloading = false'), "design.reloading: chooses the definition of the efficiency"),
    (('max_iterations = 3', 'max_iterations = 3\nduration = "1 ms"'), "design.duration: the length of the efficiency run"),
    (('velocity = "12 m/s"', 'velocity = "12 m/s"\nvelocity_min = "14 m/s"\nvelocity_max = "8 m/s"'),
     "striker.velocity_min: the lower bound 14 m/s exceeds the upper bound 8 m/s"),
    (('bore = "0 mm"', 'bore = "5 mm"'), "striker.diameter_min: the smallest diameter 0.005 m must exceed the bore"),
    (('starts = 1', 'starts = 1\nmax_steps = 0'), "design.max_steps"),
    (('force = "-80e3 * sin(pi * t / 24e-6)"', 'force = "-80e3 / (t - 6e-6)"'),
     "target.force: the expression '-80e3 / (t - 6e-6)' gives -inf at t = 6e-06; it must be finite"),
])
def test_bad_specs_name_the_key(tmp_path, capsys, monkeypatch, edit, message):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "b.toml").write_text(SMALL.replace(*edit))
    assert cli.main(["design", "b.toml", "-o", "o"]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_efficiency_spec_needs_bit_rock(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    text = SMALL.replace('objective = "match"', 'objective = "efficiency"')
    text = text[:text.index("\n[target]\n")] + text[text.index("\n[[struck]]"):]
    (tmp_path / "e.toml").write_text(text)
    assert cli.main(["design", "e.toml", "-o", "o"]) == 2
    assert "far_end: the 'efficiency' objective" in capsys.readouterr().err


def test_existing_output_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(SMALL)
    assert cli.main(["design", "s.toml", "-o", "o", "--quiet", "--no-plots"]) == 0
    assert cli.main(["design", "s.toml", "-o", "o"]) == 2
    assert "o: exists and is not empty" in capsys.readouterr().err


def test_docs_list_the_design_spec_keys():
    from pathlib import Path

    from rodimpact.io.design_spec import spec_reference_markdown

    page = (Path(__file__).resolve().parents[2] / "docs" / "cli.md").read_text(encoding="utf-8")
    generated = spec_reference_markdown().replace("### ", "#### ").replace("#### Top level",
                                                                           "#### Design spec, top level")
    assert generated in page, "docs/cli.md: regenerate the design spec reference section"


def test_efficiency_spec_first_pass_length_range_and_uniform_reference(tmp_path):
    """Issue 20, items 3 and 6 from a file: `reloading = false` and `elements_min` reach design, and the summary
    says which efficiency was computed, which lengths were designed and the best uniform piston of the mass."""
    from rodimpact.io.design_spec import format_summary, run, summarize_run

    text = SMALL.replace('objective = "match"', 'objective = "efficiency"\nreloading = false\nelements_min = 3')
    text = text[:text.index("\n[target]\n")] + text[text.index("\n[[struck]]"):]
    text = text.replace('far_end = "nonreflecting"',
                        'far_end = { type = "bit-rock", loading_stiffness = "300 MN/m", '
                        'unloading_stiffness = "900 MN/m" }')
    text = text.replace('bore = "0 mm"', 'bore = "0 mm"\nmass = "0.02 kg"')
    spec = loads_spec(text)
    assert spec.kwargs["target"] == ri.EfficiencyObjective(reloading=False) and spec.kwargs["n"] == (3, 6)
    r = run(spec)
    s = summarize_run(r, spec)
    text_summary = format_summary(s, spec)
    assert "first pass only" in s["efficiency_definition"] and "first pass only" in text_summary
    assert s["uniform_reference"]["elements"] is not None
    assert "best uniform piston of the same mass" in text_summary
    assert s["efficiency"] >= s["uniform_reference"]["efficiency"] - 1e-9
    json.dumps(s)


def test_progress_flag_prints_progress_lines_to_stderr(tmp_path, capsys, monkeypatch):
    """Issue 20, item 5: `--progress` asks for the progress lines even when stderr is not a terminal; without it
    a captured (non-terminal) stderr gets none."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(SMALL)
    assert cli.main(["design", "s.toml", "-o", "a", "--no-plots", "--progress"]) == 0
    err = capsys.readouterr().err
    assert "design: start 1" in err and "best so far" in err
    assert cli.main(["design", "s.toml", "-o", "b", "--no-plots"]) == 0
    assert "best so far" not in capsys.readouterr().err
