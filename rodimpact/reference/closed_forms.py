"""Closed-form impact solutions (contact force histories and fields).

Sign convention: normal force N positive in tension, so impact forces are negative; the striker moves in +x
with ``impact_velocity > 0`` and hits the rod (or wall) at its right face x = 0 at t = 0. Impedance
``Z = rho c A`` (N s/m, thesis eq. 2.8), travel time ``T = L / c``.

References: thesis Sec. 2.3 (D'Alembert solution, transmission/reflection factors 2.37-2.44) and Sec. 4.2.1
(eq. 4.26, after Lundberg & Lesser, J. Sound Vib. 1978); Graff, *Wave Motion in Elastic Solids*, Sec. 2.3;
Johnson, *Impact Strength of Materials*, Ch. 4 (rigid mass on a bar).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact._validate import finite, finite_values, positive, positive_array
from rodimpact.reference.wavetrains import UniformPiece, solve_wave_trains

__all__ = [
    "uniform_striker_force",
    "rigid_mass_force",
    "rod_against_wall_force",
    "rod_against_wall_fields",
    "stepped_striker_force",
    "lundberg_lesser_impedance",
    "lundberg_lesser_force",
    "lundberg_lesser_face_impedance",
]


def _times(t: ArrayLike) -> NDArray[np.float64]:
    """Times t (s): a number or a non-empty array of finite real numbers (any shape; the result has it)."""
    return finite_values("t", t, "times (s)")


def uniform_striker_force(
    t: ArrayLike, striker_impedance: float, rod_impedance: float, striker_travel_time: float, impact_velocity: float
) -> NDArray[np.float64]:
    """Contact force of a uniform striker (Z1, T1 = L1/c1, free far end) on a semi-infinite uniform rod (Z2).

    Derivation. At t = 0 continuity of velocity and force at the face (eqs. 2.30-2.31) gives
    ``N0 = -Z1 Z2 v / (Z1 + Z2)``. The wave N0 runs through the striker, is reflected at its free end as ``-N0``
    (eq. 2.44) and is back at the face at ``2 T1``. There the face force changes by ``T21 (-N0)`` with
    ``T21 = 2 Z2/(Z1 + Z2)`` (eq. 2.37 seen from the striker side), i.e. ``N1 = N0 (Z1 - Z2)/(Z1 + Z2) = r N0``;
    repeating, ``N_k = r^k N0`` on ``[2 k T1, 2 (k+1) T1)`` as long as the force stays compressive:

    * ``Z1 <= Z2`` (r <= 0): rectangular pulse ``N0`` of duration ``2 T1``; then the striker is stress-free with
      uniform velocity ``r v <= 0`` and the rod face at rest, so the contact ends for good;
    * ``Z1 > Z2`` (0 < r < 1): the staircase ``r^k N0`` for all time (no separation).

    For a finite rod the result holds until its far-end reflection returns, ``t < 2 L2/c2``.
    """
    ta = _times(t)
    z1 = positive("striker_impedance", striker_impedance, "N s/m")
    z2 = positive("rod_impedance", rod_impedance, "N s/m")
    t1 = positive("striker_travel_time", striker_travel_time, "s")
    v = positive("impact_velocity", impact_velocity, "m/s")
    n0 = -z1 * z2 * v / (z1 + z2)
    r = (z1 - z2) / (z1 + z2)
    k = np.floor(np.maximum(ta, 0.0) / (2.0 * t1))
    if r <= 0.0:
        return np.where((ta >= 0.0) & (k < 1), n0, 0.0)
    return np.where(ta >= 0.0, n0 * r**k, 0.0)


def rigid_mass_force(t: ArrayLike, mass: float, rod_impedance: float, impact_velocity: float) -> NDArray[np.float64]:
    """Contact force of a rigid mass M hitting a semi-infinite uniform rod (Z): ``N = -Z v exp(-Z t / M)``.

    Derivation. The rod at rest only carries a wave travelling away from the face, so at the face
    ``N = -Z V(t)`` (D'Alembert, eq. 2.24, with N = -Z v for +x waves). Newton for the mass, ``M V' = N``
    (the face force acts on the mass in -x when compressive), gives ``M V' = -Z V``, ``V = v exp(-Z t/M)``.
    The force never turns tensile, so there is no separation. It is the limit of the staircase of
    :func:`uniform_striker_force` for ``Z1 -> inf`` at fixed mass ``M = Z1 T1``:
    ``r^(t / 2 T1) -> exp(-Z2 t / M)``. Fields in the rod: ``N(x, t) = N(0, t - x/c)``.
    """
    ta = _times(t)
    m = positive("mass", mass, "kg")
    z = positive("rod_impedance", rod_impedance, "N s/m")
    v = positive("impact_velocity", impact_velocity, "m/s")
    return np.where(ta >= 0.0, -z * v * np.exp(-z * np.maximum(ta, 0.0) / m), 0.0)


def rod_against_wall_force(
    t: ArrayLike, impedance: float, travel_time: float, impact_velocity: float
) -> NDArray[np.float64]:
    """Wall force of a uniform rod (Z, T = L/c, free far end) hitting a rigid wall: ``-Z v`` for ``0 <= t < 2T``.

    Derivation. A fixed face (u = 0) stops the particles it reaches: the wave leaving the wall carries
    ``v -> 0`` and ``N = -Z v`` (the limit ``Z2 -> inf`` of ``-Z1 Z2 v/(Z1 + Z2)``, eq. 2.43). At the free end
    (t = T) it is reflected as an unloading wave (eq. 2.44) behind which ``N = 0`` and the velocity is ``-v``;
    it reaches the wall at ``2T``, where the rod leaves the wall with ``-v`` (elastic rebound) and never returns.
    """
    ta = _times(t)
    z = positive("impedance", impedance, "N s/m")
    t1 = positive("travel_time", travel_time, "s")
    v = positive("impact_velocity", impact_velocity, "m/s")
    return np.where((ta >= 0.0) & (ta < 2.0 * t1), -z * v, 0.0)


def rod_against_wall_fields(
    x: ArrayLike, t: float, impedance: float, length: float, wave_speed: float, impact_velocity: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Force N and velocity v along a uniform rod on ``[-L, 0]`` hitting a rigid wall at x = 0 at t = 0.

    With ``s = -x`` the distance from the wall: before the loading front (``c t < s``) the rod is unloaded and
    moves with v; between the fronts (``s <= c t < 2L - s``) it is at rest under ``N = -Z v``; behind the
    unloading front (``c t >= 2L - s``) it is unloaded and moves with ``-v`` (see :func:`rod_against_wall_force`).
    """
    xa = finite_values("x", x, "positions (m)")
    tt = finite("t", t, "s")
    z = positive("impedance", impedance, "N s/m")
    ll = positive("length", length, "m")
    c = positive("wave_speed", wave_speed, "m/s")
    v = positive("impact_velocity", impact_velocity, "m/s")
    if tt < 0:
        raise ValueError(f"t: must be >= 0 s, got {t!r}")
    if np.any(xa < -ll * (1 + 1e-12)) or np.any(xa > 0.0):
        bad = float(xa[(xa < -ll * (1 + 1e-12)) | (xa > 0.0)].ravel()[0])
        raise ValueError(f"x: positions must lie in [-{ll:.6g}, 0] m (the rod, wall at x = 0), got {bad!r}")
    s = -xa
    ct = c * tt
    loaded = (ct >= s) & (ct < 2 * ll - s)
    released = ct >= 2 * ll - s
    force = np.where(loaded, -z * v, 0.0)
    vel = np.where(released, -v, np.where(loaded, 0.0, v))
    return force, vel


def stepped_striker_force(
    t: ArrayLike,
    impedances: Sequence[float],
    travel_times: Sequence[float] | float,
    rod_impedance: float,
    impact_velocity: float,
    contact: Literal["unilateral", "bonded"] = "unilateral",
) -> NDArray[np.float64]:
    """Contact force of a stepped striker on a semi-infinite uniform rod at rest, exact up to ``max(t)``.

    The striker steps are listed left to right (free end first, impact face last), each with impedance Z_i
    (N s/m) and travel time T_i (s; a scalar applies to all). The force is the sum of all wave trains reflected
    and transmitted at the steps (de Saint-Venant's construction; thesis eqs. 2.37-2.44), followed exactly by
    :func:`~rodimpact.reference.wavetrains.solve_wave_trains`; with ``contact="unilateral"`` the striker
    separates when the force would become tensile and re-contacts if the gap closes. With one step this is
    :func:`uniform_striker_force`.
    """
    ta = _times(t)
    z = positive_array("impedances", impedances)
    tt = finite_values("travel_times", travel_times, "travel times (s)")
    if tt.ndim > 1 or (tt.ndim == 1 and tt.size != z.size):
        raise ValueError(f"travel_times: one per impedance ({z.size}) or a single value, got shape {tt.shape}")
    tt = positive_array("travel_times", np.broadcast_to(tt, z.shape))
    zr = positive("rod_impedance", rod_impedance, "N s/m")
    v = positive("impact_velocity", impact_velocity, "m/s")
    duration = max(float(np.max(ta, initial=0.0)), 0.0)
    striker = [UniformPiece(float(zi), float(ti)) for zi, ti in zip(z, tt)]
    rod = [UniformPiece(zr, max(duration, float(tt.min())))]
    sol = solve_wave_trains(striker, rod, v, duration, contact=contact, left="free", right="nonreflecting")
    return np.where(ta >= 0.0, sol.contact_force(np.maximum(ta, 0.0)), 0.0)


def lundberg_lesser_face_impedance(rod_impedance: float, peak_force: float, impact_velocity: float) -> float:
    """Striker impedance at the impact face, ``Z0 = 1 / (v / N_hat - 1 / Z_rod)`` (thesis eq. 4.26).

    ``N_hat = Z0 Z_rod v / (Z0 + Z_rod)`` is the initial force of two impedances meeting at relative velocity v;
    a positive Z0 exists only for ``N_hat < Z_rod v`` (the rigid-striker limit).
    """
    zr = positive("rod_impedance", rod_impedance, "N s/m")
    nh = positive("peak_force", peak_force, "N")
    v = positive("impact_velocity", impact_velocity, "m/s")
    if nh >= zr * v:
        raise ValueError(f"peak_force: must be < rod_impedance * impact_velocity = {zr * v:.6g} N, got {nh!r}")
    return 1.0 / (v / nh - 1.0 / zr)


def lundberg_lesser_impedance(
    theta: ArrayLike, rod_impedance: float, peak_force: float, time_constant: float, impact_velocity: float
) -> NDArray[np.float64]:
    """Striker impedance Z(theta) that gives the impact force ``-N_hat exp(-t/t0)`` (thesis eq. 4.26).

    ``Z(theta) = Z0 / (1 + (Z_rod + Z0) theta / (Z_rod t0))^2`` with theta the travel time from the impact face
    into the striker (eq. 4.25) and Z0 from :func:`lundberg_lesser_face_impedance`.

    Derivation (Laplace transform, s). Write ``Z = Z0 / (a y)^2`` with ``y = theta + 1/a``. In travel-time
    coordinates the striker obeys ``(Z u_theta)_theta = Z u_tt``; with ``u = y phi`` this becomes
    ``phi'' - 2 phi / y^2 = s^2 phi``, whose outgoing solution is ``exp(-s y) (1 + 1/(s y))``. Hence the
    perturbation displacement is ``U = C exp(-s y) (y + 1/s)`` and the face (theta = 0) force/velocity ratio is
    ``N / W = Z0 s / (s + a)``: a spring-like high-pass. With the semi-infinite rod at rest (``N = -Z_rod
    (v/s + W)``), ``N(s) = -(Z0 Z_rod v / (Z0 + Z_rod)) / (s + a Z_rod / (Z0 + Z_rod))``, i.e.
    ``N(t) = -N_hat exp(-t/t0)`` with ``1/t0 = a Z_rod/(Z0 + Z_rod)``: this is eq. (4.26). A finite striker of
    total travel time Theta reproduces it for ``t < 2 Theta`` (until its free-end reflection returns).
    """
    th = finite_values("theta", theta, "travel times into the striker (s)")
    if np.any(th < 0.0):
        raise ValueError(f"theta: travel times into the striker must be >= 0 s, got {float(th[th < 0.0].ravel()[0])!r}")
    zr = positive("rod_impedance", rod_impedance, "N s/m")
    t0 = positive("time_constant", time_constant, "s")
    z0 = lundberg_lesser_face_impedance(zr, peak_force, impact_velocity)
    return z0 / (1.0 + (zr + z0) * th / (zr * t0)) ** 2


def lundberg_lesser_force(t: ArrayLike, peak_force: float, time_constant: float) -> NDArray[np.float64]:
    """The target impact force of eq. (4.24), ``-N_hat exp(-t/t0)`` for t >= 0 (0 before), in N."""
    ta = _times(t)
    nh = positive("peak_force", peak_force, "N")
    t0 = positive("time_constant", time_constant, "s")
    return np.where(ta >= 0.0, -nh * np.exp(-np.maximum(ta, 0.0) / t0), 0.0)
