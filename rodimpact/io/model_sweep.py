"""Sweeps over the keys of a model file (``rodimpact sweep``): every combination of the grid values, one table.

:func:`sweep_model` loads the model once per grid point with the point's values as overrides
(:mod:`rodimpact.io.overrides`), so that a bad key or value is an error naming the key path before anything runs,
then runs :func:`rodimpact.sweep` (batched when only the striker and its velocity change). The summary quantities
are :data:`rodimpact.direct.sweep.DEFAULT_METRICS` at the first contact (rod 0 | rod 1), with
:data:`~rodimpact.direct.sweep.ROCK_METRICS` for a model with a bit-rock end; probes and snapshots are
not recorded. :func:`write_files` writes the table (``sweep.csv``, ``sweep.nc``; the command line's folder adds the
plot and ``summary.json``: :mod:`rodimpact.output_folders`); :func:`format_sweep` gives the table as text.
"""

from __future__ import annotations

import csv
import itertools
import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence

from ..direct.sweep import METRIC_DISPLAY
from ..rods.conditions import BitRockEnd
from . import _toml
from .model import Model, load_model
from .overrides import parse_assignment, parse_value
from .preflight import check_run, run_size
from .quantities import ModelError
from .storage import save

#: How the table shows each summary quantity: label, unit and factor from the SI value (as the sweep plots do).
COLUMNS: dict[str, tuple[str, str, float]] = METRIC_DISPLAY


def split_values(text: str) -> list[str]:
    """``v1,v2,...`` split at the commas that are not inside quotes, brackets or braces."""
    items, depth, quote, start = [], 0, "", 0
    for i, ch in enumerate(text):
        if quote:
            quote = "" if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            items.append(text[start:i].strip())
            start = i + 1
    items.append(text[start:].strip())
    return items


def parse_grid(options: Sequence[str]) -> dict[str, list[Any]]:
    """``--grid KEY=V1,V2,...`` options -> key path -> values (TOML values or plain text, as ``--set`` takes)."""
    grid: dict[str, list[Any]] = {}
    for option in options:
        key, text = parse_assignment(option, "--grid")
        if key in grid:
            raise ValueError(f"--grid {key}: given twice; list all its values in one --grid {key}=V1,V2,...")
        values = split_values(text)
        if "" in values:
            raise ValueError(f"--grid {key}: an empty value in {text!r}; give values separated by commas, e.g. "
                             f"--grid {key}=4,5,6")
        grid[key] = [parse_value(v) for v in values]
    return grid


@dataclass(frozen=True)
class _Point:
    """One grid point for :func:`rodimpact.sweep`: the model's run with the command's element-update limit."""

    model: Model
    max_element_updates: Optional[float]

    def simulate(self, progress: Optional[bool] = None):
        return self.model.simulate(progress=progress, max_element_updates=self.max_element_updates)

    @property
    def problem(self):
        """The point's :class:`~rodimpact.direct.problem.Problem` (what a batched sweep groups points by)."""
        return self.model.problem

    @property
    def backend(self) -> str:
        return self.model.backend


def sweep_model(path: str | Path, grid: Mapping[str, Sequence[Any]], overrides: Optional[Mapping[str, Any]] = None,
                *, workers: Optional[int] = None, progress: Optional[bool] = None,
                max_element_updates: Optional[float] = None):
    """Run the model file ``path`` at every combination of the ``grid`` values (key path -> values) with
    ``overrides`` (key path -> value) set at every point; returns the :class:`xarray.Dataset` of
    :func:`rodimpact.sweep` whose dimensions are the key paths, with the values as given (text for values that
    are not numbers or strings, e.g. ``true``). ``progress``: ``None`` reports progress on stderr for sweeps of
    more than :data:`~rodimpact.direct.guards.PROGRESS_UPDATES` element updates in all."""
    from ..direct.guards import PROGRESS_UPDATES
    from ..direct.sweep import drilling_metrics, sweep

    overrides = dict(overrides or {})
    keys, labels = _grid(grid, overrides)
    check_model_grid_size([len(labels[k]) for k in keys], "grid")
    points = {index: _point_model(path, {**overrides, **{k: grid[k][i] for k, i in zip(keys, index)}},
                                  max_element_updates)
              for index in itertools.product(*(range(len(labels[k])) for k in keys))}
    if progress is None and sum(math.prod(run_size(p.model)) for p in points.values()) > PROGRESS_UPDATES:
        progress = True

    def build(**point: Any) -> _Point:
        return points[tuple(labels[k].index(point[k]) for k in keys)]

    # a model with a bit-rock end reports what a drilling engineer wants: energy into the rock, efficiency and
    # penetration per blow (with the default quantities)
    system = next(iter(points.values())).model.system
    drilling = any(isinstance(end, BitRockEnd) for end in (system.left, system.right))
    ds = sweep(build, labels, drilling_metrics() if drilling else None, workers=workers, progress=progress)
    for key in keys:            # plain numbers are SI in a model file: their unit is the key's
        if ds[key].dtype.kind in "fiu" and not ds[key].attrs.get("units"):
            unit = key_unit(key)
            if unit:
                ds[key].attrs["units"] = unit
    return ds


