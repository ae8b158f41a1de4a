"""The boundary step of the lattice, shared by every compiled solver: the outer end laws (:func:`end_solve`) and
everything of one step that is not a plain interior node (:func:`boundaries`: ends, junctions, loaded and
frictional nodes, probes).

The forward loops of :mod:`rodimpact.direct._kernels` and :mod:`rodimpact.direct._batch_kernels`, the adjoint of
:mod:`rodimpact.design` and the rectangular-pulse response of :mod:`rodimpact.inverse` all use these functions,
so they form a public module rather than private kernels imported across packages (docs/architecture.md). The
array layout and the symbols are those documented in :mod:`rodimpact.direct._kernels`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .joints import joint_solve
from .soil import SOIL_TOE, shaft_soil, toe_soil

#: end-law codes (``end_code``) and junction codes (``junction_code``) of the kernel arrays
FREE, FIXED, FORCE, VELOCITY, NONREFLECTING, SPRING, BITROCK = 0, 1, 2, 3, 4, 5, 6   # SOIL_TOE = 8: .soil
BONDED, CONTACT, SPRING_DASHPOT, LAW_JOINT = 0, 1, 2, 3

#: slots of the work and impulse accumulator ``acc``: [W_left, W_right, W_loads, W_friction, I_left, I_right,
#: I_loads, I_friction, W_joints, W_soil, I_soil] (J and N s); joint forces act on both faces and carry no net
#: impulse. W_soil and I_soil are those of the shaft soil (rodimpact.direct.soil); a soil toe's work and impulse
#: are those of its end (W_right or W_left), like every end law's
ACC_SLOTS = 11


@njit(inline="always", error_model="numpy", cache=True)
def end_solve(code, a, z, value, p0, p1, delta, delta_max, dt):
    """Solve one outer end for the outward velocity w and the end force N.

    The element side gives N = a + z w (a = N + Z v at a left end, N - Z v at a right end; eqs. 3.16-3.19),
    the device gives a second relation. Returns (w, N, new delta_max).

    The node force is constant during the step while the end moves at the constant w, so delta runs linearly
    from delta to delta + w dt. A displacement-dependent device acts with the mean of its force over that
    path: then the impulse N dt and the work N w dt are exactly those of the continuous law along the path.
    For the linear spring this mean is the force at the midpoint delta + w dt/2. The bit-rock law F (force on
    the bit, N = -F) is piecewise linear in delta given delta_max: 0 up to the release point
    r = delta_max (1 - k1/k2), slope k2 up to delta_max, then virgin loading k1 delta. With s = w dt,
    a + z s/dt + (1/s) int_delta^{delta+s} F = 0 is solved exactly: the pieces are walked in the direction of
    motion until the one holding the root, where the equation (times s) is a quadratic in s. A load reversal
    or release inside the step is thereby located exactly, and the scheme stays second order
    (tests/direct/test_bitrock_order.py). delta_max is the largest end displacement at the ends of the steps,
    i.e. the largest penetration of the (piecewise-linear) path.
    """
    h = 0.5 * dt
    if code == SOIL_TOE:        # solved by toe_soil after this (the soil arrays are not end parameters)
        w, n = 0.0, 0.0
    elif code == FREE or code == FORCE:
        n = value
        w = (n - a) / z
    elif code == FIXED:
        w = 0.0
        n = a
    elif code == VELOCITY:
        w = value
        n = a + z * w
    elif code == NONREFLECTING:
        w = (p1 - a) / (z + p0)
        n = a + z * w
    elif code == SPRING:
        w = -(a + p0 * delta) / (z + p1 + p0 * h)
        n = a + z * w
    else:  # BITROCK: a s + (z/dt) s^2 + int_delta^{delta+s} F = 0, s = w dt the path of the step
        k1 = p0
        k2 = p1
        pm = delta_max
        r = pm - k1 * pm / k2                   # release point of the unloading line
        zd = z / dt
        if delta <= r:                          # F at the start of the path
            f = 0.0
        elif delta < pm:
            f = k1 * pm + k2 * (delta - pm)
        else:
            f = k1 * delta
        up = a + f < 0.0                        # the end moves into the rock
        sign = 1.0 if up else -1.0
        # pieces of F: 0 released (up to r), 1 unloading/reloading (r to delta_max, slope k2), 2 virgin (k1)
        piece = (0 if delta < r else (1 if delta < pm else 2)) if up else (0 if delta <= r else 1)
        sb = 0.0                                # start of the current piece relative to delta
        jb = 0.0                                # integral of F from delta to the start of the piece
        while (up and piece < 2) or (not up and piece > 0):
            nxt = pm if up and piece == 1 else r   # end of the piece in the direction of motion
            c = k2 if piece == 1 else 0.0
            sn = nxt - delta
            jn = jb + (f + 0.5 * c * (sn - sb)) * (sn - sb)
            if a * sn + zd * sn * sn + jn >= 0.0:  # the root lies in this piece
                break
            sb = sn
            jb = jn
            f = k1 * pm if up and piece == 1 else 0.0    # F at the crossed breakpoint
            piece += 1 if up else -1
        c = k1 if piece == 2 else (k2 if piece == 1 else 0.0)
        # in the piece: A u^2 + B u + C = 0 for u = s - sb, the root in the direction of motion (C <= 0)
        qa = zd + 0.5 * c
        qb = sign * (a + 2.0 * zd * sb + f)
        qc = a * sb + zd * sb * sb + jb
        root = np.sqrt(qb * qb - 4.0 * qa * qc)
        u = -2.0 * qc / (qb + root) if qb > 0.0 else (root - qb) / (2.0 * qa)
        w = (sb + sign * u) / dt
        n = a + z * w
        q = delta + w * dt
        if q > pm:
            delta_max = q
    return w, n, delta_max


@njit(error_model="numpy", cache=True)
def law_joint_force(q, par, r, mu, s0, delta, dt):
    """Face force of the law joint ``r`` in this step (:func:`rodimpact.direct.joints.joint_solve`, which also
    advances its state ``q[r]``).

    ``q`` is None when the system has no law joint (:func:`law_state`). Numba prunes the branch on a None
    argument at compile time, so the step loops of such systems contain no call into the joint solver: its mere
    presence in the inlined boundary step cost the thesis-scale run 50 % more time (0.73 ms against 0.45 ms,
    docs/performance.md), although it was never taken there."""
    if q is None:
        return 0.0
    return joint_solve(par[r], q[r], mu, s0, delta, dt)


def law_state(junction_code: np.ndarray, junction_q: np.ndarray) -> np.ndarray | None:
    """The joint states as the step loops take them: ``junction_q``, or None if no junction is a law joint
    (then the loops are compiled without the joint solver, :func:`law_joint_force`)."""
    return junction_q if np.any(junction_code == LAW_JOINT) else None


@njit(error_model="numpy", cache=True)
def fresh_law_state(q):
    """Zeroed joint states shaped like ``q`` (one run's start), or None for a system without law joints."""
    if q is None:
        return None
    return np.zeros_like(q)


@njit(inline="always", error_model="numpy", cache=True)
def boundaries(out, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes):
    """Everything of one step that is not a plain interior node: the two outer ends, the junctions,
    loaded/frictional interior nodes and the probes. Uses only the element states at t_k; writes node
    forces/velocities of each rod's first and last node into rod_NL/rod_VL/rod_NR/rod_VR and the resolved
    node forces of special nodes into sp_F. ``out`` is the step's column in the per-step inputs and outputs. The
    arrays come grouped in tuples (see :func:`run_numba`) so that the compiler can inline this function into the
    step loop."""
    end_code, end_par, end_state, end_value = ends
    junction_code, junction_state, gap, gap_tol, u_end, junction_par, junction_q = junctions
    sp_elem, sp_cap, sp_force, sp_F, sp_V, soil = specials
    pr_rod, pr_local, pr_sp, pr_N, pr_V, pr_u, pr_disp = probes
    junction_N, junction_contact, end_N, end_V = outputs
    rod_NL, rod_VL, rod_NR, rod_VR = rod_nodes
    n_rods = rod_start.size - 1
    n_el = rod_start[n_rods]
    # ---- left end of rod 0: element side N^- = N_0 + Z_0 v_0 - Z_0 V, outward w = -V
    w, nn, dm = end_solve(end_code[0], N[0] + Z[0] * v[0], Z[0], end_value[0, out], end_par[0, 0],
                          end_par[0, 1], end_state[0, 0], end_state[0, 1], dt)
    w, nn = toe_soil(soil, end_code[0], sp_elem.size, N[0] + Z[0] * v[0], Z[0], dt, w, nn)
    end_state[0, 0] += w * dt
    end_state[0, 1] = dm
    rod_NL[0] = nn
    rod_VL[0] = -w
    acc[0] += nn * w * dt
    acc[4] += -nn * dt
    end_N[0, out] = nn
    end_V[0, out] = -w
    # ---- right end of the last rod: N^+ = N - Z v + Z V, outward w = V
    e = n_el - 1
    w, nn, dm = end_solve(end_code[1], N[e] - Z[e] * v[e], Z[e], end_value[1, out], end_par[1, 0],
                          end_par[1, 1], end_state[1, 0], end_state[1, 1], dt)
    w, nn = toe_soil(soil, end_code[1], sp_elem.size + 1, N[e] - Z[e] * v[e], Z[e], dt, w, nn)
    end_state[1, 0] += w * dt
    end_state[1, 1] = dm
    rod_NR[n_rods - 1] = nn
    rod_VR[n_rods - 1] = w
    acc[1] += nn * w * dt
    acc[5] += nn * dt
    end_N[1, out] = nn
    end_V[1, out] = w
    # ---- junctions between rod r (element a) and rod r + 1 (element b)
    for r in range(n_rods - 1):
        a = rod_start[r + 1] - 1
        b = a + 1
        za = Z[a]
        zb = Z[b]
        va_free = v[a] - N[a] / za
        vb_free = v[b] + N[b] / zb
        code = junction_code[r]
        if code == SPRING_DASHPOT or code == LAW_JOINT:
            # faces: V_a = va_free + N/za, V_b = vb_free - N/zb; shortening rate s = V_a - V_b = N mu + s0
            s0 = va_free - vb_free
            if code == SPRING_DASHPOT:
                # law at the step's midpoint: N = -(k (delta + s dt/2) + c s), delta = -gap (linear in N: exact)
                k = junction_par[r, 0]
                kc = k * 0.5 * dt + junction_par[r, 1]
                nj = -(k * (-gap[r]) + kc * s0) / (1.0 + kc * (1.0 / za + 1.0 / zb))
                if junction_par[r, 2] != 0.0 and nj > 0.0:      # compression only: the faces separate
                    nj = 0.0
            else:   # a constitutive law: one monotone scalar equation, bracketed root (rodimpact.direct.joints)
                nj = law_joint_force(junction_q, junction_par, r, 1.0 / za + 1.0 / zb, s0, -gap[r], dt)
            rod_NR[r] = nj
            rod_NL[r + 1] = nj
            rod_VR[r] = va_free + nj / za
            rod_VL[r + 1] = vb_free - nj / zb
            junction_N[r, out] = nj
            junction_contact[r, out] = 1.0 if nj < 0.0 or junction_par[r, 2] == 0.0 else 0.0
            acc[8] += nj * (rod_VR[r] - rod_VL[r + 1]) * dt
        else:
            if code == CONTACT and junction_state[r] == 0:
                # re-contact if the gap closes within the first half of the step, by more than rounding
                if gap[r] + 0.5 * (vb_free - va_free) * dt <= -gap_tol[r]:
                    junction_state[r] = 1
            touching = code == BONDED or junction_state[r] == 1
            if touching:
                vn = (N[b] - N[a] + za * v[a] + zb * v[b]) / (za + zb)
                nj = N[a] + za * (vn - v[a])
                # unilateral: only a compressive force keeps the rods together; a force that is zero to
                # rounding (e.g. equal impedances after the pulse has passed) counts as separation
                scale = abs(N[a]) + abs(N[b]) + za * abs(v[a]) + zb * abs(v[b])
                if code == CONTACT and nj >= -1e-13 * scale:
                    junction_state[r] = 0
                    touching = False
            if touching:
                rod_NR[r] = nj
                rod_NL[r + 1] = nj
                rod_VR[r] = vn
                rod_VL[r + 1] = vn
                junction_N[r, out] = nj
            else:
                rod_NR[r] = 0.0
                rod_NL[r + 1] = 0.0
                rod_VR[r] = va_free
                rod_VL[r + 1] = vb_free
                junction_N[r, out] = 0.0
            junction_contact[r, out] = 1.0 if touching else 0.0
        gap[r] += (rod_VL[r + 1] - rod_VR[r]) * dt
    # ---- loaded, frictional and soil interior nodes (Coulomb law solved exactly: stick if the driving force
    #      fits; the Smith soil by a bracketed root, rodimpact.direct.soil)
    for i in range(sp_elem.size):
        a = sp_elem[i]
        zs = Z[a] + Z[a + 1]
        f_load = sp_force[i, out]
        v0 = (f_load + N[a + 1] - N[a] + Z[a] * v[a] + Z[a + 1] * v[a + 1]) / zs
        cap = sp_cap[i]
        f_fric = 0.0
        vn = v0
        if cap > 0.0:
            if abs(v0) * zs <= cap:
                f_fric = -v0 * zs
                vn = 0.0
            else:
                f_fric = -cap if v0 > 0.0 else cap
                vn = v0 + f_fric / zs
        f_node = f_load + f_fric
        f_node, vn = shaft_soil(soil, i, f_node, vn, zs, dt, acc)   # Smith soil (no-op without soil)
        sp_F[i] = f_node
        sp_V[i] = vn
        acc[2] += f_load * vn * dt
        acc[3] += f_fric * vn * dt
        acc[6] += f_load * dt
        acc[7] += f_fric * dt
    # ---- probes: node values during step k (force = N^+ of the element left of the node) and the node
    #      displacement at t_k; then advance the displacement exactly, u(k+1) = u(k) + V dt
    for p in range(pr_rod.size):
        r = pr_rod[p]
        m = pr_local[p]
        n_r = rod_start[r + 1] - rod_start[r]
        if m == 0:
            nn = rod_NL[r]
            vn = rod_VL[r]
        elif m == n_r:
            nn = rod_NR[r]
            vn = rod_VR[r]
        else:
            a = rod_start[r] + m - 1
            if pr_sp[p] >= 0:
                vn = sp_V[pr_sp[p]]
            else:
                vn = (N[a + 1] - N[a] + Z[a] * v[a] + Z[a + 1] * v[a + 1]) / (Z[a] + Z[a + 1])
            nn = N[a] + Z[a] * (vn - v[a])
        pr_N[p, out] = nn
        pr_V[p, out] = vn
        pr_u[p, out] = pr_disp[p]
        pr_disp[p] += vn * dt
    for r in range(n_rods):
        u_end[r, 0] += rod_VL[r] * dt
        u_end[r, 1] += rod_VR[r] * dt
