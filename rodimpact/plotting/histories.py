"""Histories over time: contact and probe forces, energies (thesis Fig. 3.9)."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from .._validate import positive
from ._common import check_result, new_axes, rod_label, time_scale


def plot_forces(result: Any, ax: Any = None, *, probes: Optional[Sequence[str]] = None, contact: bool = True,
                ends: Optional[bool] = None):
    """Contact force(s) and probe forces (kN) against time; returns the figure.

    Node values are constant during each step, so the curves are drawn as steps from the step start times.
    Forces are positive in tension (impacts are negative). ``probes``: names to show (default all); ``ends``:
    also the outer-end forces where they are not zero (default: only for a single rod, which has no contact).
    """
    check_result(result)
    if probes is None:
        names = list(result.probes)
    else:
        names = [probes] if isinstance(probes, str) else list(probes)
        unknown = [n for n in names if n not in result.probes]
        if unknown:
            raise ValueError(f"probes: {unknown[0]!r} was not recorded; recorded probes: "
                             f"{', '.join(map(repr, result.probes)) or 'none'}")
    fig, ax = new_axes(ax)
    if ends is None:
        ends = result.junction_force.shape[0] == 0
    t = result.time
    k, unit = time_scale(float(t[-1]) if t.size else 0.0)
    if contact:
        for j in range(result.junction_force.shape[0]):
            label = f"contact {rod_label(result, j)} | {rod_label(result, j + 1)}"
            ax.plot(t * k, result.junction_force[j] / 1e3, drawstyle="steps-post", lw=1.4, label=label)
    if ends:
        for side in ("left", "right"):
            if np.any(result.end_force[side] != 0):
                ax.plot(t * k, result.end_force[side] / 1e3, drawstyle="steps-post", lw=1.0, ls="--",
                        label=f"{side} end")
    for name in names:
        p = result.probe(name)
        ax.plot(t * k, p.force / 1e3, drawstyle="steps-post", lw=1.0,
                label=f"{name} ({rod_label(result, p.probe.rod)}, x = {p.probe.position * 1e3:.4g} mm)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"time [{unit}]")
    ax.set_ylabel("normal force [kN] (tension > 0)")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize="small")
    ax.set_title("Forces")
    return fig


def plot_energy(result: Any, ax: Any = None):
    """Kinetic + strain energy of each rod, the total, and the total minus the work done on the rods by ends,
    loads and friction (constant when the bookkeeping balances); returns the figure."""
    check_result(result)
    fig, ax = new_axes(ax)
    e = result.energy
    k, unit = time_scale(float(e.time[-1]) if e.time.size else 0.0)
    for i in range(e.kinetic.shape[0]):
        ax.plot(e.time * k, e.kinetic[i] + e.strain[i], lw=1.0, label=f"{rod_label(result, i)}")
    ax.plot(e.time * k, e.total, color="k", lw=1.6, label="total E_tot (thesis eq. 3.25)")
    if np.any(e.exchanged != 0):
        ax.plot(e.time * k, e.total - e.exchanged, color="k", ls=":", lw=1.2,
                label="total - work of ends, loads, friction")
    ax.set_xlabel(f"time [{unit}]")
    ax.set_ylabel("energy [J]")
    ax.set_ylim(bottom=min(0.0, float(np.min(e.total)) if e.total.size else 0.0))
    ax.legend(fontsize="small")
    ax.set_title("Energy")
    return fig


def plot_energy_comparison(results: Sequence[Any], labels: Sequence[str], ax: Any = None, *,
                           round_trip_time: Optional[float] = None):
    """Total energy of several runs on one axis (thesis Fig. 3.9: with and without friction).

    With ``round_trip_time`` (s) the abscissa counts round trips ("iterations" in the thesis) instead of time.
    """
    if isinstance(results, (str, bytes)) or not hasattr(results, "__len__"):
        raise TypeError(f"results: must be a sequence of SimulationResults, got {type(results).__name__}")
    if isinstance(labels, (str, bytes)) or not hasattr(labels, "__len__"):
        raise TypeError(f"labels: must be a sequence of strings, one per result, got {type(labels).__name__}")
    if len(results) == 0:
        raise ValueError("results: give at least one result")
    for i, res in enumerate(results):
        check_result(res, f"results[{i}]")
    if len(results) != len(labels):
        raise ValueError(f"labels: need one per result ({len(results)}), got {len(labels)}")
    if round_trip_time is not None:
        round_trip_time = positive("round_trip_time", round_trip_time, "s")
    fig, ax = new_axes(ax)
    for res, label in zip(results, labels):
        e = res.energy
        if round_trip_time:
            ax.plot(e.time / round_trip_time, e.total, label=str(label))
        else:
            k, unit = time_scale(float(e.time[-1]))
            ax.plot(e.time * k, e.total, label=str(label))
    ax.set_xlabel("round trips of the wave in the struck rod" if round_trip_time else "time")
    ax.set_ylabel("total energy E_tot [J]")
    ax.legend(fontsize="small")
    ax.set_title("Total energy")
    return fig
