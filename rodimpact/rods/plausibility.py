"""Warnings for geometry that is most likely a unit slip (bare numbers are SI).

``diameter = 20`` meant as mm is taken as 20 m; the run is valid arithmetic but not a rod. Such inputs are kept
(bare numbers stay SI) and warned about with the likely intended unit. A slip is a factor of 1000 (mm read as
m), so the rules sit beyond the largest real parts of the applications served -- split-Hopkinson bars and
specimens (a few mm), drilling pistons and rods, pile rams, cushions and piles -- and below what a slip makes of
ordinary parts:

* a cross-section wider than :data:`MAX_DIAMETER` = 12 m (equivalent diameter sqrt(4 A / pi)): wider than the
  widest driven pile (offshore monopiles reach about 11 m); a bar of 12.7 mm written as ``12.7`` is 12.7 m;
* a cross-section wider than :data:`DISC_DIAMETER` = 1 m *and* more than :data:`DISC_RATIO` = 10 times wider than
  the rod is long: a thin disc no hammer, anvil, cushion or pile is (a 0.1 m cushion on a 0.4 m pile is 0.22
  times as long as wide; a 1.4 m cylinder pile's cushion is thicker than 0.15 m), but a bar of 20 mm and less
  than 20 m written as ``diameter = 20`` is;
* a striker (a rod that moves at t = 0) heavier than :data:`MAX_STRIKER_MASS` = 1000 t, five times the heaviest
  pile-hammer ram in service (about 200 t): every dimension written in mm multiplies the mass by 1e9;
* a rod moving faster than a tenth of its bar wave speed (:data:`MAX_SPEED_RATIO`; 518 m/s for steel): an impact
  strain v/(2c) above 5 %, far beyond any elastic rod (a velocity of 3e8 m/s is 58,000 times the steel wave speed).

Short, thick parts (a 3.204 mm x 6 mm SHPB specimen, a cushion) and heavy rams are not warned about: 1D theory
needs length >> diameter for the waves, but that is a modelling choice the user makes, not a unit mistake. From
model files, a value written with its unit (``"3.204 mm"``) is never the subject of a warning or a suggested fix
(:class:`KeyPath` drops those), since its unit cannot have slipped.

Impedance-level rods (:meth:`Rod.from_impedance`) are taken as given and not checked. The warnings are
:class:`PlausibilityWarning` objects that carry the offending key (``segments[0].diameter``) so that model files
can re-issue them under their key path (``rods[0].segments[0].diameter``).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from typing import TYPE_CHECKING, Callable, Optional

import numpy as np

from .._validate import caller_stacklevel

if TYPE_CHECKING:
    from .rod import Rod

#: Widest plausible cross-section (equivalent diameter, m): beyond the widest driven pile (about 11 m).
MAX_DIAMETER = 12.0
#: A cross-section wider than DISC_DIAMETER (m) and DISC_RATIO times wider than its rod is long is a thin disc.
DISC_DIAMETER = 1.0
DISC_RATIO = 10.0
#: Heaviest plausible striker (kg): five times the heaviest pile-hammer ram in service (about 200 t).
MAX_STRIKER_MASS = 1.0e6
#: Fastest plausible rod, as a fraction of its bar wave speed c: an elastic impact of equal rods strains them by
#: v / (2c), so 0.1 c means 5 % strain, five times the elastic limit of the strongest rod materials (steel and
#: titanium stay elastic below about 1 %); Taylor and gas-gun tests stay below (steel: 518 m/s).
MAX_SPEED_RATIO = 0.1


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
    """Warn about a geometry-based rod whose cross-section is most likely a unit slip (module docstring); True if
    a warning was issued."""
    if rod.native is not None:
        return False
    warned = False
    for i, seg in enumerate(rod.segments):
        key, d, is_diameter = _widest(seg)
        if key in getattr(seg, "_with_units", ()):      # written with its unit ("20 m"): no slip to suggest
            continue
        disc = d > DISC_DIAMETER and DISC_RATIO * rod.length < d
        if not (d > MAX_DIAMETER or disc):
            continue
        warned = True
        why = (f"wider than {MAX_DIAMETER:g} m, the widest driven piles" if d > MAX_DIAMETER else
               f"a disc {d / rod.length:.3g} times wider than the rod is long ({rod.length:.6g} m)")
        if is_diameter:
            value = float(getattr(seg, key)) if hasattr(seg, key) else d
            warn(f"segments[{i}].{key}", f"= {value:.6g} m: did you mean {value:.6g} mm? bare numbers are SI (m); "
                 f"the rod would be {why}", "Rod.")
        else:
            area = 0.25 * math.pi * d * d
            warn(f"segments[{i}].{key}", f"gives a cross-section of {area:.6g} m^2 ({d:.4g} m wide): did you "
                 f"mean mm^2? bare numbers are SI (m^2); the rod would be {why}", "Rod.")
    return warned


def _all_with_units(segment) -> bool:
    """Whether every dimension of a segment (its dataclass fields but the material) was given with a unit."""
    names = [f.name for f in dataclasses.fields(segment) if f.name != "material"] \
        if dataclasses.is_dataclass(segment) else []
    given = getattr(segment, "_with_units", frozenset())
    return bool(names) and all(n in given for n in names)


def _slowest_wave_speed(rod: "Rod") -> float:
    """The smallest bar wave speed of a rod's materials, m/s."""
    if rod.native is not None:
        return float(rod.native.wave_speed)
    return min(rod.segment_material(i).wave_speed for i in range(len(rod.segments)))


