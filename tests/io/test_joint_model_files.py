"""The spring-and-dashpot joint in model files (issue 21): read, written back exactly, run bit for bit, and
refused with key paths when impossible. Its keys come from the class's field declarations alone."""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.model import ModelError, dump_model, loads_model

MODEL = """
[[rods]]
name = "striker"
velocity = "5 m/s"
[[rods.segments]]
shape = "cylinder"
length = "0.2 m"
diameter = "40 mm"

[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "1.0 m"
diameter = "40 mm"

[[junctions]]
type = "spring-dashpot"
stiffness = "250 MN/m"
damping = "2 kN s/m"
compression_only = true

[ends]
right = "nonreflecting"

[simulation]
duration = "0.3 ms"
dt = "1 us"
"""


def test_the_joint_is_read_with_units() -> None:
    model = loads_model(MODEL)
    joint = model.system.junctions[0]
    assert isinstance(joint, ri.SpringDashpot)
    assert (joint.stiffness, joint.damping, joint.compression_only) == (250e6, 2e3, True)


def test_written_back_exactly_and_run_bit_for_bit() -> None:
    model = loads_model(MODEL)
    text = dump_model(model)
    again = loads_model(text)
    assert again.system.junctions == model.system.junctions
    assert dump_model(again) == text
    a, b = model.simulate(), again.simulate()
    assert np.array_equal(a.contact_force, b.contact_force)
    assert a.contact_force.min() < -10e3                 # the joint does carry the blow
    assert a.energy.balance_error < 1e-12


@pytest.mark.parametrize("replace, message", [
    ('stiffness = "250 MN/m"', r"junctions\[0\]\.stiffness: must be >= 0, got -250 MN/m"),
    ('damping = "2 kN s/m"', r"junctions\[0\]\.damping: expected a damping .* \(a force\)"),
    ("compression_only = true", r"junctions\[0\]\.compression_only: expected true or false"),
    ('type = "spring-dashpot"', r"junctions\[0\]\.type: unknown type 'spring-dashpt' \(did you mean "
                                r"'spring-dashpot'\?\)"),
])
def test_impossible_joints_are_refused_by_key_path(replace: str, message: str) -> None:
    bad = {'stiffness = "250 MN/m"': 'stiffness = "-250 MN/m"', 'damping = "2 kN s/m"': 'damping = "2 kN"',
           "compression_only = true": 'compression_only = "yes"',
           'type = "spring-dashpot"': 'type = "spring-dashpt"'}[replace]
    with pytest.raises(ModelError, match=message):
        loads_model(MODEL.replace(replace, bad))


SPECIMEN = MODEL.replace('''[[junctions]]
type = "spring-dashpot"
stiffness = "250 MN/m"
damping = "2 kN s/m"
compression_only = true''', '''[[junctions]]
type = "specimen"
law = { type = "johnson-cook", youngs_modulus = "117 GPa", a = "90 MPa", b = "292 MPa", n = 0.31, c = 0.025 }
diameter = "30 mm"
length = "5 mm"''')


def test_a_specimen_with_its_law_round_trips() -> None:
    model = loads_model(SPECIMEN)
    joint = model.system.junctions[0]
    assert isinstance(joint, ri.Specimen) and isinstance(joint.law, ri.JohnsonCook)
    assert (joint.law.a, joint.law.b, joint.diameter, joint.length) == (90e6, 292e6, 0.03, 0.005)
    again = loads_model(dump_model(model))
    assert again.system.junctions == model.system.junctions
    assert np.array_equal(model.simulate().contact_force, again.simulate().contact_force)


@pytest.mark.parametrize("replace, bad, message", [
    ('b = "292 MPa"', 'b = "-292 MPa"', r"junctions\[0\]\.law\.b: must be >= 0, got -292 MPa"),
    ('type = "johnson-cook"', 'type = "johnson-cok"', r"junctions\[0\]\.law\.type: unknown type 'johnson-cok' "
                                                       r"\(did you mean 'johnson-cook'\?\)"),
    ('length = "5 mm"', 'length = "-5 mm"', r"junctions\[0\]\.length: must be > 0"),
    ('diameter = "30 mm"', 'diameter = "60 mm"', r"junctions\[0\]\.diameter: the specimen \(60 mm.* wider"),
])
def test_an_impossible_specimen_is_refused_by_key_path(replace: str, bad: str, message: str) -> None:
    with pytest.raises(ModelError, match=message):
        loads_model(SPECIMEN.replace(replace, bad))


def test_the_specimen_outcome_is_saved_and_loaded(tmp_path) -> None:
    result = loads_model(SPECIMEN).simulate()
    assert result.joints and result.joints[0].plastic_work > 0.0
    ri.save(result, tmp_path / "run")
    again = ri.load(tmp_path / "run")
    assert again.joints == result.joints
    assert np.array_equal(again.energy.work_joints, result.energy.work_joints)