def key_unit(key: str) -> str:
    """The SI unit of the quantity at model-file key path ``key`` (``"m/s"`` for ``rods.piston.velocity``,
    ``"1"`` for a pure number), from the schema; ``""`` when the key holds no quantity or is not known."""
    from .overrides import parse_key
    from .quantities import DIMENSIONS
    from .schema import MODEL

    try:
        steps = parse_key(key)
    except ModelError:
        return ""
    tables = [MODEL]
    i = 0
    while i < len(steps):
        step = steps[i]
        if not isinstance(step, str):
            return ""
        fields = []
        for table in tables:
            try:
                fields.append(table.field(step))
            except KeyError:
                pass
        if not fields:
            return ""
        i += 1
        if i == len(steps):
            dims = {f.dimension for f in fields if f.kind == "quantity" and f.dimension}
            if len(dims) != 1:
                return ""
            si = DIMENSIONS[dims.pop()].si
            return "1" if si == "-" else si
        if any(f.kind in ("tables", "mapping") for f in fields):
            i += 1                          # the entry: an index or a name
        tables = []
        for f in fields:
            if f.table is not None:
                tables.append(f.table)
            elif f.variants is not None:
                tables.extend(f.variants.options.values())
    return ""


#: Most points of one model-file sweep: every point is loaded and checked before the first run (about 10 ms and
#: :data:`MODEL_BYTES_PER_POINT` bytes each), so 100,000 points already take a quarter of an hour to prepare.
MAX_MODEL_SWEEP_POINTS = 100_000
#: Memory held per point of a model-file sweep before it runs (the loaded model), bytes; a generous estimate.
MODEL_BYTES_PER_POINT = 50_000


def check_model_grid_size(sizes: Sequence[int], name: str = "--grid") -> int:
    """The number of points of a model-file sweep with ``sizes`` values per key, after checking it is at most
    :data:`MAX_MODEL_SWEEP_POINTS` and fits in memory; the :class:`ModelError` names ``name`` and the limit."""
    from ..direct.sweep import check_grid_size

    try:
        return check_grid_size(sizes, name, MAX_MODEL_SWEEP_POINTS, MODEL_BYTES_PER_POINT)
    except ValueError as exc:
        raise ModelError(str(exc)) from None


def _grid(grid: Mapping[str, Sequence[Any]], overrides: Mapping[str, Any]) -> tuple[list[str], dict[str, list]]:
    """The grid keys and each key's values as coordinate labels; errors name the key."""
    if not grid:
        raise ModelError("grid: give at least one key and its values, e.g. --grid rods[0].velocity=4,5,6")
    labels: dict[str, list] = {}
    for key, values in grid.items():
        if key in overrides:
            raise ModelError(f"{key}: both swept and set; give it either as a grid key or as an override")
        if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) or not values:
            raise ModelError(f"{key}: give a non-empty list of values to sweep, got {values!r}")
        labels[key] = [_label(v) for v in values]
        if len(set(map(str, labels[key]))) != len(values):
            raise ModelError(f"{key}: the values {labels[key]} repeat; give each value once")
    return list(labels), labels


def _label(value: Any) -> Any:
    """A grid value as a coordinate: numbers and strings as they are, anything else as text (TOML where it can)."""
    if isinstance(value, (int, float, str)) and not isinstance(value, bool):
        return value
    return _toml.value(value) if isinstance(value, (bool, list, dict)) else str(value)


#: What a sweep does not record, left out before the model is validated (a probe beyond the end of a shortened
#: rod is no error in a sweep).
_UNRECORDED = {"probes": [], "output.snapshot_times": []}


