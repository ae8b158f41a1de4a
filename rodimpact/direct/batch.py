"""Many strikers against one struck system: :func:`simulate_batch` runs them in one compiled call.

Design ``d`` is exactly the run ``simulate(system with rod 0 = striker d moving at velocities[d], ...)``: the
batched kernel (:mod:`rodimpact.direct._batch_kernels`) does the same arithmetic, so the contact force, the
energies and the junction events equal :func:`~rodimpact.simulate`'s bit for bit. It records only what
parameter studies need (the contact force at the impact junction, energies per rod at the start and the end,
the work of the ends and loads, the junction events), which keeps 10^5 designs in memory; the designs run in
parallel on the numba threads, or in batches as tasks of a ``concurrent.futures`` executor or a
``dask.distributed`` client.
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
import warnings
from dataclasses import dataclass, field
from typing import Any, Iterator, Optional

import numpy as np

from .._moved import moved
from .._version import __version__
from .._validate import caller_stacklevel, finite_array, finite_values, fits_in_memory, positive
from ..lattice.discretize import discretize_rod
from ..rods.conditions import NonReflectingEnd
from ..rods.material import STEEL
from ..rods.rod import Rod
from ..rods.soil import ShaftResistance, SoilToe
from ..rods.system import System
from . import _batch_kernels as BK
from . import boundary as B
from ._momentum import mean_velocities
from .result import BitRockOutcome, JunctionEvents, bit_rock_outcomes
from .recording import step_stride
from .problem import Problem, TimeGrid
from .simulate import passive_right, quiet_front

#: contact phases per junction and design kept by default (all are counted)
MAX_PHASES = 16


@dataclass(frozen=True, repr=False)
class BatchResult:
    """What :func:`simulate_batch` computed: design on the first axis, time on the last.

    Forces in N (tension positive, so impact forces are negative), energies and work in J, times in s.
    Junction quantities have one column per junction (0 = the impact face between the striker and rod 1);
    events are taken at every step whatever ``record_every``.
    """

    system: System                 # the struck system; rod 0 is the striker slot
    impedance: np.ndarray          # (designs, n_striker) striker element impedances, left to right, N s/m
    velocity: np.ndarray           # (designs,) striker impact velocity, m/s
    dt: float
    n_steps: int
    record_every: int
    time: np.ndarray               # (n_recorded,) step start times of contact_force, s
    contact_force: Optional[np.ndarray]   # (designs, n_recorded) junction 0 force, or None if not recorded
    energy_time: np.ndarray        # (2,) start and end of the run, s
    kinetic: np.ndarray            # (designs, n_rods, 2) kinetic energy per rod at energy_time
    strain: np.ndarray             # (designs, n_rods, 2) strain energy per rod at energy_time
    work_left: np.ndarray          # (designs,) work done on the rods by the left end, J (at the end)
    work_right: np.ndarray         # (designs,) ... by the right (far) end, e.g. a BitRockEnd
    work_loads: np.ndarray         # (designs,) ... by prescribed nodal loads
    work_friction: np.ndarray      # (designs,) ... by bearing friction (<= 0)
    work_joints: np.ndarray        # (designs,) ... by the joints between rods (<= 0: a passive joint absorbs)
    final_force: Optional[np.ndarray]     # (designs, n_striker) striker element forces at the end, or None
    final_velocity: Optional[np.ndarray]  # (designs, n_striker) striker element velocities at the end, or None
    rigid_body_velocity: np.ndarray  # (designs,) striker's mean (centre-of-mass) velocity at the end, m/s:
                                     # momentum / lattice mass, as SimulationResult.rigid_body_velocity
    peak_force: np.ndarray         # (designs, n_junctions) most compressive junction force (JunctionEvents.min_force)
    peak_force_step: np.ndarray    # (designs, n_junctions) its first step
    max_abs_force: np.ndarray      # (designs, n_junctions) largest |junction force|
    contact_steps: np.ndarray      # (designs, n_junctions) steps in contact
    n_phases: np.ndarray           # (designs, n_junctions) contact phases (first impact and re-contacts)
    phase_start: np.ndarray        # (designs, n_junctions, max_phases) first step of each phase, -1 = none
    phase_stop: np.ndarray         # (designs, n_junctions, max_phases) step after its last, n_steps if still on
    phase_max_abs_force: np.ndarray  # (designs, n_junctions, max_phases) largest |force| in each phase
    end_state: np.ndarray          # (designs, 2, 2) left/right end: (outward displacement, largest one) at the end, m
    diagnostics: dict[str, Any] = field(default_factory=dict)

    def __repr__(self) -> str:
        return (f"BatchResult({self.n_designs} designs, {self.impedance.shape[1]}-element striker, "
                f"{self.n_steps} steps of dt = {self.dt:.4g} s; peak contact force "
                f"{self.peak_force[:, 0].min():.6g} .. {self.peak_force[:, 0].max():.6g} N)")

    @property
    def n_designs(self) -> int:
        """Number of designs."""
        return int(self.velocity.size)

    @property
    def contact_duration(self) -> np.ndarray:
        """Total contact time per design and junction, s."""
        return self.contact_steps * self.dt

    @property
    def efficiency(self) -> np.ndarray:
        """Energy-transfer efficiency per design, (E_0(0) - E_0(end)) / E_0(0) for the striker (rod 0); NaN
        for a striker that starts without energy."""
        e0 = self.kinetic[:, 0] + self.strain[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(e0[:, 0] > 0.0, (e0[:, 0] - e0[:, -1]) / e0[:, 0], np.nan)

    def bit_rock(self, design: int) -> tuple[BitRockOutcome, ...]:
        """The :class:`~rodimpact.BitRockOutcome` of every outer end with a :class:`~rodimpact.BitRockEnd` for
        ``design`` (as :attr:`SimulationResult.bit_rock`): energy into the rock, drilling efficiency,
        penetration per blow."""
        d = self._design(design)
        initial = self.kinetic[d, :, 0] + self.strain[d, :, 0]
        return bit_rock_outcomes(self.system, self.end_state[d], self.work_left[d], self.work_right[d], initial)

    def junction_events(self, design: int) -> tuple[JunctionEvents, ...]:
        """The :class:`~rodimpact.JunctionEvents` of every junction of ``design`` (as
        :attr:`SimulationResult.junction_events`); refuses a design with more phases than were kept."""
        d = self._design(design)
        out = []
        for r in range(self.n_phases.shape[1]):
            n = int(self.n_phases[d, r])
            if n > self.phase_start.shape[2]:
                raise ValueError(f"design {d}, junction {r}: {n} contact phases, only {self.phase_start.shape[2]} "
                                 f"kept; run again with outputs=BatchOutputs(max_phases={n})")
            out.append(JunctionEvents(
                start=self.phase_start[d, r, :n].copy(), stop=self.phase_stop[d, r, :n].copy(),
                max_abs_force=self.phase_max_abs_force[d, r, :n].copy(), min_force=float(self.peak_force[d, r]),
                min_force_step=int(self.peak_force_step[d, r]), max_abs_force_run=float(self.max_abs_force[d, r])))
        return tuple(out)

    def contact_times(self, design: int, junction: int = 0) -> np.ndarray:
        """Start times of the contact phases of ``design`` at ``junction`` (first impact and re-contacts), s."""
        return self.junction_events(design)[junction].start * self.dt

    def separation_times(self, design: int, junction: int = 0) -> np.ndarray:
        """Times at which the rods at ``junction`` separate in ``design``, s."""
        ev = self.junction_events(design)[junction]
        return ev.stop[ev.stop < self.n_steps] * self.dt

    def _design(self, design: int) -> int:
        if isinstance(design, bool) or not isinstance(design, (int, np.integer)) \
                or not -self.n_designs <= design < self.n_designs:
            raise ValueError(f"design: must be an index 0..{self.n_designs - 1}, got {design!r}")
        return int(design) % self.n_designs

    def to_xarray(self):
        """The results as an :class:`xarray.Dataset` (dimensions design, junction, rod, time, energy_time,
        phase)."""
        import xarray as xr

        dj, dp = ("design", "junction"), ("design", "junction", "phase")
        data: dict[str, Any] = {
            "impedance": (("design", "element"), self.impedance, {"units": "N s/m"}),
            "velocity": (("design",), self.velocity, {"units": "m/s"}),
            "kinetic_energy": (("design", "rod", "energy_time"), self.kinetic, {"units": "J"}),
            "strain_energy": (("design", "rod", "energy_time"), self.strain, {"units": "J"}),
            "efficiency": (("design",), self.efficiency, {"units": "1"}),
            "striker_final_velocity": (("design",), self.rigid_body_velocity, {"units": "m/s"}),
            "peak_force": (dj, self.peak_force, {"units": "N"}),
            "max_abs_force": (dj, self.max_abs_force, {"units": "N"}),
            "contact_duration": (dj, self.contact_duration, {"units": "s"}),
            "n_phases": (dj, self.n_phases, {}),
            "phase_start": (dp, self.phase_start, {"units": "step"}),
            "phase_stop": (dp, self.phase_stop, {"units": "step"}),
            "phase_max_abs_force": (dp, self.phase_max_abs_force, {"units": "N"}),
        }
        for side in ("left", "right", "loads", "friction"):
            data[f"work_{side}"] = (("design",), getattr(self, f"work_{side}"), {"units": "J"})
        coords: dict[str, Any] = {"energy_time": ("energy_time", self.energy_time, {"units": "s"})}
        if self.contact_force is not None:
            data["contact_force"] = (("design", "time"), self.contact_force, {"units": "N"})
            coords["time"] = ("time", self.time, {"units": "s"})
        attrs = {"dt": self.dt, "n_steps": self.n_steps, "record_every": self.record_every,
                 **{k: str(v) for k, v in self.diagnostics.items()}}
        return xr.Dataset(data, coords=coords, attrs=attrs)


@dataclass(frozen=True)
class BatchOutputs:
    """What :func:`simulate_batch` records besides the peak forces, contact phases, energies and work (which are
    always kept).

    record_every:
        Keep every n-th step of the contact force (``time = [0, n dt, ...]``); events use every step.
    contact_force:
        Record the contact-force history at junction 0 (False: only events, energies and work).
    final_state:
        Keep the striker's element forces and velocities at the end (``final_force``, ``final_velocity``;
        False: None, and only its :attr:`~BatchResult.rigid_body_velocity` is kept). False makes the result
        smaller and, with an ``executor``, what the workers send back: 2 x designs x striker elements floats less.
    max_phases:
        Contact phases kept per design and junction (all are counted in ``n_phases``).
    """

    record_every: int = 1
    contact_force: bool = True
    final_state: bool = True
    max_phases: int = MAX_PHASES

    def __post_init__(self) -> None:
        object.__setattr__(self, "record_every", step_stride("record_every", self.record_every))
        for name in ("contact_force", "final_state"):
            value = getattr(self, name)
            if not isinstance(value, (bool, np.bool_)):
                raise TypeError(f"{name}: must be True or False, got {value!r}")
            object.__setattr__(self, name, bool(value))
        m = self.max_phases
        if isinstance(m, bool) or not isinstance(m, (int, np.integer)) or m < 1:
            raise ValueError(f"max_phases: must be an integer >= 1, got {m!r}")
        object.__setattr__(self, "max_phases", int(m))


_TIME = ("{key}: give the time as one TimeGrid: ri.simulate_batch(system, strikers, velocities, "
         "ri.TimeGrid.of(duration=..., dt=...)) (or ri.TimeGrid(dt, steps))")
#: the keywords simulate_batch() took before its parameters moved into the objects it receives, and where each went
MOVED = {
    **{key: _TIME.format(key=key) for key in ("duration", "dt", "steps")},
    **{key: (f"{key}: give the recording options as one BatchOutputs: ri.simulate_batch(system, strikers, "
             f"velocities, time, outputs=ri.BatchOutputs({key}=...))")
       for key in ("record_every", "contact_force", "final_state", "max_phases")},
}


@moved(MOVED, positional=("system", "strikers", "velocities", "duration", "dt"))
def simulate_batch(system: System, strikers: Any, velocities: Any, time: TimeGrid, *,
                   wave_speed: Optional[float] = None, outputs: Optional[BatchOutputs] = None,
                   threads: Optional[int] = None, executor: Any = None,
                   chunk_size: Optional[int] = None) -> BatchResult:
    """Simulate many strikers against one struck system (thesis Sec. 3.1), one compiled call for all.

    Design ``d`` is the run ``simulate(dataclasses.replace(system, rods=(striker_d, *system.rods[1:]),
    velocities=(velocities[d], *system.velocities[1:])), steps=time.steps, dt=time.dt)``, and its
    contact force, energies, work and junction events equal that run's bit for bit.

    Parameters
    ----------
    system:
        The struck system: a :class:`~rodimpact.System` whose rod 0 is the striker slot. Rod 0's profile and
        velocity are replaced by each design; everything else (the struck rods, junctions, end conditions,
        loads and initial states of rods 1, 2, ...) is shared. The slot must carry no loads or initial state.
    strikers:
        Either a 2-d array of element impedances, designs x elements (N s/m, listed left to right: from the
        striker's free end to its impact face), row d meaning ``Rod.from_impedance(row, dt, wave_speed)``;
        or a sequence of :class:`~rodimpact.Rod` that all have the same number of elements at ``dt``.
    velocities:
        Impact velocity of each design's striker (m/s, positive to the right), or one for all.
    time:
        The :class:`~rodimpact.TimeGrid`: time step = element travel time (s) and number of steps, e.g.
        ``TimeGrid(1e-6, 400)`` or ``TimeGrid.of(duration=400e-6, dt=1e-6)`` (the rounding of
        :func:`~rodimpact.simulate`).
    wave_speed:
        Wave speed of impedance rows (default that of :meth:`Rod.from_impedance`, steel): sets only the
        element lengths, hence the re-contact tolerance of a gap.
    outputs:
        The recording options, a :class:`BatchOutputs` (``record_every``, ``contact_force``, ``final_state``,
        ``max_phases``); default ``BatchOutputs()``: every step of the contact force, the striker's final
        state, 16 contact phases kept per design and junction.
    threads:
        numba threads for an in-process run (default ``numba.get_num_threads()``); designs run in parallel.
    executor:
        A ``concurrent.futures.Executor`` or a ``dask.distributed.Client``: batches of ``chunk_size`` designs
        are sent as tasks (each runs its designs in one thread), results are gathered in order. Default:
        in-process. Only numpy arrays travel to the workers (the system is turned into kernel arrays first).
    chunk_size:
        Designs per task with an ``executor`` (default: about 32 tasks, between 64 and 4096 designs each).

    The keywords this function took before (``duration``, ``dt``, ``steps``; ``record_every``,
    ``contact_force``, ``final_state``, ``max_phases``) raise a ``TypeError`` that says where each went
    (:data:`MOVED`).

    Returns
    -------
    BatchResult
    """
    if not isinstance(system, System):
        raise TypeError(f"system: must be a System whose rod 0 is the striker slot, got {type(system).__name__}")
    problem = slot_problem(system)
    if problem:
        raise ValueError(problem)
    if not isinstance(time, TimeGrid):
        raise TypeError(f"time: must be a TimeGrid, e.g. ri.TimeGrid(dt, steps) or ri.TimeGrid.of(duration=..., "
                        f"dt=...), got {type(time).__name__}")
    if outputs is None:
        outputs = BatchOutputs()
    elif not isinstance(outputs, BatchOutputs):
        raise TypeError(f"outputs: must be a BatchOutputs(record_every=..., contact_force=..., final_state=..., "
                        f"max_phases=...), got {type(outputs).__name__}")
    dt = time.dt
    zs, tail = _striker_impedances(strikers, dt, wave_speed)
    vel = _velocities(velocities, zs.shape[0])
    return run_designs(system, zs, tail, vel, dt, time.steps, outputs.record_every, outputs.contact_force,
                       outputs.final_state, outputs.max_phases, _threads(threads), executor, chunk_size)


def run_designs(system: System, zs: np.ndarray, tail: np.ndarray, vel: np.ndarray, dt: float, n_steps: int,
                stride: int, contact_force: bool, final_state: bool, max_phases: int, threads: int,
                executor: Any, chunk_size: Optional[int]) -> BatchResult:
    """:func:`simulate_batch` on checked input: striker impedances ``zs`` (designs x elements), the length of
    each striker's last element ``tail`` (m) and the velocities ``vel``."""
    n_d, n_s = zs.shape
    n_rec = -(-n_steps // stride) if contact_force else 0
    n_j = system.n_rods - 1
    # (the kernel fills the striker's final fields even when final_state is False)
    per_design = 8.0 * (n_rec + 3 * n_s + 5 * system.n_rods + (3 * max_phases + 6) * n_j)
    # each running design also keeps its per-step junction and end values (events are taken from them)
    per_thread = 8.0 * (2 * n_j + 4) * n_steps
    fits_in_memory("strikers", per_design * n_d + per_thread * max(threads, 1), f"the results of {n_d} designs",
                   "record the contact force with a larger BatchOutputs(record_every=...) (or contact_force=False), "
                   "or split the batch")
    wall0 = _time.perf_counter()
    plan, end_par, gap_tol = _plan(system, zs, vel, tail, dt, n_steps, stride, n_rec, max_phases)
    if executor is None:
        out = _run_chunk(plan, zs, vel, end_par, gap_tol, final_state, threads)
    else:
        out = _run_on(executor, plan, zs, vel, end_par, gap_tol, final_state, chunk_size)
    hist, kin, pot, work, fin_n, fin_v, rbv, low, low_step, peak, on, n_ph, ph_start, ph_stop, ph_peak, ends = out
    return BatchResult(
        system=system, impedance=zs, velocity=vel, dt=dt, n_steps=n_steps, record_every=stride,
        time=np.arange(0, n_steps, stride) * dt if contact_force else np.zeros(0),
        contact_force=hist if contact_force else None, energy_time=np.array([0.0, n_steps * dt]),
        kinetic=kin, strain=pot, work_left=work[:, 0], work_right=work[:, 1], work_loads=work[:, 2],
        work_friction=work[:, 3], work_joints=work[:, 4], final_force=fin_n if final_state else None,
        final_velocity=fin_v if final_state else None, rigid_body_velocity=rbv, peak_force=low,
        peak_force_step=low_step, max_abs_force=peak, contact_steps=on, n_phases=n_ph, phase_start=ph_start,
        phase_stop=ph_stop, phase_max_abs_force=ph_peak, end_state=ends,
        diagnostics={"version": __version__, "wall_time_s": _time.perf_counter() - wall0, "designs": n_d,
                     "steps": n_steps, "elements": plan.z0.size,
                     "executor": "in-process" if executor is None else type(executor).__name__})


# ---------------------------------------------------------------------------------------------- helpers
def slot_problem(system: System) -> str:
    """Why rod 0 of ``system`` cannot be the striker slot of a batch ("" if it can)."""
    if system.n_rods < 2:
        return "system: needs the striker slot (rod 0) and at least one struck rod, got a single rod"
    if any(ld.rod == 0 for ld in system.loads):
        return ("system.loads: rod 0 is the striker slot, which is replaced per design; loads on it are not "
                "supported in a batch (use simulate)")
    if any(isinstance(ld, ShaftResistance) for ld in system.loads) or any(
            isinstance(e, SoilToe) for e in (system.left, system.right)):
        return ("system: simulate_batch does not support Smith soil (ShaftResistance, SoilToe) yet; run the "
                "designs one by one with simulate")
    if system.initial[0] is not None:
        return ("system.initial[0]: the striker slot starts force-free with velocities[d]; give None for rod 0 "
                "(use simulate for a non-uniform initial state)")
    return ""


@dataclass(frozen=True)
class _Plan:
    """Everything the batched kernel shares between designs (numpy arrays only, so tasks pickle cheaply)."""

    n_steps: int
    stride: int
    n_rec: int
    max_phases: int
    dt: float
    quiet: int
    z0: np.ndarray
    N0: np.ndarray
    v0: np.ndarray
    rod_start: np.ndarray
    touch: np.ndarray
    end_code: np.ndarray
    end_value: np.ndarray
    junction_code: np.ndarray
    junction_par: np.ndarray
    law_q: np.ndarray | None        # the joint states to start from; None without law joints (boundary.law_state)
    gap0: np.ndarray
    sp_elem: np.ndarray
    sp_cap: np.ndarray
    sp_force: np.ndarray


def _striker_impedances(strikers: Any, dt: float, wave_speed: Optional[float]) -> tuple[np.ndarray, np.ndarray]:
    """Striker impedances (designs x elements) and the length of each striker's last element (m)."""
    if isinstance(strikers, Rod):
        strikers = [strikers]
    if isinstance(strikers, (list, tuple)) and strikers and all(isinstance(r, Rod) for r in strikers):
        discs = [discretize_rod(rod, dt, 0) for rod in strikers]
        counts = {d.n_elements for d in discs}
        if len(counts) > 1:
            raise ValueError(f"strikers: every striker needs the same number of elements at dt = {dt:.6g} s; got "
                             f"{sorted(counts)}")
        bad = [i for i, d in enumerate(discs) if not d.exact and abs(d.time_scale - 1.0) > 0.01]
        if bad:
            warnings.warn(f"strikers {bad[:5]}{'...' if len(bad) > 5 else ''}: travel time represented with more "
                          f"than 1 % error; use a smaller dt", stacklevel=caller_stacklevel())
        return np.array([d.impedance for d in discs]), np.array([d.length[-1] for d in discs])
    c = STEEL.wave_speed if wave_speed is None else positive("wave_speed", wave_speed, "m/s")
    if isinstance(strikers, (list, tuple)) and any(isinstance(r, Rod) for r in strikers):
        raise TypeError("strikers: give either Rods only or an array of impedances (designs x elements)")
    zs = finite_array("strikers", strikers, ndim=2)
    if zs.shape[0] < 1 or zs.shape[1] < 1:
        raise ValueError(f"strikers: need at least one design and one element, got shape {zs.shape}")
    if (zs <= 0).any():
        d, j = np.argwhere(zs <= 0)[0]
        raise ValueError(f"strikers: impedances must be > 0 N s/m, design {d} element {j} is {float(zs[d, j])!r}")
    return np.ascontiguousarray(zs), np.full(zs.shape[0], c * dt)


def _velocities(velocities: Any, n_d: int) -> np.ndarray:
    vel = finite_values("velocities", velocities, "impact velocities (m/s)", max_ndim=1).ravel()
    if vel.size == 1:
        return np.full(n_d, vel[0])
    if vel.size != n_d:
        raise ValueError(f"velocities: need one impact velocity per design ({n_d}) or one for all, got {vel.size}")
    return vel


def _threads(threads: Optional[int]) -> int:
    import numba

    if threads is None:
        return numba.get_num_threads()
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise ValueError(f"threads: must be an integer >= 1, got {threads!r}")
    return min(int(threads), numba.config.NUMBA_NUM_THREADS)


def _quiet_from(n_s: int, N: np.ndarray, v: np.ndarray, arrays: dict, end_value: np.ndarray,
                sp_force: np.ndarray) -> int:
    """:func:`~rodimpact.direct.simulate.quiet_front` of the struck part (from element ``n_s``) with the whole
    run's end values and loads known: a right end with prescribed values that are all zero is passive too,
    and only loads that act at some step count."""
    passive = passive_right(arrays) or (int(arrays["end_code"][1]) in (B.FORCE, B.VELOCITY)
                                        and not end_value[1].any())
    forced = arrays["sp_elem"][sp_force.any(axis=1)] if sp_force.size else arrays["sp_elem"][:0]
    return quiet_front(N, v, n_s, passive, forced)


def _plan(system: System, zs: np.ndarray, vel: np.ndarray, tail: np.ndarray, dt: float, n_steps: int, stride: int,
          n_rec: int, max_phases: int) -> tuple[_Plan, np.ndarray, np.ndarray]:
    """The shared arrays (from the system with design 0 in the slot) and the per-design end parameters and
    re-contact tolerances."""
    template = dataclasses.replace(system, rods=(Rod.from_impedance(zs[0], dt), *system.rods[1:]),
                                   velocities=(float(vel[0]), *system.velocities[1:]))
    compiled = Problem(template, TimeGrid(dt, n_steps)).compile()
    lattice, arrays = compiled.lattice, compiled.arrays
    state = {"N": compiled.N, "v": compiled.v}
    _, touch = compiled.wave_arrays()
    n_s = zs.shape[1]
    end_value, sp_force = arrays["step_inputs"](0, n_steps)
    end_par = np.repeat(arrays["end_par"][None], zs.shape[0], axis=0)
    if isinstance(system.left, NonReflectingEnd):
        # the continuation starts in the state of the striker's first element (see problem._end_setup)
        zx = zs[:, 0] if system.left.impedance is None else np.full(zs.shape[0], system.left.impedance)
        end_par[:, 0, 0] = zx
        end_par[:, 0, 1] = 0.0 + -1.0 * zx * vel
    gap_tol = np.repeat(arrays["gap_tol"][None], zs.shape[0], axis=0)
    gap_tol[:, 0] = 1e-9 * np.minimum(tail, lattice.element_length[n_s])
    plan = _Plan(n_steps=n_steps, stride=stride, n_rec=n_rec, max_phases=max_phases, dt=dt,
                 quiet=_quiet_from(n_s, state["N"], state["v"], arrays, end_value, sp_force), z0=lattice.impedance, N0=state["N"], v0=state["v"],
                 rod_start=arrays["rod_start"], touch=touch, end_code=arrays["end_code"], end_value=end_value,
                 junction_code=arrays["junction_code"],
                 junction_par=arrays["junction_par"], law_q=B.law_state(arrays["junction_code"], arrays["junction_q"]),
                 gap0=arrays["gap"], sp_elem=arrays["sp_elem"],
                 sp_cap=arrays["sp_cap"], sp_force=sp_force)
    return plan, end_par, gap_tol


def _run_chunk(plan: _Plan, zs: np.ndarray, vel: np.ndarray, end_par: np.ndarray, gap_tol: np.ndarray,
               final_state: bool, threads: int = 1) -> tuple[np.ndarray, ...]:
    """Run the designs ``zs`` (rows) with ``threads`` numba threads; returns the kernel's output arrays with
    the striker's rigid-body velocity after its final velocities (which, with ``final_state`` False, are left
    out with the final forces: zero columns)."""
    n_d, n_s = zs.shape
    n_rods = plan.rod_start.size - 1
    n_j, m = n_rods - 1, plan.max_phases
    out = (np.zeros((n_d, plan.n_rec)), np.zeros((n_d, n_rods, 2)), np.zeros((n_d, n_rods, 2)), np.zeros((n_d, 5)),
           np.zeros((n_d, n_s)), np.zeros((n_d, n_s)), np.zeros((n_d, n_j)), np.zeros((n_d, n_j), dtype=np.int64),
           np.zeros((n_d, n_j)), np.zeros((n_d, n_j), dtype=np.int64), np.zeros((n_d, n_j), dtype=np.int64),
           np.full((n_d, n_j, m), -1, dtype=np.int64), np.full((n_d, n_j, m), -1, dtype=np.int64),
           np.zeros((n_d, n_j, m)), np.zeros((n_d, 2, 2)))
    args = (plan.n_steps, plan.stride, plan.quiet, zs, vel, plan.z0, plan.N0, plan.v0, plan.rod_start, plan.touch,
            plan.end_code, end_par, plan.end_value, plan.junction_code, (plan.junction_par, plan.law_q), plan.gap0, gap_tol, plan.sp_elem,
            plan.sp_cap, plan.sp_force, plan.dt, out)
    if threads <= 1 or n_d == 1:
        BK.run_batch_serial(*args)
    else:
        import numba

        before = numba.get_num_threads()
        numba.set_num_threads(threads)
        try:
            BK.run_batch_parallel(*args)
        finally:
            numba.set_num_threads(before)
    # momentum / lattice mass by the function of SimulationResult.rigid_body_velocity (so equal bit for bit)
    rbv = mean_velocities(zs, out[5], np.array([0, n_s]))[:, 0]
    fin = out[4:6] if final_state else (np.zeros((n_d, 0)), np.zeros((n_d, 0)))   # no views: free the fields
    return (*out[:4], *fin, rbv, *out[6:])


def default_chunk_size(n_designs: int) -> int:
    """Designs per task with an executor: about 32 tasks, between 64 and 4096 designs each."""
    return int(min(4096, max(64, math.ceil(n_designs / 32))))


def gather(executor: Any, fn: Any, arguments: list[tuple]) -> Iterator[Any]:
    """Submit ``fn(*args)`` for every entry of ``arguments`` to ``executor`` (``submit``/``result`` of
    concurrent.futures or dask.distributed) and yield the results in order; pending tasks are cancelled when
    one fails or the caller stops early. Finished tasks are not cancelled: dask names a task after its
    arguments, so cancelling a finished one could cancel the same task resubmitted by the next call."""
    if not callable(getattr(executor, "submit", None)):
        raise TypeError(f"executor: must be a concurrent.futures.Executor or a dask.distributed.Client, got "
                        f"{type(executor).__name__}")
    futures = [executor.submit(fn, *args) for args in arguments]
    complete = False
    try:
        for fut in futures:
            yield fut.result()
        complete = True
    finally:
        if not complete:
            for fut in futures:
                fut.cancel()


def _run_on(executor: Any, plan: _Plan, zs: np.ndarray, vel: np.ndarray, end_par: np.ndarray,
            gap_tol: np.ndarray, final_state: bool, chunk_size: Optional[int]) -> tuple[np.ndarray, ...]:
    """Send batches of designs to ``executor`` and join their outputs in design order."""
    n_d = zs.shape[0]
    size = default_chunk_size(n_d) if chunk_size is None else chunk_size
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 1:
        raise ValueError(f"chunk_size: must be an integer >= 1 (designs per task), got {chunk_size!r}")
    bounds = list(range(0, n_d, int(size))) + [n_d]
    parts = list(gather(executor, _run_chunk, [(plan, zs[a:b], vel[a:b], end_par[a:b], gap_tol[a:b],
                                                final_state) for a, b in zip(bounds[:-1], bounds[1:])]))
    return tuple(np.concatenate(arrays, axis=0) for arrays in zip(*parts))
