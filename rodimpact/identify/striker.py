"""Striker identification: what a measured incident pulse implies about the striker that made it, its impedance
profile, length and impact velocity, with bands from the record's noise (:func:`identify_striker`).

It is the inverse of the face response, i.e. the recursive method (thesis chapter 4) run on a measured force:
the force at the bar's impact face, ``F(t)`` (N, tension positive: the pulse is negative), is the target of
:func:`rodimpact.synthesize` against the bar (impedance ``Z_b``, at rest, long enough that nothing returns while
the pulse lasts), whose face moves at ``V = -F / Z_b`` (a right-going wave). The striker, moving at v0 before
the impact and counted from its impact face, follows element by element (eqs. 4.4-4.9):
``Z_1 = F_1 / (V_1 - v0)`` and so on. The one number a pulse alone cannot give is v0 (a striker of twice the
impedance at a lower speed can make the same force); it is taken

* as given (``velocity``), or
* from a known striker impedance ``Z_s`` (material and diameter) and the pulse's plateau ``F_p``: for a uniform
  striker ``F_p = -Z_s Z_b v0 / (Z_s + Z_b)`` (thesis eq. 4.4 with the two impedances in series), so
  ``v0 = -F_p (Z_s + Z_b) / (Z_s Z_b)``; for ``Z_s = Z_b`` this is ``v0 = -2 c eps_p``
  (:func:`rodimpact.signals.pulses.striker_velocity_from_strain`).

The length is ``L = c_s T / 2`` with the pulse duration T between the crossings of half the plateau (a uniform
striker's pulse lasts its two-way travel time). The profile is synthesized over the same span: its force windows
(two element travel times each) start at the first half-plateau crossing and hold the mean force of the samples
in them; their length defaults to the rise time, so that the ringing of a measured plateau (Pochhammer-Chree
dispersion between the impact face and the gauge) is averaged over and the first window is close to the plateau:
a window much shorter than the rise asks the striker's tip for a force growth that its waves cannot give
(existence, thesis eq. 4.20), since a 1D striker cannot make a finite rise time other than by a soft tip.

Bands: the pre-trigger baseline is noise alone; an autoregressive model of it
(:func:`rodimpact.identify.uncertainty.ar_noise_model`: Yule-Walker, the order by AIC, up to 20 and a quarter of
the baseline) gives its level and its colour. ``resamples`` copies of the pulse, each with an independent draw
of that stationary process added, go through the whole identification, and the 5 % and 95 % quantiles of each
number are its 90 % band. The colour matters: the impact velocity rests on the plateau's mean, the length on
two crossings, and low-frequency noise moves both far more than white noise of the same variance.
"""

from __future__ import annotations

import time as _time
import warnings
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from .._validate import caller_stacklevel, integer, positive
from .._version import __version__
from ..inverse.recursive import SynthesisWarning, synthesize
from ..rods.rod import Rod
from ..signals.pulses import pulse_features
from .records import check_uniform, time_series
from .uncertainty import ar_noise_model
from .validity import IdentificationWarning
from .result import IdentificationResult

__all__ = ["StrikerEstimate", "estimate_striker", "identify_striker"]

#: Share of the peak whose first crossing marks the pulse's onset when no baseline span is given.
EDGE_SHARE = 0.1
#: Quantiles of the 90 % band.
BAND = (0.05, 0.95)


@dataclass(frozen=True)
class StrikerEstimate:
    """The numbers of one identification: profile (N s/m from the impact face), v0 (m/s), length (m), the
    synthesis that gave the profile and its element travel time dt (s)."""

    impedance: np.ndarray
    velocity: float
    length: float
    synthesis: Any
    dt: float


def estimate_striker(time: np.ndarray, force: np.ndarray, bar_impedance: float, striker_wave_speed: float,
                     velocity: Optional[float], striker_impedance: Optional[float],
                     window: Optional[int] = None) -> StrikerEstimate:
    """One identification from a baseline-free pulse (module docstring); ``window``: samples per force window
    (default: the pulse's 10-90 % rise time in samples)."""
    feat = pulse_features(time, force, polarity=-1)
    length = 0.5 * striker_wave_speed * feat.duration
    if velocity is None:
        zs = bar_impedance if striker_impedance is None else striker_impedance
        velocity = -feat.plateau * (zs + bar_impedance) / (zs * bar_impedance)
    interval = float(time[1] - time[0])
    per = max(int(round(feat.rise_time / interval)), 1) if window is None else window
    inside = np.flatnonzero((time >= feat.start) & (time <= feat.end))
    pulse = force[inside[0]:inside[-1] + 1]
    n = pulse.size // per
    values = pulse[:n * per].reshape(n, per).mean(axis=1)     # window values: the mean over each window
    dt = 0.5 * per * interval                                   # one force window is 2 dt
    bar = Rod.from_impedance([bar_impedance] * (n + 1), dt=dt)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SynthesisWarning)
        syn = synthesize(values, bar, velocity, dt=dt)
    return StrikerEstimate(np.asarray(syn.impedance, dtype=float), float(velocity), float(length), syn, dt)


