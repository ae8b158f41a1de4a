"""Model files: units, every shape and condition, and error messages with key paths.

References are hand values (unit conversions, areas, impedances) and objects built directly with the Python
API, never output of the loader itself.
"""

import math
import re
import textwrap

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.expressions import SafeExpression
from rodimpact.io.model import load_model, loads_model
from rodimpact.io.quantities import ModelError, parse_quantity

MINIMAL = """
[[rods]]
name = "striker"
velocity = "4.6 m/s"
[[rods.segments]]
shape = "cylinder"
length = "0.5 m"
diameter = "40 mm"

[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "1.8 m"
diameter = "50 mm"

[simulation]
duration = "1 ms"
"""


def load(text: str, **kw):
    return loads_model(textwrap.dedent(text), **kw)


@pytest.mark.parametrize("text, dim, expected", [
    ("50 mm", "length", 0.05), ("210 GPa", "pressure", 210e9), ("51.0 kN s/m", "impedance", 51.0e3),
    ("4.6 m/s", "velocity", 4.6), ("0.5 us", "time", 0.5e-6), ("7.84 g/cm^3", "density", 7840.0),
    ("300 MN/m", "stiffness", 300e6), ("9.81 N/kg", "acceleration", 9.81), ("1.26e-3 m^2", "area", 1.26e-3),
    ("12.6 cm^2", "area", 12.6e-4), ("0.5 1/m", "wavenumber", 0.5), ("30 %", "dimensionless", 0.3),
    (0.064e-3, "time", 0.064e-3), (3, "velocity", 3.0),
])
def test_quantities_convert_to_si(text, dim, expected):
    assert parse_quantity(text, dim, "q") == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize("value, dim, match", [
    ("5 kg", "length", r'q: expected a length such as "50 mm" \(or a number in m\), got "5 kg" \(a mass\)'),
    ("3 m/s", "time", "got \"3 m/s\" \\(a velocity\\)"),
    ("4.6 bananas/s", "velocity", "cannot read"),
    (True, "length", "boolean"),
    ([1, 2], "length", "a list"),
    ("1e999 m", "length", "must be finite"),
])
def test_quantity_errors_name_the_path_and_what_is_valid(value, dim, match):
    with pytest.raises(ModelError, match=match):
        parse_quantity(value, dim, "q")


def test_minimal_model_builds_the_same_objects_as_the_api():
    m = load(MINIMAL)
    striker = ri.Rod([ri.Cylinder(0.5, 0.04)], name="striker")
    bar = ri.Rod([ri.Cylinder(1.8, 0.05)], name="bar")
    assert m.system.rods == (striker, bar)
    assert m.system.velocities == (4.6, 0.0)
    assert m.duration == pytest.approx(1e-3, rel=1e-15) and m.steps is None and m.dt is None
    assert isinstance(m.system.left, ri.FreeEnd) and isinstance(m.system.right, ri.FreeEnd)
    assert m.system.junctions == (ri.Contact(0.0),)


