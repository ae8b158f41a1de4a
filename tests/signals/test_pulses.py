"""Pulse features and the 1D equal-impedance striker prediction."""

import numpy as np
import pytest

from rodimpact.signals import (
    equal_impedance_pulse,
    pulse_features,
    rectangular_pulse,
    striker_velocity_estimate,
    striker_velocity_from_impulse,
    striker_velocity_from_strain,
)


def trapezoid(t):
    """0 -> -1 linearly on [10, 12] us, -1 until 30 us, back to 0 linearly on [30, 34] us."""
    rise = np.clip((t - 10e-6) / 2e-6, 0, 1)
    fall = np.clip((t - 30e-6) / 4e-6, 0, 1)
    return -(rise - fall)


def test_pulse_features_of_a_trapezoid_hand_values():
    t = np.arange(0, 50e-6, 0.01e-6)
    pf = pulse_features(t, trapezoid(t))
    assert pf.plateau == pytest.approx(-1.0, abs=1e-12)
    assert pf.start == pytest.approx(11e-6, abs=1e-12)  # 50 % of the 2 us rise
    assert pf.end == pytest.approx(32e-6, abs=1e-12)  # 50 % of the 4 us fall
    assert pf.duration == pytest.approx(21e-6, abs=1e-12)
    assert pf.rise_time == pytest.approx(0.8 * 2e-6, abs=1e-12)  # 10 % -> 90 %
    assert pf.fall_time == pytest.approx(0.8 * 4e-6, abs=1e-12)


def test_equal_impedance_pulse_level_duration_and_momentum():
    # steel striker 0.2 m, d = 50 mm: c = sqrt(210e9/7840), Z = rho c A; v = 4.6 m/s
    rho, e_mod, area, length, v = 7840.0, 210e9, np.pi * 0.025**2, 0.2, 4.6
    c = np.sqrt(e_mod / rho)
    z = rho * c * area
    dt = 1e-8
    t = np.arange(-10e-6, 150e-6, dt)
    n = equal_impedance_pulse(t, length, c, z, v, arrival_time=0.0)
    assert n.min() == pytest.approx(-z * v / 2)
    assert np.count_nonzero(n) * dt == pytest.approx(2 * length / c, abs=dt)  # t* = 2 L / c, eq. (5.4)
    # the striker stops: its momentum rho A L v goes into the bar
    assert np.sum(n) * dt == pytest.approx(-rho * area * length * v, rel=1e-3)


def test_striker_velocity_from_strain_hand_value():
    # eps_p = -1e-3 in a bar with c = 5000 m/s -> particle velocity 5 m/s, striker 10 m/s
    assert striker_velocity_from_strain(-1e-3, 5000.0) == pytest.approx(10.0)


def test_velocity_estimators_recover_a_synthetic_shot():
    c, rho, area, length, v = 5000.0, 2800.0, 1e-5, 0.05, 12.0
    e_mod = rho * c * c
    t = np.arange(-5e-6, 40e-6, 1e-8)
    eps = rectangular_pulse(t, 0.0, 2 * length / c, -v / (2 * c))
    est = striker_velocity_estimate(t, eps, c, {"gauge factor": 0.005})
    assert est.velocity == pytest.approx(v, rel=1e-12)
    assert est.components["plateau definition"] == pytest.approx(0.0, abs=1e-12)
    assert est.uncertainty == pytest.approx(0.005 * v, rel=1e-12)
    imp = striker_velocity_from_impulse(t, e_mod * area * eps, rho * area * length, (-5e-6, 40e-6))
    assert imp.velocity == pytest.approx(v, rel=1e-3)


def test_pulse_features_rejects_a_missing_pulse():
    t = np.linspace(0, 1, 10)
    with pytest.raises(ValueError, match="polarity"):
        pulse_features(t, np.ones(10), polarity=-1)
    with pytest.raises(ValueError, match="polarity"):
        pulse_features(t, -np.ones(10), polarity=0)
