"""One hammer blow on a pile: the system the solver steps (driving system at the head, the pile, the soil along the
shaft and at the toe), and what the blow did: the permanent set and blow count, the envelopes of the largest
compressive and tensile stresses along the pile (where and when), the energy transferred through the head
(ENTHRU, its maximum EMX) and the forces and velocities at gauge stations.

The pile is an exact lattice rod (thesis ch. 3): x runs down from the pile head, forces are tension positive, the
pile moves down with positive velocity. Node values (head force and velocity, gauges) are exact and constant
during each step, so the head's transferred energy is an exact sum:

    ENTHRU(t_k+1) = sum_{j <= k} -N_j v_j dt       (J; -N v is the power the part above a node delivers below it)

and EMX = max ENTHRU (the energy measure of pile driving analysers, ASTM D4945 -- not checked against the
standard's text here: the integral of force times velocity at the gauges).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Iterable, Iterator, Mapping, Optional

import numpy as np

from .._validate import integer, non_negative, positive
from ..direct.problem import Problem, TimeGrid
from ..direct.recording import Outputs
from ..direct.result import PEAK_REL_TOL, Probe, ProbeHistory, SimulationResult
from ..direct.simulate import simulate, solve_compiled
from ..direct.soil_result import next_blow
from ..lattice.lattice import default_time_step
from ..rods.conditions import Contact, FreeEnd
from ..rods.rod import Rod
from ..rods.soil import ShaftResistance, SoilToe
from ..rods.system import System
from .driving import DrivingSystem
from .soil import SoilResistance
from .units import blows_per_foot, blows_per_inch, blows_per_quarter_metre

#: default run length: this many round trips 2 L / c of the pile after impact
ROUND_TRIPS = 10
#: default time step: the longest rod gets at least this many lattice elements
PILE_ELEMENTS = 50


def transferred_energy(force: np.ndarray, velocity: np.ndarray, dt: float) -> np.ndarray:
    """ENTHRU after each step, J: the cumulative sum of -N v dt over the steps (``force`` N tension positive and
    ``velocity`` m/s of a node, constant during each step of length ``dt``)."""
    return np.cumsum(-np.asarray(force) * np.asarray(velocity)) * dt


@dataclass(frozen=True, repr=False)
class StressEnvelope:
    """The largest stresses along the pile over a blow, per element: ``depth`` (m from the pile head, element
    centres), ``compression`` (Pa, the largest compressive stress, >= 0) at ``compression_time`` (s), ``tension``
    (Pa, the largest tensile stress, >= 0) at ``tension_time``. Element stresses are N / A of each element at the
    samples t = k dt."""

    depth: np.ndarray
    compression: np.ndarray
    compression_time: np.ndarray
    tension: np.ndarray
    tension_time: np.ndarray

    def __repr__(self) -> str:
        c, t = self.max_compression, self.max_tension
        return (f"StressEnvelope(max compression {c[0] / 1e6:.4g} MPa at {c[1]:.4g} m, {c[2] * 1e3:.4g} ms; max "
                f"tension {t[0] / 1e6:.4g} MPa at {t[1]:.4g} m, {t[2] * 1e3:.4g} ms)")

    @property
    def max_compression(self) -> tuple[float, float, float]:
        """(stress Pa, depth m, time s) of the largest compressive stress of the blow (of equal maxima within
        rounding, the one reached first)."""
        return _extreme(self.compression, self.depth, self.compression_time)

    @property
    def max_tension(self) -> tuple[float, float, float]:
        """(stress Pa, depth m, time s) of the largest tensile stress of the blow (the first, as above)."""
        return _extreme(self.tension, self.depth, self.tension_time)


def _extreme(values: np.ndarray, depth: np.ndarray, time: np.ndarray) -> tuple[float, float, float]:
    top = float(values.max())
    near = np.flatnonzero(values >= top - PEAK_REL_TOL * top)
    i = int(near[np.argmin(time[near])])
    return float(values[i]), float(depth[i]), float(time[i])


def _first_near(stress: np.ndarray, extreme: np.ndarray) -> np.ndarray:
    """Per row, the first sample within rounding (:data:`PEAK_REL_TOL` x the row's largest magnitude) of
    ``extreme``: where a plateau at the extreme begins, not the sample rounding made largest."""
    tol = PEAK_REL_TOL * np.abs(stress).max(axis=1)
    return np.argmax(np.abs(stress - extreme[:, None]) <= tol[:, None], axis=1)


def stress_envelope(depth: np.ndarray, time: np.ndarray, stress: np.ndarray) -> StressEnvelope:
    """The envelope of ``stress`` (Pa, tension positive, shape (elements, samples)) sampled at ``time`` (s), at
    element ``depth`` (m): per element the largest compression (-min, clipped at 0) and tension (max, clipped at
    0) and the first time each is reached (within rounding)."""
    low, high = stress.min(axis=1), stress.max(axis=1)
    t = np.asarray(time)
    return StressEnvelope(np.asarray(depth), np.maximum(-low, 0.0), t[_first_near(stress, low)],
                          np.maximum(high, 0.0), t[_first_near(stress, high)])


@dataclass(frozen=True, eq=False)
class BlowSetup:
    """A blow as the solver sees it: the :class:`~rodimpact.Problem`, the index of the pile among its rods and the
    soil it meets."""

    problem: Problem
    pile_index: int
    soil: Optional[SoilResistance]


def blow_setup(pile: Rod, driving: DrivingSystem, soil: Optional[SoilResistance] = None, *,
               gauges: Optional[Mapping[str, float]] = None, duration: Optional[float] = None,
               dt: Optional[float] = None, toe: Any = None) -> BlowSetup:
    """The problem of one blow of ``driving`` on ``pile`` (x down from its head) against ``soil`` (its toe at
    ``soil.penetration`` below ground, which must not exceed the pile's length; ``None``: no soil, the toe is
    ``toe``, default free). ``gauges``: name -> distance below the pile head (m). ``dt`` default: the longest rod
    in at least :data:`PILE_ELEMENTS` elements, every rod represented within 1 %; ``duration`` default: :data:`ROUND_TRIPS` round trips 2 L / c of the pile."""
    if not isinstance(pile, Rod):
        raise TypeError(f"pile: must be a Rod, got {type(pile).__name__}")
    if not isinstance(driving, DrivingSystem):
        raise TypeError(f"driving: must be a DrivingSystem, got {type(driving).__name__}")
    duration = (ROUND_TRIPS * 2.0 * pile.total_travel_time if duration is None
                else positive("duration", duration, "s"))
    if driving.ram is None:
        rods, velocities, junctions, left = [pile], [0.0], [], driving.pile_head()
    else:
        rods, velocities, left = [driving.ram, pile], [driving.impact_velocity, 0.0], FreeEnd()
        junctions = [driving.ram_joint() or Contact()]
    index = len(rods) - 1
    loads: list[Any] = []
    right = FreeEnd() if toe is None else toe
    if soil is not None:
        if soil.penetration > pile.length * (1 + 1e-12):
            raise ValueError(f"penetration: the soil reaches {soil.penetration:.6g} m, deeper than the pile "
                             f"({pile.length:.6g} m long)")
        if toe is not None:
            raise ValueError("toe: the soil gives the toe's resistance; give a toe end condition only without soil")
        loads, right = soil_elements(soil, index, pile.length)
    probes = [Probe("head", index, 0.0)]
    for name, position in (gauges or {}).items():
        x = non_negative(f"gauges.{name}", position, "m")
        if x > pile.length:
            raise ValueError(f"gauges.{name}: {x:.6g} m is below the pile's toe ({pile.length:.6g} m)")
        probes.append(Probe(name, index, x))
    system = System(rods, velocities, junctions=junctions, left=left, right=right, loads=loads)
    dt = default_time_step(system, min_elements=PILE_ELEMENTS) if dt is None else positive("dt", dt, "s")
    outputs = Outputs(probes=probes, snapshot_every=1)
    return BlowSetup(Problem(system, TimeGrid.of(duration=duration, dt=dt), outputs), index, soil)


def soil_elements(soil: SoilResistance, pile_index: int, pile_length: float) -> tuple[list[Any], Any]:
    """The shaft resistance (a load on the pile) and the toe (its lower end) of ``soil``: depths below ground z
    become positions x = L - D + z from the pile head."""
    d = soil.dynamics
    top = pile_length - soil.penetration
    shaft = [] if not np.any(soil.unit_shaft > 0) else [
        ShaftResistance(pile_index, tuple(top + soil.depths), tuple(soil.unit_shaft), d.shaft_quake, None,
                        d.shaft_damping, d.damping_kind)]
    toe = SoilToe(soil.toe, d.toe_quake, d.unloading_quake, d.toe_damping, d.damping_kind)
    return shaft, toe


@dataclass(frozen=True, eq=False, repr=False)
class Blow:
    """What one blow did (:func:`drive_blow`). Times are step start times (s); head and gauge values are those
    held during each step. ``permanent_set`` (m, down positive) is ``None`` without soil."""

    result: SimulationResult
    pile: Rod
    pile_index: int
    soil: Optional[SoilResistance]
    head: ProbeHistory
    enthru: np.ndarray
    envelope: StressEnvelope
    permanent_set: Optional[float]

    def __repr__(self) -> str:
        blows = "" if self.permanent_set is None else (f", set {self.permanent_set * 1e3:.4g} mm, "
                                                       f"{self.blows_per_quarter_metre:.4g} blows/0.25 m")
        return f"Blow(EMX {self.emx / 1e3:.4g} kJ{blows}; {self.envelope!r})"

    @property
    def time(self) -> np.ndarray:
        """Step start times, s."""
        return self.result.time

    @property
    def emx(self) -> float:
        """The largest transferred energy at the head, J."""
        return float(self.enthru.max())

    @property
    def head_impedance(self) -> float:
        """Impedance Z = E A / c of the pile's first element, N s/m (for the Z v trace beside the head force)."""
        return float(self.result.lattice.impedance[self.result.lattice.rod_start[self.pile_index]])

    @property
    def gauges(self) -> dict[str, ProbeHistory]:
        """Force and velocity histories at the gauge stations (not the head)."""
        return {k: v for k, v in self.result.probes.items() if k != "head"}

    def _set(self) -> float:
        if self.permanent_set is None:
            raise ValueError("permanent_set: a blow without soil has no permanent set")
        return self.permanent_set

    @property
    def blows_per_quarter_metre(self) -> float:
        """0.25 m / set (``inf``: refusal)."""
        return blows_per_quarter_metre(self._set())

    @property
    def blows_per_foot(self) -> float:
        """0.3048 m / set."""
        return blows_per_foot(self._set())

    @property
    def blows_per_inch(self) -> float:
        """0.0254 m / set."""
        return blows_per_inch(self._set())


def drive_blow(pile: Rod, driving: DrivingSystem, soil: Optional[SoilResistance] = None, *,
               gauges: Optional[Mapping[str, float]] = None, duration: Optional[float] = None,
               dt: Optional[float] = None, toe: Any = None, backend: str = "numba") -> Blow:
    """Simulate one blow (arguments: :func:`blow_setup`) and evaluate it."""
    setup = blow_setup(pile, driving, soil, gauges=gauges, duration=duration, dt=dt, toe=toe)
    result = simulate(setup.problem, backend=backend, progress=False)
    return evaluate_blow(result, pile, setup.pile_index, soil)


def drive_blow_batch(pile: Rod, driving: DrivingSystem, soils: Iterable[SoilResistance], *,
                     gauges: Optional[Mapping[str, float]] = None, duration: Optional[float] = None,
                     dt: Optional[float] = None, backend: str = "numba") -> Iterator[Blow]:
    """One blow of ``driving`` on ``pile`` against each of ``soils`` (each from the same initial state; arguments
    as :func:`drive_blow`), yielded in order: equal to ``drive_blow`` for each soil (tested), the lattice of
    the pile and the driving system built once for all (the soil does not change it: its default time step
    and run length depend on the rods only). The bearing graph and drivability run their points through
    this."""
    lattice = None
    for soil in soils:
        setup = blow_setup(pile, driving, soil, gauges=gauges, duration=duration, dt=dt)
        lattice = setup.problem.lattice if lattice is None else lattice
        result = solve_compiled(setup.problem.compile(lattice), backend, progress=False)
        yield evaluate_blow(result, pile, setup.pile_index, soil)


def evaluate_blow(result: SimulationResult, pile: Rod, pile_index: int, soil: Optional[SoilResistance]) -> Blow:
    """The :class:`Blow` of a finished run ``result`` of :func:`blow_setup`'s problem."""
    lat, snaps = result.lattice, result.snapshots
    s, e = lat.rod_start[pile_index], lat.rod_start[pile_index + 1]
    lengths = lat.element_length[s:e]
    depth = np.cumsum(lengths) - 0.5 * lengths
    stress = snaps.force[s:e] / np.asarray(pile.area(depth))[:, None]
    head = result.probes["head"]
    enthru = transferred_energy(head.force, head.velocity, result.dt)
    permanent = None if soil is None else toe_permanent_set(result)
    return Blow(result, pile, pile_index, soil, head, enthru, stress_envelope(depth, snaps.time, stress), permanent)


def drive_blows(pile: Rod, driving: DrivingSystem, soil: SoilResistance, count: int, *,
                gauges: Optional[Mapping[str, float]] = None, duration: Optional[float] = None,
                dt: Optional[float] = None, backend: str = "numba", residual: bool = True) -> list[Blow]:
    """``count`` successive blows: each next blow starts from the soil state the previous one left (every node's
    static resistance and plastic set, :func:`rodimpact.direct.soil_result.next_blow`) and, with ``residual``,
    the pile's final element forces (the residual stress that balances the loaded soil), the pile at rest and
    the hammer as at the first blow. The soil is the same for every blow (the pile's advance, a few millimetres
    per blow, does not change it); each blow's ``permanent_set`` is its own, from where it started."""
    n = integer("count", count, 1, "blows")
    setup = blow_setup(pile, driving, soil, gauges=gauges, duration=duration, dt=dt)
    problem = setup.problem
    blows: list[Blow] = []
    for _ in range(n):
        result = simulate(problem, backend=backend, progress=False)
        blows.append(evaluate_blow(result, pile, setup.pile_index, soil))
        system = next_blow(result, problem.system.velocities, residual)
        if driving.ram is None:
            system = dataclasses.replace(system, left=driving.pile_head())
        problem = dataclasses.replace(problem, system=system)
    return blows


def toe_permanent_set(result: SimulationResult) -> float:
    """The toe's permanent set of a blow with soil, m: the plastic set u_p of the toe's soil spring at the end of
    the run (the set once the pile has come to rest; :class:`~rodimpact.direct.soil_result.SoilOutcome`)."""
    return float(result.soil.toe_set)
