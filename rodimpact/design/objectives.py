"""Objectives of striker design and their seeds for the adjoint gradient.

Every objective is a function of the forward run's histories (``fw``) and of the striker itself, returned as
``(value, seeds, dvalue_dZ_direct, dvalue_dv_direct)``: ``seeds`` are dJ/d(history_k) for
:meth:`ImpactProblem.gradient`, the last two the explicit dependence on the impedances Z_q (N s/m) and on the
impact velocity v (m/s) that does not pass through the histories.

``match``
    J = sum_k w_k (y_k - r_k)^2 / sum_k w_k r_k^2, the squared relative L2 misfit of the achieved force y_k
    to the target r_k over the target's span: at the impact face every step k, with r_k = the window value X_j
    of its window [2(j-1) dt, 2j dt) (held for 2 dt); at a position the window starts after the dead time d,
    steps d + 2(j-1), with r = X_j (see :meth:`MatchObjective.build`). The reported misfit is sqrt(J).
``efficiency``
    eta = W / E_k with W = -dt sum_k N_k v_k the work done on the rock by the far end (N_k the normal force,
    compressive < 0, v_k the outward velocity; node values are constant over a step, so the sum is the exact
    work of the lattice's end) and E_k = m v^2 / 2 the striker's kinetic energy, m = dt sum Z_q. The optimiser
    minimises J = -eta.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

Seeds = dict[str, np.ndarray]


@dataclass(frozen=True)
class MatchObjective:
    """Weighted relative L2 misfit of the observed history at the steps ``index`` against ``reference``."""

    index: np.ndarray          # compared steps
    reference: np.ndarray      # target at those steps, N
    weights: np.ndarray        # weights >= 0 at those steps
    steps: int                 # length of the forward run's histories

    @classmethod
    def build(cls, windows: np.ndarray, dead_time: Optional[int], weights: Any, dt: float) -> "MatchObjective":
        """At the impact face (``dead_time`` None) every step of every window is compared with its window value
        (held for 2 dt); at a position the window starts after the dead time d, steps d + 2(j-1), as the
        transformation of :func:`~rodimpact.synthesize` matches them (devices that act every step, such as a
        bit-rock spring, make the quantity vary within a window, which no striker can shape)."""
        nw = windows.size
        if dead_time is None:
            index, ref = np.arange(2 * nw), np.repeat(windows, 2)
        else:
            index, ref = dead_time + 2 * np.arange(nw), windows.copy()
        w = per_step_weights(weights, nw, dt)
        if dead_time is not None:
            w = w[0::2]
        return cls(index, ref, w, int(index[-1]) + (2 if dead_time is None else 1))

    def achieved(self, fw: Any) -> np.ndarray:
        """The compared values of the forward run."""
        return np.asarray(fw.observed)[self.index]

    def evaluate(self, fw: Any, impedance: np.ndarray, velocity: float) -> tuple[float, Seeds, np.ndarray, float]:
        r = self.reference
        res = self.achieved(fw) - r
        norm = float(np.sum(self.weights * r * r))
        value = float(np.sum(self.weights * res * res)) / norm
        seed = np.zeros(self.steps)
        seed[self.index] = 2.0 * self.weights * res / norm
        return value, {"observed": seed}, np.zeros(impedance.size), 0.0


@dataclass(frozen=True)
class EfficiencyObjective:
    """J = -eta, eta = (work done on the rock) / (striker kinetic energy)."""

    dt: float
    steps: int

    @staticmethod
    def work(fw: Any, dt: float) -> float:
        """W = -dt sum N_k v_k: work done by the far end on the rock over the run, J."""
        return float(-dt * np.dot(fw.end_force, fw.end_velocity))

    def efficiency(self, fw: Any, impedance: np.ndarray, velocity: float) -> float:
        """eta = W / (m v^2 / 2)."""
        return self.work(fw, self.dt) / (0.5 * self.dt * float(np.sum(impedance)) * velocity * velocity)

    def evaluate(self, fw: Any, impedance: np.ndarray, velocity: float) -> tuple[float, Seeds, np.ndarray, float]:
        dt = self.dt
        mass = dt * float(np.sum(impedance))
        ek = 0.5 * mass * velocity * velocity
        w = self.work(fw, dt)
        eta = w / ek
        seeds = {"end_force": dt * np.asarray(fw.end_velocity) / ek,       # d(-eta)/dN_k
                 "end_velocity": dt * np.asarray(fw.end_force) / ek}       # d(-eta)/dv_k
        # explicit dependence of -eta through E_k: d(-eta)/dZ_q = eta / E_k * dE_k/dZ_q, dE_k/dZ_q = dt v^2 / 2
        dz = np.full(impedance.size, eta / ek * 0.5 * dt * velocity * velocity)
        dv = eta / ek * mass * velocity
        return -eta, seeds, dz, float(dv)


def per_step_weights(weights: Optional[Any], n_windows: int, dt: float) -> np.ndarray:
    """Weights over the 2 n_w compared steps: None (all 1), a callable w(t) of the time from the start of the
    target (s), n_w values (one per window) or 2 n_w values (one per step); finite, >= 0, not all zero."""
    m = 2 * n_windows
    if weights is None:
        return np.ones(m)
    if callable(weights):
        try:
            w = np.asarray(weights(dt * np.arange(m)), dtype=float)
            w = np.broadcast_to(w, (m,)).copy()
        except Exception as exc:  # noqa: BLE001 - report the user's function failing, with context
            raise ValueError(f"weights: calling the weight function with an array of times failed ({exc}); it "
                             f"must accept a numpy array t (s) and return one weight per time") from exc
    else:
        w = np.asarray(weights)
        if w.dtype.kind not in "iuf":
            raise TypeError(f"weights: must be real numbers (one per window or per step) or a function w(t), got "
                            f"{type(weights).__name__} {weights!r}")
        w = w.astype(float)
        if w.ndim != 1 or w.size not in (n_windows, m):
            raise ValueError(f"weights: give {n_windows} values (one per window) or {m} (one per step), or a "
                             f"function w(t); got shape {w.shape}")
        if w.size == n_windows:
            w = np.repeat(w, 2)
    if not np.all(np.isfinite(w)) or np.any(w < 0) or not np.any(w > 0):
        raise ValueError("weights: must be finite and >= 0, with at least one > 0")
    return w
