"""The head's response to an impulse from a band-limited blow: regularised deconvolution of the record by the
blow (:func:`impulse_response`), the first step of dynamic deconvolution before layer peeling (Bube and
Burridge 1983, "The one-dimensional inverse problem of reflection seismology", SIAM Review 25, sec. 2;
Robinson's layer peeling of an impulse response on Goupillaud's equal-travel-time layers), and the length it
resolves (:func:`resolution`).

A lossless rod below the head is linear and time-invariant. With the head force N (N, tension positive) as the
input, the up-going force wave is u = N * G, G the head's up-going wave under a unit impulse of force (one
sample per two-way element travel time T, :mod:`rodimpact.identify.peeling`; G[0] = 0 by causality: the first
interface answers one sample after the onset); the down-going wave is then d = N - u = N * (delta - G). In terms
of the reflection impulse response R of the rod below (u = d * R), G = R / (1 + R). Layer peeling divides by
d[0]; a hammer's half-sine starts from zero, so the plain recursion cannot use it. The recursion is linear in the
pair of waves and keeps its structure under convolution of both by one sequence, so (d, u) = N * (delta - G, G)
peels to the same impedances as the pair (delta - G, G), whose first down sample is 1: deconvolve first, then
peel the impulse response.

Why by N and not u by d (u = d * R, the textbook form): when the head is free after the blow and the toe reflects, d
carries every echo reflected at the head, D = N / (1 + R), and its inverse rings as long as the rod does; the record
is cut at its end, and a regularised inverse spreads that cut over all of R (measured on a lattice rod with a free
toe, half-sines of 6, 12 and 24 samples: the profile above the toe wrong by up to 77 % to 79 % a pulse length from
its steps, against 1.3 % to 1.8 % with a non-reflecting toe). N is the blow alone, short, and its regularised
inverse is a few pulse lengths long: the cut corrupts only the last few pulse lengths of G. The noise of the
velocity then enters the numerator only.

The deconvolution is regularised (Tikhonov; the "water level" of seismic deconvolution), in the frequency
domain on a grid zero-padded to at least twice the record so that the circular convolution of the FFT does not
wrap the late samples onto the early ones:

    G(f) = U(f) conj(P(f)) / (|P(f)|^2 + eps max_f |P(f)|^2),     P = the pulse N,

the least-squares inverse where |P| is well above sqrt(eps) max|P|, fading to zero where the blow carries no
energy (there the record holds only noise). The estimate is G convolved with the zero-phase wavelet
w = IFFT(|P|^2 / (|P|^2 + eps max|P|^2)): band-limited, centred on the true arrivals (no delay), so the peeled
profile is a smoothed one with its steps at the right depths. An optional zero-phase low-pass ``corner`` (Hz)
multiplies G(f) by 1 / (1 + (f / corner)^8), the gain of the fourth-order Butterworth run forward and backward
(:func:`rodimpact.identify.records.band_limited`).

The choice of eps: it is the noise-to-signal power ratio of the Wiener filter, relative to the peak of |P|^2.
The default :data:`WATER_LEVEL` = 0.01 keeps the band where |P| > 0.1 max|P| (20 dB below the pulse's peak
spectral amplitude): for a half-sine of duration tau that is f < about 1.3 / tau, the band a hammer blow puts
its energy into, and 1 % of the peak power is the conventional water level (a choice, stated as such). When the
noise is known, the Wiener ratio is the guide: white noise of standard deviation sigma (N) on the up wave has
the power K sigma^2 in every bin of a K-sample record, against |P|^2 |G|^2 of the signal; eps = K sigma^2 /
(max|P|^2 |G|^2) with |G| about the toe's reflection. Noisier records want a larger eps, cleaner ones a smaller.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from .._validate import finite_array, positive

__all__ = ["WATER_LEVEL", "impulse_response", "resolution"]

#: The default eps of the regularised deconvolution, a share of max |P|^2 (module docstring).
WATER_LEVEL = 1e-2
#: Order of the zero-phase low-pass of ``corner``: the power of (f / corner) in its gain (Butterworth 4, run
#: forward and backward).
CORNER_POWER = 8
#: The wavelet's lobes below this share of its peak are taken as resolved (:func:`resolution`).
LOBE_SHARE = 0.05


def impulse_response(pulse: Any, response: Any, interval: float, *, water_level: float = WATER_LEVEL,
                     corner: Optional[float] = None) -> np.ndarray:
    """The impulse response X (one sample per ``interval``, X[0] = 0) with ``response`` = ``pulse`` * X, by
    regularised frequency-domain deconvolution (module docstring).

    ``pulse``, ``response``: samples from the onset, of one length (at the head: the force N and the up-going
    force wave u, N; :func:`rodimpact.identify.records.split_waves`); ``interval``: their sampling interval (s);
    ``water_level``: eps > 0, a share of max |P|^2; ``corner``: an optional zero-phase low-pass (Hz, below the
    Nyquist frequency).
    """
    p = finite_array("pulse", pulse, min_size=2)
    y = finite_array("response", response)
    if y.size != p.size:
        raise ValueError(f"response: must have one sample per sample of pulse ({p.size}), got {y.size}")
    nfft, inverse = _inverse(p, interval, water_level, corner)
    out = np.fft.irfft(np.fft.rfft(y, nfft) * inverse, nfft)[:p.size]
    out[0] = 0.0                                      # causality: nothing has come back at the onset
    return out


def resolution(pulse: Any, interval: float, *, water_level: float = WATER_LEVEL,
               corner: Optional[float] = None) -> int:
    """The half-length (samples) of the zero-phase wavelet w = IFFT(|P|^2 / (|P|^2 + eps max|P|^2)) that the
    deconvolved response is the true one convolved with: the largest lag k with |w[k]| >= :data:`LOBE_SHARE`
    w[0], plus one (w includes the low-pass of ``corner``). Two reflectors closer than this (in samples, i.e.
    elements) are not told apart; for a half-sine of L = 6, 12, 24 samples at the default eps it is 9, 17, 34
    (the ringing of the half-sine's spectral notches, filled by eps)."""
    p = finite_array("pulse", pulse, min_size=2)
    nfft, inverse = _inverse(p, interval, water_level, corner)
    w = np.fft.irfft(np.fft.rfft(p, nfft) * inverse, nfft)[:nfft // 2]
    return int(np.flatnonzero(np.abs(w) >= LOBE_SHARE * w[0])[-1]) + 1


def _inverse(pulse: np.ndarray, interval: float, water_level: float,
             corner: Optional[float]) -> tuple[int, np.ndarray]:
    """The FFT length (>= twice the record: no wrap-around of the linear convolution) and the regularised
    inverse conj(P) / (|P|^2 + eps max|P|^2), times the low-pass of ``corner``, on its rfft grid."""
    dt = positive("interval", interval, "s")
    eps = positive("water_level", water_level)
    if not np.any(pulse):
        raise ValueError("pulse: is zero; there is no blow to deconvolve by")
    nfft = 1 << int(np.ceil(np.log2(2 * pulse.size)))
    P = np.fft.rfft(pulse, nfft)
    power = np.abs(P) ** 2
    inverse = np.conj(P) / (power + eps * power.max())
    if corner is not None:
        fc = positive("corner", corner, "Hz")
        nyquist = 0.5 / dt
        if fc >= nyquist:
            raise ValueError(f"corner: must be below the Nyquist frequency {nyquist:.6g} Hz, got {fc:.6g} Hz")
        inverse /= 1.0 + (np.fft.rfftfreq(nfft, dt) / fc) ** CORNER_POWER
    return nfft, inverse
