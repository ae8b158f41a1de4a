"""The direct problem: :func:`simulate` runs the wave propagation method on a system of rods."""

from __future__ import annotations

import math
import time as _time
import warnings
from typing import Any, Callable, Iterable, Literal, Optional, Sequence

import numpy as np

from .. import __version__
from .._validate import finite_array, positive
from ..lattice.lattice import Lattice, build_lattice, default_time_step
from ..rods.conditions import (BitRockEnd, EndCondition, FixedEnd, ForceEnd, FreeEnd, NonReflectingEnd,
                               SpringEnd, VelocityEnd)
from ..rods.loads import Bearings, NodalForce
from ..rods.rod import Rod
from ..rods.system import InitialState, System
from . import _kernels as K
from . import guards
from .result import EnergyHistory, EventTracker, FieldSnapshots, Probe, ProbeHistory, SimulationResult

Backend = Literal["numba", "numpy"]
#: longest run in steps (step indices are stored as int32 in result files)
_MAX_STEPS = 2_000_000_000
_MAX_CHUNK = 65536   # steps per compiled call at most: bounds the per-chunk input arrays


def simulate(rods: System | Sequence[Rod] | Rod, velocities: Optional[Sequence[float]] = None,
             duration: Optional[float] = None, dt: Optional[float] = None, *,
             steps: Optional[int] = None, elements: Optional[int | tuple[int, int]] = None,
             resolution: Optional[float] = None, left: EndCondition | str = "free", right: EndCondition | str = "free",
             junctions: Optional[Sequence[Any]] = None, loads: Sequence[NodalForce | Bearings] = (),
             initial: Optional[Sequence[Optional[InitialState]]] = None, probes: Iterable[Probe] = (),
             snapshot_times: Optional[Sequence[float]] = None, snapshot_every: Optional[int] = None,
             energy_every: Optional[int] = None, record_every: int = 1, backend: Backend = "numba",
             progress: bool | None = None, max_element_updates: Optional[float] = None) -> SimulationResult:
    """Simulate the longitudinal impact of rods with the exact wave propagation method (thesis Sec. 3.1).

    Parameters
    ----------
    rods:
        Rods listed left to right (or a ready :class:`~rodimpact.rods.system.System`, in which case
        ``velocities``, ``left``, ``right``, ``junctions``, ``loads`` and ``initial`` come from it).
    velocities:
        Initial velocity of each rod, m/s (positive to the right).
    duration:
        Simulated time, s (or give ``steps``).
    dt:
        Time step = travel time of every element, s. Default: the ``dt`` of impedance-level rods, else one
        that gives each segment >= 4 and the longest rod >= 200 elements.
    elements:
        Instead of ``dt``: the number of elements of rod 0, or ``(rod_index, n)``; dt = travel time / n.
    resolution:
        Instead of ``dt``: the largest element length in m; dt = resolution / (largest wave speed).
    left, right:
        Outer end conditions (objects or "free", "fixed", "nonreflecting"); default free.
    junctions:
        One per neighbouring pair; default unilateral :class:`~rodimpact.Contact`.
    loads:
        :class:`~rodimpact.NodalForce` / :class:`~rodimpact.Bearings`.
    initial:
        Optional per-rod :class:`~rodimpact.InitialState` (non-uniform initial force/velocity).
    probes:
        :class:`~rodimpact.Probe` objects: force, velocity, displacement and strain histories.
    snapshot_times, snapshot_every:
        Field snapshots N(x), v(x), u(x) at the steps nearest to the given times and/or every k steps.
    energy_every:
        Energy sampling stride in steps (default: about 256 samples per run).
    record_every:
        Keep every ``record_every``-th step of the histories (contact force, contact flag, end values, probes);
        default 1 (every step). A stride bounds their memory on long runs; contact and separation times, contact
        durations and the peak contact force are still taken at every step (``result.junction_events``).
    backend:
        "numba" (compiled, default) or "numpy" (readable reference path; slow).
    progress:
        Report progress on stderr (default: for runs of more than 10^9 element updates; a bar on a terminal,
        else a line every 10 %).
    max_element_updates:
        Refuse runs of more elements x steps than this (default 1e11, see
        :data:`rodimpact.direct.guards.DEFAULT_MAX_ELEMENT_UPDATES`; ``math.inf``: no limit). The memory the
        histories and snapshots need is checked against the available memory before the run as well.
    """
    system = rods if isinstance(rods, System) else System(
        rods, velocities if velocities is not None else _missing("velocities"), junctions, left, right,
        tuple(loads), initial)
    dt = _time_step(system, dt, elements, resolution)
    n_steps = _step_count(duration, steps, dt)
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    lattice = build_lattice(system, dt)
    probe_list = [_named_rod(p, i, system) for i, p in enumerate(probes)]
    snap_steps = _snapshot_steps(snapshot_times, snapshot_every, n_steps, dt)
    every = _energy_stride(energy_every, n_steps)
    stride = _record_stride(record_every)
    wall0 = _time.perf_counter()
    state = _initial_state(system, lattice)
    arrays = _kernel_arrays(system, lattice, state, probe_list)
    rows = sum(arrays[key].shape[0] for key in _HISTORIES) + len(probe_list)      # + strain per probe
    guards.check_simulation(lattice.n_elements, n_steps, rows, stride, len(snap_steps), max_element_updates)
    history = _History(arrays, n_steps, stride)
    run = K.run_numba if backend == "numba" else K.run_numpy

    N, v = state["N"], state["v"]
    N0 = N.copy()
    reflection, touch = _wave_arrays(lattice, arrays)
    z = lattice.impedance
    rs = lattice.rod_start
    energy_steps = sorted(set(range(0, n_steps + 1, every)) | {n_steps})
    events = sorted(set(energy_steps) | set(snap_steps) | set(range(0, n_steps, _MAX_CHUNK)))
    bar = guards.progress(progress, n_steps, lattice.n_elements)
    e_rec: dict[str, list] = {k: [] for k in ("t", "kin", "pot", "mom", "acc")}
    snaps: list[tuple[float, np.ndarray, np.ndarray, np.ndarray]] = []
    static = {key: val for key, val in arrays.items() if key not in _HISTORIES and key != "step_inputs"}
    k = 0
    for target in events:
        if target > k:
            kw = {**static, **history.buffers(target - k)}
            kw["end_value"], kw["sp_force"] = arrays["step_inputs"](k, target - k)
            run(target - k, N, v, z, reflection, touch, **kw, dt=dt)
            if bar is not None:
                bar.update(target - k)
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
    if bar is not None:
        bar.close()
    wall = _time.perf_counter() - wall0

    history.flush()
    time = np.arange(0, n_steps, stride) * dt
    arrays.update(history.recorded)
    acc = np.array(e_rec["acc"])
    energy = EnergyHistory(
        time=np.array(e_rec["t"]), kinetic=np.array(e_rec["kin"]).T, strain=np.array(e_rec["pot"]).T,
        momentum=np.array(e_rec["mom"]).T, work_left=acc[:, 0], work_right=acc[:, 1], work_loads=acc[:, 2],
        work_friction=acc[:, 3], impulse=acc[:, 4:].sum(axis=1))
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


