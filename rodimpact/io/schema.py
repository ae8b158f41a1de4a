"""The model-file schema: one declarative description used to validate files and to write
``docs/model-reference.md`` (``python -m rodimpact.io.schema docs/model-reference.md``; a test checks that the
page equals :func:`reference_markdown`, so the documentation cannot drift from the code).

Validation turns the raw TOML data into plain Python values in SI units (quantities -> float), fills in
defaults and rejects unknown keys. Every message starts with the key path, counted from 0 in the order the
tables appear in the file: ``rods[1].segments[2].diameter: must be > 0, got -5 mm``.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import math
import sys
from dataclasses import dataclass
from typing import Any, Optional

from ..rods import conditions as _conditions, laws as _laws, loads as _loads, segments as _segments  # noqa: F401
from ..rods.declared import ELEMENTS as ELEMENT_CLASSES, declarations, has_default, summary
from ..direct.result import Probe
from ..rods.material import Material
from . import _toml
from .quantities import (DIMENSIONS, ModelError, check_sign, parse_quantity, pint_quantity, show_as_written,
                         si_magnitude)

_MISSING = object()


@dataclass(frozen=True)
class Field:
    """One key of a table.

    ``kind`` is one of: ``quantity`` (needs ``dimension``), ``integer``, ``string``, ``boolean``, ``quantities``
    (a list of quantities), ``strings``, ``rod`` (a rod name or index), ``history`` (a time history of a
    ``dimension``), ``field`` (an initial field along x), ``expression``, ``spans``, ``parameters``,
    ``table`` (``table`` gives the nested :class:`Table`), ``tables`` (an array of tables; ``table`` or
    ``variants``), ``variant`` (one table chosen by its ``type``; a bare string names a type without
    parameters), ``mapping`` (name -> ``table``).
    """

    name: str
    kind: str
    doc: str
    dimension: Optional[str] = None
    sign: Optional[str] = None              # "positive" | "non_negative" | None
    required: bool = False
    default: Any = None
    choices: Optional[tuple[str, ...]] = None
    minimum: Optional[int] = None
    table: Optional["Table"] = None
    variants: Optional["Variants"] = None
    variables: tuple[str, ...] = ()         # expression variables


@dataclass(frozen=True)
class Table:
    """A TOML table: its fields, a title and a short description for the reference page."""

    name: str
    doc: str
    fields: tuple[Field, ...]
    example: str = ""

    def field(self, name: str) -> Field:
        for f in self.fields:
            if f.name == name:
                return f
        raise KeyError(name)


@dataclass(frozen=True)
class Variants:
    """Tables told apart by a discriminator key (``shape`` for segments, ``type`` otherwise)."""

    key: str
    options: dict[str, Table]
    default: Optional[str] = None
    doc: str = ""
    aliases: tuple[tuple[str, str], ...] = ()    # (other spelling, option name)


# ============================================================================================ the schema
#: Field kinds of the element declarations (rodimpact.rods.declared) -> field kinds of the schema
_DECLARED_KINDS = {"quantity": "quantity", "history": "history", "choice": "string", "flag": "boolean",
                   "rod": "rod", "spans": "spans", "path": "string", "text": "string",
                   "quantities": "quantities"}


def element_table(name: str, cls: type, example: str = "") -> Table:
    """The table of one element class, generated from its field declarations (:mod:`rodimpact.rods.declared`):
    keys, kinds, dimensions, bounds, defaults and docs; the description is the class docstring's first
    paragraph."""
    fields = []
    for f, d in declarations(cls):
        optional = has_default(f)
        if d.kind == "part":               # a nested element, chosen by its type
            fields.append(Field(f.name, "variant", d.doc, required=True,
                                variants=Variants("type", element_tables(d.family))))
            continue
        fields.append(Field(f.name, _DECLARED_KINDS[d.kind], d.doc,
                            dimension=d.dimension if d.kind in ("quantity", "quantities", "history") else None,
                            sign=d.bound if d.kind == "quantity" else None, required=not optional,
                            default=f.default if optional else None, choices=d.choices or None))
    return Table(name, summary(cls), tuple(fields), example)


def element_tables(family: str, examples: Optional[dict[str, str]] = None) -> dict[str, Table]:
    """The tables of every registered element kind of ``family`` (``end``, ``junction``, ``load``, ``segment``),
    by type name, with the reference page's ``examples`` of some."""
    return {name: element_table(name, cls, (examples or {}).get(name, ""))
            for name, cls in ELEMENT_CLASSES[family].items()}


def _q(name: str, dimension: str, doc: str, sign: Optional[str] = "positive", required: bool = True,
       default: Any = None) -> Field:
    return Field(name, "quantity", doc, dimension=dimension, sign=sign, required=required, default=default)


