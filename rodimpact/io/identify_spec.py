"""Identification specs: what ``rodimpact identify RECORD --spec SPEC.toml`` needs besides the record
(docs/identification.md, ``rodimpact docs identify``).

A record is a plain CSV table of time, force and velocity at the head (:func:`rodimpact.io.identification.
read_head_csv`; several files are blows, averaged), a recording with named channels in a format the package reads
(a CSV table with a time column, TDMS, Tektronix CSV files; ``record.force_channel`` and ``velocity_channel``) or,
for ``method = "striker"``, a LANL ``.raw`` shot (its sheet gives the bar and gauge, the spec the bridge).
:func:`load_spec` reads and validates the spec (errors name the
key path), :func:`run` identifies, :func:`summarize` and :func:`format_summary` report, :func:`write_files` writes
the data files (figures: :func:`rodimpact.output_folders.write_identification`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Mapping, Optional, Sequence

import numpy as np

from ..identify import (HeadRecord, IdentificationResult, average_blows, band_limited, identify_by_beta,
                        identify_by_peeling, identify_striker)
from ..identify.matching import identify_by_matching
from .identification import read_head_csv, save_identification_csv
from .model import parse_toml, read_text_file
from .overrides import spec_with_overrides
from .quantities import ModelError, parse_quantity
from .recordings import hoppybar_bar, read_csv_recording, read_lanl_raw, read_tdms, read_tektronix_csv
from .schema import Field, Table, _q, _table_md, validate_table

METHODS = ("matching", "peeling", "beta", "striker")
CSV_FILE, NETCDF_FILE, SPEC_FILE = "profile.csv", "identification.nc", "spec.toml"

RECORD = Table("record", "The measured record. Files given on the command line take the place of `files`.", (
    Field("files", "strings", "Record files, relative to the spec: CSV tables `time [s], force [N], velocity "
                              "[m/s]` (units in brackets, any of the right dimension; several files are blows, "
                              "averaged) or one LANL `.raw` shot (method striker)."),
    Field("force_sign", "string", "Sign of the CSV force column: `tension` (positive in tension, the package's "
                                  "convention) or `compression` (pile practice).", default="tension",
          choices=("tension", "compression")),
    _q("start", "time", "Time of the blow's onset: the record is used from the first sample at or after it.",
       sign=None, required=False),
    _q("end", "time", "Use the record up to this time (striker: before the reflected pulse arrives).", sign=None,
       required=False),
    _q("low_pass", "rate", "Corner of a zero-phase low-pass filter (4th-order Butterworth) applied first.",
       required=False),
    Field("format", "string", "With `force_channel`: the recording's format (default from the extension: "
                              "`.csv` a plain table with a time column, `.tdms` tdms; `tektronix-csv`: one file per "
                              "channel).", choices=("csv", "tdms", "tektronix-csv")),
    Field("force_channel", "string", "Read a recording with named channels instead of a head CSV table: the force "
                                     "channel (its unit from the file, else N)."),
    Field("velocity_channel", "string", "The velocity channel (its unit from the file, else m/s)."),
    Field("bridge", "string", "LANL shot: bridge circuit of the incident bar's gauge (the sheet does not record "
                              "it)."),
    Field("polarity", "integer", "LANL shot: -1 if compression was recorded as positive voltage.", default=1),
), '[record]\nfiles = ["blow1.csv", "blow2.csv"]\nforce_sign = "compression"\nlow_pass = "20 kHz"')

ROD = Table("rod", "The rod below the measured face (the bar, for method striker).", (
    _q("impedance", "impedance", "Impedance at the head Z = E A / c (default for a LANL shot: the incident "
                                 "bar's from the sheet; method matching: estimated from the rise of the blow, "
                                 "Z = -F / v).", required=False),
    _q("wave_speed", "velocity", "Wave speed c: turns travel time into depth (default for a LANL shot: the "
                                 "sheet's calibrated speed).", required=False),
    _q("diameter", "length", "Diameter, for the 1D-validity checks (methods peeling and beta).", required=False),
    _q("length", "length", "Known or expected length (method beta: the toe is the echo nearest to it; matching: "
                           "required, the toe is identified within 1 + extension times it; deconvolved peeling: "
                           "the toe is the largest drop near it).", required=False),
), '[rod]\nimpedance = "1.2 MN s/m"\nwave_speed = "4000 m/s"\ndiameter = "0.4 m"\nlength = "12 m"')

SETTINGS = Table("identify", "The method and its settings.", (
    Field("method", "string", "`matching` (regularised signal matching with soil and 90 % bands: the method for "
                              "real pile records), `peeling` (clean lossless force and velocity, or any blow with "
                              "`deconvolve`), `beta` (reflectors and integrity factors from the reflectogram) or "
                              "`striker` (the striker from an incident pulse).", choices=METHODS),
    _q("threshold", "dimensionless", "The smallest relative change reported as an anomaly (default: the "
                                     "method's, 0.08 for matching, 0.05 for peeling and beta).", required=False),
    Field("penalty", "string", "Matching: `tv` (total variation of ln Z, keeps steps) or `smooth` (second "
                               "differences).", default="tv", choices=("tv", "smooth")),
    _q("weight", "dimensionless", "Matching: the penalty weight alpha (default: chosen by the discrepancy "
                                  "principle from the baseline's noise, else the L-curve).", sign="non_negative",
       required=False),
    Field("bands", "string", "Matching: `laplace` (Gauss-Newton covariance), `sampling` (MCMC chains, stopped "
                             "at convergence) or `none`.", default="laplace", choices=("laplace", "sampling", "none")),
    _q("band_scale", "dimensionless", "Matching: an empirical factor on the widths of the Laplace bands and "
                                      "the toe interval, not the anomaly depth bands (1: none; the "
                                      "identification benchmark's calibration is 1.624, docs/"
                                      "identification-matching.md).", default=1.0, required=False),
    _q("velocity_noise", "velocity", "Matching: standard deviation of the velocity record's noise (default: from "
                                     "the record's pre-trigger baseline).", required=False),
    _q("extension", "dimensionless", "Matching: the model reaches (1 + extension) length; at most 2.",
       sign="non_negative", default=0.25, required=False),
    Field("elements", "integer", "Matching: elements over the length (default: one per sample interval; the "
                                 "record is resampled).", minimum=4),
    Field("toe", "string", "Matching: the toe a `spring` (spring-dashpot, fitted) or `fixed`.", default="spring",
          choices=("spring", "fixed")),
    Field("soil", "boolean", "Matching: fit a shaft spring and dashpot.", default=True),
    Field("deconvolve", "boolean", "Peeling: deconvolve the blow first (for a smooth blow such as a hammer's "
                                   "half-sine).", default=False),
    _q("water_level", "dimensionless", "Peeling with `deconvolve`: the regularisation eps, a share of the blow's "
                                       "peak power (default 0.01).", required=False),
    _q("depth", "length", "Peeling: identify down to this depth.", required=False),
    _q("noise", "force", "Peeling: standard deviation of the force record's noise, for 90 % bands by "
                         "resampling (the velocity's: noise / Z).", required=False),
    _q("amplification", "rate", "Reflectogram plot: exponential amplification rate.", sign="non_negative",
       default=0.0, required=False),
    _q("striker_wave_speed", "velocity", "Striker: its wave speed (default: the bar's).", required=False),
    _q("striker_impedance", "impedance", "Striker: its impedance, for the velocity (default: the bar's).",
       required=False),
    _q("striker_velocity", "velocity", "Striker: its impact velocity if known.", required=False),
    Field("resamples", "integer", "Striker, and peeling with `noise`: noisy copies for the 90 % bands.",
          default=100),
), '[identify]\nmethod = "beta"\nthreshold = 0.05')

OUTPUT = Table("output", "What to write.", (Field("plots", "boolean", "Write the plots.", default=True),))

SPEC = Table("identify spec", "Top level of an identification spec.", (
    Field("title", "string", "Short title."),
    Field("identify", "table", "The method.", table=SETTINGS, required=True),
    Field("record", "table", "The record.", table=RECORD),
    Field("rod", "table", "The rod.", table=ROD),
    Field("output", "table", "Output settings.", table=OUTPUT),
))

TEMPLATE = '''# rodimpact identification spec: rodimpact identify RECORD.csv --spec identify.toml
# RECORD.csv: columns "time [s], force [N], velocity [m/s]" at the head (units in brackets, any of the right
# dimension); keys: rodimpact docs identify
title = "pile integrity test"

[identify]
method = "matching"      # matching, peeling, beta or striker
threshold = 0.08         # smallest relative impedance change reported

[record]
force_sign = "compression"   # pile practice: force positive in compression

[rod]
impedance = "1.2 MN s/m"     # E A / c at the head
wave_speed = "4000 m/s"
length = "12 m"              # expected length (matching: the toe is found within 1.25 times it)
'''


def spec_reference_markdown() -> str:
    """Reference tables of the spec keys (``rodimpact docs identify``)."""
    lines: list[str] = []
    for title, table in (("Top level", SPEC), ("`[identify]`", SETTINGS), ("`[record]`", RECORD), ("`[rod]`", ROD),
                         ("`[output]`", OUTPUT)):
        _table_md(title, table, 4, lines)
    return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class IdentifySpec:
    """A validated spec: ``values`` (SI, defaults filled in), the folder relative names are read from, its text
    and name."""

    values: dict
    base: Path
    text: str
    name: str

    @property
    def plots(self) -> bool:
        return self.values["output"]["plots"]


def load_spec(path: Optional[str | Path], overrides: Optional[Mapping[str, Any]] = None) -> IdentifySpec:
    """Read a spec file (``None``: only ``overrides``, key path -> value)."""
    if path is None:
        return loads_spec("", ".", "options", overrides)
    p = Path(path)
    return loads_spec(read_text_file(p, str(p), "spec file"), p.parent, str(p), overrides)


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> IdentifySpec:
    """Read a spec from TOML text."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given, name))


