"""Result objects of :func:`rodimpact.simulate` (frozen dataclasses, time on the last axis)."""

from __future__ import annotations

from dataclasses import dataclass, field
import functools
import math
from typing import Any, Optional, Sequence

import numpy as np

from ..lattice.lattice import Lattice
from ..rods.conditions import BitRockEnd, DeformableJoint, LumpedEnd, LumpedJoint, PointMass
from ..rods.declared import check, quantity, text
from ..rods.declared import rod as rod_index
from ..rods.laws import FREW
from ..rods.system import System
from ._momentum import mean_velocities
from .joints import softening
from .lumped import chain_energies
from .tables import SimulationTables


@dataclass(frozen=True)
class Probe:
    """An output request: histories at ``position`` (m from the left end of rod number ``rod``).

    ``rod`` may also be the rod's name. The probe reads the lattice node nearest to ``position``; node values
    are exact and constant during each step. ``strain`` uses the true E and A at ``position``.
    """

    name: str = text("Unique name (used in CSV headers and plots).")
    rod: int | str = rod_index("The rod: its name or its index (0 = first rod).")
    position: float = quantity("length", "Distance from the rod's left end.", bound="non_negative")

    def __post_init__(self) -> None:
        check(self)


@dataclass(frozen=True, repr=False)
class ProbeHistory:
    """Histories recorded by a :class:`Probe`, one value per recorded step (step start time)."""

    probe: Probe
    node_position: float      # position of the node actually read, m from the rod's left end
    force: np.ndarray         # N, tension positive
    velocity: np.ndarray      # m/s
    displacement: np.ndarray  # m, relative to the initial configuration, at the step start
    strain: np.ndarray        # -, N / (E A) at the probe position

    def __repr__(self) -> str:
        return (f"ProbeHistory({self.probe.name!r}: rod {self.probe.rod} at {self.node_position:.6g} m, "
                f"{self.force.size} steps, peak force {self.force.min():.6g} N)")


@dataclass(frozen=True, repr=False)
class FieldSnapshots:
    """Fields along x at selected times (columns). Element values are uniform in each element at t = k dt."""

    time: np.ndarray          # (m,)
    element_x: np.ndarray     # (n_elements,) reference centre positions, m
    node_x: np.ndarray        # (n_nodes,) reference node positions, m (n_j + 1 per rod)
    element_rod: np.ndarray   # (n_elements,)
    node_rod: np.ndarray      # (n_nodes,)
    force: np.ndarray         # (n_elements, m) N
    velocity: np.ndarray      # (n_elements, m) m/s
    displacement: np.ndarray  # (n_nodes, m) m

    def __repr__(self) -> str:
        return f"FieldSnapshots({self.time.size} times, {self.element_x.size} elements)"


@dataclass(frozen=True, repr=False)
class EnergyHistory:
    """Energy bookkeeping sampled every few steps (thesis eq. 3.25 per rod).

    ``work_*`` is the cumulative work done on the rods since t = 0 by each outer end, the prescribed nodal
    loads and the bearing friction (J; friction work is <= 0). ``impulse_*`` likewise in N s. Without
    losses, ``total - total[0] - exchanged`` vanishes to rounding. ``work_soil`` is the work of the shaft soil
    (:class:`~rodimpact.rods.soil.ShaftResistance`, <= 0); a soil toe's work is that of its end
    (``work_right`` or ``work_left``), like every end law's. Without soil it is zero.
    """

    time: np.ndarray
    kinetic: np.ndarray       # (n_rods, m) J
    strain: np.ndarray        # (n_rods, m) J
    momentum: np.ndarray      # (n_rods, m) N s
    work_left: np.ndarray
    work_right: np.ndarray
    work_loads: np.ndarray
    work_friction: np.ndarray
    work_joints: np.ndarray   # (m,) work done on the rods by the joints between them (<= 0 if passive)
    impulse: np.ndarray       # (m,) total external impulse, N s
    work_soil: Optional[np.ndarray] = None   # (m,) work of the shaft soil on the rods (<= 0); None: zero

    def __post_init__(self) -> None:
        if self.work_soil is None:
            object.__setattr__(self, "work_soil", np.zeros_like(self.work_friction))

    def __repr__(self) -> str:
        return (f"EnergyHistory({self.time.size} samples, total {self.total[0]:.6g} J -> {self.total[-1]:.6g} J, "
                f"balance error {self.balance_error:.2g})")

    @property
    def total(self) -> np.ndarray:
        """Total mechanical energy of all rods, J (rod by rod, as ``sum(axis=0)`` adds them; row additions are
        faster than a reduction across the short rod axis)."""
        return functools.reduce(np.add, self.kinetic) + functools.reduce(np.add, self.strain)

    @property
    def exchanged(self) -> np.ndarray:
        """Cumulative work done on the rods by ends, loads, friction, joints and the shaft soil, J."""
        return (self.work_left + self.work_right + self.work_loads + self.work_friction + self.work_joints
                + self.work_soil)

    @property
    def balance_error(self) -> float:
        """max |E(t) - E(0) - W(t)| relative to max(E): the energy bookkeeping error."""
        total = self.total
        err = total - total[0] - self.exchanged
        return float(np.abs(err).max() / max(float(np.abs(total).max()), 1e-300))


