"""Fields along x: snapshots of displacement and force (thesis Figs. 3.6, 3.8) and the Lagrangian x-t diagram."""

from __future__ import annotations

from typing import Any, Optional, Sequence

import numpy as np

from .._validate import positive
from ._common import check_result, junction_positions, nearest_snapshots, new_axes, time_scale


def _rod_slices(result: Any):
    lat = result.lattice
    for r in range(lat.n_rods):
        a, b = int(lat.rod_start[r]), int(lat.rod_start[r + 1])
        n0 = lat.node_index(r, 0)
        yield r, slice(a, b), slice(n0, n0 + (b - a) + 1)


def plot_snapshots(result: Any, times: Optional[Sequence[float]] = None, axes: Any = None):
    """Displacement u(x) (mm, left column) and normal force N(x) (kN, right column) at the recorded snapshots
    nearest to ``times`` (s; default three spread over the run), one row per time, as in thesis Figs. 3.6 and
    3.8. Each rod is drawn separately, so a displacement jump at a contact face shows the separation; contact
    faces are dashed. ``times`` must lie within the recorded snapshot times (to one time step). ``axes``: one row
    of two Axes per distinct snapshot shown, or ``None``. Draws on several Axes, so it returns the Figure."""
    check_result(result)
    s = result.snapshots
    if s is None:
        raise ValueError("plot_snapshots: the result holds no field snapshots; record some with "
                         "Outputs(snapshot_times=...) or Outputs(snapshot_every=...) ([output] in a model file)")
    idx = nearest_snapshots(s.time, times, result.dt, "times")
    if axes is None:
        fig, axes = new_axes(None, nrows=len(idx), ncols=2, figsize=(9.0, 2.3 * len(idx) + 0.6), sharex=True)
    else:
        flat = np.ravel(np.asarray(axes, dtype=object))
        if flat.size != 2 * len(idx) or not all(hasattr(a, "plot") for a in flat):
            raise ValueError(f"axes: need {2 * len(idx)} Axes ({len(idx)} row(s) of 2: displacement, force), "
                             f"got {flat.size} object(s)")
        fig = flat[0].figure
    axes = np.asarray(axes, dtype=object).reshape(len(idx), 2)
    faces = junction_positions(result)
    for row, k in enumerate(idx):
        ax_u, ax_n = axes[row]
        for r, el, nd in _rod_slices(result):
            line, = ax_u.plot(s.node_x[nd], s.displacement[nd, k] * 1e3, lw=1.2)
            ax_n.stairs(s.force[el, k] / 1e3, s.node_x[nd], lw=1.2, color=line.get_color(), baseline=None)
        for ax in (ax_u, ax_n):
            for xf in faces:
                ax.axvline(xf, color="0.5", ls="--", lw=0.8)
            ax.axhline(0.0, color="0.8", lw=0.6)
        tk, unit = time_scale(float(s.time[-1]))
        ax_u.set_ylabel("displacement u [mm]")
        ax_n.set_ylabel("normal force N [kN]")
        ax_u.set_title(f"t = {s.time[k] * tk:.4g} {unit}", fontsize="medium", loc="left")
    axes[-1, 0].set_xlabel("x [m]")
    axes[-1, 1].set_xlabel("x [m]")
    fig.suptitle("Displacement (left) and normal force (right, tension > 0)")
    return fig


def _grid(result: Any):
    """Cell edges in x (with NaN-cells in initial gaps) and the element of every cell."""
    lat = result.lattice
    edges: list[float] = []
    cell_el: list[int] = []
    for r, el, nd in _rod_slices(result):
        nodes = lat.node_x[nd]
        if edges and nodes[0] > edges[-1] + 1e-12:
            cell_el.append(-1)            # a gap between rods
        elif edges:
            edges.pop()
        edges.extend(nodes.tolist())
        cell_el.extend(range(el.start, el.stop))
    return np.array(edges), np.array(cell_el)


def _check_cmap(cmap: Any) -> None:
    from matplotlib import colormaps
    from matplotlib.colors import Colormap

    if isinstance(cmap, Colormap):
        return
    if not isinstance(cmap, str) or cmap not in colormaps:
        raise ValueError(f"cmap: must be a matplotlib colormap or its name (e.g. 'RdBu_r', 'coolwarm', 'seismic'), "
                         f"got {cmap!r}")


def plot_xt(result: Any, ax: Any = None, *, cmap: str = "RdBu_r", limit: Optional[float] = None):
    """The Lagrangian x-t diagram: the normal force (colour, kN; red tension, blue compression) over the
    reference position x and time, from the recorded snapshots. Wave fronts are straight lines of slope 1/c;
    contact faces are dashed. ``limit``: colour scale +-limit in kN (default: the largest |N|). Returns the Axes
    of the diagram (the colour bar is a second Axes of ``ax.figure``)."""
    check_result(result)
    if limit is not None:
        limit = positive("limit", limit, "kN")
    _check_cmap(cmap)
    s = result.snapshots
    if s is None or s.time.size < 2:
        raise ValueError("plot_xt: needs at least two field snapshots; record them with Outputs(snapshot_every=...) or "
                         "snapshot_count ([output] in a model file)")
    fig, ax = new_axes(ax, figsize=(7.0, 5.0))
    order = np.argsort(s.time)
    t = s.time[order]
    x_edges, cell_el = _grid(result)
    values = np.full((t.size, cell_el.size), np.nan)
    ok = cell_el >= 0
    values[:, ok] = s.force[cell_el[ok]][:, order].T / 1e3
    dtl = np.diff(t)
    t_edges = np.concatenate([t, [t[-1] + (dtl[-1] if dtl.size else result.dt)]])
    k, unit = time_scale(float(t_edges[-1]))
    vmax = limit if limit is not None else float(np.nanmax(np.abs(values))) or 1.0
    mesh = ax.pcolormesh(x_edges, t_edges * k, np.ma.masked_invalid(values), cmap=cmap, vmin=-vmax, vmax=vmax,
                         shading="flat", rasterized=True)
    for xf in junction_positions(result):
        ax.axvline(xf, color="k", ls="--", lw=0.8)
    fig.colorbar(mesh, ax=ax, label="normal force N [kN] (tension > 0)")
    ax.set_xlabel("x [m] (reference position)")
    ax.set_ylabel(f"time [{unit}]")
    ax.set_title("x-t diagram of the normal force")
    return ax
