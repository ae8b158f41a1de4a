"""Plots of an identification (:class:`~rodimpact.identify.IdentificationResult`) and of a head record: the
reflectogram with exponential amplification (pile-integrity style), the impedance profile with its band and
reflectors, and the matched signals. Every function takes an optional Axes and returns it (the rule of
:mod:`rodimpact.plotting`). Impedances in kN s/m, depths in m, times in ms.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._common import new_axes


def _check(result: Any) -> None:
    from ..identify.result import IdentificationResult

    if not isinstance(result, IdentificationResult):
        raise TypeError(f"result: must be an IdentificationResult, got {type(result).__name__}")


def plot_reflectogram(source: Any, impedance: Optional[float] = None, wave_speed: Optional[float] = None, *,
                      amplification: float = 0.0, ax: Optional[Any] = None):
    """The up-going wave over the peak of the down-going one (the reflection coefficient of a reflector at its
    echo; :func:`rodimpact.identify.reflectogram`) against depth ``c t / 2`` below the head, multiplied by
    ``exp(amplification t)`` (1/s; a display aid that offsets the decay of deep echoes). ``source``: a
    :class:`~rodimpact.identify.HeadRecord` (with ``impedance`` and ``wave_speed``) or the result of
    :func:`rodimpact.identify.identify_by_beta` (its reflectogram and the primaries of the reflectors it found,
    dashed)."""
    from ..identify.records import amplified
    from ..identify.reflectors import reflectogram
    from ..identify.result import IdentificationResult

    if isinstance(source, IdentificationResult):
        if "reflectogram" not in source.matched:
            raise ValueError(f"source: a {source.method!r} result holds no reflectogram (identify_by_beta's does)")
        t, rho, fitted = source.matched["reflectogram"]
        wave_speed = source.wave_speed
    else:
        if impedance is None or wave_speed is None:
            raise ValueError("impedance, wave_speed: needed to draw the reflectogram of a record")
        t, rho, _ = reflectogram(source, impedance)
        fitted = None
    after = t >= 0.0
    _, ax = new_axes(ax)
    depth = 0.5 * wave_speed * t[after]
    ax.plot(depth, amplified(t[after], rho[after], amplification), lw=1, label="measured")
    if fitted is not None:
        ax.plot(depth, amplified(t[after], fitted[after], amplification), "--", lw=1, label="primaries")
        ax.legend(fontsize=8)
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.set_xlabel("depth below the head c t / 2 [m]")
    ax.set_ylabel("up / down peak [-]" + (f" x exp({amplification:g} t)" if amplification else ""))
    ax.set_title("Reflectogram (tension-positive waves: a reduction shows as a negative echo)")
    return ax


def plot_identified_profile(result: Any, ax: Optional[Any] = None):
    """The identified impedance against depth, with its 90 % band and the reflectors (beta and class)."""
    _check(result)
    _, ax = new_axes(ax)
    edges = result.depth
    ax.stairs(result.impedance / 1e3, edges, label=f"{result.method}", lw=1.5)
    if result.lower is not None:
        ax.stairs(result.upper / 1e3, edges, baseline=result.lower / 1e3, fill=True, alpha=0.3, label="90 % band")
    for a in result.anomalies:
        ax.axvline(a.depth, color="tab:red", lw=0.8, ls="--")
        ax.annotate(f"β = {a.beta:.2f}\n{a.beta_class}", (a.depth, ax.get_ylim()[1]), fontsize=7, va="top")
    if result.toe is not None:
        ax.axvline(result.toe, color="k", lw=1)
    ax.set_xlabel("depth [m]")
    ax.set_ylabel("impedance [kN s/m]")
    ax.legend(fontsize=8)
    return ax


def plot_matched(result: Any, name: Optional[str] = None, ax: Optional[Any] = None):
    """A matched signal (measured and fitted) against time; ``name``: which (default the first)."""
    _check(result)
    if not result.matched:
        raise ValueError("result: has no matched signals")
    name = name or next(iter(result.matched))
    if name not in result.matched:
        raise ValueError(f"name: one of {', '.join(result.matched)}, got {name!r}")
    t, measured, fitted = result.matched[name]
    _, ax = new_axes(ax)
    ax.plot(np.asarray(t) * 1e3, measured, label="measured", lw=1.5)
    ax.plot(np.asarray(t) * 1e3, fitted, "--", label="fitted", lw=1)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel(name)
    ax.legend(fontsize=8)
    return ax
