"""Numerical kernels of the wave propagation method (thesis Sec. 3.1, eqs. 3.2-3.20).

Symbols as in the thesis: Z = impedance (N s/m), N = normal force (N, tension positive), v = particle
velocity (m/s); N^+ / N^- = force at the right / left end of an element during a step, V = node velocity.

Pure functions on arrays: no objects, no I/O. Two paths share the boundary code
(:func:`rodimpact.direct.boundary.boundaries`, compiled with ``inline="always"`` so that it is inlined into the
compiled step loop; the numpy path runs its Python source ``boundaries.py_func``):

* :func:`run_numpy` -- the readable reference: the bulk of the interior nodes is one vectorised numpy
  expression per step (eqs. 3.6-3.15 literally);
* :func:`run_numba` -- the compiled path (``numba.njit(cache=True)``): the same lattice in travelling-wave
  variables kept in the frame in which they travel, where a node without reflection costs nothing
  (:func:`reflect_blocks`). Two formulations that agree to rounding are a real check.

Both run many steps per call and record inside the loop (the bundles are built by
:class:`rodimpact.direct.recording.Recorder`): every ``stride``-th step of the node histories
(:func:`keep_step`), the contact phases of every step (:func:`track_events`) and the energy sums and field
snapshots at precomputed step indices.

Array layout (all rods concatenated left to right; ``rod_start`` has n_rods + 1 entries):

* end codes 0 free/force, 1 fixed, 2 force, 3 velocity, 4 non-reflecting, 5 spring-dashpot, 6 bit-rock;
  ``end_par[e] = (p0, p1)``: non-reflecting (Z_ext, incoming invariant), spring (k, c), bit-rock (k1, k2);
  ``end_state[e] = (delta, delta_max)``: outward displacement and largest penetration;
  ``end_value[e, i]``: prescribed normal force (codes 0, 2) or outward velocity (code 3) in the i-th step of
  the call.
* junction codes 0 bonded, 1 contact; ``junction_state`` 1 = touching; ``gap`` in m; ``gap_tol`` (m) the
  closing distance below which a separated pair is not re-contacted (rounding of the gap bookkeeping).
* special interior nodes (loads, friction): ``sp_elem`` = element left of the node (ascending),
  ``sp_cap`` = Coulomb friction capacity (N), ``sp_force[i, j]`` = prescribed force (N, +x) in the j-th step of the call.
* ``acc`` accumulates work and impulse: [W_left, W_right, W_loads, W_friction, I_left, I_right, I_loads,
  I_friction] in J and N s.
"""

from __future__ import annotations

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from .boundary import boundaries


# ------------------------------------------------------------------------------------------------ recording
@njit(inline="always", cache=True)
def has_room(events):
    """True if every junction can take one more closed contact phase (at most one closes per step)."""
    _, phases, count = events
    for j in range(count.size):
        if count[j] >= phases.shape[1]:
            return False
    return True


@njit(inline="always", cache=True)
def track_events(k, out, junction_N, junction_contact, events):
    """Contact phases of every junction with step ``k`` (column ``out`` of the step outputs): a phase is a maximal
    run of steps in contact; its peak is the largest |N| in it; the most compressive N (first step) and the
    largest |N| are taken over all steps. Returns True if a junction's buffer of closed phases is now full."""
    state, phases, count = events
    full = False
    for j in range(count.size):
        nj = junction_N[j, out]
        a = abs(nj)
        if nj < state[j, 2]:
            state[j, 2] = nj
            state[j, 3] = k
        if a > state[j, 4]:
            state[j, 4] = a
        if junction_contact[j, out] > 0.5:
            if state[j, 0] < 0.0:
                state[j, 0] = k
                state[j, 1] = a
            elif a > state[j, 1]:
                state[j, 1] = a
        elif state[j, 0] >= 0.0:
            m = count[j]
            phases[j, m, 0] = state[j, 0]
            phases[j, m, 1] = k
            phases[j, m, 2] = state[j, 1]
            count[j] = m + 1
            state[j, 0] = -1.0
            full = full or m + 1 == phases.shape[1]
    return full


@njit(inline="always", cache=True)
def _copy_column(src, out, dst, c):
    for row in range(src.shape[0]):
        dst[row, c] = src[row, out]


