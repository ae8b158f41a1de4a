"""Exact gradients through law joints (specimens, pulse shapers; docs/adjoint.md, "Law joints").

The adjoint gradient of ImpactProblem through a specimen equals central finite differences of the forward model
(to 1e-6 relative) for each differentiated law in its elastic and plastic regimes and with the compression-only
lift-off; the law Jacobians equal finite differences of law_stress in each branch; numba and numpy agree; the
strain-rate objective's seeds are checked the same way; tabulated laws are refused."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.design._joint_adjoint import law_jacobian
from rodimpact.design.objectives import StrainRateCost
from rodimpact.direct.joints import law_stress

DT = 0.5e-6
Z_BAR = 1.5e4
L0, D0 = 3e-3, 6e-3
H = 1e-5            # relative finite-difference step (as test_adjoint_gradient.py; the Cowper-Symonds forward's
                    # rounding noise needs it: its FD error grows as 1/H below, 1.4e-6 at H = 1e-6)
LAWS = {
    "elastic": ri.LinearElastic(117e9),
    "plastic": ri.ElasticPlastic(117e9, 90e6, 500e6),
    "johnson-cook": ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, 0.025, 1.0, 1.09),
    "cowper-symonds": ri.CowperSymonds(200e9, 250e6, 40.4, 5.0, 1e9),
    "frew": ri.FrewShaper(360e6, 0.3, 2.0),
}
# impact velocities: elastic regime (the specimen's stress stays below yield) and plastic regime (several % strain)
ELASTIC_V, PLASTIC_V = 0.02, 10.0


def problem(law, steps, measure="true", backend="numba", n=12):
    inc = ri.Rod.from_impedance(np.full(30, Z_BAR), dt=DT)
    tr = ri.Rod.from_impedance(np.full(30, Z_BAR), dt=DT)
    if isinstance(law, ri.FrewShaper):
        joint = ri.PulseShaper(law, D0, L0)
    else:
        joint = ri.Specimen(law, D0, L0, measure=measure)
    struck = ri.System.struck([inc, tr], junctions=[joint])
    return ImpactProblem(struck, DT, n, steps, backend=backend)


def objective(pb, seed=0):
    """J = 1e-4 sum w_k s_k^2 + 1e-12 sum u_k F_k^2: the specimen's shortening rate s_k (from the shortening
    history) and the face force F_k, random positive weights; returns J(z, v) and its adjoint gradient."""
    rng = np.random.default_rng(seed)
    w = rng.uniform(0.5, 1.5, pb.steps)
    u = rng.uniform(0.5, 1.5, pb.steps)

    def run(z, v):
        fw = pb.forward(z, v)
        s = np.diff(fw.shortening[1], prepend=0.0) / DT
        return 1e-4 * float(np.sum(w * s * s)) + 1e-12 * float(np.sum(u * fw.observed ** 2)), fw, s

    def grad(z, v):
        _, fw, s = run(z, v)
        c = 2e-4 * w * s / DT
        seed_d = c.copy()
        seed_d[:-1] -= c[1:]
        shortening = np.zeros((2, pb.steps))
        shortening[1] = seed_d
        return pb.gradient(fw, observed=2e-12 * u * fw.observed, shortening=shortening), fw
    return (lambda z, v: run(z, v)[0]), grad


def central(J, z, v):
    fd = np.empty(z.size)
    for q in range(z.size):
        h = H * z[q]
        zp, zm = z.copy(), z.copy()
        zp[q] += h
        zm[q] -= h
        fd[q] = (J(zp, v) - J(zm, v)) / (2 * h)
    return fd, (J(z, v * (1 + H)) - J(z, v * (1 - H))) / (2 * H * v)


def striker(n=12, seed=0):
    rng = np.random.default_rng(seed)
    return Z_BAR * rng.uniform(0.6, 1.4, n)


def check(pb, v, seed=0):
    z = striker(pb.n, seed)
    J, grad = objective(pb, seed)
    (dz, dv), fw = grad(z, v)
    fd, fdv = central(J, z, v)
    assert np.max(np.abs(dz - fd)) <= 1e-6 * np.max(np.abs(fd))
    assert abs(dv - fdv) <= 1e-6 * abs(fdv)
    return fw


def lifted_off(fw):
    """Steps after the specimen's first load in which the compression-only joint carries exactly nothing."""
    force = fw.junction_force[1]
    return int(np.sum(force[np.flatnonzero(force < 0.0)[0]:] == 0.0))


