"""Histories over time: contact and probe forces, probe strains, energies (thesis Fig. 3.9). Each function draws
on one Axes (``ax``, or a new headless figure) and returns that Axes."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from .._validate import positive
from ._common import check_result, format_length, new_axes, rod_label, time_scale


def plot_forces(result: Any, ax: Any = None, *, probes: Optional[Sequence[str]] = None, contact: bool = True,
                ends: Optional[bool] = None):
    """Contact force(s) and probe forces (kN) against time; returns the Axes.

    Node values are constant during each step, so the curves are drawn as steps from the step start times.
    Forces are positive in tension (impacts are negative); a probe's legend gives the position of the lattice node
    it reads, from its rod's left end. ``probes``: names to show (default all); ``ends``:
    also the outer-end forces where they are not zero (default: only for a single rod, which has no contact).
    """
    check_result(result)
    names = _probe_names(result, probes)
    _, ax = new_axes(ax)
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
        ax.plot(t * k, result.probe(name).force / 1e3, drawstyle="steps-post", lw=1.0,
                label=_probe_label(result, name))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"time [{unit}]")
    ax.set_ylabel("normal force [kN] (tension > 0)")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize="small")
    ax.set_title("Forces")
    return ax


def _probe_names(result: Any, probes: Optional[Sequence[str]]) -> list[str]:
    """The probe names to draw: all recorded ones, or ``probes`` (a name or names) after checking they exist."""
    if probes is None:
        return list(result.probes)
    names = [probes] if isinstance(probes, str) else list(probes)
    unknown = [n for n in names if n not in result.probes]
    if unknown:
        raise ValueError(f"probes: {unknown[0]!r} was not recorded; recorded probes: "
                         f"{', '.join(map(repr, result.probes)) or 'none'}")
    return names


def _probe_label(result: Any, name: str) -> str:
    """The legend entry of a probe: its name, rod and the position of the lattice node it reads (which may differ
    from the requested position by up to half an element), in mm below 1 m, else in m."""
    p = result.probe(name)
    return f"{name} ({rod_label(result, p.probe.rod)}, x = {format_length(p.node_position)})"


def plot_strain(result: Any, ax: Any = None, *, probes: Optional[Sequence[str]] = None):
    """Axial strain at the probes in microstrain (µε = 1e-6, tension > 0) against time, as a strain gauge on a
    Hopkinson bar reads it; returns the Axes.

    The strain is the probe's ``strain`` history, N / (E A) with the true modulus and area at the probe position
    (the lattice node force, constant during each step, so drawn as steps). ``probes``: names to show (default
    all; at least one probe must have been recorded).
    """
    check_result(result)
    names = _probe_names(result, probes)
    if not names:
        raise ValueError("plot_strain: the result holds no probes; record strains with outputs=Outputs(probes=["
                         "Probe(name, rod, position)]) ([[probes]] in a model file)")
    _, ax = new_axes(ax)
    t = result.time
    k, unit = time_scale(float(t[-1]) if t.size else 0.0)
    for name in names:
        ax.plot(t * k, result.probe(name).strain * 1e6, drawstyle="steps-post", lw=1.0,
                label=_probe_label(result, name))
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel(f"time [{unit}]")
    ax.set_ylabel("strain [µε] (tension > 0)")
    ax.legend(fontsize="small")
    ax.set_title("Strain at the probes")
    return ax


def plot_energy(result: Any, ax: Any = None):
    """Kinetic + strain energy of each rod, the total, and the total minus the work done on the rods by ends,
    loads and friction (constant when the bookkeeping balances); returns the Axes."""
    check_result(result)
    _, ax = new_axes(ax)
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
    return ax


def plot_energy_comparison(results: Sequence[Any], labels: Sequence[str], ax: Any = None, *,
                           round_trip_time: Optional[float] = None):
    """Total energy of several runs on one axis (thesis Fig. 3.9: with and without friction).

    With ``round_trip_time`` (s) the abscissa counts round trips ("iterations" in the thesis) instead of time.
    Returns the Axes.
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
    _, ax = new_axes(ax)
    k, unit = time_scale(max(float(r.energy.time[-1]) if r.energy.time.size else 0.0 for r in results))
    for res, label in zip(results, labels):
        e = res.energy
        ax.plot(e.time / round_trip_time if round_trip_time else e.time * k, e.total, label=str(label))
    ax.set_xlabel("round trips of the wave in the struck rod [-]" if round_trip_time else f"time [{unit}]")
    ax.set_ylabel("total energy E_tot [J]")
    ax.legend(fontsize="small")
    ax.set_title("Total energy")
    return ax
