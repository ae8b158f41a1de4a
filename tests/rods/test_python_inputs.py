"""Python accepts what model files accept, with did-you-mean, refuses wrong types, and warns about absurd
velocities (issue 20, item 12)."""

import warnings

import pytest

import rodimpact as ri
from rodimpact.rods.material import MATERIALS
from rodimpact.rods.plausibility import PlausibilityWarning


def test_a_rod_accepts_a_preset_material_name_as_model_files_do():
    rod = ri.Rod([ri.Cylinder(0.3, 0.02)], material="steel")
    assert rod.material == ri.STEEL
    assert ri.Rod([ri.Cylinder(0.3, 0.02)], material=" Ti-6Al-4V ").material is MATERIALS["ti-6al-4v"]
    assert ri.Cylinder(0.3, 0.02, material="aluminum-7075-t6").material is MATERIALS["aluminium-7075-t6"]


@pytest.mark.parametrize("build, where, near", [
    (lambda: ri.Rod([ri.Cylinder(0.3, 0.02)], material="stel"), "Rod.material", "steel"),
    (lambda: ri.Cylinder(0.3, 0.02, material="ti6al4v"), "Cylinder.material", "ti-6al-4v"),
])
def test_an_unknown_material_name_suggests_the_closest_preset(build, where, near):
    with pytest.raises(ValueError, match=rf"^{where}: unknown material preset .* did you mean '{near}'\? valid "
                                         rf"presets are 'aluminium-7075-t6', 'steel', 'ti-6al-4v'"):
        build()


def test_a_material_of_another_type_is_refused():
    with pytest.raises(TypeError, match=r"^Rod.material: must be a Material or a preset name"):
        ri.Rod([ri.Cylinder(0.3, 0.02)], material=7840.0)
    with pytest.raises(TypeError, match=r"^Cylinder.material: must be a Material or a preset name"):
        ri.Cylinder(0.3, 0.02, material=["steel"])


def _two_rods(**kw):
    return ri.System([ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0], **kw)


@pytest.mark.parametrize("kw, match", [
    (dict(right="fixd"), r"^right: must be an end condition .* got 'fixd' \(did you mean 'fixed'\?\)$"),
    (dict(left="non reflecting"), r"^left: .* \(did you mean 'nonreflecting'\?\)$"),
    (dict(junctions=["bonde"]), r"^junctions\[0\]: must be Contact\(gap=...\), Bonded\(\) .* \(did you mean 'bonded'\?\)$"),
])
def test_end_and_junction_names_suggest_the_closest(kw, match):
    with pytest.raises(ValueError, match=match):
        _two_rods(**kw)


@pytest.mark.parametrize("kw", [dict(left=5), dict(right=None), dict(junctions=[1])])
def test_ends_and_junctions_of_another_type_are_type_errors(kw):
    with pytest.raises(TypeError, match="of type"):
        _two_rods(**kw)


def _plausibility(build):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        build()
    return [str(w.message) for w in caught if issubclass(w.category, PlausibilityWarning)]


def test_a_striker_at_3e8_m_per_s_is_warned_about():
    rods = [ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])]
    messages = _plausibility(lambda: ri.simulate(rods, [3e8, 0.0], duration=1e-5))
    assert len(messages) == 1
    # 3e8 / 5175.5 = 57,965 times the steel bar wave speed, strain v / 2c = 28,983
    assert messages[0].startswith("rods[0].velocity = 3e+08 m/s is 5.8e+04 times the bar wave speed")
    assert "2.9e+04" in messages[0]


def test_the_speed_limit_is_a_tenth_of_the_slowest_wave_speed_of_each_rod():
    c_al = MATERIALS["aluminium-7075-t6"].wave_speed            # 5051 m/s
    bar = ri.Rod([ri.Cylinder(1.0, 0.02)])
    aluminium = ri.Rod([ri.Cylinder(0.1, 0.02), ri.Cylinder(0.1, 0.02, material="aluminium-7075-t6")])
    assert _plausibility(lambda: ri.System([aluminium, bar], [0.099 * c_al, 0.0])) == []
    assert len(_plausibility(lambda: ri.System([aluminium, bar], [0.101 * c_al, 0.0]))) == 1
    # a rod moving left, and an impedance-level rod (its wave speed is given)
    assert len(_plausibility(lambda: ri.System([bar, aluminium], [0.0, -0.101 * c_al]))) == 1
    native = ri.Rod.from_impedance([51e3] * 10, 1e-6, 2000.0)
    assert len(_plausibility(lambda: ri.System([native, bar], [201.0, 0.0]))) == 1
    assert _plausibility(lambda: ri.System([native, bar], [199.0, 0.0])) == []


def test_realistic_impacts_are_quiet():
    rods = [ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])]
    assert _plausibility(lambda: ri.System(rods, [300.0, 0.0])) == []      # a Taylor-test speed


def test_a_model_file_names_the_velocity_key():
    text = """
[[rods]]
velocity = "300000 km/s"
segments = [{ shape = "cylinder", length = "0.3 m", diameter = "20 mm" }]
[[rods]]
velocity = 0
segments = [{ shape = "cylinder", length = "1 m", diameter = "20 mm" }]
[simulation]
duration = "0.01 ms"
"""
    messages = _plausibility(lambda: ri.loads_model(text))
    assert [m.split(" m/s")[0] for m in messages] == ["rods[0].velocity = 3e+08"]
