"""Rectangular response of a passive struck chain by a band-limited sweep (thesis Sec. 4.1.2, eq. 4.12).

The rectangular response G is the force and velocity at one node p of the struck system at rest when its
impact face is driven by a unit force for two steps (one window). The direct solver gets it by running the
whole lattice for t_dt + 2n - 1 steps; :func:`rectangular_response` runs the same lattice equations but only
where they can matter (the domain of dependence). :func:`chain_response` does the same for any force history
at the face (the face response of Step 1 of the synthesis: node p = the face, 2n steps, a triangle of n^2
node updates instead of 2n times the struck system):

* ahead of the wavefront the lattice is still at rest (node k is reached after k steps);
* a node k at step i can influence the node p at step t only if |p - k| <= t - i; nodes outside the backward
  cone of the last requested step are skipped (their values would never reach p in time).

* inside the band only the nodes with a reflection (R != 0) cost anything: the sweep keeps the travelling
  waves in the frame in which they move (see :func:`_sweep`), where a node between equal impedances is no
  operation. A uniform section is free; runs of reflecting nodes (a taper, a profile that changes every
  element) are updated as contiguous views, which the compiler vectorises.

For the percussion-drilling string (node p at the far end, t_dt = 5.5 n steps) the band is 2n nodes wide
instead of 5.5 n, and of the string's 4 n nodes only the section joints and the steps of the bit's taper
reflect (about 44 nodes at every n). Same lattice, the same operations at the reflecting
interior nodes, the ends (:func:`rodimpact.direct._kernels.end_solve`) and the node read-out as the compiled
direct solver, so the result equals it to rounding (bit for bit on a single rod; bonded junctions between rods
are plain interior nodes here, which differs from the direct solver's junction law in the last bits).

Symbols: Z impedance of each element (N s/m), R_k = (Z_k - Z_{k-1}) / (Z_k + Z_{k-1}) reflection factor of
node k between elements k-1 and k (eq. 2.40), f / g right- / left-going force waves in each element
(N = f + g, Z v = g - f, thesis Sec. 2.3.2).
"""

from __future__ import annotations

from typing import Optional

import numpy as np
from numba import njit

from ..direct import boundary as BL
from ..lattice import tolerance
from ..lattice.lattice import build_lattice
from ..rods.conditions import BitRockEnd, Bonded, FixedEnd, FreeEnd, NonReflectingEnd, SpringEnd
from ..rods.system import System


def _sweep(z, refl, blocks, node, steps, end_code, end_p0, end_p1, dt, drive):
    """Force and velocity of node ``node`` (0 = impact face, z.size = far end) in steps 0..steps-1 of the
    lattice at rest whose face is driven by the force ``drive[i]`` in step i (N, tension positive; 0 after
    the end of ``drive``). ``blocks``: rows [a, b) of consecutive interior nodes with a reflection (R != 0).

    The waves are kept in the frame in which they travel: f_i(k) = F[k - i + steps] and g_i(k) = G[k + i] at
    step i. A node without reflection passes both waves on unchanged (f_{i+1}(k) = f_i(k - 1),
    g_{i+1}(k - 1) = g_i(k)), which in this frame is no operation at all; a node with reflection changes the
    two slots in place (the slot of f_i(k - 1) becomes f_{i+1}(k), that of g_i(k) becomes g_{i+1}(k - 1)), and
    the face and the far end write fresh slots. A step therefore costs the reflecting nodes of the band, not
    its length: a uniform section is free."""
    n_el = z.size
    e = n_el - 1
    F = np.zeros(n_el + steps + 1)
    G = np.zeros(n_el + steps + 1)
    force = np.zeros(steps)
    velocity = np.zeros(steps)
    delta = 0.0
    delta_max = 0.0
    for i in range(steps):
        s = steps - i                              # f_i(k) = F[k + s], g_i(k) = G[k + i]
        reach = steps - 1 - i                      # steps left in which a change can still reach the node
        k_lo = max(node - reach - 1, 0)            # nodes k_lo..k_hi can matter (one node of margin)
        k_hi = min(node + reach + 1, i + 1, n_el)
        # reads of step i first: the reflecting nodes below overwrite slots of step i
        if 0 < node < n_el:                        # interior node (eqs. 3.5-3.7), from the element states
            a = node - 1
            n_a = F[a + s] + G[a + i]
            v_a = (G[a + i] - F[a + s]) / z[a]
            n_b = F[node + s] + G[node + i]
            v_b = (G[node + i] - F[node + s]) / z[node]
            vn = (n_b - n_a + z[a] * v_a + z[node] * v_b) / (z[a] + z[node])
            force[i] = n_a + z[a] * (vn - v_a)
            velocity[i] = vn
        if k_lo == 0:                              # impact face: N^- = prescribed force (eq. 3.16)
            value = drive[i] if i < drive.size else 0.0
            f0 = F[s]
            g0 = G[i]
            if node == 0:
                force[i] = value
                velocity[i] = -(value - ((f0 + g0) + z[0] * ((g0 - f0) / z[0]))) / z[0]
            F[s - 1] = value - g0                  # f_{i+1}(0), a fresh slot
        if k_hi == n_el:                           # far end: the direct solver's end law
            fe = F[e + s]
            ge = G[e + i]
            n_e = fe + ge
            v_e = (ge - fe) / z[e]
            w, nn, delta_max = BL.end_solve(end_code, n_e - z[e] * v_e, z[e], 0.0, end_p0, end_p1, delta, delta_max,
                                            dt)
            delta += w * dt
            if node == n_el:
                force[i] = nn
                velocity[i] = w
            G[e + i + 1] = nn - fe                 # g_{i+1}(e), a fresh slot
        k1 = max(k_lo, 1)                          # interior nodes k1..k2 of the band
        k2 = min(k_hi, n_el - 1)
        for q in range(blocks.shape[0]):
            a = max(blocks[q, 0], k1)
            b = min(blocks[q, 1], k2 + 1)
            if a >= b:
                continue
            # nodes a..b-1 as views indexed from 0 (the compiler vectorises): f_i(k-1), g_i(k), R_k
            fa_v = F[a - 1 + s:b - 1 + s]
            gb_v = G[a + i:b + i]
            r_v = refl[a:b]
            for j in range(b - a):
                fa = fa_v[j]
                gb = gb_v[j]
                sc = r_v[j] * (fa - gb)
                gb_v[j] = gb + sc                  # g_{i+1}(k - 1)
                fa_v[j] = fa + sc                  # f_{i+1}(k)
    return force, velocity


