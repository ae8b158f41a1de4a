"""Kernels of the inverse problem: layer peeling of the striker (thesis Sec. 4.1.1, eqs. 4.4-4.9).

Symbols: Z = impedance (N s/m), N = normal force (N, tension positive), U = v - v_in = face velocity
relative to the striker's initial velocity (m/s); R = force reflection coefficient of a wavefront at an
interface, K = energy transmission factor (eq. 4.6).

Pure functions on arrays, no objects, I/O or warnings inside. The layer loops work on a block of layers
(:func:`peel_block_numba`, compiled with ``numba.njit(cache=True)``, plain loops; :func:`peel_block_numpy`,
the readable reference, one vectorised numpy expression per layer); the O(n^2) peel is one block of all layers
(:func:`peel_numba`, :func:`peel_numpy`), the superfast peel of :mod:`rodimpact.inverse._schur` many small
ones, for which the block loops also build the block's layer matrix.

The method (derived in docs/inverse.md, "Step 2: peel the striker layer by layer")
---------------------------------------------------------
The striker (rod 1) is stress-free and moves uniformly at v_in before the impact, carries no nodal loads and
consists of elements of travel time dt, counted q = 1, 2, ... from the impact face. In element q write the
state as two force waves relative to the initial state: ``g`` travelling away from the impact face and ``f``
travelling towards it, N = g + f, Z_q U = g - f. Every path that leaves the face and comes back is an even
number of steps long, so the samples of the face history at the window starts, k = 0, 2, 4, ..., form a
closed system ("sample" s = 0 .. n-1 is step 2s, window s + 1).

* Face, element 1: before the first reflection returns, f = 0, so Z_1 = N[0]/U[0] (eq. 4.4); then
  g = (N + Z_1 U)/2 and f = (N - Z_1 U)/2 for all samples.
* Interface q (between elements q and q+1), wavefront arriving at step q: g at interface q, sample s, is the
  g leaving interface q-1 one step earlier (same s); f at interface q, sample s, is the f arriving at
  interface q-1 one step later (sample s + 1). Storing f of interface q, sample s, at ``F[s + q]`` makes this
  shift free: the arrays stay in place.
* The wavefront g_0 reaching interface q meets nothing coming back (element q+1 is still at rest), so the
  wave f_1 that interface q returns is its reflection: R_{q,q+1} = f_1/g_0 = (Z_{q+1} - Z_q)/(Z_{q+1} + Z_q),
  i.e. Z_{q+1} = Z_q (1 + R)/(1 - R) (eq. 4.9 with Delta N_{q+1} = K_{q+1} R N_0, eq. 4.7).
* Crossing the interface (continuity of N and v) turns (g, f) of element q into those of element q+1:
  g' = (g - R f)/(1 - R), f' = (f - R g)/(1 - R). This removes the reflection, f'_0 = 0, and leaves the
  data the next layer needs. Cost: O(n - q) per layer, O(n^2/2) in total.

Existence (eq. 4.20): |Delta N| < |K N_0| is |R| < 1, i.e. 0 < Z_{q+1} < inf. The first element whose R is
not a finite number with |R| < 1 (or whose impedance would overflow) stops the recursion.

Trust: ``MG``/``MF`` run the same recursion on absolute values (no cancellation), starting from the largest
wave amplitude of the face data in every sample (data carry errors relative to their largest value, not to
each sample). The *amplitude growth* kappa_q = (MG[0] + MF[q]) / |G[0]| says how much larger the peeled
amplitudes that met in the wavefront can be than the wavefront itself; errors of relative size eps in the
data and in the arithmetic become errors of about eps * kappa_q in R_q, and 2 dR/(1 - R^2) in ln Z (errors
add up along the rod). Started from constant arrays, MG and MF stay constant along the entries the recursion
reads (every entry receives the same update), so both kernels carry them as two numbers.
"""

from __future__ import annotations

import numpy as np
from numba import njit

EPS = float(np.finfo(float).eps)


def start(force: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, ...]:
    """Output arrays (z, refl, kappa), the waves g and f of element 1 and the state [Z_1, MG, MF]; state is None
    when Z_1 = N/U of the first sample (eq. 4.4) is not a positive finite number (nothing stored then)."""
    n = force.size
    z = np.zeros(n)
    refl = np.zeros(n)
    kappa = np.zeros(n)
    z1 = force[0] / velocity[0]
    if not (np.isfinite(z1) and z1 > 0.0):
        return z, refl, kappa, None, None, None
    z[0] = z1
    kappa[0] = 1.0
    g = 0.5 * (force + z1 * velocity)
    f = 0.5 * (force - z1 * velocity)
    scale = 0.5 * float(np.max(np.abs(force) + np.abs(z1 * velocity)))      # MG = MF (constant arrays)
    return z, refl, kappa, g, f, np.array([z1, scale, scale])


