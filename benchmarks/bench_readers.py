"""Speed of the measurement CSV reader: rodimpact.io.read_csv_recording (pandas table, pint units) against the
cell-by-cell Python parse it replaced (kept below as the baseline), on a file of ROWS rows x 11 columns (time and
ten channels, comma-separated, header with units). Both must give the same numbers; the script checks that.

Run:  python benchmarks/bench_readers.py [ROWS]   (default 1000000; prints the times)
      python benchmarks/bench_readers.py 1000000 --docs   (also writes the "readers" section of docs/performance.md)

Part two, ``--models``: the CPU time of load_model on large model files (issue 20, item 17), each at n and 4n
entries so that the ratio shows whether validation is linear in the file's size; ``--docs`` writes the
"model-files" section of docs/performance.md:

      python benchmarks/bench_readers.py --models [--docs]
"""

from __future__ import annotations

import csv
import math
import platform
import sys
import tempfile
from pathlib import Path

import numpy as np

from rodimpact.io import read_csv_recording

try:
    from _report import best_time, write_section
except ImportError:  # run from the repository root
    from benchmarks._report import best_time, write_section

CHANNELS = 10


def baseline(path: Path) -> np.ndarray:
    """The reader before issue 14 (item 12): split every line with the csv module, float() every cell, check it."""
    lines = path.read_bytes().decode("utf-8-sig").splitlines()
    content = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    rows = content[1:]
    n_cols = len(next(csv.reader([content[0][1]])))
    data = np.empty((len(rows), n_cols))
    for r, (line_no, line) in enumerate(rows):
        fields = next(csv.reader([line], delimiter=","))
        if len(fields) != n_cols:
            raise ValueError(f"{path}, line {line_no}: expected {n_cols} columns, found {len(fields)}")
        for c, text in enumerate(fields):
            value = float(text)
            if not math.isfinite(value):
                raise ValueError(f"{path}, line {line_no}: value {text!r} is not finite")
            data[r, c] = value
    return data


def write_file(path: Path, rows: int) -> None:
    rng = np.random.default_rng(12)
    header = ",".join(["time [s]"] + [f"ch{c} [V]" for c in range(CHANNELS)])
    block = 100_000
    with open(path, "w") as fh:
        fh.write(header + "\n")
        for start in range(0, rows, block):
            n = min(block, rows - start)
            t = (start + np.arange(n)) * 1e-7
            values = rng.standard_normal((n, CHANNELS)) * 1e-2
            np.savetxt(fh, np.column_stack([t, values]), delimiter=",", fmt="%.9g")


#: model files of n entries: (description, text builder); sizes chosen at 1-30 MB, as in the issue
MODEL_FILES = {
    "rods": ("N rods of one cylinder each, unit strings, a duplicate name at rods[1]",
             lambda n: "[simulation]\nsteps = 5\n" + "\n".join(
                 f'[[rods]]\nname = "{"a" if i < 2 else f"r{i}"}"\nvelocity = "{1 if i == 0 else 0} m/s"\n'
                 f'[[rods.segments]]\nshape = "cylinder"\nlength = "0.1 m"\ndiameter = "20 mm"\n' for i in range(n))),
    "table": ("a table profile of N points, x and diameter as unit strings",
              lambda n: '[simulation]\nsteps = 5\n[[rods]]\nvelocity = 9\n[[rods.segments]]\nshape = "table"\n'
                        f'x = [{", ".join(f"{chr(34)}{i * 0.01:.2f} mm{chr(34)}" for i in range(n))}]\n'
                        f'diameter = [{", ".join(f"{chr(34)}{20 + i % 5} mm{chr(34)}" for i in range(n))}]\n'),
    "numbers": ("an impedance array of N bare numbers",
                lambda n: '[simulation]\nsteps = 5\n[[rods]]\nvelocity = 9\n[rods.elements]\n'
                          f'element_length = "5 mm"\nimpedance = [{", ".join(str(51000 + i % 7) for i in range(n))}]\n'),
    "runs": ("N impedance runs (inline tables with a unit string each)",
             lambda n: '[simulation]\nsteps = 5\n[[rods]]\nvelocity = 9\n[rods.elements]\nelement_length = "5 mm"\n'
                       f'runs = [{", ".join(f"{{ impedance = {chr(34)}{51 + i % 7} kN s/m{chr(34)}, count = 2 }}" for i in range(n))}]\n'),
}
MODEL_SIZES = {"rods": 10_000, "table": 75_000, "numbers": 300_000, "runs": 75_000}
#: CPU seconds at n and 4n measured by this script on the code before issue 20 item 17 (commit 9bd718e), same
#: machine, for the "before" column; re-measure with ``git stash; python benchmarks/bench_readers.py --models``
BEFORE = {"rods": (1.85, 7.74), "table": (15.38, 66.91), "numbers": (1.05, 4.46), "runs": (6.06, 28.33)}


