"""A rod: ordered segments from left to right, each with a shape and a material."""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Sequence as SequenceABC
from dataclasses import dataclass, field
from typing import Optional, Sequence

import numpy as np

from .._validate import positive, positive_array
from .material import STEEL, Material, as_material
from .plausibility import check_rod
from .segments import Cylinder, Segment


@dataclass(frozen=True)
class ImpedanceProfile:
    """The exact element-level description of a rod built with :meth:`Rod.from_impedance`.

    ``impedance[j]`` (N s/m) is the impedance of element j (left to right); every element has travel time
    ``dt`` (s) and wave speed ``wave_speed`` (m/s).
    """

    impedance: np.ndarray
    dt: float
    wave_speed: float


class _CylinderRuns(SequenceABC):
    """The segments of an impedance-level rod: one :class:`Cylinder` per run of equal impedance, listed left to
    right and made on demand (a rod with 10^6 different elements does not hold 10^6 objects).

    Behaves like the tuple of cylinders it stands for (``len``, indexing, iteration, equality with a tuple);
    ``lengths`` (m) and ``diameters`` (m) are the cylinders' fields, all of ``material``.
    """

    def __init__(self, lengths: np.ndarray, diameters: np.ndarray, material: Material) -> None:
        self.lengths = lengths
        self.diameters = diameters
        for a in (lengths, diameters):
            a.setflags(write=False)                       # a Rod is immutable
        self.material = material
        self._areas: Optional[np.ndarray] = None

    def __len__(self) -> int:
        return int(self.lengths.size)

    def _cylinder(self, length: float, diameter: float) -> Cylinder:
        # the values were validated for the whole rod at once: skip the per-segment checks of Cylinder
        cyl = object.__new__(Cylinder)
        cyl.__dict__.update(length=length, material=self.material, diameter=diameter)
        return cyl

    def __getitem__(self, i):  # type: ignore[override]
        if isinstance(i, slice):
            return tuple(self[j] for j in range(*i.indices(len(self))))
        j = range(len(self))[i]                        # IndexError / TypeError as for a tuple
        return self._cylinder(float(self.lengths[j]), float(self.diameters[j]))

    def __iter__(self) -> Iterator[Cylinder]:
        for length, diameter in zip(self.lengths.tolist(), self.diameters.tolist()):
            yield self._cylinder(length, diameter)

    def areas(self) -> np.ndarray:
        """Cross-section area of every cylinder, m^2, computed as :meth:`Cylinder.area` does (same rounding)."""
        if self._areas is None:
            self._areas = np.array([0.25 * math.pi * d**2 for d in self.diameters.tolist()])
        return self._areas

    def __eq__(self, other: object) -> bool:
        if isinstance(other, _CylinderRuns):
            return (self.material == other.material and np.array_equal(self.lengths, other.lengths)
                    and np.array_equal(self.diameters, other.diameters))
        if isinstance(other, tuple):
            return len(other) == len(self) and all(a == b for a, b in zip(self, other))
        return NotImplemented

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"({len(self)} Cylinder(s) of an impedance-level rod)"


