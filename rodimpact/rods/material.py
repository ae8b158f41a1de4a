"""Linear elastic materials (SI units)."""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from typing import Any

from .._validate import positive
from .declared import check, quantity


@dataclass(frozen=True)
class Material:
    """A homogeneous linear elastic material.

    Parameters
    ----------
    youngs_modulus:
        Young's modulus E in Pa.
    density:
        Mass density rho in kg/m^3.
    name:
        Optional label used in reports.
    """

    youngs_modulus: float = quantity("pressure", "Young's modulus E.")
    density: float = quantity("density", "Density rho.")
    name: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise TypeError(f"Material.name: must be a string, got {type(self.name).__name__} {self.name!r} "
                            "(Material takes youngs_modulus, density, name; the Poisson ratio is not used in 1D)")
        check(self)

    @property
    def wave_speed(self) -> float:
        """Bar wave speed c = sqrt(E / rho) in m/s (thesis eq. 2.9)."""
        return math.sqrt(self.youngs_modulus / self.density)

    def impedance(self, area: float) -> float:
        """Characteristic impedance Z = A rho c in N s/m for a cross-section area in m^2 (thesis eq. 2.8)."""
        return positive("area", area, "m^2") * self.density * self.wave_speed

    def scaled(self, youngs_factor: float = 1.0, density_factor: float = 1.0, name: str = "") -> "Material":
        """A copy with E and rho multiplied by the given factors (thesis setup 3: 1.5 E0, 1.2 rho0)."""
        return Material(self.youngs_modulus * youngs_factor, self.density * density_factor, name or self.name)

    @classmethod
    def preset(cls, name: str, where: str = "material") -> "Material":
        """A named material from :data:`MATERIALS` (case-insensitive; ``aluminum`` spellings too); an unknown
        name is a ``ValueError`` naming ``where`` with the closest preset."""
        if not isinstance(name, str):
            raise TypeError(f"{where}: a preset name must be a string, got {type(name).__name__} {name!r}")
        key = name.strip().lower().replace("aluminum", "aluminium")
        if key not in MATERIALS:
            near = difflib.get_close_matches(key, list(MATERIALS), n=1, cutoff=0.6)
            hint = f"did you mean {near[0]!r}? " if near else ""
            raise ValueError(f"{where}: unknown material preset {name!r}; {hint}valid presets are "
                             f"{', '.join(repr(k) for k in sorted(MATERIALS))}, or give Material(youngs_modulus, "
                             f"density)")
        return MATERIALS[key]


def as_material(value: Any, where: str) -> Material:
    """A :class:`Material`, or a preset name (``"steel"``, as model files accept) turned into one; an unknown name
    is a ``ValueError`` with did-you-mean, any other type a ``TypeError``, both naming ``where``."""
    if isinstance(value, Material):
        return value
    if isinstance(value, str):
        return Material.preset(value, where)
    raise TypeError(f"{where}: must be a Material or a preset name ({', '.join(repr(k) for k in sorted(MATERIALS))}), "
                    f"got {type(value).__name__}")


#: Steel as used throughout the thesis (Tabs. 3.2, 3.3, 5.2): E = 210 GPa, rho = 7840 kg/m^3.
STEEL = Material(210e9, 7840.0, "steel")
#: Aluminium 7075-T6 (mini-Kolsky bars of the HopPyBar data set): E = 71.7 GPa, rho = 2810 kg/m^3.
ALUMINIUM_7075 = Material(71.7e9, 2810.0, "aluminium-7075-t6")
#: Titanium Ti-6Al-4V (LANL Kolsky bars): E = 113.8 GPa, rho = 4430 kg/m^3 (typical handbook values).
TITANIUM_TI6AL4V = Material(113.8e9, 4430.0, "ti-6al-4v")

MATERIALS: dict[str, Material] = {m.name: m for m in (STEEL, ALUMINIUM_7075, TITANIUM_TI6AL4V)}
