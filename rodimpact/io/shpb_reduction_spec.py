"""Split-Hopkinson-bar reduction specs: what ``rodimpact shpb reduce`` needs besides the recording (the Kolsky-bar
model's specs of ``rodimpact shpb predict`` are :mod:`rodimpact.io.shpb_spec`).

A recording is a LANL ``.raw`` file (its metadata sheet gives the bars, gauges and specimen; only the bridge
circuit is missing), a set of Tektronix ``.csv`` files (one channel each), a ``.tdms`` file or a plain CSV table
(``recording.format = "csv"``). A small TOML spec gives what the files lack or overrides what they hold: the
channels, a HopPyBar/LANL input sheet, the bars and their gauges, the specimen and the reduction settings
(docs/cli.md, ``rodimpact docs shpb-reduce``). Everything is optional where a sheet supplies it.

:func:`read_shot` turns a spec and the recording files into the reduction's inputs, :func:`run` reduces the shot
(:func:`rodimpact.shpb.reduce_shot`), :func:`summarize_run` and :func:`format_summary` report it and
:func:`write_files` writes its data files (the figures: :func:`rodimpact.output_folders.write_shpb_reduction`).
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence

import numpy as np

from .._result_files import write_new_file
from ..rods.material import Material
from ..shpb import Bar, GaugeSignals, ShpbReduction, SpecimenGeometry, find_windows, reduce_shot
from ..signals.gauges import Bridge, GaugedBar
from ..signals.recording import Recording
from .model import parse_toml, read_text_file
from .overrides import spec_with_overrides
from .quantities import ModelError
from .recordings import (_convert, _entry, hoppybar_bar, read_csv_recording, read_hoppybar_input, read_lanl_raw,
                         read_tdms, read_tektronix_csv)
from .schema import Field, Table, _q, _table_md, validate_table

# ============================================================================================ schema
FORMATS = {".raw": "lanl-raw", ".csv": "tektronix-csv", ".tdms": "tdms"}

RECORDING = Table("recording", "The recorded shot. Files given on the command line take the place of `files`.", (
    Field("files", "strings", "Recording files, relative to the spec: one LANL `.raw` or `.tdms` file or plain CSV "
                              "table, or one Tektronix `.csv` file per channel."),
    Field("format", "string", "File format; default from the first file's extension (`.raw` lanl-raw, `.csv` "
                              "tektronix-csv, `.tdms` tdms); `csv` is a plain table with a time column "
                              "(`rodimpact.io.read_csv_recording`).",
          choices=("lanl-raw", "tektronix-csv", "tdms", "csv")),
    Field("sheet", "string", "HopPyBar/LANL input sheet (`*_Input.dat`, relative to the spec) with the bars, gauges "
                             "and specimen; a LANL `.raw` file carries its own."),
    Field("incident_channels", "strings", "Channel(s) of the incident-bar gauges (several: opposite gauges, "
                                          "averaged); default `[\"incident\"]` for a `.raw` file, else the first "
                                          "channel."),
    Field("transmitted_channels", "strings", "Channel(s) of the transmitted-bar gauges; default "
                                             "`[\"transmitted\"]` for a `.raw` file, else the second channel."),
    _q("baseline_start", "time", "Start of the span whose mean is each channel's zero offset (with "
                                 "`baseline_end`); default: the samples before the channel's first pulse.",
       sign=None, required=False),
    _q("baseline_end", "time", "End of that span.", sign=None, required=False),
), '[recording]\nfiles = ["shot_Ch1.csv", "shot_Ch3.csv"]\nsheet = "shot_Input.dat"\nincident_channels = ["Ch1"]\n'
   'transmitted_channels = ["Ch3"]')

BAR = Table("bar", "One bar and its gauge station (`[incident_bar]`, `[transmitted_bar]`); keys given here replace the "
                   "sheet's.", (
    _q("youngs_modulus", "pressure", "Young's modulus E_b.", required=False),
    _q("density", "density", "Density (or `wave_speed`).", required=False),
    _q("wave_speed", "velocity", "Bar wave speed c_b instead of the density (density = E_b / c_b^2).",
       required=False),
    _q("diameter", "length", "Diameter of a round bar (or `area`).", required=False),
    _q("area", "area", "Cross-section area.", required=False),
    _q("gauge_distance", "length", "Distance from the gauge station to the specimen face.", sign="non_negative",
       required=False),
    _q("poisson_ratio", "dimensionless", "Poisson's ratio (for the dispersion correction).", sign="non_negative",
       required=False),
    Field("bridge", "string", "Bridge circuit: `quarter`, `half-axial`, `half-bending`, `half-poisson`, "
                              "`full-bending` or `full-poisson` (the sheets do not record it)."),
    Field("polarity", "integer", "-1 if the recorder shows compression as positive voltage.", default=1),
    _q("gauge_factor", "dimensionless", "Gauge factor.", required=False),
    _q("excitation_voltage", "voltage", "Bridge excitation voltage.", required=False),
    _q("gain", "dimensionless", "Amplifier gain (default: the sheet's gain of this shot).", sign=None,
       required=False),
), '[incident_bar]\nyoungs_modulus = "109.3 GPa"\nwave_speed = "4975 m/s"\ndiameter = "9.47 mm"\n'
   'gauge_distance = "381 mm"\nbridge = "half-axial"\ngauge_factor = 2.061\nexcitation_voltage = "8 V"\ngain = 200')

SPECIMEN = Table("specimen", "The specimen's initial size (default: the sheet's).", (
    _q("length", "length", "Initial length L0.", required=False),
    _q("diameter", "length", "Initial diameter (or `area`).", required=False),
    _q("area", "area", "Initial cross-section area A0.", required=False),
), '[specimen]\nlength = "3.204 mm"\ndiameter = "6.34 mm"')

REDUCTION = Table("reduction", "Pulse windows and the reduction (docs/shpb.md).", (
    _q("threshold", "dimensionless", "Incident arrival: this fraction of the record's peak.", default=0.1,
       required=False),
    _q("foot", "dimensionless", "The window starts where the pulse was last at or below this fraction of the "
                                "peak.", sign="non_negative", default=0.0, required=False),
    _q("incident_start", "time", "Start of the incident window at the gauge (replaces the one found).",
       sign=None, required=False),
    _q("reflected_start", "time", "Start of the reflected window at the gauge.", sign=None, required=False),
    _q("transmitted_start", "time", "Start of the transmitted window at the gauge.", sign=None, required=False),
    _q("duration", "time", "Length of the windows (replaces the one found).", required=False),
    Field("dispersion", "boolean", "Undo the Pochhammer-Chree dispersion between gauges and specimen.",
          default=False),
    _q("pass_limit", "dimensionless", "Equilibrium: largest R(t) of the pass band.", default=0.05, required=False),
    _q("review_limit", "dimensionless", "Equilibrium: largest R(t) of the review band.", default=0.10,
       required=False),
), '[reduction]\ndispersion = true\nreflected_start = "150.2 us"')

OUTPUT = Table("output", "What to write.", (Field("plots", "boolean", "Write the plots.", default=True),))

SPEC = Table("shpb spec", "Top level of a split-Hopkinson-bar reduction spec; every table is optional.", (
    Field("title", "string", "Short title."),
    Field("recording", "table", "The recording.", table=RECORDING),
    Field("incident_bar", "table", "The incident bar.", table=BAR),
    Field("transmitted_bar", "table", "The transmitted bar.", table=BAR),
    Field("specimen", "table", "The specimen.", table=SPECIMEN),
    Field("reduction", "table", "Reduction settings.", table=REDUCTION),
    Field("output", "table", "Output settings.", table=OUTPUT),
))


def spec_reference_markdown() -> str:
    """Reference tables of the spec keys (included in docs/cli.md)."""
    lines: list[str] = []
    for title, table in (("Top level", SPEC), ("`[recording]`", RECORDING),
                         ("`[incident_bar]` and `[transmitted_bar]`", BAR), ("`[specimen]`", SPECIMEN),
                         ("`[reduction]`", REDUCTION), ("`[output]`", OUTPUT)):
        _table_md(title, table, 4, lines)
    return "\n".join(lines) + "\n"


# ============================================================================================ spec objects
@dataclass(frozen=True)
class ReductionSpec:
    """A validated spec: ``values`` (the tables in SI, defaults filled in), the folder relative file names are
    read from, the spec's ``text`` as it ran (written as ``spec.toml``) and its ``name``."""

    values: dict
    base: Path
    text: str
    name: str

    @property
    def title(self) -> str:
        return self.values["title"] or ""

    @property
    def plots(self) -> bool:
        return self.values["output"]["plots"]


