"""Prescribed force histories for impactor synthesis and how they become window values.

The recursive method (thesis Sec. 4.1) can only shape a force that is constant on the windows
``[2(j-1) dt, 2j dt)``, j = 1..n (eq. 4.11): element j of the striker first influences the impact force at
t = 2(j-1) dt and the next element two steps later. A target is therefore always turned into ``n`` window
values X_j. Rules (``rule=``):

``"midpoint"`` (default)
    X_j = F((2j-1) dt), the value in the middle of the window. Centred in time, so the window values carry no
    lag of dt, and second-order accurate: for the Lundberg-Lesser case (eq. 4.26) the impedance error at the
    element midpoints theta = (q - 1/2) dt falls like dt^2 whatever the impedance ratio Z_0/Z~, while with
    ``"start"`` it falls like dt unless Z_0 = Z~ (tests/inverse/test_lundberg_lesser.py).
``"start"``
    X_j = F(2(j-1) dt), the value at the start of the window: the thesis's convention. The first value is the
    initial impact force F(0) and element q is compared with the continuous solution at the travel time of
    its leading edge, theta_q = (q-1) dt (eq. 4.27). Use it to reproduce the thesis: tables 4.3/4.4 and the
    1.10e-3 % of the Lundberg-Lesser comparison (tests/inverse/test_inverse_thesis_examples.py).
``"mean"``
    X_j = average of F over the window (impulse-preserving): the synthesized striker transfers exactly the
    target's momentum in every window; also second order, compared at the element midpoints.

Samples ``(t, F)`` are interpolated linearly between samples (for ``"mean"``, the linear interpolant is
integrated exactly). Window values can also be given directly. Times are measured from the impact, or, for a
force prescribed at a position inside the struck system, from the arrival of the wavefront there (the dead
time is removed, as in thesis Fig. 4.10).

Forces are normal forces, tension positive: an impact force is negative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Literal, Optional, Union

import numpy as np

from .._validate import finite, finite_array, finite_values, positive
from ..reference.closed_forms import lundberg_lesser_impedance as _reference_impedance

Rule = Literal["start", "midpoint", "mean"]
RULES = ("start", "midpoint", "mean")
_GAUSS = np.polynomial.legendre.leggauss(8)


def checked_rule(rule: str, name: str = "rule") -> str:
    """``rule`` after checking it is one of :data:`RULES` (how a continuous target becomes window values); the
    message names ``name``."""
    if rule not in RULES:
        raise ValueError(f"{name}: must be one of {RULES} (how a target becomes window values), got {rule!r}")
    return rule


@dataclass(frozen=True, eq=False)
class ForceTarget:
    """A prescribed force history, N (tension positive), and the rule that makes window values of it.

    Build it with :meth:`from_callable`, :meth:`from_samples` or :meth:`from_window_values` (or let
    :func:`as_target` guess from the type). ``duration`` is the time span the target covers (s) when known.
    """

    kind: Literal["callable", "samples", "windows"]
    source: Any
    rule: str = "midpoint"
    duration: Optional[float] = None
    window_dt: Optional[float] = None

    def __post_init__(self) -> None:
        checked_rule(self.rule)

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_callable(cls, force: Callable[[np.ndarray], np.ndarray], rule: str = "midpoint",
                      duration: Optional[float] = None) -> "ForceTarget":
        """``force(t)`` (N) for an array of times t (s) from the impact (or the arrival at the position)."""
        if not callable(force):
            raise TypeError(f"target: must be callable f(t), got {type(force).__name__}")
        if duration is not None:
            duration = positive("target duration", duration, "s")
        return cls("callable", force, checked_rule(rule), duration)

    @classmethod
    def from_samples(cls, t: Any, force: Any, rule: str = "midpoint") -> "ForceTarget":
        """Samples ``force[i]`` (N) at times ``t[i]`` (s, increasing, starting at 0)."""
        ts = finite_array("target time samples", t, min_size=2)
        fs = finite_array("target force samples", force, min_size=2)
        if ts.shape != fs.shape:
            raise ValueError(f"target: time samples ({ts.size}) and force samples ({fs.size}) differ in length")
        if np.any(np.diff(ts) <= 0):
            i = int(np.flatnonzero(np.diff(ts) <= 0)[0])
            raise ValueError(f"target time samples: must increase strictly; t[{i + 1}] = {ts[i + 1]!r} <= "
                             f"t[{i}] = {ts[i]!r}")
        if abs(ts[0]) > 1e-9 * (ts[-1] - ts[0]):
            raise ValueError(f"target time samples: must start at t = 0 (the impact, or the arrival at the "
                             f"position), got t[0] = {ts[0]!r} s")
        return cls("samples", (ts, fs), checked_rule(rule), float(ts[-1]))

    @classmethod
    def from_window_values(cls, values: Any, dt: Optional[float] = None) -> "ForceTarget":
        """Window values X_j (N), j = 1..n, each held on [2(j-1) dt, 2j dt) (eq. 4.11). ``dt`` (optional)
        is the time step they were made for; it is checked against the synthesis's."""
        x = finite_array("target window values", values)
        if dt is not None:
            dt = positive("target dt", dt, "s")
        return cls("windows", x, "midpoint", None if dt is None else 2 * x.size * dt, dt)

    # ------------------------------------------------------------------ evaluation
    def available_windows(self, dt: float) -> Optional[int]:
        """How many whole windows of length 2 dt the target covers (None for a callable without duration)."""
        if self.kind == "windows":
            return int(self.source.size)
        if self.duration is None:
            return None
        x = self.duration / (2.0 * dt)
        return int(math.floor(x + 1e-9 * max(x, 1.0)))

    def window_values(self, n: int, dt: float) -> np.ndarray:
        """The ``n`` window values X_1..X_n (N) for the time step ``dt`` (s)."""
        if self.kind == "windows":
            if self.window_dt is not None and abs(self.window_dt - dt) > 1e-9 * dt:
                raise ValueError(f"dt: the window values were made for dt = {self.window_dt!r} s, "
                                 f"synthesis uses dt = {dt!r} s")
            x = self.source
            if n != x.size:
                raise ValueError(f"n: the target gives {x.size} window values, n = {n} was requested; "
                                 f"give n = {x.size} (or None) or pass {n} window values")
            return x.copy()
        avail = self.available_windows(dt)
        if avail is not None and n > avail:
            raise ValueError(
                f"n: {n} windows of 2*dt = {2 * dt:.6g} s need a target lasting {2 * n * dt:.6g} s, but the "
                f"target covers {self.duration:.6g} s ({avail} windows); lower n or dt, or extend the target")
        j = np.arange(n, dtype=float)
        if self.kind == "callable":
            return self._callable_windows(j, dt)
        ts, fs = self.source
        if self.rule == "start":
            return np.interp(2.0 * j * dt, ts, fs)
        if self.rule == "midpoint":
            return np.interp((2.0 * j + 1.0) * dt, ts, fs)
        edges = 2.0 * dt * np.arange(n + 1)
        return np.diff(_linear_antiderivative(ts, fs, edges)) / (2.0 * dt)

    def _callable_windows(self, j: np.ndarray, dt: float) -> np.ndarray:
        f = self.source
        if self.rule == "start":
            t = 2.0 * j * dt
        elif self.rule == "midpoint":
            t = (2.0 * j + 1.0) * dt
        else:
            g, _ = _GAUSS
            t = ((2.0 * j + 1.0)[:, None] + g[None, :]) * dt
        try:
            y = np.asarray(f(t), dtype=float)
        except Exception as exc:  # noqa: BLE001 - report the user's function failing, with context
            raise ValueError(f"target: calling the force function with an array of times failed ({exc}); "
                             f"it must accept a numpy array t (s) and return forces (N)") from exc
        try:
            y = np.broadcast_to(y, t.shape)
        except ValueError:
            raise ValueError(f"target: the force function returned shape {y.shape} for times of shape {t.shape}; it "
                             "must return one force per time (N)") from None
        if self.rule == "mean":
            y = y @ _GAUSS[1] / 2.0
        return np.array(y, dtype=float)


