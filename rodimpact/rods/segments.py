"""Cross-section shapes of rod segments.

A segment is a piece of rod of given length whose cross-section area is a function of the local
coordinate ``s`` in ``[0, length]`` (m, measured from the segment's left end). A segment may carry its
own :class:`~rodimpact.rods.material.Material`; ``material=None`` means "the rod's material".

The four analytic families of thesis Tab. 2.1 (quadratic, exponential, cosh^2, cos^2) are provided, plus the
shapes engineers draw: cylinders, tubes, cones (linear diameter), linear-area tapers, tabulated profiles and
arbitrary area functions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from .._units import is_quantity
from .._validate import finite_array
from .declared import check, element, quantity
from .material import Material, as_material

ArrayLike = np.ndarray | float


def _check_area(name: str, area: np.ndarray, where: str) -> None:
    if not np.all(np.isfinite(area)) or np.any(area <= 0):
        bad = np.flatnonzero(~np.isfinite(area) | (area <= 0))[0]
        raise ValueError(f"{name}: the cross-section area must be finite and > 0 everywhere; {where} gives "
                         f"{float(area[bad])} m^2 at sample {bad}")


@dataclass(frozen=True)
class Segment:
    """Base class: a rod piece of ``length`` (m) with area function :meth:`area` and optional material."""

    length: float = quantity("length", "Length of the segment.")
    material: Optional[Material] = field(default=None, kw_only=True)

    def __init_subclass__(cls, **kwargs) -> None:
        # before a subclass's __post_init__ converts its fields to SI floats, note the fields given with a unit
        # ("20 mm" or a pint Quantity) in ``_with_units``: the plausibility check never suggests changing those
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("__post_init__")
        if own is None:
            return

        def __post_init__(self, _own=own) -> None:
            self._note_units()
            _own(self)

        cls.__post_init__ = __post_init__

    def _note_units(self) -> None:
        if "_with_units" not in self.__dict__:
            object.__setattr__(self, "_with_units", frozenset(
                k for k, v in self.__dict__.items() if isinstance(v, str) or is_quantity(v)))

    def __post_init__(self) -> None:
        self._note_units()
        check(self)            # the declared fields: SI floats within their bounds
        if self.material is not None:          # a Material or a preset name ("steel"), as Rod accepts
            object.__setattr__(self, "material", as_material(self.material, f"{type(self).__name__}.material"))
        s = np.linspace(0.0, self.length, 65)
        try:
            with np.errstate(all="ignore"):
                area = np.asarray(self.area(s), dtype=float)
        except (OverflowError, ZeroDivisionError):     # Python float arithmetic on values near the float range
            area = np.array([math.inf])
        _check_area(type(self).__name__, area, "the profile")

    def area(self, s: ArrayLike) -> np.ndarray:
        """Cross-section area in m^2 at local positions ``s`` (m)."""
        raise NotImplementedError

    def equivalent_diameter(self, s: ArrayLike) -> np.ndarray:
        """Equivalent solid-circle diameter sqrt(4 A / pi) in m (for plots of arbitrary shapes)."""
        return np.sqrt(4.0 * self.area(s) / math.pi)


@element("segment", "cylinder")
@dataclass(frozen=True)
class Cylinder(Segment):
    """Solid circular cylinder."""

    diameter: float = quantity("length", "Diameter.")

    def area(self, s: ArrayLike) -> np.ndarray:
        return np.full(np.shape(s), 0.25 * math.pi * self.diameter**2)


@element("segment", "tube")
@dataclass(frozen=True)
class Tube(Segment):
    """Hollow circular tube (constant bore)."""

    outer_diameter: float = quantity("length", "Outer diameter.")
    inner_diameter: float = quantity("length", "Inner diameter (bore), 0 <= inner < outer.", bound="non_negative")

    def __post_init__(self) -> None:
        check(self)
        if not 0.0 <= self.inner_diameter < self.outer_diameter:
            raise ValueError(f"Tube.inner_diameter: must satisfy 0 <= inner < outer = {self.outer_diameter} m, "
                             f"got {self.inner_diameter} m")
        super().__post_init__()

    def area(self, s: ArrayLike) -> np.ndarray:
        return np.full(np.shape(s), 0.25 * math.pi * (self.outer_diameter**2 - self.inner_diameter**2))


@element("segment", "cone")
@dataclass(frozen=True)
class Cone(Segment):
    """Frustum: the diameter changes linearly along the segment."""

    diameter_start: float = quantity("length", "Diameter at the left end.")
    diameter_end: float = quantity("length", "Diameter at the right end.")

    def area(self, s: ArrayLike) -> np.ndarray:
        d = self.diameter_start + (self.diameter_end - self.diameter_start) * np.asarray(s) / self.length
        return 0.25 * math.pi * d**2


@element("segment", "linear-area")
@dataclass(frozen=True)
class LinearAreaTaper(Segment):
    """The cross-section area changes linearly (thesis setup 3, x1..x2)."""

    area_start: float = quantity("area", "Area at the left end.")
    area_end: float = quantity("area", "Area at the right end.")

    def area(self, s: ArrayLike) -> np.ndarray:
        return self.area_start + (self.area_end - self.area_start) * np.asarray(s, dtype=float) / self.length


@dataclass(frozen=True)
class _AnalyticHorn(Segment):
    """Common parameters of the thesis Tab. 2.1 families: ``area_start`` A0 (m^2) and ``xi`` (1/m)."""

    area_start: float = quantity("area", "Area A0 at the left end.")
    xi: float = quantity("wavenumber", "Flare constant xi.", bound=None)


@element("segment", "quadratic-horn")
@dataclass(frozen=True)
class QuadraticHorn(_AnalyticHorn):
    """A(s) = area_start * (1 + xi s)^2 (thesis Tab. 2.1, b = 0: non-dispersive)."""

    def area(self, s: ArrayLike) -> np.ndarray:
        return self.area_start * (1.0 + self.xi * np.asarray(s, dtype=float)) ** 2


@element("segment", "exponential-horn")
@dataclass(frozen=True)
class ExponentialHorn(_AnalyticHorn):
    """A(s) = area_start * exp(xi s) (thesis Tab. 2.1, eq. 3.28; setup 1 / Fig. 3.11 with xi = 1/2 per m)."""

    def area(self, s: ArrayLike) -> np.ndarray:
        return self.area_start * np.exp(self.xi * np.asarray(s, dtype=float))


@element("segment", "cosh-horn")
@dataclass(frozen=True)
class CoshHorn(_AnalyticHorn):
    """A(s) = area_start * cosh(xi s)^2 (thesis Tab. 2.1)."""

    def area(self, s: ArrayLike) -> np.ndarray:
        return self.area_start * np.cosh(self.xi * np.asarray(s, dtype=float)) ** 2


@element("segment", "cos-horn")
@dataclass(frozen=True)
class CosHorn(_AnalyticHorn):
    """A(s) = area_start * cos(xi s)^2 (thesis Tab. 2.1); |xi| length < pi/2."""

    def __post_init__(self) -> None:
        check(self)
        if abs(self.xi) * self.length >= math.pi / 2:
            raise ValueError(f"CosHorn.xi: |xi| * length must be < pi/2 so that the area stays > 0, "
                             f"got {abs(self.xi) * self.length:.4g}")
        super().__post_init__()

    def area(self, s: ArrayLike) -> np.ndarray:
        return self.area_start * np.cos(self.xi * np.asarray(s, dtype=float)) ** 2


def _table_arrays(x, diameter, area) -> tuple[np.ndarray, np.ndarray, str]:
    """Positions (m), values and their kind ("diameter" in m or "area" in m^2) of a tabulated profile, checked
    for everything but the order of x: at least two finite positions, one finite value > 0 per position."""
    xs = finite_array("TabulatedProfile.x", x, min_size=2, unit="m")
    if (diameter is None) == (area is None):
        raise ValueError("TabulatedProfile: give exactly one of diameter= or area=")
    name = "diameter" if diameter is not None else "area"
    vals = finite_array(f"TabulatedProfile.{name}", diameter if diameter is not None else area, min_size=2,
                        unit="m" if name == "diameter" else "m^2")
    if vals.shape != xs.shape:
        raise ValueError(f"TabulatedProfile.{name}: needs one value per x ({xs.size}), got {vals.size}")
    if np.any(vals <= 0):
        i = int(np.flatnonzero(vals <= 0)[0])
        raise ValueError(f"TabulatedProfile.{name}: every value must be > 0, entry {i} is {vals[i]}")
    return xs, vals, name


class TabulatedProfile(Segment):
    """A profile given by points: positions ``x`` (m, strictly increasing) and either ``diameter`` (m,
    interpolated linearly, i.e. conical pieces) or ``area`` (m^2, interpolated linearly).

    The segment's length is ``x[-1] - x[0]``; local s = x - x[0]. A profile with steps (a position given twice)
    is a chain of such segments: :func:`stepped_profile`.
    """

    def __init__(self, x, diameter=None, area=None, *, material: Optional[Material] = None) -> None:
        xs, vals, name = _table_arrays(x, diameter, area)
        if np.any(np.diff(xs) <= 0):
            i = int(np.flatnonzero(np.diff(xs) <= 0)[0])
            step = (" (a step? a TabulatedProfile has none: rodimpact.stepped_profile makes one segment per piece "
                    "between steps)" if xs[i + 1] == xs[i] else "")
            raise ValueError(f"TabulatedProfile.x: must be strictly increasing; x[{i + 1}] = {xs[i + 1]} <= "
                             f"x[{i}] = {xs[i]}{step}")
        object.__setattr__(self, "x", xs)
        object.__setattr__(self, "values", vals)
        object.__setattr__(self, "kind", name)
        object.__setattr__(self, "length", float(xs[-1] - xs[0]))
        object.__setattr__(self, "material", material)
        Segment.__post_init__(self)

    def area(self, s: ArrayLike) -> np.ndarray:
        v = np.interp(np.asarray(s, dtype=float) + self.x[0], self.x, self.values)
        return 0.25 * math.pi * v**2 if self.kind == "diameter" else v

    def __repr__(self) -> str:
        return f"TabulatedProfile({self.x.size} points, {self.kind}, length={self.length:.6g} m)"

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, TabulatedProfile) and self.kind == other.kind and self.material == other.material
                and np.array_equal(self.x, other.x) and np.array_equal(self.values, other.values))

    __hash__ = None  # type: ignore[assignment]


def stepped_profile(x, diameter=None, area=None, *,
                    material: Optional[Material] = None) -> tuple[TabulatedProfile, ...]:
    """A tabulated profile with steps, as the chain of :class:`TabulatedProfile` segments between its steps.

    ``x`` (m) must not decrease; a position given twice is a step: the profile runs up to the first ``diameter``
    (m) or ``area`` (m^2) given at that position and continues from the second (``x = [0, 0.1, 0.1, 0.15]``,
    ``diameter = [0.04, 0.04, 0.05, 0.05]``: 40 mm up to 0.1 m, then 50 mm). Between the points the values are
    interpolated linearly. A step must have length on both sides (not at the first or last position) and a
    position may appear at most twice. Without repeated positions the result is a single profile.

    The pieces are separate segments, listed left to right, so that each step is a segment end for the lattice
    (the mass is integrated piece by piece; a piece shorter than one element is reported like a short segment).
    Model files do the same for a ``table`` with repeated ``x``.
    """
    xs, vals, name = _table_arrays(x, diameter, area)
    dx = np.diff(xs)
    if np.any(dx < 0):
        i = int(np.flatnonzero(dx < 0)[0])
        raise ValueError(f"TabulatedProfile.x: must not decrease; x[{i + 1}] = {xs[i + 1]} < x[{i}] = {xs[i]}")
    steps = np.flatnonzero(dx == 0)          # a step between points i and i + 1
    if steps.size and (steps[0] == 0 or steps[-1] == xs.size - 2):
        i = int(steps[0] if steps[0] == 0 else steps[-1])
        raise ValueError(f"TabulatedProfile.x: x[{i}] = x[{i + 1}] = {xs[i]} is a step at the "
                         f"{'first' if i == 0 else 'last'} position, which leaves no length on one side")
    if np.any(np.diff(steps) == 1):
        i = int(steps[np.flatnonzero(np.diff(steps) == 1)[0]])
        raise ValueError(f"TabulatedProfile.x: x[{i}] = {xs[i]} appears three times; a step repeats a position "
                         f"once")
    bounds = np.concatenate([[0], steps + 1, [xs.size]])
    return tuple(TabulatedProfile(xs[a:b], **{name: vals[a:b]}, material=material)
                 for a, b in zip(bounds[:-1], bounds[1:]))


class AreaFunction(Segment):
    """Arbitrary area ``area(s)`` (m^2) for local s in [0, length]; must be vectorised over numpy arrays
    (scalars are accepted and broadcast). Thesis eq. 3.24 is an example."""

    def __init__(self, length: float, area: Callable[[np.ndarray], np.ndarray], *,
                 material: Optional[Material] = None, name: str = "") -> None:
        if not callable(area):
            raise TypeError(f"AreaFunction.area: must be a callable area(s) in m^2, got {type(area).__name__}")
        object.__setattr__(self, "function", area)
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "material", material)
        Segment.__post_init__(self)

    def area(self, s: ArrayLike) -> np.ndarray:
        s = np.asarray(s, dtype=float)
        return np.broadcast_to(np.asarray(self.function(s), dtype=float), s.shape).copy()

    def __repr__(self) -> str:
        return f"AreaFunction(length={self.length:.6g} m{', ' + self.name if self.name else ''})"

    def __eq__(self, other: object) -> bool:
        return (isinstance(other, AreaFunction) and self.length == other.length and self.material == other.material
                and (self.function is other.function or self.function == other.function))

    __hash__ = None  # type: ignore[assignment]
