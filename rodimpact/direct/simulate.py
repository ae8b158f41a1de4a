"""The direct problem: :func:`simulate` runs the wave propagation method on a system of rods."""

from __future__ import annotations

import time as _time
from typing import Any, Literal, Optional, Sequence

import numpy as np

from .._moved import moved
from .._version import __version__
from ..lattice import tolerance
from ..lattice.lattice import Lattice
from ..rods.rod import Rod
from ..rods.system import System
from . import _kernels as K
from . import boundary as B
from . import guards
from .problem import CompiledProblem, Problem, wave_arrays
from .recording import Recorder, Outputs
from .soil import soil_arrays
from .soil_result import soil_outcome
from .result import Probe, ProbeHistory, SimulationResult, bit_rock_outcomes, joint_outcomes, \
    lumped_outcomes

Backend = Literal["numba", "numpy"]
_MAX_CHUNK = 65536   # steps per compiled call at most: bounds the per-step input and output arrays


_SYSTEM = ("give the {what} in the System: ri.System(rods, velocities, {key}=...), then "
           "ri.simulate(system, duration=...)")
_TIME = ("give the time-step rule to the Problem: ri.simulate(ri.Problem.of(rods, velocities, duration=..., "
         "{key}=...)) (or ri.TimeGrid.of(system, duration=..., {key}=...))")
_OUTPUT = ("give the outputs as one Outputs: ri.simulate(rods, velocities, duration=..., "
           "outputs=ri.Outputs({key}=...))")
#: the keywords simulate() took before its parameters moved into the objects it receives, and where each went
MOVED = {
    "rods": "rods: the rods (or a System or a Problem) are the first argument: ri.simulate(rods, velocities, "
            "duration=...)",
    **{key: f"{key}: " + _SYSTEM.format(what=what, key=key) for key, what in (
        ("left", "ends"), ("right", "ends"), ("junctions", "junctions"), ("loads", "loads"),
        ("initial", "initial state"))},
    **{key: f"{key}: " + _TIME.format(key=key) for key in ("elements", "resolution")},
    **{key: f"{key}: " + _OUTPUT.format(key=key) for key in ("probes", "snapshot_times", "snapshot_every",
                                                             "energy_every", "record_every")},
    "allow_discretization_error": "allow_discretization_error: it is part of the Problem now: ri.simulate("
                                  "ri.Problem.of(rods, velocities, duration=..., allow_discretization_error=True))",
}


