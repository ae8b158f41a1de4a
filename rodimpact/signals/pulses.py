"""Features of a (nearly) rectangular stress pulse and the 1D striker-on-bar prediction.

For a striker of length ``L`` hitting a bar of equal impedance ``Z = rho c A`` at velocity
``v``, 1D wave theory (thesis Fig. 5.14, eq. 5.4) gives a rectangular incident force pulse

    N(t) = -Z v / 2        for   0 <= t - t_arrival < 2 L / c,

i.e. a compressive (negative) plateau of duration ``t* = 2 L / c``. Conversely a measured
plateau strain ``eps_p`` (negative) gives the striker velocity ``v = -2 c eps_p``
(equivalently ``v = 2 |sigma| / (rho c)``). Since the striker stops, its momentum passes
entirely into the bar, which gives a second estimate ``v = -(integral N dt) / m_striker``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import finite, positive
from .compare import _series, _window, crossing_times

__all__ = [
    "PulseFeatures",
    "VelocityEstimate",
    "equal_impedance_pulse",
    "pulse_features",
    "rectangular_pulse",
    "striker_velocity_estimate",
    "striker_velocity_from_impulse",
    "striker_velocity_from_strain",
]


def _positive(value: Any, what: str, unit: str = "") -> float:
    return positive(what, value, unit)


def _times(time: Any) -> np.ndarray:
    """``time`` as a float array of any shape, every entry finite."""
    try:
        t = np.asarray(time, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"time: must be a number or an array of numbers in s, got {type(time).__name__}") from None
    bad = ~np.isfinite(t)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"time: must be finite, entry {i} is {t.ravel()[i]!r}")
    return t


def rectangular_pulse(time: Any, start: float, duration: float, amplitude: float) -> np.ndarray:
    """``amplitude`` on ``start <= t < start + duration``, zero elsewhere."""
    t = _times(time)
    start = finite("start", start, "s")
    duration = _positive(duration, "duration", "s")
    amplitude = finite("amplitude", amplitude)
    return np.where((t >= start) & (t < start + duration), amplitude, 0.0)


def equal_impedance_pulse(
    time: Any,
    striker_length: float,
    wave_speed: float,
    impedance: float,
    velocity: float,
    arrival_time: float = 0.0,
) -> np.ndarray:
    """1D incident force (N, compression negative) of a striker on a bar of equal impedance.

    Amplitude ``-impedance * velocity / 2``, duration ``2 striker_length / wave_speed``,
    starting at ``arrival_time`` (module docstring).
    """
    length = _positive(striker_length, "striker_length", "m")
    c = _positive(wave_speed, "wave_speed", "m/s")
    z = _positive(impedance, "impedance", "N s/m")
    v = finite("velocity", velocity, "m/s")
    return rectangular_pulse(time, finite("arrival_time", arrival_time, "s"), 2.0 * length / c, -0.5 * z * v)


def striker_velocity_from_strain(plateau_strain: float, wave_speed: float) -> float:
    """Striker velocity ``v = -2 c eps_p`` (m/s) from the incident plateau strain (negative).

    Valid for a striker of the same impedance (material and section) as the bar.
    """
    return -2.0 * _positive(wave_speed, "wave_speed", "m/s") * finite("plateau_strain", plateau_strain)


@dataclass(frozen=True)
class PulseFeatures:
    """Timing and level of the main pulse of a signal (times in s, levels in signal units).

    ``start``/``end``: crossings of ``fraction`` x plateau on the leading/trailing edge;
    ``duration = end - start``. ``rise_time``: from ``low`` to ``high`` x plateau on the
    leading edge; ``fall_time``: from ``high`` to ``low`` x plateau on the trailing edge.
    ``plateau``/``plateau_std``: mean and standard deviation over ``plateau_window``.
    """

    start: float
    end: float
    duration: float
    plateau: float
    plateau_std: float
    rise_time: float
    fall_time: float
    plateau_window: tuple[float, float]


def _last_before(times: np.ndarray, limit: float) -> float:
    sel = times[times <= limit]
    if sel.size == 0:
        raise ValueError("pulse edge not found (level never crossed before the peak)")
    return float(sel[-1])


def _first_after(times: np.ndarray, limit: float) -> float:
    sel = times[times >= limit]
    if sel.size == 0:
        raise ValueError("pulse edge not found (level never crossed after the peak; is the pulse cut off?)")
    return float(sel[0])


def pulse_features(
    time: Any,
    values: Any,
    polarity: int = -1,
    plateau_window: tuple[float, float] | None = None,
    fraction: float = 0.5,
    low: float = 0.1,
    high: float = 0.9,
    plateau_trim: float = 0.2,
) -> PulseFeatures:
    """Duration, plateau level, rise and fall time of the largest pulse in a signal.

    ``polarity=-1`` for compressive (negative) pulses. The signal is assumed to start from
    a zero baseline (subtract the pre-trigger mean first). Without ``plateau_window`` the
    plateau is the mean over the central part of the pulse: the pulse is first delimited
    by the crossings of ``fraction`` x peak around the peak, and ``plateau_trim`` of its
    length is dropped at each end. Edges are then located with respect to that plateau
    level, with linear interpolation between samples.
    """
    if isinstance(polarity, bool) or polarity not in (1, -1):
        raise ValueError(f"polarity: must be +1 or -1, got {polarity!r}")
    polarity = int(polarity)
    low, fraction, high = finite("low", low), finite("fraction", fraction), finite("high", high)
    if not 0 < low < fraction < high < 1:
        raise ValueError(f"low, fraction, high: need 0 < low < fraction < high < 1, got {low}, {fraction}, {high}")
    plateau_trim = _plateau_trim(plateau_trim)
    t, y = _series(time, values)
    if t.size < 3:
        raise ValueError(f"time and values: need at least 3 samples, got {t.size}")
    y = polarity * y
    i_peak = int(np.argmax(y))
    t_peak = float(t[i_peak])
    peak = float(y[i_peak])
    if peak <= 0:
        raise ValueError(f"values: the signal has no pulse of the requested polarity ({polarity:+d})")

    def edges(level: float) -> tuple[float, float]:
        return (
            _last_before(crossing_times(t, y, level, "rising"), t_peak),
            _first_after(crossing_times(t, y, level, "falling"), t_peak),
        )

    if plateau_window is None:
        s0, e0 = edges(fraction * peak)
        trim = plateau_trim * (e0 - s0)
        plateau_window = (s0 + trim, e0 - trim)
    w0, w1 = _window(plateau_window, "plateau_window")
    mask = (t >= w0) & (t <= w1)
    if np.count_nonzero(mask) < 2:
        raise ValueError(f"plateau_window: ({w0}, {w1}) s holds fewer than 2 samples")
    level = float(np.mean(y[mask]))
    spread = float(np.std(y[mask], ddof=1))
    if level <= 0:
        raise ValueError(f"plateau_window: the plateau level has the wrong sign for the requested polarity "
                         f"({polarity:+d})")
    start, end = edges(fraction * level)
    rise_lo = _last_before(crossing_times(t, y, low * level, "rising"), start)
    rise_hi = _first_after(crossing_times(t, y, high * level, "rising"), start)
    fall_hi = _last_before(crossing_times(t, y, high * level, "falling"), end)
    fall_lo = _first_after(crossing_times(t, y, low * level, "falling"), end)
    return PulseFeatures(
        start=start,
        end=end,
        duration=end - start,
        plateau=polarity * level,
        plateau_std=spread,
        rise_time=rise_hi - rise_lo,
        fall_time=fall_lo - fall_hi,
        plateau_window=(float(w0), float(w1)),
    )


@dataclass(frozen=True)
class VelocityEstimate:
    """A striker velocity (m/s) with its standard uncertainty (k = 1) and the relative
    uncertainty components it was combined from (root sum of squares)."""

    velocity: float
    uncertainty: float
    components: dict[str, float]

    @property
    def relative_uncertainty(self) -> float:
        return self.uncertainty / abs(self.velocity)


def _plateau_trim(value: Any, name: str = "plateau_trim") -> float:
    trim = finite(name, value)
    if not 0 <= trim < 0.5:
        raise ValueError(f"{name}: the fraction of the pulse dropped at each end must lie in [0, 0.5), got {value!r}")
    return trim


def _relative_uncertainties(values: Any) -> dict[str, float]:
    if values is None:
        return {}
    if not isinstance(values, Mapping):
        raise TypeError(f"relative_uncertainties: must be a mapping name -> relative standard uncertainty, e.g. "
                        f"{{'gauge factor': 0.005}}, got {type(values).__name__}")
    out = {}
    for name, value in values.items():
        x = finite(f"relative_uncertainties[{name!r}]", value)
        if x < 0:
            raise ValueError(f"relative_uncertainties[{name!r}]: must be >= 0, got {value!r}")
        out[str(name)] = x
    return out


def _combine(velocity: float, components: dict[str, float]) -> VelocityEstimate:
    for name, value in components.items():
        if not np.isfinite(value) or value < 0:
            raise ValueError(f"relative uncertainty {name!r} must be finite and >= 0, got {value!r}")
    rel = float(np.sqrt(sum(v * v for v in components.values())))
    return VelocityEstimate(float(velocity), abs(float(velocity)) * rel, dict(components))


def striker_velocity_estimate(
    time: Any,
    strain: Any,
    wave_speed: float,
    relative_uncertainties: dict[str, float] | None = None,
    trims: tuple[float, float, float] = (0.1, 0.2, 0.3),
) -> VelocityEstimate:
    """Striker velocity ``v = -2 c eps_p`` from the plateau of a compressive incident strain pulse.

    The plateau is the mean over the central part of the pulse (:func:`pulse_features`,
    middle entry of ``trims``). Its definition is uncertain for a ringing or sloping plateau;
    the component ``"plateau definition"`` is the largest relative change of the plateau
    when the trimmed fraction is changed to the other entries of ``trims``. Further relative
    standard uncertainties (gauge factor, wave speed, ...) are passed in
    ``relative_uncertainties`` and combined in quadrature. Every entry of ``trims`` is a
    ``plateau_trim`` of :func:`pulse_features`, a fraction in [0, 0.5); a single entry gives no
    plateau-definition component (0).
    """
    if isinstance(trims, (str, bytes)) or not isinstance(trims, (Sequence, np.ndarray)):
        raise TypeError(f"trims: must be a sequence of plateau trims (fractions in [0, 0.5)), e.g. (0.1, 0.2, 0.3), "
                        f"got {type(trims).__name__} {trims!r}")
    trims = [_plateau_trim(trim, f"trims[{i}]") for i, trim in enumerate(trims)]
    if not trims:
        raise ValueError("trims: give at least one plateau trim (a fraction in [0, 0.5)), e.g. (0.1, 0.2, 0.3)")
    wave_speed = _positive(wave_speed, "wave_speed", "m/s")
    extra = _relative_uncertainties(relative_uncertainties)
    levels = [pulse_features(time, strain, polarity=-1, plateau_trim=trim).plateau for trim in trims]
    central = levels[len(levels) // 2]
    components = {"plateau definition": max(abs(level / central - 1.0) for level in levels)}
    components.update(extra)
    return _combine(striker_velocity_from_strain(central, wave_speed), components)


def striker_velocity_from_impulse(
    time: Any,
    force: Any,
    striker_mass: float,
    window: tuple[float, float],
    relative_uncertainties: dict[str, float] | None = None,
) -> VelocityEstimate:
    """Striker velocity from momentum, ``v = -(integral of N over the pulse) / m_striker``.

    Valid when the striker comes to rest (equal impedance) and the whole pulse lies in
    ``window``; the force must be baseline-corrected. The integral is the trapezoidal rule.
    Relative uncertainties (e.g. of the striker mass) are combined in quadrature.
    """
    t, n = _series(time, force, "force")
    start, stop = _window(window)
    mass = _positive(striker_mass, "striker_mass", "kg")
    extra = _relative_uncertainties(relative_uncertainties)
    mask = (t >= start) & (t <= stop)
    if np.count_nonzero(mask) < 2:
        raise ValueError(f"window: ({start}, {stop}) s holds fewer than 2 samples of the record "
                         f"[{t[0]!r}, {t[-1]!r}] s")
    impulse = float(np.trapezoid(n[mask], t[mask]))
    if impulse == 0.0:
        raise ValueError(f"force: its integral over window ({start}, {stop}) s is zero; no pulse in the window")
    return _combine(-impulse / mass, extra)