# ---------------------------------------------------------------------------------------------- helpers
def _named_rod(probe: Any, i: int, system: System) -> Any:
    """``probe`` with a rod name replaced by the rod's index (other objects are checked later)."""
    if not isinstance(probe, Probe) or not isinstance(probe.rod, str):
        return probe
    names = [r.name for r in system.rods]
    if probe.rod not in names:
        raise ValueError(f"probes[{i}].rod: no rod is named {probe.rod!r}; rod names: {names}")
    return Probe(probe.name, names.index(probe.rod), probe.position)


def _missing(name: str):
    raise ValueError(f"{name}: required when rods are given as a list (one initial velocity per rod, m/s)")


def _time_step(system: System, dt, elements, resolution) -> float:
    """dt from exactly one of dt / elements / resolution (or the default)."""
    given = [name for name, val in (("dt", dt), ("elements", elements), ("resolution", resolution)) if val is not None]
    if len(given) > 1:
        raise ValueError(f"{given[1]}: give only one of dt=, elements= or resolution= (got {', '.join(given)})")
    if dt is not None:
        return positive("dt", dt, "s")
    if elements is not None:
        rod, n = (0, elements) if not isinstance(elements, tuple) else elements
        if isinstance(rod, bool) or not isinstance(rod, (int, np.integer)) or not 0 <= rod < system.n_rods:
            raise ValueError(f"elements: rod index must be 0..{system.n_rods - 1}, got {rod!r}")
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"elements: the number of elements must be an integer >= 1, got {n!r}")
        return system.rods[int(rod)].total_travel_time / int(n)
    if resolution is not None:
        res = positive("resolution", resolution, "m")
        c_max = max(float(np.max(r.wave_speed(r.segment_bounds[:-1]))) for r in system.rods)
        return res / c_max
    return default_time_step(system)


