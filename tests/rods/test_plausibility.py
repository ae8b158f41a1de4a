"""Issue 14 item 1: bare numbers stay SI, but a geometry that is most likely a unit slip is warned about with the
likely intended unit, located at the caller's line in Python and under its key path from model files.

Issue 20 item 7: the rules sit beyond the largest real parts (wider than 12 m, a disc wider than 1 m and ten times
wider than long, a striker above 1000 t), so that SHPB specimens, pile cushions and pile rams are quiet, and a
value a model file writes with its unit is never the subject of a warning or a suggested fix."""

import warnings

import pytest

import rodimpact as ri
from rodimpact.rods.plausibility import PlausibilityWarning

REPRODUCER = """
[[rods]]
name = "striker"
velocity = "5 m/s"
segments = [{ shape = "cylinder", length = 0.3, diameter = 20 }]

[[rods]]
velocity = 0
segments = [{ shape = "cylinder", length = "1 m", diameter = "20 mm" }]

[simulation]
duration = "1 ms"
"""


def _caught(build):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = build()
    return out, [w for w in caught if issubclass(w.category, PlausibilityWarning)]


def test_the_issue_reproducer_warns_with_the_key_path_and_the_intended_unit():
    model, caught = _caught(lambda: ri.loads_model(REPRODUCER))
    assert len(caught) == 1      # one slip, one warning (the 7e5 kg mass follows from it and is not repeated)
    assert str(caught[0].message).startswith(
        "rods[0].segments[0].diameter = 20 m: did you mean 20 mm? bare numbers are SI (m)")
    assert caught[0].filename == __file__        # located at the caller (this test), not inside rodimpact
    assert model.system.rods[0].segments[0].diameter == 20.0          # the number itself stays SI


def test_python_warnings_point_at_the_callers_line():
    _, caught = _caught(lambda: ri.Rod([ri.Cylinder(0.3, 20)]))
    assert [str(w.message).split(":")[0] for w in caught] == ["Rod.segments[0].diameter = 20 m"]
    assert "did you mean 20 mm?" in str(caught[0].message)
    assert caught[0].filename == __file__


