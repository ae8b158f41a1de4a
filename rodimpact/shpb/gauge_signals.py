"""The two gauge records of a split-Hopkinson-bar shot as strains: :class:`GaugeSignals`.

The incident-bar gauge sees the incident pulse and, a round trip later, the pulse reflected from the specimen;
the transmitted-bar gauge sees the transmitted pulse. Strains are **positive in tension** (the package's
convention, docs/architecture.md): a compression test gives a negative incident and transmitted pulse and,
for a specimen softer than the bar, a positive reflected one.
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Sequence
from typing import Any, Optional, Union

import numpy as np

from .._validate import finite, finite_array
from ..signals.gauges import GaugedBar
from ..signals.recording import Recording

__all__ = ["GaugeSignals", "onset"]

#: Strain channels: a recording channel in one of these units is taken as strain, without a gauge.
STRAIN_UNITS = ("", "-", "1", "strain", "m/m")
#: One channel name, or the names of several channels of one bar (averaged).
Channels = Union[str, Sequence[str]]


@dataclass(frozen=True)
class GaugeSignals:
    """Strain at the incident-bar gauge and at the transmitted-bar gauge on one uniform time axis.

    Parameters
    ----------
    time:
        Sample times (s), uniform and increasing, at least 3 samples.
    incident:
        Strain at the incident-bar gauge (incident and reflected pulses), tension positive, baseline removed.
    transmitted:
        Strain at the transmitted-bar gauge, tension positive, baseline removed.
    source:
        Where the signals came from (a file name), for reports.
    """

    time: np.ndarray
    incident: np.ndarray
    transmitted: np.ndarray
    source: str = ""

    def __post_init__(self) -> None:
        time = finite_array("GaugeSignals.time", self.time, min_size=3, unit="s")
        steps = np.diff(time)
        dt = float(np.median(steps))
        if dt <= 0 or np.any(np.abs(steps - dt) > 1e-6 * dt):
            raise ValueError("GaugeSignals.time: must be uniform and increasing (one sampling interval); resample "
                             "the records onto a uniform axis first")
        for name in ("incident", "transmitted"):
            values = finite_array(f"GaugeSignals.{name}", getattr(self, name))
            if values.shape != time.shape:
                raise ValueError(f"GaugeSignals.{name}: has {values.size} samples but time has {time.size}")
            values.setflags(write=False)
            object.__setattr__(self, name, values)
        time.setflags(write=False)
        object.__setattr__(self, "time", time)
        if not isinstance(self.source, str):
            raise TypeError(f"GaugeSignals.source: must be a string, got {type(self.source).__name__}")

    @property
    def dt(self) -> float:
        """Sampling interval (s)."""
        return float(self.time[1] - self.time[0])

    @classmethod
    def from_recording(cls, recording: Recording, incident_gauge: Optional[GaugedBar] = None,
                       transmitted_gauge: Optional[GaugedBar] = None, *,
                       channels: tuple[Channels, Channels] = ("incident", "transmitted"),
                       baseline: Union[str, tuple[Any, Any], None] = "auto") -> "GaugeSignals":
        """The strains of a :class:`~rodimpact.signals.Recording` (e.g. from :func:`rodimpact.io.read_lanl_raw`).

        ``channels`` names the incident-bar and the transmitted-bar channel; several channels of one bar (gauges
        on opposite sides) are averaged after the conversion to strain, which cancels bending (thesis eq. 5.1,
        :func:`rodimpact.signals.opposite_gauge_average`). A channel in volts is converted to strain by its bar's
        gauge (``incident_gauge``, ``transmitted_gauge``: :class:`~rodimpact.signals.GaugedBar`, e.g. from
        :func:`rodimpact.io.hoppybar_bar`, which applies the bridge, gauge factor, excitation, gain and
        polarity); a channel already in strain (unit ``""``) needs none. ``baseline``: the zero offset
        subtracted from each channel, ``"auto"`` (the mean before the channel's first pulse: the samples before
        the first excursion beyond 10 % of the channel's peak deviation from its median, up to where that
        excursion last crossed the median), a time span ``(start, stop)`` in s to average over, or ``None`` (no
        offset removed).
        """
        if not isinstance(recording, Recording):
            raise TypeError(f"recording: must be a rodimpact.signals.Recording, got {type(recording).__name__}")
        if isinstance(channels, str) or len(channels) != 2:
            raise ValueError(f"channels: give the incident-bar and the transmitted-bar channel(s), got {channels!r}")
        strains = []
        for role, names, gauge in (("incident_gauge", channels[0], incident_gauge),
                                   ("transmitted_gauge", channels[1], transmitted_gauge)):
            if gauge is not None and not isinstance(gauge, GaugedBar):
                raise TypeError(f"{role}: must be a rodimpact.signals.GaugedBar, got {type(gauge).__name__}")
            names = [names] if isinstance(names, str) else list(names)
            if not names:
                raise ValueError(f"channels: no channel given for the {role.split('_')[0]} bar")
            strains.append(np.mean([_strain(recording, name, gauge, role, baseline) for name in names], axis=0))
        return cls(recording.time, strains[0], strains[1], recording.source or "")


def _strain(recording: Recording, channel: str, gauge: Optional[GaugedBar], role: str,
            baseline: Union[str, tuple[Any, Any], None]) -> np.ndarray:
    """One channel of ``recording`` as strain, offset removed (:meth:`GaugeSignals.from_recording`)."""
    if channel not in recording:
        raise ValueError(f"channels: no channel {channel!r} in the recording; channels: {recording.channel_names}")
    values = recording[channel]
    unit = recording.units.get(channel, "")
    if gauge is None and unit not in STRAIN_UNITS:
        raise ValueError(f"{role}: channel {channel!r} is in {unit!r}; give the GaugedBar that converts it to "
                         f"strain (e.g. rodimpact.io.hoppybar_bar)")
    values = values - _offset(recording.time, values, baseline, channel)
    return values if gauge is None else gauge.strain(values)


def onset(x: np.ndarray, level: float, foot: float) -> tuple[int, int]:
    """``(cross, first)``: the first sample whose magnitude reaches ``level`` and the foot of that excursion,
    the last sample at or before it whose value, in the excursion's direction, is at most ``foot`` (the first
    sample if none is). ``ValueError`` if no sample reaches ``level``."""
    above = np.flatnonzero(np.abs(x) >= level)
    if above.size == 0:
        raise ValueError(f"no sample reaches {level!r}")
    cross = int(above[0])
    quiet = np.flatnonzero(np.sign(x[cross]) * x[:cross + 1] <= foot)
    return cross, int(quiet[-1]) if quiet.size else 0


def _offset(time: np.ndarray, values: np.ndarray, baseline: Union[str, tuple[Any, Any], None], channel: str) -> float:
    """The zero offset of one channel (:meth:`GaugeSignals.from_recording`)."""
    if baseline is None:
        return 0.0
    if isinstance(baseline, str):
        if baseline != "auto":
            raise ValueError(f"baseline: must be 'auto', a time span (start, stop) in s or None, got {baseline!r}")
        deviation = values - np.median(values)
        peak = float(np.max(np.abs(deviation)))
        first = onset(deviation, 0.1 * peak, 0.0)[1] if peak > 0 else values.size
        if first < 10:
            raise ValueError(f"baseline: channel {channel!r} has {first} sample(s) before its first pulse, too few "
                             f"for the automatic baseline; give baseline=(start, stop) in s, or None")
        return float(np.mean(values[:first]))
    if not isinstance(baseline, (tuple, list)) or len(baseline) != 2:
        raise TypeError(f"baseline: must be 'auto', a time span (start, stop) in s or None, got {baseline!r}")
    start, stop = (finite("baseline", b, "s") for b in baseline)
    inside = (time >= start) & (time <= stop)
    if not inside.any():
        raise ValueError(f"baseline: no sample of channel {channel!r} lies in [{start!r}, {stop!r}] s")
    return float(np.mean(values[inside]))