def _step_count(duration: Optional[float], steps: Optional[int], dt: float) -> int:
    if (duration is None) == (steps is None):
        raise ValueError("duration: give exactly one of duration= (s) or steps= (number of time steps)")
    if steps is not None:
        if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
            raise ValueError(f"steps: must be an integer >= 1, got {steps!r}")
        if steps > _MAX_STEPS:
            raise ValueError(f"steps: at most {_MAX_STEPS:.0e} per run, got {steps}; use a larger dt")
        return int(steps)
    duration = positive("duration", duration, "s")
    x = duration / dt
    if not x <= _MAX_STEPS:
        raise ValueError(f"duration: {duration:.4g} s needs {x:.3g} steps of dt = {dt:.4g} s; at most "
                         f"{_MAX_STEPS:.0e} per run")
    n = int(round(x)) if abs(x - round(x)) <= 1e-9 * max(x, 1.0) else int(math.ceil(x))
    return max(n, 1)


def _snapshot_steps(times, every, n_steps: int, dt: float) -> list[int]:
    out: set[int] = set()
    if times is not None:
        t = finite_array("snapshot_times", np.atleast_1d(times))
        if np.any(t < 0) or np.any(t > n_steps * dt * (1 + 1e-12)):
            raise ValueError(f"snapshot_times: must lie in [0, {n_steps * dt:.6g}] s, got {t.min():.6g}..{t.max():.6g}")
        out |= set(np.round(t / dt).astype(int).tolist())
    if every is not None:
        if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
            raise ValueError(f"snapshot_every: must be an integer number of steps >= 1, got {every!r}")
        if n_steps // int(every) + 1 > 100_000:      # checked before the steps are listed (they could be billions)
            raise ValueError(f"snapshot_every: {every} gives {n_steps // int(every) + 1} snapshots; use a larger stride")
        out |= set(range(0, n_steps + 1, int(every)))
        if len(out) > 100_000:
            raise ValueError(f"snapshot_every: {every} gives {len(out)} snapshots; use a larger stride")
    return sorted(out)


