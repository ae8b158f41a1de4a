"""The direct problem as one value, and the one step that turns it into the lattice and the kernel inputs.

A :class:`Problem` holds everything that defines a run: the :class:`~rodimpact.System` (rods, junctions, ends,
loads, initial state), the :class:`TimeGrid` (time step and number of steps) and the declared outputs
(:class:`~rodimpact.Outputs`). It is validated once, when it is made. :meth:`Problem.compile` builds the
equal-travel-time lattice (thesis Sec. 3.1) and the arrays of :mod:`rodimpact.direct._kernels`: the solvers
(:func:`~rodimpact.simulate`, :func:`~rodimpact.simulate_batch`, the design adjoint, sweeps, model files) all
go through it, so no solver sets up a run by itself (docs/architecture.md, "The problem object").
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence

import numpy as np

from .._validate import positive
from ..lattice.lattice import Lattice, build_lattice, default_time_step
from ..rods.conditions import (BitRockEnd, EndCondition, FixedEnd, ForceEnd, FreeEnd, LumpedEnd, LumpedJoint,
                               NonReflectingEnd, DeformableJoint, PointMass, SpringDashpot, SpringEnd, VelocityEnd)
from ..rods.laws import N_PARAMS
from ..rods.loads import Bearings, NodalForce
from ..rods.rod import Rod
from ..rods.soil import ShaftResistance, SmithSoil, SoilToe
from ..rods.system import InitialState, System
from . import boundary as B
from . import soil as S
from .joints import HEADER_COLUMNS, STATE_COLUMNS
from .lumped import CUSHION, MASS
from .recording import Outputs, check_probes
from .result import Probe

#: longest run in steps (step indices are stored as int32 in result files)
MAX_STEPS = 2_000_000_000
#: the outputs of a run that declares none: one immutable instance serves every such run
NO_OUTPUTS = Outputs()


@dataclass(frozen=True)
class TimeGrid:
    """The time discretisation of a run: the time step ``dt`` (s), which is the travel time of every lattice
    element, and the number of steps. Node values are held during step k = 0 .. steps - 1, on
    [k dt, (k + 1) dt) (architecture.md, "Lattice")."""

    dt: float
    steps: int

    def __post_init__(self) -> None:
        object.__setattr__(self, "dt", positive("dt", self.dt, "s"))
        s = self.steps
        if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or s < 1:
            raise ValueError(f"steps: must be an integer >= 1, got {s!r}")
        if s > MAX_STEPS:
            raise ValueError(f"steps: at most {MAX_STEPS:.0e} per run, got {s}; use a larger dt")
        object.__setattr__(self, "steps", int(s))

    @classmethod
    def of(cls, system: Optional[System] = None, *, duration: Optional[float] = None, steps: Optional[int] = None,
           dt: Optional[float] = None, elements: Optional[int | tuple[int, int]] = None,
           resolution: Optional[float] = None) -> TimeGrid:
        """The grid of a run of ``duration`` (s) or ``steps`` (exactly one), with ``dt`` from exactly one of the
        rules (``system`` is needed by all but ``dt``):

        * ``dt``: given, s;
        * ``elements``: ``n`` elements in rod 0, or ``(rod, n)``; dt = that rod's travel time / n;
        * ``resolution``: the longest element, m; dt = resolution / (largest wave speed);
        * none: :func:`~rodimpact.lattice.lattice.default_time_step` (impedance-level rods keep their own dt).

        ``TimeGrid.of(duration=400e-6, dt=1e-6)`` needs no system (e.g. for :func:`~rodimpact.simulate_batch`).

        A duration becomes ``round(duration / dt)`` steps when it is a whole number of steps to 1e-9, else the
        next whole number: the run covers at least ``duration``.
        """
        dt = _time_step(system, dt, elements, resolution)
        return cls(dt, _step_count(duration, steps, dt))

    @property
    def duration(self) -> float:
        """Simulated time, s."""
        return self.steps * self.dt


@dataclass(frozen=True, eq=False)
class Problem:
    """Everything that defines a run of the direct problem: ``system`` (a :class:`~rodimpact.System`), ``time``
    (a :class:`TimeGrid`) and ``outputs`` (a :class:`~rodimpact.Outputs`: probes, snapshots, energy and
    history strides; the contact force and end values are always kept); ``allow_discretization_error``: run
    even if the lattice represents a rod's travel time or mass with an error above 1 % or smears a segment
    shorter than one element (:mod:`rodimpact.lattice.tolerance`; the error is then a warning, also listed in
    ``result.diagnostics["warnings"]``), default ``False``: the solver refuses such a lattice with a ``ValueError``
    that names the rod, the error and a dt that would satisfy it. Validated when made: probes that name a
    rod are resolved to its index. :meth:`compile` turns it into the lattice and the kernel inputs;
    :func:`~rodimpact.simulate` solves it.

    >>> import rodimpact as ri
    >>> striker = ri.Rod.from_impedance([51e3] * 50, dt=1e-6)
    >>> bar = ri.Rod.from_impedance([51e3] * 200, dt=1e-6)
    >>> p = ri.Problem.of([striker, bar], [5.0, 0.0], duration=300e-6, right="nonreflecting")
    >>> p.time.steps, round(ri.simulate(p).contact_force.min())
    (300, -127500)
    """

    system: System
    time: TimeGrid
    outputs: Outputs = NO_OUTPUTS
    allow_discretization_error: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.system, System):
            raise TypeError(f"system: must be a System, got {type(self.system).__name__}")
        if not isinstance(self.time, TimeGrid):
            raise TypeError(f"time: must be a TimeGrid(dt, steps), got {type(self.time).__name__}")
        if not isinstance(self.outputs, Outputs):
            raise TypeError(f"outputs: must be an Outputs(probes=..., snapshot_times=..., ...), got "
                            f"{type(self.outputs).__name__}")
        if not isinstance(self.allow_discretization_error, (bool, np.bool_)):
            raise TypeError(f"allow_discretization_error: must be True or False, got "
                            f"{self.allow_discretization_error!r}")
        object.__setattr__(self, "allow_discretization_error", bool(self.allow_discretization_error))
        probes = tuple(_named_rod(p, i, self.system) for i, p in enumerate(self.outputs.probes))
        if probes != self.outputs.probes:
            object.__setattr__(self, "outputs", _with_probes(self.outputs, probes))

    @classmethod
    def of(cls, rods: System | Sequence[Rod] | Rod, velocities: Optional[Sequence[float]] = None, *,
           duration: Optional[float] = None, steps: Optional[int] = None, dt: Optional[float] = None,
           elements: Optional[int | tuple[int, int]] = None, resolution: Optional[float] = None,
           left: EndCondition | str = "free", right: EndCondition | str = "free",
           junctions: Optional[Sequence[Any]] = None, loads: Sequence[NodalForce | Bearings] = (),
           initial: Optional[Sequence[Optional[InitialState]]] = None,
           outputs: Optional[Outputs] = None, allow_discretization_error: bool = False) -> Problem:
        """The short form: rods listed left to right with their initial ``velocities`` (m/s) and the system's
        other parts as keywords (or a ready :class:`~rodimpact.System`, and then none of them), the time rule
        of :meth:`TimeGrid.of`, the ``outputs`` and ``allow_discretization_error``."""
        if isinstance(rods, System):
            given = [k for k, v in (("velocities", velocities), ("junctions", junctions), ("initial", initial))
                     if v is not None] + [k for k, v in (("left", left), ("right", right)) if v != "free"]
            if tuple(loads):
                given.append("loads")
            if given:
                raise ValueError(f"{given[0]}: a System already holds its {', '.join(given)}; give either the System "
                                 f"or the rods with their {', '.join(given)}")
            system = rods
        else:
            if velocities is None:
                raise ValueError("velocities: required when rods are given as a list (one initial velocity per "
                                 "rod, m/s)")
            system = System(rods, velocities, junctions, left, right, tuple(loads), initial)
        time = TimeGrid.of(system, duration=duration, steps=steps, dt=dt, elements=elements, resolution=resolution)
        return cls(system, time, NO_OUTPUTS if outputs is None else outputs, allow_discretization_error)

    @functools.cached_property
    def lattice(self) -> Lattice:
        """The equal-travel-time lattice of the system at ``time.dt`` (built once per problem)."""
        return build_lattice(self.system, self.time.dt)

    def compile(self, lattice: Optional[Lattice] = None) -> CompiledProblem:
        """The lattice, the initial element state and the kernel inputs of this problem (a fresh state each
        call: the solvers advance it in place). ``lattice``: the lattice of another problem with the same rods
        and time step, built once for a batch of problems that differ only in their ends, junctions, loads or
        initial state (the soils of a bearing graph, :func:`rodimpact.pile.blow.drive_blow_batch`); its time
        step and rod count are checked here, the rods by the discretisation check of the run."""
        lat = self.lattice if lattice is None else lattice
        if lattice is not None and (lattice.dt != self.time.dt or lattice.n_rods != len(self.system.rods)):
            raise ValueError(f"lattice: built for other rods or another time step (dt = {lattice.dt:.6g} s, "
                             f"{lattice.n_rods} rods) than this problem's (dt = {self.time.dt:.6g} s, "
                             f"{len(self.system.rods)} rods)")
        N, v = initial_state(self.system, lat)
        arrays = kernel_arrays(self.system, lat, N, v, list(self.outputs.probes))
        return CompiledProblem(self, lat, N, v, arrays)


@dataclass(frozen=True, eq=False)
class CompiledProblem:
    """A :class:`Problem` turned into what the kernels read: its ``lattice``, the element forces ``N`` (N) and
    velocities ``v`` (m/s) at t = 0, and ``arrays``, the kernel inputs in the layout documented in
    :mod:`rodimpact.direct._kernels` (end codes and parameters, junctions, special nodes, probes, per-step
    inputs ``step_inputs(first, n)``)."""

    problem: Problem
    lattice: Lattice
    N: np.ndarray
    v: np.ndarray
    arrays: dict

    def wave_arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """The reflection factor of every node and the elements the boundary step reads: the numpy reference of
        :func:`rodimpact.direct._kernels.wave_setup` (see :func:`wave_arrays`)."""
        return wave_arrays(self.lattice, self.arrays)


# ---------------------------------------------------------------------------------------------- time rule
def _time_step(system: Optional[System], dt: Any, elements: Any, resolution: Any) -> float:
    """dt from exactly one of dt / elements / resolution (or the default)."""
    given = [name for name, val in (("dt", dt), ("elements", elements), ("resolution", resolution)) if val is not None]
    if len(given) > 1:
        raise ValueError(f"{given[1]}: give only one of dt=, elements= or resolution= (got {', '.join(given)})")
    if dt is not None:
        return positive("dt", dt, "s")
    if system is None:
        raise ValueError("dt: required (s): the time step is the element travel time")
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
        if steps > MAX_STEPS:
            raise ValueError(f"steps: at most {MAX_STEPS:.0e} per run, got {steps}; use a larger dt")
        return int(steps)
    duration = positive("duration", duration, "s")
    x = duration / dt
    if not x <= MAX_STEPS:
        raise ValueError(f"duration: {duration:.4g} s needs {x:.3g} steps of dt = {dt:.4g} s; at most "
                         f"{MAX_STEPS:.0e} per run")
    n = int(round(x)) if abs(x - round(x)) <= 1e-9 * max(x, 1.0) else int(math.ceil(x))
    return max(n, 1)


# ---------------------------------------------------------------------------------------------- outputs
def _named_rod(probe: Any, i: int, system: System) -> Any:
    """``probe`` with a rod name replaced by the rod's index (other objects are checked by the Outputs)."""
    if not isinstance(probe, Probe) or not isinstance(probe.rod, str):
        return probe
    names = [r.name for r in system.rods]
    if probe.rod not in names:
        raise ValueError(f"probes[{i}].rod: no rod is named {probe.rod!r}; rod names: {names}")
    return Probe(probe.name, names.index(probe.rod), probe.position)


