"""Striker design when the exact inverse fails: :func:`design`.

The recursive method (:func:`rodimpact.synthesize`) is exact but stops where the existence condition (thesis
eq. 4.20) fails, which it does for every force that starts at 0 N. :func:`design` instead minimises an objective
over the n element impedances (and optionally the impact velocity) under bounds, a mass and manufacturability
limits, with exact gradients from the adjoint of the lattice (:mod:`rodimpact.design._adjoint`, docs/adjoint.md)
and scipy's L-BFGS-B (:mod:`rodimpact.design.optimize`). The method is described in docs/design.md.
"""

from __future__ import annotations

import time as _time
import warnings
from typing import Any, Optional, Sequence

import numpy as np

from .. import __version__
from .._validate import non_negative
from ..lattice.lattice import build_lattice
from ..rods.conditions import BitRockEnd
from ..rods.material import STEEL, Material
from ..rods.system import InitialState
from ..inverse.diagnosis import explain_bounds
from ..inverse.recursive import synthesize
from ..inverse.struck import as_struck_system, locate, window_count_check
from ..inverse.targets import as_target
from ..inverse.transform import _check_quantity, _resolve_dt, _resolve_n
from ._adjoint import ImpactProblem
from .constraints import Constraints, build_constraints, velocity_start
from .objectives import EfficiencyObjective, MatchObjective
from .optimize import Evaluator, Levels, Run, best_of, minimise
from .result import DesignResult
from .screening import candidate_pool, screen as screen_pool
from .stepped import stepped_design

OBJECTIVES = ("match", "efficiency")
#: default run length of the efficiency objective: the striker's pulse (2 n steps) plus this many round trips
#: through the struck system, so that the reflected waves can come back and load the rock again
EFFICIENCY_ROUND_TRIPS = 3
#: misfit below which the recursive method's striker is returned as the exact answer
EXACT_MISFIT = 1e-9
#: several starts: each runs for max(SCREEN_MIN, max_iterations // SCREEN_FRACTION) iterations, then the best
#: CONTINUED of them continue up to max_iterations
SCREEN_MIN, SCREEN_FRACTION, CONTINUED = 10, 10, 2


