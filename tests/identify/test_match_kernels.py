"""The matching forward model (rodimpact.identify._match_kernels): against the general solver, its numpy twin,
an energy balance, and its adjoint and tangent against central differences."""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.identify import _match_kernels as mk

N_EL = 30
DT = 2e-5
STEPS = 160


def _pile(seed: int = 0):
    rng = np.random.default_rng(seed)
    Z = 1.0e5 * np.exp(rng.normal(0.0, 0.25, N_EL))
    c = np.r_[0.0, rng.uniform(0.0, 3e3, N_EL - 1), 0.0]
    k = np.r_[0.0, rng.uniform(0.0, 2e7, N_EL - 1), 0.0]
    t = np.arange(STEPS)
    F = np.where(t < 12, -2e4 * np.sin(np.pi * (t + 0.5) / 12), 0.0) + 300.0 * rng.normal(size=STEPS) * (t < 40)
    return Z, c, k, F


def _empty(n):
    return np.empty((0, n)), np.empty((0, n)), np.empty((0, n + 1))


def _run(Z, c, k, kt, ct, fixed, F, fn=mk.forward_numba):
    return fn(Z, c, k, kt, ct, fixed, F, DT, *_empty(Z.size))


@pytest.mark.parametrize("toe", ["free", "fixed", "spring"])
def test_forward_without_shaft_soil_equals_the_general_solver(toe):
    Z, _, _, F = _pile(1)
    zero = np.zeros(N_EL + 1)
    kt, ct = (4e8, 3e4) if toe == "spring" else (0.0, 0.0)
    right = {"free": "free", "fixed": "fixed", "spring": ri.SpringEnd(stiffness=kt, damping=ct)}[toe]
    t = (np.arange(STEPS) + 0.5) * DT
    left = ri.ForceEnd(force=(t, F))
    rod = ri.Rod.from_impedance(list(Z), dt=DT)
    system = ri.System([rod], [0.0], left=left, right=right)
    res = ri.simulate(system, steps=STEPS, dt=DT)
    head = res.end_velocity["left"]          # velocity of the head along +x
    y = _run(Z, zero, zero, kt, ct, toe == "fixed", F)
    assert head.shape == y.shape
    np.testing.assert_allclose(y, head, rtol=0, atol=1e-12 * np.abs(head).max())


def test_numpy_twin_equals_numba_forward_and_adjoint():
    Z, c, k, F = _pile(2)
    for fixed in (False, True):
        st = [np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL + 1))]
        st2 = [np.empty_like(a) for a in st]
        y = mk.forward_numba(Z, c, k, 3e8, 2e4, fixed, F, DT, *st)
        y2 = mk.forward_numpy(Z, c, k, 3e8, 2e4, fixed, F, DT, *st2)
        np.testing.assert_allclose(y2, y, rtol=0, atol=1e-12 * np.abs(y).max())
        by = np.sin(np.arange(STEPS))
        g = mk.adjoint_numba(Z, c, k, 3e8, 2e4, fixed, F, DT, *st, by)
        g2 = mk.adjoint_numpy(Z, c, k, 3e8, 2e4, fixed, F, DT, *st, by)
        for a, b in zip(g, g2):
            a, b = np.atleast_1d(a), np.atleast_1d(b)
            np.testing.assert_allclose(b, a, rtol=0, atol=1e-12 * max(np.abs(a).max(), 1e-300))


