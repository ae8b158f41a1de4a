"""Warnings of the library point at the caller's line, not inside rodimpact (issue 14, item 6).

``warnings.warn`` reports the frame ``stacklevel`` levels up; rodimpact computes it with
:func:`rodimpact._validate.caller_stacklevel` (the first frame outside the package), so that a warning shows the
user's own line -- whatever the depth of the library call that issued it. Each test triggers a warning from this
file through a public entry point and checks the reported file; the last test guards new ``warnings.warn`` calls.
"""

import ast
from pathlib import Path

import pytest

import rodimpact as ri
from rodimpact.inverse import SynthesisWarning, academic_example, impedance_to_shape, synthesize
from rodimpact.io import loads_model
from rodimpact.rods.plausibility import PlausibilityWarning

PACKAGE = Path(ri.__file__).parent
MODEL = (Path(__file__).parent / "data" / "warning-model.toml").read_text(encoding="utf-8")


def _pair():
    return [ri.Rod([ri.Cylinder(0.3, 0.02)]), ri.Rod([ri.Cylinder(1.0, 0.02)])]


def _located_here(record, category=UserWarning) -> None:
    mine = [w for w in record if issubclass(w.category, category)]
    assert mine, "no warning was issued"
    assert all(w.filename == __file__ for w in mine), [(w.filename, w.lineno, str(w.message)[:60]) for w in mine]


def test_rod_construction():
    with pytest.warns(PlausibilityWarning, match="did you mean 20 mm") as record:
        ri.Rod([ri.Cylinder(0.3, 20)])
    _located_here(record, PlausibilityWarning)


def test_model_loading_and_running():
    with pytest.warns(PlausibilityWarning, match=r"rods\[0\].segments\[0\].diameter") as record:
        model = loads_model(MODEL)
    _located_here(record, PlausibilityWarning)
    with pytest.warns(UserWarning, match="dt: rod 0") as record:
        result = model.simulate(progress=False)
    _located_here(record)
    assert result.diagnostics["warnings"] == [str(record[0].message)]     # the record repeats the warning's text


def test_simulate_with_a_dt_that_misrepresents_a_rod():
    with pytest.warns(UserWarning, match="travel time is represented with a") as record:
        ri.simulate(ri.Problem.of(_pair(), [5.0, 0.0], duration=1e-4, dt=7e-6, allow_discretization_error=True))
    _located_here(record)


def test_simulate_batch():
    system = ri.System(_pair(), [0.0, 0.0])
    with pytest.warns(UserWarning, match="travel time represented with more than 1 % error") as record:
        ri.simulate_batch(system, [ri.Rod([ri.Cylinder(0.3, 0.02)])], [5.0], ri.TimeGrid.of(duration=1e-4, dt=7e-6))
    _located_here(record)


def test_synthesis_existence_and_shape():
    problem = academic_example(2)
    with pytest.warns(SynthesisWarning, match="only 78 of 100") as record:
        result = problem.solve()
    _located_here(record, SynthesisWarning)
    with pytest.warns(SynthesisWarning, match="striker elements exist") as record:
        synthesize(problem.target, problem.struck, problem.striker_velocity, problem.n, problem.dt)
    _located_here(record, SynthesisWarning)
    with pytest.warns(UserWarning, match="impractical to make") as record:
        result.shape(max_diameter_ratio=1.01)
    _located_here(record)
    with pytest.warns(UserWarning, match="impractical to make") as record:
        impedance_to_shape([1e4, 121e4], 1e-6)
    _located_here(record)


def _fixed_stacklevels(path: Path) -> list[str]:
    """``warnings.warn`` calls in ``path`` whose stacklevel is not ``caller_stacklevel()``."""
    bad = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "warn"
                and isinstance(node.func.value, ast.Name) and node.func.value.id == "warnings"):
            level = next((k.value for k in node.keywords if k.arg == "stacklevel"), None)
            if not (isinstance(level, ast.Call) and getattr(level.func, "id", "") == "caller_stacklevel"):
                bad.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno}")
    return bad


def test_every_warning_of_the_package_uses_the_callers_stacklevel():
    bad = [hit for path in sorted(PACKAGE.rglob("*.py")) for hit in _fixed_stacklevels(path)]
    assert not bad, f"warnings.warn without stacklevel=caller_stacklevel(): {bad}"