def test_every_segment_shape_against_hand_areas(tmp_path):
    (tmp_path / "profile.csv").write_text("x [mm],diameter [mm]\n0,30\n100,30\n150,40\n")
    m = load("""
        [parameters]
        A0 = "1.26e-3 m^2"
        [materials.insert]
        base = "steel"
        youngs_factor = 1.5
        density_factor = 1.2
        [[rods]]
        [[rods.segments]]
        shape = "tube"
        length = "0.2 m"
        outer_diameter = "50 mm"
        inner_diameter = "20 mm"
        [[rods.segments]]
        shape = "cone"
        length = "0.1 m"
        diameter_start = "50 mm"
        diameter_end = "40 mm"
        [[rods.segments]]
        shape = "linear-area"
        length = "0.1 m"
        area_start = "10 cm^2"
        area_end = "20 cm^2"
        [[rods.segments]]
        shape = "exponential-horn"
        length = "0.3 m"
        area_start = "1e-3 m^2"
        xi = "0.5 1/m"
        [[rods.segments]]
        shape = "quadratic-horn"
        length = "0.3 m"
        area_start = "1e-3 m^2"
        xi = 0.5
        [[rods.segments]]
        shape = "cosh-horn"
        length = "0.3 m"
        area_start = "1e-3 m^2"
        xi = 0.5
        [[rods.segments]]
        shape = "cos-horn"
        length = "0.3 m"
        area_start = "1e-3 m^2"
        xi = 0.5
        [[rods.segments]]
        shape = "table"
        file = "profile.csv"
        [[rods.segments]]
        shape = "table"
        x = ["0 m", "0.1 m"]
        area = ["1e-3 m^2", "2e-3 m^2"]
        [[rods.segments]]
        shape = "expression"
        length = "0.55 m"
        area = "2*A0 - 0.3*A0*sin(pi*s/L)"
        material = "insert"
        [simulation]
        steps = 10
        """, base_dir=tmp_path)
    seg = m.system.rods[0].segments
    assert seg[0].area(0.1) == pytest.approx(math.pi / 4 * (0.05**2 - 0.02**2), rel=1e-14)
    assert seg[1].area(0.05) == pytest.approx(math.pi / 4 * 0.045**2, rel=1e-14)
    assert seg[2].area(0.05) == pytest.approx(1.5e-3, rel=1e-14)
    assert seg[3].area(0.2) == pytest.approx(1e-3 * math.exp(0.1), rel=1e-14)
    assert seg[4].area(0.2) == pytest.approx(1e-3 * 1.1**2, rel=1e-14)
    assert seg[5].area(0.2) == pytest.approx(1e-3 * math.cosh(0.1) ** 2, rel=1e-14)
    assert seg[6].area(0.2) == pytest.approx(1e-3 * math.cos(0.1) ** 2, rel=1e-14)
    assert seg[7].length == pytest.approx(0.15) and seg[7].area(0.125) == pytest.approx(math.pi / 4 * 0.035**2)
    assert seg[8].area(0.05) == pytest.approx(1.5e-3, rel=1e-14)
    s = np.array([0.0, 0.275, 0.55])
    np.testing.assert_allclose(seg[9].area(s), 2 * 1.26e-3 - 0.3 * 1.26e-3 * np.sin(np.pi * s / 0.55), rtol=1e-14)
    assert seg[9].material.youngs_modulus == pytest.approx(1.5 * 210e9) and seg[9].material.density == \
        pytest.approx(1.2 * 7840)
    assert seg[9].material.name == "insert"


def test_impedance_level_rod_with_runs_and_ramp():
    m = load("""
        [[rods]]
        velocity = 9
        [rods.elements]
        element_length = "5 mm"
        runs = [{ impedance = "51.0 kN s/m", count = 3 }, { impedance = "115 kN s/m", length = "10 mm" },
                { impedance_start = "156 kN s/m", impedance_end = "248 kN s/m", count = 5 }]
        [simulation]
        steps = 5
        """)
    rod = m.system.rods[0]
    c = ri.STEEL.wave_speed
    np.testing.assert_array_equal(rod.native.impedance,
                                  [51e3] * 3 + [115e3] * 2 + [156e3, 179e3, 202e3, 225e3, 248e3])
    assert rod.native.dt == pytest.approx(0.005 / c, rel=1e-15)
    assert rod.length == pytest.approx(10 * 0.005, rel=1e-12)


