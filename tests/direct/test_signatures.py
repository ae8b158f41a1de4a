"""Small solver signatures (issue 21): each physical fact has one home, so the public solver functions take the
object that holds it and a few run options. A keyword whose value moved into an object is refused with a message
that says where it went, not Python's bare "unexpected keyword argument"."""

import inspect

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct import batch as batch_module
from rodimpact.direct import simulate as simulate_module

DT = 1e-6

#: most parameters each public solver function may take (the catch of moved keywords adds none)
LIMITS = {"simulate": 9, "simulate_batch": 9, "synthesize": 12, "transform_force": 9, "design": 9}


def bars():
    return [ri.Rod.from_impedance([51e3] * 50 + [28.7e3] * 50, dt=DT), ri.Rod.from_impedance([51e3] * 400, dt=DT)]


@pytest.mark.parametrize("name, limit", sorted(LIMITS.items()))
def test_public_solvers_take_few_parameters(name, limit):
    params = inspect.signature(getattr(ri, name)).parameters
    assert len(params) <= limit, f"{name} takes {len(params)} parameters ({', '.join(params)}), at most {limit}"
    assert not any(p.kind == p.VAR_KEYWORD for p in params.values()), f"{name} takes **keywords"


@pytest.mark.parametrize("module, name", [(simulate_module, "simulate"), (batch_module, "simulate_batch")])
def test_no_parameter_is_a_field_of_an_object_the_function_receives(module, name):
    """A parameter that is also a field of System, Outputs, BatchOutputs or Problem would be a second home."""
    params = set(inspect.signature(getattr(module, name)).parameters)
    fields = {"rods", "left", "right", "junctions", "loads", "initial", "probes", "snapshot_times", "snapshot_every",
              "energy_every", "record_every", "contact_force", "final_state", "max_phases", "elements", "resolution",
              "allow_discretization_error"}
    assert not params & fields
    assert set(getattr(module, "MOVED")) <= fields | {"duration", "dt", "steps"}


def test_the_short_notebook_forms_run():
    striker, bar = bars()
    free = ri.simulate([striker, bar], [5.0, 0.0], duration=400e-6)
    system = ri.simulate(ri.System([striker, bar], [5.0, 0.0], right="nonreflecting"), duration=400e-6)
    problem = ri.simulate(ri.Problem.of([striker, bar], [5.0, 0.0], duration=400e-6, right="nonreflecting"))
    assert free.n_steps == system.n_steps == 400
    np.testing.assert_array_equal(system.contact_force, problem.contact_force)
    assert system.contact_force[0] == pytest.approx(-28.7e3 * 51e3 / (28.7e3 + 51e3) * 5.0, rel=1e-12)


@pytest.mark.parametrize("keyword, value, where", [
    ("right", "nonreflecting", r"right: give the ends in the System: ri.System\(rods, velocities, right=...\)"),
    ("left", "fixed", r"left: give the ends in the System: ri.System\(rods, velocities, left=...\)"),
    ("junctions", [ri.Bonded()], r"junctions: give the junctions in the System: ri.System\(rods, velocities, junctions="),
    ("loads", [], r"loads: give the loads in the System"),
    ("initial", None, r"initial: give the initial state in the System"),
    ("elements", 40, r"elements: give the time-step rule to the Problem: ri.simulate\(ri.Problem.of\(rods, "
                     r"velocities, duration=..., elements=...\)\)"),
    ("resolution", 1e-3, r"resolution: give the time-step rule to the Problem"),
    ("probes", [], r"probes: give the outputs as one Outputs: .*outputs=ri.Outputs\(probes=...\)"),
    ("snapshot_times", [0.0], r"snapshot_times: give the outputs as one Outputs"),
    ("snapshot_every", 10, r"snapshot_every: give the outputs as one Outputs"),
    ("energy_every", 10, r"energy_every: give the outputs as one Outputs"),
    ("record_every", 2, r"record_every: give the outputs as one Outputs"),
    ("allow_discretization_error", True, r"allow_discretization_error: it is part of the Problem now: "
                                         r"ri.simulate\(ri.Problem.of\(.*allow_discretization_error=True\)\)"),
    ("rods", None, r"rods: the rods \(or a System or a Problem\) are the first argument"),
])
def test_a_moved_simulate_keyword_says_where_it_went(keyword, value, where):
    with pytest.raises(TypeError, match=where) as info:
        ri.simulate(bars(), [5.0, 0.0], duration=400e-6, **{keyword: value})
    assert "unexpected keyword" not in str(info.value)
    with pytest.raises(TypeError, match=where):          # whatever the first argument
        ri.simulate(ri.Problem.of(bars(), [5.0, 0.0], steps=10), **{keyword: value})


