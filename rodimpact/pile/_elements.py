"""PLACEHOLDER until the branch pile-chain is merged: stand-ins with the agreed names and fields of the lumped-chain
elements, so that the application layer can be built and its conversions tested. Replaced by imports from
``rodimpact.rods.conditions`` at the merge."""

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
