"""Speed of impactor synthesis (recursive method, thesis chapter 4) for n = 400, 3,000 and 30,000 elements.

Cases
-----
A. Thesis example 1 scaled: the Lundberg-Lesser exponential on a semi-infinite uniform bar (closed-form face
   response), fixed duration 0.193 ms cut into n windows.
B. A stepped struck bar of 400 elements (impedance rising by half after 200 elements, non-reflecting far end)
   whose face response comes from the lattice equations of the direct solver (band sweep of 2n steps,
   inverse/_rectangular.py), same target.
C. The percussion-drilling example (force prescribed at the bit-rock interface): the rectangular and the face
   response through the drill string by band-limited sweeps of the lattice in the frame of the travelling
   waves (only reflecting nodes cost anything: the section joints and the steps of the bit's taper), the
   triangular Toeplitz solve, then the peeling; n = 30,000 is not run (the verification would need a direct
   run of ~1e10 node updates).

Baseline: the thesis's recursion with a full re-simulation per element
(:func:`rodimpact.inverse.synthesize_by_resimulation`, same compiled direct solver), run for small n only;
its times for n = 3,000 and 30,000 are extrapolated (said so in the table) with the model
t = a n + b n^2 + c n^3 fitted (non-negative least squares) to the measured points: n simulations, each with a
fixed overhead, O(n) steps through the struck bar and O(n^2) element updates in the growing striker.

Scale (section "synthesis-scale"): three measurements, each against the implementation it replaced (kept here
as the baseline):

1. Peeling (inverse/_schur.py): the O(n^2) loops (``peel_numba``) for n = 1e3 .. 1e5 and the divide-and-
   conquer Schur recursion (``peel_superfast``) for n = 1e3 .. 1e6, on the face data of a smooth target
   against a semi-infinite bar (closed form); fitted log-log slopes, the measured crossover, the largest
   relative difference of the impedances, and ``synthesize()`` end to end at n = 1e6 (thesis example 1
   scaled, closed-form face response).
2. ``Rod.from_impedance`` with a profile that changes at every element, 1e6 elements: cylinders made on demand
   vs one validated Cylinder per element (the former implementation, below).
3. ``transform_force`` for the percussion-drilling string (thesis Sec. 4.2.2), n = 1e4: band-limited sweep vs
   one run of the direct solver for the rectangular response (the former implementation, below).

Run:  python benchmarks/bench_synthesis.py                 (both sections of docs/performance.md)
      python benchmarks/bench_synthesis.py --part scale    (only the "synthesis-scale" section)
      python benchmarks/bench_synthesis.py --quick         (scale part at small sizes, prints only: a check)
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import time
import warnings

import numba
import numpy as np
import scipy
from scipy.optimize import nnls

import rodimpact as ri
from rodimpact.inverse import ExponentialDecay, percussion_drilling_example, synthesize, synthesize_by_resimulation
from rodimpact.inverse import _kernels as K, _schur as S
from rodimpact.inverse._toeplitz import solve_lower_toeplitz
from rodimpact.inverse.struck import (at_rest, driven, linearized, locate, position_probe,
                                      position_quantity)
from rodimpact.rods.material import Material
from rodimpact.rods.rod import ImpedanceProfile
from rodimpact.rods.segments import Cylinder

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _old_loop import old_simulate  # noqa: E402

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
    return lambda: synthesize(TARGET, ri.System.struck(bar, far_end="nonreflecting"), 6.0, n=n, dt=dt)


def _stepped(dt: float) -> ri.Rod:
    return ri.Rod.from_impedance([79.7e3] * 200 + [1.2e5] * 200, dt)


def _case_b(n: int):
    dt = DURATION / n
    bar = _stepped(dt)
    return lambda: synthesize(TARGET, ri.System.struck(bar, far_end="nonreflecting"), 6.0, n=n, dt=dt)


def _case_c(n: int):
    prob = percussion_drilling_example(n)
    return lambda: prob.solve(dt=prob.dt)


def _reference(n: int, case: str):
    dt = DURATION / n
    if case == "A":
        system = ri.System.struck(ri.Rod.from_impedance([79.7e3] * 4, dt), far_end="nonreflecting")
    else:
        system = ri.System.struck(_stepped(dt), far_end="nonreflecting")
    x = TARGET(dt * (2 * np.arange(n) + 1.0))
    return lambda: synthesize_by_resimulation(x, system, 6.0, dt)


def _face_data(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Smooth compressive target (window values) and the relative face velocity of a semi-infinite bar."""
    t = np.arange(n) / n
    x = -2e5 * (1.0 + 0.3 * t + 0.1 * np.sin(7.0 * t) + 0.05 * np.cos(23.0 * t))
    return x, -x / 8e4 - 6.0


