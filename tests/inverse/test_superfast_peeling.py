"""Superfast (divide-and-conquer Schur, O(n log^2 n)) peeling against the O(n^2) peel, known strikers, the
thesis examples, the existence stop and a 50-digit reference."""

import warnings

import numpy as np
import pytest
import test_inverse_thesis_examples as thesis
from test_peeling_kernel import _face_history, _peel_decimal

import rodimpact as ri
from rodimpact.inverse import ExponentialDecay, SynthesisWarning, _kernels as K, _schur as S, synthesize


def _smooth_target(rng, n):
    """Window values of a random smooth compressive force: a few random low-frequency harmonics."""
    t = np.arange(n) / n
    shape = 1.0 + 0.4 * t
    for k in range(1, 4):
        shape += 0.1 / k * rng.uniform(-1, 1) * np.sin(np.pi * k * t + rng.uniform(0, np.pi))
    return -2e5 * shape


def _bar_face_data(x, z_bar=9e4, v_in=8.0):
    """Face velocity relative to the striker for a semi-infinite bar at rest: V = -N / Z~ (closed form)."""
    return -x / z_bar - v_in


def _assert_same(a, b, m=None):
    """Both peel results: same number of elements, equal impedances, reflections, amplitude growth."""
    assert a[3] == b[3]
    m = a[3] if m is None else m
    np.testing.assert_allclose(b[0][:m], a[0][:m], rtol=1e-12, atol=0)
    np.testing.assert_allclose(b[1][:m + 1], a[1][:m + 1], rtol=0, atol=1e-13)
    np.testing.assert_allclose(b[2][:m + 1], a[2][:m + 1], rtol=1e-12, atol=0)


def test_one_leaf_is_the_quadratic_peel_bit_for_bit():
    rng = np.random.default_rng(0)
    x = _smooth_target(rng, 300)
    u = _bar_face_data(x)
    a = K.peel_numba(x, u)
    b = S.peel_superfast(x, u, leaf=300)
    for i in range(3):
        np.testing.assert_array_equal(b[i], a[i])
    assert a[3] == b[3] == 300


@pytest.mark.parametrize("seed", [0, 1])
def test_numba_and_numpy_leaves_agree(seed):
    rng = np.random.default_rng(seed)
    x = _smooth_target(rng, 700)
    u = _bar_face_data(x)
    a = S.peel_superfast(x, u, "numba", leaf=8)
    b = S.peel_superfast(x, u, "numpy", leaf=8)
    assert a[3] == b[3] == 700
    for i in range(3):
        np.testing.assert_allclose(a[i], b[i], rtol=1e-14, atol=0)


@pytest.mark.parametrize("seed", [3, 4])
def test_superfast_recovers_a_known_striker(seed):
    """Face histories of a known random striker from the direct solver (independent of the peeling)."""
    rng = np.random.default_rng(seed)
    z_true = 8e4 * np.exp(np.cumsum(rng.normal(0.0, 0.05, 900)))
    x, u = _face_history(z_true, 9e4, 7.0)
    z, refl, _, m = S.peel_superfast(x, u, leaf=16)
    assert m == 900
    np.testing.assert_allclose(z, z_true, rtol=1e-12)
    np.testing.assert_allclose(refl[1:], np.diff(z_true) / (z_true[1:] + z_true[:-1]), atol=1e-12)


@pytest.mark.parametrize("n, seed, leaf", [(3000, 0, 8), (3000, 1, 64), (20000, 2, None), (20000, 3, 32)])
def test_superfast_equals_quadratic_on_random_smooth_targets(n, seed, leaf):
    x = _smooth_target(np.random.default_rng(seed), n)
    u = _bar_face_data(x)
    a = K.peel_numba(x, u)
    assert a[3] == n                       # the whole striker exists: the comparison covers every element
    _assert_same(a, S.peel_superfast(x, u, leaf=leaf))


def _stepped_bar(dt):
    return ri.Rod.from_impedance([7.97e4] * 150 + [1.2e5] * 150 + [6e4] * 100, dt)


