"""Exact derivatives of one law-joint step (:func:`rodimpact.direct.joints.joint_solve`) for the reverse sweep of
the lattice (docs/adjoint.md, "Law joints").

The forward step of joint r (faces a | b): free face velocities V_a^free = -2 f_a / Z_a and V_b^free = 2 g_b / Z_b,
shortening rate s(N) = mu N + s0 (mu = 1/Z_a + 1/Z_b, s0 = V_a^free - V_b^free), and the face force N solves

    g(N) = N + F(s(N), delta_k, q_k) = 0,

F the compressive force of the law at the step's midpoint (strain e = (delta_k + s dt/2) / L0, rate s / L0; with
true measures the law sees -ln(1 - e), the rate (s / L0) / (1 - e) and the area A0 / (1 - e)). Outputs of the step:
N, the face velocities V_a = V_a^free + N / Z_a, V_b = V_b^free - N / Z_b, delta_k+1 = delta_k + s dt and the state
q_k+1 = (2 ep_mid - ep_k, 2 alpha_mid - alpha_k, em_mid) with (ep_mid, alpha_mid, em_mid) = Q(s, delta_k, q_k) the
law's state at the midpoint. At the converged root, implicit differentiation gives

    dN = -(F_s (ds0 + N dmu) + F_delta ddelta + F_q dq) / (1 + mu F_s),

and :func:`joint_vjp` applies the transpose of the whole step. :func:`law_jacobian` holds the partial derivatives
of each law (elastic; elastic-plastic with its return mapping in the elastic and the plastic branch; Johnson-Cook
with its rate factor; Cowper-Symonds; Frew loading and unloading); :func:`point_jacobian` chains them through the
strain measure and the compression-only lift-off. Tabulated laws (and user functions sampled into tables) are
refused by :class:`~rodimpact.design._adjoint.ImpactProblem`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..direct.joints import HEADER_COLUMNS, flow_stress, frew_loading, frew_tangent, law_stress
from ..rods.laws import COWPER_SYMONDS, ELASTIC, FREW, JOHNSON_COOK, PLASTIC, TABULATED

#: law codes whose derivatives :func:`law_jacobian` knows
DIFFERENTIATED = (ELASTIC, PLASTIC, JOHNSON_COOK, COWPER_SYMONDS, FREW)
#: the law codes refused by the adjoint (piecewise-linear tables in strain and log rate)
NOT_DIFFERENTIATED = (TABULATED,)
#: rows of the law Jacobian (sigma, ep, alpha, eps_max) and its columns (eps, rate, q0, q1, q2)
LAW_ROWS, LAW_COLS = 4, 5


@njit(error_model="numpy", cache=True)
def flow_partials(code, p, alpha, rate):
    """(sigma_y, d sigma_y / d alpha, d sigma_y / d rate) of the plastic laws of
    :func:`rodimpact.direct.joints.flow_stress` (not the tabulated one):

    * elastic-plastic: sigma_y = Y + H alpha, (H, 0);
    * Johnson-Cook: sigma_y = (A + B alpha^n) phi(r) theta, phi = 1 + C ln(r / r0) for r > r0 (else 1):
      (B n alpha^(n-1) phi theta, (A + B alpha^n) theta C / r for r > r0, else 0);
    * Cowper-Symonds: sigma_y = (Y + H alpha)(1 + (r / D)^(1/q)): (H (1 + (r/D)^(1/q)),
      (Y + H alpha) (r / D)^(1/q) / (q r) for r > 0, else 0).
    """
    if code == PLASTIC:
        return p[1] + p[2] * alpha, p[2], 0.0
    if code == JOHNSON_COOK:
        r = rate / p[5]
        factor = 1.0 + p[4] * math.log(r) if r > 1.0 else 1.0
        d_factor = p[4] / rate if r > 1.0 else 0.0
        base = p[1] + p[2] * alpha ** p[3]
        if alpha > 0.0:
            d_base = p[2] * p[3] * alpha ** (p[3] - 1.0)
        else:
            d_base = p[2] if p[3] == 1.0 else (0.0 if p[3] > 1.0 else math.inf)
        return base * factor * p[6], d_base * factor * p[6], base * d_factor * p[6]
    # COWPER_SYMONDS
    base = p[1] + p[2] * alpha
    enh = (rate / p[3]) ** (1.0 / p[4]) if rate > 0.0 else 0.0
    d_rate = base * enh / (p[4] * rate) if rate > 0.0 else 0.0
    return base * (1.0 + enh), p[2] * (1.0 + enh), d_rate


@njit(error_model="numpy", cache=True)
def frew_curvature(p, eps):
    """Second derivative of the Frew loading curve L = sigma_0 e^n / (1 - e^m) (0 < e < 1): with
    P = n e^(n-1) + (m - n) e^(n+m-1) (so that L' = sigma_0 P / w^2, w = 1 - e^m),
    L'' = sigma_0 (P' w + 2 m e^(m-1) P) / w^3, P' = n (n-1) e^(n-2) + (m-n)(n+m-1) e^(n+m-2)."""
    if eps <= 0.0 or eps >= 1.0:
        return 0.0
    n = p[2]
    m = p[3]
    w = 1.0 - eps ** m
    pp = n * eps ** (n - 1.0) + (m - n) * eps ** (n + m - 1.0)
    dp = n * (n - 1.0) * eps ** (n - 2.0) + (m - n) * (n + m - 1.0) * eps ** (n + m - 2.0)
    return p[1] * (dp * w + 2.0 * m * eps ** (m - 1.0) * pp) / (w * w * w)


@njit(error_model="numpy", cache=True)
def law_jacobian(code, p, eps, rate, q, jac):
    """Stress of :func:`rodimpact.direct.joints.law_stress` at (eps, rate) from the state q = (ep, alpha, em), and
    in ``jac`` (4 x 5) the derivatives of (sigma, ep, alpha, em) after the point with respect to
    (eps, rate, q0, q1, q2), in the branch law_stress takes (same expressions, so the same decisions):

    * elastic: sigma = E eps;
    * Frew loading (eps >= em): sigma = L(eps), em' = eps; unloading: sigma = L(em) - S (em - eps),
      S = max(E, L'(em)), so d sigma / d eps = S, d sigma / d em = L'(em) - S - S'(em) (em - eps) with
      S' = L''(em) where the tangent is the steeper; 0 where the unloading line has reached sigma = 0;
    * plastic laws, trial = E (eps - ep), elastic branch: sigma = trial; plastic branch: the increment d solves
      |trial| - E d - sigma_y(alpha + d, r) = 0 (r = max(sign(trial) rate, 0)), so
      dd = (sign E (deps - dep) - sigma_y,alpha dalpha - sigma_y,r dr) / (E + sigma_y,alpha) with sigma_y's
      partials at alpha + d; then sigma = trial - sign E d, ep' = ep + sign d, alpha' = alpha + d, em' = em.
    """
    e_mod = p[0]
    jac[:, :] = 0.0
    jac[1, 2] = 1.0
    jac[2, 3] = 1.0
    jac[3, 4] = 1.0
    if code == ELASTIC:
        jac[0, 0] = e_mod
        return e_mod * eps
    if code == FREW:
        if eps >= q[2]:
            jac[0, 0] = frew_tangent(p, eps)
            jac[3, 0] = 1.0
            jac[3, 4] = 0.0
            return frew_loading(p, eps)
        tangent = frew_tangent(p, q[2])
        slope = max(e_mod, tangent)
        value = frew_loading(p, q[2]) - slope * (q[2] - eps)
        if value <= 0.0:
            return 0.0
        d_slope = frew_curvature(p, q[2]) if tangent > e_mod else 0.0
        jac[0, 0] = slope
        jac[0, 4] = tangent - slope - d_slope * (q[2] - eps)
        return value
    trial = e_mod * (eps - q[0])
    sign = 1.0 if trial > 0.0 else -1.0
    flow_rate = max(sign * rate, 0.0)
    excess = abs(trial) - flow_stress(code, p, q[1], flow_rate)
    if excess <= 0.0:
        jac[0, 0] = e_mod
        jac[0, 2] = -e_mod
        return trial
    sigma, ep, al, em = law_stress(code, p, eps, rate, q)
    _, s_alpha, s_rate = flow_partials(code, p, al, flow_rate)
    d_rate = sign if sign * rate > 0.0 else 0.0          # d flow_rate / d rate
    den = e_mod + s_alpha
    dd_eps = sign * e_mod / den
    dd_q0 = -sign * e_mod / den
    dd_q1 = -s_alpha / den
    dd_rate = -s_rate * d_rate / den
    jac[0, 0] = e_mod - sign * e_mod * dd_eps
    jac[0, 1] = -sign * e_mod * dd_rate
    jac[0, 2] = -e_mod - sign * e_mod * dd_q0
    jac[0, 3] = -sign * e_mod * dd_q1
    jac[1, 0] = sign * dd_eps
    jac[1, 1] = sign * dd_rate
    jac[1, 2] = 1.0 + sign * dd_q0
    jac[1, 3] = sign * dd_q1
    jac[2, 0] = dd_eps
    jac[2, 1] = dd_rate
    jac[2, 2] = dd_q0
    jac[2, 3] = 1.0 + dd_q1
    return sigma


@njit(error_model="numpy", cache=True)
def point_jacobian(par, q, n, mu, s0, delta, dt, jac, out):
    """The joint at face force ``n`` (as :func:`rodimpact.direct.joints.joint_point`): fills ``out`` (4 x 5) with
    the derivatives of (F, ep_mid, alpha_mid, em_mid) with respect to (s, delta, q0, q1, q2), s = mu n + s0 the
    shortening rate, through the strain measure (engineering: e = (delta + s dt/2) / L0, rate s / L0, area A0;
    true: e_t = -ln(1 - e), rate_t = rate / (1 - e), area A0 / (1 - e)). Where the compression-only joint has
    lifted off (F = 0, state unchanged) only the identity of the state remains. ``jac`` is scratch (4 x 5)."""
    out[:, :] = 0.0
    out[1, 2] = 1.0
    out[2, 3] = 1.0
    out[3, 4] = 1.0
    length = par[4]
    s = mu * n + s0
    e = (delta + 0.5 * dt * s) / length
    rate = s / length
    area = par[5]
    e_s = 0.5 * dt / length                 # d e / d s, d e / d delta, d rate / d s, d rate / d delta
    e_d = 1.0 / length
    r_s = 1.0 / length
    r_d = 0.0
    a_s = 0.0
    a_d = 0.0
    if par[6] != 0.0:
        if e >= 1.0:
            return
        w = 1.0 - e
        rate_eng = rate
        rate = rate / (1.0 - e)
        area = area / (1.0 - e)
        e = -math.log1p(-e)
        r_s = r_s / w + rate_eng / (w * w) * e_s
        r_d = rate_eng / (w * w) * e_d
        a_s = par[5] / (w * w) * e_s
        a_d = par[5] / (w * w) * e_d
        e_s = e_s / w
        e_d = e_d / w
    code = int(par[3])
    if par[2] != 0.0 and (e <= q[0] if code != FREW else e <= 0.0):
        return
    sigma = law_jacobian(code, par[HEADER_COLUMNS:], e, rate, q, jac)
    if par[2] != 0.0 and sigma * area < 0.0:
        return
    out[0, 0] = area * (jac[0, 0] * e_s + jac[0, 1] * r_s) + sigma * a_s
    out[0, 1] = area * (jac[0, 0] * e_d + jac[0, 1] * r_d) + sigma * a_d
    for i in range(1, 4):
        out[i, 0] = jac[i, 0] * e_s + jac[i, 1] * r_s
        out[i, 1] = jac[i, 0] * e_d + jac[i, 1] * r_d
    for j in range(3):
        for i in range(4):
            out[i, 2 + j] = jac[i, 2 + j] * (area if i == 0 else 1.0)


@njit(error_model="numpy", cache=True)
def joint_vjp(par, q, n, fa, ga, fb, gb, za, zb, delta, dt, ln, lva, lvb, lstate, scratch):
    """Transpose of one law-joint step (module docstring). ``q``: the joint's state before the step (not
    changed); ``n`` the face force the forward step found (recorded, so the root is not solved again); waves f_a, g_a (element a left of the joint) and f_b, g_b (element b right of it) before the step;
    ``delta`` the shortening before the step. Adjoints in: ln = dJ/dN, lva = dJ/dV_a, lvb = dJ/dV_b and
    ``lstate`` = dJ/d(delta, ep, alpha, em) after the step, which it overwrites with dJ/d(the same) before the
    step. Returns (dJ/df_a, dJ/dg_b, dJ/dZ_a, dJ/dZ_b). ``scratch``: (8, 5), rows 0-3 the law's Jacobian, 4-7
    the point's.

    With c = (2, 2, 1) (q' = 2 Q - q for ep, alpha; em' = Q_em): l_s = dt l_delta' + sum_i c_i l_qi' Q_i,s,
    l_N = ln + lva / Z_a - lvb / Z_b + mu l_s, lambda = l_N / (1 + mu F_s); then l_s0 = l_s - lambda F_s,
    l_mu = N l_s0, l_delta = l_delta' + sum_i c_i l_qi' Q_i,delta - lambda F_delta, l_qj = sum_i c_i l_qi' Q_i,qj
    - [j < 2] l_qj' - lambda F_qj, and through V^free: l_fa = -2 (lva + l_s0) / Z_a, l_gb = 2 (lvb - l_s0) / Z_b."""
    # the forward's expressions (rodimpact.direct.boundary.boundaries), so that s = mu N + s0 and with it every
    # branch decision of the law is the forward's to the bit
    na = fa + ga
    va = (ga - fa) / za
    nb = fb + gb
    vb = (gb - fb) / zb
    va_free = va - na / za
    vb_free = vb + nb / zb
    s0 = va_free - vb_free
    mu = 1.0 / za + 1.0 / zb
    jac = scratch[0:4]
    out = scratch[4:8]
    point_jacobian(par, q, n, mu, s0, delta, dt, jac, out)
    ld_new = lstate[0]
    lq0 = lstate[1]
    lq1 = lstate[2]
    lq2 = lstate[3]
    # explicit paths of s and delta into delta' and q'
    ls = dt * ld_new + 2.0 * lq0 * out[1, 0] + 2.0 * lq1 * out[2, 0] + lq2 * out[3, 0]
    ld = ld_new + 2.0 * lq0 * out[1, 1] + 2.0 * lq1 * out[2, 1] + lq2 * out[3, 1]
    lqs0 = 2.0 * lq0 * out[1, 2] + 2.0 * lq1 * out[2, 2] + lq2 * out[3, 2] - lq0
    lqs1 = 2.0 * lq0 * out[1, 3] + 2.0 * lq1 * out[2, 3] + lq2 * out[3, 3] - lq1
    lqs2 = 2.0 * lq0 * out[1, 4] + 2.0 * lq1 * out[2, 4] + lq2 * out[3, 4]
    # s = mu N + s0, then the root N(s0, mu, delta, q)
    l_n = ln + lva / za - lvb / zb + mu * ls
    lam = l_n / (1.0 + mu * out[0, 0])
    l_s0 = ls - lam * out[0, 0]
    l_mu = n * l_s0
    lstate[0] = ld - lam * out[0, 1]
    lstate[1] = lqs0 - lam * out[0, 2]
    lstate[2] = lqs1 - lam * out[0, 3]
    lstate[3] = lqs2 - lam * out[0, 4]
    l_vaf = lva + l_s0
    l_vbf = lvb - l_s0
    # V_a = V_a^free + N / Z_a, V_a^free = -2 f_a / Z_a; V_b = V_b^free - N / Z_b, V_b^free = 2 g_b / Z_b;
    # mu = 1 / Z_a + 1 / Z_b
    lza = -n * lva / (za * za) - l_mu / (za * za) + 2.0 * fa * l_vaf / (za * za)
    lzb = n * lvb / (zb * zb) - l_mu / (zb * zb) - 2.0 * gb * l_vbf / (zb * zb)
    return -2.0 * l_vaf / za, 2.0 * l_vbf / zb, lza, lzb


def law_refusal(code: int, fails: bool = False) -> str | None:
    """Why the adjoint cannot take a law of this code, with failure if ``fails`` (None if it can)."""
    if fails:
        return ("a law with failure (failure_strain, softening_strain) has no derivatives in the adjoint: its "
                "lagged softening w(alpha) is not differentiated; drop the failure or simulate without gradients")
    if code in DIFFERENTIATED:
        return None
    if code == TABULATED:
        return ("a tabulated law (also TabulatedLaw.from_function, a user's flow-stress function) is piecewise "
                "linear in plastic strain and log rate; design's exact gradients cover the elastic, "
                "elastic-plastic, Johnson-Cook, Cowper-Symonds and Frew laws")
    return f"law code {code} has no derivatives in the adjoint"


def scratch_array() -> np.ndarray:
    """Scratch room of :func:`joint_vjp`."""
    return np.zeros((2 * LAW_ROWS, LAW_COLS))
