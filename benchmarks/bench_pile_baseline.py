"""Smith's 1960 lumped-mass method against rodimpact's exact lattice on one pile blow (issue 23).

The same hammer, cushion, pile and soil are run with Smith's method (``benchmarks/smith1960.py``, plain numpy,
dt = half the critical step as Smith chose) at segment lengths L/10, L/20, ... and with rodimpact's lattice
(``LumpedEnd`` hammer, ``ShaftResistance`` and ``SoilToe``) at the same numbers of elements: set per blow, peak
compressive and tensile pile stress, and the wall time of each blow, side by side in one run.

Case (illustrative inputs, not a product or a site): a drop hammer with a 4536 kg (10 kip) ram falling 0.9144 m
(3 ft; V0 = sqrt(2 g h) = 4.235 m/s), a hammer cushion k = 1.0e9 N/m with e = 0.8, a 907 kg (2 kip) helmet and no
pile cushion, on a 20 m steel H pile of the HP14x73 section (A = 21.4 in^2 = 0.013806 m^2, AISC shape tables;
E = 210 GPa, rho = 7850 kg/m^3, Z = 560.5 kN s/m) embedded 15 m. Smith soil: half the ultimate resistance on
the shaft (even over the embedded length), half at the toe; quake 2.54 mm (0.1 in), damping 0.164 s/m (0.05
s/ft) on the shaft and 0.492 s/m (0.15 s/ft) at the toe: the values usually attributed to Smith (1960), not
checked against his paper here (see docs/validation-pile.md). Gravity is left out in both.

Smith's shaft damping R = R_s (1 + J V) is run as published ("smith") and mirrored for R_s < 0 ("mirrored",
R = R_s + J |R_s| V: the law of rodimpact's ``damping_kind="smith"``), so that the difference of the laws is
not taken for a difference of the discretisations.

Run:  python benchmarks/bench_pile_baseline.py          (writes the "pile-baseline" sections of
                                                         docs/performance.md and docs/validation-pile.md)
      python benchmarks/bench_pile_baseline.py --quick  (n = 10, 20, 40 and two resistances; prints only)
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

import numpy as np

import smith1960 as smith
from _report import write_section

G = 9.80665                                  # m/s^2, standard gravity
RAM, DROP, HELMET = 4536.0, 0.9144, 907.0    # kg, m, kg
CUSHION_K, CUSHION_E = 1.0e9, 0.8            # N/m, -
LENGTH, EMBEDMENT = 20.0, 15.0               # m
AREA, MODULUS, DENSITY = 0.013806, 210e9, 7850.0
QUAKE = 0.1 * 0.0254                         # m
J_SHAFT, J_TOE = 0.05 / 0.3048, 0.15 / 0.3048  # s/m
SHAFT_SHARE = 0.5
DURATION = 0.06                              # s: the toe stops at ~17 ms, the run is 3.5 times longer
VALIDATION = Path(__file__).resolve().parents[1] / "docs" / "validation-pile.md"

HAMMER = smith.Hammer(RAM, math.sqrt(2.0 * G * DROP), CUSHION_K, CUSHION_E, HELMET)
PILE = smith.Pile(LENGTH, AREA, MODULUS, DENSITY)


def soil(ultimate: float) -> smith.Soil:
    """The Smith soil of the case for a total ultimate resistance ``ultimate`` (N)."""
    return smith.Soil(SHAFT_SHARE * ultimate, EMBEDMENT, QUAKE, J_SHAFT, (1 - SHAFT_SHARE) * ultimate, QUAKE,
                      J_TOE)


@dataclass(frozen=True)
class Row:
    """One blow: set (m, down positive), peak compression and tension (Pa, tension positive), wall time (s)."""

    n: int
    dt: float
    steps: int
    set: float
    compression: float
    tension: float
    wall: float


def smith_row(ultimate: float, n: int, law: str = "smith") -> Row:
    """Smith's method with ``n`` pile segments (the best of two timed runs)."""
    best, out = math.inf, None
    for _ in range(2):
        t0 = time.perf_counter()
        out = smith.blow(HAMMER, PILE, soil(ultimate), n, DURATION, shaft_damping=law)
        best = min(best, time.perf_counter() - t0)
    return Row(n, out.dt, out.steps, out.set, out.peak_compression, out.peak_tension, best)