def _with_probes(outputs: Outputs, probes: tuple[Probe, ...]) -> Outputs:
    import dataclasses

    return dataclasses.replace(outputs, probes=probes)


# ---------------------------------------------------------------------------------------------- compilation
def _field(value: Any, x: np.ndarray, n: int, name: str) -> np.ndarray:
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


def initial_state(system: System, lat: Lattice) -> tuple[np.ndarray, np.ndarray]:
    """Element forces N (N, tension positive) and velocities v (m/s) at t = 0: each rod's velocity, replaced
    where an :class:`~rodimpact.InitialState` gives a field (evaluated at the element centres)."""
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
    return N, v


def _end_setup(cond: EndCondition, side: int, N: np.ndarray, v: np.ndarray, z: np.ndarray,
               dt: float) -> tuple[int, tuple[float, float], Optional[Callable[[int, int], np.ndarray]]]:
    """Kernel code, parameters and the per-step values (a function of first step and count; ``None``: the end
    has none, its row stays 0) of one outer end (side 0 = left, 1 = right)."""
    e = 0 if side == 0 else z.size - 1
    sign = -1.0 if side == 0 else 1.0        # outward direction in x
    values: Optional[Callable[[int, int], np.ndarray]] = None
    par = (0.0, 0.0)
    if isinstance(cond, FreeEnd):
        code = B.FREE
    elif isinstance(cond, FixedEnd):
        code = B.FIXED
    elif isinstance(cond, ForceEnd):
        code = B.FORCE
        values = lambda first, n: cond.force.step_values(n, dt, first)  # noqa: E731
    elif isinstance(cond, VelocityEnd):
        code = B.VELOCITY
        values = lambda first, n: sign * cond.velocity.step_values(n, dt, first)  # noqa: E731
    elif isinstance(cond, NonReflectingEnd):
        code = B.NONREFLECTING
        zx = z[e] if cond.impedance is None else cond.impedance
        # incoming characteristic of the continuation, in its initial state (= that of the end element):
        # left: N - Zx V = const, right: N + Zx V = const; written as N = invariant - Zx w
        par = (zx, N[e] + sign * zx * v[e])
    elif isinstance(cond, SpringEnd):
        code = B.SPRING
        par = (cond.stiffness, cond.damping)
    elif isinstance(cond, BitRockEnd):
        code = B.BITROCK
        par = (cond.loading_stiffness, cond.unloading_stiffness)
    elif isinstance(cond, LumpedEnd):
        code = B.LUMPED                  # its items go to lumped_arrays
    elif isinstance(cond, SoilToe):
        code = B.SOIL_TOE           # its law is a row of the soil arrays (soil_rows); p1: its start R_s
        par = (0.0, cond.resistance)
    else:  # pragma: no cover - System validates
        raise TypeError(f"unknown end condition {cond!r}")
    return code, par, values