def _slope(ns, ts) -> float:
    return float(np.polyfit(np.log(ns), np.log(ts), 1)[0])


# ---------------------------------------------------------------------------------------------- 1. peeling
def bench_peeling(quad_sizes, fast_sizes, crossover_sizes, n_synth) -> list[str]:
    x, u = _face_data(3000)
    K.peel_numba(x, u)
    S.peel_superfast(x, u)                                  # JIT / cache warm-up
    rows = []
    quad = {}
    for n in sorted(set(quad_sizes) | set(fast_sizes)):
        x, u = _face_data(n)
        rep = 3 if n <= 1e5 else 2
        tf, b = _best(lambda: S.peel_superfast(x, u), rep)
        tq, diff = float("nan"), float("nan")
        if n in quad_sizes:
            tq, a = _best(lambda: K.peel_numba(x, u), 3 if n <= 3e4 else 1)
            quad[n] = tq
            m = a[3]
            assert m == b[3] == n, "the benchmark target must be feasible for every n"
            diff = float(np.max(np.abs(b[0][:m] / a[0][:m] - 1.0)))
        rows.append((n, tq, tf, diff))
        print(f"peel n={n}: O(n^2) {tq:.4g} s, superfast {tf:.4g} s, max |dZ/Z| {diff:.2e}")
    qs = [(n, tq) for n, tq, _, _ in rows if np.isfinite(tq) and n >= 1e4]
    fs = [(n, tf) for n, _, tf, _ in rows if n >= 1e4]
    slope_q = _slope(*zip(*qs)) if len(qs) > 1 else float("nan")
    slope_f = _slope(*zip(*fs)) if len(fs) > 1 else float("nan")
    cross = []
    for n in crossover_sizes:
        x, u = _face_data(n)
        tq, _ = _best(lambda: K.peel_numba(x, u), 7)
        tf, _ = _best(lambda: S.peel_superfast(x, u), 7)
        cross.append((n, tq, tf))
    faster = [n for n, tq, tf in cross if tf < tq]
    measured_cross = faster[0] if faster else None
    dt = 100 * 1.93e-6 / n_synth
    bar = ri.Rod.from_impedance([79.7e3] * 4, dt)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.inverse.SynthesisWarning)
        struck = ri.System.struck(bar, far_end="nonreflecting")
        t_syn, res = _best(lambda: synthesize(ExponentialDecay(239.1e3, 0.383e-3), struck, 6.0, n=n_synth, dt=dt), 2)
    print(f"synthesize n={n_synth}: {t_syn:.3f} s ({res.diagnostics['peeling']}, {res.n_feasible} elements)")
    lines = ["### Peeling: O(n^2) loops vs superfast Schur recursion", "",
             "Face data of a smooth compressive target against a semi-infinite bar (closed form); best of 3 "
             "(O(n^2) at n >= 1e5 and superfast at 1e6: fewer runs). `max |dZ/Z|` = largest relative "
             "difference of the impedances of the two paths.", "",
             "| n | O(n^2) / s | superfast / s | speed-up | max abs(dZ/Z) |", "|---:|---:|---:|---:|---:|"]
    for n, tq, tf, diff in rows:
        q = "-" if np.isnan(tq) else f"{tq:.4g}"
        sp = "-" if np.isnan(tq) else f"{tq / tf:.3g}"
        d = "-" if np.isnan(diff) else f"{diff:.1e}"
        lines.append(f"| {n:,} | {q} | {tf:.4g} | {sp} | {d} |")
    lines += ["", f"Fitted log-log slopes (n >= 1e4): O(n^2) path {slope_q:.2f}, superfast {slope_f:.2f} "
              f"(for comparison: n log^2 n has the local slope 1 + 2 / ln n = 1.22 at n = 1e4, 1.14 at 1e6).", "",
              "Crossover (best of 7): " + ", ".join(f"n = {n:,}: {tq * 1e3:.3g} / {tf * 1e3:.3g} ms" for n, tq, tf
                                                    in cross)
              + f" (O(n^2) / superfast). Superfast first faster at n = {measured_cross}; "
              f"`method=\"auto\"` switches at `_schur.CROSSOVER` = {S.CROSSOVER:,}, leaf blocks of at most "
              f"`_schur.LEAF` = {S.LEAF} layers.", "",
              f"`synthesize()` end to end, thesis example 1 scaled to n = {n_synth:,} (closed-form face response): "
              f"**{t_syn:.3g} s** (best of 2; peeling: {res.diagnostics['peeling']})."]
    return lines


