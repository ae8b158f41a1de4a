"""Alignment, normalisation, repeatability statistics and error metrics."""

import numpy as np
import pytest

from rodimpact.signals import (
    align,
    crossing_times,
    delay_by_trigger,
    delay_by_xcorr,
    normalize_by_global_minimum,
    normalized_rms_error,
    peak_error,
    shifted,
    shot_statistics,
    step_timing_errors,
    trigger_time,
)

DT = 1e-6
T = np.arange(0, 2e-3, DT)


def smooth_pulse(t, t0, width=20e-6):
    """Compressive pulse: a smoothed rectangle (two error-function-like edges via tanh)."""
    return -0.5 * (np.tanh((t - t0) / width) - np.tanh((t - t0 - 300e-6) / width))


@pytest.mark.parametrize("shift_samples", [37.3, -12.75, 0.4])
def test_xcorr_recovers_a_known_subsample_shift(shift_samples):
    shift = shift_samples * DT
    reference = smooth_pulse(T, 500e-6)
    signal = smooth_pulse(T, 500e-6 + shift)  # generated analytically, not by interpolation
    assert delay_by_xcorr(T, reference, signal) == pytest.approx(shift, abs=0.01 * DT)


def test_xcorr_with_noise_still_recovers_the_shift_to_a_tenth_of_a_sample():
    # noise 0.3 % of the pulse height. Expected error: the noise x noise part of the
    # correlation fluctuates by ~ sigma^2 sqrt(N) = 4e-4 from lag to lag, against a peak
    # curvature of ~ sum(s'^2) / 2 = 0.017 per sample^2: about 0.02 sample.
    rng = np.random.default_rng(7)
    reference = smooth_pulse(T, 500e-6) + rng.normal(0, 0.003, T.size)
    signal = smooth_pulse(T, 523.6e-6) + rng.normal(0, 0.003, T.size)
    assert delay_by_xcorr(T, reference, signal) == pytest.approx(23.6e-6, abs=0.1 * DT)


def test_trigger_alignment_is_exact_for_linear_edges():
    # ramps from 0 to -1 over 10 us; level -0.5 is crossed at t0 + 5 us exactly
    def ramp_step(t0):
        return -np.clip((T - t0) / 10e-6, 0, 1)

    reference, signal = ramp_step(100.25e-6), ramp_step(143.7e-6)
    assert trigger_time(T, reference, -0.5) == pytest.approx(105.25e-6, abs=1e-12)
    assert delay_by_trigger(T, reference, signal, -0.5) == pytest.approx(43.45e-6, abs=1e-12)


def test_align_puts_the_signal_onto_the_reference():
    reference = smooth_pulse(T, 500e-6)
    signal = smooth_pulse(T, 612.4e-6)
    aligned, delay = align(T, reference, signal, method="xcorr")
    assert delay == pytest.approx(112.4e-6, abs=0.01 * DT)
    assert np.max(np.abs(aligned - reference)) < 1e-3
    aligned_t, delay_t = align(T, reference, signal, method="trigger", level=-0.5)
    assert delay_t == pytest.approx(112.4e-6, abs=0.01 * DT)


def test_shifted_delays_a_signal():
    x = np.clip((T - 1e-4) / 1e-4, 0, 1)
    y = shifted(T, x, 50e-6)
    assert trigger_time(T, y, 0.5, "rising") == pytest.approx(trigger_time(T, x, 0.5, "rising") + 50e-6, abs=1e-12)


def test_crossing_times_both_slopes():
    t = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
    x = np.array([0.0, -2.0, -2.0, 0.0, 0.0])
    np.testing.assert_allclose(crossing_times(t, x, -1.0, "falling"), [0.5])
    np.testing.assert_allclose(crossing_times(t, x, -1.0, "rising"), [2.5])
    np.testing.assert_allclose(crossing_times(t, x, -1.0, "either"), [0.5, 2.5])
    with pytest.raises(ValueError, match="never crosses"):
        trigger_time(t, x, -3.0)


def test_normalize_by_global_minimum_hand_values():
    np.testing.assert_allclose(normalize_by_global_minimum([1.0, -4.0, 2.0]), [0.25, -1.0, 0.5])
    with pytest.raises(ValueError, match="negative"):
        normalize_by_global_minimum([1.0, 2.0])


def test_shots_scaled_by_velocity_collapse_after_normalisation():
    # thesis 5.3.3: results scale with impact velocity; normalised shots coincide
    base = smooth_pulse(T, 500e-6)
    shots = [v * base for v in (3.47, 4.60, 5.60)]
    normalised = [normalize_by_global_minimum(s) for s in shots]
    assert np.max(np.abs(normalised[0] - normalised[2])) < 1e-12


def test_shot_statistics_hand_values():
    stats = shot_statistics([[1.0, 2.0], [2.0, 4.0], [3.0, 6.0]])
    np.testing.assert_allclose(stats.mean, [2.0, 4.0])
    np.testing.assert_allclose(stats.std, [1.0, 2.0])  # sample standard deviation (ddof=1)
    lo, hi = stats.band(2.0)
    np.testing.assert_allclose(lo, [0.0, 0.0])
    np.testing.assert_allclose(hi, [4.0, 8.0])
    np.testing.assert_allclose(stats.minimum, [1.0, 2.0])
    np.testing.assert_allclose(stats.maximum, [3.0, 6.0])
    assert stats.n_shots == 3
    with pytest.raises(ValueError, match="at least 2"):
        shot_statistics([[1.0, 2.0]])
    with pytest.raises(ValueError, match="same length"):
        shot_statistics([[1.0, 2.0], [1.0]])


def test_error_metrics_hand_values():
    t = np.array([0.0, 1.0, 2.0, 3.0])
    predicted = np.array([0.0, -10.0, -10.0, 0.0])
    measured = np.array([0.0, -11.0, -9.0, 1.0])
    peak = peak_error(t, measured, predicted)
    assert peak.measured == -11.0 and peak.predicted == -10.0
    assert peak.relative_error == pytest.approx(-0.1)
    assert peak.time_difference == 0.0
    # RMS of (0, -1, 1, 1) = sqrt(3/4); / max|predicted| = 10
    assert normalized_rms_error(t, measured, predicted) == pytest.approx(np.sqrt(0.75) / 10)
    assert normalized_rms_error(t, measured, predicted, window=(1.0, 2.0)) == pytest.approx(0.1)


def test_step_timing_errors_hand_values():
    t = np.linspace(0, 100e-6, 1001)
    predicted = -np.clip((t - 10e-6) / 2e-6, 0, 1) - np.clip((t - 40e-6) / 2e-6, 0, 1)
    measured = -np.clip((t - 10.5e-6) / 2e-6, 0, 1) - np.clip((t - 39e-6) / 2e-6, 0, 1)
    errors = step_timing_errors(t, measured, predicted, levels=[-0.5, -1.5])
    np.testing.assert_allclose(errors, [0.5e-6, -1e-6], atol=1e-12)
