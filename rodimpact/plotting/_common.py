"""Helpers shared by the plotting functions: figures without pyplot (headless-safe), units, rod geometry."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np


def new_axes(ax: Any = None, *, nrows: int = 1, ncols: int = 1, figsize=(7.0, 4.0), sharex: bool = False):
    """Return ``(figure, axes)``: the given Axes' figure, or a new :class:`matplotlib.figure.Figure`.

    New figures are not registered with pyplot, so the functions work on any backend, in threads and
    without a display (save them with ``fig.savefig``; Jupyter shows a returned figure).
    """
    if ax is not None:
        return ax.figure, ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    axes = fig.subplots(nrows, ncols, sharex=sharex)
    return fig, axes


def rod_label(result_or_system: Any, i: int) -> str:
    """The rod's name or ``rod i``."""
    system = getattr(result_or_system, "system", result_or_system)
    if system is not None:
        name = system.rods[i].name
        if name:
            return name
    return f"rod {i}"


def junction_positions(result: Any) -> np.ndarray:
    """Reference x of the contact faces (left end of rods 1..n-1), m."""
    lat = result.lattice
    return np.array([lat.node_x[lat.node_index(r, 0)] for r in range(1, lat.n_rods)])


def time_scale(t_max: float) -> tuple[float, str]:
    """A factor and unit label for time axes (ms below 1 s, else s)."""
    return (1e3, "ms") if t_max < 1.0 else (1.0, "s")


def nearest_snapshots(times: np.ndarray, wanted: Optional[np.ndarray]) -> list[int]:
    """Indices of the recorded snapshots nearest to ``wanted`` times (default: 3 spread over the run)."""
    if times.size == 0:
        raise ValueError("snapshots: the result holds no field snapshots; record some with snapshot_times= or "
                         "snapshot_every= ([output] in a model file)")
    if wanted is None or len(wanted) == 0:
        picks = np.quantile(times, [0.2, 0.5, 0.8]) if times.size >= 3 else times
        wanted = np.asarray(picks)
    idx = [int(np.argmin(np.abs(times - t))) for t in np.atleast_1d(wanted)]
    return list(dict.fromkeys(idx))
