"""Overrides of model and spec keys (``--set KEY=VALUE``, ``overrides=``): applied before validation, errors name
the key path and the override that set it."""

import tomllib

import pytest

from rodimpact.io import design_spec, synthesis_spec
from rodimpact.io.model import ModelError, loads_model
from rodimpact.io.overrides import apply_overrides, parse_assignment, parse_key, parse_value
from rodimpact.io.templates import SIMULATE
from rodimpact.rods.material import STEEL

#: A two-rod impact run for a number of steps, as the model.toml written beside every result gives it.
SMALL_STEPS = """
[[rods]]
velocity = "5 m/s"
segments = [{ shape = "cylinder", length = "0.1 m", diameter = "40 mm" }]
[[rods]]
segments = [{ shape = "cylinder", length = "0.4 m", diameter = "40 mm" }]
[simulation]
steps = 150
dt = 1.932183566158592e-06
"""


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
    assert design.kwargs["search"].starts == 1 and design_spec.loads_spec(design.text).kwargs["search"].starts == 1
    with pytest.raises(ModelError, match=r"design.starts: .*\(set by the override design.starts = 0\)"):
        design_spec.loads_spec(design_spec.TEMPLATE, overrides={"design.starts": 0})


# ------------------------------------------------------------------ keys that exclude each other (issue 20, item 8)
def test_setting_duration_replaces_the_steps_of_a_written_model(tmp_path):
    """The model.toml that rodimpact writes beside a result (and design / synthesize in ``verification/``) gives
    ``steps``; ``--set simulation.duration=...`` on it used to fail with "give exactly one of duration or steps"."""
    import rodimpact as ri
    from rodimpact.io.model import load_model, model_from_result

    res = loads_model(SMALL_STEPS).simulate()
    ri.save(res, tmp_path / "out", model=model_from_result(res))
    written = (tmp_path / "out" / "model.toml").read_text()
    assert "\nsteps = 150" in written and "duration" not in written          # what the file sets
    model = load_model(tmp_path / "out" / "model.toml", overrides={"simulation.duration": 300 * res.dt})
    assert model.duration == 300 * res.dt and model.steps is None
    assert model.simulate().n_steps == 300                                    # 300 steps of the file's dt
    back = load_model(tmp_path / "out" / "model.toml", overrides={"simulation.steps": 20})   # and the other way
    assert back.steps == 20 and back.duration is None
    raw = tomllib.loads(written)
    out, applied = apply_overrides(raw, {"simulation.duration": "0.58 ms"})
    assert "steps" not in out["simulation"] and raw["simulation"]["steps"] == 150        # the file is left alone
    assert applied == {"simulation.duration": 'simulation.duration = "0.58 ms" (replacing the file\'s '
                                              'simulation.steps = 150)'}


def test_steps_replaces_duration_and_setting_both_is_still_an_error():
    model = loads_model(SIMULATE, overrides={"simulation.steps": 40})
    assert model.steps == 40 and model.duration is None
    with pytest.raises(ModelError, match="simulation: give exactly one of duration"):      # both set: no guessing
        loads_model(SIMULATE, overrides={"simulation.steps": 40, "simulation.duration": "1 ms"})
    with pytest.raises(ModelError, match="simulation: give exactly one of duration"):
        loads_model(SIMULATE, overrides={"simulation.duration": "1 ms", "simulation.steps": 40})


ELEMENTS = '''
[[rods]]
name = "striker"
velocity = "5 m/s"
[rods.elements]
dt = "2 us"
runs = [{ impedance = "10 kN s/m", count = 3 }, { impedance_start = "10 kN s/m", impedance_end = "20 kN s/m", count = 2 }]
[[rods]]
name = "bar"
[[rods.segments]]
shape = "table"
x = ["0 m", "0.2 m", "0.4 m"]
diameter = ["20 mm", "20 mm", "20 mm"]
[simulation]
steps = 10
'''


def test_every_exclusive_pair_of_a_rod_is_replaced():
    c = STEEL.wave_speed                                # the default wave speed of an impedance-level rod
    m = loads_model(ELEMENTS, overrides={"rods.striker.elements.element_length": c * 1e-6})
    assert m.system.rods[0].native.dt == pytest.approx(1e-6) and m.system.rods[0].native.impedance.size == 5
    m = loads_model(ELEMENTS, overrides={"rods.striker.elements.impedance": ["30 kN s/m"] * 4})      # runs go
    assert list(m.system.rods[0].native.impedance) == pytest.approx([3e4] * 4)
    m = loads_model(ELEMENTS, overrides={"rods.striker.elements.runs[0].length": c * 2e-6 * 4})      # count goes
    assert m.system.rods[0].native.impedance.size == 6
    m = loads_model(ELEMENTS, overrides={"rods.striker.elements.runs[1].impedance": "40 kN s/m"})    # start, end go
    assert list(m.system.rods[0].native.impedance) == pytest.approx([1e4] * 3 + [4e4] * 2)
    m = loads_model(ELEMENTS, overrides={"rods.bar.segments[0].area": ["1 cm^2"] * 3})               # diameter goes
    assert m.system.rods[1].segments[0].area(0.1) == pytest.approx(1e-4)
    m = loads_model(ELEMENTS, overrides={"rods.striker.segments": [{"shape": "cylinder", "length": "0.1 m",
                                                                    "diameter": "20 mm"}]})        # elements go
    assert m.system.rods[0].length == pytest.approx(0.1)
    m = loads_model(ELEMENTS, overrides={"rods.bar.elements.impedance": ["20 kN s/m"] * 2,
                                         "rods.bar.elements.dt": "2 us"})                          # segments go
    assert list(m.system.rods[1].native.impedance) == pytest.approx([2e4] * 2)
    _, applied = apply_overrides(tomllib.loads(ELEMENTS), {"rods.bar.elements.impedance": [1, 2]})
    assert applied["rods[1].elements.impedance"].startswith(
        "rods.bar.elements.impedance = [1, 2] (replacing the file's rods[1].segments = [{")


def test_a_design_striker_takes_impedance_bounds_or_a_mass_range_in_place_of_the_file_s():
    spec = design_spec.loads_spec(design_spec.TEMPLATE, overrides={"striker.impedance_min": "2 kN s/m",
                                                                   "striker.impedance_max": "50 kN s/m"})
    limits = spec.kwargs["limits"]
    assert limits.impedance_bounds == (2e3, 5e4) and limits.diameter_bounds is None
    assert design_spec.loads_spec(spec.text).kwargs["limits"].impedance_bounds == (2e3, 5e4)      # as it ran
    ranged = design_spec.loads_spec(design_spec.TEMPLATE.replace("[striker]\n", '[striker]\nmass = "1 kg"\n'),
                                    overrides={"striker.mass_min": "1 kg", "striker.mass_max": "2 kg"})
    assert ranged.kwargs["limits"].mass == (1.0, 2.0)
