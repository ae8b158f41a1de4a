"""The direct solver's time loop as it was before it moved into compiled code (commit 5518828), frozen: the
per-chunk compiled kernel (scalar interior sweep, 31 keyword arrays per call, waves rebuilt from (N, v) at every
call) and the Python loop that stopped it at every energy sample and snapshot. Kept as the "before" of
``bench_kernel.py`` and as the bit-for-bit baseline of ``tests/direct/test_compiled_loop.py``. Not used by the
package.
"""

from __future__ import annotations

import time as _time
import warnings

import numpy as np
from numba import njit

from rodimpact import __version__
from rodimpact.direct.boundary import boundaries, law_state
from rodimpact.direct.result import EnergyHistory, EventTracker, FieldSnapshots, SimulationResult
from rodimpact.direct.problem import initial_state, kernel_arrays, wave_arrays
from rodimpact.direct.simulate import _probe_histories
from rodimpact.lattice.lattice import build_lattice

_MAX_CHUNK = 65536
_HISTORIES = ("pr_N", "pr_V", "pr_u", "junction_N", "junction_contact", "end_N", "end_V")


@njit(inline="always", cache=True)
def _grouped(end_code, end_par, end_state, end_value, junction_code, junction_state, gap, gap_tol, u_end,
             sp_elem, sp_cap, sp_force, sp_F, sp_V, pr_rod, pr_local, pr_sp, pr_N, pr_V, pr_u, pr_disp, junction_N,
             junction_contact, end_N, end_V, rod_NL, rod_VL, rod_NR, rod_VR):
    """The arrays :func:`boundaries` needs, grouped into tuples (ends, junctions, specials, probes, outputs,
    rod-end nodes); few arguments let the compiler inline :func:`boundaries` into the step loop."""
    return ((end_code, end_par, end_state, end_value), (junction_code, junction_state, gap, gap_tol, u_end),
            (sp_elem, sp_cap, sp_force, sp_F, sp_V, None), (pr_rod, pr_local, pr_sp, pr_N, pr_V, pr_u, pr_disp),
            (junction_N, junction_contact, end_N, end_V), (rod_NL, rod_VL, rod_NR, rod_VR))


