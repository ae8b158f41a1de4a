"""Model files: TOML descriptions of a simulation -> :class:`Model` (rodimpact objects) -> TOML.

A model file describes everything :func:`rodimpact.simulate` accepts: materials, rods (segments of any shape,
tabulated profiles from CSV files, area expressions, impedance-level rods), junctions, end conditions, nodal
loads and bearings, initial velocities and states, probes, discretisation and output requests. The keys are
listed in ``docs/model-reference.md`` (generated from :mod:`rodimpact.io.schema`).

Quantities are numbers in SI units or strings with units (``"50 mm"``); everything is converted to SI here.
Errors are :class:`~rodimpact.io.quantities.ModelError` (a ``ValueError``) whose message starts with the key
path: ``rods[1].segments[2].diameter: must be > 0, got -5 mm``.

:func:`dump_model` writes a :class:`Model` back as a self-contained TOML file in bare SI numbers (unit comments
at the end of each line); floats are written with their shortest round-trip representation, so loading the
written file gives identical objects.
"""

from __future__ import annotations

import csv
import functools
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence

import numpy as np

from .._version import __version__
from .._validate import fits_in_memory
from ..direct.problem import Problem, TimeGrid
from ..direct.recording import Outputs
from ..direct.result import Probe, SimulationResult
from ..rods.conditions import Contact
from ..rods.declared import ELEMENTS, declarations, has_default, type_name
from ..rods.history import History
from ..rods.material import MATERIALS, STEEL, Material
from ..rods.plausibility import KeyPath
from ..rods.rod import Rod
from ..rods.segments import AreaFunction, Segment, TabulatedProfile, stepped_profile
from ..rods.system import InitialState, System
from . import _toml
from ._files import read_bytes_limited, write_text_atomic
from .dimensions import Parameters, check_dimension
from .expressions import SafeExpression, expression_area
from .overrides import apply_overrides, naming_overrides
from .quantities import DIMENSIONS, ModelError, parse_quantity
from .schema import MODEL, PLOT_NAMES, validate_table

DEFAULT_PLOTS: tuple[str, ...] = ("forces", "profile", "snapshots", "xt", "energy")


@dataclass(frozen=True)
class OutputSpec:
    """Output requests of a model file (``[output]``).

    ``snapshot_times`` (s) are recorded as they are; in addition ``snapshot_every`` steps, or, if that is not
    given, about ``snapshot_count`` evenly spaced snapshots (``None``: none) for x-t diagrams and animations.
    ``record_every``: keep every n-th step of the signal histories (1: all).
    """

    snapshot_times: tuple[float, ...] = ()
    snapshot_every: Optional[int] = None
    snapshot_count: Optional[int] = 200
    plots: tuple[str, ...] = DEFAULT_PLOTS
    csv: bool = True
    fields: bool = True
    record_every: int = 1

    def __post_init__(self) -> None:
        for i, p in enumerate(self.plots):
            if p not in PLOT_NAMES:
                raise ValueError(f"output.plots: unknown plot {p!r}; valid: {', '.join(PLOT_NAMES)}")
            if p in self.plots[:i]:
                raise ValueError(f"output.plots[{i}]: {p!r} is listed twice")


