"""Forces acting on nodes inside rods: prescribed nodal forces and Coulomb friction of bearings."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence

from .._validate import finite
from .declared import check, choice, element, history, quantity
from .declared import rod as rod_index
from .declared import spans as span_list
from .history import HistoryLike

_ROD = "The rod: its name or its index (0 = first rod)."


@element("load", "force")
@dataclass(frozen=True, eq=False)
class NodalForce:
    """A prescribed force (positive in +x) at the node nearest to `position`.

    F(t) in N acts at ``position`` (m from the left end of rod number ``rod``), on the lattice node nearest to
    it (thesis Sec. 3.1: line loads are lumped to nodes, forces are constant during a step). End faces take
    :class:`~rodimpact.ForceEnd` instead.
    """

    rod: int = rod_index(_ROD)
    position: float = quantity("length", "Distance from the rod's left end.", bound=None)
    force: HistoryLike = history("force", "Force history.")
    interpolation: str = choice("How samples are interpolated: `linear` or `previous` (hold).",
                                ("linear", "previous"), "linear")

    def __post_init__(self) -> None:
        check(self)


@element("load", "bearings")
@dataclass(frozen=True)
class Bearings:
    """Coulomb friction of plain bearings (thesis eqs. 3.21-3.23): the total friction mu m g is shared by the
    nodes inside the spans. One table per rod.

    The total friction force F_R = mu m g (``friction_coefficient`` mu, the rod's mass m, ``gravity`` g in
    N/kg) -- or ``normal_load`` * mu if a normal load in N is given -- is shared equally by the interior nodes
    whose reference position lies in one of the ``spans`` [(x_start, x_end), ...] (m from the rod's left end).
    Each node's friction opposes its velocity; a node whose driving force is within its share sticks
    (v = 0) instead of chattering (set-valued Coulomb law, see docs/method.md).
    """

    rod: int = rod_index(_ROD)
    spans: Sequence[tuple[float, float]] = span_list("Bearing spans `[[start, end], ...]` from the rod's left end.")
    friction_coefficient: float = quantity("dimensionless", "Friction coefficient mu.", bound="non_negative")
    gravity: float = quantity("acceleration", "Gravitational acceleration g.", default=9.81)
    normal_load: Optional[float] = quantity("force", "Total normal load instead of the rod's weight.",
                                            bound="non_negative", default=None)

    def __post_init__(self) -> None:
        check(self)
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
