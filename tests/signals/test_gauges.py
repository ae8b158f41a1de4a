"""Gauge and bridge conversions against hand-computed values (thesis eqs. 5.1-5.3)."""

import math

import numpy as np
import pytest

from rodimpact.signals import (
    Bridge,
    GaugedBar,
    bending_ratio,
    bending_stress,
    bridge_to_strain,
    opposite_gauge_average,
    strain_to_force,
)


def test_quarter_bridge_with_nonlinearity_correction_hand_value():
    # V_out = 0.5 V, V_exc = 10 V, gain 100 -> V_r = 0.5 / 1000 = 5e-4
    # eps = 4 V_r / (GF (1 - 2 V_r)) = 2e-3 / (2.1 * 0.999) = 2e-3 / 2.0979
    eps = bridge_to_strain(0.5, gauge_factor=2.1, excitation_voltage=10.0, gain=100.0, bridge="quarter")
    assert eps == pytest.approx(2e-3 / 2.0979, rel=1e-12)
    # compression: V_r = -5e-4 -> eps = -2e-3 / (2.1 * 1.001) = -2e-3 / 2.1021
    eps = bridge_to_strain(-0.5, 2.1, 10.0, 100.0, "quarter")
    assert eps == pytest.approx(-2e-3 / 2.1021, rel=1e-12)


def test_quarter_bridge_linearized_hand_value():
    # 4 * 5e-4 / 2.1 = 2e-3 / 2.1
    eps = bridge_to_strain(0.5, 2.1, 10.0, 100.0, "quarter", linearize=True)
    assert eps == pytest.approx(2e-3 / 2.1, rel=1e-12)


def test_nonlinearity_matters_at_large_output():
    # at V_r = 0.01 the correction factor 1/(1 - 2 V_r) = 1/0.98 changes the strain by 2 %
    exact = bridge_to_strain(0.01, 2.0, 1.0, bridge="quarter")
    linear = bridge_to_strain(0.01, 2.0, 1.0, bridge="quarter", linearize=True)
    assert exact / linear == pytest.approx(1 / 0.98, rel=1e-12)


@pytest.mark.parametrize(
    ("bridge", "vr", "expected_x"),
    [
        # half bridge, two axial gauges in opposite arms: V_r = x / (2 + x) -> x = 2 V_r / (1 - V_r)
        (Bridge.half_axial(), 2e-3, 4e-3 / 0.998),
        # half bridge, opposite-face gauges in adjacent arms: V_r = x / 2 (exactly linear)
        (Bridge.half_bending(), 1e-3, 2e-3),
        # full bending bridge: V_r = x (exactly linear)
        (Bridge.full_bending(), 1e-3, 1e-3),
        # half bridge with Poisson gauge, nu = 0.3: V_r = x (1 + nu) / (2 (2 + x (1 - nu)))
        #   -> x = 4 V_r / ((1 + nu) - 2 V_r (1 - nu)) = 4e-3 / (1.3 - 0.0014)
        (Bridge.half_poisson(0.3), 1e-3, 4e-3 / 1.2986),
        # full bridge, 2 axial + 2 Poisson gauges: V_r = x (1 + nu) / (2 + x (1 - nu))
        #   -> x = 2 V_r / ((1 + nu) - V_r (1 - nu)) = 2e-3 / (1.3 - 0.0007)
        (Bridge.full_poisson(0.3), 1e-3, 2e-3 / 1.2993),
    ],
)
def test_other_bridges_hand_values(bridge, vr, expected_x):
    gf = 2.0
    eps = bridge.strain(vr, gf)
    assert eps == pytest.approx(expected_x / gf, rel=1e-12)
    # and the forward model reproduces the output ratio
    assert bridge.output_ratio(eps, gf) == pytest.approx(vr, rel=1e-12)


def test_lanl_style_conversion_hand_value():
    # LANL bar: +3.2 V recorded for compression (polarity -1), gain 200, excitation 8 V, GF 2.061,
    # half bridge of two opposite axial gauges: V_r = -3.2 / 1600 = -2e-3,
    # eps = 2 V_r / (GF (1 - V_r)) = -4e-3 / (2.061 * 1.002)
    bar = GaugedBar(
        youngs_modulus=109.297184e9,
        density=4416.0,
        area=math.pi * 0.00947**2 / 4,
        gauge_factor=2.061,
        excitation_voltage=8.0,
        gain=200.0,
        bridge="half-axial",
        polarity=-1,
    )
    eps = bar.strain(3.2)
    assert eps == pytest.approx(-4e-3 / (2.061 * 1.002), rel=1e-12)
    # N = E A eps = 109.297184e9 * 7.0435214e-5 * eps
    assert bar.force(3.2) == pytest.approx(109.297184e9 * 7.04352142e-5 * eps, rel=1e-8)
    # c0 = sqrt(109.297184e9 / 4416) = 4974.96 m/s (the sheet's "rod sound speed" 4974.964141)
    assert bar.wave_speed == pytest.approx(4974.964141, rel=1e-8)


def test_strain_to_force_hand_value():
    # thesis rod: E = 210 GPa, d = 50 mm -> A = 1.9634954e-3 m^2; eps = -1e-4 -> N = -41233.4 N
    assert strain_to_force(-1e-4, 210e9, 1.9634954e-3) == pytest.approx(-41233.40, rel=1e-6)


