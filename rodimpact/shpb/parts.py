"""The parts of a split-Hopkinson (Kolsky) bar that the data reduction needs: the two bars with their gauge
stations (:class:`Bar`) and the specimen's initial size (:class:`SpecimenGeometry`).

SI units. A quantity may be given as a unit string (``"9.47 mm"``) or a pint Quantity; bare numbers are SI.
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass
from typing import Any, Optional

from .._validate import finite, non_negative, positive
from ..rods.material import Material, as_material
from ..signals.gauges import GaugedBar

__all__ = ["Bar", "SpecimenGeometry"]


def _section(owner: str, diameter: Any, area: Any) -> tuple[float, float]:
    """``(diameter, area)`` of a solid circular section from exactly one of them (``A = pi d^2 / 4``); for a
    non-circular section give the area: the diameter is then that of the circle of equal area."""
    if (diameter is None) == (area is None):
        raise ValueError(f"{owner}: give exactly one of diameter and area, got "
                         f"{'both' if diameter is not None else 'neither'}")
    if diameter is not None:
        d = positive(f"{owner}.diameter", diameter, "m")
        return d, math.pi * d * d / 4.0
    a = positive(f"{owner}.area", area, "m^2")
    return math.sqrt(4.0 * a / math.pi), a


@dataclass(frozen=True)
class Bar:
    """An elastic pressure bar with a strain-gauge station: ``Bar(material, diameter=..., gauge_distance=...)``.

    Parameters
    ----------
    material:
        The bar's :class:`~rodimpact.Material` (Young's modulus E_b, density rho_b, so the bar wave speed
        ``c_b = sqrt(E_b / rho_b)``) or a preset name. A measured wave speed c is used by giving the density
        ``E_b / c^2``.
    diameter, area:
        Exactly one: the diameter (m) of a solid round bar, or its cross-section area A_b (m^2).
    gauge_distance:
        Distance (m) from the gauge station to the bar face that touches the specimen, >= 0. It sets the
        travel time ``gauge_distance / c_b`` by which the pulses are moved to the specimen faces.
    poisson_ratio:
        Poisson's ratio of the bar, in [0, 0.5); needed only for the Pochhammer-Chree dispersion correction.
    name:
        A label for reports.
    """

    material: Material
    _: KW_ONLY
    diameter: Optional[float] = None
    area: Optional[float] = None
    gauge_distance: float
    poisson_ratio: Optional[float] = None
    name: str = ""

    def __post_init__(self) -> None:
        owner = f"Bar{f' {self.name!r}' if self.name else ''}"
        object.__setattr__(self, "material", as_material(self.material, f"{owner}.material"))
        d, a = _section(owner, self.diameter, self.area)
        object.__setattr__(self, "diameter", d)
        object.__setattr__(self, "area", a)
        object.__setattr__(self, "gauge_distance", non_negative(f"{owner}.gauge_distance", self.gauge_distance,
                                                                "m"))
        if self.poisson_ratio is not None:
            nu = finite(f"{owner}.poisson_ratio", self.poisson_ratio)
            if not 0.0 <= nu < 0.5:
                raise ValueError(f"{owner}.poisson_ratio: must lie in [0, 0.5), got {self.poisson_ratio!r}")
            object.__setattr__(self, "poisson_ratio", nu)
        if not isinstance(self.name, str):
            raise TypeError(f"Bar.name: must be a string, got {type(self.name).__name__} {self.name!r}")

    @classmethod
    def from_gauged(cls, gauged: GaugedBar, gauge_distance: Any, name: str = "") -> "Bar":
        """The bar of a :class:`~rodimpact.signals.GaugedBar` (as :func:`rodimpact.io.hoppybar_bar` returns it:
        E, density, area, Poisson ratio) with its gauge ``gauge_distance`` (m) from the specimen face."""
        if not isinstance(gauged, GaugedBar):
            raise TypeError(f"gauged: must be a rodimpact.signals.GaugedBar, got {type(gauged).__name__}")
        return cls(material=Material(gauged.youngs_modulus, gauged.density, gauged.name),
                   area=gauged.area, gauge_distance=gauge_distance, poisson_ratio=gauged.poisson_ratio,
                   name=name or gauged.name)

    @property
    def youngs_modulus(self) -> float:
        """E_b (Pa)."""
        return self.material.youngs_modulus

    @property
    def wave_speed(self) -> float:
        """Bar wave speed ``c_b = sqrt(E_b / rho_b)`` (m/s)."""
        return self.material.wave_speed

    @property
    def stiffness(self) -> float:
        """``E_b A_b`` (N): the normal force per unit strain, ``N = E_b A_b eps``."""
        return self.material.youngs_modulus * self.area

    @property
    def travel_time(self) -> float:
        """Time (s) a pulse takes between the gauge and the specimen face, ``gauge_distance / c_b``."""
        return self.gauge_distance / self.wave_speed


@dataclass(frozen=True)
class SpecimenGeometry:
    """The specimen's initial length L0 (m) and cross-section: exactly one of ``diameter`` (m, a cylinder) and
    ``area`` A0 (m^2), given by name."""

    length: float
    _: KW_ONLY
    diameter: Optional[float] = None
    area: Optional[float] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", positive("SpecimenGeometry.length", self.length, "m"))
        d, a = _section("SpecimenGeometry", self.diameter, self.area)
        object.__setattr__(self, "diameter", d)
        object.__setattr__(self, "area", a)