@njit(inline="always", cache=True)
def keep_step(out, c, chunk, kept):
    """Copy column ``out`` of the step outputs ``chunk`` (junction N, contact flag, end N, end V, probe N, V, u)
    into column ``c`` of the recorded histories ``kept``."""
    _copy_column(chunk[0], out, kept[0], c)
    _copy_column(chunk[1], out, kept[1], c)
    _copy_column(chunk[2], out, kept[2], c)
    _copy_column(chunk[3], out, kept[3], c)
    _copy_column(chunk[4], out, kept[4], c)
    _copy_column(chunk[5], out, kept[5], c)
    _copy_column(chunk[6], out, kept[6], c)


@njit(cache=True, fastmath={"reassoc", "nsz"})
def _rod_energy(f, g, inv_Z, a, b):
    """Sums over elements a .. b - 1 of (g - f)^2 / Z, (f + g)^2 / Z and g - f: 2 / dt times the kinetic energy
    1/2 m v^2 (m = Z dt, Z v = g - f), 2 / dt times the strain energy 1/2 N^2 dt / Z (N = f + g) and the momentum
    m v / dt. The sums may be reordered (vectorised); the result then differs from a left-to-right sum by
    rounding only."""
    kin = 0.0
    pot = 0.0
    mom = 0.0
    for j in range(a, b):
        d = g[j] - f[j]
        s = f[j] + g[j]
        kin += d * d * inv_Z[j]
        pot += s * s * inv_Z[j]
        mom += d
    return kin, pot, mom


@njit(inline="always", cache=True)
def _take_samples(k, fresh, state, Z, dt, rod_start, acc, u_end, samples):
    """If step ``k`` is a sample step: the energy sums per rod (thesis eq. 3.25: kinetic 1/2 m v^2 with m = Z dt,
    strain 1/2 N^2 dt / Z, momentum m v) with the work/impulse accumulators, and the fields N, v, u (node
    displacement = left-end displacement + element elongations (N - N0) dt / Z). The waves (f, g) hold the
    state at t = k dt; (N, v) too if ``fresh``, else they are brought up to date first."""
    N, v, f, g = state
    e_steps, s_steps, cursor, e_kin, e_pot, e_mom, e_acc, s_N, s_v, s_u, N0, inv_Z = samples
    n_rods = rod_start.size - 1
    m = cursor[0]
    if m < e_steps.size and e_steps[m] == k:
        for r in range(n_rods):
            kin, pot, mom = _rod_energy(f, g, inv_Z, rod_start[r], rod_start[r + 1])
            e_kin[m, r] = 0.5 * dt * kin
            e_pot[m, r] = 0.5 * dt * pot
            e_mom[m, r] = dt * mom
        for q in range(acc.size):
            e_acc[m, q] = acc[q]
        cursor[0] = m + 1
    m = cursor[1]
    if m < s_steps.size and s_steps[m] == k:
        if not fresh:
            _element_states(f, g, Z, N, v)
        row_N = s_N[m]
        row_v = s_v[m]
        row_u = s_u[m]
        for j in range(N.size):
            row_N[j] = N[j]
            row_v[j] = v[j]
        node = 0
        for r in range(n_rods):
            u = u_end[r, 0]
            row_u[node] = u
            node += 1
            for j in range(rod_start[r], rod_start[r + 1]):
                u += (N[j] - N0[j]) * dt * inv_Z[j]
                row_u[node] = u
                node += 1
        cursor[1] = m + 1


@njit(inline="always", cache=True)
def _next_sample(samples):
    """The step of the next energy sample or snapshot (-1 if there is none)."""
    e_steps, s_steps, cursor = samples[0], samples[1], samples[2]
    e = e_steps[cursor[0]] if cursor[0] < e_steps.size else -1
    sn = s_steps[cursor[1]] if cursor[1] < s_steps.size else -1
    return e if sn < 0 or (0 <= e < sn) else sn


@njit(inline="always", cache=True)
def _element_states(f, g, Z, N, v):
    """N = f + g, v = (g - f) / Z for every element."""
    for j in range(N.size):
        N[j] = f[j] + g[j]
        v[j] = (g[j] - f[j]) / Z[j]


