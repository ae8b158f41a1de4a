"""Parameter studies: one :func:`~rodimpact.simulate` run per point of a grid, in parallel threads.

The compiled kernel releases the GIL, so the runs of a sweep advance on several cores without copying systems
between processes (and ``build`` may be any function, also one defined in a notebook). Each run is exactly the
run :func:`~rodimpact.simulate` would do alone; the sweep only collects scalar metrics of every result into an
:class:`xarray.Dataset` whose dimensions are the grid parameters (``.to_netcdf()`` saves it).

A grid that changes only the striker (rod 0) and its velocity runs as batches of
:func:`~rodimpact.simulate_batch` designs instead (:mod:`rodimpact.direct._batched_sweep`), with the same
numbers; ``executor=`` sends batches of designs (or chunks of points) to a ``concurrent.futures`` executor or a
``dask.distributed`` client.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import re
import sys
import time as _time
from concurrent.futures import ThreadPoolExecutor, as_completed
from typing import Any, Callable, Mapping, Optional, Sequence

import numpy as np

from .._version import __version__
from ._sweep_keywords import problem_of
from .guards import Progress
from .problem import Problem
from .result import ROCK_QUANTITIES, SimulationResult, rock_value
from .simulate import simulate

Metric = Callable[[SimulationResult], float]


def _peak_contact_force(res: SimulationResult) -> float:
    return float(_first_junction(res).min_force)


def _contact_time(res: SimulationResult) -> float:
    _first_junction(res)
    return res.contact_duration(0)


def _energy_transfer(res: SimulationResult) -> float:
    e0 = res.energy.kinetic[0, 0] + res.energy.strain[0, 0]
    return res.efficiency if e0 > 0.0 else math.nan       # rod 0 at rest: no transfer to speak of


def _first_junction(res: SimulationResult):
    if not res.junction_events:
        raise ValueError("metrics: the default metrics need a junction (two or more rods); give metrics= for a "
                         "single rod, e.g. {'end_force': lambda r: r.end_force['right'].min()}")
    return res.junction_events[0]


#: :data:`ROCK_QUANTITIES` as metrics: ``sweep(build, grid, drilling_metrics())``; ``rodimpact sweep`` adds them
#: for a model with a bit-rock end. A batched sweep computes them too.
ROCK_METRICS: dict[str, tuple[Metric, str]] = {
    name: ((lambda r, q=q: rock_value(r.bit_rock, q)), unit) for name, (q, unit) in ROCK_QUANTITIES.items()}


#: Metrics of :func:`sweep` when none are given: name -> (function of the result, unit). Contact quantities are
#: those of junction 0 and are taken at every step, whatever the recording stride.
DEFAULT_METRICS: dict[str, tuple[Metric, str]] = {
    "peak_contact_force": (_peak_contact_force, "N"),
    "contact_time": (_contact_time, "s"),
    "energy_transfer": (_energy_transfer, "1"),
    "striker_final_velocity": (lambda r: float(r.rigid_body_velocity[0]), "m/s"),
}


#: every metric a batched sweep can compute, with its unit
KNOWN_METRICS: dict[str, tuple[Metric, str]] = {**DEFAULT_METRICS, **ROCK_METRICS}


#: How tables and plots show each known metric: label, unit and factor from the SI value.
METRIC_DISPLAY: dict[str, tuple[str, str, float]] = {
    "peak_contact_force": ("peak contact force", "kN", 1e-3),
    "contact_time": ("contact time", "ms", 1e3),
    "energy_transfer": ("energy transfer", "%", 100.0),
    "striker_final_velocity": ("striker final velocity", "m/s", 1.0),
    "rock_energy": ("energy into the rock", "J", 1.0),
    "drilling_efficiency": ("drilling efficiency", "%", 100.0),
    "penetration_per_blow": ("penetration per blow", "mm", 1e3),
}

#: Most points one :func:`sweep` runs. Every point costs bookkeeping before its run (its index, a task, one value
#: per metric: about :data:`BYTES_PER_POINT` bytes) and at least ~0.05 ms of simulation in a batch, ~1 ms alone:
#: a million points is already minutes to hours. Larger grids are refused before anything runs.
MAX_SWEEP_POINTS = 1_000_000
#: Memory per grid point of :func:`sweep` before its run (index tuple, task, metric values), bytes.
BYTES_PER_POINT = 1_000


def check_grid_size(sizes: Sequence[int], name: str = "grid", limit: int = MAX_SWEEP_POINTS,
                    bytes_per_point: float = BYTES_PER_POINT) -> int:
    """The number of points of a grid with ``sizes`` values per key, after checking it is at most ``limit`` and
    that their bookkeeping (``bytes_per_point`` each) fits in memory; the ``ValueError`` names ``name`` (``grid``
    in Python, ``--grid`` on the command line), the grid's size and the limit."""
    n = math.prod(int(k) for k in sizes)          # Python integers: no overflow for any grid
    shape = " x ".join(f"{int(k):,}" for k in sizes)
    if n > limit:
        raise ValueError(f"{name}: {shape} values make {n:,} points, more than the {limit:,} one sweep runs; "
                         "give fewer values per key, or split the sweep into several")
    from .._validate import fits_in_memory

    fits_in_memory(name, n * float(bytes_per_point), f"a sweep of {n:,} points ({shape})",
                   "give fewer values per key, or split the sweep into several")
    return n


