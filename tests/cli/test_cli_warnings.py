"""Warnings on the command line (issue 14, item 6): each warning once, as one clean line ``warning: <message>`` on
stderr, without Python's file/line/source display; nothing at all with ``--quiet``. Run as the console script
runs (a subprocess), since Python's default display is what went wrong."""

import os
import re
import shutil
import json
import subprocess
import sys
from pathlib import Path

import pytest

from rodimpact.io.synthesis_spec import TEMPLATE as SYNTHESIS

ROOT = Path(__file__).resolve().parents[2]
RAW_DISPLAY = re.compile(r"Warning:|\.py:\d+|<frozen|warnings\.warn|sys\.exit")


def rodimpact(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("RODIMPACT_DEBUG", None)
    env.pop("PYTHONWARNINGS", None)
    return subprocess.run([sys.executable, "-m", "rodimpact", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300, env=env)


@pytest.fixture
def files(tmp_path):
    shutil.copy(ROOT / "tests" / "data" / "warning-model.toml", tmp_path / "m.toml")
    (tmp_path / "s.toml").write_text(SYNTHESIS, encoding="utf-8")
    return tmp_path


def _warning_lines(stderr: str) -> list[str]:
    lines = stderr.splitlines()
    assert all(line.startswith("warning: ") for line in lines), stderr
    assert not RAW_DISPLAY.search(stderr), stderr
    assert len(set(lines)) == len(lines), f"a warning is shown twice: {stderr}"
    return lines


def test_each_warning_once_as_one_clean_line(files):
    p = rodimpact("simulate", "m.toml", "-o", "out", "--no-plots", cwd=files)
    assert p.returncode == 0, p.stderr
    lines = _warning_lines(p.stderr)
    assert len(lines) == 2, lines
    assert "rods[0].segments[0].diameter = 20 m: did you mean 20 mm?" in lines[0]
    assert lines[1].startswith("warning: dt: rod 0 (striker): its travel time is represented")
    assert "warning" not in p.stdout                     # not repeated in the summary on stdout


def test_quiet_prints_no_warning(files):
    # the linear ramp cannot be produced over its whole span: the exit status (3) still says so, quietly
    for args, code in ((["simulate", "m.toml", "--no-output", "--quiet"], 0),
                       (["sweep", "m.toml", "--grid", "rods.striker.velocity=3,4", "--no-output", "--quiet"], 0),
                       (["synthesize", "s.toml", "--set", "target.type=linear-ramp", "--no-output", "--quiet"], 3)):
        p = rodimpact(*args, cwd=files)
        assert (p.returncode, p.stdout, p.stderr) == (code, "", ""), (args, p.stdout, p.stderr)


def test_a_sweep_and_a_synthesis_warn_once(files):
    p = rodimpact("sweep", "m.toml", "--grid", "rods.striker.velocity=3,4,5", "--no-output", cwd=files)
    assert p.returncode == 0, p.stderr
    assert len(_warning_lines(p.stderr)) == 2                # the same two warnings at every point: shown once
    p = rodimpact("synthesize", "s.toml", "--set", "target.type=linear-ramp", "--no-output", "--json", cwd=files)
    assert p.returncode == 3, p.stderr                      # thesis academic example 2 stops at its limit:
    summary = json.loads(p.stdout)                           # the existence diagnosis is the summary's own
    assert summary["n_feasible"] == 78 and summary["failure"].startswith("element 79")   # field, not a warning
    (shape,) = _warning_lines(p.stderr)
    assert shape.startswith("warning: striker shape: the outer diameter varies by a factor 126")
    assert summary["warnings"] == [shape.removeprefix("warning: ")]      # listed in the JSON summary too


def test_every_command_in_one_process_shows_its_warnings(files, capsys, monkeypatch):
    """Python shows a warning once per source line and process by default; each command still shows its own."""
    from rodimpact import cli

    monkeypatch.chdir(files)
    for _ in range(2):
        assert cli.main(["simulate", "m.toml", "--no-output"]) == 0
        assert len(_warning_lines(capsys.readouterr().err)) == 2
