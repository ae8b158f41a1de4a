"""Modal expansion for chains of Tab. 2.1 segments (thesis Sec. 3.2, eqs. 3.26-3.47, generalised).

A chain is a sequence of homogeneous segments, each a piece of one Tab. 2.1 family (:class:`AnalyticProfile`),
bonded to each other (continuous displacement u and normal force N = E A u_x), with a free (N = 0) or fixed
(u = 0) condition at either end. The thesis's Setup 3 (uniform striker + exponential horn with a fixed far end,
Fig. 3.11, Tab. 3.3) is the chain built by :class:`HornImpact`.

Mode shapes (eqs. 3.27-3.28 generalised). On a segment with area ``A(x) = A_ref s(x)^2`` (``s = sqrt(A/A_ref)``
in family coordinates) and ``k^2 = omega^2/c0^2 - b`` (eq. 2.17), ``w = s U`` solves ``w'' + k^2 w = 0``, so
``U = (P C(xl) + Q S(xl)) / s(x)`` with the entire functions ``C = cos(k xl)``, ``S = sin(k xl)/k`` of the local
coordinate xl (see :mod:`._entire`); ``k^2 < 0`` (the thesis's imaginary beta below the cutoff ``c0 xi/2``) needs
no special branch. ``N_U = E A_ref (s w' - s' w)``. Instead of solving the 4x4 system (3.33) the modes are shot
from the left end, ``(U, N_U) = (1, 0)`` (free) or ``(0, N_ref)`` (fixed), through the segments (a transfer-matrix
product); the characteristic function is the residual of the right-end condition: ``U(right)`` (fixed) or
``N_U(right)`` (free). For Setup 3 it equals ``exp(-xi l2/2)/2`` times eq. (3.35) divided by alpha beta.

Counting (proof that no root is missed or duplicated). ``(U, N_U)`` defines a Pruefer angle theta(x) that
increases through every zero of U and of N_U (Sturm-Liouville problem with p = E A > 0, weight rho A > 0,
omega^2 > 0). The number of eigenfrequencies in (0, omega] therefore follows exactly from the number of zeros of
U in (left, right] plus the signs of the end state (Sturm oscillation theorem): for a fixed right end it is that
number; for a free right end one less if theta(right) mod pi lies in [0, pi/2), i.e. if U(right) = 0 (the shot
U can round to exactly 0.0, e.g. halfway between two roots of a cut uniform bar) or U(right), N_U(right) have the
same sign, and one more if the left end is fixed. Zeros of ``P cos + (Q/k) sin`` are counted in closed form per
segment, a zero on an interface exactly once. :meth:`ModalChain.eigenfrequencies` brackets on a grid with a
quarter of the asymptotic spacing ``pi / T`` (T: total travel time), subdivides every cell whose count jump is not
0 or 1, and refines each single-root cell with ``scipy.optimize.brentq``.

Orthogonality (3.41-3.43): ``int rho A U_j U_k dx = B_k delta_jk`` with ``rho A U^2 = rho A_ref w^2`` (the shape
factor cancels), integrated in closed form. Initial velocities (3.45-3.46): for a uniform velocity V on a
segment, ``int rho A V U dx = -V [N_U]_a^b / omega^2`` exactly (integrate the mode equation
``(E A U')' = -omega^2 rho A U``). Initial displacements are zero (3.47 gives C6 = 0). Then::

    u(x, t) = sum_k a_k U_k(x) sin(omega_k t) / omega_k   (+ V_bar t for a free-free chain: rigid mode)
    v(x, t) = sum_k a_k U_k(x) cos(omega_k t)              (+ V_bar)
    N(x, t) = sum_k a_k N_Uk(x) sin(omega_k t) / omega_k,  a_k = sum_seg V_seg int rho A U_k / B_k.

The thesis's C5_k is ``a_k / omega_k``. The transitions stay bonded for all time: a modal model cannot separate.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
import scipy.optimize
from numpy.typing import ArrayLike, NDArray

from rodimpact._validate import finite, positive
from rodimpact.reference._entire import cos_sinc, cos_sinc_scalar, square_integrals
from rodimpact.reference.families import STEEL_BAR_SPEED, AnalyticProfile

__all__ = ["ModalSegment", "ModalChain", "ModalSolution"]

End = Literal["free", "fixed"]
_CHUNK = 1 << 21  # max elements of one (positions x modes) block


@dataclass(frozen=True)
class ModalSegment:
    """A homogeneous piece ``[start, start + length]`` (family coordinates) of one Tab. 2.1 family.

    Parameters
    ----------
    profile:
        The family, with A0 = area at family coordinate 0 and the bar speed c0 = sqrt(E/rho).
    length:
        Segment length in m (> 0).
    density:
        Mass density rho in kg/m^3; E = rho c0^2.
    start:
        Family coordinate of the segment's left end (default 0: the segment starts where A = A0).
    """

    profile: AnalyticProfile
    length: float
    density: float = 7840.0
    start: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.profile, AnalyticProfile):
            raise TypeError(f"profile: must be an AnalyticProfile, got {type(self.profile).__name__}")
        object.__setattr__(self, "length", positive("length", self.length, "m"))
        object.__setattr__(self, "density", positive("density", self.density, "kg/m^3"))
        object.__setattr__(self, "start", finite("start", self.start, "m"))
        # validates that the area stays positive on the closed segment
        self.profile.area(np.linspace(self.start, self.start + self.length, 257))

    @classmethod
    def uniform(
        cls, length: float, area: float, density: float = 7840.0, wave_speed: float = STEEL_BAR_SPEED
    ) -> ModalSegment:
        """A uniform segment (quadratic family with xi = 0)."""
        return cls(AnalyticProfile("quadratic", area, 0.0, wave_speed), length, density)

    @property
    def youngs_modulus(self) -> float:
        """E = rho c0^2 in Pa."""
        return self.density * self.profile.wave_speed**2

    @property
    def travel_time(self) -> float:
        """Wave travel time L / c0 in s."""
        return self.length / self.profile.wave_speed

    def shape(self, local_x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """s = sqrt(A/A0) and its derivative s' at local positions (0 = segment start)."""
        xf = self.start + np.asarray(local_x, dtype=float)
        s = 1.0 / self.profile.amplitude(xf)
        return s, 0.5 * self.profile.area_gradient_ratio(xf) * s

    def area(self, local_x: ArrayLike) -> NDArray[np.float64]:
        """Cross-section area in m^2 at local positions."""
        return self.profile.area(self.start + np.asarray(local_x, dtype=float))

    @property
    def mass(self) -> float:
        """Segment mass in kg (Gauss-Legendre quadrature of rho A; smooth integrand)."""
        nodes, weights = np.polynomial.legendre.leggauss(64)
        xl = 0.5 * self.length * (nodes + 1.0)
        return float(self.density * 0.5 * self.length * np.sum(weights * self.area(xl)))


