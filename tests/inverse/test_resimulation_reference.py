"""Fast peeling synthesis against the thesis's recursion with a full re-simulation per element (eqs. 4.4-4.9,
Tab. 4.1). The two share only the direct solver; the reference obtains Delta N_q = X_q - N_bar_q from a
simulation with Z_q = Z_{q-1}, the fast path from the peeled reflection, Delta N_q = K_q R N_0."""

import warnings

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import SynthesisWarning, synthesize, synthesize_by_resimulation

DT = 1e-6


def _target(t):
    return -1.5e5 * (1.0 + 0.6 * np.sin(2.3e4 * t) * np.exp(-1e4 * t) + 1.5e3 * t)


CASES = {
    "semi-infinite uniform bar": dict(struck=ri.System.struck(ri.Rod.from_impedance([8e4] * 4, DT),
                                                             far_end="nonreflecting")),
    "stepped rods, free far end": dict(struck=ri.System.struck(
        [ri.Rod.from_impedance([6e4] * 6, DT), ri.Rod.from_impedance([1.2e5] * 10 + [5e4] * 8, DT)],
        far_end="free")),
    "moving, fixed end, nodal load": dict(struck=ri.System.struck(
        ri.Rod.from_impedance([9e4] * 8 + [7e4] * 14, DT), far_end="fixed", velocity=0.5,
        loads=[ri.NodalForce(0, 12 * ri.STEEL.wave_speed * DT, -2e4)])),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_fast_path_equals_resimulation(case):
    kw = CASES[case]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SynthesisWarning)     # the stepped case ends before n (checked below)
        res = synthesize(_target, striker_velocity=8.0, n=40, dt=DT, rule="midpoint", **kw)
    assert res.n_feasible >= 30
    ref = synthesize_by_resimulation(res.window_values, res.struck, 8.0, DT)
    assert ref.n_feasible == res.n_feasible
    # near the existence limit Z_q is ill-conditioned (d ln Z = 2 dR / (1 - R^2)); allow 10x the rounding
    # bound the fast path estimates for itself (the reference carries errors of the same kind), at least 1e-12
    tol = np.maximum(1e-12, 10 * res.error_estimate)
    assert np.all(np.abs(res.impedance / ref.impedance - 1) <= tol)
    np.testing.assert_allclose(res.transmission_factor, ref.transmission_factor, rtol=1e-12)
    np.testing.assert_allclose(res.force_reserve, ref.force_reserve, rtol=1e-12)
    np.testing.assert_allclose(res.force_difference, ref.force_difference, rtol=0, atol=1e-9 * abs(ref.n0))
    assert res.impact_force_n0 == pytest.approx(ref.n0, rel=1e-14)      # eq. 4.3
    assert res.verify().max_deviation < 1e-12


def test_reference_stops_where_the_fast_path_stops():
    bar = ri.Rod.from_impedance([8e4] * 4, DT)
    x = -2e5 * (1 + 0.08 * np.arange(30))           # steep ramp: eq. 4.20 fails after a few elements
    with pytest.warns(SynthesisWarning):
        res = synthesize(x, ri.System.struck(bar, far_end="nonreflecting"), 6.0, dt=DT)
    ref = synthesize_by_resimulation(x, res.struck, 6.0, DT)
    assert 1 < res.n_feasible < 30
    assert ref.n_feasible == res.n_feasible
    np.testing.assert_allclose(res.impedance, ref.impedance, rtol=1e-12)


def test_closed_form_face_response_only_when_valid():
    """The closed form V = v~ - N/Z~ is used only when nothing can reach the face within 2n steps: a velocity
    jump 6 elements deep arrives after 6 steps (< 2n = 10), so the direct solver must be used."""
    x = -5e4 * np.ones(5)
    rods = [ri.Rod.from_impedance([3e4] * 6, DT), ri.Rod.from_impedance([3e4] * 2, DT)]
    res = synthesize(x, ri.System.struck(rods, far_end="free", velocity=[0.0, 1.0]), 2.7, dt=DT)
    assert res.diagnostics["face_response"] == "simulated"
    assert res.verify().max_deviation < 1e-13
    same = synthesize(x, ri.System.struck(rods, far_end="free", velocity=[0.5, 0.5]), 2.7, dt=DT)
    assert same.diagnostics["face_response"] == "analytic"
    assert same.verify().max_deviation < 1e-13
    moving_fixed = synthesize(x, ri.System.struck(rods, far_end="fixed", velocity=0.5), 2.7, dt=DT)
    assert moving_fixed.diagnostics["face_response"] == "simulated"     # the fixed end stops a moving bar
    assert moving_fixed.verify().max_deviation < 1e-13
