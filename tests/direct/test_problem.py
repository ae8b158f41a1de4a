"""The problem object (issue 21): one value holds the system, the time grid and the outputs; it is validated when
made, compiled by one public step, and solved by simulate() exactly as the short forms are."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct.problem import Problem, TimeGrid

DT = 1e-6


def rods():
    return [ri.Rod.from_impedance([51e3] * 50 + [28.7e3] * 50, dt=DT), ri.Rod.from_impedance([51e3] * 400, dt=DT)]


def test_the_problem_and_the_system_form_give_the_same_run_bit_for_bit():
    probe = ri.Probe("g", 1, 0.2)
    a = ri.simulate(ri.System(rods(), [5.0, 0.0], right="nonreflecting"), duration=400e-6,
                    outputs=ri.Outputs(probes=[probe]))
    p = Problem.of(rods(), [5.0, 0.0], outputs=ri.Outputs(probes=[probe]), duration=400e-6, right="nonreflecting")
    b = ri.simulate(p)
    np.testing.assert_array_equal(a.contact_force, b.contact_force)
    np.testing.assert_array_equal(a.probe("g").force, b.probe("g").force)
    # the first step: the striker's face element (28.7 kN s/m) meets the bar: F = -Z1 Z2 / (Z1 + Z2) v
    assert b.contact_force[0] == pytest.approx(-28.7e3 * 51e3 / (28.7e3 + 51e3) * 5.0, rel=1e-12)
    assert p.time == TimeGrid(DT, 400) and p.time.duration == pytest.approx(400e-6, rel=1e-15)


def test_a_duration_becomes_whole_steps_covering_it():
    system = ri.System(rods(), [5.0, 0.0])
    assert TimeGrid.of(system, duration=10e-6, dt=DT).steps == 10                 # 10 steps to rounding
    assert TimeGrid.of(system, duration=10.5e-6, dt=DT).steps == 11               # at least the duration
    assert TimeGrid.of(system, steps=7).dt == DT                                   # impedance rods keep their dt
    assert TimeGrid.of(system, steps=7, elements=25).dt == pytest.approx(100 * DT / 25, rel=1e-15)


@pytest.mark.parametrize("make, match", [
    (lambda: TimeGrid(0.0, 10), "dt: must be > 0"),
    (lambda: TimeGrid(DT, 0), "steps: must be an integer >= 1"),
    (lambda: TimeGrid(DT, 2.5), "steps: must be an integer >= 1"),
    (lambda: TimeGrid.of(None, steps=3), "dt: required"),
    (lambda: Problem("bars", TimeGrid(DT, 3)), "system: must be a System"),
    (lambda: Problem(ri.System(rods(), [1.0, 0.0]), (DT, 3)), r"time: must be a TimeGrid"),
    (lambda: Problem(ri.System(rods(), [1.0, 0.0]), TimeGrid(DT, 3), {"probes": []}), "outputs: must be an Outputs"),
    (lambda: Problem(ri.System(rods(), [1.0, 0.0]), TimeGrid(DT, 3), ri.Outputs(probes=[ri.Probe("p", "x", 0.0)])),
     r"probes\[0\].rod: no rod is named 'x'"),
    (lambda: Problem.of(ri.System(rods(), [1.0, 0.0]), [2.0, 0.0], steps=3), "velocities: a System already holds"),
    (lambda: Problem.of(ri.System(rods(), [1.0, 0.0]), steps=3, right="fixed"), "right: a System already holds"),
    (lambda: Problem.of(rods(), steps=3), "velocities: required"),
    (lambda: ri.simulate(Problem.of(rods(), [1.0, 0.0], steps=3), steps=5), "steps: a Problem already holds"),
    (lambda: ri.simulate(Problem.of(rods(), [1.0, 0.0], steps=3), velocities=[1.0, 0.0]),
     "velocities: a Problem already holds"),
    (lambda: ri.simulate(Problem.of(rods(), [1.0, 0.0], steps=3), right="fixed"), "right: give the ends in the System"),
    (lambda: Problem(ri.System(rods(), [1.0, 0.0]), TimeGrid(DT, 3), allow_discretization_error="yes"),
     "allow_discretization_error: must be True or False"),
])
def test_bad_problems_are_refused_when_made_naming_the_part(make, match):
    with pytest.raises((TypeError, ValueError), match=match):
        make()


def test_probes_named_by_rod_are_resolved_once_when_the_problem_is_made():
    bar = ri.Rod.from_impedance([51e3] * 400, dt=DT, name="bar")
    p = Problem.of([rods()[0], bar], [5.0, 0.0], steps=50, outputs=ri.Outputs(probes=[ri.Probe("g", "bar", 0.1)]))
    assert p.outputs.probes == (ri.Probe("g", 1, 0.1),)


def test_compile_gives_a_fresh_initial_state_each_time():
    p = Problem.of(rods(), [5.0, 0.0], steps=20)
    a, b = p.compile(), p.compile()
    a.N[:] = 1.0
    assert not b.N.any() and b.v[0] == 5.0 and b.v[-1] == 0.0
    assert a.lattice is b.lattice is p.lattice            # the lattice is built once per problem
    reflection, touch = a.wave_arrays()
    assert reflection[49] == pytest.approx((28.7e3 - 51e3) / (28.7e3 + 51e3), rel=1e-15)   # thesis eq. 2.40


def test_a_model_file_is_a_problem():
    from rodimpact.io.model import loads_model

    m = loads_model("""
        [[rods]]
        velocity = "5 m/s"
        [rods.elements]
        dt = "1 us"
        impedance = ["51 kN s/m", "51 kN s/m", "28.7 kN s/m"]
        [[rods]]
        [rods.elements]
        dt = "1 us"
        impedance = ["51 kN s/m", "51 kN s/m", "51 kN s/m", "51 kN s/m"]
        [simulation]
        duration = "10.5 us"
        [output]
        snapshot_count = 5
    """.replace("\n        ", "\n"))
    assert m.problem.time == TimeGrid(DT, 11) and m.n_steps == 11
    assert m.problem.outputs.snapshot_every == 2
    np.testing.assert_array_equal(m.simulate().contact_force, ri.simulate(m.problem).contact_force)


def test_compile_on_a_shared_lattice_equals_its_own_and_refuses_another_time_step():
    """Problem.compile(lattice): a lattice built for the same rods and dt gives the same kernel inputs as the
    problem's own; one built at another dt is refused, naming the argument."""
    rod = ri.Rod([ri.Cylinder(1.0, 0.02)])
    first = Problem.of([rod, rod], [5.0, 0.0], steps=50, dt=2e-6)
    second = Problem.of(ri.System([rod, rod], [5.0, 0.0], right="fixed"), steps=50, dt=2e-6)
    own, shared = second.compile(), second.compile(first.lattice)
    assert shared.lattice is first.lattice
    assert np.array_equal(own.N, shared.N) and np.array_equal(own.v, shared.v)
    assert np.array_equal(own.arrays["end_code"], shared.arrays["end_code"])
    other = Problem.of([rod, rod], [5.0, 0.0], steps=50, dt=1e-6)
    with pytest.raises(ValueError, match=r"^lattice: built for other rods or another time step"):
        second.compile(other.lattice)