def test_old_positional_time_arguments_are_refused_by_name():
    with pytest.raises(TypeError, match=r"simulate\(\) takes at most 2 positional arguments, got 3; duration: give "
                                        r"it by name \(duration=...\)"):
        ri.simulate(bars(), [5.0, 0.0], 400e-6)
    system = ri.System(bars(), [0.0, 0.0])
    zs = np.full((2, 50), 51e3)
    with pytest.raises(TypeError, match=r"takes at most 4 positional arguments, got 5; dt: give the time as one "
                                        r"TimeGrid"):
        ri.simulate_batch(system, zs, 5.0, 400e-6, DT)
    with pytest.raises(TypeError, match=r"time: must be a TimeGrid, e.g. ri.TimeGrid\(dt, steps\)"):
        ri.simulate_batch(system, zs, 5.0, 400e-6)


@pytest.mark.parametrize("keyword, value, where", [
    ("duration", 400e-6, r"duration: give the time as one TimeGrid: ri.simulate_batch\(system, strikers, velocities, "
                         r"ri.TimeGrid.of\(duration=..., dt=...\)\)"),
    ("dt", DT, r"dt: give the time as one TimeGrid"),
    ("steps", 400, r"steps: give the time as one TimeGrid"),
    ("record_every", 2, r"record_every: give the recording options as one BatchOutputs: .*"
                        r"outputs=ri.BatchOutputs\(record_every=...\)"),
    ("contact_force", False, r"contact_force: give the recording options as one BatchOutputs"),
    ("final_state", False, r"final_state: give the recording options as one BatchOutputs"),
    ("max_phases", 4, r"max_phases: give the recording options as one BatchOutputs"),
])
def test_a_moved_simulate_batch_keyword_says_where_it_went(keyword, value, where):
    system = ri.System(bars(), [0.0, 0.0])
    with pytest.raises(TypeError, match=where) as info:
        ri.simulate_batch(system, np.full((2, 50), 51e3), 5.0, **{keyword: value})
    assert "unexpected keyword" not in str(info.value)


def test_batch_outputs_are_frozen_and_validated():
    out = ri.BatchOutputs(record_every=np.int64(3), contact_force=np.bool_(False), max_phases=np.int32(4))
    assert (out.record_every, out.contact_force, out.final_state, out.max_phases) == (3, False, True, 4)
    assert type(out.record_every) is int and type(out.contact_force) is bool and type(out.max_phases) is int
    with pytest.raises(AttributeError):
        out.max_phases = 5
    for bad, error, match in ((dict(record_every=0), ValueError, "record_every: must be an integer"),
                              (dict(contact_force="yes"), TypeError, "contact_force: must be True or False"),
                              (dict(final_state=None), TypeError, "final_state: must be True or False"),
                              (dict(max_phases=True), ValueError, "max_phases: must be an integer >= 1")):
        with pytest.raises(error, match=match):
            ri.BatchOutputs(**bad)


def test_a_batch_with_its_time_grid_equals_simulate():
    """The time as one TimeGrid (TimeGrid.of needs no system): the run simulate does with the same grid."""
    striker, bar = bars()
    system = ri.System([striker, bar], [0.0, 0.0], right="nonreflecting")
    time = ri.TimeGrid.of(duration=300.5e-6, dt=DT)
    assert time == ri.TimeGrid(DT, 301)
    res = ri.simulate_batch(system, striker, 5.0, time, outputs=ri.BatchOutputs(record_every=3))
    alone = ri.simulate(ri.System([striker, bar], [5.0, 0.0], right="nonreflecting"), duration=300.5e-6, dt=DT,
                        outputs=ri.Outputs(record_every=3))
    np.testing.assert_array_equal(res.contact_force[0], alone.junction_force[0])
    assert res.record_every == 3 and res.n_steps == 301


def test_a_sweep_point_dict_is_read_by_one_rule():
    """``build`` of a sweep may still return the keywords simulate took before: system parts and the time rule go
    to Problem.of, the output fields make one Outputs, backend / progress / max_element_updates go to simulate."""
    from rodimpact.direct._sweep_keywords import problem_of

    probe = ri.Probe("g", 1, 0.2)
    problem, run = problem_of(dict(rods=bars(), velocities=[5.0, 0.0], steps=300, elements=(1, 400),
                                   right="nonreflecting", probes=[probe], energy_every=7,
                                   allow_discretization_error=True, backend="numpy", progress=False))
    assert problem.time == ri.TimeGrid(DT, 300) and isinstance(problem.system.right, ri.NonReflectingEnd)
    assert problem.outputs == ri.Outputs(probes=[probe], energy_every=7) and problem.allow_discretization_error
    assert run == {"backend": "numpy", "progress": False}
    with pytest.raises(TypeError, match=r"build: 'rigth' is not a keyword of a sweep point; a point's dict takes "
                                        r"rods, velocities, left, right"):
        problem_of(dict(rods=bars(), velocities=[5.0, 0.0], steps=3, rigth="fixed"))


