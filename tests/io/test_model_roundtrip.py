"""Round trips: objects -> model file -> objects, and model file -> objects -> model file."""

import math

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.examples import EXAMPLES, load_example, model_text
from rodimpact.io.expressions import SafeExpression, expression_area
from rodimpact.io.model import Model, ModelWriteError, OutputSpec, dump_model, loads_model

T = np.linspace(0.0, 2e-3, 7)


def _same_history(a, b):
    assert type(a.source) is type(b.source)
    assert a.interpolation == b.interpolation
    if isinstance(a.source, tuple):
        np.testing.assert_array_equal(a.source[0], b.source[0])
        np.testing.assert_array_equal(a.source[1], b.source[1])
    else:
        assert a.source == b.source
    np.testing.assert_array_equal(a(T), b(T))


def _same_field(a, b):
    if a is None or b is None:
        assert a is None and b is None
    elif isinstance(a, SafeExpression):
        assert a == b
    else:
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b))


def assert_same_model(a: Model, b: Model) -> None:
    sa, sb = a.system, b.system
    assert len(sa.rods) == len(sb.rods)
    for ra, rb in zip(sa.rods, sb.rods):
        assert ra == rb
        for x, y in zip(ra.segments, rb.segments):          # AreaFunction equality compares only length/material
            assert type(x) is type(y)
            s = np.linspace(0.0, x.length, 11)
            np.testing.assert_array_equal(x.area(s), y.area(s))
            if isinstance(x, ri.AreaFunction):
                assert x.function == y.function
    assert sa.velocities == sb.velocities
    assert sa.junctions == sb.junctions
    for ea, eb in ((sa.left, sb.left), (sa.right, sb.right)):
        assert type(ea) is type(eb)
        if isinstance(ea, ri.ForceEnd):
            _same_history(ea.force, eb.force)
        elif isinstance(ea, ri.VelocityEnd):
            _same_history(ea.velocity, eb.velocity)
        else:
            assert ea == eb
    assert len(sa.loads) == len(sb.loads)
    for la, lb in zip(sa.loads, sb.loads):
        assert type(la) is type(lb)
        if isinstance(la, ri.NodalForce):
            assert (la.rod, la.position) == (lb.rod, lb.position)
            _same_history(la.force, lb.force)
        else:
            assert la == lb
    for ia, ib in zip(sa.initial, sb.initial):
        if ia is None or ib is None:
            assert ia is None and ib is None
        else:
            _same_field(ia.force, ib.force)
            _same_field(ia.velocity, ib.velocity)
    assert a.probes == b.probes
    assert (a.duration, a.steps, a.dt, a.backend, a.energy_every) == (b.duration, b.steps, b.dt, b.backend,
                                                                       b.energy_every)
    assert a.output == b.output
    assert (a.title, a.description) == (b.title, b.description)


def hand_built_model() -> Model:
    insert = ri.STEEL.scaled(1.5, 1.2, "insert")
    al = ri.ALUMINIUM_7075
    a0 = 1.26e-3
    striker = ri.Rod([
        ri.Cylinder(0.1, 0.04), ri.Tube(0.2, 0.05, 0.02, material=insert), ri.Cone(0.1, 0.05, 0.04),
        ri.LinearAreaTaper(0.1, 1e-3, 2e-3), ri.ExponentialHorn(0.3, 1e-3, 0.5), ri.QuadraticHorn(0.3, 1e-3, -0.4),
        ri.CoshHorn(0.3, 1e-3, 0.7), ri.CosHorn(0.3, 1e-3, 0.9),
        ri.TabulatedProfile([0.0, 0.1, 0.15], diameter=[0.03, 0.03, 0.04]),
        ri.TabulatedProfile([1.0, 1.1], area=[1e-3, 2e-3], material=al),
        ri.AreaFunction(0.55, expression_area("A1 - 0.3*A0*sin(pi*s/L)", 0.55, {"A0": a0, "A1": 1.96e-3}),
                        material=insert),
    ], material=ri.STEEL, name="striker")
    z = np.concatenate([np.full(3, 51.0e3), np.full(2, 115e3), np.linspace(156e3, 248e3, 4)])
    middle = ri.Rod.from_impedance(z, 1e-6, 5000.0, density=7800.0, name="middle")
    bar = ri.Rod([ri.Cylinder(1.8, 0.05)], material=insert, name="bar")
    system = ri.System(
        [striker, middle, bar], [4.6, 0.1 + 0.2, -1.0 / 3.0], junctions=[ri.Contact(1e-4), ri.Bonded()],
        left=ri.ForceEnd((np.array([0.0, 1e-4, 2e-4]), np.array([0.0, -5e3, 0.0])), interpolation="previous"),
        right=ri.SpringEnd(3e8, 2e3),
        loads=[ri.NodalForce(2, 0.5, SafeExpression("-1e3*sin(pi*t/T0)", ("t",), {"T0": 2e-4})),
               ri.Bearings(0, [(0.05, 0.15), (0.5, 0.9)], 0.3, 9.81, normal_load=12.5)],
        initial=[ri.InitialState(force=SafeExpression("-1e3*x", ("x",))), None,
                 ri.InitialState(velocity=np.linspace(0.0, 1.0, 5))])
    return Model(system, duration=2e-3, dt=5e-7, probes=(ri.Probe("SG 1", 2, 0.11), ri.Probe("face", 1, 0.0)),
                 output=OutputSpec((0.064e-3, 0.259e-3), snapshot_every=None, snapshot_count=50,
                                   plots=("forces", "xt"), csv=False, fields=True),
                 backend="numpy", energy_every=3, title="all features", description='quotes " and \\ and é',
                 parameters={})


