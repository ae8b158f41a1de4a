"""The strain-rate plateau of a specimen's history: where a Kolsky-bar test loads the specimen, its mean strain
rate there, and how flat the rate is.

One rule, so that the summary of ``rodimpact shpb predict``, its strain-rate plot and Python users report the same
numbers: the plateau is the contiguous stretch of samples around the specimen's largest force in which the force
stays at or above ``level`` times that force (by default half of it). It leaves out the elastic rise, whose rate
spikes while the specimen is still elastic, and the unloading, where the rate is not the test's. Force and rate are
positive in compression (the SHPB habit, as :class:`~rodimpact.shpb.KolskyPrediction` gives them).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from .._validate import finite_array


@dataclass(frozen=True)
class RatePlateau:
    """A strain-rate plateau: its ``start`` and ``end`` (s, the first and last sample in it), the ``mean`` strain
    rate over its samples (1/s) and its ``flatness``, the largest relative deviation |rate / mean - 1| there."""

    start: float
    end: float
    mean: float
    flatness: float


def rate_plateau(time: np.ndarray, force: np.ndarray, rate: np.ndarray, level: float = 0.5) -> Optional[RatePlateau]:
    """The plateau of a specimen's strain-rate history ``rate`` (1/s) with its ``force`` (N), both compression
    positive, sampled at ``time`` (s): the contiguous samples around the largest force where the force is at least
    ``level`` (0 < level < 1) times it. ``None`` when the specimen never carries a compressive force."""
    t = finite_array("time", time)
    f = finite_array("force", force)
    r = finite_array("rate", rate)
    if not t.shape == f.shape == r.shape:
        raise ValueError(f"force, rate: need one value per time ({t.size}), got {f.size} and {r.size}")
    if not 0.0 < level < 1.0:
        raise ValueError(f"level: must lie between 0 and 1, got {level!r}")
    if not f.max() > 0.0:
        return None
    peak = int(np.argmax(f))
    below = f < level * f[peak]
    first = peak - int(np.argmax(below[peak::-1])) + 1 if below[:peak].any() else 0
    last = peak + int(np.argmax(below[peak:])) - 1 if below[peak:].any() else f.size - 1
    inside = r[first:last + 1]
    mean = float(inside.mean())
    flatness = float(np.abs(inside / mean - 1.0).max()) if mean > 0.0 else float("inf")
    return RatePlateau(float(t[first]), float(t[last]), mean, flatness)
