"""`rodimpact synthesize SPEC.toml` and `rodimpact init synthesize`: end to end, against the thesis's numbers
(Lundberg-Lesser comparison of Sec. 4.2.1, percussion-drilling round trip of Sec. 4.2.2) and bad input."""

import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.inverse import lundberg_lesser_impedance
from rodimpact.io.synthesis_spec import TEMPLATE, loads_spec, run, spec_reference_markdown
from rodimpact.output_folders import write_spec_run

RODIMPACT = [sys.executable, "-m", "rodimpact"]


def run_cli(*args, cwd, code):
    env = {k: v for k, v in os.environ.items() if k != "RODIMPACT_DEBUG"}
    p = subprocess.run(RODIMPACT + list(args), cwd=cwd, capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == code, (p.stdout, p.stderr)
    return p


def test_init_synthesize_then_synthesize_reproduces_lundberg_lesser(tmp_path):
    """The template is thesis academic example 1 (Tab. 4.2): v = 6 m/s, -239 kN exp(-t/0.383 ms), n = 100,
    dt = 1.93 us, on a semi-infinite 50 mm steel bar. The thesis reports a maximum impedance error of
    1.10e-3 % against Lundberg and Lesser's closed form (eq. 4.26); the first element follows from eq. 4.4."""
    run_cli("init", "synthesize", cwd=tmp_path, code=0)
    p = run_cli("synthesize", "synthesis.toml", "-o", "out", "--json", cwd=tmp_path, code=0)
    summary = json.loads(p.stdout)
    assert summary["feasible"] and summary["n_feasible"] == 100
    assert summary["verification"]["max_deviation"] < 1e-12
    out = tmp_path / "out"
    assert {"spec.toml", "report.txt", "striker.csv", "synthesis.nc", "summary.json", "plots", "verification"} <= \
        {f.name for f in out.iterdir()}
    assert {"impedance.png", "force.png", "existence.png", "shape.png"} <= {f.name for f in (out / "plots").iterdir()}
    res = ri.load(out / "synthesis.nc")
    z_bar = ri.STEEL.impedance(math.pi / 4 * 0.05**2)
    assert res.impedance[0] == pytest.approx(1.0 / (6.0 / 239e3 - 1.0 / z_bar), rel=1e-12)     # eq. 4.4
    exact = lundberg_lesser_impedance(res.theta, 239e3, 0.383e-3, z_bar, 6.0)
    assert np.max(np.abs(res.impedance / exact - 1)) == pytest.approx(1.10e-5, rel=0.1)
    # the verification folder holds a model file that `rodimpact simulate` runs: striker + struck bar
    from rodimpact.io.model import load_model
    m = load_model(out / "verification" / "model.toml")
    assert m.system.rods[0].name == "striker" and m.system.velocities[0] == 6.0
    np.testing.assert_array_equal(m.system.rods[0].native.impedance, res.impedance[::-1])


def test_bad_spec_and_existing_output(tmp_path, capsys, monkeypatch):
    (tmp_path / "bad.toml").write_text(TEMPLATE.replace('peak = "239 kN"', 'peak = "-239 kN"'))
    p = run_cli("synthesize", "bad.toml", "-o", "out", cwd=tmp_path, code=2)
    assert p.stderr.strip() == "rodimpact: error: target.peak: must be > 0, got -239 kN"
    assert not (tmp_path / "out").exists()
    monkeypatch.chdir(tmp_path)
    cases = [(TEMPLATE.replace('type = "exponential-decay"', 'type = "exponential-decline"'),
              "target.type: unknown type 'exponential-decline' (did you mean 'exponential-decay'?)"),
             (TEMPLATE.replace('velocity = "6 m/s"', 'velocity = "-6 m/s"'), "striker.velocity: must be > 0"),
             (TEMPLATE.replace('elements = 100', 'element = 100'), "striker.element: unknown key"),
             (TEMPLATE.replace('velocity = "6 m/s"', 'velocity = "0.5 m/s"'), "error: striker.velocity: 0.5 m/s")]   # the key, not the argument
    for text, message in cases:
        (tmp_path / "b.toml").write_text(text)
        assert cli.main(["synthesize", "b.toml", "-o", "o2"]) == 2
        assert message in capsys.readouterr().err
    (tmp_path / "good.toml").write_text(TEMPLATE)
    assert cli.main(["synthesize", "good.toml", "-o", "o3", "--quiet", "--no-plots"]) == 0
    assert cli.main(["synthesize", "good.toml", "-o", "o3"]) == 2
    assert "o3: exists and is not empty" in capsys.readouterr().err


def test_percussion_drilling_spec_round_trip_at_machine_precision(tmp_path):
    """Thesis Sec. 4.2.2: the incident force -187 kN exp(5.88 t/ms) prescribed at the bit-rock interface of the
    drill string (Tab. 4.5, k1 = 300 MN/m), piston of 100 elements (0.5 m) at 9 m/s. The thesis's round trip
    error is 1.13e-12 %: simulating the synthesized piston reproduces the target to rounding."""
    spec = loads_spec("""
        title = "percussion drilling piston"
        far_end = { type = "bit-rock", loading_stiffness = "300 MN/m" }
        [striker]
        velocity = "9.00 m/s"
        elements = 100
        [target]
        type = "exponential-growth"
        initial = "187 kN"
        rate = "5.88 1/ms"
        position = "2.0 m"
        quantity = "incident"
        rule = "start"
        [[struck]]
        name = "drill string"
        [struck.elements]
        element_length = "5 mm"
        runs = [{ impedance = "51.0 kN s/m", count = 70 }, { impedance = "115 kN s/m", count = 30 },
                { impedance = "79.7 kN s/m", count = 250 }, { impedance = "156 kN s/m", count = 10 },
                { impedance_start = "156 kN s/m", impedance_end = "248 kN s/m", count = 40 }]
        """.replace("\n        ", "\n"))
    r = run(spec)
    assert r.result.n_feasible == 100 and r.result.feasible
    assert r.verification.max_deviation < 1e-13
    summary = write_spec_run(r, spec, tmp_path / "drill", plots=False)
    assert summary["position_m"] == pytest.approx(2.0)
    assert summary["striker"]["length_m"] == pytest.approx(0.5, rel=1e-9)


def test_spec_reference_is_in_the_cli_docs():
    from pathlib import Path

    page = (Path(__file__).parents[2] / "docs" / "cli.md").read_text(encoding="utf-8")
    assert spec_reference_markdown() in page, "docs/cli.md: regenerate the spec reference section"


def test_a_striker_that_does_not_exist_over_the_requested_span_says_so_first_and_exits_3(tmp_path):
    """Issue 20, item 2: a growing target that only 5 of 25 elements can produce. The summary's first line says
    that no exact striker exists and over which span it does; the verification names that span; `rodimpact design`
    is suggested; the existence diagnosis is printed once; the exit status is 3 (docs/cli.md) and the partial
    result is written."""
    spec = (TEMPLATE.replace("elements = 100 ", "elements = 25 ")
            .replace('type = "exponential-decay"', 'type = "exponential-growth"')
            .replace('peak = "239 kN"', 'initial = "400 kN"').replace('time_constant = "0.383 ms"', 'rate = "20000 1/s"'))
    (tmp_path / "grow.toml").write_text(spec)
    p = run_cli("synthesize", "grow.toml", "-o", "out", cwd=tmp_path, code=3)
    lines = p.stdout.splitlines()
    dt = 1.93e-6
    assert lines[0].startswith("NO EXACT STRIKER") and "only elements 1..5 of 25 exist" in lines[0], lines[0]
    assert f"0 <= t < {10 * dt:.4g} s" in lines[0] and f"requested {50 * dt:.4g} s" in lines[0]
    verification = next(line for line in lines if line.startswith("verification"))
    assert f"only over the span that exists, 0 <= t < {10 * dt:.4g} s" in verification
    assert any("rodimpact design" in line for line in lines)
    assert (p.stdout + p.stderr).count("existence condition") == 1
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert not summary["feasible"] and summary["n_feasible"] == 5
    assert summary["exact_span_s"] == pytest.approx(10 * dt, rel=1e-12)
    # --json reports the same and keeps the exit status
    p = run_cli("synthesize", "grow.toml", "--no-output", "--json", cwd=tmp_path, code=3)
    assert json.loads(p.stdout)["n_feasible"] == 5