def _linear_antiderivative(ts: np.ndarray, fs: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Exact integral from ts[0] to x of the piecewise-linear interpolant of (ts, fs)."""
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (fs[1:] + fs[:-1]) * np.diff(ts))])
    i = np.clip(np.searchsorted(ts, x, side="right") - 1, 0, ts.size - 2)
    h = x - ts[i]
    slope = (fs[i + 1] - fs[i]) / (ts[i + 1] - ts[i])
    return cum[i] + fs[i] * h + 0.5 * slope * h * h


TargetLike = Union[ForceTarget, Callable[[np.ndarray], np.ndarray], tuple, np.ndarray, list]


def as_target(target: Any, rule: str = "midpoint") -> ForceTarget:
    """Interpret ``target``: a :class:`ForceTarget`; a callable f(t); a pair ``(t, F)`` of 1-d arrays of equal
    length (samples); or a 1-d sequence of numbers (window values X_1..X_n)."""
    if isinstance(target, ForceTarget):
        return target
    if callable(target):
        return ForceTarget.from_callable(target, rule)
    if isinstance(target, (tuple, list)) and len(target) == 2 and all(np.ndim(a) == 1 for a in target):
        return ForceTarget.from_samples(target[0], target[1], rule)
    if np.ndim(target) == 1:
        return ForceTarget.from_window_values(target)
    raise TypeError(f"target: give a callable f(t), samples (t, F), window values (1-d array) or a ForceTarget; "
                    f"got {type(target).__name__}")


# ---------------------------------------------------------------------------------------------- thesis targets
def _force(name: str, times: Any, value: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """``value(t)`` for finite times t >= 0 and 0 before the impact (t < 0), checked to be finite (an overflow
    for a too late time is reported, not returned as inf)."""
    t = finite_values("t", times, "times (s)")
    tp = np.maximum(t, 0.0)
    with np.errstate(over="ignore", invalid="ignore"):
        f = np.where(t >= 0.0, value(tp), 0.0)
    if not np.all(np.isfinite(f)):
        i = int(np.flatnonzero(~np.isfinite(f).ravel())[0])
        raise ValueError(f"t: {name} overflows the floating-point range at t = {float(t.ravel()[i])!r} s; evaluate it "
                         f"at earlier times")
    return f[()]  # a number for a number t


@dataclass(frozen=True)
class ExponentialDecay:
    """N(t) = -peak * exp(-t / time_constant) (thesis eq. 4.24; Lundberg-Lesser's exact case, eq. 4.26).

    ``peak`` N > 0 is the magnitude at t = 0, ``time_constant`` s > 0. Called with times t (s, finite) it
    returns N(t), and 0 before the impact (t < 0).
    """

    peak: float
    time_constant: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "peak", positive("ExponentialDecay.peak", self.peak, "N"))
        object.__setattr__(self, "time_constant", positive("ExponentialDecay.time_constant", self.time_constant, "s"))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return _force("ExponentialDecay", t, lambda tp: -self.peak * np.exp(-tp / self.time_constant))


@dataclass(frozen=True)
class LinearRamp:
    """N(t) = -peak * (1 + 2 t / time_constant) (thesis eq. 4.28): a compressive force growing linearly
    (0 before the impact, t < 0)."""

    peak: float
    time_constant: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "peak", positive("LinearRamp.peak", self.peak, "N"))
        object.__setattr__(self, "time_constant", positive("LinearRamp.time_constant", self.time_constant, "s"))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return _force("LinearRamp", t, lambda tp: -self.peak * (1.0 + 2.0 * tp / self.time_constant))


@dataclass(frozen=True)
class ExponentialGrowth:
    """N(t) = -initial * exp(rate * t) (thesis eq. 4.29): the incident force that maximises the efficiency of
    percussive drilling (Lundberg and Collet), ``initial`` N > 0, ``rate`` 1/s (C in the thesis); 0 before the
    impact (t < 0)."""

    initial: float
    rate: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "initial", positive("ExponentialGrowth.initial", self.initial, "N"))
        object.__setattr__(self, "rate", finite("ExponentialGrowth.rate", self.rate, "1/s"))

    def __call__(self, t: np.ndarray) -> np.ndarray:
        return _force("ExponentialGrowth", t, lambda tp: -self.initial * np.exp(self.rate * tp))


def lundberg_lesser_impedance(theta: np.ndarray, peak: float, time_constant: float, struck_impedance: float,
                              striker_velocity: float) -> np.ndarray:
    """Exact striker impedance Z(theta) (N s/m) for the force -peak exp(-t/t0) on a semi-infinite uniform bar
    of impedance Z~ at rest (Lundberg and Lesser; thesis eq. 4.26), theta = travel time from the impact face:
    Z(theta) = Z0 / (1 + (Z~ + Z0) theta / (Z~ t0))^2 with Z0 = 1 / (v_in/peak - 1/Z~).

    The synthesis-side names of :func:`rodimpact.reference.lundberg_lesser_impedance`, the one copy of eq. 4.26
    (checked against the thesis's table there)."""
    peak = positive("peak", peak, "N")
    time_constant = positive("time_constant", time_constant, "s")
    struck_impedance = positive("struck_impedance", struck_impedance, "N s/m")
    striker_velocity = positive("striker_velocity", striker_velocity, "m/s")
    if not striker_velocity / peak - 1.0 / struck_impedance > 0:
        raise ValueError(f"striker_velocity: {striker_velocity} m/s is too slow for the peak force {peak} N on "
                         f"impedance {struck_impedance} N s/m (need v_in > peak / Z~)")
    return _reference_impedance(theta, struck_impedance, peak, time_constant, striker_velocity)
