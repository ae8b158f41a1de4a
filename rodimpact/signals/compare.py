"""Comparing measured and simulated signals (thesis sections 5.3-5.4).

Time alignment (trigger level, cross-correlation), normalisation by the global minimum
(thesis 5.3.3), repeatability statistics over several shots (5.3.1) and error metrics.
All functions take plain arrays: ``time`` in s and signal values in any unit.

Delay convention: a *delay* ``tau`` of ``signal`` relative to ``reference`` means
``signal(t) ~ reference(t - tau)``; ``tau > 0`` when the signal arrives later.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import signal as _signal

from .._validate import finite, non_negative

__all__ = [
    "PeakComparison",
    "ShotStatistics",
    "align",
    "crossing_times",
    "delay_by_trigger",
    "delay_by_xcorr",
    "normalize_by_global_minimum",
    "normalized_rms_error",
    "peak_error",
    "shifted",
    "shot_statistics",
    "step_timing_errors",
    "trigger_time",
]

_SLOPES = ("falling", "rising", "either")


def _series(time: Any, values: Any, what: str = "values") -> tuple[np.ndarray, np.ndarray]:
    t = np.asarray(time, dtype=float)
    x = np.asarray(values, dtype=float)
    if t.ndim != 1 or x.shape != t.shape:
        raise ValueError(f"time and {what} must be 1-D arrays of equal length, got {t.shape} and {x.shape}")
    if t.size < 2:
        raise ValueError(f"{what} needs at least 2 samples")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x))):
        raise ValueError(f"time and {what} must be finite")
    if np.any(np.diff(t) <= 0):
        raise ValueError("time must be strictly increasing")
    return t, x


def _check_slope(slope: Any) -> str:
    if slope not in _SLOPES:
        raise ValueError(f"slope: must be one of {_SLOPES}, got {slope!r}")
    return slope


def crossing_times(time: Any, values: Any, level: float, slope: str = "either") -> np.ndarray:
    """All times where the signal crosses ``level``, linearly interpolated between samples.

    ``slope='falling'`` keeps downward crossings (the signal goes from above to at-or-below
    the level), ``'rising'`` upward ones, ``'either'`` both.
    """
    t, x = _series(time, values)
    level = finite("level", level)
    _check_slope(slope)
    above = x > level
    falling = np.flatnonzero(above[:-1] & ~above[1:])
    rising = np.flatnonzero(~above[:-1] & above[1:])
    if slope == "falling":
        idx = falling
    elif slope == "rising":
        idx = rising
    else:
        idx = np.sort(np.concatenate([falling, rising]))
    x0, x1 = x[idx], x[idx + 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(x1 != x0, (level - x0) / (x1 - x0), 0.0)
    return t[idx] + frac * (t[idx + 1] - t[idx])


def trigger_time(time: Any, values: Any, level: float, slope: str = "falling", after: float | None = None) -> float:
    """First crossing of ``level`` (after ``after``, if given), like an oscilloscope trigger.

    Sub-sample by linear interpolation. Compressive pulses (negative) trigger on a falling
    slope. Raises ``ValueError`` if the level is never crossed.
    """
    times = crossing_times(time, values, level, slope)
    if after is not None:
        after = finite("after", after, "s")
        times = times[times >= after]
    if times.size == 0:
        raise ValueError(f"level: the signal never crosses level {level!r} with slope {slope!r}"
                         + (f" after t={after}" if after is not None else ""))
    return float(times[0])


def delay_by_trigger(time: Any, reference: Any, signal: Any, level: float, slope: str = "falling") -> float:
    """Delay of ``signal`` relative to ``reference`` from their first crossings of ``level`` (s)."""
    return trigger_time(time, signal, level, slope) - trigger_time(time, reference, level, slope)


def delay_by_xcorr(time: Any, reference: Any, signal: Any, max_delay: float | None = None) -> float:
    """Delay of ``signal`` relative to ``reference`` by cross-correlation (s), sub-sample.

    Both signals must share the uniform time axis ``time``. The integer lag maximising the
    correlation is refined by a parabola through the peak and its two neighbours (exact for
    a locally quadratic correlation peak; for smooth pulses spanning many samples the error
    is a small fraction of a sample). Signals are not de-meaned: pass pulses on a zero
    baseline. ``max_delay`` limits the search to ``|tau| <= max_delay``.
    """
    t, ref = _series(time, reference, "reference")
    _, sig = _series(time, signal, "signal")
    steps = np.diff(t)
    dt = float(np.median(steps))
    if np.any(np.abs(steps - dt) > 1e-6 * dt):
        raise ValueError("delay_by_xcorr needs a uniform time axis; resample first")
    corr = _signal.correlate(sig, ref, mode="full", method="auto")
    lags = _signal.correlation_lags(sig.size, ref.size, mode="full")
    if max_delay is not None:
        max_delay = non_negative("max_delay", max_delay, "s")
        keep = np.abs(lags) * dt <= max_delay + 1e-12 * dt
        if not np.any(keep):
            raise ValueError(f"max_delay: {max_delay} s is shorter than one sample ({dt:.6g} s)")
        corr, lags = corr[keep], lags[keep]
    i = int(np.argmax(corr))
    if np.all(corr == corr[i]):
        raise ValueError("cross-correlation is flat (zero signals?); delay undefined")
    frac = 0.0
    if 0 < i < corr.size - 1:
        ym, y0, yp = corr[i - 1], corr[i], corr[i + 1]
        curvature = ym - 2 * y0 + yp
        if curvature < 0:
            frac = 0.5 * (ym - yp) / curvature
    return (lags[i] + frac) * dt


def shifted(time: Any, values: Any, delay: float) -> np.ndarray:
    """The signal delayed by ``delay`` seconds, on the same time axis: ``y(t) = x(t - delay)``.

    Linear interpolation; outside the recorded span the first/last value is held.
    """
    t, x = _series(time, values)
    return np.interp(t - finite("delay", delay, "s"), t, x)


def align(
    time: Any,
    reference: Any,
    signal: Any,
    method: str = "xcorr",
    level: float | None = None,
    slope: str = "falling",
    max_delay: float | None = None,
) -> tuple[np.ndarray, float]:
    """Shift ``signal`` onto ``reference``; returns ``(aligned_signal, delay)``.

    ``method='xcorr'`` uses :func:`delay_by_xcorr`, ``method='trigger'`` uses
    :func:`delay_by_trigger` with ``level``. ``aligned_signal(t) = signal(t + delay)``.
    """
    if method == "xcorr":
        delay = delay_by_xcorr(time, reference, signal, max_delay)
    elif method == "trigger":
        if level is None:
            raise ValueError("level: method='trigger' needs a trigger level")
        delay = delay_by_trigger(time, reference, signal, level, slope)
    else:
        raise ValueError(f"method: must be 'xcorr' or 'trigger', got {method!r}")
    return shifted(time, signal, -delay), delay


def normalize_by_global_minimum(values: Any) -> np.ndarray:
    """``values / |min(values)|`` (thesis 5.3.3): the deepest compression becomes -1.

    Used to compare shots at different impact velocities. Raises if the signal has no
    negative (compressive) part.
    """
    x = np.asarray(values, dtype=float)
    if x.size == 0 or not np.all(np.isfinite(x)):
        raise ValueError("values must be a non-empty finite array")
    low = float(np.min(x))
    if low >= 0:
        raise ValueError(f"values: the global minimum is {low!r}; normalisation by the global minimum needs a "
                         "negative (compressive) value")
    return x / abs(low)


@dataclass(frozen=True)
class ShotStatistics:
    """Sample statistics across repeated shots, per time sample (arrays of shape ``(n,)``)."""

    mean: np.ndarray
    std: np.ndarray
    minimum: np.ndarray
    maximum: np.ndarray
    n_shots: int

    def band(self, k: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
        """``(mean - k std, mean + k std)``."""
        k = finite("k", k)
        return self.mean - k * self.std, self.mean + k * self.std

    @property
    def max_std(self) -> float:
        """Largest standard deviation over the record."""
        return float(np.max(self.std))


def shot_statistics(shots: Sequence[Any], ddof: int = 1) -> ShotStatistics:
    """Mean, standard deviation (``ddof=1``: sample std) and envelope of aligned shots.

    ``shots`` are equally long arrays on one common time axis (align them first). ``ddof``
    is an integer with ``0 <= ddof < number of shots`` (the divisor is ``n_shots - ddof``).
    """
    if isinstance(shots, (str, bytes)) or not hasattr(shots, "__iter__"):
        raise TypeError(f"shots: must be a sequence of arrays (one per shot), got {type(shots).__name__}")
    arrays = []
    for i, s in enumerate(shots):
        try:
            arrays.append(np.asarray(s, dtype=float))
        except (TypeError, ValueError):
            raise TypeError(f"shots[{i}]: must be an array of numbers, got {type(s).__name__}") from None
    if len(arrays) < 2:
        raise ValueError(f"shots: repeatability statistics need at least 2 shots, got {len(arrays)}")
    shapes = {a.shape for a in arrays}
    if len(shapes) != 1 or arrays[0].ndim != 1:
        raise ValueError(f"shots: all shots must be 1-D arrays of the same length, got shapes {sorted(shapes)}")
    if arrays[0].size == 0:
        raise ValueError("shots: the shots hold no samples")
    if isinstance(ddof, bool) or not isinstance(ddof, (int, np.integer)):
        raise TypeError(f"ddof: must be an integer (0 <= ddof < {len(arrays)} shots), got {ddof!r}")
    if not 0 <= ddof < len(arrays):
        raise ValueError(f"ddof: must satisfy 0 <= ddof < number of shots = {len(arrays)} (1: sample standard "
                         f"deviation, 0: population), got {ddof!r}")
    stack = np.vstack(arrays)
    if not np.all(np.isfinite(stack)):
        i, j = (int(v[0]) for v in np.nonzero(~np.isfinite(stack)))
        raise ValueError(f"shots: must be finite, shot {i} sample {j} is {stack[i, j]!r}")
    return ShotStatistics(
        mean=stack.mean(axis=0),
        std=stack.std(axis=0, ddof=ddof),
        minimum=stack.min(axis=0),
        maximum=stack.max(axis=0),
        n_shots=len(arrays),
    )


@dataclass(frozen=True)
class PeakComparison:
    """Peak (extremum of largest magnitude, with sign) of a measured and a predicted signal."""

    measured: float
    predicted: float
    measured_time: float
    predicted_time: float

    @property
    def relative_error(self) -> float:
        """``(measured - predicted) / |predicted|``."""
        return (self.measured - self.predicted) / abs(self.predicted)

    @property
    def time_difference(self) -> float:
        """``measured_time - predicted_time`` (s)."""
        return self.measured_time - self.predicted_time


def _window(window: Any, name: str = "window") -> tuple[float, float]:
    """``(start, stop)`` in s, finite, ``start < stop``."""
    try:
        start, stop = window
    except (TypeError, ValueError):
        raise TypeError(f"{name}: must be a pair (start, stop) in s, got {window!r}") from None
    start, stop = finite(f"{name} start", start, "s"), finite(f"{name} stop", stop, "s")
    if not start < stop:
        raise ValueError(f"{name}: start must be before stop, got ({start!r}, {stop!r}) s")
    return start, stop


def _window_mask(t: np.ndarray, window: tuple[float, float] | None) -> np.ndarray:
    if window is None:
        return np.ones(t.shape, dtype=bool)
    start, stop = _window(window)
    mask = (t >= start) & (t <= stop)
    if not np.any(mask):
        raise ValueError(f"window: ({start}, {stop}) s contains no samples of the record "
                         f"[{t[0]!r}, {t[-1]!r}] s")
    return mask


def peak_error(time: Any, measured: Any, predicted: Any, window: tuple[float, float] | None = None) -> PeakComparison:
    """Compare the peaks (largest |value|, sign kept) of two signals on one time axis."""
    t, m = _series(time, measured, "measured")
    _, p = _series(time, predicted, "predicted")
    mask = _window_mask(t, window)
    tw, mw, pw = t[mask], m[mask], p[mask]
    im, ip = int(np.argmax(np.abs(mw))), int(np.argmax(np.abs(pw)))
    if pw[ip] == 0:
        raise ValueError("predicted signal is zero in the window; relative peak error undefined")
    return PeakComparison(float(mw[im]), float(pw[ip]), float(tw[im]), float(tw[ip]))


def normalized_rms_error(time: Any, measured: Any, predicted: Any, window: tuple[float, float] | None = None) -> float:
    """``sqrt(mean((measured - predicted)^2)) / max|predicted|`` over the window.

    Normalising by the predicted peak makes the number comparable between shots of
    different amplitude (0.01 = an RMS deviation of 1 % of the peak).
    """
    t, m = _series(time, measured, "measured")
    _, p = _series(time, predicted, "predicted")
    mask = _window_mask(t, window)
    scale = float(np.max(np.abs(p[mask])))
    if scale == 0:
        raise ValueError("predicted signal is zero in the window; normalised RMS undefined")
    return float(np.sqrt(np.mean((m[mask] - p[mask]) ** 2)) / scale)


def step_timing_errors(
    time: Any,
    measured: Any,
    predicted: Any,
    levels: Sequence[float],
    slope: str = "falling",
    after: float | None = None,
) -> np.ndarray:
    """Timing error of steps: first crossing of each level, measured minus predicted (s).

    Typical use: levels at 50 % of each step height of the predicted signal.
    """
    if isinstance(levels, (str, bytes)) or not hasattr(levels, "__iter__"):
        raise TypeError(f"levels: must be a sequence of levels, got {type(levels).__name__} {levels!r}")
    levels = list(levels)
    if not levels:
        raise ValueError("levels: give at least one level")
    return np.array(
        [
            trigger_time(time, measured, level, slope, after) - trigger_time(time, predicted, level, slope, after)
            for level in levels
        ]
    )