@njit(cache=True, nogil=True)
def reflecting_blocks(R, rod_start, sp_elem):
    """Rows [a, b) of consecutive plain nodes k (not a rod end, not a loaded node) with R[k-1] != 0."""
    n_el = R.size + 1
    special = np.zeros(n_el + 1, dtype=np.bool_)
    for r in range(1, rod_start.size - 1):
        special[rod_start[r]] = True
    for p in range(sp_elem.size):
        special[sp_elem[p] + 1] = True
    blocks = np.empty((n_el, 2), dtype=np.int64)
    m = 0
    k = 1
    while k < n_el:
        if R[k - 1] != 0.0 and not special[k]:
            start = k
            while k < n_el and R[k - 1] != 0.0 and not special[k]:
                k += 1
            blocks[m, 0] = start
            blocks[m, 1] = k
            m += 1
        else:
            k += 1
    return blocks[:m]


@njit(cache=True, nogil=True)
def pair_blocks(blocks, touch):
    """The rows of ``blocks`` split between the two nodes of every ``touch`` element (ascending) that has both in
    one row, so that such nodes are the first or last of a row: in the second step of a pair of steps
    (:func:`reflect_blocks`) those are updated after the boundary solver has read the element."""
    out = np.empty((blocks.shape[0] + touch.size, 2), dtype=np.int64)
    m = 0
    for q in range(blocks.shape[0]):
        a = blocks[q, 0]
        b = blocks[q, 1]
        for t in touch:
            if a <= t and t + 1 < b:
                out[m, 0] = a
                out[m, 1] = t + 1
                m += 1
                a = t + 1
        out[m, 0] = a
        out[m, 1] = b
        m += 1
    return out[:m]


@njit(inline="always", cache=True)
def boundary_updates(i, fo, F, G, N, v, Z, rod_start, sp_elem, sp_F, sp_V, rod_NL, rod_NR):
    """The waves leaving the rod ends and loaded nodes in step i, in the wave frame f_i(k) = F[k + fo],
    g_i(k) = G[k + i]: from their node forces (g_a' = N_a^+ - f_a, f_b' = N_b^- - g_b; the outer ends write
    fresh slots, a junction k = rod_start[r] turns the slots of f_i(k-1) and g_i(k) into f_{i+1}(k) and
    g_{i+1}(k-1)), loaded nodes alike (N^+ from the node velocity sp_V, N^- = N^+ - sp_F). Each node reads and
    writes only its own two slots."""
    n_el = Z.size
    n_rods = rod_start.size - 1
    F[fo - 1] = rod_NL[0] - G[i]
    for r in range(1, n_rods):
        k = rod_start[r]
        f_last = F[k - 1 + fo]
        g_first = G[k + i]
        G[k + i] = rod_NR[r - 1] - f_last
        F[k - 1 + fo] = rod_NL[r] - g_first
    G[n_el + i] = rod_NR[n_rods - 1] - F[n_el - 1 + fo]
    for p in range(sp_elem.size):
        a = sp_elem[p]
        n_plus = N[a] + Z[a] * (sp_V[p] - v[a])
        f_a = F[a + fo]
        g_b = G[a + 1 + i]
        G[a + 1 + i] = n_plus - f_a
        F[a + fo] = n_plus - sp_F[p] - g_b


#: bits of an index that is not negative (below 2^62)
_INDEX_BITS = (1 << 62) - 1


@njit(inline="always", cache=True)
def _index(x):
    """``x`` (0 <= x < 2^62 by construction) in a form the compiler can see is not negative: it then drops
    numba's wraparound of negative indices from the loops of :func:`reflect_blocks` and vectorises them."""
    return x & _INDEX_BITS


@njit(inline="always", cache=True, error_model="numpy")
def reflection(f, g, r):
    """The waves leaving a reflecting plain node with reflection factor r (eq. 2.40), f arriving from the left,
    g from the right: (g + r (f - g), f + r (f - g)), the one leaving to the left and the one leaving to the
    right (transmission 1 -+ r, eq. 2.39 in waves)."""
    sc = r * (f - g)
    return g + sc, f + sc


#: nodes per vector in the pass of :func:`reflect_blocks` that takes two steps at once
LANES = 8


