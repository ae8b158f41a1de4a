"""Cross-section families with exact travelling-wave solutions (thesis Sec. 2.2, Tab. 2.1).

For a homogeneous rod (Young's modulus E, density rho, bar speed ``c0 = sqrt(E/rho)``) the governing PDE (2.6)
becomes (2.12)::

    u_xx + h(x) u_x - u_tt / c0**2 = 0,        h(x) = A'(x) / A(x).

The ansatz (2.13) ``u = a(x) exp(i (k x - omega t))`` separates into (2.14) ``2 a' + h a = 0``, whence (2.16)
``a(x) = a0 sqrt(A0 / A(x))``, and (2.15), which reduces to (2.17)::

    k**2 = omega**2 / c0**2 - b(x),            b(x) = h(x)**2 / 4 + h'(x) / 2.

A wave number independent of x needs a constant ``b``; Guo and Yang showed this singles out the four families of
Tab. 2.1 (areas measured from the origin of the segment, ``A(0) = A0``):

==============  ===========  =====================  =============================================
family          A(x)         b                      cutoff angular frequency ``omega_c = c0 sqrt(b)``
==============  ===========  =====================  =============================================
quadratic       A0(1+xi x)^2 0                      0 (non-dispersive)
exponential     A0 exp(xi x) xi^2 / 4               c0 xi / 2
cosh2           A0 cosh^2    xi^2                   c0 xi
cos2            A0 cos^2     -xi^2                  0 (b < 0: no cutoff, c_p < c0)
==============  ===========  =====================  =============================================

Phase velocity (2.18): ``c_p = omega / k = c0 / sqrt(1 - c0**2 b / omega**2)``. Below the cutoff ``k`` is
imaginary (evanescent field); :meth:`AnalyticProfile.wave_number` then returns the decaying branch
``k = +i sqrt(b - omega**2/c0**2)`` and :meth:`AnalyticProfile.phase_velocity` refuses (no propagating wave).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact._validate import finite, positive

__all__ = ["FAMILIES", "AnalyticProfile", "STEEL_BAR_SPEED"]

#: Bar speed of the thesis steel, sqrt(210 GPa / 7840 kg/m^3) = 5175.5 m/s.
STEEL_BAR_SPEED: float = math.sqrt(210e9 / 7840.0)

Family = Literal["quadratic", "exponential", "cosh2", "cos2"]
#: Names of the four Tab. 2.1 families, in the order of the table.
FAMILIES: tuple[str, ...] = ("quadratic", "exponential", "cosh2", "cos2")


@dataclass(frozen=True)
class AnalyticProfile:
    """One row of thesis Tab. 2.1: a cross-section family with a constant wave number.

    Parameters
    ----------
    family:
        ``"quadratic"`` (A0 (1 + xi x)^2), ``"exponential"`` (A0 exp(xi x)), ``"cosh2"`` (A0 cosh^2(xi x)) or
        ``"cos2"`` (A0 cos^2(xi x)).
    area_start:
        A0 = A(0) in m^2 (> 0).
    xi:
        Shape parameter in 1/m (any finite real; negative values give decreasing quadratic/exponential
        profiles). For ``cos2`` the area vanishes at ``xi x = pi/2``; :meth:`area` refuses such positions.
    wave_speed:
        Bar speed c0 = sqrt(E/rho) in m/s (default: thesis steel).
    """

    family: Family
    area_start: float
    xi: float
    wave_speed: float = STEEL_BAR_SPEED

    def __post_init__(self) -> None:
        if self.family not in FAMILIES:
            raise ValueError(f"family: must be one of {FAMILIES}, got {self.family!r}")
        object.__setattr__(self, "area_start", positive("area_start", self.area_start, "m^2"))
        object.__setattr__(self, "xi", finite("xi", self.xi, "1/m"))
        object.__setattr__(self, "wave_speed", positive("wave_speed", self.wave_speed, "m/s"))

    # ------------------------------------------------------------------ geometry
    def _shape(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """sqrt(A(x)/A0) = 1 / (a(x)/a0): the square root of the relative area."""
        xi = self.xi
        if self.family == "quadratic":
            return 1.0 + xi * x
        if self.family == "exponential":
            return np.exp(0.5 * xi * x)
        if self.family == "cosh2":
            return np.cosh(xi * x)
        return np.cos(xi * x)

    def _positions(self, x: ArrayLike) -> NDArray[np.float64]:
        arr = np.asarray(x, dtype=float)
        if not np.all(np.isfinite(arr)):
            raise ValueError("x: positions must be finite (m)")
        s = self._shape(arr)
        if np.any(s <= 0.0):
            bad = float(np.ravel(arr)[np.flatnonzero(np.ravel(s) <= 0.0)[0]])
            raise ValueError(
                f"x: the {self.family} area vanishes or changes sign at x = {bad!r} m for xi = {self.xi!r} 1/m; "
                f"valid positions have {'1 + xi x > 0' if self.family == 'quadratic' else '|xi x| < pi/2'}"
            )
        return arr

    def area(self, x: ArrayLike) -> NDArray[np.float64]:
        """Cross-section area A(x) in m^2 (Tab. 2.1, first column)."""
        arr = self._positions(x)
        return self.area_start * self._shape(arr) ** 2

    def area_gradient_ratio(self, x: ArrayLike) -> NDArray[np.float64]:
        """h(x) = A'(x)/A(x) in 1/m (eq. 2.12)."""
        arr = self._positions(x)
        xi = self.xi
        if self.family == "quadratic":
            return 2.0 * xi / (1.0 + xi * arr)
        if self.family == "exponential":
            return np.full_like(arr, xi)
        if self.family == "cosh2":
            return 2.0 * xi * np.tanh(xi * arr)
        return -2.0 * xi * np.tan(xi * arr)

    # ------------------------------------------------------------------ dispersion (Tab. 2.1)
    @property
    def b(self) -> float:
        """The constant b = h^2/4 + h'/2 of eq. (2.17) in 1/m^2."""
        xi2 = self.xi**2
        return {"quadratic": 0.0, "exponential": 0.25 * xi2, "cosh2": xi2, "cos2": -xi2}[self.family]

    @property
    def cutoff_angular_frequency(self) -> float:
        """omega_c = c0 sqrt(b) in rad/s for b > 0 (eq. 2.19); 0 for b <= 0 (no cutoff)."""
        return self.wave_speed * math.sqrt(self.b) if self.b > 0.0 else 0.0

    def wave_number(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """k(omega) = sqrt(omega^2/c0^2 - b) in 1/m, eq. (2.17), as a complex array.

        Real and >= 0 at and above the cutoff; below it purely imaginary with positive imaginary part (the
        branch that decays in +x for the ansatz exp(i k x)).
        """
        w = np.asarray(omega, dtype=float)
        if not np.all(np.isfinite(w)) or np.any(w < 0.0):
            raise ValueError("omega: angular frequencies must be finite and >= 0 (rad/s)")
        k2 = (w / self.wave_speed) ** 2 - self.b
        return np.where(k2 >= 0.0, np.sqrt(np.abs(k2)) + 0j, 1j * np.sqrt(np.abs(k2)))

    def phase_velocity(self, omega: ArrayLike) -> NDArray[np.float64]:
        """Phase velocity c_p = omega/k in m/s, eq. (2.18), for propagating waves.

        Raises ``ValueError`` for ``omega <= omega_c`` (no propagating wave; c_p -> infinity at the cutoff) and for
        ``omega <= 0``.
        """
        w = np.asarray(omega, dtype=float)
        wc = self.cutoff_angular_frequency
        if not np.all(np.isfinite(w)) or np.any(w <= max(wc, 0.0)):
            raise ValueError(
                f"omega: the phase velocity of the {self.family} family exists only for omega > "
                f"{wc:.6g} rad/s (cutoff, eq. 2.19) and omega > 0"
            )
        c0 = self.wave_speed
        return c0 / np.sqrt(1.0 - c0**2 * self.b / w**2)

    def amplitude(self, x: ArrayLike, amplitude_start: float = 1.0) -> NDArray[np.float64]:
        """Wave amplitude a(x) = a0 sqrt(A0/A(x)), eq. (2.16) (last column of Tab. 2.1)."""
        a0 = finite("amplitude_start", amplitude_start)
        arr = self._positions(x)
        return a0 / self._shape(arr)

    def travelling_wave(self, x: ArrayLike, t: ArrayLike, omega: float) -> NDArray[np.complex128]:
        """u(x, t) = a(x) exp(i (k x - omega t)), eq. (2.13), with a0 = 1; broadcasts x against t.

        It solves the PDE (2.12) exactly for every omega (evanescent below the cutoff).
        """
        w = finite("omega", omega, "rad/s")
        if w < 0.0:
            raise ValueError(f"omega: must be >= 0 rad/s, got {omega!r}")
        k = self.wave_number(w)
        xa = np.asarray(x, dtype=float)
        return self.amplitude(xa) * np.exp(1j * (k * xa - w * np.asarray(t, dtype=float)))

    @classmethod
    def table(cls, area_start: float, xi: float, wave_speed: float = STEEL_BAR_SPEED) -> tuple[AnalyticProfile, ...]:
        """All four Tab. 2.1 families with the same A0, xi and c0, in table order."""
        return tuple(cls(f, area_start, xi, wave_speed) for f in FAMILIES)  # type: ignore[arg-type]
