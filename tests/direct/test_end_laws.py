"""End laws of the direct solver against closed forms derived by hand (not from the implementation).

Setting of every test: a uniform rod of impedance Z (travel time T_rod = n dt) at rest; its left end is a
:class:`~rodimpact.ForceEnd` whose force history launches a force wave f(t) towards the right end, where it
arrives after T_rod. Write the right-end force as N = f + g (g the reflected wave) and the outward end velocity
as w = (g - f) / Z (d'Alembert, tension positive); eliminating g gives the **end relation**

    N = 2 f + Z w,                                                            (*)

which together with the device law gives an ordinary differential equation for the end displacement delta
(delta' = w). The reflected wave returns to the left end after 2 T_rod; the tests stop before anything
reflected there can come back (3 T_rod). The lattice reports the end force of step k (held on
[k dt, (k+1) dt)); it is compared with the closed form at the step midpoint, t = (k - n + 1/2) dt after the
wave's arrival (the spring law is the implicit midpoint rule).
"""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri

Z = 40.0e3            # N s/m
T = 100e-6            # s: travel time of the rod and duration of the rectangular waves
F_I = 1000.0          # N: magnitude of the incident (compressive) force wave
REFINEMENTS = (25, 50, 100, 200, 400)


def run_right_end(n: int, right: ri.EndCondition, incident) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Rod of n elements (travel time T); returns (t since arrival at the step midpoints, end force, outward
    end velocity, dt) over the 2 T after the incident wave reaches the right end."""
    dt = T / n
    rod = ri.Rod.from_impedance(np.full(n, Z), dt=dt)
    res = ri.simulate(ri.System([rod], [0.0], left=ri.ForceEnd(incident), right=right), steps=3 * n)
    force = res.end_force["right"]
    assert np.all(force[:n] == 0.0)                      # nothing arrives before the travel time
    t = (np.arange(2 * n) + 0.5) * dt
    return t, force[n:3 * n], res.end_velocity["right"][n:3 * n], dt


def order(ns, errors) -> float:
    """Convergence order: minus the slope of log(error) against log(n) (least squares)."""
    return -float(np.polyfit(np.log(ns), np.log(errors), 1)[0])


# ------------------------------------------------------------------------------------------ spring (dashpot)
def spring_step_response(t: np.ndarray, k: float, c: float, f: float) -> np.ndarray:
    """Step wave f (constant from t = 0) on a spring k with a parallel dashpot c.

    Device: N = -(k delta + c delta'). With (*): (Z + c) delta' + k delta = -2 f, delta(0) = 0, so
    delta = -(2 f / k) (1 - exp(-t/tau)) with tau = (Z + c)/k, and
    N = 2 f [1 - Z/(Z + c) exp(-t/tau)]: at t = 0 the dashpot alone reflects with (c - Z)/(c + Z)
    (N = 2 f c/(Z + c)), for t >> tau the spring holds like a fixed end (N = 2 f).
    """
    tau = (Z + c) / k
    return 2 * f * (1.0 - Z / (Z + c) * np.exp(-t / tau))


@pytest.mark.parametrize("c", [0.0, 30e3], ids=["spring", "spring-dashpot"])
def test_spring_end_step_response_converges_at_second_order(c):
    k = (Z + c) / (T / 3)                 # time constant T/3: the response settles within the window
    errors = []
    for n in REFINEMENTS:
        t, force, _, _ = run_right_end(n, ri.SpringEnd(k, c), -F_I)
        errors.append(np.max(np.abs(force - spring_step_response(t, k, c, -F_I))) / F_I)
    p = order(REFINEMENTS, errors)
    assert p == pytest.approx(2.0, abs=0.1), errors
    # the error constant of the dt^2 law is the same at every refinement (no stagnation, no pre-asymptotic luck)
    scaled = np.asarray(errors) * np.asarray(REFINEMENTS) ** 2
    assert np.ptp(scaled) < 0.15 * np.mean(scaled), scaled
    assert errors[-1] < 2e-5


def test_spring_end_energy_bookkeeping_is_exact():
    """The midpoint spring force makes the spring energy k delta^2 / 2 at the end of the run equal the work
    sum(-N w dt) done on the spring (no dashpot), to rounding; delta = sum(w dt)."""
    n = 100
    k = Z / (T / 3)
    t, force, w, dt = run_right_end(n, ri.SpringEnd(k), -F_I)
    delta = np.sum(w) * dt
    assert np.sum(-force * w) * dt == pytest.approx(0.5 * k * delta**2, rel=1e-12)


# ------------------------------------------------------------------------------------------ bit-rock
def bitrock_loading_unloading(t: np.ndarray, k1: float, k2: float) -> np.ndarray:
    """End force for a rectangular incident wave -F_I on [0, T) into the bilinear rock (hand calculation).

    Loading (0 <= t < T), F = k1 delta: with (*) and N = -F, Z delta' = 2 F_I - k1 delta, so
    delta = (2 F_I / k1)(1 - exp(-k1 t / Z)) grows up to delta_m = delta(T) (delta' > 0 throughout).
    Unloading (t >= T, no incident wave): F = k1 delta_m + k2 (delta - delta_m) and Z delta' = -F, so
    F decays as k1 delta_m exp(-k2 (t - T) / Z), reaching zero only asymptotically (no lift-off).
    """
    dm = 2 * F_I / k1 * (1.0 - np.exp(-k1 * T / Z))
    return np.where(t < T, -2 * F_I * (1.0 - np.exp(-k1 * t / Z)), -k1 * dm * np.exp(-k2 * (t - T) / Z))


def rectangular(t):
    return np.where(t < T, -F_I, 0.0)


def test_bitrock_loading_and_unloading_against_hand_calculation():
    """Unloading three times stiffer than loading (k2 = 3 k1). The bit-rock end converges at first order
    today (the switch from loading to unloading falls inside a step); the test asserts the measured order and
    that the finest error is what that order predicts from the coarsest, not a fixed loose tolerance."""
    k1 = Z / T
    k2 = 3.0 * k1
    errors = []
    for n in REFINEMENTS:
        t, force, _, _ = run_right_end(n, ri.BitRockEnd(k1, k2), rectangular)
        errors.append(np.max(np.abs(force - bitrock_loading_unloading(t, k1, k2))) / F_I)
    p = order(REFINEMENTS, errors)
    assert p >= 0.9, errors
    assert errors[-1] <= errors[0] * (REFINEMENTS[0] / REFINEMENTS[-1]) ** 0.9, errors
    # the onset: in the first step after arrival the force is -2 F_I (1 - exp(-k1 t/Z)) ~ -2 F_I k1 t / Z at the
    # step midpoint t = dt/2, to a relative O(k1 dt / Z) (the midpoint rule gives -2 F_I k1 h/(Z + k1 h), h = dt/2)
    for n in REFINEMENTS:
        t, force, _, dt = run_right_end(n, ri.BitRockEnd(k1, k2), rectangular)
        onset = bitrock_loading_unloading(t[:1], k1, k2)[0]
        assert abs(force[0] - onset) <= 0.5 * k1 * dt / Z * abs(onset), n
    # the unloading slope is visible: with k2 = k1 the force 2 T after arrival would be 3 x larger than this
    t, force, _, _ = run_right_end(REFINEMENTS[-1], ri.BitRockEnd(k1, k2), rectangular)
    late = bitrock_loading_unloading(t[-1:], k1, k2)[0]
    assert force[-1] == pytest.approx(late, rel=0.01)
    assert bitrock_loading_unloading(t[-1:], k1, k1)[0] / late > 3.0


def test_bitrock_lifts_off_when_a_tensile_wave_follows():
    """Incident -F_I on [0, T) then +F_I on [T, 2T). Unloading (t >= T): Z delta' = -2 F_I - F with
    F = k1 delta_m + k2 (delta - delta_m), so F = (F_T + 2 F_I) exp(-k2 (t - T)/Z) - 2 F_I (F_T = k1 delta_m)
    until F = 0 at t_r = T + (Z/k2) ln((F_T + 2 F_I)/(2 F_I)); then the bit is off the rock: N = 0, no
    tension (the force never pulls the bit)."""
    k1, k2 = Z / T, 4.0 * Z / T
    n = 400
    t, force, _, dt = run_right_end(n, ri.BitRockEnd(k1, k2), lambda s: np.where(s < T, -F_I, np.where(s < 2 * T, F_I, 0.0)))
    f_t = 2 * F_I * (1.0 - np.exp(-k1 * T / Z))
    t_r = T + Z / k2 * np.log((f_t + 2 * F_I) / (2 * F_I))
    exact = np.where(t < T, -2 * F_I * (1.0 - np.exp(-k1 * t / Z)),
                     np.where(t < t_r, -((f_t + 2 * F_I) * np.exp(-k2 * (t - T) / Z) - 2 * F_I), 0.0))
    assert np.all(force <= 0.0)
    off = t > t_r + dt
    assert np.all(force[off] == 0.0)
    # first order at the loading-unloading switch (see the previous test): measured 0.28 dt / tau_2 at
    # n = 100 .. 800 (tau_2 = Z / k2, the unloading time constant)
    assert np.max(np.abs(force - exact)) / F_I < 0.5 * dt * k2 / Z


@pytest.mark.parametrize("x", [0.5, 1.26, 3.0])
def test_bitrock_efficiency_matches_lundberg_closed_form(x):
    """Lundberg's efficiency of a rectangular wave into a loading-only rock, eta(x) = 2 (1 - e^-x)^2 / x.

    Derivation: rock F = k delta, incident rectangular force wave of magnitude F_I and duration T in a rod of
    impedance Z. While the wave arrives, (*) with N = -F gives Z delta' + k delta = 2 F_I, so
    delta = (2 F_I/k)(1 - exp(-k t/Z)); after T, Z delta' = -k delta < 0, hence the maximum penetration is
    delta_m = (2 F_I/k)(1 - e^-x) with x = k T/Z. The work done on the rock up to then is k delta_m^2 / 2
    = 2 F_I^2 (1 - e^-x)^2 / k, and the incident wave carries F_I^2 T / Z (force wave energy f^2/Z per unit
    time), so eta = 2 (1 - e^-x)^2 Z/(k T) = 2 (1 - e^-x)^2 / x. On the lattice: work = sum(-N w dt) over the
    steps up to the largest penetration sum(w dt).
    """
    k = x * Z / T
    eta_exact = 2 * (1 - np.exp(-x)) ** 2 / x
    errors = []
    for n in REFINEMENTS:
        _, force, w, dt = run_right_end(n, ri.BitRockEnd(k), rectangular)
        k_max = int(np.argmax(np.cumsum(w)))
        eta = np.sum(-force[:k_max + 1] * w[:k_max + 1]) * dt / (F_I**2 * T / Z)
        errors.append(abs(eta - eta_exact))
    assert order(REFINEMENTS, errors) >= 0.9, errors
    assert errors[-1] <= errors[0] * (REFINEMENTS[0] / REFINEMENTS[-1]) ** 0.9, errors
    assert errors[-1] < 1e-5 * eta_exact        # measured: 5e-7 .. 1.5e-6 at n = 400


# ------------------------------------------------------------------------------------------ non-reflecting
@pytest.mark.parametrize("z_end", [10e3, 40e3, 160e3])
def test_nonreflecting_end_with_its_own_impedance_reflects_with_the_impedance_ratio(z_end):
    """A continuation of impedance Z_end reflects R = (Z_end - Z)/(Z_end + Z) and carries the end force
    (1 + R) f; exact on the lattice (piecewise-constant impedance)."""
    n = 50
    rod = ri.Rod.from_impedance(np.full(n, Z), dt=T / n)
    probe = ri.Probe("mid", 0, rod.length / 2)
    res = ri.simulate(ri.System([rod], [0.0], left=ri.ForceEnd(rectangular), right=ri.NonReflectingEnd(z_end)),
                      steps=2 * n, outputs=ri.Outputs(probes=[probe]))
    r = (z_end - Z) / (z_end + Z)
    end = res.end_force["right"]
    np.testing.assert_allclose(end[n:2 * n], (1 + r) * -F_I, rtol=1e-12)
    # the midpoint sees the incident wave on [T/2, 3T/2) and, after it has passed, the reflected one alone
    mid = res.probe("mid").force
    np.testing.assert_allclose(mid[3 * n // 2:2 * n], r * -F_I, rtol=1e-12)
    np.testing.assert_allclose(mid[n // 2:n], -F_I, rtol=1e-12)


def test_nonreflecting_end_leaves_a_uniformly_moving_rod_alone():
    """The continuation is in the initial state of the end element: a rod moving uniformly at v (any end
    impedance) stays unstressed; with an end that ignored the motion the force would be Z_end v / 2 or so."""
    rod = ri.Rod.from_impedance(np.full(30, Z), dt=T / 30)
    res = ri.simulate(ri.System([rod], [3.0], left=ri.NonReflectingEnd(2 * Z), right=ri.NonReflectingEnd(Z / 3)),
                      steps=90)
    assert np.max(np.abs(res.end_force["left"])) <= 1e-12 * Z * 3.0
    assert np.max(np.abs(res.end_force["right"])) <= 1e-12 * Z * 3.0
    np.testing.assert_allclose(res.final_velocity, 3.0, rtol=1e-12)
