"""Output folders under concurrency and kills (issue 13).

* 50 pairs of simultaneous ``rodimpact simulate ... -o OUT`` (the CLI's ``main`` in two forked processes released
  together): in every pair exactly one run writes its own result and the other is refused; no result is replaced.
* A run killed (SIGKILL) inside the write window leaves the previous result intact (or no folder); the next run
  removes the leftover temporary folder. A run killed between moving the old result aside and moving the new one in
  leaves the old one aside; the next run puts it back (and, without --force, refuses to replace it).
* SIGTERM is handled like Ctrl-C: exit 143, no temporary folder left, the previous result intact.

The kills are deterministic: the real command runs in a new process with the test-only environment variable
``_RODIMPACT_TEST_PAUSE=POINT:FILE`` (rodimpact/io/results.py), which makes it create FILE at POINT of the write
window and wait there; the test sends the signal once FILE exists.
"""

from __future__ import annotations

import io
import json
import multiprocessing
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.io import results
from rodimpact.io.model import loads_model, model_from_result

from robust_inputs import ROOT, small_model

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the tests fork processes (POSIX)")
FORK = multiprocessing.get_context("fork") if hasattr(os, "fork") else None


def _title(folder: Path) -> str:
    return json.loads((folder / "summary.json").read_text())["title"]


def _cli_run(argv: list[str], start, queue) -> None:
    """Child: wait for the start signal, run the command line, report (exit code, stderr)."""
    err = io.StringIO()
    sys.stderr = err
    start.wait()
    code = cli.main(argv)
    queue.put((argv[1], code, err.getvalue()))


def test_50_pairs_of_simultaneous_runs_into_one_folder(tmp_path):
    for name in ("a", "b"):
        (tmp_path / f"{name}.toml").write_text(small_model(f"run {name}"))
    assert cli.main(["simulate", str(tmp_path / "a.toml"), "-o", str(tmp_path / "warm"), "--quiet"]) == 0
    outcomes = []
    for k in range(50):
        out = tmp_path / f"o{k}"
        start, queue = FORK.Event(), FORK.Queue()
        procs = [FORK.Process(target=_cli_run, args=(["simulate", str(tmp_path / f"{n}.toml"), "-o", str(out),
                                                      "--quiet"], start, queue)) for n in ("a", "b")]
        for p in procs:
            p.start()
        start.set()
        reports = [queue.get(timeout=120) for _ in procs]
        for p in procs:
            p.join(60)
            assert p.exitcode == 0
        codes = {Path(model).stem: code for model, code, _ in reports}
        assert sorted(codes.values()) == [0, 2], reports            # one writes, the other is refused
        winner = next(n for n, c in codes.items() if c == 0)
        assert _title(out) == f"run {winner}"                       # the folder holds the winner's own result
        refusal = next(e for _, c, e in reports if c == 2)
        assert ("another rodimpact run is writing this output folder now" in refusal
                or "exists and is not empty" in refusal), refusal
        outcomes.append("claimed" if "another rodimpact run" in refusal else "after")
        # nothing else is left beside it: no temporary folders, no lock files
        assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith((f".o{k}.", f"o{k}-"))) == []
    assert len(outcomes) == 50
    assert outcomes.count("claimed") >= 1          # the pairs did meet (else this would test nothing)


def _small_result():
    return loads_model(small_model("x")).simulate()


