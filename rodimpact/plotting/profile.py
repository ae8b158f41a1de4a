"""The system along x: impedance and equivalent diameter of every rod, and the lattice that represents it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._common import check_int, format_length, new_axes, rod_label

#: A rod or segment shorter than this fraction of the drawn length would be a few pixels wide: it is drawn this wide
#: (centred on its true position) and labelled with its true length.
MIN_DRAWN_FRACTION = 0.025
#: At most this many short pieces are labelled (a tabulated profile may have many short ones side by side).
MAX_MARKED = 6


def plot_profile(obj: Any, axes: Any = None, *, samples: int = 400):
    """Impedance Z(x) (kN s/m, top) and equivalent diameter sqrt(4A/pi) (mm, bottom) along the global x.

    ``obj`` is a :class:`~rodimpact.System` or a result (then the lattice impedance, one value per
    equal-travel-time element, is drawn as steps over the true profile). ``axes``: two Axes or ``None``.
    Contact faces are marked by dashed lines. A rod or segment shorter than :data:`MIN_DRAWN_FRACTION` of the
    whole length (a 3 mm specimen between 1 m bars) is drawn that wide as a thick bar at its value, centred on
    its position, and labelled with its true length. The legend sits beside the impedance Axes, outside the data.
    ``samples``: points per rod for the true profile (2 to 100000). Draws on two Axes, so it returns the Figure
    (``fig.axes[:2]`` are the impedance and diameter Axes).
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
    span = float(offsets[-1] + system.rods[-1].length - offsets[0])
    short = _short_pieces(system, offsets, MIN_DRAWN_FRACTION * span)
    colours = []
    for i, rod in enumerate(system.rods):
        bounds = rod.segment_bounds
        xs = np.unique(np.concatenate([np.linspace(0.0, rod.length, samples), bounds,
                                       np.nextafter(bounds[1:-1], -np.inf)]))
        z = rod.impedance(xs)
        a = rod.area(xs)
        line, = ax_z.plot(offsets[i] + xs, np.asarray(z) / 1e3, lw=1.4, label=rod_label(system, i))
        colours.append(line.get_color())
        ax_d.plot(offsets[i] + xs, np.sqrt(4.0 * np.asarray(a) / math.pi) * 1e3, lw=1.4, color=line.get_color())
        if i > 0:
            for ax in (ax_z, ax_d):
                ax.axvline(offsets[i], color="0.5", ls="--", lw=0.8)
    for n, (i, a, b, whole_rod) in enumerate(short[:MAX_MARKED]):
        colour = colours[i]
        rod = system.rods[i]
        mid = 0.5 * (a + b)
        width = _round_width(MIN_DRAWN_FRACTION * span)
        x0, x1 = offsets[i] + mid - 0.5 * width, offsets[i] + mid + 0.5 * width
        z = float(np.asarray(rod.impedance(np.array([mid])))[0]) / 1e3
        d = math.sqrt(4.0 * float(np.asarray(rod.area(np.array([mid])))[0]) / math.pi) * 1e3
        for ax, y in ((ax_z, z), (ax_d, d)):
            ax.plot([x0, x1], [y, y], color=colour, lw=4.0, solid_capstyle="butt", zorder=4)
        what = rod_label(system, i) if whole_rod else f"{rod_label(system, i)}, segment"
        ax_d.annotate(f"{what}: {format_length(b - a)} long (drawn {format_length(width)} wide)",
                      xy=(offsets[i] + mid, d), xytext=(0, 14 + 12 * (n % 2)), textcoords="offset points",
                      ha="center", fontsize="x-small", color=colour, zorder=5,
                      bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85),
                      arrowprops=dict(arrowstyle="-", color=colour, lw=0.6))
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
    # beside the Axes: a legend inside covered the profile of long rods
    ax_z.legend(handles, labels, fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    ax_z.set_title("Impedance and diameter along the rods")
    return fig


def _round_width(w: float) -> float:
    """``w`` rounded to one significant digit (a drawn width is no measurement)."""
    if w <= 0:
        return w
    k = 10.0 ** math.floor(math.log10(w))
    return round(w / k) * k


def _short_pieces(system: Any, offsets: Any, min_length: float) -> list[tuple[int, float, float, bool]]:
    """The rods, and the segments of longer rods, shorter than ``min_length``: (rod index, start, end from the
    rod's left end in m, whether it is the whole rod)."""
    out = []
    for i, rod in enumerate(system.rods):
        if rod.length < min_length:
            out.append((i, 0.0, float(rod.length), True))
            continue
        bounds = np.asarray(rod.segment_bounds, dtype=float)
        for a, b in zip(bounds[:-1], bounds[1:]):
            if b - a < min_length:
                out.append((i, float(a), float(b), False))
    return out
