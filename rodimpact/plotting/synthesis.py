"""Plots of synthesis results (matplotlib only). Every function takes a result and an optional Axes and returns
``(fig, ax)``; without an Axes a new :class:`matplotlib.figure.Figure` is made without pyplot (headless-safe,
see :func:`rodimpact.plotting._common.new_axes`)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._common import new_axes


def _check_synthesis(result: Any, name: str = "result") -> None:
    from ..inverse.result import SynthesisResult

    if not isinstance(result, SynthesisResult):
        raise TypeError(f"{name}: must be a SynthesisResult (from a synthesis solve), got {type(result).__name__}")


def plot_impedance(result: Any, ax: Optional[Any] = None, x: str = "s", log: Optional[bool] = None):
    """Impedance Z_q of the synthesized striker (steps) against ``x`` = "s" (distance from the impact face, m),
    "theta" (travel time, s) or "q" (element number). The failing element, if any, is marked. ``log``: log
    scale for Z (default: when Z spans more than a factor 100)."""
    _check_synthesis(result)
    fig, ax = new_axes(ax)
    m = result.n_feasible
    if x == "s":
        edges = result.material.wave_speed * result.dt * np.arange(m + 1)
        label = "distance from impact face s / m"
    elif x == "theta":
        edges = result.dt * np.arange(m + 1)
        label = r"travel time $\theta$ / s"
    elif x == "q":
        edges = np.arange(m + 1) + 0.5
        label = "element q"
    else:
        raise ValueError(f"x: must be 's', 'theta' or 'q', got {x!r}")
    z = result.impedance
    if m:
        ax.stairs(z, edges, baseline=None, label="synthesized $Z_q$")
    if result.failure is not None:
        ax.axvline(edges[-1], color="C3", ls="--", label=f"no solution from q = {result.failure.element}")
    if log is None:
        log = m > 0 and z.max() / z.min() > 100
    if log:
        ax.set_yscale("log")
    ax.set_xlabel(label)
    ax.set_ylabel("impedance Z / (N s/m)")
    ax.legend(loc="best")
    return fig, ax


def plot_force(result: Any, verification: Optional[Any] = None, ax: Optional[Any] = None):
    """Target window values (and, with a :class:`~rodimpact.inverse.result.VerificationReport`, the force the
    synthesized striker achieves) against time. For a position target the prescribed quantity there is shown
    (time from the wavefront's arrival) together with the transformed impact force."""
    _check_synthesis(result)
    if verification is not None:
        from ..inverse.result import VerificationReport

        if not isinstance(verification, VerificationReport):
            raise TypeError(f"verification: must be a VerificationReport or None, got {type(verification).__name__}")
    fig, ax = new_axes(ax)
    dt = result.dt
    n = result.window_values.size
    edges = 2.0 * dt * np.arange(n + 1) * 1e3
    tr = result.transformation
    if tr is None:
        ax.stairs(result.window_values / 1e3, edges, baseline=None, label="target impact force $X_j$")
    else:
        ax.stairs(tr.target / 1e3, edges, baseline=None, label=f"target {tr.quantity} at {tr.location.used:.4g} m")
        ax.stairs(result.window_values / 1e3, edges, baseline=None, ls=":", label="required impact force $X_j$")
    if result.failure is not None:
        ax.axvline(2.0 * dt * result.n_feasible * 1e3, color="C3", ls="--", label="end of existence")
    if verification is not None:
        t0 = 0.0 if tr is None else tr.dead_time
        ax.plot((verification.time - t0) * 1e3, verification.achieved / 1e3, ".", ms=3,
                label="achieved (direct solver)")
    ax.set_xlabel("time / ms" if tr is None else "time after arrival / ms")
    ax.set_ylabel("force / kN")
    ax.legend(loc="best")
    return fig, ax


def plot_existence(result: Any, ax: Optional[Any] = None):
    """Force difference |Delta N_q| against the force reserve |K_q N_0| (thesis eq. 4.20) per element."""
    _check_synthesis(result)
    fig, ax = new_axes(ax)
    q = result.element
    ax.plot(q, result.force_reserve / 1e3, label=r"force reserve $|K_q N_0|$")
    ax.plot(q, np.abs(result.force_difference) / 1e3, label=r"force difference $|\Delta N_q|$")
    f = result.failure
    if f is not None:
        ax.plot([f.element], [f.force_reserve / 1e3], "x", color="C0")
        ax.plot([f.element], [abs(f.force_difference) / 1e3], "x", color="C1", label=f"q = {f.element}: no solution")
    ax.set_xlabel("element q")
    ax.set_ylabel("force / kN")
    ax.legend(loc="best")
    return fig, ax


def plot_shape(shape: Any, ax: Optional[Any] = None):
    """Drawing-style side view of a :class:`~rodimpact.inverse.shape.StrikerShape` (or of a synthesis result
    as a solid steel striker): outline +-d/2 against the distance from the impact face, bore dashed."""
    from ..inverse.result import SynthesisResult
    from ..inverse.shape import StrikerShape

    if isinstance(shape, SynthesisResult):
        shape = shape.shape()
    elif not isinstance(shape, StrikerShape):
        raise TypeError(f"shape: must be a StrikerShape or a SynthesisResult, got {type(shape).__name__}")
    fig, ax = new_axes(ax)
    s = shape.boundaries * 1e3
    r = 0.5 * shape.outer_diameter * 1e3
    ax.stairs(r, s, color="k", baseline=None)
    ax.stairs(-r, s, color="k", baseline=None)
    ax.vlines([s[0], s[-1]], [-r[0], -r[-1]], [r[0], r[-1]], color="k")
    if shape.bore > 0:
        ax.hlines([0.5 * shape.bore * 1e3, -0.5 * shape.bore * 1e3], s[0], s[-1], color="k", ls="--", lw=0.8)
    ax.axhline(0.0, color="0.5", ls="-.", lw=0.6)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("distance from impact face / mm")
    ax.set_ylabel("radius / mm")
    ax.set_title(f"length {shape.length * 1e3:.4g} mm, mass {shape.mass:.4g} kg, diameter ratio "
                 f"{shape.diameter_ratio:.3g}", fontsize="small")
    return fig, ax


def plot_synthesis(result: Any, verification: Optional[Any] = None):
    """Summary figure: impedance, force (target/achieved), existence margin and shape. Returns (fig, axes)."""
    _check_synthesis(result)
    fig, axes = new_axes(None, nrows=2, ncols=2, figsize=(11.0, 7.0))
    plot_impedance(result, axes[0, 0])
    plot_force(result, verification, axes[0, 1])
    plot_existence(result, axes[1, 0])
    if result.n_feasible:
        plot_shape(result.shape(), axes[1, 1])
    return fig, axes
