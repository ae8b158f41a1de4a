"""What :func:`rodimpact.simulate` records, declared up front (:class:`Outputs`), and the preallocated arrays
the time loop fills at precomputed step indices (:class:`Recorder`).

Samples belong to a step index k: element fields and energies are taken at t = k dt (before step k), node
histories (contact force, end values, probes) are the values held during step k, reported with its start time.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Iterable, Optional

import numpy as np

from .._validate import finite_array
from ..lattice.lattice import Lattice
from . import guards
from .boundary import ACC_SLOTS
from .result import EnergyHistory, FieldSnapshots, JunctionEvents, Probe

#: most snapshots of one run
MAX_SNAPSHOTS = 100_000
#: most energy samples of one run
MAX_ENERGY_SAMPLES = 1_000_000
#: energy samples per run when ``energy_every`` is not given
DEFAULT_ENERGY_SAMPLES = 256


def step_stride(name: str, every: Any) -> int:
    """``every`` as a stride in steps (an integer >= 1), or a ValueError naming ``name``."""
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise ValueError(f"{name}: must be an integer number of steps >= 1, got {every!r}")
    return int(every)


def check_probes(probes: Iterable[Any]) -> tuple[Probe, ...]:
    """``probes`` as a tuple after checking that each is a :class:`Probe` and that their names differ."""
    out = tuple(probes)
    names: set[str] = set()
    for i, p in enumerate(out):
        if not isinstance(p, Probe):
            raise TypeError(f"probes[{i}]: must be a Probe(name, rod, position), got {type(p).__name__}")
        if p.name in names:
            raise ValueError(f"probes[{i}].name: {p.name!r} is used twice")
        names.add(p.name)
    return out


@dataclass(frozen=True)
class Outputs:
    """The outputs of a run besides the contact force and end values (which are always kept).

    probes:
        :class:`~rodimpact.Probe` objects: force, velocity, displacement and strain histories at a node.
    snapshot_times, snapshot_every:
        Field snapshots N(x), v(x), u(x) at the steps nearest to the given times (s) and/or every k steps.
    energy_every:
        Energy sampling stride in steps (default ``None``: about 256 samples per run).
    record_every:
        Keep every ``record_every``-th step of the histories (contact force and flag, end values, probes);
        contact events are still taken at every step (``result.junction_events``).
    """

    probes: tuple[Probe, ...] = ()
    snapshot_times: Optional[tuple[float, ...]] = None
    snapshot_every: Optional[int] = None
    energy_every: Optional[int] = None
    record_every: int = 1

    def __post_init__(self) -> None:
        if isinstance(self.probes, (Probe, str)) or not isinstance(self.probes, Iterable):
            raise TypeError(f"probes: must be a sequence of Probe(name, rod, position), got "
                            f"{type(self.probes).__name__}")
        object.__setattr__(self, "probes", check_probes(self.probes))
        if self.snapshot_times is not None:
            times = self.snapshot_times
            t = finite_array("snapshot_times", times if np.ndim(times) else [times], unit="s")
            if np.any(t < 0):
                raise ValueError(f"snapshot_times: must lie in [0, duration of the run] s, got {t.min():.6g} s")
            object.__setattr__(self, "snapshot_times", tuple(float(x) for x in t))
        if self.snapshot_every is not None:
            object.__setattr__(self, "snapshot_every", step_stride("snapshot_every", self.snapshot_every))
        if self.energy_every is not None:
            object.__setattr__(self, "energy_every", step_stride("energy_every", self.energy_every))
        object.__setattr__(self, "record_every", step_stride("record_every", self.record_every))

    def snapshot_steps(self, n_steps: int, dt: float) -> np.ndarray:
        """Sorted step indices of the snapshots of a run of ``n_steps`` steps of ``dt``."""
        out: set[int] = set()
        if self.snapshot_times is not None:
            t = np.asarray(self.snapshot_times)
            if np.any(t > n_steps * dt * (1 + 1e-12)):
                raise ValueError(f"snapshot_times: must lie in [0, {n_steps * dt:.6g}] s, got "
                                 f"{t.min():.6g}..{t.max():.6g}")
            out |= set(np.round(t / dt).astype(int).tolist())
        if self.snapshot_every is not None:
            count = n_steps // self.snapshot_every + 1
            if len(out) + count > MAX_SNAPSHOTS:
                raise ValueError(f"snapshot_every: {self.snapshot_every} gives {count} snapshots; use a larger "
                                 f"stride (at most {MAX_SNAPSHOTS})")
            out |= set(range(0, n_steps + 1, self.snapshot_every))
        return np.array(sorted(out), dtype=np.int64)

    def energy_steps(self, n_steps: int) -> np.ndarray:
        """Sorted step indices of the energy samples: every ``energy_every`` steps and the last step."""
        every = self.energy_every or max(1, -(-n_steps // DEFAULT_ENERGY_SAMPLES))
        if n_steps // every > MAX_ENERGY_SAMPLES:        # checked before the steps are listed
            raise ValueError(f"energy_every: {every} gives {n_steps // every + 1} energy samples of {n_steps} steps; "
                             f"at most {MAX_ENERGY_SAMPLES:,} (use a larger stride)")
        steps = np.arange(0, n_steps + 1, every, dtype=np.int64)
        return steps if steps[-1] == n_steps else np.append(steps, np.int64(n_steps))


#: per-step node histories the kernels write (one column per step), in the order of the kernels' tuples
HISTORIES = ("junction_N", "junction_contact", "end_N", "end_V", "pr_N", "pr_V", "pr_u")
#: contact phases per junction held before the compiled loop returns to have the buffer enlarged
_PHASES = 16


class Recorder:
    """The preallocated arrays of one run that the time loop fills (see :mod:`rodimpact.direct._kernels`):

    * ``chunk``: the step columns :func:`~rodimpact.direct._kernels.boundaries` writes, for at most ``capacity``
      steps of one call of the loop (0 when the compiled loop keeps every step: it then writes them straight into
      ``kept``); ``kept``: every ``stride``-th step of them (the recorded histories);
    * ``events``: per junction (open phase start or -1, its peak |N|, min N, its step, max |N|), the closed
      phases (start, stop, peak |N|) and their count;
    * ``samples``: the energy and snapshot step indices, a cursor into each, the energy sums per rod
      (kinetic, strain, momentum) with the work/impulse accumulators, the fields N, v, u at the snapshots, the
      initial element forces (for u) and 1 / Z (for the energy sums of the compiled path).
    """

    def __init__(self, recording: Outputs, lattice: Lattice, arrays: dict, initial_force: np.ndarray, n_steps: int,
                 capacity: int) -> None:
        self.n_steps, self.stride = n_steps, recording.record_every
        rows = {key: arrays[key].shape[0] for key in HISTORIES}
        n_rec = -(-n_steps // self.stride)
        self.energy_steps = recording.energy_steps(n_steps)
        self.snapshot_steps = recording.snapshot_steps(n_steps, lattice.dt)
        n_el, n_nodes, n_rods = lattice.n_elements, lattice.n_elements + lattice.n_rods, lattice.n_rods
        n_hist = sum(rows.values()) + rows["pr_N"]                      # + strain per probe
        guards.check_run_memory(n_el, n_steps, n_hist, self.stride, self.snapshot_steps.size)
        self.chunk = tuple(np.zeros((rows[key], capacity)) for key in HISTORIES)
        self.kept = tuple(np.zeros((rows[key], n_rec)) for key in HISTORIES)
        n_j = rows["junction_N"]
        state = np.zeros((n_j, 5))
        state[:, 0], state[:, 2] = -1.0, np.inf
        self.events = (state, np.zeros((n_j, _PHASES, 3)), np.zeros(n_j, dtype=np.int64))
        m, ms = self.energy_steps.size, self.snapshot_steps.size
        self.samples = (self.energy_steps, self.snapshot_steps, np.zeros(2, dtype=np.int64), np.zeros((m, n_rods)),
                        np.zeros((m, n_rods)), np.zeros((m, n_rods)), np.zeros((m, ACC_SLOTS)), np.zeros((ms, n_el)),
                        np.zeros((ms, n_el)), np.zeros((ms, n_nodes)), initial_force,
                        1.0 / lattice.impedance)

    def grow_events(self) -> None:
        """Twice the room for closed contact phases (the compiled loop returned because a junction's is full)."""
        state, phases, count = self.events
        bigger = np.zeros((phases.shape[0], 2 * phases.shape[1], 3))
        bigger[:, :phases.shape[1]] = phases
        self.events = (state, bigger, count)

    @property
    def record(self) -> tuple:
        """The recording bundle of the kernels: (stride, kept histories, events, samples)."""
        return self.stride, self.kept, self.events, self.samples

    def histories(self) -> dict[str, np.ndarray]:
        """The recorded histories by name (``HISTORIES``)."""
        return dict(zip(HISTORIES, self.kept))

    def junction_events(self) -> tuple[JunctionEvents, ...]:
        """Contact phases of every junction; a phase still open at the end stops at ``n_steps``."""
        state, phases, count = self.events
        out = []
        for j, (open_start, open_peak, low, low_step, peak) in enumerate(state.tolist()):
            rows = phases[j, :count[j]].T
            start, stop, top = rows[0].astype(np.int64), rows[1].astype(np.int64), rows[2].copy()
            if open_start >= 0:
                start, stop = np.append(start, int(open_start)), np.append(stop, self.n_steps)
                top = np.append(top, open_peak)
            out.append(JunctionEvents(start=start, stop=stop, max_abs_force=top,
                                      min_force=low if math.isfinite(low) else 0.0, min_force_step=int(low_step),
                                      max_abs_force_run=peak))
        return tuple(out)

    def energy(self, dt: float) -> EnergyHistory:
        """The energy samples (thesis eq. 3.25 per rod) with the cumulative work and impulse."""
        steps, _, _, kin, pot, mom, acc = self.samples[:7]
        return EnergyHistory(time=steps * dt, kinetic=kin.T, strain=pot.T, momentum=mom.T, work_left=acc[:, 0],
                             work_right=acc[:, 1], work_loads=acc[:, 2], work_friction=acc[:, 3],
                             work_joints=acc[:, 8], work_soil=acc[:, 9],
                             # I_left + I_right + ... (+ the shaft soil's, if any: the sums of runs without
                             # soil are those they always were)
                             impulse=functools.reduce(np.add, acc[:, 4:8].T) + acc[:, 10] if acc[:, 10].any()
                             else functools.reduce(np.add, acc[:, 4:8].T))

    def snapshots(self, lattice: Lattice) -> Optional[FieldSnapshots]:
        """The field snapshots (``None`` if none were requested)."""
        steps, s_N, s_v, s_u = self.snapshot_steps, *self.samples[7:10]
        if steps.size == 0:
            return None
        return FieldSnapshots(time=steps * lattice.dt, element_x=lattice.element_x, node_x=lattice.node_x,
                              element_rod=lattice.element_rod, node_rod=lattice.node_rod, force=s_N.T,
                              velocity=s_v.T, displacement=s_u.T)