_LENGTH = element_table("segment", _segments.Segment).field("length")      # the declaration of every segment
_SEG_MATERIAL = Field("material", "string", "Material of this segment (a preset or a name from `[materials]`); "
                                            "default: the rod's material.")

SEGMENT_SHAPES: dict[str, Table] = {
    **{name: Table(t.name, t.doc, t.fields + (_SEG_MATERIAL,), t.example) for name, t in element_tables(
        "segment", {"cylinder": 'shape = "cylinder"\nlength = "0.5 m"\ndiameter = "50 mm"'}).items()},
    "table": Table("table", "A tabulated profile, interpolated linearly between points, with steps where a "
                            "position is given twice: either inline lists `x` with `diameter` or `area`, or a CSV "
                            "`file` with a column `x` and a column `diameter` or `area` (units in the header, e.g. "
                            "`x [mm]`; default SI; lines starting with `#` are comments). **Steps:** at a repeated x "
                            "the profile runs up to the first value given there and continues from the second (the "
                            "example: 40 mm up to 100 mm, then 50 mm). A step needs length on both sides and a "
                            "position may appear at most twice. Each piece between steps becomes a segment of its "
                            "own (`rodimpact.stepped_profile`), so a step is a segment end for the lattice: the "
                            "mass is integrated piece by piece, and messages about the lattice count the pieces as "
                            "segments.", (
        Field("file", "string", "CSV file, relative to the model file."),
        Field("x", "quantities", "Positions, increasing, a position given twice for a step; the segment's length is "
                                 "x[-1] - x[0].", dimension="length", sign=None),
        Field("diameter", "quantities", "Diameter at each x.", dimension="length", sign="positive"),
        Field("area", "quantities", "Area at each x.", dimension="area", sign="positive"),
        _SEG_MATERIAL),
        'shape = "table"\nx = ["0 mm", "100 mm", "100 mm", "150 mm", "200 mm"]\n'
        'diameter = ["40 mm", "40 mm", "50 mm", "50 mm", "45 mm"]   # a step at 100 mm, then a taper'),
    "expression": Table("expression", "Area given by an expression of the local position `s` (m, 0..L) and the "
                                      "segment length `L`, in SI units (result in m^2); may use `[parameters]`. "
                                      "See 'Expressions' below.", (
        _LENGTH, Field("area", "expression", "Area A(s) in m^2.", required=True, variables=("s", "L")),
        _SEG_MATERIAL),
        'shape = "expression"\nlength = "0.55 m"\narea = "A1 - 0.3*A0*sin(pi*s/L)"   # thesis eq. 3.24'),
}

RUN = Table("runs item", "A run of equal-travel-time elements: constant `impedance`, or a linear change from "
                         "`impedance_start` to `impedance_end` (first and last element take these values), over "
                         "`count` elements or a `length` (must be a whole number of elements c*dt).", (
    _q("impedance", "impedance", "Impedance of every element of the run.", required=False),
    _q("impedance_start", "impedance", "Impedance of the first element of a linear run.", required=False),
    _q("impedance_end", "impedance", "Impedance of the last element of a linear run.", required=False),
    Field("count", "integer", "Number of elements.", minimum=1),
    _q("length", "length", "Length of the run (instead of `count`).", required=False),
))

ELEMENTS = Table("rods.elements", "An impedance-level rod (`Rod.from_impedance`): elements listed left to right, "
                                  "each with travel time `dt` (or length `element_length`). Give exactly one of "
                                  "`impedance`, `runs`, `file`.", (
    _q("dt", "time", "Travel time of every element; default: the spacing of the `theta` column of `file`, else "
                     "`simulation.dt`.", required=False),
    _q("element_length", "length", "Length of every element instead of `dt` (dt = element_length / wave_speed).",
       required=False),
    _q("wave_speed", "velocity", "Wave speed (sets element lengths c*dt only); default steel, 5175.5 m/s.",
       required=False),
    _q("density", "density", "Density (sets the equivalent area Z/(rho c) only); default steel.", required=False),
    Field("impedance", "quantities", "Impedance of each element.", dimension="impedance", sign="positive"),
    Field("runs", "tables", "Runs of elements, see the table below.", table=RUN),
    Field("file", "string", "CSV file (relative to the model file), one row per element left to right, with a "
                            "column `impedance` (unit in the header, e.g. `impedance [kN s/m]`; default N s/m); "
                            "lines starting with `#` are comments. An optional column `theta` (the travel time of "
                            "each element's face-side edge from the impact face, evenly spaced) sets dt; a `dt` or "
                            "`element_length` given as well must agree with it. The `striker.csv` of `rodimpact "
                            "synthesize` and `rodimpact design` reads as it is: see 'Striker profiles' below."),
), '[rods.elements]\nelement_length = "5 mm"\nruns = [{ impedance = "51.0 kN s/m", count = 40 },\n'
   '        { impedance = "28.7 kN s/m", length = "0.5 m" }]')

