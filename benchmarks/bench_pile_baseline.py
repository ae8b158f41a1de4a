"""Smith's 1960 lumped-mass method against rodimpact's exact lattice on one pile blow (issue 23).

The same pile and soil are run with Smith's method (``benchmarks/smith1960.py``, plain numpy, dt = half the
critical step, the customary choice) at segment lengths L/10, L/20, ... and with rodimpact's lattice
(``ShaftResistance`` and ``SoilToe``; the hammer as a ``LumpedEnd``) at the same numbers of elements: set per blow,
peak compressive and tensile pile stress, and the wall time of each blow, side by side in one run. Two drives of
the same pile:

* **head force**: a prescribed half-sine push of 3 MN lasting 4 ms on the pile head (no hammer): compares the
  pile and the soil alone;
* **hammer**: a drop hammer with a 4536 kg (10 kip) ram falling 0.9144 m (3 ft; V0 = sqrt(2 g h) = 4.235 m/s), a
  hammer cushion k = 1.0e9 N/m with e = 0.8, a 907 kg (2 kip) helmet resting on the pile head, no pile cushion
  (needs rodimpact's ``PointMass``, ``Cushion`` and ``LumpedEnd``; the rodimpact columns stay empty without them).

Pile and soil (illustrative inputs, not a product or a site): a 20 m steel H pile of the HP14x73 section
(A = 21.4 in^2 = 0.013806 m^2, AISC shape tables; E = 210 GPa, rho = 7850 kg/m^3, Z = 560.5 kN s/m) embedded
15 m. Smith soil: half the ultimate resistance on the shaft (even over the embedded length), half at the toe;
quake 2.54 mm (0.1 in), damping 0.164 s/m (0.05 s/ft) on the shaft and 0.492 s/m (0.15 s/ft) at the toe: the
values usually attributed to Smith (1960), not checked against his paper here (see docs/validation-pile.md).
Gravity is left out in both.

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
from typing import Optional

import numpy as np

import smith1960 as smith
from _report import timed, write_section

G = 9.80665                                  # m/s^2, standard gravity
RAM, DROP, HELMET = 4536.0, 0.9144, 907.0    # kg, m, kg
CUSHION_K, CUSHION_E = 1.0e9, 0.8            # N/m, -
PUSH, PUSH_TIME = 3.0e6, 4.0e-3              # N, s: the head-force drive
LENGTH, EMBEDMENT = 20.0, 15.0               # m
AREA, MODULUS, DENSITY = 0.013806, 210e9, 7850.0
QUAKE = 0.1 * 0.0254                         # m
J_SHAFT, J_TOE = 0.05 / 0.3048, 0.15 / 0.3048  # s/m
SHAFT_SHARE = 0.5
DURATION = 0.04                              # s: the toe stops moving down by ~17 ms in both drives
CASE_RESISTANCE = 1.5e6                      # N, the resistance of the convergence tables
VALIDATION = Path(__file__).resolve().parents[1] / "docs" / "validation-pile.md"

HAMMER = smith.Hammer(RAM, math.sqrt(2.0 * G * DROP), CUSHION_K, CUSHION_E, HELMET)
PILE = smith.Pile(LENGTH, AREA, MODULUS, DENSITY)
DRIVES = ("head force", "hammer")


def soil(ultimate: float) -> smith.Soil:
    """The Smith soil of the case for a total ultimate resistance ``ultimate`` (N)."""
    return smith.Soil(SHAFT_SHARE * ultimate, EMBEDMENT, QUAKE, J_SHAFT, (1 - SHAFT_SHARE) * ultimate, QUAKE,
                      J_TOE)


def head_push(t):
    """The head-force drive: a half-sine push PUSH sin(pi t / T) for 0 <= t <= T (N, compression positive)."""
    t = np.asarray(t, float)
    return PUSH * np.sin(np.pi * t / PUSH_TIME) * ((t >= 0.0) & (t <= PUSH_TIME))


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


def smith_row(drive: str, ultimate: float, n: int, law: str = "smith") -> Row:
    """Smith's method with ``n`` pile segments, dt = half the critical step."""
    if drive == "hammer":
        def run():
            return smith.blow(HAMMER, PILE, soil(ultimate), n, DURATION, shaft_damping=law)
    else:
        model = smith.pile_model(None, PILE, soil(ultimate), n)
        dt = 0.5 * model.critical_time_step()

        def run():
            return smith.drive(model, dt, int(math.ceil(DURATION / dt)), shaft_damping=law,
                               external_force=lambda t: float(head_push(t)))
    out, wall = timed(run, 3 if n <= 80 else 1)
    return Row(n, out.dt, out.steps, out.set, out.peak_compression, out.peak_tension, wall)


