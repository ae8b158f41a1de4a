"""Striker design when the exact inverse fails: :func:`design`.

The recursive method (:func:`rodimpact.synthesize`) is exact but stops where the existence condition (thesis
eq. 4.20) fails, which it does for every force that starts at 0 N. :func:`design` instead minimises an objective
over the n element impedances (and optionally the impact velocity) under bounds, a mass and manufacturability
limits, with exact gradients from the adjoint of the lattice (:mod:`rodimpact.design._adjoint`, docs/adjoint.md)
and scipy's L-BFGS-B (:mod:`rodimpact.design.optimize`). The method is described in docs/design.md.

What is asked lives in three small objects: the objective (:class:`~rodimpact.design.objectives.MatchObjective`
or :class:`~rodimpact.design.objectives.EfficiencyObjective`), the striker's limits
(:class:`~rodimpact.design.constraints.StrikerLimits`) and how the optimum is searched (:class:`SearchOptions`);
the struck system is one :class:`~rodimpact.System` (:meth:`System.struck <rodimpact.rods.system.System.struck>`).
"""

from __future__ import annotations

import dataclasses
import sys
import time as _time
import warnings
from dataclasses import dataclass
from typing import Any, Callable, Optional, Union

import numpy as np

from .._moved import moved
from .._validate import integer, real_number
from .._version import __version__
from ..lattice.lattice import build_lattice
from ..rods.conditions import BitRockEnd, Specimen
from ..inverse.diagnosis import explain_bounds
from ..inverse.recursive import synthesize
from ..inverse.struck import STRUCK_KEYWORDS, as_struck_system, locate, window_count_check
from ..inverse.targets import as_target
from ..inverse.transform import struck_time_step, window_count
from ._adjoint import ImpactProblem
from .constraints import Constraints, StrikerLimits, build_constraints, velocity_start
from .objectives import (EfficiencyCost, EfficiencyObjective, MatchCost, MatchObjective, StrainRateCost,
                         StrainRateObjective)
from .optimize import Evaluator, Levels, OptimisationProgress, Run, best_of, minimise
from .result import DesignResult
from .screening import POOL_SIZE, candidate_pool, diverse, screen as screen_pool
from .stepped import stepped_design

#: misfit below which the recursive method's striker is returned as the exact answer
EXACT_MISFIT = 1e-9
#: several starts: each runs for max(SCREEN_MIN, max_iterations // SCREEN_FRACTION) iterations, then the best
#: CONTINUED of them continue up to max_iterations
SCREEN_MIN, SCREEN_FRACTION, CONTINUED = 10, 10, 2
#: coarse stages of every start: profiles of n / COARSE_DIVISORS[i] levels (only those with at least 2 elements
#: per level and at least 2 levels), each run for the screening iterations before the free profile
COARSE_DIVISORS = (6, 3)
#: basin hopping: relative amplitude (in log Z) of the smooth random perturbation, and the seed of its draws
HOP_AMPLITUDE, HOP_SEED = 0.3, 1


