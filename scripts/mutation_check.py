"""Mutation check: apply each curated mutation of the physics to a copy of the repository and run its tests.

Every entry of ``scripts/mutations.toml`` is one deliberate mistake in a physics law or numerical scheme:
``file`` (relative to the repository root), ``old`` (exact text, must occur exactly once, or
``count`` times: all are replaced), ``new`` (its
replacement) and ``tests`` (the pytest subset expected to catch it). For each entry the script

1. copies the repository's tracked and untracked-but-not-ignored files to a temporary directory (the working
   tree is never modified),
2. replaces ``old`` by ``new`` there (an ``old`` text that is missing or ambiguous is reported as ``stale``:
   the code was refactored and the entry must be updated),
3. runs ``python -m pytest -x`` on the subset with ``PYTHONPATH`` pointing at the copy and a fresh
   ``NUMBA_CACHE_DIR`` (so the compiled kernels are rebuilt from the mutated source), with a timeout,
4. records ``killed`` (a test failed: its name is reported), ``survived`` (all passed: a gap in the tests),
   ``timeout`` (counted as killed, flagged) or ``stale``.

Usage::

    python scripts/mutation_check.py                       # all mutations, report to docs/mutation-report.md
    python scripts/mutation_check.py --jobs 2              # two at a time
    python scripts/mutation_check.py --only 'bitrock*'     # a selection (fnmatch on the names)
    python scripts/mutation_check.py --check               # only verify that every 'old' text is found once
    python scripts/mutation_check.py --baseline            # also run every subset unmutated first (must pass)
    python scripts/mutation_check.py --state s.json --only 'x*'   # re-check some, keep the others' verdicts
    python scripts/mutation_check.py --state s.json --report-only # rewrite the report from the stored verdicts

Exit status 0 when every mutation is killed, 1 otherwise (survivor, stale entry or failing baseline).
See docs/mutation-testing.md.
"""

from __future__ import annotations

import argparse
import concurrent.futures as cf
import fnmatch
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_LIST = ROOT / "scripts" / "mutations.toml"
DEFAULT_REPORT = ROOT / "docs" / "mutation-report.md"
#: directories never copied (caches, environments, results)
SKIP_PARTS = {".git", ".venv", "__pycache__", ".pytest_cache", ".hypothesis", "results"}


@dataclass(frozen=True)
class Mutation:
    """One entry of the list: replace ``old`` by ``new`` in ``file``; ``tests`` must then fail."""

    name: str
    file: str
    old: str
    new: str
    tests: tuple[str, ...]
    why: str = ""
    count: int = 1                   # occurrences of ``old`` (all replaced): e.g. a law in both kernel paths


@dataclass
class Outcome:
    mutation: Mutation
    status: str                      # killed | survived | timeout | stale | baseline-failed
    killer: str = ""                 # first failing test (or the reason)
    seconds: float = 0.0
    log: str = field(default="", repr=False)