def elements() -> dict[str, type]:
    """rodimpact's pile elements that this build has (the names of the pile-chain and pile-soil work): from the
    package root or their modules; missing ones are left out."""
    import importlib

    found = {}
    for name, modules in (("PointMass", ("rodimpact", "rodimpact.rods.conditions")),
                          ("Cushion", ("rodimpact", "rodimpact.rods.conditions")),
                          ("LumpedEnd", ("rodimpact", "rodimpact.rods.conditions")),
                          ("ShaftResistance", ("rodimpact", "rodimpact.rods.soil")),
                          ("SoilToe", ("rodimpact", "rodimpact.rods.soil"))):
        for module in modules:
            try:
                cls = getattr(importlib.import_module(module), name, None)
            except ImportError:
                cls = None
            if cls is not None:
                found[name] = cls
                break
    return found


def can_run(found: dict[str, type], drive: str) -> bool:
    """Whether rodimpact's side of ``drive`` can run with the elements ``found``."""
    need = {"ShaftResistance", "SoilToe"} | ({"PointMass", "Cushion", "LumpedEnd"} if drive == "hammer" else set())
    return need <= set(found)


def _head_and_pile(found: dict[str, type], drive: str):
    """rodimpact's pile head (the hammer's lumped chain or the prescribed push, tension positive) and pile rod."""
    import rodimpact as ri

    if drive == "hammer":
        mass, cushion = found["PointMass"], found["Cushion"]
        head = found["LumpedEnd"](items=(mass(RAM, HAMMER.impact_velocity), cushion(CUSHION_K, CUSHION_E),
                                         mass(HELMET, 0.0)))
    else:
        head = ri.ForceEnd(lambda t: -head_push(t))
    pile = ri.Rod([ri.Cylinder(LENGTH, math.sqrt(4.0 * AREA / math.pi))], material=ri.Material(MODULUS, DENSITY))
    return head, pile


def ours_row(found: dict[str, type], drive: str, ultimate: float, n: int) -> Row:
    """rodimpact's lattice with ``n`` elements in the pile (compiled kernels; call once before timing).

    The set is the toe's permanent set (``result.soil.toe_set``, the toe's plastic displacement, as Smith's
    D'_p); the peak stresses are the extreme element forces over all steps (snapshots every step) over the area.
    """
    import rodimpact as ri

    s = soil(ultimate)
    shaft = found["ShaftResistance"](0, depths=[LENGTH - EMBEDMENT, LENGTH],
                                     unit_resistance=[s.shaft_ultimate / EMBEDMENT], quake=QUAKE,
                                     damping=J_SHAFT, damping_kind="smith")
    toe = found["SoilToe"](s.toe_ultimate, quake=QUAKE, damping=J_TOE, damping_kind="smith")
    head, pile = _head_and_pile(found, drive)
    system = ri.System([pile], [0.0], left=head, right=toe, loads=[shaft])
    problem = ri.Problem.of(system, duration=DURATION, elements=n, outputs=ri.Outputs(snapshot_every=1))
    result, wall = timed(lambda: ri.simulate(problem, progress=False), 3 if n <= 80 else 1)
    force = result.snapshots.force
    return Row(n, problem.time.dt, problem.time.steps, float(result.soil.toe_set),
               float(force.min()) / AREA, float(max(0.0, force.max())) / AREA, wall)


