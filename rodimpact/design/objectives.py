"""Objectives of striker design: what :func:`~rodimpact.design` is asked for, and the cost functions it minimises
with their seeds for the adjoint gradient.

What is asked: a :class:`MatchObjective` (a force history, where and how it is observed) or an
:class:`EfficiencyObjective` (the work done on the rock per blow, with or without reloading). Each becomes a
cost J (:class:`MatchCost`, :class:`EfficiencyCost`), a function of the forward run's histories (``fw``) and of
the striker itself, returned as ``(value, seeds, dvalue_dZ_direct, dvalue_dv_direct)``: ``seeds`` are
dJ/d(history_k) for :meth:`ImpactProblem.gradient`, the last two the explicit dependence on the impedances Z_q
(N s/m) and on the impact velocity v (m/s) that does not pass through the histories.

``match``
    J = sum_k w_k (y_k - r_k)^2 / sum_k w_k r_k^2, the squared relative L2 misfit of the achieved force y_k
    to the target r_k over the target's span: at the impact face every step k, with r_k = the window value X_j
    of its window [2(j-1) dt, 2j dt) (held for 2 dt); at a position the window starts after the dead time d,
    steps d + 2(j-1), with r = X_j (see :meth:`MatchCost.build`). The reported misfit is sqrt(J).
``efficiency``
    eta = W / E_k with W = -dt sum_k N_k v_k the work done on the rock by the far end (N_k the normal force,
    compressive < 0, v_k the outward velocity; node values are constant over a step, so the sum is the exact
    work of the lattice's end) and E_k = m v^2 / 2 the striker's kinetic energy, m = dt sum Z_q. The optimiser
    minimises J = -eta.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from .._validate import integer, non_negative, positive
from ..inverse.targets import checked_rule
from ..inverse.transform import checked_quantity

Seeds = dict[str, np.ndarray]

#: default run length of the efficiency objective: the striker's pulse (2 n steps) plus this many round trips
#: through the struck system, so that the reflected waves can come back and load the rock again
EFFICIENCY_ROUND_TRIPS = 3


@dataclass(frozen=True, eq=False)
class MatchObjective:
    """Match a wished force history: minimise the relative L2 misfit of the achieved force to ``target``.

    target:
        The wished force (N, tension positive, impact forces negative) in any form :func:`rodimpact.synthesize`
        accepts: a callable f(t), samples (t, F), window values or a
        :class:`~rodimpact.inverse.targets.ForceTarget`. Its window values X_j (``rule``) held for 2 dt are
        compared with the achieved force at every step over the target's span (n windows for a function
        without duration); at a ``position``, at the window starts after the dead time (:meth:`MatchCost.build`).
    position:
        Distance (m >= 0) from the impact face into the struck system where the force is observed; time then
        counts from the wavefront's arrival (dead time). None (default): the contact force at the impact face.
    quantity:
        At a ``position``: ``"force"`` (the normal force) or ``"incident"`` (the force wave arriving from the
        impact side).
    rule:
        How a continuous target becomes window values: ``"midpoint"`` (default), ``"start"`` (thesis), ``"mean"``.
    weights:
        Optional weights of the misfit: a function w(t) of the time from the start of the target (s), one value
        per window or one per step (finite, >= 0, not all 0).
    """

    target: Any
    position: Optional[float] = None
    quantity: str = "force"
    rule: str = "midpoint"
    weights: Any = None

    def __post_init__(self) -> None:
        if self.target is None:
            raise ValueError("MatchObjective.target: give the force history to match (a callable f(t), samples "
                             "(t, F) or window values, N); for the efficiency use ri.EfficiencyObjective()")
        if self.position is not None:
            object.__setattr__(self, "position", non_negative("MatchObjective.position", self.position, "m"))
        checked_quantity(self.quantity, "MatchObjective.quantity")
        checked_rule(self.rule, "MatchObjective.rule")


@dataclass(frozen=True)
class EfficiencyObjective:
    """Maximise the efficiency of a blow: eta = W / (m v^2 / 2), the work W done on the rock by the
    :class:`~rodimpact.BitRockEnd` far end of the struck system over the striker's kinetic energy (m = dt sum Z_q
    its mass, v its impact velocity).

    reloading:
        True (default): W over the whole run, so that waves reflected at the bit come back and load the rock
        again. False: Lundberg's classical efficiency of the first pass: the run ends when the first wave
        reflected at the bit could be back there (3 travel times from the impact face to the bit), so only the
        striker's incident wave loads the rock; the striker's pulse (2 n dt) must then fit inside the round trip
        of the struck system.
    duration, steps:
        Length of the run with reloading, s, or in steps of dt (one of them). Default: the striker's pulse
        2 n dt plus :data:`EFFICIENCY_ROUND_TRIPS` round trips through the struck system.
    """

    reloading: bool = True
    duration: Optional[float] = None
    steps: Optional[int] = None

    def __post_init__(self) -> None:
        if not isinstance(self.reloading, (bool, np.bool_)):
            raise TypeError(f"EfficiencyObjective.reloading: must be True (count the reloading of the rock by "
                            f"reflected waves) or False (first pass only, Lundberg's classical efficiency), got "
                            f"{self.reloading!r}")
        object.__setattr__(self, "reloading", bool(self.reloading))
        if self.steps is not None and self.duration is not None:
            raise ValueError("EfficiencyObjective.steps, duration: give one of them")
        if self.duration is not None:
            object.__setattr__(self, "duration", positive("EfficiencyObjective.duration", self.duration, "s"))
        if self.steps is not None:
            object.__setattr__(self, "steps", integer("EfficiencyObjective.steps", self.steps, 1))
        if not self.reloading and (self.steps is not None or self.duration is not None):
            given = "duration" if self.duration is not None else "steps"
            raise ValueError(f"EfficiencyObjective.{given}: the first-pass efficiency (reloading=False) runs until "
                             f"the first reflected wave returns to the bit; omit it, or use reloading=True")

    def run_steps(self, n: int, n_struck: int, dt: float) -> int:
        """Steps of the run with reloading for n striker elements and ``n_struck`` struck elements of travel
        time ``dt`` (s): ``steps``, ``duration`` / dt rounded, or 2 n + 2 EFFICIENCY_ROUND_TRIPS n_struck."""
        if self.duration is not None:
            return int(round(self.duration / dt))
        if self.steps is not None:
            return self.steps
        return 2 * n + 2 * EFFICIENCY_ROUND_TRIPS * n_struck


@dataclass(frozen=True)
class MatchCost:
    """Weighted relative L2 misfit of the observed history at the steps ``index`` against ``reference``."""

    index: np.ndarray          # compared steps
    reference: np.ndarray      # target at those steps, N
    weights: np.ndarray        # weights >= 0 at those steps
    steps: int                 # length of the forward run's histories

    @classmethod
    def build(cls, windows: np.ndarray, dead_time: Optional[int], weights: Any, dt: float,
              name: str = "weights") -> "MatchCost":
        """At the impact face (``dead_time`` None) every step of every window is compared with its window value
        (held for 2 dt); at a position the window starts after the dead time d, steps d + 2(j-1), as the
        transformation of :func:`~rodimpact.synthesize` matches them (devices that act every step, such as a
        bit-rock spring, make the quantity vary within a window, which no striker can shape). ``weights`` as
        :func:`per_step_weights` takes them; its errors name ``name``."""
        nw = windows.size
        if dead_time is None:
            index, ref = np.arange(2 * nw), np.repeat(windows, 2)
        else:
            index, ref = dead_time + 2 * np.arange(nw), windows.copy()
        w = per_step_weights(weights, nw, dt, name)
        if dead_time is not None:
            w = w[0::2]
        return cls(index, ref, w, int(index[-1]) + (2 if dead_time is None else 1))

    def achieved(self, fw: Any) -> np.ndarray:
        """The compared values of the forward run."""
        return np.asarray(fw.observed)[self.index]

    def evaluate(self, fw: Any, impedance: np.ndarray, velocity: float) -> tuple[float, Seeds, np.ndarray, float]:
        r = self.reference
        res = self.achieved(fw) - r
        norm = float(np.sum(self.weights * r * r))
        value = float(np.sum(self.weights * res * res)) / norm
        seed = np.zeros(self.steps)
        seed[self.index] = 2.0 * self.weights * res / norm
        return value, {"observed": seed}, np.zeros(impedance.size), 0.0


@dataclass(frozen=True)
class EfficiencyCost:
    """J = -eta, eta = (work done on the rock) / (striker kinetic energy)."""

    dt: float
    steps: int

    @staticmethod
    def work(fw: Any, dt: float) -> float:
        """W = -dt sum N_k v_k: work done by the far end on the rock over the run, J."""
        return float(-dt * np.dot(fw.end_force, fw.end_velocity))

    def efficiency(self, fw: Any, impedance: np.ndarray, velocity: float) -> float:
        """eta = W / (m v^2 / 2)."""
        return self.work(fw, self.dt) / (0.5 * self.dt * float(np.sum(impedance)) * velocity * velocity)

    def evaluate(self, fw: Any, impedance: np.ndarray, velocity: float) -> tuple[float, Seeds, np.ndarray, float]:
        dt = self.dt
        mass = dt * float(np.sum(impedance))
        ek = 0.5 * mass * velocity * velocity
        w = self.work(fw, dt)
        eta = w / ek
        seeds = {"end_force": dt * np.asarray(fw.end_velocity) / ek,       # d(-eta)/dN_k
                 "end_velocity": dt * np.asarray(fw.end_force) / ek}       # d(-eta)/dv_k
        # explicit dependence of -eta through E_k: d(-eta)/dZ_q = eta / E_k * dE_k/dZ_q, dE_k/dZ_q = dt v^2 / 2
        dz = np.full(impedance.size, eta / ek * 0.5 * dt * velocity * velocity)
        dv = eta / ek * mass * velocity
        return -eta, seeds, dz, float(dv)


def per_step_weights(weights: Optional[Any], n_windows: int, dt: float, name: str = "weights") -> np.ndarray:
    """Weights over the 2 n_w compared steps: None (all 1), a callable w(t) of the time from the start of the
    target (s), n_w values (one per window) or 2 n_w values (one per step); finite, >= 0, not all zero (errors
    name ``name``)."""
    m = 2 * n_windows
    if weights is None:
        return np.ones(m)
    if callable(weights):
        try:
            w = np.asarray(weights(dt * np.arange(m)), dtype=float)
            w = np.broadcast_to(w, (m,)).copy()
        except Exception as exc:  # noqa: BLE001 - report the user's function failing, with context
            raise ValueError(f"{name}: calling the weight function with an array of times failed ({exc}); it "
                             f"must accept a numpy array t (s) and return one weight per time") from exc
    else:
        w = np.asarray(weights)
        if w.dtype.kind not in "iuf":
            raise TypeError(f"{name}: must be real numbers (one per window or per step) or a function w(t), got "
                            f"{type(weights).__name__} {weights!r}")
        w = w.astype(float)
        if w.ndim != 1 or w.size not in (n_windows, m):
            raise ValueError(f"{name}: give {n_windows} values (one per window) or {m} (one per step), or a "
                             f"function w(t); got shape {w.shape}")
        if w.size == n_windows:
            w = np.repeat(w, 2)
    if not np.all(np.isfinite(w)) or np.any(w < 0) or not np.any(w > 0):
        raise ValueError(f"{name}: must be finite and >= 0, with at least one > 0")
    return w


@dataclass(frozen=True, eq=False)
class StrainRateObjective:
    """Hold the strain rate of the struck system's specimen (a :class:`~rodimpact.Specimen` joint) at ``rate``
    (1/s, engineering, compression positive) over a time window, with the specimen's law in the loop: minimise
    the mean square relative deviation J = (1/M) sum_k (rate_k / rate - 1)^2 over the M steps of the window, where
    rate_k = (delta_k - delta_k-1) / (dt L0) is the specimen's engineering strain rate in step k from its
    shortening delta (the joint's state, simulated with the law at every step; docs/adjoint.md, "Law joints").

    start, end:
        The window, s after the incident wave's first arrival at the specimen (0 <= start < end).
    start_impedance, start_velocity:
        Optional starting striker (Z_1..Z_n from the impact face, N s/m) and velocity (m/s), e.g. the striker of
        the target method (:func:`rodimpact.shpb.rate_design.design_striker`); default a uniform striker of the
        face's impedance.
    """

    rate: float
    start: float
    end: float
    start_impedance: Any = None
    start_velocity: Optional[float] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "rate", positive("StrainRateObjective.rate", self.rate, "1/s"))
        object.__setattr__(self, "start", non_negative("StrainRateObjective.start", self.start, "s"))
        object.__setattr__(self, "end", positive("StrainRateObjective.end", self.end, "s"))
        if not self.start < self.end:
            raise ValueError(f"StrainRateObjective.end: must be after start = {self.start:.6g} s, got "
                             f"{self.end:.6g} s")
        if self.start_velocity is not None:
            object.__setattr__(self, "start_velocity",
                               positive("StrainRateObjective.start_velocity", self.start_velocity, "m/s"))


@dataclass(frozen=True)
class StrainRateCost:
    """J = (1/M) sum_{k in index} (rate_k / rate - 1)^2, rate_k = (delta_k - delta_k-1) / (dt L0) of junction
    ``joint`` (a row of the forward run's ``shortening``; delta_-1 = 0). Seeds: with c_k = 2 (rate_k / rate - 1) /
    (M rate dt L0), dJ/d delta_k += c_k and dJ/d delta_k-1 -= c_k."""

    joint: int
    junctions: int
    length: float
    rate: float
    index: np.ndarray
    dt: float
    steps: int

    def rates(self, fw: Any) -> np.ndarray:
        """The specimen's engineering strain rate (1/s) in every step of the run."""
        d = np.asarray(fw.shortening[self.joint])
        return np.diff(d, prepend=0.0) / (self.dt * self.length)

    def evaluate(self, fw: Any, impedance: np.ndarray, velocity: float) -> tuple[float, Seeds, np.ndarray, float]:
        dev = self.rates(fw)[self.index] / self.rate - 1.0
        m = self.index.size
        value = float(np.sum(dev * dev)) / m
        c = 2.0 * dev / (m * self.rate * self.dt * self.length)
        seed = np.zeros((self.junctions, self.steps))
        np.add.at(seed[self.joint], self.index, c)
        earlier = self.index - 1
        keep = earlier >= 0
        np.add.at(seed[self.joint], earlier[keep], -c[keep])
        return value, {"shortening": seed}, np.zeros(impedance.size), 0.0
