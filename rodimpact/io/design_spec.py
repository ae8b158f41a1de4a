"""Design specifications: TOML files for ``rodimpact design`` (best striker under constraints, docs/design.md).

A design spec is a synthesis spec (docs/cli.md: ``[[struck]]``, ``far_end``, ``[target]``, ``[materials]``,
``[parameters]``) plus the constraints of the striker (``[striker]``: velocity or its bounds, diameter or
impedance bounds, bore, mass) and the ``[design]`` settings (objective, elements, dt, steps). Reading it makes
the arguments of :func:`rodimpact.design`: the objective (``[target]`` or the efficiency), the struck
:class:`~rodimpact.System`, the :class:`~rodimpact.StrikerLimits` and the :class:`~rodimpact.SearchOptions`.
:func:`run` calls :func:`rodimpact.design` and verifies the result with the direct solver; :func:`write_files`
writes its data files (the command line's folder with figures: :mod:`rodimpact.output_folders`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional

import numpy as np

from ..design import EfficiencyObjective, MatchObjective, SearchOptions, StrikerLimits
from ..rods.material import STEEL
from ..rods.system import System
from .dimensions import Parameters
from .model import _material, _materials, parse_toml, read_text_file
from .keypaths import DESIGN_KEYS, translated
from .overrides import spec_with_overrides
from .quantities import ModelError
from .schema import END_TYPES, JUNCTION_TYPES, LOAD_TYPES, MATERIAL, ROD, Field, Table, Variants, _q, _table_md, \
    validate_table
from .storage import save
from .synthesis_spec import TARGET_TYPES, _target, read_struck

# ============================================================================================ schema
STRIKER = Table("striker", "The striker to be designed and its constraints.", (
    _q("velocity", "velocity", "Impact velocity (the start value when `velocity_min`/`velocity_max` are given).",
       required=False),
    _q("velocity_min", "velocity", "Lower bound of a free impact velocity.", required=False),
    _q("velocity_max", "velocity", "Upper bound of a free impact velocity.", required=False),
    Field("material", "string", "Material (preset or `[materials]`) for the diameter bounds, the shape and the "
                                "CSV; default `steel`."),
    _q("diameter_min", "length", "Smallest outer diameter.", required=False),
    _q("diameter_max", "length", "Largest outer diameter.", required=False),
    _q("impedance_min", "impedance", "Smallest element impedance (instead of diameters).", required=False),
    _q("impedance_max", "impedance", "Largest element impedance (instead of diameters).", required=False),
    _q("bore", "length", "Central bore (0: solid).", sign="non_negative", required=False, default=0.0),
    _q("mass", "mass", "Prescribed striker mass.", required=False),
    _q("mass_min", "mass", "Lower bound of the mass.", required=False),
    _q("mass_max", "mass", "Upper bound of the mass.", required=False),
), '[striker]\nvelocity = "12 m/s"\ndiameter_min = "5 mm"\ndiameter_max = "60 mm"')

DESIGN = Table("design", "What to optimise and how.", (
    Field("objective", "string", "`match` (relative L2 misfit to `[target]`) or `efficiency` (work on the rock "
                                 "per blow / striker kinetic energy; needs a `bit-rock` far end).",
          default="match", choices=("match", "efficiency")),
    Field("elements", "integer", "Number n of striker elements; default: the target's windows.", minimum=1),
    _q("dt", "time", "Travel time of one element; default: that of impedance-level struck rods.", required=False),
    Field("max_steps", "integer", "Return a stepped striker with at most this many constant-impedance steps.",
          minimum=1),
    _q("smoothness", "dimensionless", "Weight of the total-variation penalty (0: none).", sign="non_negative",
       required=False, default=0.0),
    _q("duration", "time", "Length of the efficiency run (default: pulse + 3 round trips of the struck system).",
       required=False),
    Field("elements_min", "integer", "Objective `efficiency` with a `striker.mass`: let the piston's length vary "
                                      "from this many elements up to `elements` (default: the length is fixed).",
          minimum=1),
    Field("reloading", "boolean", "Objective `efficiency`: `true` counts the reloading of the rock by reflected "
                                  "waves (run: pulse + 3 round trips, or `duration`); `false` only the first pass, "
                                  "Lundberg's classical efficiency.", default=True),
    Field("starts", "integer", "Number of starting profiles (each continued from coarse to fine).", default=16,
          minimum=1),
    Field("max_iterations", "integer", "L-BFGS-B iterations per start and stage.", default=300, minimum=1),
    _q("improvement", "dimensionless", "Stop a run when its best objective improved by less than this fraction "
                                       "over the last 10 iterations (0: never).", sign="non_negative",
       required=False, default=1e-6),
    Field("hops", "integer", "Basin-hopping rounds after the starts.", default=8, minimum=0),
    Field("backend", "string", "`numba` or `numpy`.", default="numba", choices=("numba", "numpy")),
))

DESIGN_OUTPUT = Table("output", "What to write.", (Field("plots", "boolean", "Write the plots.", default=True),))

DESIGN_SPEC = Table("design spec", "Top level of a design spec.", (
    Field("title", "string", "Short title."),
    Field("description", "string", "Free text."),
    Field("parameters", "parameters", "Named constants for expressions, converted to SI."),
    Field("materials", "mapping", "Named materials (as in model files).", table=MATERIAL),
    Field("striker", "table", "The striker and its constraints.", table=STRIKER, required=True),
    Field("design", "table", "Objective and settings.", table=DESIGN),
    Field("target", "variant", "The wished force (objective `match`), as in synthesis specs.",
          variants=Variants("type", TARGET_TYPES)),
    Field("struck", "tables", "The struck system, from the impact face outwards (keys of `[[rods]]`).",
          table=ROD, required=True, minimum=1),
    Field("junctions", "tables", "Between struck rods; default bonded.", variants=Variants("type", JUNCTION_TYPES)),
    Field("far_end", "variant", "Condition at the far end of the struck system.", default="free",
          variants=Variants("type", END_TYPES)),
    Field("loads", "tables", "Loads on struck rods.", variants=Variants("type", LOAD_TYPES)),
    Field("output", "table", "Output settings.", table=DESIGN_OUTPUT),
))


def spec_reference_markdown() -> str:
    """Reference tables of the design-spec keys (docs/cli.md)."""
    lines: list[str] = []
    _table_md("Top level", DESIGN_SPEC, 3, lines)
    _table_md("`[striker]`", STRIKER, 3, lines)
    _table_md("`[design]`", DESIGN, 3, lines)
    _table_md("`[output]`", DESIGN_OUTPUT, 3, lines)
    lines.append("`[target]`, `[[struck]]`, `[[junctions]]`, `far_end` and `[[loads]]` take the keys of a synthesis "
                 "spec (above).")
    return "\n".join(lines) + "\n"


# ============================================================================================ spec objects
@dataclass(frozen=True, eq=False)
class DesignSpec:
    """A validated design spec: the arguments of :func:`rodimpact.design` (``target``: the objective, ``struck``,
    ``striker_velocity``, ``n``, ``dt``, ``limits``, ``search``, ``backend``) plus output settings."""

    kwargs: dict[str, Any]
    plots: bool = True
    title: str = ""
    text: str = ""

    def design(self):
        """Run :func:`rodimpact.design` with these settings."""
        from ..design import design

        try:
            return design(**self.kwargs)
        except ModelError:
            raise
        except (ValueError, TypeError) as exc:     # errors name the spec's keys, not design()'s arguments
            raise translated(exc, DESIGN_KEYS) from None


def load_spec(path: str | Path, overrides: Optional[Mapping[str, Any]] = None) -> DesignSpec:
    """Read a design spec file (relative file names are resolved against its folder); ``overrides``: key path ->
    value, set before the spec is validated (:mod:`rodimpact.io.overrides`)."""
    p = Path(path)
    return loads_spec(read_text_file(p, str(p), "spec file"), p.parent, str(p), overrides)


def _pair(st: dict, lo: str, hi: str, prefix: str = "striker") -> Optional[tuple[float, float]]:
    a, b = st[lo], st[hi]
    if (a is None) != (b is None):
        missing = lo if a is None else hi
        raise ModelError(f"{prefix}.{missing}: missing; give {prefix}.{lo} and {prefix}.{hi} together, or neither")
    return None if a is None else (a, b)


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> DesignSpec:
    """Read a design spec from TOML text (``overrides`` as in :func:`load_spec`)."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given))


