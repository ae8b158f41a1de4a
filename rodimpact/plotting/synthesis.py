"""Plots of synthesis results (matplotlib only). The functions that draw one Axes take an optional ``ax`` and
return that Axes; :func:`plot_synthesis` draws four and returns the Figure. Without an Axes a new
:class:`matplotlib.figure.Figure` is made without pyplot (headless-safe, see
:func:`rodimpact.plotting._common.new_axes`). Forces in kN, impedances in kN s/m, as in the other plots."""

from __future__ import annotations

import math
from typing import Any, Optional

import numpy as np

from .._validate import positive
from ._common import new_axes


def _check_synthesis(result: Any, name: str = "result") -> None:
    from ..inverse.result import SynthesisResult

    if not isinstance(result, SynthesisResult):
        raise TypeError(f"{name}: must be a SynthesisResult (from a synthesis solve), got {type(result).__name__}")


def plot_impedance(result: Any, ax: Optional[Any] = None, x: str = "s", log: Optional[bool] = None):
    """Impedance Z_q of the synthesized striker (steps) against ``x`` = "s" (distance from the impact face, m),
    "theta" (travel time) or "q" (element number), in kN s/m. The failing element, if any, is marked. ``log``:
    log scale for Z (default: when Z spans more than a factor 100). Returns the Axes."""
    _check_synthesis(result)
    _, ax = new_axes(ax)
    m = result.n_feasible
    if x == "s":
        edges = result.material.wave_speed * result.dt * np.arange(m + 1)
        label = "distance from impact face s [m]"
    elif x == "theta":
        edges = result.dt * np.arange(m + 1) * 1e6
        label = r"travel time $\theta$ [µs]"
    elif x == "q":
        edges = np.arange(m + 1) + 0.5
        label = "element q [-]"
    else:
        raise ValueError(f"x: must be 's', 'theta' or 'q', got {x!r}")
    z = result.impedance
    if m:
        ax.stairs(z / 1e3, edges, baseline=None, label="synthesized $Z_q$")
    if result.failure is not None:
        ax.axvline(edges[-1], color="C3", ls="--", label=f"no striker from element {result.failure.element} on")
    if log is None:
        log = m > 0 and z.max() / z.min() > 100
    if log:
        ax.set_yscale("log")
    ax.set_xlabel(label)
    ax.set_ylabel("impedance Z [kN s/m]")
    ax.legend(loc="best")
    ax.set_title(f"Impedance of the synthesized striker ({m} element{'s' if m != 1 else ''})")
    return ax


def plot_force(result: Any, verification: Optional[Any] = None, ax: Optional[Any] = None):
    """Target window values (and, with a :class:`~rodimpact.inverse.result.VerificationReport`, the force the
    synthesized striker achieves) in kN against time in ms. For a position target the prescribed quantity there is
    shown (time from the wavefront's arrival) together with the transformed impact force. Returns the Axes."""
    _check_synthesis(result)
    if verification is not None:
        from ..inverse.result import VerificationReport

        if not isinstance(verification, VerificationReport):
            raise TypeError(f"verification: must be a VerificationReport or None, got {type(verification).__name__}")
    _, ax = new_axes(ax)
    dt = result.dt
    n = result.window_values.size
    edges = 2.0 * dt * np.arange(n + 1) * 1e3
    tr = result.transformation
    # the target is piecewise constant on windows of 2 dt: drawn as steps, wide and light so that the achieved
    # force stays visible on top of it
    target_style = dict(baseline=None, lw=3.0, alpha=0.45, color="C0")
    if tr is None:
        ax.stairs(result.window_values / 1e3, edges, label="target impact force (per window of 2 dt)",
                  **target_style)
    else:
        ax.stairs(tr.target / 1e3, edges, label=f"target {tr.quantity} at {tr.location.used:.4g} m",
                  **target_style)
        ax.stairs(result.window_values / 1e3, edges, baseline=None, ls=":", color="C2",
                  label="impact force it requires")
    if result.failure is not None:
        ax.axvline(2.0 * dt * result.n_feasible * 1e3, color="C3", ls="--",
                   label="no striker produces the target beyond")
    if verification is not None:
        t0 = 0.0 if tr is None else tr.dead_time
        t = (verification.time - t0) * 1e3
        # node values are constant during a step: steps, as in plot_forces (dots came in pairs per window)
        if t.size:
            gaps = np.diff(t)
            step = float(np.min(gaps[gaps > 0])) if np.any(gaps > 0) else dt * 1e3
            ax.stairs(verification.achieved / 1e3, np.append(t, t[-1] + step), baseline=None, color="C1", lw=1.2,
                      label="achieved (direct solver)")
    ax.set_xlabel("time [ms]" if tr is None else "time after arrival [ms]")
    ax.set_ylabel("force [kN] (tension > 0)")
    ax.legend(loc="best")
    what = "Impact force" if tr is None else f"{tr.quantity.capitalize()} at {tr.location.used:.4g} m"
    ax.set_title(f"{what}: target" + (" and achieved" if verification is not None else ""))
    return ax