def _peel(block, force: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    force = np.ascontiguousarray(force, dtype=float)
    velocity = np.ascontiguousarray(velocity, dtype=float)
    z, refl, kappa, g, f, state = start(force, velocity)
    if state is None:
        return z, refl, kappa, 0
    n = force.size
    # layer 1 meets g at sample s and f at sample s + 1: one block of layers 1 .. n-1
    done, _ = block(g[:n - 1].copy(), f[1:].copy(), 1, state, z, refl, kappa, False)
    return z, refl, kappa, 1 + done


def peel_numpy(force: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Peel the striker from its face history (reference path).

    Parameters
    ----------
    force:
        N at the impact face at the window starts (step 2s), s = 0..n-1, N (tension positive; impact < 0).
    velocity:
        U = V - v_in at the same steps, m/s (face velocity relative to the striker's initial velocity).

    Returns
    -------
    z:
        (n,) impedances Z_1..Z_n from the impact face (N s/m); only the first ``m`` are valid.
    refl:
        (n,) refl[q] = R_{q,q+1} (0-based q >= 1: reflection of the wavefront at the interface between
        elements q and q+1, 1-based), refl[0] = 0; if m < n, refl[m] holds the failing value.
    kappa:
        (n,) amplitude growth at each layer (kappa[0] = 1); valid up to index m (inclusive if m < n).
    m:
        Number of feasible elements (the existence condition held for elements 1..m).
    """
    return _peel(peel_block_numpy, force, velocity)


def peel_numba(force: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """Same as :func:`peel_numpy` with the compiled layer loops."""
    return _peel(peel_block_numba, force, velocity)


def _block_loops(g, f, q0, state, z, refl, kappa, want_matrix):
    """Peel the layers q0 .. q0+k-1 (compiled path): ``g`` and ``f`` (length k, overwritten) hold the waves
    the layer q0 reads, g of its sample s at g[s] and f of its sample s at f[s] (f[0] meets the wavefront).

    ``state`` = [Z_q0, MG, MF] (impedance of element q0 and the trust numbers; updated in place); results go
    to ``z``, ``refl``, ``kappa`` at the global layer index. Returns the number of layers that satisfied the
    existence condition (k if all) and, if ``want_matrix``, the composed layer matrix P of the block (shape
    (2, 2, k + 1), polynomial coefficients; see :mod:`rodimpact.inverse._schur`).
    """
    k = g.size
    p = np.zeros((2, 2, k + 1 if want_matrix else 1))
    p[0, 0, 0] = 1.0
    p[1, 1, 0] = 1.0
    zq = state[0]
    vg = state[1]
    vf = state[2]
    for j in range(k):
        q = q0 + j
        g0 = g[0]
        r = f[j] / g0
        refl[q] = r
        kappa[q] = (vg + vf) / abs(g0)
        z_next = zq * (1.0 + r) / (1.0 - r)
        if not (abs(r) < 1.0 and 0.0 < z_next < np.inf):
            state[0] = zq
            return j, p
        zq = z_next
        z[q] = zq
        c = 1.0 / (1.0 - r)
        ac = abs(c)
        ar = abs(r)
        vg, vf = (vg + ar * vf) * ac, (vf + ar * vg) * ac
        for s in range(k - j):
            gs = g[s]
            fs = f[s + j]
            g[s] = (gs - r * fs) * c
            f[s + j] = (fs - r * gs) * c
        if want_matrix:
            for col in range(2):
                for i in range(j + 1, 0, -1):          # row 0 <- c x (row0 - R row1), row 1 <- c (row1 - R row0)
                    a = p[0, col, i]
                    b = p[1, col, i]
                    p[1, col, i] = (b - r * a) * c
                    p[0, col, i] = (p[0, col, i - 1] - r * p[1, col, i - 1]) * c
                p[1, col, 0] = (p[1, col, 0] - r * p[0, col, 0]) * c
                p[0, col, 0] = 0.0
    state[0] = zq
    state[1] = vg
    state[2] = vf
    return k, p


def peel_block_numpy(g, f, q0, state, z, refl, kappa, want_matrix):
    """Reference path of :func:`peel_block_numba`: one vectorised numpy expression per layer."""
    k = g.size
    p = np.zeros((2, 2, k + 1 if want_matrix else 1))
    p[0, 0, 0] = p[1, 1, 0] = 1.0
    zq, vg, vf = state
    for j in range(k):
        q = q0 + j
        r = f[j] / g[0]
        refl[q] = r
        kappa[q] = (vg + vf) / abs(g[0])
        z_next = zq * (1.0 + r) / (1.0 - r)
        if not (abs(r) < 1.0 and 0.0 < z_next < np.inf):
            state[0] = zq
            return j, p
        zq = z_next
        z[q] = zq
        c = 1.0 / (1.0 - r)
        vg, vf = (vg + abs(r) * vf) * abs(c), (vf + abs(r) * vg) * abs(c)
        gs, fs = g[:k - j].copy(), f[j:].copy()
        g[:k - j] = (gs - r * fs) * c
        f[j:] = (fs - r * gs) * c
        if want_matrix:
            row0, row1 = p[0].copy(), p[1].copy()
            p[1] = (row1 - r * row0) * c
            p[0, :, 1:] = (row0[:, :-1] - r * row1[:, :-1]) * c
            p[0, :, 0] = 0.0
    state[:] = (zq, vg, vf)
    return k, p


peel_block_numba = njit(cache=True)(_block_loops)


def error_estimate(refl: np.ndarray, kappa: np.ndarray, m: int) -> np.ndarray:
    """First-order estimate of the relative rounding error of Z_1..Z_m.

    eps_q = eps * (1 + sum_{r=2..q} 2 kappa_r / (1 - R_r^2)): the error of R_r is about eps * kappa_r, and
    d ln Z = 2 dR / (1 - R^2) accumulates along the rod (Z_q = Z_1 prod (1 + R)/(1 - R)). For face data
    accurate to rounding it bounds the actual error (absolute values throughout; actual errors are typically
    10 to 10^4 times smaller). Data with a larger relative error delta (measured, or simulated through many
    strong reflections) scale it by about delta / eps.
    """
    out = np.empty(m)
    if m == 0:
        return out
    r = refl[1:m]
    terms = 2.0 * kappa[1:m] / (1.0 - r * r)
    out[0] = EPS
    out[1:] = EPS * (1.0 + np.cumsum(terms))
    return out
