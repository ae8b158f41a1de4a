"""Regression: a uniform bar cut into equal-area pieces must have the spectrum of the uncut bar.

The shot end state of such a chain can come out as exactly U(right) = 0.0 at frequencies halfway between two
eigenfrequencies (e.g. 0.5 + 1.0 m, free-free, omega = 101.5 pi c / 1.5). The free-right-end correction of the
oscillation count used to treat U(right) = 0 like "U and N of opposite sign" instead of "Pruefer angle at a
multiple of pi", so the count there came out one too high and the search stopped with "mode count not monotone".
"""

import math

import numpy as np
import pytest

from rodimpact.reference import STEEL_BAR_SPEED, ModalChain, ModalSegment

C0 = STEEL_BAR_SPEED
AREA = 2e-3
ENDS = [("free", "free"), ("free", "fixed"), ("fixed", "free"), ("fixed", "fixed")]
SPLITS = [
    (0.5, 1.0),
    (1.0 / 3.0, 2.0 / 3.0),
    (0.3, 0.7),
    (0.4, 0.6),
    (1.0, 1.0),
    (0.5, 0.5, 0.5),
    (0.2, 0.3, 1.0),
    (0.25, 0.5, 0.75),
]


def split_bar(lengths, left, right):
    return ModalChain(tuple(ModalSegment.uniform(length, AREA) for length in lengths), left, right)


def closed_form(lengths, left, right, n):
    """Uniform bar of length L: k pi c / L (equal end conditions), (k - 1/2) pi c / L (mixed)."""
    k = np.arange(1, n + 1, dtype=float)
    return (k - (0.5 if left != right else 0.0)) * math.pi * C0 / sum(lengths)


@pytest.mark.parametrize(("left", "right"), ENDS)
@pytest.mark.parametrize("lengths", SPLITS, ids=lambda s: "+".join(f"{x:.3g}" for x in s))
@pytest.mark.parametrize("n_modes", [100, 500, 2000, 2500, 5000])
def test_split_uniform_bar_has_the_uncut_spectrum(lengths, left, right, n_modes):
    chain = split_bar(lengths, left, right)
    w = chain.eigenfrequencies(n_modes)
    np.testing.assert_allclose(w, closed_form(lengths, left, right, n_modes), rtol=1e-12)
    # the count between consecutive roots is exactly 1, 2, ..., n - 1 (no gaps, no doubles)
    mid = 0.5 * (w[:-1] + w[1:])
    np.testing.assert_array_equal(chain.mode_count(mid), np.arange(1, n_modes))


def test_reported_case_free_free_half_plus_one():
    """The reviewer's reproduction: 0.5 + 1.0 m, free-free; eigenfrequencies and expand used to raise."""
    chain = split_bar((0.5, 1.0), "free", "free")
    for n in (5, 100, 500, 1000, 2000):
        np.testing.assert_allclose(chain.eigenfrequencies(n), closed_form((0.5, 1.0), "free", "free", n),
                                   rtol=1e-12)
    # striker (first 0.5 m) at V, rest at rest: U_k = cos(k pi x / L), B_k = rho A L / 2, so
    # a_k = 2 V sin(k pi a / L) / (k pi) and the rigid velocity is V a / L.
    v, a, length = 5.0, 0.5, 1.5
    sol = chain.expand([v, 0.0], 2000)
    k = np.arange(1, 2001)
    np.testing.assert_allclose(sol.amplitudes, 2 * v * np.sin(k * math.pi * a / length) / (k * math.pi),
                               rtol=1e-9, atol=1e-12 * v)
    np.testing.assert_allclose(sol.modal_masses, 7840.0 * AREA * length / 2, rtol=1e-12)
    assert sol.rigid_velocity == pytest.approx(v * a / length, rel=1e-14)


def test_twenty_thousand_modes_of_a_split_free_free_bar():
    lengths = (0.4, 0.6)
    chain = split_bar(lengths, "free", "free")
    np.testing.assert_allclose(chain.eigenfrequencies(20000), closed_form(lengths, "free", "free", 20000),
                               rtol=1e-12)


@pytest.mark.parametrize(("left", "right"), ENDS)
@pytest.mark.parametrize("lengths", [(0.5, 1.0), (0.3, 0.7), (0.2, 0.3, 1.0)], ids=str)
def test_count_on_a_dense_grid_between_the_roots(lengths, left, right):
    """mode_count at every quarter of the spacing (except the eigenfrequencies themselves) for 6000 modes:
    these grid points include the anti-resonances where the shot U(right) can round to exactly 0.0."""
    chain = split_bar(lengths, left, right)
    shift = 0.5 if left != right else 0.0
    kappa = np.arange(1, 4 * 6000 + 1) / 4.0
    kappa = kappa[(kappa + shift) % 1.0 != 0.0]
    w = kappa * math.pi * C0 / sum(lengths)
    np.testing.assert_array_equal(chain.mode_count(w), np.floor(kappa + shift).astype(np.int64))


@pytest.mark.parametrize("right", ["free", "fixed"])
@pytest.mark.parametrize("third", [0.25, 0.5, 1.0])
def test_zero_of_the_shot_mode_on_an_interface_is_counted_once(third, right):
    """At omega0 = 101.5 pi c / 1.5 the 0.5 + 1.0 m chain's U(1.5 m) = cos(101.5 pi) = 0 (it evaluates to
    exactly 0.0 with IEEE doubles); a third piece turns that point into an interface. The count at omega0 and
    its floating-point neighbours must be the uncut bar's, and so must the whole spectrum."""
    lengths = (0.5, 1.0, third)
    chain = split_bar(lengths, "free", right)
    w0 = 101.5 * math.pi * C0 / 1.5
    ws = np.array([np.nextafter(w0, 0.0), w0, np.nextafter(w0, np.inf)])
    shift = 0.5 if right == "fixed" else 0.0
    expected = math.floor(w0 * sum(lengths) / (math.pi * C0) + shift)
    np.testing.assert_array_equal(chain.mode_count(ws), expected)
    np.testing.assert_allclose(chain.eigenfrequencies(3000), closed_form(lengths, "free", right, 3000), rtol=1e-12)
