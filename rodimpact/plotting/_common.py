"""Helpers shared by the plotting functions: figures without pyplot (headless-safe), units, rod geometry, and the
checks of their arguments (clear messages instead of errors from deep inside matplotlib)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional

import numpy as np

from .._validate import fits_in_memory, positive

#: matplotlib's Agg renderer draws at most this many pixels per side.
MAX_PIXELS_PER_SIDE = 2**23


def check_result(result: Any, name: str = "result"):
    """``result`` itself if it is a :class:`~rodimpact.SimulationResult`, else a ``TypeError`` naming ``name``."""
    from ..direct.result import SimulationResult

    if not isinstance(result, SimulationResult):
        raise TypeError(f"{name}: must be a SimulationResult (from rodimpact.simulate or rodimpact.io.load), "
                        f"got {type(result).__name__}")
    return result


def check_int(name: str, value: Any, minimum: int, maximum: Optional[int] = None) -> int:
    """``value`` as an int after checking it is an integer in ``[minimum, maximum]``."""
    limits = f">= {minimum}" if maximum is None else f"from {minimum} to {maximum}"
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name}: must be an integer {limits}, got {type(value).__name__} {value!r}")
    if value < minimum or (maximum is not None and value > maximum):
        raise ValueError(f"{name}: must be an integer {limits}, got {value!r}")
    return int(value)


def check_dpi(dpi: Any) -> float:
    """``dpi`` as a float after checking it is a finite number > 0."""
    return positive("dpi", dpi, "dots per inch")


def check_figure_pixels(fig: Any, dpi: float, what: str) -> None:
    """Raise ``ValueError`` naming ``dpi`` if ``fig`` at ``dpi`` would be an empty image, too large for matplotlib,
    or too large for this machine's memory."""
    w, h = (float(v) * dpi for v in fig.get_size_inches())
    if min(w, h) < 1.0:
        raise ValueError(f"dpi: {dpi:g} makes the {what} {w:.3g} x {h:.3g} pixels, less than one pixel; "
                         "use e.g. dpi=120")
    if max(w, h) >= MAX_PIXELS_PER_SIDE:
        raise ValueError(f"dpi: {dpi:g} makes the {what} {w:.0f} x {h:.0f} pixels; matplotlib draws fewer than "
                         f"{MAX_PIXELS_PER_SIDE} per side")
    fits_in_memory("dpi", 8.0 * w * h, f"drawing the {what} at {dpi:g} dpi ({w:.0f} x {h:.0f} pixels)",
                   "use a smaller dpi, e.g. 120 to 300")


def check_output_folder(folder: Path, name: str = "folder") -> None:
    """Raise ``ValueError`` if ``folder`` or one of its parents exists as a file (so it cannot be a folder)."""
    for p in (folder, *folder.parents):
        if p.exists():
            if not p.is_dir():
                what = "is" if p == folder else f"(a parent of {str(folder)!r}) is"
                raise ValueError(f"{name}: {str(p)!r} {what} a file, not a folder")
            return


def check_output_file(path: Path, name: str = "path") -> None:
    """Raise ``ValueError`` if ``path`` is a folder or lies below a file."""
    if path.is_dir():
        raise ValueError(f"{name}: {str(path)!r} is a folder, not a file")
    check_output_folder(path.parent, name)


def new_axes(ax: Any = None, *, nrows: int = 1, ncols: int = 1, figsize=(7.0, 4.0), sharex: bool = False):
    """Return ``(figure, axes)``: the given Axes' figure, or a new :class:`matplotlib.figure.Figure`.

    New figures are not registered with pyplot, so the functions work on any backend, in threads and
    without a display (save them with ``fig.savefig``; Jupyter shows a returned figure).
    """
    if ax is not None:
        if not hasattr(ax, "figure") or not hasattr(ax, "plot"):
            raise TypeError(f"ax: must be a matplotlib Axes (or None for a new figure), got {type(ax).__name__}")
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


def format_length(x: float) -> str:
    """A length (m) as a reader writes it: in mm below 1 m (``"822 mm"``, ``"3.2 mm"``), in m from 1 m on
    (``"19.9 m"``, ``"2.5 m"``), with up to four significant digits and no exponent for lengths of rods."""
    x = float(x)
    if abs(x) < 1.0:
        return f"{x * 1e3:.4g} mm"
    text = f"{x:.4g}"
    return f"{x:.0f} m" if "e" in text else f"{text} m"


def time_scale(t_max: float) -> tuple[float, str]:
    """A factor and unit label for time axes (ms below 1 s, else s)."""
    return (1e3, "ms") if t_max < 1.0 else (1.0, "s")


def check_snapshot_times(recorded: np.ndarray, wanted: Any, dt: float, name: str = "times") -> np.ndarray:
    """``wanted`` as a 1-d float array after checking every time is finite and lies within the recorded snapshot
    times (to one lattice step ``dt``): the nearest snapshot of a time outside would be a different instant."""
    try:
        t = np.atleast_1d(np.asarray(wanted, dtype=float))
    except (TypeError, ValueError):
        raise TypeError(f"{name}: must be a sequence of times in s, got {wanted!r}") from None
    if t.ndim != 1:
        raise ValueError(f"{name}: must be a 1-d sequence of times in s, got shape {t.shape}")
    bad = ~np.isfinite(t)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{name}: must be finite, entry {i} is {float(t[i])!r}")
    if recorded.size and t.size:
        lo, hi = float(np.min(recorded)), float(np.max(recorded))
        tol = dt * (1 + 1e-9)
        outside = (t < lo - tol) | (t > hi + tol)
        if outside.any():
            i = int(np.flatnonzero(outside)[0])
            raise ValueError(f"{name}: {t[i]:.6g} s (entry {i}) lies outside the recorded snapshots, "
                             f"{lo:.6g} to {hi:.6g} s ({recorded.size} snapshot(s)); record snapshots there with "
                             "Outputs(snapshot_times=...) or Outputs(snapshot_every=...) ([output] in a model file)")
    return t


def nearest_snapshots(times: np.ndarray, wanted: Optional[np.ndarray], dt: float = 0.0,
                      name: str = "times") -> list[int]:
    """Indices of the recorded snapshots nearest to ``wanted`` times (default: 3 spread over the run); every wanted
    time must lie within the recorded ones (to ``dt``, see :func:`check_snapshot_times`)."""
    if times.size == 0:
        raise ValueError("snapshots: the result holds no field snapshots; record some with "
                         "Outputs(snapshot_times=...) or Outputs(snapshot_every=...) ([output] in a model file)")
    if wanted is not None:
        wanted = check_snapshot_times(times, wanted, dt, name)
    if wanted is None or len(wanted) == 0:
        picks = np.quantile(times, [0.2, 0.5, 0.8]) if times.size >= 3 else times
        wanted = np.asarray(picks)
    idx = [int(np.argmin(np.abs(times - t))) for t in np.atleast_1d(wanted)]
    return list(dict.fromkeys(idx))
