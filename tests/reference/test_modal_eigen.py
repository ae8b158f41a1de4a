"""Eigenfrequencies of the modal expansion: completeness of the root search, counting, branches."""

import math

import numpy as np
import pytest

from rodimpact.reference import HornImpact, ModalChain, ModalSegment, STEEL_BAR_SPEED

C0 = STEEL_BAR_SPEED
SETUP3 = HornImpact()  # thesis Tab. 3.3


def thesis_3_35(omega, l1=1.0, l2=1.0, xi=0.5, c0=C0):
    """Eq. (3.35) / (alpha beta), written independently with numpy's complex square root (any branch works:
    cos(beta l2) and sin(beta l2)/beta are even in beta). Complex omega allowed."""
    a = np.asarray(omega, dtype=complex) / c0
    b = np.sqrt(a * a - xi**2 / 4 + 0j)
    b = np.where(b == 0, 1e-300, b)
    return 2 * np.cos(a * l1) * np.cos(b * l2) + xi * np.cos(a * l1) * np.sin(b * l2) / b \
        - 2 * a * np.sin(a * l1) * np.sin(b * l2) / b


def sign_scan_roots(f, hi, step):
    """Brute force: every sign change of the real function f on a uniform grid, located to +- step."""
    w = np.arange(step / 2, hi, step)
    d = f(w).real
    i = np.flatnonzero(np.sign(d[:-1]) != np.sign(d[1:]))
    return 0.5 * (w[i] + w[i + 1])


def argument_principle_count(f, lo, hi, height, n_per_side=40000):
    """Zeros of an entire f inside the rectangle [lo, hi] x [-height, height] (winding number of f)."""
    s = np.linspace(0, 1, n_per_side, endpoint=False)
    path = np.concatenate([
        lo + (hi - lo) * s - 1j * height,
        hi + 1j * height * (2 * s - 1),
        hi - (hi - lo) * s + 1j * height,
        lo - 1j * height * (2 * s - 1),
        [lo - 1j * height],
    ])
    phase = np.unwrap(np.angle(f(path)))
    return (phase[-1] - phase[0]) / (2 * np.pi)


def test_uniform_chain_end_conditions_give_textbook_frequencies():
    """Two identical uniform pieces = one rod of length 2 m: all four end-condition pairs, 3000 modes."""
    seg = ModalSegment.uniform(1.0, 1e-3)
    n = np.arange(1, 3001)
    base = math.pi * C0 / 2.0
    expected = {
        ("free", "fixed"): (n - 0.5) * base,
        ("fixed", "free"): (n - 0.5) * base,
        ("fixed", "fixed"): n * base,
        ("free", "free"): n * base,  # elastic modes; the rigid mode omega = 0 is treated separately
    }
    for (left, right), w_exact in expected.items():
        w = ModalChain((seg, seg), left, right).eigenfrequencies(3000)
        np.testing.assert_allclose(w, w_exact, rtol=1e-13, err_msg=f"{left}-{right}")


def test_clustered_roots_of_a_strong_impedance_step_are_all_found():
    """Free-fixed, equal travel times tau, area ratio r = A1/A2 = 1e4: cos^2(w tau) = r sin^2(w tau), i.e.
    w tau = k pi +- atan(1/sqrt(r)): pairs only 0.02 rad apart (far below the grid spacing pi/8 rad)."""
    r = 1e4
    chain = ModalChain((ModalSegment.uniform(1.0, r * 1e-4), ModalSegment.uniform(1.0, 1e-4)), "free", "fixed")
    tau = 1.0 / C0
    eps = math.atan(1 / math.sqrt(r))
    k = np.arange(0, 501)
    exact = np.sort(np.concatenate([k * math.pi + eps, (k + 1) * math.pi - eps]))[:1000] / tau
    np.testing.assert_allclose(chain.eigenfrequencies(1000), exact, rtol=1e-12)


def test_chain_characteristic_is_thesis_3_35_up_to_a_positive_factor():
    w = np.linspace(100.0, 2e5, 777)
    ratio = SETUP3.chain.characteristic(w) / thesis_3_35(w).real
    np.testing.assert_allclose(ratio, math.exp(-0.25) / 2, rtol=1e-9)  # exp(-xi l2 / 2) / 2
    np.testing.assert_allclose(SETUP3.characteristic(w), thesis_3_35(w).real, rtol=1e-10, atol=1e-12)


