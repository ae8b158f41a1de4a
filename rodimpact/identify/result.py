"""The result of an identification, :class:`IdentificationResult`, and one reflector it found, :class:`Anomaly`,
with their layouts as an ``xarray.Dataset`` and as a table. The classes know nothing about files
(docs/architecture.md): :func:`rodimpact.save` writes the dataset as a netCDF file (or the table as CSV) and
:func:`rodimpact.load` reads them back.

Conventions (docs/identification.md): ``depth`` is the distance from the measured face (the pile head, the bar's
impact face) along the rod (m, +x); the profile is piecewise constant, element ``j`` between ``depth[j]`` and
``depth[j + 1]`` with impedance ``impedance[j]`` (N s/m, ``Z = E A / c = rho c A``). Bands are two-sided 90 %
intervals (5 % and 95 % quantiles) or ``None`` when a method gives none.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any, Mapping, Optional

import numpy as np

__all__ = ["Anomaly", "IdentificationResult"]

#: The attribute ``kind`` of an identification's dataset (how :func:`rodimpact.load` recognises it).
KIND = "identification"
Band = Optional[tuple[float, float]]


@dataclass(frozen=True)
class Anomaly:
    """One reflector in an identified profile.

    ``depth`` (m): where the impedance changes, measured from the head; ``length`` (m): the extent of the changed
    zone (0 for a single step, the distance to the next opposite step for a neck or bulge); ``relative_change``:
    ``(Z2 - Z1) / Z1`` across the reflector (negative for a reduction); ``beta``: the integrity factor
    ``Z2 / Z1`` (Rausche and Goble 1979; docs/identification.md), ``beta_class`` its class (``"uniform"``,
    ``"slight damage"``, ``"damage"``, ``"broken"``, or ``"increase"`` for beta > 1); ``depth_band``,
    ``size_band``: 90 % bands of the depth (m) and of the relative change, or ``None``.
    """

    depth: float
    length: float
    relative_change: float
    beta: float
    beta_class: str
    depth_band: Band = None
    size_band: Band = None

    def __post_init__(self) -> None:
        for name in ("depth", "length", "relative_change", "beta"):
            value = getattr(self, name)
            if not np.isfinite(value):
                raise ValueError(f"Anomaly.{name}: must be finite, got {value!r}")
        if self.depth < 0 or self.length < 0:
            raise ValueError(f"Anomaly.depth and length: must be >= 0 m, got {self.depth!r} and {self.length!r}")
        if self.beta <= 0:
            raise ValueError(f"Anomaly.beta: must be > 0 (an impedance ratio), got {self.beta!r}")
        for name in ("depth_band", "size_band"):
            band = getattr(self, name)
            if band is not None:
                lo, hi = (float(b) for b in band)
                if not (np.isfinite(lo) and np.isfinite(hi) and lo <= hi):
                    raise ValueError(f"Anomaly.{name}: must be (low, high) finite with low <= high, got {band!r}")
                object.__setattr__(self, name, (lo, hi))


@dataclass(frozen=True)
class IdentificationResult:
    """An identified impedance profile with its bands, reflectors and toe.

    ``depth`` (m, n + 1 element boundaries from the head, increasing), ``impedance`` (N s/m, n), ``lower`` /
    ``upper`` (N s/m, the 90 % band, or ``None``), ``anomalies`` (:class:`Anomaly`, by depth), ``toe`` (m, the
    depth of the toe reflection, or ``None``) and ``toe_band``, ``wave_speed`` (m/s, the one used to turn
    travel time into depth: ``depth = c t / 2`` for a reflection arriving at ``t``), ``matched`` (name ->
    ``(time, measured, fitted)`` arrays, s and the signal's SI unit), ``misfit`` (the method's measure of the
    mismatch, see ``diagnostics["misfit_definition"]``), ``method`` (``"peeling"``, ``"beta"``, ...) and
    ``diagnostics`` (version, warnings, the method's settings; JSON-serialisable values).
    """

    depth: np.ndarray
    impedance: np.ndarray
    lower: Optional[np.ndarray] = None
    upper: Optional[np.ndarray] = None
    anomalies: tuple[Anomaly, ...] = ()
    toe: Optional[float] = None
    toe_band: Band = None
    wave_speed: float = float("nan")
    matched: Mapping[str, tuple[np.ndarray, np.ndarray, np.ndarray]] = field(default_factory=dict)
    misfit: float = float("nan")
    method: str = ""
    diagnostics: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        depth = np.asarray(self.depth, dtype=float)
        z = np.asarray(self.impedance, dtype=float)
        if z.ndim != 1 or z.size < 1:
            raise ValueError(f"IdentificationResult.impedance: must be a 1-D array of n >= 1 values, got shape "
                             f"{z.shape}")
        if depth.shape != (z.size + 1,):
            raise ValueError(f"IdentificationResult.depth: must hold the n + 1 = {z.size + 1} element boundaries, "
                             f"got shape {depth.shape}")
        if not (np.all(np.isfinite(depth)) and np.all(np.diff(depth) > 0)):
            raise ValueError("IdentificationResult.depth: must be finite and strictly increasing (m)")
        if not (np.all(np.isfinite(z)) and np.all(z > 0)):
            raise ValueError("IdentificationResult.impedance: must be finite and > 0 N s/m")
        object.__setattr__(self, "depth", depth)
        object.__setattr__(self, "impedance", z)
        for name in ("lower", "upper"):
            band = getattr(self, name)
            if band is not None:
                band = np.asarray(band, dtype=float)
                if band.shape != z.shape or not np.all(np.isfinite(band)):
                    raise ValueError(f"IdentificationResult.{name}: must be {z.size} finite values (N s/m) or "
                                     f"None, got shape {band.shape}")
                object.__setattr__(self, name, band)
        if (self.lower is None) != (self.upper is None):
            raise ValueError("IdentificationResult.lower, upper: give both bands or neither")
        anomalies = tuple(self.anomalies)
        if not all(isinstance(a, Anomaly) for a in anomalies):
            raise TypeError("IdentificationResult.anomalies: must be Anomaly objects")
        object.__setattr__(self, "anomalies", tuple(sorted(anomalies, key=lambda a: a.depth)))
        if self.toe_band is not None:
            object.__setattr__(self, "toe_band", tuple(float(b) for b in self.toe_band))
        matched = {}
        for name, arrays in dict(self.matched).items():
            t, m, f = (np.asarray(a, dtype=float) for a in arrays)
            if not (t.ndim == 1 and t.shape == m.shape == f.shape):
                raise ValueError(f"IdentificationResult.matched[{name!r}]: time, measured and fitted must be 1-D "
                                 f"arrays of one length, got {t.shape}, {m.shape}, {f.shape}")
            matched[str(name)] = (t, m, f)
        object.__setattr__(self, "matched", matched)
        object.__setattr__(self, "diagnostics", dict(self.diagnostics))

    # -- derived ---------------------------------------------------------------------------------------------
    @property
    def length(self) -> float:
        """The identified length (m): the deepest element boundary."""
        return float(self.depth[-1])

    @property
    def midpoints(self) -> np.ndarray:
        """The element midpoints (m)."""
        return 0.5 * (self.depth[1:] + self.depth[:-1])

    def summary(self) -> dict[str, Any]:
        """The numbers a report needs (SI units), JSON-serialisable."""
        return {"method": self.method, "elements": int(self.impedance.size), "length_m": self.length,
                "wave_speed_m_per_s": float(self.wave_speed), "toe_m": self.toe,
                "impedance_head_N_s_per_m": float(self.impedance[0]),
                "impedance_min_N_s_per_m": float(self.impedance.min()),
                "anomalies": [_anomaly_dict(a) for a in self.anomalies], "misfit": float(self.misfit)}

    # -- data ------------------------------------------------------------------------------------------------
    def table(self) -> tuple[list[str], list[np.ndarray]]:
        """The profile as the columns of one table, one row per element: headers ``name [unit]``."""
        header = ["depth_top [m]", "depth_bottom [m]", "impedance [N s/m]"]
        columns = [self.depth[:-1], self.depth[1:], self.impedance]
        if self.lower is not None:
            header += ["lower [N s/m]", "upper [N s/m]"]
            columns += [self.lower, self.upper]
        return header, columns

    def to_dataframe(self):  # -> pandas.DataFrame
        """The profile as a ``pandas.DataFrame`` (:meth:`table`'s columns, one row per element)."""
        import pandas as pd

        header, columns = self.table()
        return pd.DataFrame(dict(zip(header, columns)))

    def metadata(self) -> dict[str, str]:
        """Everything but the arrays, as JSON strings by name (the netCDF attributes and the CSV comment lines)."""
        return {"kind": KIND, "method": self.method, "wave_speed": json.dumps(float(self.wave_speed)),
                "misfit": json.dumps(float(self.misfit)), "toe": json.dumps(self.toe),
                "toe_band": json.dumps(self.toe_band),
                "anomalies": json.dumps([_anomaly_dict(a) for a in self.anomalies]),
                "diagnostics": json.dumps(self.diagnostics, default=_plain)}

    def to_xarray(self):  # -> xarray.Dataset
        """All arrays as an :class:`xarray.Dataset`: the profile on ``element`` (with ``depth`` on ``boundary``),
        each matched signal on its own time coordinate ``time_<name>``; the rest as attributes (JSON strings)."""
        import xarray as xr

        data: dict[str, Any] = {
            "depth": ("boundary", self.depth, {"units": "m", "long_name": "element boundary depth from the head"}),
            "impedance": ("element", self.impedance, {"units": "N s/m", "long_name": "impedance Z = E A / c"}),
        }
        if self.lower is not None:
            for name, band in (("lower", self.lower), ("upper", self.upper)):
                data[name] = ("element", band, {"units": "N s/m", "long_name": f"{name} end of the 90 % band"})
        for i, (name, (t, m, f)) in enumerate(self.matched.items()):
            dim = f"time_{i}"
            data[f"{dim}_time"] = (dim, t, {"units": "s", "signal": name})
            data[f"{dim}_measured"] = (dim, m, {"signal": name})
            data[f"{dim}_fitted"] = (dim, f, {"signal": name})
        attrs = self.metadata()
        attrs["matched"] = json.dumps(list(self.matched))
        return xr.Dataset(data, attrs=attrs)

    @classmethod
    def from_xarray(cls, ds: Any) -> "IdentificationResult":
        """The result a :meth:`to_xarray` dataset holds (:func:`rodimpact.load` reads a saved one with it)."""
        a = ds.attrs
        if a.get("kind") != KIND:
            raise ValueError(f"ds: not an identification result (no attribute kind = {KIND!r})")
        matched = {name: tuple(np.asarray(ds[f"time_{i}_{q}"].values, dtype=float)
                               for q in ("time", "measured", "fitted"))
                   for i, name in enumerate(json.loads(a["matched"]))}
        bands = [np.asarray(ds[n].values, dtype=float) if n in ds else None for n in ("lower", "upper")]
        return cls.from_metadata(a, np.asarray(ds["depth"].values, dtype=float),
                                 np.asarray(ds["impedance"].values, dtype=float), *bands, matched=matched)

    @classmethod
    def from_metadata(cls, meta: Mapping[str, str], depth: np.ndarray, impedance: np.ndarray,
                      lower: Optional[np.ndarray] = None, upper: Optional[np.ndarray] = None,
                      matched: Optional[Mapping[str, tuple]] = None) -> "IdentificationResult":
        """The result from :meth:`metadata`'s strings and the arrays (the readers of the netCDF file and the
        CSV table)."""
        toe_band = json.loads(meta["toe_band"])
        return cls(depth, impedance, lower, upper,
                   tuple(_anomaly(d) for d in json.loads(meta["anomalies"])), json.loads(meta["toe"]),
                   tuple(toe_band) if toe_band is not None else None, json.loads(meta["wave_speed"]),
                   matched or {}, json.loads(meta["misfit"]), str(meta["method"]),
                   json.loads(meta["diagnostics"]))


def _anomaly_dict(a: Anomaly) -> dict[str, Any]:
    return {"depth": a.depth, "length": a.length, "relative_change": a.relative_change, "beta": a.beta,
            "beta_class": a.beta_class, "depth_band": a.depth_band, "size_band": a.size_band}


def _anomaly(d: Mapping[str, Any]) -> Anomaly:
    return Anomaly(float(d["depth"]), float(d["length"]), float(d["relative_change"]), float(d["beta"]),
                   str(d["beta_class"]), None if d["depth_band"] is None else tuple(d["depth_band"]),
                   None if d["size_band"] is None else tuple(d["size_band"]))


def _plain(value: Any) -> Any:
    """JSON for the numpy values a diagnostics dict may hold."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"diagnostics: {type(value).__name__} is not JSON-serialisable")
