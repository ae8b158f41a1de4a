"""Deformable joints between two rods (specimens, pulse shapers): the constitutive laws of
:mod:`rodimpact.rods.laws` compiled, and the per-step solution of a joint, shared by every compiled solver
through :func:`rodimpact.direct.boundary.boundaries`.

A joint joins the right face of rod i (last element a, impedance z_a) and the left face of rod i + 1 (first
element b). It is massless, so both faces carry the same normal force N (tension positive). During a step the
faces obey their characteristics (thesis eqs. 3.16-3.19), V_a = V_a^free + N / z_a and V_b = V_b^free - N / z_b,
so the joint's shortening rate is linear in N, s(N) = mu N + s0 with mu = 1/z_a + 1/z_b and s0 = V_a^free -
V_b^free, and its shortening runs linearly through the step from delta_k. The element's law is evaluated at the
step's midpoint (implicit midpoint rule for the shortening and the internal variables, second order):

    g(N) = N + F(delta_k + s(N) dt / 2, s(N), q_k) = 0,

F >= 0 in compression. F does not decrease with the shortening and its rate for every law here, so g increases
strictly and the root is unique; it is bracketed (below) and found by the Illinois variant of regula falsi with
bisection steps (never diverges), to a bracket of a few ulps.

Strain measures (``par[6]``): engineering, strain eps = delta / L0, rate s / L0, force F = sigma A0; or true
(large strain, incompressible flow): the law sees eps_t = -ln(1 - eps) and rate (s / L0) / (1 - eps), and the
force is F = sigma A0 / (1 - eps).

The functions are compiled on their own, not inlined into the step loops: inlining the nested law calls
multiplied the first run's compile time (50 s more CPU for the first example), and a joint costs one call per
step.

Failure (:class:`rodimpact.rods.laws.Failure`): a plastic law with a failure strain eps_f > 0 (``p[8]``) gives
the stress (1 - w) sigma_law with the softening w(alpha) = min(1, max(0, (alpha - eps_f) / p[9])). Within a step
w is LAGGED: taken at the accumulated plastic strain alpha_k of the step's start, and updated with the state after
the step. A softening law evaluated at the midpoint would let F fall as the shortening grows, and g(N) could have
several roots; with w fixed during the step F is (1 - w_k) times a non-decreasing function and the root stays
unique. The lag costs one order: the force is first order in dt once softening has started (measured in
tests/direct/test_joint_failure.py). The damage dissipation (w_k+1 - w_k) E (eps_k+1 - eps_p,k+1)^2 / 2 A0 L0 is
booked per step (the elastic energy released by the softening), so that the work the joint absorbs is the stored
energy (1 - w) E eps_e^2 / 2 A0 L0, the plastic work and the damage work.

Array layout per joint r: ``junction_par[r]`` = (k, c, compression_only, law code, L0, A0, true measure, 0,
then the law's vector :meth:`rodimpact.rods.laws.Law.kernel`: parameters p0..p9 (p8, p9 the failure) and, for a
tabulated law, its table; the array is as wide as the widest law of the system); ``junction_q[r]`` = (eps_p, alpha, eps_max,
plastic work, crushed, damage work): the plastic strain, the accumulated plastic strain, the largest strain
reached (loading curves), the plastic work done so far, J (sigma dEps_p V0 in the law's strain measure), 1 once the
shortening has reached the body's length (the run is then refused, :func:`rodimpact.direct.result.joint_outcomes`),
and the damage dissipation so far, J (failure, above).
"""

from __future__ import annotations

import math

from numba import njit

from ..rods.laws import ELASTIC, FAILURE_STRAIN, FREW, JOHNSON_COOK, N_PARAMS, PLASTIC, SOFTENING_STRAIN, TABULATED

#: columns of ``junction_par`` before the law's vector, and of ``junction_q``
HEADER_COLUMNS, STATE_COLUMNS = 8, 6


