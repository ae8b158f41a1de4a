"""Plots of a Kolsky-bar prediction (:class:`rodimpact.shpb.KolskyPrediction`; matplotlib only): the gauge signals
aligned at the specimen, the specimen's stress-strain curve and its strain rate. Each function takes the prediction
and an optional Axes and returns the Axes (the rule of :mod:`rodimpact.plotting`); the time axis shows the loading
(where the signals are not zero) with a margin.

Units and signs: bar strains in microstrain (µε), tension positive, as the gauges read them; the specimen's stress
(MPa), strain and strain rate (1/s) positive in compression (the SHPB habit); times in µs, since a Kolsky-bar pulse
lasts tens of microseconds.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._common import new_axes

US = 1e6            # s -> µs


def _check(prediction: Any) -> None:
    from ..shpb import KolskyPrediction

    if not isinstance(prediction, KolskyPrediction):
        raise TypeError(f"prediction: must be a KolskyPrediction (from rodimpact.shpb.KolskyBar.predict), got "
                        f"{type(prediction).__name__}")


def _shifted(x: np.ndarray, steps: int) -> np.ndarray:
    """``x`` moved by ``steps`` samples (later for steps > 0), NaN where it has no value."""
    out = np.full(x.size, np.nan)
    if abs(steps) >= x.size:
        return out
    if steps >= 0:
        out[steps:] = x[:x.size - steps]
    else:
        out[:steps] = x[-steps:]
    return out


def _show_loading(ax: Any, time_us: np.ndarray, *signals: np.ndarray) -> None:
    """Limit the time axis to where any of ``signals`` exceeds 1e-3 of its largest magnitude, with a margin of 15 %."""
    busy = np.zeros(time_us.size, dtype=bool)
    for s in signals:
        mag = np.abs(np.nan_to_num(s))
        if mag.max() > 0.0:
            busy |= mag > 1e-3 * mag.max()
    if busy.any():
        a, b = time_us[np.flatnonzero(busy)[[0, -1]]]
        margin = 0.15 * (b - a) if b > a else 1.0
        ax.set_xlim(a - margin, b + margin)


def plot_predicted_signals(prediction: Any, ax: Optional[Any] = None):
    """The predicted incident, reflected and transmitted strains (µε, tension positive) moved to the specimen faces
    by their travel times from the gauges (:attr:`~rodimpact.shpb.KolskyPrediction.face_delays`), with the front
    face's incident + reflected, against the time at the specimen (µs): in equilibrium the front face's strain
    equals the transmitted one (the 1- and 2-wave forces agree)."""
    _check(prediction)
    _, ax = new_axes(ax)
    p = prediction
    dt = p.result.dt
    steps_i, steps_t = (int(round(d / dt)) for d in p.face_delays)
    incident, reflected = _shifted(p.incident, steps_i), _shifted(p.reflected, -steps_i)
    transmitted = _shifted(p.transmitted, -steps_t)
    t = p.time * US
    for y, label, style in ((incident, "incident", "-"), (reflected, "reflected", "-"),
                            (transmitted, "transmitted", "-"), (incident + reflected, "incident + reflected", "--")):
        ax.plot(t, y * 1e6, ls=style, lw=1.2, label=label)
    ax.axhline(0.0, color="0.6", lw=0.6)
    _show_loading(ax, t, incident, reflected, transmitted)
    ax.set_xlabel("time at the specimen [µs]")
    ax.set_ylabel("bar strain [µε] (tension > 0)")
    ax.set_title("Predicted gauge signals, aligned at the specimen faces")
    ax.legend(loc="best", fontsize="small")
    return ax


def plot_predicted_stress_strain(prediction: Any, ax: Optional[Any] = None):
    """The specimen's predicted stress (MPa) against its strain, engineering and true (compression positive)."""
    _check(prediction)
    _, ax = new_axes(ax)
    p = prediction
    ax.plot(p.strain, p.stress / 1e6, lw=1.4, label="engineering")
    ax.plot(p.true_strain, p.true_stress / 1e6, lw=1.2, ls="--", label="true")
    ax.set_xlabel("specimen strain [-] (compression > 0)")
    ax.set_ylabel("specimen stress [MPa] (compression > 0)")
    ax.set_title("Predicted specimen stress-strain curve")
    ax.legend(loc="best", fontsize="small")
    return ax


def plot_predicted_strain_rate(prediction: Any, ax: Optional[Any] = None):
    """The specimen's predicted engineering strain rate (1/s, compression positive) against time (µs), with its
    mean over the plateau (:func:`rodimpact.shpb.plateau.rate_plateau`: where the specimen's force is at least half
    its largest)."""
    from ..shpb.plateau import rate_plateau

    _check(prediction)
    _, ax = new_axes(ax)
    p = prediction
    t = p.time * US
    ax.plot(t, p.strain_rate, lw=1.2, label="strain rate")
    plateau = rate_plateau(p.time, p.force, p.strain_rate)
    if plateau is not None:
        ax.hlines(plateau.mean, plateau.start * US, plateau.end * US, colors="0.3", linestyles="--",
                  label=f"plateau mean {plateau.mean:.4g} 1/s (flatness {plateau.flatness * 100:.3g} %)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    _show_loading(ax, t, p.force)
    ax.set_xlabel("time at the specimen [µs]")
    ax.set_ylabel("specimen strain rate [1/s] (compression > 0)")
    ax.set_title("Predicted specimen strain rate")
    ax.legend(loc="best", fontsize="small")
    return ax
