"""Parameter studies: one :func:`~rodimpact.simulate` run per point of a grid, in parallel threads.

The compiled kernel releases the GIL, so the runs of a sweep advance on several cores without copying systems
between processes (and ``build`` may be any function, also one defined in a notebook). Each run is exactly the
run :func:`~rodimpact.simulate` would do alone; the sweep only collects scalar metrics of every result into an
:class:`xarray.Dataset` whose dimensions are the grid parameters (``.to_netcdf()`` saves it).
"""

from __future__ import annotations

import itertools
import json
import math
import os
import sys
import time as _time
from concurrent.futures import ThreadPoolExecutor, as_completed
from typing import Any, Callable, Mapping, Optional, Sequence

import numpy as np

from .. import __version__
from .result import SimulationResult
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


#: Metrics of :func:`sweep` when none are given: name -> (function of the result, unit). Contact quantities are
#: those of junction 0 and are taken at every step, whatever the recording stride.
DEFAULT_METRICS: dict[str, tuple[Metric, str]] = {
    "peak_contact_force": (_peak_contact_force, "N"),
    "contact_time": (_contact_time, "s"),
    "energy_transfer": (_energy_transfer, "1"),
    "striker_final_velocity": (lambda r: float(r.rigid_body_velocity[0]), "m/s"),
}


def sweep(build: Callable[..., Any], grid: Mapping[str, Sequence[Any]],
          metrics: Optional[Mapping[str, Metric]] = None, *, workers: Optional[int] = None,
          progress: Optional[bool] = None, errors: str = "raise"):
    """Simulate every combination of the ``grid`` values and collect scalar ``metrics`` of each result.

    Parameters
    ----------
    build:
        ``build(**point)`` for a grid point (e.g. ``build(length=0.2, velocity=5.0)``) returns the keyword
        arguments of :func:`~rodimpact.simulate` as a dict, or an object with a ``simulate()`` method (a
        :class:`~rodimpact.io.model.Model`).
    grid:
        Parameter name -> 1-d sequence of values (numbers or strings); all combinations are run.
    metrics:
        Name -> function of the :class:`~rodimpact.SimulationResult` returning one real number. Default
        :data:`DEFAULT_METRICS`: the peak (most compressive) contact force and the total contact time at
        junction 0, the energy transfer (:attr:`~rodimpact.SimulationResult.efficiency`; NaN when rod 0 starts
        without energy) and the striker's final rigid-body velocity.
    workers:
        Parallel threads (default: the number of CPUs, at most the number of points).
    progress:
        Show a progress bar over the points (default: on a terminal for more than 10 points).
    errors:
        ``"raise"`` (default): the first failing point stops the sweep with an error naming it. ``"nan"``: a
        failing point gets NaN metrics and is listed (with its error) in the ``failures`` attribute (JSON).

    Returns
    -------
    xarray.Dataset
        One variable per metric with the grid parameters as dimensions and coordinates (in grid order).
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
    points = list(itertools.product(*(range(n) for n in shape)))
    if workers is None:
        workers = os.cpu_count() or 1
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers: must be an integer >= 1, got {workers!r}")
    out = {name: np.full(shape, np.nan) for name in chosen}
    failures: list[dict[str, Any]] = []
    wall0 = _time.perf_counter()

    def run(index: tuple[int, ...]) -> dict[str, float]:
        point = {n: v[i] for n, v, i in zip(names, values, index)}
        try:
            result = _simulate(build(**point))
            return {name: _scalar(name, f(result)) for name, f in chosen.items()}
        except Exception as exc:
            message = f"sweep at {_show(point)}: {type(exc).__name__}: {exc}"
            if errors == "raise":
                raise ValueError(message) from exc
            failures.append({"point": point, "error": message})
            return {}

    bar = _progress_bar(progress, len(points))
    with ThreadPoolExecutor(max_workers=min(int(workers), len(points))) as pool:
        futures = {pool.submit(run, index): index for index in points}
        try:
            for fut in as_completed(futures):
                for name, value in fut.result().items():
                    out[name][futures[fut]] = value
                if bar is not None:
                    bar.update(1)
        except BaseException:
            for fut in futures:
                fut.cancel()
            raise
        finally:
            if bar is not None:
                bar.close()
    coords = {n: (n, np.asarray(v)) for n, v in zip(names, values)}
    data = {name: (names, out[name], {"units": units[name]} if units[name] else {}) for name in chosen}
    return xr.Dataset(data, coords=coords, attrs={
        "title": "rodimpact parameter sweep", "rodimpact_version": __version__, "points": len(points),
        "workers": int(min(workers, len(points))), "wall_time_s": _time.perf_counter() - wall0,
        "failures": json.dumps(failures, default=str)})


def _grid(grid: Any) -> tuple[list[str], list[list[Any]]]:
    if not isinstance(grid, Mapping) or not grid:
        raise ValueError("grid: must be a non-empty mapping name -> list of values, e.g. "
                         "{'velocity': [4.0, 5.0, 6.0]}")
    names, values = [], []
    for name, vals in grid.items():
        if not isinstance(name, str) or not name.isidentifier():
            raise ValueError(f"grid: parameter names must be identifiers (keyword arguments of build), got {name!r}")
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
    return dict(metrics), {name: DEFAULT_METRICS[name][1] if name in DEFAULT_METRICS else "" for name in metrics}


def _simulate(spec: Any) -> SimulationResult:
    if isinstance(spec, Mapping):
        return simulate(**{"progress": False, **spec})
    if callable(getattr(spec, "simulate", None)):
        return spec.simulate(progress=False)
    raise TypeError(f"build: must return the keyword arguments of rodimpact.simulate as a dict, or a Model; got "
                    f"{type(spec).__name__}")


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
    if not progress:
        return None
    from tqdm.auto import tqdm
    return tqdm(total=n, unit="run", desc="sweep")
