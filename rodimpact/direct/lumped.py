"""Lumped chains of point masses and cushions (a pile-driving hammer: ram, hammer cushion, helmet, pile cushion)
at an outer end or between two rods, and the exact path-mean solve of the bilinear (bit-rock) law they share
with :class:`~rodimpact.BitRockEnd`; used by :func:`rodimpact.direct.boundary.boundaries`.

**The chain.** Nodes (rod faces and masses) alternate with links (cushions, or the unilateral contact of a mass
with a rod face), numbered along the chain's direction y: from the outside towards the rod face at an outer
end (y = +x at a left end, -x at a right end), from the left rod's face to the right rod's face in a joint.
U_j is the velocity of node j along y during the step (a mass's midpoint velocity) and C_l >= 0 the
compressive force of link l between nodes l and l + 1. Each node's velocity is linear in the forces of its two
links, U_j = U0_j + g_j (C_{j-1} - C_j) (no link beyond a chain's ends):

* a mass M with velocity V_k at the step's start: U0 = V_k, g = dt / (2 M) (M (V_k+1 - V_k) = (C_{j-1} - C_j) dt
  with U = (V_k + V_k+1) / 2; docs/architecture.md, "Point masses");
* a rod face with impedance z (its characteristic, thesis eqs. 3.16-3.19, N = -C): g = 1/z; U0 = a / z at an
  outer end (a = N + Z v of the end element at a left end, N - Z v at a right end, as :func:`end_solve` takes
  it), the free face velocity at a joint (V^free_a = v_a - N_a / z_a at the first node, V^free_b = v_b + N_b / z_b
  at the last).

So the shortening rate of link l is s_l = U_l - U_{l+1} = s0_l - (g_l + g_{l+1}) C_l with s0_l = U0_l - U0_{l+1}
+ g_l C_{l-1} + g_{l+1} C_{l+1}, and its compression runs linearly from d_k to d_k + s_l dt in the step. A
cushion carries the mean of its law over that path (exact impulse and work, like the bit-rock end):
C_l = Fbar(d_k, s_l dt), the scalar equation that :func:`bilinear_path` solves exactly (with a = -s0 / G,
z = 1 / G, G = g_l + g_{l+1}). A touching contact keeps s_l = 0: C_l = s0_l / G; a separated one carries 0.

**The solve.** The equations of all links form F(C) = C - Fbar(sigma(C)) = 0 with Fbar non-decreasing in the
path sigma, which falls with C_l and rises with C_{l-1}, C_{l+1}: F is an M-function (off-diagonally antitone,
strictly diagonally dominant), for which nonlinear Gauss-Seidel with exact scalar solves converges from any
start (W. C. Rheinboldt, On M-functions and their application to nonlinear Gauss-Seidel iterations and to
network flows, J. Math. Anal. Appl. 32 (1970) 274-307). Sweeps run until no force changes by more than
:data:`TOLERANCE` of the largest; the coupling through a mass is
(k dt / 2) dt / (2 M) against 1, so a few sweeps suffice for dt well below the chain's periods (docs/lumped.md: at
most 5 for the issue's hammer at dt = 10 us). Chosen over a safeguarded Newton iteration because each scalar
solve is exact and bracketed (the law's kinks at release and return to virgin loading need no smoothing) and the
sweeps cannot diverge. They contract slowly only when a mass is so light that dt / (2 M) is large against a
cushion's compliance 1 / (k dt) (the forces on its two sides then nearly equal each other); after
:data:`MAX_SWEEPS` sweeps Newton's method with a backtracking line search takes over from the sweeps' iterate
(:func:`_newton`; the Jacobian is a tridiagonal M-matrix). Contacts: an active-set pass around the sweeps: a
touching contact whose force would be tensile (C <= 1e-13 of its terms) separates, a separated one whose gap
closes within the first half of the step touches (each at most once per step), and the sweeps are repeated.

**The update.** From the converged forces: U_j, each mass V_k+1 = 2 U_j - V_k, each link's path
sigma_l = (U_l - U_{l+1}) dt (a cushion's compression d, its largest compression d_max and its work
W += C_l sigma_l; a separated contact's compression, i.e. minus its gap). The masses' kinetic energy changes by
exactly the work of their link forces (M (V_k+1^2 - V_k^2) / 2 = (C_{j-1} - C_j) U_j dt), the cushions take
exactly the work of the mean force over their paths, and the rod faces the work of their forces: the balance
closes to the sweeps' tolerance.

Array layout (``lumped = (n_items, kind, par, state, contact)``, one row per chain place: 0 the left end, 1 the
right end, 2 + r junction r): ``n_items[row]`` (0: no chain there); ``kind[row, i]`` :data:`MASS` or
:data:`CUSHION`; ``par[row, i]`` = (M, 0) or (k, k / e^2); ``state[row, i]`` = (V, 0, 0) of a mass, (d, d_max,
W) of a cushion; ``contact[row, c]`` = (touching, compression) of the contact at the first (c = 0) and last
(c = 1) rod face, used where a mass sits next to that face.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: item kinds of ``kind``
MASS, CUSHION = 0, 1
#: the largest change of a link force relative to the largest force below which the iteration stops, and the
#: most Gauss-Seidel sweeps per contact configuration before Newton's method takes over
TOLERANCE, MAX_SWEEPS = 2e-15, 50
#: a touching contact separates when its force is below this fraction of the terms it is made of (rounding)
SEPARATION = 1e-13


@njit(inline="always", error_model="numpy", cache=True)
def bilinear_path(a, z, k1, k2, delta, delta_max, dt):
    """Solve a + z s/dt + (1/s) int_delta^{delta+s} F = 0 for the path s = w dt of one step (w the velocity
    along the compression) with the bilinear compression-only law F: 0 up to the release point
    r = delta_max (1 - k1/k2), slope k2 up to delta_max, then virgin loading k1 delta. Returns (w, N, new
    delta_max) with N = a + z w = -Fbar, the mean of F over the path.

    Multiplied by s the equation is a s + (z/dt) s^2 + int_delta^{delta+s} F = 0. The pieces are walked in the
    direction of motion until the one holding the root, where the equation (times s) is a quadratic in s. A
    load reversal or release inside the step is thereby located exactly, and the scheme stays second order
    (tests/direct/test_bitrock_order.py). delta_max is the largest compression at the ends of the steps, i.e.
    the largest of the (piecewise-linear) path. The bit-rock end (:func:`rodimpact.direct.boundary.end_solve`)
    and the cushions of a lumped chain use it."""
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
def _link_force(q, C, U0, g, link, row, par, state, contact, dt):
    """The force of link ``q`` that solves its own equation exactly, its neighbours' forces held (one Gauss-Seidel
    update; its shortening rate is s = s0 - G C)."""
    m = C.size
    cl = C[q - 1] if q > 0 else 0.0
    cr = C[q + 1] if q + 1 < m else 0.0
    s0 = U0[q] - U0[q + 1] + g[q] * cl + g[q + 1] * cr
    gg = g[q] + g[q + 1]
    i = link[q]
    if i >= 0:           # a cushion: C = Fbar(d, s dt), s = s0 - G C
        c = -bilinear_path(-s0 / gg, 1.0 / gg, par[row, i, 0], par[row, i, 1], state[row, i, 0], state[row, i, 1],
                           dt)[1]
    elif contact[row, -1 - i, 0] != 0.0:     # a touching contact: s = 0
        c = s0 / gg
    else:
        c = 0.0
    return c


@njit(error_model="numpy", cache=True)
def path_mean(d, d_max, k1, k2, sigma):
    """The mean Fbar of the bilinear law over the path from d to d + sigma within one step, and dFbar/dsigma. Along
    a path that starts at d <= d_max the law is one function of the compression, F(x) = max(0, min(k1 x,
    k1 d_max + k2 (x - d_max))) (k2 >= k1); its integral is summed piece by piece (trapezoids of the linear
    pieces: no cancellation for short paths)."""
    r = d_max - k1 * d_max / k2
    lo = min(d, d + sigma)
    hi = max(d, d + sigma)
    total = 0.0
    a = lo
    for b in (r, d_max, hi):         # breakpoints inside (lo, hi), then hi
        b = min(max(b, a), hi)
        if b > a:
            fa = max(0.0, min(k1 * a, k1 * d_max + k2 * (a - d_max)))
            fb = max(0.0, min(k1 * b, k1 * d_max + k2 * (b - d_max)))
            total += 0.5 * (fa + fb) * (b - a)
            a = b
    end = d + sigma
    f_end = max(0.0, min(k1 * end, k1 * d_max + k2 * (end - d_max)))
    if sigma == 0.0:
        f0 = max(0.0, min(k1 * d, k1 * d_max + k2 * (d - d_max)))
        slope = 0.0 if d < r else (k2 if d < d_max else k1)
        return f0, 0.5 * slope
    mean = total / (hi - lo)
    return mean, (f_end - mean) / sigma


@njit(error_model="numpy", cache=True)
def _newton(U0, g, link, C, row, par, state, contact, dt):
    """Newton's method with a backtracking line search on the whole chain, from the Gauss-Seidel iterate: for
    chains whose sweeps contract slowly (a mass so light that dt / (2 M) is not small against the cushions'
    compliance, where the forces on its two sides nearly equal each other). The Jacobian of the residuals
    r_l = C_l - Fbar_l (cushions), C_l - s0_l / G_l (touching contacts), C_l (separated) is tridiagonal; it is
    an M-matrix, solved by the Thomas algorithm."""
    m = C.size
    res = np.empty(m)
    low = np.empty(m)
    diag = np.empty(m)
    up = np.empty(m)
    trial = np.empty(m)

    def residual(x, out, jac):
        norm = 0.0
        for q in range(m):
            cl = x[q - 1] if q > 0 else 0.0
            cr = x[q + 1] if q + 1 < m else 0.0
            s0 = U0[q] - U0[q + 1] + g[q] * cl + g[q + 1] * cr
            gg = g[q] + g[q + 1]
            i = link[q]
            if i >= 0:
                fm, dfm = path_mean(state[row, i, 0], state[row, i, 1], par[row, i, 0], par[row, i, 1],
                                    (s0 - gg * x[q]) * dt)
                out[q] = x[q] - fm
                if jac:
                    diag[q] = 1.0 + dfm * dt * gg
                    low[q] = -dfm * dt * g[q]
                    up[q] = -dfm * dt * g[q + 1]
            elif contact[row, -1 - i, 0] != 0.0:
                out[q] = x[q] - s0 / gg
                if jac:
                    diag[q] = 1.0
                    low[q] = -g[q] / gg
                    up[q] = -g[q + 1] / gg
            else:
                out[q] = x[q]
                if jac:
                    diag[q] = 1.0
                    low[q] = 0.0
                    up[q] = 0.0
            norm += out[q] * out[q]
        return norm

    norm = residual(C, res, True)
    for _ in range(100):
        # Thomas algorithm: (low, diag, up) delta = res
        for q in range(1, m):
            w = low[q] / diag[q - 1]
            diag[q] -= w * up[q - 1]
            res[q] -= w * res[q - 1]
        res[m - 1] /= diag[m - 1]
        for q in range(m - 2, -1, -1):
            res[q] = (res[q] - up[q] * res[q + 1]) / diag[q]
        step = 1.0
        scale = 0.0
        change = 0.0
        for q in range(m):
            scale = max(scale, abs(C[q]))
            change = max(change, abs(res[q]))
        while True:
            for q in range(m):
                trial[q] = C[q] - step * res[q]
            new = residual(trial, low, False)
            if new <= (1.0 - 1e-4 * step) * norm or step < 1e-12:
                break
            step *= 0.5
        C[:] = trial
        if change <= TOLERANCE * scale or new == 0.0:
            break
        norm = residual(C, res, True)


@njit(error_model="numpy", cache=True)
def _sweeps(U0, g, link, C, row, par, state, contact, dt):
    """Nonlinear Gauss-Seidel sweeps over the links (module docstring) until the forces ``C`` settle; if they have
    not after :data:`MAX_SWEEPS`, Newton's method from there (:func:`_newton`)."""
    m = C.size
    for _ in range(MAX_SWEEPS):
        change = 0.0
        scale = 0.0
        for q in range(m):
            c = _link_force(q, C, U0, g, link, row, par, state, contact, dt)
            change = max(change, abs(c - C[q]))
            scale = max(scale, abs(c))
            C[q] = c
        if change <= TOLERANCE * scale:
            return
    _newton(U0, g, link, C, row, par, state, contact, dt)


