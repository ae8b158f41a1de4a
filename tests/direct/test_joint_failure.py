"""Failure of a specimen's law (Johnson and Cook's 1985 cumulative damage with a constant failure strain, linear
softening; rodimpact.rods.laws.Failure): a closed form and its convergence order, the energy split, the numpy
twin, refusals by name, the adjoint's refusal and the model-file round trip.

Set-up: two identical bars of impedance Z, the incident bar driven by a force end F_i (a rectangular incident pulse
reaching the joint after n steps), the transmitted bar non-reflecting (as tests/direct/test_deformable_joints.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.io.model import Model, dump_model, loads_model

Z, C, F_I, L = 40e3, 5000.0, -10e3, 0.2
D, L0 = 6e-3, 3e-3
A0 = math.pi / 4 * D * D
SIGMA_Y, EPS_F, SOFT = 100e6, 0.004, 0.002


def _run(law, n: int, *, steps: int | None = None, backend: str = "numba", measure: str = "engineering",
         force: float = F_I):
    dt = L / C / n
    bars = [ri.Rod.from_impedance(np.full(n, Z), dt=dt, wave_speed=C, name=k) for k in ("in", "out")]
    system = ri.System(bars, [0.0, 0.0], [ri.Specimen(law, D, L0, measure=measure)], ri.ForceEnd(force),
                       "nonreflecting")
    return dt, ri.simulate(ri.Problem.of(system, steps=steps or 3 * n, dt=dt), backend=backend)


def rigid_plastic_force(t: np.ndarray) -> np.ndarray:
    """Closed form: the joint force (tension positive) of a rigid-perfectly-plastic specimen with failure between
    identical semi-infinite bars, the incident force F_i < 0 arriving at t = 0. The faces give the shortening rate
    L0 eps' = 2 (|F_i| - F) / Z with F >= 0 the specimen's compressive force, so eps' = a (|F_i| - F), a = 2 / (Z L0):
    flat flow at F_y = sigma_y A0 until eps = eps_f at t_f = eps_f / (a (|F_i| - F_y)); then F = (1 - u / h) F_y,
    u = eps - eps_f, and u' = a (|F_i| - F_y + F_y u / h) gives u = (|F_i| - F_y) h / F_y (exp(a F_y (t - t_f) / h)
    - 1) until u = h (t = t_0), after which F = 0."""
    f_y, drive, a = SIGMA_Y * A0, abs(F_I), 2.0 / (Z * L0)
    t_f = EPS_F / (a * (drive - f_y))
    u = (drive - f_y) * SOFT / f_y * np.expm1(a * f_y * np.maximum(t - t_f, 0.0) / SOFT)
    force = np.where(t < t_f, f_y, np.maximum(1.0 - u / SOFT, 0.0) * f_y)
    return -np.where(t < 0.0, 0.0, force)


def test_rigid_plastic_specimen_fails_as_the_closed_form_at_first_order() -> None:
    # the softening is lagged one step (rodimpact.direct.joints): first order in dt once it has started
    errors, flat = [], []
    for n in (100, 200, 400, 800):
        dt, res = _run(ri.ElasticPlastic(1e16, SIGMA_Y, failure_strain=EPS_F, softening_strain=SOFT), n)
        t = res.time - n * dt + 0.5 * dt              # the step midpoints, from the incident wave's arrival
        after = np.arange(t.size) >= n + 5            # past the few steps of the (stiff) elastic rise
        exact = rigid_plastic_force(t)
        errors.append(np.abs(res.contact_force[after] - exact[after]).max() / abs(F_I))
        before = after & (exact == -SIGMA_Y * A0) & (t < 0.9 * EPS_F * Z * L0 / (2 * (abs(F_I) - SIGMA_Y * A0)))
        flat.append(np.abs(res.contact_force[before] - exact[before]).max() / abs(F_I))
        assert res.joints[0].softening == 1.0 and np.all(res.contact_force[-n // 2:] == 0.0)   # failed: no force
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert max(flat) <= 1e-12                          # before failure: the flow force, exactly
    assert errors[-1] < 2e-3 and np.all(orders > 0.9), (errors, orders)


def test_elastic_hardening_specimen_fails_as_an_independent_ode_integration() -> None:
    # E finite and hardening H: eps' = 2 (|F_i| - F) / (Z L0), F = (1 - w(alpha)) E (eps - alpha) A0, and while the
    # effective stress E (eps - alpha) is on the yield surface sigma_y + H alpha and eps grows, alpha' = E eps' /
    # (E + H) (monotone compression: eps_p = alpha), integrated by scipy (DOP853, rtol 1e-11)
    e_mod, hard = 117e9, 1e9
    law = ri.ElasticPlastic(e_mod, SIGMA_Y, hard, failure_strain=EPS_F, softening_strain=SOFT)

    def force(y):
        w = min(1.0, max(0.0, (y[1] - EPS_F) / SOFT))
        return (1.0 - w) * e_mod * (y[0] - y[1]) * A0

    def rhs(_t, y):
        rate = 2.0 * (abs(F_I) - force(y)) / (Z * L0)
        flowing = e_mod * (y[0] - y[1]) >= SIGMA_Y + hard * y[1] and rate > 0.0
        return [rate, e_mod * rate / (e_mod + hard) if flowing else 0.0]

    errors, sizes = [], (100, 200, 400, 800, 1600)
    for n in sizes:
        dt, res = _run(law, n)
        t = res.time - n * dt + 0.5 * dt
        after = t > 0.0
        sol = solve_ivp(rhs, (0.0, t[-1]), [0.0, 0.0], t_eval=t[after], rtol=1e-11, atol=1e-15, method="DOP853",
                        max_step=dt)
        exact = -np.array([force(y) for y in sol.y.T])
        errors.append(np.abs(res.contact_force[after] - exact).max() / abs(F_I))
        assert res.joints[0].softening == 1.0
    # the largest error sits where w reaches 1 (a kink of the force): the pairwise orders scatter there (measured
    # 0.87, 0.82, 0.80, 1.42), so the order is the least-squares slope over the five resolutions (measured 0.94)
    order = -np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert errors[-1] < 1e-3 and order > 0.9, (errors, order)


def test_a_law_without_failure_is_unchanged() -> None:
    _, intact = _run(ri.ElasticPlastic(1e16, SIGMA_Y), 200)
    _, failing = _run(ri.ElasticPlastic(1e16, SIGMA_Y, failure_strain=0.5, softening_strain=SOFT), 200)
    assert np.array_equal(intact.contact_force, failing.contact_force)   # eps_f not reached
    assert failing.joints[0].softening == 0.0 and failing.joints[0].damage_work == 0.0


@pytest.mark.parametrize("measure, tolerance", [("engineering", 1e-9)])
def test_the_work_absorbed_is_stored_plastic_and_damage_work(measure: str, tolerance: float) -> None:
    law = ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, 0.025, 1.0, 1.09, failure_strain=0.004, softening_strain=0.003)
    n = 100
    _, res = _run(law, n, steps=8 * n, measure=measure, force=-8e3)   # later the free bars crush it
    e, joint = res.energy, res.joints[0]
    assert e.balance_error < 1e-13
    assert joint.softening == 1.0 and joint.damage_work > 0.0 and joint.plastic_work > 0.0
    absorbed = -e.work_joints[-1]
    assert joint.plastic_work + joint.damage_work + joint.stored_energy == pytest.approx(absorbed, rel=tolerance)


def test_numpy_twin_agrees_with_failure() -> None:
    law = ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, 0.025, 1.0, failure_strain=0.004, softening_strain=0.003)
    _, a = _run(law, 100)
    _, b = _run(law, 100, backend="numpy")
    assert a.joints[0].softening > 0.0
    assert np.abs(a.contact_force - b.contact_force).max() <= 1e-9 * abs(F_I)


@pytest.mark.parametrize("make, message", [
    (lambda: ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, failure_strain=-0.1, softening_strain=0.01),
     r"JohnsonCook\.failure_strain: must be > 0"),
    (lambda: ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, failure_strain=0.1, softening_strain=0.0),
     r"JohnsonCook\.softening_strain: must be > 0"),
    (lambda: ri.ElasticPlastic(117e9, 80e6, failure_strain=0.1), r"ElasticPlastic\.softening_strain: failure needs "
                                                                 r"both"),
    (lambda: ri.ElasticPlastic(117e9, 80e6, softening_strain=0.1), r"ElasticPlastic\.softening_strain: failure "
                                                                   r"needs both"),
])
def test_bad_failure_parameters_are_refused_by_name(make, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make()


def test_the_adjoint_refuses_a_failing_law() -> None:
    dt = 0.5e-6
    law = ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, failure_strain=0.1, softening_strain=0.01)
    inc = ri.Rod.from_impedance(np.full(10, 1.5e4), dt=dt)
    struck = ri.System.struck([inc, inc], junctions=[ri.Specimen(law, D, L0)])
    with pytest.raises(ValueError, match=r"junctions\[0\]\.law: JohnsonCook: a law with failure"):
        ImpactProblem(struck, dt, 5, 20)


def test_a_failing_law_round_trips_through_a_model_file() -> None:
    law = ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, failure_strain=0.05, softening_strain=0.01)
    bar = ri.Rod([ri.Cylinder(1.0, 0.0095)])
    text = dump_model(Model(ri.System([bar, bar], [1.0, 0.0], junctions=[ri.Specimen(law, D, L0)]), steps=3))
    assert "failure_strain" in text and "softening_strain" in text
    back = loads_model(text).system.junctions[0].law
    assert back == law