def _spec(raw: dict, base: Path, text: str, name: str) -> IdentifySpec:
    if "identify" not in raw:
        raise ModelError("identify: missing; give [identify] with method = \"matching\", \"peeling\", \"beta\" or "
                         "\"striker\"")
    d = validate_table(SPEC, raw, "")
    for key, table in (("record", RECORD), ("rod", ROD), ("output", OUTPUT)):
        d[key] = d[key] or validate_table(table, {}, key)
    settings = d["identify"]
    if settings["method"] is None:
        raise ModelError(f"identify.method: missing; one of {', '.join(METHODS)}")
    if d["record"]["polarity"] not in (1, -1):
        raise ModelError(f"record.polarity: must be 1 or -1, got {d['record']['polarity']}")
    if not settings["extension"] <= 2.0:
        raise ModelError(f"identify.extension: must be a share of the length in [0, 2], got {settings['extension']}")
    if settings["resamples"] < 0:
        raise ModelError(f"identify.resamples: must be >= 0, got {settings['resamples']}")
    start, end = d["record"]["start"], d["record"]["end"]
    if start is not None and end is not None and not end > start:
        raise ModelError(f"record.end: must be after record.start ({start!r} s), got {end!r} s")
    return IdentifySpec(d, base, text, name)


def run(spec: IdentifySpec, files: Sequence[str | Path] = (),
        progress: Optional[Callable[[str], None]] = None) -> IdentificationResult:
    """Read the record (``files``, else ``record.files``) and identify with the spec's method; ``progress``
    receives the matching method's progress lines."""
    rec, rod, settings = spec.values["record"], spec.values["rod"], spec.values["identify"]
    if files and rec["files"]:
        raise ModelError("record.files: the record is given on the command line as well; give it once")
    paths = [Path(f) for f in files] or [spec.base / f for f in rec["files"] or ()]
    if not paths:
        raise ModelError("record.files: no record given; name the file(s) on the command line")
    if paths[0].suffix.lower() == ".raw":
        return _striker_from_lanl(paths, spec)
    if rec["force_channel"] is not None or rec["velocity_channel"] is not None:
        record = _from_channels(paths, rec)
    else:
        blows = [read_head_csv(p, compression_positive=rec["force_sign"] == "compression") for p in paths]
        record = average_blows(blows) if len(blows) > 1 else blows[0]
    keep = np.ones(record.time.size, dtype=bool)
    if rec["start"] is not None:
        keep &= record.time >= rec["start"]
    if rec["end"] is not None:
        keep &= record.time <= rec["end"]
    if np.count_nonzero(keep) < 2:
        raise ModelError("record.start, record.end: keep fewer than 2 samples of the record")
    record = HeadRecord(record.time[keep] - record.time[keep][0], record.force[keep], record.velocity[keep],
                        record.source)
    if rec["low_pass"] is not None:
        record = band_limited(record, rec["low_pass"])
    method = settings["method"]
    threshold = {} if settings["threshold"] is None else {"threshold": settings["threshold"]}
    if method == "matching":
        return identify_by_matching(
            record, rod["impedance"], _required(rod, "wave_speed"), length=_required(rod, "length"),
            elements=settings["elements"], extension=settings["extension"], noise=settings["velocity_noise"],
            penalty=settings["penalty"], weight="auto" if settings["weight"] is None else settings["weight"],
            soil=settings["soil"], toe=settings["toe"], bands=settings["bands"], band_scale=settings["band_scale"],
            progress=progress, **({} if not threshold else {"min_change": threshold["threshold"]}))
    z, c = _required(rod, "impedance"), _required(rod, "wave_speed")
    if method == "peeling":
        extra = {"length": rod["length"]} if settings["deconvolve"] else {}
        if settings["water_level"] is not None:
            extra["water_level"] = settings["water_level"]
        return identify_by_peeling(record, z, c, depth=settings["depth"], noise=settings["noise"],
                                   resamples=max(settings["resamples"], 2), diameter=rod["diameter"],
                                   deconvolve=settings["deconvolve"], **threshold, **extra)
    if method == "beta":
        return identify_by_beta(record, z, c, length=rod["length"], diameter=rod["diameter"], **threshold)
    return identify_striker(record.time, record.force, z, settings["striker_wave_speed"] or c,
                            velocity=settings["striker_velocity"], striker_impedance=settings["striker_impedance"],
                            resamples=settings["resamples"])


