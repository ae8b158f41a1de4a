"""Reflectors: the integrity factor beta (Rausche and Goble 1979) and its classes, reflectors read from a
reflectogram (:func:`identify_by_beta`) and from an identified profile (:func:`anomalies_of_profile`).

A step of impedance from Z1 above to Z2 below reflects a down-going force wave with the coefficient

    r = (Z2 - Z1) / (Z2 + Z1),   so   beta = Z2 / Z1 = (1 + r) / (1 - r)

(thesis eq. 4.9; Rausche and Goble write beta = (1 - alpha) / (1 + alpha) with alpha = -r in the compression-
positive waves of practice). From a head record r is read as the extreme of the up-going wave over the reflector's
arrival divided by the peak of the down-going pulse; a reflector below others is reached through them, each
passage scaling a primary reflection by the two-way transmission 1 - r_k^2, which is divided out (primaries
only: multiples between reflectors are neglected, docs/identification.md measures what that costs).

Classes (:data:`BETA_CLASSES`): beta = 1 uniform, 0.8 <= beta < 1 slight damage, 0.6 <= beta < 0.8 damage,
beta < 0.6 broken, as quoted in pile-testing practice after Rausche and Goble (1979); the search of this work
found the method's papers (Likins and Rausche 2014, "Pile damage prevention and assessment using dynamic
monitoring and the Beta method", ASCE; Verbeek and Goble's re-evaluation) but could not read the table itself:
the bounds are unverified here (docs/identification.md). beta > 1 is an increase of impedance (a bulge, a
stiffer section), classed ``"increase"``.
"""

from __future__ import annotations

import time as _time
import warnings
from typing import Optional

import numpy as np

from .._validate import caller_stacklevel, positive
from .._version import __version__
from .records import HeadRecord, check_units, split_waves
from .result import Anomaly, IdentificationResult
from .validity import IdentificationWarning, one_dimensional_warnings

__all__ = ["BETA_CLASSES", "beta_class", "anomalies_of_profile", "first_peak", "identify_by_beta", "reflectogram"]

#: (lower bound of beta, class) from the top; beta > 1 is an "increase" (module docstring for the source).
BETA_CLASSES = ((1.0, "uniform"), (0.8, "slight damage"), (0.6, "damage"), (0.0, "broken"))


def beta_class(beta: float) -> str:
    """The class of an integrity factor beta = Z2 / Z1 (:data:`BETA_CLASSES`)."""
    if beta > 1.0:
        return "increase"
    return next(name for low, name in BETA_CLASSES if beta >= low)


def anomalies_of_profile(depth: np.ndarray, impedance: np.ndarray, threshold: float) -> tuple[Anomaly, ...]:
    """The reflectors of a piecewise-constant profile: every interface where the impedance changes by more than
    ``threshold`` (a share) from the element above starts an anomaly, which lasts while the impedance stays more
    than ``threshold`` away from that level. ``beta`` is Z2 / Z1 at the interface (the first element of the run
    over the one above), ``relative_change`` beta - 1, ``length`` the run's length (m)."""
    z = np.asarray(impedance, dtype=float)
    out = []
    i = 1
    while i < z.size:
        above = z[i - 1]
        if abs(z[i] / above - 1.0) > threshold:
            j = i
            while j < z.size and abs(z[j] / above - 1.0) > threshold:
                j += 1
            beta = float(z[i] / above)
            out.append(Anomaly(float(depth[i]), float(depth[j] - depth[i]), beta - 1.0, beta, beta_class(beta)))
            i = j + 1
        else:
            i += 1
    return tuple(out)


def reflectogram(record: HeadRecord, impedance: float) -> tuple[np.ndarray, np.ndarray, int]:
    """The up-going wave divided by the peak of the down-going one, ``rho(t) = up(t) / down(t_peak)``: at the
    arrival of a single reflector's echo it equals that reflector's r (module docstring). Returns the time
    after the down-going peak (s; a reflector at depth x shows at 2 x / c), rho and the peak's sample index."""
    down, up = split_waves(record, impedance)
    peak = first_peak(down)
    return record.time - record.time[peak], up / down[peak], peak


