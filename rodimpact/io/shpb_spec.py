"""Kolsky-bar specifications: TOML files for ``rodimpact shpb predict`` (the split-Hopkinson bar's forward model,
:class:`rodimpact.shpb.KolskyBar`).

A spec gives the bars (``[bars.incident]``, ``[bars.transmitted]``, optional ``[bars.striker]`` and
``[bars.momentum_trap]``, each with the keys of a model file's ``[[rods]]``: segments of any shape or
impedance-level elements, materials, units), the ``[specimen]`` and an optional pulse ``[shaper]`` (the keys of the
``specimen`` and ``pulse-shaper`` junctions of model files, with their nested ``law = { type = ... }``, built from
the classes' declarations), the gauge stations ``[gauges.incident]`` and ``[gauges.transmitted]``, the ``[input]``
(the striker's velocity or a measured incident pulse from a CSV file) and the ``[simulation]`` settings.
:func:`load_spec` builds the :class:`~rodimpact.shpb.KolskyBar` (errors name the spec's keys: ``specimen.law.b:
must be >= 0, got -1 MPa``), :func:`run` predicts, :func:`write_files` writes the data files (the command line's
folder with figures: :mod:`rodimpact.output_folders`).

Signs: bar strains are tension positive (an incident compressive pulse is negative); the specimen's stress, strain
and strain rate are compression positive. Keys: docs/cli.md (generated from :data:`SHPB_SPEC` by
:func:`spec_reference_markdown`).
"""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional

import numpy as np

from .._result_files import netcdf_engine
from ..rods.declared import ELEMENTS
from ..rods.rod import Rod
from ..shpb import Gauge, KolskyBar, KolskyPrediction
from ..shpb.plateau import rate_plateau
from ..signals.gauges import BRIDGE_NAMES
from .dimensions import Parameters
from .keypaths import SHPB_KEYS, translated
from .model import _element, _materials, _rod, _wrap, parse_toml, read_csv_columns, read_text_file
from .overrides import spec_with_overrides
from .quantities import ModelError
from .results import _write_csv
from .schema import JUNCTION_TYPES, MATERIAL, ROD, Field, Table, _q, _table_md, validate_table

# ============================================================================================ schema
BAR = Table("bars.NAME", "A bar, the striker or the momentum trap, with the keys of a model file's `[[rods]]` but "
                         "`name`, `velocity` and `initial`: `[[bars.NAME.segments]]` (geometry, any shape; keys: "
                         "`rodimpact docs model`) or `[bars.NAME.elements]` (impedance level, e.g. the `striker.csv` "
                         "of `rodimpact design` as the striker; not for the incident and transmitted bars, whose "
                         "gauges read N / (E A)). The striker hits the incident bar's left end; the incident bar's "
                         "right end and the transmitted bar's left end touch the specimen.",
            tuple(f for f in ROD.fields if f.name in ("material", "segments", "elements")),
            '[bars.incident]\nmaterial = "ti-6al-4v"\n\n[[bars.incident.segments]]\nshape = "cylinder"\n'
            'length = "1 m"\ndiameter = "9.47 mm"')

BARS = Table("bars", "The bars.", (
    Field("striker", "table", "The striker; needed with `input.striker_velocity`.", table=BAR),
    Field("incident", "table", "The incident bar.", table=BAR, required=True),
    Field("transmitted", "table", "The transmitted bar.", table=BAR, required=True),
    Field("momentum_trap", "table", "A bar in unilateral contact behind the transmitted bar; without one, the "
                                    "transmitted bar's far end is free.", table=BAR),
))

SPECIMEN = dataclasses.replace(JUNCTION_TYPES["specimen"], name="specimen", example=(
    '[specimen]\ndiameter = "6.34 mm"\nlength = "3.204 mm"\nlaw = { type = "elastic-plastic", '
    'youngs_modulus = "117 GPa", yield_stress = "90 MPa", hardening = "300 MPa" }'))
