"""Synthesis specifications: TOML files for ``rodimpact synthesize`` (the inverse problem, thesis chapter 4).

A spec names the struck system (``[[struck]]`` rods listed from the impact face outwards, written like the
``[[rods]]`` of a model file), its far end, the striker's velocity and material, and the prescribed force
(``[target]``: a thesis target, an expression of ``t``, samples, a CSV file or window values; optionally at a
``position`` inside the struck system). :func:`run` calls :func:`rodimpact.synthesize`, checks the result with
the direct solver and derives the striker's shape; :func:`write_files` writes its data files (the command line's
folder with figures: :mod:`rodimpact.output_folders`).

Keys are listed in ``docs/cli.md`` (generated from :data:`SPEC` by :func:`spec_reference_markdown`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional

import numpy as np

from ..rods.material import STEEL
from .dimensions import Parameters, check_dimension
from .expressions import SafeExpression
from .model import (_element, _junctions, _loads, _material, _materials, _rod, _wrap, parse_toml,
                    read_csv_columns, read_text_file)
from .overrides import spec_with_overrides
from .quantities import ModelError
from .schema import (END_TYPES, JUNCTION_TYPES, LOAD_TYPES, MATERIAL, ROD, Field, Table, Variants, _q, _table_md,
                     validate_table)
from .storage import save


# ============================================================================================ schema
_COMMON = (
    Field("rule", "string", "How a continuous target becomes the window values X_j on [2(j-1)dt, 2j dt): "
                            "`midpoint` (F at the window centre, default), `start` (the thesis's convention), "
                            "`mean` (window average).", default="midpoint", choices=("midpoint", "start", "mean")),
    _q("position", "length", "Prescribe the force at this distance from the impact face inside the struck system "
                             "(thesis Sec. 4.1.2); time then counts from the wavefront's arrival. Default: at the "
                             "impact face.", sign="non_negative", required=False),
    Field("quantity", "string", "With `position`: the normal `force` there or the `incident` force wave.",
          default="force", choices=("force", "incident")),
)
TARGET_TYPES = {
    "exponential-decay": Table("exponential-decay", "N(t) = -peak exp(-t / time_constant) (thesis eq. 4.24).", (
        _q("peak", "force", "Magnitude at t = 0."), _q("time_constant", "time", "Time constant.")) + _COMMON),
    "linear-ramp": Table("linear-ramp", "N(t) = -peak (1 + 2 t / time_constant) (thesis eq. 4.28).", (
        _q("peak", "force", "Magnitude at t = 0."), _q("time_constant", "time", "Time constant.")) + _COMMON),
    "exponential-growth": Table("exponential-growth", "N(t) = -initial exp(rate t) (thesis eq. 4.29, percussive "
                                                      "drilling).", (
        _q("initial", "force", "Magnitude at t = 0 (N^ of Tab. 4.5)."),
        _q("rate", "rate", "Growth rate C (Tab. 4.5: 5.88 1/ms).", sign=None)) + _COMMON),
    "expression": Table("expression", "An expression of `t` in SI units (N, tension positive).", (
        Field("force", "expression", "Force N(t).", required=True, variables=("t",)),
        _q("duration", "time", "Time span the target covers (sets the number of elements if "
                               "`striker.elements` is not given).", required=False)) + _COMMON),
    "samples": Table("samples", "Samples interpolated linearly.", (
        Field("time", "quantities", "Sample times.", dimension="time", sign="non_negative", required=True),
        Field("force", "quantities", "Forces (tension positive).", dimension="force", sign=None,
              required=True)) + _COMMON),
    "file": Table("file", "Samples from a CSV file with two columns, time and force (units in the header, e.g. "
                          "`time [ms]`, `force [kN]`; default SI).", (
        Field("file", "string", "CSV file, relative to the spec.", required=True),) + _COMMON),
    "windows": Table("windows", "The window values X_1..X_n directly.", (
        Field("values", "quantities", "Window values.", dimension="force", sign=None, required=True),) + _COMMON),
}

STRIKER = Table("striker", "The striker to be found.", (
    _q("velocity", "velocity", "Initial velocity v_in towards the struck system (> 0)."),
    Field("material", "string", "Material for lengths and the shape (preset or `[materials]`); default `steel`."),
    Field("elements", "integer", "Number n of striker elements (= force windows); default: as many as the target "
                                 "covers.", minimum=1),
    _q("bore", "length", "Central bore of the shape (0: solid).", sign="non_negative", required=False, default=0.0),
    _q("max_diameter_ratio", "dimensionless", "Outer-diameter ratio above which the shape is reported as "
                                              "impractical.", required=False, default=10.0),
), '[striker]\nvelocity = "6 m/s"\nelements = 100')

SYNTHESIS = Table("synthesis", "Numerical settings.", (
    _q("dt", "time", "Travel time of one element (windows are 2 dt long); default: that of impedance-level "
                     "struck rods.", required=False),
    Field("backend", "string", "`numba` or `numpy`.", default="numba", choices=("numba", "numpy")),
    Field("verify", "boolean", "Simulate the synthesized striker against the struck system and report the "
                               "deviation from the target.", default=True),
))

SPEC_OUTPUT = Table("output", "What to write.", (
    Field("plots", "boolean", "Write the plots.", default=True),
))

SPEC = Table("synthesis spec", "Top level of a synthesis spec.", (
    Field("title", "string", "Short title."),
    Field("description", "string", "Free text."),
    Field("parameters", "parameters", "Named constants for expressions, converted to SI."),
    Field("materials", "mapping", "Named materials (as in model files).", table=MATERIAL),
    Field("striker", "table", "The striker.", table=STRIKER, required=True),
    Field("target", "variant", "The prescribed force, chosen by `type`.", required=True,
          variants=Variants("type", TARGET_TYPES)),
    Field("struck", "tables", "The struck system: rods from the impact face outwards, with the keys of "
                              "`[[rods]]` in model files.", table=ROD, required=True, minimum=1),
    Field("junctions", "tables", "Between struck rods; default bonded.", variants=Variants("type", JUNCTION_TYPES)),
    Field("far_end", "variant", "Condition at the far end of the struck system.", default="free",
          variants=Variants("type", END_TYPES)),
    Field("loads", "tables", "Loads on struck rods.", variants=Variants("type", LOAD_TYPES)),
    Field("synthesis", "table", "Numerical settings.", table=SYNTHESIS),
    Field("output", "table", "Output settings.", table=SPEC_OUTPUT),
))


def spec_reference_markdown() -> str:
    """Reference tables of the spec keys (included in docs/cli.md)."""
    lines: list[str] = []
    _table_md("Top level", SPEC, 3, lines)
    _table_md("`[striker]`", STRIKER, 3, lines)
    lines.extend(["### `[target]`", "", "Chosen by `type`; every type also takes `rule`, `position` and "
                  "`quantity`.", ""])
    for name, t in TARGET_TYPES.items():
        _table_md(f"type = \"{name}\"", t, 4, lines, key="type")
    _table_md("`[synthesis]`", SYNTHESIS, 3, lines)
    _table_md("`[output]`", SPEC_OUTPUT, 3, lines)
    lines.append("`[[struck]]`, `[[junctions]]`, `far_end` and `[[loads]]` take the keys of `[[rods]]`, "
                 "`[[junctions]]`, `[ends]` entries and `[[loads]]` in model files (`rodimpact docs model`); "
                 "rod references in `loads` name struck rods.")
    return "\n".join(lines) + "\n"


# ============================================================================================ spec objects
@dataclass(frozen=True, eq=False)
class SynthesisSpec:
    """A validated synthesis specification: the arguments of :func:`rodimpact.synthesize` plus output settings."""

    target: Any
    struck: tuple
    striker_velocity: float
    n: Optional[int]
    dt: Optional[float]
    far_end: Any
    struck_velocity: tuple[float, ...]
    junctions: Optional[list]
    loads: tuple
    initial: Optional[list]
    position: Optional[float]
    quantity: str
    rule: str
    material: Any
    bore: float
    max_diameter_ratio: float
    backend: str = "numba"
    verify: bool = True
    plots: bool = True
    title: str = ""
    text: str = ""
    source: Optional[Path] = None

    def synthesize(self):
        """Run :func:`rodimpact.synthesize` with these settings; errors name the spec's keys (``synthesis.dt``,
        ``striker.elements``), see :mod:`rodimpact.io.keypaths`."""
        from .keypaths import SPEC_KEYS, translated

        try:
            return self._synthesize()
        except ModelError:
            raise
        except (ValueError, TypeError) as exc:
            raise translated(exc, SPEC_KEYS) from None

    def _synthesize(self):
        from ..inverse import synthesize

        from ..rods.system import System

        struck = System.struck(list(self.struck), self.far_end, list(self.struck_velocity), junctions=self.junctions,
                               loads=self.loads, initial=self.initial)
        return synthesize(self.target, struck, self.striker_velocity, self.n, self.dt, position=self.position,
                          quantity=self.quantity, rule=self.rule, material=self.material, backend=self.backend)


def load_spec(path: str | Path, overrides: Optional[Mapping[str, Any]] = None) -> SynthesisSpec:
    """Read a synthesis spec file (relative file names are resolved against its folder); ``overrides``: key path ->
    value, set before the spec is validated (:mod:`rodimpact.io.overrides`)."""
    p = Path(path)
    text = read_text_file(p, str(p), "spec file")
    spec = loads_spec(text, p.parent, str(p), overrides)
    object.__setattr__(spec, "source", p)
    return spec


def loads_spec(text: str, base_dir: str | Path = ".", name: str = "spec",
               overrides: Optional[Mapping[str, Any]] = None) -> SynthesisSpec:
    """Read a synthesis spec from TOML text (``overrides`` as in :func:`load_spec`)."""
    return spec_with_overrides(parse_toml(text, name), overrides, name, text,
                               lambda raw, given: _spec(raw, Path(base_dir), given))


def _spec(raw: dict, base: Path, text: str) -> SynthesisSpec:
    """The validated spec of the parsed file ``raw`` (``text``: the file as given)."""
    d = validate_table(SPEC, raw, "")
    params = Parameters(d["parameters"] or {}, raw.get("parameters") or {})
    materials = _materials(d["materials"] or {})
    syn = d["synthesis"] or {"dt": None, "backend": "numba", "verify": True}
    rods, vel, initial, junctions, far_end, loads = read_struck(d, params, materials, syn["dt"], base)
    st = d["striker"]
    if not st["velocity"] > 0:
        raise ModelError(f"striker.velocity: must be > 0 (towards the struck system), got {st['velocity']:g} m/s")
    mat = _material(st["material"], materials, "striker.material") or STEEL
    t = d["target"]
    target = _wrap("target", lambda: _target(t, params, base))
    out = d["output"] or {"plots": True}
    return SynthesisSpec(target=target, struck=tuple(rods), striker_velocity=st["velocity"], n=st["elements"],
                         dt=syn["dt"], far_end=far_end, struck_velocity=tuple(vel), junctions=junctions,
                         loads=tuple(loads), initial=initial if any(s is not None for s in initial) else None,
                         position=t["position"], quantity=t["quantity"], rule=t["rule"], material=mat,
                         bore=st["bore"], max_diameter_ratio=st["max_diameter_ratio"], backend=syn["backend"],
                         verify=syn["verify"], plots=out["plots"], title=d["title"] or "", text=text)


def read_struck(d: dict, params: Parameters, materials: dict, dt: Optional[float], base: Path) -> tuple:
    """The struck system of a validated spec (keys ``struck``, ``junctions``, ``far_end``, ``loads``): rods,
    velocities, initial states, junctions, far end and loads (also used by design specs)."""
    rods, vel, initial = [], [], []
    for i, r in enumerate(d["struck"]):
        rod, st = _rod(r, f"struck[{i}]", materials, params, dt, base)
        rods.append(rod)
        vel.append(r["velocity"])
        initial.append(st)
    names = {r.name: i for i, r in enumerate(rods) if r.name is not None}
    junctions = _junctions(d["junctions"], len(rods), params, base, "struck rods")
    far_end = _element("end", d["far_end"], "far_end", params, base)
    loads = _loads(d["loads"] or [], rods, names, params, base)
    return rods, vel, initial, junctions, far_end, loads


def _target(t: dict, params: dict[str, float], base: Path) -> Any:
    from ..inverse import ExponentialDecay, ExponentialGrowth, LinearRamp
    from ..inverse.targets import ForceTarget

    kind = t["type"]
    if kind == "exponential-decay":
        return ExponentialDecay(t["peak"], t["time_constant"])
    if kind == "linear-ramp":
        return LinearRamp(t["peak"], t["time_constant"])
    if kind == "exponential-growth":
        return ExponentialGrowth(t["initial"], t["rate"])
    if kind == "expression":
        f = SafeExpression(t["force"], ("t",), params, path="target.force")
        check_dimension(f, "force", {"t": "time"}, params)
        f(np.zeros(1))       # at the impact; synthesize checks every window it uses
        if t["duration"] is not None:
            return ForceTarget.from_callable(f, t["rule"], duration=t["duration"])
        return f
    if kind == "samples":
        if len(t["time"]) != len(t["force"]) or len(t["time"]) < 2:
            raise ModelError(f"target: time and force need the same number (>= 2) of entries, got "
                             f"{len(t['time'])} and {len(t['force'])}")
        return (np.array(t["time"]), np.array(t["force"]))
    if kind == "file":
        cols = read_csv_columns(base / t["file"], "target.file", None, positional=("time", "force"))
        return (cols["time"], cols["force"])
    if not t["values"]:
        raise ModelError("target.values: needs at least one window value")
    return np.array(t["values"])


# ============================================================================================ running, saving
@dataclass
class SynthesisRun:
    """A synthesis result with its verification and the striker's shape."""

    result: Any
    verification: Any = None
    shape: Any = None
    warnings: list[str] = field(default_factory=list)