@njit(error_model="numpy", cache=True)
def chain_step(lumped, row, u_first, g_first, u_last, g_last, dt):
    """Advance the chain ``row`` by one step and return (C_first, C_last): the force of its first and last link
    (compression positive), from which the faces' velocities follow by their characteristics. A joint
    gives ``g_first`` > 0 (its first node is the left rod's face, U0 = ``u_first``); an outer end gives
    ``g_first = 0`` (its first node is the outermost mass). The last node is always a rod face."""
    n_items, kind, par, state, contact = lumped
    n = n_items[row]
    face = g_first > 0.0
    n_mass = 0
    for i in range(n):
        if kind[row, i] == MASS:
            n_mass += 1
    m = n_mass + (2 if face else 1)         # nodes
    U0 = np.empty(m)
    g = np.empty(m)
    link = np.empty(m - 1, dtype=np.int64)  # item index of a cushion; -1, -2: contact at the first, last face
    j = 0
    q = 0
    node_before = face
    if face:
        U0[0] = u_first
        g[0] = g_first
        j = 1
    for i in range(n):
        if kind[row, i] == MASS:
            if node_before:
                link[q] = -1
                q += 1
            U0[j] = state[row, i, 0]
            g[j] = 0.5 * dt / par[row, i, 0]
            j += 1
            node_before = True
        else:
            link[q] = i
            q += 1
            node_before = False
    if node_before:
        link[q] = -2
    U0[m - 1] = u_last
    g[m - 1] = g_last
    C = np.zeros(m - 1)
    switched = np.zeros(2)
    for _ in range(3):                      # active set of the contacts: each switches at most once per step
        _sweeps(U0, g, link, C, row, par, state, contact, dt)
        again = False
        for q in range(m - 1):
            if link[q] >= 0 or switched[-1 - link[q]] != 0.0:
                continue
            c = -1 - link[q]
            cl = C[q - 1] if q > 0 else 0.0
            cr = C[q + 1] if q + 1 < m - 1 else 0.0
            if contact[row, c, 0] != 0.0:
                terms = (abs(U0[q]) + abs(U0[q + 1]) + g[q] * abs(cl) + g[q + 1] * abs(cr)) / (g[q] + g[q + 1])
                if C[q] <= SEPARATION * terms:
                    contact[row, c, 0] = 0.0
                    C[q] = 0.0
                    switched[c] = 1.0
                    again = True
            else:
                s = U0[q] - U0[q + 1] + g[q] * cl + g[q + 1] * cr
                if contact[row, c, 1] + 0.5 * s * dt > 0.0:     # the gap closes within the first half step
                    contact[row, c, 0] = 1.0
                    switched[c] = 1.0
                    again = True
        if not again:
            break
    # the step's node velocities from the forces, then the states at its end
    j = 0
    q = 0
    for i in range(-1 if face else 0, n + 1):
        if i == -1 or i == n or kind[row, i] == MASS:       # a node
            cl = C[j - 1] if j > 0 else 0.0
            cr = C[j] if j < m - 1 else 0.0
            U = U0[j] + g[j] * (cl - cr)
            if 0 <= i < n:
                state[row, i, 0] = 2.0 * U - U0[j]
            U0[j] = U                       # from here on: the node velocities
            j += 1
    for q in range(m - 1):
        sigma = (U0[q] - U0[q + 1]) * dt
        i = link[q]
        if i >= 0:
            d = state[row, i, 0] + sigma
            state[row, i, 0] = d
            if d > state[row, i, 1]:
                state[row, i, 1] = d
            state[row, i, 2] += C[q] * sigma
        elif contact[row, -1 - i, 0] == 0.0:
            contact[row, -1 - i, 1] += sigma
    return C[0], C[m - 2]