@pytest.mark.parametrize("name", ["plastic", "johnson-cook", "cowper-symonds", "elastic"])
@pytest.mark.parametrize("measure", ["true", "engineering"])
def test_plastic_regime_and_lift_off(name, measure):
    """Large strains (plastic flow for the plastic laws), then the pulse passes and the compression-only
    specimen lifts off (steps with no force after the load: 32 to 92 of the 200 in these runs)."""
    law = LAWS[name]
    fw = check(problem(law, 200, measure), PLASTIC_V)
    if name != "elastic":
        yield_strain = law.yield_stress / law.youngs_modulus if name != "johnson-cook" else law.a / law.youngs_modulus
        assert fw.shortening[1].max() / L0 > 10 * yield_strain     # well into the plastic regime
    assert lifted_off(fw) > 10


@pytest.mark.parametrize("name", ["plastic", "johnson-cook", "cowper-symonds"])
def test_elastic_regime(name):
    law = LAWS[name]
    fw = check(problem(law, 90), ELASTIC_V)
    y = law.yield_stress if name != "johnson-cook" else law.a
    assert 0.0 < fw.shortening[1].max() / L0 < 0.9 * y / law.youngs_modulus
    assert lifted_off(fw) == 0                                      # loaded throughout this short run


def test_frew_shaper_loading_and_unloading():
    """A Frew shaper: loading to several % strain, unloading along the steeper of E and the tangent, lift-off."""
    fw = check(problem(LAWS["frew"], 200), PLASTIC_V)
    d = fw.shortening[1]
    assert d.max() / L0 > 0.02 and d[-1] < d.max() and lifted_off(fw) > 10


def test_lift_off_branch_is_taken():
    """An elastic compression-only specimen whose faces open after the pulse (shortening < 0: no force)."""
    fw = check(problem(LAWS["elastic"], 160, "engineering", n=6), PLASTIC_V)
    assert fw.shortening[1].min() < 0.0 and lifted_off(fw) > 10


@pytest.mark.parametrize("code_name,eps,rate,q", [
    ("plastic", 0.05, 3000.0, (0.03, 0.03, 0.0)),          # plastic branch
    ("plastic", 0.031, 3000.0, (0.03, 0.03, 0.0)),         # elastic branch
    ("plastic", -0.02, -3000.0, (0.03, 0.03, 0.0)),        # reversed yielding
    ("johnson-cook", 0.05, 3000.0, (0.03, 0.04, 0.0)),     # plastic, rate factor active
    ("johnson-cook", 0.05, 0.5, (0.03, 0.04, 0.0)),        # plastic, below the reference rate
    ("johnson-cook", 0.0301, 3000.0, (0.03, 0.04, 0.0)),   # elastic
    ("cowper-symonds", 0.05, 300.0, (0.03, 0.03, 0.0)),
    ("cowper-symonds", 0.0301, 300.0, (0.03, 0.03, 0.0)),
    ("elastic", 0.01, 100.0, (0.0, 0.0, 0.0)),
    ("frew", 0.1, 100.0, (0.0, 0.0, 0.05)),                # loading beyond the largest strain
    ("frew", 0.985, 100.0, (0.0, 0.0, 0.99)),              # unloading along the tangent (steeper than E)
    ("frew", 0.048, 100.0, (0.0, 0.0, 0.05)),              # unloading along E
])
def test_law_jacobian_equals_finite_differences(code_name, eps, rate, q):
    law = LAWS[code_name]
    p = law.kernel()
    jac = np.zeros((4, 5))
    x0 = np.array([eps, rate, *q])

    def value(x):
        out = law_stress(law.code, p, x[0], x[1], np.array([*x[2:], 0.0, 0.0]))
        return np.array(out)

    sigma = law_jacobian(law.code, p, eps, rate, np.array([*q, 0.0, 0.0]), jac)
    assert sigma == value(x0)[0]
    for j in range(5):
        h = 1e-7 * max(abs(x0[j]), 1e-3)
        xp, xm = x0.copy(), x0.copy()
        xp[j] += h
        xm[j] -= h
        fd = (value(xp) - value(xm)) / (2 * h)
        scale = np.array([law.youngs_modulus, 1.0, 1.0, 1.0])       # stresses in units of E
        err = np.max(np.abs(fd - jac[:, j]) / scale)
        assert err <= 1e-6 * max(np.max(np.abs(fd) / scale), 1e-9), (j, fd, jac[:, j])


