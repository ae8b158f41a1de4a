"""Two-gauge wave separation on a uniform, non-dispersive bar (Lundberg and Henchoz 1977, "Analysis of elastic
waves from two-point strain measurement", Experimental Mechanics 17, 213-218): :func:`separate_waves`.

Gauge A at x_a and gauge B at x_b = x_a + c tau (tau: the travel time between them, a whole number k of sampling
intervals) on a bar at rest before the record. With f the wave travelling towards +x and g the one towards -x,
both seen at A, the strains are

    eps_A(t) = f(t) + g(t),    eps_B(t) = f(t - tau) + g(t + tau),

so g(t) = eps_B(t - tau) - f(t - 2 tau) and

    f(t) = eps_A(t) - eps_B(t - tau) + f(t - 2 tau),    g = eps_A - f,

a recursion that starts from the bar at rest (f = g = 0 before the first sample). Exact for a lossless,
non-dispersive bar; errors (noise, a wrong tau, dispersion) are carried forward every 2 tau, so it is used over a
few round trips (the source discusses the growth). One gauge alone separates the waves only while they do not
overlap at it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._validate import finite_array, integer

__all__ = ["separate_waves"]


def separate_waves(strain_a: Any, strain_b: Any, delay: int) -> tuple[np.ndarray, np.ndarray]:
    """The waves towards +x (f) and towards -x (g) at gauge A from the strains at gauges A and B (B lies
    ``delay`` sampling intervals of travel time further along +x; module docstring). Strain in any unit (the
    waves come in the same); returns ``(f, g)``."""
    a = finite_array("strain_a", strain_a)
    b = finite_array("strain_b", strain_b)
    if a.size != b.size:
        raise ValueError(f"strain_b: must have one sample per sample of strain_a ({a.size}), got {b.size}; the "
                         f"gauges must be recorded on one time axis")
    k = integer("delay", delay, 1, "sampling intervals of travel time from gauge A to gauge B")
    f = np.zeros(a.size)
    shifted = np.r_[np.zeros(k), b[:-k]] if k < b.size else np.zeros(b.size)
    drive = a - shifted
    for i in range(a.size):
        f[i] = drive[i] + (f[i - 2 * k] if i >= 2 * k else 0.0)
    return f, a - f
