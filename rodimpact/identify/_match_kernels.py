"""Kernels of the matching forward model: a pile on the equal-travel-time lattice with shaft and toe soil,
its exact discrete adjoint (reverse mode) and its forward sensitivities (tangent mode).

Symbols as in :mod:`rodimpact.direct._kernels` (thesis Sec. 3.1, eqs. 3.2-3.20): Z_j impedance of element j
(N s/m, j = 0 .. n-1 from the head), N_j / v_j element force (N, tension positive) and particle velocity (m/s,
+x = into the ground) at t = k dt; node i (i = 0 .. n) lies between elements i-1 and i, node 0 is the head,
node n the toe; V_i is the node velocity, constant during step k, u_i the node displacement (m).

One step k (state (N, v, u) at t = k dt -> t = (k+1) dt):

* head (node 0), a force end: N^-_0 = F_k (the hammer force, compression negative) and, from the element's
  left-going characteristic (eq. 3.16), V_0 = v_0 + (N_0 - F_k) / Z_0. The record is y_k = V_0.
* shaft node i = 1 .. n-1 between a = i-1 and b = i with the soil force on the pile
  S_i = -k_i (u_i + V_i dt/2) - c_i V_i (a linear spring at the midpoint of the step's path, as the spring end of
  :func:`rodimpact.direct.boundary.end_solve`, and a dashpot). With the characteristics N^+_a = N_a + Z_a (V - v_a),
  N^-_b = N_b - Z_b (V - v_b) and the node balance N^-_b = N^+_a - S_i (eq. 3.2):
  d = V - v_a = (-q v_a - k_i u_i + N_b - N_a + Z_b (v_b - v_a)) / (Z_a + Z_b + q), q = c_i + k_i dt/2.
  With k_i = c_i = 0 this is eqs. 3.6-3.9 literally.
* toe (node n), a spring-dashpot end (stiffness k_t, dashpot c_t; free when both are 0) or a fixed end:
  A = N_a - Z_a v_a, w = -(A + k_t u_n) / (Z_a + c_t + k_t dt/2), N^+_a = A + Z_a w (fixed: w = 0, N^+_a = A).
* elements (eqs. 3.10-3.15): N_j <- N^-_j + N^+_j - N_j, v_j <- V_j + V_{j+1} - v_j; nodes u_i <- u_i + V_i dt.

The map is linear in the state for fixed parameters, so its reverse mode (:func:`adjoint_numba`) is the transpose
of the step applied backwards from the last step, plus the parameter partials of each node formula evaluated at
the stored forward states: this is the exact gradient of the discrete objective, not a discretised continuous
adjoint. ``by[k]`` is dJ/dy_k. Arrays: ``c``, ``k`` have n+1 entries (per node; entries 0 and n are not used).
"""

from __future__ import annotations

import numpy as np
from numba import njit


