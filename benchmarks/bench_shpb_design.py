"""Strikers and pulse shapers for a constant strain rate in a Kolsky bar (issue 22), against a uniform striker.

Case: the LANL-like bar of the tests (Ti-6Al-4V, E = 113.8 GPa, rho = 4430 kg/m^3, 9.47 mm; incident and
transmitted bars 1.5 m, gauges 0.5 m from the specimen), an annealed OFHC copper specimen 6.34 mm x 3.204 mm
with the Johnson-Cook parameters of Johnson and Cook (Eng. Fract. Mech. 21 (1985) 31-48: A = 90 MPa, B = 292 MPa,
n = 0.31, C = 0.025, m = 1.09), requested engineering rate 2000 1/s over 2-15 % strain.

* designed striker, target method: ``design_striker`` (n = 100 elements, the incident pulse for the constant
  rate matched with the lattice's exact adjoint gradients), then the whole bar simulated with the specimen;
* designed striker, law in the loop: ``design_striker(method="law")``: from a uniform striker, the specimen's
  simulated strain rate held at the request (exact gradients through the Johnson-Cook law, no target pulse);
* designed shapers: ``design_shaper`` for a 0.4 m striker of the bar's section (thickness at most half the
  diameter), with two shaper laws: an OFHC copper disc with the specimen's Johnson-Cook constants (Johnson and
  Cook 1985, true measures: the area grows as A0 / (1 - eps)), and a copper-like shaper of the Frew, Forrestal and
  Chen (2002) form with sigma_0 = 360 MPa, n = 0.3, m = 2 (illustrative constants of that form, not a fit to a
  tested copper; engineering measures);
* baseline: a uniform striker of the designed striker's length at its best velocity (same run, same measure).

Flatness: the largest |rate / 2000 - 1| while the specimen is inside the strain window.

Run:  python benchmarks/bench_shpb_design.py          (writes the "shpb-design" section of docs/performance.md)
      python benchmarks/bench_shpb_design.py --quick  (n = 30, one start per shaper; prints only)
"""

from __future__ import annotations

import argparse
import platform
import warnings

import rodimpact as ri
from rodimpact.shpb import Gauge, KolskyBar
from rodimpact.shpb.rate_design import design_shaper, design_striker

from _report import write_section

TI = ri.Material(113.8e9, 4430.0, "ti-6al-4v")
D_BAR = 9.47e-3
RATE, WINDOW = 2000.0, (0.02, 0.15)
COPPER = ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, 0.025, 1.0, 1.09)     # Johnson and Cook 1985, OFHC copper
C_COPPER = (117e9 / 8960.0) ** 0.5                                       # elastic bar wave speed of copper, m/s


def kolsky(striker_length: float) -> KolskyBar:
    bar = lambda length, name: ri.Rod([ri.Cylinder(length, D_BAR)], material=TI, name=name)  # noqa: E731
    specimen = ri.Specimen(COPPER, 6.34e-3, 3.204e-3, density=8960.0)
    return KolskyBar(bar(1.5, "incident"), bar(1.5, "transmitted"), specimen, Gauge(0.5), Gauge(0.5),
                     striker=bar(striker_length, "striker"))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    n = 30 if args.quick else 100
    warnings.simplefilter("ignore", UserWarning)       # the rectangular uniform pulse's equilibrium warning
    striker = design_striker(kolsky(0.25), RATE, WINDOW, n=n, progress=False)
    law = design_striker(kolsky(0.25), RATE, WINDOW, n=n, progress=False, method="law", compare_uniform=False)
    quick = {"starts": [(0.9e-3, 9e-3, 22.8)], "max_evaluations": 40} if args.quick else {}
    shapers = [(name, design_shaper(kolsky(0.4), RATE, law, WINDOW, **quick))
               for name, law in (("Johnson-Cook OFHC Cu", COPPER),
                                 ("Frew Cu-like (illustrative)", ri.FrewShaper(360e6, 0.3, 2.0)))]
    rows = [
        ("designed striker, target method", f"{n} elements, {striker.design.n_elements * striker.design.dt * 1e6:.1f}"
                                            f" us travel time, {striker.striker_velocity:.2f} m/s",
         striker.flatness, striker.wall_time),
        ("designed striker, law in the loop", f"{n} elements from a uniform start, {law.striker_velocity:.2f} m/s, "
                                              f"{law.design.iterations} iterations",
         law.flatness, law.wall_time),
        ("uniform striker (baseline)", "bar section, same travel time, best velocity", striker.uniform_flatness,
         None),
    ] + [(f"designed shaper, {name}", f"{d.shaper.diameter * 1e3:.2f} mm x {d.shaper.thickness * 1e3:.3f} mm "
          f"({d.shaper.measure} measures, elastic transit {d.shaper.thickness / C_COPPER * 1e6:.2f} us), 0.4 m "
          f"striker at {d.striker_velocity:.2f} m/s", d.flatness, d.wall_time) for name, d in shapers]
    lines = ["## Kolsky bar: strikers and shapers for a constant strain rate (`benchmarks/bench_shpb_design.py`)",
             "",
             f"Machine: {platform.machine()}, Python {platform.python_version()}. JC copper specimen (Johnson and "
             f"Cook 1985) at {RATE:g} 1/s over {WINDOW[0]:g}-{WINDOW[1]:g} strain, Ti-6Al-4V bars 9.47 mm; "
             "flatness = largest |rate / requested - 1| inside the window (goal: 5 %). The time includes the "
             "whole-bar verification runs (the uniform baseline's velocity search is in the target method's time).",
             "", "| | set-up | flatness | wall time |", "|---|---|---:|---:|"]
    for name, setup, flat, wall in rows:
        lines.append(f"| {name} | {setup} | {100 * flat:.2f} % | {'-' if wall is None else f'{wall:.1f} s'} |")
    lines += ["", f"Equilibrium (four elastic transits of the specimen, Ravichandran and Subhash 1994): "
                  f"{striker.equilibrium_time * 1e6:.2f} us after the start of loading.",
              "",
              "Shapers: thickness at most half the diameter (`max_aspect=0.5`), diameter at most the bar's; the "
              "search (two starts, a root-mean-square stage then a minimax polish, at most 100 whole-bar runs per "
              "stage and start) includes its final run. Before this search (one minimax Nelder-Mead stage from six "
              "starts, Frew shaper only): 6.19 % in 22.2 s for the Frew shaper (9.39 mm x 1.949 mm at 22.15 m/s)."]
    text = "\n".join(lines)
    print(text)
    if not args.quick:
        write_section("shpb-design", text)


if __name__ == "__main__":
    main()
