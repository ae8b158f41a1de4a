"""Array kernels of the exact gradient (reverse mode) of the wave propagation method; see docs/adjoint.md.

Symbols as in :mod:`rodimpact.direct._kernels`: Z impedance (N s/m), f / g the right- / left-going force waves
of an element (N = f + g, v = (g - f) / Z, thesis Sec. 2.3.2), R_j = (Z_{j+1} - Z_j)/(Z_{j+1} + Z_j) the
reflection factor of the node between elements j and j+1 (eq. 2.40). Adjoint variables carry the prefix ``l``
(lambda = dJ/d(variable)); ``mf``/``mg`` are the adjoints of the waves *before* a step.

Forward (:func:`advance_numba`, :func:`advance_numpy`): the lattice step of :func:`~rodimpact.direct._kernels.run_numba`
(the shared :func:`~rodimpact.direct._kernels.boundaries` solves ends, junctions, loaded nodes and probes),
bit-identical to it, with the state (f, g, end state, junction state, gap) stored before every ``stride``-th
step: checkpoints (stride C) or the full history of a segment (stride 1). Like ``simulate``, whose waves persist
between its compiled calls, the run never passes through (N, v) between steps, so it is bit-identical to it.

Reverse (:func:`reverse_numba`, :func:`reverse_numpy`): the transpose of one step, applied from the last step
of a segment to its first with the branches (contact/separated, stick/slip) taken as in the forward run and
the bit-rock end differentiated through its pieces (its step map is smooth where the path crosses a piece
boundary). ``seed[:, k]`` = dJ/d(output at step k) for the rows: 0 force at junction 0 (the
impact face), 1 right end force, 2 right end outward velocity, 3 probe force, 4 probe velocity.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..direct.boundary import BITROCK, FIXED, FORCE, FREE, LAW_JOINT, NONREFLECTING, SPRING, boundaries, end_solve
from ._joint_adjoint import joint_vjp

SEED_FACE, SEED_END_FORCE, SEED_END_VELOCITY, SEED_PROBE_FORCE, SEED_PROBE_VELOCITY = range(5)


# ---------------------------------------------------------------------------------------------- forward
def _save(slot, f, g, end_state, junction_state, gap, ck):
    """Checkpoint: the complete state (waves, end state, junction state, gap) into slot ``slot``."""
    ck[0][slot] = f
    ck[1][slot] = g
    ck[2][slot] = end_state
    ck[3][slot] = junction_state
    ck[4][slot] = gap


_save_nb = njit(inline="always", cache=True)(_save)


# ---------------------------------------------------------------------------------------------- law joints
# ``jt`` is None for a system without law joints (numba then compiles these helpers to nothing and the step
# loops carry no joint code, as rodimpact.direct.boundary.law_joint_force), else the joint tape
# (ck_q, seg_q, seg_gap, shortening, l_state, shortening_seed, scratch, junction_code, junction_par, junction_N):
# the joint states (eps_p, alpha, eps_max, work, crushed) at the checkpoints, the states and gaps before each step
# of the recomputed segment, the shortening delta after every step (n_j, steps), the adjoint of each joint's
# state (delta, eps_p, alpha, eps_max), the seeds dJ/d(shortening after step k), scratch of joint_vjp, and the
# per-step junction forces the step loop records (the recomputed segment's face forces, read by the transpose).
JT_CK_Q, JT_SEG_Q, JT_SEG_GAP, JT_SHORTENING, JT_LSTATE, JT_SEED, JT_SCRATCH, JT_CODE, JT_PAR, JT_FORCE = range(10)


@njit(error_model="numpy", cache=True)
def joint_save(jt, slot, q):
    """Checkpoint the joint states ``q`` into slot ``slot``."""
    if jt is None:
        return
    jt[0][slot] = q


@njit(error_model="numpy", cache=True)
def joint_restore(jt, slot, q):
    """Restore the joint states ``q`` from checkpoint ``slot``."""
    if jt is None:
        return
    q[:] = jt[0][slot]


@njit(error_model="numpy", cache=True)
def joint_record(jt, row, q, gap):
    """Record the joint states and gaps before the step of the segment's row ``row``."""
    if jt is None:
        return
    jt[1][row] = q
    jt[2][row] = gap