def run(spec: SynthesisSpec) -> SynthesisRun:
    """Synthesize, verify with the direct solver (if ``spec.verify``) and derive the shape."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = spec.synthesize()
        verification = result.verify(spec.backend) if spec.verify and result.n_feasible > 0 else None
        shape = result.shape(spec.material, spec.bore, spec.max_diameter_ratio) if result.n_feasible else None
    # the existence diagnosis is the summary's own line (format_summary): not repeated as a warning
    repeated = None if result.failure is None else (
        f"only {result.n_feasible} of {result.n_requested} striker elements exist: {result.failure.message}")
    return SynthesisRun(result, verification, shape, [str(w.message) for w in caught if str(w.message) != repeated])


def summarize_run(r: SynthesisRun, spec: SynthesisSpec) -> dict[str, Any]:
    """Key numbers of a synthesis (JSON-ready, SI units)."""
    res = r.result
    out: dict[str, Any] = {"title": spec.title, "n_requested": res.n_requested, "n_feasible": res.n_feasible,
                           "feasible": bool(res.feasible),
                           # the exact striker's span: windows 1..m of 2 dt each at the impact face
                           "exact_span_s": 2.0 * res.n_feasible * res.dt,
                           "requested_span_s": 2.0 * res.n_requested * res.dt,
                           "failure": None if res.failure is None else res.failure.message,
                           "dt_s": res.dt, "striker_velocity_m_s": res.striker_velocity,
                           "impact_force_n0_N": res.impact_force_n0,
                           "position_m": None if res.position is None else float(res.position.used)}
    if r.shape is not None:
        s = r.shape
        out["striker"] = {"material": s.material.name, "length_m": s.length, "mass_kg": s.mass,
                          "impedance_min_N_s_per_m": float(res.impedance.min()),
                          "impedance_max_N_s_per_m": float(res.impedance.max()),
                          "outer_diameter_min_m": float(s.outer_diameter.min()),
                          "outer_diameter_max_m": float(s.outer_diameter.max()),
                          "diameter_ratio": s.diameter_ratio, "practical": bool(s.practical), "bore_m": s.bore}
    v = r.verification
    out["verification"] = None if v is None else {"compared": v.compared, "max_deviation": v.max_deviation,
                                                  "max_deviation_all_steps": v.max_deviation_all_steps}
    out["warnings"] = list(r.warnings)
    return out


def format_summary(summary: dict[str, Any], spec: SynthesisSpec) -> str:
    """A short text version of the summary."""
    lines = []
    m, n = summary["n_feasible"], summary["n_requested"]
    span = f"0 <= t < {summary['exact_span_s']:.4g} s"
    if not summary["feasible"]:
        lines.append(f"NO EXACT STRIKER: the target cannot be produced over the requested "
                     f"{summary['requested_span_s']:.4g} s; only elements 1..{m} of {n} exist "
                     f"(target produced for {span})" if m else
                     f"NO EXACT STRIKER: the target cannot be produced at all (not even element 1 of {n} exists)")
    if spec.title:
        lines.append(spec.title)
    lines.append(f"recursive method: {m} of {n} elements exist")
    if summary["failure"]:
        lines.append(summary["failure"])
    s = summary.get("striker")
    if s:
        lines.append(f"striker: length {s['length_m']:.4g} m, mass {s['mass_kg']:.4g} kg, impedance "
                     f"{s['impedance_min_N_s_per_m'] / 1e3:.4g} .. {s['impedance_max_N_s_per_m'] / 1e3:.4g} kN s/m, "
                     f"outer diameter {s['outer_diameter_min_m'] * 1e3:.4g} .. {s['outer_diameter_max_m'] * 1e3:.4g} "
                     f"mm{'' if s['practical'] else ' (impractical: diameter ratio %.3g)' % s['diameter_ratio']}")
    v = summary["verification"]
    if v:
        lines.append(f"verification with the direct solver: max deviation {v['max_deviation']:.2e} "
                     f"(relative, {v['compared']}"
                     + (")" if summary["feasible"] else f"; only over the span that exists, {span})"))
    if not summary["feasible"]:
        lines.append("the best striker that exists for the whole target: rodimpact design (rodimpact init design; "
                     "docs/design.md), with diameter, mass and velocity limits")
    for w in summary["warnings"]:
        lines.append(f"warning: {w}")
    return "\n".join(lines)


def write_files(r: SynthesisRun, spec: SynthesisSpec, folder: Path) -> list[str]:
    """Write the data files of a synthesis into the (new) ``folder`` and return their names: ``spec.toml`` (the
    spec as given), ``report.txt`` (per-element table, thesis Tabs. 4.3/4.4), ``striker.csv`` (profile listed left
    to right, impact face last: :meth:`StrikerShape.to_csv`; a model file reads it as a rod) and ``synthesis.nc``
    (all per-element arrays). The command line's output folder adds ``verification/``, ``plots/`` and
    ``summary.json`` (:func:`rodimpact.output_folders.write_spec_run`)."""
    res = r.result
    (folder / "spec.toml").write_text(spec.text, encoding="utf-8")
    (folder / "report.txt").write_text(res.report() + "\n", encoding="utf-8")
    files = ["spec.toml", "report.txt"]
    if r.shape is not None:
        r.shape.to_csv(folder / "striker.csv",
                       note=f"synthesized striker; impact velocity {res.striker_velocity!r} m/s")
        files.append("striker.csv")
    save(res, folder / "synthesis.nc")
    files.append("synthesis.nc")
    return files


# ============================================================================================ template
TEMPLATE = '''\
# rodimpact synthesis spec -- run it with:   rodimpact synthesize synthesis.toml -o results/synthesis
#
# Finds the striker (impedance profile, then a shape) that produces a prescribed force history, with the
# recursive method of the thesis (chapter 4). Quantities take units ("50 mm", "239 kN"); bare numbers are SI.
# Forces are positive in tension: an impact force is negative. All keys: rodimpact docs synthesis.
#
# This template: thesis academic example 1 (Tab. 4.2): the exponentially decaying force
# N(t) = -239 kN exp(-t / 0.383 ms) at the impact face of a semi-infinite 50 mm steel bar (Z = 79.7 kN s/m),
# striker velocity 6 m/s, 100 elements of dt = 1.93 us. Lundberg and Lesser's exact solution is eq. 4.26.

title = "Striker for an exponentially decaying impact force"

# The far end of the struck system: "free", "fixed", "nonreflecting" (semi-infinite), or an inline table such as
# { type = "bit-rock", loading_stiffness = "300 MN/m" } (percussion drilling, thesis Fig. 4.9).
far_end = "nonreflecting"

[striker]
velocity = "6 m/s"             # v_in, towards the struck system
material = "steel"             # sets lengths and the shape; the impedances do not depend on it
elements = 100                 # n: striker elements = force windows of 2 dt
bore = "0 mm"                  # central bore of the shape (0 = solid)
max_diameter_ratio = 10        # warn when the outer diameter varies more than this

[target]
type = "exponential-decay"     # or linear-ramp, exponential-growth, expression, samples, file, windows
peak = "239 kN"
time_constant = "0.383 ms"
rule = "start"                 # window value = F at the window start (the thesis's convention); or midpoint, mean
# position = "1.0 m"           # prescribe the force inside the struck system instead (thesis Sec. 4.1.2)
# quantity = "incident"        # ... as the incident force wave there (percussion drilling, Fig. 4.10)

# The struck system, from the impact face outwards; the keys of [[rods]] in model files.
[[struck]]
name = "bar"
velocity = "0 m/s"

[[struck.segments]]
shape = "cylinder"
length = "1.0 m"
diameter = "50 mm"             # Z = 79.7 kN s/m for steel

[synthesis]
dt = "1.93 us"                 # travel time of one element
backend = "numba"
verify = true                  # simulate the striker and report the deviation from the target

[output]
plots = true
'''