def kernel_arrays(system: System, lat: Lattice, N: np.ndarray, v: np.ndarray, probes: list[Probe]) -> dict:
    """All arrays the kernels need, in the layout documented in :mod:`rodimpact.direct._kernels`, for the
    initial element state ``N``, ``v`` (the non-reflecting ends continue it) and the ``probes`` (rod indices)."""
    dt = lat.dt
    z = lat.impedance
    n_rods = lat.n_rods
    left, right = _end_setup(system.left, 0, N, v, z, dt), _end_setup(system.right, 1, N, v, z, dt)
    codes, pars, end_values = (left[0], right[0]), (left[1], right[1]), (left[2], right[2])
    junction_code = np.array([j.code for j in system.junctions], dtype=np.int64)
    gap = np.array([getattr(j, "gap", 0.0) for j in system.junctions], dtype=float)
    laws = [j.law.kernel() if isinstance(j, DeformableJoint) else np.zeros(0) for j in system.junctions]
    junction_par = np.zeros((len(system.junctions), HEADER_COLUMNS + max([w.size for w in laws] + [N_PARAMS])))
    for r, j in enumerate(system.junctions):
        if isinstance(j, SpringDashpot):
            junction_par[r, :3] = j.stiffness, j.damping, float(j.compression_only)
        elif isinstance(j, DeformableJoint):
            junction_par[r, 2:7] = (float(j.compression_only), j.law.code, j.initial_length, j.area,
                                    float(j.measure == "true"))
            junction_par[r, HEADER_COLUMNS:HEADER_COLUMNS + laws[r].size] = laws[r]
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
        elif isinstance(ld, Bearings):
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
    soil_nodes = _shaft_soil_nodes(system, lat, sp)
    sp_elem = np.array(sorted(sp), dtype=np.int64)
    sp_cap = np.array([sp[a][0] for a in sp_elem], dtype=float)
    soil_par, soil_state = soil_rows(system, z, sp_elem, soil_nodes)
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
        gap_tol=gap_tol, junction_par=junction_par, junction_q=np.zeros((len(system.junctions), STATE_COLUMNS)),
        u_end=np.zeros((n_rods, 2)), sp_elem=sp_elem, sp_cap=sp_cap,
        sp_loaded=np.array([a in node_loads for a in sp_elem], dtype=bool)
        | (soil_state[:sp_elem.size, S.R_S] != 0.0),       # a soil node that starts loaded may move by itself
        soil_par=soil_par, soil_state=soil_state,
        has_soil=bool(soil_nodes) or isinstance(system.left, SoilToe) or isinstance(system.right, SoilToe),
        pr_rod=np.array(pr_rod, dtype=np.int64), pr_local=np.array(pr_local, dtype=np.int64),
        pr_sp=np.array(pr_sp, dtype=np.int64), pr_disp=np.zeros(n_p), acc=np.zeros(B.ACC_SLOTS),
        # per-step histories: shapes only (rows); the steps are written through _History's buffers
        pr_N=np.zeros((n_p, 0)), pr_V=np.zeros((n_p, 0)), pr_u=np.zeros((n_p, 0)), junction_N=np.zeros((n_j, 0)),
        junction_contact=np.zeros((n_j, 0)), end_N=np.zeros((2, 0)), end_V=np.zeros((2, 0)),
        lumped=lumped_arrays(system))


