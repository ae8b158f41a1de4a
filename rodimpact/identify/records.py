"""Head records and their pre-processing as pile-integrity practice does it (docs/identification.md):
:class:`HeadRecord` (force and velocity at the measured face, validated), :func:`average_blows`,
:func:`band_limited`, :func:`split_waves` (down- and up-going force waves), :func:`amplified` (exponential
amplification for display).

Conventions (shared/architecture.md): SI units; the normal force N is positive in **tension** (a blow on the
head gives N < 0); the velocity v is positive along +x, i.e. **down the rod** from the measured face (the
head is the rod's left end). For a wave travelling down (+x) the characteristic relation is ``N = -Z v``, for
one travelling up ``N = +Z v`` (thesis eq. 3.3 with the sign of the direction). Hence the split of the head's
force and velocity into force waves

    down = (N - Z v) / 2,   up = (N + Z v) / 2,   N = down + up,   Z v = up - down.

Pile practice writes force positive in compression, F = -N, and its wave down ``WD = (F + Z V)/2`` is ``-down``
and ``WU = (F - Z V)/2`` is ``-up`` (Rausche and Goble 1979; the same waves with the other force sign).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from .._validate import finite_array, positive

__all__ = ["HeadRecord", "amplified", "average_blows", "band_limited", "hammer_record", "split_waves",
           "waves_record"]

#: Relative spread of the sampling intervals accepted as uniform sampling (rounding of the time column in files).
UNIFORM_SAMPLING = 1e-6
#: The ratio |N| / (Z |v|) at the first peak of the down-going wave that is accepted as consistent units: a
#: force in kN or a velocity in mm/s is off by a factor of 1000 (high-strain practice checks that F and Z v
#: agree at impact within a few per cent, so a factor 10 is far outside what a real record shows).
UNIT_RATIO_LIMIT = 10.0


def time_series(time: Any, values: Any, name: str, min_size: int = 2) -> tuple[np.ndarray, np.ndarray]:
    """``time`` and the samples ``values`` of the quantity ``name`` as float arrays, finite, of one length (at
    least ``min_size``); an error names the argument."""
    t = finite_array("time", time, min_size=min_size)
    x = finite_array(name, values)
    if x.size != t.size:
        raise ValueError(f"{name}: must have one sample per time sample ({t.size}), got {x.size}")
    return t, x


def check_uniform(t: np.ndarray, name: str = "time") -> float:
    """The sampling interval (s) of the time axis ``t``, which must increase strictly and uniformly (to
    :data:`UNIFORM_SAMPLING`); an error names ``name``."""
    steps = np.diff(t)
    if not np.all(steps > 0):
        i = int(np.flatnonzero(steps <= 0)[0]) + 1
        raise ValueError(f"{name}: must be strictly increasing; sample {i} (t = {t[i]!r} s) is not after "
                         f"sample {i - 1}")
    spread = float((steps.max() - steps.min()) / steps.mean())
    if spread > UNIFORM_SAMPLING:
        raise ValueError(f"{name}: must be uniformly sampled (intervals from {steps.min():.6g} to "
                         f"{steps.max():.6g} s, spread {spread:.3g} > {UNIFORM_SAMPLING:g}); resample the "
                         f"record first")
    return float((t[-1] - t[0]) / (t.size - 1))


@dataclass(frozen=True)
class HeadRecord:
    """Force and velocity at the measured face, on one uniform time axis.

    ``time`` (s, strictly increasing, uniformly sampled), ``force`` (N, tension positive), ``velocity`` (m/s,
    positive down the rod, +x). ``source`` names where it came from (used in messages). Validated when made:
    arrays of one length, at least 2 samples, finite, uniform sampling; each error names the argument.
    """

    time: np.ndarray
    force: np.ndarray
    velocity: np.ndarray
    source: str = ""

    def __post_init__(self) -> None:
        where = f" ({self.source})" if self.source else ""
        arrays = {}
        for name, unit in (("time", "s"), ("force", "N"), ("velocity", "m/s")):
            arrays[name] = finite_array(f"{name}{where}", getattr(self, name), min_size=2, unit=unit)
        t = arrays["time"]
        for name in ("force", "velocity"):
            if arrays[name].size != t.size:
                raise ValueError(f"{name}{where}: must have one sample per time sample ({t.size}), got "
                                 f"{arrays[name].size}; the force and velocity records have different lengths")
        check_uniform(t, f"time{where}")
        for name, value in arrays.items():
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    @property
    def interval(self) -> float:
        """The sampling interval (s)."""
        return float((self.time[-1] - self.time[0]) / (self.time.size - 1))

    @property
    def duration(self) -> float:
        """The recorded span, last minus first sample time (s)."""
        return float(self.time[-1] - self.time[0])

    def from_onset(self, onset: int) -> "HeadRecord":
        """The record from sample ``onset`` on, time shifted so that the onset is t = 0."""
        return HeadRecord(self.time[onset:] - self.time[onset], self.force[onset:], self.velocity[onset:],
                          self.source)


def hammer_record(time: Any, velocity: Any, impedance: float, width: float, start: float = 0.0,
                  source: str = "") -> HeadRecord:
    """A low-strain record from the head velocity alone and a parametrised hammer pulse: the force is the
    half-sine ``N(t) = -A sin(pi (t - start) / width)`` on ``[start, start + width)`` (zero elsewhere; tension
    positive, so a blow is negative), whose amplitude A follows from the velocity during the pulse. Before any
    echo returns the head carries the down-going wave alone, ``v = -N / Z``, so A is the least-squares fit of
    ``Z v`` to the half-sine shape over the pulse, ``A = Z sum(v s) / sum(s^2)`` with ``s`` the unit half-sine.
    Valid while no echo arrives within the pulse (reflectors deeper than c width / 2)."""
    t, v = time_series(time, velocity, "velocity")
    z = positive("impedance", impedance, "N s/m")
    w = positive("width", width, "s")
    shape = np.where((t >= start) & (t < start + w), np.sin(np.pi * (t - start) / w), 0.0)
    if not np.any(shape > 0):
        raise ValueError(f"width, start: the pulse [{start:.6g}, {start + w:.6g}) s holds no sample of the record")
    amplitude = z * float(np.dot(v, shape) / np.dot(shape, shape))
    return HeadRecord(t, -amplitude * shape, v, source)


def waves_record(time: Any, down: Any, up: Any, impedance: float, source: str = "") -> HeadRecord:
    """A record at a measuring section from its separated force waves (N, tension positive): ``down`` travelling
    along +x, ``up`` along -x (e.g. :func:`rodimpact.identify.separate_waves` times E A): ``N = down + up``,
    ``v = (up - down) / Z`` (module docstring), so that the identifications see the section as a head."""
    t, d = time_series(time, down, "down")
    _, u = time_series(time, up, "up")
    z = positive("impedance", impedance, "N s/m")
    return HeadRecord(t, d + u, (u - d) / z, source)


def average_blows(records: Sequence[HeadRecord]) -> HeadRecord:
    """The sample-by-sample mean of several blows (low-strain practice averages a few blows to lower the noise by
    about 1/sqrt(blows)). All records must share one time axis (same length and sampling); each mismatch is an
    error naming the blow."""
    records = list(records)
    if not records or not all(isinstance(r, HeadRecord) for r in records):
        raise TypeError("records: must be a non-empty sequence of HeadRecord")
    first = records[0]
    for i, r in enumerate(records[1:], start=1):
        if r.time.size != first.time.size:
            raise ValueError(f"records[{i}]: {r.time.size} samples, records[0] has {first.time.size}; blows must "
                             f"have one length to be averaged")
        if not np.allclose(r.time, first.time, rtol=0.0, atol=1e-9 * first.interval):
            raise ValueError(f"records[{i}]: its time axis differs from that of records[0] (sampling interval "
                             f"{r.interval:.6g} s vs {first.interval:.6g} s, or another start); align the blows")
    return HeadRecord(first.time, np.mean([r.force for r in records], axis=0),
                      np.mean([r.velocity for r in records], axis=0), f"mean of {len(records)} blows")


def band_limited(record: HeadRecord, corner: float, order: int = 4) -> HeadRecord:
    """The record low-pass filtered, zero phase (Butterworth of ``order``, corner ``corner`` Hz, run forward
    and backward by ``scipy.signal.sosfiltfilt``: no delay, so reflection times stay put). The corner must lie
    below the Nyquist frequency."""
    from scipy import signal

    corner = positive("corner", corner, "Hz")
    nyquist = 0.5 / record.interval
    if corner >= nyquist:
        raise ValueError(f"corner: must be below the Nyquist frequency {nyquist:.6g} Hz of the record, got "
                         f"{corner:.6g} Hz")
    sos = signal.butter(int(order), corner, fs=1.0 / record.interval, output="sos")
    return HeadRecord(record.time, signal.sosfiltfilt(sos, record.force), signal.sosfiltfilt(sos, record.velocity),
                      record.source)


def split_waves(record: HeadRecord, impedance: float) -> tuple[np.ndarray, np.ndarray]:
    """The down- and up-going force waves at the head (N, tension positive; module docstring):
    ``down = (N - Z v)/2``, ``up = (N + Z v)/2`` with the head impedance ``impedance`` (N s/m)."""
    z = positive("impedance", impedance, "N s/m")
    return 0.5 * (record.force - z * record.velocity), 0.5 * (record.force + z * record.velocity)


def amplified(time: Any, values: Any, rate: float, start: float = 0.0) -> np.ndarray:
    """``values * exp(rate (t - start))`` for t >= start (unchanged before): the exponential amplification of
    pile-integrity reflectograms, which offsets the decay of the reflections by shaft friction and material
    damping for display (a display aid, not a correction: it also amplifies the noise). ``rate`` in 1/s (>= 0)."""
    t, x = time_series(time, values, "values", min_size=1)
    rate = float(rate)
    if not (np.isfinite(rate) and rate >= 0.0):
        raise ValueError(f"rate: must be a finite amplification rate >= 0 1/s, got {rate!r}")
    return x * np.exp(rate * np.clip(t - start, 0.0, None))


def check_units(record: HeadRecord, impedance: float, onset: int = 0) -> float:
    """The ratio |N| / (Z |v|) at the largest force within the first rise of the record (before any reflection
    can have come back the down-going wave alone gives N = -Z v, ratio 1); a ratio beyond
    :data:`UNIT_RATIO_LIMIT` either way is an error that names the likely unit mistake."""
    f = record.force[onset:]
    v = record.velocity[onset:]
    peak = int(np.argmax(np.abs(f) > 0.5 * np.abs(f).max())) if np.any(f) else 0
    ratio = float(abs(f[peak]) / max(impedance * abs(v[peak]), 1e-300))
    if not (1.0 / UNIT_RATIO_LIMIT <= ratio <= UNIT_RATIO_LIMIT):
        raise ValueError(f"force, velocity, impedance: at the first rise |N| = {abs(f[peak]):.6g} N but Z |v| = "
                         f"{impedance * abs(v[peak]):.6g} N (ratio {ratio:.3g}); a down-going wave has ratio 1. The "
                         f"units are inconsistent: force in N (not kN), velocity in m/s (not mm/s), impedance in "
                         f"N s/m (E A / c)")
    return ratio