def test_numpy_agrees_with_numba():
    for name in ("johnson-cook", "frew"):
        grads = []
        for backend in ("numba", "numpy"):
            pb = problem(LAWS[name], 80, "engineering" if name == "frew" else "true", backend, n=8)
            _, grad = objective(pb)
            grads.append(grad(striker(8), PLASTIC_V)[0])
        assert np.allclose(grads[0][0], grads[1][0], rtol=1e-10, atol=0.0)
        assert grads[0][1] == pytest.approx(grads[1][1], rel=1e-10)


def test_checkpoints_do_not_change_the_gradient():
    z = striker()
    out = []
    for c in (1, 7, None):
        inc = ri.Rod.from_impedance(np.full(30, Z_BAR), dt=DT)
        struck = ri.System.struck([inc, inc], junctions=[ri.Specimen(LAWS["johnson-cook"], D0, L0)])
        pb = ImpactProblem(struck, DT, 12, 100, checkpoint_every=c)
        _, grad = objective(pb)
        out.append(grad(z, PLASTIC_V)[0])
    for dz, dv in out[1:]:
        assert np.array_equal(dz, out[0][0]) and dv == out[0][1]


def test_strain_rate_cost_seeds():
    """StrainRateCost's value and seeds: its adjoint gradient equals central differences."""
    pb = problem(LAWS["johnson-cook"], 100)
    cost = StrainRateCost(1, 2, L0, 2500.0, np.arange(40, 95), DT, 100)
    z = striker()

    def J(zz, v):
        return cost.evaluate(pb.forward(zz, v), zz, v)[0]
    fw = pb.forward(z, PLASTIC_V)
    _, seeds, _, _ = cost.evaluate(fw, z, PLASTIC_V)
    dz, dv = pb.gradient(fw, **seeds)
    fd, fdv = central(J, z, PLASTIC_V)
    assert np.max(np.abs(dz - fd)) <= 1e-6 * np.max(np.abs(fd))
    assert abs(dv - fdv) <= 1e-6 * abs(fdv)


def test_tabulated_law_is_refused():
    law = ri.TabulatedLaw(117e9, plastic_strain=[0.0, 1.0], stress=[[90e6, 300e6]])
    inc = ri.Rod.from_impedance(np.full(10, Z_BAR), dt=DT)
    struck = ri.System.struck([inc, inc], junctions=[ri.Specimen(law, D0, L0)])
    with pytest.raises(ValueError, match="junctions\\[0\\].law: TabulatedLaw: a tabulated law"):
        ImpactProblem(struck, DT, 5, 20)


def test_shortening_seed_needs_a_law_joint():
    pb = ImpactProblem(ri.System.struck(ri.Rod.from_impedance(np.full(10, Z_BAR), dt=DT)), DT, 5, 20)
    fw = pb.forward(np.full(5, Z_BAR), 1.0)
    assert fw.shortening is None
    with pytest.raises(ValueError, match="shortening: the system has no law joint"):
        pb.gradient(fw, shortening=np.zeros((0, 20)))