# ------------------------------------------------------------------------------------------------ forward
@njit(cache=True, nogil=True)
def forward_numba(Z, c, k, kt, ct, fixed_toe, F, dt, Ns, vs, us):
    """Head velocity y (len(F)) of the pile at rest driven by the head force F; if ``Ns`` has rows, the state
    before every step is stored into ``Ns``, ``vs``, ``us`` (shapes (K, n), (K, n), (K, n+1))."""
    n = Z.size
    K = F.size
    store = Ns.shape[0] > 0
    N = np.zeros(n)
    v = np.zeros(n)
    u = np.zeros(n + 1)
    Vn = np.empty(n + 1)
    Nm = np.empty(n)
    Np = np.empty(n)
    y = np.empty(K)
    h = 0.5 * dt
    inv_D = np.empty(n)                 # 1 / (Z_a + Z_b + q) of every shaft node: constant during the run
    for i in range(1, n):
        inv_D[i] = 1.0 / (Z[i - 1] + Z[i] + c[i] + k[i] * h)
    for s in range(K):
        # the front: before step s only elements < s and nodes < s have left rest (the head is driven from step
        # 0, a wave crosses one element per step), so nodes and elements beyond s + 1 stay exactly zero and their
        # formulas are skipped
        top = min(s + 1, n - 1)
        if store:
            for j in range(n):
                Ns[s, j] = N[j]
                vs[s, j] = v[j]
            for i in range(n + 1):
                us[s, i] = u[i]
        Vn[0] = v[0] + (N[0] - F[s]) / Z[0]
        Nm[0] = F[s]
        for i in range(1, top + 1):
            a = i - 1
            q = c[i] + k[i] * h
            num = -q * v[a] - k[i] * u[i] + N[i] - N[a] + Z[i] * (v[i] - v[a])
            d = num * inv_D[i]
            V = v[a] + d
            Vn[i] = V
            Np[a] = N[a] + Z[a] * d
            Nm[i] = N[i] - Z[i] * (V - v[i])
        if top == n - 1:
            a = n - 1
            A = N[a] - Z[a] * v[a]
            if fixed_toe:
                Vn[n] = 0.0
                Np[a] = A
            else:
                w = -(A + kt * u[n]) / (Z[a] + ct + kt * h)
                Vn[n] = w
                Np[a] = A + Z[a] * w
        y[s] = Vn[0]
        for j in range(top):            # element top (if not the last) has Np from node top + 1: still at rest
            N[j] = Nm[j] + Np[j] - N[j]
            v[j] = Vn[j] + Vn[j + 1] - v[j]
        if top == n - 1:
            N[top] = Nm[top] + Np[top] - N[top]
            v[top] = Vn[top] + Vn[top + 1] - v[top]
        for i in range(top + 1 if top < n - 1 else n + 1):
            u[i] += Vn[i] * dt
    return y


def forward_numpy(Z, c, k, kt, ct, fixed_toe, F, dt, Ns, vs, us):
    """:func:`forward_numba` with the nodes of a step as vectorised numpy expressions (the readable twin)."""
    n = Z.size
    K = F.size
    store = Ns.shape[0] > 0
    N = np.zeros(n)
    v = np.zeros(n)
    u = np.zeros(n + 1)
    y = np.empty(K)
    h = 0.5 * dt
    a = np.arange(n - 1)
    b = a + 1
    q = c[1:n] + k[1:n] * h
    for s in range(K):
        if store:
            Ns[s], vs[s], us[s] = N, v, u
        Vn = np.empty(n + 1)
        Nm = np.empty(n)
        Np = np.empty(n)
        Vn[0] = v[0] + (N[0] - F[s]) / Z[0]
        Nm[0] = F[s]
        d = (-q * v[a] - k[1:n] * u[1:n] + N[b] - N[a] + Z[b] * (v[b] - v[a])) / (Z[a] + Z[b] + q)
        Vn[1:n] = v[a] + d
        Np[a] = N[a] + Z[a] * d
        Nm[b] = N[b] - Z[b] * (Vn[1:n] - v[b])
        A = N[-1] - Z[-1] * v[-1]
        w = 0.0 if fixed_toe else -(A + kt * u[n]) / (Z[-1] + ct + kt * h)
        Vn[n] = w
        Np[-1] = A + Z[-1] * w
        y[s] = Vn[0]
        N = Nm + Np - N
        v = Vn[:-1] + Vn[1:] - v
        u = u + Vn * dt
    return y