@dataclass(frozen=True, eq=False)
class Rod:
    """A rod made of ``segments`` listed left to right.

    Parameters
    ----------
    segments:
        Sequence of :class:`~rodimpact.rods.segments.Segment`.
    material:
        Material of every segment that does not carry its own (default: thesis steel).
    name:
        Optional label for reports and plots.

    Positions ``x`` passed to the profile methods are measured from the rod's left end (m).
    """

    segments: tuple[Segment, ...]
    material: Material = STEEL
    name: Optional[str] = None
    native: Optional[ImpedanceProfile] = field(default=None, repr=False)

    def __post_init__(self) -> None:
        if isinstance(self.segments, _CylinderRuns):        # from from_impedance(), validated there
            object.__setattr__(self, "material", as_material(self.material, "Rod.material"))
            object.__setattr__(self, "_ends", np.concatenate([[0.0], np.cumsum(self.segments.lengths)]))
            return
        if isinstance(self.segments, (str, bytes)) or not isinstance(self.segments, (Segment, Iterable)):
            raise TypeError(f"Rod.segments: must be a Segment or a list of Segments (Cylinder, Cone, ...), got "
                            f"{type(self.segments).__name__}")
        segs = tuple(self.segments) if not isinstance(self.segments, Segment) else (self.segments,)
        if not segs:
            raise ValueError("Rod.segments: needs at least one segment")
        for i, s in enumerate(segs):
            if not isinstance(s, Segment):
                raise TypeError(f"Rod.segments[{i}]: must be a Segment (Cylinder, Cone, ...), got {type(s).__name__}")
        object.__setattr__(self, "material", as_material(self.material, "Rod.material"))
        object.__setattr__(self, "segments", segs)
        ends = np.concatenate([[0.0], np.cumsum([s.length for s in segs])])
        object.__setattr__(self, "_ends", ends)
        object.__setattr__(self, "_implausible", check_rod(self))

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_impedance(cls, impedances: Sequence[float], dt: float, wave_speed: Optional[float] = None,
                       *, density: Optional[float] = None, name: Optional[str] = None) -> "Rod":
        """An impedance-level rod: element j (listed left to right) has impedance ``impedances[j]`` (N s/m)
        and travel time ``dt`` (s).

        The wave speed (default: that of :data:`STEEL`, 5175.5 m/s) only sets element lengths ``c*dt`` for
        positions; the density (default steel) only sets the equivalent cross-section area A = Z/(rho c).
        Dynamics, energies and momenta depend on Z and dt alone.
        """
        z = positive_array("impedances", impedances, unit="N s/m")
        dt = positive("dt", dt, "s")
        c = STEEL.wave_speed if wave_speed is None else positive("wave_speed", wave_speed, "m/s")
        rho = STEEL.density if density is None else positive("density", density, "kg/m^3")
        mat = Material(rho * c * c, rho, "impedance-level")
        # merge runs of equal impedance into one cylinder each (made on demand: see _CylinderRuns)
        cuts = np.flatnonzero(np.diff(z) != 0) + 1
        starts = np.concatenate([[0], cuts])
        stops = np.concatenate([cuts, [z.size]])
        with np.errstate(over="ignore", under="ignore"):          # checked just below
            lengths = (stops - starts) * c * dt
            diameters = np.sqrt(4.0 * z[starts] / (rho * c) / math.pi)
        for what, v, size in (("element length wave_speed * dt", lengths, lengths),
                              ("equivalent diameter", diameters, np.square(diameters))):
            bad = ~(np.isfinite(v) & (size > 0.0))
            if bad.any():
                j = int(starts[np.flatnonzero(bad)[0]])
                raise ValueError(f"impedances: element {j} (Z = {z[j]:.6g} N s/m, dt = {dt:.6g} s, wave_speed = "
                                 f"{c:.6g} m/s) gives the {what} {float(v[bad][0])!r} m; it must be finite and > 0 "
                                 "(choose values of a physical size)")
        return cls(_CylinderRuns(lengths, diameters, mat), mat, name, ImpedanceProfile(z.copy(), dt, c))

    # ------------------------------------------------------------------ geometry
    @property
    def length(self) -> float:
        """Total length in m."""
        return float(self._ends[-1])

    @property
    def segment_bounds(self) -> np.ndarray:
        """Positions of the segment ends from the left end, shape (n_segments + 1,), m."""
        return self._ends.copy()

    def segment_material(self, i: int) -> Material:
        """Material of segment ``i`` (its own or the rod's)."""
        return self.segments[i].material or self.material

    @property
    def mass(self) -> float:
        """Total mass in kg (Gauss-Legendre quadrature of rho A over each segment; rho A L for the cylinders of
        an impedance-level rod)."""
        if isinstance(self.segments, _CylinderRuns):
            runs = self.segments
            return float(np.sum(runs.material.density * runs.lengths * runs.areas()))
        total = 0.0
        g, w = np.polynomial.legendre.leggauss(16)
        for i, seg in enumerate(self.segments):
            s = 0.5 * seg.length * (g + 1.0)
            total += self.segment_material(i).density * 0.5 * seg.length * float(np.dot(w, seg.area(s)))
        return total

    def _locate(self, x) -> tuple[np.ndarray, np.ndarray]:
        xa = np.atleast_1d(np.asarray(x, dtype=float))
        if not np.all(np.isfinite(xa)) or xa.min() < -1e-12 * self.length or xa.max() > self.length * (1 + 1e-12):
            raise ValueError(f"x: positions must lie within the rod, 0 <= x <= {self.length:.6g} m, "
                             f"got range [{xa.min():.6g}, {xa.max():.6g}]")
        idx = np.clip(np.searchsorted(self._ends, xa, side="right") - 1, 0, len(self.segments) - 1)
        return xa, idx

    def _per_segment(self, x, fn, runs_fn=None) -> np.ndarray | float:
        """fn(i, s) of segment i at local positions s; for the cylinder runs of an impedance-level rod
        ``runs_fn(idx, s)`` evaluates all segments at once."""
        xa, idx = self._locate(x)
        if runs_fn is not None and isinstance(self.segments, _CylinderRuns):
            out = np.asarray(runs_fn(idx, xa - self._ends[idx]), dtype=float)
            return out if np.ndim(x) else float(out[0])
        out = np.empty_like(xa)
        for i in np.unique(idx):
            m = idx == i
            out[m] = fn(i, xa[m] - self._ends[i])
        return out if np.ndim(x) else float(out[0])

    def area(self, x) -> np.ndarray | float:
        """Cross-section area A(x) in m^2. At a segment boundary the right segment's value is returned."""
        return self._per_segment(x, lambda i, s: self.segments[i].area(s),
                                 lambda idx, s: self.segments.areas()[idx])

    def wave_speed(self, x) -> np.ndarray | float:
        """Bar wave speed c(x) = sqrt(E/rho) in m/s."""
        return self._per_segment(x, lambda i, s: np.full(s.shape, self.segment_material(i).wave_speed),
                                 lambda idx, s: np.full(s.shape, self.segments.material.wave_speed))

    def impedance(self, x) -> np.ndarray | float:
        """Characteristic impedance Z(x) = A rho c in N s/m (thesis eq. 2.8)."""
        def z(i, s):
            m = self.segment_material(i)
            return self.segments[i].area(s) * m.density * m.wave_speed
        def z_runs(idx, s):
            m = self.segments.material
            return self.segments.areas()[idx] * m.density * m.wave_speed
        return self._per_segment(x, z, z_runs)

    @property
    def segment_travel_times(self) -> np.ndarray:
        """Travel time of a wavefront through each segment, s."""
        if isinstance(self.segments, _CylinderRuns):
            return self.segments.lengths / self.segments.material.wave_speed
        return np.array([s.length / self.segment_material(i).wave_speed for i, s in enumerate(self.segments)])

    @property
    def total_travel_time(self) -> float:
        """Travel time theta(L) of a wavefront from the left to the right end, s (computed once: a rod does not
        change)."""
        theta = self.__dict__.get("_total_travel_time")
        if theta is None:
            theta = float(self.segment_travel_times.sum())
            object.__setattr__(self, "_total_travel_time", theta)
        return theta

    def travel_time(self, x) -> np.ndarray | float:
        """Travel time theta(x) = int_0^x dx'/c(x') from the left end, s (thesis eq. 2.10)."""
        before = np.concatenate([[0.0], np.cumsum(self.segment_travel_times)])
        return self._per_segment(x, lambda i, s: before[i] + s / self.segment_material(i).wave_speed,
                                 lambda idx, s: before[idx] + s / self.segments.material.wave_speed)

    def __repr__(self) -> str:
        label = f"{self.name!r}, " if self.name else ""
        return f"Rod({label}{len(self.segments)} segment(s), length={self.length:.6g} m)"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Rod):
            return NotImplemented
        same_native = (self.native is None and other.native is None) or (
            self.native is not None and other.native is not None
            and np.array_equal(self.native.impedance, other.native.impedance)
            and self.native.dt == other.native.dt and self.native.wave_speed == other.native.wave_speed)
        return (self.segments == other.segments and self.material == other.material
                and self.name == other.name and same_native)

    __hash__ = None  # type: ignore[assignment]
