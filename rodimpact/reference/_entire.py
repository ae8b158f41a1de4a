"""Entire functions of k^2 used by the modal expansion (private).

For ``w'' + k^2 w = 0`` the fundamental solutions ``C(x) = cos(k x)`` and ``S(x) = sin(k x)/k`` are even in k,
hence entire functions of ``k^2``: for ``k^2 < 0`` (below a cutoff, thesis eq. 3.34 with imaginary beta) they
become ``cosh(g x)`` and ``sinh(g x)/g`` with ``g = sqrt(-k^2)``, and ``S -> x`` as ``k -> 0``. Working with
``k^2`` instead of k removes the branch question of the thesis's beta altogether.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

_SMALL = 1e-2  # |k^2 x^2| below which series replace cancelling closed forms


def cos_sinc(k2: NDArray[np.float64], x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return ``C = cos(k x)`` and ``S = sin(k x)/k`` (entire in k^2), broadcasting ``k2`` against ``x``."""
    k2 = np.asarray(k2, dtype=float)
    x = np.asarray(x, dtype=float)
    if np.all(k2 > 0.0):  # fast path: every mode oscillatory
        k = np.sqrt(k2)
        kx = k * x
        return np.cos(kx), np.sin(kx) / k
    k2, x = np.broadcast_arrays(k2, x)
    pos = k2 > 0.0
    k = np.sqrt(np.abs(k2))
    kx = k * x
    zero = k == 0.0
    ksafe = np.where(zero, 1.0, k)
    kx_osc = np.where(pos, kx, 0.0)  # each branch sees only its own arguments (no cosh overflow)
    kx_exp = np.where(pos, 0.0, kx)
    c = np.where(pos, np.cos(kx_osc), np.cosh(kx_exp))
    s = np.where(pos, np.sin(kx_osc), np.sinh(kx_exp)) / ksafe
    s = np.where(zero, x, s)
    return c, s


def cos_sinc_scalar(k2: float, x: float) -> tuple[float, float]:
    """Scalar twin of :func:`cos_sinc` (math module; used inside scipy.optimize.brentq)."""
    if k2 > 0.0:
        k = math.sqrt(k2)
        return math.cos(k * x), math.sin(k * x) / k
    if k2 < 0.0:
        g = math.sqrt(-k2)
        return math.cosh(g * x), math.sinh(g * x) / g
    return 1.0, x


def square_integrals(
    k2: NDArray[np.float64], length: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Integrals over [0, L] of C^2, C S and S^2 (C, S of :func:`cos_sinc`), entire in k^2.

    ``int C^2 = (L + C S)/2``, ``int C S = S^2/2``, ``int S^2 = (L - C S)/(2 k^2)``; the last one cancels for
    small ``z = k^2 L^2`` and is then replaced by its Taylor series
    ``L^3 (1/3 - z/15 + 2 z^2/315 - z^3/2835 + 2 z^4/155925)`` (truncation < 1e-16 relative for |z| < 1e-2).
    """
    k2 = np.asarray(k2, dtype=float)
    c, s = cos_sinc(k2, np.full_like(k2, length))
    icc = 0.5 * (length + c * s)
    ics = 0.5 * s * s
    z = k2 * length**2
    small = np.abs(z) < _SMALL
    series = length**3 * (1.0 / 3.0 + z * (-1.0 / 15.0 + z * (2.0 / 315.0 + z * (-1.0 / 2835.0 + z * 2.0 / 155925.0))))
    direct = (length - c * s) / (2.0 * np.where(small, 1.0, k2))
    iss = np.where(small, series, direct)
    return icc, ics, iss