def one_step(par, x, dt=DT):
    """One law-joint step as rodimpact.direct.boundary.boundaries takes it, from x = (f_a, g_a, f_b, g_b, Z_a,
    Z_b, delta, ep, alpha, em): y = (N, V_a, V_b, delta', ep', alpha', em')."""
    from rodimpact.direct.joints import joint_solve

    fa, ga, fb, gb, za, zb, delta = x[:7]
    va_free = (ga - fa) / za - (fa + ga) / za
    vb_free = (gb - fb) / zb + (fb + gb) / zb
    q = np.array([*x[7:10], 0.0, 0.0])
    n = joint_solve(par, q, 1.0 / za + 1.0 / zb, va_free - vb_free, delta, dt)
    va, vb = va_free + n / za, vb_free - n / zb
    return np.array([n, va, vb, delta + (va - vb) * dt, q[0], q[1], q[2]])


def joint_par(law, measure="true"):
    pb = problem(law, 4, "engineering" if isinstance(law, ri.FrewShaper) else measure, n=2)
    return np.ascontiguousarray(pb._arrays["junction_par"][1])


@pytest.mark.parametrize("name,measure,speed,ep,em,branch", [
    ("plastic", "true", 10.0, 0.025, 0.03, "flow"),
    ("plastic", "engineering", -3.0, 0.0297, 0.03, "elastic"),   # unloading inside the yield surface
    ("johnson-cook", "true", 10.0, 0.025, 0.03, "flow"),
    ("johnson-cook", "engineering", 10.0, 0.025, 0.03, "flow"),
    ("johnson-cook", "true", -3.0, 0.0297, 0.03, "elastic"),
    ("cowper-symonds", "true", 10.0, 0.025, 0.03, "flow"),
    ("elastic", "true", 10.0, 0.0, 0.0, "elastic"),
    ("frew", "engineering", 10.0, 0.0, 0.03, "loading"),         # beyond the largest strain
    ("frew", "engineering", -3.0, 0.0, 0.0305, "elastic"),       # unloading
    ("plastic", "true", -30.0, 0.029, 0.03, "lifted"),           # the faces open
])
def test_one_joint_step_transpose_equals_finite_differences(name, measure, speed, ep, em, branch):
    """joint_vjp is the transpose of one joint step's Jacobian, all inputs (waves, both bar impedances,
    shortening, state) against central differences of the step, for a random adjoint of its outputs (the bar
    impedances do not enter a striker's gradient, so only this test sees their terms)."""
    from rodimpact.design._joint_adjoint import joint_vjp, scratch_array

    par = joint_par(LAWS[name], measure)
    z = Z_BAR
    # a compressive wave f_a arriving from the incident side (free face velocity `speed`), some g_a and f_b
    x = np.array([-0.5 * z * speed, 123.0, -77.0, 40.0, z, 1.3 * z, 0.03 * L0, ep, ep, em])
    y = one_step(par, x)
    lam = np.random.default_rng(7).uniform(-1.0, 1.0, 7) * np.array([1e-3, 1e2, 1e2, 1e6, 1.0, 1.0, 1.0])
    lstate = lam[3:].copy()
    dfa, dgb, dza, dzb = joint_vjp(par, np.array([*x[7:], 0.0, 0.0]), y[0], *x[:7], DT, lam[0], lam[1], lam[2],
                                   lstate, scratch_array())
    adjoint = np.array([dfa, 0.0, 0.0, dgb, dza, dzb, *lstate])     # g_a and f_b cancel from the free velocities
    fd = np.empty(10)
    for j in range(10):
        h = 1e-6 * max(abs(x[j]), 1e-3 if j >= 7 else 1e-6 * L0 if j == 6 else 1.0)
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        fd[j] = lam @ (one_step(par, xp) - one_step(par, xm)) / (2 * h)
    scale = np.abs(fd * np.maximum(np.abs(x), 1e-12)).max()         # compare d(J)/d(log x): one scale for all
    assert np.all(np.abs((adjoint - fd) * np.maximum(np.abs(x), 1e-12)) <= 1e-6 * scale), (adjoint, fd)
    flows = y[4] != x[7]                                             # eps_p changed
    assert (branch == "lifted") == (y[0] == 0.0) and flows == (branch == "flow")
    assert (y[6] != x[9]) == (branch == "loading")                   # a new largest strain (Frew)