@njit(error_model="numpy", cache=True)
def softening(code, p, alpha):
    """The softening w in [0, 1] of a failing plastic law at accumulated plastic strain ``alpha``: 0 before the
    failure strain p[8] (and for a law without failure, p[8] = 0), rising linearly to 1 over the softening strain
    p[9]; the stress is (1 - w) times the law's."""
    if code == ELASTIC or code == FREW or p[FAILURE_STRAIN] <= 0.0:
        return 0.0
    return min(1.0, max(0.0, (alpha - p[FAILURE_STRAIN]) / p[SOFTENING_STRAIN]))


@njit(error_model="numpy", cache=True)
def _interpolate(x, xs, ys):
    """Linear interpolation of (xs, ys) at x, held constant beyond the ends (xs increasing)."""
    if x <= xs[0]:
        return ys[0]
    n = xs.size
    if x >= xs[n - 1]:
        return ys[n - 1]
    lo = 0
    hi = n - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    w = (x - xs[lo]) / (xs[hi] - xs[lo])
    return ys[lo] + w * (ys[hi] - ys[lo])


@njit(error_model="numpy", cache=True)
def tabulated_flow(p, alpha, rate):
    """Flow stress of a tabulated law (Pa): each rate's curve interpolated in the plastic strain, then between
    the rates linearly in log(rate) (held beyond the first and last rate). Table layout after the N_PARAMS
    parameters (p[1] points, p[2] rates): rates, plastic strains, stresses rate by rate."""
    n_points = int(p[1])
    n_rates = int(p[2])
    rates = p[N_PARAMS:N_PARAMS + n_rates]
    strains = p[N_PARAMS + n_rates:N_PARAMS + n_rates + n_points]
    stress = p[N_PARAMS + n_rates + n_points:N_PARAMS + n_rates + n_points * (n_rates + 1)]
    if n_rates == 1 or rate <= rates[0]:
        return _interpolate(alpha, strains, stress[:n_points])
    if rate >= rates[n_rates - 1]:
        return _interpolate(alpha, strains, stress[(n_rates - 1) * n_points:])
    j = 0
    while rates[j + 1] < rate:
        j += 1
    low = _interpolate(alpha, strains, stress[j * n_points:(j + 1) * n_points])
    high = _interpolate(alpha, strains, stress[(j + 1) * n_points:(j + 2) * n_points])
    w = math.log(rate / rates[j]) / math.log(rates[j + 1] / rates[j])
    return low + w * (high - low)


@njit(error_model="numpy", cache=True)
def flow_stress(code, p, alpha, rate):
    """Yield stress of the plastic laws, Pa, at accumulated plastic strain ``alpha`` and |strain rate| ``rate``."""
    if code == PLASTIC:
        return p[1] + p[2] * alpha
    if code == TABULATED:
        return tabulated_flow(p, alpha, rate)
    if code == JOHNSON_COOK:
        r = rate / p[5]
        factor = 1.0 + p[4] * math.log(r) if r > 1.0 else 1.0
        return (p[1] + p[2] * alpha ** p[3]) * factor * p[6]
    # COWPER_SYMONDS (the last plastic law)
    return (p[1] + p[2] * alpha) * (1.0 + (rate / p[3]) ** (1.0 / p[4]))


@njit(error_model="numpy", cache=True)
def frew_loading(p, eps):
    """Frew-Forrestal-Chen loading curve sigma_0 eps^n / (1 - eps^m), Pa (0 for eps <= 0, inf for eps >= 1)."""
    if eps <= 0.0:
        return 0.0
    if eps >= 1.0:
        return math.inf
    return p[1] * eps ** p[2] / (1.0 - eps ** p[3])


@njit(error_model="numpy", cache=True)
def frew_tangent(p, eps):
    """Slope of the Frew-Forrestal-Chen loading curve at ``eps`` (0 < eps < 1), Pa."""
    if eps <= 0.0:
        return 0.0
    if eps >= 1.0:
        return math.inf
    em = eps ** p[3]
    return p[1] * (p[2] * eps ** (p[2] - 1.0) * (1.0 - em) + p[3] * eps ** (p[2] + p[3] - 1.0)) / (1.0 - em) ** 2