_NUMBER_FIRST = re.compile(r"\s*[+-]?(?:\d|\.\d)")


def grid_coordinate(name: str, values: Sequence[Any]) -> tuple[np.ndarray, str]:
    """The coordinate of grid parameter ``name`` and its unit: numbers stay numbers; when every value is a number
    or a quantity string (``"6 m/s"``, ``"1.2 m"``: a number first, then a unit) of one dimension, the strings
    become their SI values and the unit is that dimension's SI unit (``""`` when no value names a unit, e.g. plain
    numbers, which model files take as SI). Other values (``"fixed"``, ``"true"``) stay text."""
    if not any(isinstance(v, str) for v in values):
        return np.asarray(values), ""
    if not all(not isinstance(v, str) or _NUMBER_FIRST.match(v) for v in values):
        return np.asarray(values), ""
    from .._quantities import DIMENSIONS, ModelError, pint_quantity, si_magnitude

    si: list[float] = []
    units: set[str] = set()
    for v in values:
        if not isinstance(v, str):
            si.append(float(v))
            continue
        try:
            q = pint_quantity(v, f"grid[{name!r}]")
        except ModelError:
            return np.asarray(values), ""
        dim = next((d for d in DIMENSIONS.values()
                    if (q.dimensionless if d.name == "dimensionless" else q.check(d.pint))), None)
        if dim is None:                     # a dimension no model key has: leave the text as it is
            return np.asarray(values), ""
        if str(q.units) != "dimensionless":             # "6 m/s", "30 %"; not a bare "3"
            units.add("1" if dim.name == "dimensionless" else dim.si)
        si.append(si_magnitude(q, dim.pint, v, f"grid[{name!r}]", f"a {dim.name}"))
    if len(units) > 1:                      # mixed dimensions: the run names the bad value
        return np.asarray(values), ""
    if len(set(si)) != len(si):
        raise ValueError(f"grid[{name!r}]: the values {list(values)!r} repeat once in SI units ({si!r}); give "
                         "each value once")
    return np.asarray(si, dtype=float), (units.pop() if units else "")


def drilling_metrics() -> dict[str, Metric]:
    """``metrics=`` for :func:`sweep` of a drilling system: :data:`DEFAULT_METRICS` and :data:`ROCK_METRICS`."""
    return {name: f for name, (f, _) in KNOWN_METRICS.items()}


