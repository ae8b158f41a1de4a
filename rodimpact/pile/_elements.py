"""PLACEHOLDER until the branches pile-chain and pile-soil are merged: stand-ins with the agreed names and fields
of the kernel elements, so that the application layer can be built and its conversions tested. Replaced by imports
from ``rodimpact.rods`` at the merge."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence


@dataclass(frozen=True)
class PointMass:
    mass: float
    velocity: float = 0.0


@dataclass(frozen=True)
class Cushion:
    stiffness: float
    restitution: float = 1.0

    def __post_init__(self) -> None:
        if not self.stiffness > 0:
            raise ValueError(f"Cushion.stiffness: must be > 0, got {self.stiffness!r} N/m")
        if not 0 < self.restitution <= 1:
            raise ValueError(f"Cushion.restitution: must lie in (0, 1], got {self.restitution!r}")


@dataclass(frozen=True)
class LumpedEnd:
    items: Sequence[Any]


@dataclass(frozen=True)
class LumpedJoint:
    items: Sequence[Any]


@dataclass(frozen=True)
class ShaftResistance:
    rod: int
    depths: Sequence[float]
    unit_resistance: Sequence[float]
    quake: float
    unloading_quake: float | None = None
    damping: float | None = None
    damping_kind: str = "smith"
    resistance: Sequence[float] = ()
    plastic_set: Sequence[float] = ()


@dataclass(frozen=True)
class SoilToe:
    ultimate: float
    quake: float
    unloading_quake: float | None = None
    damping: float | None = None
    damping_kind: str = "smith"
    resistance: float = 0.0
    plastic_set: float = 0.0