@intrinsic
def _pair_lanes(typingctx, F, G, R, fa, gb, ra, n_vec, f2, f1):
    """The loop of the two-step pass of :func:`reflect_blocks` for ``n_vec`` vectors of LANES nodes, written with
    explicit vectors: returns (f2, f1) after them. Node k = a + 2 + m (m = 0 .. LANES n_vec - 1) in step i
    gives g_{i+1}(k-1), f_{i+1}(k); node k-1 in step i + 1 takes f_{i+1}(k-2) from two lanes back (from the
    previous vector for the first two lanes: one shuffle) and writes g_{i+2}(k-2) into G[gb + m],
    f_{i+2}(k-1) into F[fa + m]. Element-wise the operations of :func:`reflection` in the same order (no
    fused multiply-add): the same numbers as the scalar loop.

    The compiler's own vectoriser keeps to 256-bit vectors on CPUs whose 512-bit units may lower the clock and
    turns the two-lane delay into two shuffles per four nodes; here a vector holds eight nodes and the delay
    costs one shuffle. On CPUs without 512-bit vectors the compiler splits each into narrower ones."""
    sig = types.UniTuple(types.float64, 2)(F, G, R, fa, gb, ra, n_vec, f2, f1)

    def codegen(context, builder, signature, args):
        F_, G_, R_, fa_, gb_, ra_, n_vec_, f2_, f1_ = args
        f_ptr, g_ptr, r_ptr = (context.make_array(aty)(context, builder, arr).data
                               for aty, arr in zip(signature.args[:3], (F_, G_, R_)))
        vec = ir.VectorType(ir.DoubleType(), LANES)
        lane = ir.IntType(32)

        def load(ptr, offset):
            return builder.load(builder.bitcast(builder.gep(ptr, [offset]), vec.as_pointer()), align=8)

        def store(value, ptr, offset):
            builder.store(value, builder.bitcast(builder.gep(ptr, [offset]), vec.as_pointer()), align=8)

        # f_{i+1} of the previous vector's nodes, of which the last two lanes are used: at first f2, f1
        last = builder.insert_element(ir.Constant(vec, ir.Undefined), f2_, ir.Constant(lane, LANES - 2))
        last = builder.insert_element(last, f1_, ir.Constant(lane, LANES - 1))
        previous = cgutils.alloca_once_value(builder, last)
        two_back = ir.Constant(ir.VectorType(lane, LANES), list(range(LANES - 2, 2 * LANES - 2)))
        with cgutils.for_range(builder, n_vec_) as loop:
            m = builder.mul(loop.index, ir.Constant(fa_.type, LANES))
            fm = builder.add(fa_, m)
            gm = builder.add(gb_, m)
            rm = builder.add(ra_, m)
            f = load(f_ptr, builder.add(fm, ir.Constant(fa_.type, 2)))
            g = load(g_ptr, gm)
            sc = builder.fmul(load(r_ptr, builder.add(rm, ir.Constant(ra_.type, 1))), builder.fsub(f, g))
            gn = builder.fadd(g, sc)                                    # g_{i+1}(k-1)
            fn = builder.fadd(f, sc)                                    # f_{i+1}(k)
            f_left = builder.shuffle_vector(builder.load(previous), fn, two_back)    # f_{i+1}(k-2)
            sc = builder.fmul(load(r_ptr, rm), builder.fsub(f_left, gn))
            store(builder.fadd(gn, sc), g_ptr, gm)                      # g_{i+2}(k-2)
            store(builder.fadd(f_left, sc), f_ptr, fm)                  # f_{i+2}(k-1)
            builder.store(fn, previous)
        last = builder.load(previous)
        out = [builder.extract_element(last, ir.Constant(lane, LANES - 2)),
               builder.extract_element(last, ir.Constant(lane, LANES - 1))]
        return context.make_tuple(builder, signature.return_type, out)

    return sig, codegen


