"""Pile-driving specifications: TOML files for ``rodimpact drive`` (:mod:`rodimpact.pile`).

A spec gives the ``[pile]`` (the keys of a model file's ``[[rods]]``: material and segments; x runs down from the
head), the ``[driving]`` system (a shipped hammer, a ram mass or a ram rod; the impact velocity or a drop height
with the hammer efficiency; cushions and helmet), the ``[soil]`` (a capacity with a shaft share and distribution,
or layers of unit resistances; Smith's quakes and damping; the penetration), optional ``[[gauges]]``, the
``[analysis]`` (one blow, a bearing graph, drivability over depth or an inspector's chart) and ``[simulation]``
settings. :func:`load_spec` builds the objects (errors name the spec's keys: ``driving.efficiency: missing``),
:func:`run` runs the analysis, :func:`summarize_run` and :func:`format_summary` report it (SI, or US customary
with ``output.units = "us"`` or ``--units us``), :func:`write_files` writes the data files. Keys: ``rodimpact docs
drive`` (generated from :data:`PILE_SPEC`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional

import numpy as np

from ..pile import (Blow, CapacitySoil, DrivingSystem, SoilDynamics, SoilLayer, SoilProfile, drive_blows, hammer,
                    hammer_names)
from ..pile.soil import DAMPING_KINDS, DISTRIBUTIONS
from ..pile.soil_sets import soil_set, soil_set_names
from ..pile.studies import COLUMNS, BlowTable, bearing_graph, drivability, inspector_chart, pile_edges
from ..pile.units import UNIT_SYSTEMS
from ..rods.conditions import Cushion
from ..rods.rod import Rod
from .dimensions import Parameters
from .keypaths import Rule, translated
from .model import _materials, _rod, parse_toml, read_text_file
from .overrides import spec_with_overrides
from .quantities import ModelError
from .results import _write_csv
from .schema import MATERIAL, ROD, Field, Table, _q, _table_md, validate_table

# ============================================================================================ schema
PILE = Table("pile", "The pile, with the keys of a model file's `[[rods]]` but `name`, `velocity` and `initial`: "
                     "`[[pile.segments]]` of any shape, from the head (top) down to the toe.",
             tuple(f for f in ROD.fields if f.name in ("material", "segments", "elements")),
             '[pile]\nmaterial = "steel"\n\n[[pile.segments]]\nshape = "tube"\nlength = "30 m"\n'
             'outer_diameter = "610 mm"\ninner_diameter = "590 mm"')

CUSHION = Table("driving.CUSHION", "A cushion: a compression-only spring, stiffness k on loading and k / e^2 on "
                                   "unloading (Smith 1960).", (
    _q("stiffness", "stiffness", "Loading stiffness k = E A / t of the cushion."),
    _q("restitution", "dimensionless", "Coefficient of restitution e, in (0, 1]."),
), 'hammer_cushion = { stiffness = "1.5 GN/m", restitution = 0.8 }')

RAM = Table("driving.ram", "An elastic ram: the keys of `[pile]` (its lower end strikes).", PILE.fields)

DRIVING = Table("driving", "What strikes the pile head: the ram (one of `hammer`, `ram_mass`, `[driving.ram]`), its "
                           "impact velocity (`impact_velocity`, or `drop_height` with `efficiency`; with `hammer` "
                           "the hammer's rated stroke is the default drop height), the cushions and the helmet.", (
    Field("hammer", "string", "A shipped hammer (its published ram weight and stroke): "
                              + ", ".join(f"`{n}`" for n in hammer_names()) + ".", choices=tuple(hammer_names())),
    _q("ram_mass", "mass", "Mass of a rigid ram.", required=False),
    Field("ram", "table", "An elastic ram rod.", table=RAM),
    _q("impact_velocity", "velocity", "Velocity of the ram at impact.", required=False),
    _q("drop_height", "length", "Drop height (stroke) of the ram; needs `efficiency`.", required=False),
    _q("efficiency", "dimensionless", "Hammer efficiency eta in (0, 1]: kinetic energy at impact / (W h).",
       required=False),
    Field("hammer_cushion", "table", "Cushion between the ram and the helmet.", table=CUSHION),
    _q("helmet_mass", "mass", "Mass of the helmet (0: none).", sign="non_negative", required=False, default=0.0),
    Field("pile_cushion", "table", "Cushion between the helmet and the pile head.", table=CUSHION),
), '[driving]\nhammer = "vulcan-010"\nefficiency = 0.67\nhelmet_mass = "900 kg"\n'
   'hammer_cushion = { stiffness = "1.5 GN/m", restitution = 0.8 }')

LAYER = Table("soil.layers", "A soil layer from the layer above (or the ground) down to `bottom`.", (
    _q("bottom", "length", "Depth of the layer's bottom below the ground."),
    _q("unit_shaft_resistance", "pressure", "Static unit shaft resistance (on the pile's perimeter).",
       sign="non_negative"),
    _q("unit_toe_resistance", "pressure", "Static unit toe resistance (on the toe area) when the toe is in this "
                                          "layer.", sign="non_negative", required=False, default=0.0),
    _q("setup_factor", "dimensionless", "Static long-term / during driving: > 1 setup (clays), < 1 relaxation.",
       required=False, default=1.0),
    Field("name", "string", "A label."),
), '[[soil.layers]]\nname = "soft clay"\nbottom = "8 m"\nunit_shaft_resistance = "20 kPa"\nsetup_factor = 2.0')

SOIL = Table("soil", "The soil: either a total `capacity` with `shaft_share` and `distribution`, or "
                     "`[[soil.layers]]` with `perimeter` and `toe_area`; Smith's quakes and damping.", (
    _q("penetration", "length", "Depth of the pile's toe below the ground (at most the pile's length).",
       required=False),
    _q("capacity", "force", "Total static ultimate capacity (shaft and toe).", required=False),
    _q("shaft_share", "dimensionless", "Part of the capacity on the shaft, in [0, 1].", sign="non_negative",
       required=False),
    Field("distribution", "string", "Shaft resistance over depth.", default="uniform", choices=DISTRIBUTIONS),
    _q("top_ratio", "dimensionless", "Trapezoid: resistance per metre at the ground / at the toe.",
       sign="non_negative", required=False),
    Field("depths", "quantities", "Custom: depths below ground, from 0, increasing.", dimension="length",
          sign="non_negative"),
    Field("shaft_resistances", "quantities", "Custom: shaft resistance on each interval between `depths`; they "
                                             "sum to shaft_share x capacity.", dimension="force",
          sign="non_negative"),
    _q("setup_factor", "dimensionless", "With `capacity`: static long-term / during driving.", required=False,
       default=1.0),
    Field("layers", "tables", "Soil layers, from the ground down.", table=LAYER),
    _q("perimeter", "length", "With `layers`: shaft perimeter of the pile.", required=False),
    _q("toe_area", "area", "With `layers`: area the toe pushes (plugged or closed end: the full section).",
       required=False),
    _q("shaft_quake", "length", "Quake of the shaft resistance (> 0; a rigid-plastic soil is a small quake); "
                                "required without `parameter_set`.", required=False),
    _q("toe_quake", "length", "Quake of the toe resistance (> 0); required without `parameter_set`, or with a set "
                              "instead of `toe_quake_rule`.", required=False),
    _q("unloading_quake", "length", "Unloading quake of the toe, at most `toe_quake` (default: `toe_quake`).",
       required=False),
    _q("shaft_damping", "dimensionless", "Shaft damping factor (s/m for smith kinds, as a number in SI); required "
                                         "without `parameter_set`.", sign="non_negative", required=False),
    _q("toe_damping", "dimensionless", "Toe damping factor (s/m for smith kinds, as a number in SI); required "
                                       "without `parameter_set`.", sign="non_negative", required=False),
    Field("damping_kind", "string", "Damping law.", default="smith", choices=DAMPING_KINDS),
    Field("parameter_set", "string", "A published set of Smith quakes and damping instead of `shaft_quake`, "
                                     "`shaft_damping` and `toe_damping` (docs/pile-driving.md, \"Soil parameters "
                                     "and their sources\"): " + ", ".join(f"`{n}`" for n in soil_set_names()) + ".",
          choices=tuple(soil_set_names())),
    Field("shaft_soil", "string", "With `parameter_set`: the shaft soil whose damping the set gives (`gec12`: "
                                  "`non-cohesive`, `silty-sand`, `cohesive-silt`, `cohesive`; `grlweap`: `sand`, "
                                  "`clay`)."),
    Field("toe_quake_rule", "string", "With `parameter_set`: the set's toe quake rule (`grlweap`: "
                                      "`very-dense-or-hard` D/120, `soft-or-loose` D/60, `non-displacement`, "
                                      "`hard-rock`), or give `toe_quake`."),
    _q("toe_diameter", "length", "With a toe quake rule D / n: the pile's toe diameter D.", required=False),
), '[soil]\npenetration = "20 m"\ncapacity = "2 MN"\nshaft_share = 0.6\ndistribution = "triangular"\n'
   'shaft_quake = "2.54 mm"\ntoe_quake = "2.54 mm"\nshaft_damping = 0.164\ntoe_damping = 0.492')

GAUGE = Table("gauges", "A gauge station: force and velocity are recorded there.", (
    Field("name", "string", "Name of the station.", required=True),
    _q("distance", "length", "Distance below the pile head.", sign="non_negative"),
), '[[gauges]]\nname = "gauges"\ndistance = "1 m"')

ANALYSES = ("blow", "bearing-graph", "drivability", "inspector-chart")
ANALYSIS = Table("analysis", "What to compute.", (
    Field("kind", "string", "`blow` (`blows` successive blows at `soil.penetration`), `bearing-graph` (over "
                            "`capacities`), "
                            "`drivability` (over `depths`, needs layers), `inspector-chart` (over `velocities` or "
                            "`strokes`).", default="blow", choices=ANALYSES),
    Field("blows", "integer", "`blow`: successive blows, each from the soil state and residual forces the one "
                              "before left; the summary is the last blow's.", default=1, minimum=1),
    Field("capacities", "quantities", "Bearing graph: capacities during driving.", dimension="force",
          sign="positive"),
    Field("depths", "quantities", "Drivability: toe depths below the ground.", dimension="length", sign="positive"),
    Field("velocities", "quantities", "Inspector's chart: impact velocities.", dimension="velocity",
          sign="positive"),
    Field("strokes", "quantities", "Inspector's chart: strokes (with `driving.efficiency`).", dimension="length",
          sign="positive"),
), '[analysis]\nkind = "bearing-graph"\ncapacities = ["0.5 MN", "1 MN", "2 MN", "3 MN"]')

SIMULATION = Table("simulation", "Run settings.", (
    _q("dt", "time", "Time step; default: the longest rod in at least 50 elements.", required=False),
    _q("duration", "time", "Simulated time of a blow; default: 10 round trips 2 L / c of the pile.", required=False),
    Field("backend", "string", "`numba` (compiled) or `numpy` (reference).", default="numba",
          choices=("numba", "numpy")),
))

OUTPUT = Table("output", "What to write and how to print it.", (
    Field("plots", "boolean", "Write the plots.", default=True),
    Field("units", "string", "Units of the printed summary: `si` or `us` (kips, ft, blows/ft).", default="si",
          choices=tuple(UNIT_SYSTEMS)),
))

PILE_SPEC = Table("pile-driving spec", "Top level of a pile-driving spec.", (
    Field("title", "string", "Short title."),
    Field("description", "string", "Free text."),
    Field("parameters", "parameters", "Named constants for expressions, converted to SI."),
    Field("materials", "mapping", "Named materials (as in model files).", table=MATERIAL),
    Field("pile", "table", "The pile.", table=PILE, required=True),
    Field("driving", "table", "The driving system.", table=DRIVING, required=True),
    Field("soil", "table", "The soil.", table=SOIL, required=True),
    Field("gauges", "tables", "Gauge stations on the pile.", table=GAUGE),
    Field("analysis", "table", "What to compute.", table=ANALYSIS),
    Field("simulation", "table", "Run settings.", table=SIMULATION),
    Field("output", "table", "Output settings.", table=OUTPUT),
))

#: field names of the pile layer's classes -> key paths of a pile-driving spec
PILE_KEYS: dict[str, Rule] = {
    "dt": "simulation.dt", "duration": "simulation.duration", "backend": "simulation.backend",
    "drop_height": "driving.drop_height", "efficiency": "driving.efficiency", "penetration": "soil.penetration",
    "capacities": "analysis.capacities", "depths": "analysis.depths", "velocities": "analysis.velocities",
    "strokes": "analysis.strokes", "gauges": "gauges",
    **{f"DrivingSystem.{k}": f"driving.{k}" for k in ("impact_velocity", "ram_mass", "ram", "hammer_cushion",
                                                      "helmet_mass", "pile_cushion")},
    **{f"CapacitySoil.{k}": f"soil.{k}" for k in ("capacity", "shaft_share", "distribution", "top_ratio", "depths",
                                                  "shaft_resistances", "setup_factor")},
    **{f"SoilProfile.{k}": f"soil.{k}" for k in ("layers", "perimeter", "toe_area")},
    **{f"SoilDynamics.{k}": f"soil.{k}" for k in ("shaft_quake", "toe_quake", "unloading_quake", "shaft_damping",
                                                  "toe_damping", "damping_kind")},
    r"SoilProfile\.layers\[(\d+)\]": lambda m: f"soil.layers[{m.group(1)}]",
}


def spec_reference_markdown() -> str:
    """Reference tables of the pile-driving spec keys (``rodimpact docs drive``)."""
    lines: list[str] = []
    for title, table in (("Pile-driving spec, top level", PILE_SPEC), ("`[pile]`", PILE), ("`[driving]`", DRIVING),
                         ("Cushions (`hammer_cushion`, `pile_cushion`)", CUSHION), ("`[soil]`", SOIL),
                         ("`[[soil.layers]]`", LAYER), ("`[[gauges]]`", GAUGE), ("`[analysis]`", ANALYSIS),
                         ("`[simulation]`", SIMULATION), ("`[output]`", OUTPUT)):
        _table_md(title, table, 4, lines)
    return "\n".join(lines) + "\n"


# ============================================================================================ spec objects
@dataclass(frozen=True, eq=False)
class PileSpec:
    """A validated pile-driving spec: the pile, the driving system, the soil (a :class:`CapacitySoil` or a
    :class:`SoilProfile`) and its penetration, the gauges, the analysis and its points, run and output settings."""

    pile: Rod
    driving: DrivingSystem
    soil: CapacitySoil | SoilProfile
    penetration: Optional[float]
    gauges: dict[str, float]
    analysis: str
    blows: int
    points: Optional[np.ndarray]
    points_key: Optional[str]
    efficiency: Optional[float]
    dt: Optional[float] = None
    duration: Optional[float] = None
    backend: str = "numba"
    plots: bool = True
    units: str = "si"
    title: str = ""
    text: str = ""
    source: Optional[Path] = None

    @property
    def blow_options(self) -> dict[str, Any]:
        """The keywords of :func:`rodimpact.pile.drive_blow` this spec sets."""
        return {"gauges": self.gauges, "dt": self.dt, "duration": self.duration, "backend": self.backend}


def load_spec(path: str | Path, overrides: Optional[Mapping[str, Any]] = None) -> PileSpec:
    """Read a pile-driving spec file; ``overrides``: key path -> value, set before validation."""
    p = Path(path)
    spec = loads_spec(read_text_file(p, str(p), "spec file"), p.parent, str(p), overrides)
    object.__setattr__(spec, "source", p)
    return spec


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> PileSpec:
    """Read a pile-driving spec from TOML text (``overrides`` as in :func:`load_spec`)."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given))


