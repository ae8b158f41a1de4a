"""The struck system (rod 2 of thesis Fig. 4.1) as the inverse problem sees it.

The struck system is everything to the right of the impact face: one or more rods listed from the impact face
outwards (bonded by default), their initial velocities, end condition at the far end, nodal loads and an
optional initial state. Its left end is the impact face; during synthesis it is driven there by the
prescribed impact force (:class:`~rodimpact.ForceEnd`) and its face velocity is read back.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from .._validate import fits_in_memory, non_negative
from ..direct.result import Probe
from ..direct.problem import Problem
from ..direct.recording import Outputs
from ..direct.simulate import simulate
from ..lattice.lattice import Lattice, build_lattice
from ..rods.conditions import (BitRockEnd, Bonded, Contact, FixedEnd, ForceEnd, FreeEnd, LumpedEnd, LumpedJoint,
                               NonReflectingEnd, SpringDashpot, SpringEnd)
from ..rods.rod import Rod
from ..rods.system import System
from ._rectangular import chain_response


def as_struck_system(struck: Any) -> System:
    """The struck system of :func:`~rodimpact.synthesize` and :func:`~rodimpact.design` as a :class:`System`
    whose left end is the (free) impact face: a ready :class:`System` (see :meth:`System.struck
    <rodimpact.rods.system.System.struck>`), or a :class:`Rod` or rods listed from the impact face outwards,
    bonded, at rest, with a free far end."""
    if isinstance(struck, System):
        if not isinstance(struck.left, FreeEnd):
            raise ValueError("struck.left: the left end of the struck system is the impact face; give left='free' "
                             f"(it is driven by the contact force), got {struck.left!r}")
        _refuse_lumped(struck)
        return struck
    if isinstance(struck, Rod) or (isinstance(struck, (list, tuple)) and struck):
        for i, r in enumerate([struck] if isinstance(struck, Rod) else struck):
            if not isinstance(r, Rod):
                raise TypeError(f"struck[{i}]: must be a Rod, got {type(r).__name__}")
        return System.struck(struck)
    raise TypeError(f"struck: must be a Rod, a list of Rods (from the impact face outwards) or a System such as "
                    f"ri.System.struck(rods, far_end=...), got {type(struck).__name__}")


def _refuse_lumped(struck: System) -> None:
    """Refuse lumped chains (point masses and cushions): synthesis, force transformation and design's exact
    gradients do not cover them (their cushions are nonlinear and the adjoint has no transpose of the chain);
    ``simulate`` takes them."""
    places = [("struck.right", struck.right)] + [(f"struck.junctions[{i}]", j) for i, j in enumerate(struck.junctions)]
    for where, p in places:
        if isinstance(p, (LumpedEnd, LumpedJoint)):
            raise ValueError(f"{where}: a {type(p).__name__} (point masses and cushions) is not supported by "
                             "synthesize, transform_force and design; simulate takes it")


#: where the struck-system keywords of synthesize, transform_force and design went (rodimpact._moved)
STRUCK_KEYWORDS = {
    "far_end": "far_end: give the struck system as one System: ri.System.struck(rods, far_end=...)",
    "struck_velocity": "struck_velocity: give the struck system as one System: ri.System.struck(rods, velocity=...)",
    "junctions": "junctions: give the struck system as one System: ri.System.struck(rods, junctions=...)",
    "loads": "loads: give the struck system as one System: ri.System.struck(rods, loads=...)",
    "initial": "initial: give the struck system as one System: ri.System.struck(rods, initial=...)",
}


def driven(system: System, force_windows: np.ndarray, dt: float) -> System:
    """The struck system with its impact face driven by the window values (held for two steps each)."""
    t = 2.0 * dt * np.arange(force_windows.size)
    if t.size == 1:
        left = ForceEnd(float(force_windows[0]))
    else:
        left = ForceEnd((t, np.asarray(force_windows, dtype=float)), interpolation="previous")
    return dataclasses.replace(system, left=left)


def linearized(system: System) -> tuple[System, list[str]]:
    """A linear version of the struck system for superposition (rectangular responses, thesis Sec. 4.1.2):
    unilateral contacts become bonded joints, a bit-rock interface its loading spring k1. Returns the
    system and a list of what was changed."""
    notes = []
    junctions = []
    for i, j in enumerate(system.junctions):
        if isinstance(j, Contact):
            if j.gap != 0.0:
                raise ValueError(f"junctions[{i}]: a struck system with an initial gap ({j.gap} m) is not linear "
                                 f"and cannot be transformed; close the gap or use Bonded()")
            notes.append(f"junction {i}: Contact treated as bonded (valid while it stays compressed)")
            junctions.append(Bonded())
        elif isinstance(j, SpringDashpot) and j.compression_only:
            notes.append(f"junction {i}: compression-only SpringDashpot treated as pulling too (valid while it "
                         "stays compressed)")
            junctions.append(SpringDashpot(j.stiffness, j.damping))
        else:
            junctions.append(j)
    right = system.right
    if isinstance(right, BitRockEnd):
        notes.append(f"far end: BitRockEnd treated as its loading spring k1 = {right.loading_stiffness:.6g} N/m "
                     "(valid while the bit keeps penetrating)")
        right = SpringEnd(right.loading_stiffness)
    return dataclasses.replace(system, junctions=tuple(junctions), right=right), notes


def at_rest(system: System) -> System:
    """The same system without initial velocities, initial state and loads (for impulse responses)."""
    return dataclasses.replace(system, velocities=tuple(0.0 for _ in system.rods), loads=(), initial=None)


def has_free_motion(system: System) -> bool:
    """True when the system moves or is loaded on its own (non-zero free response possible)."""
    return bool(system.loads) or any(s is not None for s in system.initial) or any(
        v != 0.0 for v in system.velocities)


def face_impedance(system: System, dt: float) -> float:
    """Impedance of the struck system's first lattice element (Z~_1 of the thesis), N s/m."""
    return float(build_lattice(system, dt).impedance[0])