@pytest.mark.parametrize("n", [2500, 12000])
def test_synthesize_on_a_struck_system_same_with_both_paths(monkeypatch, n):
    """A stepped struck bar (face response from the direct solver): synthesize() with the O(n^2) and the
    superfast peel gives the same striker and the same bookkeeping."""
    dt = 2e-4 / n
    target = ExponentialDecay(2.0e5, 1e-3)
    runs = {}
    for crossover, leaf in ((10**9, S.LEAF), (1, 16)):
        monkeypatch.setattr(S, "CROSSOVER", crossover)
        monkeypatch.setattr(S, "LEAF", leaf)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SynthesisWarning)
            runs[crossover] = synthesize(target, ri.System.struck(_stepped_bar(dt), far_end="nonreflecting"), 8.0, n=n, dt=dt)
    a, b = runs[10**9], runs[1]
    assert a.diagnostics["peeling"] == "quadratic" and b.diagnostics["peeling"] == "superfast"
    assert a.diagnostics["face_response"] == "simulated"
    assert a.n_feasible == b.n_feasible == n
    np.testing.assert_allclose(b.impedance, a.impedance, rtol=1e-12, atol=0)
    np.testing.assert_allclose(b.reflection, a.reflection, rtol=0, atol=1e-13)
    np.testing.assert_allclose(b.amplitude_growth, a.amplitude_growth, rtol=1e-12)
    np.testing.assert_allclose(b.error_estimate, a.error_estimate, rtol=1e-12)


@pytest.mark.parametrize("jump", [1, 2, 63, 64, 65, 128, 129, 1234, 2998])
def test_existence_failure_mid_way_stops_at_the_same_element(jump):
    """A force jump beyond the force reserve (eq. 4.20) after `jump` windows, placed at the start, inside and
    at the edges of the leaf blocks (leaf 64: blocks start at multiples of 64 layers, layer 1 first)."""
    n = 3000
    t = np.arange(n) / n
    x = -2e5 * (1.0 + 0.2 * np.sin(3.0 * t))
    x[jump:] *= 3.5
    u = _bar_face_data(x)
    a = K.peel_numba(x, u)
    b = S.peel_superfast(x, u, leaf=64)
    assert a[3] == jump                        # the stop is where the jump is
    _assert_same(a, b)
    assert abs(b[1][jump]) >= 1.0              # the failing reflection is reported
    assert np.all(b[0][jump:] == 0.0)


def test_a_failing_first_element_gives_no_striker():
    x = np.full(10, -1e5)
    u = np.full(10, 1.0)                       # Z_1 = X_1 / U_1 < 0
    assert S.peel_superfast(x, u)[3] == K.peel_numba(x, u)[3] == 0


@pytest.mark.parametrize("seed, n, noise, leaf", [(5, 120, 0.02, 2), (6, 120, 0.02, 2), (7, 500, 0.002, 4)])
def test_error_estimate_bounds_the_superfast_rounding_error(seed, n, noise, leaf):
    """The O(n^2) path's first-order estimate also bounds the superfast path's actual error (FFTs at every
    level; 50-digit decimal reference), on rough strongly rising data where it is far from eps."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / n
    x = -2e5 * (1 + 0.8 * t + noise * rng.standard_normal(n))
    u = -x / 8e4 - 6.0
    z, refl, kappa, m = S.peel_superfast(x, u, leaf=leaf)
    assert m > 60
    assert m == K.peel_numba(x, u)[3]
    exact = _peel_decimal(x[:m], u[:m])
    err = np.abs(z[:m] / exact - 1)
    est = K.error_estimate(refl, kappa, m)
    assert np.all(err <= est)
    assert err.max() > 0


@pytest.fixture
def superfast_everywhere(monkeypatch):
    """synthesize() takes the superfast path for every size, with FFTs at every level (leaf 4)."""
    monkeypatch.setattr(S, "CROSSOVER", 1)
    monkeypatch.setattr(S, "LEAF", 4)


@pytest.mark.parametrize("check", [thesis.test_example_1_at_printed_parameters_is_feasible,
                                   thesis.test_example_2_existence_limit,
                                   thesis.test_percussion_drilling_round_trip])
def test_thesis_examples_through_the_superfast_path(superfast_everywhere, check):
    check()


@pytest.mark.parametrize("target_cls, table, z_unit", [(thesis.ExponentialDecay, thesis.TABLE_4_3, 1e3),
                                                       (thesis.LinearRamp, thesis.TABLE_4_4, 1e6)])
def test_thesis_tables_through_the_superfast_path(superfast_everywhere, target_cls, table, z_unit):
    thesis.test_tables_4_3_and_4_4(target_cls, table, z_unit)


def test_method_choice_and_validation():
    assert S.chosen_method(S.CROSSOVER - 1) == "quadratic"
    assert S.chosen_method(S.CROSSOVER) == "superfast"
    assert S.chosen_method(10, "superfast") == "superfast"
    x = np.full(4, -1e5)
    with pytest.raises(ValueError, match="method: must be one of"):
        S.peel(x, -x / 8e4 - 5.0, method="fast")
    with pytest.raises(ValueError, match="backend"):
        S.peel(x, -x / 8e4 - 5.0, backend="cuda")
    with pytest.raises(ValueError, match="leaf"):
        S.peel_superfast(x, -x / 8e4 - 5.0, leaf=0)
