"""End conditions at the two outer ends of a system, and junctions between neighbouring rods.

Sign conventions (architecture.md): the normal force N is positive in tension; x grows to the right.
At an end, the *outward* velocity w is the end's velocity pointing out of the rod (to the left at the left
end, to the right at the right end) and the *outward displacement* delta its time integral; the devices
below are described in these terms so the same law applies at either end.
"""

from __future__ import annotations

import difflib
import math

from dataclasses import dataclass
from typing import Any, Optional

from .declared import check, choice, element, flag, history, part, parts, quantity, type_name
from .laws import FREW, Law
from .history import HistoryLike


class EndCondition:
    """Base class of the end conditions. ``code`` identifies the law in the kernels."""

    code: int = -1


@element("end", "free")
@dataclass(frozen=True)
class FreeEnd(EndCondition):
    """Stress-free end: N = 0 (thesis eq. 2.42)."""

    code = 0


@element("end", "fixed")
@dataclass(frozen=True)
class FixedEnd(EndCondition):
    """Fixed end: u = 0, v = 0 (thesis eq. 2.41)."""

    code = 1


_INTERPOLATION = ("How samples are interpolated: `linear` or `previous` (hold).", ("linear", "previous"), "linear")


@element("end", "force")
@dataclass(frozen=True, eq=False)
class ForceEnd(EndCondition):
    """Prescribed normal force at the end face (tension positive; push on the end -> negative).

    ``force`` is a number, a callable f(t) or samples (t, N); see :class:`~rodimpact.rods.history.History`.
    """

    force: HistoryLike = history("force", "Force history.")
    interpolation: str = choice(*_INTERPOLATION)
    code = 2

    def __post_init__(self) -> None:
        check(self)


@element("end", "velocity")
@dataclass(frozen=True, eq=False)
class VelocityEnd(EndCondition):
    """Prescribed end velocity (positive to the right, as x)."""

    velocity: HistoryLike = history("velocity", "Velocity history.")
    interpolation: str = choice(*_INTERPOLATION)
    code = 3

    def __post_init__(self) -> None:
        check(self)


@element("end", "nonreflecting")
@dataclass(frozen=True)
class NonReflectingEnd(EndCondition):
    """Impedance-matched semi-infinite continuation ("energy sink", thesis eq. 3.20): outgoing waves leave,
    nothing comes in; also spelled `non-reflecting`.

    Eq. (3.20), N^- = N (left) / N^+ = N (right) with v^- = v from eqs. (3.16)/(3.17), makes the boundary's
    increments in the update of eqs. (3.10)-(3.15) zero: no wave enters the end element from outside. Since
    left-running increments keep N - Z v of the end element (N + Z v at a right end), that value stays at its
    initial one; the kernel writes the condition as an impedance-matched semi-infinite continuation in the end
    element's initial state, N = c0 - Z w with the outward velocity w and c0 = N0 - Z v0 at a left end,
    N0 + Z v0 at a right end, which equals eq. (3.20) step by step (for any initial prestress and velocity; a
    rod moving uniformly keeps moving). ``impedance`` (N s/m) other than the default
    (that of the end element) gives a continuation of that impedance, which reflects with
    R = (Z_ext - Z) / (Z_ext + Z). See docs/method.md.
    """

    impedance: Optional[float] = quantity("impedance", "Impedance of the continuation; default that of "
                                                                "the end element.", default=None)
    code = 4

    def __post_init__(self) -> None:
        check(self)


@element("end", "spring")
@dataclass(frozen=True)
class SpringEnd(EndCondition):
    """Linear spring with optional parallel dashpot to the ground.

    Outward motion compresses the spring: N = -(k delta + c w). The spring force is taken at the step's
    midpoint displacement delta + w dt/2 (implicit midpoint), which makes the energy bookkeeping exact:
    the spring's energy change equals the work done on it.
    """

    stiffness: float = quantity("stiffness", "Spring stiffness.", bound="non_negative")
    damping: float = quantity("damping", "Dashpot coefficient.", bound="non_negative", default=0.0)
    code = 5

    def __post_init__(self) -> None:
        check(self)