def _spec(raw: dict, base: Path, text: str) -> DesignSpec:
    """The validated spec of the parsed file ``raw`` (``text``: the file as given)."""
    d = validate_table(DESIGN_SPEC, raw, "")
    params = Parameters(d["parameters"] or {}, raw.get("parameters") or {})
    materials = _materials(d["materials"] or {})
    ds = d["design"] or validate_table(DESIGN, {}, "design")
    rods, vel, initial, junctions, far_end, loads = read_struck(d, params, materials, ds["dt"], base)
    st = d["striker"]
    mat = _material(st["material"], materials, "striker.material") or STEEL
    vb = _pair(st, "velocity_min", "velocity_max")
    if st["velocity"] is None and vb is None:
        raise ModelError("striker.velocity: give the impact velocity, or velocity_min and velocity_max")
    db = _pair(st, "diameter_min", "diameter_max")
    zb = _pair(st, "impedance_min", "impedance_max")
    if db is not None and zb is not None:
        raise ModelError("striker: give diameter_min/diameter_max or impedance_min/impedance_max, not both")
    mb = _pair(st, "mass_min", "mass_max")
    if st["mass"] is not None and mb is not None:
        raise ModelError("striker.mass, striker.mass_min/mass_max: give a mass or a range, not both")
    t = d["target"]
    match = ds["objective"] == "match"
    if match and t is None:
        raise ModelError("target: the objective 'match' needs a [target] table")
    if not match and t is not None:
        raise ModelError("target: the objective 'efficiency' takes no [target]; remove it")
    if match and not ds["reloading"]:
        raise ModelError("design.reloading: chooses the definition of the efficiency; give it only with objective = "
                         "\"efficiency\"")
    if match and ds["duration"] is not None:
        raise ModelError("design.duration: the length of the efficiency run; give it only with objective = "
                         "\"efficiency\" (a match runs over the target's span)")
    n = ds["elements"]
    if ds["elements_min"] is not None:
        if match or ds["elements"] is None:
            raise ModelError("design.elements_min: give it only with objective = \"efficiency\" and "
                             "design.elements (the longest piston)")
        if ds["elements_min"] > ds["elements"]:
            raise ModelError(f"design.elements_min: must not exceed design.elements ({ds['elements']}), got "
                             f"{ds['elements_min']}")
        n = (ds["elements_min"], ds["elements"])
    target = None if t is None else _target(t, params, base)
    try:
        objective = (MatchObjective(target, position=t["position"], quantity=t["quantity"], rule=t["rule"]) if match
                     else EfficiencyObjective(reloading=ds["reloading"], duration=ds["duration"]))
        struck = System.struck(list(rods), far_end, list(vel), junctions=junctions, loads=tuple(loads),
                               initial=initial if any(s is not None for s in initial) else None)
        limits = StrikerLimits(impedance_bounds=zb, diameter_bounds=db, material=mat, bore=st["bore"],
                               mass=st["mass"] if st["mass"] is not None else mb, velocity_bounds=vb,
                               max_steps=ds["max_steps"], smoothness=ds["smoothness"])
        search = SearchOptions(starts=ds["starts"], max_iterations=ds["max_iterations"],
                               improvement=ds["improvement"], hops=ds["hops"])
    except (ValueError, TypeError) as exc:     # errors name the spec's keys, not the Python arguments
        raise translated(exc, DESIGN_KEYS) from None
    kwargs: dict[str, Any] = dict(target=objective, struck=struck, striker_velocity=st["velocity"], n=n,
                                  dt=ds["dt"], limits=limits, search=search, backend=ds["backend"])
    out = d["output"] or {"plots": True}
    return DesignSpec(kwargs, out["plots"], d["title"] or "", text)


