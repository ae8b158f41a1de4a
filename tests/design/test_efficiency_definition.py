"""The efficiency objective's two definitions (issue 20, item 3): Lundberg's classical first-pass efficiency
(only the striker's incident wave loads the rock) and the efficiency with the reloading of the rock by reflected
waves (the default)."""

import numpy as np
import pytest

import rodimpact as ri


def eta_closed_form(x):
    """Rectangular incident wave of duration T into a loading-only rock spring k under a rod of impedance Z:
    eta = 2 (1 - exp(-x))^2 / x, x = k T / Z (docs/design.md)."""
    return 2.0 * (1.0 - np.exp(-x)) ** 2 / x


def _uniform_piston(x, reloading, n=100, z=50e3, dt=1e-6, unloading=1e6, piston=1.0):
    """A uniform piston of ``piston`` times the rod's impedance z (bounds lower = upper force it; x = k T / z with
    T = 2 n dt), n elements, on a rod of 2 n
    elements ending on a rock of loading stiffness k and unloading stiffness ``unloading`` k (1e6: loading
    only)."""
    k = x * z / (2 * n * dt)
    rod = ri.Rod.from_impedance([z] * (2 * n), dt)
    return ri.design(ri.EfficiencyObjective(reloading=reloading), ri.System.struck(rod, far_end=ri.BitRockEnd(
        k, unloading * k)), 10.0, n, dt, limits=ri.StrikerLimits(impedance_bounds=(piston * z, piston * z)),
        search=ri.SearchOptions(max_iterations=1, starts=1))


@pytest.mark.parametrize("x", [1.2564, 3.0])
def test_first_pass_efficiency_is_lundbergs_classical_efficiency(x):
    d = _uniform_piston(x, reloading=False)
    assert d.efficiency == pytest.approx(eta_closed_form(x), abs=1e-2)
    assert "first pass" in d.diagnostics["efficiency_definition"]
    # the run ends when the first wave reflected at the bit is back there: 3 travel times of the 2 n = 200 rod
    assert d.time.size == 3 * 200


def test_reloading_counts_the_work_of_the_reflected_waves():
    """A piston twice as stiff as the rod on a rock that unloads (k2 = 3 k): the piston stays in contact, waves
    reflected at the bit come back, unload and load the rock again, so the efficiency with reloading differs
    from the first pass, and its run is longer."""
    first = _uniform_piston(1.0, reloading=False, unloading=3.0, piston=2.0)
    again = _uniform_piston(1.0, reloading=True, unloading=3.0, piston=2.0)
    assert abs(again.efficiency - first.efficiency) > 0.01, (first.efficiency, again.efficiency)
    assert again.time.size > first.time.size
    assert "reloading" in again.diagnostics["efficiency_definition"]


def test_first_pass_refuses_a_pulse_longer_than_the_round_trip_and_a_run_length():
    struck = ri.System.struck(ri.Rod.from_impedance([50e3] * 4, 1e-6), far_end=ri.BitRockEnd(1e9))
    first_pass = ri.EfficiencyObjective(reloading=False)
    with pytest.raises(ValueError, match="EfficiencyObjective.reloading: the first pass cannot be separated"):
        ri.design(first_pass, struck, 10.0, n=6, dt=1e-6, search=ri.SearchOptions(max_iterations=1, starts=1))
    with pytest.raises(ValueError, match="EfficiencyObjective.steps: the first-pass efficiency .* omit it"):
        ri.EfficiencyObjective(reloading=False, steps=50)
    with pytest.raises(ValueError, match="EfficiencyObjective.duration: the first-pass efficiency"):
        ri.EfficiencyObjective(reloading=False, duration=1e-4)
    with pytest.raises(TypeError, match="EfficiencyObjective.reloading: must be True"):
        ri.EfficiencyObjective(reloading="no")


def test_the_run_length_of_the_efficiency_is_validated_and_computed_in_one_place():
    assert ri.EfficiencyObjective().run_steps(5, 40, 1e-6) == 2 * 5 + 2 * 3 * 40
    assert ri.EfficiencyObjective(steps=np.int64(77)).run_steps(5, 40, 1e-6) == 77
    assert ri.EfficiencyObjective(duration=50.4e-6).run_steps(5, 40, 1e-6) == 50
    for kw, error, match in ((dict(steps=10, duration=1e-5), ValueError, "EfficiencyObjective.steps, duration: give "
                                                                         "one of them"),
                             (dict(steps=0), ValueError, "EfficiencyObjective.steps: must be an integer >= 1"),
                             (dict(duration=-1e-3), ValueError, "EfficiencyObjective.duration: must be > 0"),
                             (dict(duration="x"), TypeError, "EfficiencyObjective.duration")):
        with pytest.raises(error, match=match):
            ri.EfficiencyObjective(**kw)