@dataclass(frozen=True, repr=False)
class BitRockOutcome:
    """What a run did to the rock at an outer end with a :class:`~rodimpact.BitRockEnd` (percussive drilling; the
    bilinear law of thesis Fig. 4.9), from the impact to the end of the run.

    Penetration delta is the displacement of the bit's face into the rock from its position at t = 0, m: +x at a
    right end, -x at a left end (positive = into the rock). The rock force on the bit is F >= 0 (the bit's normal
    force is N = -F): F = k1 delta while delta exceeds its previous maximum, else k2 (delta - r) above the release
    point r = delta_max (1 - k1/k2) and 0 below it.

    Attributes
    ----------
    end:
        ``"left"`` or ``"right"``.
    loading_stiffness, unloading_stiffness:
        k1 and k2, N/m.
    max_penetration:
        delta_max, the largest penetration of the run, m (taken at the ends of the steps, exact for the bit's
        path, which is linear within each step).
    final_penetration:
        delta at the end of the run, m (below :attr:`penetration` when the bit has moved back off the rock).
    energy:
        The energy into the rock: the work done by the bit on the rock from t = 0 to the end of the run, J (minus
        the end's work in the energy bookkeeping, ``energy.work_right[-1]`` or ``work_left[-1]``). Once the bit has
        lifted off (:attr:`in_contact` False) it is the energy the rock has taken for good, k1 delta_max^2 / 2
        (1 - k1/k2); while the bit still presses on the rock it includes the elastic energy F^2 / (2 k2) the rock
        will give back.
    striker:
        Index of the striker, the rod at the other end of the system (rod 0 for a rock at the right end).
    striker_energy:
        The striker's initial energy (kinetic plus strain: 1/2 m v^2 for a striker without initial stress), J.
    """

    end: str
    loading_stiffness: float
    unloading_stiffness: float
    max_penetration: float
    final_penetration: float
    energy: float
    striker: int
    striker_energy: float

    @property
    def penetration(self) -> float:
        """The penetration per blow, m: the permanent penetration delta_max (1 - k1/k2), where the rock force
        returns to zero on unloading, i.e. the depth the rock keeps after the blow (0 for an elastic rock, k2 =
        k1)."""
        return self.max_penetration * (1.0 - self.loading_stiffness / self.unloading_stiffness)

    @property
    def final_force(self) -> float:
        """The rock force on the bit at the end of the run, F >= 0 (N), from the bilinear law at
        :attr:`final_penetration`."""
        if self.final_penetration >= self.max_penetration:
            return self.loading_stiffness * self.final_penetration
        return max(self.unloading_stiffness * (self.final_penetration - self.penetration), 0.0)

    @property
    def in_contact(self) -> bool:
        """True when the rock still pushes on the bit at the end of the run (:attr:`final_force` above 1e-9 of the
        largest rock force k1 delta_max): the blow is not over and :attr:`energy` includes elastic energy."""
        return self.final_force > 1e-9 * self.loading_stiffness * self.max_penetration

    @property
    def efficiency(self) -> Optional[float]:
        """The drilling efficiency: :attr:`energy` / :attr:`striker_energy` (``None`` when the striker starts
        without energy, e.g. a rod driven by a prescribed force)."""
        return self.energy / self.striker_energy if self.striker_energy > 0.0 else None

    def __repr__(self) -> str:
        eff = "" if self.efficiency is None else f" ({self.efficiency:.2%} of rod {self.striker}'s initial energy)"
        return (f"BitRockOutcome({self.end} end: energy into the rock {self.energy:.6g} J{eff}, penetration per "
                f"blow {self.penetration:.6g} m, largest {self.max_penetration:.6g} m"
                f"{', still in contact' if self.in_contact else ''})")