def test_first_roots_against_brute_force_sign_scan():
    spacing = math.pi * C0 / 2.0
    step = spacing / 400
    scan = sign_scan_roots(thesis_3_35, 60.5 * spacing, step)
    w = SETUP3.chain.eigenfrequencies(scan.size + 5)
    assert scan.size == 60
    np.testing.assert_array_less(np.abs(w[:60] - scan), step)
    assert w[60] > 60.5 * spacing


def test_no_root_below_the_cutoff_for_tab_3_3():
    """beta is imaginary for omega < c0 xi / 2 = 1294 rad/s; the oscillation count there is 0 and the first
    eigenfrequency lies above the cutoff. The brute-force scan (cosh/sinh branch) sees no sign change either."""
    wc = SETUP3.cutoff_angular_frequency
    assert wc == pytest.approx(C0 / 4)
    assert SETUP3.chain.mode_count(wc) == 0
    assert SETUP3.chain.eigenfrequencies(1)[0] > wc
    assert sign_scan_roots(thesis_3_35, wc, wc / 2000).size == 0


def test_roots_below_the_cutoff_exist_for_a_long_striker():
    """With l1 = 10 m the striker's own low modes fall below the horn cutoff (beta imaginary there)."""
    setup = HornImpact(striker_length=10.0)
    wc = setup.cutoff_angular_frequency
    f = lambda w: thesis_3_35(w, l1=10.0)  # noqa: E731
    spacing = math.pi * C0 / 11.0
    scan = sign_scan_roots(f, 20.5 * spacing, spacing / 400)
    w = setup.chain.eigenfrequencies(scan.size)
    assert np.sum(scan < wc) >= 1 and np.sum(w < wc) == np.sum(scan < wc)
    np.testing.assert_array_less(np.abs(w - scan), spacing / 400)


@pytest.mark.parametrize(("lo_mode", "hi_mode"), [(0, 12), (37, 80), (400, 460)])
def test_count_in_interval_matches_argument_principle(lo_mode, hi_mode):
    """Winding number of the (entire) eq. 3.35 around a rectangle vs the number of roots found in it."""
    chain = SETUP3.chain
    w = chain.eigenfrequencies(hi_mode + 2)
    lo = 0.5 * (w[lo_mode - 1] + w[lo_mode]) if lo_mode > 0 else 10.0
    hi = 0.5 * (w[hi_mode - 1] + w[hi_mode])
    height = C0 / 2.0  # |Im(alpha)| (l1 + l2) = 1
    n_ap = argument_principle_count(thesis_3_35, lo, hi, height)
    assert abs(n_ap - round(n_ap)) < 1e-6
    assert round(n_ap) == hi_mode - lo_mode
    assert np.sum((w > lo) & (w < hi)) == hi_mode - lo_mode
    assert int(chain.mode_count(hi) - chain.mode_count(lo)) == hi_mode - lo_mode


def test_thousands_of_modes_follow_the_asymptotic_count():
    """For alpha l1 + beta l2 >> 1 eq. (3.35) ~ -cos(alpha l1 + beta l2): the n-th root has
    alpha l1 + beta l2 = (n - 1/2) pi + o(1). Check all 5000 roots, and that the count has no gaps."""
    w = SETUP3.chain.eigenfrequencies(5000)
    a = w / C0
    phase = a * 1.0 + np.sqrt(a * a - 1 / 16) * 1.0
    n = np.arange(1, 5001)
    dev = phase / math.pi - (n - 0.5)
    assert np.all(np.abs(dev) < 0.5)
    assert np.all(np.abs(dev[1000:]) < 1e-3)  # the correction decays like 1/alpha
    assert np.all(np.diff(w) > 0.5 * math.pi * C0 / 2)  # no duplicates: spacing stays near pi c0 / 2
    mid = 0.5 * (w[:-1] + w[1:])
    np.testing.assert_array_equal(SETUP3.chain.mode_count(mid), n[:-1])


def test_bad_input():
    with pytest.raises(ValueError, match="n_modes"):
        SETUP3.chain.eigenfrequencies(0)
    with pytest.raises(ValueError, match="left"):
        ModalChain((ModalSegment.uniform(1.0, 1e-3),), left="clamped")
    with pytest.raises(TypeError, match="segments"):
        ModalChain(())
    with pytest.raises(ValueError, match="length"):
        ModalSegment.uniform(-1.0, 1e-3)
    with pytest.raises(ValueError, match="omega"):
        SETUP3.chain.characteristic([-1.0])
