"""Plots of a parameter sweep (the :class:`xarray.Dataset` of :func:`rodimpact.sweep`, or ``sweep.nc`` of
``rodimpact sweep``): every metric against every grid key, one panel each."""

from __future__ import annotations

import itertools
import json
from typing import Any, Optional, Sequence

import numpy as np

from ._common import new_axes

#: At most this many curves per panel get a legend entry; more are drawn thin and grey, without one.
MAX_LABELLED_CURVES = 8


def _check_sweep(ds: Any) -> tuple[list[str], list[str]]:
    """The grid keys and metric names of a sweep dataset, or a TypeError/ValueError saying what is expected."""
    import xarray as xr

    if not isinstance(ds, xr.Dataset):
        raise TypeError(f"ds: must be the xarray.Dataset of rodimpact.sweep (or xarray.open_dataset('sweep.nc')), "
                        f"got {type(ds).__name__}")
    names = list(ds.data_vars)
    if not names:
        raise ValueError("ds: the dataset holds no metrics; pass the dataset rodimpact.sweep returned")
    keys = list(ds[names[0]].dims)
    if not keys or any(list(ds[n].dims) != keys for n in names):
        dims = {n: list(ds[n].dims) for n in names}
        raise ValueError(f"ds: every metric must lie on the grid keys {keys}; got {dims}")
    return keys, names


def _key_axis(ds: Any, key: str) -> tuple[np.ndarray, str, Optional[list[str]]]:
    """Positions of the values of grid key ``key``, the axis label, and tick labels for text values.

    Numbers are drawn at their values (SI, ``units`` attribute); text values that are quantities (``"6 m/s"``, as
    ``sweep.nc`` files written before rodimpact stored numbers) are read as SI numbers; other text values
    (``"fixed"``) are drawn at 0, 1, 2, ... and labelled."""
    from ..direct.sweep import grid_coordinate

    values = ds[key].values
    unit = ds[key].attrs.get("units", "")
    if values.dtype.kind in "USO":
        numbers, unit_read = grid_coordinate(key, [str(v) for v in values])
        if numbers.dtype.kind in "fiu":
            values, unit = numbers, unit or unit_read
        else:
            return np.arange(values.size, dtype=float), key, [str(v) for v in values]
    label = f"{key} [{unit}]" if unit else key
    return np.asarray(values, dtype=float), label, None


def _metric_axis(ds: Any, name: str) -> tuple[float, str]:
    """Factor from the stored value and the axis label of metric ``name`` (kN, ms, % as in the sweep table)."""
    from ..direct.sweep import METRIC_DISPLAY

    if name in METRIC_DISPLAY:
        label, unit, factor = METRIC_DISPLAY[name]
        return factor, f"{label} [{unit}]"
    unit = ds[name].attrs.get("units", "")
    return 1.0, f"{name} [{unit}]" if unit else name


