"""Transformation of a force prescribed inside the struck system into the impact force (thesis Sec. 4.1.2).

The struck system is linear (after :func:`~rodimpact.inverse.struck.linearized`), so the quantity Q at the
node p responds to the impact force N_I(t) = X_j on [2(j-1) dt, 2j dt) (eq. 4.11) as

    Q(t_dt + 2(j-1) dt) = Q_free(...) + sum_{k=1..j} X_k G_{j-k+1}                           (eqs. 4.13-4.17)

where t_dt (the dead time) is the travel time from the impact face to p, G is the *rectangular response*
(response at p to a unit force on [0, 2 dt), eq. 4.12, sampled at the window starts t_dt + 2(j-1) dt) and
Q_free is the struck system's own response with a force-free face (initial velocities, initial state, nodal
loads; the thesis's examples start at rest, where it vanishes). Requiring Q = Y_j at the window starts is a
lower-triangular Toeplitz system for X, solved by forward substitution (eq. 4.17) or, for many windows, by
an FFT-based O(n log n) solver (:mod:`rodimpact.inverse._toeplitz`).

Why the window starts: every path from the face to p is t_dt plus an even number of steps long, so in a
struck system whose own reflections change only every second step the response at p is piecewise constant on
the shifted windows and matching the start matches the whole window. Devices that act every step (the
spring of a bit-rock interface, thesis Fig. 4.9, is integrated per step by the direct solver) make Q vary
within a window; the transformation is then exact at the window starts and the in-window variation is
reported by :meth:`~rodimpact.inverse.result.SynthesisResult.verify`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .._moved import moved
from .._validate import positive
from ..direct.problem import Problem
from ..direct.recording import Outputs
from ..direct.simulate import simulate
from ..rods.system import System
from ._rectangular import rectangular_response
from ._toeplitz import solve_lower_toeplitz
from .struck import (STRUCK_KEYWORDS, Location, as_struck_system, at_rest, driven, has_free_motion, linearized,
                     locate, position_probe, position_quantity, window_count_check)
from .targets import as_target

QUANTITIES = ("force", "incident")


@dataclass(frozen=True)
class ForceTransformation:
    """Result of :func:`transform_force`: the impact-face window values X_j that produce the prescribed
    quantity at a position inside the struck system.

    All arrays have one value per window j = 1..n; forces in N (tension positive).
    """

    impact_force: np.ndarray           # X_j at the impact face
    target: np.ndarray                 # Y_j prescribed at the position (window starts after the dead time)
    rectangular_response: np.ndarray   # G_j, response at the position to a unit force on [0, 2 dt) (eq. 4.13)
    free_response: np.ndarray          # struck system's own response at the position (force-free face)
    dt: float
    location: Location
    quantity: str
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def dead_time(self) -> float:
        """Travel time t_dt from the impact face to the position, s."""
        return self.location.node * self.dt

    @property
    def time(self) -> np.ndarray:
        """Window start times at the impact face, 2(j-1) dt, s."""
        return 2.0 * self.dt * np.arange(self.impact_force.size)

    @property
    def residual(self) -> float:
        """max_j |free + G * X - Y| / max |Y|: how well the triangular system is solved."""
        n = self.impact_force.size
        back = self.free_response + np.convolve(self.rectangular_response, self.impact_force)[:n]
        return float(np.max(np.abs(back - self.target)) / max(np.max(np.abs(self.target)), 1e-300))


def checked_quantity(quantity: str, name: str = "quantity") -> str:
    """``quantity`` after checking it names what a target at a position prescribes: ``"force"`` (the normal force
    at the node) or ``"incident"`` (the force wave arriving from the impact side); the message names ``name``."""
    if quantity not in QUANTITIES:
        raise ValueError(f"{name}: must be one of {QUANTITIES} ('force' = normal force at the position, "
                         f"'incident' = force wave arriving from the impact side), got {quantity!r}")
    return quantity


def _response(system: System, location: Location, dt: float, steps: int, quantity: str, backend: str,
              relative_to_initial: bool) -> np.ndarray:
    """Quantity at the located node, per step, from one run of the direct solver."""
    outputs = Outputs(probes=[position_probe(location)],
                      snapshot_times=[0.0] if quantity == "incident" and relative_to_initial else None)
    res = simulate(Problem.of(system, steps=steps, dt=dt, outputs=outputs, allow_discretization_error=True),
                   backend=backend)     # the synthesis runs at the user's dt: a warning
    p = res.probe("synthesis_position")
    z_left = float(res.lattice.impedance[location.element_left])
    n0 = v0 = 0.0
    if quantity == "incident" and relative_to_initial:
        n0 = float(res.snapshots.force[location.element_left, 0])
        v0 = float(res.snapshots.velocity[location.element_left, 0])
    return position_quantity(quantity, p.force, p.velocity, z_left, n0, v0)


def _rectangular(system: System, location: Location, dt: float, steps: int, quantity: str,
                 backend: str) -> np.ndarray:
    """Rectangular response (eq. 4.12) per step: by the band-limited sweep of
    :mod:`rodimpact.inverse._rectangular` for a passive chain at rest (compiled backend), else by one run of
    the direct solver driven by a unit force for one window."""
    fast = rectangular_response(system, location.node, dt, steps) if backend == "numba" else None
    if fast is None:
        return _response(driven(system, np.array([1.0, 0.0]), dt), location, dt, steps, quantity, backend, False)
    force, velocity, z = fast
    return position_quantity(quantity, force, velocity, float(z[location.element_left]))


def transform_windows(system: System, location: Location, target: np.ndarray, dt: float,
                      quantity: str = "force", method: str = "auto", backend: str = "numba") -> ForceTransformation:
    """Core of :func:`transform_force` on normalised input (``system`` from
    :func:`~rodimpact.inverse.struck.as_struck_system`, ``location`` from
    :func:`~rodimpact.inverse.struck.locate`, window values ``target``)."""
    quantity = checked_quantity(quantity)
    if quantity == "incident" and location.element_left < 0:
        raise ValueError("position: the incident wave is defined at a node inside the struck system; "
                         "position = 0 is the impact face itself (prescribe the impact force there)")
    y = np.asarray(target, dtype=float)
    n = y.size
    lin, notes = linearized(system)
    d = location.node
    steps = d + 2 * n - 1
    sample = d + 2 * np.arange(n)
    g = _rectangular(at_rest(lin), location, dt, steps, quantity, backend)[sample]
    if has_free_motion(lin):
        free = _response(driven(lin, np.array([0.0]), dt), location, dt, steps, quantity, backend, True)[sample]
    else:
        free = np.zeros(n)
    scale = np.max(np.abs(g))
    if not abs(g[0]) > 1e-12 * scale:
        raise ValueError(f"position: the {quantity} at {location.used:.6g} m does not respond to the first impact "
                         "window (rectangular response G_1 = 0); choose another position or quantity")
    x = solve_lower_toeplitz(g, y - free, method)
    return ForceTransformation(x, y, g, free, dt, location, quantity, tuple(notes))


@moved(STRUCK_KEYWORDS)
def transform_force(target: Any, struck: Any, position: float, n: Optional[int] = None,
                    dt: Optional[float] = None, *, quantity: str = "force", rule: str = "midpoint",
                    method: str = "auto", backend: str = "numba") -> ForceTransformation:
    """Transform a force history prescribed at ``position`` (m from the impact face into the struck system)
    into the impact-force window values that produce it (thesis Sec. 4.1.2, eqs. 4.10-4.17).

    ``target`` is a callable f(t), samples (t, F) or window values (see :mod:`rodimpact.inverse.targets`);
    its time is measured from the arrival of the wavefront at the position. ``quantity`` is ``"force"`` (the
    normal force at the node) or ``"incident"`` (the force wave arriving from the impact side, as in the
    thesis's percussion-drilling example). ``struck`` is as in :func:`~rodimpact.synthesize` (a rod, rods
    from the impact face outwards, or a ``ri.System.struck(rods, far_end=...)``). ``method`` selects the triangular
    Toeplitz solver ("auto", "substitution",
    "fft").
    """
    system = as_struck_system(struck)
    dt = struck_time_step(system, dt)
    tgt = as_target(target, rule)
    n = window_count(tgt, n, dt)
    y = tgt.window_values(n, dt)
    return transform_windows(system, locate(system, position, dt), y, dt, quantity, method, backend)


def struck_time_step(system: System, dt: Optional[float]) -> float:
    """The element travel time of a synthesis or design, s: ``dt``, or, when it is ``None``, the smallest one of
    the struck rods built with ``Rod.from_impedance``."""
    if dt is None:
        natives = [r.native.dt for r in system.rods if r.native is not None]
        if not natives:
            raise ValueError("dt: give the time step (s); it can only be inferred from struck rods built with "
                             "Rod.from_impedance")
        return float(min(natives))
    return positive("dt", dt, "s")


def window_count(target, n: Optional[int], dt: float) -> int:
    """The number of striker elements (force windows of 2 dt): ``n``, or, when it is ``None``, as many windows as
    the target's duration covers."""
    if n is None:
        avail = target.available_windows(dt)
        if avail is None:
            raise ValueError("n: give the number of striker elements (the target is a function without a "
                             "duration)")
        if avail < 1:
            raise ValueError(f"n: the target lasts {target.duration:.6g} s, shorter than one window 2*dt = "
                             f"{2 * dt:.6g} s")
        return avail
    return window_count_check(n)


__all__ = ["ForceTransformation", "transform_force", "transform_windows"]