def design(target: Any = None, struck: Any = None, striker_velocity: Optional[float] = None,
           n: Optional[int] = None, dt: Optional[float] = None, *, objective: str = "match",
           far_end: Any = "free", struck_velocity: Any = 0.0, junctions: Optional[Sequence[Any]] = None,
           loads: Sequence[Any] = (), initial: Optional[Sequence[Optional[InitialState]]] = None,
           position: Optional[float] = None, quantity: str = "force", rule: str = "midpoint",
           weights: Any = None, impedance_bounds: Any = None, diameter_bounds: Any = None,
           material: Material = STEEL, bore: float = 0.0, mass: Any = None, velocity_bounds: Any = None,
           max_steps: Optional[int] = None, smoothness: float = 0.0, steps: Optional[int] = None,
           duration: Optional[float] = None, starts: int = 3, max_iterations: int = 300,
           tolerance: float = 1e-14, warm_start: bool = True, backend: str = "numba") -> DesignResult:
    """Find the striker impedance profile that minimises an objective under constraints.

    Parameters
    ----------
    target:
        ``objective="match"``: the wished force (N, tension positive, impact forces negative) in any form
        :func:`rodimpact.synthesize` accepts (callable f(t), samples (t, F), window values, ForceTarget). Its
        window values X_j (``rule``) held for 2 dt are compared with the achieved force at every step over the
        target's span (n windows for a function without duration); at a ``position``, at the window starts after
        the dead time (see :mod:`rodimpact.design.objectives`). ``objective="efficiency"``: None.
    struck, far_end, struck_velocity, junctions, loads, initial:
        The struck system, as for :func:`rodimpact.synthesize` (left end = impact face).
    striker_velocity:
        Impact velocity, m/s (> 0); the start value when ``velocity_bounds`` is given.
    n, dt:
        Number of striker elements (default: as many as the target's windows) and their travel time, s.
    objective:
        ``"match"`` (relative L2 misfit, default) or ``"efficiency"`` (work done on the rock per blow divided by
        the striker's kinetic energy m v^2 / 2; needs a :class:`~rodimpact.BitRockEnd` far end).
    position, quantity:
        Observe the ``"force"`` or the ``"incident"`` force wave at this distance (m) from the impact face inside
        the struck system; time then counts from the wavefront's arrival (dead time).
    weights:
        Optional weights of the misfit: w(t), one per window or one per step.
    impedance_bounds, diameter_bounds, material, bore:
        Bounds (lower, upper) of the element impedances (N s/m; numbers or one per element) or of the outer
        diameters (m) of a striker of ``material`` with a central ``bore`` (m). Default: 1/100..100 times the
        struck face impedance.
    mass:
        Striker mass (kg), or a range (lo, hi); the mass is dt sum Z_q.
    velocity_bounds:
        (lo, hi) m/s: optimise the impact velocity too.
    max_steps:
        Return a stepped striker with at most this many constant-impedance steps (see :mod:`.stepped`).
    smoothness:
        Weight of a smoothed total-variation penalty sum |Z_{q+1} - Z_q| / Z_ref (0: none).
    steps, duration:
        Length of the efficiency run (default: the pulse 2 n dt plus ``EFFICIENCY_ROUND_TRIPS`` round trips
        through the struck system).
    starts, max_iterations, tolerance:
        Number of starting profiles (each screened for max(10, max_iterations / 10) iterations, the best two
        continued), L-BFGS-B iterations per stage, and its relative ``ftol``. Where the objective is observed
        at the impact face or is the efficiency, the starts are the best of a pool of
        :data:`~rodimpact.design.screening.POOL_SIZE` candidates simulated together by
        :func:`rodimpact.simulate_batch` (:mod:`rodimpact.design.screening`); otherwise the named starts.
    warm_start:
        Try the exact recursive method first (match only).
    backend:
        "numba" or "numpy" (forward and adjoint runs).
    """
    wall0 = _time.perf_counter()
    if objective not in OBJECTIVES:
        raise ValueError(f"objective: must be one of {OBJECTIVES}, got {objective!r}")
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    _check_quantity(quantity)
    if struck is None:
        raise ValueError("struck: give the struck system (a Rod, a list of Rods or a System)")
    if isinstance(starts, bool) or not isinstance(starts, (int, np.integer)) or starts < 1:
        raise ValueError(f"starts: must be an integer >= 1, got {starts!r}")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, (int, np.integer)) or max_iterations < 1:
        raise ValueError(f"max_iterations: must be an integer >= 1, got {max_iterations!r}")
    smoothness = _real("smoothness", smoothness, "a finite number >= 0 (weight of the total-variation penalty)",
                       lambda x: x >= 0.0)
    tolerance = _real("tolerance", tolerance, "a finite number with 0 < tolerance < 1 (L-BFGS-B's relative "
                      "reduction ftol of the objective per iteration)", lambda x: 0.0 < x < 1.0)
    non_negative("bore", bore, "m")
    if max_steps is not None and (isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer))
                                  or max_steps < 1):
        raise ValueError(f"max_steps: must be an integer >= 1 (number of constant-impedance steps), got {max_steps!r}")
    system = as_struck_system(struck, struck_velocity, far_end, junctions, loads, initial)
    dt = _resolve_dt(system, dt)
    lat = build_lattice(system, dt)
    face_z = float(lat.impedance[0])
    diag: dict[str, Any] = {"version": __version__, "backend": backend}

    if objective == "match":
        if target is None:
            raise ValueError("target: the 'match' objective needs a target force history")
        if steps is not None or duration is not None:
            raise ValueError("steps, duration: the 'match' run covers the target's span; give them only for "
                             "objective='efficiency'")
        tgt = as_target(target, rule)
        n = _resolve_n(tgt, n, dt)
        avail = tgt.available_windows(dt)
        nw = n if avail is None else avail
        windows = tgt.window_values(nw, dt)
        bad = np.flatnonzero(~np.isfinite(windows))
        if bad.size:
            j = int(bad[0])
            raise ValueError(f"target: window {j + 1} (from t = {2 * j} dt) is {windows[j]}; forces must be finite")
        if not np.any(windows != 0.0):
            raise ValueError("target: is zero in every window; nothing to match")
        location = None if position is None else locate(system, position, dt)
        obj: Any = MatchObjective.build(windows, None if location is None else location.node, weights, dt)
        run_steps = obj.steps
        obs_quantity = quantity if location is not None else "force"
    else:
        if target is not None:
            raise ValueError("target: the 'efficiency' objective takes no target; pass None")
        if not isinstance(system.right, BitRockEnd):
            raise ValueError(f"far_end: the 'efficiency' objective (work done on the rock / striker kinetic energy) "
                             f"needs a BitRockEnd far end, e.g. far_end=ri.BitRockEnd(k1, k2); got "
                             f"{type(system.right).__name__}")
        if n is None:
            raise ValueError("n: give the number of striker elements for the 'efficiency' objective")
        n = window_count_check(n)
        if position is not None:
            raise ValueError("position: the 'efficiency' objective observes the bit-rock interface; omit position")
        run_steps = _efficiency_steps(n, lat.n_elements, dt, steps, duration)
        location = locate(system, sum(r.length for r in system.rods), dt)
        obs_quantity = "incident"       # the incident wave at the bit, for the report and plots
        windows = np.zeros(0)
        obj = EfficiencyObjective(dt, run_steps)

    cons = build_constraints(n, dt, face_z, impedance_bounds=impedance_bounds, diameter_bounds=diameter_bounds,
                             material=material, bore=bore, mass=mass, striker_velocity=striker_velocity,
                             velocity_bounds=velocity_bounds)
    v0 = velocity_start(cons, striker_velocity)
    if objective == "match" and location is None and not any(system.velocities):
        diag["bounds_diagnosis"] = explain_bounds(windows, v0, face_z, float(cons.lower[0]), float(cons.upper[0]))
    problem = ImpactProblem(system, dt, n, run_steps, location=location, quantity=obs_quantity, backend=backend)
    z_ref = float(np.exp(np.mean(np.log(np.sqrt(cons.lower * cons.upper)))))
    ev = Evaluator(problem, obj, float(smoothness), z_ref)

    def finish(z: np.ndarray, v: float, fw: Any, iterations: int, runs: list[Run]) -> DesignResult:
        diag.update(bounds=(cons.lower, cons.upper), forward_runs=ev.forward_runs, gradient_runs=ev.gradient_runs,
                    convergence=[r.history for r in runs], start_values=[r.value for r in runs])
        if objective == "match":
            diag["weights"] = obj.weights
        value = obj.evaluate(fw, z, v)[0]
        return DesignResult(
            impedance=z, striker_velocity=float(v), dt=dt, objective=objective, time=dt * np.arange(run_steps),
            achieved=np.asarray(fw.observed, dtype=float), face_force=np.asarray(fw.face_force, dtype=float),
            target=obj.reference if objective == "match" else np.zeros(0),
            compared=obj.index if objective == "match" else np.zeros(0, dtype=int),
            window_values=windows, misfit=float(np.sqrt(value)) if objective == "match" else None,
            efficiency=-value if objective == "efficiency" else None,
            constraint_report=cons.report(z, v), iterations=iterations, wall_time=_time.perf_counter() - wall0,
            struck=system, location=location if (position is not None or objective == "efficiency") else None,
            quantity=obs_quantity, material=material, diagnostics=diag)

    initial_profiles: list[tuple[str, np.ndarray]] = []
    if objective == "match":
        exact = _warm_start(target, system, v0, n, nw, dt, position, quantity, rule, backend, cons, diag) \
            if warm_start else None
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
    else:
        zu = np.full(n, face_z)
        initial_profiles += [("uniform", zu), ("rising taper", np.linspace(0.5, 2.0, n) * face_z),
                             ("falling taper", np.linspace(2.0, 0.5, n) * face_z)]
    free = Levels.free(cons)
    named = _distinct([(name, cons.project(z0)) for name, z0 in initial_profiles])
    if objective == "efficiency" or location is None:     # observed by simulate_batch: screen a pool first
        ranked = screen_pool(system, dt, run_steps, obj, candidate_pool(named, cons), v0, float(smoothness), z_ref)
        # the recursive method's striker (or prefix) stays first: it is the theory's guess, often in the basin
        # of the best optimum even when its value is not the lowest; the best screened candidates follow
        warm = [(name, z) for name, z in named if name.startswith("recursive")]
        profiles = _distinct(warm + list(zip(ranked.names, ranked.impedance)))[:starts]
        diag["screened"] = {"candidates": len(ranked.names), "best_values": ranked.values[:starts].tolist()}
    else:
        profiles = named[:starts]
    diag["starts"] = [name for name, _ in profiles]
    # screen every start briefly, then continue the best two (the tail of the convergence is slow and alike)
    screen = max(SCREEN_MIN, max_iterations // SCREEN_FRACTION) if len(profiles) > 1 else max_iterations
    runs = [minimise(ev, cons, free, z0, v0, max_iterations=min(screen, max_iterations), tolerance=tolerance)
            for _, z0 in profiles]
    best = best_of(runs)
    if max_iterations > screen:
        # the best CONTINUED starts go on (a start that leads after the screen is not always the one that
        # ends best); a start that has converged already is not continued
        ranked = sorted(runs, key=lambda r: r.value if np.isfinite(r.value) else np.inf)[:CONTINUED]
        more = [minimise(ev, cons, free, r.levels, r.velocity, max_iterations=max_iterations - screen,
                         tolerance=tolerance) for r in ranked if r.message.startswith("STOP")]
        runs += more
        best = best_of([best, *more])
    iterations = sum(r.iterations for r in runs)
    z, v, fw = free.expand(best.levels), best.velocity, best.fw
    diag["optimizer_message"] = best.message
    diag["mass_violation_before_projection"] = best.mass_violation
    if max_steps is not None:
        free_value = best.value
        st = stepped_design(ev, cons, z, v, max_steps, max_iterations=max_iterations, tolerance=tolerance)
        runs.append(st.run)
        iterations += st.run.iterations
        z, v, fw = st.impedance, st.run.velocity, st.run.fw
        diag["free_profile"] = {"impedance": best.levels.copy(), "velocity": best.velocity,
                                ("misfit" if objective == "match" else "efficiency"):
                                    float(np.sqrt(free_value)) if objective == "match" else -free_value}
        diag["breakpoints"] = st.breaks.tolist()
    return finish(z, v, fw, iterations, runs)


def _real(name: str, value: Any, valid: str, ok: Any) -> float:
    """``value`` as a float if it is a real number (int or float, not bool, no string or sequence coerced),
    finite and ``ok``; otherwise a TypeError (wrong type) or ValueError (wrong value) naming ``name`` and saying
    what is ``valid``."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: must be {valid}, got {type(value).__name__} {value!r}")
    x = float(value)
    if not (np.isfinite(x) and ok(x)):
        raise ValueError(f"{name}: must be {valid}, got {value!r}")
    return x


def _distinct(profiles: list[tuple[str, np.ndarray]]) -> list[tuple[str, np.ndarray]]:
    """Drop starting profiles equal to an earlier one (e.g. a one-element recursive prefix extended and clipped
    is the uniform striker of the first force level)."""
    out: list[tuple[str, np.ndarray]] = []
    for name, z in profiles:
        if not any(np.allclose(z, o, rtol=1e-12, atol=0.0) for _, o in out):
            out.append((name, z))
    return out


def _efficiency_steps(n: int, n_struck: int, dt: float, steps: Optional[int], duration: Optional[float]) -> int:
    if steps is not None and duration is not None:
        raise ValueError("steps, duration: give one of them")
    if duration is not None:
        if not (isinstance(duration, (int, float)) and np.isfinite(duration) and duration > 0):
            raise ValueError(f"duration: must be a finite time > 0 s, got {duration!r}")
        steps = int(round(duration / dt))
    if steps is None:
        return 2 * n + 2 * EFFICIENCY_ROUND_TRIPS * n_struck
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ValueError(f"steps: must be an integer >= 1, got {steps!r}")
    return int(steps)


def _impedance_for_force(level: float, face_z: float, v: float, c: Constraints) -> float:
    """Uniform striker impedance Z whose contact force Z Z~ v / (Z + Z~) has magnitude ``level`` (clipped into
    the bounds; the upper bound when no striker is strong enough)."""
    if level <= 0.0:
        return float(np.min(c.lower))
    if face_z * v <= level:
        return float(np.max(c.upper))
    return float(np.clip(level * face_z / (face_z * v - level), np.min(c.lower), np.max(c.upper)))


def _warm_start(target: Any, system: Any, v: float, n: int, nw: int, dt: float, position: Optional[float],
                quantity: str, rule: str, backend: str, cons: Constraints, diag: dict[str, Any]) -> Optional[np.ndarray]:
    """Run the recursive method on the same problem. Return its striker when all n elements exist inside the
    bounds and the mass range; otherwise record the diagnosis and put its feasible prefix, clipped and extended
    with its last value, into ``diag['recursive_prefix']``."""
    m_win = min(n, nw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            res = synthesize(target, system, v, m_win, dt, position=position, quantity=quantity, rule=rule,
                             backend=backend)
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