def plot_sweep(ds: Any, axes: Any = None, *, metrics: Optional[Sequence[str]] = None,
               keys: Optional[Sequence[str]] = None):
    """Every metric of a sweep against every grid key: one panel per (metric, key), metrics in rows and keys in
    columns. In a panel the metric is drawn against the key's values, one curve per combination of the other
    keys' values (labelled when there are at most :data:`MAX_LABELLED_CURVES`, else thin grey lines); points
    whose metric does not exist (NaN, e.g. the energy transfer of a striker at rest) are left out.

    ``ds``: the :class:`xarray.Dataset` of :func:`rodimpact.sweep` or an opened ``sweep.nc`` (also one written
    before grid values were stored as numbers). ``metrics``, ``keys``: names to draw (default all). ``axes``:
    as many Axes as panels (rows x columns) or ``None`` for a new figure. Draws on several Axes, so it returns
    the Figure.
    """
    all_keys, all_names = _check_sweep(ds)
    names = _subset("metrics", metrics, all_names)
    keys_ = _subset("keys", keys, all_keys)
    rows, cols = len(names), len(keys_)
    legend_axes: list[Any] = []
    varied = [k for k in all_keys if ds.sizes[k] > 1]
    if axes is None and (len(varied) < 2 or (len(varied) == 2 and keys is not None and len(keys_) == 1
                                             and keys_[0] not in varied)):
        fig, grid = new_axes(None, nrows=rows, ncols=cols, figsize=(4.2 * cols + 1.0, 2.6 * rows + 0.6))
        flat = np.ravel(np.asarray(grid, dtype=object))
    elif axes is None:
        # a first row of empty panels holds each column's legend, so that no legend covers a curve
        from matplotlib.figure import Figure

        fig = Figure(figsize=(4.2 * cols + 1.0, 2.6 * rows + 1.6), layout="constrained")
        grid = fig.subplots(rows + 1, cols, squeeze=False, height_ratios=[0.45] + [1.0] * rows)
        legend_axes = list(grid[0])
        for ax in legend_axes:
            ax.axis("off")
        flat = np.ravel(np.asarray(grid[1:], dtype=object))
    else:
        flat = np.ravel(np.asarray(axes, dtype=object))
        if flat.size != rows * cols or not all(hasattr(a, "plot") for a in flat):
            raise ValueError(f"axes: need {rows * cols} Axes ({rows} metric(s) x {cols} key(s)) or None, got "
                             f"{flat.size} object(s)")
        fig = flat[0].figure
    for c, key in enumerate(keys_):
        x, xlabel, ticks = _key_axis(ds, key)
        # curves: one per combination of the other keys that have more than one value
        others = [k for k in all_keys if k != key and ds.sizes[k] > 1]
        fixed = {k: 0 for k in all_keys if k != key and ds.sizes[k] == 1}
        combos = list(itertools.product(*(range(ds.sizes[k]) for k in others)))
        colour_key = None if len(combos) <= MAX_LABELLED_CURVES else next(
            (k for k in others if ds.sizes[k] <= MAX_LABELLED_CURVES), None)
        for r, name in enumerate(names):
            factor, ylabel = _metric_axis(ds, name)
            ax = flat[r * cols + c]
            seen: set[str] = set()
            for n_curve, combo in enumerate(combos):
                at = {**fixed, **dict(zip(others, combo))}
                y = ds[name].isel(at).transpose(key).values * factor if at else ds[name].values * factor
                if len(combos) <= MAX_LABELLED_CURVES:
                    style = dict(color=f"C{n_curve % 10}", marker="o", ms=3, lw=1.3)
                    label = ", ".join(_shown(ds, k, i) for k, i in zip(others, combo)) or None
                elif colour_key is not None:
                    i = combo[others.index(colour_key)]
                    style = dict(color=f"C{i % 10}", marker="o", ms=2, lw=0.7, alpha=0.8)
                    label = _shown(ds, colour_key, i)
                else:
                    style = dict(color="0.55", lw=0.6, marker="o", ms=1.5)
                    label = None
                if label in seen:
                    label = None
                seen.add(label)
                ok = np.isfinite(y)
                ax.plot(x[ok], y[ok], label=label, **style, **({"ls": ":"} if ticks is not None else {}))
            if ticks is not None:
                ax.set_xticks(x, ticks)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.grid(True, lw=0.4, color="0.85")
            if r == 0:
                handles, labels = ax.get_legend_handles_labels()
                if handles:
                    title = (", ".join(others) if colour_key is None
                             else f"{colour_key} ({len(combos)} curves: all values of the other keys)")
                    where = dict(loc="center", fontsize="x-small", title_fontsize="x-small", title=title,
                                 ncol=min(len(handles), 4 if len(labels[0]) < 20 else 2), frameon=False)
                    (legend_axes[c] if legend_axes else ax).legend(handles, labels, **where)
                elif len(combos) > 1:
                    ax.set_title(f"{len(combos)} curves, one per value of the other keys", fontsize="small")
    fig.suptitle(f"Parameter sweep: {ds.attrs.get('points', int(np.prod([ds.sizes[k] for k in all_keys])))} "
                 f"runs, each metric against each grid key")
    return fig


def _subset(what: str, chosen: Optional[Sequence[str]], available: list[str]) -> list[str]:
    if chosen is None:
        return available
    names = [chosen] if isinstance(chosen, str) else list(chosen)
    unknown = [n for n in names if n not in available]
    if unknown or not names:
        raise ValueError(f"{what}: {unknown[0] if unknown else 'none'!r} is not in the sweep; "
                         f"available: {', '.join(available)}")
    return names


def _shown(ds: Any, key: str, i: int) -> str:
    """Value ``i`` of grid key ``key`` for a legend: as the user gave it where known, else the stored value."""
    given = ds[key].attrs.get("values_as_given")
    if given:
        try:
            return str(json.loads(given)[i])
        except (ValueError, IndexError, TypeError):
            pass
    v = ds[key].values[i]
    unit = ds[key].attrs.get("units", "")
    text = f"{v:.4g}" if isinstance(v, (float, np.floating)) else str(v)
    return f"{text} {unit}" if unit and unit != "1" else text
