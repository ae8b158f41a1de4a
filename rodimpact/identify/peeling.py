"""Exact layer peeling of a clean, lossless head record (thesis chapter 1, the scattering problem, solved by the
recursion of chapter 4): :func:`identify_by_peeling` and the plain reference :func:`peel_waves`.

The rod below the head is taken as equal-travel-time elements whose two-way travel time is one sampling
interval T: travel time dt = T / 2, element length c dt. Every path that leaves the head and returns is an even
number of steps long, so the head's samples form a closed system (docs/inverse.md, "Step 2"): from the down- and
up-going waves d_s, u_s (s = 0, 1, ...; :func:`rodimpact.identify.records.split_waves`) the elements follow one by
one. At the bottom of element q, in the time frame of its wavefront, ``d_bot[s] = d_top[s]`` and ``u_bot[s] =
u_top[s + 1]`` (the up wave is met one sample, two steps, earlier); the wavefront meets nothing coming back from
below, so ``r_q = u_bot[0] / d_bot[0]`` is the reflection coefficient ``(Z_{q+1} - Z_q) / (Z_{q+1} + Z_q)`` and

    Z_{q+1} = Z_q (1 + r_q) / (1 - r_q)                                              (thesis eq. 4.9)

Crossing the interface keeps the force N = d + u and the velocity v = (u - d) / Z_q; below it
``d = (N - Z_{q+1} v) / 2``, ``u = (N + Z_{q+1} v) / 2``. n samples give n elements. A free toe reflects with
r = -1 (Z -> 0), a fixed one with r = +1: the recursion stops there (existence, thesis eq. 4.20), which is the toe.

Requirements (checked): the record starts at the onset of the down-going wave, whose first sample must not be
small (the recursion divides by it: a smooth pulse that starts from zero, like a hammer's half-sine, cannot be
peeled at the sampling resolution; use :func:`rodimpact.identify.identify_by_beta`); lossless rod, no soil
resistance, no dispersion (the 1D model: docs/identification.md).

Two paths: ``method="schur"`` runs the package's O(n log^2 n) peel (:func:`rodimpact.inverse.peel_layers`, the
same recursion written on the waves ``g = d``, ``f = u``); ``method="reference"`` the loops of this module (O(n^2),
numpy). They agree to rounding (tests/identify/test_peeling.py).

Band-limited records (``deconvolve=True``): the recursion is linear in the pair (d, u) and keeps its structure
when both are convolved with one sequence, so (d, u) = N * (delta - G, G) peels to the same impedances as
(delta - G, G): the head's waves under a unit impulse of force, G estimated by regularised deconvolution of u by
the force N (:mod:`rodimpact.identify.deconvolution`, which says why by N and not by d). A smooth blow such as a
hammer's half-sine can then be used (dynamic deconvolution before layer peeling; Bube and Burridge 1983, SIAM
Review 25). G is band-limited, so the profile is a smoothed one: its steps are spread over about the pulse's
length (the wavelet's half-length, :func:`~rodimpact.identify.deconvolution.resolution`, in elements) and the
element-to-element jumps are small. Anomalies are then read against a running-median baseline
(:func:`rodimpact.identify.uncertainty.find_anomalies`, the reader of the matching method): a run of at least two
elements departing from the median of ``window`` elements by more than ``threshold``. The toe: where the
recursion stops (|r| >= 1, as without deconvolution); given the expected ``length``, the largest drop of ln Z
from one element to the next within :data:`TOE_SEARCH` of it (a smoothed free or soft toe need not reach
|r| = 1). The profile is cut at the toe; a run that ends within the resolution of the toe is the toe's own
smoothed step (its drop and the wavelet's lobes before it), not an anomaly.
"""

from __future__ import annotations

import time as _time
import warnings
from typing import Optional

import numpy as np

from .._validate import caller_stacklevel, integer, positive
from .._version import __version__
from ..inverse import peel_layers
from . import uncertainty as unc
from .deconvolution import WATER_LEVEL, impulse_response, resolution
from .records import HeadRecord, check_units, split_waves
from .reflectors import anomalies_of_profile, beta_class
from .result import Anomaly, IdentificationResult
from .validity import IdentificationWarning, resolution_warnings

__all__ = ["identify_by_peeling", "peel_waves"]

