"""The FFT Toeplitz solver on ill-conditioned systems, where its iterative refinement matters.

Test systems: the column G(z) = 1 - 2 r cos(w) z + r^2 z^2, a lightly damped resonance (like the rectangular
response of a struck system ringing between reflections). Its inverse series is known in closed form,
h_k = r^k sin((k + 1) w) / sin(w) (the impulse response of the recursion x_j = y_j + 2 r cos(w) x_{j-1}
- r^2 x_{j-2}), and the exact solution is chosen first and the right-hand side computed from it (an exact
integer-free convolution of three terms, accurate to rounding), so nothing is taken from the solver.

For r close to 1 the Newton iteration for 1/G accumulates FFT rounding over thousands of slowly decaying
terms: H * Y alone misses the solution by 1e-5 .. 1e-3; the two refinement steps X <- X + H * (Y - G * X) bring
it to the level of forward substitution (1e-13).
"""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.inverse._toeplitz import SUBSTITUTION_MAX, _conv, inverse_series, solve_lower_toeplitz

N = 4096


def resonance(r: float, w: float) -> np.ndarray:
    g = np.zeros(N)
    g[:3] = 1.0, -2.0 * r * np.cos(w), r * r
    return g


def system(r: float, w: float, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    g = resonance(r, w)
    x_true = np.random.default_rng(seed).standard_normal(N)
    y = g[0] * x_true
    y[1:] += g[1] * x_true[:-1]
    y[2:] += g[2] * x_true[:-2]
    return g, y, x_true


@pytest.mark.parametrize("r, w", [(0.995, 0.02), (0.999, 0.05), (0.998, 0.02)])
def test_fft_solver_is_as_accurate_as_substitution_on_a_resonant_system(r, w):
    assert N > SUBSTITUTION_MAX                       # "auto" takes the FFT path here
    g, y, x_true = system(r, w, seed=1)
    for method in ("fft", "auto", "substitution"):
        x = solve_lower_toeplitz(g, y, method)
        assert np.max(np.abs(x - x_true)) <= 1e-12 * np.max(np.abs(x_true)), method


@pytest.mark.parametrize("r, w", [(0.995, 0.02), (0.999, 0.05)])
def test_without_refinement_the_fft_product_misses_the_tolerance(r, w):
    """The same system solved as X = H * Y only (the solver's first step): off by far more than the
    tolerance above, which is what the refinement repairs. The inverse series itself is checked against the
    closed form to show where the error comes from."""
    g, y, x_true = system(r, w, seed=2)
    h = inverse_series(g, N)
    k = np.arange(N)
    h_exact = r**k * np.sin((k + 1) * w) / np.sin(w)
    assert np.max(np.abs(h - h_exact)) > 1e-8 * np.max(np.abs(h_exact))
    x_plain = _conv(h, y, N)
    assert np.max(np.abs(x_plain - x_true)) > 1e-7 * np.max(np.abs(x_true))
    x = solve_lower_toeplitz(g, y, "fft")
    assert np.max(np.abs(x - x_true)) <= 1e-12 * np.max(np.abs(x_true))


def test_inverse_series_of_a_well_damped_resonance_matches_the_closed_form():
    r, w = 0.9, 0.3
    h = inverse_series(resonance(r, w), 512)
    k = np.arange(512)
    np.testing.assert_allclose(h, r**k * np.sin((k + 1) * w) / np.sin(w), rtol=0, atol=1e-13)
