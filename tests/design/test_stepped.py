"""Stepped strikers: optimal segmentation (against brute force) and a design with at most 3 steps whose misfit
is reported against the free profile's."""

import itertools

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.design.optimize import segment


def _cost(z, cuts):
    return sum(float(np.sum((z[a:b] - z[a:b].mean()) ** 2)) for a, b in zip(cuts[:-1], cuts[1:]))


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("k", [1, 2, 3])
def test_segmentation_is_optimal(seed, k):
    z = np.random.default_rng(seed).uniform(1, 5, 9)
    best = min(_cost(z, (0,) + c + (9,)) for g in range(k) for c in itertools.combinations(range(1, 9), g))
    cuts = segment(z, k)
    assert cuts[0] == 0 and cuts[-1] == 9 and len(cuts) - 1 <= k
    assert _cost(z, cuts) == pytest.approx(best, rel=1e-12, abs=1e-12)


def test_segmentation_finds_an_exact_step_profile():
    z = np.repeat([3.0, 1.0, 2.0], [4, 2, 5])
    assert segment(z, 3).tolist() == [0, 4, 6, 11]
    assert segment(z, 5).tolist() == [0, 4, 6, 11]       # no more steps than needed


def test_stepped_half_sine_with_three_steps():
    dt, n = 2e-6, 10
    bar = ri.Rod.from_impedance([1.27e4] * 4, dt)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -60e3 * np.sin(np.pi * t / (2 * n * dt)),
                                                  duration=2 * n * dt)
    d = ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 12.0, n, dt,
                  limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5), max_steps=3),
                  search=ri.SearchOptions(max_iterations=20, starts=1))
    assert d.steps <= 3
    free = d.diagnostics["free_profile"]
    assert free["misfit"] <= d.misfit * (1 + 1e-9)      # the free profile includes every stepped one
    assert d.misfit < 0.5
    assert len(d.diagnostics["breakpoints"]) - 1 == d.steps
    assert d.verify().misfit == pytest.approx(d.misfit, rel=1e-9)