def load_spec(path: Optional[str | Path], overrides: Optional[Mapping[str, Any]] = None) -> ReductionSpec:
    """Read a spec file (``None``: no file, only ``overrides``); ``overrides``: key path -> value, set before the
    spec is validated (:mod:`rodimpact.io.overrides`)."""
    if path is None:
        return loads_spec("", ".", "options", overrides)
    p = Path(path)
    return loads_spec(read_text_file(p, str(p), "spec file"), p.parent, str(p), overrides)


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> ReductionSpec:
    """Read a spec from TOML text (``overrides`` as in :func:`load_spec`)."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given, name))


def _spec(raw: dict, base: Path, text: str, name: str) -> ReductionSpec:
    d = validate_table(SPEC, raw, "")
    for key, table in (("recording", RECORDING), ("incident_bar", BAR), ("transmitted_bar", BAR),
                       ("specimen", SPECIMEN), ("reduction", REDUCTION), ("output", OUTPUT)):
        d[key] = d[key] or validate_table(table, {}, key)
    for role in ("incident_bar", "transmitted_bar"):
        if d[role]["polarity"] not in (1, -1):
            raise ModelError(f"{role}.polarity: must be 1 or -1, got {d[role]['polarity']}")
    rec = d["recording"]
    if (rec["baseline_start"] is None) != (rec["baseline_end"] is None):
        raise ModelError("recording.baseline_start: give baseline_start and baseline_end together, or neither")
    return ReductionSpec(d, base, text, name)


# ============================================================================================ reading a shot
@dataclass(frozen=True)
class ShotInput:
    """What :func:`read_shot` read: the gauge strains, the bars, the specimen and the recording files."""

    signals: GaugeSignals
    incident_bar: Bar
    transmitted_bar: Bar
    specimen: SpecimenGeometry
    files: tuple[str, ...]


def read_shot(spec: ReductionSpec, files: Sequence[str | Path] = ()) -> ShotInput:
    """The recording (``files``, else ``recording.files`` of the spec) as gauge strains, with the bars and the
    specimen from the spec and the sheet; a missing value is a :class:`ModelError` naming its key."""
    rec_spec = spec.values["recording"]
    if files and rec_spec["files"]:
        raise ModelError("recording.files: the recording is given on the command line as well; give it once")
    paths = [Path(f) for f in files] or [spec.base / f for f in rec_spec["files"] or ()]
    if not paths:
        raise ModelError("recording.files: no recording given; name the file(s) on the command line")
    recording, sheet = _read_recording(paths, rec_spec, spec.base)
    channels = _channels(recording, rec_spec, bool(sheet is not None and recording.metadata.get("format")
                                                   == "lanl-raw"))
    gauges, bars = {}, {}
    for role in ("incident", "transmitted"):
        bars[role], gauges[role] = _bar(role, spec.values[f"{role}_bar"], sheet)
    baseline = ("auto" if rec_spec["baseline_start"] is None
                else (rec_spec["baseline_start"], rec_spec["baseline_end"]))
    signals = GaugeSignals.from_recording(recording, gauges["incident"], gauges["transmitted"], channels=channels,
                                          baseline=baseline)
    return ShotInput(signals, bars["incident"], bars["transmitted"], _specimen(spec.values["specimen"], sheet),
                     tuple(os.fspath(p) for p in paths))


def _read_recording(paths: list[Path], rec_spec: dict, base: Path) -> tuple[Recording, Optional[dict]]:
    """The recording and the metadata sheet (the ``.raw`` file's own, or ``recording.sheet``), if any."""
    fmt = rec_spec["format"] or FORMATS.get(paths[0].suffix.lower())
    if fmt is None:
        raise ModelError(f"recording.format: {paths[0].name}: unknown file type {paths[0].suffix!r}; give "
                         f"recording.format (lanl-raw, tektronix-csv, tdms, csv)")
    if fmt != "tektronix-csv" and len(paths) != 1:
        raise ModelError(f"recording.files: a {fmt} recording is one file, got {len(paths)}")
    reader = {"lanl-raw": read_lanl_raw, "tdms": read_tdms, "csv": read_csv_recording}
    recording = read_tektronix_csv(paths) if fmt == "tektronix-csv" else reader[fmt](paths[0])
    sheet = recording.metadata if fmt == "lanl-raw" else None
    if rec_spec["sheet"] is not None:
        sheet = read_hoppybar_input(base / rec_spec["sheet"])
    return recording, sheet


def _channels(recording: Recording, rec_spec: dict, lanl: bool) -> tuple[list[str], list[str]]:
    names = recording.channel_names
    out = []
    for i, role in enumerate(("incident", "transmitted")):
        given = rec_spec[f"{role}_channels"]
        if given is not None:
            out.append(list(given))
        elif lanl:
            out.append([role])
        elif len(names) == 2:
            out.append([names[i]])
        else:
            raise ModelError(f"recording.{role}_channels: missing; the recording has {len(names)} channels "
                             f"({', '.join(names)}): say which are the {role} bar's")
    return out[0], out[1]


def _bar(role: str, given: dict, sheet: Optional[dict]) -> tuple[Bar, Optional[GaugedBar]]:
    """The bar and its gauge (``None`` for strain channels) from the spec's ``[<role>_bar]`` and the sheet."""
    path = f"{role}_bar"
    if given["bridge"] is not None:
        try:
            Bridge.named(given["bridge"], given["poisson_ratio"] if given["poisson_ratio"] is not None else 0.3)
        except ValueError as exc:
            raise ModelError(f"{path}.bridge: {exc}") from None
    from_sheet: Optional[GaugedBar] = None
    if sheet is not None:
        if given["bridge"] is None:
            raise ModelError(f"{path}.bridge: missing; the LANL and HopPyBar sheets do not record the bridge "
                             f"circuit: give it (--bridge half-axial, or {path}.bridge in a spec)")
        try:
            from_sheet = hoppybar_bar(sheet, role, bridge=given["bridge"], polarity=given["polarity"],
                                      gain="shot" if given["gain"] is None else given["gain"])
        except ValueError as exc:
            raise ModelError(f"{path}: from the sheet: {exc}") from None

    def value(key: str, attribute: Optional[str] = None) -> Any:
        if given[key] is not None:
            return given[key]
        if from_sheet is not None and attribute is not None:
            return getattr(from_sheet, attribute)
        raise ModelError(f"{path}.{key}: missing (no sheet gives it); give it in the spec")

    youngs = value("youngs_modulus", "youngs_modulus")
    if given["density"] is not None and given["wave_speed"] is not None:
        raise ModelError(f"{path}.wave_speed: give density or wave_speed, not both")
    density = youngs / given["wave_speed"] ** 2 if given["wave_speed"] is not None else value("density", "density")
    if given["diameter"] is not None and given["area"] is not None:
        raise ModelError(f"{path}.area: give diameter or area, not both")
    area = math.pi * given["diameter"] ** 2 / 4 if given["diameter"] is not None else value("area", "area")
    distance = given["gauge_distance"]
    if distance is None:
        distance = _sheet_length(sheet, f"{role.capitalize()} Bar Strain Gage Location", f"{path}.gauge_distance")
    poisson = given["poisson_ratio"] if given["poisson_ratio"] is not None else (
        from_sheet.poisson_ratio if from_sheet is not None else None)
    bar = Bar(material=Material(youngs, density, f"{role} bar"), area=area, gauge_distance=distance,
              poisson_ratio=poisson, name=role)
    gauge = _gauge(path, given, from_sheet, youngs, density, area, poisson)
    return bar, gauge


def _gauge(path: str, given: dict, from_sheet: Optional[GaugedBar], youngs: float, density: float, area: float,
           poisson: Optional[float]) -> Optional[GaugedBar]:
    """The bar's gauge: the sheet's with the spec's values put in, or the spec's alone (``None`` if it gives no
    gauge: the channels are then strains)."""
    keys = ("bridge", "gauge_factor", "excitation_voltage")
    if from_sheet is None and all(given[k] is None for k in keys):
        return None
    if from_sheet is None:
        missing = [k for k in keys if given[k] is None]
        if missing:
            raise ModelError(f"{path}.{missing[0]}: missing; a gauge needs bridge, gauge_factor and "
                             f"excitation_voltage (or a sheet)")
        return GaugedBar(youngs, density, area, given["gauge_factor"], given["excitation_voltage"],
                         1.0 if given["gain"] is None else given["gain"], given["bridge"], given["polarity"],
                         poisson)
    changes = {k: given[k] for k in ("gauge_factor", "excitation_voltage") if given[k] is not None}
    return replace(from_sheet, youngs_modulus=youngs, density=density, area=area, poisson_ratio=poisson, **changes)


def _specimen(given: dict, sheet: Optional[dict]) -> SpecimenGeometry:
    length = given["length"]
    if length is None:
        length = _sheet_length(sheet, "Initial Sample Length", "specimen.length")
    if given["diameter"] is not None and given["area"] is not None:
        raise ModelError("specimen.area: give diameter or area, not both")
    if given["area"] is not None:
        return SpecimenGeometry(length=length, area=given["area"])
    diameter = given["diameter"]
    if diameter is None:
        diameter = _sheet_length(sheet, "Initial Sample Diameter", "specimen.diameter")
    return SpecimenGeometry(length=length, diameter=diameter)


def _sheet_length(sheet: Optional[dict], entry: str, key: str) -> float:
    """A length entry of the sheet in m; a :class:`ModelError` naming ``key`` when there is none."""
    if sheet is None:
        raise ModelError(f"{key}: missing (no sheet gives it); give it in the spec")
    try:
        value, unit, name = _entry(sheet, entry)
        return _convert(value, unit, "length", name)
    except ValueError as exc:
        raise ModelError(f"{key}: missing; the sheet: {exc}") from None


# ============================================================================================ running
#: The data files of a reduction's output folder.
CSV_FILE, NETCDF_FILE, SPEC_FILE = "reduction.csv", "reduction.nc", "spec.toml"


def run(spec: ReductionSpec, shot: ShotInput) -> ShpbReduction:
    """Reduce the shot with the spec's windows and settings (:func:`rodimpact.shpb.reduce_shot`)."""
    r = spec.values["reduction"]
    windows = find_windows(shot.signals, shot.incident_bar, shot.transmitted_bar, threshold=r["threshold"],
                           foot=r["foot"], incident=r["incident_start"], reflected=r["reflected_start"],
                           transmitted=r["transmitted_start"], duration=r["duration"])
    return reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=windows,
                       dispersion=r["dispersion"], bands=(r["pass_limit"], r["review_limit"]))


