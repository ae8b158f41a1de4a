"""Layer peeling of band-limited records (rodimpact/identify/deconvolution.py and ``identify_by_peeling(...,
deconvolve=True)``): the regularised deconvolution against convolutions made by numpy, its zero-phase wavelet,
the deconvolved peel of clean lattice records hit by a half-sine (rodimpact.simulate, numpy path), its agreement
with the plain peel for a sharp blow, and bad input."""

import numpy as np
import pytest

from rodimpact.identify import identify_by_peeling
from rodimpact.identify.deconvolution import WATER_LEVEL, impulse_response, resolution
from rodimpact.identify.matching import half_sine

DT = 1e-6
N = 120
PULSE = 12                       # samples of the half-sine (sampling interval 2 DT: the rod's two-way time)


def wave_speed(rod):
    m = rod.segments[0].material
    return float(np.sqrt(m.youngs_modulus / m.density))


def test_impulse_response_inverts_a_convolution_made_by_numpy():
    """A sharp pulse whose spectrum has no zeros and a response with its tail inside the record: with eps tiny the
    deconvolution returns the impulse response that np.convolve was given."""
    n = 64
    pulse = np.r_[1.0, 0.6, 0.3, 0.1, np.zeros(n - 4)]
    x = np.zeros(n)
    x[[1, 3, 7, 12, 19]] = [0.2, -0.1, 0.05, 0.3, -0.25]
    y = np.convolve(pulse, x)[:n]
    assert np.all(np.convolve(pulse, x)[n:] == 0.0)      # nothing cut off at the record's end
    got = impulse_response(pulse, y, 1e-3, water_level=1e-12)
    assert np.max(np.abs(got - x)) < 1e-9


def test_a_single_echo_comes_back_as_a_zero_phase_wavelet_at_its_arrival():
    """One reflector (r = 0.4, arriving at sample 128) seen through a half-sine of 12 samples: the estimate is r
    times a zero-phase wavelet (symmetric about the arrival, to rounding: no delay, so depths are not shifted),
    its peak at the arrival and a main lobe wider than one sample (a 12-sample blow resolves no single sample;
    without the regularisation the clean echo would come back as one spike)."""
    n, m, r = 256, 128, 0.4
    pulse = half_sine(np.arange(n, dtype=float), 1.0, PULSE, 0.0)
    x = np.zeros(n)
    x[m] = r
    got = impulse_response(pulse, np.convolve(pulse, x)[:n], 1e-3)
    j = np.arange(1, 100)
    assert np.max(np.abs(got[m + j] - got[m - j])) < 1e-12 * r
    assert int(np.argmax(np.abs(got))) == m and 0.0 < got[m] < r
    assert got[m + 1] > 0.5 * got[m]
    assert resolution(pulse, 1e-3) >= PULSE // 2
    first = np.zeros(n)
    first[1] = r                                 # an echo one sample after the onset: the wavelet reaches t < 0
    assert impulse_response(pulse, np.convolve(pulse, first)[:n], 1e-3)[0] == 0.0     # causality


def _neck_profile():
    z = np.full(N, 4.0e5)
    z[40:52] *= 0.7                              # a 30 % necking, 12 elements long
    return z


def _steps_far(size, steps, margin):
    far = np.ones(size, bool)
    for s in steps:
        far[max(0, s - margin):s + margin] = False
    return far