def test_ends_junctions_loads_probes_and_histories(tmp_path):
    (tmp_path / "push.csv").write_text("time [ms],force [kN]\n0,0\n0.1,-5\n0.2,0\n")
    m = load("""
        [[rods]]
        name = "a"
        [[rods.segments]]
        shape = "cylinder"
        length = 1
        diameter = 0.05
        [rods.initial]
        force = { expression = "-1e3*x" }
        [[rods]]
        name = "b"
        [[rods.segments]]
        shape = "cylinder"
        length = 1
        diameter = 0.05
        [[junctions]]
        type = "bonded"
        [ends]
        left = { type = "force", force = { file = "push.csv" } }
        right = { type = "bit-rock", loading_stiffness = "300 MN/m", unloading_stiffness = "1 GN/m" }
        [[loads]]
        type = "force"
        rod = "b"
        position = "0.5 m"
        force = { time = ["0 ms", "1 ms"], value = ["0 N", "10 N"] }
        interpolation = "previous"
        [[loads]]
        type = "bearings"
        rod = 0
        spans = [["0.1 m", "0.3 m"], [0.5, 0.9]]
        friction_coefficient = 0.2
        [[probes]]
        name = "g"
        rod = "b"
        position = "250 mm"
        [simulation]
        duration = "2 ms"
        dt = "1 us"
        energy_every = 10
        backend = "numpy"
        [output]
        snapshot_times = ["0.5 ms"]
        snapshot_every = 7
        plots = ["forces"]
        csv = false
        """, base_dir=tmp_path)
    s = m.system
    assert s.junctions == (ri.Bonded(),)
    np.testing.assert_allclose(s.left.force(np.array([0.05e-3, 0.15e-3, 1e-3])), [-2.5e3, -2.5e3, 0.0])
    assert s.right == ri.BitRockEnd(300e6, 1e9)
    force, bearings = s.loads
    assert (force.rod, force.position) == (1, 0.5)
    np.testing.assert_allclose(force.force(np.array([0.5e-3, 1.0e-3])), [0.0, 10.0])   # zero-order hold
    assert bearings == ri.Bearings(0, [(0.1, 0.3), (0.5, 0.9)], 0.2)
    assert s.initial[0].force(np.array([0.5])) == pytest.approx(-500.0)
    assert s.initial[1] is None
    assert m.probes == (ri.Probe("g", 1, 0.25),)
    assert (m.dt, m.energy_every, m.backend) == (1e-6, 10, "numpy")
    assert m.output.snapshot_times == (0.5e-3,) and m.output.snapshot_every == 7 and m.output.plots == ("forces",)
    assert m.output.csv is False


def _bad(edit_from: str, edit_to: str) -> str:
    assert edit_from in MINIMAL
    return MINIMAL.replace(edit_from, edit_to, 1)


