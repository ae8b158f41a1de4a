"""Report plots of pile driving (:mod:`rodimpact.pile`; matplotlib only): the head force beside velocity x
impedance, the stress envelopes along the pile, the bearing graph and drivability. Each function takes the blow or
the study's table and an optional Axes and returns the Axes (the rule of :mod:`rodimpact.plotting`).

Units and signs: forces in kN and stresses in MPa, compression positive on the envelope and the head force plotted
as compression positive (the pile-driving habit: F and Z v coincide until the first reflection); times in ms;
depths in m below the pile head (envelopes) or below the ground (drivability), increasing downwards.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._common import new_axes

MS, KN, MPA = 1e3, 1e-3, 1e-6


def _check(obj: Any, cls_name: str) -> None:
    from ..pile import Blow
    from ..pile.studies import BlowTable

    cls = {"Blow": Blow, "BlowTable": BlowTable}[cls_name]
    if not isinstance(obj, cls):
        raise TypeError(f"must be a {cls_name} of rodimpact.pile, got {type(obj).__name__}")


def plot_head_force(blow: Any, ax: Optional[Any] = None) -> Any:
    """Head force -N (compression positive) and Z v at the head against time: until the first reflection returns
    from the soil or the toe (2 L / c) the two coincide; their gap afterwards is what came back."""
    _check(blow, "Blow")
    _, ax = new_axes(ax)
    t = blow.time * MS
    ax.plot(t, -blow.head.force * KN, label="force F")
    ax.plot(t, blow.head_impedance * blow.head.velocity * KN, label="velocity x impedance Z v", linestyle="--")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("force at the pile head [kN] (compression +)")
    ax.legend()
    return ax


def plot_stress_envelope(blow: Any, ax: Optional[Any] = None) -> Any:
    """The largest compressive and tensile stresses of the blow along the pile (depth below the head downwards)."""
    _check(blow, "Blow")
    _, ax = new_axes(ax)
    e = blow.envelope
    ax.plot(e.compression * MPA, e.depth, label="compression")
    ax.plot(e.tension * MPA, e.depth, label="tension")
    ax.invert_yaxis()
    ax.set_xlabel("largest stress [MPa]")
    ax.set_ylabel("depth below the pile head [m]")
    ax.legend()
    return ax


def plot_bearing_graph(table: Any, ax: Optional[Any] = None) -> Any:
    """Ultimate capacity during driving (kN) against the blow count (blows per 0.25 m), with the largest
    compressive and tensile stresses on a second axis; refusal points (no set) are left out."""
    _check(table, "BlowTable")
    _, ax = new_axes(ax)
    blows = np.where(np.isfinite(table.blows_per_quarter_metre), table.blows_per_quarter_metre, np.nan)
    ax.plot(blows, table.x * KN, marker="o", label="capacity")
    ax.set_xlabel("blow count [blows / 0.25 m]")
    ax.set_ylabel("ultimate capacity during driving [kN]")
    twin = ax.twinx()
    twin.plot(blows, table.max_compression * MPA, color="C1", linestyle="--", label="compression")
    twin.plot(blows, table.max_tension * MPA, color="C2", linestyle=":", label="tension")
    twin.set_ylabel("largest stress [MPa]")
    twin.legend(loc="lower right")
    return ax


def plot_drivability(table: Any, ax: Optional[Any] = None) -> Any:
    """Blow count (blows per 0.25 m) against the toe's depth below the ground (downwards), with EMX (kJ) on a
    second axis."""
    _check(table, "BlowTable")
    _, ax = new_axes(ax)
    blows = np.where(np.isfinite(table.blows_per_quarter_metre), table.blows_per_quarter_metre, np.nan)
    ax.plot(blows, table.x, marker="o", label="blow count")
    ax.invert_yaxis()
    ax.set_xlabel("blow count [blows / 0.25 m]")
    ax.set_ylabel(f"{table.x_name} [{table.x_unit}]")
    twin = ax.twiny()
    twin.plot(table.emx * 1e-3, table.x, color="C1", linestyle="--")
    twin.set_xlabel("EMX [kJ]")
    return ax
