"""Plain-language diagnosis of why an exact striker does not exist (used by :func:`~rodimpact.synthesize` and
:func:`~rodimpact.design`).

Two facts of the recursive method (thesis Sec. 4.1) explain most failures:

* **The contact jump.** At contact a striker whose first element has the impedance Z_1, moving at v into a
  struck system at rest with face impedance Z~, makes the force jump at once to magnitude
  F_0 = Z_1 Z~ v / (Z_1 + Z~): a force cannot start at 0 N, and a lower bound on Z_1 sets the smallest jump.
* **The force reserve.** In window q an impedance step of the striker can change the force by less than
  |K_q N_0| (eq. 4.20), the part of the initial wave N_0 = -Z~ v / 2 that still reaches the contact
  (K_q = prod (1 - R_r^2) over the steps passed). A thin first element (small F_0) leaves a small reserve:
  for a struck face that is uniform over the first elements, K_2 = 4 a (1 - a) with a = F_0 / (Z~ v), so the
  second window can reach at most |X_2| < F_0 (3 - 2 F_0 / (Z~ v)). The smallest jump from which a target's
  second window |X_2| is reachable is therefore F_0 = Z~ v (3 - sqrt(9 - 8 |X_2| / (Z~ v))) / 4.
"""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

#: first-window magnitude, relative to the target's largest, below which a target counts as "starting at 0 N"
NEAR_ZERO_START = 0.25


def contact_jump(first_impedance: float, face_impedance: float, velocity: float) -> float:
    """Magnitude of the force at contact, F_0 = Z_1 Z~ v / (Z_1 + Z~), N (struck system at rest)."""
    return first_impedance * face_impedance * velocity / (first_impedance + face_impedance)


def smallest_start(second_window: float, face_impedance: float, velocity: float) -> Optional[float]:
    """Smallest contact jump F_0 (N) from which the magnitude ``second_window`` |X_2| is reachable in window 2,
    F_0 = Z~ v (3 - sqrt(9 - 8 |X_2| / (Z~ v))) / 4; None when no jump below Z~ v reaches it."""
    s = face_impedance * velocity
    disc = 9.0 - 8.0 * abs(second_window) / s
    if disc < 0.0:
        return None
    return s * (3.0 - math.sqrt(disc)) / 4.0


def _kn(x: float) -> str:
    return f"{x / 1e3:.4g} kN"


def explain_failure(element: int, windows: np.ndarray, dt: float, velocity: float, face_impedance: float,
                    force_difference: float, force_reserve: float) -> str:
    """Plain words for an existence failure of the recursive method at ``element`` q (1-based)."""
    q = element
    grow = force_difference < 0.0          # more compression needs an impedance rise (R > 0, N_0 < 0)
    rate = force_reserve / (2.0 * dt)
    parts = []
    x = np.abs(np.asarray(windows, dtype=float))
    if q == 2 and x.size >= 2 and x[0] <= NEAR_ZERO_START * x.max():
        f0 = smallest_start(x[1], face_impedance, velocity)
        parts.append(
            f"A force starting at (nearly) 0 N cannot be produced: at contact the force jumps at once to "
            f"Z_1 Z~ v / (Z_1 + Z~); the first window's {_kn(x[0])} needs a first element of only "
            f"Z_1 = {x[0] * face_impedance / (face_impedance * velocity - x[0]):.4g} N s/m, and behind so thin an "
            f"element the force can grow by less than {_kn(force_reserve)} in the next window, while the target "
            f"grows by {_kn(x[1] - x[0])}.")
        if f0 is not None:
            parts.append(f"To make the start feasible, let the force jump at contact to at least {_kn(f0)} "
                         f"(here Z~ = {face_impedance:.4g} N s/m, v = {velocity:.4g} m/s).")
        else:
            parts.append(f"No contact jump reaches the second window's {_kn(x[1])} at v = {velocity:.4g} m/s; "
                         f"raise the velocity above {x[1] / face_impedance:.4g} m/s at least.")
        return " ".join(parts)
    verb = "grow" if grow else "fall"
    parts.append(
        f"From t = {2 * (q - 1) * dt:.6g} s on, the target asks the force to {verb} by {_kn(abs(force_difference))} "
        f"in one window (2 dt = {2 * dt:.3g} s) more than the waves already in the striker give, but an impedance "
        f"step there can change it by less than {_kn(force_reserve)} (the part of the initial wave that still "
        f"reaches the contact). The target must not {verb} faster than about {_kn(force_reserve)} per window "
        f"({rate / 1e6:.4g} kN/ms) here; a slower change, a higher striker velocity or a shorter target would be "
        f"feasible.")
    return " ".join(parts)


def explain_bounds(windows: np.ndarray, velocity: float, face_impedance: float, lower: float,
                   upper: float) -> list[str]:
    """Plain words for targets that the impedance bounds alone make impossible: a first window below the contact
    jump of the thinnest allowed first element, or a force above that of the thickest."""
    x = np.abs(np.asarray(windows, dtype=float))
    out = []
    jmin = contact_jump(lower, face_impedance, velocity)
    if x.size and x[0] < jmin:
        need = x[0] * face_impedance / (face_impedance * velocity - x[0]) if x[0] < face_impedance * velocity else None
        out.append(f"A force starting at {_kn(x[0])} cannot be produced: at contact the force jumps to at least "
                   f"{_kn(jmin)} for the thinnest allowed first element (Z_1 = {lower:.4g} N s/m, "
                   f"Z_1 Z~ v / (Z_1 + Z~) with Z~ = {face_impedance:.4g} N s/m, v = {velocity:.4g} m/s)"
                   + (f"; it would need Z_1 = {need:.4g} N s/m." if need else "."))
    jmax = face_impedance * velocity
    if x.size and x.max() >= jmax:
        out.append(f"The peak of {_kn(x.max())} cannot be reached at v = {velocity:.4g} m/s: no striker pushes "
                   f"harder than Z~ v = {_kn(jmax)} on a struck face of impedance {face_impedance:.4g} N s/m at rest.")
    return out
