"""Constraints of design: bounds from diameters, the exact projection onto {bounds, mass}, bad input."""

import math

import numpy as np
import pytest
from scipy.optimize import minimize

import rodimpact as ri
from rodimpact.design.constraints import build_constraints, diameter_to_impedance

DT = 1e-6


def test_diameter_bounds_become_impedance_bounds_by_hand():
    # steel: rho c = 7840 * sqrt(210e9 / 7840); d = 20 mm, bore 6 mm: A = pi (0.02^2 - 0.006^2) / 4
    rc = 7840.0 * math.sqrt(210e9 / 7840.0)
    a = math.pi * (0.02 ** 2 - 0.006 ** 2) / 4
    assert diameter_to_impedance(0.02, ri.STEEL, 0.006) == pytest.approx(rc * a, rel=1e-12)
    c = build_constraints(4, DT, 1e4, ri.StrikerLimits(diameter_bounds=(0.01, 0.02), material=ri.STEEL, bore=0.006),
                          5.0)
    assert c.upper[0] == pytest.approx(rc * a, rel=1e-12)
    assert c.lower[0] == pytest.approx(rc * math.pi * (0.01 ** 2 - 0.006 ** 2) / 4, rel=1e-12)


@pytest.mark.parametrize("seed", range(4))
def test_projection_is_the_euclidean_projection(seed):
    """Against a generic QP solver (SLSQP) on min |z' - z|^2 s.t. bounds and dt sum z' = m."""
    rng = np.random.default_rng(seed)
    n = 8
    lo, hi = rng.uniform(1, 3, n), rng.uniform(4, 9, n)
    z = rng.uniform(-2, 12, n)
    m = DT * rng.uniform(lo.sum() * 1.05, hi.sum() * 0.95)
    c = build_constraints(n, DT, 1.0, ri.StrikerLimits(impedance_bounds=(lo, hi), mass=m), 1.0)
    p = c.project(z)
    assert DT * p.sum() == pytest.approx(m, rel=1e-13)
    assert np.all(p >= lo) and np.all(p <= hi)
    ref = minimize(lambda y: np.sum((y - z) ** 2), np.clip(z, lo, hi), jac=lambda y: 2 * (y - z),
                   bounds=list(zip(lo, hi)), constraints=[{"type": "eq", "fun": lambda y: y.sum() - m / DT}],
                   method="SLSQP", options={"ftol": 1e-14, "maxiter": 500})
    assert np.allclose(p, ref.x, rtol=0, atol=1e-6)
    assert np.sum((p - z) ** 2) <= np.sum((ref.x - z) ** 2) + 1e-9


def test_mass_range_projection_only_when_outside():
    c = build_constraints(3, DT, 1.0, ri.StrikerLimits(impedance_bounds=(1.0, 10.0), mass=(DT * 9, DT * 15)), 1.0)
    z = np.array([3.0, 4.0, 5.0])              # mass 12 dt: inside, unchanged
    assert np.array_equal(c.project(z), z)
    p = c.project(np.array([8.0, 8.0, 8.0]))    # 24 dt -> upper 15 dt: shift by -3
    assert np.allclose(p, [5.0, 5.0, 5.0])


