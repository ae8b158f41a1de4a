"""From a striker impedance profile to a striker someone can machine.

Element q (counted from the impact face) of travel time dt has impedance Z_q = A_q rho c (thesis eq. 2.8),
so for a chosen material its cross-section area is A_q = Z_q / (rho c) and its length is c dt (eq. 3.1). A
solid striker has the diameter d_q = sqrt(4 A_q / pi); a striker with a through bore of diameter d_i (flushing
channel) has the outer diameter sqrt(4 A_q / pi + d_i^2). The mass is sum rho A_q c dt = dt sum Z_q,
whatever the material.
"""

from __future__ import annotations

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
from .._result_files import write_new_file

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

    def to_csv(self, path: str | Path, overwrite: bool = False, note: str = "") -> Path:
        """Write the profile as CSV (SI units, full precision) and return the path; the one striker-profile format
        of rodimpact (``rodimpact synthesize`` and ``rodimpact design`` write it as ``striker.csv``).

        Rows are the elements listed **left to right as the striker lies in a simulation**: the rear end first,
        the impact face last (``element_from_face`` = 1), like ``[rods.elements]`` of a model file, which reads the
        file back as the same rod (``file = 'striker.csv'``; its ``theta`` column gives the element travel time
        dt). Columns: ``element_from_face`` (q = 1..m from the impact face), ``s_start [m]`` and ``s_end [m]``
        (distances of the element's face-side and rear-side edges from the impact face), ``theta [s]`` (travel
        time of the face-side edge from the impact face, (q - 1) dt), ``impedance [N s/m]``, ``area [m^2]``,
        ``outer_diameter [m]``, ``inner_diameter [m]``. The lines before the header start with ``#`` (no quoting:
        ``pandas.read_csv(path, comment="#")`` reads the table); they state the orientation, dt, material, bore,
        length, mass and ``note`` (one line, e.g. the impact velocity), if given.

        An existing file is refused unless ``overwrite=True``; the file is written atomically."""
        if "\n" in note or "\r" in note:
            raise ValueError("note: must be a single line (it becomes a comment line of the CSV file)")
        return write_new_file(path, lambda tmp: self._write_csv(tmp, Path(path).name, note), overwrite)

    def _write_csv(self, path: Path, name: str, note: str) -> None:
        m = self.material
        comments = [
            "rodimpact striker profile: one row per element of equal travel time dt, listed LEFT TO RIGHT as the "
            "striker lies in a simulation (rear end first; impact face last, element_from_face = 1)",
            f"dt = {self.dt!r} s; {self.n_elements} elements; length {self.length:.6g} m; mass {self.mass:.6g} kg; "
            f"material {m.name or 'custom'} (E = {m.youngs_modulus:.6g} Pa; rho = {m.density:.6g} kg/m^3; "
            f"c = {m.wave_speed:.6g} m/s); bore {self.bore:.6g} m",
            *([note] if note else []),
            f"read it as a rod in a model file: [rods.elements] file = '{name}' "
            f"(dt from the theta column); wave_speed = {m.wave_speed!r} and density = {m.density!r} give the "
            "element lengths and areas of this material",
        ]
        header = ["element_from_face", "s_start [m]", "s_end [m]", "theta [s]", "impedance [N s/m]", "area [m^2]",
                  "outer_diameter [m]", "inner_diameter [m]"]
        s = self.boundaries
        theta = self.dt * np.arange(self.n_elements)
        columns = [s[:-1], s[1:], theta, self.impedance, self.area, self.outer_diameter,
                   np.full(self.n_elements, self.bore)]
        with path.open("w", encoding="utf-8", newline="") as fh:
            fh.writelines(f"# {c}\n" for c in comments)
            fh.write(",".join(header) + "\n")
            for q in range(self.n_elements - 1, -1, -1):
                fh.write(",".join([str(q + 1), *(repr(float(c[q])) for c in columns)]) + "\n")

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
