"""First-mode Pochhammer-Chree dispersion and dispersive propagation.

References used here (independent of the solver's own algebra):

* Rayleigh's surface-wave speed for nu = 1/4 in closed form, c_R / c2 = sqrt(2 - 2/sqrt(3))
  (Lord Rayleigh, Proc. London Math. Soc. 17, 4-11, 1885): the short-wavelength limit.
* Rayleigh's long-wavelength correction c / c0 = 1 - nu^2 pi^2 (a/Lambda)^2 + O((a/Lambda)^4)
  (Rayleigh, *Theory of Sound* vol. 1, sec. 157; Love, *Mathematical Theory of Elasticity*,
  sec. 278): checked by the convergence of the remainder / (a/Lambda)^4.
* The frequency equation in its original complex form (Pochhammer 1876; Graff, *Wave Motion
  in Elastic Solids*, sec. 8.2), evaluated with complex Bessel functions at the solver's roots.
* Bancroft's table of the first-mode phase velocity (Phys. Rev. 59, 588, 1941), c/c0 to five
  decimals at 25 values of d/Lambda for nu = 0.10 ... 0.40, and its limiting row:
  ``tests/data/dispersion/bancroft_1941.csv`` (provenance and two resolved transcription
  differences in its header).
"""

from pathlib import Path

import numpy as np
import pytest
from scipy import signal as sps
from scipy import special
from scipy.interpolate import lagrange

from rodimpact.signals import (
    PochhammerChree,
    phase_velocity_at_frequency,
    phase_velocity_at_wavelength,
    propagate_dispersive,
    rayleigh_speed_ratio,
)

BANCROFT = Path(__file__).resolve().parents[1] / "data" / "dispersion" / "bancroft_1941.csv"
# one unit in the last printed decimal: the table is rounded to 5 decimals (half a unit) and was
# computed by hand in 1941, so its last digit is not guaranteed beyond that
PRINTED_DIGIT = 1e-5


def _bancroft():
    """(d/Lambda rows without the limiting row, Poisson ratios, c/c0 table, limiting row)."""
    rows = [line.split(",") for line in BANCROFT.read_text().splitlines() if not line.startswith("#")]
    nus = np.array([float(name.removeprefix("nu_")) for name in rows[0][1:]])
    data = np.array(rows[1:], dtype=float)     # "inf" marks the limiting row
    finite = np.isfinite(data[:, 0])
    return data[finite, 0], nus, data[finite, 1:], data[~finite, 1:][0]


def test_rayleigh_speed_closed_form_for_quarter_poisson_ratio():
    assert rayleigh_speed_ratio(0.25) == pytest.approx(np.sqrt(2 - 2 / np.sqrt(3)), rel=1e-12)


@pytest.mark.parametrize("nu", [0.29, 0.30])
def test_long_wavelength_limit_is_rayleighs_correction(nu):
    ratios = np.array([0.005, 0.01])
    c = phase_velocity_at_wavelength(nu, ratios)
    remainder = (c - (1 - nu**2 * np.pi**2 * ratios**2)) / ratios**4
    # a wrong second-order term would make this ratio grow 4x from 0.01 to 0.005
    assert remainder[0] == pytest.approx(remainder[1], rel=2e-3)
    assert phase_velocity_at_wavelength(nu, 0.0) == 1.0


@pytest.mark.parametrize("nu", [0.25, 0.29, 0.30])
def test_short_wavelength_limit_is_the_rayleigh_speed(nu):
    c_r = rayleigh_speed_ratio(nu) / np.sqrt(2 * (1 + nu))  # c_R / c0
    dev = phase_velocity_at_wavelength(nu, np.array([10.0, 20.0, 40.0])) / c_r - 1
    assert np.all(np.abs(dev) < 2e-3)
    # the deviation shrinks like 1 / (a/Lambda) (surface curvature)
    assert abs(dev[2]) < 0.6 * abs(dev[1]) < 0.36 * abs(dev[0])


