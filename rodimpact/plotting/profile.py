"""The system along x: impedance and equivalent diameter of every rod, and the lattice that represents it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._common import check_int, new_axes, rod_label


def plot_profile(obj: Any, axes: Any = None, *, samples: int = 400):
    """Impedance Z(x) (kN s/m, top) and equivalent diameter sqrt(4A/pi) (mm, bottom) along the global x.

    ``obj`` is a :class:`~rodimpact.System` or a result (then the lattice impedance, one value per
    equal-travel-time element, is drawn as steps over the true profile). ``axes``: two Axes or ``None``.
    Contact faces are marked by dashed lines. ``samples``: points per rod for the true profile (2 to 100000).
    Draws on two Axes, so it returns the Figure (``fig.axes[:2]`` are the impedance and diameter Axes).
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import StepPatch

    from ..direct.result import SimulationResult
    from ..rods.system import System

    if not isinstance(obj, (System, SimulationResult)):
        raise TypeError(f"obj: must be a System or a SimulationResult (from rodimpact.simulate or rodimpact.io.load), "
                        f"got {type(obj).__name__}")
    samples = check_int("samples", samples, 2, 100_000)
    system = getattr(obj, "system", obj)
    lattice = getattr(obj, "lattice", None)
    if system is None:
        raise ValueError("plot_profile: the result carries no system (it was loaded without model.toml)")
    if axes is None:
        fig, (ax_z, ax_d) = new_axes(None, nrows=2, figsize=(7.0, 5.0), sharex=True)
    else:
        flat = np.ravel(np.asarray(axes, dtype=object))
        if flat.size != 2 or not all(hasattr(a, "plot") for a in flat):
            raise ValueError(f"axes: need two Axes (impedance, diameter) or None, got {flat.size} object(s)")
        ax_z, ax_d = flat
        fig = ax_z.figure
    offsets = system.rod_offsets()
    for i, rod in enumerate(system.rods):
        bounds = rod.segment_bounds
        xs = np.unique(np.concatenate([np.linspace(0.0, rod.length, samples), bounds,
                                       np.nextafter(bounds[1:-1], -np.inf)]))
        z = rod.impedance(xs)
        a = rod.area(xs)
        line, = ax_z.plot(offsets[i] + xs, np.asarray(z) / 1e3, lw=1.4, label=rod_label(system, i))
        ax_d.plot(offsets[i] + xs, np.sqrt(4.0 * np.asarray(a) / math.pi) * 1e3, lw=1.4, color=line.get_color())
        if i > 0:
            for ax in (ax_z, ax_d):
                ax.axvline(offsets[i], color="0.5", ls="--", lw=0.8)
    if lattice is not None:
        # on top of the true profile and dotted, so that it stays visible where both agree
        style = dict(color="k", lw=1.2, ls=":", zorder=3)
        for r in range(lattice.n_rods):
            a, b = lattice.rod_start[r], lattice.rod_start[r + 1]
            nodes = lattice.node_x[lattice.node_index(r, 0): lattice.node_index(r, 0) + (b - a) + 1]
            ax_z.stairs(lattice.impedance[a:b] / 1e3, nodes, baseline=None,
                        label="lattice (equal travel time)" if r == 0 else None, **style)
    ax_z.set_ylabel("impedance [kN s/m]")
    ax_z.set_ylim(bottom=0.0)
    ax_d.set_ylabel("equivalent diameter [mm]")
    ax_d.set_ylim(bottom=0.0)
    ax_d.set_xlabel("x [m]")
    handles, labels = ax_z.get_legend_handles_labels()
    # a line in the lattice's own style instead of the default patch handle of a step patch
    handles = [Line2D([], [], color="k", lw=1.2, ls=":") if isinstance(h, StepPatch) else h for h in handles]
    ax_z.legend(handles, labels, fontsize="small")
    ax_z.set_title("Profile")
    return fig