def plot_existence(result: Any, ax: Optional[Any] = None):
    """Whether the striker can be built, element by element from the impact face, in plain words.

    For each element the plot compares the force change the target asks of it (|Delta N_q|, thesis eq. 4.7)
    with the largest force change still possible there (the force reserve |K_q N_0|, eq. 4.8): the element
    exists while the first stays below the second (eq. 4.20). When the target cannot be produced to the end, the
    curves run up to and include the first impossible element m + 1 (its values from ``result.failure``), which
    is shaded and marked with crosses; the title says in words how many elements exist and for how long the
    target force can be produced. Markers are drawn on short strikers (a one-element curve is a point). Returns
    the Axes."""
    _check_synthesis(result)
    _, ax = new_axes(ax)
    q = result.element
    reserve = result.force_reserve
    difference = np.abs(result.force_difference)
    f = result.failure
    if f is not None:
        q = np.append(q, f.element)
        reserve = np.append(reserve, f.force_reserve)
        difference = np.append(difference, abs(f.force_difference))
    marker = "o" if q.size <= 60 else None
    ax.plot(q, reserve / 1e3, marker=marker, ms=3, label="largest force change still possible")
    ax.plot(q, difference / 1e3, marker=marker, ms=3, label="force change the target asks for")
    n, m = result.n_requested, result.n_feasible
    if f is None:
        title = (f"The striker exists: all {n} elements can be built\n"
                 "(the target never asks for more force change than is possible)")
    else:
        why = ("the target asks for more force change than is possible" if f.reason == "existence" else
               "the impact force would have to pull, which a contact cannot do" if f.reason == "tension" else
               f.reason)
        title = (f"The striker exists for {m} of {n} elements only: target reached for "
                 f"{2.0 * result.dt * m * 1e3:.4g} ms\n(element {f.element}: {why})")
        ax.axvspan(f.element - 0.5, f.element + 0.5, color="C3", alpha=0.15, lw=0)
        ax.plot([f.element, f.element], [f.force_reserve / 1e3, abs(f.force_difference) / 1e3], "x", color="C3",
                ms=8, mew=2, label=f"element {f.element}: impossible")
    from matplotlib.ticker import MaxNLocator

    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("striker element, counted from the impact face [-]")
    ax.set_ylabel("force change [kN]")
    ax.set_ylim(bottom=0.0, top=max(float(np.max(reserve)) if reserve.size else 0.0,
                                    float(np.max(difference)) if difference.size else 0.0) / 1e3 * 1.25 or None)
    ax.legend(loc="best")           # matplotlib places it where it covers the fewest points
    ax.set_title(title, fontsize="small")
    return ax


def _nice_scale(x: float) -> float:
    """The largest of 1, 2, 5, 10, 20, 50, ... not above ``x`` (1 for x <= 1)."""
    if x <= 1.0:
        return 1.0
    k = math.floor(math.log10(x))
    return max(m * 10.0**k for m in (1, 2, 5) if m * 10.0**k <= x)


def plot_shape(shape: Any, ax: Optional[Any] = None, *, radial_scale: Optional[float] = None):
    """Drawing-style side view of a :class:`~rodimpact.inverse.shape.StrikerShape` (or of a synthesis result
    as a solid steel striker): outline +-d/2 in mm against the distance from the impact face, bore dashed.

    A striker is long and slim, so at true scale its diameter changes are hard to see: the radial direction is
    drawn ``radial_scale`` times larger than the axial one (default: the largest of 1, 2, 5, 10, ... that keeps the
    drawing at most a third as high as long; 1 = true scale), and the y label says so. Returns the Axes.
    """
    from ..inverse.result import SynthesisResult
    from ..inverse.shape import StrikerShape

    if isinstance(shape, SynthesisResult):
        shape = shape.shape()
    elif not isinstance(shape, StrikerShape):
        raise TypeError(f"shape: must be a StrikerShape or a SynthesisResult, got {type(shape).__name__}")
    if radial_scale is None:
        radial_scale = _nice_scale(shape.length / 3.0 / float(np.max(shape.outer_diameter)))
    else:
        radial_scale = positive("radial_scale", radial_scale)
    _, ax = new_axes(ax)
    s = shape.boundaries * 1e3
    r = 0.5 * shape.outer_diameter * 1e3
    ax.stairs(r, s, color="k", baseline=None)
    ax.stairs(-r, s, color="k", baseline=None)
    ax.vlines([s[0], s[-1]], [-r[0], -r[-1]], [r[0], r[-1]], color="k")
    if shape.bore > 0:
        ax.hlines([0.5 * shape.bore * 1e3, -0.5 * shape.bore * 1e3], s[0], s[-1], color="k", ls="--", lw=0.8)
    ax.axhline(0.0, color="0.5", ls="-.", lw=0.6)
    ax.set_aspect(radial_scale, adjustable="datalim")
    ax.set_xlabel("distance from impact face [mm]")
    ax.set_ylabel("radius [mm]" + (f" (radial scale x{radial_scale:g})" if radial_scale != 1.0 else ""))
    ax.set_title(f"Striker shape: length {shape.length * 1e3:.4g} mm, mass {shape.mass:.4g} kg, diameter ratio "
                 f"{shape.diameter_ratio:.3g}", fontsize="small")
    return ax


def plot_synthesis(result: Any, verification: Optional[Any] = None):
    """Summary figure: impedance, force (target/achieved), existence margin and shape on a 2 x 2 grid. Draws on
    several Axes, so it returns the Figure (``fig.axes`` in reading order)."""
    _check_synthesis(result)
    fig, axes = new_axes(None, nrows=2, ncols=2, figsize=(11.0, 7.0))
    plot_impedance(result, axes[0, 0])
    plot_force(result, verification, axes[0, 1])
    plot_existence(result, axes[1, 0])
    if result.n_feasible:
        plot_shape(result.shape(), axes[1, 1])
    return fig
