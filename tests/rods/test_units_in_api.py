"""Issue 14 item 9: unit strings and pint Quantities wherever the Python API takes a physical quantity; a wrong
dimension is a clear error naming the argument; ``"non-reflecting"`` is accepted in model files as in Python."""

import numpy as np
import pint
import pytest

import rodimpact as ri

U = pint.UnitRegistry()     # a registry of the user's own, not rodimpact's


def test_segments_and_materials_take_unit_strings_and_quantities():
    assert ri.Cylinder("300 mm", "20 mm") == ri.Cylinder(0.3, 0.02)
    assert ri.Cylinder(300 * U.mm, 0.787402 * U.inch).diameter == pytest.approx(0.02, rel=1e-6)
    assert ri.Tube("1 m", "40 mm", "1 cm") == ri.Tube(1.0, 0.04, 0.01)
    assert ri.Cone("0.5 m", "30 mm", "50 mm") == ri.Cone(0.5, 0.03, 0.05)
    assert ri.LinearAreaTaper("1 m", "3 cm^2", 5e-4 * U.m**2).area_start == pytest.approx(3e-4, rel=1e-12)
    assert ri.ExponentialHorn("2 m", "1 cm^2", "0.5 1/m").xi == 0.5
    mat = ri.Material(youngs_modulus="210 GPa", density="7.84 g/cm^3")
    assert mat.youngs_modulus == pytest.approx(210e9, rel=1e-12) and mat.density == pytest.approx(7840.0, rel=1e-12)
    prof = ri.TabulatedProfile([0, 10, 20] * U.mm, diameter=["10 mm", "12 mm", 0.014])
    assert np.allclose(prof.x, [0.0, 0.01, 0.02], rtol=1e-12) and np.allclose(prof.values, [0.01, 0.012, 0.014])
    rod = ri.Rod.from_impedance(["10 kN s/m", 2e4], "1 us")
    assert np.array_equal(rod.native.impedance, [1e4, 2e4]) and rod.native.dt == pytest.approx(1e-6, rel=1e-12)
    assert ri.Probe("p", 1, "110 mm").position == pytest.approx(0.11, rel=1e-12)
    assert ri.SpringEnd("300 MN/m").stiffness == pytest.approx(3e8, rel=1e-12)
    assert ri.Contact(gap="1 mm").gap == pytest.approx(1e-3, rel=1e-12)
    assert ri.ForceEnd("-5 kN").force.source == pytest.approx(-5e3, rel=1e-12)
    assert ri.NodalForce(0, "0.1 m", 2 * U.kN).force.source == pytest.approx(2e3, rel=1e-12)
    ramp = ri.VelocityEnd((["0 ms", "1 ms"], [0, "2 m/s"])).velocity
    assert np.allclose(ramp(np.array([0.0, 5e-4, 1e-3])), [0.0, 1.0, 2.0], rtol=1e-12)
    assert ri.Bearings(1, [("0.1 m", "20 cm")], 0.3, gravity="9.81 N/kg").spans == ((0.1, 0.2),)
    with pytest.raises(ValueError, match="ForceEnd.force: expected a quantity in N, got \"5 m/s\""):
        ri.ForceEnd("5 m/s")


def test_simulate_takes_units_and_gives_the_same_result_as_si_numbers():
    rods = [ri.Rod([ri.Cylinder("300 mm", "20 mm")]), ri.Rod([ri.Cylinder(1.0 * U.m, 20 * U.mm)])]
    with_units = ri.simulate(rods, velocities=["5 m/s", 0], duration="0.3 ms", dt="1 us")
    si = ri.simulate([ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0],
                     duration=3e-4, dt=1e-6)
    assert with_units.dt == si.dt and with_units.n_steps == si.n_steps
    assert np.array_equal(with_units.junction_force, si.junction_force)
    quantity = ri.simulate(rods, velocities=[5000 * U.mm / U.s, 0 * U.m / U.s], duration=0.3 * U.ms,
                           dt=1 * U.us)
    assert np.array_equal(quantity.junction_force, si.junction_force)


@pytest.mark.parametrize("build, message", [
    (lambda: ri.Cylinder("300 mm", "5 kg"), r"Cylinder.diameter: expected a quantity in m, got \"5 kg\" \(a mass\)"),
    (lambda: ri.Cylinder(0.3 * U.s, 0.02), r"Cylinder.length: expected a quantity in m, got 0.3 s \(a time\)"),
    (lambda: ri.Material("210 GPa", "7840 kg"), r"density: expected a quantity in kg/m\^3, got \"7840 kg\""),
    (lambda: ri.simulate([ri.Rod([ri.Cylinder(0.3, 0.02)])], ["5 m"], duration=1e-4),
     r"velocities\[0\]: expected a quantity in m/s, got \"5 m\" \(a length\)"),
    (lambda: ri.simulate([ri.Rod([ri.Cylinder(0.3, 0.02)])], [5.0], duration="1 mm"),
     r"duration: expected a quantity in s, got \"1 mm\" \(a length\)"),
])
def test_a_wrong_dimension_names_the_argument(build, message):
    with pytest.raises(ValueError, match=message):
        build()


def test_strings_that_are_not_quantities_stay_type_errors():
    with pytest.raises(TypeError, match="Cylinder.diameter: must be a real number in m"):
        ri.Cylinder(0.3, "twenty")
    with pytest.raises(TypeError, match="Cylinder.diameter: must be a real number in m"):
        ri.Cylinder(0.3, "20")     # a number in a string: give the number, or a unit


def test_non_reflecting_is_spelled_both_ways_in_python_and_in_model_files():
    text = """
[[rods]]
velocity = 5
segments = [{{shape = "cylinder", length = "0.3 m", diameter = "20 mm"}}]
[ends]
right = {right}
[simulation]
duration = "0.1 ms"
"""
    for spelling in ("nonreflecting", "non-reflecting"):
        assert isinstance(ri.System([ri.Rod([ri.Cylinder(0.3, 0.02)])], [5.0], right=spelling).right,
                          ri.NonReflectingEnd)
        m = ri.loads_model(text.format(right=f'"{spelling}"'))
        assert m.system.right == ri.NonReflectingEnd()
        m = ri.loads_model(text.format(right=f'{{ type = "{spelling}", impedance = "60 kN s/m" }}'))
        assert m.system.right == ri.NonReflectingEnd(6e4)


@pytest.mark.parametrize("text, match", [("10**10**10 m", "power"), ("10**400 m", "power"),
                                         ("1e400 m", "finite"), ("m" * 100_000, "at most 200 characters")])
def test_hostile_unit_strings_in_python_are_refused_at_once(text, match):
    """The Python API parses unit strings with the same limits as model files: an exponent tower (which pint
    would evaluate exactly, never finishing), a number beyond the float range and a huge string are named errors."""
    with pytest.raises(ValueError, match=match):
        ri.Cylinder(text, 0.02)