@pytest.mark.parametrize("kw, match", [
    (dict(impedance_bounds=(5e4, 1e4)), r"^StrikerLimits.impedance_bounds: the lower bound exceeds the upper bound "
                                        r"at element 1 \(50000 > 10000 N s/m\)"),
    (dict(impedance_bounds=([1e4, 3e4] * 5, 2e4)), r"^StrikerLimits.impedance_bounds: .* at element 2 "
                                                   r"\(30000 > 20000 N s/m\)"),
    (dict(diameter_bounds=(0.06, 0.005)), r"^StrikerLimits.diameter_bounds: the lower bound exceeds .*"
                                          r"\(0.06 > 0.005 m\)"),
    (dict(impedance_bounds=(1e4, 2e4), mass=10.0), "^StrikerLimits.mass: no striker of 10 elements.*can weigh"),
    (dict(impedance_bounds=(1e4, 2e4), mass=(1e-6, 2e-6)), "^StrikerLimits.mass: no striker"),
    (dict(mass=(2.0, 1.0)), r"^StrikerLimits.mass: the lower bound 2 kg exceeds"),
    (dict(mass=-1.0), r"^StrikerLimits.mass: must be > 0"),
    (dict(velocity_bounds=(12.0, 5.0)), "^StrikerLimits.velocity_bounds: the lower bound"),
    (dict(impedance_bounds=(1e4,)), "^StrikerLimits.impedance_bounds: give a pair"),
    (dict(impedance_bounds=(float("nan"), 1e5)), r"^StrikerLimits.impedance_bounds\[0\]: must be finite"),
    (dict(impedance_bounds=(1e4, [2e4] * 9)), r"^StrikerLimits.impedance_bounds\[1\]: give one value or one per "
                                              r"element \(10\), got 9 values"),
    (dict(impedance_bounds=(1e4, 2e4), diameter_bounds=(0.01, 0.02)), "give one of them"),
    (dict(diameter_bounds=(0.005, 0.02), bore=0.006), "^StrikerLimits.diameter_bounds: .*must exceed the bore"),
    (dict(max_steps=0), r"^StrikerLimits.max_steps: must be an integer >= 1"),
])
def test_bad_constraints_name_the_field(kw, match):
    """Refused when the StrikerLimits is made, or, where the number of elements matters, by design."""
    bar = ri.Rod.from_impedance([1.27e4] * 4, DT)
    t = 2 * DT * (np.arange(10) + 0.5)
    with pytest.raises(ValueError, match=match):
        ri.design(-5e4 * np.sin(np.pi * t / 20e-6), ri.System.struck(bar, far_end="nonreflecting"), 12.0, n=10,
                  dt=DT, limits=ri.StrikerLimits(**kw))


@pytest.mark.parametrize("target, match", [
    (np.array([-1e4, np.nan, -2e4]), "target.*window values"),
    (lambda t: np.where(t > 2e-6, np.inf, -1e4), "target: window 2"),
])
def test_non_finite_targets(target, match):
    bar = ri.Rod.from_impedance([1.27e4] * 4, DT)
    with pytest.raises(ValueError, match=match):
        ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 12.0, n=3, dt=DT)


def test_other_bad_arguments():
    bar = ri.Rod.from_impedance([1.27e4] * 4, DT)
    x = np.full(3, -1e4)
    with pytest.raises(ValueError, match="target: give the force history to match"):
        ri.design(None, bar, 12.0, n=3, dt=DT)
    with pytest.raises(ValueError, match="MatchObjective.target: give the force history to match"):
        ri.MatchObjective(None)
    with pytest.raises(ValueError, match="striker_velocity: give"):
        ri.design(x, struck=bar, dt=DT)
    with pytest.raises(ValueError, match="target: is zero"):
        ri.design(np.zeros(3), struck=bar, striker_velocity=12.0, dt=DT)
    with pytest.raises(TypeError, match=r"limits: must be a StrikerLimits \(ri.StrikerLimits\(...\)\) or None"):
        ri.design(x, bar, 12.0, dt=DT, limits={"mass": 1.0})
    with pytest.raises(TypeError, match="search: must be a SearchOptions"):
        ri.design(x, bar, 12.0, dt=DT, search=ri.StrikerLimits())
    with pytest.raises(ValueError, match="MatchObjective.quantity: must be one of"):
        ri.MatchObjective(x, quantity="stress")
    with pytest.raises(ValueError, match="MatchObjective.rule: must be one of"):
        ri.MatchObjective(x, rule="end")
    with pytest.raises(ValueError, match="MatchObjective.position: must be >= 0"):
        ri.MatchObjective(x, position=-0.1)