def identify_striker(time: Any, force: Any, bar_impedance: float, striker_wave_speed: float, *,
                     velocity: Optional[float] = None, striker_impedance: Optional[float] = None,
                     baseline: Optional[tuple[float, float]] = None, window: Optional[int] = None,
                     resamples: int = 100, seed: int = 0) -> IdentificationResult:
    """The striker implied by an incident pulse (module docstring).

    ``time`` (s) and ``force`` (N, tension positive) at the bar's impact face: the incident-bar gauge's force
    moved to the face (non-dispersive: shifted by the gauge distance over c). ``bar_impedance`` (N s/m),
    ``striker_wave_speed`` (m/s; depth along the striker = c_s x travel time). ``velocity``: v0 if known, else
    from ``striker_impedance`` (default: that of the bar) and the plateau. ``baseline``: the (start, end) time
    span (s) of the pre-trigger baseline (default: everything before the pulse's 10 % crossing less 5 % of the
    record); its mean is removed and its AR model is the noise (module docstring). ``resamples``: noisy copies for
    the bands (0: no bands); ``seed``: their random generator's seed. ``window``: samples per force window (two
    element travel times; default: the pulse's 10-90 % rise time; module docstring).

    The result's ``depth`` runs from the impact face along the striker, ``toe`` is the length from the pulse
    duration, ``diagnostics`` holds v0 (``striker_velocity_m_per_s``) and its band.
    """
    wall0 = _time.perf_counter()
    t, f = time_series(time, force, "force", min_size=8)
    check_uniform(t)
    resamples = integer("resamples", resamples, 0, "noisy copies for the bands")
    if window is not None:
        window = integer("window", window, 1, "samples per force window")
    zb = positive("bar_impedance", bar_impedance, "N s/m")
    cs = positive("striker_wave_speed", striker_wave_speed, "m/s")
    if velocity is not None:
        velocity = positive("velocity", velocity, "m/s")
    if striker_impedance is not None:
        striker_impedance = positive("striker_impedance", striker_impedance, "N s/m")
    if baseline is None:
        onset = int(np.argmax(-f >= EDGE_SHARE * np.max(-f))) if np.max(-f) > 0 else 0
        base = np.arange(max(onset - max(t.size // 20, 1), 0))
    else:
        b0, b1 = (float(b) for b in baseline)
        base = np.flatnonzero((t >= b0) & (t <= b1))
    if base.size < 2:
        raise ValueError("baseline: fewer than 2 pre-trigger samples; the record must start before the pulse "
                         "(or give baseline=(start, end) in s)")
    f = f - float(np.mean(f[base]))
    noise = ar_noise_model(f[base], max_order=min(20, base.size // 4))
    sigma = float(np.sqrt(noise.variance()))
    if not np.max(-f) > 0:
        raise ValueError("force: no compressive pulse (tension positive: an incident pulse is negative)")
    point = estimate_striker(t, f, zb, cs, velocity, striker_impedance, window)
    if point.synthesis.failure is not None:
        warnings.warn(f"the pulse implies a striker only for the first {point.impedance.size} force windows: "
                      f"{point.synthesis.failure.message}", IdentificationWarning, stacklevel=caller_stacklevel())
    rng = np.random.default_rng(seed)
    samples = []
    for _ in range(resamples):
        try:
            samples.append(estimate_striker(t, f + noise.draw(rng, f.size), zb, cs, velocity,
                                            striker_impedance, int(round(2 * point.dt / (t[1] - t[0])))))
        except ValueError:              # a noisy copy whose synthesis fails counts as missing, reported below
            continue
    m = point.impedance.size
    lower = upper = None
    bands: dict[str, Any] = {}
    if samples:
        k = min(m, min(s.impedance.size for s in samples))
        if k == m:
            stack = np.array([s.impedance[:m] for s in samples])
            lower, upper = np.quantile(stack, BAND, axis=0)
            lower, upper = np.minimum(lower, point.impedance), np.maximum(upper, point.impedance)
        for name in ("velocity", "length"):
            bands[name] = tuple(float(q) for q in np.quantile([getattr(s, name) for s in samples], BAND))
    depth = cs * point.dt * np.arange(m + 1)
    report = point.synthesis.verify()
    matched = {"face force": (report.time, report.target, report.achieved)}
    diagnostics = {"version": __version__, "wall_time_s": _time.perf_counter() - wall0,
                   "striker_velocity_m_per_s": point.velocity, "striker_velocity_band": bands.get("velocity"),
                   "length_m": point.length, "noise_sigma_N": sigma, "noise_model_order": noise.order,
                   "resamples": resamples,
                   "resamples_used": len(samples), "velocity_given": velocity is not None,
                   "elements_synthesized": m, "element_travel_time_s": point.dt,
                   "synthesis_failure": None if point.synthesis.failure is None
                   else point.synthesis.failure.message,
                   "misfit_definition": "max |simulated - target face force| / max |target| over the windows "
                                        "(the identified striker re-simulated against the bar)"}
    return IdentificationResult(depth=depth, impedance=point.impedance, lower=lower, upper=upper,
                                toe=point.length,
                                toe_band=bands.get("length"), wave_speed=cs, matched=matched,
                                misfit=float(report.max_deviation),
                                method="striker", diagnostics=diagnostics)