def _build(build: Any) -> Any:
    """``build()`` with the errors of the pile layer's classes naming the spec's keys."""
    try:
        return build()
    except ModelError:
        raise
    except (ValueError, TypeError) as exc:
        raise translated(exc, PILE_KEYS) from None


def _spec(raw: dict, base: Path, text: str) -> PileSpec:
    d = validate_table(PILE_SPEC, raw, "")
    params = Parameters(d["parameters"] or {}, raw.get("parameters") or {})
    materials = _materials(d["materials"] or {})
    sim = d["simulation"] or validate_table(SIMULATION, {}, "simulation")
    pile = _rod({**d["pile"], "name": "pile", "initial": None}, "pile", materials, params, sim["dt"], base,
                raw["pile"])[0]
    dr = d["driving"]
    ram = None if dr["ram"] is None else _rod({**dr["ram"], "name": "ram", "initial": None}, "driving.ram",
                                               materials, params, sim["dt"], base, raw["driving"]["ram"])[0]
    driving = _driving(dr, ram)
    soil, penetration = _soil(d["soil"], pile)
    analysis = d["analysis"] or validate_table(ANALYSIS, {}, "analysis")
    points_key = _points_key(analysis, soil, penetration, dr)
    points = None if points_key is None else np.asarray(analysis[points_key], dtype=float)
    gauges: dict[str, float] = {}
    for i, g in enumerate(d["gauges"] or []):
        if g["name"] in gauges or g["name"] == "head":
            raise ModelError(f"gauges[{i}].name: {g['name']!r} is " + ("reserved for the pile head" if g["name"] ==
                                                                       "head" else "used twice"))
        gauges[g["name"]] = g["distance"]
    out = d["output"] or validate_table(OUTPUT, {}, "output")
    if analysis["blows"] != 1 and analysis["kind"] != "blow":
        raise ModelError(f"analysis.blows: successive blows belong to the blow analysis, not {analysis['kind']!r}")
    return PileSpec(pile, driving, soil, penetration, gauges, analysis["kind"], analysis["blows"], points, points_key,
                    dr["efficiency"],
                    sim["dt"],
                    sim["duration"], sim["backend"], out["plots"], out["units"], d["title"] or "", text)