def test_opposite_gauge_average_and_bending_stress_hand_values():
    n_0 = np.array([-1000.0, -500.0])
    n_180 = np.array([-800.0, -700.0])
    np.testing.assert_allclose(opposite_gauge_average(n_0, n_180), [-900.0, -600.0])  # eq. (5.1)
    # eq. (5.2) with A = 1e-3 m^2: (-1000 + 800) / 2e-3 = -1e5 Pa; (-500 + 700) / 2e-3 = +1e5 Pa
    np.testing.assert_allclose(bending_stress(n_0, n_180, 1e-3), [-1e5, 1e5])


def test_bending_ratio_hand_values():
    n_0 = np.array([-1000.0, -500.0])
    n_180 = np.array([-800.0, -700.0])
    # max |sigma_bend| = 100 N / A, max |sigma| = 900 N / A -> e = 1/9
    assert bending_ratio(n_0, n_180) == pytest.approx(1 / 9, rel=1e-12)
    # four gauges: bending 100 N (0-180) and 50 N (90-270) -> resultant sqrt(12500) = 111.803;
    # normal force (-1000 - 800 - 950 - 850) / 4 = -900 -> e = 0.124226
    e4 = bending_ratio([-1000.0], [-800.0], [-950.0], [-850.0])
    assert e4 == pytest.approx(0.1242260, rel=1e-6)


def test_bending_ratio_agrees_with_thesis_formula_in_stresses():
    rng = np.random.default_rng(1)
    n_0 = -1e4 * np.sin(np.linspace(0, np.pi, 50)) + rng.normal(0, 100, 50)
    n_180 = -1e4 * np.sin(np.linspace(0, np.pi, 50)) + rng.normal(0, 100, 50)
    area = 2e-3
    sigma = opposite_gauge_average(n_0, n_180) / area
    sigma_bend = bending_stress(n_0, n_180, area)
    e = np.max(np.abs(sigma_bend)) / np.max(np.abs(sigma))  # eq. (5.3) without the factor 100
    assert bending_ratio(n_0, n_180) == pytest.approx(e, rel=1e-12)


def test_bad_input_is_rejected_with_names():
    with pytest.raises(ValueError, match="gauge_factor"):
        bridge_to_strain(0.1, 0.0, 10.0)
    with pytest.raises(ValueError, match="excitation_voltage"):
        bridge_to_strain(0.1, 2.0, -1.0)
    with pytest.raises(ValueError, match="gain"):
        bridge_to_strain(0.1, 2.0, 10.0, gain=0.0)
    with pytest.raises(ValueError, match="unknown bridge"):
        bridge_to_strain(0.1, 2.0, 10.0, bridge="eighth")
    with pytest.raises(ValueError, match="poisson_ratio"):
        Bridge.named("half-poisson")
    with pytest.raises(ValueError, match="cannot be produced"):
        Bridge.quarter().strain(0.6, 2.0)  # a quarter bridge never exceeds V_r = 1/2
    with pytest.raises(ValueError, match="polarity"):
        GaugedBar(1e9, 1e3, 1e-4, 2.0, 5.0, polarity=2)
    with pytest.raises(ValueError, match="non-finite"):
        strain_to_force([1e-4, np.nan], 1e9, 1e-4)


def test_gauge_length_average_of_a_sine_hand_value():
    # L_g = 6.35 mm, c = 5000 m/s, f = 200 kHz -> Lambda = 25 mm, L_g / Lambda = 0.254:
    # sinc = sin(0.79796) / 0.79796 = 0.71594 / 0.79796 = 0.89720
    from rodimpact.signals import gauge_length_average

    dt = 0.01e-6
    t = np.arange(0, 200e-6, dt)
    envelope = np.exp(-0.5 * ((t - 100e-6) / 25e-6) ** 2)  # starts and ends at rest
    x = envelope * np.sin(2 * np.pi * 200e3 * t)
    y = gauge_length_average(t, x, 6.35e-3, wave_speed=5000.0)
    centre = slice(int(90e-6 / dt), int(110e-6 / dt))
    ratio = np.max(np.abs(y[centre])) / np.max(np.abs(x[centre]))
    # the Gaussian envelope (sigma = 25 us) varies over the gauge's travel time L_g / c = 1.27 us: averaging
    # its curvature changes the peak by about (L_g / c)^2 / (24 sigma^2) = 1.1e-4 (relative)
    assert ratio == pytest.approx(0.89720, abs=2e-4)


def test_gauge_length_average_equals_a_moving_average_for_a_non_dispersive_wave():
    from rodimpact.signals import gauge_length_average

    dt = 0.01e-6
    t = np.arange(0, 100e-6, dt)
    x = -np.clip((t - 30e-6) / 5e-6, 0, 1) + np.clip((t - 60e-6) / 5e-6, 0, 1)
    # L_g / c = 6.4 mm / 5000 m/s = 1.28 us = 128 sample intervals: a centred trapezoid-rule
    # boxcar of 129 points (half weights at the ends)
    y = gauge_length_average(t, x, 6.4e-3, wave_speed=5000.0)
    kernel = np.ones(129)
    kernel[0] = kernel[-1] = 0.5
    kernel /= kernel.sum()
    moving = np.convolve(x, kernel, mode="same")
    inner = slice(1000, 9000)
    assert np.max(np.abs(y[inner] - moving[inner])) < 1e-5