@dataclass(frozen=True)
class SearchOptions:
    """How :func:`design` searches for the optimum: the global phase (a screened pool, starts continued from
    coarse to fine, basin hops) and the local L-BFGS-B runs. Validated when made.

    starts:
        Number of starting profiles (>= 1). Where the objective is observed at the impact face or is the
        efficiency, the starts are the best, mutually different candidates of a pool of ``pool`` profiles
        simulated together by :func:`rodimpact.simulate_batch` (:mod:`rodimpact.design.screening`); otherwise the
        named starts. With several starts, each start is continued from a coarse profile (n/6, then n/3 levels)
        to the free one, max(10, max_iterations / 10) iterations per stage, and the best two free profiles
        continue for up to ``max_iterations``; every stage is a *run* of the convergence history (so there are
        more runs than starts).
    max_iterations:
        L-BFGS-B iterations per stage (>= 1).
    tolerance:
        L-BFGS-B's relative reduction ``ftol`` of the objective per iteration (0 < tolerance < 1).
    improvement:
        Relative-improvement stopping criterion: a run stops when its best objective has improved by less than
        this fraction over the last 10 iterations (0 <= improvement < 1; 0: never).
    pool:
        Candidates screened by :func:`rodimpact.simulate_batch` before the starts (>= 1).
    hops:
        Basin-hopping rounds after the starts (>= 0; with several starts): the best profile, perturbed (a smooth
        random factor, or a thin tail from a random element on), runs again and replaces the best if it ends
        better (default 8: on the half-sine of issue 20 they take the misfit from 0.1262 to 0.1260).
        ``diagnostics["local_optima"]`` lists the objective at the end of every start and hop.
    warm_start:
        Try the exact recursive method first (:class:`~rodimpact.design.objectives.MatchObjective` only): its
        striker is the answer when it exists inside the limits, else its feasible prefix is a start.
    """

    starts: int = 16
    max_iterations: int = 300
    tolerance: float = 1e-14
    improvement: float = 1e-6
    pool: int = POOL_SIZE
    hops: int = 8
    warm_start: bool = True

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        put("starts", integer("SearchOptions.starts", self.starts, 1))
        put("max_iterations", integer("SearchOptions.max_iterations", self.max_iterations, 1))
        put("tolerance", real_number("SearchOptions.tolerance", self.tolerance, "a finite number with 0 < "
                                     "tolerance < 1 (L-BFGS-B's relative reduction ftol of the objective per "
                                     "iteration)", lambda x: 0.0 < x < 1.0))
        put("improvement", real_number("SearchOptions.improvement", self.improvement, "a finite number with 0 <= "
                                       "improvement < 1 (relative improvement of the best objective over 10 "
                                       "iterations below which a run stops)", lambda x: 0.0 <= x < 1.0))
        put("pool", integer("SearchOptions.pool", self.pool, 1, "candidates screened by simulate_batch"))
        put("hops", integer("SearchOptions.hops", self.hops, 0, "basin-hopping rounds after the starts"))
        if not isinstance(self.warm_start, (bool, np.bool_)):
            raise TypeError(f"SearchOptions.warm_start: must be True (try the exact recursive method first) or "
                            f"False, got {self.warm_start!r}")
        put("warm_start", bool(self.warm_start))


def coarse_levels(n: int) -> list[int]:
    """Level counts of the coarse-to-fine continuation for n elements (coarsest first)."""
    out: list[int] = []
    for d in COARSE_DIVISORS:
        k = int(round(n / d))
        if 2 <= k <= n // 2 and k not in out:
            out.append(k)
    return out


def _even_breaks(n: int, k: int) -> np.ndarray:
    """Boundaries [0, ..., n] of k groups of (nearly) equal size."""
    return np.unique(np.linspace(0, n, k + 1).round().astype(int))


_OBJECTIVE = ("{key}: give the objective as the first argument: ri.design(ri.MatchObjective(target, {key}=...), "
              "struck, ...)")
_EFFICIENCY = ("{key}: give the objective as the first argument: ri.design(ri.EfficiencyObjective({key}=...), "
               "struck, ...)")
_LIMITS = ("{key}: give the striker's limits as one StrikerLimits: ri.design(target, struck, ..., "
           "limits=ri.StrikerLimits({key}=...))")
_SEARCH = ("{key}: give the search options as one SearchOptions: ri.design(target, struck, ..., "
           "search=ri.SearchOptions({key}=...))")
#: the keywords design() took before its parameters moved into the objects it receives, and where each went
MOVED = {
    **STRUCK_KEYWORDS,
    "objective": ("objective: give the objective as the first argument: ri.design(ri.EfficiencyObjective(), struck, "
                  "...) or ri.design(ri.MatchObjective(target, position=...), struck, ...) (a bare target is "
                  "matched at the impact face)"),
    **{key: _OBJECTIVE.format(key=key) for key in ("position", "quantity", "rule", "weights")},
    **{key: _EFFICIENCY.format(key=key) for key in ("reloading", "steps", "duration")},
    **{key: _LIMITS.format(key=key) for key in ("impedance_bounds", "diameter_bounds", "material", "bore", "mass",
                                                 "velocity_bounds", "max_steps", "smoothness")},
    **{key: _SEARCH.format(key=key) for key in ("starts", "max_iterations", "tolerance", "improvement", "pool",
                                                 "hops", "warm_start")},
}