@pytest.mark.parametrize("method", ["schur", "reference"])
def test_half_sine_on_a_clean_necked_rod(simulated_head, method):
    """Lattice rod, 30 % necking at elements 40-51, non-reflecting below, hit by a half-sine of 12 samples (the
    plain peel refuses it). The deconvolved peel: Z within 2 % of the truth one pulse length (12 elements) or
    more from the neck's steps (measured 1.4 %: the wavelet's lobes); one anomaly, the neck, its top within 3
    elements (a quarter pulse length; measured 2 early: the smoothed step crosses the threshold before the step) of
    element 40, its size within 0.05 of -0.3 (measured -0.307) and its length within half a pulse length of 12
    elements (each smoothed edge may cross the threshold a quarter pulse away; measured 16)."""
    z = _neck_profile()
    record, rod = simulated_head(z, DT, lambda t: half_sine(t, 1e5, 2 * PULSE * DT, 0.0), 2 * (N + 40))
    c = wave_speed(rod)
    h = c * DT
    with pytest.raises(ValueError, match="deconvolve=True"):
        identify_by_peeling(record, z[0], c, method=method)
    out = identify_by_peeling(record, z[0], c, method=method, deconvolve=True)
    m = out.impedance.size
    truth = np.r_[z, np.full(m, z[-1])][:m]
    far = _steps_far(m, (40, 52), PULSE)
    assert np.max(np.abs(out.impedance[far] / truth[far] - 1.0)) < 0.02
    (neck,) = out.anomalies
    assert abs(neck.depth - 40 * h) <= 3 * h
    assert abs(neck.relative_change + 0.3) < 0.05 and neck.beta_class == "damage"
    assert abs(neck.length - 12 * h) <= 0.5 * PULSE * h
    assert out.toe is None and out.diagnostics["water_level"] == WATER_LEVEL


def test_free_toe_is_found_near_the_expected_length(simulated_head):
    """The same rod with a free toe at 120 elements, the expected length 5 % too long, a record of 256 samples
    that rings to its end (free head after the blow, free toe: the deconvolved record is cut while echoes still
    arrive). The toe is the largest drop within 20 % of the expected length, found at element 120 (within one
    element asked); Z within 2 % one pulse length or more from the neck's steps and two above the toe (measured
    1.4 %; an FFT on 256 points, without the zero padding, wraps the cut onto the first samples: 5.0 %); the neck
    is the only anomaly at the benchmark's threshold 0.08 (the toe's smoothed step and the wavelet's lobes before
    it are not)."""
    z = _neck_profile()
    record, rod = simulated_head(z, DT, lambda t: half_sine(t, 1e5, 2 * PULSE * DT, 0.0), 2 * 256, right="free")
    assert record.time.size == 256
    c = wave_speed(rod)
    h = c * DT
    out = identify_by_peeling(record, z[0], c, deconvolve=True, length=1.05 * N * h, threshold=0.08)
    assert out.toe == pytest.approx(N * h, abs=1.01 * h)
    m = out.impedance.size
    assert m == round(out.toe / h)
    far = _steps_far(m, (40, 52), PULSE)
    far[m - 2 * PULSE:] = False
    assert np.max(np.abs(out.impedance[far] / z[:m][far] - 1.0)) < 0.02
    (neck,) = out.anomalies
    assert abs(neck.depth - 40 * h) <= 3 * h


@pytest.mark.parametrize("method", ["schur", "reference"])
@pytest.mark.parametrize("blow", ["exponential", "impulse"])
def test_sharp_blow_deconvolved_equals_the_plain_peel(simulated_head, method, blow):
    """A sharp blow (a mass impact's exponential decay, or a one-step impulse) on a rod of 24 random elements
    above a uniform non-reflecting part: the echoes have died out before the record ends (nothing is cut off), so
    with eps = 1e-12 the deconvolved peel is the plain one (the recursion commutes with convolving both waves by
    the blow) to 1e-8 (measured 3.5e-13 and 3.5e-12 with the numpy reference; this checks the conjugate, the
    zero padding and the pair (delta - G, G) of the deconvolution)."""
    n = 200
    z = np.full(n, 4.0e5)
    z[:24] = 4.0e5 * np.exp(np.cumsum(np.random.default_rng(1).normal(0.0, 0.08, 24)))
    z[24:] = z[23]
    force = {"exponential": lambda t: -1e5 * np.exp(-t / 10e-6),
             "impulse": lambda t: np.where(t < 1.5 * DT, -1e5, 0.0)}[blow]
    record, rod = simulated_head(z, DT, force, 2 * n)
    c = wave_speed(rod)
    plain = identify_by_peeling(record, z[0], c, method=method)
    deconvolved = identify_by_peeling(record, z[0], c, method=method, deconvolve=True, water_level=1e-12)
    assert plain.impedance.size == deconvolved.impedance.size == n
    assert np.max(np.abs(plain.impedance / z - 1.0)) < 1e-10
    assert np.max(np.abs(deconvolved.impedance / plain.impedance - 1.0)) < 1e-8


