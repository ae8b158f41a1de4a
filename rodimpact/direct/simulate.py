"""The direct problem: :func:`simulate` runs the wave propagation method on a system of rods."""

from __future__ import annotations

import math
import time as _time
from typing import Any, Callable, Iterable, Literal, Optional, Sequence

import numpy as np

from .._version import __version__
from .._validate import positive
from ..lattice import tolerance
from ..lattice.lattice import Lattice, build_lattice, default_time_step
from ..rods.conditions import (BitRockEnd, EndCondition, FixedEnd, ForceEnd, FreeEnd, NonReflectingEnd,
                               SpringEnd, VelocityEnd)
from ..rods.loads import Bearings, NodalForce
from ..rods.rod import Rod
from ..rods.system import InitialState, System
from . import _kernels as K
from . import guards
from .recording import Recorder, Recording, check_probes
from .result import Probe, ProbeHistory, SimulationResult, bit_rock_outcomes

Backend = Literal["numba", "numpy"]
#: longest run in steps (step indices are stored as int32 in result files)
_MAX_STEPS = 2_000_000_000
_MAX_CHUNK = 65536   # steps per compiled call at most: bounds the per-step input and output arrays
_DEFAULT_RECORDING = Recording()      # immutable: one instance serves every run that gives no outputs