def check_strikers(rods, velocities) -> None:
    """Warn about a rod moving faster than :data:`MAX_SPEED_RATIO` times its bar wave speed (impedance-level rods
    included), and about a moving geometry-based rod (a striker) heavier than :data:`MAX_STRIKER_MASS` unless its
    geometry was already warned about."""
    for i, (rod, v) in enumerate(zip(rods, velocities)):
        c = _slowest_wave_speed(rod)
        if abs(v) > MAX_SPEED_RATIO * c:
            warn(f"rods[{i}].velocity", f"= {v:.6g} m/s is {abs(v) / c:.3g} times the bar wave speed of the rod "
                 f"({c:.6g} m/s): the impact would strain it by about v/(2c) = {abs(v) / (2 * c):.3g}, far beyond "
                 f"the elastic limit of any rod material (about 0.01), where this linear elastic model does not "
                 f"hold; check the value and its unit (bare numbers are m/s)")
    for i, (rod, v) in enumerate(zip(rods, velocities)):
        if v != 0.0 and rod.native is None and not getattr(rod, "_implausible", False) and rod.mass > MAX_STRIKER_MASS \
                and not all(_all_with_units(seg) for seg in rod.segments):
            warn(f"rods[{i}]", f"is a striker (initial velocity {v:.6g} m/s) of {rod.mass:.6g} kg, heavier than "
                 f"{MAX_STRIKER_MASS / 1000:g} t (five times the heaviest pile-hammer ram): check the units of its "
                 f"dimensions (bare numbers are SI: m, not mm)")


class KeyPath:
    """Context manager for model files: plausibility warnings raised inside are re-issued under the key path
    ``path`` (``rods[0]`` + ``segments[0].diameter``), except those whose full key the predicate
    ``written_with_unit`` says the file wrote with its unit; other warnings pass through unchanged."""

    def __init__(self, path: str, written_with_unit: Optional[Callable[[str], bool]] = None) -> None:
        self.path = path
        self.written_with_unit = written_with_unit
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
                if self.written_with_unit is not None and self.written_with_unit(key):
                    continue          # the file gives the value with its unit: no slip to warn about
                warnings.warn(PlausibilityWarning(key, w.message.text), stacklevel=caller_stacklevel())
            else:
                warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
