"""Materials, segments and rods: geometry helpers against hand calculations; bad input is rejected."""

import math

import pytest

import rodimpact as ri


def test_steel_preset_and_helpers():
    assert ri.STEEL.youngs_modulus == 210e9 and ri.STEEL.density == 7840.0
    assert ri.STEEL.wave_speed == pytest.approx(math.sqrt(210e9 / 7840.0), rel=1e-15)
    a = 1.96e-3
    assert ri.STEEL.impedance(a) == pytest.approx(a * math.sqrt(210e9 * 7840.0), rel=1e-14)
    assert ri.Material.preset("Steel") is ri.STEEL
    scaled = ri.STEEL.scaled(1.5, 1.2)
    assert scaled.youngs_modulus == pytest.approx(315e9) and scaled.density == pytest.approx(9408.0)


def test_rod_profile_queries_against_hand_values():
    mat2 = ri.STEEL.scaled(1.5, 1.2)
    rod = ri.Rod([ri.Cylinder(0.2, 0.05), ri.Cone(0.1, 0.05, 0.04), ri.Tube(0.3, 0.04, 0.02, material=mat2)])
    assert rod.length == pytest.approx(0.6)
    a1 = math.pi / 4 * 0.05**2
    a3 = math.pi / 4 * (0.04**2 - 0.02**2)
    cone_volume = math.pi * 0.1 / 12 * (0.05**2 + 0.05 * 0.04 + 0.04**2)
    mass = 7840 * (a1 * 0.2 + cone_volume) + mat2.density * a3 * 0.3
    assert rod.mass == pytest.approx(mass, rel=1e-13)
    assert rod.area(0.25) == pytest.approx(math.pi / 4 * 0.045**2, rel=1e-14)
    assert rod.impedance(0.5) == pytest.approx(mat2.impedance(a3), rel=1e-14)
    c = ri.STEEL.wave_speed
    assert rod.travel_time(0.6) == pytest.approx(0.3 / c + 0.3 / mat2.wave_speed, rel=1e-14)
    with pytest.raises(ValueError, match="within the rod"):
        rod.area(0.7)


def test_table_21_families_areas():
    a0, xi, s = 1.96e-3, 0.5, 0.8
    assert ri.ExponentialHorn(1.0, a0, xi).area(s) == pytest.approx(a0 * math.exp(xi * s))
    assert ri.QuadraticHorn(1.0, a0, xi).area(s) == pytest.approx(a0 * (1 + xi * s) ** 2)
    assert ri.CoshHorn(1.0, a0, xi).area(s) == pytest.approx(a0 * math.cosh(xi * s) ** 2)
    assert ri.CosHorn(1.0, a0, xi).area(s) == pytest.approx(a0 * math.cos(xi * s) ** 2)
    tab = ri.TabulatedProfile([0.0, 0.1, 0.3], diameter=[0.04, 0.05, 0.05])
    assert tab.length == pytest.approx(0.3) and tab.area(0.05) == pytest.approx(math.pi / 4 * 0.045**2)
    f = ri.AreaFunction(0.5, lambda s: 1e-3 * (1 + s))
    assert f.area(0.25) == pytest.approx(1.25e-3)


def test_from_impedance_rod():
    rod = ri.Rod.from_impedance([51e3] * 50 + [28.7e3] * 50, dt=1e-6)
    c = ri.STEEL.wave_speed
    assert rod.length == pytest.approx(100 * c * 1e-6, rel=1e-14)
    assert rod.impedance(0.1 * rod.length) == pytest.approx(51e3, rel=1e-13)
    assert rod.impedance(0.9 * rod.length) == pytest.approx(28.7e3, rel=1e-13)
    assert rod.mass == pytest.approx((51e3 + 28.7e3) * 50 * 1e-6, rel=1e-13)   # m = Z dt per element


@pytest.mark.parametrize("make, match", [
    (lambda: ri.Material(-210e9, 7840), "youngs_modulus: must be > 0"),
    (lambda: ri.Material(210e9, 0.0), "density: must be > 0"),
    (lambda: ri.Material(float("nan"), 7840), "youngs_modulus: must be finite"),
    (lambda: ri.Cylinder(0.1, -0.05), "Cylinder.diameter: must be > 0"),
    (lambda: ri.Cylinder(0.0, 0.05), "Cylinder.length: must be > 0"),
    (lambda: ri.Tube(0.1, 0.04, 0.05), "inner_diameter"),
    (lambda: ri.LinearAreaTaper(0.1, 1e-3, 0.0), "area_end: must be > 0"),
    (lambda: ri.CosHorn(2.0, 1e-3, 1.0), "pi/2"),
    (lambda: ri.AreaFunction(1.0, lambda s: 1e-3 - 2e-3 * s), "area must be finite and > 0"),
    (lambda: ri.TabulatedProfile([0, 0.2, 0.1], diameter=[1, 1, 1]), "strictly increasing"),
    (lambda: ri.Rod([]), "at least one segment"),
    (lambda: ri.Rod(None), "Rod.segments: must be a Segment or a list of Segments"),
    (lambda: ri.Material(210e9, 7840, 0.3), "Material.name: must be a string"),
    (lambda: ri.Rod.from_impedance([1e4, -1e4], dt=1e-6), r"impedances: every entry must be > 0"),
    (lambda: ri.Rod.from_impedance([1e4, float("nan")], dt=1e-6), "impedances: must be finite"),
    (lambda: ri.Bearings(0, [(0.0, 0.5), (0.4, 0.8)], 0.3), "must not overlap"),
])
def test_bad_model_input_is_rejected_with_named_quantity(make, match):
    with pytest.raises((ValueError, TypeError), match=match):
        make()
