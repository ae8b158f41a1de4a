"""Speed of impactor synthesis (recursive method, thesis chapter 4) for n = 400, 3,000 and 30,000 elements.

Cases
-----
A. Thesis example 1 scaled: the Lundberg-Lesser exponential on a semi-infinite uniform bar (closed-form face
   response), fixed duration 0.193 ms cut into n windows.
B. A stepped struck bar of 400 elements (impedance rising by half after 200 elements, non-reflecting far end)
   whose face response comes from the direct solver (one run of 2n steps), same target.
C. The percussion-drilling example (force prescribed at the bit-rock interface): two runs of the direct
   solver for the rectangular and the face response through the 2.75 m drill string, the triangular Toeplitz
   solve, then the peeling. The drill string has 4 n elements, so the direct solver's cost grows like n^2
   with a large constant; n = 30,000 would need ~2e10 element updates and is not run.

Baseline: the thesis's recursion with a full re-simulation per element
(:func:`rodimpact.inverse.synthesize_by_resimulation`, same compiled direct solver), run for small n only;
its times for n = 3,000 and 30,000 are extrapolated (said so in the table) with the model
t = a n + b n^2 + c n^3 fitted (non-negative least squares) to the measured points: n simulations, each with a
fixed overhead, O(n) steps through the struck bar and O(n^2) element updates in the growing striker.

Run:  python benchmarks/bench_synthesis.py   (writes the "synthesis" section of docs/performance.md)
"""

from __future__ import annotations

import platform
import time
import warnings

import numba
import numpy as np
from scipy.optimize import nnls

import rodimpact as ri
from rodimpact.inverse import ExponentialDecay, percussion_drilling_example, synthesize, synthesize_by_resimulation
from rodimpact.inverse.struck import as_struck_system

try:
    from _report import write_section
except ImportError:  # run from the repository root
    from benchmarks._report import write_section

DURATION = 100 * 1.93e-6          # thesis: 100 elements of 1.93 us
TARGET = ExponentialDecay(239.1e3, 0.383e-3)
SIZES = (400, 3000, 30000)
REF_SIZES = (50, 100, 200, 400, 800)


def _best(fn, repeat: int) -> tuple[float, object]:
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _case_a(n: int):
    dt = DURATION / n
    bar = ri.Rod.from_impedance([79.7e3] * 4, dt)
    return lambda: synthesize(TARGET, bar, 6.0, n=n, dt=dt, far_end="nonreflecting")


def _stepped(dt: float) -> ri.Rod:
    return ri.Rod.from_impedance([79.7e3] * 200 + [1.2e5] * 200, dt)


def _case_b(n: int):
    dt = DURATION / n
    bar = _stepped(dt)
    return lambda: synthesize(TARGET, bar, 6.0, n=n, dt=dt, far_end="nonreflecting")


def _case_c(n: int):
    prob = percussion_drilling_example(n)
    dt = 0.5 / n / ri.STEEL.wave_speed
    return lambda: prob.solve(dt=dt)


def _reference(n: int, case: str):
    dt = DURATION / n
    if case == "A":
        system = as_struck_system(ri.Rod.from_impedance([79.7e3] * 4, dt), far_end="nonreflecting")
    else:
        system = as_struck_system(_stepped(dt), far_end="nonreflecting")
    x = TARGET(dt * (2 * np.arange(n) + 1.0))
    return lambda: synthesize_by_resimulation(x, system, 6.0, dt)