SHAPER = dataclasses.replace(JUNCTION_TYPES["pulse-shaper"], name="shaper", example=(
    '[shaper]\ndiameter = "4 mm"\nthickness = "1 mm"\nlaw = { type = "frew", stress = "360 MPa", n = 0.3, m = 2.0 }'))

GAUGE = Table("gauges.NAME", "A strain-gauge station on the incident or the transmitted bar "
                             "(`rodimpact.shpb.Gauge`). With `gauge_factor` and `excitation_voltage` the gauge's "
                             "voltage is predicted too: polarity x gain x excitation x the exact bridge output.", (
    _q("distance", "length", "Distance from the bar's specimen face."),
    Field("bridge", "string", "Wheatstone bridge of the gauges.", default="quarter", choices=BRIDGE_NAMES),
    _q("gauge_factor", "dimensionless", "Gauge factor (with `excitation_voltage`).", required=False),
    _q("excitation_voltage", "voltage", "Bridge excitation voltage (with `gauge_factor`).", required=False),
    _q("gain", "dimensionless", "Amplifier gain.", required=False, default=1.0),
    Field("polarity", "integer", "`1`, or `-1` where compression was recorded as a positive voltage.", default=1),
    _q("poisson_ratio", "dimensionless", "Poisson's ratio of the bar, for the `half-poisson` and `full-poisson` "
                                         "bridges.", sign=None, required=False),
), '[gauges.incident]\ndistance = "381 mm"\ngauge_factor = 2.061\nexcitation_voltage = "8 V"\ngain = 200')

GAUGES = Table("gauges", "The gauge stations.", (
    Field("incident", "table", "On the incident bar.", table=GAUGE, required=True),
    Field("transmitted", "table", "On the transmitted bar.", table=GAUGE, required=True),
))

PULSE = Table("input.incident_pulse", "A measured incident pulse: a CSV file with a column `time` and a column "
                                      "`strain` (units in the header, e.g. `time [us]`, `strain [-]` or `strain "
                                      "[microstrain]`; default SI; lines starting with `#` are comments), tension "
                                      "positive, zero outside the pulse. It drives the incident bar so that it "
                                      "passes the incident gauge as recorded; the prediction keeps the record's "
                                      "clock.", (
    Field("file", "string", "CSV file, relative to the spec.", required=True),))

INPUT = Table("input", "What loads the bars: exactly one of the two keys.", (
    _q("striker_velocity", "velocity", "Impact velocity of `[bars.striker]` towards the incident bar.",
       required=False),
    Field("incident_pulse", "table", "A measured incident pulse instead of the striker: `{ file = \"...\" }`. "
                                     "The striker and the shaper are then not simulated (the pulse is what they "
                                     "made).", table=PULSE),
), '[input]\nstriker_velocity = "10 m/s"\n# incident_pulse = { file = "incident.csv" }')

SIMULATION = Table("simulation", "Run settings.", (
    _q("dt", "time", "Time step = travel time of every bar element; default: every segment >= 4 and the longest "
                     "bar >= 200 elements.", required=False),
    _q("duration", "time", "Simulated time; default: until the transmitted pulse has passed its gauge.",
       required=False),
    Field("backend", "string", "`numba` (compiled) or `numpy` (reference).", default="numba",
          choices=("numba", "numpy")),
    Field("specimen_inertia", "boolean", "Give the specimen its mass: its elastic part a rod of the lattice (needs "
                                         "`specimen.density`), its inelastic part a massless law joint "
                                         "(`KolskyBar(specimen_inertia=True)`, docs/shpb.md).", default=False),
), '[simulation]\ndt = "0.2 us"')

SHPB_OUTPUT = Table("output", "What to write.", (Field("plots", "boolean", "Write the plots.", default=True),))

