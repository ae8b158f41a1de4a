"""Cost of one exact gradient (adjoint of the lattice, docs/adjoint.md) relative to one forward run.

Case: a percussive-drilling blow. A striker of n elements (random impedances between 40 and 120 kN s/m,
10 m/s) hits a uniform drill rod of 4n elements (Z = 80 kN s/m) ending on a BitRockEnd (k1 = 0.6 Z / (n dt),
k2 = 4 k1); the run lasts 2 (n + 4n) steps, long enough for the blow to reach the rock and come back. The
objective is the rock efficiency (seeds for the end force and velocity).

Columns: forward = ``ImpactProblem.forward`` (one run, storing a checkpoint every C = ceil(sqrt(steps)) steps);
simulate = ``rodimpact.simulate`` on the same system (for comparison); gradient = ``ImpactProblem.gradient``
(recompute each segment from its checkpoint, then the reverse sweep); ratio = (forward + gradient) / forward,
the cost of one gradient in forward simulations. Best of several repeats; numba compilation excluded.

Run:  python benchmarks/bench_adjoint.py            (n = 50, 200, 1000; writes the "adjoint" section of
      docs/performance.md)
      python benchmarks/bench_adjoint.py --quick    (n = 20, 50; prints only)
"""

from __future__ import annotations

import platform
import sys

import numba
import numpy as np

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.inverse.struck import with_striker

try:
    from _report import best_time as _best, write_section
except ImportError:  # run from the repository root
    from benchmarks._report import best_time as _best, write_section

DT = 1e-6


def measure(n: int) -> dict:
    rng = np.random.default_rng(n)
    z_rod = 80e3
    struck = ri.System.struck(ri.Rod.from_impedance([z_rod] * (4 * n), dt=DT),
                              far_end=ri.BitRockEnd(0.6 * z_rod / (n * DT), 2.4 * z_rod / (n * DT)))
    steps = 2 * (n + 4 * n)
    problem = ImpactProblem(struck, DT, n, steps)
    z = rng.uniform(40e3, 120e3, size=n)
    v = 10.0
    fw = problem.forward(z, v)
    energy = 0.5 * fw.striker_mass * v * v
    seeds = dict(end_force=-fw.end_velocity * DT / energy, end_velocity=-fw.end_force * DT / energy)
    problem.gradient(fw, **seeds)                         # compile / warm up
    system = with_striker(struck, ri.Rod.from_impedance(z[::-1], dt=DT), v)
    ri.simulate(system, steps=steps, dt=DT)
    repeat = 7 if n <= 200 else 3
    t_fw = _best(lambda: problem.forward(z, v), repeat)
    t_sim = _best(lambda: ri.simulate(system, steps=steps, dt=DT), repeat)
    t_gr = _best(lambda: problem.gradient(fw, **seeds), repeat)
    return dict(n=n, elements=5 * n, steps=steps, forward=t_fw, simulate=t_sim, gradient=t_gr,
                ratio=(t_fw + t_gr) / t_fw, efficiency=-float(np.sum(fw.end_force * fw.end_velocity)) * DT / energy)


def main(argv: list[str]) -> None:
    sizes = (20, 50) if "--quick" in argv else (50, 200, 1000)
    rows = [measure(n) for n in sizes]
    lines = ["| n | elements | steps | forward (ms) | simulate (ms) | gradient (ms) | (forward + gradient) / forward |",
             "|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['n']} | {r['elements']} | {r['steps']} | {1e3 * r['forward']:.3g} | "
                     f"{1e3 * r['simulate']:.3g} | {1e3 * r['gradient']:.3g} | {r['ratio']:.2f} |")
    table = "\n".join(lines)
    print(table)
    if "--quick" in argv:
        return
    body = ("## Exact gradient (adjoint) for striker design\n\n"
            "`python benchmarks/bench_adjoint.py`: one gradient of the rock efficiency of a drilling blow "
            "(striker of n elements on a drill rod of 4n elements with a bit-rock end, 10 n steps) in units of "
            "one forward run; checkpoint every ceil(sqrt(steps)) steps. Best of several repeats.\n\n"
            f"{table}\n\n"
            f"Machine: {platform.processor() or platform.machine()}, Python {platform.python_version()}, "
            f"numpy {np.__version__}, numba {numba.__version__}.\n")
    write_section("adjoint", body)


if __name__ == "__main__":
    main(sys.argv[1:])
