"""Closed forms: hand values and agreement with each other where they overlap."""

import math

import numpy as np
import pytest

import rodimpact.reference as rr

Z = 79.7e3  # N s/m, thesis Tab. 4.2
V = 6.0
T = 1.93e-4  # s


def test_uniform_equal_impedance_is_a_rectangle_of_half_zv():
    t = np.array([-1e-9, 0.0, 0.5 * T, 1.999 * T, 2.0 * T, 3 * T, 50 * T])
    f = rr.uniform_striker_force(t, Z, Z, T, V)
    np.testing.assert_array_equal(f, [0, -Z * V / 2, -Z * V / 2, -Z * V / 2, 0, 0, 0])


def test_uniform_unequal_impedance_hand_values():
    t = np.array([0.1, 1.9, 2.1, 3.9, 4.1, 6.1, 8.1]) * T
    # Z1 = 3 Z2: N0 = -3/4 Z2 v, r = 1/2 (staircase, never separates)
    f = rr.uniform_striker_force(t, 3 * Z, Z, T, V)
    n0 = -0.75 * Z * V
    np.testing.assert_allclose(f, n0 * np.array([1, 1, 0.5, 0.5, 0.25, 0.125, 0.0625]), rtol=1e-15)
    # Z1 = Z2/3: N0 = -Z2 v / 4 for 2 T, then the striker rebounds
    g = rr.uniform_striker_force(t, Z / 3, Z, T, V)
    np.testing.assert_allclose(g, [-Z * V / 4, -Z * V / 4, 0, 0, 0, 0, 0], rtol=1e-15)


@pytest.mark.parametrize("eps", [1e-3, 1e-6, 1e-9])
def test_unequal_formula_tends_to_the_equal_case(eps):
    t = np.linspace(0, 20 * T, 401)
    equal = rr.uniform_striker_force(t, Z, Z, T, V)
    for z1 in (Z * (1 + eps), Z * (1 - eps)):
        np.testing.assert_allclose(rr.uniform_striker_force(t, z1, Z, T, V), equal, atol=2 * eps * Z * V)


def test_infinitely_stiff_rod_gives_the_wall_force():
    t = np.linspace(0, 6 * T, 61)
    wall = rr.rod_against_wall_force(t, Z, T, V)
    np.testing.assert_allclose(rr.uniform_striker_force(t, Z, 1e12 * Z, T, V), wall, rtol=1e-11, atol=1e-6)
    np.testing.assert_array_equal(wall[t < 2 * T], -Z * V)
    np.testing.assert_array_equal(wall[t >= 2 * T], 0.0)


def test_wall_fields_by_hand_and_at_the_wall():
    length, c = 1.0, 5000.0
    x = np.array([-1.0, -0.75, -0.5, -0.25, 0.0])
    n, v = rr.rod_against_wall_fields(x, 0.3 / c, Z, length, c, V)  # loading front at s = 0.3
    np.testing.assert_array_equal(n, [0, 0, 0, -Z * V, -Z * V])
    np.testing.assert_array_equal(v, [V, V, V, 0, 0])
    n, v = rr.rod_against_wall_fields(x, 1.6 / c, Z, length, c, V)  # unloading front at s = 0.4
    np.testing.assert_array_equal(n, [0, 0, 0, -Z * V, -Z * V])
    np.testing.assert_array_equal(v, [-V, -V, -V, 0, 0])
    for tt in np.linspace(0, 2.5, 11) * length / c:
        assert rr.rod_against_wall_fields(0.0, tt, Z, length, c, V)[0] == rr.rod_against_wall_force(tt, Z, length / c, V)


def test_stepped_striker_with_one_or_two_equal_steps_is_uniform():
    t = (np.arange(3000) + 0.5) * 0.01 * T  # no sample exactly on a jump instant 2 k T
    for z1 in (0.4 * Z, Z, 2.5 * Z):
        uniform = rr.uniform_striker_force(t, z1, Z, T, V)
        np.testing.assert_allclose(rr.stepped_striker_force(t, [z1], T, Z, V), uniform, rtol=1e-13, atol=1e-9)
        two = rr.stepped_striker_force(t, [z1, z1], [0.3 * T, 0.7 * T], Z, V)
        np.testing.assert_allclose(two, uniform, rtol=1e-12, atol=1e-7)


def test_two_step_striker_hand_calculation():
    """Face piece Z_b = Z (tau_b = 4 tau), back piece Z_a = 2 Z (tau): N0 = -Z v/2 on [0, 8 tau); the wave
    trapped in the back piece then returns every 2 tau, each time weakened by R_ab = -1/3:
    N = -(2/3)(1/3)^(k-1) Z v on [8 tau + 2 k tau, 10 tau + 2 k tau) (T_ba T_ab = 8/9, T_face = 1, R_ba = 1/3)."""
    tau = 1e-5
    t = np.array([0.5, 7.9, 8.1, 9.9, 10.1, 11.9, 12.1, 13.9, 14.1]) * tau
    f = rr.stepped_striker_force(t, [2 * Z, Z], [tau, 4 * tau], Z, V)
    zv = Z * V
    np.testing.assert_allclose(f, [-zv / 2, -zv / 2, -2 * zv / 3, -2 * zv / 3, -2 * zv / 9, -2 * zv / 9,
                                   -2 * zv / 27, -2 * zv / 27, -2 * zv / 81], rtol=1e-13)
    # impulse = striker momentum (Z_a tau + Z_b tau_b) v: the striker comes to rest
    tt = np.linspace(0, 200 * tau, 200001)
    impulse = np.sum(rr.stepped_striker_force(tt[:-1], [2 * Z, Z], [tau, 4 * tau], Z, V)) * (tt[1] - tt[0])
    assert -impulse == pytest.approx(6 * Z * tau * V, rel=1e-4)