def bare_row(drive: str, n: int) -> Row:
    """rodimpact's lattice for the same pile and drive without soil (free toe): what the soil costs."""
    import rodimpact as ri

    found = elements()
    head, pile = _head_and_pile(found, drive)
    problem = ri.Problem.of(ri.System([pile], [0.0], left=head, right="free"), duration=DURATION, elements=n,
                            outputs=ri.Outputs(snapshot_every=1))
    ri.simulate(problem, progress=False)
    _, wall = timed(lambda: ri.simulate(problem, progress=False), 3)
    return Row(n, problem.time.dt, problem.time.steps, math.nan, math.nan, math.nan, wall)


def orders(values: list[float]) -> list[float]:
    """Observed orders log2((a_n - a_2n) / (a_2n - a_4n)) of a sequence over halvings (nan when undefined)."""
    d = np.diff(np.asarray(values, float))
    with np.errstate(divide="ignore", invalid="ignore"):
        return list(np.log2(np.abs(d[:-1] / d[1:])))


def _fmt(x: Optional[float], scale: float, digits: int) -> str:
    return "--" if x is None or not np.isfinite(x) else f"{x * scale:.{digits}f}"


def convergence_section(drive: str, sizes: list[int], found: dict[str, type]) -> str:
    """Set and peak stresses against segment length, Smith (both shaft laws) and ours, for one drive."""
    smith_rows = [smith_row(drive, CASE_RESISTANCE, n) for n in sizes]
    mirrored = [smith_row(drive, CASE_RESISTANCE, n, "mirrored") for n in sizes]
    ours = [ours_row(found, drive, CASE_RESISTANCE, n) for n in sizes] if can_run(found, drive) else []
    lines = [f"**{drive}**, ultimate resistance {CASE_RESISTANCE / 1e6:.2f} MN. Set in mm; peak stresses in MPa "
             "(compression negative), Smith as published / with the mirrored shaft damping; wall time of one "
             "blow in ms.", "",
             "| segments | segment length | Smith set | Smith set, mirrored | rodimpact set | Smith compression | "
             "rodimpact compression | Smith tension (published / mirrored) | rodimpact tension | Smith time | "
             "Smith steps | rodimpact time | rodimpact steps |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for i, n in enumerate(sizes):
        a, m = smith_rows[i], mirrored[i]
        o = ours[i] if ours else None
        lines.append(
            f"| {n} | {LENGTH / n:.4g} m | {a.set * 1e3:.4f} | {m.set * 1e3:.4f} | "
            f"{_fmt(o.set if o else None, 1e3, 4)} | {a.compression / 1e6:.2f} | "
            f"{_fmt(o.compression if o else None, 1e-6, 2)} | {a.tension / 1e6:.2f} / {m.tension / 1e6:.2f} | "
            f"{_fmt(o.tension if o else None, 1e-6, 2)} | {a.wall * 1e3:.1f} | {a.steps} | "
            f"{_fmt(o.wall if o else None, 1e3, 1)} | {o.steps if o else '--'} |")
    lines += ["", "Observed order of Smith's set over successive halvings (log2 of the ratio of successive "
              "differences): " + ", ".join(_fmt(x, 1, 2) for x in orders([r.set for r in smith_rows])) + "."]
    if ours:
        lines += ["Observed order of rodimpact's set: "
                  + ", ".join(_fmt(x, 1, 2) for x in orders([r.set for r in ours])) + "."]
        ref = ours[-1]
        gap = [abs(r.set - ref.set) / ref.set for r in mirrored]
        own = [abs(r.set - ref.set) / ref.set for r in ours[:-1]]
        lines += [f"Set relative to rodimpact's at {sizes[-1]} elements: Smith (mirrored) "
                  + ", ".join(f"{g:.3%}" for g in gap) + "; rodimpact " + ", ".join(f"{g:.3%}" for g in own) + "."]
        a, o = smith_rows[-1], ours[-1]
        per = (lambda r, masses: r.wall / (masses * r.steps) * 1e6)
        masses = smith.pile_model(HAMMER if drive == "hammer" else None, PILE, soil(CASE_RESISTANCE), a.n).mass.size
        lines += [f"Cost per mass (element) and step at {a.n} segments: Smith {per(a, masses):.2f} us, rodimpact "
                  f"{per(o, o.n):.2f} us; rodimpact without soil (same pile and drive, free toe) "
                  f"{per(bare_row(drive, o.n), o.n):.3f} us."]
    else:
        lines += ["rodimpact's side of this drive needs elements this build does not have: "
                  + ", ".join(sorted({"PointMass", "Cushion", "LumpedEnd", "ShaftResistance", "SoilToe"}
                                     - set(found))) + "."]
    return "\n".join(lines)


def bearing_section(drive: str, resistances: list[float], sizes: tuple[int, int], found: dict[str, type]) -> str:
    """The bearing graph of one drive: blows per metre (1 / set) against the ultimate resistance."""
    coarse, fine = sizes
    ours = can_run(found, drive)
    lines = [f"**{drive}**: blows per metre (1 / set) against the ultimate resistance (MN).", "",
             f"| ultimate resistance | Smith, {coarse} segments | Smith, {fine} segments | rodimpact, {coarse} "
             f"elements | rodimpact, {fine} elements |", "|---:|---:|---:|---:|---:|"]
    for ru in resistances:
        cells = [smith_row(drive, ru, coarse), smith_row(drive, ru, fine)]
        cells += [ours_row(found, drive, ru, coarse), ours_row(found, drive, ru, fine)] if ours else [None, None]
        bpm = ["--" if r is None else (f"{1.0 / r.set:.1f}" if r.set > 0 else "refusal") for r in cells]
        lines.append(f"| {ru / 1e6:.2f} | " + " | ".join(bpm) + " |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="n = 10, 20, 40, two resistances; prints only")
    args = parser.parse_args()
    found = elements()
    for drive in DRIVES:                        # load (or compile) the kernels before anything is timed
        if can_run(found, drive):
            ours_row(found, drive, CASE_RESISTANCE, 10)
    sizes = [10, 20, 40] if args.quick else [10, 20, 40, 80, 160, 320, 640]
    resistances = [1.0e6, 2.0e6] if args.quick else [0.5e6, 1.0e6, 1.5e6, 2.0e6, 2.5e6, 3.0e6]
    t0 = time.perf_counter()
    conv = [convergence_section(drive, sizes, found) for drive in DRIVES]
    bear = [bearing_section(drive, resistances, (10, 40 if args.quick else 160), found) for drive in DRIVES]
    machine = (f"Machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
               f"numpy {np.__version__}; load average {os.getloadavg()[0]:.1f} at the end of the run; whole run "
               f"{time.perf_counter() - t0:.0f} s. Wall times: the best of three runs up to 80 segments, one run "
               f"above; rodimpact's compiled kernels loaded before timing.")
    print("\n\n".join(conv + bear))
    print(machine)
    if args.quick:
        return
    perf = ("## Smith's 1960 method against the lattice, one pile blow (`benchmarks/bench_pile_baseline.py`)\n\n"
            f"{machine} Case and method: docs/validation-pile.md.\n\n" + "\n\n".join(conv) + "\n")
    write_section("pile-baseline", perf)
    write_section("pile-baseline", "\n\n".join(conv + bear) + f"\n\n{machine}\n", path=VALIDATION,
                  header="# Validation: pile driving\n")


if __name__ == "__main__":
    main()
