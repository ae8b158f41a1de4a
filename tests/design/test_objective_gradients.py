"""The objectives' seeds and explicit terms, chained through ImpactProblem.gradient, equal central finite
differences of the objective (match at the face with weights, at a position, efficiency, the smoothing
penalty). The engine's own gradient is verified in the adjoint tests; this checks the chain."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.design.objectives import EfficiencyCost, MatchCost
from rodimpact.design.optimize import Evaluator, total_variation
from rodimpact.inverse.struck import locate

DT = 1e-6


def _fd_check(ev, z, v, rtol=1e-5):
    total, _, dz, dv = ev.value_and_gradient(z, v)

    def full(zz, vv):
        t, *_ = ev.value_and_gradient(zz, vv)
        return t

    g_fd = np.empty(z.size)
    for i in range(z.size):
        h = 1e-5 * z[i]
        zp, zm = z.copy(), z.copy()
        zp[i] += h
        zm[i] -= h
        g_fd[i] = (full(zp, v) - full(zm, v)) / (2 * h)
    hv = 1e-5 * v
    dv_fd = (full(z, v + hv) - full(z, v - hv)) / (2 * hv)
    assert np.linalg.norm(dz - g_fd) <= rtol * np.linalg.norm(g_fd)
    assert dv == pytest.approx(dv_fd, rel=rtol, abs=rtol * np.linalg.norm(g_fd) * z.mean() / v)   # efficiency: 0 (degree-1 homogeneous)


def _random(seed, n=6):
    rng = np.random.default_rng(seed)
    return rng.uniform(5e3, 30e3, n), rng.uniform(5e3, 30e3, 8), rng.uniform(5.0, 15.0)


@pytest.mark.parametrize("seed", [0, 1])
def test_match_at_the_face_with_weights(seed):
    z, zs, v = _random(seed)
    s = ri.System.struck(ri.Rod.from_impedance(zs, DT), far_end="fixed")
    x = -np.linspace(30e3, 60e3, 8)
    obj = MatchCost.build(x, None, np.linspace(1, 2, 8), DT)
    ev = Evaluator(ImpactProblem(s, DT, z.size, obj.steps), obj)
    _fd_check(ev, z, v)


def test_match_incident_at_a_position_on_bit_rock():
    z, zs, v = _random(3)
    s = ri.System.struck(ri.Rod.from_impedance(zs, DT), far_end=ri.BitRockEnd(2e9, 4e9))
    loc = locate(s, 5 * DT * ri.STEEL.wave_speed, DT)
    obj = MatchCost.build(-np.linspace(20e3, 40e3, 6), loc.node, None, DT)
    ev = Evaluator(ImpactProblem(s, DT, z.size, obj.steps, location=loc, quantity="incident"), obj)
    _fd_check(ev, z, v)


def test_efficiency_with_smoothing_penalty():
    z, zs, v = _random(4)
    s = ri.System.struck(ri.Rod.from_impedance(zs, DT), far_end=ri.BitRockEnd(3e9, 6e9))
    steps = 40
    ev = Evaluator(ImpactProblem(s, DT, z.size, steps), EfficiencyCost(DT, steps), smoothness=0.1,
                   z_ref=1e4)
    _fd_check(ev, z, v)


def test_total_variation_value_by_hand():
    p, g = total_variation(np.array([1.0, 3.0, 2.0]), 0.0 + 1e-12)
    assert p == pytest.approx(3.0, rel=1e-9)
    assert np.allclose(g, [-1.0, 2.0, -1.0])
