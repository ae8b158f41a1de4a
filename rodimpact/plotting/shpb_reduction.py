"""Plots of a split-Hopkinson-bar reduction (:class:`~rodimpact.shpb.ShpbReduction`): the pulses aligned at the
specimen faces, the stress-strain curves, the strain rate and the equilibrium ratio with its bands. Every function
takes the reduction and an optional Axes and returns the Axes (the rule of :mod:`rodimpact.plotting`).

Times are in µs (the scale of a Hopkinson-bar pulse), bar strains in microstrain (tension positive, as measured),
specimen stress in MPa and specimen strain and strain rate compression positive (the Hopkinson-bar habit).
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from ._common import new_axes

#: One colour per analysis, the same on every plot.
_COLOURS = {"1-wave": "tab:blue", "2-wave": "tab:orange", "3-wave": "tab:green"}
#: Band colours of the equilibrium plot: pass, review, fail.
_BANDS = ("tab:green", "gold", "tab:red")


def _check(reduction: Any) -> None:
    from ..shpb.result import ShpbReduction

    if not isinstance(reduction, ShpbReduction):
        raise TypeError(f"reduction: must be a ShpbReduction (from rodimpact.shpb.reduce_shot), got "
                        f"{type(reduction).__name__}")


def _analyses(analyses: Sequence[str]) -> list[str]:
    names = [analyses] if isinstance(analyses, str) else list(analyses)
    unknown = [a for a in names if a not in _COLOURS]
    if unknown or not names:
        raise ValueError(f"analyses: choose from {', '.join(_COLOURS)}, got {analyses!r}")
    return names


def _micro(t: np.ndarray) -> np.ndarray:
    return np.asarray(t) * 1e6


def plot_pulses(reduction: Any, ax: Optional[Any] = None):
    """The incident, reflected and transmitted bar strains at the specimen faces (microstrain, tension
    positive) against the time there (µs), with eps_I + eps_R: it lies on eps_T when the faces carry equal
    forces (equal bars)."""
    _check(reduction)
    _, ax = new_axes(ax)
    t = _micro(reduction.time)
    for name, values in (("incident $\\varepsilon_I$", reduction.incident),
                         ("reflected $\\varepsilon_R$", reduction.reflected),
                         ("transmitted $\\varepsilon_T$", reduction.transmitted)):
        ax.plot(t, values * 1e6, label=name)
    ax.plot(t, (reduction.incident + reduction.reflected) * 1e6, "k--", lw=1,
            label="$\\varepsilon_I + \\varepsilon_R$")
    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.set_xlabel("time at the specimen faces [µs]")
    ax.set_ylabel("bar strain [µε]")
    ax.set_title("Pulses moved to the specimen faces" + (" (dispersion corrected)"
                                                         if reduction.dispersion_corrected else ""))
    ax.legend(loc="best")
    return ax


def plot_stress_strain(reduction: Any, ax: Optional[Any] = None, analyses: Sequence[str] = ("1-wave", "2-wave",
                                                                                           "3-wave"),
                       measure: str = "both"):
    """Specimen stress (MPa) against strain (-), compression positive, for each of ``analyses``:
    ``measure`` ``"engineering"``, ``"true"`` or ``"both"`` (engineering solid, true dashed). A dot marks where
    the specimen reaches equilibrium (R within the pass band) on the 3-wave curve."""
    _check(reduction)
    names = _analyses(analyses)
    if measure not in ("engineering", "true", "both"):
        raise ValueError(f"measure: must be 'engineering', 'true' or 'both', got {measure!r}")
    _, ax = new_axes(ax)
    for name in names:
        r = reduction.response(name)
        if measure in ("engineering", "both"):
            ax.plot(r.strain, r.stress / 1e6, color=_COLOURS[name], label=f"{name}, engineering")
        if measure in ("true", "both"):
            ax.plot(r.true_strain, r.true_stress / 1e6, "--", color=_COLOURS[name], label=f"{name}, true")
    t_eq = reduction.equilibrium.equilibrium_time
    if t_eq is not None and "3-wave" in names:
        r = reduction.three_wave
        eps, sig = (r.true_strain, r.true_stress) if measure == "true" else (r.strain, r.stress)
        ax.plot(np.interp(t_eq, reduction.time, eps), np.interp(t_eq, reduction.time, sig) / 1e6, "o", color="k",
                label="equilibrium from here")
    ax.set_xlabel("strain (compression positive) [-]")
    ax.set_ylabel("stress (compression positive) [MPa]")
    ax.set_title("Specimen stress-strain")
    ax.legend(loc="best", fontsize="small")
    return ax


def plot_strain_rate(reduction: Any, ax: Optional[Any] = None, analyses: Sequence[str] = ("2-wave", "3-wave")):
    """Engineering strain rate (1/s, compression positive) against the time at the faces (µs) for each of
    ``analyses``; the span in equilibrium is shaded."""
    _check(reduction)
    names = _analyses(analyses)
    _, ax = new_axes(ax)
    t = _micro(reduction.time)
    for name in names:
        ax.plot(t, reduction.response(name).strain_rate, color=_COLOURS[name], label=name)
    eq = reduction.equilibrium
    if eq.equilibrium_time is not None:
        ax.axvspan(eq.equilibrium_time * 1e6, eq.loading_end * 1e6, color=_BANDS[0], alpha=0.12,
                   label="in equilibrium (R within the pass band)")
    ax.set_xlabel("time at the specimen faces [µs]")
    ax.set_ylabel("strain rate (compression positive) [1/s]")
    ax.set_title(f"Specimen strain rate (mean {reduction.mean_strain_rate():.4g} 1/s in equilibrium, 3-wave)")
    ax.legend(loc="best")
    return ax


def plot_equilibrium(reduction: Any, ax: Optional[Any] = None):
    """The equilibrium ratio R(t) = 2 |F1 - F2| / |F1 + F2| (%) against the time at the faces (µs) over the pass,
    review and fail bands, with the time from which the specimen is in equilibrium and the loading end."""
    _check(reduction)
    _, ax = new_axes(ax)
    eq = reduction.equilibrium
    t = _micro(reduction.time)
    top = 3.0 * eq.review_limit * 100
    for (low, high), colour, label in zip(((0.0, eq.pass_limit), (eq.pass_limit, eq.review_limit),
                                           (eq.review_limit, 1e9)), _BANDS,
                                          (f"pass (R <= {eq.pass_limit:.0%})", f"review (R <= {eq.review_limit:.0%})",
                                           "fail")):
        ax.axhspan(low * 100, min(high * 100, top), color=colour, alpha=0.15, label=label)
    ax.plot(t, eq.ratio * 100, color="k", lw=1, label="R(t)")
    ax.axvline(eq.loading_end * 1e6, color="0.4", ls=":", label="loading end (peak mean force)")
    if eq.equilibrium_time is not None:
        ax.axvline(eq.equilibrium_time * 1e6, color=_BANDS[0], ls="--",
                   label=f"equilibrium from {eq.equilibrium_time * 1e6:.4g} µs")
    ax.set_ylim(0.0, top)
    ax.set_xlabel("time at the specimen faces [µs]")
    ax.set_ylabel("equilibrium ratio R [%]")
    ax.set_title("Force equilibrium R = 2|F1 - F2| / |F1 + F2|")
    ax.legend(loc="upper right", fontsize="small")
    return ax