def test_a_sweep_takes_dicts_and_problems_alike():
    def as_dict(velocity):
        return dict(rods=bars(), velocities=[velocity, 0.0], steps=300, right="nonreflecting",
                    probes=[ri.Probe("g", 1, 0.2)])

    def as_problem(velocity):
        return ri.Problem.of(bars(), [velocity, 0.0], steps=300, right="nonreflecting",
                             outputs=ri.Outputs(probes=[ri.Probe("g", 1, 0.2)]))

    metrics = {"gauge": lambda r: r.probe("g").force.min()}
    a = ri.sweep(as_dict, {"velocity": [3.0, 5.0]}, metrics, workers=1)
    b = ri.sweep(as_problem, {"velocity": [3.0, 5.0]}, metrics, workers=1)
    np.testing.assert_array_equal(a["gauge"].values, b["gauge"].values)
    assert a.attrs["runner"] == b.attrs["runner"] == "simulate"


def _design_fields():
    """Fields of the objects design receives: the struck System, the objectives, StrikerLimits, SearchOptions."""
    import dataclasses

    classes = (ri.System, ri.MatchObjective, ri.EfficiencyObjective, ri.StrikerLimits, ri.SearchOptions)
    return {f.name for cls in classes for f in dataclasses.fields(cls)}


def test_no_design_parameter_is_a_field_of_an_object_it_receives():
    params = set(inspect.signature(ri.design).parameters)
    assert not params & (_design_fields() - {"target"})       # MatchObjective.target is design's first argument
    assert set(ri.design.moved_keywords) <= _design_fields() | {"far_end", "struck_velocity", "objective"}


def test_the_short_notebook_form_of_design_runs():
    """A target, the struck rod, the velocity, n and dt: matched at the impact face, default limits and search."""
    bar = ri.Rod.from_impedance([51e3] * 20, DT)
    short = ri.design(-np.linspace(20e3, 40e3, 4), bar, striker_velocity=6.0, n=4, dt=DT,
                      search=ri.SearchOptions(max_iterations=2, starts=1, hops=0))
    assert short.objective == "match" and short.n_elements == 4 and short.striker_velocity == 6.0
    assert short.struck.right == ri.FreeEnd() and short.material == ri.STEEL


@pytest.mark.parametrize("keyword, value, where", [
    ("far_end", "nonreflecting", r"far_end: give the struck system as one System: ri.System.struck\(rods, far_end="),
    ("struck_velocity", 1.0, r"struck_velocity: give the struck system as one System: ri.System.struck\(rods, "
                             r"velocity=...\)"),
    ("junctions", [], r"junctions: give the struck system as one System"),
    ("loads", (), r"loads: give the struck system as one System"),
    ("initial", None, r"initial: give the struck system as one System"),
    ("objective", "efficiency", r"objective: give the objective as the first argument: "
                                r"ri.design\(ri.EfficiencyObjective\(\), struck, ...\) or "
                                r"ri.design\(ri.MatchObjective\(target, position=...\), struck, ...\)"),
    ("position", 0.1, r"position: give the objective as the first argument: "
                      r"ri.design\(ri.MatchObjective\(target, position=...\), struck, ...\)"),
    ("quantity", "incident", r"quantity: .*ri.MatchObjective\(target, quantity=...\)"),
    ("rule", "start", r"rule: .*ri.MatchObjective\(target, rule=...\)"),
    ("weights", None, r"weights: .*ri.MatchObjective\(target, weights=...\)"),
    ("reloading", False, r"reloading: give the objective as the first argument: "
                         r"ri.design\(ri.EfficiencyObjective\(reloading=...\), struck, ...\)"),
    ("steps", 100, r"steps: .*ri.EfficiencyObjective\(steps=...\)"),
    ("duration", 1e-4, r"duration: .*ri.EfficiencyObjective\(duration=...\)"),
    *[(key, None, rf"{key}: give the striker's limits as one StrikerLimits: ri.design\(target, struck, ..., "
                  rf"limits=ri.StrikerLimits\({key}=...\)\)")
      for key in ("impedance_bounds", "diameter_bounds", "material", "bore", "mass", "velocity_bounds", "max_steps",
                  "smoothness")],
    *[(key, None, rf"{key}: give the search options as one SearchOptions: ri.design\(target, struck, ..., "
                  rf"search=ri.SearchOptions\({key}=...\)\)")
      for key in ("starts", "max_iterations", "tolerance", "improvement", "pool", "hops", "warm_start")],
])
def test_a_moved_design_keyword_says_where_it_went(keyword, value, where):
    bar = ri.Rod.from_impedance([51e3] * 20, DT)
    with pytest.raises(TypeError, match=where) as info:
        ri.design(-np.linspace(20e3, 40e3, 4), bar, 6.0, n=4, dt=DT, **{keyword: value})
    assert "unexpected keyword" not in str(info.value)
    with pytest.raises(TypeError, match=where):        # the old efficiency form, too
        ri.design(None, struck=bar, striker_velocity=6.0, n=4, dt=DT, **{keyword: value})