def _driving(dr: dict, ram: Optional[Rod]) -> DrivingSystem:
    chosen = [k for k in ("hammer", "ram_mass", "ram") if dr[k] is not None]
    if len(chosen) != 1:
        raise ModelError("driving: give exactly one of hammer, ram_mass or [driving.ram], "
                         + (f"not {' and '.join(chosen)}" if chosen else "got none"))
    h = None if dr["hammer"] is None else hammer(dr["hammer"])
    drop = dr["drop_height"] if dr["drop_height"] is not None or h is None else h.stroke
    if (dr["impact_velocity"] is None) == (drop is None):
        raise ModelError("driving.impact_velocity: give the impact_velocity or a drop_height (with efficiency), "
                         + ("not both" if drop is not None else "got neither"))
    parts: dict[str, Any] = {"helmet_mass": dr["helmet_mass"]}
    for key in ("hammer_cushion", "pile_cushion"):
        if dr[key] is not None:
            parts[key] = _build(lambda c=dr[key], k=key: _cushion(c, k))
    if h is not None:
        parts["ram_mass"] = h.ram_mass
    elif ram is not None:
        parts["ram"] = ram
    else:
        parts["ram_mass"] = dr["ram_mass"]
    if drop is None:
        return _build(lambda: DrivingSystem(dr["impact_velocity"], **parts))
    return _build(lambda: DrivingSystem.dropped(drop, dr["efficiency"], **parts))