@pytest.mark.parametrize("n, K", [(30, 12), (30, 29), (30, 31), (30, 59), (30, 61), (2, 9), (1, 5)])
def test_numba_kernels_equal_the_twin_when_the_record_ends_before_or_after_the_toe_echo(n, K):
    """The compiled kernels skip what lies beyond the wave front (forward) and beyond what the record can still
    see (adjoint): against the numpy twin, which runs every node of every step, on records shorter than the
    travel to the toe, about one or two travel times, and longer; stored states from NaN-filled buffers."""
    rng = np.random.default_rng(n * 100 + K)
    Z = 1.0e5 * np.exp(rng.normal(0.0, 0.25, n))
    c = np.r_[0.0, rng.uniform(0.0, 3e3, n - 1), 0.0] if n > 1 else np.zeros(2)
    k = np.r_[0.0, rng.uniform(0.0, 2e7, n - 1), 0.0] if n > 1 else np.zeros(2)
    F = -2e4 * rng.uniform(size=K)
    by = rng.normal(size=K)
    for fixed in (False, True):
        st = [np.full((K, n), np.nan), np.full((K, n), np.nan), np.full((K, n + 1), np.nan)]
        y = mk.forward_numba(Z, c, k, 3e8, 2e4, fixed, F, DT, *st)
        ref = [np.empty_like(a) for a in st]
        y2 = mk.forward_numpy(Z, c, k, 3e8, 2e4, fixed, F, DT, *ref)
        np.testing.assert_allclose(y, y2, rtol=0, atol=1e-12 * np.abs(y2).max())
        g = mk.adjoint_numba(Z, c, k, 3e8, 2e4, fixed, F, DT, *st, by)
        g2 = mk.adjoint_numpy(Z, c, k, 3e8, 2e4, fixed, F, DT, *ref, by)
        for a, b in zip(g, g2):
            a, b = np.atleast_1d(a), np.atleast_1d(b)
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-12 * max(np.abs(b).max(), 1e-300))


def test_energy_balance_with_shaft_and_toe_soil():
    """Work of the head force = element energy + spring energy + energy dissipated by the dashpots, with the
    lattice energy 1/2 dt sum(Z v^2 + N^2 / Z) (thesis eq. 3.25); exact for the midpoint spring."""
    Z, c, k, F = _pile(3)
    kt, ct = 4e8, 3e4
    st = [np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL + 1))]
    y = mk.forward_numba(Z, c, k, kt, ct, False, F, DT, *st)
    Ns, vs, us = st
    # node velocities from the stored displacements u_{s+1} = u_s + V_s dt
    V = np.diff(us, axis=0) / DT
    s = STEPS - 1
    work = np.sum(-F[:s] * y[:s]) * DT                     # head force -F pushes along +x at V_0
    kk = k.copy()
    kk[-1] = kt
    cc = c.copy()
    cc[-1] = ct
    spring = 0.5 * np.sum(kk * us[s] ** 2)
    damped = np.sum(cc * V ** 2) * DT
    energy = 0.5 * DT * np.sum(Z * vs[s] ** 2 + Ns[s] ** 2 / Z)
    assert damped > 0.05 * work and spring > 1e-4 * work
    assert abs(work - energy - spring - damped) < 1e-11 * work


def _objective(Z, c, k, kt, ct, fixed, F, d):
    return 0.5 * np.sum((_run(Z, c, k, kt, ct, fixed, F) - d) ** 2)


def _central(fun, x, i, h):
    """Central difference with one Richardson step (error O(h^4))."""
    def diff(step):
        xp, xm = x.copy(), x.copy()
        xp[i] += step
        xm[i] -= step
        return (fun(xp) - fun(xm)) / (2 * step)
    return (4.0 * diff(h) - diff(2 * h)) / 3.0


@pytest.mark.parametrize("fixed", [False, True])
def test_adjoint_gradient_equals_central_differences(fixed):
    Z, c, k, F = _pile(4)
    kt, ct = 4e8, 3e4
    d = _run(Z * 1.1, c, k, kt, ct, fixed, F) + 1e-3 * np.cos(np.arange(STEPS))
    st = [np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL + 1))]
    y = mk.forward_numba(Z, c, k, kt, ct, fixed, F, DT, *st)
    gZ, gc, gk, gkt, gct = mk.adjoint_numba(Z, c, k, kt, ct, fixed, F, DT, *st, y - d)
    f = lambda Z_=Z, c_=c, k_=k, kt_=kt, ct_=ct: _objective(Z_, c_, k_, kt_, ct_, fixed, F, d)
    checks = []
    for j in (0, 7, N_EL - 1):
        checks.append((_central(lambda x: f(Z_=x), Z, j, 1e-4 * Z[j]), gZ[j]))
    for i in (1, 15, N_EL - 1):
        checks.append((_central(lambda x: f(c_=x), c, i, 1e-2), gc[i]))
        checks.append((_central(lambda x: f(k_=x), k, i, 1e2), gk[i]))
    if not fixed:
        checks.append((_central(lambda x: f(kt_=x[0]), np.array([kt]), 0, 1e3), gkt))
        checks.append((_central(lambda x: f(ct_=x[0]), np.array([ct]), 0, 1e-1), gct))
    else:
        assert gkt == 0.0 and gct == 0.0
    for fd, ad in checks:
        assert ad != 0.0
        assert abs(fd - ad) <= 1e-6 * abs(ad), (fd, ad)