INITIAL = Table("rods.initial", "Optional non-uniform initial state of the rod.", (
    Field("force", "field", "Initial normal force N(x) (tension positive).", dimension="force"),
    Field("velocity", "field", "Initial velocity v(x); overrides the rod's `velocity`.", dimension="velocity"),
))

ROD = Table("rods", "A rod, listed left to right (`[[rods]]`, one table per rod). Give either `[[rods.segments]]` "
                    "(geometry) or `[rods.elements]` (impedance level).", (
    Field("name", "string", "Name used in reports and to refer to the rod in `loads` and `probes`."),
    Field("material", "string", "Material of the segments without their own: a preset (`steel`, "
                                "`aluminium-7075-t6`, `ti-6al-4v`) or a name from `[materials]`; default `steel`. "
                                "Not used by impedance-level rods."),
    _q("velocity", "velocity", "Initial rigid-body velocity (positive to the right).", sign=None, required=False,
       default=0.0),
    Field("segments", "tables", "Segments left to right, each chosen by its `shape`.",
          variants=Variants("shape", SEGMENT_SHAPES)),
    Field("elements", "table", "Impedance-level description instead of segments.", table=ELEMENTS),
    Field("initial", "table", "Non-uniform initial state.", table=INITIAL),
), '[[rods]]\nname = "striker"\nvelocity = "4.6 m/s"\n\n[[rods.segments]]\nshape = "cylinder"\n'
   'length = "0.5 m"\ndiameter = "50 mm"')

MATERIAL = Table("materials", "Named materials (`[materials.NAME]`), used by `material = \"NAME\"`. Either "
                              "`youngs_modulus` and `density`, or a `base` material scaled by the factors.", (
    *(dataclasses.replace(f, required=False) for f in element_table("materials", Material).fields),
    Field("base", "string", "A preset or an earlier material to start from."),
    _q("youngs_factor", "dimensionless", "Factor on the base's E (thesis setup 3: 1.5).", required=False,
       default=1.0),
    _q("density_factor", "dimensionless", "Factor on the base's rho (thesis setup 3: 1.2).", required=False,
       default=1.0),
), '[materials.heavy]\nbase = "steel"\nyoungs_factor = 1.5\ndensity_factor = 1.2')

JUNCTION_TYPES = element_tables("junction")
LAW_TYPES = element_tables("law")
END_TYPES = element_tables("end")

_END_VARIANTS = Variants("type", END_TYPES, aliases=(("non-reflecting", "nonreflecting"),))

ENDS = Table("ends", "Conditions at the outer left end of the first rod and the outer right end of the last rod. "
                     "A name (`\"free\"`) or an inline table with a `type` and its parameters.", (
    Field("left", "variant", "Left end.", default="free", variants=_END_VARIANTS),
    Field("right", "variant", "Right end.", default="free", variants=_END_VARIANTS),
), '[ends]\nleft = "free"\nright = { type = "bit-rock", loading_stiffness = "300 MN/m" }')

LOAD_TYPES = element_tables("load")

PROBE = dataclasses.replace(element_table("probes", Probe), doc="An output request: force, velocity, displacement "
                            "and strain histories at a position (e.g. a strain gauge).",
                            example='[[probes]]\nname = "SG1"\nrod = "bar"\nposition = "110 mm"')

SIMULATION = Table("simulation", "How long and how finely to simulate. Give `duration` or `steps`.", (
    _q("duration", "time", "Simulated time.", required=False),
    Field("steps", "integer", "Number of time steps (instead of `duration`).", minimum=1),
    _q("dt", "time", "Time step = travel time of every element; default: that of impedance-level rods, else "
                     "one giving every segment >= 4 and the longest rod >= 200 elements, and every rod's travel "
                     "time and mass within 1 %.", required=False),
    Field("allow_discretization_error", "boolean", "Run even if a rod's travel time or mass is represented with "
          "an error above 1 % or a segment is shorter than one element (else an error naming a dt that "
          "satisfies it).", default=False),
    Field("backend", "string", "`numba` (compiled) or `numpy` (reference).", default="numba",
          choices=("numba", "numpy")),
    Field("energy_every", "integer", "Energy sampling stride in steps; default about 256 samples per run.",
          minimum=1),
), '[simulation]\nduration = "1 ms"\ndt = "0.5 us"')