def main() -> None:
    warnings.simplefilter("ignore", ri.inverse.SynthesisWarning)
    for fn in (_case_a(50), _case_b(50), _case_c(20), _reference(5, "A")):   # JIT warm-up (numba cache)
        fn()
    rows = []
    fast: dict[tuple[str, int], float] = {}
    for case, make in (("A", _case_a), ("B", _case_b), ("C", _case_c)):
        for n in SIZES:
            if case == "C" and n > 3000:
                continue
            repeat = 3 if n <= 3000 else 2
            t, res = _best(make(n), repeat)
            fast[case, n] = t
            verify = res.verify().max_deviation if n <= 3000 else float("nan")
            rows.append((case, n, t, res.n_feasible, res.diagnostics["face_response"], verify))
            print(f"case {case} n={n}: {t:.4f} s ({res.n_feasible} elements, verify {verify:.2e})")
    ref_rows = []
    fits = {}
    for case in ("A", "B"):
        ts = []
        for n in REF_SIZES:
            t, _ = _best(_reference(n, case), 1)
            ts.append(t)
            ref_rows.append((case, n, t))
            print(f"reference case {case} n={n}: {t:.3f} s")
        ns = np.array(REF_SIZES, dtype=float)
        coef, _ = nnls(np.column_stack([ns, ns**2, ns**3]) / np.array(ts)[:, None], np.ones(ns.size))
        fits[case] = coef                     # relative least squares: each point weighted by 1/t
    lines = ["## Impactor synthesis (`benchmarks/bench_synthesis.py`)", "",
             f"Machine: {platform.machine()}, Python {platform.python_version()}, numpy {np.__version__}, "
             f"numba {numba.__version__}; single thread. Best of 3 runs (2 for n = 30,000), after JIT warm-up.",
             "",
             "Case A: thesis example 1 scaled (Lundberg-Lesser exponential, semi-infinite uniform bar, closed-form "
             "face response). Case B: same target on a stepped 400-element bar (impedance x1.5 after 200 elements, "
             "non-reflecting end; face response from one direct-solver run). Case C: percussion drilling, "
             "force prescribed at the bit-rock interface (two direct-solver runs through a drill string of "
             "4 n elements, Toeplitz solve, peeling; n = 30,000 not run: ~2e10 element updates in the "
             "struck system alone). "
             "`verify` = max relative deviation of the direct solver with the synthesized striker from the "
             "target (n <= 3,000).",
             "",
             "| case | n | synthesize() / s | elements found | face response | verify |",
             "|---|---:|---:|---:|---|---:|"]
    for case, n, t, m, how, ver in rows:
        lines.append(f"| {case} | {n:,} | {t:.4f} | {m:,} | {how} | {'-' if np.isnan(ver) else f'{ver:.1e}'} |")
    lines += ["", "Baseline: the thesis's recursion, re-simulating the whole impact from t = 0 for every element "
              "(same compiled direct solver; `synthesize_by_resimulation`). Measured up to n = 800; the values "
              "for n = 3,000 and 30,000 are extrapolations with t = a n + b n^2 + c n^3 fitted to the "
              "measurements (estimates, not measurements):", "",
              "| case | measured n: time / s | fitted a, b, c | n = 400 | est. n = 3,000 | est. n = 30,000 |",
              "|---|---|---|---:|---:|---:|"]

    def model(coef, n):
        return coef[0] * n + coef[1] * n**2 + coef[2] * n**3

    for case in ("A", "B"):
        coef = fits[case]
        meas = ", ".join(f"{n}: {t:.3g}" for cc, n, t in ref_rows if cc == case)
        t400 = [t for cc, n, t in ref_rows if cc == case and n == 400][0]
        lines.append(f"| {case} | {meas} | {coef[0]:.2e}, {coef[1]:.2e}, {coef[2]:.2e} | {t400:.3g} s "
                     f"(measured) | {model(coef, 3000):.3g} s | {model(coef, 30000):.3g} s |")
    lines += ["", "Speed-up of the peeling formulation over the re-simulation baseline (baseline / fast path; "
              "n = 400 measured, larger n from the extrapolated baseline):", "",
              "| case | n = 400 | n = 3,000 | n = 30,000 |", "|---|---:|---:|---:|"]
    for case in ("A", "B"):
        coef = fits[case]
        t400 = [t for cc, n, t in ref_rows if cc == case and n == 400][0]
        ratios = [t400 / fast[case, 400]] + [model(coef, n) / fast[case, n] for n in SIZES[1:]]
        lines.append(f"| {case} | {ratios[0]:.3g} | {ratios[1]:.3g} | {ratios[2]:.3g} |")
    write_section("synthesis", "\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
