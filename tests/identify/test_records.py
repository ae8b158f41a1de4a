"""Head records and pre-processing (rodimpact/identify/records.py): closed forms and the refusals of bad input,
each naming the argument."""

import numpy as np
import pytest

from rodimpact.identify import HeadRecord, amplified, average_blows, band_limited, identify_by_peeling

T = np.arange(100) * 1e-6


def test_refuses_records_of_different_lengths():
    with pytest.raises(ValueError, match=r"velocity: must have one sample per time sample \(100\), got 99"):
        HeadRecord(T, np.ones(100), np.ones(99))


def test_refuses_non_uniform_sampling():
    t = T.copy()
    t[50] += 0.3e-6
    with pytest.raises(ValueError, match="time: must be uniformly sampled"):
        HeadRecord(t, np.ones(100), np.ones(100))


def test_refuses_non_finite_samples():
    f = np.ones(100)
    f[7] = np.nan
    with pytest.raises(ValueError, match="force: must be finite, entry 7"):
        HeadRecord(T, f, np.ones(100))


def test_refuses_a_force_in_kilonewton_with_an_impedance_in_newton_seconds_per_metre():
    """A down-going wave has N = -Z v; a force written in kN is 1000 times too small."""
    z = 4.0e5
    v = np.r_[np.full(50, 0.25), np.zeros(50)]
    record = HeadRecord(T, -z * v / 1000.0, v)
    with pytest.raises(ValueError, match=r"force, velocity, impedance: .*force in N \(not kN\)"):
        identify_by_peeling(record, z, 4000.0)


def test_refuses_a_record_too_short_for_the_depth():
    z = 4.0e5
    v = np.full(100, 0.25)
    record = HeadRecord(T, -z * v, v)
    with pytest.raises(ValueError, match=r"depth: 1 m needs a record of 2 depth / c = 0.0005 s .* at most 0.2 m"):
        identify_by_peeling(record, z, 4000.0, depth=1.0)


def test_refuses_a_smooth_onset_for_peeling():
    z = 4.0e5
    v = np.sin(np.pi * T / T[-1]) * 0.1
    with pytest.raises(ValueError, match="record: the down-going wave's first sample"):
        identify_by_peeling(HeadRecord(T, -z * v, v), z, 4000.0)


def test_averaging_blows_refuses_other_time_axes():
    a = HeadRecord(T, np.ones(100), np.ones(100))
    b = HeadRecord(T[:90], np.ones(90), np.ones(90))
    with pytest.raises(ValueError, match=r"records\[1\]: 90 samples, records\[0\] has 100"):
        average_blows([a, b])


def test_averaging_blows_is_the_mean():
    a = HeadRecord(T, np.full(100, 1.0), np.full(100, 3.0))
    b = HeadRecord(T, np.full(100, 2.0), np.full(100, 5.0))
    m = average_blows([a, b])
    assert np.all(m.force == 1.5) and np.all(m.velocity == 4.0)


def test_band_limit_keeps_a_slow_signal_and_removes_a_fast_one():
    """Zero-phase Butterworth at 50 kHz: a 5 kHz sine passes (gain 1 - O((5/50)^8) twice), a 400 kHz sine is
    attenuated by (400/50)^-8 per pass."""
    t = np.arange(4000) * 1e-7
    slow = np.sin(2 * np.pi * 5e3 * t)
    fast = np.sin(2 * np.pi * 400e3 * t)
    out = band_limited(HeadRecord(t, slow + fast, slow), 50e3)
    inner = slice(1000, 3000)
    assert np.max(np.abs(out.force[inner] - slow[inner])) < 1e-4
    with pytest.raises(ValueError, match="corner: must be below the Nyquist frequency"):
        band_limited(out, 6e6)


def test_amplification_closed_form():
    t = np.arange(5) * 1e-3
    assert np.allclose(amplified(t, np.ones(5), 100.0, start=1e-3), [1, 1, np.exp(0.1), np.exp(0.2), np.exp(0.3)],
                       rtol=1e-15)
    with pytest.raises(ValueError, match="rate: must be a finite amplification rate >= 0"):
        amplified(t, np.ones(5), -1.0)