@njit(error_model="numpy", cache=True)
def lumped_end(lumped, row, a, z, dt):
    """The outward velocity w and force N of the rod face at outer end ``row`` (0 left, 1 right) carrying a
    lumped chain, the face obeying N = a + z w (:func:`rodimpact.direct.boundary.end_solve`): the last node's
    velocity along the chain is U = (a + C) / z = -w and N = -C. ``lumped`` is None when the system has no chain:
    numba prunes the branch at compile time, so the step loops of such systems contain no call into the chain
    solver (as :func:`rodimpact.direct.boundary.law_joint_force`)."""
    if lumped is None:
        return 0.0, 0.0
    c_last = chain_step(lumped, row, 0.0, 0.0, a / z, 1.0 / z, dt)[1]
    return -(a + c_last) / z, -c_last


@njit(error_model="numpy", cache=True)
def lumped_joint(lumped, r, va_free, za, vb_free, zb, dt):
    """Face forces and velocities (N_a, N_b, V_a, V_b) of junction ``r`` carrying a lumped chain, between the right
    face of element a (free velocity ``va_free``, impedance ``za``) and the left face of element b: N_a = -C_first,
    V_a = V_a^free - C_first / z_a, N_b = -C_last, V_b = V_b^free + C_last / z_b. None-pruned like
    :func:`lumped_end`."""
    if lumped is None:
        return 0.0, 0.0, 0.0, 0.0
    c_first, c_last = chain_step(lumped, 2 + r, va_free, 1.0 / za, vb_free, 1.0 / zb, dt)
    return -c_first, -c_last, va_free - c_first / za, vb_free + c_last / zb


def chain_energies(lumped: tuple, row: int) -> tuple[float, float, float]:
    """Kinetic energy of the masses, energy stored in the cushions (the area under the unloading line,
    k2 (d - r)^2 / 2 above the release point r = d_max (1 - k1/k2), what the cushion would give back) and the
    work the cushions have taken in total (J) of chain ``row`` at its current state."""
    n_items, kind, par, state, _ = lumped
    kinetic = stored = work = 0.0
    for i in range(int(n_items[row])):
        if kind[row, i] == MASS:
            kinetic += 0.5 * par[row, i, 0] * state[row, i, 0] ** 2
        else:
            k1, k2 = par[row, i]
            d, d_max, w = state[row, i]
            release = d_max - k1 * d_max / k2
            stored += 0.5 * k2 * (d - release) ** 2 if d > release else 0.0
            work += w
    return float(kinetic), float(stored), float(work)