def cpu_time(fn) -> float:
    """CPU seconds of one call of ``fn()`` (errors are part of the work measured)."""
    import time

    t0 = time.process_time()
    try:
        fn()
    except ValueError:
        pass
    return time.process_time() - t0


def bench_models() -> list[str]:
    """load_model's CPU time for every file of :data:`MODEL_FILES` at n and 4n entries."""
    import warnings

    from rodimpact.io import load_model

    warnings.simplefilter("ignore")
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        load_model_warm = Path(tmp) / "warm.toml"       # pint's registry is loaded once, outside the times
        load_model_warm.write_text(MODEL_FILES["table"][1](10))
        load_model(load_model_warm)
        for key, (what, build) in MODEL_FILES.items():
            row = []
            for n in (MODEL_SIZES[key], 4 * MODEL_SIZES[key]):
                path = Path(tmp) / f"{key}_{n}.toml"
                path.write_text(build(n))
                size = path.stat().st_size / 1e6
                t = min(cpu_time(lambda: load_model(path)) for _ in range(2))
                row.append((n, size, t))
            (n1, s1, t1), (n4, s4, t4) = row
            b1, b4 = BEFORE[key]
            lines.append(f"| {what} | {n1:,}: {s1:.2f} MB, {t1:.2f} s | {n4:,}: {s4:.2f} MB, {t4:.2f} s | "
                         f"{t4 / t1:.2f} | {b1:.2f} s, {b4:.2f} s |")
            print(lines[-1], flush=True)
    return lines


def main() -> None:
    if "--models" in sys.argv:
        lines = bench_models()
        if "--docs" in sys.argv:
            write_section("model-files", MODEL_SECTION.format(
                machine=platform.processor() or platform.machine(), python=platform.python_version(),
                rows="\n".join(lines)))
        return
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    rows = int(args[0]) if args else 1_000_000
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "shot.csv"
        write_file(path, rows)
        rec = read_csv_recording(path)
        ref = baseline(path)
        assert np.array_equal(rec.time, ref[:, 0]) and all(
            np.array_equal(rec[f"ch{c}"], ref[:, c + 1]) for c in range(CHANNELS)), "the readers disagree"
        repeat = 3 if rows <= 200_000 else 1
        t_new = best_time(lambda: read_csv_recording(path), repeat)
        t_old = best_time(lambda: baseline(path), repeat)
        size = path.stat().st_size / 1e6
    line = (f"read_csv_recording, {rows} rows x {CHANNELS + 1} columns ({size:.0f} MB): cell by cell "
            f"{t_old:.2f} s, pandas {t_new:.2f} s ({t_old / t_new:.1f}x)")
    print(line)
    if "--docs" in sys.argv:
        write_section("readers", "## Measurement CSV reader\n\n"
                      f"`python benchmarks/bench_readers.py {rows}` on {platform.processor() or platform.machine()}, "
                      f"Python {platform.python_version()}:\n\n{line}\n")


MODEL_SECTION = """## Model files: validation time (`python benchmarks/bench_readers.py --models`)

CPU time of `load_model` (best of two) on {machine}, Python {python}, for files of n and 4n entries; "ratio" is
the ratio of the two times (4 for work linear in the file's size; repeated runs on this shared 2-core machine vary
by up to 0.3 s, so ratios of 4.0-4.5 are within the noise; with the garbage collector off they were no closer
to 4). Before issue 20 (item 17) pint
converted every unit string (~0.1 ms each), psutil was asked for the memory after every impedance run, the
parsed file was deep-copied for overrides that were not given, and a duplicate rod name was reported only
after every rod had been validated and built (10.9 s for 10,000 rods on the reviewer's loaded machine). The
work was linear already (ratios near 4 before too) but with a large constant: a table of 300,000 unit-string
points took 67 s. Now each unit is converted once (the value is the number times pint's factor for that unit, equal bit for bit), the memory is asked for once, and
duplicate rod names are checked on the parsed file first. What remains is Python's TOML parser (`tomllib`,
roughly 1-2 s per 10 MB of arrays) and the per-value checks. `tests/io/test_model_scaling.py` counts the
operations (pint conversions, memory queries, tables validated) at n and 4n instead of timing them.

| file | n | 4n | ratio | before (9bd718e): n, 4n |
|---|---|---|---|---|
{rows}
"""


if __name__ == "__main__":
    main()