# ============================================================================================ running, saving
@dataclass
class DesignRun:
    """A design result with its verification by the direct solver."""

    result: Any
    verification: Any = None
    warnings: list[str] = field(default_factory=list)


def run(spec: DesignSpec) -> DesignRun:
    """Design, then verify with the direct solver."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = spec.design()
        verification = result.verify(spec.kwargs["backend"])
    return DesignRun(result, verification, [str(w.message) for w in caught])


def summarize_run(r: DesignRun, spec: DesignSpec) -> dict[str, Any]:
    """Key numbers of a design (JSON-ready, SI units)."""
    res = r.result
    limits = spec.kwargs["limits"]
    shape = res.shape(limits.material, limits.bore)
    diag = res.diagnostics
    out: dict[str, Any] = {
        "title": spec.title, "objective": res.objective, "elements": res.n_elements, "dt_s": res.dt,
        "striker_velocity_m_s": res.striker_velocity, "misfit": res.misfit, "efficiency": res.efficiency,
        "steps": res.steps, "mass_kg": res.mass, "length_m": shape.length,
        "impedance_min_N_s_per_m": float(res.impedance.min()), "impedance_max_N_s_per_m": float(res.impedance.max()),
        "outer_diameter_min_m": float(shape.outer_diameter.min()),
        "outer_diameter_max_m": float(shape.outer_diameter.max()),
        "constraints": res.constraint_report, "iterations": res.iterations, "wall_time_s": res.wall_time,
        "forward_runs": diag.get("forward_runs"), "gradient_runs": diag.get("gradient_runs"),
        "warm_start": diag.get("warm_start"), "existence": diag.get("existence"),
        "bounds_diagnosis": diag.get("bounds_diagnosis", []),
        "free_profile_misfit": (diag.get("free_profile") or {}).get("misfit"),
        "efficiency_definition": diag.get("efficiency_definition"),
        "uniform_reference": _jsonable(diag.get("uniform_reference")),
        "lengths": _jsonable(diag.get("lengths")),
        "local_optima": diag.get("local_optima"),
        "verification": None if r.verification is None else {
            "max_deviation": r.verification.max_deviation, "misfit": r.verification.misfit,
            "efficiency": r.verification.efficiency},
        "warnings": list(r.warnings)}
    return out


def _jsonable(d: Any) -> Any:
    """Dictionaries with integer keys (element counts) as JSON-ready dictionaries with string keys."""
    if isinstance(d, dict):
        return {str(k) if isinstance(k, (int, np.integer)) else k: _jsonable(v) for k, v in d.items()}
    return d


def format_summary(s: dict[str, Any], spec: DesignSpec) -> str:
    """A short text version of the summary."""
    lines = [spec.title] if spec.title else []
    what = (f"misfit {s['misfit']:.4g} (relative L2)" if s["objective"] == "match"
            else f"efficiency {s['efficiency']:.4g} (work on the rock / striker kinetic energy)")
    lines.append(f"design ({s['objective']}): {what}, {s['elements']} elements, {s['steps']} step(s)")
    if s.get("efficiency_definition"):
        lines.append(f"efficiency definition: {s['efficiency_definition']}")
    ref = s.get("uniform_reference")
    if ref and ref.get("elements") is not None:
        lines.append(f"best uniform piston of the same mass: {ref['elements']} elements, impedance "
                     f"{ref['impedance'] / 1e3:.4g} kN s/m, efficiency {ref['efficiency']:.4g} (the design: "
                     f"{s['efficiency']:.4g}, {s['elements']} elements)")
    if s.get("lengths"):
        lines.append("piston lengths designed: " + ", ".join(f"{m} elements -> {e:.4g}"
                                                             for m, e in s["lengths"].items()))
    opt = s.get("local_optima")
    if opt and len(opt["values"]) > 1:
        v = opt["values"]
        lines.append(f"local optima from {len(v)} starts and hops: {opt['name']} {v[0]:.4g} (best) .. {v[-1]:.4g}, "
                     f"median {float(np.median(v)):.4g}")
    if s["free_profile_misfit"] is not None:
        lines.append(f"free (unstepped) profile: misfit {s['free_profile_misfit']:.4g}")
    lines.append(f"striker: length {s['length_m']:.4g} m, mass {s['mass_kg']:.4g} kg, impedance "
                 f"{s['impedance_min_N_s_per_m'] / 1e3:.4g} .. {s['impedance_max_N_s_per_m'] / 1e3:.4g} kN s/m, outer "
                 f"diameter {s['outer_diameter_min_m'] * 1e3:.4g} .. {s['outer_diameter_max_m'] * 1e3:.4g} mm, "
                 f"velocity {s['striker_velocity_m_s']:.4g} m/s")
    c = s["constraints"]
    act = []
    if c["elements_at_lower_bound"]:
        act.append(f"{len(c['elements_at_lower_bound'])} element(s) at the lower bound")
    if c["elements_at_upper_bound"]:
        act.append(f"{len(c['elements_at_upper_bound'])} element(s) at the upper bound")
    if c["mass_active"] not in (None, "inactive"):
        act.append(f"mass {c['mass_active']}")
    if c["velocity_active"] not in (None, "inactive"):
        act.append(f"velocity at its {c['velocity_active']} bound")
    lines.append("active constraints: " + (", ".join(act) if act else "none"))
    if s["warm_start"]:
        lines.append(f"exact method: {s['warm_start']}")
    for b in s["bounds_diagnosis"]:
        lines.append(b)
    if s["existence"]:
        lines.append(f"why the exact striker stops: {s['existence']}")
    v = s["verification"]
    if v:
        lines.append(f"verification with the direct solver: max deviation {v['max_deviation']:.2e} from the "
                     f"design's run")
    lines.append(f"{s['iterations']} iterations, {s['forward_runs']} forward and {s['gradient_runs']} gradient runs, "
                 f"{s['wall_time_s']:.3g} s")
    for w in s["warnings"]:
        lines.append(f"warning: {w}")
    return "\n".join(lines)


def write_files(r: DesignRun, spec: DesignSpec, folder: Path) -> list[str]:
    """Write the data files of a design into the (new) ``folder`` and return their names: ``spec.toml``,
    ``striker.csv`` (profile listed left to right, readable by ``[rods.elements] file``) and ``design.nc``. The
    command line's output folder adds ``verification/`` (the direct simulation with its ``model.toml``),
    ``plots/`` and ``summary.json`` (:func:`rodimpact.output_folders.write_spec_run`)."""
    res = r.result
    (folder / "spec.toml").write_text(spec.text, encoding="utf-8")
    limits = spec.kwargs["limits"]
    res.to_csv(folder / "striker.csv", limits.material, limits.bore)
    save(res, folder / "design.nc")
    return ["spec.toml", "striker.csv", "design.nc"]


# ============================================================================================ template
TEMPLATE = '''\
# rodimpact design spec -- run it with:   rodimpact design design.toml -o results/design
#
# Finds the best striker that can exist and be machined: the impedance profile (n elements of travel time dt,
# counted from the impact face) that minimises an objective inside diameter (or impedance) bounds, with an
# optional mass, free impact velocity and a maximum number of steps (docs/design.md). Quantities take units
# ("20 mm", "80 kN"); bare numbers are SI. Forces are positive in tension: an impact force is negative.
#
# This template: a half-sine pulse of 80 kN and 100 us on a 20 mm steel Hopkinson bar (non-reflecting far
# end), steel striker of 5..60 mm at 12 m/s. The exact recursive method cannot produce it (a force cannot
# start at 0 N); design returns the closest striker and says why the exact one does not exist.

title = "Half-sine striker for a Hopkinson bar"
far_end = "nonreflecting"      # or "free", "fixed", { type = "bit-rock", loading_stiffness = "300 MN/m" }

[design]
objective = "match"            # or "efficiency" (needs a bit-rock far end and no [target])
elements = 25                  # n striker elements of travel time dt (a window of 2 dt each)
dt = "2 us"
# max_steps = 3                # a stepped striker with at most 3 cylinders
# smoothness = 0.01            # total-variation penalty
starts = 2                     # starting profiles, each continued from a coarse to the free profile
max_iterations = 50            # L-BFGS-B iterations per start
# improvement = 1e-6           # stop a run when it improves by less than this fraction over 10 iterations
# reloading = false            # efficiency: first pass only (Lundberg's classical efficiency)
# elements_min = 10            # efficiency with a striker mass: the piston may be 10..elements long

[striker]
velocity = "12 m/s"
# velocity_min = "8 m/s"       # optimise the velocity too, within these bounds
# velocity_max = "16 m/s"
material = "steel"
diameter_min = "5 mm"          # or impedance_min / impedance_max
diameter_max = "60 mm"
bore = "0 mm"
# mass = "0.2 kg"              # or mass_min / mass_max

[target]
type = "expression"            # any target of a synthesis spec
force = "-80e3 * sin(pi * t / 100e-6)"
duration = "100 us"

[[struck]]
name = "bar"
velocity = "0 m/s"

[[struck.segments]]
shape = "cylinder"
length = "1.0 m"
diameter = "20 mm"

[output]
plots = true
'''