# ------------------------------------------------------------------------------------------------ reverse
@njit(cache=True, nogil=True)
def adjoint_numba(Z, c, k, kt, ct, fixed_toe, F, dt, Ns, vs, us, by):
    """Gradient of J(y) with respect to (Z, c, k, k_t, c_t) given by = dJ/dy and the stored forward states.

    Returns (gZ (n), gc (n+1), gk (n+1), gkt, gct). Reverse of each step of :func:`forward_numba`: the adjoint of
    the element update first (N' = N^- + N^+ - N, v' = V_j + V_{j+1} - v, u' = u + V dt), then of the node
    formulas in reverse order of their evaluation."""
    n = Z.size
    K = F.size
    h = 0.5 * dt
    bN = np.zeros(n)
    bv = np.zeros(n)
    bu = np.zeros(n + 1)
    gZ = np.zeros(n)
    gc = np.zeros(n + 1)
    gk = np.zeros(n + 1)
    gkt = 0.0
    gct = 0.0
    bV = np.empty(n + 1)
    bNe = np.empty(n)
    inv_D = np.empty(n)                 # 1 / (Z_a + Z_b + q) of every shaft node, as in the forward run
    for i in range(1, n):
        inv_D[i] = 1.0 / (Z[i - 1] + Z[i] + c[i] + k[i] * h)
    sNa = np.empty(n)                   # per-node scratch of the shaft pass: what node i gives element i-1 (a)
    sva = np.empty(n)
    sZa = np.empty(n)
    sNb = np.empty(n)                   # ... and element i (b)
    svb = np.empty(n)
    sZb = np.empty(n)
    for s in range(K - 1, -1, -1):
        # the two cones: the forward states of step s are zero beyond element s (the front), the adjoint ones
        # beyond element K - 1 - s (what the head records from step s on has come from no deeper); the gradient
        # needs both nonzero, and neither cone takes values from outside itself, so the step's nodes and elements
        # beyond top (each cone with a margin) are skipped. Outside, bN, bv, bu keep stale values never read again.
        top = min(n - 1, s + 1, K - s + 1)
        # element update: N^- and N^+ of element j both receive bN'_j; node i receives bv' of elements i-1, i
        for j in range(top + 1):
            bNe[j] = bN[j]
        for i in range(top + 2):
            t = bu[i] * dt
            if i < n:
                t += bv[i]
            if i > 0:
                t += bv[i - 1]
            bV[i] = t
        for j in range(top + 1):
            bN[j] = -bN[j]
            bv[j] = -bv[j]
        bV[0] += by[s]
        # head: V_0 = v_0 + (N_0 - F) / Z_0
        g = bV[0]
        bv[0] += g
        bN[0] += g / Z[0]
        gZ[0] -= g * (Ns[s, 0] - F[s]) / (Z[0] * Z[0])
        # shaft nodes, in two passes so that both vectorise: node i's partials into per-node scratch (pass 1, no
        # node writes a neighbour's entry), then every element collects from its two nodes (pass 2)
        for i in range(1, top + 1):
            a = i - 1
            va = vs[s, a]
            vb = vs[s, i]
            ui = us[s, i]
            q = c[i] + k[i] * h
            iD = inv_D[i]
            d = (-q * va - k[i] * ui + Ns[s, i] - Ns[s, a] + Z[i] * (vb - va)) * iD
            V = va + d
            gm = bNe[i]                     # N^-_b = N_b - Z_b (V - v_b)
            gp = bNe[a]                     # N^+_a = N_a + Z_a d
            bVi = bV[i] - Z[i] * gm
            bd = Z[a] * gp + bVi            # V = v_a + d
            bnum = bd * iD
            bD = -bnum * d
            bq = bD - va * bnum
            sNb[i] = gm + bnum
            sNa[i] = gp - bnum
            svb[i] = Z[i] * gm + Z[i] * bnum
            sva[i] = bVi - (q + Z[i]) * bnum
            sZb[i] = -(V - vb) * gm + bD + (vb - va) * bnum
            sZa[i] = d * gp + bD
            bu[i] -= k[i] * bnum
            gk[i] += h * bq - ui * bnum
            gc[i] += bq
        for j in range(top):
            bN[j] += sNa[j + 1]
            bv[j] += sva[j + 1]
            gZ[j] += sZa[j + 1]
        for j in range(1, top + 1):
            bN[j] += sNb[j]
            bv[j] += svb[j]
            gZ[j] += sZb[j]
        if top < n - 1:
            continue
        # toe
        a = n - 1
        Na = Ns[s, a]
        va = vs[s, a]
        g = bNe[a]
        bA = g
        if not fixed_toe:
            A = Na - Z[a] * va
            E = Z[a] + ct + kt * h
            w = -(A + kt * us[s, n]) / E
            gZ[a] += w * g
            bw = bV[n] + Z[a] * g
            bA -= bw / E
            gkt -= us[s, n] * bw / E
            bu[n] -= kt * bw / E
            bE = -w / E * bw
            gZ[a] += bE
            gct += bE
            gkt += h * bE
        bN[a] += bA
        bv[a] -= Z[a] * bA
        gZ[a] -= va * bA
    return gZ, gc, gk, gkt, gct


