"""First-mode Pochhammer-Chree dispersion in a solid circular bar, and dispersive propagation.

The 1D model of the thesis propagates every frequency at the bar speed ``c0 = sqrt(E/rho)``.
A real bar of radius ``a`` propagates the first longitudinal mode at a phase velocity
``c(f) < c0`` that falls towards the Rayleigh surface-wave speed ``c_R`` at short
wavelengths. That is what makes a measured step ring ("Pochhammer-Chree oscillations") and
rise over a finite time, even for a perfectly flat impact.

Frequency equation
------------------
For axisymmetric waves ``exp(i(k z - omega t))`` in a traction-free cylinder (Pochhammer
1876, Chree 1889; in the form used by Bancroft 1941 and Graff, *Wave Motion in Elastic
Solids*, sec. 8.2),

    (2 alpha / a) (beta^2 + k^2) J1(alpha a) J1(beta a)
        - (beta^2 - k^2)^2 J0(alpha a) J1(beta a) - 4 k^2 alpha beta J1(alpha a) J0(beta a) = 0,

    alpha^2 = omega^2 / c1^2 - k^2,   beta^2 = omega^2 / c2^2 - k^2,

with the dilatational speed ``c1`` and shear speed ``c2``; ``c0^2 / c2^2 = 2 (1 + nu)`` and
``c2^2 / c1^2 = (1 - 2 nu) / (2 (1 - nu))``. Dividing by ``beta`` and by ``k^4`` and writing
``H(x) = J1(sqrt(x) a) / (sqrt(x) a)``, ``E(x) = J0(sqrt(x) a)`` (real for both signs of
``x``: ``I1(s)/s`` and ``I0(s)`` for ``x < 0``) gives the real, regular function solved here

    F = H_beta [2 (b + 1) a' H_alpha - (b - 1)^2 E_alpha] - 4 a' H_alpha E_beta,

``a' = alpha^2 / k^2 = c^2/c1^2 - 1``, ``b = beta^2 / k^2 = c^2/c2^2 - 1``. Its long-wave limit
gives exactly ``c = c0``. Modified Bessel functions are used exponentially scaled (every
term holds one alpha and one beta factor, so a common positive factor drops out), which
keeps ``F`` finite at short wavelengths.

Root selection
--------------
The first mode is the smallest positive root: for a given wavenumber (or frequency) ``F`` is
sampled on a grid of phase velocities from ``0.9 c_R`` up to ``c0``, the first sign change is
bracketed and refined with :func:`scipy.optimize.brentq`. Higher modes lie above the first
at every wavenumber, so they are never picked. (The first mode does not stay above ``c_R``:
at short wavelengths it dips slightly below it - by at most 2.2 % for ``nu >= 0``, checked
by a fine scan down to ``0.3 c_R`` for ``k a`` up to 200 - and approaches ``c_R`` from below; hence the margin.)

Propagation
-----------
:func:`propagate_dispersive` moves a signal over a distance ``z`` along the bar *relative to
the 1D travel time* ``z / c0``: each Fourier component is delayed by
``z (1 / c(f) - 1 / c0)``. The result is therefore directly comparable with a 1D prediction at
the same position. A negative distance undoes the propagation (dispersion correction); the two
are exact inverses except for content that leaves the record and, for signals with content at
the Nyquist frequency, the phase there, which cannot be represented consistently for +f_N and
-f_N (odd transform lengths are used so that no lone Nyquist bin exists). Only the phase is
changed; the radial variation of strain over the cross-section (Davies' factors) is not
modelled, and all energy is assumed to travel in the first mode.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np
from scipy import fft as _fft
from scipy import optimize, special
from scipy.interpolate import CubicSpline

from .._validate import finite, fits_in_memory, positive

__all__ = [
    "PochhammerChree",
    "phase_velocity_at_frequency",
    "phase_velocity_at_wavelength",
    "propagate_dispersive",
    "rayleigh_speed_ratio",
]

_SCAN_POINTS = 400

#: Largest dispersion table (nodes, each an exact root solve of about 0.5 ms) a :class:`PochhammerChree` builds.
_MAX_TABLE_NODES = 50_000

#: Largest accepted ``table_step`` (in ``f a / c0``): coarser tables interpolate the curve poorly.
_MAX_TABLE_STEP = 0.05


def _poisson(nu: Any) -> float:
    nu = finite("poisson_ratio", nu)
    if not 0.0 <= nu < 0.5:
        raise ValueError(f"poisson_ratio must lie in [0, 0.5) for the Pochhammer-Chree solver, got {nu!r}")
    return nu


def _speed_ratios(nu: float) -> tuple[float, float]:
    """``(c0/c2, c2/c1)`` for Poisson's ratio ``nu``."""
    return float(np.sqrt(2.0 * (1.0 + nu))), float(np.sqrt((1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))))


