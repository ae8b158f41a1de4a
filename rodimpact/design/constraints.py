"""Constraints of striker design: impedance (or diameter) bounds, striker mass, impact velocity.

A striker element of travel time dt and impedance Z_q = rho c A_q has the mass rho A_q c dt = Z_q dt, so the
striker mass m = dt sum Z_q is linear in the impedances whatever the material. Diameter bounds d_min..d_max of
a material (rho, c) with an optional central bore d_i become impedance bounds
Z = rho c pi (d^2 - d_i^2) / 4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from .._validate import finite, non_negative, positive
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


def _bound_array(name: str, value: Any, n: int, unit: str) -> np.ndarray:
    a = real_array(name, value, unit)
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape != (n,):
        raise ValueError(f"{name}: give one value or one per element ({n}), got shape {a.shape}")
    if not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise ValueError(f"{name}: must be finite and > 0 {unit}, got {a[~(np.isfinite(a) & (a > 0))][0]!r}")
    return a


def build_constraints(n: int, dt: float, face_impedance: float, *, impedance_bounds: Any = None,
                      diameter_bounds: Any = None, material: Material = STEEL, bore: float = 0.0,
                      mass: Any = None, striker_velocity: Optional[float] = None,
                      velocity_bounds: Any = None) -> Constraints:
    """Check the constraint arguments of :func:`~rodimpact.design` and turn them into a :class:`Constraints`.

    Without impedance or diameter bounds the impedances may range over 1/100 .. 100 times the struck system's
    face impedance."""
    if impedance_bounds is not None and diameter_bounds is not None:
        raise ValueError("impedance_bounds, diameter_bounds: give one of them, not both")
    if diameter_bounds is not None:
        if not isinstance(material, Material):
            raise TypeError(f"material: must be a Material, got {type(material).__name__}")
        d_i = non_negative("bore", bore, "m")
        dlo, dhi = _pair("diameter_bounds", diameter_bounds, "m")
        dlo = _bound_array("diameter_bounds[0]", dlo, n, "m")
        dhi = _bound_array("diameter_bounds[1]", dhi, n, "m")
        if np.any(dlo <= d_i):
            raise ValueError(f"diameter_bounds: the smallest diameter {dlo.min():.6g} m must exceed the bore "
                             f"{d_i:.6g} m")
        lo = np.array([diameter_to_impedance(d, material, d_i) for d in dlo])
        hi = np.array([diameter_to_impedance(d, material, d_i) for d in dhi])
        name = "diameter_bounds"
    else:
        zlo, zhi = ((face_impedance / 100.0, face_impedance * 100.0) if impedance_bounds is None
                    else _pair("impedance_bounds", impedance_bounds, "N s/m"))
        lo = _bound_array("impedance_bounds[0]", zlo, n, "N s/m")
        hi = _bound_array("impedance_bounds[1]", zhi, n, "N s/m")
        name = "impedance_bounds"
    bad = np.flatnonzero(lo > hi)
    if bad.size:
        q = int(bad[0])
        raise ValueError(f"{name}: the lower bound exceeds the upper bound at element {q + 1} "
                         f"(impedance {lo[q]:.6g} > {hi[q]:.6g} N s/m); give lower <= upper")
    mass_range = None
    if mass is not None:
        if isinstance(mass, (tuple, list)):
            mass_range = _positive_range("mass", mass, "kg")
        else:
            m = positive("mass", mass, "kg")
            mass_range = (m, m)
        reach = (dt * float(lo.sum()), dt * float(hi.sum()))
        if mass_range[1] < reach[0] * (1 - 1e-12) or mass_range[0] > reach[1] * (1 + 1e-12):
            raise ValueError(f"mass: no striker of {n} elements inside the {name.replace('_', ' ')} can have a mass "
                             f"of {_fmt_range(mass_range)} kg; with dt = {dt:.6g} s it can weigh "
                             f"{reach[0]:.6g} .. {reach[1]:.6g} kg (mass = dt * sum Z)")
    if velocity_bounds is not None:
        vel = _positive_range("velocity_bounds", velocity_bounds, "m/s")
    else:
        if striker_velocity is None:
            raise ValueError("striker_velocity: give the impact velocity (m/s), or velocity_bounds to optimise it")
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