#: Drilling metrics for a system with a :class:`~rodimpact.BitRockEnd` (the first such end), as
#: :class:`~rodimpact.BitRockOutcome` defines them: name -> (outcome attribute, unit): the energy into the rock,
#: the drilling efficiency (that energy / the striker's initial energy) and the penetration per blow.
ROCK_QUANTITIES: dict[str, tuple[str, str]] = {"rock_energy": ("energy", "J"),
                                               "drilling_efficiency": ("efficiency", "1"),
                                               "penetration_per_blow": ("penetration", "m")}


def rock_value(outcomes: Sequence[Any], quantity: str) -> float:
    """``quantity`` of the first :class:`~rodimpact.BitRockOutcome` of ``outcomes`` (NaN without a BitRockEnd,
    or for an efficiency without striker energy)."""
    value = getattr(outcomes[0], quantity) if outcomes else None
    return math.nan if value is None else float(value)


def bit_rock_outcomes(system: System, end_state: np.ndarray, work_left: float, work_right: float,
                      initial_energy: np.ndarray) -> tuple[BitRockOutcome, ...]:
    """A :class:`BitRockOutcome` for each outer end of ``system`` with a :class:`~rodimpact.BitRockEnd`: the
    kernel's final end state ``end_state[e] = (delta, delta_max)`` (e = 0 left, 1 right; m), the end's work from
    the energy bookkeeping (J; the energy into the rock is minus it) and each rod's initial energy (J). The
    striker is the rod at the other end of the system."""
    out = []
    for e, (side, cond) in enumerate((("left", system.left), ("right", system.right))):
        if not isinstance(cond, BitRockEnd):
            continue
        striker = system.n_rods - 1 if side == "left" else 0
        out.append(BitRockOutcome(
            end=side, loading_stiffness=cond.loading_stiffness, unloading_stiffness=cond.unloading_stiffness,
            max_penetration=float(end_state[e, 1]), final_penetration=float(end_state[e, 0]),
            energy=-float(work_left if side == "left" else work_right), striker=striker,
            striker_energy=float(initial_energy[striker])))
    return tuple(out)


@dataclass(frozen=True)
class JointOutcome:
    """The state of a deformable joint (:class:`~rodimpact.Specimen`, :class:`~rodimpact.PulseShaper`) at the end
    of a run, and the split of the work it absorbed.

    ``shortening`` delta (m, positive when compressed); ``strain`` in the joint's measure (engineering
    delta / L0, or true -ln(1 - delta / L0)); ``plastic_strain`` eps_p and ``accumulated_plastic_strain`` alpha of
    the plastic laws; ``plastic_work`` (J) the work dissipated in plastic flow, sum of sigma_mid (eps_p,k+1 -
    eps_p,k) A0 L0 over the steps; ``stored_energy`` (J) the elastic energy sigma^2 / (2 E) A0 L0 at the end
    (plastic laws and the elastic law; ``nan`` for a loading-curve law such as Frew's, whose absorbed work is not
    split; a failing law's (:class:`~rodimpact.rods.laws.Failure`) times 1 - softening). ``softening`` w of a
    failing law (0 intact, 1 failed: sigma = (1 - w) sigma_law) and ``damage_work`` (J) the elastic energy its
    softening released, sum of (w_k+1 - w_k) E eps_e,k+1^2 / 2 A0 L0 (0 without failure). For a joint alone
    between two rods, ``plastic_work + damage_work + stored_energy`` equals minus the joints' work in
    :attr:`EnergyHistory.work_joints` (to the root finder's tolerance with engineering measures, to second
    order in dt with true measures).
    """

    junction: int
    shortening: float
    strain: float
    plastic_strain: float
    accumulated_plastic_strain: float
    plastic_work: float
    stored_energy: float
    damage_work: float = 0.0
    softening: float = 0.0


