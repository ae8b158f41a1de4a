"""Exact wave-train (de Saint-Venant) solution for rods made of uniform pieces (thesis Sec. 2.3).

Every piece i has a constant impedance Z_i and travel time tau_i (any positive reals: no common time step).
The initial state is piecewise uniform (N = 0, velocity ``striker_velocity`` in the striker pieces and
``rod_velocity`` in the struck-rod pieces), so the solution is a superposition of step waves (D'Alembert,
eq. 2.24): each *front* carries a force jump ``a`` and a velocity jump ``-a/Z`` (travelling in +x) or ``+a/Z``
(travelling in -x). Fronts are followed from interface to interface in time order:

* bonded interface from Z1 (left) to Z2 (right), incident amplitudes a_L (from the left) and a_R (from the right):
  outgoing ``b_L = R12 a_L + T21 a_R`` into the left piece, ``b_R = T12 a_L + R21 a_R`` into the right piece with
  ``T_ij = 2 Z_j/(Z_i + Z_j)``, ``R_ij = (Z_j - Z_i)/(Z_i + Z_j)`` (eqs. 2.37-2.40);
* free end ``b = -a``, fixed end ``b = +a`` (eqs. 2.43-2.44), non-reflecting end: absorbed;
* the contact between striker and rod (or a rigid wall): bonded scattering while the resulting contact force is
  compressive; if it would become tensile (``contact="unilateral"``) both faces become free, ``b = -(N_c + a)``,
  and the gap ``u_rod - u_striker`` is integrated exactly from the (piecewise constant) face velocities; when it
  closes the faces meet like a new impact: ``N_c = -Z1 Z2 (v_l - v_r)/(Z1 + Z2)`` (a wall: ``Z2 -> inf``).

Fronts arriving at the same interface at the same time (within 1e-9 of the shortest travel time) are summed,
so commensurate travel times keep the number of fronts linear in time. The result is exact up to ``duration``
(up to rounding); the number of fronts is capped by ``max_fronts``.

Coordinates: striker pieces occupy ``[-L1, 0]`` (left to right), rod pieces ``[0, L2]``; the contact is x = 0.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rodimpact._validate import finite, finite_values, positive
from rodimpact.reference.families import STEEL_BAR_SPEED

__all__ = ["UniformPiece", "WaveTrainSolution", "solve_wave_trains"]

EndKind = Literal["free", "fixed", "nonreflecting"]


@dataclass(frozen=True)
class UniformPiece:
    """A piece of constant impedance ``Z = rho c A`` (N s/m) and travel time ``tau`` (s); length = c tau."""

    impedance: float
    travel_time: float
    wave_speed: float = STEEL_BAR_SPEED

    def __post_init__(self) -> None:
        object.__setattr__(self, "impedance", positive("impedance", self.impedance, "N s/m"))
        object.__setattr__(self, "travel_time", positive("travel_time", self.travel_time, "s"))
        object.__setattr__(self, "wave_speed", positive("wave_speed", self.wave_speed, "m/s"))

    @property
    def length(self) -> float:
        return self.wave_speed * self.travel_time


@dataclass(frozen=True, eq=False)
class WaveTrainSolution:
    """Result of :func:`solve_wave_trains`: contact-force history and all fronts (fields on demand)."""

    pieces: tuple[UniformPiece, ...]
    n_striker: int
    x_left: NDArray[np.float64]  # global x of each piece's left end
    initial_velocity: NDArray[np.float64]  # per piece
    duration: float
    contact_times: NDArray[np.float64]  # times at which the contact force changes
    contact_values: NDArray[np.float64]  # contact force from that time on (N, tension positive)
    front_piece: NDArray[np.int64]
    front_direction: NDArray[np.int64]  # +1 travelling in +x, -1 in -x
    front_time: NDArray[np.float64]  # emission time at the piece boundary
    front_amplitude: NDArray[np.float64]  # force jump across the front (N)
    separations: NDArray[np.float64]  # times of loss of contact
    recontacts: NDArray[np.float64]  # times of (re-)contact, including the impact at t = 0

    def contact_force(self, t: ArrayLike) -> NDArray[np.float64]:
        """Contact force N(0, t) in N (right-continuous in t; 0 before the impact); t finite, up to ``duration``."""
        ta = finite_values("t", t, "times (s)")
        if np.any(ta > self.duration * (1 + 1e-12)):
            raise ValueError(f"t: the wave-train solution was computed up to duration = {self.duration:.6g} s")
        i = np.searchsorted(self.contact_times, ta, side="right") - 1
        return np.where(i >= 0, self.contact_values[np.clip(i, 0, None)], 0.0)

    def fields(self, x: ArrayLike, t: float) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Normal force N (N), velocity v (m/s) and displacement u (m) at global positions x and time t (s)."""
        tt = finite("t", t, "s")
        if tt > self.duration * (1 + 1e-12) or tt < 0:
            raise ValueError(f"t: must lie in [0, {self.duration:.6g}] s")
        xa = np.atleast_1d(finite_values("x", x, "positions (m)", max_ndim=1))
        edges = np.append(self.x_left, self.x_left[-1] + self.pieces[-1].length)
        if np.any(xa < edges[0] - 1e-12) or np.any(xa > edges[-1] + 1e-12):
            raise ValueError(f"x: positions must lie in [{edges[0]:.6g}, {edges[-1]:.6g}] m")
        idx = np.clip(np.searchsorted(edges, xa, side="right") - 1, 0, len(self.pieces) - 1)
        n_out = np.zeros(xa.size)
        v_out = np.zeros(xa.size)
        u_out = np.zeros(xa.size)
        for i, piece in enumerate(self.pieces):
            sel = np.flatnonzero(idx == i)
            if sel.size == 0:
                continue
            fr = np.flatnonzero(self.front_piece == i)
            v0 = self.initial_velocity[i]
            v_out[sel] = v0
            u_out[sel] = v0 * tt
            if fr.size == 0:
                continue
            d = self.front_direction[fr]
            xl = xa[sel] - self.x_left[i]
            dist = np.where(d[None, :] > 0, xl[:, None], piece.length - xl[:, None])
            passed = tt - (self.front_time[fr][None, :] + dist / piece.wave_speed)
            hit = passed >= 0.0
            amp = self.front_amplitude[fr]
            dv = -d * amp / piece.impedance
            n_out[sel] = (hit * amp).sum(axis=1)
            v_out[sel] += (hit * dv).sum(axis=1)
            u_out[sel] += (np.where(hit, passed, 0.0) * dv).sum(axis=1)
        return n_out, v_out, u_out


