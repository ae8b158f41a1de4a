"""Overrides of model and spec keys (``--set KEY=VALUE``, ``overrides=``): applied before validation, errors name
the key path and the override that set it."""

import tomllib

import pytest

from rodimpact.io import design_spec, synthesis_spec
from rodimpact.io.model import ModelError, loads_model
from rodimpact.io.overrides import apply_overrides, parse_assignment, parse_key, parse_value
from rodimpact.io.templates import SIMULATE


def test_values_are_toml_or_plain_text():
    assert parse_value("5") == 5 and parse_value("1.5e-6") == 1.5e-6 and parse_value("true") is True
    assert parse_value('"50 mm"') == "50 mm" and parse_value("[1, 2]") == [1, 2]
    assert parse_value('{ type = "spring", stiffness = "3 MN/m" }') == {"type": "spring", "stiffness": "3 MN/m"}
    assert parse_value("5 m/s") == "5 m/s" and parse_value("steel") == "steel" and parse_value("") == ""
    assert parse_value("1\nx = 2") == "1\nx = 2"          # one value, never more keys
    assert parse_assignment("rods[0].velocity = 5 m/s") == ("rods[0].velocity", "5 m/s")
    with pytest.raises(ValueError, match="--set 'velocity': expected KEY=VALUE"):
        parse_assignment("velocity")


def test_key_paths():
    assert parse_key("rods[1].segments[0].diameter") == ["rods", 1, "segments", 0, "diameter"]
    assert parse_key('rods."bar 2".velocity') == ["rods", "bar 2", "velocity"]
    assert parse_key("materials.hard-steel.youngs_factor") == ["materials", "hard-steel", "youngs_factor"]
    for bad in ("rods..velocity", "rods.", ".rods", "rods[x]", "rods velocity"):
        with pytest.raises(ModelError, match="not a key path"):
            parse_key(bad)


def test_overrides_set_keys_by_index_or_name_and_create_tables():
    model = loads_model(SIMULATE, overrides={"rods.piston.velocity": "5 m/s", "rods[1].segments[0].length": "2 m",
                                             "output.record_every": 2, "probes.SG3.position": "1.9 m"})
    assert model.system.velocities == (5.0, 0.0) and model.system.rods[1].length == 2.0
    assert model.output.record_every == 2 and model.probes[2].position == 1.9
    raw = tomllib.loads(SIMULATE)
    _, applied = apply_overrides(raw, {"rods.rod.velocity": 1, "simulation.dt": "1 us"})
    assert applied == {"rods[1].velocity": "rods.rod.velocity = 1", "simulation.dt": 'simulation.dt = "1 us"'}
    assert raw == tomllib.loads(SIMULATE)                   # the parsed file itself is left alone


@pytest.mark.parametrize("overrides, match", [
    ({"rods.pistn.velocity": 5}, r"rods.pistn.velocity: rods has no entry named 'pistn' \(names: piston, rod; or "
                                 r"give an index, e.g. rods\[0\]\)"),
    ({"rods[3].velocity": 5}, r"rods\[3\].velocity: rods has 2 entries \(rods\[0\] .. rods\[1\]\)"),
    ({"simulation.dt.unit": "s"}, r"simulation.dt.unit: simulation.dt is '0.5 us', not a table or an array"),
    ({"simulation[0]": 1}, r"simulation\[0\]: simulation is a table, not an array"),
    ({"rods.piston.velocty": 5}, r"rods\[0\].velocty: unknown key \(did you mean 'velocity'\?\).*\(set by the "
                                 r"override rods.piston.velocty = 5\)"),
    ({"rods.piston.velocity": "5 kg"}, r"rods\[0\].velocity: expected a velocity .* \(set by the override "
                                       r'rods.piston.velocity = "5 kg"\)'),
    ({"rods.piston.velocity": 1, "rods[0].velocity": 2}, r"rods\[0\].velocity: set twice, by rods.piston.velocity "
                                                         r"= 1 and by rods\[0\].velocity = 2"),
])
def test_bad_overrides_name_the_key(overrides, match):
    with pytest.raises(ModelError, match=match):
        loads_model(SIMULATE, overrides=overrides)


def test_specs_take_overrides_and_record_what_ran():
    spec = synthesis_spec.loads_spec(synthesis_spec.TEMPLATE, overrides={"striker.velocity": "7 m/s"})
    assert spec.striker_velocity == 7.0
    assert spec.text.startswith('# spec with the overrides striker.velocity = "7 m/s"')
    again = synthesis_spec.loads_spec(spec.text)              # the recorded spec runs as the overridden one
    assert again.striker_velocity == 7.0 and again.n == spec.n and again.target == spec.target
    assert synthesis_spec.loads_spec(synthesis_spec.TEMPLATE).text == synthesis_spec.TEMPLATE
    design = design_spec.loads_spec(design_spec.TEMPLATE, overrides={"design.starts": 1})
    assert design.kwargs["starts"] == 1 and design_spec.loads_spec(design.text).kwargs["starts"] == 1
    with pytest.raises(ModelError, match=r"design.starts: .*\(set by the override design.starts = 0\)"):
        design_spec.loads_spec(design_spec.TEMPLATE, overrides={"design.starts": 0})
