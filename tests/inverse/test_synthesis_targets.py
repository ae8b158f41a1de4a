"""Targets and the rules that turn them into window values."""

import numpy as np
import pytest

from rodimpact.inverse import (ExponentialDecay, ExponentialGrowth, ForceTarget, LinearRamp, as_target,
                               lundberg_lesser_impedance)

DT = 1e-6


def test_callable_rules_on_a_quadratic():
    f = lambda t: -1e5 - 3e9 * t - 2e15 * t**2     # noqa: E731
    n = 5
    j = np.arange(n)
    a, b = 2 * j * DT, 2 * (j + 1) * DT
    start = ForceTarget.from_callable(f, "start").window_values(n, DT)
    mid = ForceTarget.from_callable(f, "midpoint").window_values(n, DT)
    mean = ForceTarget.from_callable(f, "mean").window_values(n, DT)
    np.testing.assert_allclose(start, f(a), rtol=1e-15)
    np.testing.assert_allclose(mid, f((a + b) / 2), rtol=1e-15)
    exact_mean = -1e5 - 3e9 * (a + b) / 2 - 2e15 * (b**3 - a**3) / (3 * (b - a))    # integral by hand
    np.testing.assert_allclose(mean, exact_mean, rtol=1e-14)


def test_sample_rules_interpolate_linearly_and_integrate_exactly():
    t = np.array([0.0, 3e-6, 5e-6, 1.2e-5])
    F = np.array([-1.0, -4.0, -2.0, -2.0]) * 1e5
    n = 6
    start = ForceTarget.from_samples(t, F, "start").window_values(n, DT)
    mid = ForceTarget.from_samples(t, F, "midpoint").window_values(n, DT)
    mean = ForceTarget.from_samples(t, F, "mean").window_values(n, DT)
    np.testing.assert_allclose(start, np.interp(2 * DT * np.arange(n), t, F))
    np.testing.assert_allclose(mid, np.interp(DT * (2 * np.arange(n) + 1), t, F))
    # window 2 = [2, 4] us: by hand, the interpolant is -1e5 - 1e5*t/us up to 3 us, then rises by 1e5/us
    w2 = (-(3.0e5 + 4.0e5) / 2 * 1.0 - (4.0e5 + 3.0e5) / 2 * 1.0) / 2.0
    assert mean[1] == pytest.approx(w2, rel=1e-14)
    assert mean[5] == pytest.approx(-2e5, rel=1e-14)


def test_window_values_direct_and_as_target_dispatch():
    x = [-1.0, -2.0, -3.0]
    tgt = as_target(x)
    assert tgt.kind == "windows"
    np.testing.assert_array_equal(tgt.window_values(3, DT), x)
    assert as_target((np.array([0.0, 1.0]), np.array([-1.0, -1.0]))).kind == "samples"
    assert as_target(lambda t: -t).kind == "callable"
    with pytest.raises(ValueError, match="n: the target gives 3 window values"):
        tgt.window_values(4, DT)
    with pytest.raises(ValueError, match="dt: the window values were made for"):
        ForceTarget.from_window_values(x, dt=2e-6).window_values(3, DT)


def test_duration_and_sample_errors():
    tgt = ForceTarget.from_samples([0.0, 1e-5], [-1.0, -1.0])
    assert tgt.available_windows(DT) == 5
    with pytest.raises(ValueError, match="n: 6 windows .* need a target lasting"):
        tgt.window_values(6, DT)
    with pytest.raises(ValueError, match="must start at t = 0"):
        ForceTarget.from_samples([1e-6, 2e-6], [-1.0, -1.0])
    with pytest.raises(ValueError, match="must increase strictly"):
        ForceTarget.from_samples([0.0, 2e-6, 1e-6], [-1.0, -1.0, -1.0])
    with pytest.raises(ValueError, match="differ in length"):
        ForceTarget.from_samples([0.0, 2e-6], [-1.0, -1.0, -1.0])
    with pytest.raises(ValueError, match="rule: must be one of"):
        ForceTarget.from_callable(lambda t: -t, "end")
    with pytest.raises(ValueError, match="must be finite"):
        ForceTarget.from_samples([0.0, 1e-5], [-1.0, np.nan])
    with pytest.raises(TypeError, match="target: give a callable"):
        as_target(3.0)


def test_thesis_targets():
    t = np.array([0.0, 1e-4, 3e-4])
    np.testing.assert_allclose(ExponentialDecay(239e3, 0.383e-3)(t), -239e3 * np.exp(-t / 0.383e-3))   # eq. 4.24
    np.testing.assert_allclose(LinearRamp(239e3, 0.383e-3)(t), -239e3 * (1 + 2 * t / 0.383e-3))          # eq. 4.28
    np.testing.assert_allclose(ExponentialGrowth(187e3, 5.88e3)(t), -187e3 * np.exp(5.88e3 * t))         # eq. 4.29
    with pytest.raises(ValueError, match="ExponentialDecay.peak"):
        ExponentialDecay(-1.0, 1.0)


def test_lundberg_lesser_closed_form_values():
    # eq. 4.26 by hand: Z0 = 1/(v/N - 1/Z~) = 1/(6/239.1e3 - 1/79.7e3) = 79.7e3 exactly for N = 6 Z~ / 2
    z = lundberg_lesser_impedance(np.array([0.0, 0.383e-3 / 2]), 239.1e3, 0.383e-3, 79.7e3, 6.0)
    assert z[0] == pytest.approx(79.7e3, rel=1e-12)
    assert z[1] == pytest.approx(79.7e3 / 4, rel=1e-12)      # theta = t0/2: (1 + 2 * 1/2)^2 = 4