def _is_semi_infinite_uniform(system: System, lattice: Lattice, n: int) -> bool:
    """True when, for the 2n steps of the synthesis, the face sees a uniform bar at uniform velocity.

    Reflections from depth m return after 2m steps, but a disturbance present at t = 0 at depth m (a velocity
    jump between rods, a far end that acts on a moving bar) arrives after m steps. So: no loads, no initial
    state, every rod at the same velocity, and either the first rod is uniform over >= n elements with a far
    end that is quiet (free, non-reflecting, or at rest and passive) or >= 2n elements deep, or the system is
    one uniform rod with a matched non-reflecting far end.
    """
    if system.loads or any(s is not None for s in system.initial):
        return False
    v0 = system.velocities[0]
    if any(v != v0 for v in system.velocities):
        return False
    z = lattice.impedance
    right = system.right
    if system.n_rods == 1 and isinstance(right, NonReflectingEnd) and np.all(z == z[0]):
        return right.impedance is None or right.impedance == z[0]
    if int(lattice.rod_start[1]) < n or not np.all(z[:n] == z[0]):
        return False
    quiet = isinstance(right, (FreeEnd, NonReflectingEnd)) or (
        v0 == 0.0 and isinstance(right, (FixedEnd, SpringEnd, BitRockEnd)))
    return quiet or z.size >= 2 * n


@dataclass(frozen=True)
class FaceResponse:
    """Velocity of the impact face of the struck system driven by the window forces, one value per step."""

    velocity: np.ndarray      # (2n,) m/s, positive away from the striker
    face_impedance: float     # Z~_1, N s/m
    method: str               # "analytic" or "simulated"


def face_response(system: System, force_windows: np.ndarray, dt: float, backend: str = "numba") -> FaceResponse:
    """Face velocity history V(k), k = 0..2n-1, of the struck system driven by ``force_windows``.

    For a uniform bar that the waves cannot leave within 2n steps (or a matched semi-infinite one), at
    uniform velocity v~ and without loads, V = v~ - N / Z~ (a right-going wave: dN = -Z dv); for a passive
    chain at rest the lattice is swept where it can reach the face within 2n steps
    (:func:`rodimpact.inverse._rectangular.chain_response`); otherwise the direct solver runs once with a
    :class:`~rodimpact.ForceEnd` at the face.
    """
    n = force_windows.size
    lat = build_lattice(system, dt)
    z1 = float(lat.impedance[0])
    if _is_semi_infinite_uniform(system, lat, n):
        v0 = system.velocities[0]
        return FaceResponse(v0 - np.repeat(force_windows, 2) / z1, z1, "analytic")
    fast = chain_response(system, 0, dt, 2 * n, np.repeat(force_windows, 2)) if backend == "numba" else None
    if fast is not None:         # the same lattice equations, only where they reach the face in time
        return FaceResponse(fast[1], z1, "simulated")
    res = simulate(Problem.of(driven(system, force_windows, dt), steps=2 * n, dt=dt,
                              allow_discretization_error=True), backend=backend)   # at the user's dt: a warning
    return FaceResponse(np.asarray(res.end_velocity["left"], dtype=float), z1, "simulated")


