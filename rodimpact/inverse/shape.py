"""From a striker impedance profile to a striker someone can machine.

Element q (counted from the impact face) of travel time dt has impedance Z_q = A_q rho c (thesis eq. 2.8),
so for a chosen material its cross-section area is A_q = Z_q / (rho c) and its length is c dt (eq. 3.1). A
solid striker has the diameter d_q = sqrt(4 A_q / pi); a striker with a through bore of diameter d_i (flushing
channel) has the outer diameter sqrt(4 A_q / pi + d_i^2). The mass is sum rho A_q c dt = dt sum Z_q,
whatever the material.
"""

from __future__ import annotations

import csv
import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np

from .._validate import caller_stacklevel, non_negative, positive, positive_array
from ..rods.material import STEEL, Material
from ..rods.rod import Rod
from ..rods.segments import Cylinder, Tube
from ._files import write_new_file

#: Default limit of the outer-diameter ratio max/min above which a profile is reported as impractical.
MAX_DIAMETER_RATIO = 10.0


@dataclass(frozen=True, eq=False)
class StrikerShape:
    """Geometry of a synthesized striker, elements listed from the impact face (q = 1..m).

    Parameters
    ----------
    impedance:
        Z_q in N s/m.
    dt:
        Travel time of each element, s.
    material:
        Striker material (default thesis steel).
    bore:
        Diameter of a central through bore, m (0: solid striker).
    max_diameter_ratio:
        Outer-diameter ratio max/min above which :attr:`practical` is False and a warning is issued.
    """

    impedance: np.ndarray
    dt: float
    material: Material = STEEL
    bore: float = 0.0
    max_diameter_ratio: float = MAX_DIAMETER_RATIO

    def __post_init__(self) -> None:
        object.__setattr__(self, "impedance", positive_array("impedance", self.impedance))
        object.__setattr__(self, "dt", positive("dt", self.dt, "s"))
        if not isinstance(self.material, Material):
            raise TypeError(f"material: must be a Material, got {type(self.material).__name__}")
        object.__setattr__(self, "bore", non_negative("bore", self.bore, "m"))
        object.__setattr__(self, "max_diameter_ratio", positive("max_diameter_ratio", self.max_diameter_ratio))
        if not self.practical:
            warnings.warn(
                f"striker shape: the outer diameter varies by a factor {self.diameter_ratio:.3g} "
                f"({self.outer_diameter.min() * 1e3:.4g} mm to {self.outer_diameter.max() * 1e3:.4g} mm), more "
                f"than {self.max_diameter_ratio:g}; such a striker is impractical to make and its large steps "
                "strain the 1D model", stacklevel=caller_stacklevel())

    # ------------------------------------------------------------------ geometry
    @property
    def n_elements(self) -> int:
        """Number of elements m."""
        return int(self.impedance.size)

    @property
    def element_length(self) -> float:
        """Length of every element, c dt (m)."""
        return self.material.wave_speed * self.dt

    @property
    def boundaries(self) -> np.ndarray:
        """Distances of the element boundaries from the impact face, (m + 1,) m."""
        return self.element_length * np.arange(self.n_elements + 1)

    @property
    def area(self) -> np.ndarray:
        """Cross-section areas A_q = Z_q / (rho c), m^2."""
        return self.impedance / (self.material.density * self.material.wave_speed)

    @property
    def outer_diameter(self) -> np.ndarray:
        """Outer diameters sqrt(4 A / pi + bore^2), m."""
        return np.sqrt(4.0 * self.area / math.pi + self.bore ** 2)

    @property
    def wall_thickness(self) -> np.ndarray:
        """(outer - bore) / 2 for a bored striker, the radius for a solid one, m."""
        return 0.5 * (self.outer_diameter - self.bore)

    @property
    def length(self) -> float:
        """Striker length, m."""
        return self.element_length * self.n_elements

    @property
    def mass(self) -> float:
        """Striker mass dt * sum Z_q, kg."""
        return float(self.dt * self.impedance.sum())

    @property
    def diameter_ratio(self) -> float:
        """max / min outer diameter."""
        d = self.outer_diameter
        return float(d.max() / d.min())

    @property
    def practical(self) -> bool:
        """False when the outer-diameter ratio exceeds ``max_diameter_ratio``."""
        return self.diameter_ratio <= self.max_diameter_ratio

    # ------------------------------------------------------------------ outputs
    def to_rod(self, name: Optional[str] = "striker") -> Rod:
        """The striker as a geometric :class:`Rod` (cylinders, or tubes around the bore), listed left to right,
        i.e. the element farthest from the impact face first, the impact face at the right end."""
        ell = self.element_length
        mat = self.material
        d = self.outer_diameter[::-1]
        # merge runs of equal diameter into one segment each
        cuts = np.flatnonzero(np.diff(d) != 0) + 1
        starts = np.concatenate([[0], cuts])
        stops = np.concatenate([cuts, [d.size]])
        if self.bore > 0.0:
            segs = [Tube((b - a) * ell, float(d[a]), self.bore, material=mat) for a, b in zip(starts, stops)]
        else:
            segs = [Cylinder((b - a) * ell, float(d[a]), material=mat) for a, b in zip(starts, stops)]
        return Rod(segs, mat, name)

    def to_csv(self, path: str | Path, overwrite: bool = False) -> Path:
        """Write the profile, one row per element from the impact face (SI units), and return the path.
        An existing file is refused unless ``overwrite=True``; the file is written atomically."""
        return write_new_file(path, self._write_csv, overwrite)

    def _write_csv(self, path: Path) -> None:
        th = self.dt * np.arange(self.n_elements)
        s = self.boundaries
        with path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow([f"# striker profile: material {self.material.name or 'custom'} "
                        f"(E = {self.material.youngs_modulus:.6g} Pa, rho = {self.material.density:.6g} kg/m^3), "
                        f"bore {self.bore:.6g} m, length {self.length:.6g} m, mass {self.mass:.6g} kg"])
            w.writerow(["element", "s_start_m", "s_end_m", "theta_start_s", "impedance_Ns_per_m", "area_m2",
                        "outer_diameter_m", "inner_diameter_m"])
            for q in range(self.n_elements):
                w.writerow([q + 1, repr(float(s[q])), repr(float(s[q + 1])), repr(float(th[q])),
                            repr(float(self.impedance[q])), repr(float(self.area[q])),
                            repr(float(self.outer_diameter[q])), repr(self.bore)])

    def summary(self) -> str:
        """One paragraph: length, mass, diameters and practicality."""
        d = self.outer_diameter
        kind = f"bored (d_i = {self.bore * 1e3:.4g} mm)" if self.bore > 0 else "solid"
        return (f"{kind} {self.material.name or 'custom-material'} striker of {self.n_elements} elements: length "
                f"{self.length:.6g} m, mass {self.mass:.6g} kg, outer diameter {d.min() * 1e3:.4g}..."
                f"{d.max() * 1e3:.4g} mm (ratio {self.diameter_ratio:.3g}"
                f"{'' if self.practical else ', impractical'})")


def impedance_to_shape(impedance: np.ndarray, dt: float, material: Material = STEEL, bore: float = 0.0,
                       max_diameter_ratio: float = MAX_DIAMETER_RATIO) -> StrikerShape:
    """The :class:`StrikerShape` for impedances Z_q (N s/m, from the impact face) of elements of travel time
    ``dt`` (s) made of ``material``, solid or with a central ``bore`` (m)."""
    return StrikerShape(np.asarray(impedance, dtype=float), dt, material, bore, max_diameter_ratio)