def test_rigid_mass_hand_value_and_staircase_limit():
    """A uniform striker of mass M = Z1 T1 becomes rigid as T1 -> 0. With eps = Z T1 / M the staircase
    N0 r^k (N0 = -Z v/(1 + eps), r = (1 - eps)/(1 + eps)) deviates from -Z v exp(-Z t/M) by at most
    eps Z v (1 + O(eps)): at the start of each step by +eps, at its end by -eps (to first order)."""
    m = 2.0
    assert rr.rigid_mass_force(m / Z, m, Z, V) == pytest.approx(-Z * V / math.e, rel=1e-15)
    t = np.linspace(0, 3 * m / Z, 30001)
    exact = rr.rigid_mass_force(t, m, Z, V)
    for t1 in (1e-6, 5e-7, 2.5e-7, 1.25e-7):
        eps = Z * t1 / m
        stair = rr.uniform_striker_force(t, m / t1, Z, t1, V)
        err = np.max(np.abs(stair - exact)) / (Z * V)
        assert abs(err / eps - 1) < 2 * eps  # first order exact, O(eps^2) remainder


def test_lundberg_lesser_reproduces_thesis_table_4_3():
    """Thesis Tab. 4.2/4.3: Z_rod = 79.7 kN s/m, N_hat = 239 kN, t0 = 0.383 ms, dt = 1.93 us, v = 6 m/s.
    Rows q = 10..90 of the printed Z_q (3 digits, apparently truncated) are eq. (4.26) at theta = q dt.
    (Row q = 1 prints Z_rod; row q = 100 prints 19.9 where eq. 4.26 gives 19.76 at q dt and 19.96 at
    (q - 1) dt - see docs/validation-reference.md.)"""
    dt = 1.93e-6
    q = np.array([10, 20, 30, 40, 50, 60, 70, 80, 90])
    printed = np.array([65.7, 55.1, 46.9, 40.4, 35.2, 30.9, 27.3, 24.4, 21.9]) * 1e3
    zq = rr.lundberg_lesser_impedance(q * dt, 79.7e3, 239e3, 0.383e-3, 6.0)
    assert np.all(zq - printed >= -0.005e3) and np.all(zq - printed < 0.1e3)
    assert rr.lundberg_lesser_face_impedance(79.7e3, 239e3, 6.0) == pytest.approx(1 / (6 / 239e3 - 1 / 79.7e3))
    # N_hat = Z_rod v / 2 (the printed 239 kN is 239.1 rounded) gives Z0 = Z_rod exactly
    assert rr.lundberg_lesser_face_impedance(79.7e3, 79.7e3 * 3, 6.0) == pytest.approx(79.7e3, rel=1e-14)


def test_lundberg_lesser_striker_gives_exponential_force():
    """Independent check of eq. (4.26): sample Z(theta) at the middle of n equal travel-time steps and compute
    the exact force of that stepped striker. It is constant on windows [2 k dth, 2 (k+1) dth) and matches
    -N_hat exp(-t/t0) at the window middles with an O(dth^2) error, for t < 2 Theta."""
    zr, nh, t0, v = 79.7e3, 239e3, 0.383e-3, 6.0
    theta_total = 0.2e-3
    errs, ns = [], np.array([50, 100, 200, 400])
    for n in ns:
        dth = theta_total / n
        mid = (np.arange(n) + 0.5) * dth  # travel time from the face to the step's middle
        t = (2 * np.arange(int(0.95 * n)) + 1) * dth  # window middles up to 1.9 Theta
        f = rr.stepped_striker_force(t, rr.lundberg_lesser_impedance(mid, zr, nh, t0, v)[::-1], dth, zr, v)
        errs.append(np.max(np.abs(f - rr.lundberg_lesser_force(t, nh, t0))) / nh)
    slope = np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert errs[-1] < 1e-7
    assert -2.1 < slope < -1.9


def test_bad_input_names_the_quantity():
    with pytest.raises(ValueError, match="striker_impedance"):
        rr.uniform_striker_force(0.0, -1.0, Z, T, V)
    with pytest.raises(ValueError, match="peak_force"):
        rr.lundberg_lesser_face_impedance(Z, 2 * Z * V, V)
    with pytest.raises(ValueError, match="impedances"):
        rr.stepped_striker_force([0.0], [Z, 0.0], T, Z, V)
    with pytest.raises(ValueError, match="theta"):
        rr.lundberg_lesser_impedance(-1.0, Z, 1e3, 1e-4, V)
    with pytest.raises(TypeError, match="mass"):
        rr.rigid_mass_force(0.0, "two kg", Z, V)
    with pytest.raises(ValueError, match="mass: expected a quantity in kg"):     # units are accepted, if right
        rr.rigid_mass_force(0.0, "2 m", Z, V)


def test_stepped_striker_needs_one_travel_time_per_step():
    with pytest.raises(ValueError, match=r"travel_times: one per impedance \(2\) or a single value"):
        rr.stepped_striker_force([1e-5], [4e4, 3e4], [1e-5] * 3, 4e4, 5.0)