@dataclass(frozen=True, eq=False)
class Model:
    """A complete simulation description: the :class:`~rodimpact.System` plus run and output settings.

    Exactly one of ``duration`` (s) and ``steps`` is given; ``dt`` (s) may be ``None`` (the solver's default).
    ``parameters`` are the named constants used by expressions (SI values).
    """

    system: System
    duration: Optional[float] = None
    steps: Optional[int] = None
    dt: Optional[float] = None
    probes: tuple[Probe, ...] = ()
    output: OutputSpec = field(default_factory=OutputSpec)
    backend: str = "numba"
    energy_every: Optional[int] = None
    title: str = ""
    description: str = ""
    parameters: dict[str, float] = field(default_factory=dict)
    source: Optional[Path] = None
    allow_discretization_error: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.system, System):
            raise TypeError(f"Model.system: must be a System, got {type(self.system).__name__}")
        if (self.duration is None) == (self.steps is None):
            raise ValueError("simulation: give exactly one of duration (s) or steps")
        object.__setattr__(self, "probes", tuple(self.probes))

    @functools.cached_property
    def time(self) -> TimeGrid:
        """The run's :class:`~rodimpact.direct.problem.TimeGrid`: ``dt`` (or the solver's default for this system)
        and the number of steps (``steps``, or ``duration`` rounded as :meth:`TimeGrid.of` does)."""
        return TimeGrid.of(self.system, duration=self.duration, steps=self.steps, dt=self.dt)

    @property
    def time_step(self) -> float:
        """The time step the run will use, s (``dt`` or the solver's default for this system)."""
        return self.time.dt

    @property
    def n_steps(self) -> int:
        """Number of time steps of the run."""
        return self.time.steps

    def snapshot_every(self) -> Optional[int]:
        """The snapshot stride in steps implied by ``output`` (``None``: only ``snapshot_times``)."""
        if self.output.snapshot_every is not None:
            return self.output.snapshot_every
        if self.output.snapshot_count:
            return max(1, self.n_steps // self.output.snapshot_count)
        return None

    @property
    def problem(self) -> Problem:
        """The run as a :class:`~rodimpact.direct.problem.Problem`: the system, :attr:`time` and the outputs the
        file declares (probes, snapshots, energy and history strides), and ``allow_discretization_error``."""
        outputs = Outputs(probes=self.probes, snapshot_times=list(self.output.snapshot_times) or None,
                            snapshot_every=self.snapshot_every(), energy_every=self.energy_every,
                            record_every=self.output.record_every)
        return Problem(self.system, self.time, outputs, self.allow_discretization_error)

    def simulate(self, *, progress: Optional[bool] = None, backend: Optional[str] = None,
                 max_element_updates: Optional[float] = None) -> SimulationResult:
        """Run :func:`rodimpact.simulate` with this model's settings (``max_element_updates``: see there); errors
        name the model file's keys (``simulation.dt``, ``rods[1].initial.force``), see
        :mod:`rodimpact.io.keypaths`."""
        from ..direct.simulate import simulate
        from .keypaths import MODEL_KEYS, translated

        try:
            return simulate(self.problem, backend=backend or self.backend, progress=progress,
                            max_element_updates=max_element_updates)
        except ModelError:
            raise
        except (ValueError, TypeError) as exc:
            raise translated(exc, MODEL_KEYS) from None


# ============================================================================================ reading
def read_text_file(path: Path, label: str, kind: str, encoding: str = "utf-8-sig") -> str:
    """The text of ``path`` (read by :func:`read_bytes_limited`); every way of failing becomes a
    :class:`ModelError` that starts with ``label`` (the key path, or the file itself) and says what kind of file
    was expected. A UTF-8 byte-order mark is dropped; the content is never shown in messages."""
    data = read_bytes_limited(Path(path), label, kind)
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as exc:
        raise ModelError(f"{label}: {str(path)!r} is not a text file ({exc.reason} at byte {exc.start}); expected "
                         f"a {kind}") from None


#: Deepest nesting of arrays and tables accepted in a model or spec file (the schema needs 5).
MAX_NESTING = 32


def parse_toml(text: str, name: str) -> dict:
    """Parse TOML ``text``; every failure (syntax, nesting too deep for the parser, an integer beyond the
    conversion limit) and nesting deeper than :data:`MAX_NESTING` is a :class:`ModelError` naming ``name`` and,
    for nesting, the key path."""
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{name}: not valid TOML: {exc}") from None
    except RecursionError:
        raise ModelError(f"{name}: arrays or tables nested too deeply (at most {MAX_NESTING} levels)") from None
    except (ValueError, MemoryError, OverflowError) as exc:
        raise ModelError(f"{name}: not valid TOML: {type(exc).__name__}: {str(exc)[:200]}") from None
    _check_nesting(raw)
    return raw


def _check_nesting(raw: dict) -> None:
    """Raise a :class:`ModelError` naming the key path where ``raw`` nests deeper than :data:`MAX_NESTING`
    (iteratively, so that the check itself cannot overflow the stack). Only tables and arrays are visited, and
    the key path is spelled out only for the error (a file of 10^6 numbers costs no strings)."""
    # entries: (container, parent entry, key in the parent, depth)
    stack: list[tuple[Any, Any, Any, int]] = [(raw, None, None, 0)]
    while stack:
        entry = stack.pop()
        value, _, _, depth = entry
        items = value.items() if isinstance(value, dict) else enumerate(value)
        if depth + 1 > MAX_NESTING and value:          # its entries lie deeper than allowed
            k, v = list(items)[-1]                       # the entry the former depth-first walk named
            raise ModelError(f"{_entry_path((v, entry, k, depth + 1))}: arrays or tables nested too deeply "
                             f"(at most {MAX_NESTING} levels)")
        for k, v in items:
            if isinstance(v, (dict, list)):
                stack.append((v, entry, k, depth + 1))


def _entry_path(entry: tuple[Any, Any, Any, int]) -> str:
    """The key path of an entry of :func:`_check_nesting`'s stack (``rods[0].segments[1].x``)."""
    keys = []
    while entry[1] is not None:
        keys.append(entry[2])
        entry = entry[1]
    path = ""
    for k in reversed(keys):
        path = f"{path}[{k}]" if isinstance(k, int) else (f"{path}.{_toml.key(str(k))}" if path
                                                          else _toml.key(str(k)))
    return path


def load_model(path: str | Path, overrides: Optional[Mapping[str, Any]] = None) -> Model:
    """Read a model file; relative file names inside it are resolved against its folder. ``overrides``: key path
    -> value, set before the file is validated (``{"rods.piston.velocity": "5 m/s"}``, see
    :mod:`rodimpact.io.overrides`)."""
    p = Path(path)
    text = read_text_file(p, str(p), "model file")
    model = loads_model(text, base_dir=p.parent, name=str(p), overrides=overrides)
    object.__setattr__(model, "source", p)
    return model


def loads_model(text: str, base_dir: str | Path | None = None, name: str = "model",
                overrides: Optional[Mapping[str, Any]] = None) -> Model:
    """Read a model from TOML text (``base_dir``: folder for relative file names, default the current one;
    ``overrides`` as in :func:`load_model`)."""
    raw = parse_toml(text, name)
    # apply_overrides works on a deep copy: skipped without overrides (the copy of a 30 MB file costs seconds)
    raw, applied = apply_overrides(raw, overrides) if overrides else (raw, {})
    with naming_overrides(applied):
        return model_from_dict(raw, base_dir=Path(base_dir) if base_dir is not None else Path("."))


def model_from_dict(raw: dict, base_dir: Path = Path(".")) -> Model:
    """Build a :class:`Model` from parsed TOML data (validated against :data:`rodimpact.io.schema.MODEL`).

    Every error of the data is a :class:`ModelError` (docs/security.md promises it): the checks below raise it
    with the key path; a ``ValueError``/``TypeError`` of the library that a check missed is turned into one here,
    message unchanged, rather than escaping as a plain exception."""
    try:
        return _model_from_dict(raw, base_dir)
    except ModelError:
        raise
    except (ValueError, TypeError) as exc:
        raise ModelError(str(exc)) from exc


def _duplicate_rod_names(raw: dict) -> None:
    """Refuse a rod name used twice, from the parsed file before anything is validated or built, so that a
    duplicate at ``rods[1]`` of a file with 10,000 rods is reported at once (the names' types are checked by
    the schema later; only strings are compared here)."""
    rods = raw.get("rods")
    if not isinstance(rods, list):
        return
    names: dict[str, int] = {}
    for i, r in enumerate(rods):
        name = r.get("name") if isinstance(r, dict) else None
        if isinstance(name, str):
            if name in names:
                raise ModelError(f"rods[{i}].name: {name!r} is already the name of rods[{names[name]}]")
            names[name] = i


def _model_from_dict(raw: dict, base_dir: Path) -> Model:
    _duplicate_rod_names(raw)
    d = validate_table(MODEL, raw, "")
    params = Parameters(d["parameters"] or {}, raw.get("parameters") or {})
    materials = _materials(d["materials"] or {})
    rods, velocities, initial = [], [], []
    sim = d["simulation"]
    for i, r in enumerate(d["rods"]):
        rod, st = _rod(r, f"rods[{i}]", materials, params, sim["dt"], base_dir, raw["rods"][i])
        rods.append(rod)
        velocities.append(r["velocity"])
        initial.append(st)
    names = {}
    for i, rod in enumerate(rods):
        if rod.name is not None:
            if rod.name in names:
                raise ModelError(f"rods[{i}].name: {rod.name!r} is already the name of rods[{names[rod.name]}]")
            names[rod.name] = i
    n = len(rods)
    junctions = _junctions(d["junctions"], n, params, base_dir)
    ends = d["ends"] or {"left": {"type": "free"}, "right": {"type": "free"}}
    left, right = (_element("end", ends[side], f"ends.{side}", params, base_dir) for side in ("left", "right"))
    loads = _loads(d["loads"] or [], rods, names, params, base_dir)
    probes = []
    seen: dict[str, int] = {}
    for i, p in enumerate(d["probes"] or []):
        path = f"probes[{i}]"
        if p["name"] in seen:
            raise ModelError(f"{path}.name: {p['name']!r} is already used by probes[{seen[p['name']]}]")
        seen[p["name"]] = i
        k = _rod_index(p["rod"], names, n, f"{path}.rod")
        if p["position"] > rods[k].length * (1 + 1e-12):
            raise ModelError(f"{path}.position: must lie within rod {k}, 0 <= x <= {rods[k].length:.6g} m, "
                             f"got {p['position']:.6g} m")
        probes.append(_wrap(path, lambda: Probe(p["name"], k, p["position"])))
    if (sim["duration"] is None) == (sim["steps"] is None):
        raise ModelError("simulation: give exactly one of duration (e.g. \"1 ms\") or steps")
    out = d["output"] or {f.name: f.default for f in MODEL.field("output").table.fields}
    if sim["duration"] is not None and out["snapshot_times"]:
        for i, t in enumerate(out["snapshot_times"]):
            if t > sim["duration"] * (1 + 1e-12):
                raise ModelError(f"output.snapshot_times[{i}]: {t:.6g} s lies after the end of the run "
                                 f"(simulation.duration = {sim['duration']:.6g} s)")
    output = _wrap("model", lambda: OutputSpec(tuple(out["snapshot_times"] or ()), out["snapshot_every"],
                                               out["snapshot_count"], tuple(out["plots"]), out["csv"], out["fields"],
                                               out["record_every"]))
    with KeyPath("model", lambda key: _rod_written_with_units(raw, key)):
        system = _wrap("model", lambda: System(rods, velocities, junctions, left, right, loads,
                                               initial if any(s is not None for s in initial) else None))
    return Model(system, sim["duration"], sim["steps"], sim["dt"], tuple(probes), output, sim["backend"],
                 sim["energy_every"], d["title"] or "", d["description"] or "", dict(params),
                 allow_discretization_error=sim["allow_discretization_error"])


def _wrap(path: str, build, owner: Optional[str] = None):
    """Call ``build()``; re-raise errors of the core classes with the key path in front. With ``owner`` (the
    class's name), the message's ``Owner.field`` names become the file's key paths ``path.field`` instead, so a
    message that compares two fields names both keys."""
    try:
        return build()
    except ModelError:
        raise
    except (ValueError, TypeError) as exc:
        from .keypaths import MODEL_KEYS, translate

        msg = str(exc)
        if owner is not None and msg.startswith(f"{owner}."):
            raise ModelError(msg.replace(f"{owner}.", f"{path}.")) from None
        raise ModelError(translate(msg, MODEL_KEYS) if path == "model" else f"{path}: {msg}") from None


def _materials(table: dict[str, dict]) -> dict[str, Material]:
    known: dict[str, Material] = dict(MATERIALS)
    for name, m in table.items():
        path = f"materials.{_toml.key(name)}"
        if name in MATERIALS:
            raise ModelError(f"{path}: {name!r} is a preset name; choose another name")
        if m["base"] is not None:
            if m["base"] not in known:
                raise ModelError(f"{path}.base: unknown material {m['base']!r}; known: {', '.join(known)}")
            base = known[m["base"]]
            e = m["youngs_modulus"] if m["youngs_modulus"] is not None else base.youngs_modulus
            rho = m["density"] if m["density"] is not None else base.density
        else:
            for key in ("youngs_modulus", "density"):
                if m[key] is None:
                    raise ModelError(f"{path}.{key}: missing; give youngs_modulus and density, or a base material")
            e, rho = m["youngs_modulus"], m["density"]
        known[name] = _wrap(path, lambda: Material(e * m["youngs_factor"], rho * m["density_factor"], name))
    return known


def _material(name: Optional[str], known: dict[str, Material], path: str) -> Optional[Material]:
    if name is None:
        return None
    key = name if name in known else name.strip().lower()
    if key not in known:
        raise ModelError(f"{path}: unknown material {name!r}; known: {', '.join(known)} "
                         f"(define others in [materials.NAME])")
    return known[key]


#: a number followed by a unit name: "3.204 mm", "0.1 m", "1.26e-3 m^2"
_NUMBER_WITH_UNIT = re.compile(r"\s*[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\s*[A-Za-zµμ].*", re.DOTALL)


def _with_unit(value: Any) -> bool:
    """Whether a raw quantity (or every entry of a list of them) is written as a number with its unit
    (``"3.204 mm"``), so that its unit cannot have slipped; bare numbers, numbers in quotes and expressions of
    parameters are not."""
    if isinstance(value, list):
        return bool(value) and all(_with_unit(v) for v in value)
    return isinstance(value, str) and _NUMBER_WITH_UNIT.fullmatch(value) is not None


_GEOMETRY_KEYS = ("length", "diameter", "outer_diameter", "inner_diameter", "diameter_start", "diameter_end",
                  "area", "area_start", "area_end", "x")


def _rod_written_with_units(raw: dict, key: str) -> bool:
    """For a plausibility warning about ``rods[i]`` (a striker's mass): whether the file gives every length,
    diameter and area of that rod's segments with a unit."""
    m = re.fullmatch(r"rods\[(\d+)\]", key)
    if m is None:
        return False
    segments = raw["rods"][int(m.group(1))].get("segments")
    if not isinstance(segments, list) or not segments:
        return False
    return all(isinstance(s, dict) and all(_with_unit(s[k]) for k in _GEOMETRY_KEYS if k in s)
               and any(k in s for k in _GEOMETRY_KEYS) for s in segments)


def _rod(r: dict, path: str, materials: dict[str, Material], params: dict[str, float], sim_dt: Optional[float],
         base_dir: Path, raw_rod: Optional[dict] = None) -> tuple[Rod, Optional[InitialState]]:
    has_seg, has_el = r["segments"] is not None, r["elements"] is not None
    if has_seg == has_el:
        raise ModelError(f"{path}: give either [[{path.split('[')[0]}.segments]] (geometry) or "
                         f"[{path.split('[')[0]}.elements] (impedance level), {'not both' if has_seg else 'none given'}")
    if has_seg:
        if not r["segments"]:
            raise ModelError(f"{path}.segments: needs at least one segment")
        mat = _material(r["material"], materials, f"{path}.material") or STEEL
        segs, origin = [], []          # origin[k]: the file's segment of the rod's segment k (tables split)
        for j, s in enumerate(r["segments"]):
            pieces = _segment(s, f"{path}.segments[{j}]", materials, params, base_dir)
            segs.extend(pieces)
            origin.extend([j] * len(pieces))

        def written_with_unit(key: str) -> bool:
            m = re.fullmatch(rf"{re.escape(path)}\.segments\[(\d+)\]\.(\w+)", key)
            if m is None or raw_rod is None or not isinstance(raw_rod.get("segments"), list):
                return False
            seg = raw_rod["segments"][origin[int(m.group(1))]]
            return isinstance(seg, dict) and m.group(2) in seg and _with_unit(seg[m.group(2)])

        with KeyPath(path, written_with_unit):
            rod = _wrap(path, lambda: Rod(segs, mat, r["name"]))
    else:
        if r["material"] is not None:
            raise ModelError(f"{path}.material: an impedance-level rod has no material; give "
                             f"{path}.elements.wave_speed and density if they matter")
        rod = _elements(r["elements"], f"{path}.elements", r["name"], sim_dt, base_dir)
    with np.errstate(all="ignore"):
        travel = rod.total_travel_time
    if not 0.0 < travel < math.inf or not rod.length < math.inf:
        raise ModelError(f"{path}: its length ({rod.length:.6g} m) or wave travel time ({travel:.6g} s) is out of the "
                         f"range of floating point numbers; check the lengths of its segments")
    st = None
    if r["initial"] is not None and (r["initial"]["force"] is not None or r["initial"]["velocity"] is not None):
        ini = r["initial"]
        st = InitialState(force=_field_value(ini["force"], f"{path}.initial.force", params, "force"),
                          velocity=_field_value(ini["velocity"], f"{path}.initial.velocity", params, "velocity"))
    return rod, st




def _segment(s: dict, path: str, materials: dict[str, Material], params: dict[str, float],
             base_dir: Path) -> tuple[Segment, ...]:
    """The rod segment(s) of one ``[[rods.segments]]`` table: one segment, or for a ``table`` with steps (a
    repeated x) one per piece between the steps (:func:`rodimpact.rods.segments.stepped_profile`)."""
    mat = _material(s["material"], materials, f"{path}.material")
    if s["shape"] == "table":
        return _table(s, path, mat, base_dir)
    return (_shape(s, path, mat, params),)


def _shape(s: dict, path: str, mat: Optional[Material], params: dict[str, float]) -> Segment:
    """The segment of one ``[[rods.segments]]`` table of an analytic shape or an expression."""
    shape = s["shape"]
    if shape in ELEMENTS["segment"]:            # a registered shape: its declared fields
        cls = ELEMENTS["segment"][shape]
        values = {f.name: s[f.name] for f, _ in declarations(cls)}
        return _wrap(path, lambda: cls(**values, material=mat), cls.__name__)
    func = expression_area(s["area"], s["length"], params, path=f"{path}.area")    # shape == "expression"
    check_dimension(func, "area", {"s": "length", "L": "length"}, params)
    return _wrap(path, lambda: AreaFunction(s["length"], func, material=mat, name=s["area"]))


def _table(s: dict, path: str, mat: Optional[Material], base_dir: Path) -> tuple[TabulatedProfile, ...]:
    """The segments of a ``table`` shape: points inline or from a CSV file; a repeated x is a step."""
    inline = s["x"] is not None
    if s["file"] is not None and (inline or s["diameter"] is not None or s["area"] is not None):
        raise ModelError(f"{path}: give either file or the inline lists x and diameter/area, not both")
    if s["file"] is not None:
        cols = read_csv_columns(base_dir / s["file"], f"{path}.file",
                                {"x": "length", "diameter": "length", "area": "area", "impedance": "impedance"})
        if "x" not in cols or ("diameter" in cols) == ("area" in cols):
            hint = (f"; a file of element impedances (such as rodimpact's striker.csv) is read as a rod with "
                    f"[rods.elements] file = '{s['file']}'" if "impedance" in cols and "x" not in cols else "")
            raise ModelError(f"{path}.file: needs a column x and exactly one of diameter, area; found "
                             f"{', '.join(cols) or 'none'}{hint}")
        x, kind = cols["x"], "diameter" if "diameter" in cols else "area"
        values = cols[kind]
    else:
        if not inline or (s["diameter"] is None) == (s["area"] is None):
            raise ModelError(f"{path}: a table needs x and exactly one of diameter or area (or a file)")
        kind = "diameter" if s["diameter"] is not None else "area"
        x, values = s["x"], s[kind]
        if len(values) != len(x):
            raise ModelError(f"{path}.{kind}: needs one value per x ({len(x)}), got {len(values)}")
    return _wrap(path, lambda: stepped_profile(x, **{kind: values}, material=mat))


def _elements(e: dict, path: str, name: Optional[str], sim_dt: Optional[float], base_dir: Path) -> Rod:
    c = e["wave_speed"] if e["wave_speed"] is not None else STEEL.wave_speed
    if e["dt"] is not None and e["element_length"] is not None:
        raise ModelError(f"{path}: give dt or element_length, not both")
    given = [k for k in ("impedance", "runs", "file") if e[k] is not None]
    if len(given) != 1:
        raise ModelError(f"{path}: give exactly one of impedance, runs or file, got "
                         f"{', '.join(given) if given else 'none'}")
    file_dt = None
    if e["file"] is not None:
        cols = read_csv_columns(base_dir / e["file"], f"{path}.file", {"impedance": "impedance", "theta": "time"},
                                needed=("impedance",))
        z = np.asarray(cols["impedance"])
        if "theta" in cols:
            file_dt = _theta_spacing(cols["theta"], f"{path}.file", e["file"])
    key = "dt" if e["dt"] is not None else "element_length" if e["element_length"] is not None else None
    dt = e["dt"] if e["dt"] is not None else e["element_length"] / c if e["element_length"] is not None else \
        file_dt if file_dt is not None else sim_dt
    if dt is None:
        raise ModelError(f"{path}.dt: missing; give the element travel time dt or element_length here, or "
                         f"simulation.dt")
    if not 0.0 < dt < math.inf or not 0.0 < c * dt < math.inf:
        raise ModelError(f"{path}.{key or 'dt'}: gives an element travel time of {dt:.6g} s and an element length of "
                         f"{c * dt:.6g} m; both must be finite and > 0 (out of the range of floating point numbers)")
    if key is not None and file_dt is not None and abs(dt / file_dt - 1.0) > _SAME_DT:
        raise ModelError(f"{path}.{key}: gives an element travel time of {dt!r} s, but the theta column of "
                         f"{e['file']} is spaced by {file_dt!r} s, the dt the profile was made for; leave {key} "
                         f"out to use the file's dt")
    if e["impedance"] is not None:
        z = np.array(e["impedance"], dtype=float)
    elif e["file"] is None:
        parts = []
        counts = [_run_count(run, f"{path}.runs[{i}]", c * dt) for i, run in enumerate(e["runs"])]
        totals = np.cumsum(np.array(counts, dtype=float))
        # each element becomes a lattice element (about 128 bytes of state and history, as lattice.py counts);
        # the memory is asked for once (it costs ~0.1 ms), and the message names the first run that does not fit
        if totals.size and not _fits(_BYTES_PER_ELEMENT * totals[-1]):
            lo, hi = 0, totals.size - 1          # bisection: the first run whose running total does not fit
            while lo < hi:
                mid = (lo + hi) // 2
                lo, hi = (mid + 1, hi) if _fits(_BYTES_PER_ELEMENT * totals[mid]) else (lo, mid)
            i = lo
            rp, run = f"{path}.runs[{i}]", e["runs"][i]
            try:
                fits_in_memory(f"{rp}.{'count' if run['count'] is not None else 'length'}",
                               _BYTES_PER_ELEMENT * totals[i], f"{int(totals[i]):,} elements"
                               + (f" (runs[0..{i}])" if i else ""),
                               "use fewer elements (a larger dt or element_length, shorter runs)")
            except ValueError as exc:       # its message already names the key path
                raise ModelError(str(exc)) from None
        for i, (run, count) in enumerate(zip(e["runs"], counts)):
            rp = f"{path}.runs[{i}]"
            if run["impedance"] is not None:
                if run["impedance_start"] is not None or run["impedance_end"] is not None:
                    raise ModelError(f"{rp}: give impedance, or impedance_start and impedance_end, not both")
                parts.append(np.full(count, run["impedance"]))
            else:
                if run["impedance_start"] is None or run["impedance_end"] is None:
                    raise ModelError(f"{rp}: give impedance, or impedance_start and impedance_end")
                parts.append(np.linspace(run["impedance_start"], run["impedance_end"], count))
        z = np.concatenate(parts) if parts else np.empty(0)
    if z.size == 0:
        raise ModelError(f"{path}: needs at least one element")
    return _wrap(path, lambda: Rod.from_impedance(z, dt, c, density=e["density"], name=name))


_BYTES_PER_ELEMENT = 128.0


def _fits(n_bytes: float) -> bool:
    """Whether :func:`fits_in_memory` would accept an allocation of ``n_bytes``."""
    try:
        fits_in_memory("", n_bytes, "")
    except ValueError:
        return False
    return True
#: Largest relative difference between a given dt and the spacing of a profile file's theta column.
_SAME_DT = 1e-9


def _theta_spacing(theta: np.ndarray, key: str, name: str) -> Optional[float]:
    """The element travel time dt implied by the ``theta`` column of a striker profile (travel time of each
    element's face-side edge from the impact face, (q - 1) dt, in either row order): its constant spacing, s;
    ``None`` for a single element. Unevenly spaced values are a :class:`ModelError` naming ``key``."""
    if theta.size < 2:
        return None
    dt = abs(float(theta[-1] - theta[0])) / (theta.size - 1)
    steps = np.abs(np.diff(theta))
    if not dt > 0.0 or np.max(np.abs(steps - dt)) > _SAME_DT * dt:
        k = int(np.argmax(np.abs(steps - dt)))
        raise ModelError(f"{key}: the theta column of {name} must be evenly spaced (theta = (q - 1) dt, the travel "
                         f"time of each element's face-side edge from the impact face); rows {k + 1} and {k + 2} "
                         f"of its data are {steps[k]!r} s apart, the mean spacing is {dt!r} s")
    return dt


def _run_count(run: dict, path: str, element_length: float) -> int:
    if (run["count"] is None) == (run["length"] is None):
        raise ModelError(f"{path}: give exactly one of count or length")
    if run["count"] is not None:
        return run["count"]
    x = run["length"] / element_length
    if not x < 2**62:
        raise ModelError(f"{path}.length: {run['length']:.6g} m is {x:.3g} elements of length c*dt = "
                         f"{element_length:.6g} m; far too many (use a shorter run or longer elements)")
    k = int(round(x))
    if k < 1 or abs(x - k) > 1e-6 * max(x, 1.0):
        raise ModelError(f"{path}.length: {run['length']:.6g} m is {x:.6g} elements of length c*dt = "
                         f"{element_length:.6g} m; it must be a whole number (or give count)")
    return k


def _history(h: dict, path: str, params: dict[str, float], base_dir: Path, dimension: str) -> Any:
    if h["kind"] == "constant":
        return h["value"]
    if h["kind"] == "samples":
        return (np.array(h["time"]), np.array(h["value"]))
    if h["kind"] == "file":
        cols = read_csv_columns(base_dir / h["file"], f"{path}.file", None, positional=("time", dimension))
        return (cols["time"], cols[dimension])
    expr = SafeExpression(h["source"], ("t",), params, path=f"{path}.expression")
    check_dimension(expr, dimension, {"t": "time"}, params)
    expr(np.zeros(1))    # surface evaluation errors now, with the key path (the run checks its whole span)
    return expr


def _field_value(v: Optional[dict], path: str, params: dict[str, float], dimension: str) -> Any:
    if v is None:
        return None
    if v["kind"] == "constant":
        return v["value"]
    if v["kind"] == "values":
        return np.array(v["values"])
    expr = SafeExpression(v["source"], ("x",), params, path=f"{path}.expression")
    check_dimension(expr, dimension, {"x": "length"}, params)
    expr(np.zeros(1))    # at the left end; the run checks the whole rod
    return expr


def _junctions(tables: Optional[list[dict]], n_rods: int, params: dict[str, float], base_dir: Path,
               rods: str = "rods") -> Optional[list]:
    """The junctions of validated ``[[junctions]]`` tables (``None``: the default), one per neighbouring pair."""
    if tables is None:
        return None
    if len(tables) != n_rods - 1:
        raise ModelError(f"junctions: need one per neighbouring pair of {rods} ({n_rods - 1}), got {len(tables)}")
    return [_element("junction", j, f"junctions[{i}]", params, base_dir) for i, j in enumerate(tables)]


def _loads(tables: list[dict], rods: list[Rod], names: dict[str, int], params: dict[str, float],
           base_dir: Path) -> list:
    """The loads of validated ``[[loads]]`` tables, their rod references resolved and their positions checked
    against the rods (``names``: rod name -> index)."""
    loads = []
    for i, ld in enumerate(tables):
        path = f"loads[{i}]"
        k = _rod_index(ld["rod"], names, len(rods), f"{path}.rod")
        if ld["type"] == "force" and not 0.0 < ld["position"] < rods[k].length:
            raise ModelError(f"{path}.position: must lie inside rod {k}, 0 < x < {rods[k].length:.6g} m, got "
                             f"{ld['position']:.6g} m (end faces take [ends] force conditions)")
        for j, (a, b) in enumerate(ld.get("spans") or ()):
            if b > rods[k].length * (1 + 1e-12):
                raise ModelError(f"{path}.spans[{j}]: the span ends at {b:.6g} m, beyond the end of rod {k} "
                                 f"({rods[k].length:.6g} m)")
        loads.append(_element("load", {**ld, "rod": k}, path, params, base_dir))
    return loads


def _element(family: str, d: dict | str, path: str, params: dict[str, float], base_dir: Path) -> Any:
    """The element of ``family`` (``end``, ``junction``, ``load``) that the validated table ``d`` describes, built
    from its class's field declarations (:mod:`rodimpact.rods.declared`): histories are read here, every other
    value goes to the class as it is (rod references already resolved to indices). The class's messages
    ``Class.field: ...`` become the key paths ``path.field: ...``."""
    d = d if isinstance(d, dict) else {"type": d}
    cls = ELEMENTS[family][d["type"]]
    values = {}
    for f, decl in declarations(cls):
        where = f"{path}.{f.name}"
        values[f.name] = (_history(d[f.name], where, params, base_dir, decl.dimension) if decl.kind == "history"
                          else _element(decl.family, d[f.name], where, params, base_dir) if decl.kind == "part"
                          else [_element(decl.family, x, f"{where}[{i}]", params, base_dir)
                                for i, x in enumerate(d[f.name])] if decl.kind == "parts"
                          else str(base_dir / d[f.name]) if decl.kind == "path" and d[f.name] is not None
                          else d[f.name])
    return _wrap(path, lambda: cls(**values), cls.__name__)


def _rod_index(ref: int | str, names: dict[str, int], n: int, path: str) -> int:
    if isinstance(ref, int):
        if ref >= n:
            raise ModelError(f"{path}: rod index {ref} does not exist (the model has rods 0..{n - 1})")
        return ref
    if ref not in names:
        raise ModelError(f"{path}: no rod is named {ref!r}; named rods: {', '.join(map(repr, names)) or 'none'}")
    return names[ref]


_HEADER = re.compile(r"^\s*([^\[\(]+?)\s*(?:[\[\(]\s*(.*?)\s*[\]\)])?\s*$")


def read_csv_columns(path: Path, key: str, dims: Optional[dict[str, str]], *, needed: Sequence[str] = (),
                     positional: Sequence[str] = ()) -> dict[str, np.ndarray]:
    """Read numeric columns from a CSV file whose header names them, optionally with a unit in brackets
    (``x [mm]``, ``impedance (kN s/m)``, ``strain [-]`` for a pure number, as rodimpact's CSV files write it); values
    are converted to SI. Lines starting with ``#`` are comments.

    ``dims`` maps the recognised column names to dimensions (other columns are ignored); with ``positional``
    the columns are taken in order instead and named accordingly (``("time", "force")``).
    """
    text = read_text_file(Path(path), key, "CSV file")
    lines = [ln for ln in text.splitlines() if not ln.lstrip().startswith("#")]    # comment lines, never parsed
    rows = [r for r in csv.reader(lines) if r and any(c.strip() for c in r)]
    rows = [r for r in rows if not r[0].lstrip().startswith("#")]                   # a quoted "# ..." comment
    if len(rows) < 2:
        raise ModelError(f"{key}: {path} needs a header line and at least one row of numbers")
    header = rows[0]
    cols: dict[str, tuple[int, str]] = {}
    for i, h in enumerate(header):
        m = _HEADER.match(h)
        name, unit = (m.group(1).strip().lower(), (m.group(2) or "").strip()) if m else (h.strip().lower(), "")
        if positional:
            if i < len(positional):
                cols[positional[i]] = (i, unit)
        elif dims is not None and name in dims:
            cols[name] = (i, unit)
    for n in list(needed) + list(positional):
        if n not in cols:
            raise ModelError(f"{key}: {path} has no column {n!r} among the {len(header)} column(s) of its header "
                             f"line; expected a CSV file whose first line names the columns"
                             + (f" ({', '.join(positional)})" if positional else f", e.g. '{n} [unit]'"))
    out = {}
    for name, (i, unit) in cols.items():
        dim = dims[name] if dims is not None else name if name in DIMENSIONS else "time"
        try:
            scale = 1.0 if not unit or unit == DIMENSIONS[dim].si == "-" else parse_quantity(f"1 {unit}", dim, key)
        except ModelError:
            raise ModelError(f"{key}: {path}, column {i + 1}: the unit in its header is not {_a(dim)} unit (such as "
                             f"{DIMENSIONS[dim].si}); the file's content is not shown") from None
        vals = []
        for line_no, r in enumerate(rows[1:], start=2):
            try:
                vals.append(float(r[i]) * scale)
            except (IndexError, ValueError):
                got = "text that is not a number" if i < len(r) else "no value"
                raise ModelError(f"{key}: {path}, data row {line_no - 1}, column {i + 1} ({name}): expected a number, got "
                                 f"{got} (the file's content is not shown)") from None
        arr = np.array(vals)
        if not np.all(np.isfinite(arr)):
            raise ModelError(f"{key}: {path}, column {i + 1} ({name}) contains a non-finite value")
        out[name] = arr
    return out


def _a(dimension: str) -> str:
    return ("an " if dimension[0] in "aeiou" else "a ") + dimension


# ============================================================================================ writing
class ModelWriteError(TypeError):
    """A model that cannot be written as a file (e.g. it holds a Python callable)."""


def dump_model(model: Model) -> str:
    """The model as TOML text (bare SI numbers with unit comments); :func:`loads_model` reads it back into
    equal objects."""
    doc = model_to_dict(model)
    head = (f"# rodimpact model file written by rodimpact {__version__}.\n"
            "# Numbers are in SI units (m, s, kg, N, Pa, N s/m); all keys: rodimpact docs model.\n")
    return head + "\n" + _toml.dumps(doc)


def save_model(model: Model, path: str | Path, *, overwrite: bool = False) -> Path:
    """Write :func:`dump_model` to ``path`` (refuses to replace an existing file unless ``overwrite``)."""
    p = Path(path)
    if p.exists() and not overwrite:
        raise FileExistsError(f"{p}: exists; pass overwrite=True to replace it")
    write_text_atomic(p, dump_model(model))
    return p


def _c(v: Any, dimension: str) -> Any:
    unit = DIMENSIONS[dimension].si
    return _toml.Commented(float(v), unit) if unit != "-" else float(v)


class _Writer:
    def __init__(self, model: Model) -> None:
        self.model = model
        self.params: dict[str, float] = dict(model.parameters)
        self.materials: dict[str, Material] = {}
        rods = model.system.rods
        names = [r.name for r in rods]
        self.rod_ref = [n if n is not None and names.count(n) == 1 else i for i, n in enumerate(names)]

    def material(self, m: Material, path: str) -> str:
        if m.name in MATERIALS and MATERIALS[m.name] == m:
            return m.name
        base = m.name or "material"
        name, k = base, 1
        while name in MATERIALS or (name in self.materials and self.materials[name] != m):
            k += 1
            name = f"{base}-{k}"
        self.materials[name] = m
        return name

    def expression(self, f: SafeExpression, path: str) -> str:
        for k in f.used_parameters:
            v = f.parameters[k]
            if k in self.params and self.params[k] != v:
                raise ModelWriteError(f"{path}: parameter {k!r} has two different values ({self.params[k]!r} "
                                      f"and {v!r}) in different expressions")
            self.params[k] = v
        return f.source

    def history(self, h: Optional[History], path: str) -> Any:
        src = h.source
        if isinstance(src, SafeExpression):
            return _toml.Inline(expression=self.expression(src, path))
        if callable(src):
            raise ModelWriteError(f"{path}: a Python callable cannot be written to a model file; use "
                                  f"samples (t, values) or rodimpact.io.SafeExpression")
        if isinstance(src, tuple):
            return _toml.Inline(time=[float(x) for x in src[0]], value=[float(x) for x in src[1]])
        return float(src)

    def field_value(self, v: Any, path: str) -> Any:
        if isinstance(v, SafeExpression):
            return _toml.Inline(expression=self.expression(v, path))
        if callable(v):
            raise ModelWriteError(f"{path}: a Python callable cannot be written to a model file; use "
                                  f"rodimpact.io.SafeExpression(source, ('x',))")
        if np.ndim(v) == 0:
            return float(v)
        return [float(x) for x in np.asarray(v, dtype=float)]

    def segment(self, s: Segment, path: str) -> dict:
        if type(s) in ELEMENTS["segment"].values():      # a registered shape: its declared fields
            d = {"shape": type_name(s), **{f.name: _c(getattr(s, f.name), decl.dimension)
                                           for f, decl in declarations(type(s))}}
        elif isinstance(s, TabulatedProfile):
            d = {"shape": "table", "x": [float(v) for v in s.x], s.kind: [float(v) for v in s.values]}
        elif isinstance(s, AreaFunction):
            func = s.function
            if not isinstance(func, SafeExpression) or set(func.bound) != {"L"}:
                raise ModelWriteError(f"{path}: an AreaFunction holding a Python callable cannot be written to a "
                                      f"model file; build it with rodimpact.io.expression_area(...) or use a "
                                      f"TabulatedProfile")
            d = {"shape": "expression", "length": _c(s.length, "length"), "area": self.expression(func, path)}
        else:
            raise ModelWriteError(f"{path}: cannot write a {type(s).__name__} segment")
        if s.material is not None:
            d["material"] = self.material(s.material, f"{path}.material")
        return d

    def rod(self, i: int, rod: Rod, velocity: float, st: Optional[InitialState]) -> dict:
        path = f"rods[{i}]"
        d: dict[str, Any] = {}
        if rod.name is not None:
            d["name"] = rod.name
        if rod.native is None:
            d["material"] = self.material(rod.material, f"{path}.material")
        d["velocity"] = _c(velocity, "velocity")
        if st is not None:
            ini = {}
            if st.force is not None:
                ini["force"] = self.field_value(st.force, f"{path}.initial.force")
            if st.velocity is not None:
                ini["velocity"] = self.field_value(st.velocity, f"{path}.initial.velocity")
            if ini:
                d["initial"] = _toml.Inline(ini)
        if rod.native is not None:
            nat = rod.native
            z = nat.impedance
            cuts = np.flatnonzero(np.diff(z) != 0) + 1
            starts, stops = np.concatenate([[0], cuts]), np.concatenate([cuts, [z.size]])
            runs = [_toml.Inline(impedance=float(z[a]), count=int(b - a)) for a, b in zip(starts, stops)]
            d["elements"] = {"dt": _c(nat.dt, "time"), "wave_speed": _c(nat.wave_speed, "velocity"),
                             "density": _c(rod.material.density, "density"), "runs": runs}
        else:
            d["segments"] = [self.segment(s, f"{path}.segments[{j}]") for j, s in enumerate(rod.segments)]
        return d

    def element(self, e: Any, path: str, inline: bool = False) -> Any:
        """An end, junction or load as a table (``type`` and the declared fields that differ from their
        defaults), from its class's field declarations; an element without such fields as its type name.
        ``inline``: an inline table (bare SI numbers: TOML has no room for unit comments inside one)."""
        d = {"type": type_name(e)}
        for f, decl in declarations(type(e)):
            value = getattr(e, f.name)
            if decl.kind == "history":
                d[f.name] = self.history(value, f"{path}.{f.name}")
            elif decl.kind == "rod":
                d[f.name] = self.rod_ref[value]
            elif decl.kind == "spans":
                d[f.name] = [[float(a), float(b)] for a, b in value]
            elif decl.kind == "quantities":
                if value != f.default:
                    d[f.name] = [float(x) for x in value]
            elif decl.kind == "part":
                d[f.name] = self.element(value, f"{path}.{f.name}", inline=True)
            elif decl.kind == "parts":
                d[f.name] = [self.element(x, f"{path}.{f.name}[{i}]", inline=True) for i, x in enumerate(value)]
            elif decl.kind == "path" and value is None:
                raise ModelWriteError(f"{path}.{f.name}: {type(e).__name__} holds its data as arrays, which a "
                                      f"model file cannot; give it as a file ({decl.doc})")
            elif has_default(f) and value == f.default:
                continue
            elif decl.kind == "quantity":
                d[f.name] = float(value) if inline else _c(value, decl.dimension)
            else:
                d[f.name] = value
        return d["type"] if len(d) == 1 else _toml.Inline(**d) if inline else d

    def document(self) -> dict:
        m, s = self.model, self.model.system
        doc: dict[str, Any] = {}
        if m.title:
            doc["title"] = m.title
        if m.description:
            doc["description"] = m.description
        rods = [self.rod(i, r, s.velocities[i], s.initial[i]) for i, r in enumerate(s.rods)]
        ends = {side: self.element(e, f"ends.{side}", inline=True) for side, e in (("left", s.left),
                                                                                   ("right", s.right))}
        loads = [self.element(ld, f"loads[{i}]") for i, ld in enumerate(s.loads)]
        if self.params:
            doc["parameters"] = dict(self.params)
        if self.materials:
            doc["materials"] = {k: {"youngs_modulus": _c(v.youngs_modulus, "pressure"),
                                    "density": _c(v.density, "density")} for k, v in self.materials.items()}
        doc["rods"] = rods
        if any(not (isinstance(j, Contact) and j.gap == 0.0) for j in s.junctions):
            doc["junctions"] = [{"type": j} if isinstance(j, str) else j
                                for j in (self.element(j, f"junctions[{i}]") for i, j in enumerate(s.junctions))]
        doc["ends"] = ends
        if loads:
            doc["loads"] = loads
        if m.probes:
            doc["probes"] = [{"name": p.name, "rod": self.rod_ref[p.rod], "position": _c(p.position, "length")}
                             for p in m.probes]
        sim: dict[str, Any] = {}
        if m.duration is not None:
            sim["duration"] = _c(m.duration, "time")
        else:
            sim["steps"] = int(m.steps)
        if m.dt is not None:
            sim["dt"] = _c(m.dt, "time")
        sim["backend"] = m.backend
        if m.energy_every is not None:
            sim["energy_every"] = int(m.energy_every)
        if m.allow_discretization_error:
            sim["allow_discretization_error"] = True
        doc["simulation"] = sim
        o = m.output
        out: dict[str, Any] = {}
        if o.snapshot_times:
            out["snapshot_times"] = [float(t) for t in o.snapshot_times]
        if o.snapshot_every is not None:
            out["snapshot_every"] = int(o.snapshot_every)
        if o.snapshot_count is not None:
            out["snapshot_count"] = int(o.snapshot_count)
        out["plots"] = list(o.plots)
        out["csv"] = bool(o.csv)
        out["fields"] = bool(o.fields)
        if o.record_every != 1:
            out["record_every"] = int(o.record_every)
        doc["output"] = out
        return doc


def model_to_dict(model: Model) -> dict:
    """The model as nested dicts ready for TOML (SI numbers)."""
    return _Writer(model).document()


def model_from_result(result: SimulationResult, **settings: Any) -> Model:
    """A :class:`Model` that reproduces ``result``: its system, time step, step count and probes, with
    snapshot settings read from the recorded snapshots; ``settings`` override :class:`Model` fields."""
    snaps = result.snapshots
    output = OutputSpec(snapshot_times=tuple(float(t) for t in snaps.time) if snaps is not None else (),
                        snapshot_count=None, record_every=int(result.record_every))
    kw: dict[str, Any] = dict(system=result.system, steps=int(result.n_steps), dt=float(result.dt),
                              probes=tuple(p.probe for p in result.probes.values()), output=output,
                              backend=str(result.diagnostics.get("backend", "numba")))
    kw.update(settings)
    return Model(**kw)
