"""Warnings for geometry outside 1D-rod plausibility, the usual sign of a unit slip (bare numbers are SI).

``diameter = 20`` meant as mm is taken as 20 m; the run is valid arithmetic but not a rod. Such inputs are kept
(bare numbers stay SI) and warned about with the likely intended unit:

* a cross-section wider than 1 m (equivalent diameter sqrt(4 A / pi));
* a rod wider than it is long (the 1D theory of thesis ch. 2 needs length >> diameter);
* a striker (a rod that moves at t = 0) heavier than a tonne.

Impedance-level rods (:meth:`Rod.from_impedance`) are taken as given and not checked. The warnings are
:class:`PlausibilityWarning` objects that carry the offending key (``segments[0].diameter``) so that model files
can re-issue them under their key path (``rods[0].segments[0].diameter``).
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING

import numpy as np

from .._validate import caller_stacklevel

if TYPE_CHECKING:
    from .rod import Rod

#: Thresholds: widest plausible cross-section (equivalent diameter, m) and heaviest plausible striker (kg).
MAX_DIAMETER = 1.0
MAX_STRIKER_MASS = 1000.0


class PlausibilityWarning(UserWarning):
    """Input outside 1D-rod plausibility. ``key`` names the quantity relative to the object that was built
    (``segments[0].diameter``, or ``rods[0]`` for a system), ``text`` says what is wrong and what was likely meant."""

    def __init__(self, key: str, text: str, owner: str = "") -> None:
        super().__init__(f"{owner}{key} {text}")
        self.key, self.text = key, text


def warn(key: str, text: str, owner: str = "") -> None:
    """Issue a :class:`PlausibilityWarning` located at the user's code (``owner``: a prefix such as ``"Rod."``)."""
    warnings.warn(PlausibilityWarning(key, text, owner), stacklevel=caller_stacklevel())


def _widest(segment) -> tuple[str, float, bool]:
    """The key of a segment's widest cross-section, its equivalent diameter (m) and whether the key is a
    diameter (else an area)."""
    for names in (("diameter",), ("outer_diameter",), ("diameter_start", "diameter_end")):
        if all(hasattr(segment, n) for n in names):
            values = [float(getattr(segment, n)) for n in names]
            i = int(np.argmax(values))
            return names[i], values[i], True
    if getattr(segment, "kind", None) == "diameter":
        return "diameter", float(np.max(segment.values)), True
    s = np.linspace(0.0, segment.length, 65)
    d = float(np.max(segment.equivalent_diameter(s)))
    key = "area_start" if hasattr(segment, "area_start") and not hasattr(segment, "area_end") else "area"
    if hasattr(segment, "area_end"):
        key = "area_start" if segment.area_start >= segment.area_end else "area_end"
    return key, d, False


def check_rod(rod: "Rod") -> bool:
    """Warn about a geometry-based rod wider than 1 m or wider than long; True if a warning was issued."""
    if rod.native is not None:
        return False
    warned = False
    widest = 0.0
    for i, seg in enumerate(rod.segments):
        key, d, is_diameter = _widest(seg)
        widest = max(widest, d)
        if d > MAX_DIAMETER:
            warned = True
            if is_diameter:
                warn(f"segments[{i}].{key}", f"= {d:.6g} m: did you mean {d:.6g} mm? bare numbers are SI (m); a rod "
                     f"wider than {MAX_DIAMETER:g} m is outside 1D-rod plausibility", "Rod.")
            else:
                area = 0.25 * math.pi * d * d
                warn(f"segments[{i}].{key}", f"gives a cross-section of {area:.6g} m^2 ({d:.4g} m wide): did you "
                     f"mean mm^2? bare numbers are SI (m^2)", "Rod.")
    if not warned and widest > rod.length:
        warned = True
        warn("length", f"= {rod.length:.6g} m is smaller than the rod's diameter {widest:.6g} m, outside 1D-rod "
             f"theory (length >> diameter): check the units; bare numbers are SI (m), e.g. \"{rod.length:.6g} mm\" "
             f"must be written with its unit", "Rod.")
    return warned


def check_strikers(rods, velocities) -> None:
    """Warn about a moving geometry-based rod (a striker) heavier than a tonne, unless its geometry was
    already warned about."""
    for i, (rod, v) in enumerate(zip(rods, velocities)):
        if v != 0.0 and rod.native is None and not getattr(rod, "_implausible", False) and rod.mass > MAX_STRIKER_MASS:
            warn(f"rods[{i}]", f"is a striker (initial velocity {v:.6g} m/s) of {rod.mass:.6g} kg, heavier than "
                 f"{MAX_STRIKER_MASS / 1000:g} t: check the units of its dimensions (bare numbers are SI: m, not mm)")


class KeyPath:
    """Context manager for model files: plausibility warnings raised inside are re-issued under the key path
    ``path`` (``rods[0]`` + ``segments[0].diameter``); other warnings pass through unchanged."""

    def __init__(self, path: str) -> None:
        self.path = path
        self._catcher = warnings.catch_warnings(record=True)

    def __enter__(self) -> "KeyPath":
        self._caught = self._catcher.__enter__()
        warnings.simplefilter("always")
        return self

    def __exit__(self, *exc) -> None:
        self._catcher.__exit__(*exc)
        for w in self._caught:
            if isinstance(w.message, PlausibilityWarning):
                key = w.message.key if w.message.key.startswith("rods[") else f"{self.path}.{w.message.key}"
                warnings.warn(PlausibilityWarning(key, w.message.text), stacklevel=caller_stacklevel())
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