def summarize_run(reduction: ShpbReduction, spec: ReductionSpec, shot: ShotInput) -> dict[str, Any]:
    """The reduction's numbers (JSON-ready, SI units; :meth:`ShpbReduction.summary`) with the title, the recording
    files and the bars."""
    bars = {role: {"youngs_modulus_Pa": bar.youngs_modulus, "wave_speed_m_s": bar.wave_speed,
                   "diameter_m": bar.diameter, "gauge_distance_m": bar.gauge_distance}
            for role, bar in (("incident", shot.incident_bar), ("transmitted", shot.transmitted_bar))}
    return {"title": spec.title, "recording": list(shot.files), "bars": bars, **reduction.summary(),
            "warnings": []}


def format_summary(summary: dict[str, Any]) -> str:
    """A short text version of the summary."""
    us = 1e6
    sp, eq, w = summary, summary["equilibrium"], summary["windows"]
    lines = [summary["title"] or ", ".join(Path(f).name for f in summary["recording"])]
    bar = summary["bars"]["incident"]
    lines.append(f"specimen {sp['specimen_length_m'] * 1e3:.4g} mm long, {sp['specimen_diameter_m'] * 1e3:.4g} mm "
                 f"diameter; incident bar E {bar['youngs_modulus_Pa'] / 1e9:.4g} GPa, c {bar['wave_speed_m_s']:.5g} "
                 f"m/s, d {bar['diameter_m'] * 1e3:.4g} mm, gauge {bar['gauge_distance_m'] * 1e3:.4g} mm from the "
                 f"specimen" + ("; dispersion corrected" if sp["dispersion_corrected"] else ""))
    lines.append("windows at the gauges: " + ", ".join(
        f"{name} {w[name]['start_s'] * us:.4g} us{' (given)' if w[name]['given'] else ''}" for name in w)
        + f", {w['incident']['duration_s'] * us:.4g} us long")
    if eq["equilibrium_time_s"] is None:
        lines.append(f"equilibrium: R exceeds the pass band ({eq['pass_limit']:.0%}) at the loading end "
                     f"({eq['loading_end_s'] * us:.4g} us): not in equilibrium")
    else:
        lines.append(f"equilibrium (R <= {eq['pass_limit']:.0%}) from {eq['equilibrium_time_s'] * us:.4g} us, "
                     f"strain {eq['strain_at_equilibrium']:.3g}, to the loading end {eq['loading_end_s'] * us:.4g} us")
    if eq["review_time_s"] is not None:
        lines.append(f"review band (R <= {eq['review_limit']:.0%}) from {eq['review_time_s'] * us:.4g} us")
    where = "in equilibrium" if eq["equilibrium_time_s"] is not None else "over the loading"
    for name, a in summary["analyses"].items():
        lines.append(f"{name}: peak stress {a['peak_stress_Pa'] / 1e6:.4g} MPa, final strain {a['final_strain']:.3g}, "
                     f"mean strain rate {a['mean_strain_rate_per_s']:.4g} 1/s {where}")
    lines.append("specimen stress, strain and strain rate are positive in compression")
    return "\n".join(lines)