def adjoint_numpy(Z, c, k, kt, ct, fixed_toe, F, dt, Ns, vs, us, by):
    """:func:`adjoint_numba` with the nodes of a step as vectorised numpy expressions (the readable twin)."""
    n = Z.size
    K = F.size
    h = 0.5 * dt
    bN = np.zeros(n)
    bv = np.zeros(n)
    bu = np.zeros(n + 1)
    gZ = np.zeros(n)
    gc = np.zeros(n + 1)
    gk = np.zeros(n + 1)
    gkt = 0.0
    gct = 0.0
    a = np.arange(n - 1)
    b = a + 1
    i = b
    q = c[i] + k[i] * h
    D = Z[a] + Z[b] + q
    for s in range(K - 1, -1, -1):
        N, v, u = Ns[s], vs[s], us[s]
        bNe = bN.copy()
        bV = bu * dt
        bV[:-1] += bv
        bV[1:] += bv
        bN = -bN
        bv = -bv
        bu = bu.copy()
        bV[0] += by[s]
        bv[0] += bV[0]
        bN[0] += bV[0] / Z[0]
        gZ[0] -= bV[0] * (N[0] - F[s]) / Z[0] ** 2
        d = (-q * v[a] - k[i] * u[i] + N[b] - N[a] + Z[b] * (v[b] - v[a])) / D
        V = v[a] + d
        gm = bNe[b]
        gp = bNe[a]
        bVi = bV[i] - Z[b] * gm
        bd = Z[a] * gp + bVi
        bnum = bd / D
        bD = -bd * d / D
        bq = bD - v[a] * bnum
        np.add.at(bN, b, gm + bnum)
        np.add.at(bN, a, gp - bnum)
        np.add.at(bv, b, Z[b] * gm + Z[b] * bnum)
        np.add.at(bv, a, bVi - (q + Z[b]) * bnum)
        np.add.at(gZ, b, -(V - v[b]) * gm + bD + (v[b] - v[a]) * bnum)
        np.add.at(gZ, a, d * gp + bD)
        bu[i] -= k[i] * bnum
        gk[i] += -u[i] * bnum + h * bq
        gc[i] += bq
        bA = bNe[-1]
        if not fixed_toe:
            A = N[-1] - Z[-1] * v[-1]
            E = Z[-1] + ct + kt * h
            w = -(A + kt * u[n]) / E
            bw = bV[n] + Z[-1] * bA
            bE = -w / E * bw
            gZ[-1] += w * bA + bE
            gkt += -u[n] * bw / E + h * bE
            gct += bE
            bu[n] -= kt * bw / E
            bA = bA - bw / E
        bN[-1] += bA
        bv[-1] -= Z[-1] * bA
        gZ[-1] -= v[-1] * bA
    return gZ, gc, gk, gkt, gct


