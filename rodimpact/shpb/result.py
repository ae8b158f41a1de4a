"""The result of a split-Hopkinson-bar data reduction, :class:`ShpbReduction`, and the specimen response of one
analysis, :class:`SpecimenResponse`, and their layout as an ``xarray.Dataset`` and as a table. The classes know
nothing about files (docs/architecture.md): :func:`rodimpact.save` and :func:`rodimpact.load` store the dataset as
a netCDF file, :func:`rodimpact.io.save_reduction_csv` the table.

Two sign conventions meet here, and every array says which it follows (docstrings, ``sign`` attributes):
bar strains and face forces are **positive in tension** (the package's convention); specimen stress, strain and
strain rate are **positive in compression** (the habit of Hopkinson-bar work), so that a compression test gives
a positive stress-strain curve.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..rods.material import Material
from .equilibrium import BANDS, EquilibriumCheck, check_equilibrium
from .parts import Bar, SpecimenGeometry
from .windows import PULSES, PulseWindows, Window

__all__ = ["ANALYSES", "ShpbReduction", "SpecimenResponse"]

#: The analyses of a reduction, by the faces whose forces give the stress (docs/shpb.md).
ANALYSES = ("1-wave", "2-wave", "3-wave")
_COMPRESSION = "positive in compression"
_TENSION = "positive in tension"


@dataclass(frozen=True)
class SpecimenResponse:
    """The specimen's engineering stress (Pa), strain (-) and strain rate (1/s) from one analysis, **positive in
    compression**, on the reduction's time axis; the true measures follow for incompressible flow
    (``A = A0 / (1 - eps)``)."""

    stress: np.ndarray
    strain: np.ndarray
    strain_rate: np.ndarray

    @property
    def true_strain(self) -> np.ndarray:
        """Logarithmic strain ``-ln(1 - eps)`` (compression positive)."""
        return -np.log1p(-self.strain)

    @property
    def true_stress(self) -> np.ndarray:
        """Cauchy stress ``sigma (1 - eps)`` (Pa, compression positive): the force over the grown area."""
        return self.stress * (1.0 - self.strain)

    @property
    def true_strain_rate(self) -> np.ndarray:
        """``d(true strain)/dt = eps_dot / (1 - eps)`` (1/s, compression positive)."""
        return self.strain_rate / (1.0 - self.strain)


@dataclass(frozen=True)
class ShpbReduction:
    """Everything a reduction found (:func:`rodimpact.shpb.reduce_shot`).

    ``time`` (s) is the time at the specimen faces: the incident window's start moved to the face, then one
    sample per sampling interval. ``incident``, ``reflected``, ``transmitted``: the bar strains moved to the
    specimen faces (tension positive; dispersion-corrected if ``dispersion_corrected``). ``one_wave``,
    ``two_wave``, ``three_wave``: the specimen responses (compression positive). ``equilibrium``: R(t) and its
    verdict. ``windows``: the pulse windows in the gauge records. The bars, the specimen and the source file
    complete it. Save it with ``rodimpact.save(reduction, "shot.nc")`` (read back by ``rodimpact.load``), the
    time series as a CSV table with ``rodimpact.io.save_reduction_csv(reduction, "shot.csv")``.
    """

    time: np.ndarray
    incident: np.ndarray
    reflected: np.ndarray
    transmitted: np.ndarray
    one_wave: SpecimenResponse
    two_wave: SpecimenResponse
    three_wave: SpecimenResponse
    equilibrium: EquilibriumCheck
    windows: PulseWindows
    incident_bar: Bar
    transmitted_bar: Bar
    specimen: SpecimenGeometry
    dispersion_corrected: bool = False
    source: str = ""

    @property
    def responses(self) -> dict[str, SpecimenResponse]:
        """The three analyses by name: ``"1-wave"``, ``"2-wave"``, ``"3-wave"``."""
        return dict(zip(ANALYSES, (self.one_wave, self.two_wave, self.three_wave)))

    def response(self, analysis: str) -> SpecimenResponse:
        """The response of one analysis (``"1-wave"``, ``"2-wave"`` or ``"3-wave"``)."""
        if analysis not in ANALYSES:
            raise ValueError(f"analysis: must be one of {', '.join(ANALYSES)}, got {analysis!r}")
        return self.responses[analysis]

    def flow_stress(self, strain: float, analysis: str = "3-wave", true: bool = False) -> float:
        """The stress (Pa) when the strain first reaches ``strain`` (compression positive), linearly
        interpolated; engineering measures, or true ones with ``true=True``. ``ValueError`` if the strain never
        gets there."""
        r = self.response(analysis)
        eps, sigma = (r.true_strain, r.true_stress) if true else (r.strain, r.stress)
        reached = np.flatnonzero(eps >= strain)
        if reached.size == 0:
            raise ValueError(f"strain: the {analysis} {'true' if true else 'engineering'} strain reaches at most "
                             f"{float(np.max(eps)):.4g}, not {strain!r}")
        k = int(reached[0])
        if k == 0:
            return float(sigma[0])
        w = (strain - eps[k - 1]) / (eps[k] - eps[k - 1])
        return float(sigma[k - 1] + w * (sigma[k] - sigma[k - 1]))

    def mean_strain_rate(self, analysis: str = "3-wave") -> float:
        """The mean engineering strain rate (1/s) while the specimen is in equilibrium (from the equilibrium
        time to the loading end; over the whole loading part if it never is)."""
        eq = self.equilibrium
        start = eq.equilibrium_time if eq.equilibrium_time is not None else float(self.time[0])
        span = (self.time >= start) & (self.time <= eq.loading_end)
        return float(np.mean(self.response(analysis).strain_rate[span]))

    def summary(self) -> dict[str, Any]:
        """The numbers a report states (SI units; specimen quantities compression positive)."""
        eq = self.equilibrium
        at_eq = (None if eq.equilibrium_time is None
                 else float(np.interp(eq.equilibrium_time, self.time, self.three_wave.strain)))
        out: dict[str, Any] = {
            "source": self.source,
            "specimen_length_m": self.specimen.length, "specimen_diameter_m": self.specimen.diameter,
            "dispersion_corrected": self.dispersion_corrected,
            "windows": {name: {"start_s": getattr(self.windows, name).start,
                               "duration_s": getattr(self.windows, name).duration,
                               "given": name in self.windows.given} for name in PULSES},
            "equilibrium": {"pass_limit": eq.pass_limit, "review_limit": eq.review_limit,
                            "equilibrium_time_s": eq.equilibrium_time, "strain_at_equilibrium": at_eq,
                            "review_time_s": eq.review_time, "loading_end_s": eq.loading_end},
            "analyses": {},
        }
        for name, r in self.responses.items():
            out["analyses"][name] = {"peak_stress_Pa": float(np.max(r.stress)),
                                     "final_strain": float(r.strain[-1]),
                                     "mean_strain_rate_per_s": self.mean_strain_rate(name)}
        return out

    # -- data -----------------------------------------------------------------------------------------------
    def to_xarray(self):  # -> xarray.Dataset
        """All arrays as an :class:`xarray.Dataset` on the coordinates ``time`` (s, at the specimen faces) and
        ``analysis`` (1-wave, 2-wave, 3-wave); every variable has ``units`` and, where it matters, ``sign``; the
        bars, the specimen, the windows and the band limits are attributes (SI)."""
        import xarray as xr

        stack = {q: np.stack([getattr(r, q) for r in self.responses.values()])
                 for q in ("stress", "strain", "strain_rate", "true_stress", "true_strain", "true_strain_rate")}
        eq = self.equilibrium
        data = {
            "incident": ("time", self.incident, _attrs("1", _TENSION, "incident bar strain at the specimen face")),
            "reflected": ("time", self.reflected, _attrs("1", _TENSION, "reflected bar strain at the specimen face")),
            "transmitted": ("time", self.transmitted, _attrs("1", _TENSION,
                                                             "transmitted bar strain at the specimen face")),
            "front_force": ("time", eq.front_force, _attrs("N", _TENSION, "F1 = E_I A_I (eps_I + eps_R)")),
            "back_force": ("time", eq.back_force, _attrs("N", _TENSION, "F2 = E_T A_T eps_T")),
            "equilibrium_ratio": ("time", eq.ratio, _attrs("1", "", "R = 2 |F1 - F2| / |F1 + F2|; NaN where the "
                                                                    "mean face force is below 1 % of its peak")),
            "equilibrium_band": ("time", eq.band, _attrs("1", "", ", ".join(f"{k} {v}" for k, v in BANDS.items()))),
        }
        for q, unit in (("stress", "Pa"), ("strain", "1"), ("strain_rate", "1/s")):
            data[q] = (("analysis", "time"), stack[q], _attrs(unit, _COMPRESSION, f"engineering {q}"))
            data[f"true_{q}"] = (("analysis", "time"), stack[f"true_{q}"], _attrs(unit, _COMPRESSION, f"true {q}"))
        attrs: dict[str, Any] = {"kind": "shpb-reduction", "source": self.source,
                                 "dispersion_corrected": int(self.dispersion_corrected),
                                 "specimen_length": self.specimen.length, "specimen_area": self.specimen.area,
                                 "pass_limit": eq.pass_limit, "review_limit": eq.review_limit,
                                 "windows_given": ",".join(self.windows.given)}
        for role, bar in (("incident_bar", self.incident_bar), ("transmitted_bar", self.transmitted_bar)):
            attrs.update({f"{role}_youngs_modulus": bar.youngs_modulus, f"{role}_density": bar.material.density,
                          f"{role}_material": bar.material.name, f"{role}_area": bar.area,
                          f"{role}_gauge_distance": bar.gauge_distance, f"{role}_name": bar.name})
            if bar.poisson_ratio is not None:
                attrs[f"{role}_poisson_ratio"] = bar.poisson_ratio
        for name in PULSES:
            w = getattr(self.windows, name)
            attrs[f"{name}_window_start"], attrs[f"{name}_window_duration"] = w.start, w.duration
        coords = {"time": ("time", self.time, {"units": "s", "long_name": "time at the specimen faces"}),
                  "analysis": ("analysis", list(ANALYSES))}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_xarray(cls, ds: Any) -> "ShpbReduction":
        """The reduction a :meth:`to_xarray` dataset holds (:func:`rodimpact.load` reads a saved one with it)."""
        a = ds.attrs
        if a.get("kind") != "shpb-reduction":
            raise ValueError("ds: not a split-Hopkinson-bar reduction (no attribute kind = 'shpb-reduction')")
        time = np.asarray(ds["time"].values, dtype=float)
        bars = []
        for role in ("incident_bar", "transmitted_bar"):
            material = Material(float(a[f"{role}_youngs_modulus"]), float(a[f"{role}_density"]),
                                str(a[f"{role}_material"]))
            bars.append(Bar(material=material,
                            area=float(a[f"{role}_area"]), gauge_distance=float(a[f"{role}_gauge_distance"]),
                            poisson_ratio=a.get(f"{role}_poisson_ratio"), name=str(a[f"{role}_name"])))
        given = tuple(g for g in str(a["windows_given"]).split(",") if g)
        windows = PulseWindows(*(Window(float(a[f"{n}_window_start"]), float(a[f"{n}_window_duration"]))
                                 for n in PULSES), given=given)
        responses = [SpecimenResponse(*(np.asarray(ds[q].sel(analysis=name).values, dtype=float)
                                        for q in ("stress", "strain", "strain_rate"))) for name in ANALYSES]
        equilibrium = check_equilibrium(time, np.asarray(ds["front_force"].values, dtype=float),
                                        np.asarray(ds["back_force"].values, dtype=float),
                                        (float(a["pass_limit"]), float(a["review_limit"])))
        return cls(time, *(np.asarray(ds[n].values, dtype=float) for n in PULSES), *responses, equilibrium,
                   windows, bars[0], bars[1],
                   SpecimenGeometry(length=float(a["specimen_length"]), area=float(a["specimen_area"])),
                   bool(a["dispersion_corrected"]), str(a["source"]))

    # -- files ------------------------------------------------------------------------------------------------
    def table(self) -> tuple[list[str], list[np.ndarray]]:
        """The time series as the columns of one table: headers ``name [unit]`` (specimen columns
        ``3-wave.stress [Pa]`` and so on, compression positive; bar strains and face forces tension positive) and
        the arrays, one value per sample (written as CSV by :func:`rodimpact.io.save_reduction_csv`)."""
        header = ["time [s]", "incident [-]", "reflected [-]", "transmitted [-]", "front_force [N]",
                  "back_force [N]", "equilibrium_ratio [-]"]
        eq = self.equilibrium
        columns = [self.time, self.incident, self.reflected, self.transmitted, eq.front_force, eq.back_force,
                   eq.ratio]
        for name, r in self.responses.items():
            for q, unit in (("stress", "Pa"), ("strain", "-"), ("strain_rate", "1/s"), ("true_stress", "Pa"),
                            ("true_strain", "-"), ("true_strain_rate", "1/s")):
                header.append(f"{name}.{q} [{unit}]")
                columns.append(getattr(r, q))
        return header, columns


def _attrs(units: str, sign: str, long_name: str) -> dict[str, str]:
    out = {"units": units, "long_name": long_name}
    if sign:
        out["sign"] = sign
    return out