def simulate(rods: System | Sequence[Rod] | Rod, velocities: Optional[Sequence[float]] = None,
             duration: Optional[float] = None, dt: Optional[float] = None, *,
             steps: Optional[int] = None, elements: Optional[int | tuple[int, int]] = None,
             resolution: Optional[float] = None, left: EndCondition | str = "free", right: EndCondition | str = "free",
             junctions: Optional[Sequence[Any]] = None, loads: Sequence[NodalForce | Bearings] = (),
             initial: Optional[Sequence[Optional[InitialState]]] = None, record: Optional[Recording] = None,
             probes: Optional[Iterable[Probe]] = None, snapshot_times: Optional[Sequence[float]] = None,
             snapshot_every: Optional[int] = None, energy_every: Optional[int] = None,
             record_every: Optional[int] = None, backend: Backend = "numba",
             progress: bool | None = None, allow_discretization_error: bool = False,
             max_element_updates: Optional[float] = None) -> SimulationResult:
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
    record:
        What to record besides the contact force and end values: a :class:`~rodimpact.Recording` (probes,
        snapshots, energy stride, history stride). Or give its fields as the keywords below (not both).
    probes, snapshot_times, snapshot_every, energy_every, record_every:
        The fields of :class:`~rodimpact.Recording`: probe histories; field snapshots at the steps nearest to
        the given times and/or every k steps; the energy sampling stride (default: about 256 samples per run);
        keep every ``record_every``-th step of the histories (default 1). Contact and separation times, contact
        durations and the peak contact force are taken at every step whatever the stride
        (``result.junction_events``).
    backend:
        "numba" (compiled, default) or "numpy" (readable reference path; slow).
    progress:
        Report progress on stderr (default: for runs of more than 10^9 element updates; a bar on a terminal,
        else a line every 10 %).
    allow_discretization_error:
        Run even if the lattice represents a rod's travel time or mass with an error above 1 % or smears a
        segment shorter than one element (:mod:`rodimpact.lattice.tolerance`); the error is then a warning (also
        listed in ``result.diagnostics["warnings"]``).
        Default ``False``: a ``ValueError`` that names the rod, the error and a dt that would satisfy it.
    max_element_updates:
        Refuse runs of more elements x steps than this (default 1e11, see
        :data:`rodimpact.direct.guards.DEFAULT_MAX_ELEMENT_UPDATES`; ``math.inf``: no limit). The memory the
        histories and snapshots need is checked against the available memory before the run as well.

    Physical quantities may be numbers in SI units, unit strings (``"2 ms"``) or pint Quantities.
    """
    system = rods if isinstance(rods, System) else System(
        rods, velocities if velocities is not None else _missing("velocities"), junctions, left, right,
        tuple(loads), initial)
    dt = _time_step(system, dt, elements, resolution)
    n_steps = _step_count(duration, steps, dt)
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    record = _recording(record, probes=probes, snapshot_times=snapshot_times, snapshot_every=snapshot_every,
                        energy_every=energy_every, record_every=record_every)
    lattice = build_lattice(system, dt)
    allowed = tolerance.check(system, lattice, allow_discretization_error)
    guards.check_element_updates(lattice.n_elements, n_steps, max_element_updates)
    probe_list = [_named_rod(p, i, system) for i, p in enumerate(record.probes)]
    wall0 = _time.perf_counter()
    state = _initial_state(system, lattice)
    arrays = _kernel_arrays(system, lattice, state, probe_list)
    bar = guards.progress(progress, n_steps, lattice.n_elements)
    capacity = max(1, min(n_steps, _MAX_CHUNK, int(1e8 // lattice.n_elements) if bar is not None else _MAX_CHUNK))
    # the compiled loop writes the steps straight into the histories when it keeps every step (no step columns)
    columns = 0 if backend == "numba" and record.record_every == 1 else capacity
    recorder = Recorder(record, lattice, arrays, state["N"].copy(), n_steps, columns)
    _advance(backend, n_steps, capacity, lattice, arrays, state, recorder, bar)
    wall = _time.perf_counter() - wall0

    N, v = state["N"], state["v"]
    hist = recorder.histories()
    energy = recorder.energy(dt)
    diagnostics = {"version": __version__, "backend": backend, "wall_time_s": wall, "steps": n_steps,
                   "record_every": recorder.stride,
                   "elements": lattice.n_elements, "dt": dt, "energy_balance_error": energy.balance_error,
                   "lattice_report": lattice.report(), "warnings": allowed}
    return SimulationResult(
        system=system, lattice=lattice, time=np.arange(0, n_steps, recorder.stride) * dt,
        junction_force=hist["junction_N"], junction_contact=hist["junction_contact"].astype(bool),
        end_force={"left": hist["end_N"][0], "right": hist["end_N"][1]},
        end_velocity={"left": hist["end_V"][0], "right": hist["end_V"][1]},
        probes=_probe_histories(system, lattice, probe_list, hist), snapshots=recorder.snapshots(lattice),
        energy=energy, final_force=N.copy(), final_velocity=v.copy(), diagnostics=diagnostics,
        record_every=recorder.stride, n_steps=n_steps, junction_events=recorder.junction_events(),
        bit_rock=bit_rock_outcomes(system, arrays["end_state"], energy.work_left[-1], energy.work_right[-1],
                                   energy.kinetic[:, 0] + energy.strain[:, 0]))


def _advance(backend: Backend, n_steps: int, capacity: int, lat: Lattice, arrays: dict, state: dict,
             recorder: Recorder, bar: Any) -> None:
    """Run all steps in calls of the ``backend``'s loop of at most ``capacity`` steps (the per-step inputs of
    each are evaluated before it), the array bundles of :mod:`rodimpact.direct._kernels` built once."""
    z = lat.impedance
    N, v = state["N"], state["v"]
    run = K.run_numba if backend == "numba" else K.run_numpy
    if backend == "numba":       # the same arrays as below, in one compiled call
        f, g, reflection, touch, quiet = K.wave_setup(N, v, z, arrays["rod_start"], arrays["sp_elem"],
                                                      arrays["sp_loaded"], arrays["pr_rod"], arrays["pr_local"],
                                                      passive_right(arrays))
    else:
        reflection, touch = _wave_arrays(lat, arrays)
        f, g = K.waves(N, v, z)
        quiet = quiet_front(N, v, 0, passive_right(arrays), arrays["sp_elem"][arrays["sp_loaded"]])
    wave_state = (N, v, f, g)
    lattice = (z, reflection, touch, arrays["rod_start"], quiet)
    junctions = tuple(arrays[key] for key in ("junction_code", "junction_state", "gap", "gap_tol", "u_end"))
    n_sp = arrays["sp_elem"].size
    scratch = (np.zeros(n_sp), np.zeros(n_sp))      # resolved force and velocity of each special node
    chunk = recorder.chunk
    probes = (arrays["pr_rod"], arrays["pr_local"], arrays["pr_sp"], *chunk[4:], arrays["pr_disp"])
    k = 0
    while k < n_steps:
        n = min(capacity, n_steps - k)
        end_value, sp_force = arrays["step_inputs"](k, n)
        ends = (arrays["end_code"], arrays["end_par"], arrays["end_state"], end_value)
        specials = (arrays["sp_elem"], arrays["sp_cap"], sp_force, *scratch)
        done = run(k, n, wave_state, lattice, lat.dt, ends, junctions, specials, probes, chunk[:4], arrays["acc"],
                   recorder.record)
        if done < n:
            recorder.grow_events()
        k += done
        if bar is not None:
            bar.update(done)
    if bar is not None:
        bar.close()


def quiet_front(N: np.ndarray, v: np.ndarray, first: int, right_passive: bool, forced: np.ndarray) -> int:
    """First element (>= ``first``) from which the lattice starts at rest and stays so until a wave from the
    left arrives: behind the last element with an initial force or velocity and behind the last node with a
    prescribed nodal force (``forced``: the elements left of those nodes); the element count (nothing is at
    rest) if the right end is not ``right_passive`` (it could move the rods by itself). Friction nodes do not
    count: at rest they stay at rest."""
    if not right_passive:
        return int(N.size)
    moving = np.flatnonzero((N[first:] != 0.0) | (v[first:] != 0.0))
    quiet = first + (int(moving[-1]) + 1 if moving.size else 0)
    return max(quiet, int(forced.max()) + 2 if forced.size else 0)


def passive_right(arrays: dict) -> bool:
    """The right end cannot start a wave by itself: fixed, free, a spring or bit-rock law, or a non-reflecting
    end whose continuation is at rest (prescribed forces and velocities may act at any step)."""
    code, par = int(arrays["end_code"][1]), arrays["end_par"][1]
    return code in (K.FREE, K.FIXED, K.SPRING, K.BITROCK) or (code == K.NONREFLECTING and par[1] == 0.0)


def _recording(record: Optional[Recording], **keywords: Any) -> Recording:
    """``record``, or a :class:`Recording` of the keywords that were given (not both)."""
    given = {key: val for key, val in keywords.items() if val is not None}
    if record is None:
        return Recording(**given) if given else _DEFAULT_RECORDING
    if not isinstance(record, Recording):
        raise TypeError(f"record: must be a Recording(probes=..., snapshot_times=..., ...), got "
                        f"{type(record).__name__}")
    if given:
        raise ValueError(f"record: give the outputs either as record=Recording(...) or as the keywords "
                         f"{', '.join(f'{key}=' for key in given)}, not both")
    return record


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
    v = np.empty(lat.n_elements)
    rs = lat.rod_start.tolist()
    for r, velocity in enumerate(system.velocities):
        v[rs[r]:rs[r + 1]] = velocity
    for r, st in enumerate(system.initial):
        if st is None:
            continue
        a, b = lat.rod_start[r], lat.rod_start[r + 1]
        x_local = lat.element_x[a:b] - system.rod_offsets()[r]
        if st.force is not None:
            N[a:b] = _field(st.force, x_local, b - a, f"initial[{r}].force")
        if st.velocity is not None:
            v[a:b] = _field(st.velocity, x_local, b - a, f"initial[{r}].velocity")
    return {"N": N, "v": v}


def _end_setup(cond: EndCondition, side: int, N: np.ndarray, v: np.ndarray, z: np.ndarray,
               dt: float) -> tuple[int, tuple[float, float], Optional[Callable[[int, int], np.ndarray]]]:
    """Kernel code, parameters and the per-step values (a function of first step and count; ``None``: the end
    has none, its row stays 0) of one outer end (side 0 = left, 1 = right)."""
    e = 0 if side == 0 else z.size - 1
    sign = -1.0 if side == 0 else 1.0        # outward direction in x
    values: Optional[Callable[[int, int], np.ndarray]] = None
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
    left, right = _end_setup(system.left, 0, N, v, z, dt), _end_setup(system.right, 1, N, v, z, dt)
    codes, pars, end_values = (left[0], right[0]), (left[1], right[1]), (left[2], right[2])
    junction_code = np.array([j.code for j in system.junctions], dtype=np.int64)
    gap = np.array([getattr(j, "gap", 0.0) for j in system.junctions], dtype=float)
    rs = lat.rod_start.tolist()
    length = lat.element_length
    gap_tol = np.array([1e-9 * min(length[a - 1], length[a]) for a in rs[1:-1]], dtype=float)
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
        end_value = np.zeros((2, n))
        for e, values in enumerate(end_values):
            if values is not None:
                end_value[e] = values(first, n)
        return end_value, sp_force

    # ---- probes
    pr_rod, pr_local, pr_sp = [], [], []
    for i, p in enumerate(check_probes(probes)):
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
        gap_tol=gap_tol,
        u_end=np.zeros((n_rods, 2)), sp_elem=sp_elem, sp_cap=sp_cap,
        sp_loaded=np.array([a in node_loads for a in sp_elem], dtype=bool),
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