@pytest.mark.parametrize("text, message", [
    (_bad('diameter = "50 mm"', 'diameter = "-5 mm"'), "rods[1].segments[0].diameter: must be > 0, got -5 mm"),
    (_bad('diameter = "50 mm"', 'diameter = "5 kg"'), 'rods[1].segments[0].diameter: expected a length'),
    (_bad('diameter = "50 mm"', 'diamter = "50 mm"'), "rods[1].segments[0].diamter: unknown key (did you mean "
                                                      "'diameter'?)"),
    (_bad('shape = "cylinder"', 'shape = "cylindre"'), "rods[0].segments[0].shape: unknown shape 'cylindre' "
                                                       "(did you mean 'cylinder'?)"),
    (_bad('length = "1.8 m"', 'length = "0 m"'), "rods[1].segments[0].length: must be > 0, got 0 m"),
    (_bad('name = "bar"', 'name = "bar"\nmaterial = "unobtainium"'), "rods[1].material: unknown material "
                                                                     "'unobtainium'"),
    (_bad('velocity = "4.6 m/s"', 'velocity = "4.6 m"'), "rods[0].velocity: expected a velocity"),
    (_bad('duration = "1 ms"', 'duration = "1 ms"\nsteps = 5'), "simulation: give exactly one of duration"),
    (_bad('duration = "1 ms"', ''), "simulation: give exactly one of duration"),
    (MINIMAL + '\n[extra]\nx = 1\n', "extra: unknown key"),
    (MINIMAL + '\n[[probes]]\nname = "g"\nrod = "nope"\nposition = 0.1\n', "probes[0].rod: no rod is named 'nope'"),
    (MINIMAL + '\n[[probes]]\nname = "g"\nrod = 7\nposition = 0.1\n', "probes[0].rod: rod index 7 does not exist"),
    (MINIMAL + '\n[[probes]]\nname = "g"\nrod = 1\nposition = "2 m"\n', "probes[0].position: must lie within "
                                                                         "rod 1"),
    (MINIMAL + '\n[[probes]]\nname = "g"\nrod = 1\nposition = 0.1\n[[probes]]\nname = "g"\nrod = 1\n'
               'position = 0.2\n', "probes[1].name: 'g' is already used"),
    (MINIMAL + '\n[ends]\nright = "sticky"\n', "ends.right.type: unknown type 'sticky'"),
    (MINIMAL + '\n[ends]\nright = { type = "spring" }\n', "ends.right.stiffness: missing"),
    (MINIMAL + '\n[ends]\nright = { type = "bit-rock", loading_stiffness = "1600 MN/m", unloading_stiffness = '
               '"1200 MN/m" }\n', "ends.right.unloading_stiffness: must be >= ends.right.loading_stiffness"),
    (MINIMAL + '\n[[junctions]]\ntype = "contact"\ngap = "-1 mm"\n', "junctions[0].gap: must be >= 0, got -1 mm"),
    (MINIMAL + '\n[[junctions]]\ntype = "contact"\n[[junctions]]\ntype = "bonded"\n', "junctions: need one per "
                                                                                       "neighbouring pair"),
    (MINIMAL + '\n[[loads]]\ntype = "bearings"\nrod = 1\nspans = [[0.5, 0.2]]\nfriction_coefficient = 0.3\n',
     "loads[0].spans[0]: the end must lie after the start"),
    (MINIMAL + '\n[[loads]]\ntype = "bearings"\nrod = 1\nspans = [[0.5, 2.2]]\nfriction_coefficient = 0.3\n',
     "loads[0].spans[0]: the span ends at 2.2 m, beyond the end of rod 1"),
    (MINIMAL + '\n[[loads]]\ntype = "force"\nrod = 1\nposition = 0.5\nforce = { expression = "import os" }\n',
     "loads[0].force.expression: cannot read the expression"),
    (MINIMAL + '\n[[loads]]\ntype = "force"\nrod = 1\nposition = 0.5\nforce = { expression = "t.__class__" }\n',
     "loads[0].force.expression: Attribute is not allowed"),
    (MINIMAL + '\n[[loads]]\ntype = "force"\nrod = 1\nposition = 0.5\nforce = { expression = "open(t)" }\n',
     "loads[0].force.expression: unknown function"),
    (MINIMAL + '\n[[loads]]\ntype = "force"\nrod = 1\nposition = 0.5\nforce = { expression = "1/t" }\n',
     "loads[0].force.expression: the expression '1/t' gives inf at t = 0"),
    (MINIMAL + '\n[output]\nsnapshot_times = ["2 ms"]\n', "output.snapshot_times[0]: 0.002 s lies after the end"),
    (MINIMAL + '\n[output]\nplots = ["pie"]\n', "output.plots[0]: must be one of"),
    (MINIMAL.replace('[simulation]', '[materials.steel]\ndensity = 1\nyoungs_modulus = 1\n[simulation]'),
     "materials.steel: 'steel' is a preset name"),
    ('[[rods]]\n[rods.elements]\nimpedance = [1e4]\n[simulation]\nsteps = 3\n', "rods[0].elements.dt: missing"),
    ('[[rods]]\n[rods.elements]\ndt = 1e-6\nruns = [{ impedance = 1e4, length = "7 mm" }]\n[simulation]\nsteps = 3\n',
     r"rods\[0\].elements.runs\[0\].length: 0.007 m is 1.35\d* elements"),
    ('[[rods]]\nmaterial = "steel"\n[rods.elements]\ndt = 1e-6\nimpedance = [1e4]\n[simulation]\nsteps = 3\n',
     "rods[0].material: an impedance-level rod has no material"),
    ('[[rods]]\n[[rods.segments]]\nshape = "tube"\nlength = 1\nouter_diameter = 0.02\ninner_diameter = 0.03\n'
     '[simulation]\nsteps = 3\n', "rods[0].segments[0].inner_diameter: must satisfy 0 <= inner < outer"),
    ('[[rods]]\n[[rods.segments]]\nshape = "cos-horn"\nlength = 4\narea_start = 1e-3\nxi = 0.5\n'
     '[simulation]\nsteps = 3\n', "rods[0].segments[0].xi: |xi| * length must be < pi/2"),
    ('[[rods]]\n[[rods.segments]]\nshape = "expression"\nlength = 1\narea = "1e-3 - 2e-3*s"\n'
     '[simulation]\nsteps = 3\n', "rods[0].segments[0]: AreaFunction: the cross-section area must be finite and > 0"),
    ('[[rods]]\n[[rods.segments]]\nshape = "expression"\nlength = 1\narea = "A9*s"\n[simulation]\nsteps = 3\n',
     "rods[0].segments[0].area: unknown name 'A9'"),
    ('[[rods]]\n[simulation]\nsteps = 3\n', "rods[0]: give either [[rods.segments]] (geometry) or [rods.elements]"),
    ('[simulation]\nsteps = 3\n', "rods: missing"),
    ('rods = 3\n[simulation]\nsteps = 3\n', "rods: expected an array of tables"),
    ('[[rods]\n', "model: not valid TOML"),
])
def test_bad_model_files_name_the_key_path(text, message):
    with pytest.raises(ModelError) as info:
        load(text)
    msg = str(info.value)
    if message.startswith("rods\\[") or "\\d" in message:
        import re
        assert re.search(message, msg), msg
    else:
        assert message in msg, msg