@njit(error_model="numpy", cache=True)
def law_stress(code, p, eps, rate, q):
    """Stress (Pa, compression positive) at strain ``eps`` and rate ``rate`` starting from the state ``q``, and
    the state at that point: (sigma, eps_p, alpha, eps_max). Plastic laws: return mapping (backward Euler from
    q to this point), sigma = E (eps - eps_p) within |sigma| <= sigma_y(alpha, r), with r the strain rate in the
    direction of the stress (r = max(sign(sigma) rate, 0): a body being unloaded flows at the static yield stress).
    With that r the stress does not decrease with the strain and its rate, so a joint's equation stays monotone;
    taking |rate| instead made an unloading specimen's flow stress rise with the unloading speed.
    Frew: unloading from the largest strain eps_max along the steeper of E and the loading curve's tangent at
    eps_max (elastic unloading along E alone would give back more work than the steep loading near lock-up put
    in)."""
    e_mod = p[0]
    if code == ELASTIC:
        return e_mod * eps, q[0], q[1], q[2]
    if code == FREW:
        if eps >= q[2]:
            return frew_loading(p, eps), q[0], q[1], eps
        slope = max(e_mod, frew_tangent(p, q[2]))
        return max(0.0, frew_loading(p, q[2]) - slope * (q[2] - eps)), q[0], q[1], q[2]
    trial = e_mod * (eps - q[0])
    sign = 1.0 if trial > 0.0 else -1.0
    flow_rate = max(sign * rate, 0.0)
    excess = abs(trial) - flow_stress(code, p, q[1], flow_rate)
    if excess <= 0.0:
        return trial, q[0], q[1], q[2]
    if code == PLASTIC:
        d = excess / (e_mod + p[2])
    else:   # f(d) = |trial| - E d - sigma_y(alpha + d) decreases from excess > 0 to <= 0 at |trial| / E
        lo = 0.0
        hi = abs(trial) / e_mod
        for _ in range(200):
            d = 0.5 * (lo + hi)
            if not lo < d < hi:                 # adjacent doubles: the bisection cannot go further
                break
            if abs(trial) - e_mod * d - flow_stress(code, p, q[1] + d, flow_rate) > 0.0:
                lo = d
            else:
                hi = d
        d = 0.5 * (lo + hi)
    return trial - sign * e_mod * d, q[0] + sign * d, q[1] + d, q[2]


@njit(error_model="numpy", cache=True)
def joint_point(par, q, n, mu, s0, delta, dt):
    """The joint at face force ``n``: (F, sigma, eps_p, alpha, eps_max, strain) at the step's midpoint, F the
    compressive force (>= 0 where the joint acts in compression only) and strain in the law's measure."""
    s = mu * n + s0
    e = (delta + 0.5 * dt * s) / par[4]
    rate = s / par[4]
    area = par[5]
    if par[6] != 0.0:                       # true measures, incompressible flow
        if e >= 1.0:
            return math.inf, math.inf, q[0], q[1], q[2], math.inf
        rate = rate / (1.0 - e)
        area = area / (1.0 - e)
        e = -math.log1p(-e)
    code = int(par[3])
    if par[2] != 0.0 and (e <= q[0] if code != FREW else e <= 0.0):
        return 0.0, 0.0, q[0], q[1], q[2], e   # compression only: the faces have lifted off the specimen
    sigma, ep, al, em = law_stress(code, par[HEADER_COLUMNS:], e, rate, q)
    sigma *= 1.0 - softening(code, par[HEADER_COLUMNS:], q[1])     # lagged: the damage of the step's start
    f = sigma * area
    if par[2] != 0.0 and f < 0.0:
        return 0.0, 0.0, q[0], q[1], q[2], e
    return f, sigma, ep, al, em, e