def _cushion(c: dict, key: str) -> Cushion:
    try:
        return Cushion(c["stiffness"], c["restitution"])
    except (ValueError, TypeError) as exc:
        raise ModelError(str(exc).replace("Cushion.", f"driving.{key}.", 1)) from None


#: keys of [soil] a published parameter set replaces, and the keys that belong to a set
_SET_GIVES = ("shaft_quake", "shaft_damping", "toe_damping")
_SET_KEYS = ("shaft_soil", "toe_quake_rule", "toe_diameter")


def _dynamics(s: dict) -> SoilDynamics:
    """Smith's parameters of ``[soil]``: given one by one, or from ``parameter_set`` (its shaft quake and damping,
    the shaft damping of ``shaft_soil``, the toe quake of ``toe_quake_rule`` or ``toe_quake``)."""
    if s["parameter_set"] is None:
        for key in ("shaft_quake", "toe_quake", "shaft_damping", "toe_damping"):
            if s[key] is None:
                raise ModelError(f"soil.{key}: missing; give it, or a published parameter_set "
                                 f"({', '.join(soil_set_names())})")
        for key in _SET_KEYS:
            if s[key] is not None:
                raise ModelError(f"soil.{key}: only with soil.parameter_set")
        return _build(lambda: SoilDynamics(s["shaft_quake"], s["toe_quake"], s["shaft_damping"], s["toe_damping"],
                                           s["damping_kind"], s["unloading_quake"]))
    name = s["parameter_set"]
    for key in _SET_GIVES:
        if s[key] is not None:
            raise ModelError(f"soil.{key}: the parameter_set {name!r} gives it; give either the set or the quakes "
                             f"and damping one by one")
    if s["damping_kind"] != "smith":
        raise ModelError(f"soil.damping_kind: the parameter_set {name!r} gives Smith damping factors, not "
                         f"{s['damping_kind']!r}")
    if s["shaft_soil"] is None:
        raise ModelError(f"soil.shaft_soil: missing; the parameter_set {name!r} gives the shaft damping by soil: "
                         f"{', '.join(soil_set(name).shaft_damping)}")
    if (s["toe_quake"] is None) == (s["toe_quake_rule"] is None):
        raise ModelError("soil.toe_quake_rule: with a parameter_set give the toe quake rule or the toe_quake, "
                         + ("not both" if s["toe_quake"] is not None else "got neither"))
    toe = s["toe_quake_rule"] if s["toe_quake"] is None else s["toe_quake"]
    try:
        return SoilDynamics.published(name, s["shaft_soil"], toe, s["toe_diameter"], s["unloading_quake"])
    except (ValueError, TypeError) as exc:
        key, _, rest = str(exc).partition(":")
        spec_key = {"shaft_soil": "soil.shaft_soil", "toe_diameter": "soil.toe_diameter",
                    "toe_quake": "soil.toe_quake" if s["toe_quake_rule"] is None else "soil.toe_quake_rule"}.get(key)
        raise (translated(exc, PILE_KEYS) if spec_key is None else ModelError(spec_key + ":" + rest)) from None