@njit(inline="always", cache=True, error_model="numpy")
def reflect_blocks(F, G, R, blocks, lim, fo, go, part):
    """The reflecting plain nodes k <= ``lim`` of the rows [a, b) of ``blocks``, in place in the wave frame
    (f_i(k) = F[k + fo], g_i(k) = G[k + go], see :func:`_run_waves`): node k, between elements k-1 and k,
    turns the slot of f_i(k-1) into f_{i+1}(k) and that of g_i(k) into g_{i+1}(k-1) (:func:`reflection` with
    R = R[k-1]).

    ``part`` 0: step i. ``part`` 1: step i and, in the rows left of ``lim`` entirely, the inner nodes (all but
    the first and last) in step i + 1 too, in one pass over the slots; ``part`` 2 (called for step i + 1,
    ``lim`` one more): the rest of step i + 1, the first and last node of those rows (after the boundary solver
    has read the elements next to them) and the other rows in full. Node k in step i + 1 needs f_{i+1}(k-1)
    and g_{i+1}(k), the outputs of nodes k-1 and k+1 in step i: the pass takes node k in step i with node k-1
    in step i + 1, g_{i+1}(k-1) just computed and f_{i+1}(k-2) from two nodes before, both kept in registers
    (:func:`_pair_lanes`, LANES nodes at a time; the two-node delay is a lane shift), so that a slot is loaded
    and stored once for the two steps instead of twice. Every node and step does the same operations in the
    same order either way.

    All in one inlined function without array views and loops indexed from offsets known not to be negative
    (:func:`_index`), so that they vectorise: a call cost more than 100 reflecting nodes (simulate_batch ran
    12,000 instead of 18,500 thesis-scale impacts/s on one thread), and views or array arguments of further
    inlined functions leave reference counting in the step loop."""
    for q in range(blocks.shape[0]):
        a = blocks[q, 0]
        b = blocks[q, 1]
        if a > lim:
            break
        if part == 1 and b - a >= 2 and b - 1 <= lim:
            for k in range(a, a + 2):                   # nodes a, a + 1 in step i
                g, f = reflection(F[k - 1 + fo], G[k + go], R[k - 1])
                G[k + go] = g
                F[k - 1 + fo] = f
            fa = _index(a - 1 + fo)     # F[fa + m]: slot of f_i(a-1+m), then f_{i+1}(a+m), then f_{i+2}(a+1+m)
            gb = _index(a + 2 + go)     # G[gb + m]: slot of g_i(a+2+m), then g_{i+1}(a+1+m), then g_{i+2}(a+m)
            ra = _index(a)              # R[ra + m]: R of node a+1+m
            f2 = F[fa]                  # f_{i+1}(k-2) and f_{i+1}(k-1) for k = a + 2
            f1 = F[fa + 1]
            # node k = a + 2 + m in step i with node k-1 in step i + 1
            n_vec = (b - a - 2) // LANES
            f2, f1 = _pair_lanes(F, G, R, fa, gb, ra, n_vec, f2, f1)
            for m in range(_index(LANES * n_vec), _index(b - a - 2)):   # the rest, one node at a time
                gn, fn = reflection(F[fa + m + 2], G[gb + m], R[ra + m + 1])     # g_{i+1}(k-1), f_{i+1}(k)
                g, f = reflection(f2, gn, R[ra + m])                             # g_{i+2}(k-2), f_{i+2}(k-1)
                G[gb + m] = g
                F[fa + m] = f
                f2 = f1
                f1 = fn
            F[b - 3 + fo] = f2          # f_{i+1}(b-2), f_{i+1}(b-1): read by nodes b-1 and b in step i + 1
            F[b - 2 + fo] = f1
        elif part == 2 and b - a >= 2 and b - 1 <= lim - 1:
            for k in (a, b - 1):
                g, f = reflection(F[k - 1 + fo], G[k + go], R[k - 1])
                G[k + go] = g
                F[k - 1 + fo] = f
        else:
            fa = _index(a - 1 + fo)
            gb = _index(a + go)
            ra = _index(a - 1)
            for m in range(_index(min(b, lim + 1) - a)):
                g, f = reflection(F[fa + m], G[gb + m], R[ra + m])
                G[gb + m] = g
                F[fa + m] = f


@njit(inline="always", cache=True)
def node_updates(i, fo, F, G, N, v, Z, R, rod_start, sp_elem, sp_F, sp_V, rod_NL, rod_NR, blocks, lim):
    """The waves leaving every node in step i (:func:`boundary_updates`, then the reflecting plain nodes
    k <= ``lim``, :func:`reflect_blocks`); plain nodes without reflection pass both waves on, which in this
    frame is nothing to do."""
    boundary_updates(i, fo, F, G, N, v, Z, rod_start, sp_elem, sp_F, sp_V, rod_NL, rod_NR)
    reflect_blocks(F, G, R, blocks, lim, fo, i, 0)


