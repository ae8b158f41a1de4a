"""Plots of rodimpact results (matplotlib only; headless-safe: figures are created without pyplot).

Every function takes a result (or system) and an optional Axes and returns the figure.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Sequence

from ._common import check_dpi, check_figure_pixels, check_output_folder, check_result, check_snapshot_times
from .animation import animate_force, pillow_available
from .fields import plot_snapshots, plot_xt
from .histories import plot_energy, plot_energy_comparison, plot_forces
from .profile import plot_profile
from .design import plot_convergence, plot_design_force, plot_design_profile, plot_incident_wave

__all__ = ["plot_forces", "plot_energy", "plot_energy_comparison", "plot_profile", "plot_snapshots", "plot_xt",
           "animate_force", "pillow_available", "save_plots", "PLOT_FILES",
           "plot_design_force", "plot_design_profile", "plot_convergence", "plot_incident_wave"]

#: File written by :func:`save_plots` for each plot name.
PLOT_FILES = {"forces": "forces.png", "profile": "profile.png", "snapshots": "snapshots.png", "xt": "xt.png",
              "energy": "energy.png", "animation": "force.gif"}


def save_plots(result: Any, folder: str | Path, which: Sequence[str] = ("forces", "profile", "snapshots", "xt",
                                                                        "energy"),
               *, snapshot_times: Optional[Sequence[float]] = None, dpi: int = 120,
               overwrite: bool = False) -> tuple[list[Path], list[str]]:
    """Write the named plots into ``folder``; returns the files written and notes on plots that were skipped
    (no snapshots recorded, pillow missing for the animation). Existing plot files are refused unless
    ``overwrite=True``. ``snapshot_times`` (s) must lie within the recorded snapshot times (see
    :func:`plot_snapshots`). Arguments are checked before anything is written."""
    check_result(result)
    names = [which] if isinstance(which, str) else list(which)
    for name in names:
        if name not in PLOT_FILES:
            raise ValueError(f"plots: unknown plot {name!r}; valid: {', '.join(PLOT_FILES)}")
    dpi = check_dpi(dpi)
    if snapshot_times is not None and "snapshots" in names and result.snapshots is not None:
        check_snapshot_times(result.snapshots.time, snapshot_times, result.dt, "snapshot_times")
    folder = Path(folder)
    check_output_folder(folder)
    written: list[Path] = []
    notes: list[str] = []
    for name in names:
        path = folder / PLOT_FILES[name]
        if path.exists() and not overwrite:
            raise FileExistsError(f"{path}: exists; choose another folder or pass overwrite=True to replace it")
        try:
            if name == "animation":
                folder.mkdir(parents=True, exist_ok=True)
                written.append(animate_force(result, path, overwrite=overwrite))
                continue
            if name == "forces":
                fig = plot_forces(result)
            elif name == "profile":
                fig = plot_profile(result)
            elif name == "snapshots":
                fig = plot_snapshots(result, snapshot_times)
            elif name == "xt":
                fig = plot_xt(result)
            else:
                fig = plot_energy(result)
        except (ValueError, ImportError) as exc:
            notes.append(f"plot {name!r} skipped: {exc}")
            continue
        check_figure_pixels(fig, dpi, f"{name} plot")
        folder.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi)
        written.append(path)
    folder.mkdir(parents=True, exist_ok=True)
    return written, notes