PLOT_NAMES = ("forces", "strain", "profile", "snapshots", "xt", "energy", "animation")
OUTPUT = Table("output", "What to record and write besides the signals.", (
    Field("snapshot_times", "quantities", "Times of field snapshots N(x), v(x), u(x) (plotted like thesis "
                                          "Figs. 3.6, 3.8).", dimension="time", sign="non_negative"),
    Field("snapshot_every", "integer", "Also a snapshot every this many steps.", minimum=1),
    Field("snapshot_count", "integer", "Also about this many evenly spaced snapshots (for the x-t diagram and the "
                                       "animation); used when `snapshot_every` is not given.", default=200, minimum=1),
    Field("plots", "strings", "Plots to write: " + ", ".join(f"`{p}`" for p in PLOT_NAMES) + ".",
          default=("forces", "profile", "snapshots", "xt", "energy"), choices=PLOT_NAMES),
    Field("csv", "boolean", "Write `signals.csv` and `energy.csv`.", default=True),
    Field("fields", "boolean", "Keep field snapshots in `result.nc`.", default=True),
    Field("record_every", "integer", "Keep every this many steps of the signal histories (contact force, end "
                                     "values, probes) to bound memory on long runs; contact and separation times "
                                     "and the peak contact force are still taken at every step.", default=1,
          minimum=1),
), '[output]\nsnapshot_times = ["0.064 ms", "0.259 ms", "0.549 ms"]\nplots = ["forces", "snapshots", "xt"]')

MODEL = Table("model file", "Top level of a model file.", (
    Field("title", "string", "Short title (shown in summaries and plots)."),
    Field("description", "string", "Free text."),
    Field("parameters", "parameters", "Named constants for expressions (`A0 = \"1.26e-3 m^2\"`), converted "
                                      "to SI. Expressions are checked against the units written here (an area "
                                      "expression `A0` with `A0 = \"1260 mm\"` is refused); bare numbers carry "
                                      "no unit and are not checked."),
    Field("materials", "mapping", "Named materials.", table=MATERIAL),
    Field("rods", "tables", "The rods, left to right.", required=True, table=ROD, minimum=1),
    Field("junctions", "tables", "One per neighbouring pair of rods; default contact.",
          variants=Variants("type", JUNCTION_TYPES)),
    Field("ends", "table", "Outer end conditions.", table=ENDS),
    Field("loads", "tables", "Nodal forces and bearings.", variants=Variants("type", LOAD_TYPES)),
    Field("probes", "tables", "Histories at positions.", table=PROBE),
    Field("simulation", "table", "Run settings.", table=SIMULATION, required=True),
    Field("output", "table", "Output settings.", table=OUTPUT),
))

HISTORY_DOC = """A **history** (force or velocity over time) is one of
- a constant: `force = "-10 kN"`;
- samples: `force = { time = ["0 ms", "0.1 ms", "0.2 ms"], value = ["0 kN", "-50 kN", "0 kN"] }`
  (held constant before the first and after the last sample);
- an expression of `t` in SI units: `force = { expression = "-50e3*sin(pi*t/0.2e-3)*(t < 0.2e-3)" }`;
- a CSV file with two columns (time, value), units in the header: `force = { file = "force.csv" }`.

The solver takes each history at the midpoint of every time step."""

STRIKER_DOC = """`rodimpact synthesize` and `rodimpact design` write the striker as `striker.csv`
(`StrikerShape.to_csv` and `DesignResult.to_csv` in Python), one row per element of travel time dt, **listed
left to right as the striker lies in a simulation: the rear end first, the impact face last** (column
`element_from_face` = 1), as `[rods.elements]` lists elements. The lines before the header start with `#` and
state this orientation, dt, the material and the mass (`pandas.read_csv("striker.csv", comment="#")` reads the
table). Columns, SI units in the headers: `element_from_face`, `s_start [m]` and `s_end [m]` (the element's
face-side and rear-side edges from the impact face), `theta [s]` (travel time of the face-side edge from the
impact face, (q - 1) dt), `impedance [N s/m]`, `area [m^2]`, `outer_diameter [m]`, `inner_diameter [m]`.

A model file uses it as a rod with `[rods.elements] file = "striker.csv"`: the impedances in file order, dt from
the `theta` column. The dynamics depend on the impedances and dt alone; give `wave_speed` and `density` of the
striker's material (stated in the file's comment lines; default steel) for its true element lengths and areas.
The striker of a synthesis, read back this way, reproduces the synthesized force:

```python
import numpy as np
import rodimpact as ri

dt = 1e-6
bar = ri.Rod.from_impedance(np.full(300, 79.7e3), dt=dt, name="bar")
res = ri.synthesize(lambda t: -200e3 * np.exp(-t / 0.1e-3), ri.System.struck(bar, far_end="nonreflecting"),
                    striker_velocity=6.0, n=60, dt=dt)
res.shape().to_csv("striker.csv")           # the file rodimpact synthesize writes

with open("striker-on-bar.toml", "w") as fh:
    fh.write('''
[[rods]]
name = "striker"
velocity = "6 m/s"
[rods.elements]
file = "striker.csv"            # rear end first, impact face last; dt from its theta column

[[rods]]
name = "bar"
[rods.elements]
dt = "1 us"
runs = [{ impedance = "79.7 kN s/m", count = 300 }]

[ends]
right = "nonreflecting"

[simulation]
steps = 120
''')
run = ri.load_model("striker-on-bar.toml").simulate()
error = np.abs(run.contact_force - np.repeat(res.window_values, 2)).max() / np.abs(res.window_values).max()
assert error < 1e-12                         # the synthesized force, to rounding
```"""