#: Where a writer is stopped inside the write window (``_RODIMPACT_TEST_PAUSE``, rodimpact/io/results.py) and what
#: its temporary folder then holds.
INSIDE = {"entered": "the temporary folder, nothing written yet",
          "csv": "signals.csv half written (its header only), result.nc already complete",
          "finishing": "every file written, just before the rename"}


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _stopped_at(point: str, model: Path, out: Path, sig: int = signal.SIGKILL) -> tuple[int, str]:
    """Run ``rodimpact simulate MODEL -o OUT --force`` (the installed command's entry point) in a new process that
    stops at ``point`` of the write window; once it says it is there, send it ``sig``. Returns (exit code,
    stderr). Deterministic: the signal always lands at ``point``, however loaded the machine is."""
    flag = out.parent.parent / f"at-{point}"
    env = {**os.environ, "PYTHONPATH": str(ROOT), "_RODIMPACT_TEST_PAUSE": f"{point}:{flag}"}
    code = "import sys, rodimpact_cli; sys.argv[0] = 'rodimpact'; raise SystemExit(rodimpact_cli.main())"
    proc = subprocess.Popen([sys.executable, "-c", code, "simulate", str(model), "-o", str(out), "--force",
                             "--quiet"], env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        t0 = time.monotonic()
        while not flag.exists():
            if proc.poll() is not None:
                pytest.fail(f"the writer ended (exit {proc.returncode}) without reaching {point!r}: "
                            f"{proc.stderr.read()}")
            assert time.monotonic() - t0 < 600, f"the writer did not reach {point!r} in 10 minutes"
            time.sleep(0.02)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    flag.unlink()
    return proc.returncode, err


@pytest.fixture
def runs(tmp_path):
    """(model file of a run titled 'new', output folder tmp_path/runs/out, the small result)."""
    model = tmp_path / "m.toml"
    model.write_text(small_model("new"))
    (tmp_path / "runs").mkdir()
    return model, tmp_path / "runs" / "out", _small_result()


@pytest.mark.parametrize("point, previous", [("entered", True), ("csv", True), ("csv", False), ("finishing", True)],
                         ids=["entered", "csv", "csv-into-a-new-folder", "finishing"])
def test_a_run_killed_inside_the_write_window_leaves_the_previous_result_and_the_next_run_cleans_up(
        runs, point, previous):
    """SIGKILL at each point of the write window (issue 20, item 20: a kill at a random time rarely landed inside
    it): the output folder is the previous result byte for byte (or still absent), never a half-written one; the
    killed run's temporary folder holds what it had written; the next run removes it."""
    model, out, res = runs
    if previous:
        ri.save(res, out, model=model_from_result(res, title="old"))
    before = _files(out) if previous else None
    code, err = _stopped_at(point, model, out)
    assert code == -signal.SIGKILL, err
    assert (_files(out) if out.exists() else None) == before                  # intact, or still absent
    leftovers = [p for p in out.parent.iterdir() if p.name.startswith(".out.tmp-")]
    assert len(leftovers) == 1
    assert {p.name for p in out.parent.iterdir()} <= {"out", ".out.rodimpact-lock", leftovers[0].name}
    written = sorted(_files(leftovers[0]))
    if point == "entered":
        assert written == [results.MARKER]
    elif point == "csv":
        assert written == sorted([results.MARKER, "model.toml", results.RESULT_FILE, "signals.csv"])
        text = (leftovers[0] / "signals.csv").read_text()
        assert text.startswith("time [s],") and text.count("\n") == 1            # the header, no rows
    else:
        assert "summary.json" in written and "energy.csv" in written
    assert cli.main(["simulate", str(model), "-o", str(out), "--force", "--quiet"]) == 0
    assert _title(out) == "new" and ri.load(out).n_steps == res.n_steps
    assert [p.name for p in out.parent.iterdir()] == ["out"]                   # leftover and lock gone


def test_a_run_killed_between_the_renames_gets_the_old_result_back(runs):
    model, out, res = runs
    ri.save(res, out, model=model_from_result(res, title="old"))
    before = _files(out)
    code, err = _stopped_at("aside", model, out)
    assert code == -signal.SIGKILL, err
    assert not out.exists()                                     # the old result was moved aside ...
    aside = [p for p in out.parent.iterdir() if p.name.startswith(".out.old-")]
    assert len(aside) == 1 and _files(aside[0]) == before
    with pytest.raises(results.OutputExistsError, match="exists and is not empty"):
        ri.save(res, out, model=model_from_result(res, title="newer"))     # ... put back, and not replaced
    assert _files(out) == before
    assert [p.name for p in out.parent.iterdir()] == ["out"]


def test_sigterm_is_handled_like_ctrl_c(runs):
    """SIGTERM while signals.csv is half written: exit 143, one line, the previous result intact, nothing left."""
    model, out, res = runs
    ri.save(res, out, model=model_from_result(res, title="old"))
    before = _files(out)
    code, err = _stopped_at("csv", model, out, signal.SIGTERM)
    assert code == 128 + signal.SIGTERM
    assert err == "rodimpact: error: terminated; no partial results were written\n"
    assert _files(out) == before
    assert [p.name for p in out.parent.iterdir()] == ["out"]


def test_only_leftovers_of_this_folder_are_removed(tmp_path):
    """The next run into OUT removes hidden ``.OUT.tmp-XXXXXXXX`` folders that hold rodimpact's marker, and
    nothing else: not folders of other targets, not folders without the marker, not names of another form."""
    def folder(name: str, marker: bool) -> Path:
        p = tmp_path / name
        p.mkdir()
        if marker:
            (p / results.MARKER).write_text("This folder was written by rodimpact\n")
        (p / "data.txt").write_text("x")
        return p

    removed = folder(".out.tmp-abcd1234", True)
    kept = [folder(".out.tmp-abcd12345", True), folder(".out.tmp-zzzz9999", False), folder(".other.tmp-abcd1234", True),
            folder(".out.tmp-abc.tmp-abcd1234", True), folder("out.tmp-abcd1234", True)]
    res = _small_result()
    ri.save(res, tmp_path / "out", model=model_from_result(res, title="t"))
    assert not removed.exists()
    assert all((p / "data.txt").is_file() for p in kept)

