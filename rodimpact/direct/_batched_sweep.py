"""How :func:`rodimpact.sweep` runs a grid that varies only the striker and its velocity: batches of
:func:`~rodimpact.direct.batch.simulate_batch` designs instead of one :func:`~rodimpact.simulate` run per point.

A grid qualifies when every point's ``build`` result is a :class:`~rodimpact.direct.problem.Problem` (or a dict of
its keywords, :mod:`rodimpact.direct._sweep_keywords`, or a model that holds one) without probes or snapshots, and
the systems agree in everything but rod 0 and its velocity (the same struck rods, velocities of rods 1, 2, ...,
junctions, end conditions, loads, initial states, time step, number of steps and energy stride; objects compared
with ``==``) and the metrics are default metrics. The points are grouped by the striker's element count; each
group is one batch. The metrics equal those of the per-run path bit for bit (the batch reproduces ``simulate``'s
arithmetic).
"""

from __future__ import annotations

from typing import Any, Callable, Iterable, Mapping, Optional, Sequence

import numpy as np

from ..lattice.discretize import discretize_rod
from ..rods.system import System
from .batch import BatchResult, run_designs, slot_problem
from ._sweep_keywords import problem_of
from .problem import Problem
from .result import ROCK_QUANTITIES, rock_value

#: largest relative travel-time error of a striker that is batched (simulate reports larger ones per point)
_TOLERANCE = 0.01

_KEYS = {"rods", "velocities", "duration", "dt", "steps", "elements", "resolution", "left", "right", "junctions",
         "loads", "initial", "energy_every", "record_every", "backend", "progress", "probes", "snapshot_times",
         "snapshot_every", "outputs"}


def batch_metric(name: str, res: BatchResult) -> np.ndarray:
    """The default sweep metric ``name`` of every design of ``res`` (as :data:`rodimpact.direct.sweep.DEFAULT_METRICS`
    computes it from a :class:`~rodimpact.SimulationResult`)."""
    if name == "peak_contact_force":
        return res.peak_force[:, 0]
    if name == "contact_time":
        return res.contact_steps[:, 0] * res.dt
    if name == "energy_transfer":
        return res.efficiency
    if name in ROCK_QUANTITIES:             # rock_energy, drilling_efficiency, penetration_per_blow
        quantity = ROCK_QUANTITIES[name][0]
        return np.array([rock_value(res.bit_rock(d), quantity) for d in range(res.n_designs)])
    return res.rigid_body_velocity          # striker_final_velocity


def _point(spec: Any) -> tuple[System, float, int] | str:
    """(system, dt, steps) of one point: a :class:`~rodimpact.direct.problem.Problem`, a dict of keywords
    (:mod:`rodimpact.direct._sweep_keywords`) or an object that holds a problem as ``problem`` (a
    :class:`~rodimpact.io.model.Model`, with its ``backend``); or why it cannot be batched."""
    if isinstance(spec, Mapping):
        unknown = set(spec) - _KEYS
        if unknown:
            return f"keywords {sorted(unknown)} are not batched"
        if spec.get("probes") or spec.get("snapshot_times") is not None or spec.get("snapshot_every") is not None:
            return "probes and snapshots are not recorded by simulate_batch"
        try:
            problem, options = problem_of(spec)
        except Exception as exc:       # the per-run path reports it, naming the point
            return f"{type(exc).__name__}: {exc}"
        backend = options.get("backend", "numba")
    else:
        problem = spec if isinstance(spec, Problem) else getattr(spec, "problem", None)
        if not isinstance(problem, Problem):
            return f"build returns a {type(spec).__name__}, not a Problem or a dict of its keywords"
        backend = getattr(spec, "backend", "numba")
    out = problem.outputs
    if out.probes or out.snapshot_times is not None or out.snapshot_every is not None:
        return "probes and snapshots are not recorded by simulate_batch"
    if backend != "numba":
        return "backend='numpy' runs the reference path"
    return problem.system, problem.time.dt, problem.time.steps


def _same_struck(a: tuple, b: tuple) -> bool:
    sa, sb = a[0], b[0]
    return (a[1:] == b[1:] and sa.rods[1:] == sb.rods[1:] and sa.velocities[1:] == sb.velocities[1:]
            and sa.junctions == sb.junctions and sa.left == sb.left and sa.right == sb.right
            and sa.loads == sb.loads and sa.initial[1:] == sb.initial[1:])


Group = tuple[System, float, int, int, list[int], np.ndarray, np.ndarray, np.ndarray]


def _key(rod: Any) -> Any:
    """A hashable stand-in for equal rods (``None`` if the rod's parts cannot be hashed)."""
    native = rod.native
    key = (rod.segments, rod.material, None if native is None else
           (native.impedance.tobytes(), native.dt, native.wave_speed))
    try:
        hash(key)
    except TypeError:
        return None
    return key


def plan(specs: Iterable[Any], label: Callable[[int], str]) -> tuple[list[Group], str]:
    """Group the points into batches: per group (system of point 0, dt, steps, energy stride, point indices,
    striker impedances, last element lengths, striker velocities). Returns ``([], reason)`` if the grid cannot
    be batched, naming the point by ``label(index)``."""
    points = []
    for i, spec in enumerate(specs):
        p = _point(spec)
        if isinstance(p, str):
            return [], f"at {label(i)}: {p}"
        if i and not _same_struck(points[0], p):
            return [], (f"at {label(i)}: the struck system (rods 1, 2, ..., their velocities, junctions, ends, loads, "
                        f"initial states), time step, number of steps or energy stride differs from {label(0)}")
        points.append(p)
    problem = slot_problem(points[0][0])
    if problem:
        return [], problem
    system, dt, n_steps = points[0]
    groups: dict[int, list[tuple[int, Any]]] = {}
    seen: dict[Any, Any] = {}          # striker -> discretisation, for grids that repeat a striker
    for i, p in enumerate(points):
        key = _key(p[0].rods[0])
        try:
            disc = seen[key] if key in seen else discretize_rod(p[0].rods[0], dt, 0)
        except Exception as exc:
            return [], f"at {label(i)}: {type(exc).__name__}: {exc}"
        if key is not None:
            seen[key] = disc
        if not disc.exact and abs(disc.time_scale - 1.0) > _TOLERANCE:
            return [], (f"at {label(i)}: the striker's travel time is represented with a "
                        f"{abs(disc.time_scale - 1.0):.2%} error at dt = {dt:.6g} s (simulate reports it)")
        groups.setdefault(disc.n_elements, []).append((i, disc, p[0].velocities[0]))
    out = []
    for members in groups.values():
        out.append((system, dt, n_steps, [m[0] for m in members], np.array([m[1].impedance for m in members]),
                    np.array([m[1].length[-1] for m in members]), np.array([m[2] for m in members])))
    return out, ""


def run(groups: list[Group], names: Sequence[str], threads: int, executor: Any,
        chunk_size: Optional[int]) -> dict[str, np.ndarray]:
    """The metrics ``names`` of every point (flat, in point order) from one batch per group."""
    n = sum(len(g[4]) for g in groups)
    out = {name: np.full(n, np.nan) for name in names}
    for system, dt, n_steps, idx, zs, tail, vel in groups:
        res = run_designs(system, zs, tail, vel, dt, n_steps, n_steps, False, False, 1, threads, executor,
                          chunk_size)
        for name in names:
            out[name][idx] = batch_metric(name, res)
    return out

