"""Screening of starting profiles with one simulate_batch call (rodimpact.design.screening).

The batch kernel and the design's own forward engine (rodimpact.design._adjoint.ImpactProblem) are separate
implementations of the lattice; the objective values of the same strikers must agree to rounding.
"""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.design.constraints import build_constraints
from rodimpact.design.objectives import EfficiencyCost, MatchCost
from rodimpact.design.screening import POOL_SIZE, candidate_pool, screen

DT = 1e-6


def _strikers(n, count, seed=3):
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 1.0, n)
    return [4e4 * (1.0 + 0.4 * rng.uniform(-1, 1) * np.cos(np.pi * x) + 0.2 * rng.uniform(-1, 1) * x)
            for _ in range(count)]


def _independent_values(problem, objective, strikers, v):
    return np.array([objective.evaluate(problem.forward(z, v), z, v)[0] for z in strikers])


def test_face_match_values_equal_the_design_forward_runs():
    """Non-uniform two-rod struck system with a non-reflecting end; the target starts at 0 N (infeasible)."""
    n = 12
    struck = ri.System.struck([ri.Rod.from_impedance([3e4] * 10 + [6e4] * 15, DT),
                               ri.Rod.from_impedance([5e4] * 20, DT)], far_end="nonreflecting")
    windows = -6e4 * np.sin(np.pi * (np.arange(n) + 0.5) / n)
    obj = MatchCost.build(windows, None, None, DT)
    strikers = _strikers(n, 6)
    pool = [(f"s{i}", z) for i, z in enumerate(strikers)]
    ranked = screen(struck, DT, obj.steps, obj, pool, 7.0, 0.0, 1.0)
    expected = _independent_values(ImpactProblem(struck, DT, n, obj.steps), obj, strikers, 7.0)
    order = np.argsort(expected)
    assert ranked.names == [f"s{i}" for i in order]
    assert np.allclose(ranked.values, expected[order], rtol=1e-12, atol=0.0)


def test_efficiency_values_equal_the_design_forward_runs():
    """Drill rod on a bit-rock end (loading and unloading stiffness): -eta of each striker."""
    n = 10
    struck = ri.System.struck(ri.Rod.from_impedance([4e4] * 40, DT), far_end=ri.BitRockEnd(2e9, 2e10))
    steps = 2 * n + 6 * 40
    obj = EfficiencyCost(DT, steps)
    strikers = _strikers(n, 5, seed=8)
    ranked = screen(struck, DT, steps, obj, [(f"s{i}", z) for i, z in enumerate(strikers)], 9.0, 0.0, 1.0)
    expected = _independent_values(ImpactProblem(struck, DT, n, steps), obj, strikers, 9.0)
    assert np.allclose(np.sort(ranked.values), np.sort(expected), rtol=1e-12, atol=0.0)
    assert np.all(ranked.values < 0.0) and np.all(ranked.values > -1.0)    # 0 < eta < 1


def test_the_smoothness_penalty_is_added_as_in_the_optimiser():
    n = 8
    struck = ri.System.struck(ri.Rod.from_impedance([4e4] * 20, DT), far_end="nonreflecting")
    obj = MatchCost.build(np.full(n // 2, -5e4), None, None, DT)
    z = np.linspace(2e4, 6e4, n)
    plain = screen(struck, DT, obj.steps, obj, [("ramp", z)], 5.0, 0.0, 1.0).values[0]
    smooth = screen(struck, DT, obj.steps, obj, [("ramp", z)], 5.0, 0.5, 4e4).values[0]
    # total variation of the ramp in units of 4e4, smoothed with eps = 1e-3 (n - 1 equal steps of 4e4 / 7)
    step = 4e4 / (n - 1) / 4e4
    tv = (n - 1) * (np.sqrt(step ** 2 + 1e-6) - 1e-3)
    assert smooth - plain == pytest.approx(0.5 * tv, rel=1e-12)


def test_candidate_pool_is_feasible_reproducible_and_keeps_the_named_starts_first():
    n = 30
    cons = build_constraints(n, DT, 4e4, ri.StrikerLimits(impedance_bounds=(1e4, 1e5), mass=(0.9, 1.5)), 5.0)
    named = [("a", np.full(n, 3e4)), ("b", np.linspace(2e4, 9e4, n))]
    pool = candidate_pool(named, cons)
    again = candidate_pool(named, cons)
    assert len(pool) == POOL_SIZE
    assert [name for name, _ in pool[:2]] == ["a", "b"]
    for (name, z), (name2, z2) in zip(pool, again):
        assert name == name2 and np.array_equal(z, z2)
        assert np.all(z >= 1e4 * (1 - 1e-12)) and np.all(z <= 1e5 * (1 + 1e-12))
        assert 0.9 * (1 - 1e-9) <= DT * z.sum() <= 1.5 * (1 + 1e-9)
    assert len({tuple(np.round(z, 6)) for _, z in pool}) == POOL_SIZE     # all different


def _half_sine_design():
    bar = ri.Rod.from_impedance([6e4] * 8, 2e-6)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -5e4 * np.sin(np.pi * t / 40e-6), duration=40e-6)
    return ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 8.0, n=10, dt=2e-6,
                     limits=ri.StrikerLimits(impedance_bounds=(5e3, 2e5)), search=ri.SearchOptions(max_iterations=12))


def test_design_starts_from_the_screened_pool_at_the_face():
    d = _half_sine_design()
    assert d.diagnostics["screened"]["candidates"] == POOL_SIZE
    assert d.diagnostics["starts"][0] == "recursive prefix"
    assert len(d.diagnostics["starts"]) == 16          # the default number of starts
    values = d.diagnostics["screened"]["best_values"]
    assert values == sorted(values)


def test_design_at_a_position_uses_the_named_starts():
    bar = ri.Rod.from_impedance([6e4] * 30, 2e-6)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -5e4 * np.sin(np.pi * t / 40e-6), duration=40e-6)
    d = ri.design(ri.MatchObjective(target, position=0.05), ri.System.struck(bar, far_end="nonreflecting"), 8.0, n=10,
                  dt=2e-6, limits=ri.StrikerLimits(impedance_bounds=(5e3, 2e5)),
                  search=ri.SearchOptions(max_iterations=5))
    assert "screened" not in d.diagnostics
