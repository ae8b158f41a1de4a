"""Values the design reports and honours: the lower mass bound, per-element bounds of a stepped striker, per-step
weights at a position, the 1-based element numbers of the constraint report (issue 20, item 22)."""

import warnings

import numpy as np
import pytest
from scipy.optimize import minimize

import rodimpact as ri
from rodimpact.design.constraints import build_constraints
from rodimpact.design.objectives import MatchCost

DT = 1e-6
Z_BAR = 1.27e4


def _bar():
    return ri.Rod.from_impedance([Z_BAR] * 4, DT)


def test_an_active_lower_mass_bound_is_met_at_the_best_misfit():
    """A ramp of 10-20 kN wants a striker of about 0.014 kg; with mass >= 0.03 kg the lower bound is active. The
    design must reach the constrained optimum, found here independently by SLSQP over the impedances with the
    misfit computed by simulate (kills a sign error in the gradient of the lower-mass penalty, which still meets
    the mass but ends at a misfit four times worse)."""
    n, v, m_lo = 10, 12.0, 0.03
    target = -np.linspace(1e4, 2e4, n)
    bar = _bar()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        d = ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), v, dt=DT,
                      limits=ri.StrikerLimits(mass=(m_lo, 0.1), impedance_bounds=(500.0, 1e5)))
    assert d.constraint_report["mass_active"] == "lower"
    assert d.mass == pytest.approx(m_lo, rel=1e-5)
    ref = np.repeat(target, 2)

    def misfit2(z_k):             # z in kN s/m, face first
        striker = ri.Rod.from_impedance(z_k[::-1] * 1e3, DT)
        sim = ri.simulate(ri.System([striker, bar], [v, 0.0], right="nonreflecting"), steps=2 * n, dt=DT)
        return float(np.sum((sim.junction_force[0] - ref) ** 2) / np.sum(ref ** 2))

    best = min(minimize(misfit2, np.full(n, z0), method="SLSQP", bounds=[(0.5, 100.0)] * n,
                        constraints=[{"type": "ineq", "fun": lambda z: DT * z.sum() * 1e3 - m_lo}],
                        options={"ftol": 1e-12, "maxiter": 300}).fun for z0 in (3.0, 10.0))
    assert d.misfit <= np.sqrt(best) * (1 + 1e-4), (d.misfit, np.sqrt(best))


def test_a_step_of_a_stepped_striker_takes_the_tightest_bound_of_its_elements():
    """One step over elements whose lower bounds are 500 and 5000 N s/m must stay >= 5000 everywhere: the target
    (8 kN) wants about 700 N s/m, so a step bounded by the loosest element bound would break the others'."""
    lower = np.array([500.0] * 5 + [5000.0] * 5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        d = ri.design(np.full(10, -8e3), ri.System.struck(_bar(), far_end="nonreflecting"), 12.0, dt=DT,
                      limits=ri.StrikerLimits(impedance_bounds=(lower, 1e5), max_steps=1),
                      search=ri.SearchOptions(max_iterations=20, starts=1))
    assert d.steps == 1
    assert np.all(d.impedance >= lower), d.impedance


def test_per_step_weights_at_a_position_are_those_of_the_window_starts():
    """At a position the compared samples are the window starts (steps d + 2(j-1)); with one weight per step the
    weight of window j is that of its first step: [1,0, 1,0, 1,0, 0,5] -> [1, 1, 1, 0]."""
    obj = MatchCost.build(-np.ones(4), 3, [1, 0, 1, 0, 1, 0, 0, 5], DT)
    np.testing.assert_array_equal(obj.weights, [1.0, 1.0, 1.0, 0.0])
    np.testing.assert_array_equal(obj.index, [3, 5, 7, 9])


def test_the_constraint_report_numbers_elements_from_1_on_both_lists():
    """Element 1 (at the impact face) at its lower bound and element 3 at its upper bound are reported as [1] and
    [3]."""
    c = build_constraints(3, DT, Z_BAR, ri.StrikerLimits(impedance_bounds=(1e3, 1e5)), 5.0)
    rep = c.report(np.array([1e3, 5e4, 1e5]), 5.0)
    assert rep["elements_at_lower_bound"] == [1]
    assert rep["elements_at_upper_bound"] == [3]