def identify_by_beta(record: HeadRecord, impedance: float, wave_speed: float, *, threshold: float = 0.05,
                     length: Optional[float] = None, diameter: Optional[float] = None) -> IdentificationResult:
    """Reflectors, their integrity factors and a stepwise profile from the reflectogram (module docstring).

    ``record``: head force (N, tension positive) and velocity (m/s, down), measured or with the hammer force;
    ``impedance``: the head impedance (N s/m); ``wave_speed`` (m/s) turns echo times into depths, x = c t / 2.
    Every extreme of rho(t) beyond ``threshold`` (a share of the down-going peak; the package's choice, not from
    a standard) that stands apart from the previous one by at least the pulse width is a reflector. ``length``
    (m): the known length; the toe is then the reflector nearest to it, and echoes from below it are multiples
    and dropped (without it no reflector is taken for the toe: a deep break and a toe look alike).
    ``diameter`` (m): checks the 1D limits (:func:`rodimpact.identify.validity.one_dimensional_warnings`).
    """
    wall0 = _time.perf_counter()
    if not isinstance(record, HeadRecord):
        raise TypeError(f"record: must be a HeadRecord, got {type(record).__name__}")
    z1 = positive("impedance", impedance, "N s/m")
    c = positive("wave_speed", wave_speed, "m/s")
    threshold = positive("threshold", threshold)
    check_units(record, z1)
    t, rho, peak = reflectogram(record, z1)
    down, _ = split_waves(record, z1)
    width = _pulse_width(down, peak) * record.interval
    if length is not None:
        length = positive("length", length, "m")
        if 2.0 * length / c > t[-1]:
            raise ValueError(f"length: the toe echo of a {length:.6g} m rod arrives 2 L / c = {2 * length / c:.6g} s "
                             f"after the pulse peak, the record ends {t[-1]:.6g} s after it; record longer")
    picks = _extremes(rho, peak, threshold, max(int(round(width / record.interval)), 1))
    profile_z = [z1]
    boundaries = [0.0]
    passage = 1.0
    found = []
    for k in picks:
        r = float(rho[k]) / passage
        r = min(max(r, -1.0 + 1e-12), 1.0 - 1e-12)     # a free (fixed) end: r = -1 (+1); noise may pass it
        beta = (1.0 + r) / (1.0 - r)
        found.append((0.5 * c * t[k], r, beta))
        passage *= 1.0 - r * r
    reach = 0.5 * c * t[-1]
    toe = None
    if found and length is not None:
        toe = min(found, key=lambda f: abs(f[0] - length))[0]
        found = [f for f in found if f[0] <= toe]       # deeper echoes: multiples (the rod ends at the toe)
    anomalies = []
    for i, (x, r, beta) in enumerate(found):
        below = found[i + 1][0] if i + 1 < len(found) else (length if length is not None else reach)
        if x == toe:
            continue
        boundaries.append(x)
        profile_z.append(profile_z[-1] * beta)
        anomalies.append(Anomaly(x, max(float(below) - x, 0.0), beta - 1.0, beta, beta_class(beta)))
    end = toe if toe is not None else reach
    boundaries.append(max(end, boundaries[-1] + 0.5 * c * record.interval))
    fitted = _primaries(down / down[peak], [k - peak for k in picks], [float(rho[k]) for k in picks])
    after = slice(peak, None)
    misfit = float(np.sqrt(np.mean((rho[after] - fitted[after]) ** 2)) / max(np.max(np.abs(rho[after])), 1e-300))
    warn_list = one_dimensional_warnings(diameter, c * width, [a.depth for a in anomalies], length)
    for w in warn_list:
        warnings.warn(w, IdentificationWarning, stacklevel=caller_stacklevel())
    diagnostics = {"version": __version__, "wall_time_s": _time.perf_counter() - wall0, "threshold": threshold,
                   "pulse_width_s": width, "reflection_coefficients": [f[1] for f in found],
                   "depth_resolution_m": 0.25 * c * record.interval, "source": record.source,
                   "warnings": warn_list,
                   "misfit_definition": "rms(rho - primaries) / max|rho| after the down-going peak: rho the "
                                        "reflectogram, primaries the echoes of the reflectors found (each r_k "
                                        "times its passage times the down-going pulse, delayed by 2 x_k / c)"}
    return IdentificationResult(depth=np.array(boundaries), impedance=np.array(profile_z), anomalies=tuple(anomalies),
                                toe=toe, wave_speed=c, method="beta", diagnostics=diagnostics,
                                matched={"reflectogram": (t, rho, fitted)}, misfit=misfit)


def _primaries(pulse: np.ndarray, lags: list[int], heights: list[float]) -> np.ndarray:
    """The reflectogram the reflectors alone would give: each echo is the down-going ``pulse`` (over its peak)
    delayed by its lag (samples) and scaled by its height (r_k times its passage), the primaries of a lossless rod
    whose echoes are not sent down again."""
    out = np.zeros(pulse.size)
    for lag, h in zip(lags, heights):
        out[lag:] += h * pulse[:pulse.size - lag]
    return out


def first_peak(down: np.ndarray) -> int:
    """The sample of the first pulse's peak: from the first sample beyond half the largest |down|, uphill to the
    local maximum (the head re-reflects echoes as later down-going pulses, which may be as large)."""
    a = np.abs(down)
    i = int(np.argmax(a >= 0.5 * a.max()))
    while i + 1 < a.size and a[i + 1] > a[i]:
        i += 1
    return i


def _pulse_width(down: np.ndarray, peak: int) -> int:
    """Samples of the down-going pulse at or above half its peak, around the peak (the full width at half
    maximum)."""
    level = 0.5 * abs(down[peak])
    lo = peak
    while lo > 0 and abs(down[lo - 1]) >= level:
        lo -= 1
    hi = peak
    while hi + 1 < down.size and abs(down[hi + 1]) >= level:
        hi += 1
    return hi - lo + 1


def _extremes(rho: np.ndarray, peak: int, threshold: float, spacing: int) -> list[int]:
    """Sample indices of the reflectogram's extremes beyond ``threshold`` after the down-going peak, at least
    ``spacing`` samples apart (the largest within each group of samples beyond the threshold)."""
    out: list[int] = []
    above = np.abs(rho) > threshold
    i = peak + 1
    n = rho.size
    while i < n:
        if above[i]:
            j = i
            while j < n and above[j] and np.sign(rho[j]) == np.sign(rho[i]):
                j += 1
            k = i + int(np.argmax(np.abs(rho[i:j])))
            if not out or k - out[-1] >= spacing:
                out.append(k)
            i = j
        else:
            i += 1
    return out