def _original_frequency_function(c_over_c0, ka, nu):
    """Pochhammer's equation as printed (radius 1, k = ka, omega = k c), complex arithmetic."""
    c0_c2 = np.sqrt(2 * (1 + nu))
    c2_c1 = np.sqrt((1 - 2 * nu) / (2 * (1 - nu)))
    k = ka
    omega_over_c2 = k * c_over_c0 * c0_c2
    alpha = np.sqrt(complex((omega_over_c2 * c2_c1) ** 2 - k * k))
    beta = np.sqrt(complex(omega_over_c2**2 - k * k))
    j0a, j1a = special.jv(0, alpha), special.jv(1, alpha)
    j0b, j1b = special.jv(0, beta), special.jv(1, beta)
    terms = (
        2 * alpha * (beta**2 + k**2) * j1a * j1b,
        -((beta**2 - k**2) ** 2) * j0a * j1b,
        -4 * k**2 * alpha * beta * j1a * j0b,
    )
    total = sum(terms)
    part = np.real if abs(total.real) >= abs(total.imag) else np.imag
    return total, max(abs(t) for t in terms), part


@pytest.mark.parametrize("nu", [0.29, 0.30])
@pytest.mark.parametrize("radius_over_wavelength", [0.05, 0.2, 0.35, 0.5, 0.8, 1.5, 3.0])
def test_roots_satisfy_the_original_complex_frequency_equation(nu, radius_over_wavelength):
    ka = 2 * np.pi * radius_over_wavelength
    c = float(phase_velocity_at_wavelength(nu, radius_over_wavelength))
    value, scale, part = _original_frequency_function(c, ka, nu)
    assert abs(value) <= 1e-9 * scale
    lo, _, _ = _original_frequency_function(c * (1 - 1e-6), ka, nu)
    hi, _, _ = _original_frequency_function(c * (1 + 1e-6), ka, nu)
    assert part(lo) * part(hi) < 0  # a genuine (odd) root, not a touching point


@pytest.mark.parametrize("column", range(7), ids=lambda j: f"nu={0.10 + 0.05 * j:.2f}")
def test_phase_velocity_matches_bancrofts_table(column):
    d_over_l, nus, table, _ = _bancroft()
    ours = phase_velocity_at_wavelength(nus[column], d_over_l / 2)
    dev = np.abs(ours - table[:, column])
    worst = int(np.argmax(dev))
    assert dev[worst] <= PRINTED_DIGIT, (
        f"nu = {nus[column]}: c/c0 = {ours[worst]:.6f} at d/Lambda = {d_over_l[worst]}, "
        f"Bancroft {table[worst, column]:.5f}")


def test_limiting_velocity_matches_bancrofts_last_row():
    _, nus, _, limit = _bancroft()
    ours = np.array([rayleigh_speed_ratio(nu) / np.sqrt(2 * (1 + nu)) for nu in nus])  # c_R / c0
    np.testing.assert_allclose(ours, limit, rtol=0, atol=PRINTED_DIGIT)


def test_nu_029_matches_bancrofts_table_interpolated_in_poisson_ratio():
    # Bancroft has no nu = 0.29 column; interpolate each row in nu (cubic through 0.20 ... 0.35) and
    # take the difference to the degree-5 interpolant through 0.15 ... 0.40 as its error estimate
    d_over_l, nus, table, _ = _bancroft()
    cubic = np.array([lagrange(nus[2:6], row[2:6])(0.29) for row in table])
    quintic = np.array([lagrange(nus[1:7], row[1:7])(0.29) for row in table])
    ours = phase_velocity_at_wavelength(0.29, d_over_l / 2)
    assert np.all(np.abs(ours - cubic) <= PRINTED_DIGIT + np.abs(cubic - quintic))