def lumped_arrays(system: System) -> Optional[tuple]:
    """The lumped chains of ``system`` in the layout of :mod:`rodimpact.direct.lumped` (rows 0 and 1 the left and
    right end, 2 + r junction r; masses at their initial velocities, cushions uncompressed, every contact of a
    mass with a rod face touching), or None if it has none (the step loops are then compiled without the chain
    solver)."""
    places = [system.left, system.right, *system.junctions]
    chains = {row: p.items for row, p in enumerate(places) if isinstance(p, (LumpedEnd, LumpedJoint))}
    if not chains:
        return None
    width = max(len(items) for items in chains.values())
    n_items = np.zeros(len(places), dtype=np.int64)
    kind = np.zeros((len(places), width), dtype=np.int64)
    par = np.zeros((len(places), width, 2))
    state = np.zeros((len(places), width, 3))
    contact = np.zeros((len(places), 2, 2))
    contact[:, :, 0] = 1.0
    for row, items in chains.items():
        n_items[row] = len(items)
        for i, item in enumerate(items):
            if isinstance(item, PointMass):
                kind[row, i] = MASS
                par[row, i, 0] = item.mass
                state[row, i, 0] = item.velocity * (-1.0 if row == 1 else 1.0)    # along the chain: -x at right
            else:
                kind[row, i] = CUSHION
                par[row, i] = item.stiffness, item.unloading_stiffness
    return n_items, kind, par, state, contact