def joint_outcomes(system: System, gap: np.ndarray, state: np.ndarray) -> tuple[JointOutcome, ...]:
    """A :class:`JointOutcome` for each deformable joint of ``system`` from the kernel's final gaps (m; the
    shortening is minus the gap) and joint states ``state[r] = (eps_p, alpha, eps_max, plastic work, crushed)``;
    a ``ValueError`` naming the junction if a body was crushed (its shortening reached its length)."""
    out = []
    for r, j in enumerate(system.junctions):
        if not isinstance(j, DeformableJoint):
            continue
        if state[r, 4] != 0.0:
            raise ValueError(f"junctions[{r}]: the {type(j).__name__.lower()} was crushed: its shortening reached its "
                             f"initial length L0 = {j.initial_length:.6g} m, where the 1-D body model ends; lower "
                             "the load or shorten the run")
        delta = -float(gap[r])
        e = delta / j.initial_length
        strain = -math.log1p(-e) if j.measure == "true" and e < 1.0 else e
        e_mod = j.law.modulus
        w = softening.py_func(j.law.code, j.law.kernel(), float(state[r, 1]))
        if j.law.code == FREW:
            stored = math.nan
        else:
            sigma = e_mod * (strain - float(state[r, 0]))
            if j.compression_only and sigma < 0.0:
                sigma = 0.0
            stored = (1.0 - w) * sigma * sigma / (2.0 * e_mod) * j.area * j.initial_length
        out.append(JointOutcome(r, delta, strain, float(state[r, 0]), float(state[r, 1]), float(state[r, 3]),
                                stored, float(state[r, 5]), w))
    return tuple(out)


@dataclass(frozen=True)
class LumpedOutcome:
    """The energies of a lumped chain (:class:`~rodimpact.LumpedEnd`, :class:`~rodimpact.LumpedJoint`) at the end
    of a run, J, and its state.

    ``place``: ``"left"``, ``"right"`` or ``"junction <r>"``. ``initial_kinetic_energy`` and ``kinetic_energy``:
    sum of M V^2 / 2 of its masses at t = 0 and at the end. ``stored_energy``: what the cushions would give back,
    the area under their unloading lines (k / e^2) (d - r)^2 / 2 above the release point r = d_max (1 - e^2).
    ``dissipated_energy``: the work the cushions took minus ``stored_energy`` (for a cushion unloaded after one
    compression to d_max: (1 - e^2) k d_max^2 / 2). ``energy_to_rods``: the work the chain did on the rod faces,
    ``initial_kinetic_energy - kinetic_energy - stored_energy - dissipated_energy`` (at an outer end the end's
    ``EnergyHistory.work_left`` / ``work_right``, in a joint its share of ``work_joints``). ``velocities``: of
    the masses, m/s along x, in item order; ``max_compressions``: d_max of the cushions, m, in item order.
    """

    place: str
    initial_kinetic_energy: float
    kinetic_energy: float
    stored_energy: float
    dissipated_energy: float
    energy_to_rods: float
    velocities: tuple[float, ...]
    max_compressions: tuple[float, ...]


def lumped_outcomes(system: System, lumped: Optional[tuple]) -> tuple[LumpedOutcome, ...]:
    """A :class:`LumpedOutcome` for each lumped chain of ``system`` (left end, right end, junctions in order)
    from the kernel's final chain state ``lumped`` (:mod:`rodimpact.direct.lumped`)."""
    out = []
    places = [("left", system.left), ("right", system.right),
              *((f"junction {r}", j) for r, j in enumerate(system.junctions))]
    for row, (name, p) in enumerate(places):
        if not isinstance(p, (LumpedEnd, LumpedJoint)):
            continue
        kinetic, stored, work = chain_energies(lumped, row)
        initial = sum(0.5 * it.mass * it.velocity ** 2 for it in p.items if isinstance(it, PointMass))
        sign = -1.0 if row == 1 else 1.0            # along the chain -> along x
        state = lumped[3][row]
        out.append(LumpedOutcome(
            name, initial, kinetic, stored, work - stored, initial - kinetic - work,
            tuple(sign * float(state[i, 0]) for i, it in enumerate(p.items) if isinstance(it, PointMass)),
            tuple(float(state[i, 1]) for i, it in enumerate(p.items) if not isinstance(it, PointMass))))
    return tuple(out)