FIELD_DOC = """An initial **field** along a rod is a constant, an expression of the position `x` (m from the rod's
left end, SI units) such as `{ expression = "-1e3*x" }`, or a list with one value per lattice element."""

EXPRESSION_DOC = """**Expressions** are strings evaluated with numpy (never Python `eval`): numbers, the variables of
their context (`s`, `L`, `t`, `x`), names from `[parameters]`, `pi`, `e`, `+ - * / ** %`, comparisons,
`a if c else b`, and the functions `sin cos tan arcsin arccos arctan arctan2 sinh cosh tanh exp log log10 sqrt
abs sign floor ceil min max where clip heaviside`. Everything is in SI units."""


# ============================================================================================ validation
def _p(path: str, key: str | int) -> str:
    """The key path of ``key`` inside ``path`` (keys that are not bare TOML keys are quoted, long ones clipped)."""
    if isinstance(key, int):
        return f"{path}[{key}]"
    key = _key(key if len(key) <= 60 else key[:57] + "...")
    return f"{path}.{key}" if path else key


#: TOML key spelling, cached: a schema has few field names, and a large file asks for them 10^6 times
_key = functools.lru_cache(maxsize=4096)(_toml.key)


def _unknown(table: Table, data: dict, path: str, extra: tuple[str, ...] = ()) -> None:
    allowed = list(extra) + [f.name for f in table.fields]
    for k in data:
        if k not in allowed:
            near = difflib.get_close_matches(k, allowed, n=1) if len(k) <= 100 else []
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            valid = ", ".join(allowed) if allowed else "none"
            raise ModelError(f"{_p(path, k)}: unknown key{hint}; valid keys in {path or 'the top level'}: {valid}")


def validate_table(table: Table, data: Any, path: str, *, extra: tuple[str, ...] = ()) -> dict[str, Any]:
    """Check ``data`` (a dict from TOML) against ``table``; return the values in SI with defaults filled in.

    Optional keys that are absent map to their default (``None`` if there is none).
    """
    if not isinstance(data, dict):
        raise ModelError(f"{path or 'model'}: expected a table, got {type(data).__name__} {show_as_written(data)}")
    _unknown(table, data, path, extra)
    out: dict[str, Any] = {}
    for f in table.fields:
        where = _p(path, f.name)
        if f.name not in data:
            if f.required:
                example = f'; e.g. {f.name} = "{DIMENSIONS[f.dimension].example}"' if f.kind == "quantity" else ""
                raise ModelError(f"{where}: missing ({f.doc.rstrip('.')}{example})")
            out[f.name] = f.default
            continue
        out[f.name] = validate_value(f, data[f.name], where)
    return out


