"""Studies built on blows: the bearing graph (ultimate capacity during driving against blow count, with the
driving stresses), drivability (blow count, stresses and transferred energy against penetration over a soil
profile) and the inspector's chart (impact velocity or stroke against blow count at one capacity).

Each point is one blow (:func:`~rodimpact.pile.drive_blow`) from the same initial state (at rest, no residual
stress), run one after another with progress on stderr (a bar on a terminal, else a line at every 10 %; by default
when more than 10 points run on a terminal). The blows of the bearing graph and of drivability differ only in
their soil and share one lattice (:func:`~rodimpact.pile.blow.drive_blow_batch`); each costs one run of the
compiled kernels, which is nearly all of its time (the soil node solves most: docs/performance.md). The batched
solver (:func:`rodimpact.simulate_batch`) varies strikers and takes no lumped heads or soil; on one core a single
compiled call over the capacities would save only the Python set-up of each blow (about 1 ms of 12 ms at the
default 50 pile elements).
"""

from __future__ import annotations

import dataclasses
import math
import sys
from dataclasses import dataclass
from typing import Any, Callable, Iterable, Optional, Sequence

import numpy as np

from .._validate import finite_array
from ..direct.guards import Progress
from ..rods.rod import Rod
from .blow import PILE_ELEMENTS, Blow, drive_blow, drive_blow_batch
from .driving import DrivingSystem, impact_velocity
from .soil import CapacitySoil, SoilProfile, SoilResistance

#: the per-blow numbers every study tabulates (name -> unit)
COLUMNS = {"permanent_set": "m", "blows_per_quarter_metre": "1/0.25 m", "max_compression": "Pa",
           "max_tension": "Pa", "emx": "J"}


@dataclass(frozen=True, repr=False)
class BlowTable:
    """Per-blow numbers of a study, one entry per point of ``x`` (the study's variable, in ``x_name`` / ``x_unit``):
    the permanent set (m), blows per 0.25 m (``inf`` at refusal), the largest compressive and tensile stresses
    along the pile (Pa, >= 0) with their depths (m from the head), the largest transferred energy EMX (J) and the
    soil resistance during driving (N) of each blow."""

    x_name: str
    x_unit: str
    x: np.ndarray
    permanent_set: np.ndarray
    blows_per_quarter_metre: np.ndarray
    max_compression: np.ndarray
    compression_depth: np.ndarray
    max_tension: np.ndarray
    tension_depth: np.ndarray
    emx: np.ndarray
    resistance: np.ndarray

    def __repr__(self) -> str:
        return f"BlowTable({self.x.size} blows over {self.x_name} {self.x.min():.4g} .. {self.x.max():.4g} {self.x_unit})"

    @property
    def blows_per_foot(self) -> np.ndarray:
        """Blows per foot (0.3048 m / set)."""
        return self.blows_per_quarter_metre * (0.3048 / 0.25)


def _run(x_name: str, x_unit: str, xs: np.ndarray, blows: Iterable[Blow], progress: Optional[bool],
         desc: str) -> BlowTable:
    """The table of the ``blows``, one per point of ``xs`` (run as they are taken), with progress on stderr."""
    if progress is None:
        progress = sys.stderr.isatty() and xs.size > 10
    bar = Progress(xs.size, unit="blow", desc=desc) if progress else None
    rows = []
    try:
        for b in blows:
            c, t = b.envelope.max_compression, b.envelope.max_tension
            rows.append((b.permanent_set, b.blows_per_quarter_metre, c[0], c[1], t[0], t[1], b.emx, b.soil.total))
            if bar is not None:
                bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    cols = np.array(rows, dtype=float).T
    return BlowTable(x_name, x_unit, xs, *cols)


def pile_edges(pile: Rod, penetration: float) -> np.ndarray:
    """Depth edges (m below ground) of shaft segments about as long as the pile's default lattice elements."""
    n = max(1, math.ceil(PILE_ELEMENTS * penetration / pile.length))
    return np.linspace(0.0, penetration, n + 1)