def test_tangent_rows_equal_central_differences_and_the_adjoint():
    Z, c, k, F = _pile(5)
    kt, ct = 4e8, 3e4
    P = 3
    tZ = np.zeros((P, N_EL))
    tZ[0, 4] = Z[4]
    tc = np.zeros((P, N_EL + 1))
    tc[1, 1:N_EL] = 1.0
    tk = np.zeros((P, N_EL + 1))
    tkt = np.array([0.0, 0.0, 1.0])
    tct = np.zeros(P)
    y, J = mk.tangent_numba(Z, c, k, kt, ct, False, F, DT, tZ, tc, tk, tkt, tct)
    np.testing.assert_array_equal(y, _run(Z, c, k, kt, ct, False, F))
    h = 1e-5
    fd0 = (_run(Z * np.exp(h * (np.arange(N_EL) == 4)), c, k, kt, ct, False, F)
           - _run(Z * np.exp(-h * (np.arange(N_EL) == 4)), c, k, kt, ct, False, F)) / (2 * h)
    cmask = np.r_[0.0, np.ones(N_EL - 1), 0.0]
    fd1 = (_run(Z, c + 1e-2 * cmask, k, kt, ct, False, F) - _run(Z, c - 1e-2 * cmask, k, kt, ct, False, F)) / 2e-2
    fd2 = (_run(Z, c, k, kt + 1e3, ct, False, F) - _run(Z, c, k, kt - 1e3, ct, False, F)) / 2e3
    for p, fd in enumerate((fd0, fd1, fd2)):
        scale = np.abs(J[:, p]).max()
        assert scale > 0
        np.testing.assert_allclose(J[:, p], fd, rtol=0, atol=1e-6 * scale)
    st = [np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL)), np.empty((STEPS, N_EL + 1))]
    mk.forward_numba(Z, c, k, kt, ct, False, F, DT, *st)
    r = np.cos(0.3 * np.arange(STEPS))
    gZ, gc, gk, gkt, gct = mk.adjoint_numba(Z, c, k, kt, ct, False, F, DT, *st, r)
    ref = np.array([gZ[4] * Z[4], gc[1:N_EL].sum(), gkt])
    np.testing.assert_allclose(J.T @ r, ref, rtol=1e-10)


def test_forward_with_shaft_soil_equals_the_general_solvers_linear_smith_soil():
    """Below yield (R_u far above any soil force) the Smith shaft soil with smith-viscous damping is a spring
    k = R_u / q and a dashpot c = J_sv R_u at every interior node, its spring taken as the exact mean over the step's
    path = the midpoint rule for a linear spring. Lumping (docs/soil.md): each interior node takes the half elements
    on both sides, the end half elements go to the nearest interior node (nodes 1 and n-1: 1.5 elements)."""
    Z, _, _, F = _pile(6)
    c_wave = 4000.0
    h = c_wave * DT
    unit = 1e9 / h                                  # R_u = 1e9 N per element length
    quake, j_sv = 50.0, 1e-6                        # k = 2e7 N/m, c = 1e3 N s/m per element length
    share = np.r_[0.0, 1.5, np.ones(N_EL - 3), 1.5, 0.0]
    k = share * 1e9 / quake
    c = share * 1e9 * j_sv
    t = (np.arange(STEPS) + 0.5) * DT
    rod = ri.Rod.from_impedance(list(Z), dt=DT, wave_speed=c_wave)
    shaft = ri.ShaftResistance(0, depths=[0.0, N_EL * h], unit_resistance=[unit], quake=quake, damping=j_sv,
                               damping_kind="smith-viscous")
    system = ri.System([rod], [0.0], left=ri.ForceEnd(force=(t, F)), right="free", loads=[shaft])
    head = ri.simulate(system, steps=STEPS, dt=DT).end_velocity["left"]
    y = _run(Z, c, k, 0.0, 0.0, False, F)
    assert np.abs(y - _run(Z, 0 * c, 0 * k, 0.0, 0.0, False, F)).max() > 0.05 * np.abs(y).max()   # soil matters
    np.testing.assert_allclose(y, head, rtol=0, atol=1e-12 * np.abs(head).max())
