"""Plots of design results (matplotlib only): target vs achieved force, the impedance profile, convergence, and
the incident wave of a drilling piston beside the reflection-free exponential wave. Every function takes a
:class:`~rodimpact.DesignResult` and an optional Axes and returns the Axes (the rule of :mod:`rodimpact.plotting`)."""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ._common import new_axes


def _check(result: Any) -> None:
    from ..design.result import DesignResult

    if not isinstance(result, DesignResult):
        raise TypeError(f"result: must be a DesignResult (from rodimpact.design), got {type(result).__name__}")


def plot_design_force(result: Any, ax: Optional[Any] = None):
    """Achieved force (per step) and the target (window values) against time, ms; for efficiency designs the
    incident wave at the bit."""
    _check(result)
    _, ax = new_axes(ax)
    t = result.time * 1e3
    what = "contact force" if result.location is None else f"{result.quantity} at {result.location.used:.4g} m"
    if result.target.size:
        # the target holds its window value over each window (2 dt): a wide, light step line under the achieved
        # force, the last window drawn to its end
        tk = t[result.compared]
        last = tk[-1] + (tk[-1] - tk[-2] if tk.size > 1 else result.dt * 1e3)
        values = result.target / 1e3
        ax.step(np.append(tk, last), np.append(values, values[-1]), where="post", color="0.6", lw=4, alpha=0.7,
                label=f"target (misfit {result.misfit:.3g})", zorder=1)
    ax.step(t, result.achieved / 1e3, where="post", label=f"achieved ({what})", zorder=2)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("force [kN]")
    ax.set_title(design_force_title(result))
    ax.legend(loc="best")
    return ax


def design_force_title(result: Any) -> str:
    """Title of :func:`plot_design_force`: what is drawn and how good the design is."""
    if result.objective == "match":
        where = ("contact force" if result.location is None
                 else f"{result.quantity} at {result.location.used:.4g} m")
        return f"Designed striker: {where} vs target (misfit {result.misfit:.3g})"
    return f"Efficiency design: incident wave at the bit (efficiency {result.efficiency:.4g})"


def plot_design_profile(result: Any, ax: Optional[Any] = None, log: Optional[bool] = None):
    """Impedance Z_q against the distance from the impact face (m, for the design's material), with the bounds."""
    _check(result)
    _, ax = new_axes(ax)
    edges = result.material.wave_speed * result.dt * np.arange(result.n_elements + 1)
    ax.stairs(result.impedance / 1e3, edges, baseline=None, label="designed $Z_q$")
    bounds = result.diagnostics.get("bounds")
    if bounds is not None:
        ax.stairs(bounds[0] / 1e3, edges, baseline=None, ls=":", color="0.5", label="bounds")
        ax.stairs(bounds[1] / 1e3, edges, baseline=None, ls=":", color="0.5")
    free = result.diagnostics.get("free_profile")
    if free is not None:
        ax.stairs(free["impedance"] / 1e3, edges, baseline=None, ls="--", label="free profile")
    z = result.impedance if bounds is None else np.concatenate([result.impedance, bounds[0], bounds[1]])
    if log if log is not None else z.max() / z.min() > 100:
        ax.set_yscale("log")
    ax.set_xlabel("distance from impact face s [m]")
    ax.set_ylabel("impedance Z [kN s/m]")
    ax.legend(loc="best")
    return ax


def plot_convergence(result: Any, ax: Optional[Any] = None):
    """Misfit (or efficiency) after every L-BFGS-B iteration, one line per run, labelled with what the run was.

    There are more runs than starts: each start is continued from a coarse profile (few constant levels) to
    the free one, one run per stage; the best starts then continue in a run of their own; basin hops and the
    re-optimisation of a stepped striker add runs too. The title says so."""
    _check(result)
    _, ax = new_axes(ax)
    labels = result.diagnostics.get("run_labels") or []
    for i, h in enumerate(result.convergence):
        if h:
            y = np.asarray(h)
            label = labels[i] if i < len(labels) else f"run {i + 1}"
            if result.objective == "match":
                ax.semilogy(np.arange(1, y.size + 1), np.sqrt(np.maximum(y, 1e-300)), label=label)
            else:
                ax.plot(np.arange(1, y.size + 1), -y, label=label)
    ax.set_xlabel("iteration")
    ax.set_ylabel("misfit [-]" if result.objective == "match" else "efficiency [-]")
    runs, starts = len(result.convergence), len(result.diagnostics.get("starts") or [])
    if runs > starts > 0:
        ax.set_title(f"{runs} runs from {starts} starts: each start runs coarse to fine (one run per stage),\n"
                     f"the best continue in new runs", fontsize="medium")
    elif runs:
        ax.set_title(f"{runs} run(s)", fontsize="medium")
    if any(result.convergence):
        ax.legend(loc="best", fontsize="x-small", ncol=2 if runs > 8 else 1)
    else:
        ax.text(0.5, 0.5, "no iterations (exact striker)", transform=ax.transAxes, ha="center")
    return ax


def plot_incident_wave(result: Any, loading_stiffness: float, rod_impedance: float, ax: Optional[Any] = None):
    """The incident wave at the bit of an efficiency design beside the wave f0 exp(k t / Z) that an elastic
    rock of stiffness k under a rod of impedance Z absorbs without reflection (f0 = the design's first
    incident value; thesis eq. 4.29, Lundberg and Collet), over the striker's pulse (2 n steps from the wave's
    arrival)."""
    _check(result)
    if result.location is None or result.quantity != "incident":
        raise ValueError("result: needs a design whose run records the incident wave (ri.EfficiencyObjective(), or "
                         "ri.MatchObjective(target, position=..., quantity='incident'))")
    _, ax = new_axes(ax)
    d = result.location.node
    end = min(2 * result.n_elements, result.time.size - d)      # the striker's pulse: 2 n steps
    y = result.achieved[d:d + end]
    t = result.time[d:d + end] - result.time[d]
    ax.step(t * 1e3, y / 1e3, where="post", label="incident wave of the design")
    ax.plot(t * 1e3, y[0] * np.exp(loading_stiffness * t / rod_impedance) / 1e3, "--",
            label=r"$f_0\,e^{k t / Z}$ (no reflection)")
    ax.set_xlabel("time from arrival at the bit [ms]")
    ax.set_ylabel("force [kN]")
    ax.set_title(f"Incident wave at the bit vs the reflection-free exponential (efficiency {result.efficiency:.4g})")
    ax.legend(loc="best")
    return ax