@pytest.mark.parametrize("column", [4, 0, 6], ids=["nu=0.30", "nu=0.10", "nu=0.40"])
def test_phase_velocity_at_bancrofts_normalised_frequencies(column):
    # each table entry is also a point of the curve c/c0 (f a / c0), at f a / c0 = (c/c0) (a/Lambda);
    # a rounding error e of the entry moves that frequency too, so the printed-digit tolerance is
    # widened by |dc/dfbar| a/Lambda (slope from the table itself)
    d_over_l, nus, table, _ = _bancroft()
    a_over_l, c = d_over_l[1:] / 2, table[1:, column]
    fbar = c * a_over_l
    tol = PRINTED_DIGIT * (1 + np.abs(np.gradient(c, fbar)) * a_over_l)
    exact = phase_velocity_at_frequency(nus[column], fbar)
    assert np.all(np.abs(exact - c) <= tol)
    # the interpolated curve used for propagation (2e-6: its own interpolation error, tested below)
    model = PochhammerChree(nus[column], radius=0.01, bar_wave_speed=5000.0)
    interpolated = model.phase_velocity(fbar * 5000.0 / 0.01) / 5000.0
    assert np.all(np.abs(interpolated - c) <= tol + 2e-6)


def test_frequency_and_wavelength_forms_agree():
    nu = 0.29
    ratios = np.array([0.1, 0.3, 0.6, 1.2])
    c = phase_velocity_at_wavelength(nu, ratios)
    fbar = ratios * c  # f a / c0 = (a / Lambda) (c / c0)
    np.testing.assert_allclose(phase_velocity_at_frequency(nu, fbar), c, rtol=1e-10)


def test_interpolated_table_matches_direct_solves():
    model = PochhammerChree(0.29, radius=0.01, bar_wave_speed=5000.0)
    f = np.array([3e3, 47e3, 111.1e3, 180e3, 333e3, 700e3])
    direct = phase_velocity_at_frequency(0.29, f * 0.01 / 5000.0) * 5000.0
    np.testing.assert_allclose(model.phase_velocity(f), direct, rtol=2e-6)


def test_tone_burst_travels_at_the_group_velocity():
    nu, a, c0 = 0.30, 0.01, 5000.0
    model = PochhammerChree(nu, radius=a, bar_wave_speed=c0)
    f0 = 0.2 * c0 / a  # f a / c0 = 0.2 (100 kHz)
    # group velocity from exact roots, independent of the interpolation: d omega / d k
    ka = np.array([1 - 1e-4, 1 + 1e-4]) * 2 * np.pi * 0.2 / float(phase_velocity_at_frequency(nu, 0.2))
    c_k = phase_velocity_at_wavelength(nu, ka / (2 * np.pi))
    c_group = np.diff(ka * c_k)[0] / np.diff(ka)[0] * c0
    dt = 0.1e-6
    t = np.arange(0, 3.2768e-3, dt)
    t_center, width = 0.6e-3, 80e-6
    burst = np.exp(-0.5 * ((t - t_center) / width) ** 2) * np.sin(2 * np.pi * f0 * (t - t_center))
    distance = 2.0
    out = propagate_dispersive(t, burst, distance, model)
    envelope = np.abs(sps.hilbert(out))
    i = int(np.argmax(envelope))
    y0, y1, y2 = envelope[i - 1 : i + 2]
    t_peak = t[i] + 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2) * dt
    expected = distance * (1 / c_group - 1 / c0)  # relative to the 1D travel time z / c0
    assert t_peak - t_center == pytest.approx(expected, rel=0.01)