@moved(MOVED, positional=("problem", "velocities", "duration", "dt"))
def simulate(problem: Problem | System | Sequence[Rod] | Rod, velocities: Optional[Sequence[float]] = None, *,
             duration: Optional[float] = None, steps: Optional[int] = None, dt: Optional[float] = None,
             outputs: Optional[Outputs] = None, backend: Backend = "numba", progress: bool | None = None,
             max_element_updates: Optional[float] = None) -> SimulationResult:
    """Simulate the longitudinal impact of rods with the exact wave propagation method (thesis Sec. 3.1).

    ``ri.simulate([striker, bar], [5.0, 0.0], duration=400e-6)`` runs two free rods;
    ``ri.simulate(ri.System([striker, bar], [5.0, 0.0], right="nonreflecting"), duration=400e-6)`` a system
    with its ends, junctions, loads and initial state; ``ri.simulate(problem)`` a whole
    :class:`~rodimpact.Problem`.

    Parameters
    ----------
    problem:
        A :class:`~rodimpact.direct.problem.Problem` (system, time grid, outputs and
        ``allow_discretization_error``: give only the run options ``backend``, ``progress``,
        ``max_element_updates`` then); or a :class:`~rodimpact.rods.system.System` (rods, velocities, ends,
        junctions, loads, initial state), with the time (``duration`` or ``steps``, ``dt``) and ``outputs``; or
        rods listed left to right (one :class:`~rodimpact.Rod` or a sequence) with their ``velocities``: two
        free rods joined by a unilateral :class:`~rodimpact.Contact`. Ends, junctions, loads and initial state
        go into the ``System``; the other time-step rules (``elements``, ``resolution``) and
        ``allow_discretization_error`` into :meth:`Problem.of <rodimpact.direct.problem.Problem.of>`.
    velocities:
        With rods: the initial velocity of each rod, m/s (positive to the right).
    duration, steps:
        Simulated time, s, or the number of steps (exactly one).
    dt:
        Time step = travel time of every element, s. Default: the ``dt`` of impedance-level rods, else one
        that gives each segment >= 4 and the longest rod >= 200 elements (:meth:`TimeGrid.of
        <rodimpact.direct.problem.TimeGrid.of>` holds the rule).
    outputs:
        What to record besides the contact force and end values: an :class:`~rodimpact.Outputs` (probe
        histories; field snapshots at the steps nearest to given times and/or every k steps; the energy
        sampling stride, default about 256 samples per run; keep every ``record_every``-th step of the
        histories, default 1). Contact and separation times, contact durations and the peak contact force are
        taken at every step whatever the stride (``result.junction_events``).
    backend:
        "numba" (compiled, default) or "numpy" (readable reference path; slow).
    progress:
        Report progress on stderr (default: for runs of more than 10^9 element updates; a bar on a terminal,
        else a line every 10 %).
    max_element_updates:
        Refuse runs of more elements x steps than this (default 1e11, see
        :data:`rodimpact.direct.guards.DEFAULT_MAX_ELEMENT_UPDATES`; ``math.inf``: no limit). The memory the
        histories and snapshots need is checked against the available memory before the run as well.

    A lattice that represents a rod's travel time or mass with an error above 1 % (or smears a segment shorter
    than one element) is refused with a ``ValueError`` that names the rod, the error and a dt that would satisfy
    it, unless the problem allows it (``Problem.of(..., allow_discretization_error=True)``: a warning then).
    The keywords this function took before the parameters moved into these objects (``left``, ``right``,
    ``junctions``, ``loads``, ``initial``, ``elements``, ``resolution``, ``probes``, ``snapshot_times``,
    ``snapshot_every``, ``energy_every``, ``record_every``, ``allow_discretization_error``) raise a ``TypeError``
    that says where each went (:data:`MOVED`).

    Physical quantities may be numbers in SI units, unit strings (``"2 ms"``) or pint Quantities.
    """
    if isinstance(problem, Problem):
        given = [k for k, v in (("velocities", velocities), ("duration", duration), ("steps", steps), ("dt", dt),
                                ("outputs", outputs)) if v is not None]
        if given:
            raise ValueError(f"{given[0]}: a Problem already holds its system, time grid and outputs; give either "
                             f"the Problem or the rods with {', '.join(f'{k}=' for k in given)}")
    else:       # a System holds its velocities, ends, junctions, loads and initial state; Problem.of checks
        problem = Problem.of(problem, velocities, duration=duration, steps=steps, dt=dt, outputs=outputs)
    if backend not in ("numba", "numpy"):
        raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
    return _solve(problem, backend, progress, max_element_updates)


def _solve(problem: Problem, backend: Backend, progress: Optional[bool],
           max_element_updates: Optional[float]) -> SimulationResult:
    """Run ``problem``: the discretisation check, the compiled or numpy loop, the result with its diagnostics."""
    allowed = tolerance.check(problem.system, problem.lattice, problem.allow_discretization_error)
    guards.check_element_updates(problem.lattice.n_elements, problem.time.steps, max_element_updates)
    wall0 = _time.perf_counter()
    return _run(problem.compile(), backend, progress, wall0, allowed)


def solve_compiled(compiled: CompiledProblem, backend: Backend = "numba",
                   progress: Optional[bool] = None) -> SimulationResult:
    """Run a compiled problem (:meth:`Problem.compile <rodimpact.direct.problem.Problem.compile>`, whose state
    arrays the loop advances in place: each run needs its own) as :func:`simulate` runs its problem. The pile
    blows of a bearing graph (:func:`rodimpact.pile.blow.drive_blow_batch`) compile the problem of each soil on
    one lattice and run it with this."""
    problem = compiled.problem
    allowed = tolerance.check(problem.system, compiled.lattice, problem.allow_discretization_error)
    return _run(compiled, backend, progress, _time.perf_counter(), allowed)


