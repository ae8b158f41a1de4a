"""Forces acting on nodes inside rods: prescribed nodal forces and Coulomb friction of bearings."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence

from .._validate import finite, non_negative, positive
from .history import HistoryLike, as_history


@dataclass(frozen=True, eq=False)
class NodalForce:
    """A prescribed external force F(t) (N, positive in +x) at ``position`` (m from the left end of rod
    number ``rod``). It acts on the lattice node nearest to ``position`` (thesis Sec. 3.1: line loads are
    lumped to nodes, forces are constant during a step). End faces take :class:`~rodimpact.ForceEnd` instead.
    """

    rod: int
    position: float
    force: HistoryLike
    interpolation: str = "linear"

    def __post_init__(self) -> None:
        if not isinstance(self.rod, int) or self.rod < 0:
            raise ValueError(f"NodalForce.rod: must be a rod index >= 0, got {self.rod!r}")
        object.__setattr__(self, "position", finite("NodalForce.position", self.position, "m"))
        object.__setattr__(self, "force", as_history(self.force, "NodalForce.force", self.interpolation, "N"))


@dataclass(frozen=True)
class Bearings:
    """Coulomb friction of plain bearings on rod number ``rod`` (thesis eqs. 3.21-3.23).

    The total friction force F_R = mu m g (``friction_coefficient`` mu, the rod's mass m, ``gravity`` g in
    N/kg) -- or ``normal_load`` * mu if a normal load in N is given -- is shared equally by the interior nodes
    whose reference position lies in one of the ``spans`` [(x_start, x_end), ...] (m from the rod's left end).
    Each node's friction opposes its velocity; a node whose driving force is within its share sticks
    (v = 0) instead of chattering (set-valued Coulomb law, see docs/method.md).
    """

    rod: int
    spans: Sequence[tuple[float, float]]
    friction_coefficient: float
    gravity: float = 9.81
    normal_load: Optional[float] = None

    def __post_init__(self) -> None:
        if not isinstance(self.rod, int) or self.rod < 0:
            raise ValueError(f"Bearings.rod: must be a rod index >= 0, got {self.rod!r}")
        spans = []
        for i, span in enumerate(self.spans):
            if len(span) != 2:
                raise ValueError(f"Bearings.spans[{i}]: must be a pair (x_start, x_end), got {span!r}")
            a = finite(f"Bearings.spans[{i}][0]", span[0], "m")
            b = finite(f"Bearings.spans[{i}][1]", span[1], "m")
            if not a < b:
                raise ValueError(f"Bearings.spans[{i}]: x_start must be < x_end, got ({a}, {b})")
            spans.append((a, b))
        if not spans:
            raise ValueError("Bearings.spans: needs at least one span (x_start, x_end)")
        order = sorted(spans)
        for (a0, b0), (a1, b1) in zip(order, order[1:]):
            if a1 < b0:
                raise ValueError(f"Bearings.spans: bearings must not overlap, ({a0}, {b0}) and ({a1}, {b1}) do")
        object.__setattr__(self, "spans", tuple(spans))
        object.__setattr__(self, "friction_coefficient",
                           non_negative("Bearings.friction_coefficient", self.friction_coefficient))
        object.__setattr__(self, "gravity", positive("Bearings.gravity", self.gravity, "N/kg"))
        if self.normal_load is not None:
            object.__setattr__(self, "normal_load", non_negative("Bearings.normal_load", self.normal_load, "N"))
