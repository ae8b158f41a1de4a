"""Bad input gives clear errors naming the quantity; warnings where the result is partial or imprecise."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact._validate import physical_memory
from rodimpact.inverse import SynthesisWarning, synthesize

DT = 1.93e-6
BAR = ri.Rod.from_impedance([79.7e3] * 4, DT)


def _syn(target, **kw):
    args = dict(struck=ri.System.struck(BAR, far_end="nonreflecting"), striker_velocity=6.0, n=20, dt=DT)
    args.update(kw)
    return synthesize(target, **args)


def test_non_compressive_target():
    with pytest.raises(ValueError, match=r"target: window 4 has the force 1000 N, which is not compressive"):
        _syn(np.r_[[-1e5] * 3, 1e3, [-1e5] * 16])
    with pytest.raises(ValueError, match="not compressive"):
        _syn(lambda t: 0.0 * t)


def test_non_finite_target():
    with pytest.raises(ValueError, match=r"target: window 3 .* is nan; forces must be finite"):
        _syn(lambda t: np.where(t > 4 * DT, np.nan, -1e5))
    with pytest.raises(ValueError, match="must be finite"):
        _syn(np.r_[[-1e5] * 19, np.inf])


def test_striker_too_slow_for_the_first_force():
    # the face of a bar at rest moves at |X_1| / Z~ = 239e3 / 79.7e3 = 3.0 m/s under the first force
    with pytest.raises(ValueError, match=r"striker_velocity: 2.5 m/s cannot produce the first force window .* "
                                         r"faster than 2.99875 m/s"):
        _syn(lambda t: -239e3 + 0 * t, striker_velocity=2.5)


def test_n_and_dt_inconsistent_with_the_target():
    t = np.linspace(0, 30 * DT, 31)
    with pytest.raises(ValueError, match=r"n: 20 windows of 2\*dt .* need a target lasting"):
        _syn((t, -1e5 * np.ones_like(t)))
    with pytest.raises(ValueError, match="n: the target gives 19 window values, n = 20 was requested"):
        _syn(-1e5 * np.ones(19))
    with pytest.raises(ValueError, match="shorter than one window"):
        _syn((np.array([0.0, DT]), np.array([-1e5, -1e5])), n=None)
    with pytest.raises(ValueError, match="n: give the number of striker elements"):
        _syn(lambda t: -1e5 + 0 * t, n=None)
    with pytest.raises(ValueError, match="n: must be an integer number of striker elements >= 1"):
        _syn(lambda t: -1e5 + 0 * t, n=0)
    with pytest.raises(ValueError, match="dt: must be > 0"):
        _syn(lambda t: -1e5 + 0 * t, dt=-1.0)


def test_n_is_inferred_from_samples_and_window_values():
    t = np.linspace(0, 30 * DT, 31)
    assert _syn((t, -1e5 * np.ones_like(t)), n=None).n_requested == 15
    assert _syn(-1e5 * np.ones(7), n=None).n_requested == 7


def test_other_bad_arguments():
    with pytest.raises(ValueError, match="backend: must be 'numba' or 'numpy'"):
        _syn(-1e5 * np.ones(20), backend="cuda")
    with pytest.raises(TypeError, match="struck: must be a Rod"):
        _syn(-1e5 * np.ones(20), struck="steel bar")
    with pytest.raises(ValueError, match="velocity: need one value per struck rod"):
        _syn(-1e5 * np.ones(20), struck=ri.System.struck([BAR, BAR], velocity=[0.0]))
    with pytest.raises(TypeError, match=r"far_end: give the struck system as one System: ri.System.struck\(rods, "
                                        r"far_end=...\)"):
        _syn(-1e5 * np.ones(20), struck=BAR, far_end="fixed")
    with pytest.raises(TypeError, match="striker_velocity: must be a real number"):
        _syn(-1e5 * np.ones(20), striker_velocity="fast")
    with pytest.raises(ValueError, match="rule: must be one of"):
        _syn(lambda t: -1e5 + 0 * t, rule="left")
    # options that only matter with position= are still checked without it (a typo must not pass)
    with pytest.raises(ValueError, match="quantity: must be one of"):
        _syn(-1e5 * np.ones(20), quantity="forse")
    with pytest.raises(ValueError, match="toeplitz_method: must be one of"):
        _syn(-1e5 * np.ones(20), toeplitz_method="ff")
    for bad in (float("nan"), -1.0):
        with pytest.raises(ValueError, match="precision_warning: must be"):
            _syn(-1e5 * np.ones(20), precision_warning=bad)
    with pytest.raises(ValueError, match=r"target: the force function returned shape \(3,\)"):
        _syn(lambda t: -np.ones(3))


@pytest.mark.skipif(physical_memory() is None, reason="the platform does not report its memory (no sysconf)")
def test_sizes_beyond_the_memory_are_refused_before_allocating():
    with pytest.raises(ValueError, match="n: .* striker elements would need .* GiB"):
        _syn(lambda t: -1e5 + 0 * t, n=10**12)
    with pytest.raises(ValueError, match="dt: .* lattice elements"):
        _syn(lambda t: -1e5 + 0 * t, struck=ri.Rod([ri.Cylinder(1.0, 0.05)]), dt=1e-16, n=10)


def test_tensile_impact_force_required_at_a_position():
    """A force at a position that needs the striker to pull: partial result, reason 'tension'."""
    bar = ri.Rod.from_impedance([79.7e3] * 30, DT)
    y = np.r_[[-1e5] * 6, [3e4] * 14]          # the force at 10 elements depth turns tensile in window 7
    with pytest.warns(SynthesisWarning, match="is not compressive; the striker would have to pull"):
        res = synthesize(y, ri.System.struck(bar, far_end="nonreflecting"), 6.0, dt=DT,
                         position=10 * ri.STEEL.wave_speed * DT)
    assert res.n_feasible == 6 and res.failure.reason == "tension" and res.failure.element == 7
    assert res.verify().max_deviation < 1e-13


def test_struck_given_as_a_system():
    sys_ = ri.System([BAR], [0.0], right="nonreflecting")
    a = synthesize(-1e5 * np.ones(10), sys_, 6.0, dt=DT)
    b = _syn(-1e5 * np.ones(10), n=10)
    np.testing.assert_array_equal(a.impedance, b.impedance)
    with pytest.raises(ValueError, match="struck.left: the left end of the struck system is the impact face"):
        synthesize(-1e5 * np.ones(10), ri.System([BAR], [0.0], left="fixed"), 6.0, dt=DT)
    with pytest.raises(TypeError, match=r"loads: give the struck system as one System: ri.System.struck\(rods, "
                                        r"loads=...\)"):
        synthesize(-1e5 * np.ones(10), sys_, 6.0, dt=DT, loads=[ri.NodalForce(0, 0.01, 1.0)])