SHPB_SPEC = Table("Kolsky-bar spec", "Top level of a Kolsky-bar spec.", (
    Field("title", "string", "Short title."),
    Field("description", "string", "Free text."),
    Field("parameters", "parameters", "Named constants for expressions, converted to SI."),
    Field("materials", "mapping", "Named materials (as in model files).", table=MATERIAL),
    Field("bars", "table", "The striker, the incident and transmitted bars and the momentum trap.", table=BARS,
          required=True),
    Field("specimen", "table", "The specimen between the incident and the transmitted bar.", table=SPECIMEN,
          required=True),
    Field("shaper", "table", "A pulse shaper between the striker and the incident bar.", table=SHAPER),
    Field("gauges", "table", "The gauge stations.", table=GAUGES, required=True),
    Field("input", "table", "What loads the bars: `striker_velocity` (with `[bars.striker]`) or a measured "
                            "`incident_pulse`.", table=INPUT, required=True),
    Field("simulation", "table", "Run settings.", table=SIMULATION),
    Field("output", "table", "Output settings.", table=SHPB_OUTPUT),
))


def spec_reference_markdown() -> str:
    """Reference tables of the Kolsky-bar spec keys (docs/cli.md, ``rodimpact docs shpb``)."""
    lines: list[str] = []
    for title, table in (("Kolsky-bar spec, top level", SHPB_SPEC), ("`[bars.NAME]`", BAR),
                         ("`[specimen]`", SPECIMEN), ("`[shaper]`", SHAPER), ("`[gauges.NAME]`", GAUGE),
                         ("`[input]`", INPUT), ("`[input.incident_pulse]`", PULSE), ("`[simulation]`", SIMULATION),
                         ("`[output]`", SHPB_OUTPUT)):
        _table_md(title, table, 4, lines)
    lines.append("`NAME` is `striker`, `incident`, `transmitted` or `momentum_trap` for bars and `incident` or "
                 "`transmitted` for gauges. The `law` of the specimen and the shaper takes the keys of the "
                 "constitutive laws of model files (`rodimpact docs model`, 'Constitutive laws'), stresses and "
                 "strains positive in compression.")
    return "\n".join(lines) + "\n"


# ============================================================================================ spec objects
@dataclass(frozen=True, eq=False)
class ShpbSpec:
    """A validated Kolsky-bar spec: the :class:`~rodimpact.shpb.KolskyBar` and the arguments of its
    :meth:`~rodimpact.shpb.KolskyBar.predict` (``striker_velocity`` in m/s, or ``incident_pulse`` samples (time
    in s, strain tension positive); ``dt``, ``duration`` in s or ``None`` for the defaults), plus output
    settings."""

    kolsky: KolskyBar
    striker_velocity: Optional[float]
    incident_pulse: Optional[tuple[np.ndarray, np.ndarray]]
    dt: Optional[float] = None
    duration: Optional[float] = None
    backend: str = "numba"
    plots: bool = True
    title: str = ""
    text: str = ""
    pulse_file: Optional[str] = None
    source: Optional[Path] = None

    def predict(self) -> KolskyPrediction:
        """Run :meth:`KolskyBar.predict` with these settings; errors name the spec's keys (``simulation.dt``,
        ``bars.incident``; :data:`rodimpact.io.keypaths.SHPB_KEYS`)."""
        kb = self.kolsky
        bars = (["striker"] if self.incident_pulse is None else []) + ["incident"] \
            + (["specimen"] if kb.specimen_inertia else []) + ["transmitted"] \
            + (["momentum_trap"] if kb.momentum_trap is not None else [])
        try:
            return kb.predict(self.striker_velocity, incident_pulse=self.incident_pulse, duration=self.duration,
                              dt=self.dt, backend=self.backend)
        except ModelError:
            raise
        except (ValueError, TypeError) as exc:     # the system's rods are the bars, in this order
            raise translated(exc, {**SHPB_KEYS, **{f"rods[{i}]": b if b == "specimen" else f"bars.{b}"
                                                   for i, b in enumerate(bars)}}) from None


