"""Thesis Setup 3 (Fig. 3.11, Tab. 3.3): uniform striker hitting an exponential horn with a fixed far end.

Global coordinates as in the lattice solver and thesis Fig. 3.12: the striker (Rod 1, uniform area A1, free
left end) occupies ``[-l1, 0]``, the horn (Rod 2, ``A(x) = A0 exp(xi x)``, fixed right end) occupies ``[0, l2]``;
the impact face is x = 0. The thesis's Rod-1 coordinate is ``x1 = x + l1``, its Rod-2 coordinate ``x2 = x``.

The contact is bonded for all time, as in the thesis (the modal model cannot separate); for Tab. 3.3 the contact
force stays compressive at least up to the last comparison time 0.435 ms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact._validate import finite, positive
from rodimpact.reference._entire import cos_sinc
from rodimpact.reference.families import AnalyticProfile
from rodimpact.reference.modal import ModalChain, ModalSegment, ModalSolution

__all__ = ["HornImpact"]


@dataclass(frozen=True)
class HornImpact:
    """Setup 3 of the thesis; defaults are Tab. 3.3 (steel, v_in = 6 m/s, l1 = l2 = 1 m, A0 = 1.96e-3 m^2,
    xi = 0.5 1/m). ``striker_area`` defaults to A0 (Fig. 3.11: the striker has the horn's area at the face)."""

    youngs_modulus: float = 210e9
    density: float = 7840.0
    impact_velocity: float = 6.0
    striker_length: float = 1.0
    horn_length: float = 1.0
    area: float = 1.96e-3
    xi: float = 0.5
    striker_area: float | None = None

    def __post_init__(self) -> None:
        for name, unit in (("youngs_modulus", "Pa"), ("density", "kg/m^3"), ("striker_length", "m"),
                           ("horn_length", "m"), ("area", "m^2")):
            object.__setattr__(self, name, positive(name, getattr(self, name), unit))
        object.__setattr__(self, "impact_velocity", finite("impact_velocity", self.impact_velocity, "m/s"))
        object.__setattr__(self, "xi", finite("xi", self.xi, "1/m"))
        a1 = self.area if self.striker_area is None else positive("striker_area", self.striker_area, "m^2")
        object.__setattr__(self, "striker_area", a1)

    @property
    def wave_speed(self) -> float:
        """c0 = sqrt(E/rho) in m/s."""
        return math.sqrt(self.youngs_modulus / self.density)

    @property
    def cutoff_angular_frequency(self) -> float:
        """Cutoff of the horn, c0 |xi| / 2 in rad/s (Tab. 2.1): beta is imaginary below it."""
        return self.wave_speed * abs(self.xi) / 2.0

    @property
    def chain(self) -> ModalChain:
        """The equivalent :class:`ModalChain` (striker from x = -l1, horn to x = l2, free-fixed)."""
        c0 = self.wave_speed
        uniform = AnalyticProfile("quadratic", self.striker_area, 0.0, c0)
        striker = ModalSegment(uniform, self.striker_length, self.density)
        horn = ModalSegment(AnalyticProfile("exponential", self.area, self.xi, c0), self.horn_length, self.density)
        return ModalChain((striker, horn), left="free", right="fixed", origin=-self.striker_length)

    def characteristic(self, omega: ArrayLike) -> NDArray[np.float64]:
        """Eq. (3.35) divided by alpha beta, corrected for a striker area A1 != A0::

            2 cos(a l1) cos(b l2) + xi cos(a l1) sin(b l2)/b - 2 (A1/A0) a sin(a l1) sin(b l2)/b

        with ``a = omega/c0``, ``b^2 = a^2 - xi^2/4`` (eq. 3.34). Written with the entire functions
        cos(b l2) and sin(b l2)/b it is real and smooth across the cutoff (b imaginary below it) and has no
        spurious root at omega = 0 (the factor alpha of eq. 3.35 is removed).
        """
        w = np.asarray(omega, dtype=float)
        a = w / self.wave_speed
        cc, ss = cos_sinc(a * a - 0.25 * self.xi**2, self.horn_length)
        ca, sa = np.cos(a * self.striker_length), np.sin(a * self.striker_length)
        return 2.0 * ca * cc + self.xi * ca * ss - 2.0 * (self.striker_area / self.area) * a * sa * ss

    def solve(self, n_modes: int = 2500) -> ModalSolution:
        """Modal series with ``n_modes`` modes: striker at ``impact_velocity``, horn at rest, no initial strain."""
        return self.chain.expand((self.impact_velocity, 0.0), n_modes)

    def wavefront_positions(self, t: float) -> NDArray[np.float64]:
        """Global x of every force/velocity discontinuity at time t (s), sorted.

        Discontinuities start at the face x = 0 at t = 0, travel at c0 in both rods, reflect at both ends and
        split (transmit + reflect) whenever they reach x = 0. Used to exclude Gibbs zones from comparisons.
        """
        tt = finite("t", t, "s")
        c0 = self.wave_speed
        l1, l2 = self.striker_length, self.horn_length
        out = []
        pending = [(0.0, 0.0, d) for d in (-1, +1)]  # wave paths: (start time, start x, direction)
        seen = set()
        while pending:
            t0, x0, d = pending.pop()
            key = (round(t0 * 1e12), round(x0 * 1e12), d)
            if key in seen:
                continue
            seen.add(key)
            if len(seen) > 100_000:
                raise ValueError(f"t: {t!r} s is too late to list the wavefronts (more than 1e5 wave paths)")
            if x0 == 0.0:
                end = -l1 if d < 0 else l2
            else:
                end = 0.0
            dt = abs(end - x0) / c0
            if t0 + dt >= tt:
                out.append(x0 + d * c0 * (tt - t0))
                continue
            t1 = t0 + dt
            if end == 0.0:  # at the face: transmitted and reflected
                pending.append((t1, 0.0, d))
                pending.append((t1, 0.0, -d))
            else:  # at an end: reflected
                pending.append((t1, end, -d))
        return np.unique(np.round(np.array(out), 12))