@moved(MOVED)
def design(target: Any, struck: Any, striker_velocity: Optional[float] = None,
           n: Union[int, tuple[int, int], None] = None, dt: Optional[float] = None, *,
           limits: Optional[StrikerLimits] = None, search: Optional[SearchOptions] = None,
           progress: Optional[bool] = None, backend: str = "numba") -> DesignResult:
    """Find the striker impedance profile that minimises an objective under constraints.

    Parameters
    ----------
    target:
        What to design for: the wished force history (N, tension positive, impact forces negative; any form
        :func:`rodimpact.synthesize` accepts), matched at the impact face; or a
        :class:`~rodimpact.MatchObjective` (the force observed at a ``position``, ``quantity``, ``rule``,
        ``weights``); or an :class:`~rodimpact.EfficiencyObjective` (work done on the rock per blow over the
        striker's kinetic energy; needs a :class:`~rodimpact.BitRockEnd` far end); or a
        :class:`~rodimpact.design.objectives.StrainRateObjective` (the strain rate of the struck system's
        :class:`~rodimpact.Specimen` held at a rate over a window, the specimen's law in the loop; needs ``n``).
    struck:
        The struck system (left end = impact face): a :class:`~rodimpact.Rod` or rods listed from the impact face
        outwards (bonded, at rest, free far end), or a :class:`~rodimpact.System` made by
        :meth:`ri.System.struck(rods, far_end=..., velocity=..., junctions=..., loads=..., initial=...)
        <rodimpact.rods.system.System.struck>`.
    striker_velocity:
        Impact velocity, m/s (> 0); the start value when ``limits.velocity_bounds`` is given.
    n:
        Number of striker elements (default for a match: as many as the target's windows). For the efficiency
        with a prescribed ``limits.mass``, a range (lo, hi): the piston's length varies; the best uniform
        piston of the same mass is found over the range, full designs run at its count, its two neighbours and
        hi, and the best is returned with ``diagnostics["lengths"]``.
    dt:
        Travel time of one element, s (default: the smallest of struck rods built with ``Rod.from_impedance``).
    limits:
        What the striker may be (:class:`~rodimpact.StrikerLimits`: impedance or diameter bounds, material, bore,
        mass, velocity bounds, steps, smoothness). Default: impedances within 1/100..100 times the struck face
        impedance, a steel striker, any mass, the velocity fixed.
    search:
        How the optimum is searched (:class:`~rodimpact.SearchOptions`: starts, iterations, tolerance,
        improvement, screened pool, basin hops, warm start). Default: ``SearchOptions()``.
    progress:
        Print progress lines (run, iteration, objective, best so far) to stderr: True always, False never,
        None (default) when stderr is a terminal.
    backend:
        "numba" or "numpy" (forward and adjoint runs).
    """
    wall0 = _time.perf_counter()
    goal = _as_objective(target)
    match = isinstance(goal, MatchObjective)
    rate_goal = isinstance(goal, StrainRateObjective)
    limits = StrikerLimits() if limits is None else _instance("limits", limits, StrikerLimits)
    search = SearchOptions() if search is None else _instance("search", search, SearchOptions)
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    if progress is not None and not isinstance(progress, (bool, np.bool_)):
        raise TypeError(f"progress: must be True, False or None (when stderr is a terminal), got {progress!r}")
    if not match and not rate_goal and isinstance(n, (tuple, list)):
        return _design_lengths(n, limits, wall0, lambda m: design(
            goal, struck, striker_velocity, m, dt, limits=limits, search=search, progress=progress, backend=backend))
    show_progress = bool(progress) if progress is not None else _stderr_is_a_terminal()
    system = as_struck_system(struck)
    dt = struck_time_step(system, dt)
    lat = build_lattice(system, dt)
    face_z = float(lat.impedance[0])
    diag: dict[str, Any] = {"version": __version__, "backend": backend}

    if match:
        tgt = as_target(goal.target, goal.rule)
        n = window_count(tgt, n, dt)
        avail = tgt.available_windows(dt)
        nw = n if avail is None else avail
        windows = tgt.window_values(nw, dt)
        bad = np.flatnonzero(~np.isfinite(windows))
        if bad.size:
            j = int(bad[0])
            raise ValueError(f"target: window {j + 1} (from t = {2 * j} dt) is {windows[j]}; forces must be finite")
        if not np.any(windows != 0.0):
            raise ValueError("target: is zero in every window; nothing to match")
        location = None if goal.position is None else locate(system, goal.position, dt)
        obj: Any = MatchCost.build(windows, None if location is None else location.node, goal.weights, dt,
                                   "MatchObjective.weights")
        run_steps = obj.steps
        obs_quantity = goal.quantity if location is not None else "force"
    elif rate_goal:
        if n is None:
            raise ValueError("n: give the number of striker elements for the strain-rate objective")
        n = window_count_check(n)
        joints = [i for i, j in enumerate(system.junctions) if isinstance(j, Specimen)]
        if not joints:
            raise ValueError("struck.junctions: the strain-rate objective needs a Specimen between two struck rods")
        specimen = system.junctions[joints[0]]
        arrival = int(lat.rod_start[joints[0] + 1])           # steps from the impact to the specimen's face
        first = arrival + int(round(goal.start / dt))
        last = arrival + max(int(round(goal.end / dt)), int(round(goal.start / dt)) + 1)
        location, obs_quantity, windows = None, "force", np.zeros(0)
        run_steps = last
        # junction j of the struck system is junction j + 1 of the impact problem (the striker's contact first)
        obj = StrainRateCost(joints[0] + 1, len(system.junctions) + 1, float(specimen.initial_length), goal.rate,
                             np.arange(first, last), dt, run_steps)
    else:
        if not isinstance(system.right, BitRockEnd):
            raise ValueError(f"struck.right: the 'efficiency' objective (work done on the rock / striker kinetic "
                             f"energy) needs a BitRockEnd far end, e.g. ri.System.struck(rods, "
                             f"far_end=ri.BitRockEnd(k1, k2)); got {type(system.right).__name__}")
        if n is None:
            raise ValueError("n: give the number of striker elements for the 'efficiency' objective")
        n = window_count_check(n)
        location = locate(system, sum(r.length for r in system.rods), dt)
        if goal.reloading:
            run_steps = goal.run_steps(n, lat.n_elements, dt)
        else:
            run_steps = _first_pass_steps(n, location.node)
        diag["efficiency_definition"] = (
            f"with reloading: work on the rock over {run_steps} steps, reflected waves load the rock again"
            if goal.reloading else
            f"first pass only (Lundberg's classical efficiency): work on the rock over {run_steps} steps, before "
            f"the first wave reflected at the bit returns")
        obs_quantity = "incident"       # the incident wave at the bit, for the report and plots
        windows = np.zeros(0)
        obj = EfficiencyCost(dt, run_steps)

    cons = build_constraints(n, dt, face_z, limits, striker_velocity)
    v0 = velocity_start(cons, striker_velocity)
    if rate_goal and goal.start_velocity is not None:
        v0 = velocity_start(cons, goal.start_velocity)
    if match and location is None and not any(system.velocities):
        diag["bounds_diagnosis"] = explain_bounds(windows, v0, face_z, float(cons.lower[0]), float(cons.upper[0]))
    problem = ImpactProblem(system, dt, n, run_steps, location=location, quantity=obs_quantity, backend=backend)
    z_ref = float(np.exp(np.mean(np.log(np.sqrt(cons.lower * cons.upper)))))
    ev = Evaluator(problem, obj, limits.smoothness, z_ref)

    def finish(z: np.ndarray, v: float, fw: Any, iterations: int, runs: list[Run]) -> DesignResult:
        diag.update(bounds=(cons.lower, cons.upper), forward_runs=ev.forward_runs, gradient_runs=ev.gradient_runs,
                    convergence=[r.history for r in runs], start_values=[r.value for r in runs])
        if match:
            diag["weights"] = obj.weights
        elif rate_goal:
            diag["strain_rate"] = obj.rates(fw)
            diag["window_steps"] = obj.index
        else:
            diag["uniform_reference"] = uniform_reference(system, dt, cons.mass_of(z), v, cons, n, goal,
                                                          location.node)
        value = obj.evaluate(fw, z, v)[0]
        return DesignResult(
            impedance=z, striker_velocity=float(v), dt=dt,
            objective="match" if match else ("strain-rate" if rate_goal else "efficiency"),
            time=dt * np.arange(run_steps),
            achieved=np.asarray(fw.observed, dtype=float), face_force=np.asarray(fw.face_force, dtype=float),
            target=obj.reference if match else np.zeros(0),
            compared=obj.index if match else np.zeros(0, dtype=int),
            window_values=windows, misfit=float(np.sqrt(value)) if match or rate_goal else None,
            efficiency=None if match or rate_goal else -value,
            constraint_report=cons.report(z, v), iterations=iterations, wall_time=_time.perf_counter() - wall0,
            struck=system, location=location, quantity=obs_quantity, material=limits.material, diagnostics=diag)

    initial_profiles: list[tuple[str, np.ndarray]] = []
    if match:
        exact = _warm_start(goal, system, v0, n, nw, dt, backend, cons, diag) if search.warm_start else None
        if exact is not None:
            value, fw = ev.value(exact, v0)
            if np.sqrt(value) < EXACT_MISFIT:
                diag["warm_start"] = ("exact: the recursive method's striker satisfies every constraint; it is the "
                                      f"answer (misfit {np.sqrt(value):.3g}, at rounding level)")
                return finish(exact, v0, fw, 0, [])
            initial_profiles.append(("recursive method", exact))
        elif diag.get("recursive_prefix") is not None:
            initial_profiles.append(("recursive prefix", diag.pop("recursive_prefix")))
        for name, level in (("uniform at the first force level", abs(windows[0])),
                            ("uniform at the peak force level", float(np.max(np.abs(windows))))):
            initial_profiles.append((name, np.full(n, _impedance_for_force(level, face_z, v0, cons))))
    elif rate_goal:
        if goal.start_impedance is not None:
            z_start = np.asarray(goal.start_impedance, dtype=float)
            if z_start.shape != (n,):
                raise ValueError(f"StrainRateObjective.start_impedance: need {n} values (one per element), got "
                                 f"shape {z_start.shape}")
            initial_profiles.append(("given start", z_start))
        initial_profiles.append(("uniform", np.full(n, face_z)))
    else:
        zu = np.full(n, face_z)
        initial_profiles += [("uniform", zu), ("rising taper", np.linspace(0.5, 2.0, n) * face_z),
                             ("falling taper", np.linspace(2.0, 0.5, n) * face_z)]
    free = Levels.free(cons)
    named = _distinct([(name, cons.project(z0)) for name, z0 in initial_profiles])
    if match or rate_goal:
        progress_bar = OptimisationProgress(show_progress, "misfit", lambda j: float(np.sqrt(max(j, 0.0))), True)
    else:
        progress_bar = OptimisationProgress(show_progress, "efficiency", lambda j: -j, False)
    runs: list[Run] = []
    labels: list[str] = []

    def local(lv: Levels, u0: np.ndarray, v_start: float, iters: int, label: str) -> Run:
        run = minimise(ev, cons, lv, u0, v_start, max_iterations=iters, tolerance=search.tolerance,
                       improvement=search.improvement, progress=progress_bar, label=label)
        runs.append(run)
        labels.append(label)
        return run

    if not rate_goal and (not match or location is None):   # observed by simulate_batch: screen a pool first
        ranked = screen_pool(system, dt, run_steps, obj, candidate_pool(named, cons, size=search.pool), v0,
                             limits.smoothness, z_ref)
        # the recursive method's striker (or prefix) stays first: it is the theory's guess, often in the basin
        # of the best optimum even when its value is not the lowest; the best diverse candidates follow
        # (for the efficiency the uniform piston stays first: the design then never ends below it)
        warm = [(name, z) for name, z in named if name.startswith("recursive") or name == "uniform"]
        profiles = diverse(warm + [(name, z) for name, z in zip(ranked.names, ranked.impedance)
                                   if not any(np.allclose(z, w, rtol=1e-12, atol=0.0) for _, w in warm)],
                           search.starts)
        diag["screened"] = {"candidates": len(ranked.names), "best_values": ranked.values[:search.starts].tolist()}
    else:
        profiles = named[:search.starts]
    diag["starts"] = [name for name, _ in profiles]
    # each start: continuation from a coarse profile (few levels) to the free one, a short run per stage; then
    # the best CONTINUED go on (the tail of the convergence is slow and alike for all starts)
    screen = (min(max(SCREEN_MIN, search.max_iterations // SCREEN_FRACTION), search.max_iterations)
              if len(profiles) > 1 else search.max_iterations)
    stages = coarse_levels(n) if len(profiles) > 1 else []
    ends: list[Run] = []
    for s_i, (_, z0) in enumerate(profiles):
        z_stage = z0
        for k in stages:
            try:
                lv = Levels.stepped(cons, _even_breaks(n, k))
            except ValueError:          # per-element bounds that no level of k can meet: skip this stage
                continue
            u0 = lv.project(np.add.reduceat(z_stage, lv.starts) / lv.counts, cons)
            z_stage = lv.expand(local(lv, u0, v0, screen, f"start {s_i + 1}, {k} levels").levels)
        ends.append(local(free, cons.project(z_stage), v0, screen, f"start {s_i + 1}, free profile"))
    best = best_of(ends)
    finals = list(ends)
    if search.max_iterations > screen:
        # a start that leads after its stages is not always the one that ends best; a start whose run has
        # converged already is not continued
        ranked_runs = sorted(range(len(ends)), key=lambda i: ends[i].value if np.isfinite(ends[i].value) else np.inf)
        more = []
        for i in ranked_runs[:CONTINUED]:
            if ends[i].message.startswith("STOP"):
                r = local(free, ends[i].levels, ends[i].velocity, search.max_iterations,
                          f"start {i + 1}, continued")
                more.append(r)
                finals[i] = r if r.value <= ends[i].value else ends[i]
        best = best_of([best, *more])
    # basin hopping from the best optimum: a perturbed copy (a smooth random factor on Z, or the elements from a
    # random cut to the end set to their thin bound) runs for the screening iterations; if it ends better, it
    # continues and becomes the best
    rng = np.random.default_rng(HOP_SEED)
    x_el = (np.arange(n) + 0.5) / n
    modes = np.arange(1, 6)
    shapes = np.cos(np.pi * modes[:, None] * x_el[None, :])
    for h in range(search.hops if len(profiles) > 1 else 0):
        z_best = free.expand(best.levels)
        if h % 2 == 0:
            z_try = z_best * np.exp(HOP_AMPLITUDE * (rng.normal(0.0, 1.0, modes.size) / modes) @ shapes)
        else:
            cut = int(rng.integers(n // 2, n)) if n > 1 else 0
            z_try = z_best.copy()
            z_try[cut:] = cons.lower[cut:]
        r = local(free, cons.project(z_try), best.velocity, screen, f"basin hop {h + 1}")
        if r.value < best.value and r.message.startswith("STOP"):
            r = local(free, r.levels, r.velocity, search.max_iterations, f"basin hop {h + 1}, continued")
        finals.append(r)
        if r.value < best.value:
            best = r
    diag["run_labels"] = labels
    shown = [progress_bar.show(r.value) for r in finals if np.isfinite(r.value)]
    diag["local_optima"] = {"name": progress_bar.name, "values": sorted(shown, reverse=not (match or rate_goal))}
    iterations = sum(r.iterations for r in runs)
    z, v, fw = free.expand(best.levels), best.velocity, best.fw
    diag["optimizer_message"] = best.message
    diag["mass_violation_before_projection"] = best.mass_violation
    if limits.max_steps is not None:
        free_value = best.value
        st = stepped_design(ev, cons, z, v, limits.max_steps, max_iterations=search.max_iterations,
                            tolerance=search.tolerance)
        runs.append(st.run)
        labels.append(f"stepped striker, {limits.max_steps} steps at most")
        iterations += st.run.iterations
        z, v, fw = st.impedance, st.run.velocity, st.run.fw
        diag["free_profile"] = {"impedance": best.levels.copy(), "velocity": best.velocity,
                                ("misfit" if match or rate_goal else "efficiency"):
                                    float(np.sqrt(free_value)) if match or rate_goal else -free_value}
        diag["breakpoints"] = st.breaks.tolist()
    return finish(z, v, fw, iterations, runs)




def _as_objective(target: Any) -> Union[MatchObjective, EfficiencyObjective, StrainRateObjective]:
    """The objective of a design: ``target`` itself when it is one, else a :class:`MatchObjective` of the force
    history ``target`` at the impact face."""
    if isinstance(target, (MatchObjective, EfficiencyObjective, StrainRateObjective)):
        return target
    if target is None:
        raise ValueError("target: give the force history to match, a ri.MatchObjective(target, position=...) or a "
                         "ri.EfficiencyObjective()")
    return MatchObjective(target)


def _instance(name: str, value: Any, cls: type) -> Any:
    """``value`` after checking it is a ``cls``."""
    if not isinstance(value, cls):
        raise TypeError(f"{name}: must be a {cls.__name__} (ri.{cls.__name__}(...)) or None, got "
                        f"{type(value).__name__}")
    return value


def _distinct(profiles: list[tuple[str, np.ndarray]]) -> list[tuple[str, np.ndarray]]:
    """Drop starting profiles equal to an earlier one (e.g. a one-element recursive prefix extended and clipped
    is the uniform striker of the first force level)."""
    out: list[tuple[str, np.ndarray]] = []
    for name, z in profiles:
        if not any(np.allclose(z, o, rtol=1e-12, atol=0.0) for _, o in out):
            out.append((name, z))
    return out


#: element counts scanned for the best uniform piston of the same mass (all up to this many, else log-spaced)
UNIFORM_SCAN = 200


def uniform_reference(system: Any, dt: float, mass: float, v: float, cons: Constraints, n: int,
                      goal: EfficiencyObjective, arrival: int) -> dict[str, Any]:
    """The best uniform piston of mass ``mass`` (kg) among 1..n elements of travel time dt: element count m,
    impedance Z = mass / (m dt) (inside the extreme impedance bounds), and its efficiency by the same definition
    (run length for m elements; first pass only where m fits), each simulated by :func:`rodimpact.simulate`.
    Returns {"elements", "impedance", "efficiency", "length_m" (steel-independent: travel time m dt),
    "by_elements": {m: efficiency}}; "elements" None when no count is admissible."""
    from ..direct.simulate import simulate
    from ..inverse.struck import with_striker
    from ..rods.rod import Rod

    lo, hi = float(np.min(cons.lower)), float(np.max(cons.upper))
    counts = np.arange(1, n + 1) if n <= UNIFORM_SCAN else np.unique(np.geomspace(1, n, UNIFORM_SCAN).round())
    by: dict[int, float] = {}
    n_struck = build_lattice(system, dt).n_elements
    for m in counts.astype(int):
        z = mass / (m * dt)
        if not lo * (1 - 1e-12) <= z <= hi * (1 + 1e-12):
            continue
        if goal.reloading:
            k = goal.run_steps(m, n_struck, dt)
        elif m <= arrival:
            k = 3 * arrival
        else:
            continue
        sim = simulate(with_striker(system, Rod.from_impedance(np.full(m, z), dt), v), steps=k, dt=dt)
        work = -dt * float(np.dot(sim.end_force["right"], sim.end_velocity["right"]))
        by[int(m)] = work / (0.5 * mass * v * v)
    if not by:
        return {"elements": None, "impedance": None, "efficiency": None, "by_elements": by}
    m_best = max(by, key=lambda m: by[m])
    return {"elements": m_best, "impedance": mass / (m_best * dt), "efficiency": by[m_best],
            "travel_time_s": m_best * dt, "by_elements": by}


def _design_lengths(n: Any, limits: StrikerLimits, wall0: float,
                    design_with: Callable[[int], DesignResult]) -> DesignResult:
    """Efficiency design over a range ``n = (n_lo, n_hi)`` of element counts (the piston's length varies, its
    mass as given): the best uniform piston of the same mass is found over the range first; full designs
    (``design_with(m)`` for m elements) run at its count and at the two neighbouring counts inside the range and
    at n_hi; the best is returned, with ``diagnostics["lengths"]`` = {count: efficiency} of every count designed."""
    if (len(n) != 2 or any(isinstance(x, bool) or not isinstance(x, (int, np.integer)) for x in n)
            or not 1 <= n[0] <= n[1]):
        raise ValueError(f"n: give a number of elements or, for the efficiency objective, a range (lo, hi) of "
                         f"integers with 1 <= lo <= hi; got {n!r}")
    lo_n, hi_n = int(n[0]), int(n[1])
    if limits.mass is None or isinstance(limits.mass, tuple):
        raise ValueError("StrikerLimits.mass: a range of element counts n = (lo, hi) needs a prescribed striker mass "
                         "(kg): the pistons of different lengths are compared at the same mass")
    for key in ("impedance_bounds", "diameter_bounds"):
        b = getattr(limits, key)
        if b is not None and any(isinstance(x, tuple) for x in b):
            raise ValueError(f"StrikerLimits.{key}: with a range of element counts give one (lower, upper) pair for "
                             f"all elements, not one per element")
    results: dict[int, DesignResult] = {}

    def run(m: int) -> DesignResult:
        if m not in results:
            results[m] = design_with(m)
        return results[m]

    first = run(hi_n)
    ref = first.diagnostics["uniform_reference"]
    counts = {hi_n}
    if ref["elements"] is not None:
        m0 = int(ref["elements"])
        counts |= {m for m in (m0 - 1, m0, m0 + 1) if lo_n <= m <= hi_n}
    for m in sorted(counts):
        run(m)
    best = max(results.values(), key=lambda r: r.efficiency)
    diag = dict(best.diagnostics)
    diag["lengths"] = {m: r.efficiency for m, r in sorted(results.items())}
    diag["uniform_reference"] = ref
    return dataclasses.replace(best, diagnostics=diag, wall_time=_time.perf_counter() - wall0,
                               iterations=sum(r.iterations for r in results.values()))


def _first_pass_steps(n: int, arrival: int) -> int:
    """Steps of the first-pass efficiency run: 3 ``arrival`` (the wavefront reaches the bit after ``arrival``
    steps; the wave it reflects there is back at the impact face after 2 arrival and, reflected there, at the
    bit after 3 arrival). The striker's pulse of 2 n steps must arrive at the bit before that."""
    if 2 * n > 2 * arrival:
        raise ValueError(f"EfficiencyObjective.reloading: the first pass cannot be separated from the reloading "
                         f"here: the striker's pulse (2 n = {2 * n} steps) outlasts the round trip through the "
                         f"struck system ({2 * arrival} steps), so reflected waves return while it still arrives; "
                         f"use reloading=True, fewer elements or a longer struck system")
    return 3 * arrival


def _stderr_is_a_terminal() -> bool:
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):       # replaced or closed stderr
        return False


def _impedance_for_force(level: float, face_z: float, v: float, c: Constraints) -> float:
    """Uniform striker impedance Z whose contact force Z Z~ v / (Z + Z~) has magnitude ``level`` (clipped into
    the bounds; the upper bound when no striker is strong enough)."""
    if level <= 0.0:
        return float(np.min(c.lower))
    if face_z * v <= level:
        return float(np.max(c.upper))
    return float(np.clip(level * face_z / (face_z * v - level), np.min(c.lower), np.max(c.upper)))


def _warm_start(goal: MatchObjective, system: Any, v: float, n: int, nw: int, dt: float, backend: str,
                cons: Constraints, diag: dict[str, Any]) -> Optional[np.ndarray]:
    """Run the recursive method on the same problem (the target, position, quantity and rule of ``goal``). Return
    its striker when all n elements exist inside the bounds and the mass range; otherwise record the diagnosis and
    put its feasible prefix, clipped and extended with its last value, into ``diag['recursive_prefix']``."""
    m_win = min(n, nw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            res = synthesize(goal.target, system, v, m_win, dt, position=goal.position, quantity=goal.quantity,
                             rule=goal.rule, backend=backend)
        except ValueError as exc:
            diag["warm_start"] = f"the recursive method cannot start: {exc}"
            return None
    if res.failure is not None:
        diag["existence"] = res.failure.message
    z = res.impedance
    if res.feasible and nw == n:
        z_ok = bool(np.all(z >= cons.lower) and np.all(z <= cons.upper))
        m = cons.mass_of(z)
        m_ok = cons.mass is None or cons.mass[0] <= m <= cons.mass[1]
        if z_ok and m_ok:
            return z.copy()
        diag["warm_start"] = ("the recursive method's striker exists but violates "
                              + ("the impedance bounds" if not z_ok else f"the mass ({m:.6g} kg)")
                              + "; started from it, projected onto the constraints")
        diag["recursive_prefix"] = cons.project(z) if z.size == n else None
        return None
    if z.size == 0:
        diag.setdefault("warm_start", "the recursive method gives no element; started from uniform strikers")
        return None
    diag.setdefault("warm_start", f"the recursive method gives {z.size} of {n} elements; started from that prefix "
                                  "(clipped, extended with its last value) and from uniform strikers")
    ext = np.concatenate([z, np.full(n - z.size, z[-1])]) if z.size < n else z[:n]
    diag["recursive_prefix"] = cons.project(ext)
    return None