@dataclass(frozen=True)
class Location:
    """A lattice node of the struck system at a prescribed distance from the impact face."""

    requested: float      # distance asked for, m
    used: float           # distance of the node actually used, m
    rod: int              # rod index in the struck system
    local: float          # node position from that rod's left end, m
    node: int             # node index counted in elements from the impact face (= dead time in steps)
    element_left: int     # global index of the element left of the node (-1 at the impact face)


def locate(system: System, position: float, dt: float) -> Location:
    """Find the lattice node nearest to ``position`` (m from the impact face into the struck system)."""
    p = non_negative("position", position, "m")
    lengths = np.array([r.length for r in system.rods])
    for i, j in enumerate(system.junctions):
        if isinstance(j, Contact) and j.gap != 0.0:
            raise ValueError(f"position: the struck system has an initial gap at junction {i}; distances into it "
                             "are ambiguous")
    starts = np.concatenate([[0.0], np.cumsum(lengths)])
    total = float(starts[-1])
    if p > total * (1 + 1e-12):
        raise ValueError(f"position: must lie within the struck system, 0 <= position <= {total:.6g} m, got {p:.6g} m")
    rod = int(min(np.searchsorted(starts, p, side="right") - 1, len(lengths) - 1))
    lat = build_lattice(system, dt)
    m, x_node = lat.nearest_node(rod, p - starts[rod])
    # the lattice's node positions carry its discretization error: keep the node inside the rod's geometry (a
    # probe there is checked against the rod's length and finds the same nearest node)
    x_node = float(min(max(x_node, 0.0), lengths[rod]))
    node = int(lat.rod_start[rod] + m)
    return Location(p, float(starts[rod] + x_node), rod, x_node, node, node - 1)


def position_probe(location: Location, rod_offset: int = 0) -> Probe:
    """A probe at the located node (``rod_offset`` shifts the rod index when rods are prepended)."""
    return Probe("synthesis_position", location.rod + rod_offset, location.local)


def position_quantity(quantity: str, force: np.ndarray, velocity: np.ndarray, z_left: float,
                      force0: float = 0.0, velocity0: float = 0.0) -> np.ndarray:
    """The prescribed quantity at a node from its force and velocity histories.

    ``"force"``: the normal force N (tension positive). ``"incident"``: the force wave arriving from the
    impact side, N_i = ((N - N0) - Z (V - v0)) / 2 with Z the impedance of the element on the impact side of
    the node and (N0, v0) that element's initial state (a right-going wave has dN = -Z dv).
    """
    if quantity == "force":
        return force
    return 0.5 * ((force - force0) - z_left * (velocity - velocity0))


def simulate_observed(system: System, location: Optional[Location], quantity: str, steps: int, dt: float,
                      backend: str = "numba") -> tuple[Any, np.ndarray]:
    """Simulate the complete impact ``system`` (striker = rod 0) for ``steps`` and return the result and the
    observed history: the contact force at the impact face (``location`` None) or the ``quantity`` at the
    located node of the struck system (see :func:`position_quantity`)."""
    probes = [] if location is None else [position_probe(location, 1)]
    outputs = Outputs(probes=probes, snapshot_times=[0.0] if location is not None and quantity == "incident" else None)
    sim = simulate(Problem.of(system, steps=steps, dt=dt, outputs=outputs,        # at the user's dt, as
                              allow_discretization_error=True), backend=backend)  # synthesize: a warning
    if location is None:
        return sim, np.asarray(sim.junction_force[0], dtype=float)
    p = sim.probe("synthesis_position")
    k_left = sim.lattice.rod_start[1] + location.element_left
    n0 = v0 = 0.0
    if quantity == "incident":
        n0 = float(sim.snapshots.force[k_left, 0])
        v0 = float(sim.snapshots.velocity[k_left, 0])
    return sim, np.asarray(position_quantity(quantity, p.force, p.velocity, float(sim.lattice.impedance[k_left]),
                                             n0, v0), dtype=float)


def with_striker(system: System, striker: Rod, striker_velocity: float) -> System:
    """The complete impact system: the striker (left, unilateral contact at the impact face) plus the struck
    system; loads are renumbered for the prepended rod."""
    loads = tuple(dataclasses.replace(ld, rod=ld.rod + 1) for ld in system.loads)
    return System((striker,) + tuple(system.rods), (striker_velocity,) + tuple(system.velocities),
                  (Contact(),) + tuple(system.junctions), "free", system.right, loads,
                  (None,) + tuple(system.initial))


def window_count_check(n: Any) -> int:
    """Validate a number of windows/elements."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise ValueError(f"n: must be an integer number of striker elements >= 1, got {n!r}")
    # per element: the target, the face response of 2n steps, the peeled waves and the reported quantities
    fits_in_memory("n", 400.0 * n, f"{n} striker elements", "use fewer, longer elements (a larger dt)")
    return int(n)