def _soil(s: dict, pile: Rod) -> tuple[CapacitySoil | SoilProfile, Optional[float]]:
    dyn = _dynamics(s)
    by_capacity, by_layers = s["capacity"] is not None, s["layers"] is not None
    if by_capacity == by_layers:
        raise ModelError("soil: give either capacity (with shaft_share) or [[soil.layers]] (with perimeter and "
                         "toe_area), " + ("not both" if by_capacity else "got neither"))
    d = s["penetration"]
    if d is not None and d > pile.length * (1 + 1e-12):
        raise ModelError(f"soil.penetration: {d:.6g} m is deeper than the pile ({pile.length:.6g} m long)")
    if by_capacity:
        if s["shaft_share"] is None:
            raise ModelError("soil.shaft_share: missing; the part of the capacity on the shaft, in [0, 1]")
        return _build(lambda: CapacitySoil(s["capacity"], s["shaft_share"], dyn, s["distribution"], s["top_ratio"],
                                           s["depths"], s["shaft_resistances"], s["setup_factor"])), d
    for key in ("perimeter", "toe_area"):
        if s[key] is None:
            raise ModelError(f"soil.{key}: missing; a layered profile needs the pile's perimeter and toe area")
    layers = [_build(lambda layer=layer: SoilLayer(layer["bottom"], layer["unit_shaft_resistance"],
                                                   layer["unit_toe_resistance"], layer["setup_factor"],
                                                   layer["name"] or "")) for layer in s["layers"]]
    profile = _build(lambda: SoilProfile(layers, s["perimeter"], s["toe_area"], dyn))
    if profile.bottoms[-1] > pile.length * (1 + 1e-12):
        k = len(layers) - 1
        raise ModelError(f"soil.layers[{k}].bottom: the profile reaches {profile.bottoms[-1]:.6g} m, deeper than the "
                         f"pile ({pile.length:.6g} m long) can ever be driven; end the profile at the pile's length")
    return profile, d