@element("end", "bit-rock")
@dataclass(frozen=True)
class BitRockEnd(EndCondition):
    """Bilinear bit-rock interaction, compression only (percussive drilling, thesis Fig. 4.9).

    Loading along F = k1 delta (``loading_stiffness``, N/m) while the penetration delta exceeds its previous
    maximum; unloading and reloading along the line of slope k2 (``unloading_stiffness``, default k1) through
    the maximum point; the force F >= 0 pushes back on the bit (N = -F) and never pulls (no tension).
    A passive rock needs k2 >= k1 (the work returned on unloading, F_max^2 / (2 k2), cannot exceed the work
    put in, F_max^2 / (2 k1)); k2 < k1 is refused.

    In a time step the bit moves at a constant velocity and the end force is the mean of F over that linear
    path, so load reversal, release and return to virgin loading are located inside the step and the impulse
    and work are those of the continuous law; the scheme is second order in dt (docs/method.md, "Bit-rock
    model").
    """

    loading_stiffness: float = quantity("stiffness", "Loading stiffness k1.")
    unloading_stiffness: Optional[float] = quantity("stiffness", "Unloading stiffness k2 >= k1; default "
                                                                        "k1.", default=None)
    code = 6

    def __post_init__(self) -> None:
        check(self)
        k1 = self.loading_stiffness
        k2 = k1 if self.unloading_stiffness is None else self.unloading_stiffness
        if k2 < k1:
            # Unloading along k2 < k1 from the maximum returns more work than loading put in: the rock would
            # give out energy (negative energy into the rock, negative permanent penetration).
            raise ValueError(
                f"BitRockEnd.unloading_stiffness: must be >= BitRockEnd.loading_stiffness for a passive rock "
                f"(k2 >= k1), got unloading_stiffness = {k2:.6g} N/m < loading_stiffness = {k1:.6g} N/m; "
                f"unloading less stiff than loading would give energy back that was never put in")
        object.__setattr__(self, "unloading_stiffness", k2)


END_NAMES: dict[str, type] = {"free": FreeEnd, "fixed": FixedEnd, "nonreflecting": NonReflectingEnd,
                              "non-reflecting": NonReflectingEnd}


def as_end_condition(value: Any, where: str) -> EndCondition:
    """Accept an :class:`EndCondition` or one of the names ``free``, ``fixed``, ``nonreflecting``."""
    if isinstance(value, EndCondition):
        return value
    if isinstance(value, str) and value.strip().lower() in END_NAMES:
        return END_NAMES[value.strip().lower()]()
    text = (f"{where}: must be an end condition object (FreeEnd, FixedEnd, ForceEnd, VelocityEnd, "
            f"NonReflectingEnd, SpringEnd, BitRockEnd, LumpedEnd) or one of the names {sorted(END_NAMES)}, got {value!r}")
    if not isinstance(value, str):
        raise TypeError(text + f" (of type {type(value).__name__})")
    raise ValueError(text + _did_you_mean(value, END_NAMES))


def _did_you_mean(value: str, names) -> str:
    """`` (did you mean 'free'?)`` for the closest of ``names``, or nothing."""
    near = difflib.get_close_matches(value.strip().lower(), list(names), n=1, cutoff=0.6)
    return f" (did you mean {near[0]!r}?)" if near else ''


class Junction:
    """Base class of the junctions between neighbouring rods."""

    code: int = -1


@element("junction", "contact")
@dataclass(frozen=True)
class Contact(Junction):
    """Unilateral contact: compression only; separation and re-contact.

    The rods separate when the contact force would turn tensile and re-contact when the gap (tracked from the
    end displacements) closes. ``gap`` is the initial gap in m (default 0: touching at t = 0).
    """

    gap: float = quantity("length", "Initial gap.", bound="non_negative", default=0.0)
    code = 1

    def __post_init__(self) -> None:
        check(self)


@element("junction", "bonded")
@dataclass(frozen=True)
class Bonded(Junction):
    """Welded or screwed joint: continuity of displacement and force at all times."""

    code = 0


@element("junction", "spring-dashpot")
@dataclass(frozen=True)
class SpringDashpot(Junction):
    """Massless spring and dashpot in parallel between the end faces of two rods (a cushion, a joint, an
    elastic specimen).

    With the shortening delta of the joint (the left rod's face moving right against the right rod's face) and
    its rate s, the joint carries the compressive force F = k delta + c s, so both faces see the normal force
    N = -F (tension positive). In a step the faces move at constant velocities, delta runs linearly, and the
    law is taken at the step's midpoint, F = k (delta_k + s dt/2) + c s (trapezoidal rule: second order in dt,
    and the spring's energy change k (delta_k+1^2 - delta_k^2)/2 equals the work done on it exactly). With the
    two faces' wave relations the law is one linear equation for N, solved exactly each step
    (docs/method.md, "Joints between rods"). ``compression_only``: the joint pushes but never pulls (F >= 0;
    the faces separate instead), as a cushion resting between a hammer and a pile.
    """

    stiffness: float = quantity("stiffness", "Spring stiffness k.", bound="non_negative")
    damping: float = quantity("damping", "Dashpot coefficient c.", bound="non_negative", default=0.0)
    compression_only: bool = flag("Push only, never pull (F >= 0): the faces separate instead.", False)
    code = 2

    def __post_init__(self) -> None:
        check(self)


