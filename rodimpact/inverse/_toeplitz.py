"""Lower-triangular Toeplitz systems: sum_{k<=j} G_{j-k+1} X_k = Y_j (thesis eq. 4.17).

Two methods:

* ``"substitution"``: forward substitution, O(n^2), written as the recursive filter
  :func:`scipy.signal.lfilter` (b = [1], a = G), which evaluates eq. 4.17 literally;
* ``"fft"``: O(n log n). The power series H = 1/G (mod z^n) by Newton's iteration
  H <- H + H (1 - G H), doubling the number of correct terms each pass, every product an FFT convolution
  (:func:`scipy.signal.fftconvolve`); then X = H * Y followed by two steps of iterative refinement
  X <- X + H * (Y - G * X), which bring the residual down to the level of the substitution.
"""

from __future__ import annotations

import numpy as np

SUBSTITUTION_MAX = 2048


def _conv(a: np.ndarray, b: np.ndarray, n: int) -> np.ndarray:
    """First ``n`` terms of the linear convolution a * b."""
    from scipy.signal import fftconvolve   # imported on use: scipy.signal is slow to import

    return fftconvolve(a[:n], b[:n])[:n]


def inverse_series(g: np.ndarray, n: int) -> np.ndarray:
    """First ``n`` coefficients of the power series 1 / G(z), G(z) = sum g_k z^k, g_0 != 0."""
    h = np.array([1.0 / g[0]])
    k = 1
    while k < n:
        k2 = min(2 * k, n)
        e = _conv(g, h, k2)               # = 1 + O(z^k)
        e = -e
        e[0] += 1.0
        h = np.concatenate([h, np.zeros(k2 - k)])
        h = h + _conv(h, e, k2)
        k = k2
    return h


TOEPLITZ_METHODS = ("auto", "substitution", "fft")


def solve_lower_toeplitz(column: np.ndarray, rhs: np.ndarray, method: str = "auto") -> np.ndarray:
    """Solve the lower-triangular Toeplitz system whose first column is ``column`` (length >= len(rhs)).

    ``method``: "substitution", "fft" or "auto" (substitution up to 2048 unknowns, FFT above).
    """
    y = np.asarray(rhs, dtype=float)
    n = y.size
    g = np.asarray(column, dtype=float)[:n]
    if g.size < n:
        raise ValueError(f"column: needs at least {n} entries, got {g.size}")
    if not g[0] != 0.0:
        raise ValueError("column: the first entry (the response to the first window) must be non-zero")
    if method == "auto":
        method = "substitution" if n <= SUBSTITUTION_MAX else "fft"
    if method == "substitution":
        from scipy.signal import lfilter

        return lfilter([1.0], g, y)
    if method != "fft":
        raise ValueError(f"method: must be one of {TOEPLITZ_METHODS}, got {method!r}")
    h = inverse_series(g, n)
    x = _conv(h, y, n)
    for _ in range(2):
        x = x + _conv(h, y - _conv(g, x, n), n)
    return x