@pytest.mark.parametrize("bad", [0.0, -0.01, float("nan"), float("inf")])
def test_bad_water_level_is_named(simulated_head, bad):
    record, rod = simulated_head(np.full(20, 4e5), DT, lambda t: half_sine(t, 1e5, 8 * DT, 0.0), 40)
    with pytest.raises(ValueError, match="water_level"):
        identify_by_peeling(record, 4e5, wave_speed(rod), deconvolve=True, water_level=bad)
    with pytest.raises(ValueError, match="water_level"):
        impulse_response(np.ones(8), np.ones(8), 1e-3, water_level=bad)


def test_bad_input_is_named(simulated_head):
    record, rod = simulated_head(np.full(20, 4e5), DT, lambda t: half_sine(t, 1e5, 8 * DT, 0.0), 40)
    c = wave_speed(rod)
    with pytest.raises(ValueError, match="pulse"):
        impulse_response([1.0, np.nan, 0.0], [0.0, 1.0, 0.0], 1e-3)
    with pytest.raises(ValueError, match="response"):
        impulse_response([1.0, 0.5, 0.0], [0.0, np.inf, 0.0], 1e-3)
    with pytest.raises(ValueError, match="response"):
        impulse_response([1.0, 0.5, 0.0], [0.0, 1.0], 1e-3)
    with pytest.raises(ValueError, match="pulse"):
        impulse_response(np.zeros(4), np.ones(4), 1e-3)
    with pytest.raises(ValueError, match="corner"):
        identify_by_peeling(record, 4e5, c, deconvolve=True, corner=0.5 / record.interval)
    with pytest.raises(ValueError, match="corner"):
        identify_by_peeling(record, 4e5, c, corner=1e4)          # an option of the deconvolution only
    with pytest.raises(ValueError, match="length"):
        identify_by_peeling(record, 4e5, c, deconvolve=True, length=-1.0)
    with pytest.raises(ValueError, match="window"):
        identify_by_peeling(record, 4e5, c, deconvolve=True, window=1)
    with pytest.raises(TypeError, match="deconvolve"):
        identify_by_peeling(record, 4e5, c, deconvolve="yes")


def test_noise_bands_of_the_deconvolved_peel_grow_linearly_with_the_noise(simulated_head):
    """The bands by resampling deconvolve every noisy copy as the record: the deconvolution is linear and the
    peel smooth, so for small noise the band's width is proportional to it (first-order error propagation;
    measured ratio 10.00 from 1 N to 10 N, 6.2e-5 and 6.2e-4 relative median width); the band holds the profile
    and the neck is still the one anomaly."""
    z = _neck_profile()
    record, rod = simulated_head(z, DT, lambda t: half_sine(t, 1e5, 2 * PULSE * DT, 0.0), 2 * (N + 40))
    widths = []
    for sigma in (1.0, 10.0):
        out = identify_by_peeling(record, z[0], wave_speed(rod), deconvolve=True, noise=sigma, resamples=50)
        assert np.all(out.lower <= out.impedance) and np.all(out.impedance <= out.upper)
        assert len(out.anomalies) == 1
        widths.append(np.median((out.upper - out.lower) / out.impedance))
    assert widths[1] / widths[0] == pytest.approx(10.0, rel=0.05)