@dataclass(frozen=True)
class _SegmentConstants:
    k2_offset: float  # b
    inv_c2: float
    length: float
    ea_ref: float
    rho_a_ref: float
    s0: float
    s0p: float
    s_l: float
    s_lp: float


@dataclass(frozen=True)
class ModalChain:
    """Bonded chain of :class:`ModalSegment` with free/fixed ends; global x runs from ``origin`` to the right.

    Parameters
    ----------
    segments:
        Segments from left to right (at least one).
    left, right:
        End conditions, ``"free"`` (N = 0) or ``"fixed"`` (u = 0).
    origin:
        Global x of the left end in m (Setup 3: ``-l1`` so that the impact face is at x = 0).
    """

    segments: tuple[ModalSegment, ...]
    left: End = "free"
    right: End = "fixed"
    origin: float = 0.0
    _const: tuple[_SegmentConstants, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        segs = tuple(self.segments)
        if not segs or not all(isinstance(s, ModalSegment) for s in segs):
            raise TypeError("segments: must be a non-empty sequence of ModalSegment")
        object.__setattr__(self, "segments", segs)
        for name in ("left", "right"):
            if getattr(self, name) not in ("free", "fixed"):
                raise ValueError(f"{name}: end condition must be 'free' or 'fixed', got {getattr(self, name)!r}")
        object.__setattr__(self, "origin", finite("origin", self.origin, "m"))
        consts = []
        for seg in segs:
            s0, s0p = (float(v) for v in seg.shape(0.0))
            sl, slp = (float(v) for v in seg.shape(seg.length))
            e = seg.youngs_modulus
            consts.append(
                _SegmentConstants(
                    seg.profile.b, 1.0 / seg.profile.wave_speed**2, seg.length, e * seg.profile.area_start,
                    seg.density * seg.profile.area_start, s0, s0p, sl, slp,
                )
            )
        object.__setattr__(self, "_const", tuple(consts))

    # ------------------------------------------------------------------ geometry
    @property
    def boundaries(self) -> NDArray[np.float64]:
        """Global x of the segment ends, shape (n_segments + 1,)."""
        return self.origin + np.concatenate([[0.0], np.cumsum([s.length for s in self.segments])])

    @property
    def travel_time(self) -> float:
        """Total wave travel time sum L_i / c_i in s (sets the asymptotic eigenfrequency spacing pi / T)."""
        return float(sum(s.travel_time for s in self.segments))

    def _left_state(self) -> tuple[float, float]:
        if self.left == "free":
            return 1.0, 0.0
        c = self._const[0]
        total_length = float(sum(s.length for s in self.segments))
        return 0.0, c.ea_ref * c.s0**2 / total_length  # a static-like scale: U ~ (x - left) / L

    # ------------------------------------------------------------------ shooting
    def _shoot(self, omega: NDArray[np.float64]) -> dict[str, NDArray]:
        """Propagate (U, N_U) from the left end; returns per-segment (P, Q, k2), boundary states and zero counts."""
        w = np.asarray(omega, dtype=float)
        u0, n0 = self._left_state()
        u = np.full_like(w, u0)
        nf = np.full_like(w, n0)
        us, ns, ps, qs, k2s = [u], [nf], [], [], []
        zeros = np.zeros(w.shape, dtype=np.int64)
        for c in self._const:
            k2 = w * w * c.inv_c2 - c.k2_offset
            p = c.s0 * u
            q = nf / (c.ea_ref * c.s0) + c.s0p * u
            cc, ss = cos_sinc(k2, c.length)
            ww = p * cc + q * ss
            wp = -k2 * p * ss + q * cc
            zeros += _zero_count(p, q, k2, c.length, ww, wp)
            u = ww / c.s_l
            nf = c.ea_ref * (c.s_l * wp - c.s_lp * ww)
            ps.append(p), qs.append(q), k2s.append(k2), us.append(u), ns.append(nf)
        return {"p": np.array(ps), "q": np.array(qs), "k2": np.array(k2s), "u": np.array(us), "n": np.array(ns),
                "zeros": zeros}

    def _end_value_scalar(self, omega: float) -> float:
        """Scalar characteristic function (pure math; the brentq objective)."""
        u, nf = self._left_state()
        for c in self._const:
            k2 = omega * omega * c.inv_c2 - c.k2_offset
            p = c.s0 * u
            q = nf / (c.ea_ref * c.s0) + c.s0p * u
            cc, ss = cos_sinc_scalar(k2, c.length)
            ww = p * cc + q * ss
            wp = -k2 * p * ss + q * cc
            u = ww / c.s_l
            nf = c.ea_ref * (c.s_l * wp - c.s_lp * ww)
        return u if self.right == "fixed" else nf

    def characteristic(self, omega: ArrayLike) -> NDArray[np.float64]:
        """Characteristic function D(omega): residual of the right-end condition of the shot mode.

        Real for every real omega (also below cutoffs); its positive roots are the eigenfrequencies in rad/s.
        """
        w = _omega_array(omega)
        st = self._shoot(w)
        return st["u"][-1] if self.right == "fixed" else st["n"][-1]

    def mode_count(self, omega: ArrayLike) -> NDArray[np.int64]:
        """Exact number of eigenfrequencies in (0, omega] (Sturm oscillation theorem, see module docstring)."""
        return self._count_and_residual(_omega_array(omega))[0]

    def _count_and_residual(self, w: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        st = self._shoot(w)
        z = st["zeros"]
        u_end, n_end = st["u"][-1], st["n"][-1]
        if self.right == "fixed":  # roots: theta(right) = n pi, n >= 1; count = zeros of U in (left, right]
            count, residual = z, u_end
        else:  # roots: theta(right) = pi/2 + n pi; subtract the last zero if theta(right) mod pi is in [0, pi/2),
            # i.e. U(right) = 0 (exactly: the zero at the end was counted in z) or U, N of the same strict sign
            past_zero = (u_end == 0.0) | (np.sign(u_end) * np.sign(n_end) > 0.0)
            count, residual = z - past_zero + (0 if self.left == "free" else 1), n_end
        return np.where(w > 0.0, np.maximum(count, 0), 0).astype(np.int64), residual

    # ------------------------------------------------------------------ eigenfrequencies
    def eigenfrequencies(self, n_modes: int) -> NDArray[np.float64]:
        """The lowest ``n_modes`` positive angular eigenfrequencies in rad/s, ascending (cached per chain)."""
        if isinstance(n_modes, bool) or not isinstance(n_modes, (int, np.integer)) or n_modes < 1:
            raise ValueError(f"n_modes: must be a positive integer, got {n_modes!r}")
        return _eigenfrequencies_cached(self, int(n_modes)).copy()

    def _find_roots(self, n_modes: int) -> NDArray[np.float64]:
        spacing = math.pi / self.travel_time
        hi = (n_modes + 2) * spacing
        while int(self.mode_count(hi)) < n_modes:
            hi *= 1.5
        grid = np.linspace(0.0, hi, 4 * int(math.ceil(hi / spacing)) + 1)
        grid[0] = spacing * 1e-9
        total = int(self.mode_count(hi))
        if int(self.mode_count(grid[0])) != 0:
            raise RuntimeError("eigenfrequency search: a root lies below 1e-9 pi/T; chain is ill-conditioned")
        brackets = []
        pending = [grid]
        depth = 0
        while pending:
            nxt = []
            for pts in pending:
                cnt, d = self._count_and_residual(pts)
                jump = np.diff(cnt)
                if np.any(jump < 0):
                    raise RuntimeError("eigenfrequency search: mode count not monotone (numerical breakdown)")
                change = d[:-1] * d[1:] <= 0.0
                ok = (jump == 1) & change
                for i in np.flatnonzero(ok):
                    brackets.append((pts[i], pts[i + 1], d[i], d[i + 1]))
                for i in np.flatnonzero((jump >= 2) | ((jump == 1) & ~change)):
                    nxt.append(np.linspace(pts[i], pts[i + 1], 17))
            pending = nxt
            depth += 1
            if depth > 40 and pending:
                raise RuntimeError("eigenfrequency search: could not separate near-degenerate eigenfrequencies")
        roots = np.empty(len(brackets))
        for j, (a, b, fa, fb) in enumerate(brackets):
            if fa == 0.0:
                roots[j] = a
            elif fb == 0.0:
                roots[j] = b
            else:
                roots[j] = scipy.optimize.brentq(self._end_value_scalar, a, b, xtol=1e-300,
                                                 rtol=4 * np.finfo(float).eps)
        roots.sort()
        # every root sits alone in a cell whose oscillation count rises by exactly one: none missed or doubled
        if roots.size != total or np.any(np.diff(roots) <= 0.0):
            raise RuntimeError("eigenfrequency search: root count inconsistent with the oscillation count")
        return roots[:n_modes]

    # ------------------------------------------------------------------ modes
    def _segment_index(self, x: NDArray[np.float64]) -> NDArray[np.int64]:
        bnd = self.boundaries
        tol = 1e-12 * (bnd[-1] - bnd[0])
        if np.any(x < bnd[0] - tol) or np.any(x > bnd[-1] + tol):
            raise ValueError(f"x: positions must lie in the chain [{bnd[0]:.6g}, {bnd[-1]:.6g}] m")
        return np.clip(np.searchsorted(bnd, x, side="right") - 1, 0, len(self.segments) - 1)

    def mode_shapes(self, x: ArrayLike, omega: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Unnormalised mode shapes U(x) (free-left: U(left) = 1) and their forces N_U = E A U' in N per unit U.

        Shapes ``(n_x, n_omega)``; ``omega`` should be eigenfrequencies (otherwise the right-end condition fails).
        """
        xa = np.atleast_1d(np.asarray(x, dtype=float))
        w = _omega_array(omega)
        st = self._shoot(w)
        return self._shapes_from_state(xa, st)

    def _shapes_from_state(self, xa: NDArray[np.float64], st: dict) -> tuple[NDArray, NDArray]:
        idx = self._segment_index(xa)
        n_w = st["k2"].shape[1]
        u_out = np.empty((xa.size, n_w))
        n_out = np.empty((xa.size, n_w))
        bnd = self.boundaries
        for i, (seg, c) in enumerate(zip(self.segments, self._const)):
            sel = np.flatnonzero(idx == i)
            if sel.size == 0:
                continue
            xl = np.clip(xa[sel] - bnd[i], 0.0, seg.length)
            s, sp = seg.shape(xl)
            p, q, k2 = st["p"][i], st["q"][i], st["k2"][i]
            cc, ss = cos_sinc(k2[None, :], xl[:, None])
            ww = p * cc + q * ss
            wp = -k2 * p * ss + q * cc
            u_out[sel] = ww / s[:, None]
            n_out[sel] = c.ea_ref * (s[:, None] * wp - sp[:, None] * ww)
        return u_out, n_out

    def _sum_modes(self, xa: NDArray[np.float64], st: dict, weights: NDArray[np.float64], kind: str) -> NDArray:
        """sum_k weights[k, :] * U_k(x) (kind "u") or N_Uk(x) (kind "n"), shape (n_x, n_t).

        The per-mode coefficients P_k, Q_k are folded into the weights so that only the matrices
        C = cos(k x) and S = sin(k x)/k are formed, followed by BLAS products.
        """
        idx = self._segment_index(xa)
        out = np.empty((xa.size, weights.shape[1]))
        bnd = self.boundaries
        for i, (seg, c) in enumerate(zip(self.segments, self._const)):
            sel = np.flatnonzero(idx == i)
            if sel.size == 0:
                continue
            xl = np.clip(xa[sel] - bnd[i], 0.0, seg.length)
            s, sp = seg.shape(xl)
            p, q, k2 = st["p"][i], st["q"][i], st["k2"][i]
            cc, ss = cos_sinc(k2[None, :], xl[:, None])
            w_sum = cc @ (p[:, None] * weights) + ss @ (q[:, None] * weights)
            if kind == "u":
                out[sel] = w_sum / s[:, None]
            else:
                wp_sum = cc @ (q[:, None] * weights) - ss @ ((k2 * p)[:, None] * weights)
                out[sel] = c.ea_ref * (s[:, None] * wp_sum - sp[:, None] * w_sum)
        return out

    def modal_masses(self, omega: ArrayLike) -> NDArray[np.float64]:
        """B_k = int rho A U_k^2 dx over the chain in kg (eq. 3.43 times rho), closed form."""
        return self._norms(self._shoot(_omega_array(omega)))

    def _norms(self, st: dict) -> NDArray[np.float64]:
        total = np.zeros(st["k2"].shape[1])
        for i, c in enumerate(self._const):
            icc, ics, iss = square_integrals(st["k2"][i], c.length)
            p, q = st["p"][i], st["q"][i]
            total += c.rho_a_ref * (p * p * icc + 2.0 * p * q * ics + q * q * iss)
        return total

    def expand(self, initial_velocities: Sequence[float], n_modes: int) -> ModalSolution:
        """Modal solution for zero initial displacement and uniform initial velocity per segment (m/s).

        ``initial_velocities[i]`` is the velocity of segment i at t = 0 (eqs. 3.44-3.46 with C6 = 0).
        """
        vel = np.asarray([finite(f"initial_velocities[{i}]", v, "m/s") for i, v in enumerate(initial_velocities)])
        if vel.size != len(self.segments):
            raise ValueError(
                f"initial_velocities: need one velocity per segment ({len(self.segments)}), got {vel.size}")
        rigid = 0.0
        if self.left == "free" and self.right == "free":  # rigid mode U = 1, omega = 0: mean velocity
            masses = np.array([s.mass for s in self.segments])
            rigid = float(np.dot(masses, vel) / masses.sum())
        omega = self.eigenfrequencies(n_modes)
        st = self._shoot(omega)
        norms = self._norms(st)
        proj = np.zeros_like(omega)
        for i in range(len(self.segments)):
            proj += vel[i] * (-(st["n"][i + 1] - st["n"][i]) / omega**2)
        return ModalSolution(chain=self, omega=omega, amplitudes=proj / norms, modal_masses=norms,
                             initial_velocities=tuple(float(v) for v in vel), rigid_velocity=rigid)


@functools.lru_cache(maxsize=32)
def _eigenfrequencies_cached(chain: ModalChain, n_modes: int) -> NDArray[np.float64]:
    return chain._find_roots(n_modes)


def _omega_array(omega: ArrayLike) -> NDArray[np.float64]:
    w = np.asarray(omega, dtype=float)
    if not np.all(np.isfinite(w)) or np.any(w < 0.0):
        raise ValueError("omega: angular frequencies must be finite and >= 0 (rad/s)")
    return w


def _zero_count(p, q, k2, length, w_end, wp_end) -> NDArray[np.int64]:
    """Zeros of w = P cos(k x) + Q sin(k x)/k in (0, L], counted in closed form (entire in k^2).

    For k^2 > 0, ``w = R sin(theta(x))`` with ``theta = k x + phi0`` and the count is the number of multiples of
    pi in ``(theta(0), theta(L)]``. ``theta(L)`` is taken from the computed end values (unwrapped with the exact
    increase k L) so that the count agrees with the sign of the end state that the next segment starts from; a
    zero falling on an interface is then counted exactly once. For k^2 <= 0, w has at most one zero in x > 0.
    """
    pos = k2 > 0.0
    k = np.sqrt(np.where(pos, k2, 1.0))
    phi0 = np.arctan2(p, q / k)
    phi_end = np.arctan2(w_end, wp_end / k)
    turns = np.round((phi0 + k * length - phi_end) / (2.0 * np.pi))
    osc = 2.0 * turns + _floor_half_turns(w_end, wp_end) - _floor_half_turns(p, q)
    mono = (p != 0.0) & ((w_end == 0.0) | (np.sign(w_end) != np.sign(p)))
    return np.where(pos, osc, mono).astype(np.int64)


def _floor_half_turns(y, x) -> NDArray[np.float64]:
    """floor(atan2(y, x) / pi) from the signs alone (no rounding at the branch cut): -1, 0 or 1."""
    return np.where(y < 0.0, -1.0, np.where((y == 0.0) & (x < 0.0), 1.0, 0.0))


@dataclass(frozen=True, eq=False)
class ModalSolution:
    """Truncated modal series of a :class:`ModalChain` for given initial velocities (see module docstring).

    Attributes: ``omega`` (n,) eigenfrequencies in rad/s, ``amplitudes`` a_k in m/s (velocity amplitude of the
    unnormalised mode U_k), ``modal_masses`` B_k in kg, ``rigid_velocity`` V_bar (free-free chains only).
    """

    chain: ModalChain
    omega: NDArray[np.float64]
    amplitudes: NDArray[np.float64]
    modal_masses: NDArray[np.float64]
    initial_velocities: tuple[float, ...]
    rigid_velocity: float = 0.0

    @property
    def n_modes(self) -> int:
        return int(self.omega.size)

    @property
    def initial_kinetic_energy(self) -> float:
        """1/2 sum m_i V_i^2 in J (the exact energy of the initial state)."""
        return 0.5 * float(sum(s.mass * v * v for s, v in zip(self.chain.segments, self.initial_velocities)))

    @property
    def captured_energy(self) -> float:
        """Energy carried by the truncated series, 1/2 sum B_k a_k^2 (+ rigid mode) in J (Bessel/Parseval)."""
        rigid = 0.5 * sum(s.mass for s in self.chain.segments) * self.rigid_velocity**2
        return 0.5 * float(np.sum(self.modal_masses * self.amplitudes**2)) + rigid

    def _series(self, x: ArrayLike, t: ArrayLike, kind: str) -> NDArray[np.float64]:
        xa = np.asarray(x, dtype=float)
        ta = np.asarray(t, dtype=float)
        if not np.all(np.isfinite(ta)):
            raise ValueError("t: times must be finite (s)")
        xf = np.atleast_1d(xa).ravel()
        tf = np.atleast_1d(ta).ravel()
        wt = np.outer(self.omega, tf)
        if kind == "velocity":
            time_fac = self.amplitudes[:, None] * np.cos(wt)
        else:
            time_fac = (self.amplitudes / self.omega)[:, None] * np.sin(wt)
        out = np.empty((xf.size, tf.size))
        chunk = max(1, _CHUNK // max(self.n_modes, 1))
        st = self.chain._shoot(self.omega)
        for a in range(0, xf.size, chunk):
            out[a:a + chunk] = self.chain._sum_modes(xf[a:a + chunk], st, time_fac, "n" if kind == "force" else "u")
        if kind == "displacement":
            out += self.rigid_velocity * tf[None, :]
        elif kind == "velocity":
            out += self.rigid_velocity
        return out.reshape(xa.shape + ta.shape)

    def displacement(self, x: ArrayLike, t: ArrayLike) -> NDArray[np.float64]:
        """u(x, t) in m; result shape ``x.shape + t.shape`` (time last)."""
        return self._series(x, t, "displacement")

    def velocity(self, x: ArrayLike, t: ArrayLike) -> NDArray[np.float64]:
        """v(x, t) in m/s; result shape ``x.shape + t.shape``."""
        return self._series(x, t, "velocity")

    def force(self, x: ArrayLike, t: ArrayLike) -> NDArray[np.float64]:
        """Normal force N(x, t) in N (tension positive); result shape ``x.shape + t.shape``."""
        return self._series(x, t, "force")

    def smoothed(self) -> ModalSolution:
        """The same modes with Lanczos sigma factors ``sinc(omega_k / omega_{N+1})`` on the amplitudes.

        The raw partial sum of a field with jumps has a Gibbs overshoot (~9 % of each jump) next to the jump
        and an oscillating O(1/(N d)) error at distance d from it. The sigma factors replace the last modes'
        sharp cut-off by a smooth taper (equivalent to averaging the series over one wavelength of the highest
        mode), which removes the overshoot and makes the series converge much faster away from jumps, to the
        same limit. ``omega_{N+1}`` is extrapolated with the last spacing. The thesis (Fig. 3.12) uses the raw sum.
        """
        w = self.omega
        cut = w[-1] + (w[-1] - w[-2]) if w.size > 1 else 2.0 * w[-1]
        sigma = np.sinc(w / cut)
        return ModalSolution(self.chain, w, self.amplitudes * sigma, self.modal_masses, self.initial_velocities,
                             self.rigid_velocity)

    def truncated(self, n_modes: int) -> ModalSolution:
        """The same series keeping only the lowest ``n_modes`` modes."""
        if not 1 <= n_modes <= self.n_modes:
            raise ValueError(f"n_modes: must be in 1..{self.n_modes}, got {n_modes!r}")
        return ModalSolution(self.chain, self.omega[:n_modes], self.amplitudes[:n_modes],
                             self.modal_masses[:n_modes], self.initial_velocities, self.rigid_velocity)