def validate_value(f: Field, raw: Any, path: str) -> Any:
    """Validate one value according to its field."""
    kind = f.kind
    if kind == "quantity":
        return check_sign(parse_quantity(raw, f.dimension, path), f.sign, raw, path)
    if kind == "integer":
        if isinstance(raw, bool) or not isinstance(raw, int):
            raise ModelError(f"{path}: expected a whole number, got {show_as_written(raw)}")
        if f.minimum is not None and raw < f.minimum:
            raise ModelError(f"{path}: must be >= {f.minimum}, got {raw}")
        return raw
    if kind == "boolean":
        if not isinstance(raw, bool):
            raise ModelError(f"{path}: expected true or false, got {show_as_written(raw)}")
        return raw
    if kind in ("string", "expression"):
        if not isinstance(raw, str):
            raise ModelError(f"{path}: expected a string, got {show_as_written(raw)}")
        if f.choices is not None and raw not in f.choices:
            near = difflib.get_close_matches(raw, list(f.choices), n=1) if len(raw) <= 100 else []
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise ModelError(f"{path}: must be one of {', '.join(repr(c) for c in f.choices)}, got {raw!r}{hint}")
        return raw
    if kind == "strings":
        if not isinstance(raw, list) or not all(isinstance(x, str) for x in raw):
            raise ModelError(f"{path}: expected a list of strings, got {show_as_written(raw)}")
        for i, x in enumerate(raw):
            if f.choices is not None and x not in f.choices:
                raise ModelError(f"{path}[{i}]: must be one of {', '.join(repr(c) for c in f.choices)}, got {x!r}")
        return tuple(raw)
    if kind == "quantities":
        if not isinstance(raw, list):
            raise ModelError(f"{path}: expected a list of values, got {show_as_written(raw)}")
        return [check_sign(parse_quantity(x, f.dimension, f"{path}[{i}]"), f.sign, x, f"{path}[{i}]")
                for i, x in enumerate(raw)]
    if kind == "rod":
        if isinstance(raw, bool) or not isinstance(raw, (int, str)):
            raise ModelError(f"{path}: expected a rod name or index, got {show_as_written(raw)}")
        if isinstance(raw, int) and raw < 0:
            raise ModelError(f"{path}: a rod index must be >= 0, got {raw}")
        return raw
    if kind == "spans":
        if not isinstance(raw, list) or not raw:
            raise ModelError(f"{path}: expected a list of [start, end] pairs, got {show_as_written(raw)}")
        spans = []
        for i, pair in enumerate(raw):
            if not isinstance(pair, list) or len(pair) != 2:
                raise ModelError(f"{path}[{i}]: expected a pair [start, end], got {show_as_written(pair)}")
            a = check_sign(parse_quantity(pair[0], "length", f"{path}[{i}][0]"), "non_negative", pair[0],
                           f"{path}[{i}][0]")
            b = parse_quantity(pair[1], "length", f"{path}[{i}][1]")
            if not b > a:
                raise ModelError(f"{path}[{i}]: the end must lie after the start, got "
                                 f"[{show_as_written(pair[0])}, {show_as_written(pair[1])}]")
            spans.append((a, b))
        return spans
    if kind == "history":
        return _history(raw, f.dimension, path)
    if kind == "field":
        return _field(raw, f.dimension, path)
    if kind == "parameters":
        return _parameters(raw, path)
    if kind == "table":
        return validate_table(f.table, raw, path)
    if kind == "mapping":
        if not isinstance(raw, dict):
            raise ModelError(f"{path}: expected a table of named entries, got {show_as_written(raw)}")
        return {name: validate_table(f.table, sub, _p(path, name)) for name, sub in raw.items()}
    if kind == "variant":
        return validate_variant(f.variants, raw, path)
    if kind == "tables":
        if not isinstance(raw, list) or not all(isinstance(x, dict) for x in raw):
            raise ModelError(f"{path}: expected an array of tables ([[{path.split('.')[-1].split('[')[0]}]]), "
                             f"got {show_as_written(raw)}")
        if f.minimum is not None and len(raw) < f.minimum:
            raise ModelError(f"{path}: needs at least {f.minimum} entry")
        if f.variants is not None:
            return [validate_variant(f.variants, x, f"{path}[{i}]") for i, x in enumerate(raw)]
        return [validate_table(f.table, x, f"{path}[{i}]") for i, x in enumerate(raw)]
    raise AssertionError(f"unknown field kind {kind}")  # pragma: no cover


def validate_variant(variants: Variants, raw: Any, path: str) -> dict[str, Any]:
    """A table whose ``variants.key`` picks its schema (a bare string is a type name without parameters)."""
    names = ", ".join(repr(n) for n in variants.options)
    if isinstance(raw, str):
        raw = {variants.key: raw}
    if not isinstance(raw, dict):
        raise ModelError(f"{path}: expected a table with a {variants.key!r} or a type name ({names}), "
                         f"got {show_as_written(raw)}")
    kind = raw.get(variants.key, variants.default)
    if kind is None:
        raise ModelError(f"{_p(path, variants.key)}: missing; one of {names}")
    if not isinstance(kind, str):
        raise ModelError(f"{_p(path, variants.key)}: expected a string, one of {names}; got "
                         f"{show_as_written(kind)}")
    kind = dict(variants.aliases).get(kind, kind)
    if kind not in variants.options:
        near = difflib.get_close_matches(str(kind), list(variants.options), n=1)
        hint = f" (did you mean {near[0]!r}?)" if near else ""
        raise ModelError(f"{_p(path, variants.key)}: unknown {variants.key} {kind!r}{hint}; valid: {names}")
    body = {k: v for k, v in raw.items() if k != variants.key}
    out = validate_table(variants.options[kind], body, path, extra=(variants.key,))
    out[variants.key] = kind
    return out