# ---------------------------------------------------------------------------------------------- soil
def _shaft_soil_nodes(system: System, lat: Lattice, sp: dict[int, list[float]]) -> dict[int, tuple[SmithSoil,
                                                                                                 float, float]]:
    """The interior nodes that carry shaft soil (element left of the node -> (law, R_s, u_p at the start)),
    added to the special nodes ``sp`` (without friction: a node with bearing friction and soil is refused)."""
    z = lat.impedance
    nodes: dict[int, tuple[SmithSoil, float, float]] = {}
    for i, ld in enumerate(system.loads):
        if not isinstance(ld, ShaftResistance):
            continue
        s, e = int(lat.rod_start[ld.rod]), int(lat.rod_start[ld.rod + 1])
        if e - s < 2:
            raise ValueError(f"loads[{i}]: rod {ld.rod} has a single element and no interior node; use a smaller dt")
        x_nodes = np.cumsum(lat.element_length[s:e])[:-1]
        length = float(lat.element_length[s:e].sum())
        r_u = ld.node_resistance(x_nodes, length)
        z_node = 0.5 * (z[s:e - 1] + z[s + 1:e])
        for name in ("resistance", "plastic_set"):
            if getattr(ld, name) and len(getattr(ld, name)) != r_u.size:
                raise ValueError(f"loads[{i}].{name}: needs one value per interior node of rod {ld.rod} "
                                 f"({r_u.size} at this dt), got {len(getattr(ld, name))}")
        total_case = float(np.sum(r_u))
        for m in np.flatnonzero(r_u > 0.0):
            a = s + int(m)
            if a in nodes or (a in sp and sp[a][0] > 0.0):
                raise ValueError(f"loads[{i}]: the node at {x_nodes[m]:.6g} m of rod {ld.rod} already carries "
                                 f"{'soil' if a in nodes else 'bearing friction'}; give one soil profile per rod "
                                 f"and no bearings where there is soil")
            # Case damping: the shaft's J_c Z shared in proportion to R_u (rodimpact.rods.soil)
            z_case = z_node[m] * r_u[m] / total_case
            law = SmithSoil(float(r_u[m]), ld.quake, ld.unloading_quake, ld.damping, ld.damping_kind, False,
                            float(z_case))
            r0 = float(ld.resistance[m]) if ld.resistance else 0.0
            if abs(r0) > law.ultimate:
                raise ValueError(f"loads[{i}].resistance[{m}]: must lie in [-R_u, R_u] = +-{law.ultimate:.6g} N "
                                 f"(that node's ultimate resistance), got {r0:.6g} N")
            nodes[a] = (law, r0, float(ld.plastic_set[m]) if ld.plastic_set else 0.0)
            sp.setdefault(a, [0.0])
    return nodes