@pytest.mark.parametrize("nu", [0.29, 0.30, 0.35])
def test_group_velocity_is_d_omega_d_k_of_the_exact_roots(nu):
    """:meth:`PochhammerChree.group_velocity` (from the spline of the phase velocity) against d omega / d k by a
    central difference of omega = c(k) k over exact roots of the frequency equation at a / Lambda (1 +- 1e-4)
    (issue 20, item 22: a flipped sign in the method gave 5665.5 m/s instead of 4070.2 m/s at f a / c0 = 0.2, and
    no test called it). The difference's own error is O(1e-8); the spline's derivative is good to about 1e-6."""
    a, c0 = 0.01, 5000.0
    model = PochhammerChree(nu, radius=a, bar_wave_speed=c0)
    fbar = np.array([0.02, 0.1, 0.2, 0.35, 0.5, 0.8, 1.2])
    ratio = fbar / phase_velocity_at_frequency(nu, fbar)           # a / Lambda = (f a / c0) / (c / c0)
    h = 1e-4
    omega = [ratio * s * phase_velocity_at_wavelength(nu, ratio * s) for s in (1 - h, 1 + h)]    # omega a/(2 pi c0)
    expected = (omega[1] - omega[0]) / (2 * h * ratio) * c0
    np.testing.assert_allclose(model.group_velocity(fbar * c0 / a), expected, rtol=1e-5)
    if nu == 0.30:
        assert float(model.group_velocity(0.2 * c0 / a)) == pytest.approx(4070.2, abs=0.05)
    # long waves: Rayleigh's c = c0 (1 - nu^2 pi^2 (a/Lambda)^2) gives c_g = c0 (1 - 3 nu^2 pi^2 (a/Lambda)^2)
    long = ratio[:2]
    rayleigh = c0 * (1 - 3 * nu**2 * np.pi**2 * long**2)
    assert np.all(np.abs(model.group_velocity(fbar[:2] * c0 / a) / rayleigh - 1) <= 50 * long**4)
    assert float(model.group_velocity(0.0)) == pytest.approx(c0, rel=1e-12)


def test_propagate_then_correct_returns_the_pulse():
    model = PochhammerChree(0.29, radius=0.00475, bar_wave_speed=4975.0)
    dt = 0.1e-6
    t = np.arange(0, 600e-6, dt)
    edge = 0.3e-6  # a 1D pulse with edges of ~1 us, sampled at 10 MHz
    pulse = -0.5 * (np.tanh((t - 100e-6) / edge) - np.tanh((t - 151e-6) / edge))
    dispersed = propagate_dispersive(t, pulse, 0.39, model)
    assert np.max(np.abs(dispersed - pulse)) > 0.1  # dispersion really changed it (ringing)
    restored = propagate_dispersive(t, dispersed, -0.39, model)
    np.testing.assert_allclose(restored, pulse, rtol=0, atol=1e-7)


def test_propagate_then_correct_a_sharp_rectangle():
    # A sampled rectangle has spectral content up to the Nyquist frequency, where the
    # dispersive phase is discontinuous between +f_N and -f_N; its slowly decaying tails
    # (~1e-6 of the amplitude at the record ends) leave the record and are lost.
    model = PochhammerChree(0.29, radius=0.00475, bar_wave_speed=4975.0)
    t = np.arange(0, 600e-6, 0.1e-6)
    pulse = -np.where((t >= 100e-6) & (t < 151e-6), 1.0, 0.0)
    restored = propagate_dispersive(t, propagate_dispersive(t, pulse, 0.39, model), -0.39, model)
    np.testing.assert_allclose(restored, pulse, rtol=0, atol=1e-5)


def test_long_waves_are_not_dispersed():
    model = PochhammerChree(0.29, radius=0.005, bar_wave_speed=5000.0)
    t = np.arange(0, 4e-3, 1e-6)
    smooth = np.exp(-0.5 * ((t - 2e-3) / 200e-6) ** 2)  # f a / c0 ~ 1e-3
    out = propagate_dispersive(t, smooth, 1.0, model)
    assert np.max(np.abs(out - smooth)) < 1e-5


def test_bad_input():
    with pytest.raises(ValueError, match="poisson_ratio"):
        PochhammerChree(0.6, 0.01, 5000.0)
    with pytest.raises(ValueError, match="radius"):
        PochhammerChree(0.3, -0.01, 5000.0)
    model = PochhammerChree(0.3, 0.01, 5000.0)
    with pytest.raises(ValueError, match="uniform"):
        propagate_dispersive([0.0, 1e-6, 3e-6], [0.0, 1.0, 0.0], 1.0, model)
    with pytest.raises(TypeError, match="PochhammerChree"):
        propagate_dispersive([0.0, 1e-6, 2e-6], [0.0, 1.0, 0.0], 1.0, "steel")