def _run_waves(n_steps, N, v, Z, R, touch, rod_start, end_code, end_par, end_state, end_value,
               junction_code, junction_state, gap, gap_tol, u_end, junction_par, junction_q, sp_elem, sp_cap,
               sp_force, pr_rod, pr_local, pr_sp,
               pr_N, pr_V, pr_u, pr_disp, junction_N, junction_contact, end_N, end_V, acc, dt):
    """Advance ``n_steps`` steps in place (compiled path). The i-th step reads and writes column ``i`` of the
    per-step input (``end_value``, ``sp_force``) and output arrays.

    The same lattice as :func:`run_numpy`, written in travelling-wave variables: element j carries a
    right-going force wave f_j and a left-going g_j, N = f + g, v = (g - f) / Z (thesis Sec. 2.3.2). At a
    plain interior node with reflection factor R = (Z_b - Z_a)/(Z_b + Z_a) (eq. 2.40) the outgoing waves are
    g_a' = g_b + R (f_a - g_b) and f_b' = f_a + R (f_a - g_b) (transmission 1 +- R, eq. 2.39), which is eqs.
    3.6-3.15 without the division and streams at memory speed. Loaded nodes, ends and junctions are solved
    by :func:`boundaries` on (N, v), refreshed each step at the ``touch`` elements only; the outgoing waves
    there follow from the node force: g_a' = N_a^+ - f_a, f_b' = N_b^- - g_b.
    """
    n_rods = rod_start.size - 1
    rod_NL = np.empty(n_rods)
    rod_VL = np.empty(n_rods)
    rod_NR = np.empty(n_rods)
    rod_VR = np.empty(n_rods)
    sp_F = np.zeros(sp_elem.size)
    sp_V = np.zeros(sp_elem.size)
    n_sp = sp_elem.size
    ends, junctions, specials, probes, outputs, rod_nodes = _grouped(
        end_code, end_par, end_state, end_value, junction_code, junction_state, gap, gap_tol, u_end,
        sp_elem, sp_cap,
        sp_force, sp_F, sp_V, pr_rod, pr_local, pr_sp, pr_N, pr_V, pr_u, pr_disp, junction_N, junction_contact, end_N,
        end_V, rod_NL, rod_VL, rod_NR, rod_VR)
    junctions = junctions + (junction_par, junction_q)     # the joints of later work (not in the old loop)
    f = 0.5 * (N - Z * v)
    g = 0.5 * (N + Z * v)
    for i in range(n_steps):
        for t in touch:
            N[t] = f[t] + g[t]
            v[t] = (g[t] - f[t]) / Z[t]
        boundaries(i, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
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
                    sc = R[jj] * (fa - gb)
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
    for j in range(N.size):
        N[j] = f[j] + g[j]
        v[j] = (g[j] - f[j]) / Z[j]


# nogil: independent runs (rodimpact.sweep) advance in parallel threads
old_run_numba = njit(cache=True, error_model="numpy", nogil=True)(_run_waves)


class _History:
    """The per-step outputs of the kernels. The kernels write consecutive steps into buffers of at most
    ``_MAX_CHUNK`` steps; when a buffer is full (and at the end) every ``stride``-th step is kept and the contact
    events are taken from all its steps. With stride 1 the buffers are windows of the recorded arrays."""

    def __init__(self, arrays: dict, n_steps: int, stride: int) -> None:
        self.stride = stride
        self._capacity = max(1, min(n_steps, _MAX_CHUNK))
        n_rec = -(-n_steps // stride)
        self.recorded = {key: np.zeros((arrays[key].shape[0], n_rec)) for key in _HISTORIES}
        self._buf = self.recorded if stride == 1 else {
            key: np.zeros((arrays[key].shape[0], self._capacity)) for key in _HISTORIES}
        self._first = 0        # first step of the current buffer
        self._filled = 0       # steps written into it
        self.events = EventTracker(arrays["junction_N"].shape[0])

    def _offset(self) -> int:
        """Column of the current buffer's first step in the storage the kernels write to."""
        return self._first if self.stride == 1 else 0

    def buffers(self, n: int) -> dict[str, np.ndarray]:
        """Output arrays for the next ``n <= _MAX_CHUNK`` steps (views)."""
        if self._filled + n > self._capacity:
            self.flush()
        a = self._offset() + self._filled
        self._filled += n
        return {key: buf[:, a:a + n] for key, buf in self._buf.items()}

    def flush(self) -> None:
        """Record the contact events of the buffered steps and keep those that fall on the stride."""
        n, first, off = self._filled, self._first, self._offset()
        self.events.feed(first, self._buf["junction_N"][:, off:off + n], self._buf["junction_contact"][:, off:off + n])
        local = np.arange((-first) % self.stride, n, self.stride)
        if self.stride > 1 and local.size:
            target = slice((first + int(local[0])) // self.stride, (first + int(local[-1])) // self.stride + 1)
            for key, buf in self._buf.items():
                self.recorded[key][:, target] = buf[:, local]
        self._first, self._filled = first + n, 0


def _node_displacements(N, N0, z, dt, rod_start, u_end) -> np.ndarray:
    """Node displacements from the left-end displacement of each rod plus the element elongations
    (N - N0) dt / Z (exact on the lattice: elements are uniform at t = k dt)."""
    out = []
    for r in range(rod_start.size - 1):
        a, b = rod_start[r], rod_start[r + 1]
        out.append(u_end[r, 0] + np.concatenate([[0.0], np.cumsum((N[a:b] - N0[a:b]) * dt / z[a:b])]))
    return np.concatenate(out)

def old_simulate(system, steps: int, dt: float, probes=(), snapshot_every=None, energy_every=None,
                 record_every: int = 1) -> SimulationResult:
    """:func:`rodimpact.simulate` of commit 5518828 for a ready System (numba backend, no progress bar)."""
    n_steps = steps
    probe_list = list(probes)
    snap_steps = sorted(set(range(0, n_steps + 1, snapshot_every))) if snapshot_every else []
    every = energy_every or max(1, -(-n_steps // 256))
    stride = record_every
    backend = "numba"
    lattice = build_lattice(system, dt)
    wall0 = _time.perf_counter()
    N0, v0 = initial_state(system, lattice)
    state = {"N": N0, "v": v0}
    arrays = kernel_arrays(system, lattice, N0, v0, probe_list)
    history = _History(arrays, n_steps, stride)
    run = old_run_numba

    N, v = state["N"], state["v"]
    N0 = N.copy()
    reflection, touch = wave_arrays(lattice, arrays)
    z = lattice.impedance
    rs = lattice.rod_start
    energy_steps = sorted(set(range(0, n_steps + 1, every)) | {n_steps})
    events = sorted(set(energy_steps) | set(snap_steps) | set(range(0, n_steps, _MAX_CHUNK)))
    e_rec: dict[str, list] = {k: [] for k in ("t", "kin", "pot", "mom", "acc")}
    snaps: list[tuple[float, np.ndarray, np.ndarray, np.ndarray]] = []
    static = {key: val for key, val in arrays.items() if key not in _HISTORIES and key not in ("step_inputs", "sp_loaded")
              and "soil" not in key}
    static["junction_q"] = law_state(arrays["junction_code"], arrays["junction_q"])
    k = 0
    for target in events:
        if target > k:
            kw = {**static, **history.buffers(target - k)}
            kw["end_value"], kw["sp_force"] = arrays["step_inputs"](k, target - k)
            run(target - k, N, v, z, reflection, touch, **kw, dt=dt)
            k = target
        if k in energy_steps:
            e_rec["t"].append(k * dt)
            # thesis eq. 3.25 per rod: kinetic 1/2 m v^2 with m = Z dt, strain 1/2 N^2 l/(EA) = 1/2 N^2 dt / Z
            e_rec["kin"].append(np.add.reduceat(0.5 * dt * z * v * v, rs[:-1]))
            e_rec["pot"].append(np.add.reduceat(0.5 * dt * N * N / z, rs[:-1]))
            e_rec["mom"].append(np.add.reduceat(dt * z * v, rs[:-1]))
            e_rec["acc"].append(arrays["acc"].copy())
        if k in snap_steps:
            snaps.append((k * dt, N.copy(), v.copy(), _node_displacements(N, N0, z, dt, rs, arrays["u_end"])))
    wall = _time.perf_counter() - wall0

    history.flush()
    time = np.arange(0, n_steps, stride) * dt
    arrays.update(history.recorded)
    acc = np.array(e_rec["acc"])
    energy = EnergyHistory(
        time=np.array(e_rec["t"]), kinetic=np.array(e_rec["kin"]).T, strain=np.array(e_rec["pot"]).T,
        momentum=np.array(e_rec["mom"]).T, work_left=acc[:, 0], work_right=acc[:, 1], work_loads=acc[:, 2],
        work_friction=acc[:, 3], work_joints=acc[:, 8], impulse=acc[:, 4:8].sum(axis=1))
    probe_hist = _probe_histories(system, lattice, probe_list, arrays)
    snapshots = None
    if snaps:
        snapshots = FieldSnapshots(
            time=np.array([s[0] for s in snaps]), element_x=lattice.element_x, node_x=lattice.node_x,
            element_rod=lattice.element_rod, node_rod=lattice.node_rod,
            force=np.stack([s[1] for s in snaps], axis=-1), velocity=np.stack([s[2] for s in snaps], axis=-1),
            displacement=np.stack([s[3] for s in snaps], axis=-1))
    warn_list = []
    for i, r in enumerate(lattice.rods):
        if not r.exact and abs(r.time_scale - 1.0) > 0.01:
            msg = (f"rod {i}: its travel time is represented with a {abs(r.time_scale - 1) * 100:.2g} % error "
                   f"({r.n_elements} elements); use a smaller dt")
            warn_list.append(msg)
            warnings.warn(msg, stacklevel=2)
    diagnostics = {"version": __version__, "backend": backend, "wall_time_s": wall, "steps": n_steps,
                   "record_every": stride,
                   "elements": lattice.n_elements, "dt": dt, "energy_balance_error": energy.balance_error,
                   "lattice_report": lattice.report(), "warnings": warn_list}
    return SimulationResult(
        system=system, lattice=lattice, time=time, junction_force=arrays["junction_N"],
        junction_contact=arrays["junction_contact"].astype(bool),
        end_force={"left": arrays["end_N"][0], "right": arrays["end_N"][1]},
        end_velocity={"left": arrays["end_V"][0], "right": arrays["end_V"][1]},
        probes=probe_hist, snapshots=snapshots, energy=energy, final_force=N.copy(), final_velocity=v.copy(),
        diagnostics=diagnostics, record_every=stride, n_steps=n_steps, junction_events=history.events.finish(n_steps))