def sweep(build: Callable[..., Any], grid: Mapping[str, Sequence[Any]],
          metrics: Optional[Mapping[str, Metric]] = None, *, workers: Optional[int] = None,
          progress: Optional[bool] = None, errors: str = "raise", batch: Optional[bool] = None,
          executor: Any = None, chunk_size: Optional[int] = None):
    """Simulate every combination of the ``grid`` values and collect scalar ``metrics`` of each result.

    Parameters
    ----------
    build:
        ``build(**point)`` for a grid point (e.g. ``build(length=0.2, velocity=5.0)``) returns the run: a
        :class:`~rodimpact.Problem`; or a dict of keywords, read by one rule
        (:mod:`rodimpact.direct._sweep_keywords`): ``rods`` (or a ``System``), ``velocities``, the ends,
        junctions, loads, initial state, the time (``duration`` or ``steps``; ``dt``, ``elements`` or
        ``resolution``) and ``allow_discretization_error`` go to :meth:`Problem.of <rodimpact.Problem.of>`;
        ``probes``, ``snapshot_times``, ``snapshot_every``, ``energy_every``, ``record_every`` make one
        :class:`~rodimpact.Outputs` (or give ``outputs``); ``backend``, ``progress`` and
        ``max_element_updates`` go to :func:`~rodimpact.simulate`; or an object with a ``simulate()`` method
        (a :class:`~rodimpact.io.model.Model`).
    grid:
        Parameter name -> 1-d sequence of values (numbers or strings); all combinations are run, at most
        :data:`MAX_SWEEP_POINTS` (a larger grid is refused before anything runs). Names are the keyword arguments
        of ``build``: identifiers, or any text without ``/`` (e.g. model-file key paths such as
        ``"rods[0].velocity"``) when ``build`` takes ``**point``. ``build`` gets the values as given.
    metrics:
        Name -> function of the :class:`~rodimpact.SimulationResult` returning one real number. Default
        :data:`DEFAULT_METRICS`: the peak (most compressive) contact force and the total contact time at
        junction 0, the energy transfer (:attr:`~rodimpact.SimulationResult.efficiency`; NaN when rod 0 starts
        without energy) and the striker's final rigid-body velocity.
    workers:
        Parallel threads (default: the number of CPUs, at most the number of points); for a batched sweep, the
        numba threads of :func:`~rodimpact.simulate_batch`.
    progress:
        Report progress over the points of a per-point sweep on stderr, a bar on a terminal, else a line at every
        10 % (default: a bar on a terminal for more than 10 points).
    errors:
        ``"raise"`` (default): the first failing point stops the sweep with an error naming it. ``"nan"``: a
        failing point gets NaN metrics and is listed (with its error) in the ``failures`` attribute (JSON).
    batch:
        ``None`` (default): when every point differs only in rod 0 (the striker) and its velocity, records no
        probes or snapshots, and the metrics are default metrics, run the points as batches of :func:`~rodimpact.simulate_batch` designs
        (same numbers, much faster); otherwise one :func:`~rodimpact.simulate` run per point. ``False``: always
        per point. ``True``: batch or raise a ValueError saying why the grid cannot be batched.
    executor:
        A ``concurrent.futures.Executor`` or a ``dask.distributed.Client`` to run on instead of in-process
        threads: batches of ``chunk_size`` designs (or points, for per-point runs) are sent as tasks. A process
        pool or cluster pickles ``build`` and the metrics (dask's cloudpickle also takes lambdas and notebook
        functions; ``ProcessPoolExecutor`` needs module-level functions).
    chunk_size:
        Designs (or points) per executor task; default about 32 tasks, 64-4096 designs each.

    Returns
    -------
    xarray.Dataset
        One variable per metric with the grid parameters as dimensions and coordinates (in grid order). A
        parameter whose values are numbers or quantity strings (``"6 m/s"``) has numbers as coordinate, in SI units
        with a ``units`` attribute when a value named one (and ``values_as_given``, JSON); other text stays text
        (:func:`grid_coordinate`). :func:`rodimpact.plotting.plot_sweep` draws every metric against every key.
    """
    import xarray as xr

    if not callable(build):
        raise TypeError(f"build: must be a function of the grid parameters, got {type(build).__name__}")
    names, values = _grid(grid)
    chosen, units = _metrics(metrics)
    clash = sorted(set(chosen) & set(names))
    if clash:
        raise ValueError(f"metrics: the names {clash} are also grid parameters; rename the metrics")
    if errors not in ("raise", "nan"):
        raise ValueError(f"errors: must be 'raise' or 'nan', got {errors!r}")
    shape = tuple(len(v) for v in values)
    check_grid_size(shape, "grid", bytes_per_point=BYTES_PER_POINT + 8 * len(chosen))
    coords = {}
    for n, v in zip(names, values):
        coordinate, unit = grid_coordinate(n, v)
        attrs = {"units": unit} if unit else {}
        if coordinate.dtype.kind != np.asarray(v).dtype.kind:
            attrs["values_as_given"] = json.dumps([str(x) for x in v])
        coords[n] = (n, coordinate, attrs)
    points = list(itertools.product(*(range(n) for n in shape)))
    if workers is None:
        workers = os.cpu_count() or 1
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers: must be an integer >= 1, got {workers!r}")
    if batch not in (None, True, False):
        raise ValueError(f"batch: must be None (automatic), True or False, got {batch!r}")
    failures: list[dict[str, Any]] = []
    wall0 = _time.perf_counter()
    out, reason = (None, "batch=False") if batch is False else _batched(
        build, names, values, points, shape, chosen, int(workers), executor, chunk_size, strict=bool(batch))
    if out is None and batch:
        raise ValueError(f"batch: this sweep cannot run as a batch of designs: {reason}")
    runner = "simulate_batch" if out is not None else "simulate"
    if out is None:
        out = {name: np.full(shape, np.nan) for name in chosen}
        bar = _progress_bar(progress, len(points))
        try:
            for done in _per_point(build, names, values, points, chosen, errors, int(workers), executor, chunk_size):
                for index, metrics_at, failure in done:
                    for name, value in metrics_at.items():
                        out[name][index] = value
                    if failure is not None:
                        failures.append(failure)
                if bar is not None:
                    bar.update(len(done))
        finally:
            if bar is not None:
                bar.close()
    data = {name: (names, out[name], {"units": units[name]} if units[name] else {}) for name in chosen}
    return xr.Dataset(data, coords=coords, attrs={
        "title": "rodimpact parameter sweep", "rodimpact_version": __version__, "points": len(points),
        "workers": int(min(workers, len(points))), "wall_time_s": _time.perf_counter() - wall0,
        "failures": json.dumps(failures, default=str), "runner": runner,
        "executor": "in-process" if executor is None else type(executor).__name__})