def test_objects_to_file_to_objects():
    model = hand_built_model()
    text = dump_model(model)
    again = loads_model(text)
    assert_same_model(model, again)
    assert again.parameters == {"A0": 1.26e-3, "A1": 1.96e-3, "T0": 2e-4}


def test_file_to_objects_to_file_is_stable():
    text = dump_model(hand_built_model())
    once = loads_model(text)
    assert dump_model(once) == text


def test_other_end_conditions_round_trip():
    rod = ri.Rod([ri.Cylinder(1.0, 0.05)])
    for left, right in [(ri.FixedEnd(), ri.NonReflectingEnd()), (ri.NonReflectingEnd(4e4), ri.BitRockEnd(3e8)),
                        (ri.VelocityEnd(SafeExpression("2*t", ("t",))), ri.ForceEnd(-10.0)),
                        (ri.VelocityEnd(1.5), ri.BitRockEnd(3e8, 9e8))]:
        m = Model(ri.System([rod], [0.0], left=left, right=right), steps=10)
        assert_same_model(m, loads_model(dump_model(m)))


@pytest.mark.parametrize("name", list(EXAMPLES))
def test_builtin_examples_round_trip(name):
    for i in range(len(EXAMPLES[name].models)):
        model = load_example(name, i)
        text = dump_model(model)
        again = loads_model(text)
        assert_same_model(model, again)
        assert dump_model(again) == text


def test_python_callables_cannot_be_written_and_say_where():
    rod = ri.Rod([ri.Cylinder(0.2, 0.05), ri.AreaFunction(0.5, lambda s: 1e-3 + 0 * s)])
    m = Model(ri.System([rod], [0.0]), steps=3)
    with pytest.raises(ModelWriteError, match=r"rods\[0\].segments\[1\]: an AreaFunction holding a Python callable"):
        dump_model(m)
    m = Model(ri.System([ri.Rod([ri.Cylinder(1.0, 0.05)])], [0.0], left=ri.ForceEnd(lambda t: -t)), steps=3)
    with pytest.raises(ModelWriteError, match=r"ends.left.force: a Python callable cannot be written"):
        dump_model(m)


def test_written_numbers_are_exact_and_annotated_with_units():
    m = Model(ri.System([ri.Rod([ri.Cylinder(0.1 + 0.2, 0.05)])], [math.pi]), duration=1e-3 / 3)
    text = dump_model(m)
    assert "length = 0.30000000000000004  # m" in text
    assert "velocity = 3.141592653589793  # m/s" in text
    again = loads_model(text)
    assert again.system.rods[0].segments[0].length == 0.1 + 0.2 and again.duration == 1e-3 / 3


def test_example_files_keep_the_thesis_numbers_as_written():
    """The shipped files state the thesis's numbers with units, as a reader of the thesis would write them."""
    assert '"51.0 kN s/m"' in model_text("first-example.toml") and '"28.7 kN s/m"' in model_text("first-example.toml")
    complex_text = model_text("complex-example.toml")
    for s in ('"1.26e-3 m^2"', '"1.96e-3 m^2"', "youngs_factor = 1.5", "density_factor = 1.2", '"3.00 m/s"',
              '"-3.00 m/s"', "friction_coefficient = 0.3", '"9.81 N/kg"', "A1 - 0.3*A0*sin(pi*s/L)"):
        assert s in complex_text
    drill = model_text("percussion-drilling.toml")
    for s in ('"51.0 kN s/m"', '"115 kN s/m"', '"79.7 kN s/m"', '"156 kN s/m"', '"248 kN s/m"', '"300 MN/m"',
              '"9.00 m/s"'):
        assert s in drill
    rig = model_text("test-rig.toml")
    for s in ('"4.60 m/s"', '"1800 mm"', '"110 mm"', '"900 mm"', '"1690 mm"', '"40 mm"', '"50 mm"'):
        assert s in rig


def test_a_law_tabulated_from_arrays_cannot_be_written_and_says_where():
    """A tabulated law given as arrays has no file to name; writing it is refused with its key path (a law read
    from a CSV file is written by its file name, tests/io/test_model_files.py)."""
    law = ri.TabulatedLaw(117e9, plastic_strain=[0.0, 1.0], stress=[80e6, 1080e6])
    joint = ri.Specimen(law, 0.006, 0.003)
    bar = ri.Rod([ri.Cylinder(1.0, 0.0095)])
    m = Model(ri.System([bar, bar], [1.0, 0.0], junctions=[joint]), steps=3)
    with pytest.raises(ModelWriteError, match=r"junctions\[0\].law.file: TabulatedLaw holds its data as arrays"):
        dump_model(m)