def _rodimpact() -> Optional[object]:
    """rodimpact with the pile elements (``LumpedEnd``, ``ShaftResistance``, ``SoilToe``), or None."""
    try:
        import rodimpact as ri
    except ImportError:           # pragma: no cover - the benchmark runs in the project's environment
        return None
    names = ("PointMass", "Cushion", "LumpedEnd", "ShaftResistance", "SoilToe")
    return ri if all(hasattr(ri, name) for name in names) else None


def ours_row(ri, ultimate: float, n: int) -> Row:
    """rodimpact's lattice with ``n`` elements in the pile (the best of two timed runs after a warm-up).

    The set is the toe's largest displacement less its quake (the toe's plastic set, as Smith's D'_p); the
    peak stresses are the extreme element forces over all steps (snapshots every step) over the area.
    """
    ram = ri.PointMass(RAM, HAMMER.impact_velocity)
    head = ri.LumpedEnd(items=(ram, ri.Cushion(CUSHION_K, CUSHION_E), ri.PointMass(HELMET, 0.0)))
    s = soil(ultimate)
    top = LENGTH - EMBEDMENT
    shaft = ri.ShaftResistance(0, depths=[top, LENGTH], unit_resistance=[s.shaft_ultimate / EMBEDMENT],
                               quake=QUAKE, damping=J_SHAFT, damping_kind="smith")
    toe = ri.SoilToe(s.toe_ultimate, quake=QUAKE, damping=J_TOE, damping_kind="smith")
    pile = ri.Rod([ri.Cylinder(LENGTH, math.sqrt(4.0 * AREA / math.pi))], material=ri.Material(MODULUS, DENSITY))
    system = ri.System([pile], [0.0], left=head, right=toe, loads=[shaft])
    outputs = ri.Outputs(probes=[ri.Probe("toe", 0, LENGTH)], snapshot_every=1)
    problem = ri.Problem.of(system, duration=DURATION, elements=n, outputs=outputs)
    ri.simulate(problem, progress=False)                     # warm-up: compiled kernels loaded
    best, result = math.inf, None
    for _ in range(2):
        t0 = time.perf_counter()
        result = ri.simulate(problem, progress=False)
        best = min(best, time.perf_counter() - t0)
    toe_u = result.probes["toe"].displacement
    force = result.snapshots.force
    return Row(n, problem.time.dt, problem.time.steps, max(0.0, float(toe_u.max()) - QUAKE),
               float(force.min()) / AREA, float(max(0.0, force.max())) / AREA, best)