@njit(error_model="numpy", cache=True)
def joint_history(jt, k, gap):
    """The shortening delta = -gap of every junction after step k."""
    if jt is None:
        return
    jt[3][:, k] = -gap


@njit(error_model="numpy", cache=True)
def is_law_joint(jt, r):
    """Whether junction r is a law joint (always False without a joint tape)."""
    if jt is None:
        return False
    return jt[7][r] == LAW_JOINT


@njit(error_model="numpy", cache=True)
def joints_vjp(jt, k, row, f, g, Z, rod_start, seed, lNL, lNR, lVL, lVR, mf, mg, dZ, dt):
    """Transpose of the law joints of step k (``row`` its row in the segment's record): the seed on the
    shortening after the step joins the adjoint of delta, then :func:`~rodimpact.design._joint_adjoint.joint_vjp`
    (docs/adjoint.md, "Law joints")."""
    if jt is None:
        return
    code = jt[7]
    par = jt[8]
    lstate = jt[4]
    for r in range(code.size):
        if code[r] != LAW_JOINT:
            continue
        a = rod_start[r + 1] - 1
        b = a + 1
        lstate[r, 0] += jt[5][r, k]
        ln = lNR[r] + lNL[r + 1]
        if r == 0:
            ln += seed[0, k]
        dfa, dgb, dza, dzb = joint_vjp(par[r], jt[1][row, r], jt[9][r, k], f[a], g[a], f[b], g[b], Z[a], Z[b],
                                       -jt[2][row, r], dt, ln, lVR[r], lVL[r + 1], lstate[r], jt[6])
        mf[a] += dfa
        mg[b] += dgb
        dZ[a] += dza
        dZ[b] += dzb


