"""Speed and quality of striker design (rodimpact.design) against a plain baseline.

Case: a half-sine pulse of 100 us and 80 kN peak at the impact face of a 20 mm steel bar with a non-reflecting
end; steel striker of 5-60 mm diameter at 12 m/s; n = 50 and 200 elements (dt = 100 us / 2n). The exact
recursive method gives 1 element (a force cannot start at 0 N).

* ``design``: rodimpact.design with its defaults (adjoint gradients, warm start, three starts).
* baseline: scipy L-BFGS-B over the element impedances (scaled, same bounds) with finite-difference gradients
  ('2-point', n + 1 runs per gradient) through rodimpact.simulate, three starts (uniform strikers of 10, 20 and
  40 mm), at most ``BASELINE_ITERATIONS`` iterations each; same misfit definition (every step of the target's
  span against the window values, rule "midpoint").

Also: n = 1000 designed with ``design`` (wall time, peak memory traced by tracemalloc, maximum resident set).

Run:  python benchmarks/bench_design.py           (writes the "design" section of docs/performance.md)
      python benchmarks/bench_design.py --quick   (small sizes, prints only; a check that it runs)
"""

from __future__ import annotations

import argparse
import platform
import resource
import time
import tracemalloc
import warnings

import numpy as np
from scipy.optimize import minimize

import rodimpact as ri

try:
    from _report import write_section
except ImportError:  # run from the repository root
    from benchmarks._report import write_section

PEAK, SPAN, V = 80e3, 100e-6, 12.0
D_BAR, D_MIN, D_MAX = 0.020, 0.005, 0.060
BASELINE_ITERATIONS = 200


def _case(n: int):
    dt = SPAN / (2 * n)
    z_bar = ri.STEEL.impedance(np.pi / 4 * D_BAR ** 2)
    bar = ri.Rod.from_impedance([z_bar] * 8, dt)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -PEAK * np.sin(np.pi * t / SPAN), duration=SPAN)
    return dt, bar, target


def _z(d: float) -> float:
    return ri.STEEL.impedance(np.pi / 4 * d * d)


def run_design(n: int, **kw):
    dt, bar, target = _case(n)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        d = ri.design(target, struck=bar, striker_velocity=V, n=n, dt=dt, far_end="nonreflecting",
                      diameter_bounds=(D_MIN, D_MAX), material=ri.STEEL, **kw)
        return d, time.perf_counter() - t0


def run_baseline(n: int, iterations: int):
    dt, bar, target = _case(n)
    x = target.window_values(n, dt)
    ref = np.repeat(x, 2)
    zlo, zhi = _z(D_MIN), _z(D_MAX)
    zr = np.sqrt(zlo * zhi)
    runs = [0]

    def misfit(u: np.ndarray) -> float:
        runs[0] += 1
        striker = ri.Rod.from_impedance(u[::-1] * zr, dt)
        sim = ri.simulate(ri.System([striker, bar], [V, 0.0], right="nonreflecting"), steps=2 * n, dt=dt)
        return float(np.sum((sim.junction_force[0] - ref) ** 2) / np.sum(ref ** 2))

    t0 = time.perf_counter()
    best = np.inf
    for d in (0.010, 0.020, 0.040):
        res = minimize(misfit, np.full(n, _z(d) / zr), jac="2-point", method="L-BFGS-B",
                       bounds=[(zlo / zr, zhi / zr)] * n, options={"maxiter": iterations})
        best = min(best, float(res.fun))
    return float(np.sqrt(best)), time.perf_counter() - t0, runs[0]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, print only")
    args = ap.parse_args()
    sizes = (8, 16) if args.quick else (50, 200)
    big = 40 if args.quick else 1000
    iters = 5 if args.quick else BASELINE_ITERATIONS
    kw = dict(max_iterations=5) if args.quick else {}
    run_design(4, **kw)                                        # compile/load the kernels once
    rows = []
    for n in sizes:
        d, t_d = run_design(n, **kw)
        m_b, t_b, runs_b = run_baseline(n, iters)
        rows.append((n, d.misfit, t_d, d.diagnostics["forward_runs"], d.diagnostics["gradient_runs"], m_b, t_b,
                     runs_b))
        print(f"n = {n}: design misfit {d.misfit:.4g} in {t_d:.3g} s ({d.diagnostics['forward_runs']} forward, "
              f"{d.diagnostics['gradient_runs']} gradient runs); baseline misfit {m_b:.4g} in {t_b:.3g} s "
              f"({runs_b} simulations); speed-up {t_b / t_d:.3g}")
    tracemalloc.start()
    d, t_big = run_design(big, **kw)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"n = {big}: design misfit {d.misfit:.4g} in {t_big:.3g} s, {d.iterations} iterations, traced peak "
          f"{peak / 2 ** 20:.3g} MiB, max RSS {rss:.0f} MiB")
    if args.quick:
        return
    lines = [f"Striker design (`benchmarks/bench_design.py`, {platform.processor() or platform.machine()}, "
             f"numba backend): half-sine of {PEAK / 1e3:g} kN and {SPAN * 1e6:g} us on a {D_BAR * 1e3:g} mm steel "
             f"bar (non-reflecting end), steel striker {D_MIN * 1e3:g}-{D_MAX * 1e3:g} mm at {V:g} m/s. Baseline: "
             f"L-BFGS-B with finite-difference gradients through `simulate`, three uniform starts, at most "
             f"{BASELINE_ITERATIONS} iterations each.", "",
             "| n | design misfit | design time / s | forward + gradient runs | baseline misfit | baseline time / s "
             "| baseline simulations | speed-up |", "|---|---|---|---|---|---|---|---|"]
    for n, m_d, t_d, fr, gr, m_b, t_b, rb in rows:
        lines.append(f"| {n} | {m_d:.4g} | {t_d:.3g} | {fr} + {gr} | {m_b:.4g} | {t_b:.3g} | {rb} | {t_b / t_d:.3g} |")
    lines += ["", f"n = {big}: designed in {t_big:.3g} s ({d.iterations} iterations, misfit {d.misfit:.4g}); "
                  f"peak traced memory {peak / 2 ** 20:.3g} MiB, maximum resident set {rss:.0f} MiB."]
    write_section("design", "## Striker design\n\n" + "\n".join(lines))


if __name__ == "__main__":
    main()
