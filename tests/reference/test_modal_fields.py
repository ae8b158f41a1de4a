"""Modal expansion fields: orthogonality, initial conditions, mode equation, energy (thesis 3.41-3.47)."""

import math

import numpy as np
import pytest
from scipy.special import roots_legendre

from rodimpact.reference import HornImpact, ModalChain, ModalSegment, STEEL_BAR_SPEED
from rodimpact.reference._entire import square_integrals

C0 = STEEL_BAR_SPEED
SETUP3 = HornImpact()
RHO, E, A0, XI = 7840.0, 210e9, 1.96e-3, 0.5


def gauss(a, b, n):
    x, w = roots_legendre(n)
    return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * w


def area(x):
    return np.where(x < 0, A0, A0 * np.exp(XI * np.clip(x, 0, None)))


def test_orthogonality_3_43_by_quadrature():
    chain = SETUP3.chain
    w = chain.eigenfrequencies(1010)
    pick = np.r_[0:40, 1000:1010]
    x1, w1 = gauss(-1.0, 0.0, 1500)
    x2, w2 = gauss(0.0, 1.0, 1500)
    u1, _ = chain.mode_shapes(x1, w[pick])
    u2, _ = chain.mode_shapes(x2, w[pick])
    gram = (u1.T * (w1 * A0)) @ u1 + (u2.T * (w2 * area(x2))) @ u2  # eq. (3.43)
    b = np.diag(gram).copy()
    off = gram / np.sqrt(np.outer(b, b)) - np.eye(pick.size)
    assert np.max(np.abs(off)) < 1e-11
    np.testing.assert_allclose(RHO * b, chain.modal_masses(w[pick]), rtol=1e-11)


def test_square_integrals_across_the_small_k2_switch():
    """Closed forms (with the series branch near k^2 = 0) against quadrature, both signs of k^2."""
    length = 0.8
    k2 = np.array([-30.0, -1e-2, -1e-6, 0.0, 1e-7, 1.5e-2, 2.0, 400.0])
    icc, ics, iss = square_integrals(k2, length)
    x, wq = gauss(0.0, length, 200)
    for j, kk in enumerate(k2):
        if kk > 0:
            c, s = np.cos(np.sqrt(kk) * x), np.sin(np.sqrt(kk) * x) / np.sqrt(kk)
        elif kk < 0:
            c, s = np.cosh(np.sqrt(-kk) * x), np.sinh(np.sqrt(-kk) * x) / np.sqrt(-kk)
        else:
            c, s = np.ones_like(x), x
        np.testing.assert_allclose([icc[j], ics[j], iss[j]], [wq @ (c * c), wq @ (c * s), wq @ (s * s)], rtol=1e-13, atol=1e-15)


def test_mode_shapes_satisfy_equation_and_conditions():
    """dU/dx = N_U/(E A) and dN_U/dx = -omega^2 rho A U (finite differences), free/fixed ends, continuity."""
    chain = SETUP3.chain
    w = chain.eigenfrequencies(300)[[0, 1, 7, 150, 299]]
    x = np.array([-0.83, -0.31, 0.12, 0.57, 0.94])
    d = 1e-6
    u, n = chain.mode_shapes(x, w)
    up, npl = chain.mode_shapes(x + d, w)
    um, nm = chain.mode_shapes(x - d, w)
    a = area(x)[:, None]
    scale_n = np.max(np.abs(n), axis=0)
    scale_u = np.max(np.abs(u), axis=0)
    np.testing.assert_allclose((up - um) / (2 * d) * E * a / scale_n, n / scale_n, atol=2e-5)
    np.testing.assert_allclose((npl - nm) / (2 * d) / (w**2 * RHO * a) / scale_u, -u / scale_u, atol=2e-5)
    ends_u, ends_n = chain.mode_shapes([-1.0, 1.0], w)
    assert np.all(np.abs(ends_n[0]) < 1e-9 * scale_n)  # free striker end (3.29)
    assert np.all(np.abs(ends_u[1]) < 1e-9 * scale_u)  # fixed horn end (3.32)
    left, right = chain.mode_shapes([-1e-13, 1e-13], w)
    np.testing.assert_allclose(left[0], left[1], rtol=1e-9, atol=1e-12)  # (3.30)
    np.testing.assert_allclose(right[0], right[1], rtol=1e-9)  # (3.31)