def rayleigh_speed_ratio(poisson_ratio: float) -> float:
    """Rayleigh surface-wave speed over shear speed, ``c_R / c2``, from Rayleigh's equation.

    Solves ``(2 - xi)^2 = 4 sqrt(1 - xi m) sqrt(1 - xi)`` with ``xi = c^2 / c2^2`` and
    ``m = c2^2 / c1^2`` for its root in ``(0, 1)``.
    """
    return _rayleigh_speed_ratio(_poisson(poisson_ratio))


@lru_cache(maxsize=64)
def _rayleigh_speed_ratio(nu: float) -> float:
    _, r21 = _speed_ratios(nu)
    m = r21 * r21

    def rayleigh(xi: float) -> float:
        return (2.0 - xi) ** 2 - 4.0 * np.sqrt(1.0 - xi * m) * np.sqrt(1.0 - xi)

    xi = optimize.brentq(rayleigh, 1e-6, 1.0 - 1e-15, xtol=1e-15, rtol=1e-15)
    return float(np.sqrt(xi))


def _e_h(x2: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``E = J0(s)``, ``H = J1(s)/s`` with ``s = sqrt(x2)`` (radius 1), exponentially scaled
    for ``x2 < 0``; returns ``(E, H, log_scale)`` where the true values are ``(E, H) * exp(log_scale)``."""
    x2 = np.asarray(x2, dtype=float)
    s = np.sqrt(np.abs(x2))
    neg = x2 < 0
    small = s < 1e-6
    s_safe = np.where(small, 1.0, s)
    e = np.where(neg, special.i0e(s), special.j0(s))
    h_big = np.where(neg, special.i1e(s_safe), special.j1(s_safe)) / s_safe
    h_small = np.where(neg, 0.5 * np.exp(-s), 0.5 - s * s / 16.0)
    h = np.where(small, h_small, h_big)
    return e, h, np.where(neg, s, 0.0)


def _frequency_function(cbar: np.ndarray, ka: np.ndarray, nu: float) -> np.ndarray:
    """Scaled Pochhammer-Chree function ``F`` (module docstring) at phase velocity ``c/c0``
    and normalised wavenumber ``k a``; only its sign and zeros matter."""
    r02, r21 = _speed_ratios(nu)
    c_over_c2 = cbar * r02
    b = c_over_c2**2 - 1.0
    a_ = (c_over_c2 * r21) ** 2 - 1.0
    k2 = ka * ka
    e_a, h_a, _ = _e_h(k2 * a_)
    e_b, h_b, _ = _e_h(k2 * b)
    return h_b * (2.0 * (b + 1.0) * a_ * h_a - (b - 1.0) ** 2 * e_a) - 4.0 * a_ * h_a * e_b


def _first_root(func, lower: float, upper: float) -> float:
    """Smallest root of ``func`` on ``[lower, upper]`` by grid scan + Brent."""
    grid = np.linspace(lower, upper, _SCAN_POINTS)
    values = func(grid)
    sign = np.sign(values)
    change = np.flatnonzero(sign[:-1] * sign[1:] <= 0)
    if change.size == 0:
        raise RuntimeError("no first-mode root bracketed; the Pochhammer-Chree scan failed")
    i = int(change[0])
    if values[i] == 0:
        return float(grid[i])
    return float(optimize.brentq(lambda c: float(func(np.array([c]))[0]), grid[i], grid[i + 1], xtol=1e-14, rtol=1e-13))


def _lower_bound(nu: float) -> float:
    r02, _ = _speed_ratios(nu)
    return 0.9 * rayleigh_speed_ratio(nu) / r02


def phase_velocity_at_wavelength(poisson_ratio: float, radius_over_wavelength: Any) -> np.ndarray:
    """First-mode phase velocity ``c / c0`` at given ``a / Lambda`` (radius over wavelength).

    This is the form in which Bancroft (1941) tabulated the solution (there against
    ``d / Lambda = 2 a / Lambda``). ``a/Lambda = 0`` gives exactly 1.
    """
    nu = _poisson(poisson_ratio)
    ratio = np.asarray(radius_over_wavelength, dtype=float)
    if np.any(~np.isfinite(ratio)) or np.any(ratio < 0):
        raise ValueError("radius_over_wavelength must be finite and non-negative")
    lower = _lower_bound(nu)
    out = np.ones(ratio.shape)
    for idx, value in np.ndenumerate(ratio):
        if value > 0:
            ka = 2.0 * np.pi * value
            out[idx] = _first_root(lambda c, ka=ka: _frequency_function(c, np.full_like(c, ka), nu), lower, 1.0)
    return out


def phase_velocity_at_frequency(poisson_ratio: float, normalized_frequency: Any) -> np.ndarray:
    """First-mode phase velocity ``c / c0`` at normalised frequency ``f a / c0`` (exact solve)."""
    nu = _poisson(poisson_ratio)
    fbar = np.asarray(normalized_frequency, dtype=float)
    if np.any(~np.isfinite(fbar)) or np.any(fbar < 0):
        raise ValueError("normalized_frequency must be finite and non-negative")
    lower = _lower_bound(nu)
    out = np.ones(fbar.shape)
    for idx, value in np.ndenumerate(fbar):
        if value > 0:
            omega = 2.0 * np.pi * value  # omega a / c0

            def func(c: np.ndarray, omega: float = omega) -> np.ndarray:
                return _frequency_function(c, omega / c, nu)

            out[idx] = _first_root(func, lower, 1.0)
    return out


@dataclass(frozen=True)
class PochhammerChree:
    """First-mode dispersion of a solid circular bar.

    Parameters: ``poisson_ratio``, ``radius`` (m), ``bar_wave_speed`` ``c0 = sqrt(E/rho)`` (m/s).
    For non-circular bars use the radius of the circle of equal area (an approximation).

    :meth:`phase_velocity` solves the frequency equation on a grid of normalised
    frequencies with spacing ``table_step`` (in ``f a / c0``) and interpolates with a cubic
    spline; the grid is extended on demand and cached per instance.
    """

    poisson_ratio: float
    radius: float
    bar_wave_speed: float
    table_step: float = 0.005
    _table: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "poisson_ratio", _poisson(self.poisson_ratio))
        for what, unit in (("radius", "m"), ("bar_wave_speed", "m/s"), ("table_step", "")):
            object.__setattr__(self, what, positive(what, getattr(self, what), unit))
        if self.table_step > _MAX_TABLE_STEP:
            raise ValueError(f"table_step: at most {_MAX_TABLE_STEP} (in f a / c0) for an accurate interpolation of "
                             f"the dispersion curve, got {self.table_step!r}")

    def normalized_frequency(self, frequency: Any) -> np.ndarray:
        """``f a / c0``."""
        try:
            f = np.asarray(frequency, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"frequency: must be a number or an array of numbers in Hz, got {frequency!r}") from None
        if not np.all(np.isfinite(f)):
            raise ValueError(f"frequency: must be finite, got {frequency!r}")
        return np.abs(f) * self.radius / self.bar_wave_speed

    def _table_nodes(self, fbar_max: float) -> int:
        """Number of table nodes needed up to the normalised frequency ``fbar_max``."""
        return int(np.ceil(max(fbar_max * 1.25, 0.5) / self.table_step)) + 1

    def _check_table(self, fbar_max: float, name: str, hint: str) -> None:
        n = self._table_nodes(fbar_max)
        if n > _MAX_TABLE_NODES:
            f = fbar_max * self.bar_wave_speed / self.radius
            raise ValueError(f"{name}: up to {f:.4g} Hz (f a / c0 = {fbar_max:.4g}) the dispersion table would need "
                             f"{n} exact solutions at table_step = {self.table_step:g}, more than "
                             f"{_MAX_TABLE_NODES}; {hint}")

    def _spline(self, fbar_max: float) -> CubicSpline:
        cached = self._table.get("spline")
        if cached is not None and self._table["fbar_max"] >= fbar_max:
            return cached
        self._check_table(fbar_max, "frequency", "ask for lower frequencies or use a larger table_step")
        n = self._table_nodes(fbar_max)
        nodes = np.linspace(0.0, (n - 1) * self.table_step, n)
        values = phase_velocity_at_frequency(self.poisson_ratio, nodes)
        spline = CubicSpline(nodes, values)
        self._table.update(spline=spline, fbar_max=float(nodes[-1]))
        return spline

    def phase_velocity(self, frequency: Any) -> np.ndarray:
        """First-mode phase velocity (m/s) at ``frequency`` (Hz; the sign is ignored)."""
        fbar = self.normalized_frequency(frequency)
        if fbar.size == 0:
            return fbar.copy()
        if not np.all(np.isfinite(fbar)):
            raise ValueError("frequency must be finite")
        return self._spline(float(np.max(fbar)))(fbar) * self.bar_wave_speed

    def wavenumber(self, frequency: Any) -> np.ndarray:
        """``k = 2 pi f / c(f)`` (rad/m)."""
        f = np.abs(np.asarray(frequency, dtype=float))
        return 2.0 * np.pi * f / self.phase_velocity(f)

    def group_velocity(self, frequency: Any) -> np.ndarray:
        """``c_g = d omega / d k`` (m/s), from the interpolated dispersion curve.

        With ``c = c0 g(fbar)``: ``c_g = c / (1 - (fbar / g) g'(fbar))``.
        """
        fbar = self.normalized_frequency(frequency)
        spline = self._spline(float(np.max(fbar)) if fbar.size else 0.0)
        g = spline(fbar)
        dg = spline(fbar, 1)
        return self.bar_wave_speed * g / (1.0 - fbar * dg / g)


def propagate_dispersive(time: Any, values: Any, distance: float, model: PochhammerChree) -> np.ndarray:
    """The signal seen after travelling ``distance`` (m) along the bar, relative to ``distance / c0``.

    Each Fourier component at frequency ``f`` is delayed by ``distance (1/c(f) - 1/c0)``
    (module docstring); ``distance < 0`` applies the inverse (dispersion correction). The
    time axis must be uniform. The record is zero-padded by at least the largest dispersive
    shift before the FFT, so nothing wraps around into the returned window, but content
    moved beyond the end of the record (or, for ``distance < 0``, before its start) is cut
    off: leave quiet time around the pulse and start and end it at rest (zero).
    """
    t = np.asarray(time, dtype=float)
    x = np.asarray(values, dtype=float)
    if t.ndim != 1 or x.shape != t.shape or t.size < 2:
        raise ValueError("time and values must be 1-D arrays of equal length (at least 2 samples)")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x))):
        raise ValueError("time and values must be finite")
    if not isinstance(model, PochhammerChree):
        raise TypeError(f"model must be a PochhammerChree, got {type(model).__name__}")
    steps = np.diff(t)
    dt = float(np.median(steps))
    if dt <= 0 or np.any(np.abs(steps - dt) > 1e-6 * dt):
        raise ValueError("propagate_dispersive needs a uniform, increasing time axis")
    distance = finite("distance", distance, "m")
    if distance == 0.0:
        return x.copy()
    nyquist = 0.5 / dt
    model._check_table(float(model.normalized_frequency(nyquist)), "time",
                       f"its sample interval {dt:.4g} s puts the Nyquist frequency that high; resample the signal to a "
                       "coarser grid (after a low-pass) or use a model with a larger table_step")
    c_slowest = float(np.min(model.phase_velocity(np.linspace(0.0, nyquist, 64))))
    max_shift = abs(distance) * (1.0 / c_slowest - 1.0 / model.bar_wave_speed)
    n_pad = x.size + max_shift / dt + 16
    fits_in_memory("distance", 64.0 * n_pad,
                   f"propagating over {distance:.4g} m (dispersive shifts up to {max_shift:.4g} s, {n_pad:.3g} samples "
                   "with the zero padding)", "use a shorter distance or a coarser time step")
    # An odd transform length has no Nyquist bin, whose single real coefficient could not carry
    # the phase shift; that keeps propagation and correction exact inverses.
    n_total = _fft.next_fast_len(x.size + int(np.ceil(max_shift / dt)) + 16, real=True)
    while n_total % 2 == 0:
        n_total = _fft.next_fast_len(n_total + 1, real=True)
    spectrum = _fft.rfft(x, n=n_total)
    f = _fft.rfftfreq(n_total, dt)
    delay = distance * (1.0 / model.phase_velocity(f) - 1.0 / model.bar_wave_speed)
    spectrum *= np.exp(-2j * np.pi * f * delay)
    return _fft.irfft(spectrum, n=n_total)[: x.size]