#: A first down-wave sample below this share of the down wave's peak is refused (the recursion divides by it).
ONSET_SHARE = 1e-3
#: An up-going wave at the onset beyond this share of the down-going one is reported (causality makes it 0; a
#: record that starts early or late shows it, noise of the record's size does not).
ONSET_UP_SHARE = 0.01
#: A peeled impedance below this share of the head impedance is taken as the (free) toe: r = -1 in exact
#: arithmetic, -1 + O(eps kappa) after rounding.
TOE_SHARE = 1e-6
METHODS = ("schur", "reference")
#: Quantiles of the 90 % band.
BAND = (0.05, 0.95)
#: With ``deconvolve`` and an expected ``length``, the toe is sought within this share of it either way (a pile's
#: length is known to about 10 % from its records; twice that as a margin).
TOE_SEARCH = 0.2


def peel_waves(down: np.ndarray, up: np.ndarray, impedance: float) -> tuple[np.ndarray, int]:
    """Peel the element impedances from the head's down- and up-going force waves (module docstring): plain numpy
    loops, O(n^2). ``down``, ``up``: N, one sample per two-way element travel time, from the onset;
    ``impedance``: Z_1 (N s/m). Returns ``(z, m)``: z[:m] are the impedances of elements 1..m; m < n when the
    recursion met |r| >= 1 (a free or fixed end) at the bottom of element m."""
    d = np.asarray(down, dtype=float).copy()
    u = np.asarray(up, dtype=float).copy()
    n = d.size
    z = np.zeros(n)
    z[0] = impedance
    for q in range(n - 1):
        d_bot, u_bot = d[:-1], u[1:]
        r = u_bot[0] / d_bot[0]
        z_next = z[q] * (1.0 + r) / (1.0 - r)
        if not (abs(r) < 1.0 and 0.0 < z_next < np.inf):
            return z, q + 1
        force = d_bot + u_bot
        velocity = (u_bot - d_bot) / z[q]
        d = 0.5 * (force - z_next * velocity)
        u = 0.5 * (force + z_next * velocity)
        z[q + 1] = z_next
    return z, n