class DeformableJoint(Junction):
    """A short, massless deformable body between the end faces of two rods, carrying the force of its
    constitutive law (:mod:`rodimpact.rods.laws`) at its strain and strain rate: a specimen or a pulse shaper.

    It is in force equilibrium at every instant (both faces carry the same force), which holds when its elastic
    transit time is small against the loading's rise time. Strain eps = delta / L0 from the shortening delta;
    with ``measure="true"`` the law sees true strain and rate and the area grows as A0 / (1 - eps)
    (incompressible flow), with ``"engineering"`` it sees eps and the area stays A0. The solver's equation and
    rule: docs/shpb.md and :mod:`rodimpact.direct.joints`.
    """

    code = 3
    law: Law
    diameter: float
    measure: str
    compression_only: bool

    @property
    def initial_length(self) -> float:
        """Length L0 of the undeformed body along the rods, m."""
        raise NotImplementedError

    @property
    def area(self) -> float:
        """Initial cross-section area A0 = pi d^2 / 4, m^2."""
        return 0.25 * math.pi * self.diameter ** 2

    def check_fits(self, faces: float, where: str) -> None:
        """Refuse a body wider than the rod faces it joins (``faces``: the smaller face area, m^2): the 1-D joint
        needs the bars to cover it. ``where`` names the joint in the message (``junctions[1]``)."""
        if self.area > faces * (1.0 + 1e-12):
            raise ValueError(f"{where}.diameter: the {type_name(self)} ({self.diameter * 1e3:.6g} mm, "
                             f"{self.area:.6g} m^2) is wider than the rod faces it joins ({faces:.6g} m^2): the 1-D "
                             "joint needs the bars to cover it")

    def _check_joint(self) -> None:
        check(self)
        if self.law.compression_only and not self.compression_only:
            raise ValueError(f"{type(self).__name__}.compression_only: the {type(self.law).__name__} law describes "
                             f"compression only; set compression_only=True")
        if self.law.code == FREW and self.measure != "engineering":
            raise ValueError(f"{type(self).__name__}.measure: the Frew-Forrestal-Chen law is fitted in engineering "
                             f"measures (its strain term includes the area change); set measure='engineering'")


_MEASURE = ("Strain and stress measures: `true` (large strain, area A0 / (1 - eps)) or `engineering` (area A0).",
            ("true", "engineering"))
_COMPRESSION = "Push only, never pull: the faces lift off instead of stretching the body."


@element("junction", "specimen")
@dataclass(frozen=True)
class Specimen(DeformableJoint):
    """A specimen between the incident and transmitted bars of a split-Hopkinson (Kolsky) bar."""

    law: Law = part("law", "Constitutive law of the specimen.")
    diameter: float = quantity("length", "Diameter.")
    length: float = quantity("length", "Initial length L0 (along the bars).")
    measure: str = choice(*_MEASURE, "true")
    compression_only: bool = flag(_COMPRESSION, True)
    density: Optional[float] = quantity("density", "Density; with it a Kolsky-bar prediction warns when the elastic "
                                                   "transit time L0 / c is not small against the pulse's rise.",
                                        default=None)

    def __post_init__(self) -> None:
        self._check_joint()

    @property
    def initial_length(self) -> float:
        return self.length


@element("junction", "pulse-shaper")
@dataclass(frozen=True)
class PulseShaper(DeformableJoint):
    """A thin disc between the striker and the incident bar that shapes the incident pulse (copper, paper)."""

    law: Law = part("law", "Constitutive law of the disc (e.g. `frew`).")
    diameter: float = quantity("length", "Diameter.")
    thickness: float = quantity("length", "Initial thickness L0.")
    measure: str = choice(*_MEASURE, "engineering")
    compression_only: bool = flag(_COMPRESSION, True)

    def __post_init__(self) -> None:
        self._check_joint()

    @property
    def initial_length(self) -> float:
        return self.thickness


# ------------------------------------------------------------------------------------- lumped chains (issue 23)
@element("lumped", "point-mass")
@dataclass(frozen=True)
class PointMass:
    """A rigid mass in a lumped chain (a hammer ram, a helmet, an anvil), moving along the rod axis.

    ``velocity`` is its velocity at t = 0, positive along x (a ram above the head of a pile on its right moves
    with +V0). In a step it moves with its midpoint velocity V_mid = (V_k + V_k+1) / 2 and M (V_k+1 - V_k) is the
    impulse of the forces of its neighbours (docs/lumped.md). A mass next to a rod face rests on it in
    unilateral contact: it pushes, and separates when the face force would turn tensile.
    """

    mass: float = quantity("mass", "Mass M.")
    velocity: float = quantity("velocity", "Velocity at t = 0 (positive along x).", bound=None, default=0.0)

    def __post_init__(self) -> None:
        check(self)


