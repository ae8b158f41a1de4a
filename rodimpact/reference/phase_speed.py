"""Phase-speed plot of the Tab. 2.1 families (thesis Fig. 2.2)."""

from __future__ import annotations

from typing import Any

import numpy as np

from rodimpact._validate import positive
from rodimpact.reference.families import STEEL_BAR_SPEED, AnalyticProfile

__all__ = ["plot_phase_speed"]

_LABELS = {
    "quadratic": r"$A_0(1+\xi x)^2$",
    "exponential": r"$A_0 e^{\xi x}$",
    "cosh2": r"$A_0\cosh^2(\xi x)$",
    "cos2": r"$A_0\cos^2(\xi x)$",
}


def plot_phase_speed(
    xi: float = 1.0,
    wave_speed: float = STEEL_BAR_SPEED,
    omega_max: float | None = None,
    ax: Any = None,
    n_points: int = 600,
) -> Any:
    """Plot c_p(omega) (eq. 2.18) of the four Tab. 2.1 families, as in thesis Fig. 2.2 (default xi = 1 1/m).

    Curves start just above each cutoff (eq. 2.19, dotted vertical lines); below it no wave propagates.
    ``omega_max`` defaults to 8 c0 xi. Draws on ``ax`` (default: a new figure, made without pyplot) and returns
    that Axes, like the functions of :mod:`rodimpact.plotting`.
    """

    xi = positive("xi", xi, "1/m")
    c0 = positive("wave_speed", wave_speed, "m/s")
    wmax = 8.0 * c0 * xi if omega_max is None else positive("omega_max", omega_max, "rad/s")
    if ax is None:
        from matplotlib.figure import Figure

        ax = Figure(figsize=(6.0, 4.0), layout="constrained").subplots()
    for prof in AnalyticProfile.table(1.0, xi, c0):
        wc = prof.cutoff_angular_frequency
        w = np.linspace(wc, wmax, n_points)[1:] if wc > 0 else np.linspace(0.0, wmax, n_points)[1:]
        line, = ax.plot(w, prof.phase_velocity(w), label=_LABELS[prof.family])
        if wc > 0:
            ax.axvline(wc, color=line.get_color(), ls=":", lw=0.8)
    ax.set_xlabel(r"angular frequency $\omega$ [rad/s]")
    ax.set_ylabel(r"phase speed $c_p$ [m/s]")
    ax.set_ylim(0.0, 3.0 * c0)
    ax.set_xlim(0.0, wmax)
    ax.axhline(c0, color="0.5", lw=0.6)
    ax.set_title(rf"Phase speed, $\xi$ = {xi:g} 1/m, $c_0$ = {c0:.0f} m/s")
    ax.legend()
    return ax
