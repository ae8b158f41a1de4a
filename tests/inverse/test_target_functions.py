"""Thesis target histories (ExponentialDecay, LinearRamp, ExponentialGrowth): 0 before the impact like
rodimpact.reference.lundberg_lesser_force, and a clear error for non-finite, empty or overflowing times."""

import numpy as np
import pytest

from rodimpact.inverse import ExponentialDecay, ExponentialGrowth, LinearRamp, lundberg_lesser_impedance
from rodimpact.reference import lundberg_lesser_force

TARGETS = {
    "ExponentialDecay": ExponentialDecay(1e5, 1e-4),
    "LinearRamp": LinearRamp(1e5, 1e-4),
    "ExponentialGrowth": ExponentialGrowth(1e5, 5.88e3),
}


@pytest.mark.parametrize("name", TARGETS)
def test_zero_before_the_impact(name):
    f = TARGETS[name]
    t = np.array([-1.0, -1e-9, 0.0, 1e-5])
    y = f(t)
    assert np.all(np.isfinite(y))
    np.testing.assert_array_equal(y[:2], 0.0)
    assert y[2] == -1e5 and y[3] < 0
    assert f(-1.0) == 0.0 and np.ndim(f(-1.0)) == 0
    assert f(np.zeros((2, 3))).shape == (2, 3)


def test_decay_matches_the_reference_force_on_both_sides_of_the_impact():
    t = np.linspace(-2e-4, 4e-4, 61)
    np.testing.assert_allclose(TARGETS["ExponentialDecay"](t), lundberg_lesser_force(t, 1e5, 1e-4), rtol=1e-15)


@pytest.mark.parametrize("name", TARGETS)
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_times_are_refused(name, bad):
    f = TARGETS[name]
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, entry 1 is"):
        f(np.array([0.0, bad]))
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, got"):
        f(bad)


@pytest.mark.parametrize("name", TARGETS)
def test_empty_or_non_numeric_times_are_refused(name):
    f = TARGETS[name]
    with pytest.raises(ValueError, match="t: got an empty array"):
        f([])
    with pytest.raises(TypeError, match=r"t: times \(s\) must be real numbers, got str"):
        f("abc")


@pytest.mark.parametrize("name", ["LinearRamp", "ExponentialGrowth"])
def test_overflow_is_an_error_not_inf(name):
    with pytest.raises(ValueError, match=rf"t: {name} overflows the floating-point range at t = 1e\+300 s"):
        TARGETS[name](np.array([0.0, 1e300]))


def test_lundberg_lesser_impedance_checks_its_arguments():
    with pytest.raises(ValueError, match=r"theta: travel times into the striker \(s\) must be finite"):
        lundberg_lesser_impedance([np.nan], 1e3, 1e-4, 4e4, 5.0)
    with pytest.raises(ValueError, match="theta: travel times into the striker must be >= 0 s"):
        lundberg_lesser_impedance([-1e-6], 1e3, 1e-4, 4e4, 5.0)
    with pytest.raises(ValueError, match="peak: must be finite"):
        lundberg_lesser_impedance([0.0], np.nan, 1e-4, 4e4, 5.0)
    with pytest.raises(ValueError, match="striker_velocity: 5.0 m/s is too slow"):
        lundberg_lesser_impedance([0.0], 2e5, 1e-4, 4e4, 5.0)   # peak = Z~ v exactly: no division by zero