# ------------------------------------------------------------------------------------ 2. from_impedance
def from_impedance_old(z: np.ndarray, dt: float, c: float = ri.STEEL.wave_speed,
                       rho: float = ri.STEEL.density) -> ri.Rod:
    """The former Rod.from_impedance: one validated Cylinder per run of equal impedance."""
    mat = Material(rho * c * c, rho, "impedance-level")
    cuts = np.flatnonzero(np.diff(z) != 0) + 1
    starts = np.concatenate([[0], cuts])
    stops = np.concatenate([cuts, [z.size]])
    segs = tuple(Cylinder((b - a) * c * dt, math.sqrt(4.0 * z[a] / (rho * c) / math.pi), material=mat)
                 for a, b in zip(starts, stops))
    return ri.Rod(segs, mat, None, ImpedanceProfile(z.copy(), dt, c))


def bench_from_impedance(n: int) -> list[str]:
    z = 8e4 * np.exp(np.cumsum(np.random.default_rng(0).normal(0.0, 0.01, n)))
    t_new, rod = _best(lambda: ri.Rod.from_impedance(z, 1e-7), 3)
    t_old, old = _best(lambda: from_impedance_old(z, 1e-7), 1)
    same = rod == old
    print(f"from_impedance n={n}: new {t_new:.3g} s, old {t_old:.3g} s, equal rods: {same}")
    return ["### `Rod.from_impedance`, a profile that changes at every element", "",
            "| elements | former (one Cylinder each) / s | now / s | speed-up | same rod |",
            "|---:|---:|---:|---:|---|",
            f"| {n:,} | {t_old:.3g} | {t_new:.3g} | {t_old / t_new:.3g} | {same} |"]


# ----------------------------------------------------------------------------------- 3. transform_force
def transform_old(prob, n: int, dt: float, frozen: bool) -> np.ndarray:
    """The former transform_force at rest: rectangular response from one direct-solver run, Toeplitz solve;
    ``frozen``: with the solver's loop as it was before the speed work (``_old_loop.old_simulate``), else with
    today's ``simulate``."""
    o = prob.options
    system = prob.struck_system
    loc = locate(system, o["position"], dt)
    lin, _ = linearized(system)
    steps = loc.node + 2 * n - 1
    driving = driven(at_rest(lin), np.array([1.0, 0.0]), dt)
    sim = (old_simulate(driving, steps, dt, [position_probe(loc)]) if frozen
           else ri.simulate(driving, steps=steps, dt=dt, outputs=ri.Outputs(probes=[position_probe(loc)])))
    p = sim.probe("synthesis_position")
    g = position_quantity(o["quantity"], p.force, p.velocity, float(sim.lattice.impedance[loc.element_left]))
    g = g[loc.node + 2 * np.arange(n)]
    y = prob.target(2.0 * dt * np.arange(n))            # rule "start": window starts
    return solve_lower_toeplitz(g, y, "auto")


