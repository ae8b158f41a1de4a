"""How many pile elements a blow needs: the permanent set, the largest compressive and tensile stresses and EMX
of the benchmark's blow (``bench_pile.py``: 30 m pipe pile, rigid ram with hammer cushion and helmet, Smith soil,
40 % on the shaft, triangular, toe at 25 m) against the number of pile elements n (dt = L / (c n); the shaft
soil is gathered at the interior nodes below ground, the segments of the triangular distribution follow n as in
``pile_edges``), at five capacities. The reference is n = 800; the pile itself is exact at every n (the lattice
carries waves without dispersion), so what converges is the soil's lumping at the nodes and the time step of the
hammer chain and the soil node solves.

Run:  python benchmarks/pile_elements.py          (writes the "pile-elements" section of docs/pile-driving.md)
      python benchmarks/pile_elements.py --quick  (prints only, n <= 200)
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from rodimpact.pile import CapacitySoil, drive_blow

from _report import write_section
from bench_pile import DRIVING, DYNAMICS, PILE

DOCS = Path(__file__).resolve().parents[1] / "docs" / "pile-driving.md"
PENETRATION = 25.0
CAPACITIES = (0.5e6, 1e6, 2e6, 4e6, 8e6)
SIZES = (25, 35, 50, 70, 100, 140, 200, 400, 800)


def blow(capacity: float, n: int) -> tuple[float, float, float, float]:
    """(set m, largest compression Pa, largest tension Pa, EMX J) of the blow with n pile elements."""
    segments = max(1, math.ceil(n * PENETRATION / PILE.length))      # bearing_graph's pile_edges at n elements
    soil = CapacitySoil(capacity, 0.4, DYNAMICS, distribution="triangular").resistance(
        PENETRATION, np.linspace(0.0, PENETRATION, segments + 1))
    b = drive_blow(PILE, DRIVING, soil, dt=PILE.total_travel_time / n)
    return b.permanent_set, b.envelope.max_compression[0], b.envelope.max_tension[0], b.emx


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    sizes = [n for n in SIZES if n <= 200] if args.quick else list(SIZES)
    rows = []
    worst: dict[int, list[float]] = {n: [0.0, 0.0, 0.0, 0.0] for n in sizes[:-1]}
    for cap in CAPACITIES:
        values = {n: blow(cap, n) for n in sizes}
        ref = values[sizes[-1]]
        for n in sizes[:-1]:
            s, c, t, e = values[n]
            # set: relative to the reference set, but at least 0.1 mm (near refusal the set is a few micrometres)
            errs = [abs(s - ref[0]) / max(abs(ref[0]), 1e-4), abs(c / ref[1] - 1), abs(t / ref[2] - 1),
                    abs(e / ref[3] - 1)]
            worst[n] = [max(a, b) for a, b in zip(worst[n], errs)]
        rows.append((cap, values))
        print(f"{cap / 1e6:g} MN done", flush=True)
    head = "| capacity | quantity | " + " | ".join(f"n = {n}" for n in sizes) + " |"
    lines = [head, "|---|---|" + "---:|" * len(sizes)]
    for cap, values in rows:
        for q, (name, scale, fmt) in enumerate((("set (mm)", 1e3, "{:.4f}"), ("compression (MPa)", 1e-6, "{:.2f}"),
                                                ("tension (MPa)", 1e-6, "{:.2f}"), ("EMX (kJ)", 1e-3, "{:.3f}"))):
            lines.append(f"| {cap / 1e6:g} MN | {name} | " + " | ".join(fmt.format(values[n][q] * scale)
                                                                       for n in sizes) + " |")
    err = ["| n | set | compression | tension | EMX |", "|---:|---:|---:|---:|---:|"]
    for n in sizes[:-1]:
        err.append(f"| {n} | " + " | ".join(f"{100 * x:.2f} %" for x in worst[n]) + " |")
    text = ("The benchmark's blow (`benchmarks/pile_elements.py`: the 30 m pipe pile of `bench_pile.py`, rigid "
            "4536 kg ram, 2 GN/m hammer cushion, 1 t helmet, Smith soil 40 % on the shaft, triangular, toe at 25 m) "
            f"against the number of pile elements n (shaft soil at the interior nodes below ground), at five capacities; "
            f"reference n = {sizes[-1]}:\n\n" + "\n".join(lines) +
            f"\n\nLargest deviation from n = {sizes[-1]} over the five capacities (set: relative to the reference "
            "set, at least 0.1 mm, since near refusal the set is a few micrometres):\n\n" + "\n".join(err) + "\n")
    print(text)
    if not args.quick:
        write_section("pile-elements", text, path=DOCS)


if __name__ == "__main__":
    main()