@pytest.mark.parametrize("build, expected", [
    (lambda: ri.Rod([ri.Cylinder(0.5, 6.0)]),                   # a 6 mm mini-Kolsky bar written as 6: a disc
     "Rod.segments[0].diameter = 6 m: did you mean 6 mm? bare numbers are SI (m); the rod would be a disc 12 times"),
    (lambda: ri.Rod([ri.Cylinder(0.5, 0.04), ri.Cone(0.2, 0.04, 15.0)]),
     "Rod.segments[1].diameter_end = 15 m: did you mean 15 mm?"),
    (lambda: ri.Rod([ri.Tube(0.2, 3.0, 0.01)]), "Rod.segments[0].outer_diameter = 3 m: did you mean 3 mm?"),
    (lambda: ri.Rod([ri.LinearAreaTaper(3.0, 200.0, 1e-3)]),
     "Rod.segments[0].area_start gives a cross-section of 200 m^2"),
    # every dimension of a 100 x 10 mm striker in mm: 100 m long, 10 m wide, 61,575 t (100 pi/4 100 7840 kg)
    (lambda: ri.System([ri.Rod([ri.Cylinder(100.0, 10.0)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0]),
     "rods[0] is a striker (initial velocity 5 m/s) of 6.15752e+07 kg, heavier than 1000 t"),
])
def test_each_rule_warns(build, expected):
    _, caught = _caught(build)
    assert len(caught) == 1 and str(caught[0].message).startswith(expected), [str(w.message) for w in caught]


@pytest.mark.parametrize("build", [
    lambda: ri.Rod([ri.Cylinder(0.3, 0.02)]),                                   # a striker
    lambda: ri.Rod([ri.Cylinder(0.05, 0.05)]),                                  # as wide as long: still a rod
    lambda: ri.System([ri.Rod([ri.Cylinder(6.0, 0.6)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [0.0, 5.0]),  # heavy anvil at rest
    lambda: ri.Rod.from_impedance([2.46e9, 1.1e9], 1.93e-6),                   # impedance level: taken as given
    lambda: ri.Rod([ri.Cylinder(0.003204, 0.006)]),                             # SHPB specimen, 3.204 x 6 mm
    lambda: ri.Rod([ri.Cylinder(0.1, 0.45)]),                                   # pile cushion on a 0.4 m pile
    lambda: ri.Rod([ri.Cylinder(0.2, 1.4)]),                                    # cushion of a 1.4 m cylinder pile
    lambda: ri.Rod([ri.Cylinder(1.0, 3.0)]),                                    # anvil of a monopile hammer
    lambda: ri.Rod([ri.Tube(80.0, 11.0, 10.8)]),                                # an 11 m monopile
    lambda: ri.System([ri.Rod([ri.Cylinder(2.0, 0.6)]), ri.Rod([ri.Cylinder(20.0, 0.4)])], [4.0, 0.0]),  # 4.4 t ram
    lambda: ri.System([ri.Rod([ri.Cylinder(6.0, 2.0)]), ri.Rod([ri.Tube(80.0, 8.0, 7.8)])], [4.0, 0.0]),  # 148 t ram
    lambda: ri.simulate([ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0],
                        duration=1e-4),
])
def test_plausible_models_are_quiet(build):
    _, caught = _caught(build)
    assert caught == []


SPECIMEN = """
[[rods]]
name = "incident"
velocity = "10 m/s"
segments = [{ shape = "cylinder", length = "1.5 m", diameter = "12.7 mm" }]

[[rods]]
name = "specimen"
velocity = 0
segments = [{ shape = "cylinder", length = LENGTH, diameter = DIAMETER }]

[simulation]
duration = "0.1 ms"
"""


@pytest.mark.parametrize("length, diameter", [('"3.204 mm"', '"6 mm"'), ("0.003204", "0.006"),
                                              ('"3.204 mm"', "0.006"), ('"3.204 mm"', '"20 m"')])
def test_a_specimen_in_a_model_file_is_quiet(length, diameter):
    # issue 20 item 7: "rods[1].length = 0.003204 m is smaller than the rod's diameter ...: "0.003204 mm" must be
    # written with its unit" -- though the file wrote "3.204 mm"; a value written with its unit ("20 m") cannot
    # have slipped either
    _, caught = _caught(lambda: ri.loads_model(SPECIMEN.replace("LENGTH", length).replace("DIAMETER", diameter)))
    assert caught == [], [str(w.message) for w in caught]


def test_a_bare_slip_next_to_a_value_with_its_unit_names_only_the_bare_one():
    text = SPECIMEN.replace("LENGTH", '"3.204 mm"').replace("DIAMETER", "6")
    _, caught = _caught(lambda: ri.loads_model(text))
    assert len(caught) == 1
    message = str(caught[0].message)
    assert message.startswith("rods[1].segments[0].diameter = 6 m: did you mean 6 mm?")
    # the one fix suggested is for the bare diameter; the length as written ("3.204 mm") is left alone
    assert message.count("did you mean") == 1 and "0.003204 mm" not in message


def test_a_striker_written_with_units_is_not_warned_about_its_mass():
    text = """
[[rods]]
velocity = "5 m/s"
segments = [{ shape = "cylinder", length = "100 m", diameter = "10 m" }]

[[rods]]
velocity = 0
segments = [{ shape = "cylinder", length = "1 m", diameter = "20 mm" }]

[simulation]
duration = "0.1 ms"
"""
    _, caught = _caught(lambda: ri.loads_model(text))
    assert caught == []
    _, caught = _caught(lambda: ri.loads_model(text.replace('length = "100 m"', "length = 100")))
    assert [str(w.message).split(" is a striker")[0] for w in caught] == ["rods[0]"]


def test_python_values_given_with_their_unit_are_not_warned_about():
    # Python accepts unit strings too: "20 m" was meant, so "did you mean 20 mm?" would change what was written
    _, caught = _caught(lambda: ri.Rod([ri.Cylinder(0.3, "20 m")]))
    assert caught == []
    _, caught = _caught(lambda: ri.Rod([ri.Cylinder("0.3 m", 20)]))          # the bare one is still named
    assert [str(w.message).split(":")[0] for w in caught] == ["Rod.segments[0].diameter = 20 m"]


def test_python_striker_given_with_units_is_not_warned_about_its_mass():
    bar = ri.Rod([ri.Cylinder(1.0, 0.02)])
    _, caught = _caught(lambda: ri.System([ri.Rod([ri.Cylinder("100 m", "10 m")]), bar], [5.0, 0.0]))
    assert caught == []
    _, caught = _caught(lambda: ri.System([ri.Rod([ri.Cylinder(100.0, "10 m")]), bar], [5.0, 0.0]))
    assert [str(w.message).split(" is a striker")[0] for w in caught] == ["rods[0]"]