def bench_transform(n: int) -> list[str]:
    prob = percussion_drilling_example(n)
    o = prob.options
    dt = 0.5 / n / ri.STEEL.wave_speed      # the string scales with n (4n elements): the n = 1e4 case

    def new():
        return ri.inverse.transform_force(prob.target, prob.struck_system, o["position"], n=n, dt=dt,
                                          quantity=o["quantity"], rule=o["rule"])

    small = percussion_drilling_example(50)
    ri.inverse.transform_force(small.target, small.struck_system, o["position"], n=50, dt=small.dt,
                               quantity=o["quantity"], rule=o["rule"])   # warm-up
    t_new, tr = _best(new, 3)
    t_old, x_old = _best(lambda: transform_old(prob, n, dt, frozen=True), 1)
    t_direct, x_direct = _best(lambda: transform_old(prob, n, dt, frozen=False), 3)
    diff = max(float(np.max(np.abs(tr.impact_force - x)) / np.max(np.abs(x))) for x in (x_old, x_direct))
    print(f"transform_force drill string n={n}: new {t_new:.3g} s, former {t_old:.3g} s, direct solver now "
          f"{t_direct:.3g} s, max rel diff {diff:.1e}")
    return ["### `transform_force`, percussion-drilling string (bit-rock spring, incident wave at the rock)", "",
            "Former: the rectangular response from one direct-solver run with the solver's loop before the speed "
            "work (`benchmarks/_old_loop.py`, frozen); also with today's direct solver; now: the band sweep in the "
            "wave frame.", "",
            "| n | struck elements | former / s | direct solver today / s | now / s | speed-up vs former | "
            "max abs(dX)/max abs(X) |", "|---:|---:|---:|---:|---:|---:|---:|",
            f"| {n:,} | {tr.location.node:,} | {t_old:.3g} | {t_direct:.3g} | {t_new:.3g} | {t_old / t_new:.3g} | "
            f"{diff:.1e} |"]


def main_base() -> None:
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
             "non-reflecting end; face response from the lattice, band sweep of 2n steps). Case C: percussion "
             "drilling, force prescribed at the bit-rock interface (rectangular and face response by band "
             "sweeps in the frame of the travelling waves, where only the reflecting nodes of the drill string "
             "cost anything; Toeplitz solve, peeling; n = 30,000 not run). "
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


def main_scale(quick: bool) -> None:
    if quick:
        parts = [bench_peeling((1000, 3000), (1000, 3000, 10000), (1000, 3000), 20000), bench_from_impedance(20000),
                 bench_transform(300)]
    else:
        parts = [bench_peeling((1000, 3000, 10000, 30000, 100000), (1000, 3000, 10000, 30000, 100000, 300000,
                                                                    1000000),
                               (2000, 3000, 4000, 5000, 6000, 8000), 1000000),
                 bench_from_impedance(1000000), bench_transform(10000)]
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    lines = ["## Inverse problem at scale (`benchmarks/bench_synthesis.py --part scale`)", "",
             f"Machine: {platform.machine()}, {os.cpu_count()} cores, load average {load:.2f} at the end; Python "
             f"{platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, numba "
             f"{numba.__version__}; single thread.", ""]
    for part in parts:
        lines += part + [""]
    text = "\n".join(lines)
    print(text)
    if not quick:
        write_section("synthesis-scale", text)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=("all", "base", "scale"), default="all",
                    help="which section to measure and write (default: both)")
    ap.add_argument("--quick", action="store_true",
                    help="scale part only, at small sizes; prints, does not write the docs")
    args = ap.parse_args()
    if args.quick:
        main_scale(True)
        return
    if args.part in ("all", "base"):
        main_base()
    if args.part in ("all", "scale"):
        main_scale(False)


if __name__ == "__main__":
    main()