def _points_key(a: dict, soil: CapacitySoil | SoilProfile, penetration: Optional[float], dr: dict) -> Optional[str]:
    """The ``[analysis]`` key holding the points the analysis runs over (``None`` for one blow)."""
    kind = a["kind"]
    need = {"bearing-graph": "capacities", "drivability": "depths"}.get(kind)
    if kind == "inspector-chart":
        if (a["velocities"] is None) == (a["strokes"] is None):
            raise ModelError("analysis.velocities: the inspector's chart needs velocities or strokes, one of them")
        if a["strokes"] is not None and dr["efficiency"] is None:
            raise ModelError("driving.efficiency: missing; analysis.strokes need the hammer efficiency")
        need = "velocities" if a["velocities"] is not None else "strokes"
    if need is not None and a[need] is None:
        raise ModelError(f"analysis.{need}: missing; the {kind} analysis runs over them")
    if kind == "drivability" and not isinstance(soil, SoilProfile):
        raise ModelError("analysis.kind: drivability needs a layered soil ([[soil.layers]]), not a capacity")
    if kind == "bearing-graph" and not isinstance(soil, CapacitySoil):
        raise ModelError("analysis.kind: the bearing graph varies soil.capacity; give capacity and shaft_share, "
                         "not layers")
    if kind != "drivability" and penetration is None:
        raise ModelError(f"soil.penetration: missing; the {kind} analysis needs the toe's depth below the ground")
    return need


# ============================================================================================ running
@dataclass
class PileRun:
    """The outcome of a spec: one :class:`~rodimpact.pile.Blow` or a :class:`~rodimpact.pile.studies.BlowTable`,
    with the warnings raised while it ran."""

    kind: str
    blow: Optional[Blow] = None
    table: Optional[BlowTable] = None
    warnings: list[str] = field(default_factory=list)
    sets: list[float] = field(default_factory=list)


def _resistance(spec: PileSpec, depth: float) -> Any:
    if isinstance(spec.soil, SoilProfile):
        return spec.soil.resistance(depth)
    return spec.soil.resistance(depth, pile_edges(spec.pile, depth))


