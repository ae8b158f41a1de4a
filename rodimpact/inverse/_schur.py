"""Superfast layer peeling: the divide-and-conquer Schur recursion, O(n log^2 n) (thesis Sec. 4.1.1).

Same inputs and outputs as :func:`rodimpact.inverse._kernels.peel_numba` / ``peel_numpy`` (the O(n^2) peel;
symbols and the derivation are in that module and in docs/inverse.md, "Step 2: peel the striker layer by
layer"). :func:`peel` chooses
between the two by the number of elements (:data:`CROSSOVER`, measured by ``benchmarks/bench_synthesis.py``).

The layers as polynomials in the delay
--------------------------------------
Write the two wave histories of layer q as power series in the delay x (one sample = two steps):
Ghat_q(x) = sum_p g_q[p - q] x^p and Fhat_q(x) = sum_p f[p] x^p, p >= q, in the storage of the O(n^2) peel
(``g`` shifts to the start of its array, ``f`` stays in place). The reflection of layer q is the ratio of their
coefficients of x^q, R_q = Fhat_q[q] / Ghat_q[q], and crossing interface q is the 2x2 polynomial matrix

    [Ghat_{q+1}; Fhat_{q+1}] = Theta_q [Ghat_q; Fhat_q],   Theta_q = c [[x, -R x], [-R, 1]],  c = 1 / (1 - R).

k layers from q0 on compose to P = Theta_{q0+k-1} ... Theta_{q0}, a matrix of polynomials of degree <= k, and
R_{q0..q0+k-1} only need the coefficients q0 .. q0+k-1 of the data. Divide and conquer on a block of k layers:
peel the first h = k/2 (recursively) to get R and P1 (degree <= h), apply P1 to the block's data by FFT
(cyclic convolution of length >= k: the wrap-around only spoils coefficients below h, which are not needed),
peel the second half from the result (recursively) to get P2, and return P = P2 P1 (FFT product). Blocks of at
most :data:`LEAF` layers run the O(n^2) loops (:func:`rodimpact.inverse._kernels.peel_block_numba`, the same
code as the O(n^2) peel), which also build their P. Cost O(n log^2 n).

Existence and bookkeeping: every leaf checks |R| < 1 and 0 < Z < inf layer by layer as the O(n^2) peel does
and stops the whole recursion at the first failure, so both paths stop at the same element. The trust numbers
MG, MF (two scalars, see :mod:`rodimpact.inverse._kernels`) pass from leaf to leaf: the amplitude growth
kappa is the O(n^2) path's to rounding of the R's.

Accuracy: the leaves compute like the O(n^2) peel; an FFT convolution carries errors of about
eps log2(L) relative to the largest products instead of to each coefficient. docs/inverse.md ("Superfast
peeling") reports the measured agreement (1e-14 to 5e-14 relative for n = 1e3 .. 1e5 on smooth data) and
that the error estimate of :func:`rodimpact.inverse._kernels.error_estimate` still bounds the actual error.
"""

from __future__ import annotations

from typing import Callable, Optional

import numpy as np
from scipy import fft as sfft

from . import _kernels as K

#: Largest block peeled by the O(n^2) loops inside the recursion (measured: below it the loops beat the FFTs).
LEAF = 384
#: From this number of elements on, ``method="auto"`` uses the superfast peel (measured crossover).
CROSSOVER = 5000
METHODS = ("auto", "quadratic", "superfast")

Peeled = tuple[np.ndarray, np.ndarray, np.ndarray, int]


def peel_superfast(force: np.ndarray, velocity: np.ndarray, backend: str = "numba",
                   leaf: Optional[int] = None) -> Peeled:
    """Peel the striker from its face history by the divide-and-conquer Schur recursion, O(n log^2 n).

    Parameters and returns as :func:`rodimpact.inverse._kernels.peel_numpy` (force N and relative face velocity
    U = V - v_in at the window starts; impedances z, reflections refl, amplitude growth kappa, number m of
    elements that satisfy the existence condition). ``backend`` chooses the leaf loops ("numba" compiled,
    "numpy" reference); ``leaf`` is the largest block peeled by the loops (>= 1; default :data:`LEAF`).
    """
    leaf = LEAF if leaf is None else int(leaf)
    if leaf < 1:
        raise ValueError(f"leaf: the largest block peeled by the loops must be >= 1 layer, got {leaf}")
    force = np.ascontiguousarray(force, dtype=float)
    velocity = np.ascontiguousarray(velocity, dtype=float)
    n = force.size
    z, refl, kappa, g, f, state = K.start(force, velocity)
    if state is None:
        return z, refl, kappa, 0
    run_leaf = K.peel_block_numba if backend == "numba" else K.peel_block_numpy

    def solve(gb: np.ndarray, fb: np.ndarray, q0: int, want_matrix: bool) -> tuple[int, np.ndarray | None]:
        """Peel the layers q0 .. q0+k-1 (k = gb.size); return the layers done and their matrix P."""
        k = gb.size
        if k <= leaf:
            done, p = run_leaf(gb.copy(), fb.copy(), q0, state, z, refl, kappa, want_matrix)
            return done, p
        h = k // 2
        done, p1 = solve(gb[:h], fb[:h], q0, True)
        if done < h:
            return done, None
        size = sfft.next_fast_len(k + 1, real=True)
        p1f = sfft.rfft(p1, size, axis=-1)
        gf, ff = sfft.rfft(np.stack((gb, fb)), size, axis=-1)
        rest = sfft.irfft(p1f[:, 0] * gf + p1f[:, 1] * ff, size, axis=-1)[:, h:k]
        done2, p2 = solve(rest[0], rest[1], q0 + h, want_matrix)
        if done2 < k - h or not want_matrix:
            return h + done2, None
        p2f = sfft.rfft(p2, size, axis=-1)
        prod = p2f[:, :1] * p1f[:1] + p2f[:, 1:] * p1f[1:]          # (P2 P1)_ik = sum_j P2_ij P1_jk
        return k, sfft.irfft(prod, size, axis=-1)[:, :, :k + 1]

    # layer 1 reads g at sample s and f at sample s + 1 (coefficients 1 .. n-1 of Ghat_1 = x G, Fhat_1 = F)
    done, _ = solve(g[:n - 1], f[1:], 1, False)
    return z, refl, kappa, 1 + done


def peel(force: np.ndarray, velocity: np.ndarray, backend: str = "numba", method: str = "auto") -> Peeled:
    """Peel the striker with the O(n^2) loops (``method="quadratic"``), the superfast recursion
    (``"superfast"``) or whichever is faster for this size (``"auto"``: superfast from :data:`CROSSOVER`
    elements on)."""
    if method not in METHODS:
        raise ValueError(f"method: must be one of {METHODS}, got {method!r}")
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    if chosen_method(np.size(force), method) == "superfast":
        return peel_superfast(force, velocity, backend)
    quadratic: Callable[[np.ndarray, np.ndarray], Peeled] = K.peel_numba if backend == "numba" else K.peel_numpy
    return quadratic(np.ascontiguousarray(force, dtype=float), np.ascontiguousarray(velocity, dtype=float))


def chosen_method(n: int, method: str = "auto") -> str:
    """The peeling path ``method`` resolves to for n elements ("quadratic" or "superfast")."""
    if method == "auto":
        return "superfast" if n >= CROSSOVER else "quadratic"
    return method
