"""Band-limited rectangular response (inverse/_rectangular.py) against the direct solver, which is how it was
computed before: one run of simulate() driven by a unit force for one window, read by a probe."""

import warnings

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import SynthesisWarning, percussion_drilling_example, transform_force
from rodimpact.inverse._rectangular import rectangular_response
from rodimpact.inverse._toeplitz import solve_lower_toeplitz
from rodimpact.inverse.struck import (at_rest, driven, face_response, linearized, locate,
                                      position_probe, position_quantity)
from rodimpact.inverse.transform import _rectangular

DT = 1e-6
C = ri.STEEL.wave_speed


def _direct(system, loc, dt, steps, quantity, backend="numba"):
    """The old computation: the direct solver driven by [1, 0] windows, quantity at the probe per step."""
    sim = ri.simulate(driven(system, np.array([1.0, 0.0]), dt), steps=steps, dt=dt,
                      outputs=ri.Outputs(probes=[position_probe(loc)]), backend=backend)
    p = sim.probe("synthesis_position")
    return position_quantity(quantity, p.force, p.velocity, float(sim.lattice.impedance[loc.element_left]))


def _chain(far_end):
    rods = [ri.Rod.from_impedance([6e4] * 30 + [1.1e5] * 20, DT),
            ri.Rod.from_impedance(np.linspace(8e4, 1.6e5, 60), DT), ri.Rod.from_impedance([9e4] * 40, DT)]
    return at_rest(ri.System.struck(rods, far_end=far_end))


FAR_ENDS = ["free", "fixed", "nonreflecting", ri.NonReflectingEnd(1.3e5), ri.SpringEnd(4e8),
            ri.SpringEnd(2e8, 3e4)]


@pytest.mark.parametrize("far_end", FAR_ENDS)
@pytest.mark.parametrize("node", [0, 17, 50, 110, 150])      # face, inside, two junctions, far end
def test_equals_the_direct_solver(far_end, node):
    system = _chain(far_end)
    loc = locate(system, node * C * DT, DT)
    assert loc.node == node
    steps = node + 2 * 120 - 1                    # 120 windows: reflections from every junction and the end
    sim = ri.simulate(driven(system, np.array([1.0, 0.0]), DT), steps=steps, dt=DT,
                      outputs=ri.Outputs(probes=[position_probe(loc)]))
    probe = sim.probe("synthesis_position")
    force, velocity, z = rectangular_response(system, node, DT, steps)
    np.testing.assert_array_equal(z, sim.lattice.impedance)
    assert max(np.count_nonzero(probe.force), np.count_nonzero(probe.velocity)) > 50    # not vacuous
    for got, ref in ((force, probe.force), (velocity, probe.velocity)):
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))
    if node:
        ref = _direct(system, loc, DT, steps, "incident")
        np.testing.assert_allclose(_rectangular(system, loc, DT, steps, "incident", "numba"), ref, rtol=0,
                                   atol=1e-13 * np.max(np.abs(ref)))


def test_drill_string_transformation_equals_the_old_computation():
    """Percussion drilling (bit-rock spring, incident wave at the bit-rock interface), n = 300: the impact
    force equals the one from the direct solver's rectangular response to 1e-12."""
    n = 300
    prob = percussion_drilling_example(n)
    o = prob.options
    dt = 0.5 / n / C
    tr = transform_force(prob.target, prob.struck_system, o["position"], n=n, dt=dt, quantity=o["quantity"],
                         rule=o["rule"])
    system = prob.struck_system
    loc = locate(system, o["position"], dt)
    lin, _ = linearized(system)
    steps = loc.node + 2 * n - 1
    g_old = _direct(at_rest(lin), loc, dt, steps, o["quantity"])[loc.node + 2 * np.arange(n)]
    np.testing.assert_allclose(tr.rectangular_response, g_old, rtol=0, atol=1e-13 * np.max(np.abs(g_old)))
    x_old = solve_lower_toeplitz(g_old, tr.target, "auto")
    np.testing.assert_allclose(tr.impact_force, x_old, rtol=1e-12)


def test_numpy_backend_takes_the_direct_solver_and_agrees():
    system = _chain(ri.SpringEnd(4e8))
    loc = locate(system, 110 * C * DT, DT)
    steps = 110 + 2 * 60 - 1
    fast = _rectangular(system, loc, DT, steps, "incident", "numba")
    ref = _direct(system, loc, DT, steps, "incident", backend="numpy")
    np.testing.assert_allclose(fast, ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))


@pytest.mark.parametrize("change", [
    dict(velocities=(0.5, 0.5, 0.5)),
    dict(right=ri.VelocityEnd(1.0)),
    dict(junctions=(ri.Contact(), ri.Bonded())),
    dict(loads=(ri.NodalForce(1, 0.01, -1e3),)),
])
def test_only_passive_chains_at_rest_take_the_band_sweep(change):
    import dataclasses
    system = dataclasses.replace(_chain("free"), **change)
    assert rectangular_response(system, 10, DT, 50) is None
    assert rectangular_response(_chain("free"), 10, DT, 50) is not None


def test_transform_of_a_moving_loaded_system_round_trip():
    """A moving, loaded struck system: its free response still comes from the direct solver, the rectangular
    response (of the same system at rest) from the band sweep; round trip X -> simulate -> transform -> X."""
    rods = [ri.Rod.from_impedance([6e4] * 6 + [1.1e5] * 4, DT), ri.Rod.from_impedance([8e4] * 12, DT)]
    system = ri.System.struck(rods, far_end="fixed", velocity=[0.3, -0.2], loads=[ri.NodalForce(1, 4 * C * DT, -3e4)])
    x = -1e5 * (1 + 0.3 * np.sin(np.arange(20)))
    sim = ri.simulate(driven(system, x, DT), steps=14 + 40, dt=DT,
                      outputs=ri.Outputs(probes=[ri.Probe("p", 1, 4 * C * DT)]))
    y = sim.probe("p").force[14 + 2 * np.arange(20)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SynthesisWarning)
        tr = transform_force(y, system, position=14 * C * DT, dt=DT)
    np.testing.assert_allclose(tr.impact_force, x, rtol=1e-11)


@pytest.mark.parametrize("far_end", FAR_ENDS + [ri.BitRockEnd(3e8, 9e8)])
def test_face_response_equals_the_direct_solver(far_end):
    """Step 1 of the synthesis (face velocity under the window forces) by the band sweep, for 300 windows
    (reflections of every junction and of the far end, the bit-rock end loading and unloading)."""
    system = _chain(far_end)
    x = -1e5 * (1.0 + 0.5 * np.sin(np.arange(300) / 7.0)) * (np.arange(300) < 200)
    fast = face_response(system, x, DT)
    sim = ri.simulate(driven(system, x, DT), steps=600, dt=DT)
    ref = np.asarray(sim.end_velocity["left"])
    assert np.count_nonzero(np.diff(ref[:-1:2])) > 250
    np.testing.assert_allclose(fast.velocity, ref, rtol=0, atol=1e-13 * np.max(np.abs(ref)))
    if isinstance(far_end, ri.BitRockEnd):       # the bit unloads after its peak: the nonlinear branch is used
        rock = sim.end_force["right"]
        assert rock.min() < 1.1 * rock[-1] < 0
