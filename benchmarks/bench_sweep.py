"""Parallel speed-up of rodimpact.sweep (threads; the compiled kernel releases the GIL).

Sixteen runs of a percussive-drilling-sized system (pistons of 0.20-0.35 m at 6-12 m/s on a 3 m rod, 1 mm
elements: 3200-3350 elements, 4000 steps, about 1.3e7 element updates per run) with 1 worker and with as many
workers as CPUs.

Run:  python benchmarks/bench_sweep.py   (writes the "sweep" section of docs/performance.md)
"""

from __future__ import annotations

import os
import platform
import time

import numba
import numpy as np

import rodimpact as ri

try:
    from _report import write_section
except ImportError:  # run from the repository root
    from benchmarks._report import write_section

DT = 0.001 / ri.STEEL.wave_speed


def build(length: float, velocity: float) -> dict:
    rods = [ri.Rod([ri.Cylinder(length, 0.05)]), ri.Rod([ri.Cylinder(3.0, 0.04)])]
    return dict(rods=rods, velocities=[velocity, 0.0], steps=4000, dt=DT, right="nonreflecting")


def main() -> None:
    grid = {"length": [0.20, 0.25, 0.30, 0.35], "velocity": [6.0, 8.0, 10.0, 12.0]}
    ri.sweep(build, {"length": [0.2], "velocity": [6.0]}, workers=1)       # compile / load the cache
    cpus = os.cpu_count() or 1
    times = {}
    for workers in sorted({1, cpus}):
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            ri.sweep(build, grid, workers=workers, progress=False)
            best = min(best, time.perf_counter() - t0)
        times[workers] = best
        print(f"workers={workers}: {best:.3f} s")
    rows = [f"| {w} | {t:.3f} s | {times[1] / t:.2f} |" for w, t in times.items()]
    body = "\n".join([
        "## Parameter sweeps (`benchmarks/bench_sweep.py`)",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {cpus} CPUs, Python {platform.python_version()}, "
        f"numpy {np.__version__}, numba {numba.__version__}. Best of 3.",
        "",
        "`rodimpact.sweep` over 16 points (pistons of 0.20-0.35 m at 6-12 m/s on a 3 m rod, 3200-3350 elements, "
        "4000 steps each), threads sharing the process; the compiled kernel runs without the GIL, the Python part "
        "of each run (lattice, result assembly) does not, which limits the speed-up.",
        "",
        "| workers | wall time | speed-up |",
        "|---:|---:|---:|",
        *rows,
    ])
    write_section("sweep", body)


if __name__ == "__main__":
    main()