def load_mutations(path: Path) -> list[Mutation]:
    """The entries of a mutation list (TOML array of tables ``[[mutation]]``), checked for completeness."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    out = []
    names = set()
    for i, entry in enumerate(data.get("mutation", [])):
        missing = [k for k in ("name", "file", "old", "new", "tests") if k not in entry]
        if missing:
            raise ValueError(f"{path.name}: mutation[{i}] lacks {missing}")
        if entry["name"] in names:
            raise ValueError(f"{path.name}: mutation name {entry['name']!r} is used twice")
        if entry["old"] == entry["new"]:
            raise ValueError(f"{path.name}: mutation {entry['name']!r} does not change anything")
        names.add(entry["name"])
        tests = entry["tests"]
        out.append(Mutation(entry["name"], entry["file"], entry["old"], entry["new"],
                            tuple([tests] if isinstance(tests, str) else tests), entry.get("why", ""),
                            int(entry.get("count", 1))))
    if not out:
        raise ValueError(f"{path.name}: no [[mutation]] entries")
    return out


def repo_files(root: Path) -> list[str]:
    """Tracked plus untracked-not-ignored files (so that new, uncommitted tests take part); outside a git
    checkout (an exported tree) every file except caches and results."""
    res = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"], cwd=root,
                         capture_output=True)
    if res.returncode == 0:
        files = [f for f in res.stdout.decode().split("\0") if f]
    else:
        files = [str(p.relative_to(root)) for p in root.rglob("*") if p.is_file()]
    return [f for f in files if not SKIP_PARTS.intersection(Path(f).parts) and (root / f).is_file()]


def copy_repo(root: Path, files: list[str], dest: Path) -> None:
    for f in files:
        target = dest / f
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / f, target)


def occurrences(root: Path, m: Mutation) -> int:
    path = root / m.file
    if not path.is_file():
        return -1
    return path.read_text(encoding="utf-8").count(m.old)


def apply(root: Path, m: Mutation) -> None:
    path = root / m.file
    text = path.read_text(encoding="utf-8")
    path.write_text(text.replace(m.old, m.new), encoding="utf-8")


#: pytest's short summary line "FAILED node::id[param with spaces] - message"
_FAILED = re.compile(r"^(?:FAILED|ERROR) (.+?)(?: - .*)?$", re.MULTILINE)


def run_tests(copy: Path, tests: tuple[str, ...], timeout: float, python: str) -> tuple[str, str, str]:
    """Run the subset in ``copy``; returns (status, first failing test, log)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(copy)
    env["NUMBA_CACHE_DIR"] = str(copy / ".numba-cache")
    env.pop("HYPOTHESIS_PROFILE", None)             # the derandomised default profile: reproducible verdicts
    env["MPLBACKEND"] = "Agg"
    cmd = [python, "-m", "pytest", "-x", "-q", "-rfE", "-p", "no:cacheprovider", *tests]
    try:
        res = subprocess.run(cmd, cwd=copy, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired as exc:
        out = exc.stdout.decode() if isinstance(exc.stdout, bytes) else (exc.stdout or "")
        return "timeout", f"no verdict within {timeout:.0f} s", out
    log = res.stdout + res.stderr
    if res.returncode == 0:
        return "passed", "", log
    if res.returncode in (4, 5):          # the subset itself is wrong: never a kill
        return "error", "usage error or no tests collected (check the 'tests' paths)", log
    if "ERROR collecting" in log or "errors during collection" in log:
        # a test module that cannot be imported proves nothing about the law: never a kill
        return "error", "a test module failed to import (see log)", log
    hit = _FAILED.search(log)
    if hit:
        return "failed", hit.group(1), log
    return "failed", f"pytest exit status {res.returncode} (see log)", log


def check_one(m: Mutation, files: list[str], timeout: float, python: str, baseline: bool) -> Outcome:
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="rodimpact-mutation-") as tmp:
        copy = Path(tmp) / "repo"
        copy_repo(ROOT, files, copy)
        n = occurrences(copy, m)
        if n != m.count:
            why = "file not found" if n < 0 else f"'old' text found {n} times (expected {m.count})"
            return Outcome(m, "stale", why, time.perf_counter() - t0)
        if baseline:
            status, killer, log = run_tests(copy, m.tests, timeout, python)
            if status != "passed":
                return Outcome(m, "baseline-failed", killer, time.perf_counter() - t0, log)
            shutil.rmtree(copy / ".numba-cache", ignore_errors=True)
        apply(copy, m)
        status, killer, log = run_tests(copy, m.tests, timeout, python)
    verdict = {"failed": "killed", "passed": "survived", "timeout": "timeout", "error": "error"}[status]
    return Outcome(m, verdict, killer, time.perf_counter() - t0, log)


def report(outcomes: list[Outcome], path: Path, wall: float, jobs: int) -> str:
    killed = sum(o.status in ("killed", "timeout") for o in outcomes)
    lines = [
        "# Mutation report",
        "",
        "Generated by `python scripts/mutation_check.py` (list: `scripts/mutations.toml`; how and why: "
        "[mutation-testing.md](mutation-testing.md)). Each row is one deliberate mistake in a physics law or a "
        "numerical scheme, applied alone to a copy of the repository and recompiled (fresh numba cache); "
        "*killed by* is the first test of the subset that failed.",
        "",
        f"**{killed} of {len(outcomes)} mutations killed.** Time: {sum(o.seconds for o in outcomes) / 60:.0f} min "
        f"summed over the mutations (copy, recompile, tests; on a shared, loaded two-core machine); the full "
        f"run's wall time was {wall / 60:.1f} min with {jobs} job{'s' if jobs > 1 else ''}.",
        "",
        "| # | mutation | file | verdict | killed by | s |",
        "|---|---|---|---|---|---|",
    ]
    for i, o in enumerate(outcomes, 1):
        killer = o.killer.replace("|", "\\|")
        lines.append(f"| {i} | {o.mutation.name} | `{o.mutation.file}` | {o.status} | `{killer}` | "
                     f"{o.seconds:.0f} |" if killer else
                     f"| {i} | {o.mutation.name} | `{o.mutation.file}` | {o.status} |  | {o.seconds:.0f} |")
    lines += ["", "## What each mutation does", ""]
    for i, o in enumerate(outcomes, 1):
        m = o.mutation
        lines.append(f"{i}. **{m.name}** ({m.why or 'no description'}): `{_short(m.old)}` -> `{_short(m.new)}`")
    text = "\n".join(lines) + "\n"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return text