def identify_by_peeling(record: HeadRecord, impedance: float, wave_speed: float, *,
                        depth: Optional[float] = None, method: str = "schur", threshold: float = 0.05,
                        noise: Optional[float] = None, resamples: int = 100, seed: int = 0,
                        diameter: Optional[float] = None, deconvolve: bool = False,
                        water_level: Optional[float] = None, corner: Optional[float] = None,
                        length: Optional[float] = None, window: Optional[int] = None) -> IdentificationResult:
    """The impedance profile below the head from a clean, lossless force and velocity record (module docstring).

    Parameters
    ----------
    record:
        Head force (N, tension positive) and velocity (m/s, down the rod), starting at the onset of the blow.
    impedance:
        The impedance at the head Z_1 (N s/m, ``E A / c``), known from the rod's top section.
    wave_speed:
        c (m/s), assumed constant along the rod: it turns travel time into depth (element length c T / 2).
    depth:
        The depth (m) to identify down to; the record must last ``2 depth / c``. Default: as deep as the
        record reaches, ``c (samples) T / 2``.
    method:
        ``"schur"`` (the package's fast peel) or ``"reference"`` (plain numpy loops).
    threshold:
        A run of elements whose impedance differs from the one above it by more than this share is reported as
        an anomaly (a choice of this package, not from a standard; docs/identification.md). With ``deconvolve``:
        from the running median of ``window`` elements.
    noise, resamples, seed:
        90 % bands by resampling: ``noise`` (N) is the standard deviation of the force record's noise (the
        velocity's is ``noise / Z``); ``resamples`` copies with independent normal noise of that size are peeled
        and the 5 % and 95 % quantiles of each element form the band. Noise grows along the recursion: the
        profile is cut where more than 10 % of the copies stop (|r| >= 1), with a warning. ``None``: no bands.
    diameter:
        The rod's diameter (m) for the 1D-validity warnings
        (:func:`rodimpact.identify.validity.resolution_warnings`); ``None``: no check.
    deconvolve:
        Peel the head's waves under a unit impulse of force, deconvolved from the record, instead of the record
        (module docstring): for blows without a sharp front. The following options belong to it (an error
        without it).
    water_level:
        eps of the deconvolution, a share of max |P|^2, P the force's spectrum (default
        :data:`~rodimpact.identify.deconvolution.WATER_LEVEL`; the choice is discussed there).
    corner:
        An optional zero-phase low-pass (Hz) of the impulse response.
    length:
        The expected length of the rod (m): the toe is the largest drop within :data:`TOE_SEARCH` of it and the
        default ``window`` a quarter of it. ``None``: the toe is where the recursion stops, if it does.
    window:
        Elements of the running median that anomalies are read against (default a quarter of ``length``, or
        of the profile, at least 9).
    """
    wall0 = _time.perf_counter()
    if not isinstance(record, HeadRecord):
        raise TypeError(f"record: must be a HeadRecord, got {type(record).__name__}")
    if method not in METHODS:
        raise ValueError(f"method: must be one of {METHODS}, got {method!r}")
    if not isinstance(deconvolve, bool):
        raise TypeError(f"deconvolve: must be True or False, got {deconvolve!r}")
    if not deconvolve:
        given = [k for k, v in (("water_level", water_level), ("corner", corner), ("length", length),
                                ("window", window)) if v is not None]
        if given:
            raise ValueError(f"{given[0]}: applies with deconvolve=True only")
    else:
        water_level = WATER_LEVEL if water_level is None else positive("water_level", water_level)
        length = None if length is None else positive("length", length, "m")
        window = None if window is None else integer("window", window, 3, "elements of the running median")
    z1 = positive("impedance", impedance, "N s/m")
    c = positive("wave_speed", wave_speed, "m/s")
    element = 0.5 * c * record.interval
    n = record.time.size
    if depth is not None:
        depth = positive("depth", depth, "m")
        need = int(np.ceil(depth / element - 1e-9))
        if need > n:
            raise ValueError(f"depth: {depth:.6g} m needs a record of 2 depth / c = {2 * depth / c:.6g} s "
                             f"({need} samples at {record.interval:.6g} s), the record has {n} samples "
                             f"({record.duration:.6g} s); ask for at most {n * element:.6g} m")
        n = need
    check_units(record, z1)
    down, up = split_waves(record, z1)
    down, up = down[:n].copy(), up[:n].copy()
    onset_up = None
    if deconvolve:
        impulse = np.zeros(n)
        impulse[0] = 1.0

        def peel(d: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, int, Optional[np.ndarray]]:
            response = impulse_response(d + u, u, record.interval, water_level=water_level, corner=corner)
            return _profile(impulse - response, response, z1, method)
    else:
        peak = float(np.max(np.abs(down)))
        if not abs(down[0]) >= ONSET_SHARE * peak or peak == 0.0:
            raise ValueError(f"record: the down-going wave's first sample is {down[0]:.6g} N, below {ONSET_SHARE:g} "
                             f"of its peak {peak:.6g} N; peeling divides by it. Start the record at the onset of a "
                             f"blow with a sharp front (a mass impact), or use deconvolve=True, or identify_by_beta "
                             f"for a smooth pulse")
        onset_up = float(up[0] / down[0])

        def peel(d: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, int, Optional[np.ndarray]]:
            u = u.copy()
            u[0] = 0.0      # causality: nothing has come back at the onset (the first interface answers at s = 1)
            return _profile(d, u, z1, method)

    z, stop, kappa = peel(down, up)
    ends = stop < n
    warn_list = []
    lower = upper = None
    if noise is not None:
        noise = positive("noise", noise, "N")
        resamples = integer("resamples", resamples, 2, "noisy copies for the bands")
        rng = np.random.default_rng(seed)
        copies = np.full((resamples, stop), np.nan)
        for i in range(resamples):
            noisy = HeadRecord(record.time[:n], record.force[:n] + rng.normal(0.0, noise, n),
                               record.velocity[:n] + rng.normal(0.0, noise / z1, n))
            zi, reach, _ = peel(*split_waves(noisy, z1))
            k = min(reach, stop)
            copies[i, :k] = zi[:k]
        reached = np.mean(np.isfinite(copies), axis=0)
        cut = int(np.argmax(reached < 0.9)) if np.any(reached < 0.9) else stop
        if cut < stop:
            warn_list.append(f"with noise {noise:.3g} N, more than 10 % of the {resamples} noisy copies stop before "
                             f"element {cut + 1} ({cut * element:.4g} m): the profile is cut there")
            z, stop, ends = z[:cut], cut, False
        lower, upper = np.nanquantile(copies[:, :stop], BAND, axis=0)
        lower, upper = np.minimum(lower, z), np.maximum(upper, z)
    if deconvolve:
        near = resolution(down + up, record.interval, water_level=water_level, corner=corner)
        toe = _toe_of_smooth_profile(z, ends, length, element)
        if toe is not None:
            z, stop, ends = z[:toe], toe, True
            lower, upper = (None, None) if lower is None else (lower[:toe], upper[:toe])
        win = window if window is not None else max(9, int(round(length / element if length else stop)) // 4)
        anomalies = _anomalies_of_smooth_profile(z, lower, upper, element, win, threshold, near if ends else 0)
    else:
        anomalies = anomalies_of_profile(element * np.arange(stop + 1), z, threshold)
    depths = element * np.arange(stop + 1)
    warn_list += resolution_warnings(diameter, element, [a.depth for a in anomalies])
    if onset_up is not None and abs(onset_up) > ONSET_UP_SHARE:
        warn_list.append(f"the up-going wave at the onset is {onset_up:.3g} of the down-going one (0 for a record "
                         "that starts at the onset of the blow); it was set to 0: does the record start before or "
                         "after the onset?")
    for w in warn_list:
        warnings.warn(w, IdentificationWarning, stacklevel=caller_stacklevel())
    diagnostics = {"version": __version__, "wall_time_s": _time.perf_counter() - wall0, "peeling": method,
                   "element_length_m": element, "element_travel_time_s": 0.5 * record.interval,
                   "samples_used": n, "source": record.source, "warnings": warn_list,
                   "misfit_definition": "none: peeling reproduces the record exactly by construction"}
    if deconvolve:
        diagnostics.update(deconvolved=True, water_level=water_level, corner=corner, window=win,
                           resolution_elements=near,
                           misfit_definition="none: peeling reproduces the deconvolved impulse response exactly "
                                             "by construction; the deconvolution is regularised")
    else:
        diagnostics["onset_up_share"] = onset_up
    if kappa is not None:
        diagnostics["max_amplitude_growth"] = float(np.max(kappa[:max(stop, 1)]))
    if noise is not None:
        diagnostics.update(noise_N=noise, resamples=resamples, seed=int(seed))
    return IdentificationResult(
        depth=depths, impedance=z, lower=lower, upper=upper, anomalies=anomalies,
        toe=float(depths[-1]) if ends else None, wave_speed=c, method="peeling", diagnostics=diagnostics)


def _toe_of_smooth_profile(z: np.ndarray, ends: bool, length: Optional[float], element: float) -> Optional[int]:
    """The toe of a deconvolved (smoothed) profile as an element count (module docstring): the largest drop of
    ln Z from one element to the next within :data:`TOE_SEARCH` of ``length``, or where the recursion stopped
    (``ends``) if that comes first; ``None`` if neither applies."""
    stop = z.size
    if length is None:
        return stop if ends else None
    lo = max(1, int(np.floor((1.0 - TOE_SEARCH) * length / element)))
    hi = int(np.ceil((1.0 + TOE_SEARCH) * length / element))
    if ends and stop <= hi or stop <= lo:
        return stop if ends else None
    drops = np.diff(np.log(z[lo - 1:min(hi, stop)]))      # drops[i]: from element lo - 1 + i to lo + i
    return lo + int(np.argmin(drops))


def _anomalies_of_smooth_profile(z: np.ndarray, lower: Optional[np.ndarray], upper: Optional[np.ndarray],
                                 element: float, window: int, threshold: float, toe_zone: int) -> tuple[Anomaly, ...]:
    """The anomalies of a deconvolved (smoothed) profile (module docstring): runs off the running median of
    ``window`` elements by more than ``threshold`` (and, with bands, whose band excludes it), as :class:`Anomaly`
    (depth of the run's top, its length, its extreme change over the median as relative change, beta = 1 +
    change); runs that end within the last ``toe_zone`` elements (the toe's smoothed step) are left out."""
    out = []
    for ft in unc.find_anomalies(z, lower, upper, window=window, min_change=threshold):
        if ft.stop > z.size - toe_zone:
            continue
        beta = 1.0 + ft.change
        out.append(Anomaly(ft.start * element, (ft.stop - ft.start) * element, ft.change, beta, beta_class(beta)))
    return tuple(out)


def _profile(down: np.ndarray, up: np.ndarray, z1: float, method: str) -> tuple[np.ndarray, int, Optional[np.ndarray]]:
    """Peel (module docstring) and cut at the toe: the impedances, their number and the amplitude growth (schur
    path only)."""
    if method == "schur":
        z, _, kappa, m = peel_layers(down + up, (down - up) / z1)
    else:
        z, m = peel_waves(down, up, z1)
        kappa = None
    low = np.flatnonzero(z[:m] < TOE_SHARE * z1)
    stop = int(low[0]) if low.size else m
    return z[:stop], stop, kappa