def _run_waves(first, n_steps, state, lattice, dt, ends, junctions, specials, probes, outputs, acc, record):
    """Advance steps ``first .. first + n_steps - 1`` in place (compiled path) and record them; returns the number
    of steps done (fewer than ``n_steps`` only if a junction's buffer of closed contact phases is full: the
    caller enlarges it and calls again from there). The i-th step reads and writes column ``i`` of the per-step
    inputs (``end_value``, ``sp_force``) and outputs (``outputs``, the probe histories of ``probes``).

    ``state = (N, v, f, g)``, ``lattice = (Z, R, touch, rod_start, quiet)``; ``record = (stride, kept, events,
    samples)`` as built by :class:`rodimpact.direct.recording.Recorder`. ``quiet``: the elements from ``quiet``
    on are at rest at step 0 and nothing but a wave from the left can move them
    (:func:`rodimpact.direct.simulate.quiet_front`); a wave moves one element per step, so step k updates only
    the nodes left of element ``quiet + k + 1``: the others would give exactly +0 again.

    The same lattice as :func:`run_numpy`, written in travelling-wave variables: element j carries a
    right-going force wave f_j and a left-going g_j, N = f + g, v = (g - f) / Z (thesis Sec. 2.3.2). At a
    plain interior node with reflection factor R = (Z_b - Z_a)/(Z_b + Z_a) (eq. 2.40) the outgoing waves are
    g_a' = g_b + R (f_a - g_b) and f_b' = f_a + R (f_a - g_b) (transmission 1 +- R, eq. 2.39), which is eqs.
    3.6-3.15 without the division. Loaded nodes, ends and junctions are solved by :func:`boundaries` on
    (N, v), refreshed each step at the ``touch`` elements only; the outgoing waves there follow from the node
    force: g_a' = N_a^+ - f_a, f_b' = N_b^- - g_b (:func:`boundary_updates`).

    Within a call the waves live in the frame in which they travel, f_i(j) = F[j + n_steps - i] and
    g_i(j) = G[j + i] at the call's i-th step: a node with R = 0 passes both waves on unchanged
    (g_a' = g_b, f_b' = f_a), which in this frame is no operation, so a step costs the reflecting and special
    nodes, not the elements (a uniform bar is free). Two consecutive steps share one pass over the reflecting
    nodes (:func:`reflect_blocks`) unless the first is the last of the call, fills a junction's phase buffer,
    or the second is a sample step (samples read every element). The waves (f, g) persist between calls
    (copied into the frame at the start and back at the end); (N, v) are brought up to date at the sample
    steps and at the end of the call.
    """
    N, v, f, g = state
    Z, R, touch, rod_start, quiet = lattice
    sp_elem = specials[0]
    sp_F, sp_V = specials[3], specials[4]
    u_end = junctions[4]
    stride, kept, events, samples = record
    e_steps, s_steps, cursor, e_kin, e_pot, e_mom, e_acc, s_N, s_v, s_u, N0, inv_Z = samples
    chunk = (outputs[0], outputs[1], outputs[2], outputs[3], probes[3], probes[4], probes[5])
    # with every step kept the step outputs go straight into the histories (column first + i), else into the
    # step columns (column i), of which every stride-th is copied (keep_step)
    direct = stride == 1
    src = kept if direct else chunk
    col0 = first if direct else 0
    cols = (src[0][:, col0:], src[1][:, col0:], src[2][:, col0:], src[3][:, col0:], src[4][:, col0:],
            src[5][:, col0:], src[6][:, col0:])
    outputs = (cols[0], cols[1], cols[2], cols[3])
    probes = (probes[0], probes[1], probes[2], cols[4], cols[5], cols[6], probes[6])
    n_el = Z.size
    n_rods = rod_start.size - 1
    rod_nodes = (np.empty(n_rods), np.empty(n_rods), np.empty(n_rods), np.empty(n_rods))
    rod_NL, rod_VL, rod_NR, rod_VR = rod_nodes
    blocks = pair_blocks(reflecting_blocks(R, rod_start, sp_elem), touch)
    F = np.zeros(n_el + n_steps + 1)          # the wave frame: f_i(j) = F[j + n_steps - i], g_i(j) = G[j + i]
    G = np.zeros(n_el + n_steps + 1)
    F[n_steps:n_steps + n_el] = f
    G[:n_el] = g
    c = -(-first // stride)         # next recorded column and its step (no division inside the loop)
    next_kept = c * stride
    next_sample = _next_sample(samples)
    done = n_steps if has_room(events) else 0
    part = 0                        # 1, 2: the step is the first, second of a pair of steps (reflect_blocks)
    for i in range(done):
        k = first + i
        fo = n_steps - i
        if k == next_sample:    # at i = 0, (N, v) are those the previous call (or the initial state) left
            _take_samples(k, i == 0, (N, v, F[fo:fo + n_el], G[i:i + n_el]), Z, dt, rod_start, acc, u_end,
                          samples)
            next_sample = _next_sample(samples)
        for q in range(touch.size):
            t = _index(touch[q])
            f_t = F[_index(t + fo)]
            g_t = G[_index(t + i)]
            N[t] = f_t + g_t
            v[t] = (g_t - f_t) / Z[t]
        boundaries(i, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        full = track_events(k, i, outputs[0], outputs[1], events)
        if k == next_kept and not direct:
            keep_step(i, c, chunk, kept)
            c += 1
            next_kept += stride
        boundary_updates(i, fo, F, G, N, v, Z, rod_start, sp_elem, sp_F, sp_V, rod_NL, rod_NR)
        # elements >= quiet + k + 1 are still exactly at rest after this step: their nodes would give +0 again
        lim = quiet + k + 1
        if part == 1:
            part = 2
        elif not full and i + 1 < done and k + 1 != next_sample:   # step i + 1 with this one's pass
            part = 1
        else:
            part = 0
        reflect_blocks(F, G, R, blocks, lim, fo, i, part)
        if full:           # the caller enlarges the phase buffer and calls again from the next step
            done = i + 1
            break
    f[:] = F[n_steps - done:n_steps - done + n_el]
    g[:] = G[done:done + n_el]
    _element_states(f, g, Z, N, v)
    _take_samples(first + done, True, state, Z, dt, rod_start, acc, u_end, samples)
    return done


# nogil: independent runs (rodimpact.sweep) advance in parallel threads
run_numba = njit(cache=True, error_model="numpy", nogil=True)(_run_waves)


def waves(N: np.ndarray, v: np.ndarray, Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Right- and left-going force waves f = (N - Z v)/2, g = (N + Z v)/2 of the element states."""
    return 0.5 * (N - Z * v), 0.5 * (N + Z * v)


@njit(cache=True, error_model="numpy")
def wave_setup(N, v, Z, rod_start, sp_elem, sp_loaded, pr_rod, pr_local, right_passive):
    """What the compiled loop needs besides the element states, in one compiled call (the numpy functions it
    replaces are the readable reference, tested equal): the waves f = (N - Z v)/2, g = (N + Z v)/2
    (:func:`waves`); the reflection factor R_j = (Z_{j+1} - Z_j)/(Z_{j+1} + Z_j) of every node (thesis eq.
    2.40) and the ``touch`` elements whose (N, v) the boundary solver reads each step: the end elements of
    every rod, the elements on both sides of a special node and of a probed interior node
    (:func:`rodimpact.direct.simulate._wave_arrays`); and the quiet front
    (:func:`rodimpact.direct.simulate.quiet_front` from element 0, the loaded special nodes forcing)."""
    n = Z.size
    f = np.empty(n)
    g = np.empty(n)
    for j in range(n):
        f[j] = 0.5 * (N[j] - Z[j] * v[j])
        g[j] = 0.5 * (N[j] + Z[j] * v[j])
    R = np.empty(n - 1)
    for j in range(n - 1):
        R[j] = (Z[j + 1] - Z[j]) / (Z[j + 1] + Z[j])
    mark = np.zeros(n, dtype=np.bool_)
    for r in range(rod_start.size - 1):
        mark[rod_start[r]] = True
        mark[rod_start[r + 1] - 1] = True
    for a in sp_elem:
        mark[a] = True
        mark[a + 1] = True
    for p in range(pr_rod.size):
        lo, hi = rod_start[pr_rod[p]], rod_start[pr_rod[p] + 1]
        a = lo + pr_local[p] - 1
        for e in (a, a + 1):
            if lo <= e < hi:
                mark[e] = True
    touch = np.flatnonzero(mark)
    quiet = n
    if right_passive:
        quiet = 0
        for j in range(n - 1, -1, -1):
            if N[j] != 0.0 or v[j] != 0.0:
                quiet = j + 1
                break
        for q in range(sp_elem.size):
            if sp_loaded[q]:
                quiet = max(quiet, sp_elem[q] + 2)
    return f, g, R, touch, quiet


def run_numpy(first, n_steps, state, lattice, dt, ends, junctions, specials, probes, outputs, acc, record):
    """Readable reference path with the same signature as :func:`run_numba`: per step, the interior nodes
    are one vectorised evaluation of thesis eqs. 3.6-3.9 and the elements of eqs. 3.10-3.15 in the thesis's
    own variables (N, v); the wave variables, ``R`` and ``touch`` of the compiled path are not used. Energy and
    snapshots are numpy reductions; contact events and the stride share the compiled path's scalar code."""
    N, v = state[0], state[1]
    Z, rod_start = lattice[0], lattice[3]          # all nodes are updated every step: quiet (lattice[4]) unused
    sp_elem, sp_F, sp_V = specials[0], specials[3], specials[4]
    u_end = junctions[4]
    stride, kept, events, samples = record
    chunk = (*outputs, *probes[3:6])
    n_rods = rod_start.size - 1
    n_el = int(rod_start[-1])
    rod_NL, rod_VL, rod_NR, rod_VR = rod_nodes = tuple(np.empty(n_rods) for _ in range(4))
    interior = np.ones(n_el - 1, dtype=bool)          # node between j and j+1 is interior unless a rod ends at j
    interior[rod_start[1:-1] - 1] = False
    a = np.flatnonzero(interior)                      # element left of each interior node
    b = a + 1
    sp_pos = np.searchsorted(a, sp_elem)
    first_el = rod_start[:-1]
    last_el = rod_start[1:] - 1
    done = n_steps if has_room.py_func(events) else 0
    for i in range(done):
        k = first + i
        _numpy_samples(k, N, v, Z, dt, rod_start, acc, u_end, samples)
        boundaries.py_func(i, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        full = track_events.py_func(k, i, outputs[0], outputs[1], events)
        if k % stride == 0:
            keep_step.py_func(i, k // stride, chunk, kept)
        f = np.zeros(a.size)
        f[sp_pos] = sp_F
        # eq. 3.7 / 3.9 written as V = v_a + d, which keeps uniform motion exact in floating point
        d = (f + N[b] - N[a] + Z[b] * (v[b] - v[a])) / (Z[a] + Z[b])
        vn = v[a] + d
        n_plus = N[a] + Z[a] * d                                            # eq. 3.5
        n_minus = n_plus - f                                                # eq. 3.2
        n_right = np.empty(n_el)   # N^+ of every element
        v_right = np.empty(n_el)
        n_left = np.empty(n_el)    # N^- of every element
        v_left = np.empty(n_el)
        n_right[a], v_right[a] = n_plus, vn
        n_left[b], v_left[b] = n_minus, vn
        n_left[first_el], v_left[first_el] = rod_NL, rod_VL
        n_right[last_el], v_right[last_el] = rod_NR, rod_VR
        N_new = n_left + n_right - N                                        # eqs. 3.10, 3.11, 3.14
        v_new = v_left + v_right - v                                        # eqs. 3.12, 3.13, 3.15
        N[:] = N_new
        v[:] = v_new
        if full:
            done = i + 1
            break
    _numpy_samples(first + done, N, v, Z, dt, rod_start, acc, u_end, samples)
    return done


def _numpy_samples(k, N, v, Z, dt, rod_start, acc, u_end, samples):
    """:func:`_take_samples` as numpy reductions per rod."""
    e_steps, s_steps, cursor, e_kin, e_pot, e_mom, e_acc, s_N, s_v, s_u, N0, _ = samples
    starts = rod_start[:-1]
    m = cursor[0]
    if m < e_steps.size and e_steps[m] == k:
        e_kin[m] = np.add.reduceat(0.5 * dt * Z * v * v, starts)
        e_pot[m] = np.add.reduceat(0.5 * dt * N * N / Z, starts)
        e_mom[m] = np.add.reduceat(dt * Z * v, starts)
        e_acc[m] = acc
        cursor[0] = m + 1
    m = cursor[1]
    if m < s_steps.size and s_steps[m] == k:
        s_N[m], s_v[m] = N, v
        elongation = np.split((N - N0) * dt / Z, starts[1:])
        s_u[m] = np.concatenate([u_end[r, 0] + np.concatenate([[0.0], np.cumsum(el)])
                                 for r, el in enumerate(elongation)])
        cursor[1] = m + 1
