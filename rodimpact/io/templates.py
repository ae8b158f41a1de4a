"""Commented model-file templates written by ``rodimpact init``; each runs as it is."""

from __future__ import annotations

from ..rods import conditions as _conditions, loads as _loads  # noqa: F401  (register the element classes)
from ..rods.declared import ELEMENTS


def _types(family: str) -> str:
    """The registered type names of an element family, quoted, for the template's comments."""
    return ", ".join(f'"{name}"' for name in ELEMENTS[family])


SIMULATE = '''\
# rodimpact model file -- run it with:   rodimpact simulate model.toml -o results/model
#
# Every quantity is a number in SI units (m, s, kg, N, Pa, N s/m) or a string with a unit: "50 mm",
# "210 GPa", "4.6 m/s", "51.0 kN s/m". Signs: x grows to the right, rods are listed left to right, the
# normal force is positive in tension (an impact gives negative forces). All keys: rodimpact docs model.
#
# This template: a stepped steel piston (40/50/40 mm, 0.5 m) hits a 50 mm x 1.8 m rod at 4.6 m/s; three
# strain gauges on the rod (the test rig of the thesis, chapter 5).

title = "Piston on a rod"
description = "Template written by rodimpact init: stepped piston hits a uniform rod."

# Named constants for expressions (area functions, histories), converted to SI.
[parameters]
d_rod = "50 mm"

# Materials besides the presets "steel" (E = 210 GPa, rho = 7840 kg/m^3), "aluminium-7075-t6", "ti-6al-4v".
# Either youngs_modulus and density, or a base material with factors.
[materials.hard-steel]
base = "steel"
youngs_factor = 1.0
density_factor = 1.0

# ---------------------------------------------------------------------------------------------- rods
# One [[rods]] table per rod, left to right. A rod is built from [[rods.segments]] (geometry) or given by
# [rods.elements] (impedance level, see rodimpact docs model).
[[rods]]
name = "piston"                # used by probes and loads, and in reports
material = "steel"             # default material of its segments
velocity = "4.6 m/s"           # initial velocity, positive to the right

# Segments left to right; "shape" selects the keys: cylinder, tube, cone, linear-area, exponential-horn,
# quadratic-horn, cosh-horn, cos-horn, table (points or a CSV file), expression.
[[rods.segments]]
shape = "cylinder"
length = "100 mm"
diameter = "40 mm"

[[rods.segments]]
shape = "cylinder"
length = "300 mm"
diameter = "50 mm"
material = "hard-steel"        # a segment may have its own material

[[rods.segments]]
shape = "cylinder"
length = "100 mm"
diameter = "40 mm"

[[rods]]
name = "rod"
velocity = "0 m/s"

[[rods.segments]]
shape = "expression"           # area A(s) in m^2 of the local position s (m) and the segment length L
length = "1800 mm"
area = "pi/4 * d_rod**2"

# ------------------------------------------------------------------------------------- connections
# One [[junctions]] table per neighbouring pair. "contact": compression only, may separate and re-contact
# (optional gap). Default: contact without gap. All types (keys: rodimpact docs model):
# {junctions}.
[[junctions]]
type = "contact"
gap = "0 mm"

# Outer ends, one of {ends}:
# a name, or a table such as
# { type = "spring", stiffness = "300 MN/m" }, { type = "bit-rock", loading_stiffness = "300 MN/m" },
# { type = "force", force = "-1 kN" }, { type = "velocity", velocity = { time = [...], value = [...] } }.
[ends]
left = "free"
right = "free"

# Loads on interior nodes, one of {loads}: "force" (a force history at a position) or
# "bearings" (Coulomb friction mu * m * g shared by the nodes inside the spans, thesis eqs. 3.21-3.23).
[[loads]]
type = "bearings"
rod = "piston"
spans = [["0.05 m", "0.45 m"]]
friction_coefficient = 0.0     # mu; 0 = frictionless guide
gravity = "9.81 N/kg"

# ------------------------------------------------------------------------------------------ output
# Probes record force, velocity, displacement and strain histories (e.g. strain gauges); position is
# measured from the left end of the rod.
[[probes]]
name = "SG1"
rod = "rod"
position = "110 mm"

[[probes]]
name = "SG2"
rod = "rod"
position = "900 mm"

[[probes]]
name = "SG3"
rod = "rod"
position = "1690 mm"

[simulation]
duration = "1.5 ms"            # or: steps = 1000
dt = "0.5 us"                  # time step = travel time of every element; omit for a default
backend = "numba"              # or "numpy" (slow reference)

[output]
snapshot_times = ["0.05 ms", "0.15 ms", "0.3 ms"]   # field snapshots plotted along x
snapshot_count = 200           # evenly spaced snapshots for the x-t diagram and the animation
plots = ["forces", "profile", "snapshots", "xt", "energy"]   # add "animation" for force.gif
csv = true                     # signals.csv and energy.csv
fields = true                  # keep the snapshots in result.nc
# record_every = 10            # keep every 10th step of the signals (memory of very long runs)
'''.replace("{junctions}", _types("junction")).replace("{ends}", _types("end")).replace("{loads}", _types("load"))

TEMPLATES: dict[str, tuple[str, str]] = {"simulate": (SIMULATE, "model.toml")}


def template(kind: str) -> tuple[str, str]:
    """(text, default file name) of the template ``kind``."""
    if kind not in TEMPLATES:
        raise ValueError(f"init: no template {kind!r}; available: {', '.join(TEMPLATES)}")
    return TEMPLATES[kind]