def _from_channels(paths: list[Path], rec: dict) -> HeadRecord:
    """A head record from a recording with named channels (``record.force_channel``, ``record.velocity_channel``),
    each converted from the unit the file gives it to SI (a unit of another dimension is an error naming the
    key)."""
    if rec["force_channel"] is None or rec["velocity_channel"] is None:
        missing = "force_channel" if rec["force_channel"] is None else "velocity_channel"
        raise ModelError(f"record.{missing}: missing; a recording with channels needs force_channel and "
                         f"velocity_channel")
    fmt = rec["format"] or {".tdms": "tdms"}.get(paths[0].suffix.lower(), "csv")
    if fmt != "tektronix-csv" and len(paths) != 1:
        raise ModelError(f"record.files: a {fmt} recording is one file, got {len(paths)}")
    recording = (read_tektronix_csv(paths) if fmt == "tektronix-csv"
                 else {"csv": read_csv_recording, "tdms": read_tdms}[fmt](paths[0]))
    values = {}
    for key, dimension in (("force_channel", "force"), ("velocity_channel", "velocity")):
        name = rec[key]
        if name not in recording.channel_names:
            raise ModelError(f"record.{key}: no channel {name!r} in {paths[0].name}; channels: "
                             f"{', '.join(recording.channel_names)}")
        unit = recording.units.get(name, "")
        factor = parse_quantity(f"1 {unit}", dimension, f"record.{key} ({name} [{unit}])") if unit else 1.0
        values[dimension] = np.asarray(recording[name], dtype=float) * factor
    force = -values["force"] if rec["force_sign"] == "compression" else values["force"]
    return HeadRecord(recording.time, force, values["velocity"], str(paths[0]))


