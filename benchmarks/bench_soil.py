"""Speed of the Smith soil node solve (rodimpact.direct.soil): per element-step cost of a 30 m pile with shaft
soil at every interior node and a soil toe, against the same pile without soil, at n = 10 and n = 1000 elements.

The solver before this change (bracket + bisection) is not kept in the package; the benchmark measures it by
running the same measurement with another source tree on the path (``--old-tree DIR``, e.g. a checkout of the
commit before), in a subprocess with its own numba cache, side by side in the same run.

Run:  python benchmarks/bench_soil.py [--old-tree DIR]   (writes the "soil" section of docs/performance.md)
      python benchmarks/bench_soil.py --quick            (small sizes, prints only)
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

LENGTH, C, Z = 30.0, 4000.0, 1.5e6
SHAFT, TOE = 1.5e6, 0.5e6          # total shaft R_u (N), toe R_u (N)


def _problem(n: int, soil: bool, steps_per_transit: int = 4):
    import rodimpact as ri
    from rodimpact.rods.soil import ShaftResistance, SoilToe

    dt = LENGTH / C / n
    head = ri.ForceEnd(lambda t: np.where(t < 2e-3, -3.0e6, 0.0))
    toe = SoilToe(TOE, 2.5e-3, damping=0.5) if soil else ri.FreeEnd()
    loads = (ShaftResistance(0, [0.0, LENGTH], [SHAFT / LENGTH], quake=2.5e-3, damping=0.16),) if soil else ()
    system = ri.System([ri.Rod.from_impedance(np.full(n, Z), dt=dt, wave_speed=C, name="pile")], [0.0], None,
                       head, toe, loads)
    return ri.Problem.of(system, steps=steps_per_transit * n, dt=dt, outputs=ri.Outputs())


def _measure(quick: bool) -> dict:
    import rodimpact as ri
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from _report import best_time

    out = {}
    for n in ((10, 100) if quick else (10, 1000)):
        for soil in (False, True):
            long, short = (3, 1) if n >= 1000 else (2000, 200)
            prob = _problem(n, soil, long)
            ri.simulate(prob)                                   # compile
            reps = 3
            t = best_time(lambda: ri.simulate(prob), reps)
            short_prob = _problem(n, soil, short)
            t0 = best_time(lambda: ri.simulate(short_prob), reps)          # the loop's fixed cost
            out[f"{n}/{'soil' if soil else 'bare'}"] = (t - t0) / (n * (long - short) * n)
    return out


def _in_tree(tree: str, quick: bool) -> dict:
    env = dict(os.environ, PYTHONPATH=tree, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="nc_bench_soil_"))
    code = (f"import sys, json; sys.path.insert(0, {str(Path(__file__).resolve().parent)!r}); "
            f"import bench_soil; print(json.dumps(bench_soil._measure({quick})))")
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True,
                         cwd=tree)          # python -c puts the working directory first on the path
    return json.loads(res.stdout.strip().splitlines()[-1])


def main() -> None:
    quick = "--quick" in sys.argv
    old_tree = sys.argv[sys.argv.index("--old-tree") + 1] if "--old-tree" in sys.argv else None
    here = str(Path(__file__).resolve().parents[1])
    new = _in_tree(here, quick)
    old = _in_tree(old_tree, quick) if old_tree else None
    lines = ["## Smith soil node solve (`benchmarks/bench_soil.py`)", "",
             f"30 m pile (Z = {Z:.3g} N s/m, c = {C:g} m/s), shaft soil (Smith, J = 0.16 s/m, q = 2.5 mm, "
             f"R_u = {SHAFT / 1e6:g} MN) at every interior node and a Smith toe (R_u = {TOE / 1e6:g} MN), "
             "struck by a 3 MN force for 2 ms. Cost per element and step (us), the loop's fixed cost "
             "subtracted (difference of a long and a short run); one core. Without soil the uniform pile's interior "
             "nodes reflect nothing and cost nothing, so the soil columns are the whole cost of a soil node. The "
             "old tree is measured in a subprocess of the same run.", "",
             "| elements | no soil | soil, this tree |" + (" soil, old tree (bisection) | speed-up |" if old else ""),
             "|---|---|---|" + ("---|---|" if old else "")]
    for key in new:
        n, kind = key.split("/")
        if kind != "soil":
            continue
        row = f"| {n} | {new[n + '/bare'] * 1e6:.3f} | {new[key] * 1e6:.3f} |"
        if old:
            row += f" {old[key] * 1e6:.3f} | {old[key] / new[key]:.1f} |"
        lines.append(row)
    text = "\n".join(lines)
    print(text)
    if not quick:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from _report import write_section
        write_section("soil", text)


if __name__ == "__main__":
    main()
