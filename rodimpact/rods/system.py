"""A system of rods listed left to right, with junctions, end conditions, loads and initial state."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Callable, Optional, Sequence

import numpy as np

from .._units import array_to_si
from .._validate import finite
from .conditions import Bonded, Contact, DeformableJoint, EndCondition, Junction, as_end_condition, as_junction
from .loads import Bearings, NodalForce
from .soil import ShaftResistance
from .plausibility import check_strikers
from .rod import Rod

#: the default junction (immutable, so one instance serves every system)
_TOUCHING = Contact()

#: Initial field of a rod: a number, a callable of x (m from the rod's left end) or per-element values.
FieldLike = float | Callable[[np.ndarray], np.ndarray] | Sequence[float] | np.ndarray


def _rod_number(ref: int | str, rods: Sequence[Rod], where: str) -> int:
    """The index of the rod that ``ref`` names: its index (0 = first) or its ``name``."""
    if isinstance(ref, str):
        names = [r.name for r in rods]
        if ref not in names:
            raise ValueError(f"{where}: no rod is named {ref!r}; the rods are named "
                             f"{', '.join(repr(n) for n in names if n) or '(none named)'}")
        if names.count(ref) > 1:
            raise ValueError(f"{where}: {names.count(ref)} rods are named {ref!r}; give the rod's index instead")
        return names.index(ref)
    if isinstance(ref, bool) or not isinstance(ref, (int, np.integer)) or not 0 <= ref < len(rods):
        raise ValueError(f"{where}: rod index {ref!r} does not exist (0..{len(rods) - 1}, or a rod's name)")
    return int(ref)


@dataclass(frozen=True, eq=False)
class InitialState:
    """Optional non-uniform initial state of one rod: ``force`` N(x) in N and ``velocity`` v(x) in m/s.

    Each is a number, a callable of the position x (m from the rod's left end, evaluated at element centres)
    or one value per lattice element. ``velocity`` overrides the rod's uniform initial velocity.
    """

    force: Optional[FieldLike] = None
    velocity: Optional[FieldLike] = None


@dataclass(frozen=True, eq=False)
class System:
    """Rods listed left to right, the junctions between neighbours and the conditions at the outer ends.

    Parameters
    ----------
    rods:
        The rods, left to right.
    velocities:
        Initial rigid-body velocity of each rod, m/s (positive to the right). A striker on the left moves with
        positive velocity.
    junctions:
        One per neighbouring pair: :class:`Contact` (default, unilateral) or :class:`Bonded`.
    left, right:
        Conditions at the outer left end of the first rod and the outer right end of the last rod
        (default free).
    loads:
        :class:`NodalForce`, :class:`Bearings` and :class:`~rodimpact.rods.soil.ShaftResistance` objects.
    initial:
        Optional per-rod :class:`InitialState` (``None`` entries for rods at rest/uniform velocity).
    """

    rods: Sequence[Rod]
    velocities: Sequence[float]
    junctions: Optional[Sequence[Junction | str]] = None
    left: EndCondition | str = "free"
    right: EndCondition | str = "free"
    loads: Sequence[NodalForce | Bearings | ShaftResistance] = field(default_factory=tuple)
    initial: Optional[Sequence[Optional[InitialState]]] = None

    def __post_init__(self) -> None:
        rods = [self.rods] if isinstance(self.rods, Rod) else list(self.rods)
        if not rods:
            raise ValueError("rods: give at least one Rod")
        for i, r in enumerate(rods):
            if not isinstance(r, Rod):
                raise TypeError(f"rods[{i}]: must be a Rod, got {type(r).__name__}")
        given = self.velocities
        if not (isinstance(given, (list, tuple)) and all(type(v) is float for v in given)):   # else: plain floats
            given = np.atleast_1d(np.asarray(array_to_si("velocities", given, "m/s"), dtype=object))
        if len(given) != len(rods):
            raise ValueError(f"velocities: need one initial velocity per rod ({len(rods)}), got {len(given)}")
        vel = tuple(finite(f"velocities[{i}]", v, "m/s") for i, v in enumerate(given))
        n_j = len(rods) - 1
        juncs = [_TOUCHING] * n_j if self.junctions is None else list(self.junctions)
        if len(juncs) != n_j:
            raise ValueError(f"junctions: need one per neighbouring pair ({n_j}), got {len(juncs)}")
        juncs = tuple(as_junction(j, f"junctions[{i}]") for i, j in enumerate(juncs))
        for i, j in enumerate(juncs):
            if isinstance(j, DeformableJoint):
                j.check_fits(min(float(rods[i].area(rods[i].length)), float(rods[i + 1].area(0.0))), f"junctions[{i}]")
        loads = list(self.loads)
        for i, ld in enumerate(loads):
            if not isinstance(ld, (NodalForce, Bearings, ShaftResistance)):
                raise TypeError(f"loads[{i}]: must be NodalForce, Bearings or ShaftResistance, got "
                                f"{type(ld).__name__}")
            ld = loads[i] = replace(ld, rod=_rod_number(ld.rod, rods, f"loads[{i}].rod"))
            if isinstance(ld, NodalForce) and not 0.0 < ld.position < rods[ld.rod].length:
                raise ValueError(f"loads[{i}].position: must lie inside rod {ld.rod}, 0 < x < "
                                 f"{rods[ld.rod].length:.6g} m, got {ld.position:.6g} m (end faces take ForceEnd)")
            if isinstance(ld, Bearings):
                for a, b in ld.spans:
                    if a < 0.0 or b > rods[ld.rod].length:
                        raise ValueError(f"loads[{i}].spans: span ({a}, {b}) m lies outside rod {ld.rod} "
                                         f"(0 .. {rods[ld.rod].length:.6g} m)")
            if isinstance(ld, ShaftResistance):
                ld.check_fits(rods[ld.rod].length, f"loads[{i}]")
        bearing_rods = [ld.rod for ld in loads if isinstance(ld, Bearings)]
        if len(bearing_rods) != len(set(bearing_rods)):
            raise ValueError("loads: give all bearings of one rod in a single Bearings(spans=[...]) so that the "
                             "friction force mu*m*g is shared once (thesis eq. 3.23)")
        initial = [None] * len(rods) if self.initial is None else list(self.initial)
        if len(initial) != len(rods):
            raise ValueError(f"initial: need one entry (InitialState or None) per rod ({len(rods)}), got {len(initial)}")
        for i, st in enumerate(initial):
            if st is not None and not isinstance(st, InitialState):
                raise TypeError(f"initial[{i}]: must be InitialState or None, got {type(st).__name__}")
        object.__setattr__(self, "rods", tuple(rods))
        object.__setattr__(self, "velocities", vel)
        object.__setattr__(self, "junctions", juncs)
        object.__setattr__(self, "left", as_end_condition(self.left, "left"))
        object.__setattr__(self, "right", as_end_condition(self.right, "right"))
        object.__setattr__(self, "loads", tuple(loads))
        object.__setattr__(self, "initial", tuple(initial))
        check_strikers(self.rods, self.velocities)

    @classmethod
    def struck(cls, rods: Rod | Sequence[Rod], far_end: EndCondition | str = "free",
               velocity: float | Sequence[float] = 0.0, *, junctions: Optional[Sequence[Junction | str]] = None,
               loads: Sequence[NodalForce | Bearings] = (),
               initial: Optional[Sequence[Optional[InitialState]]] = None) -> System:
        """The system a striker hits, as :func:`~rodimpact.synthesize` and :func:`~rodimpact.design` take it: the
        ``rods`` listed from the impact face outwards (the free left end is the impact face), joined by
        :class:`~rodimpact.Bonded` joints unless ``junctions`` says otherwise, with the ``far_end`` condition on
        the right and the initial ``velocity`` (m/s, positive towards the far end: one value for all rods or one
        per rod).

        >>> import rodimpact as ri
        >>> bar = ri.Rod.from_impedance([79.7e3] * 100, dt=1e-6)
        >>> ri.System.struck(bar, far_end="nonreflecting").right
        NonReflectingEnd(impedance=None)
        """
        parts = [rods] if isinstance(rods, Rod) else list(rods) if isinstance(rods, (list, tuple)) else None
        if parts is None or not parts:
            raise TypeError(f"rods: must be a Rod or a list of Rods (from the impact face outwards), "
                            f"got {type(rods).__name__}")
        if np.ndim(velocity) == 0:
            velocities = [finite("velocity", velocity, "m/s")] * len(parts)
        else:
            velocities = [finite(f"velocity[{i}]", v, "m/s") for i, v in enumerate(velocity)]
            if len(velocities) != len(parts):
                raise ValueError(f"velocity: need one value per struck rod ({len(parts)}), got {len(velocities)}")
        if junctions is None:
            junctions = [Bonded()] * (len(parts) - 1)
        return cls(parts, velocities, junctions, "free", far_end, tuple(loads), initial)

    @property
    def n_rods(self) -> int:
        """Number of rods."""
        return len(self.rods)

    def rod_offsets(self) -> np.ndarray:
        """Global x of each rod's left end (m): with junctions, rod 0 ends at x = 0 (the first contact face),
        the others follow left to right separated by their initial gaps; a single rod starts at x = 0."""
        starts = [0.0] if self.n_rods == 1 else [-self.rods[0].length]
        for rod, junction in zip(self.rods[:-1], self.junctions):
            starts.append(starts[-1] + rod.length + (junction.gap if isinstance(junction, Contact) else 0.0))
        return np.array(starts)