def _required(table: dict, key: str) -> float:
    if table[key] is None:
        raise ModelError(f"rod.{key}: missing; give it in the spec ([rod] {key} = ...)")
    return table[key]


def _striker_from_lanl(paths: list[Path], spec: IdentifySpec) -> IdentificationResult:
    """Method striker on a LANL shot: the incident channel as force (the sheet's bar and gauge, the spec's
    bridge), the bar's impedance E A / c and c from the sheet unless the spec gives them."""
    rec, rod, settings = spec.values["record"], spec.values["rod"], spec.values["identify"]
    if settings["method"] != "striker":
        raise ModelError(f"identify.method: a LANL .raw shot is identified with method = \"striker\", got "
                         f"{settings['method']!r}")
    if len(paths) != 1:
        raise ModelError(f"record.files: a LANL shot is one .raw file, got {len(paths)}")
    if rec["bridge"] is None:
        raise ModelError("record.bridge: missing; the LANL sheets do not record the bridge circuit (e.g. "
                         "\"half-axial\")")
    shot = read_lanl_raw(paths[0])
    try:
        gauge = hoppybar_bar(shot.metadata, "incident", bridge=rec["bridge"], polarity=rec["polarity"])
    except ValueError as exc:
        raise ModelError(f"record.bridge: {exc}") from None
    c = rod["wave_speed"] or float(shot.metadata.get("Incident Bar Reflected Time Sound Speed(m/s)",
                                                     shot.metadata["Incident Bar Rod Sound Speed(m/s)"]))
    z = rod["impedance"] or gauge.youngs_modulus * gauge.area / c
    force = gauge.force(shot["incident"])
    keep = shot.time <= rec["end"] if rec["end"] is not None else np.ones(shot.time.size, dtype=bool)
    return identify_striker(shot.time[keep], force[keep], z, settings["striker_wave_speed"] or c,
                            velocity=settings["striker_velocity"], striker_impedance=settings["striker_impedance"],
                            resamples=settings["resamples"])


