"""Turning one rod into equal-travel-time elements (thesis eq. 3.1: l_j = c_j dt).

Rule (documented in docs/method.md, "Discretisation"):

1. The rod's total travel time theta_L = sum(l_s / c_s) is rounded to n = round(theta_L / dt) >= 1 steps.
2. Node m sits at travel time theta_m = m * theta_L / n from the left end (so the rod's true length is kept
   and every element covers the same share of travel time).
3. Element j gets the travel-time average of the impedance over its interval,
   Z_j = (1/(theta_{j+1}-theta_j)) * int Z dtheta = m_j / (theta_{j+1}-theta_j), with m_j the element's true mass
   (Gauss-Legendre quadrature per segment piece). Segment ends that fall between nodes are thus smeared over
   one element, conserving mass.
4. On the lattice every element takes exactly dt, so the lattice wave speed is l_j/dt and the lattice mass
   Z_j dt: when theta_L is not a whole number of steps, wave speeds and masses of that rod are scaled by the
   factor n dt / theta_L (reported as ``time_scale``), lengths are exact.

Rods built with :meth:`Rod.from_impedance` whose ``dt`` equals the lattice step (or is an integer multiple of
it) are taken element by element without any averaging: the lattice is then exactly the model.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..rods.rod import Rod

_GAUSS_POINTS = 8


@dataclass(frozen=True)
class RodDiscretization:
    """The elements of one rod (left to right) and how well they represent it."""

    impedance: np.ndarray          # Z_j, N s/m
    length: np.ndarray             # element lengths l_j, m (true geometry)
    n_elements: int
    time_scale: float              # n dt / theta_L (1 means the travel time is exact)
    true_length: float
    true_mass: float
    lattice_mass: float            # sum Z_j dt
    true_travel_time: float
    exact: bool                    # True when the rod is represented without approximation
    max_boundary_offset: float     # largest distance of a segment end from its nearest node, m
    method: str                    # human-readable description


def discretize_rod(rod: Rod, dt: float, index: int = 0) -> RodDiscretization:
    """Discretise ``rod`` into elements of travel time ``dt``; raises if a segment cannot be resolved."""
    native = rod.native
    if native is not None:
        ratio = native.dt / dt
        k = int(round(ratio))
        if k >= 1 and abs(ratio - k) <= 1e-9 * ratio:
            z = native.impedance.copy() if k == 1 else np.repeat(native.impedance, k)
            length = np.full(z.size, native.wave_speed * dt)
            mass = float(native.impedance.sum() * native.dt)
            return RodDiscretization(z, length, z.size, 1.0, rod.length, mass,
                                     mass if k == 1 and dt == native.dt else float(z.sum() * dt),
                                     native.impedance.size * native.dt, True, 0.0,
                                     f"impedance-level rod taken element by element ({k} lattice element(s) each)")
    tau = rod.segment_travel_times
    theta_total = float(tau.sum())
    for i, t in enumerate(tau):
        if t < 0.5 * dt:
            raise ValueError(
                f"dt: the time step {dt:.4g} s cannot resolve rod {index} ({rod.name or 'unnamed'}) segment {i} "
                f"({type(rod.segments[i]).__name__}, length {rod.segments[i].length:.4g} m, travel time {t:.4g} s); "
                f"use dt <= {t:.4g} s (preferably several times smaller)")
    n = max(1, int(round(theta_total / dt)))
    theta_nodes = np.linspace(0.0, theta_total, n + 1)
    seg_theta = np.concatenate([[0.0], np.cumsum(tau)])
    seg_x = rod.segment_bounds
    # x(theta): piecewise linear, slope c_s within segment s
    x_nodes = np.interp(theta_nodes, seg_theta, seg_x)
    mass = np.zeros(n)
    g, w = np.polynomial.legendre.leggauss(_GAUSS_POINTS)
    for s, seg in enumerate(rod.segments):
        mat = rod.segment_material(s)
        lo = np.searchsorted(x_nodes, seg_x[s], side="right") - 1
        hi = np.searchsorted(x_nodes, seg_x[s + 1], side="left")
        j = np.arange(max(lo, 0), min(hi, n))
        a = np.maximum(x_nodes[j], seg_x[s])
        b = np.minimum(x_nodes[j + 1], seg_x[s + 1])
        keep = b > a
        j, a, b = j[keep], a[keep], b[keep]
        pts = 0.5 * (b - a)[:, None] * (g[None, :] + 1.0) + a[:, None] - seg_x[s]
        area = np.asarray(seg.area(pts), dtype=float)
        np.add.at(mass, j, mat.density * 0.5 * (b - a) * (area @ w))
    dtheta = theta_total / n
    z = mass / dtheta
    offsets = [np.min(np.abs(x_nodes - xb)) for xb in seg_x]
    return RodDiscretization(
        impedance=z, length=np.diff(x_nodes), n_elements=n, time_scale=n * dt / theta_total,
        true_length=rod.length, true_mass=rod.mass, lattice_mass=float(z.sum() * dt),
        true_travel_time=theta_total, exact=False, max_boundary_offset=float(max(offsets)),
        method=("travel-time average of Z per element (mass-conserving); nodes equally spaced in travel time; "
                "segment ends between nodes smeared over one element"))