def _short(s: str, n: int = 90) -> str:
    s = " ".join(s.split()).replace("`", "'").replace("|", "\\|")
    return s if len(s) <= n else s[: n - 3] + "..."


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--list", type=Path, default=DEFAULT_LIST, help="mutation list (TOML)")
    ap.add_argument("--report", type=Path, default=DEFAULT_REPORT, help="markdown report to write")
    ap.add_argument("--only", action="append", default=[], help="fnmatch pattern(s) on mutation names")
    ap.add_argument("--jobs", type=int, default=1, help="mutations checked in parallel (default 1)")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per test run (default 900)")
    ap.add_argument("--check", action="store_true", help="only check that every 'old' text occurs exactly once")
    ap.add_argument("--baseline", action="store_true", help="run each subset unmutated first (must pass)")
    ap.add_argument("--python", default=sys.executable, help="interpreter that runs pytest")
    ap.add_argument("--report-only", action="store_true", help="rewrite the report from --state, run nothing")
    ap.add_argument("--state", type=Path, help="JSON file of earlier verdicts: read, updated with this run's, "
                    "written back; the report then covers every mutation of the list that has a verdict")
    args = ap.parse_args(argv)
    if args.jobs < 1:
        ap.error(f"--jobs: must be >= 1, got {args.jobs}")
    mutations = load_mutations(args.list)
    if args.only:
        mutations = [m for m in mutations if any(fnmatch.fnmatch(m.name, p) for p in args.only)]
        if not mutations:
            ap.error(f"--only: no mutation name matches {args.only}")
    if args.check:
        bad = [(m, occurrences(ROOT, m)) for m in mutations]
        bad = [(m, n) for m, n in bad if n != m.count]
        for m, n in bad:
            print(f"stale: {m.name}: {m.file}: "
                  + ("file not found" if n < 0 else f"'old' text found {n} times (expected {m.count})"))
        missing = sorted({t.split("::")[0] for m in mutations for t in m.tests if not (ROOT / t.split("::")[0]).exists()})
        for t in missing:
            print(f"missing test path: {t}")
        print(f"{len(mutations) - len(bad)} of {len(mutations)} mutations apply")
        return 1 if bad or missing else 0
    if args.report_only and args.state is None:
        ap.error("--report-only needs --state")
    files = repo_files(ROOT)
    t0 = time.perf_counter()
    outcomes: dict[str, Outcome] = {}
    if args.report_only:
        mutations = []
    with cf.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        futures = {pool.submit(check_one, m, files, args.timeout, args.python, args.baseline): m for m in mutations}
        for fut in cf.as_completed(futures):
            o = fut.result()
            outcomes[o.mutation.name] = o
            print(f"[{len(outcomes)}/{len(mutations)}] {o.status:9s} {o.mutation.name}  {o.killer}  ({o.seconds:.0f} s)",
                  flush=True)
            if o.status not in ("killed", "timeout") and o.log:
                print("    " + "\n    ".join(o.log.strip().splitlines()[-15:]), flush=True)
    wall = time.perf_counter() - t0
    if args.state is not None:
        everything = load_mutations(args.list)
        old = json.loads(args.state.read_text()) if args.state.exists() else {}
        new = {name: {"status": o.status, "killer": o.killer, "seconds": o.seconds} for name, o in outcomes.items()}
        merged = {**{k: v for k, v in old.items() if k not in new}, **new}
        if args.report_only or args.only:         # the report keeps the wall time of the last full run
            last = old.get("__wall__", {"seconds": wall, "jobs": args.jobs})
            wall, args.jobs = last["seconds"], last["jobs"]
        else:
            merged["__wall__"] = {"seconds": wall, "jobs": args.jobs}
        args.state.write_text(json.dumps(merged, indent=1))
        current = {m.name: m for m in everything}
        for name, v in merged.items():
            if name in current and name not in outcomes:
                outcomes[name] = Outcome(current[name], v["status"], v["killer"], v["seconds"])
        mutations = [m for m in everything if m.name in outcomes]
    ordered = [outcomes[m.name] for m in mutations]
    report(ordered, args.report, wall, args.jobs)
    killed = sum(o.status in ("killed", "timeout") for o in ordered)
    print(f"{killed} of {len(ordered)} killed; report: {args.report}")
    return 0 if killed == len(ordered) else 1


if __name__ == "__main__":
    sys.exit(main())
