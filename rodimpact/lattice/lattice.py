"""The equal-travel-time lattice of a whole system (all rods share one dt)."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from .._validate import fits_in_memory, positive
from ..rods.system import System
from ._kernels import positions
from .discretize import RodDiscretization, discretize_rod


@dataclass(frozen=True)
class Lattice:
    """Elements of all rods concatenated left to right.

    Attributes
    ----------
    dt:
        Travel time of every element, s.
    impedance:
        Z_j, N s/m, shape (n_elements,).
    element_length:
        l_j, m (true geometry).
    rod_start:
        Index of each rod's first element, shape (n_rods + 1,) with the total count last.
    node_x:
        Reference global position of every node, rod by rod (n_j + 1 nodes per rod), shape (n_elements + n_rods,).
    element_x:
        Reference global position of every element centre, shape (n_elements,).
    rods:
        Per-rod :class:`RodDiscretization` (how geometry was approximated).
    """

    dt: float
    impedance: np.ndarray
    element_length: np.ndarray
    rod_start: np.ndarray
    node_x: np.ndarray
    element_x: np.ndarray
    rods: tuple[RodDiscretization, ...]

    @property
    def n_elements(self) -> int:
        """Total number of elements."""
        return int(self.impedance.size)

    @property
    def n_rods(self) -> int:
        """Number of rods."""
        return len(self.rods)

    @property
    def element_rod(self) -> np.ndarray:
        """Rod index of every element."""
        return np.repeat(np.arange(self.n_rods), np.diff(self.rod_start))

    @property
    def node_rod(self) -> np.ndarray:
        """Rod index of every node (n_j + 1 per rod)."""
        return np.repeat(np.arange(self.n_rods), np.diff(self.rod_start) + 1)

    def node_index(self, rod: int, local: int) -> int:
        """Global node index of node ``local`` (0 = left end) of rod ``rod``."""
        return int(self.rod_start[rod] + rod + local)

    def nearest_node(self, rod: int, position: float) -> tuple[int, float]:
        """Local index of the node of ``rod`` nearest to ``position`` (m from the rod's left end) and its
        reference position in the same coordinate."""
        s, e = self.rod_start[rod], self.rod_start[rod + 1]
        xs = np.concatenate([[0.0], np.cumsum(self.element_length[s:e])])
        m = int(np.argmin(np.abs(xs - position)))
        return m, float(xs[m])

    def report(self) -> str:
        """How each rod was approximated: elements, time scale, length and mass errors."""
        lines = [f"lattice: dt = {self.dt:.6g} s, {self.n_elements} elements in {self.n_rods} rod(s)"]
        for i, r in enumerate(self.rods):
            dm = (r.lattice_mass - r.true_mass) / r.true_mass
            lines.append(
                f"  rod {i}: {r.n_elements} elements, {'exact' if r.exact else 'approximated'}; "
                f"travel time {r.true_travel_time:.6g} s -> {r.n_elements * self.dt:.6g} s "
                f"(time scale {r.time_scale:.8f}); length {r.true_length:.6g} m (exact); "
                f"mass {r.true_mass:.6g} kg -> {r.lattice_mass:.6g} kg ({dm:+.2e} relative); "
                f"largest segment-end offset from a node {r.max_boundary_offset:.3g} m; {r.method}")
        return "\n".join(lines)


def build_lattice(system: System, dt: float) -> Lattice:
    """Discretise every rod of ``system`` with the common time step ``dt`` (s)."""
    dt = positive("dt", dt, "s")
    n_est = sum(rod.total_travel_time for rod in system.rods) / dt
    # about 16 arrays of 8 bytes per element live at once (lattice, discretisation, kernel state)
    fits_in_memory("dt", 128.0 * n_est, f"{n_est:.3g} lattice elements (dt = {dt:.4g} s)",
                   "use a larger time step (fewer elements)")
    discs = tuple(discretize_rod(rod, dt, i) for i, rod in enumerate(system.rods))
    z = np.concatenate([d.impedance for d in discs])
    length = np.concatenate([d.length for d in discs])
    counts = [d.n_elements for d in discs]
    rod_start = np.array([0, *itertools.accumulate(counts)], dtype=np.int64)
    node_x, element_x = positions(length, rod_start, system.rod_offsets())
    return Lattice(dt, z, length, rod_start, node_x, element_x, discs)



def default_time_step(system: System, min_elements: int = 200, min_per_segment: int = 4) -> float:
    """A time step for geometry-based rods when the user gives none: every segment gets at least
    ``min_per_segment`` elements and the rod with the longest travel time at least ``min_elements``, made
    smaller where needed so that every rod's travel time and mass are represented within 1 %
    (:func:`rodimpact.lattice.tolerance.resolving_time_step`). Rods built from impedances impose their own dt
    (the smallest one), divided by the smallest whole number that represents the other rods within 1 %."""
    from .tolerance import resolving_time_step, within

    natives = [r.native.dt for r in system.rods if r.native is not None]
    if natives:   # keep impedance-level rods exact: their dt, or a whole fraction of it that suits the others
        base = min(natives)
        return next((base / k for k in range(1, 1001) if within(system, base / k)), base)

    longest = max(r.total_travel_time for r in system.rods)
    shortest_segment = min(float(r.segment_travel_times.min()) for r in system.rods)
    return resolving_time_step(system, min(longest / min_elements, shortest_segment / min_per_segment))
