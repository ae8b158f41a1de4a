"""Measuring-chain filters against scipy's own responses and the -3 dB definition."""

import numpy as np
import pytest
from scipy import signal

from rodimpact.signals import MeasuringChain, Recording, bessel_analog, bessel_digital, simulate_analog_filter

CHAIN = MeasuringChain()  # thesis Tab. 5.1: analog Bessel 5th 100 kHz, 1 MHz, digital Bessel 4th 40 kHz


def _steady_state_phasor(t, y, f, t_from):
    """Least-squares amplitude and phase of y = A sin(w t + phi) for t >= t_from."""
    m = t >= t_from
    w = 2 * np.pi * f
    basis = np.column_stack([np.sin(w * t[m]), np.cos(w * t[m])])
    (s, c), *_ = np.linalg.lstsq(basis, y[m], rcond=None)
    return np.hypot(s, c), np.arctan2(c, s)


def test_designed_filters_are_minus_3db_at_their_corners():
    # the -3 dB definition of the corner ('mag' normalisation), checked with scipy's freqs/sosfreqz
    z, p, k = bessel_analog(5, 100e3)
    _, h = signal.freqs_zpk(z, p, k, worN=[2 * np.pi * 100e3])
    assert abs(h[0]) == pytest.approx(1 / np.sqrt(2), rel=1e-10)
    sos = bessel_digital(4, 40e3, 1e6)
    _, h = signal.sosfreqz(sos, worN=[40e3], fs=1e6)
    assert abs(h[0]) == pytest.approx(1 / np.sqrt(2), rel=1e-10)
    # 20 log10(1/sqrt 2) = -3.0103 dB
    assert 20 * np.log10(abs(CHAIN.analog_response(100e3)[0])) == pytest.approx(-3.0103, abs=1e-4)


def test_analog_simulation_matches_lsim():
    # scipy.signal.lsim integrates the same analog filter for a piecewise-linear input
    t = np.arange(0, 200e-6, 1e-7)
    x = np.where(t > 20e-6, 1.0, 0.0) * np.sin(2 * np.pi * 3e4 * t) + np.where(t > 120e-6, -0.5, 0.0)
    grid, y = simulate_analog_filter(t, x, order=5, corner=100e3, simulation_rate=1e7)
    np.testing.assert_array_equal(grid, t)
    _, y_lsim, _ = signal.lsim(bessel_analog(5, 100e3), x, t)
    assert np.max(np.abs(y - y_lsim)) < 1e-8


def _hold_by_hand(t, x, grid):
    """Zero-order hold: at each grid time the last sample taken at or before it (a sample at exactly that time
    counts), walked through in order."""
    out, i = [], 0
    for g in grid:
        while i + 1 < len(t) and t[i + 1] <= g:
            i += 1
        out.append(x[i])
    return np.array(out)


def test_analog_simulation_of_a_held_record_matches_lsim():
    """interpolation='previous' on an uneven or too slow record holds each sample until the next one (issue 20,
    item 22: a hold that took the sample before whenever a grid time fell on a sample time lagged one sample:
    [0, 1, 2, 2, 4, 5] became [0, 0, 1, 2, 2, 4]); checked against a hold by hand and scipy's lsim. The sample
    times are whole multiples of the grid step 2^-21 s, exact in binary, so grid times fall on sample times."""
    h = 2.0**-21
    rate = 1 / h                                             # 2.1 MHz >= 10 x the corner
    t = np.array([0, 1, 2, 4, 5]) * h
    x = np.array([0.0, 1.0, 2.0, 4.0, 5.0])
    np.testing.assert_array_equal(_hold_by_hand(t, x, np.arange(6) * h), [0, 1, 2, 2, 4, 5])
    rng = np.random.default_rng(7)
    uneven = np.cumsum(np.concatenate([[0], rng.integers(1, 6, 80)])) * h
    slow = np.arange(60) * 4 * h                             # uniform, but 4 x slower than the grid
    for t in (np.array([0, 1, 2, 4, 5]) * h, uneven, slow):
        x = np.concatenate([[0.0], rng.normal(size=t.size - 1)])     # at rest at the start, as lsim begins
        grid, y = simulate_analog_filter(t, x, order=5, corner=100e3, simulation_rate=rate,
                                         interpolation="previous")
        np.testing.assert_array_equal(grid, np.arange(round(t[-1] / h) + 1) * h)
        _, y_lsim, _ = signal.lsim(bessel_analog(5, 100e3), _hold_by_hand(t, x, grid), grid)
        assert np.max(np.abs(y - y_lsim)) < 1e-8


def test_analog_stage_gain_and_phase_at_corner_match_freqs():
    f = 100e3
    dt = 1 / 20e6
    t = np.arange(0, 400e-6, dt)
    grid, y = simulate_analog_filter(t, np.sin(2 * np.pi * f * t), 5, 100e3)
    amplitude, phase = _steady_state_phasor(grid, y, f, 200e-6)
    h = CHAIN.analog_response(f)[0]
    # a sampled sine taken as piecewise linear carries the factor sinc^2(f dt) (triangle hold)
    assert amplitude == pytest.approx(abs(h) * np.sinc(f * dt) ** 2, rel=1e-7)
    assert phase == pytest.approx(np.angle(h), abs=1e-7)


