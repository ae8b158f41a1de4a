"""Soil input of a blow: Smith's soil parameters, and the static resistance along the embedded pile from a total
capacity with a shaft share and a distribution over depth (:class:`CapacitySoil`) or from a layered profile of unit
resistances (:class:`SoilProfile`), each turned into the piecewise-constant shaft resistance per metre and the toe
resistance of one penetration (:class:`SoilResistance`).

Depths z are measured down from the ground surface; the pile's toe is at the penetration depth D. Resistances are
ultimate static values in N (per metre of shaft in N/m), positive. The model (E. A. L. Smith, Pile-driving analysis
by the wave equation, J. Soil Mech. Found. Div. ASCE 86 (SM4), 1960, 35-61): an elastic-plastic spring reaching
R_u at the quake q, in parallel with a damper, of the kinds named in :data:`DAMPING_KINDS`.

Setup and relaxation: the capacity during driving differs from the static long-term capacity; each source of
resistance holds a ``setup_factor`` f = static long-term / during driving (f > 1: setup, as in clays; f < 1:
relaxation, as in dense sands and some shales), and a blow sees the static value divided by f. The bearing
graph's capacities are those during driving (f = 1 there unless stated).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional, Sequence

import numpy as np

from .._validate import finite_array, non_negative, positive
from .soil_sets import soil_set

#: Smith damping kinds: "smith" R_s (1 + J V), "smith-viscous" J R_u V, "case" J_c Z V
DAMPING_KINDS = ("smith", "smith-viscous", "case")
#: shaft distributions of a total capacity
DISTRIBUTIONS = ("uniform", "triangular", "trapezoid", "custom")
#: relative tolerance of a custom distribution's sum against the shaft capacity
SUM_TOLERANCE = 1e-6


@dataclass(frozen=True)
class SoilDynamics:
    """Smith's dynamic soil parameters: the quakes (m, > 0; deformation at which the static resistance reaches its
    ultimate value; a rigid-plastic soil is approached by a small quake) of the shaft and the toe, the toe's unloading quake (m, at most the toe quake; ``None``: the toe quake), the
    damping factors of the shaft and the toe (s/m for the ``smith`` and ``smith-viscous`` kinds, dimensionless
    for ``case``) and the ``damping_kind``. No defaults: state the values for the job, or take a published set
    with :meth:`published` (``SoilDynamics.published("grlweap", "sand", "very-dense-or-hard", toe_diameter=0.61)``;
    the sets and where each number was read: :mod:`rodimpact.pile.soil_sets`)."""

    shaft_quake: float
    toe_quake: float
    shaft_damping: float
    toe_damping: float
    damping_kind: str = "smith"
    unloading_quake: Optional[float] = None

    @classmethod
    def published(cls, parameter_set: str, shaft_soil: str, toe_quake: Any, toe_diameter: Optional[float] = None,
                  unloading_quake: Optional[float] = None) -> "SoilDynamics":
        """Smith parameters from the shipped ``parameter_set`` (``gec12``, ``grlweap``;
        :func:`rodimpact.pile.soil_sets.soil_set`): its shaft quake, the shaft damping of ``shaft_soil``, its toe
        damping (``damping_kind = "smith"``: the sets give Smith's J), and the toe quake of the set's rule
        ``toe_quake`` (with ``toe_diameter`` in m for a rule D / n) or a length given for the job."""
        s = soil_set(parameter_set)
        if shaft_soil not in s.shaft_damping:
            raise ValueError(f"shaft_soil: {shaft_soil!r} is not a soil of the {s.name!r} set; one of "
                             f"{', '.join(map(repr, s.shaft_damping))}")
        return cls(s.shaft_quake, s.resolve_toe_quake(toe_quake, toe_diameter), s.shaft_damping[shaft_soil],
                   s.toe_damping, "smith", unloading_quake)

    def __post_init__(self) -> None:
        for name in ("shaft_quake", "toe_quake"):
            object.__setattr__(self, name, positive(f"SoilDynamics.{name}", getattr(self, name), "m"))
        if self.unloading_quake is not None:
            qu = positive("SoilDynamics.unloading_quake", self.unloading_quake, "m")
            if qu > self.toe_quake:
                raise ValueError(f"SoilDynamics.unloading_quake: must be <= toe_quake = {self.toe_quake:.6g} m (a "
                                 f"passive soil unloads at least as stiffly as it loads), got {qu:.6g} m")
            object.__setattr__(self, "unloading_quake", qu)
        unit = "" if self.damping_kind == "case" else "s/m"
        for name in ("shaft_damping", "toe_damping"):
            object.__setattr__(self, name, non_negative(f"SoilDynamics.{name}", getattr(self, name), unit))
        if self.damping_kind not in DAMPING_KINDS:
            raise ValueError(f"SoilDynamics.damping_kind: must be one of {', '.join(map(repr, DAMPING_KINDS))}, got "
                             f"{self.damping_kind!r}")


@dataclass(frozen=True)
class SoilResistance:
    """The static resistance a blow meets at penetration ``penetration`` (m): ``depths`` (m below ground, the
    edges of the shaft segments, from 0 to at most the penetration), ``unit_shaft`` (N/m, constant on each
    segment), ``toe`` (N) and the ``dynamics``."""

    penetration: float
    depths: np.ndarray
    unit_shaft: np.ndarray
    toe: float
    dynamics: SoilDynamics

    @property
    def shaft(self) -> float:
        """Total shaft resistance, N."""
        return float(np.sum(self.unit_shaft * np.diff(self.depths)))

    @property
    def total(self) -> float:
        """Shaft plus toe, N."""
        return self.shaft + self.toe


def linear_distribution(shaft: float, penetration: float, top_ratio: float, edges: np.ndarray) -> np.ndarray:
    """Unit shaft resistance (N/m) on the segments between ``edges`` of a distribution linear in depth, r(z) = b
    (rho + (1 - rho) z / D) with rho = ``top_ratio`` = r(0) / r(D), scaled so that its integral over [0, D] is
    ``shaft``: b = 2 R_s / (D (1 + rho)). Each segment gets its exact mean, the value at its midpoint, so the
    segments sum to ``shaft`` exactly. rho = 1: uniform; rho = 0: triangular (zero at the ground)."""
    b = 2.0 * shaft / (penetration * (1.0 + top_ratio))
    mid = 0.5 * (edges[:-1] + edges[1:])
    return b * (top_ratio + (1.0 - top_ratio) * mid / penetration)


@dataclass(frozen=True)
class CapacitySoil:
    """A total static ``capacity`` (N) with a ``shaft_share`` in [0, 1] on the shaft, the rest at the toe.

    ``distribution`` of the shaft part over the embedded depth: ``uniform``; ``triangular`` (zero at the ground,
    growing linearly to the toe); ``trapezoid`` (linear, ``top_ratio`` = resistance per metre at the ground / at
    the toe); or ``custom``: ``shaft_resistances`` (N) on the intervals between ``depths`` (m below ground,
    increasing from 0), which must sum to shaft_share x capacity. ``setup_factor``: static / during driving
    (module docstring)."""

    capacity: float
    shaft_share: float
    dynamics: SoilDynamics
    distribution: str = "uniform"
    top_ratio: Optional[float] = None
    depths: Optional[Sequence[float]] = None
    shaft_resistances: Optional[Sequence[float]] = None
    setup_factor: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "capacity", positive("CapacitySoil.capacity", self.capacity, "N"))
        share = non_negative("CapacitySoil.shaft_share", self.shaft_share)
        if share > 1.0:
            raise ValueError(f"CapacitySoil.shaft_share: must lie in [0, 1] (the shaft's part of the capacity), got "
                             f"{self.shaft_share!r}")
        object.__setattr__(self, "shaft_share", share)
        object.__setattr__(self, "setup_factor", positive("CapacitySoil.setup_factor", self.setup_factor))
        if not isinstance(self.dynamics, SoilDynamics):
            raise TypeError(f"CapacitySoil.dynamics: must be SoilDynamics, got {type(self.dynamics).__name__}")
        if self.distribution not in DISTRIBUTIONS:
            raise ValueError(f"CapacitySoil.distribution: must be one of {', '.join(map(repr, DISTRIBUTIONS))}, got "
                             f"{self.distribution!r}")
        if (self.distribution == "trapezoid") != (self.top_ratio is not None):
            raise ValueError("CapacitySoil.top_ratio: " + ("needed by the trapezoid distribution (resistance per "
                                                           "metre at the ground / at the toe, >= 0)"
                                                           if self.top_ratio is None else
                                                           f"only for the trapezoid distribution, not "
                                                           f"{self.distribution!r}"))
        if self.top_ratio is not None:
            object.__setattr__(self, "top_ratio", non_negative("CapacitySoil.top_ratio", self.top_ratio))
        custom = self.distribution == "custom"
        if custom != (self.depths is not None) or custom != (self.shaft_resistances is not None):
            raise ValueError("CapacitySoil.depths: " + ("the custom distribution needs depths and "
                                                        "shaft_resistances" if custom else
                                                        f"depths and shaft_resistances belong to the custom "
                                                        f"distribution, not {self.distribution!r}"))
        if custom:
            self._check_custom()

    def _check_custom(self) -> None:
        z = finite_array("CapacitySoil.depths", self.depths, min_size=2, unit="m")
        r = finite_array("CapacitySoil.shaft_resistances", self.shaft_resistances, unit="N")
        if z[0] != 0.0 or not np.all(np.diff(z) > 0):
            raise ValueError(f"CapacitySoil.depths: must start at 0 (the ground) and increase strictly, got "
                             f"{z.tolist()} m")
        if r.size != z.size - 1:
            raise ValueError(f"CapacitySoil.shaft_resistances: one per interval between depths ({z.size - 1}), got "
                             f"{r.size}")
        if np.any(r < 0):
            raise ValueError(f"CapacitySoil.shaft_resistances: must be >= 0 N, got {r.min():.6g} N")
        want = self.shaft_share * self.capacity
        if not math.isclose(float(r.sum()), want, rel_tol=SUM_TOLERANCE, abs_tol=SUM_TOLERANCE * self.capacity):
            raise ValueError(f"CapacitySoil.shaft_resistances: must sum to shaft_share x capacity = {want:.6g} N, "
                             f"got {r.sum():.6g} N")
        object.__setattr__(self, "depths", z)
        object.__setattr__(self, "shaft_resistances", r)

    def resistance(self, penetration: float, edges: Optional[np.ndarray] = None) -> SoilResistance:
        """The resistance during driving with the toe at ``penetration`` (m): the shaft on the segments between
        ``edges`` (m below ground, from 0 to the penetration; default one segment; ignored by ``custom``, whose
        depths are the segments and must not go below the toe)."""
        d = positive("penetration", penetration, "m")
        shaft = self.shaft_share * self.capacity / self.setup_factor
        if self.distribution == "custom":
            z = np.asarray(self.depths)
            if z[-1] > d * (1 + 1e-12):
                raise ValueError(f"CapacitySoil.depths: the distribution reaches {z[-1]:.6g} m, deeper than the "
                                 f"pile's penetration {d:.6g} m")
            unit = np.asarray(self.shaft_resistances) / np.diff(z) / self.setup_factor
        else:
            z = np.array([0.0, d]) if edges is None else np.asarray(edges, dtype=float)
            ratio = {"uniform": 1.0, "triangular": 0.0}.get(self.distribution, self.top_ratio)
            unit = linear_distribution(shaft, d, ratio, z)
        toe = (1.0 - self.shaft_share) * self.capacity / self.setup_factor
        return SoilResistance(d, z, unit, toe, self.dynamics)


@dataclass(frozen=True)
class SoilLayer:
    """A layer of a :class:`SoilProfile` from the previous layer's bottom (or the ground) down to ``bottom`` (m
    below ground): static long-term unit shaft resistance (Pa, on the pile's perimeter), unit toe resistance (Pa,
    on the toe area, used when the toe is in this layer) and the ``setup_factor`` (static / during driving)."""

    bottom: float
    unit_shaft_resistance: float
    unit_toe_resistance: float = 0.0
    setup_factor: float = 1.0
    name: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "bottom", positive("SoilLayer.bottom", self.bottom, "m"))
        for key in ("unit_shaft_resistance", "unit_toe_resistance"):
            object.__setattr__(self, key, non_negative(f"SoilLayer.{key}", getattr(self, key), "Pa"))
        object.__setattr__(self, "setup_factor", positive("SoilLayer.setup_factor", self.setup_factor))


@dataclass(frozen=True)
class SoilProfile:
    """Layers of soil from the ground down (bottoms increasing), the pile's shaft ``perimeter`` (m) and ``toe_area``
    (m^2, the area the toe pushes: the full section of a closed-end or plugged pile) and the ``dynamics``."""

    layers: Sequence[SoilLayer]
    perimeter: float
    toe_area: float
    dynamics: SoilDynamics
    bottoms: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        layers = tuple(self.layers)
        if not layers:
            raise ValueError("SoilProfile.layers: give at least one layer")
        for i, layer in enumerate(layers):
            if not isinstance(layer, SoilLayer):
                raise TypeError(f"SoilProfile.layers[{i}]: must be a SoilLayer, got {type(layer).__name__}")
        bottoms = np.array([layer.bottom for layer in layers])
        if np.any(np.diff(bottoms) <= 0):
            k = int(np.argmax(np.diff(bottoms) <= 0)) + 1
            raise ValueError(f"SoilProfile.layers[{k}].bottom: must lie below the layer above ({bottoms[k - 1]:.6g} "
                             f"m), got {bottoms[k]:.6g} m")
        object.__setattr__(self, "layers", layers)
        object.__setattr__(self, "bottoms", bottoms)
        object.__setattr__(self, "perimeter", positive("SoilProfile.perimeter", self.perimeter, "m"))
        object.__setattr__(self, "toe_area", positive("SoilProfile.toe_area", self.toe_area, "m^2"))
        if not isinstance(self.dynamics, SoilDynamics):
            raise TypeError(f"SoilProfile.dynamics: must be SoilDynamics, got {type(self.dynamics).__name__}")

    def _toe_layer(self, depth: float) -> int:
        if depth > self.bottoms[-1] * (1 + 1e-12):
            raise ValueError(f"penetration: {depth:.6g} m is below the soil profile, which ends at "
                             f"{self.bottoms[-1]:.6g} m")
        return min(int(np.searchsorted(self.bottoms, depth, side="left")), len(self.layers) - 1)

    def resistance(self, penetration: float, static: bool = False) -> SoilResistance:
        """The resistance with the toe at ``penetration`` (m): unit shaft resistance x perimeter (N/m) on each layer
        above the toe, unit toe resistance of the toe's layer x toe area, each divided by its layer's setup factor
        (``static=True``: not divided; the long-term static capacity)."""
        d = positive("penetration", penetration, "m")
        k = self._toe_layer(d)
        edges = np.concatenate([[0.0], self.bottoms[:k], [d]])
        layers = self.layers[:k + 1]
        factor = np.array([1.0 if static else layer.setup_factor for layer in layers])
        unit = np.array([layer.unit_shaft_resistance for layer in layers]) * self.perimeter / factor
        keep = np.diff(edges) > 0
        toe = layers[-1].unit_toe_resistance * self.toe_area / factor[-1]
        return SoilResistance(d, np.concatenate([[0.0], edges[1:][keep]]), unit[keep], toe, self.dynamics)