# ------------------------------------------------------------------------------------------------ tangent
@njit(cache=True, nogil=True)
def tangent_numba(Z, c, k, kt, ct, fixed_toe, F, dt, tZ, tc, tk, tkt, tct):
    """Forward sensitivities: J[s, p] = dy_s along the parameter direction p = (tZ[p], tc[p], tk[p], tkt[p],
    tct[p]) (the Jacobian of the record for the Gauss-Newton covariance). The primal run of
    :func:`forward_numba` with, per node formula, its derivative carried for every direction. Returns (y, J)."""
    n = Z.size
    K = F.size
    P = tZ.shape[0]
    h = 0.5 * dt
    N = np.zeros(n)
    v = np.zeros(n)
    u = np.zeros(n + 1)
    Vn = np.empty(n + 1)
    Nm = np.empty(n)
    Np = np.empty(n)
    dd = np.empty(n + 1)
    tN = np.zeros((P, n))
    tv = np.zeros((P, n))
    tu = np.zeros((P, n + 1))
    tV = np.empty(n + 1)
    tNm = np.empty(n)
    tNp = np.empty(n)
    y = np.empty(K)
    J = np.empty((K, P))
    inv_D = np.empty(n)
    for i in range(1, n):
        inv_D[i] = 1.0 / (Z[i - 1] + Z[i] + c[i] + k[i] * h)
    for s in range(K):
        # primal
        Vn[0] = v[0] + (N[0] - F[s]) / Z[0]
        Nm[0] = F[s]
        for i in range(1, n):
            a = i - 1
            q = c[i] + k[i] * h
            d = (-q * v[a] - k[i] * u[i] + N[i] - N[a] + Z[i] * (v[i] - v[a])) * inv_D[i]
            dd[i] = d
            Vn[i] = v[a] + d
            Np[a] = N[a] + Z[a] * d
            Nm[i] = N[i] - Z[i] * (Vn[i] - v[i])
        a = n - 1
        A = N[a] - Z[a] * v[a]
        E = Z[a] + ct + kt * h
        if fixed_toe:
            Vn[n] = 0.0
            Np[a] = A
        else:
            Vn[n] = -(A + kt * u[n]) / E
            Np[a] = A + Z[a] * Vn[n]
        y[s] = Vn[0]
        # tangents
        for p in range(P):
            tV[0] = tv[p, 0] + tN[p, 0] / Z[0] - (N[0] - F[s]) * tZ[p, 0] / (Z[0] * Z[0])
            tNm[0] = 0.0
            for i in range(1, n):
                a = i - 1
                q = c[i] + k[i] * h
                tq = tc[p, i] + h * tk[p, i]
                tD = tZ[p, a] + tZ[p, i] + tq
                tnum = (-tq * v[a] - q * tv[p, a] - tk[p, i] * u[i] - k[i] * tu[p, i] + tN[p, i] - tN[p, a]
                        + tZ[p, i] * (v[i] - v[a]) + Z[i] * (tv[p, i] - tv[p, a]))
                td = (tnum - dd[i] * tD) * inv_D[i]
                tV[i] = tv[p, a] + td
                tNp[a] = tN[p, a] + tZ[p, a] * dd[i] + Z[a] * td
                tNm[i] = tN[p, i] - tZ[p, i] * (Vn[i] - v[i]) - Z[i] * (tV[i] - tv[p, i])
            a = n - 1
            tA = tN[p, a] - tZ[p, a] * v[a] - Z[a] * tv[p, a]
            if fixed_toe:
                tV[n] = 0.0
                tNp[a] = tA
            else:
                tE = tZ[p, a] + tct[p] + h * tkt[p]
                tV[n] = (-(tA + tkt[p] * u[n] + kt * tu[p, n]) - Vn[n] * tE) / E
                tNp[a] = tA + tZ[p, a] * Vn[n] + Z[a] * tV[n]
            J[s, p] = tV[0]
            for j in range(n):
                tN[p, j] = tNm[j] + tNp[j] - tN[p, j]
                tv[p, j] = tV[j] + tV[j + 1] - tv[p, j]
            for i in range(n + 1):
                tu[p, i] += tV[i] * dt
        for j in range(n):
            N[j] = Nm[j] + Np[j] - N[j]
            v[j] = Vn[j] + Vn[j + 1] - v[j]
        for i in range(n + 1):
            u[i] += Vn[i] * dt
    return y, J
