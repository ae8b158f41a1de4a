"""Pulse windows of a split-Hopkinson-bar shot: where the incident, reflected and transmitted pulses lie in the
two gauge records, found automatically and overridable one by one.

Times are those of the gauge records (s). The incident pulse is found in the incident-bar record; the reflected
and transmitted windows follow from the bars' wave travel: the reflected pulse passes the incident gauge
``2 a_I / c_I`` after the incident one (to the specimen face and back), the transmitted pulse passes the
transmitted gauge ``a_I / c_I + a_T / c_T`` after it (a = gauge distance to the specimen face, c = bar wave
speed). The specimen's own transit time is neglected, as in the classical reduction (Gray 2000; Chen and Song
2011): it is one of the things the equilibrium check judges.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Union

import numpy as np

from .._validate import finite, positive
from .gauge_signals import GaugeSignals, onset
from .parts import Bar

__all__ = ["PulseWindows", "Window", "find_windows"]

#: The pulses of a shot, in the order of :class:`PulseWindows`' fields.
PULSES = ("incident", "reflected", "transmitted")


@dataclass(frozen=True)
class Window:
    """A pulse window in a gauge record: ``start`` (s, gauge time) and ``duration`` (s, > 0)."""

    start: float
    duration: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "start", finite("Window.start", self.start, "s"))
        object.__setattr__(self, "duration", positive("Window.duration", self.duration, "s"))

    @property
    def end(self) -> float:
        """``start + duration`` (s)."""
        return self.start + self.duration


@dataclass(frozen=True)
class PulseWindows:
    """The windows of the incident and reflected pulses (incident-bar record) and of the transmitted pulse
    (transmitted-bar record). ``given`` names the windows set by hand (the others were found)."""

    incident: Window
    reflected: Window
    transmitted: Window
    given: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        for name in PULSES:
            if not isinstance(getattr(self, name), Window):
                raise TypeError(f"PulseWindows.{name}: must be a Window, got {type(getattr(self, name)).__name__}")
        unknown = [g for g in self.given if g not in PULSES]
        if unknown:
            raise ValueError(f"PulseWindows.given: unknown pulse {unknown[0]!r}; pulses: {', '.join(PULSES)}")
        object.__setattr__(self, "given", tuple(self.given))


Override = Union[Window, float, str, None]


def find_windows(signals: GaugeSignals, incident_bar: Bar, transmitted_bar: Bar, *, threshold: float = 0.1,
                 foot: float = 0.0, incident: Override = None, reflected: Override = None,
                 transmitted: Override = None, duration: Any = None) -> PulseWindows:
    """The three pulse windows of a shot, each overridable.

    **Incident arrival.** The first sample of the incident-bar record whose magnitude reaches ``threshold``
    times the record's peak magnitude; the window starts at the pulse's foot, the last sample before it whose
    value, in the pulse's direction, is at most ``foot`` times the peak: by default (``foot=0``) where the
    record was last at zero or beyond it on the other side, i.e. where the pulse leaves the noise of a record
    whose baseline is removed (raise ``foot`` for a record with an offset). **Length from the data:** the
    pulse ends where it falls back below ``threshold`` plus the time its leading edge took from the foot to
    the threshold (edges taken as alike). **Reflected and transmitted** windows start ``2 a_I / c_I`` and
    ``a_I / c_I + a_T / c_T`` after the incident one (module docstring) and last as long.

    **Overrides:** ``incident``, ``reflected``, ``transmitted`` each take a :class:`Window` (start and
    duration, s, gauge time) or a start time alone (s, or a string such as ``"153 us"``; the duration found is
    kept). A given incident window moves the windows derived from it. ``duration`` (s) replaces the duration
    found, for every window not given as a :class:`Window`.

    Raises ``ValueError`` if the incident pulse cannot be found (a record without a pulse, or one that never
    falls back), or if the incident pulse is longer than the round trip ``2 a_I / c_I``: then the incident
    and reflected pulses overlap at the gauge and cannot be told apart.
    """
    _check_types(signals, incident_bar, transmitted_bar)
    threshold = positive("threshold", threshold)
    foot = finite("foot", foot)
    if not threshold < 1.0:
        raise ValueError(f"threshold: must be < 1 (a fraction of the peak), got {threshold!r}")
    if not 0.0 <= foot < threshold:
        raise ValueError(f"foot: must lie in [0, threshold = {threshold!r}), got {foot!r}")
    given = tuple(name for name, value in zip(PULSES, (incident, reflected, transmitted)) if value is not None)
    found = _incident_window(signals, threshold, foot)
    if duration is not None:
        found = Window(found.start, positive("duration", duration, "s"))
    first = _override("incident", incident, found)
    round_trip = 2.0 * incident_bar.travel_time
    if first.duration > round_trip and "reflected" not in given:
        raise ValueError(f"incident_bar.gauge_distance: the incident pulse lasts {first.duration * 1e6:.4g} us, "
                         f"longer than the round trip from the gauge to the specimen and back "
                         f"({round_trip * 1e6:.4g} us): incident and reflected pulses overlap at the gauge; give "
                         f"the windows by hand (incident=Window(...), reflected=Window(...)) if they do not")
    across = incident_bar.travel_time + transmitted_bar.travel_time
    return PulseWindows(
        incident=first,
        reflected=_override("reflected", reflected, Window(first.start + round_trip, first.duration)),
        transmitted=_override("transmitted", transmitted, Window(first.start + across, first.duration)),
        given=given)


def _check_types(signals: Any, incident_bar: Any, transmitted_bar: Any) -> None:
    if not isinstance(signals, GaugeSignals):
        raise TypeError(f"signals: must be rodimpact.shpb.GaugeSignals, got {type(signals).__name__}")
    for name, bar in (("incident_bar", incident_bar), ("transmitted_bar", transmitted_bar)):
        if not isinstance(bar, Bar):
            raise TypeError(f"{name}: must be a rodimpact.shpb.Bar, got {type(bar).__name__}")


def _incident_window(signals: GaugeSignals, threshold: float, foot: float) -> Window:
    """The incident pulse in the incident-bar record (:func:`find_windows`)."""
    x, t = signals.incident, signals.time
    peak = float(np.max(np.abs(x)))
    if peak == 0.0:
        raise ValueError("signals.incident: the incident-bar record is zero everywhere: no pulse to find")
    cross, first = onset(x, threshold * peak, foot * peak)
    polarity = np.sign(x[cross])
    below = np.flatnonzero(polarity * x[cross:] < threshold * peak)
    if below.size == 0:
        raise ValueError(f"signals.incident: the incident pulse (from {t[first] * 1e6:.4g} us) does not fall back "
                         f"below {threshold:g} of its peak before the record ends; record longer or give "
                         f"incident=Window(start, duration)")
    fall = cross + int(below[0])
    rise = t[cross] - t[first]
    return Window(float(t[first]), float(t[fall] - t[first] + rise))


def _override(name: str, value: Override, found: Window) -> Window:
    """``found``, or the window the user gave for pulse ``name`` (a Window, or a start time keeping the found
    duration)."""
    if value is None:
        return found
    if isinstance(value, Window):
        return value
    return Window(finite(name, value, "s"), found.duration)