@dataclass(frozen=True, repr=False)
class JunctionEvents:
    """Contact phases of one junction, taken at every time step (whatever the recording stride).

    Phase ``i`` covers the steps ``start[i] <= k < stop[i]`` (``stop = n_steps`` if the faces still touch at
    the end); ``max_abs_force[i]`` is the largest magnitude of the junction force in it, N. ``min_force`` is the
    most compressive junction force of the whole run (N, tension positive) and ``min_force_step`` its first
    step. ``max_abs_force_run`` is the largest magnitude over the whole run.
    """

    start: np.ndarray
    stop: np.ndarray
    max_abs_force: np.ndarray
    min_force: float
    min_force_step: int
    max_abs_force_run: float

    def __repr__(self) -> str:
        return f"JunctionEvents({self.start.size} contact phase(s), min force {self.min_force:.6g} N)"


class EventTracker:
    """Builds :class:`JunctionEvents` from the per-step junction force and contact flag, fed in consecutive
    chunks of steps (so that the histories need not be kept at every step). Vectorised per chunk: the cost does
    not depend on how often the contact opens and closes."""

    def __init__(self, n_junctions: int) -> None:
        self._open: list[tuple[int, float] | None] = [None] * n_junctions   # (start step, max |force|) if touching
        self._closed: list[list[np.ndarray]] = [[] for _ in range(n_junctions)]   # (m, 3) rows start, stop, peak
        self._min = [(math.inf, 0)] * n_junctions
        self._max_abs = [0.0] * n_junctions

    def feed(self, first: int, force: np.ndarray, contact: np.ndarray) -> None:
        """Steps ``first .. first + n - 1``: ``force`` and ``contact`` of shape (n_junctions, n)."""
        n = force.shape[1]
        if n == 0:
            return
        for j in range(force.shape[0]):
            f, c = force[j], np.asarray(contact[j]) > 0.5
            k = int(np.argmin(f))
            if f[k] < self._min[j][0]:
                self._min[j] = (float(f[k]), first + k)
            absf = np.abs(f)
            self._max_abs[j] = max(self._max_abs[j], float(absf.max()))
            runs = np.flatnonzero(np.concatenate([[True], c[1:] != c[:-1]]))     # first step of each run of c
            ends = np.append(runs[1:], n)
            peaks = np.maximum.reduceat(absf, runs)
            on = np.flatnonzero(c[runs])
            rows = np.column_stack([first + runs[on], first + ends[on], peaks[on]]).astype(float)
            previous = self._open[j]
            if previous is not None:
                if c[0]:               # the open phase continues into this chunk
                    rows[0, 0], rows[0, 2] = previous[0], max(previous[1], rows[0, 2])
                else:                  # it ended with the last chunk
                    self._closed[j].append(np.array([[previous[0], first, previous[1]]]))
            if c[-1]:
                self._open[j] = (int(rows[-1, 0]), float(rows[-1, 2]))
                rows = rows[:-1]
            else:
                self._open[j] = None
            self._closed[j].append(rows)

    def finish(self, n_steps: int) -> tuple[JunctionEvents, ...]:
        """The events of every junction; a phase still open ends at ``n_steps``."""
        out = []
        for j, closed in enumerate(self._closed):
            still = self._open[j]
            arr = np.concatenate(closed + ([np.array([[still[0], n_steps, still[1]]])] if still else [])
                                 + [np.zeros((0, 3))])
            low, step = self._min[j]
            out.append(JunctionEvents(start=arr[:, 0].astype(np.int64), stop=arr[:, 1].astype(np.int64),
                                      max_abs_force=arr[:, 2], min_force=low if math.isfinite(low) else 0.0,
                                      min_force_step=int(step), max_abs_force_run=self._max_abs[j]))
        return tuple(out)


#: Values within this fraction of the largest magnitude of a history count as equal to its extreme when the time
#: of a peak is reported: the lattice's sums round at about 1e-14 of the force, so a flat plateau wobbles by that
#: much and its exact minimum lies anywhere on it; the time reported is where the plateau begins.
PEAK_REL_TOL = 1e-9


