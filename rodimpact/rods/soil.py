"""Soil resistance of a driven pile: Smith's (1960) elasto-plastic spring with a dashpot, along the shaft
(:class:`ShaftResistance`, a load on interior lattice nodes) and at the toe (:class:`SoilToe`, an end condition).

Conventions (docs/soil.md). The pile is a rod whose left end is the head and whose right end is the toe, so
"down" is +x. The resistance R > 0 opposes downward motion: at a shaft node the soil force on the pile is -R
(in +x), at a toe (an outer end, described with the outward displacement delta and velocity w as every end
condition) the end force is N = -R. u is the node's displacement (m, +x; at an end the outward delta).

The law (Smith 1960: R = R_s (1 + J_s V)) is R = R_s + R_d:

* static part R_s, elasto-plastic: R_s = k (u - u_p) clipped to [-R_u, R_u] along the shaft and to [0, R_u]
  at the toe (compression only: the toe separates from the soil instead of pulling). The stiffness is
  k = R_u / q (``quake`` q) while |R_s| grows ("loading") and R_u / q_u (``unloading_quake`` q_u <= q) while it
  falls towards zero ("unloading"). u_p, the plastic set, is where the current unloading line reaches R_s = 0:
  u_p = u - R_s / k_u (at the toe, while separated, the point where contact resumes). It is
  carried over between steps and, through :meth:`SmithSoil.at`, between blows. q_u > q is refused: unloading
  softer than loading would give back more work than was put in (a non-passive soil).
* damping part R_d (``damping_kind``):

  - ``"smith"``: R_d = J_s |R_s| V (J_s in s/m). For R_s >= 0 (the toe always, the shaft while pushed down)
    this is Smith's product R_s (1 + J_s V). Smith's product with R_s < 0 (the shaft after a rebound) pushes
    the pile along its motion, gives energy to the pile and makes the node equation non-monotone; with |R_s|
    the shaft law is the mirror image of the downward one and passive (a choice of rodimpact, not a citation).
  - ``"smith-viscous"``: R_d = J_sv R_u V (J_sv in s/m): a linear dashpot of constant c = J_sv R_u.
  - ``"case"``: R_d = J_c Z V (J_c a pure number, Z the pile impedance in N s/m). At the toe Z is that of
    the toe element. Along the shaft a dashpot J_c Z at every node would grow with the number of nodes, so
    the shaft's total J_c Z (Z at each node: the mean of its two elements) is shared in proportion to the
    nodes' ultimate resistance, c_i = J_c Z_i R_u,i / R_u,shaft (the distribution GRLWEAP describes for its
    Case damping option; not verified against the manual here).

Defaults. The quake q = 2.54 mm (0.1 in), the shaft damping 0.05 s/ft = 0.164 s/m and the toe damping
0.15 s/ft = 0.492 s/m are FHWA GEC-12's defaults for a non-cohesive soil (FHWA-NHI-16-009, Vol. II, sec. 12.5
and 12.8; the ``gec12`` set of :mod:`rodimpact.pile.soil_sets`, which a test keeps equal to them). Read at second
hand, from quotations of GEC-12 in a third-party report (docs/pile-driving.md, "Soil parameters and their
sources"); Smith (1960), to whom they are often attributed, could not be read. The toe's default quake, the
same 0.1 in, is GRLWEAP's toe quake for non-displacement piles ("0.1"/2.5 mm non-displacement", Rausche,
GRLWEAP Fundamentals, slide 40, read at second hand likewise: the ``grlweap`` set); displacement piles want D/120
in very dense or hard soil and D/60 in soft or loose soil (``SoilDynamics.published``). The Case damping has no default (J_c must be
given).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from .._validate import finite, non_negative
from .declared import check, choice, element, quantities, quantity
from .conditions import EndCondition
from .declared import rod as rod_index

#: damping laws (module docstring); the kernel codes of :mod:`rodimpact.direct.soil`
DAMPING_KINDS = ("smith", "smith-viscous", "case")
#: GEC-12's default quake, 0.10 in (m); see the module docstring for the source
DEFAULT_QUAKE = 0.1 * 0.0254
#: GEC-12's shaft damping of a non-cohesive soil, 0.05 s/ft in s/m; see the module docstring
DEFAULT_SHAFT_DAMPING = 0.05 / 0.3048
#: GEC-12's toe damping, 0.15 s/ft in s/m; see the module docstring
DEFAULT_TOE_DAMPING = 0.15 / 0.3048

_KIND_DOC = "Damping law: `smith` (J_s abs(R_s) V), `smith-viscous` (J_sv R_u V) or `case` (J_c Z V)."
_DAMPING_DOC = ("Damping factor J: s/m for `smith` and `smith-viscous`, a pure number for `case`; default "
                "GEC-12's for a non-cohesive soil (0.164 s/m shaft, 0.492 s/m toe) except for `case`, which "
                "needs it.")


def _check_kind(owner: str, kind: object) -> None:
    """A clear message with a did-you-mean for an unknown damping kind."""
    if kind in DAMPING_KINDS:
        return
    near = difflib.get_close_matches(str(kind).strip().lower(), DAMPING_KINDS, n=1, cutoff=0.5)
    hint = f" (did you mean {near[0]!r}?)" if near else ""
    raise ValueError(f"{owner}.damping_kind: must be one of {', '.join(map(repr, DAMPING_KINDS))}, got "
                     f"{kind!r}{hint}")


def _check_quakes(obj: object, owner: str) -> None:
    """Fill the unloading quake (default q) and refuse q_u > q (a soil that gives out work)."""
    q = obj.quake
    qu = q if obj.unloading_quake is None else obj.unloading_quake
    if qu > q:
        raise ValueError(f"{owner}.unloading_quake: must be <= {owner}.quake for a passive soil, got "
                         f"unloading_quake = {qu:.6g} m > quake = {q:.6g} m; unloading softer than loading "
                         f"would give back work that was never put in")
    object.__setattr__(obj, "unloading_quake", qu)


def _damping(obj: object, owner: str, default: float) -> None:
    """Fill the kind-dependent default damping factor (Case damping has none)."""
    if obj.damping is None:
        if obj.damping_kind == "case":
            raise ValueError(f"{owner}.damping: the Case damping factor J_c (a pure number) has no default; "
                             f"give it, e.g. damping = 0.3")
        object.__setattr__(obj, "damping", default)


@dataclass(frozen=True)
class SmithSoil:
    """Smith's soil law at one node (module docstring): ultimate resistance R_u (N, >= 0), quake q (m, > 0),
    unloading quake q_u (m, 0 < q_u <= q, default q), damping factor J and its ``damping_kind``, and whether it
    acts in ``compression_only`` (the toe). ``impedance`` (N s/m) is the Z of the Case law.

    The state carried over between blows is (``resistance``, ``plastic_set``): the static resistance R_s at
    the start (N) and the plastic set u_p measured from the start position (m). :meth:`static` is a plain
    reference of the static part (for one monotone move)."""

    ultimate: float
    quake: float
    unloading_quake: Optional[float] = None
    damping: float = 0.0
    damping_kind: str = "smith-viscous"
    compression_only: bool = False
    impedance: float = 0.0

    def __post_init__(self) -> None:
        _check_kind("SmithSoil", self.damping_kind)
        object.__setattr__(self, "ultimate", non_negative("SmithSoil.ultimate", self.ultimate, "N"))
        object.__setattr__(self, "quake", _positive_length("SmithSoil.quake", self.quake))
        if self.unloading_quake is not None:
            object.__setattr__(self, "unloading_quake",
                               _positive_length("SmithSoil.unloading_quake", self.unloading_quake))
        _check_quakes(self, "SmithSoil")
        object.__setattr__(self, "damping", non_negative("SmithSoil.damping", self.damping, ""))
        object.__setattr__(self, "impedance", non_negative("SmithSoil.impedance", self.impedance, "N s/m"))

    @property
    def loading_stiffness(self) -> float:
        """k = R_u / q, N/m."""
        return self.ultimate / self.quake

    @property
    def unloading_stiffness(self) -> float:
        """k_u = R_u / q_u, N/m."""
        return self.ultimate / self.unloading_quake

    def static(self, u: float) -> float:
        """R_s after a monotone move from rest (R_s = 0, u_p = 0) to displacement u (m): k u clipped."""
        lo = 0.0 if self.compression_only else -self.ultimate
        return float(min(max(self.loading_stiffness * u, lo), self.ultimate))


def _positive_length(name: str, value: object) -> float:
    x = finite(name, value, "m")
    if not x > 0.0:
        raise ValueError(f"{name}: must be > 0, got {x!r} m (a quake of zero is a rigid-plastic soil: give a "
                         f"small positive quake instead)")
    return x


def _check_law(obj: object, owner: str, default_damping: float) -> None:
    """The checks that a soil element shares: the damping kind (with a did-you-mean), the quake > 0 (with the
    rigid-plastic hint: a zero quake has no loading stiffness), the declared fields, q_u <= q and the default
    damping factor of the kind."""
    _check_kind(owner, obj.damping_kind)
    object.__setattr__(obj, "quake", _positive_length(f"{owner}.quake", obj.quake))
    check(obj)
    _check_quakes(obj, owner)
    _damping(obj, owner, default_damping)


@element("end", "soil-toe")
@dataclass(frozen=True)
class SoilToe(EndCondition):
    """Smith soil at a pile's toe (normally the right end): compression-only elasto-plastic spring with a
    dashpot (:mod:`rodimpact.rods.soil`).

    The soil pushes back on the toe with R = R_s + R_d (the end force is N = -R): R_s = k (delta - u_p) clipped to
    [0, R_u] with k = R_u / q on loading and R_u / q_u on unloading; the toe separates instead of pulling.
    ``resistance`` and ``plastic_set`` are the state at the start (the end of the previous blow:
    :func:`rodimpact.direct.soil_result.next_blow`); the plastic set is measured from the toe's start position.
    """

    ultimate: float = quantity("force", "Ultimate toe resistance R_u.", bound="non_negative")
    quake: float = quantity("length", "Quake q (displacement to reach R_u on loading).", default=DEFAULT_QUAKE)
    unloading_quake: Optional[float] = quantity("length", "Unloading quake q_u <= q; default q.", default=None)
    damping: Optional[float] = quantity("dimensionless", _DAMPING_DOC, bound="non_negative", default=None)
    damping_kind: str = choice(_KIND_DOC, DAMPING_KINDS, "smith")
    resistance: float = quantity("force", "Static resistance R_s at the start (0 <= R_s <= R_u).",
                                 bound="non_negative", default=0.0)
    plastic_set: float = quantity("length", "Plastic set u_p at the start, from the toe's start position.",
                                  bound=None, default=0.0)
    code = 8

    def __post_init__(self) -> None:
        _check_law(self, "SoilToe", DEFAULT_TOE_DAMPING)
        if self.resistance > self.ultimate:
            raise ValueError(f"SoilToe.resistance: must lie in [0, ultimate = {self.ultimate:.6g} N], got "
                             f"{self.resistance:.6g} N")

    def law(self, impedance: float) -> SmithSoil:
        """The toe's :class:`SmithSoil` for a toe element of ``impedance`` (N s/m)."""
        return SmithSoil(self.ultimate, self.quake, self.unloading_quake, self.damping, self.damping_kind, True,
                         impedance)


