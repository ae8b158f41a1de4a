"""Kernels of the inverse problem: layer peeling of the striker (thesis Sec. 4.1.1, eqs. 4.4-4.9).

Symbols: Z = impedance (N s/m), N = normal force (N, tension positive), U = v - v_in = face velocity
relative to the striker's initial velocity (m/s); R = force reflection coefficient of a wavefront at an
interface, K = energy transmission factor (eq. 4.6).

Pure functions on arrays, no objects, I/O or warnings inside. Two paths with the same signature:

* :func:`peel_numpy` -- readable reference; one vectorised numpy expression per layer;
* :func:`peel_numba` -- the compiled path (``numba.njit(cache=True)``), plain loops.

The method (derived in docs/inverse.md, "Layer peeling")
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
    n = force.size
    z, refl, kappa, z1 = start_arrays(force, velocity)
    if z1 is None:
        return z, refl, kappa, 0
    g = 0.5 * (force + z1 * velocity)
    f = 0.5 * (force - z1 * velocity)
    mg = mf = 0.5 * float(np.max(np.abs(force) + np.abs(z1 * velocity)))     # MG, MF (constant arrays)
    zq = z1
    for q in range(1, n):
        r = f[q] / g[0]
        refl[q] = r
        kappa[q] = (mg + mf) / abs(g[0])
        z_next = zq * (1.0 + r) / (1.0 - r)
        if not (abs(r) < 1.0 and 0.0 < z_next < np.inf):
            return z, refl, kappa, q
        zq = z_next
        z[q] = zq
        c = 1.0 / (1.0 - r)
        length = n - q
        gs = g[:length].copy()
        fs = f[q:q + length].copy()
        g[:length] = (gs - r * fs) * c
        f[q:q + length] = (fs - r * gs) * c
        mg, mf = (mg + abs(r) * mf) * abs(c), (mf + abs(r) * mg) * abs(c)
    return z, refl, kappa, n


def start_arrays(force: np.ndarray, velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float | None]:
    """Output arrays (z, refl, kappa) of a peel and Z_1 = N/U of the first sample (eq. 4.4), already stored in
    z[0] (kappa[0] = 1); Z_1 is None, and nothing stored, when it is not a positive finite number."""
    n = force.size
    z = np.zeros(n)
    refl = np.zeros(n)
    kappa = np.zeros(n)
    z1 = force[0] / velocity[0]
    if not (np.isfinite(z1) and z1 > 0.0):
        return z, refl, kappa, None
    z[0] = z1
    kappa[0] = 1.0
    return z, refl, kappa, float(z1)


def _peel_loops(force, velocity):
    """Same as :func:`peel_numpy`, written as loops for numba."""
    n = force.size
    z = np.zeros(n)
    refl = np.zeros(n)
    kappa = np.zeros(n)
    z1 = force[0] / velocity[0]
    if not (np.isfinite(z1) and z1 > 0.0):
        return z, refl, kappa, 0
    z[0] = z1
    kappa[0] = 1.0
    g = np.empty(n)
    f = np.empty(n)
    scale = 0.0
    for s in range(n):
        g[s] = 0.5 * (force[s] + z1 * velocity[s])
        f[s] = 0.5 * (force[s] - z1 * velocity[s])
        scale = max(scale, 0.5 * (abs(force[s]) + abs(z1 * velocity[s])))
    mg = scale
    mf = scale
    zq = z1
    for q in range(1, n):
        r = f[q] / g[0]
        refl[q] = r
        kappa[q] = (mg + mf) / abs(g[0])
        z_next = zq * (1.0 + r) / (1.0 - r)
        if not (abs(r) < 1.0 and 0.0 < z_next < np.inf):
            return z, refl, kappa, q
        zq = z_next
        z[q] = zq
        c = 1.0 / (1.0 - r)
        ac = abs(c)
        ar = abs(r)
        mg, mf = (mg + ar * mf) * ac, (mf + ar * mg) * ac
        for s in range(n - q):
            gs = g[s]
            fs = f[s + q]
            g[s] = (gs - r * fs) * c
            f[s + q] = (fs - r * gs) * c
    return z, refl, kappa, n


peel_numba = njit(cache=True)(_peel_loops)


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