@njit(error_model="numpy", cache=True)
def joint_solve(par, q, mu, s0, delta, dt):
    """Solve g(N) = N + F(N) = 0 for the face force N of one step (see the module docstring) and advance the
    state ``q`` in place to the end of the step (implicit midpoint: q_k+1 = 2 q_mid - q_k; the largest strain
    to the midpoint's, where the law was evaluated; the plastic work by sigma_mid (eps_p,k+1 - eps_p,k) A0 L0;
    the crushed flag when the shortening at the end of the step reaches L0; the damage work by (w_k+1 - w_k)
    E eps_e,k+1^2 / 2 A0 L0, eps_e the elastic strain, 0 where a compression-only body is in tension). Returns N."""
    f0 = joint_point(par, q, 0.0, mu, s0, delta, dt)[0]
    if f0 == 0.0:
        n = 0.0
    else:
        if f0 > 0.0:
            hi = 0.0
            # below this force the faces open (delta_mid <= 0) and a compression-only joint carries nothing
            lo = -f0 if f0 < math.inf else min((-2.0 * delta / dt - s0) / mu, 0.0) - 1.0
            g_lo = lo + joint_point(par, q, lo, mu, s0, delta, dt)[0]
            g_hi = f0
            for _ in range(100):            # a safeguard: for the laws here g(-F(0)) <= 0 already
                if g_lo <= 0.0:
                    break
                lo = 2.0 * lo - 1.0
                g_lo = lo + joint_point(par, q, lo, mu, s0, delta, dt)[0]
        else:
            lo = 0.0
            hi = -f0
            g_lo = f0
            g_hi = hi + joint_point(par, q, hi, mu, s0, delta, dt)[0]
            for _ in range(100):            # true measures in tension: the area shrinks, F may fall as N rises
                if g_hi >= 0.0:
                    break
                hi = 2.0 * hi + 1.0
                g_hi = hi + joint_point(par, q, hi, mu, s0, delta, dt)[0]
        n = hi if g_hi == 0.0 else lo
        side = 0
        for _ in range(200):
            if g_lo == 0.0 or g_hi == 0.0 or hi - lo <= 4e-16 * max(abs(lo), abs(hi)):
                break
            x = (lo * g_hi - hi * g_lo) / (g_hi - g_lo) if math.isfinite(g_hi) and math.isfinite(g_lo) \
                else 0.5 * (lo + hi)
            if not lo < x < hi:
                x = 0.5 * (lo + hi)
            gx = x + joint_point(par, q, x, mu, s0, delta, dt)[0]
            if gx > 0.0:
                hi, g_hi = x, gx
                if side == 1:
                    g_lo *= 0.5             # Illinois: halve the retained end so the bracket shrinks on both sides
                side = 1
            else:
                lo, g_lo = x, gx
                if side == -1:
                    g_hi *= 0.5
                side = -1
            n = x
    f, sigma, ep, al, em, e_mid = joint_point(par, q, n, mu, s0, delta, dt)
    ep_new = 2.0 * ep - q[0]
    q[3] += sigma * (ep_new - q[0]) * par[4] * par[5]
    q[0] = ep_new
    code = int(par[3])
    w_old = softening(code, par[HEADER_COLUMNS:], q[1])
    q[1] = 2.0 * al - q[1]
    w_new = softening(code, par[HEADER_COLUMNS:], q[1])
    if w_new != w_old:
        e_end = (delta + dt * (mu * n + s0)) / par[4]
        if par[6] != 0.0:
            e_end = -math.log1p(-e_end) if e_end < 1.0 else math.inf
        elastic = e_end - q[0]
        if par[2] != 0.0 and elastic < 0.0:
            elastic = 0.0
        q[5] += (w_new - w_old) * 0.5 * par[HEADER_COLUMNS] * elastic * elastic * par[4] * par[5]
    q[2] = em                       # the largest strain at which the law was evaluated (a midpoint)
    if delta + dt * (mu * n + s0) >= par[4]:
        q[4] = 1.0                  # crushed: the shortening reached the body's length (checked after the run)
    return n