def test_analog_stage_group_delay_at_corner_matches_freqs():
    f, df = 100e3, 100.0
    dt = 1 / 20e6
    t = np.arange(0, 400e-6, dt)
    phases = []
    for fi in (f - df, f + df):
        grid, y = simulate_analog_filter(t, np.sin(2 * np.pi * fi * t), 5, 100e3)
        phases.append(_steady_state_phasor(grid, y, fi, 200e-6)[1])
    measured = -(phases[1] - phases[0]) / (2 * np.pi * 2 * df)
    # reference 1: central difference of the unwrapped phase of scipy.signal.freqs_zpk
    z, p, k = bessel_analog(5, 100e3)
    _, h = signal.freqs_zpk(z, p, k, worN=2 * np.pi * np.array([f - df, f + df]))
    from_freqs = -np.diff(np.unwrap(np.angle(h)))[0] / (2 * np.pi * 2 * df)
    assert measured == pytest.approx(from_freqs, rel=1e-5)
    # reference 2: the chain's closed-form group delay of the analog stage
    analog_only = MeasuringChain(digital_order=None)
    assert analog_only.group_delay(f)[0] == pytest.approx(from_freqs, rel=1e-5)


def test_digital_stage_gain_and_group_delay_at_corner_match_freqz():
    fs, f, df = 1e6, 40e3, 50.0
    chain = MeasuringChain(analog_order=None)
    t = np.arange(0, 2e-3, 1 / fs)
    results = {}
    for fi in (f - df, f, f + df):
        tk, y = chain.apply(t, np.sin(2 * np.pi * fi * t))
        results[fi] = _steady_state_phasor(tk, y, fi, 1e-3)
    _, h = signal.sosfreqz(bessel_digital(4, 40e3, fs), worN=[f], fs=fs)
    assert results[f][0] == pytest.approx(abs(h[0]), rel=1e-9)
    assert results[f][0] == pytest.approx(1 / np.sqrt(2), rel=1e-9)
    measured = -(results[f + df][1] - results[f - df][1]) / (2 * np.pi * 2 * df)
    b, a = signal.sos2tf(bessel_digital(4, 40e3, fs))
    _, gd = signal.group_delay((b, a), w=[f], fs=fs)
    assert measured == pytest.approx(gd[0] / fs, rel=1e-5)
    assert chain.group_delay(f)[0] == pytest.approx(gd[0] / fs, rel=1e-9)


def test_whole_chain_response_is_product_of_stages():
    f = 25e3
    t = np.arange(0, 1.5e-3, 1e-7)  # 10 MHz input, resampled by the chain
    tk, y = CHAIN.apply(t, np.sin(2 * np.pi * f * t))
    np.testing.assert_allclose(np.diff(tk), 1e-6, rtol=1e-9)
    amplitude, phase = _steady_state_phasor(tk, y, f, 0.8e-3)
    h = CHAIN.response(f)[0]
    assert amplitude == pytest.approx(abs(h), rel=1e-4)
    assert phase == pytest.approx(np.angle(h), abs=1e-4)


def test_chain_is_causal_and_starts_in_steady_state():
    dt = 0.25e-6  # e.g. a lattice step; node values constant during a step
    t = np.arange(0, 300e-6, dt)
    x = np.where(t >= 100e-6, -5.0, 2.0)
    tk, y = CHAIN.apply(t, x, interpolation="previous")
    before = tk < 100e-6
    # steady state for the first value: nothing happens before the step, exactly
    np.testing.assert_allclose(y[before], 2.0, rtol=0, atol=1e-12)
    assert abs(y[-1] - (-5.0)) < 1e-6


def test_zero_phase_option_removes_the_delay():
    t = np.arange(0, 400e-6, 1e-7)
    x = np.exp(-0.5 * ((t - 200e-6) / 15e-6) ** 2)
    tk_c, y_c = CHAIN.apply(t, x)
    tk_z, y_z = CHAIN.apply(t, x, zero_phase=True)
    delay_causal = tk_c[np.argmax(y_c)] - 200e-6
    delay_zero = tk_z[np.argmax(y_z)] - 200e-6
    # causal: delayed by about the low-frequency group delay of the chain (12.2 us); zero phase: not delayed
    assert delay_causal == pytest.approx(CHAIN.group_delay(1e3)[0], abs=1.5e-6)
    assert abs(delay_zero) <= 1e-6


def test_apply_recording_filters_every_channel():
    t = np.arange(0, 200e-6, 1e-7)
    rec = Recording(t, {"a": np.sin(2e4 * t), "b": np.ones_like(t)}, {"a": "V", "b": "N"})
    out = CHAIN.apply_recording(rec)
    assert out.channel_names == ["a", "b"]
    assert out.units == {"a": "V", "b": "N"}
    assert out.sample_interval == pytest.approx(1e-6)
    np.testing.assert_allclose(out["b"], 1.0, atol=1e-12)


def test_bad_chain_settings_are_rejected():
    with pytest.raises(ValueError, match="digital_corner"):
        MeasuringChain(digital_corner=600e3)
    with pytest.raises(ValueError, match="analog_order"):
        MeasuringChain(analog_order=0)
    with pytest.raises(ValueError, match="norm"):
        MeasuringChain(norm="flat")
    with pytest.raises(ValueError, match="analog_rate"):
        MeasuringChain(analog_rate=500e3)
    with pytest.raises(ValueError, match="strictly increasing"):
        CHAIN.apply([0.0, 1e-6, 1e-6, 2e-6], [0.0, 1.0, 2.0, 3.0])
