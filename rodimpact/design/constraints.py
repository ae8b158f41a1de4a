"""Constraints of striker design: impedance (or diameter) bounds, striker mass, impact velocity.

A striker element of travel time dt and impedance Z_q = rho c A_q has the mass rho A_q c dt = Z_q dt, so the
striker mass m = dt sum Z_q is linear in the impedances whatever the material. Diameter bounds d_min..d_max of
a material (rho, c) with an optional central bore d_i become impedance bounds
Z = rho c pi (d^2 - d_i^2) / 4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional, Union

import numpy as np

from .._validate import finite, integer, non_negative, positive, real_number
from ..rods.material import STEEL, Material


@dataclass(frozen=True)
class Constraints:
    """Validated constraints for ``n`` elements of travel time ``dt``.

    ``lower``/``upper``: per-element impedance bounds (N s/m, face first); ``mass``: None or (lo, hi) kg (lo ==
    hi for a prescribed mass); ``velocity``: (lo, hi) m/s, lo == hi when the velocity is fixed.
    """

    lower: np.ndarray
    upper: np.ndarray
    dt: float
    mass: Optional[tuple[float, float]]
    velocity: tuple[float, float]

    @property
    def free_velocity(self) -> bool:
        return self.velocity[1] > self.velocity[0]

    def mass_of(self, impedance: np.ndarray) -> float:
        return self.dt * float(np.sum(impedance))

    def project(self, impedance: np.ndarray) -> np.ndarray:
        """The closest profile (in the Euclidean sense) inside the bounds with an admissible mass (see
        :func:`project_shift_clip`)."""
        return project_shift_clip(impedance, self.lower, self.upper, np.ones(impedance.size), self.mass, self.dt)

    def report(self, impedance: np.ndarray, velocity: float, rtol: float = 1e-6) -> dict[str, Any]:
        """Which constraints are active at the solution: the elements at their lower and upper impedance bound
        (1-based from the impact face), whether the mass sits on a bound, the velocity on a bound."""
        span = np.maximum(self.upper - self.lower, 1e-300)
        at_lo = np.flatnonzero(impedance - self.lower <= rtol * span) + 1
        at_hi = np.flatnonzero(self.upper - impedance <= rtol * span) + 1
        out: dict[str, Any] = {"elements_at_lower_bound": at_lo.tolist(), "elements_at_upper_bound": at_hi.tolist(),
                               "mass_kg": self.mass_of(impedance), "mass_active": None, "velocity_active": None}
        if self.mass is not None:
            m = self.mass_of(impedance)
            lo, hi = self.mass
            tol = rtol * max(hi, 1e-300)
            out["mass_active"] = ("prescribed" if lo == hi else "lower" if m - lo <= tol
                                  else "upper" if hi - m <= tol else "inactive")
        if self.free_velocity:
            lo, hi = self.velocity
            tol = rtol * max(abs(hi), 1e-300)
            out["velocity_active"] = ("lower" if velocity - lo <= tol else "upper" if hi - velocity <= tol
                                      else "inactive")
        return out


def project_shift_clip(z: np.ndarray, lower: np.ndarray, upper: np.ndarray, counts: np.ndarray,
                       mass: Optional[tuple[float, float]], dt: float) -> np.ndarray:
    """Projection of levels ``z`` (each standing for ``counts`` elements) onto the bounds and the mass range
    dt sum counts z in [lo, hi], in the metric sum counts (z' - z)^2.

    Clip; if the mass is outside its range, z' = clip(z + s, lower, upper) with one shift s for all levels (the
    optimality condition of this projection), found by bisection since the mass is monotone in s; the last
    rounding remainder is spread over the levels strictly inside their bounds."""
    out = np.clip(z, lower, upper)
    if mass is None:
        return out
    m = dt * float(counts @ out)
    lo, hi = mass
    if lo <= m <= hi:
        return out
    goal = (lo if m < lo else hi) / dt
    a = float(np.min(lower - z))
    b = float(np.max(upper - z))
    for _ in range(200):
        s = 0.5 * (a + b)
        if counts @ np.clip(z + s, lower, upper) < goal:
            a = s
        else:
            b = s
        if b - a <= 1e-15 * max(abs(a), abs(b), 1.0):
            break
    out = np.clip(z + 0.5 * (a + b), lower, upper)
    free = (out > lower) & (out < upper)
    if free.any():
        out[free] += (goal - counts @ out) / counts[free].sum()
    return out


def diameter_to_impedance(diameter: float, material: Material, bore: float = 0.0) -> float:
    """Z = rho c pi (d^2 - d_i^2) / 4, N s/m."""
    return material.density * material.wave_speed * math.pi * (diameter * diameter - bore * bore) / 4.0


#: one impedance or diameter bound: a number for every element, or one per element (from the impact face)
Bound = Union[float, tuple[float, ...]]


@dataclass(frozen=True)
class StrikerLimits:
    """What the designed striker may be: bounds of its element impedances or outer diameters, its material and
    bore, its mass and impact velocity, and how it can be machined. Validated when made; per-element bounds are
    checked against the number of elements n by :func:`~rodimpact.design`.

    impedance_bounds:
        (lower, upper) of the element impedances Z_q, N s/m > 0: numbers, or one per element (from the impact
        face). Default (no bounds given): 1/100 .. 100 times the struck system's face impedance.
    diameter_bounds:
        (lower, upper) of the outer diameters, m > 0 (numbers or one per element), of a striker of ``material``
        with a central ``bore``: Z = rho c pi (d^2 - d_i^2) / 4. Not together with ``impedance_bounds``.
    material:
        Striker material: turns diameters into impedances, and the result into lengths and a shape.
    bore:
        Diameter of a central bore, m >= 0 (0: solid); smaller than every diameter.
    mass:
        Striker mass, kg > 0, or a range (lower, upper); the mass of the lattice striker is m = dt sum Z_q.
    velocity_bounds:
        (lower, upper) m/s > 0: optimise the impact velocity too, within these bounds (the ``striker_velocity``
        of :func:`~rodimpact.design` is then the start value).
    max_steps:
        Return a stepped striker of at most this many constant-impedance steps (machinable as cylinders, see
        :mod:`rodimpact.design.stepped`); None: a free profile.
    smoothness:
        Weight >= 0 of a smoothed total-variation penalty sum |Z_{q+1} - Z_q| / Z_ref added to the objective
        (0: none).
    """

    impedance_bounds: Optional[tuple[Bound, Bound]] = None
    diameter_bounds: Optional[tuple[Bound, Bound]] = None
    material: Material = STEEL
    bore: float = 0.0
    mass: Union[float, tuple[float, float], None] = None
    velocity_bounds: Optional[tuple[float, float]] = None
    max_steps: Optional[int] = None
    smoothness: float = 0.0

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        if self.impedance_bounds is not None and self.diameter_bounds is not None:
            raise ValueError("StrikerLimits.impedance_bounds, diameter_bounds: give one of them, not both")
        if not isinstance(self.material, Material):
            raise TypeError(f"StrikerLimits.material: must be a Material, got {type(self.material).__name__}")
        put("bore", non_negative("StrikerLimits.bore", self.bore, "m"))
        for name, unit in (("impedance_bounds", "N s/m"), ("diameter_bounds", "m")):
            if getattr(self, name) is not None:
                put(name, _bounds(f"StrikerLimits.{name}", getattr(self, name), unit))
        if self.diameter_bounds is not None and np.min(self.diameter_bounds[0]) <= self.bore:
            raise ValueError(f"StrikerLimits.diameter_bounds: the smallest diameter "
                             f"{np.min(self.diameter_bounds[0]):.6g} m must exceed the bore {self.bore:.6g} m")
        if isinstance(self.mass, (tuple, list)):
            put("mass", _positive_range("StrikerLimits.mass", self.mass, "kg"))
        elif self.mass is not None:
            put("mass", positive("StrikerLimits.mass", self.mass, "kg"))
        if self.velocity_bounds is not None:
            put("velocity_bounds", _positive_range("StrikerLimits.velocity_bounds", self.velocity_bounds, "m/s"))
        if self.max_steps is not None:
            put("max_steps", integer("StrikerLimits.max_steps", self.max_steps, 1,
                                     "number of constant-impedance steps"))
        put("smoothness", real_number("StrikerLimits.smoothness", self.smoothness,
                                      "a finite number >= 0 (weight of the total-variation penalty)",
                                      lambda x: x >= 0.0))


def _pair(name: str, value: Any, unit: str) -> tuple[Any, Any]:
    if not isinstance(value, (tuple, list)) or len(value) != 2:
        raise ValueError(f"{name}: give a pair (lower, upper) in {unit}, got {value!r}")
    return value[0], value[1]


def real_array(name: str, value: Any, unit: str) -> np.ndarray:
    """``value`` (a number or a sequence of numbers) as a float array; strings, booleans and other objects are
    refused with a TypeError naming ``name`` (no coercion of "5" into 5)."""
    a = np.asarray(value)
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{name}: must be real numbers in {unit} (a number or one per element), got "
                        f"{type(value).__name__} {value!r}")
    return a.astype(float)


def _bounds(name: str, value: Any, unit: str) -> tuple[Bound, Bound]:
    """A pair (lower, upper) of bounds, each finite and > 0, a number or one per element (a tuple), with lower <=
    upper wherever both are given."""
    pair = []
    for i, side in enumerate(_pair(name, value, unit)):
        a = real_array(f"{name}[{i}]", side, unit)
        if a.ndim > 1:
            raise ValueError(f"{name}[{i}]: give one value or one per element, got shape {a.shape}")
        values = np.atleast_1d(a)
        bad = values[~(np.isfinite(values) & (values > 0))]
        if bad.size:
            raise ValueError(f"{name}[{i}]: must be finite and > 0 {unit}, got {bad[0]!r}")
        pair.append(float(a) if a.ndim == 0 else tuple(a.tolist()))
    lo, hi = (np.atleast_1d(p) for p in pair)
    if lo.size == 1 or hi.size == 1 or lo.size == hi.size:        # else the count is refused for the given n
        lo, hi = np.broadcast_arrays(lo, hi)
        bad = np.flatnonzero(lo > hi)
        if bad.size:
            q = int(bad[0])
            raise ValueError(f"{name}: the lower bound exceeds the upper bound at element {q + 1} "
                             f"({lo[q]:.6g} > {hi[q]:.6g} {unit}); give lower <= upper")
    return pair[0], pair[1]


def _bound_array(name: str, value: Bound, n: int) -> np.ndarray:
    """A validated bound as one value per element."""
    a = np.asarray(value, dtype=float)
    if a.ndim == 0:
        return np.full(n, float(a))
    if a.shape != (n,):
        raise ValueError(f"{name}: give one value or one per element ({n}), got {a.size} values")
    return a


def build_constraints(n: int, dt: float, face_impedance: float, limits: StrikerLimits,
                      striker_velocity: Optional[float]) -> Constraints:
    """The :class:`Constraints` of ``n`` elements of travel time ``dt`` (s) that ``limits`` set, the impact
    velocity fixed at ``striker_velocity`` (m/s) unless ``limits.velocity_bounds`` frees it.

    Without impedance or diameter bounds the impedances may range over 1/100 .. 100 times the struck system's
    face impedance (N s/m)."""
    if limits.diameter_bounds is not None:
        dlo = _bound_array("StrikerLimits.diameter_bounds[0]", limits.diameter_bounds[0], n)
        dhi = _bound_array("StrikerLimits.diameter_bounds[1]", limits.diameter_bounds[1], n)
        lo = np.array([diameter_to_impedance(d, limits.material, limits.bore) for d in dlo])
        hi = np.array([diameter_to_impedance(d, limits.material, limits.bore) for d in dhi])
        name = "diameter_bounds"
    else:
        zlo, zhi = ((face_impedance / 100.0, face_impedance * 100.0) if limits.impedance_bounds is None
                    else limits.impedance_bounds)
        lo = _bound_array("StrikerLimits.impedance_bounds[0]", zlo, n)
        hi = _bound_array("StrikerLimits.impedance_bounds[1]", zhi, n)
        name = "impedance_bounds"
    mass_range = None
    if limits.mass is not None:
        mass_range = limits.mass if isinstance(limits.mass, tuple) else (limits.mass, limits.mass)
        reach = (dt * float(lo.sum()), dt * float(hi.sum()))
        if mass_range[1] < reach[0] * (1 - 1e-12) or mass_range[0] > reach[1] * (1 + 1e-12):
            raise ValueError(f"StrikerLimits.mass: no striker of {n} elements inside the {name.replace('_', ' ')} "
                             f"can have a mass of {_fmt_range(mass_range)} kg; with dt = {dt:.6g} s it can weigh "
                             f"{reach[0]:.6g} .. {reach[1]:.6g} kg (mass = dt * sum Z)")
    if limits.velocity_bounds is not None:
        vel = limits.velocity_bounds
    else:
        if striker_velocity is None:
            raise ValueError("striker_velocity: give the impact velocity (m/s), or StrikerLimits.velocity_bounds to "
                             "optimise it")
        v = positive("striker_velocity", striker_velocity, "m/s")
        vel = (v, v)
    return Constraints(lo, hi, float(dt), mass_range, vel)


def _positive_range(name: str, value: Any, unit: str) -> tuple[float, float]:
    """A pair (lower, upper) of positive numbers with lower <= upper."""
    a, b = _pair(name, value, unit)
    r = (positive(f"{name}[0]", a, unit), positive(f"{name}[1]", b, unit))
    if r[0] > r[1]:
        raise ValueError(f"{name}: the lower bound {r[0]:.6g} {unit} exceeds the upper bound {r[1]:.6g} {unit}")
    return r


def _fmt_range(r: tuple[float, float]) -> str:
    return f"{r[0]:.6g}" if r[0] == r[1] else f"{r[0]:.6g} .. {r[1]:.6g}"


def velocity_start(c: Constraints, striker_velocity: Optional[float]) -> float:
    """The starting velocity: the given one clipped into the bounds, else the bounds' midpoint."""
    lo, hi = c.velocity
    if striker_velocity is None:
        return 0.5 * (lo + hi)
    return float(np.clip(finite("striker_velocity", striker_velocity, "m/s"), lo, hi))