@pytest.mark.parametrize("weights, match", [
    (np.ones(3), "^MatchObjective.weights: give 10 values .one per window. or 20"),
    (-np.ones(10), "^MatchObjective.weights: must be finite and >= 0"),
    (np.zeros(10), "with at least one > 0"),
    (lambda t: 1 / 0, "weights: calling the weight function"),
])
def test_bad_weights(weights, match):
    bar = ri.Rod.from_impedance([1.27e4] * 4, DT)
    with pytest.raises(ValueError, match=match):
        ri.design(ri.MatchObjective(-np.linspace(1e4, 2e4, 10), weights=weights),
                  ri.System.struck(bar, far_end="nonreflecting"), 12.0, dt=DT)


@pytest.mark.parametrize("cls, key, value, error", [
    (ri.SearchOptions, "tolerance", "5", TypeError), (ri.SearchOptions, "tolerance", [1, 2], TypeError),
    (ri.SearchOptions, "tolerance", float("nan"), ValueError), (ri.SearchOptions, "tolerance", True, TypeError),
    (ri.SearchOptions, "tolerance", 0.0, ValueError), (ri.SearchOptions, "tolerance", 2.0, ValueError),
    (ri.SearchOptions, "improvement", 1.0, ValueError), (ri.SearchOptions, "starts", 0, ValueError),
    (ri.SearchOptions, "starts", 2.0, ValueError), (ri.SearchOptions, "max_iterations", True, ValueError),
    (ri.SearchOptions, "pool", 0, ValueError), (ri.SearchOptions, "hops", -1, ValueError),
    (ri.SearchOptions, "warm_start", "yes", TypeError),
    (ri.StrikerLimits, "smoothness", True, TypeError), (ri.StrikerLimits, "smoothness", "1", TypeError),
    (ri.StrikerLimits, "smoothness", float("inf"), ValueError), (ri.StrikerLimits, "bore", "0", TypeError),
    (ri.StrikerLimits, "impedance_bounds", ("1e3", "1e6"), TypeError),
    (ri.StrikerLimits, "impedance_bounds", (["1e3"] * 10, 1e6), TypeError),
    (ri.StrikerLimits, "material", "steel", TypeError),
    (ri.MatchObjective, "weights", ["1"] * 10, TypeError), (ri.MatchObjective, "weights", [True] * 10, TypeError),
])
def test_numeric_arguments_of_design_are_refused_not_coerced(cls, key, value, error):
    """Issue 20, item 12: a string, a sequence, a bool or a non-finite number for a numeric setting of design is
    refused with an error naming the field (no coercion of "5" into 5): when its object is made, or by design where
    the number of elements matters (the weights)."""
    bar = ri.System.struck(ri.Rod.from_impedance([1.27e4] * 4, DT), far_end="nonreflecting")
    target = -np.linspace(1e4, 2e4, 10)
    with pytest.raises(error, match=f"^{cls.__name__}.{key}"):
        if cls is ri.MatchObjective:
            ri.design(ri.MatchObjective(target, **{key: value}), bar, 12.0, dt=DT,
                      search=ri.SearchOptions(max_iterations=1, starts=1))
        else:
            cls(**{key: value})


def test_limits_and_search_options_are_frozen_and_normalised():
    limits = ri.StrikerLimits(impedance_bounds=(np.array([1e3, 2e3]), np.int64(5000)), mass=[1, 2],
                              bore=np.float32(0.5), velocity_bounds=(5, 10), max_steps=np.int64(3))
    assert limits.impedance_bounds == ((1e3, 2e3), 5000.0) and limits.mass == (1.0, 2.0)
    assert limits.velocity_bounds == (5.0, 10.0) and type(limits.max_steps) is int and limits.bore == 0.5
    assert limits == ri.StrikerLimits(impedance_bounds=((1e3, 2e3), 5e3), mass=(1.0, 2.0), bore=0.5,
                                      velocity_bounds=(5.0, 10.0), max_steps=3)
    search = ri.SearchOptions(starts=np.int64(2), warm_start=np.bool_(False))
    assert type(search.starts) is int and search.warm_start is False
    with pytest.raises(AttributeError):
        limits.mass = 3.0
    with pytest.raises(AttributeError):
        search.starts = 3