def orders(values: list[float]) -> list[float]:
    """Observed orders log2((a_n - a_2n) / (a_2n - a_4n)) of a sequence over halvings (nan when undefined)."""
    a = np.asarray(values)
    d = np.diff(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        return list(np.log2(np.abs(d[:-1] / d[1:])))


def _fmt(x: float, scale: float, digits: int) -> str:
    return "--" if x is None or not np.isfinite(x) else f"{x * scale:.{digits}f}"


def convergence_section(ultimate: float, sizes: list[int], ri) -> tuple[str, dict]:
    """The table of set and peak stresses against segment length, Smith (both laws) and ours."""
    smith_rows = [smith_row(ultimate, n) for n in sizes]
    mirrored = [smith_row(ultimate, n, "mirrored") for n in sizes]
    ours = [ours_row(ri, ultimate, n) for n in sizes] if ri is not None else []
    lines = [f"Ultimate resistance {ultimate / 1e6:.2f} MN ({SHAFT_SHARE:.0%} shaft). Set in mm, stresses in MPa "
             "(compression negative), wall time of one blow in ms.", "",
             "| segments | segment length | Smith set | Smith set, mirrored shaft damping | rodimpact set | "
             "Smith compression | rodimpact compression | Smith tension | rodimpact tension | Smith time | "
             "Smith steps | rodimpact time | rodimpact steps |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for i, n in enumerate(sizes):
        s, m = smith_rows[i], mirrored[i]
        o = ours[i] if ours else None
        lines.append(
            f"| {n} | {LENGTH / n:.4g} m | {s.set * 1e3:.4f} | {m.set * 1e3:.4f} | "
            f"{_fmt(o.set if o else None, 1e3, 4)} | {s.compression / 1e6:.2f} | "
            f"{_fmt(o.compression if o else None, 1e-6, 2)} | {s.tension / 1e6:.2f} | "
            f"{_fmt(o.tension if o else None, 1e-6, 2)} | {s.wall * 1e3:.1f} | {s.steps} | "
            f"{_fmt(o.wall if o else None, 1e3, 1)} | {o.steps if o else '--'} |")
    data = dict(smith=smith_rows, mirrored=mirrored, ours=ours)
    p = orders([r.set for r in smith_rows])
    lines += ["", "Observed order of Smith's set over successive halvings (log2 of the ratio of successive "
              "differences): " + ", ".join(_fmt(x, 1, 2) for x in p) + "."]
    if ours:
        gap = [abs(s.set - o.set) / abs(o.set) for s, o in zip(mirrored, ours)]
        lines += ["Relative difference of the sets, Smith (mirrored shaft damping) against rodimpact at the same "
                  "number of segments: " + ", ".join(f"{g:.2%}" for g in gap) + "."]
    return "\n".join(lines), data


def bearing_section(resistances: list[float], sizes: tuple[int, int], ri) -> tuple[str, dict]:
    """The bearing graph: blows per metre (1 / set) against the ultimate resistance."""
    coarse, fine = sizes
    rows = []
    for ru in resistances:
        a, b = smith_row(ru, coarse), smith_row(ru, fine)
        o = ours_row(ri, ru, fine) if ri is not None else None
        rows.append((ru, a, b, o))
    head = (f"| ultimate resistance | Smith, {coarse} segments | Smith, {fine} segments | rodimpact, {fine} "
            "elements |")
    lines = ["Blows per metre (1 / set) against the ultimate resistance (MN).", "", head, "|---:|---:|---:|---:|"]
    for ru, a, b, o in rows:
        bpm = (lambda r: 1.0 / r.set if r is not None and r.set > 0 else math.inf)
        lines.append(f"| {ru / 1e6:.2f} | {bpm(a):.1f} | {bpm(b):.1f} | "
                     f"{_fmt(bpm(o) if o else None, 1, 1)} |")
    return "\n".join(lines), dict(rows=rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 10, 20, 40, two resistances; prints only")
    args = parser.parse_args()
    ri = _rodimpact()
    sizes = [10, 20, 40] if args.quick else [10, 20, 40, 80, 160, 320, 640]
    resistances = [1.0e6, 2.0e6] if args.quick else [0.5e6, 1.0e6, 1.5e6, 2.0e6, 2.5e6, 3.0e6]
    t0 = time.perf_counter()
    conv, _ = convergence_section(1.5e6, sizes, ri)
    bear, _ = bearing_section(resistances, (10, 40 if args.quick else 160), ri)
    note = ("" if ri is not None else "\nrodimpact's pile elements (LumpedEnd, ShaftResistance, SoilToe) are not "
            "in this build: the rodimpact columns are empty.\n")
    machine = (f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
               f"numpy {np.__version__}; load average {os.getloadavg()[0]:.1f} at the end of the run; whole run "
               f"{time.perf_counter() - t0:.0f} s.")
    body = "\n\n".join([conv, bear]) + "\n" + note
    print(body)
    print(machine)
    if args.quick:
        return
    perf = ("## Smith's 1960 method against the lattice, one pile blow (`benchmarks/bench_pile_baseline.py`)\n\n"
            f"{machine} Case and method: docs/validation-pile.md.\n\n{conv}\n")
    write_section("pile-baseline", perf)
    write_section("pile-baseline", f"{conv}\n\n{bear}\n{note}\n{machine}\n", path=VALIDATION,
                  header="# Validation: pile driving\n")


if __name__ == "__main__":
    main()