def _advance(k0, k1, stride, f, g, Z, R, touch, rod_start, ends, junctions, specials, probes, outputs, acc,
             rod_nodes, dt, ck, record, rec, jt):
    """Steps k0 .. k1-1 in place on the waves (f, g), exactly as :func:`~rodimpact.direct._kernels.run_numba`.

    ``ck`` (f, g, end state, junction state, gap; one slot per checkpoint, or none): the state before every
    ``stride``-th step. With ``record``, ``rec`` = (d, f_touch, g_touch, end state) receives in row k - k0 what
    the transpose of step k needs: d_j = f_j - g_{j+1} at the plain interior nodes, the waves of the ``touch``
    elements and the end state (without ``record`` its row 0 is scratch). ``jt``: the joint tape (None without
    law joints): joint states at the checkpoints and before each recorded step, shortening after each step."""
    n_rods = rod_start.size - 1
    n_el = Z.size
    N = np.empty(n_el)
    v = np.empty(n_el)
    sp_elem = specials[0]
    sp_F = specials[3]
    sp_V = specials[4]
    rod_NL, rod_VL, rod_NR, rod_VR = rod_nodes
    n_sp = sp_elem.size
    rec_d, rec_ft, rec_gt, rec_es = rec
    checkpoints = ck[0].shape[0] > 0
    for k in range(k0, k1):
        i = k - k0
        if checkpoints and i % stride == 0:
            _save_nb(i // stride, f, g, ends[2], junctions[1], junctions[2], ck)
            joint_save(jt, i // stride, junctions[6])
        row = i if record else 0
        d = rec_d[row]
        if record:
            joint_record(jt, row, junctions[6], junctions[2])
            for m in range(touch.size):
                rec_ft[row, m] = f[touch[m]]
                rec_gt[row, m] = g[touch[m]]
            rec_es[row] = ends[2]
        for t in touch:
            N[t] = f[t] + g[t]
            v[t] = (g[t] - f[t]) / Z[t]
        boundaries(k, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        joint_history(jt, k, junctions[2])
        ptr = 0
        for r in range(n_rods):
            s = rod_start[r]
            e = rod_start[r + 1]
            f_first = rod_NL[r] - g[s]
            g_last = rod_NR[r] - f[e - 1]
            fa = f[s]
            j = s
            while j < e - 1:
                stop = e - 1
                if ptr < n_sp and sp_elem[ptr] < e - 1:
                    stop = sp_elem[ptr]
                for jj in range(j, stop):
                    gb = g[jj + 1]
                    fb = f[jj + 1]
                    dd = fa - gb
                    if record:
                        d[jj] = dd
                    sc = R[jj] * dd
                    g[jj] = gb + sc
                    f[jj + 1] = fa + sc
                    fa = fb
                if stop < e - 1:
                    gb = g[stop + 1]
                    fb = f[stop + 1]
                    n_plus = N[stop] + Z[stop] * (sp_V[ptr] - v[stop])
                    g[stop] = n_plus - fa
                    f[stop + 1] = n_plus - sp_F[ptr] - gb
                    fa = fb
                    ptr += 1
                j = stop + 1
            f[s] = f_first
            g[e - 1] = g_last


advance_numba = njit(cache=True, error_model="numpy", nogil=True)(_advance)


def interior_nodes(rod_start: np.ndarray, sp_elem: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Elements left of the plain interior nodes (no rod end, no load) and of the loaded/frictional ones."""
    n_el = int(rod_start[-1])
    plain = np.ones(max(n_el - 1, 0), dtype=bool)
    plain[rod_start[1:-1] - 1] = False
    plain[sp_elem] = False
    return np.flatnonzero(plain), sp_elem


def advance_numpy(k0, k1, stride, f, g, Z, R, touch, rod_start, ends, junctions, specials, probes, outputs, acc,
                  rod_nodes, dt, ck, record, rec, jt):
    """Readable reference of :func:`advance_numba`: per step, the scattering of every plain interior node as
    one vectorised expression (g_a' = g_b + R (f_a - g_b), f_b' = f_a + R (f_a - g_b), eq. 2.39) and the loaded
    nodes and rod ends from their node forces (g_a' = N_a^+ - f_a, f_b' = N_b^- - g_b)."""
    a, sp = interior_nodes(rod_start, specials[0])
    first, last = rod_start[:-1], rod_start[1:] - 1
    rod_NL, _, rod_NR, _ = rod_nodes
    sp_F, sp_V = specials[3], specials[4]
    N = np.empty(Z.size)
    v = np.empty(Z.size)
    for k in range(k0, k1):
        i = k - k0
        if ck[0].shape[0] > 0 and i % stride == 0:
            _save(i // stride, f, g, ends[2], junctions[1], junctions[2], ck)
            if jt is not None:
                jt[JT_CK_Q][i // stride] = junctions[6]
        if record:
            if jt is not None:
                jt[JT_SEG_Q][i] = junctions[6]
                jt[JT_SEG_GAP][i] = junctions[2]
            rec[0][i, a] = f[a] - g[a + 1]
            rec[1][i] = f[touch]
            rec[2][i] = g[touch]
            rec[3][i] = ends[2]
        N[touch] = f[touch] + g[touch]
        v[touch] = (g[touch] - f[touch]) / Z[touch]
        boundaries.py_func(k, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        if jt is not None:
            jt[JT_SHORTENING][:, k] = -junctions[2]
        f_new = np.empty_like(f)
        g_new = np.empty_like(g)
        sc = R[a] * (f[a] - g[a + 1])
        g_new[a] = g[a + 1] + sc
        f_new[a + 1] = f[a] + sc
        n_plus = N[sp] + Z[sp] * (sp_V - v[sp])
        g_new[sp] = n_plus - f[sp]
        f_new[sp + 1] = n_plus - sp_F - g[sp + 1]
        f_new[first] = rod_NL - g[first]
        g_new[last] = rod_NR - f[last]
        f[:] = f_new
        g[:] = g_new


# ---------------------------------------------------------------------------------------------- reverse
@njit(inline="always", error_model="numpy", cache=True)
def end_vjp(code, a, z, value, p0, p1, delta, delta_max, dt, ln, lw, ldelta_new, ldmax_new):
    """Transpose of one outer end (:func:`~rodimpact.direct._kernels.end_solve`).

    Forward: w from the end relation, N = a + z w, delta' = delta + w dt, delta_max' = max(delta_max, delta')
    (bit-rock only). Given dJ/dN, dJ/dw and the adjoints of delta', delta_max', returns dJ/da, dJ/dz,
    dJ/ddelta, dJ/ddelta_max. The device parameters (p0, p1) are held constant.
    """
    h = 0.5 * dt
    w, _, _ = end_solve(code, a, z, value, p0, p1, delta, delta_max, dt)
    lw = lw + ldelta_new * dt
    ldelta = ldelta_new
    ldmax = ldmax_new
    if code == BITROCK and delta + w * dt > delta_max:
        lw += ldmax_new * dt
        ldelta += ldmax_new
        ldmax = 0.0
    la = ln                                   # N = a + z w
    lz = ln * w
    lw += ln * z
    if code == FREE or code == FORCE:         # w = (value - a) / z
        la -= lw / z
        lz -= lw * w / z
    elif code == NONREFLECTING:               # w = (p1 - a) / (z + p0)
        la -= lw / (z + p0)
        lz -= lw * w / (z + p0)
    elif code == SPRING:                      # w = -(a + k delta) / (z + c + k h)
        den = z + p1 + p0 * h
        la -= lw / den
        ldelta -= lw * p0 / den
        lz -= lw * w / den
    elif code == BITROCK:                     # a + z w + Fbar(w, delta, delta_max) = 0
        den, d_delta, d_dmax = _bitrock_partials(p0, p1, delta, delta_max, w * dt)
        den = z + dt * den
        la -= lw / den
        ldelta -= lw * d_delta / den
        ldmax -= lw * d_dmax / den
        lz -= lw * w / den
    # FIXED and VELOCITY: w does not depend on the state of the rod
    return la, lz, ldelta, ldmax


@njit(inline="always", error_model="numpy", cache=True)
def _bitrock_partials(k1, k2, delta, delta_max, s):
    """Partial derivatives of the bit-rock mean force Fbar = (1/s) int_delta^{delta+s} F (end_solve) along the
    step's path x = delta + s tau, 0 <= tau <= 1: dFbar/ds = int tau F' dtau, dFbar/ddelta = int F' dtau and
    dFbar/ddelta_max = int dF/ddelta_max dtau = (k1 - k2) |tau in the unloading piece|. F' is k2 on the
    unloading piece (r, delta_max), k1 beyond delta_max, 0 below r. Fbar is continuously differentiable in s
    where the path crosses r or delta_max, so the pieces need not be frozen. At s = 0 the piece end_solve
    takes (downwards) is used."""
    pm = delta_max
    r = pm - k1 * pm / k2
    if s == 0.0:
        lo2 = 0.0
        hi2 = 1.0 if delta > r else 0.0
        lo1 = 0.0
        hi1 = 0.0
    else:
        t_r = min(max((r - delta) / s, 0.0), 1.0)      # path fractions at the breakpoints
        t_m = min(max((pm - delta) / s, 0.0), 1.0)
        lo2 = min(t_r, t_m)
        hi2 = max(t_r, t_m)
        lo1 = t_m if s > 0.0 else 0.0                   # the virgin piece lies beyond delta_max >= delta
        hi1 = 1.0 if s > 0.0 else 0.0
    d_s = 0.5 * (k2 * (hi2 * hi2 - lo2 * lo2) + k1 * (hi1 * hi1 - lo1 * lo1))
    d_delta = k2 * (hi2 - lo2) + k1 * (hi1 - lo1)
    return d_s, d_delta, (k1 - k2) * (hi2 - lo2)


@njit(inline="always", error_model="numpy", cache=True)
def node_vjp(fa, gb, za, zb, ln, lv):
    """Transpose of a bonded node between elements a and b: V = 2 (g_b - f_a)/(Z_a + Z_b), N = 2 f_a + Z_a V
    (eqs. 3.5-3.7 in wave variables). Returns dJ/df_a, dJ/dg_b, dJ/dZ_a, dJ/dZ_b."""
    s = za + zb
    vn = 2.0 * (gb - fa) / s
    lvt = lv + za * ln
    return 2.0 * ln - 2.0 * lvt / s, 2.0 * lvt / s, ln * vn - lvt * vn / s, -lvt * vn / s


def _boundary_vjp(k, f, g, Z, rod_start, end_code, end_par, end_value, es, les, contact, sp_elem, sp_cap, sp_force,
                  pr_rod, pr_local, pr_sp, seed, lNL, lNR, lVL, lVR, lnp, lspF, lspV, mf, mg, dZ, dt, jt):
    """Transpose of :func:`~rodimpact.direct._kernels.boundaries` at step k: from the adjoints of the node values
    (lNL, lNR, lVL, lVR per rod; lnp = dJ/dN^+, lspF, lspV per loaded node) and the output seeds, add dJ/df,
    dJ/dg of the waves before the step into mf, mg and dJ/dZ into dZ; les (2, 2) holds the adjoint of the end
    state after the step on entry and before it on return. Branches: junction contact flags of the forward
    run; friction branches and the bit-rock step recomputed with the forward arithmetic from the stored waves.
    Law joints (``jt``, the joint tape or None) are skipped here: :func:`joints_vjp` transposes them after this
    function (a call of more than 30 arguments becomes a star-args call that numba cannot inline)."""
    n_rods = rod_start.size - 1
    n_el = Z.size
    # ---- probes (outputs read from node values)
    for p in range(pr_rod.size):
        r = pr_rod[p]
        m = pr_local[p]
        sn = seed[3, k]
        sv = seed[4, k]
        if m == 0:
            lNL[r] += sn
            lVL[r] += sv
        elif m == rod_start[r + 1] - rod_start[r]:
            lNR[r] += sn
            lVR[r] += sv
        elif pr_sp[p] >= 0:
            lnp[pr_sp[p]] += sn
            lspV[pr_sp[p]] += sv
        else:
            a = rod_start[r] + m - 1
            dfa, dgb, dza, dzb = node_vjp(f[a], g[a + 1], Z[a], Z[a + 1], sn, sv)
            mf[a] += dfa
            mg[a + 1] += dgb
            dZ[a] += dza
            dZ[a + 1] += dzb
    # ---- loaded / frictional nodes: N^+ = 2 f_a + Z_a V, V and the node force F by branch
    for i in range(sp_elem.size):
        a = sp_elem[i]
        b = a + 1
        Na = f[a] + g[a]
        va = (g[a] - f[a]) / Z[a]
        Nb = f[b] + g[b]
        vb = (g[b] - f[b]) / Z[b]
        zs = Z[a] + Z[b]
        f_load = sp_force[i, k]
        v0 = (f_load + Nb - Na + Z[a] * va + Z[b] * vb) / zs
        cap = sp_cap[i]
        stick = cap > 0.0 and abs(v0) * zs <= cap
        f_fric = 0.0
        if cap > 0.0 and not stick:
            f_fric = -cap if v0 > 0.0 else cap
        vn = 0.0 if stick else v0 + f_fric / zs
        lvn = lspV[i] + Z[a] * lnp[i]
        mf[a] += 2.0 * lnp[i]
        dZ[a] += vn * lnp[i]
        if stick:                              # F = f_load - v0 zs = 2 f_a - 2 g_b, V = 0
            mf[a] += 2.0 * lspF[i]
            mg[b] -= 2.0 * lspF[i]
        else:                                  # F constant, V = (F + 2 g_b - 2 f_a) / zs
            mg[b] += 2.0 * lvn / zs
            mf[a] -= 2.0 * lvn / zs
            dZ[a] -= vn / zs * lvn
            dZ[b] -= vn / zs * lvn
    # ---- junctions
    for r in range(n_rods - 1):
        if is_law_joint(jt, r):
            continue
        a = rod_start[r + 1] - 1
        b = a + 1
        ln = lNR[r] + lNL[r + 1]
        if r == 0:
            ln += seed[0, k]
        if contact[r, k] != 0.0:
            dfa, dgb, dza, dzb = node_vjp(f[a], g[b], Z[a], Z[b], ln, lVR[r] + lVL[r + 1])
            mf[a] += dfa
            mg[b] += dgb
            dZ[a] += dza
            dZ[b] += dzb
        else:                                  # N = 0; free node velocities -2 f_a / Z_a and 2 g_b / Z_b
            mf[a] -= 2.0 * lVR[r] / Z[a]
            dZ[a] += 2.0 * f[a] / (Z[a] * Z[a]) * lVR[r]
            mg[b] += 2.0 * lVL[r + 1] / Z[b]
            dZ[b] -= 2.0 * g[b] / (Z[b] * Z[b]) * lVL[r + 1]
    # ---- outer ends: a = N + Z v = 2 g_0 (left), a = N - Z v = 2 f_e (right)
    for side in range(2):
        e = 0 if side == 0 else n_el - 1
        Ne = f[e] + g[e]
        ve = (g[e] - f[e]) / Z[e]
        if side == 0:
            a_in = Ne + Z[e] * ve
            ln = lNL[0]
            lw = -lVL[0]
        else:
            a_in = Ne - Z[e] * ve
            ln = lNR[n_rods - 1] + seed[1, k]
            lw = lVR[n_rods - 1] + seed[2, k]
        la, lz, ld, lm = end_vjp(end_code[side], a_in, Z[e], end_value[side, k], end_par[side, 0],
                                 end_par[side, 1], es[side, 0], es[side, 1], dt, ln, lw, les[side, 0], les[side, 1])
        if side == 0:
            mg[e] += 2.0 * la
        else:
            mf[e] += 2.0 * la
        dZ[e] += lz
        les[side, 0] = ld
        les[side, 1] = lm


boundary_vjp = njit(inline="always", error_model="numpy", cache=True)(_boundary_vjp)


def _reverse(k0, k1, rec, touch, Z, R, rod_start, end_code, end_par, end_value, contact, sp_elem, sp_cap, sp_force,
             pr_rod, pr_local, pr_sp, seed, lf, lg, les, dZ, dR, dt, jt):
    """Transpose of steps k1-1 .. k0 (compiled): on entry lf, lg, les are dJ/d(state after step k1-1), on
    return dJ/d(state before step k0); dJ/dZ (boundaries) and dJ/dR (interior scattering) are accumulated.
    ``rec`` is the record of the steps written by :func:`advance_numba` (row k - k0 for step k)."""
    n_rods = rod_start.size - 1
    n_el = Z.size
    n_sp = sp_elem.size
    mf = np.empty(n_el)                                   # adjoint before the step (ping-pong with lf, lg)
    mg = np.empty(n_el)
    lNL = np.empty(n_rods)
    lNR = np.empty(n_rods)
    lVL = np.empty(n_rods)
    lVR = np.empty(n_rods)
    lnp = np.empty(n_sp)
    lspF = np.empty(n_sp)
    lspV = np.empty(n_sp)
    rec_d, rec_ft, rec_gt, rec_es = rec
    f = np.zeros(n_el)                                    # waves before the step, at the touch elements only
    g = np.zeros(n_el)
    lf_in = lf
    lg_in = lg
    for k in range(k1 - 1, k0 - 1, -1):
        d = rec_d[k - k0]
        for m in range(touch.size):
            f[touch[m]] = rec_ft[k - k0, m]
            g[touch[m]] = rec_gt[k - k0, m]
        lVL[:] = 0.0
        lVR[:] = 0.0
        lspV[:] = 0.0
        ptr = 0
        for r in range(n_rods):
            s = rod_start[r]
            e = rod_start[r + 1]
            j = s
            while j < e - 1:
                stop = e - 1
                if ptr < n_sp and sp_elem[ptr] < e - 1:
                    stop = sp_elem[ptr]
                for jj in range(j, stop):                 # plain nodes: transpose of the scattering
                    sc = lg[jj] + lf[jj + 1]
                    dR[jj] += sc * d[jj]
                    mf[jj] = lf[jj + 1] + R[jj] * sc
                    mg[jj + 1] = lg[jj] - R[jj] * sc
                if stop < e - 1:                          # loaded node: g_a' = N^+ - f_a, f_b' = N^+ - F - g_b
                    lnp[ptr] = lg[stop] + lf[stop + 1]
                    lspF[ptr] = -lf[stop + 1]
                    mf[stop] = -lg[stop]
                    mg[stop + 1] = -lf[stop + 1]
                    ptr += 1
                j = stop + 1
            lNL[r] = lf[s]                                # f_s' = N^- - g_s
            mg[s] = -lf[s]
            lNR[r] = lg[e - 1]                            # g_last' = N^+ - f_last
            mf[e - 1] = -lg[e - 1]
        boundary_vjp(k, f, g, Z, rod_start, end_code, end_par, end_value, rec_es[k - k0], les, contact, sp_elem,
                     sp_cap, sp_force, pr_rod, pr_local, pr_sp, seed, lNL, lNR, lVL, lVR, lnp, lspF, lspV, mf, mg,
                     dZ, dt, jt)
        joints_vjp(jt, k, k - k0, f, g, Z, rod_start, seed, lNL, lNR, lVL, lVR, mf, mg, dZ, dt)
        lf, mf = mf, lf                                   # the new adjoint becomes the current one
        lg, mg = mg, lg
    if (k1 - k0) % 2 == 1:
        lf_in[:] = lf
        lg_in[:] = lg


reverse_numba = njit(cache=True, error_model="numpy", nogil=True)(_reverse)


def reverse_numpy(k0, k1, rec, touch, Z, R, rod_start, end_code, end_par, end_value, contact, sp_elem, sp_cap,
                  sp_force, pr_rod, pr_local, pr_sp, seed, lf, lg, les, dZ, dR, dt, jt):
    """Readable reference of :func:`reverse_numba`: the transpose of the interior scattering as one vectorised
    expression per step (with s = l_{g_a'} + l_{f_b'}: l_{f_a} = l_{f_b'} + R s, l_{g_b} = l_{g_a'} - R s,
    dJ/dR += s (f_a - g_b)), then the transposed boundaries."""
    a, sp = interior_nodes(rod_start, sp_elem)
    first, last = rod_start[:-1], rod_start[1:] - 1
    n_rods = rod_start.size - 1
    f = np.zeros(Z.size)
    g = np.zeros(Z.size)
    for k in range(k1 - 1, k0 - 1, -1):
        d = rec[0][k - k0]
        f[touch] = rec[1][k - k0]
        g[touch] = rec[2][k - k0]
        mf = np.zeros_like(lf)
        mg = np.zeros_like(lg)
        s = lg[a] + lf[a + 1]
        dR[a] += s * d[a]
        mf[a] = lf[a + 1] + R[a] * s
        mg[a + 1] = lg[a] - R[a] * s
        lnp = lg[sp] + lf[sp + 1]
        lspF = -lf[sp + 1]
        mf[sp] = -lg[sp]
        mg[sp + 1] = -lf[sp + 1]
        lNL = lf[first].copy()
        lNR = lg[last].copy()
        mg[first] = -lf[first]
        mf[last] = -lg[last]
        lVL = np.zeros(n_rods)
        lVR = np.zeros(n_rods)
        _boundary_vjp(k, f, g, Z, rod_start, end_code, end_par, end_value, rec[3][k - k0], les, contact, sp_elem,
                      sp_cap, sp_force, pr_rod, pr_local, pr_sp, seed, lNL, lNR, lVL, lVR, lnp, lspF,
                      np.zeros(sp.size), mf, mg, dZ, dt, jt)
        joints_vjp(jt, k, k - k0, f, g, Z, rod_start, seed, lNL, lNR, lVL, lVR, mf, mg, dZ, dt)
        lf[:] = mf
        lg[:] = mg


def _restore_segment(i, stride, steps, checkpoints, f, g, ends, junctions, jt):
    """Restore the state of checkpoint ``i`` (waves, end state, junction state, gap, joint states); returns the
    segment's steps (k0, k1)."""
    f[:] = checkpoints[0][i]
    g[:] = checkpoints[1][i]
    ends[2][:] = checkpoints[2][i]
    junctions[1][:] = checkpoints[3][i]
    junctions[2][:] = checkpoints[4][i]
    joint_restore(jt, i, junctions[6])
    k0 = i * stride
    return k0, min(steps, k0 + stride)


_restore_segment_nb = njit(inline="always", error_model="numpy", cache=True)(_restore_segment)


@njit(cache=True, error_model="numpy", nogil=True)
def sweep_numba(checkpoints, no_checkpoints, segment, f, g, Z, R, touch, rod_start, ends, junctions, specials,
                probes, outputs, acc, rod_nodes, dt, steps, seed, lf, lg, les, dZ, dR, jt):
    """The whole reverse pass: for the segments between checkpoints, last first, recompute the segment forward
    from its checkpoint (recording every step into ``segment``), then transpose its steps. On return lf, lg
    hold dJ/d(initial waves); dZ, dR are accumulated. ``no_checkpoints``: empty checkpoint stores. ``jt``: the
    joint tape (None without law joints), whose adjoint of the joint states runs along.

    The compiled step and transpose are named here, not passed in (as :func:`sweep_numpy` takes its pair): numba
    keys its on-disk cache by the argument types, and the type of a dispatcher argument carries the function's
    address, so a sweep that took them as arguments was compiled again in every process (30-60 s)."""
    stride = segment[0].shape[0]
    for i in range(checkpoints[0].shape[0] - 1, -1, -1):
        k0, k1 = _restore_segment_nb(i, stride, steps, checkpoints, f, g, ends, junctions, jt)
        advance_numba(k0, k1, 1, f, g, Z, R, touch, rod_start, ends, junctions, specials, probes, outputs, acc,
                      rod_nodes, dt, no_checkpoints, True, segment, jt)
        reverse_numba(k0, k1, segment, touch, Z, R, rod_start, ends[0], ends[1], ends[3], outputs[1], specials[0],
                      specials[1], specials[2], probes[0], probes[1], probes[2], seed, lf, lg, les, dZ, dR, dt, jt)


def sweep_numpy(checkpoints, no_checkpoints, segment, f, g, Z, R, touch, rod_start, ends, junctions, specials,
                probes, outputs, acc, rod_nodes, dt, steps, seed, lf, lg, les, dZ, dR, jt):
    """Readable reference of :func:`sweep_numba` with :func:`advance_numpy` and :func:`reverse_numpy`."""
    stride = segment[0].shape[0]
    for i in range(checkpoints[0].shape[0] - 1, -1, -1):
        k0, k1 = _restore_segment(i, stride, steps, checkpoints, f, g, ends, junctions, jt)
        advance_numpy(k0, k1, 1, f, g, Z, R, touch, rod_start, ends, junctions, specials, probes, outputs, acc,
                      rod_nodes, dt, no_checkpoints, True, segment, jt)
        reverse_numpy(k0, k1, segment, touch, Z, R, rod_start, ends[0], ends[1], ends[3], outputs[1], specials[0],
                      specials[1], specials[2], probes[0], probes[1], probes[2], seed, lf, lg, les, dZ, dR, dt, jt)
