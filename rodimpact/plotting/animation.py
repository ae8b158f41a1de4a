"""Animation of the normal force N(x, t) as a GIF (matplotlib's PillowWriter; needs pillow)."""

from __future__ import annotations

import importlib.util
from pathlib import Path
from typing import Any

import numpy as np

from .._validate import finite
from ._common import check_int, check_output_file, check_result, junction_positions, time_scale

#: Frame rates a GIF can hold: its frame delays are whole hundredths of a second, at most 655.35 s.
MIN_FPS, MAX_FPS = 0.01, 100.0


def pillow_available() -> bool:
    """True when pillow (needed for GIF writing) is installed."""
    return importlib.util.find_spec("PIL") is not None


def animate_force(result: Any, path: str | Path, *, fps: int = 15, max_frames: int = 150,
                  overwrite: bool = False) -> Path:
    """Write a GIF of N(x) over the recorded snapshots (at most ``max_frames`` >= 2 evenly chosen) to ``path``
    (an existing file is refused unless ``overwrite=True``) at ``fps`` frames per second (0.01 to 100).

    Raises :class:`ImportError` with a clear message when pillow is not installed.
    """
    check_result(result)
    fps = finite("fps", fps, "frames per second")
    if not MIN_FPS <= fps <= MAX_FPS:
        raise ValueError(f"fps: must lie in [{MIN_FPS}, {MAX_FPS:g}] frames per second (GIF frame delays are whole "
                         f"hundredths of a second, at most 655 s), got {fps!r}")
    max_frames = check_int("max_frames", max_frames, 2)
    check_output_file(Path(path))
    if Path(path).exists() and not overwrite:
        raise FileExistsError(f"{path}: exists; choose another file name or pass overwrite=True to replace it")
    if not pillow_available():
        raise ImportError("animate_force: writing a GIF needs pillow (pip install pillow); skipped")
    from matplotlib.animation import FuncAnimation, PillowWriter
    from matplotlib.figure import Figure

    s = result.snapshots
    if s is None or s.time.size < 2:
        raise ValueError("animate_force: needs at least two field snapshots (Outputs(snapshot_every=...), or "
                         "snapshot_count in a model file)")
    frames = np.unique(np.linspace(0, s.time.size - 1, min(max_frames, s.time.size)).round().astype(int))
    lat = result.lattice
    fig = Figure(figsize=(7.0, 3.5), layout="constrained")
    ax = fig.subplots()
    lim = float(np.max(np.abs(s.force))) / 1e3 or 1.0
    lines = []
    for r in range(lat.n_rods):
        a, b = int(lat.rod_start[r]), int(lat.rod_start[r + 1])
        n0 = lat.node_index(r, 0)
        nodes = lat.node_x[n0:n0 + (b - a) + 1]
        xs = np.repeat(nodes, 2)[1:-1]
        line, = ax.plot(xs, np.zeros_like(xs), lw=1.3)
        lines.append((line, a, b))
    for xf in junction_positions(result):
        ax.axvline(xf, color="0.5", ls="--", lw=0.8)
    ax.set_ylim(-1.05 * lim, 1.05 * lim)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("normal force N [kN] (tension > 0)")
    k, unit = time_scale(float(s.time[-1]))
    title = ax.set_title("")

    def draw(i: int):
        f = frames[i]
        for line, a, b in lines:
            line.set_ydata(np.repeat(s.force[a:b, f], 2) / 1e3)
        title.set_text(f"t = {s.time[f] * k:.4g} {unit}")
        return [ln for ln, _, _ in lines] + [title]

    anim = FuncAnimation(fig, draw, frames=len(frames), blit=False)
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    anim.save(str(out), writer=PillowWriter(fps=fps))
    return out