def _energy_stride(every, n_steps: int) -> int:
    if every is None:   # about 256 samples: each sample ends a compiled call, so keep them few by default
        return max(1, -(-n_steps // 256))
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise ValueError(f"energy_every: must be an integer number of steps >= 1, got {every!r}")
    if n_steps // int(every) > _MAX_ENERGY_SAMPLES:
        raise ValueError(f"energy_every: {every} gives {n_steps // int(every) + 1} energy samples of {n_steps} steps; "
                         f"at most {_MAX_ENERGY_SAMPLES:,} (use a larger stride)")
    return int(every)


_MAX_ENERGY_SAMPLES = 1_000_000


def _record_stride(every) -> int:
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise ValueError(f"record_every: must be an integer number of steps >= 1, got {every!r}")
    return int(every)


#: per-step history arrays the kernels write (one column per step)
_HISTORIES = ("pr_N", "pr_V", "pr_u", "junction_N", "junction_contact", "end_N", "end_V")


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


def _field(value, x: np.ndarray, n: int, name: str) -> np.ndarray:
    if callable(value):
        out = np.broadcast_to(np.asarray(value(x), dtype=float), x.shape).astype(float)
    elif np.ndim(value) == 0:
        out = np.full(n, float(value))
    else:
        out = np.asarray(value, dtype=float)
        if out.shape != (n,):
            raise ValueError(f"{name}: needs one value per lattice element ({n}), got shape {out.shape}")
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{name}: must be finite everywhere")
    return out


def _initial_state(system: System, lat: Lattice) -> dict[str, np.ndarray]:
    N = np.zeros(lat.n_elements)
    v = np.zeros(lat.n_elements)
    offsets = system.rod_offsets()
    for r in range(system.n_rods):
        a, b = lat.rod_start[r], lat.rod_start[r + 1]
        v[a:b] = system.velocities[r]
        st = system.initial[r]
        if st is None:
            continue
        x_local = lat.element_x[a:b] - offsets[r]
        if st.force is not None:
            N[a:b] = _field(st.force, x_local, b - a, f"initial[{r}].force")
        if st.velocity is not None:
            v[a:b] = _field(st.velocity, x_local, b - a, f"initial[{r}].velocity")
    return {"N": N, "v": v}


def _end_setup(cond: EndCondition, side: int, N: np.ndarray, v: np.ndarray, z: np.ndarray,
               dt: float) -> tuple[int, tuple[float, float], Callable[[int, int], np.ndarray]]:
    """Kernel code, parameters and the per-step values (a function of first step and count) of one outer end
    (side 0 = left, 1 = right)."""
    e = 0 if side == 0 else z.size - 1
    sign = -1.0 if side == 0 else 1.0        # outward direction in x
    values: Callable[[int, int], np.ndarray] = lambda first, n: np.zeros(n)  # noqa: E731
    par = (0.0, 0.0)
    if isinstance(cond, FreeEnd):
        code = K.FREE
    elif isinstance(cond, FixedEnd):
        code = K.FIXED
    elif isinstance(cond, ForceEnd):
        code = K.FORCE
        values = lambda first, n: cond.force.step_values(n, dt, first)  # noqa: E731
    elif isinstance(cond, VelocityEnd):
        code = K.VELOCITY
        values = lambda first, n: sign * cond.velocity.step_values(n, dt, first)  # noqa: E731
    elif isinstance(cond, NonReflectingEnd):
        code = K.NONREFLECTING
        zx = z[e] if cond.impedance is None else cond.impedance
        # incoming characteristic of the continuation, in its initial state (= that of the end element):
        # left: N - Zx V = const, right: N + Zx V = const; written as N = invariant - Zx w
        par = (zx, N[e] + sign * zx * v[e])
    elif isinstance(cond, SpringEnd):
        code = K.SPRING
        par = (cond.stiffness, cond.damping)
    elif isinstance(cond, BitRockEnd):
        code = K.BITROCK
        par = (cond.loading_stiffness, cond.unloading_stiffness)
    else:  # pragma: no cover - System validates
        raise TypeError(f"unknown end condition {cond!r}")
    return code, par, values


def _kernel_arrays(system: System, lat: Lattice, state: dict, probes: list[Probe]) -> dict:
    """All arrays the kernels need, in the layout documented in :mod:`rodimpact.direct._kernels`."""
    dt = lat.dt
    N, v, z = state["N"], state["v"], lat.impedance
    n_rods = lat.n_rods
    codes, pars, end_values = zip(*(_end_setup(c, s, N, v, z, dt) for s, c in enumerate((system.left, system.right))))
    junction_code = np.array([j.code for j in system.junctions], dtype=np.int64)
    gap = np.array([getattr(j, "gap", 0.0) for j in system.junctions], dtype=float)
    # ---- special interior nodes
    sp: dict[int, list[float]] = {}        # element-left-of-node -> [friction capacity]
    node_loads: dict[int, list] = {}        # element-left-of-node -> prescribed force histories
    for i, ld in enumerate(system.loads):
        n_r = lat.rod_start[ld.rod + 1] - lat.rod_start[ld.rod]
        if isinstance(ld, NodalForce):
            m, _ = lat.nearest_node(ld.rod, ld.position)
            m = min(max(m, 1), n_r - 1)
            if n_r < 2:
                raise ValueError(f"loads[{i}]: rod {ld.rod} has a single element and no interior node; use a smaller dt")
            a = int(lat.rod_start[ld.rod] + m - 1)
            sp.setdefault(a, [0.0])
            node_loads.setdefault(a, []).append(ld.force)
        else:
            s = lat.rod_start[ld.rod]
            x_nodes = np.cumsum(lat.element_length[s:lat.rod_start[ld.rod + 1]])[:-1]   # interior nodes 1..n-1
            inside = np.zeros(x_nodes.size, dtype=bool)
            for a0, b0 in ld.spans:
                inside |= (x_nodes >= a0 - 1e-12) & (x_nodes <= b0 + 1e-12)
            n_hat = int(inside.sum())
            if n_hat == 0:
                raise ValueError(f"loads[{i}].spans: no lattice node of rod {ld.rod} lies in {list(ld.spans)}; "
                                 f"use a smaller dt (element length here ~{lat.element_length[s]:.3g} m)")
            mass = float(z[s:lat.rod_start[ld.rod + 1]].sum() * dt)    # thesis eq. 3.21 (lattice mass)
            total = ld.friction_coefficient * (ld.normal_load if ld.normal_load is not None else mass * ld.gravity)
            for m in np.flatnonzero(inside):
                a = int(s + m)
                sp.setdefault(a, [0.0])[0] += total / n_hat
    sp_elem = np.array(sorted(sp), dtype=np.int64)
    sp_cap = np.array([sp[a][0] for a in sp_elem], dtype=float)
    loaded = [(i, node_loads[a]) for i, a in enumerate(sp_elem) if a in node_loads]

    def step_inputs(first: int, n: int) -> tuple[np.ndarray, np.ndarray]:
        """Prescribed end values and nodal forces for steps first .. first + n - 1 (evaluated per chunk so
        that memory does not grow with the run length)."""
        sp_force = np.zeros((sp_elem.size, n))
        for i, histories in loaded:
            for h in histories:
                sp_force[i] += h.step_values(n, dt, first)
        return np.vstack([f(first, n) for f in end_values]), sp_force

    # ---- probes
    pr_rod, pr_local, pr_sp = [], [], []
    names = set()
    for i, p in enumerate(probes):
        if not isinstance(p, Probe):
            raise TypeError(f"probes[{i}]: must be a Probe(name, rod, position), got {type(p).__name__}")
        if p.name in names:
            raise ValueError(f"probes[{i}].name: {p.name!r} is used twice")
        names.add(p.name)
        if p.rod >= n_rods:
            raise ValueError(f"probes[{i}].rod: rod index {p.rod} does not exist (0..{n_rods - 1})")
        length = system.rods[p.rod].length
        if not (-1e-12 <= p.position <= length * (1 + 1e-12)):
            raise ValueError(f"probes[{i}].position: must lie within rod {p.rod}, 0 <= x <= {length:.6g} m, "
                             f"got {p.position:.6g} m")
        m, _ = lat.nearest_node(p.rod, p.position)
        pr_rod.append(p.rod)
        pr_local.append(m)
        a = int(lat.rod_start[p.rod] + m - 1)
        idx = np.flatnonzero(sp_elem == a)
        n_r = lat.rod_start[p.rod + 1] - lat.rod_start[p.rod]
        pr_sp.append(int(idx[0]) if idx.size and 0 < m < n_r else -1)
    n_p, n_j = len(probes), n_rods - 1
    return dict(
        rod_start=lat.rod_start.astype(np.int64), end_code=np.array(codes, dtype=np.int64),
        end_par=np.array(pars, dtype=float), end_state=np.zeros((2, 2)), step_inputs=step_inputs,
        junction_code=junction_code, junction_state=np.zeros(n_j, dtype=np.int64), gap=gap,
        gap_tol=1e-9 * np.minimum(lat.element_length[lat.rod_start[1:-1] - 1], lat.element_length[lat.rod_start[1:-1]]),
        u_end=np.zeros((n_rods, 2)), sp_elem=sp_elem, sp_cap=sp_cap,
        pr_rod=np.array(pr_rod, dtype=np.int64), pr_local=np.array(pr_local, dtype=np.int64),
        pr_sp=np.array(pr_sp, dtype=np.int64), pr_disp=np.zeros(n_p), acc=np.zeros(8),
        # per-step histories: shapes only (rows); the steps are written through _History's buffers
        pr_N=np.zeros((n_p, 0)), pr_V=np.zeros((n_p, 0)), pr_u=np.zeros((n_p, 0)), junction_N=np.zeros((n_j, 0)),
        junction_contact=np.zeros((n_j, 0)), end_N=np.zeros((2, 0)), end_V=np.zeros((2, 0)))


def _wave_arrays(lat: Lattice, arrays: dict) -> tuple[np.ndarray, np.ndarray]:
    """Reflection factor R_j = (Z_{j+1} - Z_j)/(Z_{j+1} + Z_j) of every node between elements j and j+1
    (thesis eq. 2.40) and the elements whose (N, v) the boundary solver reads each step."""
    z = lat.impedance
    reflection = (z[1:] - z[:-1]) / (z[1:] + z[:-1])
    rs = lat.rod_start
    touch = set(rs[:-1].tolist()) | set((rs[1:] - 1).tolist())
    touch |= set(arrays["sp_elem"].tolist()) | set((arrays["sp_elem"] + 1).tolist())
    for r, m in zip(arrays["pr_rod"], arrays["pr_local"]):
        a = rs[r] + m - 1
        touch |= {int(a), int(a + 1)} & set(range(rs[r], rs[r + 1]))
    return reflection, np.array(sorted(touch), dtype=np.int64)


def _node_displacements(N, N0, z, dt, rod_start, u_end) -> np.ndarray:
    """Node displacements from the left-end displacement of each rod plus the element elongations
    (N - N0) dt / Z (exact on the lattice: elements are uniform at t = k dt)."""
    out = []
    for r in range(rod_start.size - 1):
        a, b = rod_start[r], rod_start[r + 1]
        out.append(u_end[r, 0] + np.concatenate([[0.0], np.cumsum((N[a:b] - N0[a:b]) * dt / z[a:b])]))
    return np.concatenate(out)


def _probe_histories(system: System, lat: Lattice, probes: list[Probe], arrays: dict) -> dict[str, ProbeHistory]:
    out = {}
    for i, p in enumerate(probes):
        rod = system.rods[p.rod]
        seg = int(np.clip(np.searchsorted(rod.segment_bounds, p.position, side="right") - 1, 0,
                          len(rod.segments) - 1))
        ea = rod.segment_material(seg).youngs_modulus * float(rod.area(min(p.position, rod.length)))
        _, x_node = lat.nearest_node(p.rod, p.position)
        force = arrays["pr_N"][i]
        out[p.name] = ProbeHistory(p, x_node, force, arrays["pr_V"][i], arrays["pr_u"][i], force / ea)
    return out