def first_within_rounding(values: np.ndarray, extreme: float, rel_tol: float = PEAK_REL_TOL) -> int:
    """Index of the first entry of ``values`` within ``rel_tol`` x max |values| of ``extreme`` (its minimum or
    maximum): where a plateau at the extreme begins, not the entry that rounding happened to make the extreme."""
    values = np.asarray(values, dtype=float)
    if values.size == 0:
        raise ValueError("values: need at least one sample to find a peak")
    tol = rel_tol * max(float(np.max(np.abs(values))), abs(float(extreme)))
    distance = np.abs(values - extreme)
    near = np.flatnonzero(distance <= tol)
    return int(near[0]) if near.size else int(np.argmin(distance))


def junction_events_from_history(force: np.ndarray, contact: np.ndarray) -> tuple[JunctionEvents, ...]:
    """:class:`JunctionEvents` of per-step histories of shape (n_junctions, n_steps)."""
    tracker = EventTracker(force.shape[0])
    tracker.feed(0, force, contact)
    return tracker.finish(force.shape[1])


@dataclass(frozen=True)
class SimulationResult(SimulationTables):
    """Everything :func:`rodimpact.simulate` computed.

    Node values (contact force, end values, probes) belong to step k and hold on [k dt, (k+1) dt); they are
    reported with the step start time ``k dt``. The histories hold every ``record_every``-th step
    (``time = [0, s dt, 2 s dt, ...]``); contact and separation times, contact durations and the peak contact
    force come from ``junction_events``, which are taken at every step whatever the stride. With a
    :class:`~rodimpact.BitRockEnd`, ``bit_rock`` says what the blow did to the rock (energy into the rock,
    drilling efficiency, penetration per blow: :class:`BitRockOutcome`).
    """

    system: System
    lattice: Lattice
    time: np.ndarray
    junction_force: np.ndarray         # (n_junctions, n_recorded) N, tension positive (0 while apart)
    junction_contact: np.ndarray       # (n_junctions, n_recorded) bool
    end_force: dict[str, np.ndarray]   # "left"/"right" -> (n_recorded,) normal force at the outer ends
    end_velocity: dict[str, np.ndarray]
    probes: dict[str, ProbeHistory]
    snapshots: FieldSnapshots | None
    energy: EnergyHistory
    final_force: np.ndarray            # element forces at t = n_steps dt
    final_velocity: np.ndarray         # element velocities at t = n_steps dt
    diagnostics: dict[str, Any] = field(default_factory=dict)
    record_every: int = 1              # steps between recorded history samples
    n_steps: Optional[int] = None      # steps simulated (default: time.size, for record_every = 1)
    junction_events: Optional[tuple[JunctionEvents, ...]] = None   # default: from the histories
    bit_rock: tuple[BitRockOutcome, ...] = ()   # one per outer end with a BitRockEnd (left first)
    joints: tuple[JointOutcome, ...] = ()       # one per deformable joint (Specimen, PulseShaper), left first
    lumped: tuple[LumpedOutcome, ...] = ()      # one per lumped chain (LumpedEnd, LumpedJoint): left, right, joints
    soil: Any = None        # the soil's final state, a rodimpact.direct.soil_result.SoilOutcome (None: no soil)

    def __post_init__(self) -> None:
        if isinstance(self.record_every, bool) or not isinstance(self.record_every, (int, np.integer)) \
                or self.record_every < 1:
            raise ValueError(f"record_every: must be an integer >= 1, got {self.record_every!r}")
        if self.n_steps is None:
            if self.record_every != 1:
                raise ValueError("n_steps: required when record_every > 1 (the histories do not hold every step)")
            object.__setattr__(self, "n_steps", int(self.time.size))
        if self.junction_events is None:
            if self.record_every != 1:
                raise ValueError("junction_events: required when record_every > 1")
            object.__setattr__(self, "junction_events",
                               junction_events_from_history(self.junction_force, self.junction_contact))

    def __repr__(self) -> str:
        lines = [f"SimulationResult({self.system.n_rods} rod(s), {self.lattice.n_elements} elements, "
                 f"{self.n_steps} steps of dt = {self.dt:.4g} s"
                 + (f", every {self.record_every}th recorded)" if self.record_every > 1 else ")")]
        for j in range(self.junction_force.shape[0]):
            lines.append(f"  junction {j}: peak force {self.junction_events[j].min_force:.6g} N, contact "
                         f"{self.contact_duration(j):.6g} s, separations at {np.round(self.separation_times(j), 12)} s")
        lines.append(f"  rigid-body velocities at the end: {np.round(self.rigid_body_velocity, 6)} m/s; "
                     f"energy balance error {self.energy.balance_error:.2g}")
        lines += [f"  {o!r}" for o in self.bit_rock]
        if self.probes:
            lines.append(f"  probes: {', '.join(self.probes)}")
        return "\n".join(lines)

    @property
    def dt(self) -> float:
        """Time step, s."""
        return self.lattice.dt

    @property
    def contact_force(self) -> np.ndarray:
        """Force at the junction(s), one value per recorded step (``time``), tension positive (compressive
        impact < 0): shape (n_recorded,) for two rods, (n_junctions, n_recorded) for more."""
        if self.junction_force.shape[0] == 0:
            raise ValueError("contact_force: this system has a single rod and no junction; "
                             "use end_force or probes")
        return self.junction_force[0] if self.junction_force.shape[0] == 1 else self.junction_force

    def probe(self, name: str) -> ProbeHistory:
        """Histories of the probe called ``name``."""
        if name not in self.probes:
            raise KeyError(f"probe {name!r} not recorded; recorded probes: {sorted(self.probes)}")
        return self.probes[name]

    def _events(self, junction: int) -> JunctionEvents:
        events = self.junction_events or ()
        if not 0 <= junction < len(events):
            raise ValueError(f"junction: must be 0..{len(events) - 1} for {len(events) + 1} rods, got {junction!r}")
        return events[junction]

    def peak_time(self, junction: int = 0) -> float:
        """Time of the most compressive force at ``junction``, s: where the force first comes within rounding
        (:data:`PEAK_REL_TOL` of the run's largest |force|) of its peak, so a flat plateau is reported where it
        begins. The peak itself is taken at every step; with ``record_every > 1`` its plateau is searched among
        the recorded steps, so the time is exact to the recording stride."""
        ev = self._events(junction)
        step = int(ev.min_force_step)
        recorded = self.junction_force[junction]
        if recorded.size:
            tol = PEAK_REL_TOL * max(ev.max_abs_force_run, abs(ev.min_force))
            near = np.flatnonzero(np.abs(recorded - ev.min_force) <= tol)
            if near.size:
                step = min(step, int(near[0]) * int(self.record_every))
        return step * self.dt

    def contact_times(self, junction: int = 0) -> np.ndarray:
        """Start times of each contact phase at ``junction`` (first impact and every re-contact), s."""
        return self._events(junction).start * self.dt

    def separation_times(self, junction: int = 0) -> np.ndarray:
        """Times at which the rods at ``junction`` separate, s."""
        ev = self._events(junction)
        return ev.stop[ev.stop < self.n_steps] * self.dt

    def contact_duration(self, junction: int = 0) -> float:
        """Total time the rods at ``junction`` were in contact, s."""
        ev = self._events(junction)
        return float(np.sum(ev.stop - ev.start) * self.dt)

    @property
    def rigid_body_velocity(self) -> np.ndarray:
        """Mean (centre-of-mass) velocity of each rod at the end of the run, m/s: momentum / lattice mass,
        sum(Z_i v_i) / sum(Z_i) over its elements (element mass Z_i dt)."""
        z, v = self.lattice.impedance, self.final_velocity
        return mean_velocities(z[None], v[None], np.asarray(self.lattice.rod_start, dtype=np.int64))[0]

    @property
    def efficiency(self) -> float:
        """Energy-transfer efficiency: the fraction of rod 0's initial energy that it has given away by the
        end of the run, (E_0(0) - E_0(end)) / E_0(0)."""
        e0 = self.energy.kinetic[0] + self.energy.strain[0]
        if e0[0] <= 0.0:
            raise ValueError("efficiency: rod 0 starts without energy; compare energy.kinetic/strain instead")
        return float((e0[0] - e0[-1]) / e0[0])

    def to_xarray(self):
        """Everything recorded (except the system) as an :class:`xarray.Dataset`: coordinates ``time``, ``probe``
        (the names: ``ds.probe_force.sel(probe="SG1")``), ``junction``, ``end``, ``rod``, ``snapshot_time``, ...;
        the same layout as ``result.nc`` (see :mod:`rodimpact.direct.dataset`)."""
        from .dataset import result_dataset

        return result_dataset(self)