def summarize(result: IdentificationResult, spec: IdentifySpec, files: Sequence[str]) -> dict[str, Any]:
    """The numbers of a run (JSON-ready, SI) with the title and the record files."""
    out = {"title": spec.values["title"] or "", "record": list(files), **result.summary(),
           "warnings": list(result.diagnostics.get("warnings", []))}
    for key in ("striker_velocity_m_per_s", "striker_velocity_band", "length_m"):
        if key in result.diagnostics:
            out[key] = result.diagnostics[key]
    out["toe_band"] = result.toe_band
    return out


def format_summary(summary: dict[str, Any]) -> str:
    """A short text version of the summary."""
    lines = [summary["title"] or ", ".join(Path(f).name for f in summary["record"]),
             f"method {summary['method']}: {summary['elements']} elements down to {summary['length_m']:.4g} m, "
             f"c = {summary['wave_speed_m_per_s']:.5g} m/s, head impedance "
             f"{summary['impedance_head_N_s_per_m']:.5g} N s/m"]
    if summary["toe_m"] is not None:
        band = summary["toe_band"]
        lines.append(f"toe / length: {summary['toe_m']:.4g} m" + (f" (90 %: {band[0]:.4g} to {band[1]:.4g} m)"
                                                                  if band else ""))
    if "striker_velocity_m_per_s" in summary:
        band = summary["striker_velocity_band"]
        lines.append(f"striker velocity: {summary['striker_velocity_m_per_s']:.4g} m/s"
                     + (f" (90 %: {band[0]:.4g} to {band[1]:.4g} m/s)" if band else ""))
    for a in summary["anomalies"]:
        lines.append(f"reflector at {a['depth']:.4g} m: beta = {a['beta']:.3g} ({a['beta_class']}), "
                     f"{a['length']:.4g} m long")
    return "\n".join(lines)


def write_files(result: IdentificationResult, spec: IdentifySpec, folder: Path) -> list[str]:
    """Write ``profile.csv``, ``identification.nc`` and ``spec.toml`` (when there was a spec text) into
    ``folder``; returns their names."""
    from .storage import save

    save_identification_csv(result, folder / CSV_FILE)
    save(result, folder / NETCDF_FILE)
    files = [CSV_FILE, NETCDF_FILE]
    if spec.text.strip():
        (folder / SPEC_FILE).write_text(spec.text, encoding="utf-8")
        files.append(SPEC_FILE)
    return files