def load_spec(path: str | Path, overrides: Optional[Mapping[str, Any]] = None) -> ShpbSpec:
    """Read a Kolsky-bar spec file (relative file names are resolved against its folder); ``overrides``: key path
    -> value, set before the spec is validated (:mod:`rodimpact.io.overrides`)."""
    p = Path(path)
    spec = loads_spec(read_text_file(p, str(p), "spec file"), p.parent, str(p), overrides)
    object.__setattr__(spec, "source", p)
    return spec


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> ShpbSpec:
    """Read a Kolsky-bar spec from TOML text (``overrides`` as in :func:`load_spec`)."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given))


def _spec(raw: dict, base: Path, text: str) -> ShpbSpec:
    """The validated spec of the parsed file ``raw`` (``text``: the file as given)."""
    d = validate_table(SHPB_SPEC, raw, "")
    params = Parameters(d["parameters"] or {}, raw.get("parameters") or {})
    materials = _materials(d["materials"] or {})
    sim = d["simulation"] or validate_table(SIMULATION, {}, "simulation")
    bars: dict[str, Rod] = {}
    for name, b in d["bars"].items():
        if b is not None:
            bars[name] = _rod({**b, "name": name, "initial": None}, f"bars.{name}", materials, params, sim["dt"], base,
                              raw["bars"][name])[0]
    specimen = _element("junction", {**d["specimen"], "type": "specimen"}, "specimen", params, base)
    shaper = None if d["shaper"] is None else _element("junction", {**d["shaper"], "type": "pulse-shaper"},
                                                        "shaper", params, base)
    gauges = {name: _gauge(g, f"gauges.{name}") for name, g in d["gauges"].items()}
    velocity, pulse_file = d["input"]["striker_velocity"], (d["input"]["incident_pulse"] or {}).get("file")
    if (velocity is None) == (pulse_file is None):
        raise ModelError("input: give exactly one of striker_velocity (with [bars.striker]) or incident_pulse = "
                         "{ file = \"...\" } (a measured pulse), " + ("not both" if velocity is not None else
                                                                     "got neither"))
    if velocity is not None and "striker" not in bars:
        raise ModelError("input.striker_velocity: needs a striker: give [bars.striker], or a measured "
                         "input.incident_pulse instead")
    try:
        kolsky = KolskyBar(bars["incident"], bars["transmitted"], specimen, gauges["incident"],
                           gauges["transmitted"], bars.get("striker"), shaper, bars.get("momentum_trap"),
                           sim["specimen_inertia"])
    except (ValueError, TypeError) as exc:        # errors name the spec's keys, not KolskyBar's fields
        raise translated(exc, SHPB_KEYS) from None
    out = d["output"] or {"plots": True}
    return ShpbSpec(kolsky, velocity, None if pulse_file is None else _pulse(base, pulse_file), sim["dt"],
                    sim["duration"], sim["backend"], out["plots"], d["title"] or "", text, pulse_file)


def _gauge(g: dict, path: str) -> Gauge:
    """The :class:`Gauge` of a validated ``[gauges.NAME]`` table (its keys are the class's fields)."""
    if (g["gauge_factor"] is None) != (g["excitation_voltage"] is None):
        missing = "gauge_factor" if g["gauge_factor"] is None else "excitation_voltage"
        raise ModelError(f"{path}.{missing}: missing; give gauge_factor and excitation_voltage together (to "
                         "predict volts) or neither")
    if g["bridge"].endswith("poisson") and g["poisson_ratio"] is None:
        raise ModelError(f"{path}.poisson_ratio: missing; the {g['bridge']!r} bridge needs the bar's Poisson ratio")
    return _wrap(path, lambda: Gauge(**g), "Gauge")


def _pulse(base: Path, name: str) -> tuple[np.ndarray, np.ndarray]:
    """The samples (time in s, strain) of a measured incident pulse file, times strictly increasing."""
    key = "input.incident_pulse.file"
    cols = read_csv_columns(base / name, key, {"time": "time", "strain": "dimensionless"}, needed=("time", "strain"))
    t = cols["time"]
    if t.size < 2:
        raise ModelError(f"{key}: {name} needs at least two rows of samples, got {t.size}")
    steps = np.diff(t)
    if not np.all(steps > 0.0):
        k = int(np.argmax(~(steps > 0.0)))
        raise ModelError(f"{key}: {name}, data rows {k + 1} and {k + 2}: the times must increase strictly, got "
                         f"{t[k]!r} s and then {t[k + 1]!r} s")
    return t, cols["strain"]


# ============================================================================================ running, saving
@dataclass
class ShpbRun:
    """A Kolsky-bar prediction with the warnings raised while it ran (equilibrium validity, ...)."""

    prediction: KolskyPrediction
    warnings: list[str] = field(default_factory=list)


def run(spec: ShpbSpec) -> ShpbRun:
    """Predict the gauge signals and the specimen's histories of ``spec``."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        prediction = spec.predict()
    return ShpbRun(prediction, [str(w.message) for w in caught])


def _peak(x: np.ndarray) -> float:
    """The value of largest magnitude, with its sign."""
    return float(x[int(np.argmax(np.abs(x)))])


def summarize_run(r: ShpbRun, spec: ShpbSpec) -> dict[str, Any]:
    """Key numbers of a prediction (JSON-ready, SI units): the peak strains at the gauges (tension positive, the
    value of largest magnitude), the specimen's largest strain and stress (compression positive) and its mean
    strain rate over the plateau (:func:`rodimpact.shpb.plateau.rate_plateau`)."""
    p = r.prediction
    plateau = rate_plateau(p.time, p.force, p.strain_rate)
    return {
        "title": spec.title,
        "input": ({"striker_velocity_m_s": spec.striker_velocity} if spec.incident_pulse is None
                  else {"incident_pulse_file": spec.pulse_file}),
        "dt_s": p.result.dt, "steps": int(p.time.size), "start_time_s": float(p.time[0]),
        "peak_incident_strain": _peak(p.incident), "peak_reflected_strain": _peak(p.reflected),
        "peak_transmitted_strain": _peak(p.transmitted),
        "peak_volts": {name: _peak(v) for name, v in p.volts.items()},
        "specimen_max_strain": float(p.strain.max()), "specimen_max_true_strain": float(p.true_strain.max()),
        "specimen_max_stress_Pa": float(p.stress.max()), "specimen_max_true_stress_Pa": float(p.true_stress.max()),
        "strain_rate_plateau": None if plateau is None else {
            "mean_1_per_s": plateau.mean, "start_s": plateau.start, "end_s": plateau.end,
            "flatness": plateau.flatness,
            "rule": "the samples around the largest specimen force where the force is at least half of it"},
        "warnings": list(r.warnings)}


def format_summary(s: dict[str, Any], spec: ShpbSpec) -> str:
    """A short text version of the summary."""
    lines = [spec.title] if spec.title else []
    loading = (f"striker at {s['input']['striker_velocity_m_s']:.4g} m/s" if "striker_velocity_m_s" in s["input"]
               else f"measured incident pulse {s['input']['incident_pulse_file']}")
    lines.append(f"Kolsky bar: {loading}; dt {s['dt_s'] * 1e6:.4g} us, {s['steps']} steps")
    lines.append(f"incident gauge: peak incident strain {s['peak_incident_strain']:.4g}, peak reflected strain "
                 f"{s['peak_reflected_strain']:.4g} (tension positive)")
    lines.append(f"transmitted gauge: peak strain {s['peak_transmitted_strain']:.4g}")
    for name, v in s["peak_volts"].items():
        lines.append(f"{name.replace('_', ' ')}: peak voltage {v:.4g} V")
    lines.append(f"specimen (compression positive): max strain {s['specimen_max_strain']:.4g} (true "
                 f"{s['specimen_max_true_strain']:.4g}), max stress {s['specimen_max_stress_Pa'] / 1e6:.4g} MPa "
                 f"(true {s['specimen_max_true_stress_Pa'] / 1e6:.4g} MPa)")
    pl = s["strain_rate_plateau"]
    lines.append("strain rate: the specimen is never compressed" if pl is None else
                 f"strain rate: mean {pl['mean_1_per_s']:.4g} 1/s over the plateau {pl['start_s'] * 1e6:.4g} .. "
                 f"{pl['end_s'] * 1e6:.4g} us (force >= half its peak; flatness {pl['flatness'] * 100:.3g} %)")
    return "\n".join(lines)


#: The files of a prediction folder (besides ``plots/`` and ``summary.json``).
SIGNALS_FILE, PREDICTION_FILE = "signals.csv", "prediction.nc"


def write_files(r: ShpbRun, spec: ShpbSpec, folder: Path) -> list[str]:
    """Write the data files of a prediction into the (new) ``folder`` and return their names: ``spec.toml`` (the
    spec as it ran), ``signals.csv`` (one row per step: the variables of ``prediction.nc`` with their units in the
    header, ``[-]`` for strains) and ``prediction.nc`` (:meth:`KolskyPrediction.to_xarray`). The command line's
    output folder adds ``plots/`` and ``summary.json`` (:func:`rodimpact.output_folders.write_shpb_prediction`)."""
    (folder / "spec.toml").write_text(spec.text, encoding="utf-8")
    ds = r.prediction.to_xarray()
    if spec.title:
        ds.attrs["title"] = spec.title
    names = list(ds.data_vars)
    units = ["-" if ds[n].attrs["units"] == "1" else ds[n].attrs["units"] for n in names]
    _write_csv(folder / SIGNALS_FILE, ["time [s]"] + [f"{n} [{u}]" for n, u in zip(names, units)],
               [ds["time"].values] + [ds[n].values for n in names])
    ds.to_netcdf(folder / PREDICTION_FILE, engine=netcdf_engine())
    return ["spec.toml", SIGNALS_FILE, PREDICTION_FILE]


# ============================================================================================ template
TEMPLATE = '''\
# rodimpact Kolsky-bar spec -- run it with:   rodimpact shpb predict shpb.toml -o results/shpb
#
# Predicts the gauge signals of a split-Hopkinson (Kolsky) pressure bar test and the specimen's stress, strain and
# strain rate (rodimpact.shpb.KolskyBar): the bars are exact 1-D rods; the specimen (and an optional pulse
# shaper) is a massless deformable joint whose constitutive law is solved in every step. Quantities take units
# ("9.47 mm", "10 m/s"); bare numbers are SI. Signs: bar strains are tension positive (the incident pulse is
# negative); the specimen's stress, strain and strain rate are compression positive. All keys: rodimpact docs shpb.
#
# This template: a shot like LANL's standard copper test (HopPyBar, 2006-12-01): Ti-6Al-4V bars of 9.47 mm, a
# 127 mm striker at about 10 m/s, gauges 381 mm from the specimen, an annealed OFE copper specimen of 6.34 mm x
# 3.204 mm. The shot's sheet does not give the bar lengths: 1 m is assumed.

title = "LANL-like copper shot"

# The bars' material as the shot's sheet gives it: E = 109.3 GPa, rho = 4416 kg/m^3 (bar wave speed 4975 m/s).
[materials.lanl-ti-6al-4v]
youngs_modulus = "109.3 GPa"
density = "4416 kg/m^3"

# ------------------------------------------------------------------------------------------------ bars
# Each bar takes the keys of [[rods]] in model files: segments of any shape (or, for the striker only,
# [bars.striker.elements], e.g. file = "striker.csv" written by rodimpact design). The striker hits the incident
# bar's left end; the specimen sits between the incident bar's right end and the transmitted bar's left end.
[bars.striker]
material = "lanl-ti-6al-4v"

[[bars.striker.segments]]
shape = "cylinder"
length = "127 mm"
diameter = "9.47 mm"

[bars.incident]
material = "lanl-ti-6al-4v"

[[bars.incident.segments]]
shape = "cylinder"
length = "1 m"
diameter = "9.47 mm"

[bars.transmitted]
material = "lanl-ti-6al-4v"

[[bars.transmitted.segments]]
shape = "cylinder"
length = "1 m"
diameter = "9.47 mm"

# A momentum trap in contact behind the transmitted bar (without one its far end is free):
# [bars.momentum_trap]
# material = "lanl-ti-6al-4v"
# [[bars.momentum_trap.segments]]
# shape = "cylinder"
# length = "0.3 m"
# diameter = "9.47 mm"

# ------------------------------------------------------------------------------------------- specimen
# The keys of the "specimen" junction of model files. Its law (stress and strain positive in compression) is one
# of {laws} (keys: rodimpact docs model).
[specimen]
diameter = "6.34 mm"
length = "3.204 mm"
measure = "true"               # large strain: the law sees true strain and rate, the area grows as A0 / (1 - eps)
density = "8960 kg/m^3"        # with it, a warning when the specimen is too long for equilibrium during the rise

# Johnson-Cook constants of OFHC copper: A = 90 MPa, B = 292 MPa, n = 0.31, C = 0.025, m = 1.09, T_melt = 1356 K
# at a reference rate of 1 1/s (G. R. Johnson and W. H. Cook, Eng. Fract. Mech. 21 (1985) 31-48, Table 1; the
# strength constants of their 1983 paper). The shot's copper was annealed (600 C, 1 h) and is softer: fit A, B
# and n to a shot before trusting a prediction. E = 117 GPa is copper's Young's modulus.
[specimen.law]
type = "johnson-cook"
youngs_modulus = "117 GPa"
a = "90 MPa"
b = "292 MPa"
n = 0.31
c = 0.025
m = 1.09
reference_rate = "1 1/s"
temperature = "273.15 K"       # the shot ran at 0 C; below room temperature (293.15 K) the thermal factor is 1
melting_temperature = "1356 K"

# A pulse shaper between the striker and the incident bar (the keys of the "pulse-shaper" junction), e.g. an
# annealed copper disc with the law of Frew, Forrestal and Chen (Exp. Mech. 42 (2002) 93-106):
# [shaper]
# diameter = "4 mm"
# thickness = "1 mm"
# law = { type = "frew", stress = "360 MPa", n = 0.3, m = 2.0 }

# ---------------------------------------------------------------------------------------------- gauges
# Stations at a distance from the bar's specimen face. With gauge_factor and excitation_voltage the voltages are
# predicted too (bridge: "quarter", "half-axial", "half-bending", "full-bending", or "half-poisson" and
# "full-poisson" with poisson_ratio). The sheet gives GF 2.061 and 2.062, 8 V and a gain of 200; it does not
# record the bridge: a quarter bridge is assumed here.
[gauges.incident]
distance = "381 mm"
bridge = "quarter"
gauge_factor = 2.061
excitation_voltage = "8 V"
gain = 200
polarity = 1                   # -1 where compression was recorded as a positive voltage

[gauges.transmitted]
distance = "381 mm"
bridge = "quarter"
gauge_factor = 2.062
excitation_voltage = "8 V"
gain = 200

# ----------------------------------------------------------------------------------------------- input
# The striker's impact velocity, or a measured incident pulse instead: a CSV file with the columns time and strain
# (units in the header, e.g. "time [us]" and "strain [-]"; tension positive) that passes the incident gauge as
# recorded: incident_pulse = { file = "incident.csv" }.
[input]
striker_velocity = "10 m/s"

[simulation]
dt = "0.2 us"                  # time step = travel time of every bar element (about 1 mm of bar)
# duration = "500 us"          # default: until the transmitted pulse has passed its gauge
backend = "numba"              # or "numpy" (slow reference)

[output]
plots = true
'''.replace("{laws}", ", ".join(f'"{name}"' for name in ELEMENTS["law"]))