def _run(compiled: CompiledProblem, backend: Backend, progress: Optional[bool], wall0: float,
         allowed: list[str]) -> SimulationResult:
    """The loop of ``backend`` on ``compiled`` and the result (wall time from ``wall0``, the discretisation
    warnings ``allowed``)."""
    problem = compiled.problem
    system, record = problem.system, problem.outputs
    dt, n_steps = problem.time.dt, problem.time.steps
    lattice = compiled.lattice
    arrays = compiled.arrays
    state = {"N": compiled.N, "v": compiled.v}
    bar = guards.progress(progress, n_steps, lattice.n_elements)
    capacity = max(1, min(n_steps, _MAX_CHUNK, int(1e8 // lattice.n_elements) if bar is not None else _MAX_CHUNK))
    # the compiled loop writes the steps straight into the histories when it keeps every step (no step columns)
    columns = 0 if backend == "numba" and record.record_every == 1 else capacity
    recorder = Recorder(record, lattice, arrays, state["N"].copy(), n_steps, columns)
    soil_start = arrays["soil_state"].copy()
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
        probes=_probe_histories(system, lattice, list(record.probes), hist), snapshots=recorder.snapshots(lattice),
        energy=energy, final_force=N.copy(), final_velocity=v.copy(), diagnostics=diagnostics,
        record_every=recorder.stride, n_steps=n_steps, junction_events=recorder.junction_events(),
        bit_rock=bit_rock_outcomes(system, arrays["end_state"], energy.work_left[-1], energy.work_right[-1],
                                   energy.kinetic[:, 0] + energy.strain[:, 0]),
        joints=joint_outcomes(system, arrays["gap"], arrays["junction_q"]),
        lumped=lumped_outcomes(system, arrays["lumped"]), soil=soil_outcome(system, lattice, arrays, soil_start))


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
        reflection, touch = wave_arrays(lat, arrays)
        f, g = K.waves(N, v, z)
        quiet = quiet_front(N, v, 0, passive_right(arrays), arrays["sp_elem"][arrays["sp_loaded"]])
    wave_state = (N, v, f, g)
    lattice = (z, reflection, touch, arrays["rod_start"], quiet)
    junctions = (*(arrays[key] for key in ("junction_code", "junction_state", "gap", "gap_tol", "u_end",
                                          "junction_par")), B.law_state(arrays["junction_code"], arrays["junction_q"]),
                 arrays["lumped"])
    n_sp = arrays["sp_elem"].size
    soil = soil_arrays(arrays)   # None without soil: no soil code compiled
    scratch = (np.zeros(n_sp), np.zeros(n_sp))      # resolved force and velocity of each special node
    chunk = recorder.chunk
    probes = (arrays["pr_rod"], arrays["pr_local"], arrays["pr_sp"], *chunk[4:], arrays["pr_disp"])
    k = 0
    while k < n_steps:
        n = min(capacity, n_steps - k)
        end_value, sp_force = arrays["step_inputs"](k, n)
        ends = (arrays["end_code"], arrays["end_par"], arrays["end_state"], end_value)
        specials = (arrays["sp_elem"], arrays["sp_cap"], sp_force, *scratch, soil)
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
    end whose continuation is at rest (prescribed forces and velocities may act at any step), and no mass of a
    lumped chain at the right end or in a joint moves at the start."""
    code, par = int(arrays["end_code"][1]), arrays["end_par"][1]
    lumped = arrays.get("lumped")
    if lumped is not None and np.any(lumped[3][1:, :, 0] != 0.0):
        return False        # a moving mass at the right end or in a joint moves the rods right of it
    return (code in (B.FREE, B.FIXED, B.SPRING, B.BITROCK) or (code == B.NONREFLECTING and par[1] == 0.0)
            or (code == B.SOIL_TOE and par[1] == 0.0))     # a soil toe that starts unloaded


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