def _soil_row(law: SmithSoil) -> list[float]:
    """The kernel parameters of one soil node (rodimpact.direct.soil: active, R_u, k, k_u, lo, J, c)."""
    smith = law.damping_kind == "smith"
    c = 0.0 if smith else law.damping * (law.ultimate if law.damping_kind == "smith-viscous" else law.impedance)
    return [1.0, law.ultimate, law.loading_stiffness, law.unloading_stiffness,
            0.0 if law.compression_only else -law.ultimate, law.damping if smith else 0.0, c]


def soil_rows(system: System, z: np.ndarray, sp_elem: np.ndarray,
              soil_nodes: dict[int, tuple[SmithSoil, float, float]]) -> tuple[np.ndarray, np.ndarray]:
    """``soil_par`` and ``soil_state`` (:mod:`rodimpact.direct.soil`): one row per special node, then the left
    and the right end; rows without soil stay zero (inactive)."""
    n_sp = sp_elem.size
    par = np.zeros((n_sp + 2, S.PAR_COLUMNS))
    state = np.zeros((n_sp + 2, S.STATE_COLUMNS))
    for row, a in enumerate(sp_elem.tolist()):
        if a in soil_nodes:
            law, r0, up = soil_nodes[a]
            par[row] = _soil_row(law)
            state[row, S.R_S], state[row, S.U_P] = r0, up
    for side, cond in enumerate((system.left, system.right)):
        if isinstance(cond, SoilToe):
            par[n_sp + side] = _soil_row(cond.law(float(z[0] if side == 0 else z[-1])))
            state[n_sp + side, S.R_S], state[n_sp + side, S.U_P] = cond.resistance, cond.plastic_set
    return par, state


def wave_arrays(lat: Lattice, arrays: dict) -> tuple[np.ndarray, np.ndarray]:
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
