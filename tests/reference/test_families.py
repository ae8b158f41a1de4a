"""Tab. 2.1 families: hand-checkable values and the PDE (2.12) for the travelling-wave solution."""

import math

import numpy as np
import pytest

from rodimpact.reference import FAMILIES, STEEL_BAR_SPEED, AnalyticProfile, plot_phase_speed

C0 = STEEL_BAR_SPEED


def test_steel_bar_speed_by_hand():
    assert C0 == pytest.approx(5175.491, abs=1e-3)  # sqrt(210e9 / 7840)


@pytest.mark.parametrize(
    ("family", "xi", "b", "cutoff"),
    [
        ("quadratic", 0.7, 0.0, 0.0),
        ("exponential", 0.5, 0.0625, C0 * 0.25),
        ("cosh2", 2.0, 4.0, 2.0 * C0),
        ("cos2", 2.0, -4.0, 0.0),
    ],
)
def test_b_and_cutoff_table_values(family, xi, b, cutoff):
    p = AnalyticProfile(family, 1e-3, xi)
    assert p.b == pytest.approx(b, rel=1e-15, abs=0)
    assert p.cutoff_angular_frequency == pytest.approx(cutoff, rel=1e-15, abs=0)


@pytest.mark.parametrize("family", FAMILIES)
def test_b_is_constant_from_its_definition(family):
    """b = h^2/4 + h'/2 (eq. 2.17) evaluated with a finite-difference h' is the tabulated constant."""
    p = AnalyticProfile(family, 2e-3, 0.8)
    x = np.linspace(-0.5, 0.5, 11)
    d = 1e-5
    hp = (p.area_gradient_ratio(x + d) - p.area_gradient_ratio(x - d)) / (2 * d)
    b_fd = p.area_gradient_ratio(x) ** 2 / 4 + hp / 2
    np.testing.assert_allclose(b_fd, p.b, atol=1e-8)


def test_area_gradient_ratio_matches_area_derivative():
    for p in AnalyticProfile.table(1.5e-3, 0.9):
        x = np.linspace(-0.4, 0.6, 7)
        d = 1e-6
        h_fd = (np.log(p.area(x + d)) - np.log(p.area(x - d))) / (2 * d)
        np.testing.assert_allclose(p.area_gradient_ratio(x), h_fd, rtol=1e-8, atol=1e-9)


def test_hand_values_exponential():
    p = AnalyticProfile("exponential", 1.96e-3, 0.5)
    wc = C0 / 4
    # at twice the cutoff: k = sqrt(4 b - b) = sqrt(3)/4, c_p = c0 / sqrt(1 - 1/4)
    assert p.wave_number(2 * wc).real == pytest.approx(math.sqrt(3) / 4, rel=1e-14)
    assert p.phase_velocity(2 * wc) == pytest.approx(2 * C0 / math.sqrt(3), rel=1e-14)
    assert p.area(2.0) == pytest.approx(1.96e-3 * math.e, rel=1e-14)
    assert p.amplitude(2.0, 3.0) == pytest.approx(3.0 / math.sqrt(math.e), rel=1e-14)  # a0 exp(-xi x / 2)
    # below the cutoff the wave number is imaginary and decays: k = i sqrt(b - w^2/c0^2)
    k = p.wave_number(0.6 * wc)
    assert k.real == 0.0 and k.imag == pytest.approx(math.sqrt(0.0625 * (1 - 0.36)), rel=1e-14)


def test_hand_values_other_families():
    q = AnalyticProfile("quadratic", 1e-3, 2.0)
    assert q.phase_velocity(123.0) == pytest.approx(C0, rel=1e-15)
    assert q.amplitude(0.5) == pytest.approx(0.5)  # 1 / (1 + 2 * 0.5)
    ch = AnalyticProfile("cosh2", 1e-3, 1.0)
    assert ch.amplitude(1.0) == pytest.approx(1 / math.cosh(1.0))
    assert ch.phase_velocity(2 * C0) == pytest.approx(C0 / math.sqrt(0.75))
    co = AnalyticProfile("cos2", 1e-3, 1.0)
    assert co.phase_velocity(C0) == pytest.approx(C0 / math.sqrt(2.0))
    assert co.wave_number(C0).real == pytest.approx(math.sqrt(2.0))
    assert co.area(math.pi / 3) == pytest.approx(1e-3 * 0.25)


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("omega_factor", [0.5, 1.7, 6.0])
def test_travelling_wave_solves_pde_2_12(family, omega_factor):
    """u = a(x) exp(i(kx - wt)) satisfies u_xx + h u_x - u_tt/c0^2 = 0 (finite differences, O(d^2))."""
    xi = 1.3
    p = AnalyticProfile(family, 1e-3, xi)
    omega = omega_factor * C0 * xi  # below the cutoff for 0.5 in the cosh2/exponential cases: still exact
    x = np.linspace(-0.4, 0.4, 9)
    t = 1.1e-4
    dx = 2e-4
    dt = dx / C0
    u = p.travelling_wave(x, t, omega)
    uxx = (p.travelling_wave(x + dx, t, omega) - 2 * u + p.travelling_wave(x - dx, t, omega)) / dx**2
    ux = (p.travelling_wave(x + dx, t, omega) - p.travelling_wave(x - dx, t, omega)) / (2 * dx)
    utt = (p.travelling_wave(x, t + dt, omega) - 2 * u + p.travelling_wave(x, t - dt, omega)) / dt**2
    residual = uxx + p.area_gradient_ratio(x) * ux - utt / C0**2
    scale = np.abs(utt / C0**2) + np.abs(uxx) + np.abs(p.area_gradient_ratio(x) * ux)
    assert np.max(np.abs(residual) / scale) < 1e-6


def test_phase_velocity_refuses_below_cutoff_and_bad_input():
    p = AnalyticProfile("cosh2", 1e-3, 1.0)
    with pytest.raises(ValueError, match="cutoff"):
        p.phase_velocity([0.5 * C0, 2 * C0])
    with pytest.raises(ValueError, match="family"):
        AnalyticProfile("linear", 1e-3, 1.0)
    with pytest.raises(ValueError, match="area_start"):
        AnalyticProfile("cos2", -1.0, 1.0)
    with pytest.raises(ValueError, match="x:"):
        AnalyticProfile("cos2", 1e-3, 1.0).area(2.0)  # cos(2) < 0: area would vanish on the way
    with pytest.raises(ValueError, match="omega"):
        p.wave_number(-1.0)


def test_phase_speed_plot_fig_2_2():
    ax = plot_phase_speed(xi=1.0)
    lines = [ln for ln in ax.get_lines() if ln.get_label() and not ln.get_label().startswith("_")]
    assert len(lines) == 4
    # the exponential curve starts above its cutoff c0/2 and approaches c0 at high frequency
    exp_line = lines[1]
    w, cp = exp_line.get_data()
    assert w.min() > C0 / 2
    assert cp[-1] == pytest.approx(C0 / math.sqrt(1 - (C0 / (2 * w[-1])) ** 2))
    assert plot_phase_speed(xi=0.5, ax=ax) is ax
