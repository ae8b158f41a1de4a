"""How well a lattice represents the rods, and the time step that keeps it within tolerance.

A geometry-based rod of travel time theta_L gets n = round(theta_L / dt) elements, so the lattice scales its
travel time and its mass by ``time_scale = n dt / theta_L`` (:mod:`rodimpact.lattice.discretize`); a segment
shorter than one element is smeared over its neighbours. Both change the physics (a 0.3 m striker at
dt = 100 us becomes one element with 72.5 % more mass), so :func:`rodimpact.simulate` refuses a lattice whose
travel-time or mass error exceeds :data:`TOLERANCE` (1 %) or that has a segment shorter than an element, unless
the problem says ``allow_discretization_error=True`` (:class:`~rodimpact.Problem`; model files:
``simulation.allow_discretization_error = true``). The solver's own default time step always satisfies this
tolerance (:func:`resolving_time_step`).
"""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING

import numpy as np

from .._validate import caller_stacklevel
from ..rods.system import System

if TYPE_CHECKING:          # a type only: lattice.py imports this module (no import circle)
    from .lattice import Lattice

#: Largest relative travel-time or mass error of a rod's lattice accepted by default.
TOLERANCE = 0.01
#: problems named in a message (a drill string of many short segments would otherwise give pages)
_SHOWN = 3


def rounding_error(travel_time: float, dt: float) -> float:
    """Relative travel-time (= mass) error |n dt / theta - 1| of a rod of travel time ``theta`` (s) cut into
    n = round(theta / dt) >= 1 elements of travel time ``dt``."""
    n = max(1, round(travel_time / dt))
    return abs(n * dt / travel_time - 1.0)


def problems(system: System, lattice: Lattice, tolerance: float = TOLERANCE) -> list[str]:
    """The rods (and segments) of ``system`` that ``lattice`` represents worse than ``tolerance``, described."""
    out = []
    dt = lattice.dt
    for i, (rod, r) in enumerate(zip(system.rods, lattice.rods)):
        if r.exact:
            continue
        label = f"rod {i}" + (f" ({rod.name})" if rod.name else "")
        for s, tau in enumerate(rod.segment_travel_times):
            if tau < dt * (1.0 - 1e-9):
                seg = rod.segments[s]
                out.append(f"{label} segment {s} ({type(seg).__name__}, length {seg.length:.4g} m, travel time "
                           f"{tau:.4g} s) is shorter than one element (dt = {dt:.4g} s) and is smeared over its "
                           f"neighbours")
        e_time = abs(r.time_scale - 1.0)
        e_mass = abs(r.lattice_mass / r.true_mass - 1.0)
        if max(e_time, e_mass) > tolerance:
            out.append(f"{label}: its travel time is represented with a {e_time * 100:.3g} % error and its mass "
                       f"with a {e_mass * 100:.3g} % error ({r.n_elements} element(s) of dt = {dt:.4g} s for a "
                       f"travel time of {r.true_travel_time:.4g} s, {r.true_length:.4g} m)")
    return out


def _exact(rod, dt: float) -> bool:
    """True for an impedance-level rod whose own dt is a whole multiple of ``dt`` (taken element by element)."""
    if rod.native is None:
        return False
    ratio = rod.native.dt / dt
    return round(ratio) >= 1 and abs(ratio - round(ratio)) <= 1e-9 * ratio


def within(system: System, dt: float, tolerance: float = TOLERANCE) -> bool:
    """True when every geometry-based rod's rounding error is <= ``tolerance`` and no segment is shorter than
    one element at ``dt`` (impedance-level rods whose dt is a multiple of ``dt`` are exact)."""
    return all(_exact(rod, dt) or (rounding_error(rod.total_travel_time, dt) <= tolerance
                                   and float(rod.segment_travel_times.min()) >= dt * (1.0 - 1e-9))
               for rod in system.rods)


def resolving_time_step(system: System, dt: float, tolerance: float = TOLERANCE) -> float:
    """``dt`` if it represents every rod within ``tolerance``; else the largest time step < ``dt`` found that
    does so within half the tolerance (a margin): dt = theta_r / m, which makes rod r exact with m elements,
    searched over the rods r, or at least one that gives every rod 1 / tolerance elements (error <= tolerance/2
    by construction) and every segment one element."""
    if within(system, dt, tolerance):
        return dt
    half = 0.5 * tolerance
    rods = [(r.total_travel_time, float(r.segment_travel_times.min())) for r in system.rods]
    best = min(dt, min(t for _, t in rods), min(theta for theta, _ in rods) * tolerance)
    for theta, _ in rods:
        first = max(1, math.ceil(theta / dt * (1.0 - 1e-12)))
        for m in range(first, min(math.ceil(theta / best), first + 10_000) + 1):
            candidate = theta / m
            if candidate <= best:
                break
            if all(rounding_error(th, candidate) <= half and seg >= candidate * (1.0 - 1e-9) for th, seg in rods):
                best = candidate
                break
    return best


def check(system: System, lattice: Lattice, allow: bool) -> list[str]:
    """Raise (or, with ``allow``, warn) if the lattice misrepresents a rod by more than the tolerance
    (:mod:`rodimpact.lattice.tolerance`); returns the text of the warning issued (an empty list when the lattice
    is within the tolerance), for the run's ``diagnostics["warnings"]``."""
    if not isinstance(allow, (bool, np.bool_)):
        raise TypeError(f"allow_discretization_error: must be True or False, got {allow!r}")
    found = problems(system, lattice)
    if not found:
        return []
    good = resolving_time_step(system, lattice.dt)
    shown = "; ".join(found[:_SHOWN]) + (f"; and {len(found) - _SHOWN} more" if len(found) > _SHOWN else "")
    text = f"dt: {shown}. dt = {good:.6g} s represents every rod within {TOLERANCE:.0%}"
    if not allow:
        raise ValueError(text + " (or allow the error: Problem.of(..., allow_discretization_error=True), in a "
                                "model file simulation.allow_discretization_error = true)")
    warnings.warn(text, stacklevel=caller_stacklevel())
    return [text]
