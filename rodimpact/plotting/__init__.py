"""Plots of rodimpact results (matplotlib only; headless-safe: figures are created without pyplot).

The rule, as in matplotlib and pandas: a function that draws on **one** Axes takes it as ``ax`` (``None``: a new
figure) and returns that Axes (:func:`plot_forces`, :func:`plot_strain`, :func:`plot_energy`,
:func:`plot_energy_comparison`, :func:`plot_xt`, the synthesis plots :func:`plot_impedance`,
:func:`plot_force`, :func:`plot_existence`, :func:`plot_shape`, the Kolsky-bar prediction's
:func:`plot_predicted_signals`, :func:`plot_predicted_stress_strain`, :func:`plot_predicted_strain_rate`, and the
split-Hopkinson-bar reduction's :func:`plot_pulses`, :func:`plot_stress_strain`, :func:`plot_strain_rate`,
:func:`plot_equilibrium`, and the identification's :func:`plot_reflectogram`, :func:`plot_identified_profile`,
:func:`plot_matched`); its figure is ``ax.figure``. A function that draws on **several** Axes takes them as
``axes`` and returns the Figure (:func:`plot_profile`, :func:`plot_snapshots`, :func:`plot_synthesis`,
:func:`plot_sweep`). New figures are :class:`matplotlib.figure.Figure` objects not registered with pyplot: save them
with ``ax.figure.savefig(...)``. In a notebook, draw on Axes from ``plt.subplots()`` so that pyplot shows the figure
as usual.

Units are written ``quantity [unit]`` on every axis: forces in kN, impedances in kN s/m, strains in microstrain
(µε), lengths along the rods in m (mm for diameters, displacements and striker drawings), times in ms (s above
1 s; µs for the Kolsky-bar pulses of tens of microseconds). Forces are positive in tension (a Kolsky-bar
specimen's stress, strain and strain rate in compression, the SHPB habit).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Sequence

from ._common import (check_dpi, check_figure_pixels, check_output_folder, check_result, check_snapshot_times,
                      new_axes)
from .animation import animate_force, pillow_available
from .fields import plot_snapshots, plot_xt
from .histories import plot_energy, plot_energy_comparison, plot_forces, plot_strain
from .profile import plot_profile
from .design import plot_convergence, plot_design_force, plot_design_profile, plot_incident_wave
from .synthesis import plot_existence, plot_force, plot_impedance, plot_shape, plot_synthesis
from .sweep import plot_sweep
from .shpb_model import plot_predicted_signals, plot_predicted_strain_rate, plot_predicted_stress_strain
from .shpb_reduction import plot_equilibrium, plot_pulses, plot_strain_rate, plot_stress_strain
from .identify import plot_identified_profile, plot_matched, plot_reflectogram

__all__ = ["plot_forces", "plot_strain", "plot_energy", "plot_energy_comparison", "plot_profile", "plot_snapshots",
           "plot_xt", "animate_force", "pillow_available", "save_plots", "PLOT_FILES",
           "plot_impedance", "plot_force", "plot_existence", "plot_shape", "plot_synthesis", "plot_sweep",
           "plot_design_force", "plot_design_profile", "plot_convergence", "plot_incident_wave",
           "plot_phase_speed", "new_axes", "plot_predicted_signals", "plot_predicted_stress_strain",
           "plot_predicted_strain_rate", "plot_pulses", "plot_stress_strain", "plot_strain_rate", "plot_equilibrium",
           "plot_reflectogram", "plot_identified_profile", "plot_matched"]


def __getattr__(name: str) -> Any:
    """``plot_phase_speed`` (thesis Fig. 2.2) lives in :mod:`rodimpact.reference`, which imports scipy: it is
    loaded only when asked for, so that ``import rodimpact.plotting`` stays as fast as before."""
    if name == "plot_phase_speed":
        from ..reference.phase_speed import plot_phase_speed

        return plot_phase_speed
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

#: File written by :func:`save_plots` for each plot name.
PLOT_FILES = {"forces": "forces.png", "strain": "strain.png", "profile": "profile.png", "snapshots": "snapshots.png", "xt": "xt.png",
              "energy": "energy.png", "animation": "force.gif"}


def save_plots(result: Any, folder: str | Path, which: Sequence[str] = ("forces", "profile", "snapshots", "xt",
                                                                        "energy"),
               *, snapshot_times: Optional[Sequence[float]] = None, dpi: int = 120,
               overwrite: bool = False) -> tuple[list[Path], list[str]]:
    """Write the named plots into ``folder``; returns the files written and notes on plots that were skipped
    (no snapshots recorded, no probes for the strain plot, pillow missing for the animation). Existing plot files are refused unless
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
                fig = plot_forces(result).figure
            elif name == "strain":
                fig = plot_strain(result).figure
            elif name == "profile":
                fig = plot_profile(result)
            elif name == "snapshots":
                fig = plot_snapshots(result, snapshot_times)
            elif name == "xt":
                fig = plot_xt(result).figure
            else:
                fig = plot_energy(result).figure
        except (ValueError, ImportError) as exc:
            notes.append(f"plot {name!r} skipped: {exc}")
            continue
        check_figure_pixels(fig, dpi, f"{name} plot")
        folder.mkdir(parents=True, exist_ok=True)
        fig.savefig(path, dpi=dpi)
        written.append(path)
    folder.mkdir(parents=True, exist_ok=True)
    return written, notes
