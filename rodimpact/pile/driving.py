"""The driving system: the ram (a rigid mass or an elastic rod), its impact velocity, the hammer cushion, the
helmet and the pile cushion, as the lumped chain at the pile head that the solver steps
(:class:`~rodimpact.rods.conditions.LumpedEnd`, or :class:`~rodimpact.rods.conditions.LumpedJoint` between a ram
rod and the pile).

Impact velocity of a freely falling ram: a ram of weight W = M g_n released from the stroke (drop height) h would
reach sqrt(2 g_n h) (free fall: M V^2 / 2 = W h); losses in the guides, the winch or the valve gear are lumped
into the hammer efficiency eta, the ratio of the ram's kinetic energy at impact to its potential energy W h, so
that ``V = sqrt(2 g_n eta h)``. A drop height
without an efficiency is refused: the efficiency of a hammer is a property of the hammer and its condition, to be
stated, not assumed. Drop, single-acting air/steam and hydraulic hammers are modelled this way; diesel hammers are
out of scope (combustion).

Signs: x runs down the pile from its head; the ram moves down, with positive velocity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

from .._validate import non_negative, positive
from ..rods.conditions import Cushion, LumpedEnd, LumpedJoint, PointMass
from ..rods.rod import Rod
from .hammers import Hammer
from .units import STANDARD_GRAVITY


def impact_velocity(drop_height: Any, efficiency: Any) -> float:
    """The ram's impact velocity ``sqrt(2 g_n eta h)`` in m/s for a drop height ``h`` (m) and a hammer efficiency
    ``eta`` in (0, 1]."""
    h = positive("drop_height", drop_height, "m")
    if efficiency is None:
        raise ValueError("efficiency: missing; a drop_height needs the hammer efficiency eta (0 < eta <= 1), the "
                         "ratio of the ram's kinetic energy at impact to W h: V = sqrt(2 g eta h)")
    eta = positive("efficiency", efficiency)
    if eta > 1.0:
        raise ValueError(f"efficiency: must lie in (0, 1] (kinetic energy at impact / W h), got {efficiency!r}")
    return math.sqrt(2.0 * STANDARD_GRAVITY * eta * h)


@dataclass(frozen=True)
class DrivingSystem:
    """What strikes the pile head.

    ``impact_velocity`` (m/s, > 0, downwards) of the ram: a rigid ``ram_mass`` (kg) or an elastic ``ram``
    (:class:`~rodimpact.Rod`, its lower end strikes); then, in this order towards the pile, an optional
    ``hammer_cushion`` (:class:`~rodimpact.rods.conditions.Cushion`: compression only, stiffness k on loading,
    k / e^2 on unloading), the ``helmet_mass`` (kg; 0 for none) and an optional ``pile_cushion``. Two rigid masses
    need a cushion between them and two cushions a mass between them. :meth:`dropped` and :meth:`from_hammer`
    derive the impact velocity from a drop height and an efficiency.
    """

    impact_velocity: float
    ram_mass: Optional[float] = None
    ram: Optional[Rod] = None
    hammer_cushion: Optional[Cushion] = None
    helmet_mass: float = 0.0
    pile_cushion: Optional[Cushion] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "impact_velocity", positive("DrivingSystem.impact_velocity",
                                                             self.impact_velocity, "m/s"))
        if (self.ram_mass is None) == (self.ram is None):
            raise ValueError("DrivingSystem.ram_mass: give exactly one of ram_mass (a rigid ram, kg) or ram (an "
                             "elastic ram, a Rod), " + ("not both" if self.ram is not None else "got neither"))
        if self.ram_mass is not None:
            object.__setattr__(self, "ram_mass", positive("DrivingSystem.ram_mass", self.ram_mass, "kg"))
        elif not isinstance(self.ram, Rod):
            raise TypeError(f"DrivingSystem.ram: must be a Rod, got {type(self.ram).__name__}")
        object.__setattr__(self, "helmet_mass", non_negative("DrivingSystem.helmet_mass", self.helmet_mass, "kg"))
        for name in ("hammer_cushion", "pile_cushion"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, Cushion):
                raise TypeError(f"DrivingSystem.{name}: must be a Cushion(stiffness, restitution) or None, got "
                                f"{type(value).__name__}")
        if self.ram_mass is not None and self.helmet_mass > 0 and self.hammer_cushion is None:
            raise ValueError("DrivingSystem.hammer_cushion: missing; a helmet needs a hammer cushion between it and "
                             "the ram (two rigid bodies cannot meet without a spring)")
        if self.helmet_mass == 0 and self.hammer_cushion is not None and self.pile_cushion is not None:
            raise ValueError("DrivingSystem.helmet_mass: must be > 0 between a hammer cushion and a pile cushion "
                             "(without a mass between them give their series stiffness as one cushion)")

    @classmethod
    def dropped(cls, drop_height: Any, efficiency: Any = None, **parts: Any) -> "DrivingSystem":
        """A ram falling from ``drop_height`` (m) with the hammer ``efficiency`` (required):
        ``V = sqrt(2 g_n eta h)``; ``parts``: the other fields (``ram_mass`` or ``ram``, cushions, helmet)."""
        return cls(impact_velocity(drop_height, efficiency), **parts)

    @classmethod
    def from_hammer(cls, hammer: Hammer, efficiency: Any, stroke: Any = None, **parts: Any) -> "DrivingSystem":
        """The rigid ram of a published :class:`~rodimpact.pile.Hammer` falling from ``stroke`` (m; default its
        rated stroke) with the hammer ``efficiency``; ``parts``: cushions and helmet."""
        h = hammer.stroke if stroke is None else stroke
        return cls(impact_velocity(h, efficiency), ram_mass=hammer.ram_mass, **parts)

    @property
    def kinetic_energy(self) -> float:
        """The ram's kinetic energy at impact, J."""
        mass = self.ram_mass if self.ram_mass is not None else self.ram.mass
        return 0.5 * mass * self.impact_velocity**2

    def head_parts(self) -> list[Any]:
        """The cushions and the helmet from the ram towards the pile (without the ram)."""
        parts: list[Any] = []
        if self.hammer_cushion is not None:
            parts.append(self.hammer_cushion)
        if self.helmet_mass > 0:
            parts.append(PointMass(self.helmet_mass, 0.0))
        if self.pile_cushion is not None:
            parts.append(self.pile_cushion)
        return parts

    def pile_head(self) -> LumpedEnd:
        """The pile head's end condition for a rigid ram: the lumped chain ram, cushions, helmet."""
        if self.ram_mass is None:
            raise ValueError("DrivingSystem.pile_head: the ram is a rod; use ram_joint() between it and the pile")
        return LumpedEnd([PointMass(self.ram_mass, self.impact_velocity)] + self.head_parts())

    def ram_joint(self) -> Optional[LumpedJoint]:
        """The joint between a ram rod and the pile: the cushions and the helmet (``None``: the ram strikes the
        pile head directly, a unilateral contact)."""
        if self.ram is None:
            raise ValueError("DrivingSystem.ram_joint: the ram is rigid; use pile_head()")
        parts = self.head_parts()
        return LumpedJoint(parts) if parts else None