@element("load", "shaft-soil")
@dataclass(frozen=True, eq=False)
class ShaftResistance:
    """Smith soil along a pile's shaft: ultimate resistance per unit length piecewise constant between depths,
    lumped to the interior lattice nodes (:mod:`rodimpact.rods.soil`).

    ``unit_resistance[i]`` (N/m, >= 0) acts between ``depths[i]`` and ``depths[i + 1]`` (m from the rod's left
    end, the pile head; increasing, within the rod). Each interior node takes the resistance of the half
    elements on either side; the half elements at the rod's ends go to the nearest interior node (the end nodes
    are the head and the toe, which has its own :class:`SoilToe`). Every node gets the same quake, unloading
    quake and damping (its R_u is its share). ``resistance`` and ``plastic_set`` are the state of the nodes at
    the start (one value per interior node of the rod, left to right; empty: at rest), as
    :func:`rodimpact.direct.soil_result.next_blow` fills them.
    """

    rod: int = rod_index("The pile: its name or its index (0 = first rod).")
    depths: Sequence[float] = quantities("length", "Layer boundaries from the rod's left end (increasing).")
    unit_resistance: Sequence[float] = quantities("force per length", "Ultimate resistance per unit length "
                                                                      "of each layer (one fewer than depths).")
    quake: float = quantity("length", "Quake q (displacement to reach R_u on loading).", default=DEFAULT_QUAKE)
    unloading_quake: Optional[float] = quantity("length", "Unloading quake q_u <= q; default q.", default=None)
    damping: Optional[float] = quantity("dimensionless", _DAMPING_DOC, bound="non_negative", default=None)
    damping_kind: str = choice(_KIND_DOC, DAMPING_KINDS, "smith")
    resistance: Sequence[float] = quantities("force", "Static resistance R_s of each interior node at the "
                                                      "start (empty: 0).", default=())
    plastic_set: Sequence[float] = quantities("length", "Plastic set u_p of each interior node at the start "
                                                        "(empty: 0).", default=())

    def __post_init__(self) -> None:
        _check_law(self, "ShaftResistance", DEFAULT_SHAFT_DAMPING)
        d, r = self.depths, self.unit_resistance
        if len(d) < 2:
            raise ValueError(f"ShaftResistance.depths: needs at least two depths (the top and bottom of a layer), "
                             f"got {list(d)}")
        for i in range(len(d) - 1):
            if not d[i + 1] > d[i]:
                raise ValueError(f"ShaftResistance.depths: must increase, got depths[{i}] = {d[i]:.6g} m and "
                                 f"depths[{i + 1}] = {d[i + 1]:.6g} m")
        if d[0] < 0.0:
            raise ValueError(f"ShaftResistance.depths[0]: must be >= 0 (m from the pile head), got {d[0]:.6g} m")
        if len(r) != len(d) - 1:
            raise ValueError(f"ShaftResistance.unit_resistance: needs one value per layer ({len(d) - 1}, one fewer "
                             f"than depths), got {len(r)}")
        for i, x in enumerate(r):
            if x < 0.0:
                raise ValueError(f"ShaftResistance.unit_resistance[{i}]: must be >= 0, got {x:.6g} N/m")
        if len(self.resistance) != len(self.plastic_set):
            raise ValueError("ShaftResistance.resistance: give as many values as plastic_set (one per interior "
                             f"node), got {len(self.resistance)} and {len(self.plastic_set)}")

    def check_fits(self, length: float, where: str) -> None:
        """Refuse depths beyond the rod's ``length`` (m)."""
        if self.depths[-1] > length * (1 + 1e-12):
            raise ValueError(f"{where}.depths: the last depth {self.depths[-1]:.6g} m lies beyond the end of the "
                             f"rod ({length:.6g} m)")

    def node_resistance(self, x_nodes: np.ndarray, length: float) -> np.ndarray:
        """Ultimate resistance R_u (N) of the interior nodes at ``x_nodes`` (m, increasing, strictly inside the
        rod of ``length``): the integral of the unit resistance over each node's half elements, the end halves
        added to the nearest interior node."""
        edges = np.concatenate([[0.0], 0.5 * (x_nodes[1:] + x_nodes[:-1]), [length]])
        return np.diff(self._integrals(edges))

    def _integrals(self, x: np.ndarray) -> np.ndarray:
        """int_0^x of the unit resistance at every ``x`` (m), N: the layers' shares summed in depth order
        (``np.cumsum`` is sequential), as :meth:`_integral` sums them."""
        a, b = np.asarray(self.depths[:-1], dtype=float), np.asarray(self.depths[1:], dtype=float)
        shares = np.asarray(self.unit_resistance, dtype=float) * np.maximum(
            0.0, np.minimum(b, np.asarray(x, dtype=float)[:, None]) - a)
        return np.cumsum(shares, axis=1)[:, -1]

    def _integral(self, x: float) -> float:
        """int_0^x of the unit resistance, N."""
        total = 0.0
        for a, b, r in zip(self.depths[:-1], self.depths[1:], self.unit_resistance):
            total += r * max(0.0, min(b, x) - a)
        return total

    @property
    def total(self) -> float:
        """Total ultimate shaft resistance, N."""
        return self._integral(math.inf)