def reflecting_blocks(refl: np.ndarray) -> np.ndarray:
    """Rows [a, b) of consecutive interior nodes k (1 <= k < refl.size) with a reflection factor refl[k] != 0."""
    on = np.zeros(refl.size + 1, dtype=np.int8)
    on[1:refl.size] = refl[1:] != 0.0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], on])))
    return edges.reshape(-1, 2).astype(np.int64)


_sweep_numba = njit(cache=True, error_model="numpy")(_sweep)


def _far_end(system: System, z_last: float) -> Optional[tuple[int, float, float]]:
    """Kernel code and parameters of a passive far end at rest (None for the others)."""
    right = system.right
    if isinstance(right, FreeEnd):
        return BL.FREE, 0.0, 0.0
    if isinstance(right, FixedEnd):
        return BL.FIXED, 0.0, 0.0
    if isinstance(right, NonReflectingEnd):      # continuation at rest: incoming invariant 0
        return BL.NONREFLECTING, z_last if right.impedance is None else right.impedance, 0.0
    if isinstance(right, SpringEnd):
        return BL.SPRING, right.stiffness, right.damping
    if isinstance(right, BitRockEnd):
        return BL.BITROCK, right.loading_stiffness, right.unloading_stiffness
    return None


def chain_response(system: System, node: int, dt: float, steps: int,
                   drive: np.ndarray) -> Optional[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Force (N) and velocity (m/s) of lattice node ``node`` per step when the impact face of the struck
    system at rest is driven by the force ``drive[i]`` in step i, and the lattice impedances; None when the
    system is not a passive chain at rest (moving or loaded parts, non-bonded junctions, driven far end):
    then the direct solver is needed."""
    if (system.loads or any(s is not None for s in system.initial) or any(v != 0.0 for v in system.velocities)
            or not all(isinstance(j, Bonded) for j in system.junctions)):
        return None
    lattice = build_lattice(system, dt)
    z = lattice.impedance
    end = _far_end(system, float(z[-1]))
    if end is None:
        return None
    tolerance.check(system, lattice, True)     # the synthesis runs at the user's dt: a warning, as in simulate
    refl = np.zeros(z.size)
    refl[1:] = (z[1:] - z[:-1]) / (z[1:] + z[:-1])
    force, velocity = _sweep_numba(z, refl, reflecting_blocks(refl), int(node), int(steps), end[0], end[1], end[2],
                                   float(dt), np.ascontiguousarray(drive, dtype=float))
    return force, velocity, z


def rectangular_response(system: System, node: int, dt: float,
                         steps: int) -> Optional[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """:func:`chain_response` for a unit force on the impact face during the first window (two steps),
    the rectangular response of eq. 4.12."""
    return chain_response(system, node, dt, steps, np.ones(2))
