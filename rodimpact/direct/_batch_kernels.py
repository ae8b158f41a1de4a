"""Batched kernel: many strikers against one struck system, one compiled call, parallel over designs.

Each design is the run :func:`rodimpact.direct._kernels.run_numba` would do for the system whose rod 0 is that
design's striker: the same travelling-wave update (f = right-going, g = left-going force wave; N = f + g,
v = (g - f) / Z, thesis Sec. 2.3.2), the same :func:`~rodimpact.direct._kernels.boundaries` (inlined) for ends,
junctions and loaded nodes; like ``simulate``, the waves persist for the whole run. Every floating-point operation is the one the single-run
kernel does in the same order, so each design's results equal :func:`rodimpact.simulate`'s bit for bit.

The waves are kept in the frame in which they travel: at step i, f_i(k) = F[k + n_steps - i] and
g_i(k) = G[k + i] (right-going waves move one element right per step, left-going one left). A plain node
between equal impedances (R = 0) passes both waves on unchanged, which in this frame is no operation at all;
a node with a reflection updates its two slots in place (the slot of f_i(k - 1) becomes f_{i+1}(k), that of
g_i(k) becomes g_{i+1}(k - 1)); rod ends and loaded nodes write their slots from the node forces, and the
outer ends write fresh slots. A step costs the reflecting and special nodes, not the number of elements: a
uniform bar is free. Runs of consecutive reflecting nodes are updated one step at a time by the loop of
:func:`rodimpact.direct._kernels.reflect_blocks` (offsets the compiler can see are not negative: it vectorises). (At a node with R = 0 the single-run kernel computes g + 0 (f - g), which equals g; so
the values are the same, only the sign of a zero wave may differ, and no result depends on it.)

Array layout: that of :mod:`rodimpact.direct._kernels` for the template system (``z``, ``N0``, ``v0`` of all
elements, rod 0 = the striker slot of ``n_s`` elements), plus per design: ``Zs[d]`` striker impedances (left to
right), ``vel[d]`` striker velocity, ``end_par[d]`` (the left end's parameters may depend on the striker),
``gap_tol[d]`` (depends on the striker's last element length).

``quiet``: the elements from ``quiet`` on start at rest and nothing but a wave from the left can move them
(passive right end, no prescribed load there); a wave moves one element per step, so in step i only the
reflecting nodes left of element ``quiet + i + 1`` are updated: the others would give exactly +0 again.

Outputs per design d (junction index r, rod index q):

* ``hist[d, k]``: junction 0 force at step ``k * stride`` (N; not written if ``hist`` has no columns);
* ``kin[d, q, 0/1]``, ``pot[d, q, 0/1]``: kinetic 1/2 Z dt v^2 and strain 1/2 N^2 dt / Z energy of rod q at
  the start and the end (thesis eq. 3.25), summed from the waves as :func:`rodimpact.simulate` does;
* ``work[d, 0:5]``: work done by the left end, the right end, the loads, the friction and the joints
  (``acc[0:4]``, ``acc[8]``), J;
* ``ends_out[d, e]``: the outer end's state at the end, (outward displacement delta, largest delta), m;
* ``fin_N[d]``, ``fin_v[d]``: the striker's element forces and velocities at the end;
* junction events (every step, whatever the stride): ``low[d, r]`` most compressive force and ``low_step``
  its first step, ``peak[d, r]`` largest |force|, ``steps_on[d, r]`` steps in contact, ``n_ph[d, r]`` contact
  phases, of which the first ``ph_start.shape[2]`` are kept as steps ``[ph_start, ph_stop)`` with their
  largest |force| ``ph_peak``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ._kernels import _rod_energy, node_updates, reflecting_blocks
from .boundary import ACC_SLOTS, boundaries, fresh_law_state

_OPTS = dict(cache=True, error_model="numpy", nogil=True)


@njit(**_OPTS)
def _rod_energies(f, g, inv_Z, dt, rod_start, kin, pot, col):
    """Kinetic and strain energy of each rod into ``kin[:, col]``, ``pot[:, col]`` (thesis eq. 3.25), from the
    waves with the sums of :func:`rodimpact.direct._kernels._rod_energy`, as :func:`rodimpact.simulate` does."""
    for q in range(rod_start.size - 1):
        k, p, _ = _rod_energy(f, g, inv_Z, rod_start[q], rod_start[q + 1])
        kin[q, col] = 0.5 * dt * k
        pot[q, col] = 0.5 * dt * p


@njit(**_OPTS)
def _events(force, contact, r, n_steps, low, low_step, peak, steps_on, n_ph, ph_start, ph_stop, ph_peak):
    """Contact phases and extremes of junction ``r`` from its per-step force and contact flag (as
    :class:`rodimpact.direct.result.EventTracker`)."""
    lo = np.inf
    lo_k = 0
    top = 0.0
    on = 0
    count = 0
    cap = ph_start.size
    start = -1
    pk = 0.0
    for k in range(n_steps):
        fk = force[r, k]
        if fk < lo:
            lo = fk
            lo_k = k
        a = abs(fk)
        if a > top:
            top = a
        if contact[r, k] > 0.5:
            on += 1
            if start < 0:
                start = k
                pk = a
            elif a > pk:
                pk = a
        elif start >= 0:
            if count < cap:
                ph_start[count], ph_stop[count], ph_peak[count] = start, k, pk
            count += 1
            start = -1
    if start >= 0:
        if count < cap:
            ph_start[count], ph_stop[count], ph_peak[count] = start, n_steps, pk
        count += 1
    low[r] = lo
    low_step[r] = lo_k
    peak[r] = top
    steps_on[r] = on
    n_ph[r] = count


@njit(**_OPTS)
def _design(d, n_steps, stride, quiet, Zs, vel, z0, N0, v0, rod_start, touch, end_code, end_par, end_value,
            junction_code, joints, gap0, gap_tol, sp_elem, sp_cap, sp_force, dt, out):
    """One design (see the module docstring); ``out`` holds the output arrays; ``joints`` = (``junction_par``,
    the joint states to start from or None, :func:`rodimpact.direct.boundary.law_state`)."""
    junction_par, law_q = joints
    hist, kin, pot, work, fin_N, fin_v, low, low_step, peak, steps_on, n_ph, ph_start, ph_stop, ph_peak, ends_out = out
    n_s = Zs.shape[1]
    n_el = z0.size
    n_rods = rod_start.size - 1
    n_j = n_rods - 1
    n_sp = sp_elem.size
    Z = z0.copy()
    N = N0.copy()
    v = v0.copy()
    for j in range(n_s):
        Z[j] = Zs[d, j]
        N[j] = 0.0
        v[j] = vel[d]
    R = (Z[1:] - Z[:-1]) / (Z[1:] + Z[:-1])
    inv_Z = 1.0 / Z
    # per-design state and per-step outputs of boundaries() (no probes in a batch)
    junction_N = np.empty((n_j, n_steps))
    junction_contact = np.empty((n_j, n_steps))
    end_N = np.empty((2, n_steps))
    end_V = np.empty((2, n_steps))
    pr_N = np.empty((0, n_steps))
    no_int = np.empty(0, dtype=np.int64)
    acc = np.zeros(ACC_SLOTS)
    sp_F = np.zeros(n_sp)
    sp_V = np.zeros(n_sp)
    rod_NL = np.empty(n_rods)
    rod_NR = np.empty(n_rods)
    # the argument groups of boundaries() (see _kernels._grouped)
    end_state = np.zeros((2, 2))
    ends = (end_code, end_par[d].copy(), end_state, end_value)
    junctions = (junction_code, np.zeros(n_j, dtype=np.int64), gap0.copy(), gap_tol[d], np.zeros((n_rods, 2)),
                 junction_par, fresh_law_state(law_q))
    specials = (sp_elem, sp_cap, sp_force, sp_F, sp_V, None)     # no soil in a batch (batch.slot_problem)
    probes = (no_int, no_int, no_int, pr_N, pr_N, pr_N, np.empty(0))
    outputs = (junction_N, junction_contact, end_N, end_V)
    rod_nodes = (rod_NL, np.empty(n_rods), rod_NR, np.empty(n_rods))
    f = 0.5 * (N - Z * v)
    g = 0.5 * (N + Z * v)
    _rod_energies(f, g, inv_Z, dt, rod_start, kin[d], pot[d], 0)
    blocks = reflecting_blocks(R, rod_start, sp_elem)
    # the wave frame: f_i(k) = F[k + n_steps - i], g_i(k) = G[k + i]
    F = np.zeros(n_el + n_steps + 1)
    G = np.zeros(n_el + n_steps + 1)
    F[n_steps:n_steps + n_el] = f
    G[:n_el] = g
    for i in range(n_steps):
        fo = n_steps - i
        for t in touch:
            N[t] = F[t + fo] + G[t + i]
            v[t] = (G[t + i] - F[t + fo]) / Z[t]
        boundaries(i, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        # elements >= quiet + i + 1 are still exactly at rest after this step: their nodes would give +0 again
        node_updates(i, fo, F, G, N, v, Z, R, rod_start, sp_elem, sp_F, sp_V, rod_NL, rod_NR, blocks,
                     quiet + i + 1)
    f = F[:n_el].copy()
    g = G[n_steps:n_steps + n_el].copy()
    for j in range(n_el):
        N[j] = f[j] + g[j]
        v[j] = (g[j] - f[j]) / Z[j]
    _rod_energies(f, g, inv_Z, dt, rod_start, kin[d], pot[d], 1)
    for k in range(4):
        work[d, k] = acc[k]
    work[d, 4] = acc[8]
    for e in range(2):
        ends_out[d, e, 0] = end_state[e, 0]
        ends_out[d, e, 1] = end_state[e, 1]
    fin_N[d] = N[:n_s]
    fin_v[d] = v[:n_s]
    for k in range(hist.shape[1]):
        hist[d, k] = junction_N[0, k * stride]
    for r in range(n_j):
        _events(junction_N, junction_contact, r, n_steps, low[d], low_step[d], peak[d], steps_on[d], n_ph[d],
                ph_start[d, r], ph_stop[d, r], ph_peak[d, r])


def _run_parallel(n_steps, stride, quiet, Zs, vel, z0, N0, v0, rod_start, touch, end_code, end_par, end_value,
                  junction_code, joints, gap0, gap_tol, sp_elem, sp_cap, sp_force, dt, out):
    """All designs (rows of ``Zs``) on the numba threads; the outputs are written into the arrays of ``out``."""
    for d in prange(Zs.shape[0]):
        _design(d, n_steps, stride, quiet, Zs, vel, z0, N0, v0, rod_start, touch, end_code, end_par, end_value,
                junction_code, joints, gap0, gap_tol, sp_elem, sp_cap, sp_force, dt, out)


def _run_serial(n_steps, stride, quiet, Zs, vel, z0, N0, v0, rod_start, touch, end_code, end_par, end_value,
                junction_code, joints, gap0, gap_tol, sp_elem, sp_cap, sp_force, dt, out):
    """All designs one after another in the calling thread. A function of its own, not ``_run_parallel``
    compiled without ``parallel``: numba's on-disk cache is keyed by the Python function, so two dispatchers of
    one function would load each other's machine code (the serial one then ran on all threads)."""
    for d in range(Zs.shape[0]):
        _design(d, n_steps, stride, quiet, Zs, vel, z0, N0, v0, rod_start, touch, end_code, end_par, end_value,
                junction_code, joints, gap0, gap_tol, sp_elem, sp_cap, sp_force, dt, out)


#: designs on all numba threads (``numba.set_num_threads``)
run_batch_parallel = njit(parallel=True, **_OPTS)(_run_parallel)
#: designs one after another in the calling thread (tasks of an executor; releases the GIL)
run_batch_serial = njit(**_OPTS)(_run_serial)