def run(spec: PileSpec, progress: Optional[bool] = None) -> PileRun:
    """Run the spec's analysis."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = _build(lambda: _run(spec, progress))
    out.warnings = [str(w.message) for w in caught]
    return out


def _run(spec: PileSpec, progress: Optional[bool]) -> PileRun:
    opts, kind = spec.blow_options, spec.analysis
    if kind == "blow":
        blows = drive_blows(spec.pile, spec.driving, _resistance(spec, spec.penetration), spec.blows, **opts)
        return PileRun(kind, blow=blows[-1], sets=[b.permanent_set for b in blows])
    if kind == "bearing-graph":
        table = bearing_graph(spec.pile, spec.driving, spec.soil, spec.points, spec.penetration, progress=progress,
                              **opts)
    elif kind == "drivability":
        table = drivability(spec.pile, spec.driving, spec.soil, spec.points, progress=progress, **opts)
    else:
        chosen = {spec.points_key: spec.points}
        table = inspector_chart(spec.pile, spec.driving, _resistance(spec, spec.penetration), **chosen,
                                efficiency=spec.efficiency, progress=progress, **opts)
    return PileRun(kind, table=table)


def _finite(x: float) -> Optional[float]:
    """``x`` for JSON: ``None`` for an infinite blow count (refusal)."""
    return None if math.isinf(x) else float(x)


def summarize_run(r: PileRun, spec: PileSpec) -> dict[str, Any]:
    """Key numbers of the run, JSON-ready, SI units (blow counts per 0.25 m and per foot; ``None`` at refusal)."""
    out: dict[str, Any] = {"title": spec.title, "analysis": r.kind,
                           "impact_velocity_m_s": spec.driving.impact_velocity,
                           "ram_kinetic_energy_J": spec.driving.kinetic_energy, "warnings": list(r.warnings)}
    if r.blow is not None:
        b = r.blow
        c, t = b.envelope.max_compression, b.envelope.max_tension
        out.update({
            "penetration_m": spec.penetration, "soil_resistance_N": b.soil.total,
            "blows": len(r.sets), "permanent_sets_m": r.sets,
            "permanent_set_m": b.permanent_set, "blows_per_0.25m": _finite(b.blows_per_quarter_metre),
            "blows_per_ft": _finite(b.blows_per_foot), "emx_J": b.emx,
            "max_compression_Pa": c[0], "max_compression_depth_m": c[1], "max_compression_time_s": c[2],
            "max_tension_Pa": t[0], "max_tension_depth_m": t[1], "max_tension_time_s": t[2],
            "dt_s": b.result.dt, "steps": int(b.result.n_steps)})
    else:
        tb = r.table
        out["table"] = {tb.x_name + f" [{tb.x_unit}]": tb.x.tolist(),
                        **{f"{k} [{u}]": [_finite(v) for v in getattr(tb, k)] for k, u in COLUMNS.items()},
                        "blows_per_ft": [_finite(v) for v in tb.blows_per_foot]}
    return out


def format_summary(s: dict[str, Any], spec: PileSpec, units: Optional[str] = None) -> str:
    """The summary as text, in SI or US customary units (``units``: default the spec's ``output.units``)."""
    u = UNIT_SYSTEMS[units or spec.units]

    def show(value: Optional[float], quantity: str, digits: int = 4) -> str:
        if value is None:
            return "refusal"
        size, label = u[quantity]
        return f"{value / size:.{digits}g} {label}"

    lines = [spec.title] if spec.title else []
    lines.append(f"ram at {show(s['impact_velocity_m_s'], 'velocity')}, kinetic energy "
                 f"{show(s['ram_kinetic_energy_J'], 'energy')}")
    if "table" not in s:
        blows = s["blows_per_0.25m"] if u["blows"][0] == 0.25 else s["blows_per_ft"]
        lines.append(f"toe at {show(s['penetration_m'], 'length')}, soil resistance during driving "
                     f"{show(s['soil_resistance_N'], 'force')}")
        if s["blows"] > 1:
            lines.append(f"{s['blows']} blows, sets " + ", ".join(show(x, "set") for x in s["permanent_sets_m"])
                         + "; the last blow:")
        lines.append(f"permanent set {show(s['permanent_set_m'], 'set')}: "
                     + ("refusal" if blows is None else f"{blows:.4g} {u['blows'][1]}"))
        lines.append(f"EMX (largest energy through the head) {show(s['emx_J'], 'energy')}")
        lines.append(f"largest compression {show(s['max_compression_Pa'], 'stress')} at "
                     f"{show(s['max_compression_depth_m'], 'length')} below the head, "
                     f"{s['max_compression_time_s'] * 1e3:.4g} ms")
        lines.append(f"largest tension {show(s['max_tension_Pa'], 'stress')} at "
                     f"{show(s['max_tension_depth_m'], 'length')}, {s['max_tension_time_s'] * 1e3:.4g} ms")
        return "\n".join(lines)
    table = s["table"]
    x_key = next(iter(table))
    x_quantity = {"capacity": "force", "depth": "length", "impact velocity": "velocity", "stroke": "length"}
    name = x_key.split(" [")[0]
    blows = table["blows_per_0.25m [1/0.25 m]"] if u["blows"][0] == 0.25 else table["blows_per_ft"]
    lines.append(f"{name:>16} | {u['blows'][1]:>14} | {'set':>10} | {'compression':>12} | {'tension':>12} | "
                 f"{'EMX':>12}")
    for i, x in enumerate(table[x_key]):
        lines.append(f"{show(x, x_quantity[name]):>16} | "
                     f"{'refusal' if blows[i] is None else format(blows[i], '.4g'):>14} | "
                     f"{show(table['permanent_set [m]'][i], 'set'):>10} | "
                     f"{show(table['max_compression [Pa]'][i], 'stress'):>12} | "
                     f"{show(table['max_tension [Pa]'][i], 'stress'):>12} | {show(table['emx [J]'][i], 'energy'):>12}")
    return "\n".join(lines)


#: the data files of a run's folder (besides ``plots/`` and ``summary.json``)
BLOW_FILE, TABLE_FILE, ENVELOPE_FILE = "head.csv", "table.csv", "envelope.csv"


def write_files(r: PileRun, spec: PileSpec, folder: Path) -> list[str]:
    """Write the data files of a run into the (new) ``folder``: ``spec.toml`` (the spec as it ran) and, for one
    blow, ``head.csv`` (time, head force, velocity, ENTHRU and the gauges' force and velocity) and
    ``envelope.csv`` (the stress envelopes along the pile); for a study ``table.csv`` (one row per point, SI,
    ``inf`` blow counts at refusal)."""
    (folder / "spec.toml").write_text(spec.text, encoding="utf-8")
    if r.blow is not None:
        b = r.blow
        header = ["time [s]", "head force [N]", "head velocity [m/s]", "enthru [J]"]
        cols = [b.time, b.head.force, b.head.velocity, b.enthru]
        for name, g in b.gauges.items():
            header += [f"{name} force [N]", f"{name} velocity [m/s]"]
            cols += [g.force, g.velocity]
        _write_csv(folder / BLOW_FILE, header, cols)
        e = b.envelope
        _write_csv(folder / ENVELOPE_FILE, ["depth [m]", "compression [Pa]", "compression time [s]",
                                            "tension [Pa]", "tension time [s]"],
                   [e.depth, e.compression, e.compression_time, e.tension, e.tension_time])
        return ["spec.toml", BLOW_FILE, ENVELOPE_FILE]
    tb = r.table
    _write_csv(folder / TABLE_FILE, [f"{tb.x_name} [{tb.x_unit}]"] + [f"{k} [{u}]" for k, u in COLUMNS.items()]
               + ["blows_per_ft [1/ft]"], [tb.x] + [getattr(tb, k) for k in COLUMNS] + [tb.blows_per_foot])
    return ["spec.toml", TABLE_FILE]


# ============================================================================================ template
TEMPLATE = '''\
# rodimpact pile-driving spec -- run it with:   rodimpact drive drive.toml -o results/drive
#
# One blow of a hammer on a pile (rodimpact.pile): the pile is an exact 1-D rod (x down from its head), the ram,
# cushions and helmet are a lumped chain at its head, the soil is Smith's model (an elastic-plastic spring with a
# quake and a damper per node, the toe in compression only). Quantities take units ("30 m", "2 MN"); bare numbers
# are SI. Forces are tension positive; set and velocity are positive downwards. All keys: rodimpact docs drive.
# Print in US customary units (kips, ft, blows/ft) with --units us.

title = "steel pipe pile, drop hammer"

# The pile: the keys of [[rods]] in model files, segments from the head down.
[pile]
material = "steel"

[[pile.segments]]
shape = "tube"
length = "20 m"
outer_diameter = "324 mm"
inner_diameter = "300 mm"

# The driving system: a rigid ram (or hammer = "vulcan-010", a shipped hammer with its published ram weight and
# stroke; or [driving.ram], an elastic ram rod), the impact velocity (or drop_height with efficiency: V = sqrt(2 g
# eta h); the efficiency has no default: state it for the hammer), the cushions (stiffness k, restitution e) and
# the helmet. The numbers below are an example, not data of a real hammer.
[driving]
ram_mass = "3000 kg"
drop_height = "1.0 m"
efficiency = 0.8
helmet_mass = "500 kg"
hammer_cushion = { stiffness = "1 GN/m", restitution = 0.8 }

# The soil: a total capacity with a shaft share and a distribution (uniform, triangular, trapezoid, custom), or
# [[soil.layers]] of unit resistances with the pile's perimeter and toe area. Quakes and Smith damping (E. A. L.
# Smith, J. Soil Mech. Found. Div. ASCE 86 (SM4), 1960, 35-61): quake 0.1 in = 2.54 mm, toe damping 0.15 s/ft =
# 0.492 s/m and shaft damping 0.05 s/ft = 0.164 s/m are FHWA GEC-12's defaults for a non-cohesive soil (read in
# a quotation of GEC-12, not the circular itself; docs/pile-driving.md). Or take a published set instead of the
# quakes and damping: parameter_set = "gec12" or "grlweap", with shaft_soil and toe_quake_rule (or toe_quake).
[soil]
penetration = "15 m"
capacity = "1.5 MN"
shaft_share = 0.5
distribution = "triangular"
shaft_quake = "2.54 mm"
toe_quake = "2.54 mm"
shaft_damping = 0.164
toe_damping = 0.492
damping_kind = "smith"

# Gauge stations (force and velocity recorded), distance below the pile head.
[[gauges]]
name = "gauges"
distance = "0.6 m"

# blow (one blow), bearing-graph (capacities), drivability (depths; needs layers), inspector-chart (velocities or
# strokes).
[analysis]
kind = "blow"
# kind = "bearing-graph"
# capacities = ["0.5 MN", "1 MN", "1.5 MN", "2 MN", "3 MN"]

[simulation]
# dt = "20 us"                 # default: the longest rod in at least 50 elements
# duration = "40 ms"           # default: 10 round trips 2 L / c of the pile
backend = "numba"

[output]
plots = true
units = "si"                   # or "us": kips, ft, blows/ft
'''