def save_reduction_csv(reduction: ShpbReduction, path: str | Path, *, overwrite: bool = False) -> Path:
    """Write the time series of a reduction as one CSV table (:meth:`ShpbReduction.table`: a header row of
    ``name [unit]``, then one row per sample, numbers as Python writes them back exactly). An existing file is
    refused (``FileExistsError`` naming it) unless ``overwrite=True``; written under a temporary name and moved
    into place."""
    if not isinstance(reduction, ShpbReduction):
        raise TypeError(f"reduction: must be a rodimpact.shpb.ShpbReduction, got {type(reduction).__name__}")
    header, columns = reduction.table()

    def write(tmp: Path) -> None:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            out = csv.writer(fh, lineterminator="\n")
            out.writerow(header)
            out.writerows(np.column_stack(columns).tolist())

    return write_new_file(path, write, overwrite)


def write_files(reduction: ShpbReduction, spec: ReductionSpec, folder: Path) -> list[str]:
    """Write the data files of a reduction into ``folder``: ``reduction.csv`` (:func:`save_reduction_csv`),
    ``reduction.nc`` (:func:`rodimpact.save`, read back by :func:`rodimpact.load`) and ``spec.toml`` (the spec as
    it ran, when there was a spec file or options set keys); returns their names."""
    from .storage import save

    save_reduction_csv(reduction, folder / CSV_FILE)
    save(reduction, folder / NETCDF_FILE)
    files = [CSV_FILE, NETCDF_FILE]
    if spec.text.strip():
        (folder / SPEC_FILE).write_text(spec.text, encoding="utf-8")
        files.append(SPEC_FILE)
    return files