def _batched(build, names, values, points, shape, chosen, workers, executor, chunk_size, strict: bool):
    """The metrics as batches of simulate_batch designs, or ``(None, reason)`` when the grid does not qualify
    (see :mod:`rodimpact.direct._batched_sweep`)."""
    from . import _batched_sweep as BS

    if any(KNOWN_METRICS.get(name, (None,))[0] is not f for name, f in chosen.items()):
        return None, "metrics: only the default and drilling metrics are computed from a batch"
    # built lazily: planning stops at the first point that cannot be batched (the per-point path builds again)
    specs = (build(**{n: v[i] for n, v, i in zip(names, values, index)}) for index in points)
    try:
        groups, reason = BS.plan(specs, lambda i: _show({n: v[k] for n, v, k in zip(names, values, points[i])}))
    except Exception as exc:        # the per-point path reports it, naming the point
        return None, f"build: {type(exc).__name__}: {exc}"
    if not groups:
        return None, reason
    try:
        flat = BS.run(groups, list(chosen), workers, executor, chunk_size)
    except Exception as exc:
        if strict:
            raise
        return None, f"{type(exc).__name__}: {exc}"
    return {name: flat[name].reshape(shape) for name in chosen}, ""


def _run_points(build, names, values, indices, chosen, errors) -> list[tuple[tuple[int, ...], dict, Optional[dict]]]:
    """One simulate() run per grid point of ``indices``: (index, metrics, failure or None) each."""
    done = []
    for index in indices:
        point = {n: v[i] for n, v, i in zip(names, values, index)}
        try:
            result = _simulate(build(**point))
            done.append((index, {name: _scalar(name, f(result)) for name, f in chosen.items()}, None))
        except Exception as exc:
            message = f"sweep at {_show(point)}: {type(exc).__name__}: {exc}"
            if errors == "raise":
                raise ValueError(message) from exc
            done.append((index, {}, {"point": point, "error": message}))
    return done