@element("lumped", "cushion")
@dataclass(frozen=True)
class Cushion:
    """A massless, compression-only cushion in a lumped chain (hammer cushion, pile cushion) with a coefficient
    of restitution e: it loads along F = k d (virgin loading while the compression d exceeds its largest value
    d_max so far) and unloads and reloads along the line of slope k / e^2 through (d_max, k d_max), carrying
    nothing below the release point d_max (1 - e^2).

    A full load-unload cycle to d_max stores k d_max^2 / 2 and gives back e^2 of it, the usual definition of the
    cushion's restitution in pile-driving analysis (E. A. L. Smith, Pile-driving analysis by the wave equation,
    J. Soil Mech. Found. Div. ASCE 86 (1960), SM4, pp. 35-61; FHWA GEC-12, FHWA-NHI-16-009, 2016).
    It is the bit-rock law of :class:`BitRockEnd` with k1 = k, k2 = k / e^2, solved the same way (exact mean
    force over the step's linear path).
    """

    stiffness: float = quantity("stiffness", "Loading stiffness k.")
    restitution: float = quantity("dimensionless", "Coefficient of restitution e, 0 < e <= 1 (unloading slope "
                                                   "k / e^2).", default=1.0)

    def __post_init__(self) -> None:
        check(self)
        if not self.restitution <= 1.0:
            raise ValueError(f"Cushion.restitution: must be in (0, 1], got {self.restitution!r}: e > 1 would give "
                             "back more energy than the cushion took")

    @property
    def unloading_stiffness(self) -> float:
        """The unloading and reloading slope k / e^2, N/m."""
        return self.stiffness / self.restitution ** 2


def _check_chain(owner: str, items: tuple, outer_end: bool) -> None:
    """Refuse a chain that the step cannot solve: two masses next to each other (one rigid body), two cushions
    next to each other (a massless node between them), or, at an outer end, a chain that does not start with a
    mass (a cushion with a free outer face carries nothing)."""
    for i in range(1, len(items)):
        kind = type(items[i])
        if kind is type(items[i - 1]):
            what = ("join them into one mass or put a Cushion between" if kind is PointMass
                    else "combine them into one cushion or put a PointMass between")
            raise ValueError(f"{owner}.items[{i}]: a {kind.__name__} next to another {kind.__name__} "
                             f"(items[{i - 1}]); {what}")
    if outer_end and not isinstance(items[0], PointMass):
        raise ValueError(f"{owner}.items[0]: the outermost item of an end chain must be a PointMass (items are "
                         f"listed from the outside towards the rod face); a {type(items[0]).__name__} with a free "
                         "outer face carries no force")


@element("end", "lumped")
@dataclass(frozen=True)
class LumpedEnd(EndCondition):
    """A lumped chain of point masses and cushions at an outer end (a pile-driving hammer: ram, hammer cushion,
    helmet, pile cushion), items listed from the outside towards the rod face, the outermost a
    :class:`PointMass` (free on its outer side). A mass next to the rod face rests on it in unilateral contact.

    Per step the masses move with their midpoint velocities, each cushion carries the mean of its law over its
    linear compression path and the rod face follows its characteristic: a small monotone system, solved by
    nonlinear Gauss-Seidel of exact scalar solves (docs/lumped.md). The chain's energies at the end of the run:
    ``SimulationResult.lumped`` (:class:`~rodimpact.direct.result.LumpedOutcome`).
    """

    items: tuple = parts("lumped", "Point masses and cushions from the outside towards the rod face.")
    code = 7

    def __post_init__(self) -> None:
        check(self)
        _check_chain("LumpedEnd", self.items, True)


@element("junction", "lumped")
@dataclass(frozen=True)
class LumpedJoint(Junction):
    """A lumped chain of point masses and cushions between two rods (a ram rod, its cushions and helmet, and a
    pile), items listed from the left rod's face to the right rod's face. A mass next to a rod face rests on it
    in unilateral contact. The junction force recorded is the force on the right rod's face.

    Solved as :class:`LumpedEnd`, with the left rod's face as the chain's first node.
    """

    items: tuple = parts("lumped", "Point masses and cushions from the left rod's face to the right rod's face.")
    code = 4

    def __post_init__(self) -> None:
        check(self)
        _check_chain("LumpedJoint", self.items, False)


def as_junction(value: Any, where: str) -> Junction:
    """Accept a :class:`Junction` or the names ``contact`` / ``bonded``."""
    if isinstance(value, Junction):
        return value
    if isinstance(value, str) and value.strip().lower() in ("contact", "bonded"):
        return Contact() if value.strip().lower() == "contact" else Bonded()
    text = (f"{where}: must be Contact(gap=...), Bonded() or SpringDashpot(stiffness, damping), or one of "
            f"'contact', 'bonded', got {value!r}")
    if not isinstance(value, str):
        raise TypeError(text + f" (of type {type(value).__name__})")
    raise ValueError(text + _did_you_mean(value, ("contact", "bonded")))
