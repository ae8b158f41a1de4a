"""The compiled Smith soil law of the boundary step (:mod:`rodimpact.rods.soil`, docs/soil.md): one scalar
equation per soil node and step, solved piece by piece of the static law (:func:`node_root`).

Arrays (one row per special node of the lattice, then the left and the right end; rows that carry no soil have
``par[row, ACTIVE] == 0``):

* ``soil_par[row]`` = (active, R_u, k, k_u, lo, J, c): ultimate resistance (N), loading and unloading stiffness
  (N/m), lower limit of R_s (-R_u along the shaft, 0 at a compression-only toe), the Smith factor J (s/m,
  R_d = J |R_s| V) and the dashpot c (N s/m, R_d = c V: smith-viscous c = J_sv R_u, Case c = J_c Z);
* ``soil_state[row]`` = (u, R_s, u_p, W): displacement since the start (m, +x along the shaft, outward at an
  end), static resistance (N), plastic set (m) and the work done by the pile on the soil (J).

**The node equation.** During step k the node moves at the constant velocity V, so its displacement runs
linearly from u to u + s, s = V dt. The static part acts with its exact mean over that path,
Rbar(s) = (1/s) int_u^{u+s} R_s (piecewise linear in the path: loading, unloading, the plastic plateau and, at
the toe, the gap are located exactly, :func:`static_path`); then the impulse Rbar dt and the work Rbar s are
those of the continuous law along the path, and the soil's work closes the energy balance to rounding. The
node relation V = v0 + F / zs (the face relations with the soil force F = -R, zs = Z_a + Z_b inside a rod, Z at
an end) gives

    g(V) = zs (V - v0) + Rbar(V dt) + R_d(V) = 0,   R_d = J |Rbar| V  or  c V

(at a compression-only toe the sum Rbar + R_d is clipped to >= 0: the soil never pulls).

Rbar is non-decreasing in V (the mean of a function non-decreasing along the path), so g is strictly increasing
for the linear dashpot. For the Smith product, d/dV (J |Rbar| V) = J |Rbar| + J V d|Rbar|/dV can be negative
while the node unloads (|Rbar| falls), by at most J |V| k dt / 2; g stays increasing while
zs > J |V| k dt / 2 (always, for practical piles and time steps). g(0) = -zs v0 + R_s (clipped at a toe) gives
the direction of motion d; the root is the first one in that direction (the only one where g is increasing).

**The solve** (:func:`node_root`). With p = |s| the path length, the law's pieces (:func:`law_piece`: unloading,
loading, plateau, toe gap) are walked in the direction of motion as in :func:`static_path`, and h(p) = d g(d p /
dt) is evaluated exactly at the end of each piece until h >= 0 there. On that piece R_s is linear in p, the
integral j = int R_s ds a quadratic, Rbar = d j / p, and the damping J |Rbar| V = J |j| / dt (Smith) or c V
is a quadratic or linear in p: h is a smooth rational function of p (with a kink only where j changes sign or the
toe's resistance reaches 0), solved by Newton's method with the analytic derivative, safeguarded by bisection in
the piece's bracket and stopped at a step of a few units in the last place. Against the bracket + bisection it
replaced (to adjacent floating-point numbers), V agrees to ~3e-13 relative on 20000 random node states, and
the state update (:func:`static_path` at the root) is unchanged, so the energy closure is as before.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: end code of a soil toe (``end_code``, :mod:`rodimpact.direct.boundary`)
SOIL_TOE = 8
#: columns of ``soil_par`` and ``soil_state``
ACTIVE, R_U, K_LOAD, K_UNLOAD, LOW, SMITH_J, DASHPOT = range(7)
PAR_COLUMNS = 7
U, R_S, U_P, WORK = range(4)
STATE_COLUMNS = 4


@njit(inline="always", error_model="numpy", cache=True)
def law_piece(d, r, x, up, ru, kl, ku, lo):
    """The piece of the static law that a path in the direction d = +-1 enters at R_s = ``r``, position ``x``
    (plastic set ``up``, both relative to the step's start): its slope c (R = r + d c t over a distance t of the
    piece), its length t (inf for a plateau) and R_s at its end. Unloading (|R_s| falls to 0, slope k_u),
    loading (|R_s| grows to R_u, slope k), the plateau at +-R_u (c = 0), and at a compression-only toe (lo = 0)
    the gap (R_s = 0 until the contact point u_p)."""
    if d > 0.0:
        if r < 0.0:
            c = ku
            t = -r / ku
            stop = 0.0
        elif r == 0.0 and lo == 0.0 and x < up:
            c = 0.0
            t = up - x
            stop = 0.0
        elif r < ru:
            c = kl
            t = (ru - r) / kl
            stop = ru
        else:
            c = 0.0
            t = np.inf
            stop = ru
    else:
        if r > 0.0:
            c = ku
            t = r / ku
            stop = 0.0
        elif r == 0.0 and lo == 0.0:
            c = 0.0
            t = np.inf
            stop = 0.0
        elif r > lo:
            c = kl
            t = (r - lo) / kl
            stop = lo
        else:
            c = 0.0
            t = np.inf
            stop = lo
    return c, t, stop


@njit(inline="always", error_model="numpy", cache=True)
def static_path(r, up, s, ru, kl, ku, lo):
    """The static resistance along the path from the node's position (where it is ``r``, with plastic set
    ``up`` relative to the position) over the signed distance ``s``: returns (int_0^s R_s, R_s at the end,
    plastic set at the end relative to the start position).

    Walked piece by piece in the direction of motion d = sign(s), R = r + d c t over a distance t of each piece:
    unloading (|R_s| falls to 0, slope k_u), loading (|R_s| grows to R_u, slope k), the plateau at +-R_u (c = 0),
    and at a compression-only toe (lo = 0) the gap (R_s = 0 until the contact point u_p). The plastic set at the
    end is x - R_s / k_u, or, at the toe with R_s = 0, the point where contact resumes."""
    d = 1.0 if s > 0.0 else -1.0
    left = abs(s)
    x = 0.0
    j = 0.0
    for _ in range(6):
        if left <= 0.0:
            break
        c, t, stop = law_piece(d, r, x, up, ru, kl, ku, lo)
        if t >= left:
            j += d * r * left + 0.5 * c * left * left
            r = r + d * c * left
            x += d * left
            left = 0.0
        else:
            j += d * r * t + 0.5 * c * t * t
            r = stop
            x += d * t
            left -= t
            if r == 0.0 and c > 0.0:
                up = x                      # unloaded to zero here: the new zero point
    if r != 0.0 or lo != 0.0:
        up = x - r / ku
    return j, r, up


@njit(inline="always", error_model="numpy", cache=True)
def resistance(par, rbar, v):
    """R = Rbar + R_d, the damping R_d = J |Rbar| V (Smith) or c V (smith-viscous, Case); at a compression-only
    toe (lo = 0) R >= 0: a toe that leaves the soil faster than it springs back separates from it."""
    r = rbar + par[SMITH_J] * abs(rbar) * v + par[DASHPOT] * v
    if par[LOW] == 0.0 and r < 0.0:
        r = 0.0
    return r


@njit(inline="always", error_model="numpy", cache=True)
def _h_piece(par, d, zs, v0, dt, x, j0, rp, c, p):
    """h(p) = d g(d p / dt) and dh/dp at the path length p > 0 on a piece of the static law that starts at the
    path length x, where int_0 R_s = j0 (signed) and R_s = rp, with slope c (R_s = rp + d c (p - x)).

    With tau = p - x: j = j0 + d rp tau + c tau^2 / 2, dj/dp = d R_s(p), Rbar = j / s = d j / p and
    dRbar/dp = d (p dj/dp - j) / p^2; V = d p / dt; R = Rbar + J |Rbar| V + c_d V (clipped at 0 at a
    compression-only toe, where then dR/dp = 0), dR/dp = dRbar/dp (1 + J sgn(Rbar) V) + (J |Rbar| + c_d) d / dt;
    h = d (zs (V - v0) + R), dh/dp = zs / dt + d dR/dp."""
    tau = p - x
    j = j0 + d * rp * tau + 0.5 * c * tau * tau
    dj = d * rp + c * tau
    rbar = d * j / p
    drbar = d * (p * dj - j) / (p * p)
    v = d * p / dt
    sj = par[SMITH_J]
    r = resistance(par, rbar, v)
    if r == 0.0 and par[LOW] == 0.0:
        dr = 0.0
    else:
        dr = drbar * (1.0 + sj * (1.0 if rbar >= 0.0 else -1.0) * v) + (sj * abs(rbar) + par[DASHPOT]) * d / dt
    return d * (zs * (v - v0) + r), zs / dt + d * dr


@njit(error_model="numpy", cache=True)
def node_root(par, st, v0, zs, dt, d, h0):
    """The root V of the node equation g(V) = 0 (module docstring) in the direction d = +-1 from rest, where
    h(p) = d g(d p / dt) < 0 at the path length p = 0 (``h0``).

    The pieces of the static law are walked in the direction of motion (:func:`law_piece`, as
    :func:`static_path` walks them); at the end of each, h is evaluated exactly, and the first piece at whose
    end h >= 0 holds the root. On that piece h is smooth (a rational function of p: the path mean is a
    quadratic over p, the damping its product with p / dt) except where Rbar changes sign (Smith) or the toe's
    resistance is clipped at 0; the root is found by Newton's method safeguarded by bisection in the bracket
    [a, b] (h(a) < 0 <= h(b)), stopped when the step falls to a few units in the last place. On the last
    (unbounded) piece the bracket is closed at p = dt (|v0| + R_max / zs), where h >= 0 since
    d R >= -R_max = -max(|R_s|, R_u, -lo)."""
    ru, kl, ku, lo = par[R_U], par[K_LOAD], par[K_UNLOAD], par[LOW]
    r = st[R_S]
    up = st[U_P] - st[U]
    x = 0.0                              # path length walked
    j = 0.0                              # signed integral of R_s over it
    a, ha = 0.0, h0
    c, rp, xp, jp = 0.0, r, 0.0, 0.0
    b, hb = np.inf, 0.0
    for _ in range(6):
        c, t, stop = law_piece(d, r, d * x, up, ru, kl, ku, lo)
        rp, xp, jp = r, x, j
        if t == np.inf:
            rmax = max(abs(st[R_S]), ru, -lo)
            b = max(x, dt * (abs(v0) + rmax / zs)) * (1.0 + 1e-12) + 1e-300
            hb, _ = _h_piece(par, d, zs, v0, dt, xp, jp, rp, c, b)
            while hb < 0.0:
                b *= 2.0
                hb, _ = _h_piece(par, d, zs, v0, dt, xp, jp, rp, c, b)
            break
        x_end = x + t
        j_end = j + d * r * t + 0.5 * c * t * t
        h_end, _ = _h_piece(par, d, zs, v0, dt, xp, jp, rp, c, x_end)
        if h_end >= 0.0:
            b, hb = x_end, h_end
            break
        a, ha = x_end, h_end
        x, j, r = x_end, j_end, stop
        if r == 0.0 and c > 0.0:
            up = d * x                   # unloaded to zero here: the new zero point
    if hb == 0.0:
        return d * b / dt
    p = a - ha * (b - a) / (hb - ha)     # secant start
    if not (a < p < b):
        p = 0.5 * (a + b)
    for _ in range(200):
        hp, dh = _h_piece(par, d, zs, v0, dt, xp, jp, rp, c, p)
        if hp == 0.0:
            break
        if hp < 0.0:
            a = p
        else:
            b = p
        step = hp / dh if dh > 0.0 else np.inf
        if abs(step) <= 4e-16 * p:       # converged: the Newton step is within a few units in the last place
            p -= step
            break
        q = p - step
        if not (a < q < b):
            q = 0.5 * (a + b)
            if q == a or q == b:         # the bracket has closed to adjacent floating-point numbers
                p = q
                break
        p = q
    return d * p / dt


@njit(inline="always", error_model="numpy", cache=True)
def soil_solve(par, st, v0, zs, dt):
    """The node velocity V (m/s, +x along the shaft, outward at an end) and the soil's resistance R (N) in this
    step, for the velocity ``v0`` the node would have without soil and the impedance sum ``zs``; advances the
    state ``st`` (u, R_s, u_p, W). The root by :func:`node_root` (module docstring). Inlined into its callers
    (:func:`shaft_soil`, :func:`toe_soil`): called as a function with the rows ``par[i]``, ``state[i]`` it cost
    the benchmark's blow (50 pile elements, 41 soil nodes, 1000 steps) 13 ms of CPU time against 10 ms inlined
    (benchmarks/bench_pile.py), with the same results bit for bit."""
    g0 = zs * (0.0 - v0) + resistance(par, st[R_S], 0.0)      # g(0): the node at rest
    v = 0.0 if g0 == 0.0 else node_root(par, st, v0, zs, dt, -1.0 if g0 > 0.0 else 1.0, -abs(g0))
    s = v * dt
    if s == 0.0:
        rbar = st[R_S]
        r_end = st[R_S]
        up = st[U_P] - st[U]
        j = 0.0
    else:
        j, r_end, up = static_path(st[R_S], st[U_P] - st[U], s, par[R_U], par[K_LOAD], par[K_UNLOAD], par[LOW])
        rbar = j / s
    r = resistance(par, rbar, v)
    st[WORK] += r * s
    st[U_P] = st[U] + up
    st[U] += s
    st[R_S] = r_end
    return v, r


@njit(error_model="numpy", cache=True)
def shaft_soil(soil, i, f_node, vn, zs, dt, acc):
    """The soil at special node ``i`` (the boundary step's node force ``f_node`` and velocity ``vn`` without
    soil; zs = Z_a + Z_b): returns them with the soil, the soil's force -R added (N, +x), and adds its work and
    impulse on the pile to ``acc[9]``, ``acc[10]``. ``soil`` is None when the system has no soil: numba prunes
    the branch at compile time, so the step loops of such systems contain no soil code
    (:func:`rodimpact.direct.boundary.law_joint_force`)."""
    if soil is None:
        return f_node, vn
    par, state = soil
    if par[i, ACTIVE] == 0.0:
        return f_node, vn
    v, r = soil_solve(par[i], state[i], vn, zs, dt)
    acc[9] += -r * v * dt
    acc[10] += -r * dt
    return f_node - r, v


@njit(error_model="numpy", cache=True)
def toe_soil(soil, code, row, a, z, dt, w, n):
    """The outward velocity and the force (w, N) of an outer end: those given (of the end law) unless the end is
    a soil toe (``code`` SOIL_TOE, its law in row ``row`` of ``soil_par``), where the element side gives
    N = a + z w and the soil N = -R(w). ``soil`` is None when the system has no soil: numba prunes the rest at
    compile time (a
    branch on the code in the boundary step itself made the step loops of every system 3 times slower at
    n = 1000 elements)."""
    if soil is None or code != SOIL_TOE:
        return w, n
    par, state = soil
    w, r = soil_solve(par[row], state[row], -a / z, z, dt)
    return w, -r


def soil_arrays(arrays: dict) -> tuple[np.ndarray, np.ndarray] | None:
    """The soil of the kernel ``arrays`` as the step loops take it: ``(soil_par, soil_state)``, or None if the
    system has no soil (``has_soil``; then the loops are compiled without the soil solver)."""
    return (arrays["soil_par"], arrays["soil_state"]) if arrays["has_soil"] else None