def _per_point(build, names, values, points, chosen, errors, workers, executor, chunk_size):
    """Yield the finished lists of :func:`_run_points`: one point per task in threads of this process, or chunks
    of points as tasks of ``executor``."""
    from .batch import default_chunk_size, gather

    if executor is None:
        with ThreadPoolExecutor(max_workers=min(workers, len(points))) as pool:
            futures = [pool.submit(_run_points, build, names, values, [index], chosen, errors) for index in points]
            try:
                for fut in as_completed(futures):
                    yield fut.result()
            finally:
                for fut in futures:
                    fut.cancel()
        return
    size = default_chunk_size(len(points)) if chunk_size is None else chunk_size
    yield from gather(executor, _run_points, [(build, names, values, part, chosen, errors)
                                              for part in _chunks(points, size)])


def _chunks(items: list, size: Any) -> list[list]:
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 1:
        raise ValueError(f"chunk_size: must be an integer >= 1 (points per task), got {size!r}")
    return [items[a:a + int(size)] for a in range(0, len(items), int(size))]


def _grid(grid: Any) -> tuple[list[str], list[list[Any]]]:
    if not isinstance(grid, Mapping) or not grid:
        raise ValueError("grid: must be a non-empty mapping name -> list of values, e.g. "
                         "{'velocity': [4.0, 5.0, 6.0]}")
    names, values = [], []
    for name, vals in grid.items():
        if not isinstance(name, str) or not name or "/" in name:
            raise ValueError(f"grid: parameter names must be non-empty strings without '/' (keyword arguments of "
                             f"build), got {name!r}")
        if isinstance(vals, (str, bytes)) or np.ndim(vals) != 1 or len(vals) == 0:
            raise ValueError(f"grid[{name!r}]: must be a non-empty 1-d list of values, got {vals!r}")
        items = list(vals)
        for v in items:
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating, str)):
                raise TypeError(f"grid[{name!r}]: values must be numbers or strings, got {type(v).__name__} {v!r}")
            if not isinstance(v, str) and not math.isfinite(float(v)):
                raise ValueError(f"grid[{name!r}]: values must be finite, got {v!r}")
        if len(set(items)) != len(items):
            raise ValueError(f"grid[{name!r}]: values must not repeat, got {items!r}")
        names.append(name)
        values.append(items)
    return names, values


def _metrics(metrics: Any) -> tuple[dict[str, Metric], dict[str, str]]:
    if metrics is None:
        return ({k: f for k, (f, _) in DEFAULT_METRICS.items()}, {k: u for k, (_, u) in DEFAULT_METRICS.items()})
    if not isinstance(metrics, Mapping) or not metrics:
        raise ValueError("metrics: must be a non-empty mapping name -> function of the result")
    for name, f in metrics.items():
        if not isinstance(name, str) or not name or "/" in name:
            raise ValueError(f"metrics: names must be non-empty strings without '/' (NetCDF variable names), got "
                             f"{name!r}")
        if not callable(f):
            raise TypeError(f"metrics[{name!r}]: must be a function of the SimulationResult, got "
                            f"{type(f).__name__}")
    return dict(metrics), {name: KNOWN_METRICS[name][1] if KNOWN_METRICS.get(name, (None,))[0] is f else ""
                           for name, f in metrics.items()}


def _simulate(spec: Any) -> SimulationResult:
    if isinstance(spec, Problem):
        return simulate(spec, progress=False)
    if isinstance(spec, Mapping):
        problem, options = problem_of(spec)
        return simulate(problem, **{"progress": False, **options})
    if callable(getattr(spec, "simulate", None)):
        return spec.simulate(progress=False)
    raise TypeError(f"build: must return the keyword arguments of a run as a dict (rods, velocities, duration, ...: "
                    f"see rodimpact.sweep), a Problem, or a Model; got {type(spec).__name__}")


def _scalar(name: str, value: Any) -> float:
    if isinstance(value, bool) or np.ndim(value) != 0:
        raise ValueError(f"metrics[{name!r}]: must return one real number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f"metrics[{name!r}]: must return one real number, got {value!r}") from None


def _show(point: Mapping[str, Any]) -> str:
    return ", ".join(f"{k} = {v!r}" for k, v in point.items())


def _progress_bar(progress: Optional[bool], n: int):
    if progress is None:
        progress = sys.stderr.isatty() and n > 10
    return Progress(n, unit="run", desc="sweep") if progress else None
