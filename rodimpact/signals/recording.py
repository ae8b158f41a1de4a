"""The :class:`Recording` container: sampled channels on one time axis.

A recording is what a data-acquisition system hands over: a time axis (s), one or more
channels of samples on that axis, the unit of each channel and whatever metadata the file
carried. Readers for concrete file formats live in :mod:`rodimpact.io.recordings`; this
module does no file I/O.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._validate import finite

__all__ = ["Recording"]


def _frozen_array(values: Any, what: str) -> np.ndarray:
    try:
        kind = np.asarray(values).dtype.kind
        array = np.array(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{what} must be an array of numbers") from exc
    if kind not in "iuf":               # strings ("1e-6") and bools are refused, not converted
        raise TypeError(f"{what} must be an array of real numbers, got {np.asarray(values).dtype} values")
    if array.ndim != 1:
        raise ValueError(f"{what} must be one-dimensional, got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        raise ValueError(f"{what} contains a non-finite value at sample {bad[0]}")
    array.setflags(write=False)
    return array


@dataclass(frozen=True, repr=False)
class Recording:
    """Channels sampled on one common, strictly increasing time axis.

    Parameters
    ----------
    time:
        Sample times in s, shape ``(n,)``, strictly increasing.
    channels:
        Channel name -> samples, each of shape ``(n,)``.
    units:
        Channel name -> unit string (``"V"``, ``"N"``, ``""`` for strain...). Channels
        without an entry get ``""``.
    metadata:
        Free-form information from the file (calibration values, header fields...).
    source:
        Where the recording came from (a path), used in messages.

    The arrays are stored read-only; derive new recordings with :meth:`window`,
    :meth:`selected` or :meth:`with_channel`.
    """

    time: np.ndarray
    channels: Mapping[str, np.ndarray]
    units: Mapping[str, str] = field(default_factory=dict)
    metadata: Mapping[str, Any] = field(default_factory=dict)
    source: str | None = None

    def __post_init__(self) -> None:
        time = _frozen_array(self.time, "time")
        if time.size < 2:
            raise ValueError(f"time must have at least 2 samples, got {time.size}")
        steps = np.diff(time)
        bad = np.flatnonzero(steps <= 0)
        if bad.size:
            i = int(bad[0]) + 1
            raise ValueError(
                f"time must be strictly increasing: sample {i} (t={float(time[i])!r} s) is not after "
                f"sample {i - 1} (t={float(time[i - 1])!r} s)"
            )
        if not isinstance(self.channels, Mapping) or not self.channels:
            raise ValueError("channels must be a non-empty mapping name -> samples")
        channels: dict[str, np.ndarray] = {}
        for name, values in self.channels.items():
            if not isinstance(name, str) or not name:
                raise TypeError(f"channel names must be non-empty strings, got {name!r}")
            array = _frozen_array(values, f"channel {name!r}")
            if array.shape != time.shape:
                raise ValueError(
                    f"channel {name!r} has {array.size} samples but time has {time.size}"
                )
            channels[name] = array
        units = {name: "" for name in channels}
        for name, unit in dict(self.units).items():
            if name not in channels:
                raise ValueError(f"unit given for unknown channel {name!r}; channels: {list(channels)}")
            if not isinstance(unit, str):
                raise TypeError(f"unit of channel {name!r} must be a string, got {unit!r}")
            units[name] = unit
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "channels", channels)
        object.__setattr__(self, "units", units)
        if not isinstance(self.metadata, Mapping):
            raise TypeError(f"metadata: must be a mapping, got {type(self.metadata).__name__}")
        object.__setattr__(self, "metadata", dict(self.metadata))

    def __repr__(self) -> str:
        """One line: samples, time span and rate, channels with units, metadata keys (not their values: a
        recording's metadata sheet can run to hundreds of lines; see ``.metadata``) and the source."""
        chans = ", ".join(f"{n} [{self.units[n]}]" if self.units.get(n) else n for n in self.channels)
        keys = list(self.metadata)
        meta = "no metadata" if not keys else (f"metadata: {len(keys)} entr{'y' if len(keys) == 1 else 'ies'} ("
                                               + ", ".join(map(str, keys[:5])) + (", ..." if len(keys) > 5 else "")
                                               + ")")
        src = f", source={self.source!r}" if self.source else ""
        return (f"Recording({self.n_samples} samples, t = {self.time[0]:.6g} .. {self.time[-1]:.6g} s at "
                f"{self.sampling_rate:.6g} Hz, channels: {chans}; {meta}{src})")

    # -- access -----------------------------------------------------------------------
    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.channels[name]
        except KeyError:
            raise KeyError(f"no channel {name!r}; channels: {list(self.channels)}") from None

    def __contains__(self, name: object) -> bool:
        return name in self.channels

    @property
    def channel_names(self) -> list[str]:
        """Channel names in insertion order."""
        return list(self.channels)

    @property
    def n_samples(self) -> int:
        return int(self.time.size)

    @property
    def sample_interval(self) -> float:
        """Median spacing of the time axis (s)."""
        return float(np.median(np.diff(self.time)))

    @property
    def sampling_rate(self) -> float:
        """1 / :attr:`sample_interval` (Hz)."""
        return 1.0 / self.sample_interval

    def is_uniform(self, rtol: float = 1e-6) -> bool:
        """True if every time step equals the median step within ``rtol``."""
        steps = np.diff(self.time)
        return bool(np.all(np.abs(steps - np.median(steps)) <= rtol * np.median(steps)))

    # -- derived recordings -----------------------------------------------------------
    def window(self, start: float | None = None, stop: float | None = None) -> Recording:
        """The samples with ``start <= time <= stop`` (bounds in s; ``None`` = open)."""
        mask = np.ones(self.time.shape, dtype=bool)
        if start is not None:
            start = finite("start", start, "s")
            mask &= self.time >= start
        if stop is not None:
            stop = finite("stop", stop, "s")
            mask &= self.time <= stop
        if np.count_nonzero(mask) < 2:
            raise ValueError(
                f"window [{start}, {stop}] s keeps fewer than 2 samples of the recording "
                f"spanning [{self.time[0]}, {self.time[-1]}] s"
            )
        return Recording(
            self.time[mask],
            {name: values[mask] for name, values in self.channels.items()},
            self.units,
            self.metadata,
            self.source,
        )

    def selected(self, names: Iterable[str]) -> Recording:
        """A recording with only the named channels."""
        names = [names] if isinstance(names, str) else list(names)
        if not names:
            raise ValueError(f"names: select at least one channel; channels: {self.channel_names}")
        for name in names:
            self[name]
        return Recording(
            self.time,
            {name: self.channels[name] for name in names},
            {name: self.units[name] for name in names},
            self.metadata,
            self.source,
        )

    def with_channel(self, name: str, values: Any, unit: str = "") -> Recording:
        """A copy with channel ``name`` added (or replaced)."""
        channels = dict(self.channels)
        channels[name] = values
        units = dict(self.units)
        units[name] = unit
        return Recording(self.time, channels, units, self.metadata, self.source)

    def to_xarray(self):  # -> xarray.Dataset
        """The recording as an :class:`xarray.Dataset` with a ``time`` coordinate (s)."""
        import xarray as xr

        data_vars = {
            name: ("time", values, {"units": self.units[name]}) for name, values in self.channels.items()
        }
        attrs = {"source": self.source or ""}
        attrs.update(
            {str(k): v for k, v in self.metadata.items() if isinstance(v, (str, int, float))}
        )
        return xr.Dataset(data_vars, coords={"time": ("time", self.time, {"units": "s"})}, attrs=attrs)
