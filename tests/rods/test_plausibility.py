"""Issue 14 item 1: bare numbers stay SI, but a geometry outside 1D-rod plausibility (wider than 1 m, wider than
long, a striker heavier than a tonne) is warned about with the likely intended unit, located at the caller's line
in Python and under its key path from model files."""

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
    (lambda: ri.Rod([ri.Cylinder(0.3, 0.5)]), "Rod.length = 0.3 m is smaller than the rod's diameter 0.5 m"),
    (lambda: ri.Rod([ri.Cylinder(0.5, 0.04), ri.Cone(0.2, 0.04, 1.5)]),
     "Rod.segments[1].diameter_end = 1.5 m: did you mean 1.5 mm?"),
    (lambda: ri.Rod([ri.Tube(2.0, 3.0, 0.01)]), "Rod.segments[0].outer_diameter = 3 m: did you mean 3 mm?"),
    (lambda: ri.Rod([ri.LinearAreaTaper(3.0, 2.0, 1e-3)]), "Rod.segments[0].area_start gives a cross-section of 2 m^2"),
    (lambda: ri.System([ri.Rod([ri.Cylinder(6.0, 0.6)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0]),
     "rods[0] is a striker (initial velocity 5 m/s) of 13300.2 kg, heavier than 1 t"),   # 6 pi/4 0.36 7840
])
def test_each_rule_warns(build, expected):
    _, caught = _caught(build)
    assert len(caught) == 1 and str(caught[0].message).startswith(expected), [str(w.message) for w in caught]


@pytest.mark.parametrize("build", [
    lambda: ri.Rod([ri.Cylinder(0.3, 0.02)]),                                   # a striker
    lambda: ri.Rod([ri.Cylinder(0.05, 0.05)]),                                  # as wide as long: still a rod
    lambda: ri.System([ri.Rod([ri.Cylinder(6.0, 0.6)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [0.0, 5.0]),  # heavy anvil at rest
    lambda: ri.Rod.from_impedance([2.46e9, 1.1e9], 1.93e-6),                   # impedance level: taken as given
    lambda: ri.simulate([ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])], [5.0, 0.0],
                        duration=1e-4),
])
def test_plausible_models_are_quiet(build):
    _, caught = _caught(build)
    assert caught == []
