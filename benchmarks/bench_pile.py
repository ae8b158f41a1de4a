"""Pile driving (issue 23): a 20-point bearing graph of a 30 m pile and drivability at 50 depths, one core.

Case: a steel pipe pile 30 m long, 610 mm x 12.7 mm wall (E = 210 GPa, rho = 7840 kg/m^3, the package's steel),
driven 25 m into the ground by a rigid 4536 kg ram (the Vulcan 010's published ram weight, 10,000 lb) at
sqrt(2 g 0.67 x 0.99 m) (its 3.25 ft stroke, an efficiency of 0.67 assumed for the benchmark), a hammer cushion of
2 GN/m (e = 0.8) and a 1 t helmet; Smith soil with 2.54 mm quakes, damping 0.164 / 0.492 s/m; capacities 0.5 to
10 MN, 40 % on the shaft, triangular. Drivability: two layers (30 kPa over 10 m with setup 2, 80 kPa and 6 MPa at
the toe below), toe depths 0.6 to 30 m.

Each point is one blow of 10 round trips 2 L / c of the pile with the default 50 pile elements (about 1000 steps;
docs/pile-driving.md, verification, says why 50; a row with 100 elements, the default before, for comparison), the
stress envelope taken at every step; the bearing graph's blows share one lattice (``drive_blow_batch``).
Baseline: the same blows with the numpy reference path (a few points, scaled).
The goal of the issue: the 20-point bearing graph within 1 s on one core.

Run:  python benchmarks/bench_pile.py          (writes the "pile" section of docs/performance.md)
      python benchmarks/bench_pile.py --quick  (prints only)
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time

import numpy as np

import rodimpact as ri
from rodimpact.pile import CapacitySoil, DrivingSystem, SoilDynamics, SoilLayer, SoilProfile, drive_blow
from rodimpact.pile.blow import PILE_ELEMENTS
from rodimpact.pile.studies import bearing_graph, drivability, pile_edges
from rodimpact.rods.conditions import Cushion, FreeEnd

from _report import write_section

PILE = ri.Rod([ri.Tube(30.0, 0.610, 0.610 - 2 * 0.0127)])
DRIVING = DrivingSystem.dropped(3.25 * 0.3048, 0.67, ram_mass=4535.9237, hammer_cushion=Cushion(2e9, 0.8),
                                helmet_mass=1000.0)
DYNAMICS = SoilDynamics(2.54e-3, 2.54e-3, 0.164, 0.492)
SOIL = CapacitySoil(2e6, 0.4, DYNAMICS, distribution="triangular")
PROFILE = SoilProfile([SoilLayer(10.0, 30e3, 0.0, 2.0), SoilLayer(30.0, 80e3, 6e6)], math.pi * 0.610,
                      math.pi * 0.610**2 / 4, DYNAMICS)
CAPACITIES = np.linspace(0.5e6, 10e6, 20)
DEPTHS = np.linspace(0.6, 30.0, 50)


def timed(fn):
    """(wall time s, CPU time s of this thread, fn()): the CPU time is one core's work, whatever else shares the
    machine; the wall time also counts the waits for a core."""
    t0, c0 = time.perf_counter(), time.thread_time()
    out = fn()
    return time.perf_counter() - t0, time.thread_time() - c0, out


def best(fn, repeat: int) -> tuple[float, float]:
    """The shortest wall time and the shortest CPU time of ``repeat`` calls of ``fn``, s."""
    runs = [timed(fn)[:2] for _ in range(repeat)]
    return min(r[0] for r in runs), min(r[1] for r in runs)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    repeat = 1 if args.quick else 3
    bearing_graph(PILE, DRIVING, SOIL, CAPACITIES[:1], 25.0, progress=False)          # compile
    t_bg = best(lambda: bearing_graph(PILE, DRIVING, SOIL, CAPACITIES, 25.0, progress=False), repeat)
    fine = PILE.total_travel_time / 100
    t_100 = best(lambda: bearing_graph(PILE, DRIVING, SOIL, CAPACITIES, 25.0, progress=False, dt=fine), 1)
    t_dr = best(lambda: drivability(PILE, DRIVING, PROFILE, DEPTHS, progress=False), 1)
    table = drivability(PILE, DRIVING, PROFILE, DEPTHS[-1:], progress=False)
    t_np = best(lambda: bearing_graph(PILE, DRIVING, SOIL, CAPACITIES[:2], 25.0, progress=False, backend="numpy"), 1)
    bg = bearing_graph(PILE, DRIVING, SOIL, CAPACITIES, 25.0, progress=False)
    toe_only = CapacitySoil(2e6, 0.0, DYNAMICS).resistance(25.0)
    parts = [("hammer chain, pile, free toe", lambda: drive_blow(PILE, DRIVING, toe=FreeEnd())),
             ("... and a soil toe", lambda: drive_blow(PILE, DRIVING, toe_only)),
             ("... and the shaft soil (the bearing graph's blow)",
              lambda: drive_blow(PILE, DRIVING, SOIL.resistance(25.0, pile_edges(PILE, 25.0))))]
    split = [(name, *best(run, 5)) for name, run in parts]

    def row(name: str, points: int, t: tuple[float, float], scale: float = 1.0) -> str:
        return (f"| {name} | {points} | {t[0] * scale:.3f} | {t[1] * scale:.3f} | {t[0] * scale / points * 1e3:.1f} | "
                f"{t[1] * scale / points * 1e3:.1f} |")

    lines = [
        "## Pile driving (`benchmarks/bench_pile.py`)",
        "",
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} logical CPUs shared with other work (load "
        f"average {os.getloadavg()[0]:.1f} at the end of the run), one core used. A 30 m steel pipe pile "
        "(610 x 12.7 mm), a rigid 4536 kg ram with cushion and helmet, Smith soil; "
        f"each point one blow of 10 round trips 2 L/c with {PILE_ELEMENTS} pile elements (the default) and the stress "
        "envelope at every step; the bearing graph's blows share one lattice (`drive_blow_batch`).",
        "",
        "| study | points | wall time (s) | CPU time (s) | wall per blow (ms) | CPU per blow (ms) |",
        "|---|---:|---:|---:|---:|---:|",
        row(f"bearing graph, compiled kernels (best of {repeat})", 20, t_bg),
        row("bearing graph, compiled kernels, 100 pile elements (the default before)", 20, t_100),
        row("drivability, compiled kernels", 50, t_dr),
        row("baseline: bearing graph with the numpy reference path (2 points, scaled to 20)", 20, t_np, 10.0),
        "",
        "Where the time of one blow goes (best of 5):",
        "",
        "| blow | wall ms | CPU ms |",
        "|---|---:|---:|",
        *[f"| {name} | {w * 1e3:.1f} | {c * 1e3:.1f} |" for name, w, c in split],
        "",
        f"Bearing graph: {bg.blows_per_quarter_metre[0]:.3g} to "
        f"{bg.blows_per_quarter_metre[np.isfinite(bg.blows_per_quarter_metre)][-1]:.3g} blows/0.25 m over "
        f"{CAPACITIES[0] / 1e6:.1f} to {CAPACITIES[-1] / 1e6:.1f} MN; largest compression "
        f"{bg.max_compression.max() / 1e6:.0f} MPa. Drivability: {table.blows_per_quarter_metre[-1]:.3g} "
        f"blows/0.25 m at {DEPTHS[-1]:.0f} m. The issue's goal (20 points within 1 s on one core) in CPU time "
        f"(one core's work): {'met' if t_bg[1] < 1.0 else 'not met'} at the default {PILE_ELEMENTS} elements, "
        f"{'met' if t_100[1] < 1.0 else 'not met'} at 100; in wall time on this shared machine: "
        f"{'met' if t_bg[0] < 1.0 else 'not met'} at {PILE_ELEMENTS}, {'met' if t_100[0] < 1.0 else 'not met'} at 100.",
    ]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section("pile", text)


if __name__ == "__main__":
    main()