def test_table_file_errors_name_file_and_row(tmp_path):
    (tmp_path / "bad.csv").write_text("x,diameter\n0,0.03\n0.1,abc\n")
    text = ('[[rods]]\n[[rods.segments]]\nshape = "table"\nfile = "bad.csv"\n[simulation]\nsteps = 3\n')
    with pytest.raises(ModelError, match=r"rods\[0\].segments\[0\].file: .*bad.csv, data row 2, column 2 \(diameter\): "
                                         r"expected a number, got text that is not a number"):
        load(text, base_dir=tmp_path)
    with pytest.raises(ModelError, match=r"rods\[0\].segments\[0\].file: no such CSV file .*missing.csv"):
        load(text.replace("bad.csv", "missing.csv"), base_dir=tmp_path)


def test_expressions_are_evaluated_without_python_eval():
    f = SafeExpression("where(t < 1, 2*t, 3) + max(t, 0.5) if t >= 0 else 0", ("t",))
    np.testing.assert_allclose(f(np.array([0.0, 0.5, 2.0])), [0.5, 1.5, 5.0])
    for src in ["__import__('os').system('true')", "(lambda: 1)()", "[t for t in (1,)]", "t.real", "t[0]",
                "globals()", "'a' * 3", "True + t"]:
        with pytest.raises(ModelError):
            SafeExpression(src, ("t",))


def test_load_model_reports_missing_file(tmp_path):
    with pytest.raises(ModelError, match="no such model file"):
        load_model(tmp_path / "none.toml")


@pytest.mark.parametrize("run, key", [('{ impedance = "51.0 kN s/m", length = "0.2 m" }', "runs[0].length"),
                                      ('{ impedance = "51.0 kN s/m", count = 100_000_000_000 }', "runs[0].count")])
def test_a_tiny_element_length_is_a_model_error_naming_the_run(run, key):
    # 0.2 m of 1e-12 m elements needs 2e11 elements: the memory check raised a plain ValueError through
    # load_model, though docs/security.md promises that every model-file error is a ModelError (issue 20, item 16)
    text = f"""
        [[rods]]
        velocity = 9
        [rods.elements]
        element_length = "1e-12 m"
        runs = [{run}]
        [simulation]
        steps = 5
        """
    with pytest.raises(ModelError, match=rf"^rods\[0\]\.elements\.{re.escape(key)}: .* elements would need .* memory"):
        load(text)


def test_a_library_value_error_the_loader_missed_becomes_a_model_error(monkeypatch):
    # the safety net of model_from_dict: any ValueError of the library becomes a ModelError, message unchanged
    import rodimpact.io.model as model_module

    def refuse(*args, **kwargs):
        raise ValueError("materials: refused for the test")

    monkeypatch.setattr(model_module, "_materials", refuse)     # called outside any key-path wrapper
    with pytest.raises(ModelError, match="refused for the test"):
        load(MINIMAL)
