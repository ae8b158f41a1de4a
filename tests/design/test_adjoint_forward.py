"""The forward model of the striker-design gradient is the direct solver: ImpactProblem.forward gives the same
contact force, probe quantity and far-end values as rodimpact.simulate on the system with the striker prepended
(with_striker), bit for bit on the compiled path; bad input is refused with the argument's name."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.inverse.struck import locate, position_probe, position_quantity, with_striker

DT = 1e-6


def reference(struck, z, v, steps, location=None, quantity="force"):
    """simulate() on the complete system; the observed quantity as SynthesisResult.verify computes it."""
    system = with_striker(struck, ri.Rod.from_impedance(z[::-1], dt=DT), v)
    if location is None:
        sim = ri.simulate(system, steps=steps, dt=DT)
        return sim, sim.junction_force[0]
    sim = ri.simulate(system, steps=steps, dt=DT,
                      outputs=ri.Outputs(probes=[position_probe(location, 1)], snapshot_times=[0.0]))
    p = sim.probe("synthesis_position")
    k = sim.lattice.rod_start[1] + location.element_left
    q = position_quantity(quantity, p.force, p.velocity, float(sim.lattice.impedance[k]),
                          float(sim.snapshots.force[k, 0]), float(sim.snapshots.velocity[k, 0]))
    return sim, q


def two_part_struck(rng, right, loads=True):
    """A bonded two-part struck system, moving, pre-stressed, with a nodal force and bearing friction."""
    a = ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=12), dt=DT)
    b = ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=9), dt=DT)
    extra = {}
    if loads:
        extra["loads"] = [ri.NodalForce(0, a.length / 3, lambda t: -2e3 * np.sin(2e5 * t)),
                          ri.Bearings(1, [(0.0, b.length)], friction_coefficient=0.3, normal_load=4e3)]
        extra["initial"] = [ri.InitialState(force=-1e3), None]
    return ri.System.struck([a, b], right, [0.4, 0.4], **extra)


CASES = {
    "bitrock": lambda rng: ri.System.struck(ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=25), dt=DT),
                                            far_end=ri.BitRockEnd(4e9, 2e10)),
    "nonreflecting": lambda rng: ri.System.struck(ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=25), dt=DT),
                                                  far_end="nonreflecting"),
    "nonreflecting_own_impedance": lambda rng: two_part_struck(rng, ri.NonReflectingEnd(impedance=3.3e4)),
    "spring_loads_friction": lambda rng: two_part_struck(rng, ri.SpringEnd(3e9, 20.0)),
    "contact_junction_fixed": lambda rng: ri.System(
        [ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=10), dt=DT),
         ri.Rod.from_impedance(rng.uniform(2e4, 6e4, size=10), dt=DT)], [0.0, 0.0], [ri.Contact()], "free", "fixed"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_forward_is_simulate_bit_for_bit(case):
    rng = np.random.default_rng(len(case))
    struck = CASES[case](rng)
    n = 9
    z = rng.uniform(1e4, 8e4, size=n)
    z[5:] *= 4.0                  # a strong step: separation and re-contact happen in several cases
    v = 6.5
    steps = 700                   # > 256 steps: simulate splits the run into several compiled calls
    fw = ImpactProblem(struck, DT, n, steps).forward(z, v)
    sim, face = reference(struck, z, v, steps)
    np.testing.assert_array_equal(fw.face_force, face)
    np.testing.assert_array_equal(fw.observed, face)
    np.testing.assert_array_equal(fw.end_force, sim.end_force["right"])
    np.testing.assert_array_equal(fw.end_velocity, sim.end_velocity["right"])
    np.testing.assert_array_equal(fw.contact, sim.junction_contact[0])
    assert fw.striker_mass == pytest.approx(DT * z.sum(), rel=1e-15)
    assert np.any(fw.face_force < 0)


@pytest.mark.parametrize("quantity", ["force", "incident"])
@pytest.mark.parametrize("fraction", [0.0, 0.1, 0.4, 12 / 21, 0.8, 1.0])   # face, nodal force, plain node,
def test_observed_quantity_at_a_position_is_the_probe_of_simulate(quantity, fraction):   # joint, bearing, far end
    rng = np.random.default_rng(7)
    struck = two_part_struck(rng, ri.BitRockEnd(4e9, 8e9))
    loc = locate(struck, fraction * sum(r.length for r in struck.rods), DT)
    n = 7
    z = rng.uniform(1e4, 8e4, size=n)
    fw = ImpactProblem(struck, DT, n, 300, location=loc, quantity=quantity).forward(z, 4.0)
    sim, q = reference(struck, z, 4.0, 300, loc, quantity)
    np.testing.assert_array_equal(fw.observed, q)
    np.testing.assert_array_equal(fw.face_force, sim.junction_force[0])
    assert np.max(np.abs(q)) > 0


def test_numpy_path_gives_the_same_forward_run():
    rng = np.random.default_rng(3)
    struck = two_part_struck(rng, ri.BitRockEnd(4e9, 2e10))
    loc = locate(struck, 0.05, DT)
    z = rng.uniform(1e4, 8e4, size=8)
    runs = [ImpactProblem(struck, DT, 8, 400, location=loc, quantity="incident", backend=b).forward(z, 5.0)
            for b in ("numba", "numpy")]
    for name in ("face_force", "observed", "end_force", "end_velocity"):
        a, b = getattr(runs[0], name), getattr(runs[1], name)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * np.max(np.abs(a)))
    np.testing.assert_array_equal(runs[0].contact, runs[1].contact)


def test_repeated_calls_do_not_share_state():
    rng = np.random.default_rng(5)
    struck = CASES["bitrock"](rng)
    p = ImpactProblem(struck, DT, 6, 200)
    z = rng.uniform(1e4, 8e4, size=6)
    first = p.forward(z, 3.0)
    p.forward(2.0 * z, 9.0)
    again = p.forward(z, 3.0)
    np.testing.assert_array_equal(first.face_force, again.face_force)
    np.testing.assert_array_equal(first.end_velocity, again.end_velocity)


# ---------------------------------------------------------------------------------------------- bad input
@pytest.fixture(scope="module")
def problem():
    struck = ri.System.struck(ri.Rod.from_impedance(np.full(10, 3e4), dt=DT), far_end="nonreflecting")
    return ImpactProblem(struck, DT, 4, 50)


@pytest.mark.parametrize("impedance, velocity, match", [
    (np.ones(3) * 1e4, 5.0, "impedance: need one value per striker element"),
    (np.ones((4, 1)) * 1e4, 5.0, "impedance"),
    ([1e4, -1e4, 1e4, 1e4], 5.0, "impedance: every entry must be > 0"),
    ([1e4, 0.0, 1e4, 1e4], 5.0, "impedance: every entry must be > 0"),
    ([1e4, np.nan, 1e4, 1e4], 5.0, "impedance: must be finite"),
    ([1e4, np.inf, 1e4, 1e4], 5.0, "impedance: must be finite"),
    ([1e4] * 4, np.nan, "velocity: must be finite"),
    ([1e4] * 4, np.inf, "velocity: must be finite"),
])
def test_bad_striker_is_refused(problem, impedance, velocity, match):
    with pytest.raises(ValueError, match=match):
        problem.forward(impedance, velocity)


@pytest.mark.parametrize("seed", ["face_force", "observed", "end_force", "end_velocity"])
def test_seed_of_the_wrong_length_is_refused(problem, seed):
    fw = problem.forward([1e4] * 4, 5.0)
    with pytest.raises(ValueError, match=f"{seed}: the seed needs one value per step, shape \\(50,\\)"):
        problem.gradient(fw, **{seed: np.ones(49)})
    with pytest.raises(ValueError, match=f"{seed}: the seed must be finite"):
        problem.gradient(fw, **{seed: np.full(50, np.nan)})


def test_forward_of_another_problem_is_refused(problem):
    other = ImpactProblem(problem.struck, DT, 4, 50)
    with pytest.raises(ValueError, match="fw: must be the result of forward"):
        problem.gradient(other.forward([1e4] * 4, 5.0), face_force=np.ones(50))


@pytest.mark.parametrize("kw, match", [
    (dict(n=0), "n: must be an integer"), (dict(steps=2.5), "steps: must be an integer"),
    (dict(quantity="strain"), "quantity: must be one of"), (dict(backend="cuda"), "backend"),
    (dict(checkpoint_every=0), "checkpoint_every"), (dict(dt=-1.0), "dt: must be > 0"),
])
def test_bad_problem_is_refused(problem, kw, match):
    args = dict(struck=problem.struck, dt=DT, n=4, steps=50) | kw
    with pytest.raises(ValueError, match=match):
        ImpactProblem(args.pop("struck"), args.pop("dt"), args.pop("n"), args.pop("steps"), **args)