def _history(raw: Any, dimension: str, path: str) -> dict[str, Any]:
    if isinstance(raw, (int, float, str)) and not isinstance(raw, bool):
        return {"kind": "constant", "value": parse_quantity(raw, dimension, path)}
    if not isinstance(raw, dict):
        raise ModelError(f"{path}: expected a constant, {{ time = [...], value = [...] }}, {{ expression = \"...\" }} "
                         f"or {{ file = \"...\" }}, got {show_as_written(raw)}")
    keys = set(raw)
    if keys == {"time", "value"}:
        t = validate_value(Field("time", "quantities", "", dimension="time"), raw["time"], f"{path}.time")
        y = validate_value(Field("value", "quantities", "", dimension=dimension), raw["value"], f"{path}.value")
        if len(t) != len(y) or not t:
            raise ModelError(f"{path}: `time` and `value` need the same number (>= 1) of entries, got "
                             f"{len(t)} and {len(y)}")
        for i in range(1, len(t)):
            if t[i] < t[i - 1]:
                raise ModelError(f"{path}.time[{i}]: times must not decrease, {t[i]} s < {t[i - 1]} s")
        return {"kind": "samples", "time": t, "value": y}
    if keys == {"expression"}:
        if not isinstance(raw["expression"], str):
            raise ModelError(f"{path}.expression: expected a string")
        return {"kind": "expression", "source": raw["expression"]}
    if keys == {"file"}:
        if not isinstance(raw["file"], str):
            raise ModelError(f"{path}.file: expected a file name")
        return {"kind": "file", "file": raw["file"]}
    bad = sorted(keys - {"time", "value", "expression", "file"})
    raise ModelError(f"{path}: a history is {{ time, value }}, {{ expression }} or {{ file }}; got the keys "
                     f"{sorted(keys)}" + (f" (unknown: {bad})" if bad else ""))


def _field(raw: Any, dimension: str, path: str) -> dict[str, Any]:
    if isinstance(raw, (int, float, str)) and not isinstance(raw, bool):
        return {"kind": "constant", "value": parse_quantity(raw, dimension, path)}
    if isinstance(raw, list):
        vals = validate_value(Field("v", "quantities", "", dimension=dimension), raw, path)
        return {"kind": "values", "values": vals}
    if isinstance(raw, dict) and set(raw) == {"expression"} and isinstance(raw["expression"], str):
        return {"kind": "expression", "source": raw["expression"]}
    raise ModelError(f"{path}: expected a constant, a list of element values or {{ expression = \"...\" }} "
                     f"(a function of x in m), got {show_as_written(raw)}")


_RESERVED = {"s", "L", "t", "x", "pi", "e"}


def _parameters(raw: Any, path: str) -> dict[str, float]:
    from .expressions import FUNCTIONS

    if not isinstance(raw, dict):
        raise ModelError(f"{path}: expected a table of name = value")
    out = {}
    for name, v in raw.items():
        where = _p(path, name)
        if not name.isidentifier() or name in _RESERVED or name in FUNCTIONS:
            raise ModelError(f"{where}: cannot be used as a parameter name (must be an identifier other than "
                             f"{sorted(_RESERVED)} and the function names)")
        if isinstance(v, bool) or not isinstance(v, (int, float, str)):
            raise ModelError(f"{where}: expected a number or a quantity such as \"1.26e-3 m^2\", got "
                             f"{show_as_written(v)}")
        if isinstance(v, str):
            expected = "a number or a quantity such as \"1.26e-3 m^2\""
            x = si_magnitude(pint_quantity(v, where, expected), None, v, where, expected)
        else:
            x = parse_quantity(v, "dimensionless", where)
        out[name] = x
    return out


# ============================================================================================ documentation
def _value_text(f: Field) -> str:
    if f.kind == "quantity":
        d = DIMENSIONS[f.dimension]
        return "number" if d.name == "dimensionless" else f"{d.name} ({d.si})"
    if f.kind == "quantities":
        return f"list of {DIMENSIONS[f.dimension].name} ({DIMENSIONS[f.dimension].si})"
    if f.kind == "history":
        return f"history of {DIMENSIONS[f.dimension].name} ({DIMENSIONS[f.dimension].si})"
    if f.kind == "field":
        return f"field of {DIMENSIONS[f.dimension].name} ({DIMENSIONS[f.dimension].si})"
    return {"integer": "integer", "string": "string", "boolean": "true/false", "strings": "list of strings",
            "rod": "rod name or index", "spans": "list of [start, end] lengths (m)",
            "expression": f"expression of {', '.join(f.variables)}", "parameters": "table name = quantity",
            "table": "table", "tables": "array of tables", "mapping": "tables `[NAME]`",
            "variant": "name or inline table"}[f.kind]


def _default_text(f: Field) -> str:
    if f.required:
        return "**required**"
    if f.default is None:
        return "-"
    if isinstance(f.default, tuple):
        return "[" + ", ".join(f'"{x}"' for x in f.default) + "]"
    if isinstance(f.default, bool):
        return str(f.default).lower()
    if isinstance(f.default, str):
        return f'"{f.default}"'
    return repr(f.default)


def _rule_text(f: Field) -> str:
    parts = []
    if f.sign == "positive":
        parts.append("> 0")
    elif f.sign == "non_negative":
        parts.append(">= 0")
    if f.minimum is not None and f.kind == "integer":
        parts.append(f">= {f.minimum}")
    if f.choices:
        parts.append("one of " + ", ".join(f"`{c}`" for c in f.choices))
    return "; ".join(parts)