def _point_model(path: str | Path, overrides: Mapping[str, Any], max_element_updates: Optional[float]) -> _Point:
    """The model at one grid point, without probes and snapshots (the sweep reports the first contact only),
    checked before any point runs."""
    model = load_model(path, {**_UNRECORDED, **overrides})
    if model.system.n_rods < 2:
        raise ModelError("rods: a sweep reports the first contact (rods[0] | rods[1]); the model has one rod")
    check_run(model, None, (), max_element_updates)
    output = replace(model.output, snapshot_every=None, snapshot_count=None)
    return _Point(replace(model, output=output), max_element_updates)


# ============================================================================================ table
def table_rows(ds: Any) -> list[dict[str, Any]]:
    """One dict per grid point (in grid order): the key paths with their values, then the summary quantities in
    SI units (``None`` where a quantity does not exist, e.g. the energy transfer of a striker at rest)."""
    keys, names = _axes(ds)
    rows = []
    for index in itertools.product(*(range(ds.sizes[k]) for k in keys)):
        at = dict(zip(keys, index))
        row = {k: ds[k].values[i].item() for k, i in at.items()}
        for name in names:
            value = float(ds[name].isel(at).values)
            row[name] = value if math.isfinite(value) else None
        rows.append(row)
    return rows


def format_sweep(ds: Any, title: str = "") -> str:
    """The table of a sweep as aligned text (kN, ms, %, m/s); ``n/a`` where a quantity does not exist."""
    keys, names = _axes(ds)
    header = [_key_header(ds, k) for k in keys] + [f"{COLUMNS[n][0]} [{COLUMNS[n][1]}]" if n in COLUMNS else n
                                                   for n in names]
    body = [[_key_shown(row[k]) for k in keys] + [_shown(n, row[n]) for n in names] for row in table_rows(ds)]
    widths = [max(len(r[c]) for r in [header] + body) for c in range(len(header))]
    lines = [title] if title else []
    lines += ["  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip() for r in [header] + body]
    return "\n".join(lines)


def _key_header(ds: Any, key: str) -> str:
    """A grid key as a column header, with the unit of its values when they were given with one."""
    unit = ds[key].attrs.get("units", "")
    return f"{key} [{unit}]" if unit else key


def _key_shown(value: Any) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def _axes(ds: Any) -> tuple[list[str], list[str]]:
    """The grid keys (in grid order) and the names of the summary quantities of a sweep dataset."""
    names = list(ds.data_vars)
    return list(ds[names[0]].dims), names


def _shown(name: str, value: Optional[float]) -> str:
    if value is None:
        return "n/a"
    return f"{value * COLUMNS[name][2]:.4g}" if name in COLUMNS else f"{value:.6g}"


def summary(ds: Any, model: str | Path, overrides: Mapping[str, Any]) -> dict[str, Any]:
    """The sweep as JSON-ready data: the model, overrides, grid, how it ran and the table rows (SI units)."""
    return {"model": str(model), "overrides": dict(overrides),
            "grid": {k: ds[k].values.tolist() for k in _axes(ds)[0]},
            "grid_units": {k: ds[k].attrs.get("units", "") for k in _axes(ds)[0]},
            "units": {n: ds[n].attrs.get("units", "") for n in ds.data_vars},
            "points": int(ds.attrs["points"]), "runner": ds.attrs["runner"], "wall_time_s": ds.attrs["wall_time_s"],
            "rows": table_rows(ds)}


def write_files(ds: Any, data: Mapping[str, Any], folder: Path) -> list[str]:
    """Write the table of a sweep into the (new) ``folder`` and return the file names: ``sweep.csv`` (one row per
    point: the key paths, then the quantities with their units in the header; ``data`` is :func:`summary`) and
    ``sweep.nc`` (the dataset, :func:`rodimpact.io.storage.save`). The command line's output folder adds
    ``sweep.png`` and ``summary.json`` (:func:`rodimpact.output_folders.write_sweep`)."""
    _write_table(folder / "sweep.csv", ds, data["rows"])
    save(ds, folder / "sweep.nc")
    return ["sweep.csv", "sweep.nc"]


def _write_table(path: Path, ds: Any, rows: Sequence[Mapping[str, Any]]) -> None:
    keys, names = _axes(ds)
    header = [_key_header(ds, k) for k in keys] + [f"{n} [{ds[n].attrs.get('units') or '-'}]" for n in names]
    with open(path, "w", encoding="utf-8", newline="") as fh:
        writer = csv.writer(fh, lineterminator="\n")
        writer.writerow(header)
        for row in rows:
            writer.writerow([row[k] for k in keys] + ["" if row[n] is None else repr(row[n]) for n in names])