def bearing_graph(pile: Rod, driving: DrivingSystem, soil: CapacitySoil, capacities: Sequence[float],
                  penetration: float, *, progress: Optional[bool] = None, **blow_options: Any) -> BlowTable:
    """Blow count and stresses for each ultimate capacity during driving in ``capacities`` (N) of ``soil`` (its
    shaft share and distribution kept; a custom distribution scaled with the capacity), the toe at
    ``penetration`` (m). ``blow_options``: :func:`~rodimpact.pile.drive_blow`'s keywords."""
    caps = finite_array("capacities", capacities, unit="N")
    if np.any(caps <= 0):
        raise ValueError(f"capacities: must be > 0 N, got {caps.min():.6g} N")
    edges = pile_edges(pile, penetration)

    def resistance(capacity: float) -> SoilResistance:
        scaled = dataclasses.replace(soil, capacity=capacity, shaft_resistances=None if soil.shaft_resistances is None
                                     else np.asarray(soil.shaft_resistances) * capacity / soil.capacity)
        return scaled.resistance(penetration, edges)

    return _run("capacity", "N", caps, drive_blow_batch(pile, driving, (resistance(float(c)) for c in caps),
                                                        **blow_options), progress, "bearing graph")


def drivability(pile: Rod, driving: DrivingSystem, profile: SoilProfile, depths: Sequence[float], *,
                progress: Optional[bool] = None, **blow_options: Any) -> BlowTable:
    """Blow count, stresses and EMX with the toe at each of ``depths`` (m below ground, <= the pile's length) in
    the layered ``profile`` (resistance during driving: the static values divided by the layers' setup
    factors)."""
    zs = finite_array("depths", depths, unit="m")
    if profile.bottoms[-1] > pile.length * (1 + 1e-12):
        raise ValueError(f"profile.layers[{len(profile.layers) - 1}].bottom: the profile reaches "
                         f"{profile.bottoms[-1]:.6g} m, deeper than the pile ({pile.length:.6g} m long) can be driven")
    if np.any(zs <= 0) or np.any(zs > pile.length * (1 + 1e-12)):
        bad = zs[(zs <= 0) | (zs > pile.length * (1 + 1e-12))][0]
        raise ValueError(f"depths: must lie in (0, {pile.length:.6g}] m (the pile's length), got {bad:.6g} m")
    return _run("depth", "m", zs, drive_blow_batch(pile, driving, (profile.resistance(float(d)) for d in zs),
                                                   **blow_options), progress, "drivability")


def inspector_chart(pile: Rod, driving: DrivingSystem, soil: SoilResistance, *,
                    velocities: Optional[Sequence[float]] = None, strokes: Optional[Sequence[float]] = None,
                    efficiency: Any = None, progress: Optional[bool] = None, **blow_options: Any) -> BlowTable:
    """Blow count against the ram's impact ``velocities`` (m/s) or ``strokes`` (m, with the hammer
    ``efficiency``: V = sqrt(2 g eta h)) for one ``soil``: the chart an inspector reads the blow count needed
    at the observed stroke from. The rest of ``driving`` is kept."""
    if (velocities is None) == (strokes is None):
        raise ValueError("velocities: give exactly one of velocities or strokes (with efficiency)")
    if velocities is not None:
        xs, name, unit = finite_array("velocities", velocities, unit="m/s"), "impact velocity", "m/s"
        speed: Callable[[float], float] = lambda v: v
    else:
        xs, name, unit = finite_array("strokes", strokes, unit="m"), "stroke", "m"
        impact_velocity(float(xs[0]), efficiency)                      # refuses a missing efficiency up front
        speed = lambda h: impact_velocity(h, efficiency)
    return _run(name, unit, xs, (drive_blow(pile, dataclasses.replace(driving, impact_velocity=speed(float(x))),
                                            soil, **blow_options) for x in xs), progress, "inspector chart")