def test_initial_velocity_converges_in_l2_like_a_step_fourier_series():
    """v(x, 0) -> v_in in the striker, 0 in the horn; the mass-weighted L2 error of a series with a jump
    decays like N^(-1/2) and the missing energy (Parseval) like 1/N. Displacement at t = 0 is exactly 0."""
    sol = SETUP3.solve(1000)
    x1, w1 = gauss(-1.0, 0.0, 2500)
    x2, w2 = gauss(0.0, 1.0, 2500)
    ns = np.array([62, 125, 250, 500, 1000])
    err, missing = [], []
    for n in ns:
        s = sol.truncated(int(n))
        e2 = w1 @ (RHO * A0 * (s.velocity(x1, 0.0) - 6.0) ** 2) + w2 @ (RHO * area(x2) * s.velocity(x2, 0.0) ** 2)
        err.append(math.sqrt(e2))
        missing.append(s.initial_kinetic_energy - s.captured_energy)
    slope_err = np.polyfit(np.log(ns), np.log(err), 1)[0]
    slope_missing = np.polyfit(np.log(ns), np.log(missing), 1)[0]
    assert -0.55 < slope_err < -0.45
    assert -1.05 < slope_missing < -0.95
    assert np.all(np.diff(err) < 0)
    # Parseval: 1/2 * (mass-weighted L2 error)^2 is exactly the energy not carried by the series
    np.testing.assert_allclose(0.5 * np.array(err) ** 2, missing, rtol=1e-9)
    assert sol.initial_kinetic_energy == pytest.approx(0.5 * RHO * A0 * 1.0 * 36.0, rel=1e-14)
    assert np.all(sol.displacement(np.r_[x1, x2], 0.0) == 0.0)


def test_fields_are_mutually_consistent_and_conserve_energy():
    """v = du/dt, N = E A du/dx (finite differences of the truncated series), and kinetic + strain energy at
    t > 0 equals the energy carried by the series (modes orthogonal in mass and stiffness)."""
    sol = SETUP3.solve(300)
    t = 0.29e-3
    x = np.array([-0.7, -0.2, 0.3, 0.8])
    dt, dx = 1e-9, 1e-6
    v_fd = (sol.displacement(x, t + dt) - sol.displacement(x, t - dt)) / (2 * dt)
    np.testing.assert_allclose(v_fd, sol.velocity(x, t), rtol=1e-5, atol=1e-5)
    n_fd = E * area(x) * (sol.displacement(x + dx, t) - sol.displacement(x - dx, t)) / (2 * dx)
    np.testing.assert_allclose(n_fd, sol.force(x, t), rtol=1e-5, atol=1.0)
    x1, w1 = gauss(-1.0, 0.0, 1500)
    x2, w2 = gauss(0.0, 1.0, 1500)
    energy = 0.0
    for xs, ws in ((x1, w1), (x2, w2)):
        v, nn = sol.velocity(xs, t), sol.force(xs, t)
        energy += 0.5 * ws @ (RHO * area(xs) * v**2 + nn**2 / (E * area(xs)))
    assert energy == pytest.approx(sol.captured_energy, rel=1e-10)


def test_time_arrays_and_shapes():
    sol = SETUP3.solve(50)
    t = np.array([0.0, 1e-4, 2e-4])
    x = np.linspace(-1, 1, 7)
    full = sol.force(x, t)
    assert full.shape == (7, 3)
    np.testing.assert_allclose(full[:, 1], sol.force(x, 1e-4), rtol=1e-14)
    assert sol.force(0.0, t).shape == (3,)
    with pytest.raises(ValueError, match="x"):
        sol.force(1.5, 0.0)


def test_free_free_chain_keeps_the_rigid_mode():
    """Two equal uniform rods, free-free, striker at v: momentum m v is shared; the centre of mass moves at v/2
    and the mean velocity of the series is exactly v/2 at every time (elastic modes carry no momentum)."""
    seg = ModalSegment.uniform(0.5, 1e-3)
    sol = ModalChain((seg, seg), "free", "free", origin=-0.5).expand((4.0, 0.0), 3000)
    assert sol.rigid_velocity == pytest.approx(2.0, rel=1e-12)
    x, w = gauss(-0.5, 0.5, 3000)
    for t in (0.0, 0.7e-4, 1.9e-4):
        assert w @ sol.velocity(x, t) == pytest.approx(2.0, rel=1e-10)
    # equal impedances: the contact force is -Z v / 2 while the rods touch (t < 2 L / c)
    z = RHO * C0 * 1e-3
    ts = np.linspace(0.2, 0.8, 7) * 2 * 0.5 / C0  # away from the jumps at t = 0 and 2 L / c (Gibbs)
    np.testing.assert_allclose(sol.force(0.0, ts), -z * 4.0 / 2, rtol=1e-3)
