"""Output folders under concurrency and kills (issue 13).

* 50 pairs of simultaneous ``rodimpact simulate ... -o OUT`` (the CLI's ``main`` in two forked processes released
  together): in every pair exactly one run writes its own result and the other is refused; no result is replaced.
* A run killed (SIGKILL) while writing leaves the previous result intact; the next run removes the leftover
  temporary folder. A run killed between moving the old result aside and moving the new one in leaves the old one
  aside; the next run puts it back (and, without --force, refuses to replace it).
* SIGTERM is handled like Ctrl-C: exit 143, no temporary folder left, the previous result intact.
"""

from __future__ import annotations

import io
import json
import multiprocessing
import os
import signal
import sys
import time
from pathlib import Path

import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.io import results
from rodimpact.io.model import loads_model, model_from_result

from robust_inputs import small_model

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


def _slow_save(out: str, title: str, where: str, flag: str) -> None:
    """Child: save a result into ``out`` (overwrite) and stop for good at ``where`` after touching ``flag``."""
    def stop() -> None:
        Path(flag).touch()
        time.sleep(600)

    if where == "writing":
        real = results._write_csv

        def write_csv(*a, **k):
            real(*a, **k)
            stop()
        results._write_csv = write_csv
    else:                                   # between moving the old result aside and moving the new one in
        real_replace = os.replace

        def replace(src, dst):
            real_replace(src, dst)
            if ".old-" in os.fspath(dst):
                stop()
        results.os.replace = replace
    res = _small_result()
    ri.save(res, out, model=model_from_result(res, title=title), overwrite=True)


def _small_result():
    return loads_model(small_model("x")).simulate()


def _kill_while(where: str, tmp_path: Path, sig: int = signal.SIGKILL) -> int:
    out, flag = tmp_path / "out", tmp_path / "flag"
    proc = FORK.Process(target=_slow_save, args=(str(out), "new", where, str(flag)))
    proc.start()
    t0 = time.monotonic()
    while not flag.exists():
        assert time.monotonic() - t0 < 120 and proc.is_alive(), "the child never reached the point to be killed"
        time.sleep(0.02)
    os.kill(proc.pid, sig)
    proc.join(60)
    return proc.exitcode


def test_a_run_killed_while_writing_leaves_the_previous_result_and_the_next_run_cleans_up(tmp_path):
    res = _small_result()
    out = tmp_path / "out"
    ri.save(res, out, model=model_from_result(res, title="old"))
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    assert _kill_while("writing", tmp_path) == -signal.SIGKILL
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before      # intact
    assert ri.load(out).n_steps == res.n_steps
    leftovers = [p for p in tmp_path.iterdir() if p.name.startswith(".out.tmp-")]
    assert len(leftovers) == 1 and (leftovers[0] / "signals.csv").is_file()            # the killed run's files
    ri.save(res, out, model=model_from_result(res, title="newer"), overwrite=True)
    assert _title(out) == "newer"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flag", "out"]               # leftover and lock gone


def test_a_run_killed_between_the_renames_gets_the_old_result_back(tmp_path):
    res = _small_result()
    out = tmp_path / "out"
    ri.save(res, out, model=model_from_result(res, title="old"))
    assert _kill_while("renaming", tmp_path) == -signal.SIGKILL
    assert not out.exists()                                     # the old result was moved aside ...
    aside = [p for p in tmp_path.iterdir() if p.name.startswith(".out.old-")]
    assert len(aside) == 1 and _title(aside[0]) == "old"
    with pytest.raises(results.OutputExistsError, match="exists and is not empty"):
        ri.save(res, out, model=model_from_result(res, title="newer"))     # ... put back, and not replaced
    assert _title(out) == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flag", "out"]


def test_sigterm_is_handled_like_ctrl_c(tmp_path):
    (tmp_path / "m.toml").write_text(small_model("new"))
    out = tmp_path / "out"
    res = _small_result()
    ri.save(res, out, model=model_from_result(res, title="old"))
    flag = tmp_path / "flag"

    def child() -> None:
        real = results._write_csv

        def write_csv(*a, **k):
            real(*a, **k)
            flag.touch()
            time.sleep(600)
        results._write_csv = write_csv
        err = io.StringIO()
        sys.stderr = err
        code = cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(out), "--force", "--quiet"])
        (tmp_path / "stderr").write_text(err.getvalue())
        sys.exit(code)

    proc = FORK.Process(target=child)
    proc.start()
    t0 = time.monotonic()
    while not flag.exists():
        assert time.monotonic() - t0 < 120 and proc.is_alive()
        time.sleep(0.02)
    os.kill(proc.pid, signal.SIGTERM)
    proc.join(60)
    assert proc.exitcode == 128 + signal.SIGTERM
    assert (tmp_path / "stderr").read_text() == "rodimpact: error: terminated; no partial results were written\n"
    assert _title(out) == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flag", "m.toml", "out", "stderr"]


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