def solve_wave_trains(
    striker: Sequence[UniformPiece],
    rod: Sequence[UniformPiece] | Literal["wall"],
    striker_velocity: float,
    duration: float,
    rod_velocity: float = 0.0,
    contact: Literal["unilateral", "bonded"] = "unilateral",
    left: EndKind = "free",
    right: EndKind = "nonreflecting",
    max_fronts: int = 2_000_000,
) -> WaveTrainSolution:
    """Exact piecewise-constant solution of a striker hitting a rod (or a rigid wall), see module docstring.

    Parameters
    ----------
    striker, rod:
        Pieces from left to right; ``rod="wall"`` puts a rigid wall at the striker's right face.
    striker_velocity, rod_velocity:
        Initial velocities in m/s (impact needs ``striker_velocity > rod_velocity``).
    duration:
        End time in s; the solution is exact on [0, duration].
    contact:
        ``"unilateral"``: separation when the contact force would become tensile, re-contact when the gap
        closes; ``"bonded"``: the faces stay together for all time (as in the modal model).
    left, right:
        Conditions at the striker's left end and the rod's right end; ``"nonreflecting"`` makes the end piece
        semi-infinite (matched impedance). ``right`` is ignored for a wall.
    """
    def as_pieces(name: str, value: object) -> tuple:
        hint = " or 'wall'" if name == "rod" else ""
        if isinstance(value, (UniformPiece, str)):
            raise TypeError(f"{name}: a sequence of UniformPiece (left to right, e.g. [UniformPiece(Z, tau)]){hint}, "
                            f"got {type(value).__name__} {value!r}")
        try:
            return tuple(value)  # type: ignore[call-overload]
        except TypeError:
            raise TypeError(f"{name}: a sequence of UniformPiece (left to right, e.g. [UniformPiece(Z, tau)]){hint}, "
                            f"got {type(value).__name__}") from None

    pieces_s = as_pieces("striker", striker)
    wall = isinstance(rod, str)
    if wall and rod != "wall":
        raise ValueError(f"rod: a sequence of UniformPiece or 'wall', got {rod!r}")
    pieces_r = () if wall else as_pieces("rod", rod)
    if not pieces_s or (not wall and not pieces_r):
        raise ValueError("striker/rod: need at least one UniformPiece each")
    pieces = pieces_s + pieces_r
    if not all(isinstance(p, UniformPiece) for p in pieces):
        raise TypeError("striker/rod: pieces must be UniformPiece instances")
    v1 = finite("striker_velocity", striker_velocity, "m/s")
    v2 = finite("rod_velocity", rod_velocity, "m/s")
    dur = finite("duration", duration, "s")
    if dur < 0:
        raise ValueError(f"duration: must be >= 0 s, got {duration!r}")
    if isinstance(max_fronts, (bool, np.bool_)) or not isinstance(max_fronts, (int, np.integer)):
        raise TypeError(f"max_fronts: must be a whole number >= 1, got {type(max_fronts).__name__} {max_fronts!r}")
    if max_fronts < 1:
        raise ValueError(f"max_fronts: must be a whole number >= 1, got {max_fronts!r}")
    if contact not in ("unilateral", "bonded"):
        raise ValueError(f"contact: 'unilateral' or 'bonded', got {contact!r}")
    for name, val in (("left", left), ("right", right)):
        if val not in ("free", "fixed", "nonreflecting"):
            raise ValueError(f"{name}: 'free', 'fixed' or 'nonreflecting', got {val!r}")
    if wall:
        v2 = 0.0

    n = len(pieces)
    m = len(pieces_s)  # contact interface index (between piece m-1 and m; m == n for a wall)
    z = np.array([p.impedance for p in pieces])
    tau = np.array([p.travel_time for p in pieces])
    lengths = np.array([p.length for p in pieces])
    x_left = np.concatenate([[-lengths[:m].sum()], -lengths[:m].sum() + np.cumsum(lengths)[:-1]])
    v_init = np.array([v1] * m + [v2] * (n - m))
    quantum = 1e-9 * tau.min()
    z1 = z[m - 1]
    z2 = math.inf if wall else z[m]
    z_contact = z1 if wall else z1 * z2 / (z1 + z2)
    tol_n = 1e-11 * z_contact * max(abs(v1 - v2), 1e-300)
    tol_v = 1e-11 * max(abs(v1 - v2), abs(v1), abs(v2), 1e-300)

    fronts: list[tuple[int, int, float, float]] = []
    pending: dict[tuple[int, int], list[float]] = {}  # (interface, time key) -> [time, a_L, a_R]
    heap: list[tuple[float, int, int, int]] = []  # (time, priority, interface, time key or version)

    def emit(piece: int, direction: int, t_e: float, amp: float) -> None:
        if amp == 0.0:
            return
        fronts.append((piece, direction, t_e, amp))
        if len(fronts) > max_fronts:
            raise ValueError(f"duration: more than max_fronts = {max_fronts} fronts before {dur:.6g} s; "
                             "shorten the duration or use commensurate travel times")
        t_a = t_e + tau[piece]
        if t_a > dur:
            return
        j = piece + 1 if direction > 0 else piece
        key = (j, int(round(t_a / quantum)))
        slot = pending.get(key)
        if slot is None:
            pending[key] = slot = [t_a, 0.0, 0.0]
            heapq.heappush(heap, (t_a, 1, j, key[1]))
        slot[1 if direction > 0 else 2] += amp

    # contact state
    state = {"contact": False, "n_c": 0.0, "v_l": v1, "v_r": v2, "u_l": 0.0, "u_r": 0.0, "t": 0.0, "version": 0}
    contact_t: list[float] = []
    contact_v: list[float] = []
    separations: list[float] = []
    recontacts: list[float] = []

    def advance_gap(t: float) -> None:
        dt = t - state["t"]
        state["u_l"] += state["v_l"] * dt
        state["u_r"] += state["v_r"] * dt
        state["t"] = t

    def schedule_recontact(t: float) -> None:
        state["version"] += 1
        closing = state["v_l"] - state["v_r"]
        if closing <= tol_v:
            return
        gap = max(state["u_r"] - state["u_l"], 0.0)
        t_c = t + gap / closing
        if t_c <= dur:
            heapq.heappush(heap, (t_c, 0, m, state["version"]))

    def impact(t: float) -> None:
        closing = state["v_l"] - state["v_r"]
        n_c = -z1 * closing if wall else -z_contact * closing
        state["contact"] = True
        state["n_c"] = n_c
        state["v_l"] += n_c / z1
        state["v_r"] = 0.0 if wall else state["v_r"] - n_c / z2
        emit(m - 1, -1, t, n_c)
        if not wall:
            emit(m, +1, t, n_c)
        contact_t.append(t), contact_v.append(n_c), recontacts.append(t)

    # t = 0: the impact (faces touch with zero gap)
    if v1 > v2 or contact == "bonded":
        heapq.heappush(heap, (0.0, 0, m, 0))

    while heap:
        t, prio, j, key = heapq.heappop(heap)
        if prio == 0:  # (re-)contact event
            if key != state["version"] or state["contact"]:
                continue
            advance_gap(t)
            impact(t)
            state["version"] += 1
            continue
        _, a_l, a_r = pending.pop((j, key))
        if j == m:  # contact interface
            advance_gap(t)
            if state["contact"]:
                if wall:
                    b_l, b_r = a_l, 0.0
                else:
                    b_l = (z2 - z1) / (z1 + z2) * a_l + 2 * z1 / (z1 + z2) * a_r
                    b_r = 2 * z2 / (z1 + z2) * a_l + (z1 - z2) / (z1 + z2) * a_r
                n_new = state["n_c"] + a_l + b_l
                if contact == "unilateral" and n_new > tol_n:
                    b_l = -(state["n_c"] + a_l)
                    b_r = -(state["n_c"] + a_r)
                    state["contact"] = False
                    state["n_c"] = 0.0
                    separations.append(t)
                    contact_t.append(t), contact_v.append(0.0)
                else:
                    state["n_c"] = n_new
                    contact_t.append(t), contact_v.append(n_new)
            else:
                b_l, b_r = -a_l, -a_r
            state["v_l"] += (-a_l + b_l) / z1
            if not wall:
                state["v_r"] += (a_r - b_r) / z2
            emit(m - 1, -1, t, b_l)
            if not wall:
                emit(m, +1, t, b_r)
            if not state["contact"]:
                schedule_recontact(t)
        elif j == 0:  # left end of the striker
            if left != "nonreflecting":
                emit(0, +1, t, -a_r if left == "free" else a_r)
        elif j == n:  # right end of the rod
            if right != "nonreflecting":
                emit(n - 1, -1, t, -a_l if right == "free" else a_l)
        else:  # bonded interior interface
            za, zb = z[j - 1], z[j]
            emit(j - 1, -1, t, (zb - za) / (za + zb) * a_l + 2 * za / (za + zb) * a_r)
            emit(j, +1, t, 2 * zb / (za + zb) * a_l + (za - zb) / (za + zb) * a_r)

    fr = np.array(fronts, dtype=float).reshape(-1, 4)
    return WaveTrainSolution(
        pieces=pieces, n_striker=m, x_left=x_left, initial_velocity=v_init, duration=dur,
        contact_times=np.array(contact_t), contact_values=np.array(contact_v),
        front_piece=fr[:, 0].astype(np.int64), front_direction=fr[:, 1].astype(np.int64),
        front_time=fr[:, 2], front_amplitude=fr[:, 3],
        separations=np.array(separations), recontacts=np.array(recontacts),
    )