def _table_md(title: str, table: Table, level: int, lines: list[str], key: Optional[str] = None) -> None:
    lines.append(f"{'#' * level} {title}")
    lines.append("")
    lines.append(table.doc)
    lines.append("")
    lines.append("| key | value | default | rule | meaning |")
    lines.append("|---|---|---|---|---|")
    if key:
        lines.append(f"| `{key}` | string | **required** | `\"{table.name}\"` | selects this table |")
    for f in table.fields:
        lines.append(f"| `{f.name}` | {_value_text(f)} | {_default_text(f)} | {_rule_text(f)} | {f.doc} |")
    lines.append("")
    if table.example:
        lines.extend(["```toml", table.example, "```", ""])


def reference_markdown() -> str:
    """The model reference page (``docs/model-reference.md``), generated from this schema."""
    lines = ["<!-- Generated by `python -m rodimpact.io.schema docs/model-reference.md`; do not edit by hand. "
             "tests/io/test_model_reference.py checks that this page matches the schema. -->", "",
             "# Model file reference", "",
             "A model file is a [TOML](https://toml.io) file describing rods, junctions, end conditions, loads, "
             "probes and run settings. `rodimpact init simulate` writes a commented template; "
             "`rodimpact simulate MODEL.toml` runs it.", "",
             "**Units.** Every quantity is a number in SI units (m, s, kg, N, Pa, N s/m) or a string with a unit "
             "that [pint](https://pint.readthedocs.io) understands: `\"50 mm\"`, `\"210 GPa\"`, `\"4.6 m/s\"`, "
             "`\"51.0 kN s/m\"`, `\"0.5 us\"`. A unit of the wrong dimension is an error.", "",
             "**Signs.** x grows to the right; rods are listed left to right; the normal force is positive in "
             "tension (impacts give negative forces); a striker on the left moves with positive velocity.", "",
             "**Errors** name the key path counted from 0 in file order, e.g. "
             "`rods[1].segments[2].diameter: must be > 0, got -5 mm`. Unknown keys are errors.", "",
             "Units of the dimensions used below:", "",
             "| dimension | SI unit | example |", "|---|---|---|"]
    for d in DIMENSIONS.values():
        lines.append(f"| {d.name} | {d.si} | `{d.example}` |")
    lines.append("")
    _table_md("Top level", MODEL, 2, lines)
    _table_md("`[materials.NAME]`", MATERIAL, 2, lines)
    _table_md("`[[rods]]`", ROD, 2, lines)
    lines.extend(["### `[[rods.segments]]`", "", "Each segment has a `shape` that selects its keys. Positions "
                  "`s` inside a segment run from 0 at its left end.", ""])
    for name, t in SEGMENT_SHAPES.items():
        _table_md(f"shape = \"{name}\"", t, 4, lines, key="shape")
    _table_md("`[rods.elements]`", ELEMENTS, 3, lines)
    _table_md("`runs` items", RUN, 4, lines)
    lines.extend(["#### Striker profiles (`striker.csv`)", "", STRIKER_DOC, ""])
    _table_md("`[rods.initial]`", INITIAL, 3, lines)
    lines.extend(["## `[[junctions]]`", "", "One table per neighbouring pair of rods, in order; omit the array for "
                  "contact everywhere.", ""])
    for name, t in JUNCTION_TYPES.items():
        _table_md(f"type = \"{name}\"", t, 3, lines, key="type")
    lines.extend(["### Constitutive laws (`law = { type = ... }`)", "", "The `law` of a `specimen` or "
                  "`pulse-shaper`: stress and strain positive in compression, stresses in Pa "
                  "(docs/shpb.md).", ""])
    for name, t in LAW_TYPES.items():
        _table_md(f"law type = \"{name}\"", t, 4, lines, key="type")
    _table_md("`[ends]`", ENDS, 2, lines)
    for name, t in END_TYPES.items():
        _table_md(f"type = \"{name}\"", t, 3, lines, key="type")
    lines.extend(["## `[[loads]]`", "", "Forces on interior nodes.", ""])
    for name, t in LOAD_TYPES.items():
        _table_md(f"type = \"{name}\"", t, 3, lines, key="type")
    _table_md("`[[probes]]`", PROBE, 2, lines)
    _table_md("`[simulation]`", SIMULATION, 2, lines)
    _table_md("`[output]`", OUTPUT, 2, lines)
    lines.extend(["## Histories, fields and expressions", "", HISTORY_DOC, "", FIELD_DOC, "", EXPRESSION_DOC, ""])
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Write the reference page to the given path (or print it)."""
    argv = sys.argv[1:] if argv is None else argv
    text = reference_markdown()
    if argv:
        with open(argv[0], "w", encoding="utf-8") as fh:
            fh.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
