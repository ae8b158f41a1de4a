"""Speed of the measurement CSV reader: rodimpact.io.read_csv_recording (pandas table, pint units) against the
cell-by-cell Python parse it replaced (kept below as the baseline), on a file of ROWS rows x 11 columns (time and
ten channels, comma-separated, header with units). Both must give the same numbers; the script checks that.

Run:  python benchmarks/bench_readers.py [ROWS]   (default 1000000; prints the times)
      python benchmarks/bench_readers.py 1000000 --docs   (also writes the "readers" section of docs/performance.md)
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


def main() -> None:
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


if __name__ == "__main__":
    main()
