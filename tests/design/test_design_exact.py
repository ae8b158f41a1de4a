"""Where an exact striker exists, design returns the recursive method's impedances (to 1e-6 relative) with a
misfit below 1e-9: thesis example 1, Lundberg-Lesser at random parameters, the percussion-drilling example."""

import warnings

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import academic_example, percussion_drilling_example


def _exact(problem):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        return problem.solve()


def _design_of(problem, limits, search=None, backend="numba"):
    return ri.design(ri.MatchObjective(problem.target, **problem.options), problem.struck_system,
                     problem.striker_velocity, problem.n, problem.dt, limits=limits, search=search, backend=backend)


def _check(d, ref):
    assert ref.feasible
    assert np.max(np.abs(d.impedance / ref.impedance - 1)) < 1e-6
    assert d.misfit < 1e-9
    assert d.diagnostics["warm_start"].startswith("exact")
    v = d.verify()                       # the direct solver agrees with the design's run
    assert v.misfit < 1e-9


def test_thesis_example_1():
    p = academic_example(1)
    z = 79.7e3
    _check(_design_of(p, ri.StrikerLimits(impedance_bounds=(z / 50, z * 50))), _exact(p))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_lundberg_lesser_random_parameters(seed):
    rng = np.random.default_rng(seed)
    zt = rng.uniform(20e3, 200e3)
    v = rng.uniform(3.0, 15.0)
    peak = rng.uniform(0.2, 0.9) * zt * v       # v > peak / Z~ (eq. 4.26)
    t0 = rng.uniform(50e-6, 500e-6)
    n = 60
    dt = t0 / rng.uniform(20.0, 80.0)
    bar = ri.Rod.from_impedance([zt] * 4, dt)
    target = ri.ExponentialDecay(peak, t0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        ref = ri.synthesize(target, ri.System.struck(bar, far_end="nonreflecting"), v, n, dt)
    d = ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), v, n, dt,
                  limits=ri.StrikerLimits(impedance_bounds=(1.0, 1e9)))
    _check(d, ref)
    # and the closed form (second order at the element midpoints): a loose independent check of the answer
    exact = ri.inverse.lundberg_lesser_impedance(dt * (np.arange(n) + 0.5), peak, t0, zt, v)
    assert np.max(np.abs(d.impedance / exact - 1)) < 0.05


def test_percussion_drilling_example():
    p = percussion_drilling_example()
    d = _design_of(p, ri.StrikerLimits(impedance_bounds=(1e3, 1e7)))
    ref = _exact(p)
    _check(d, ref)
    assert d.location is not None and d.quantity == "incident"


def test_bounds_that_exclude_the_exact_striker_force_optimisation():
    """The same example with an upper bound below the exact striker's largest impedance: not exact, inside the
    bounds, the bound reported active."""
    p = academic_example(1, n=12)
    ref = _exact(p)
    hi = 0.9 * ref.impedance.max()
    d = _design_of(p, ri.StrikerLimits(impedance_bounds=(1e3, hi)), ri.SearchOptions(max_iterations=15, starts=1))
    assert d.impedance.max() <= hi * (1 + 1e-12)
    assert not d.diagnostics["warm_start"].startswith("exact")
    assert d.constraint_report["elements_at_upper_bound"]
    assert d.misfit > 1e-6


def test_optimiser_alone_finds_the_exact_striker():
    """Without the warm start the gradient-based optimiser reaches the recursive method's striker too."""
    p = academic_example(1, n=10)
    ref = _exact(p)
    d = _design_of(p, ri.StrikerLimits(impedance_bounds=(1e3, 1e7)), ri.SearchOptions(warm_start=False))
    assert d.misfit < 1e-7
    assert np.max(np.abs(d.impedance / ref.impedance - 1)) < 1e-6


def test_numpy_and_numba_backends_agree():
    """Through the optimiser: the upper bound excludes the exact striker."""
    p = academic_example(2, n=6)
    kw = dict(limits=ri.StrikerLimits(impedance_bounds=(1e3, 0.9 * _exact(p).impedance.max())),
              search=ri.SearchOptions(max_iterations=3, starts=2))
    a = _design_of(p, backend="numba", **kw)
    b = _design_of(p, backend="numpy", **kw)
    assert np.allclose(a.impedance, b.impedance, rtol=1e-9, atol=0)
    assert a.misfit == pytest.approx(b.misfit, rel=1e-9, abs=1e-15)
