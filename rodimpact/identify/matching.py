"""Identification by regularised signal matching: the impedance profile Z(x) of a pile whose lattice model,
driven at the head by the hammer force, reproduces the measured head velocity (docs/identification.md).

Forward model (:mod:`rodimpact.identify._match_kernels`): n equal-travel-time elements of impedance Z_j
(N s/m) below the head, the head force F_k (N, compression negative) prescribed, the head velocity y_k (m/s,
+x into the ground) recorded every step; along the shaft a linear spring and dashpot to the ground at every
interior node (the total shaft damping C_s (N s/m) and stiffness K_s (N/m) shared equally by the n - 1 nodes),
at the toe a spring-dashpot (k_t, c_t) or a fixed end. The model is longer than the pile is expected to be; the
elements below the toe take a low impedance (a semi-infinite rod of impedance Z_s is a dashpot c = Z_s to the
pile above it), and the toe is read off the profile.

Parameters theta (dimensionless, for a well-scaled search): m_j = ln(Z_j / Z_ref), then
[C_s / Z_ref, K_s T / Z_ref, k_t T / Z_ref, c_t / Z_ref] with T = n dt the travel time through the model;
all within bounds (L-BFGS-B, scipy; Byrd et al. 1995).

Objective (Vogel 2002, "Computational methods for inverse problems", ch. 1, 7, 8):

    Phi(theta) = 1/2 sum_k ((y_k(theta) - d_k) / sigma)^2 + alpha R(m),

the misfit whitened by the noise standard deviation sigma (m/s), and the penalty R on the log-impedance:

* ``"tv"`` (default): smoothed total variation R = sum_j (sqrt((m_{j+1} - m_j)^2 + eps^2) - eps)
  (Vogel ch. 8), which keeps steps sharp (a neck, a bulge and the toe are steps of Z);
* ``"smooth"``: 1/2 sum_j (m_{j+1} - 2 m_j + m_{j-1})^2 (second differences; Tikhonov, Vogel ch. 1).

The gradient is exact: the discrete adjoint of the lattice (:func:`~rodimpact.identify._match_kernels.adjoint_numba`)
for the misfit, closed forms for the penalty.

Penalty weight alpha (:func:`choose_weight`):

* the **discrepancy principle** (Morozov; Vogel sec. 7.3) when the noise level is known or estimated from the
  pre-trigger baseline of the record: the largest alpha whose fit has sum r_k^2 <= tau K (K samples, tau = 1):
  the data are fitted to the noise level and no closer. It needs sigma, which the baseline gives, and it is
  cheap (a bracketing search in log alpha with warm starts) and robust for nonlinear problems.
* otherwise the **L-curve** (Hansen; Vogel sec. 7.5): alpha at the largest curvature of (log misfit, log R) over
  a grid. GCV (Vogel sec. 7.4) needs the trace of the influence matrix of the nonlinear, bounded problem at every
  trial alpha; the L-curve needs only the fits themselves, so it is used when sigma is unknown.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Optional

import numpy as np
from scipy.optimize import minimize

from . import _match_kernels as mk

#: number of scalar soil parameters after the log-impedances: shaft damping, shaft stiffness, toe stiffness,
#: toe damping (scaled, see the module docstring)
N_SOIL = 4
SOIL_NAMES = ("shaft_damping", "shaft_stiffness", "toe_stiffness", "toe_damping")


# ------------------------------------------------------------------------------------------------ model
@dataclass(frozen=True)
class PileModel:
    """The lattice pile of the matching method.

    ``dt`` (s) element travel time = sample interval of the record; ``n`` elements; ``force`` (N, K values) the
    head force in each step; ``z_ref`` (N s/m) the impedance scale of theta; ``toe`` ``"spring"`` (spring-dashpot,
    free when both are 0) or ``"fixed"``; ``backend`` ``"numba"`` or ``"numpy"``.
    """

    dt: float
    n: int
    force: np.ndarray
    z_ref: float
    toe: str = "spring"
    backend: str = "numba"

    def __post_init__(self) -> None:
        if not (np.isfinite(self.dt) and self.dt > 0):
            raise ValueError(f"PileModel.dt: must be a finite time step > 0 s, got {self.dt!r}")
        if int(self.n) != self.n or self.n < 2:
            raise ValueError(f"PileModel.n: must be an integer >= 2 (elements), got {self.n!r}")
        force = np.asarray(self.force, dtype=float)
        if force.ndim != 1 or force.size < 2 or not np.all(np.isfinite(force)):
            raise ValueError("PileModel.force: must be a 1-D array of >= 2 finite forces (N)")
        object.__setattr__(self, "force", force)
        if not (np.isfinite(self.z_ref) and self.z_ref > 0):
            raise ValueError(f"PileModel.z_ref: must be an impedance > 0 N s/m, got {self.z_ref!r}")
        if self.toe not in ("spring", "fixed"):
            raise ValueError(f"PileModel.toe: must be 'spring' or 'fixed', got {self.toe!r}")
        if self.backend not in ("numba", "numpy"):
            raise ValueError(f"PileModel.backend: must be 'numba' or 'numpy', got {self.backend!r}")

    @property
    def steps(self) -> int:
        return int(self.force.size)

    @property
    def size(self) -> int:
        """Length of theta: n log-impedances and the soil parameters."""
        return self.n + N_SOIL

    def physical(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float, float]:
        """(Z, c, k, k_t, c_t) of theta: impedances (N s/m), per-node shaft dashpots (N s/m) and springs (N/m),
        toe spring (N/m) and dashpot (N s/m)."""
        n = self.n
        T = n * self.dt
        Z = self.z_ref * np.exp(theta[:n])
        cs, ks, kt, ct = theta[n:n + N_SOIL]
        c = np.zeros(n + 1)
        k = np.zeros(n + 1)
        c[1:n] = cs * self.z_ref / (n - 1)
        k[1:n] = ks * self.z_ref / T / (n - 1)
        return Z, c, k, kt * self.z_ref / T, ct * self.z_ref

    def _chain(self, theta: np.ndarray, gZ, gc, gk, gkt, gct) -> np.ndarray:
        """dJ/dtheta from the gradient with respect to the physical parameters."""
        n = self.n
        T = n * self.dt
        Z = self.z_ref * np.exp(theta[:n])
        return np.concatenate([gZ * Z, [np.sum(gc[1:n]) * self.z_ref / (n - 1),
                                        np.sum(gk[1:n]) * self.z_ref / T / (n - 1),
                                        gkt * self.z_ref / T, gct * self.z_ref]])

    def _states(self, steps: int):
        return np.empty((steps, self.n)), np.empty((steps, self.n)), np.empty((steps, self.n + 1))

    def simulate(self, theta: np.ndarray) -> np.ndarray:
        """Head velocity y_k (m/s) for k = 0 .. K-1."""
        fwd = mk.forward_numba if self.backend == "numba" else mk.forward_numpy
        return fwd(*self.physical(theta), self.toe == "fixed", self.force, self.dt, *self._states(0))

    def misfit_gradient(self, theta: np.ndarray, data: np.ndarray, weight: np.ndarray) -> tuple[float, np.ndarray,
                                                                                               np.ndarray]:
        """(1/2 sum w_k (y_k - d_k)^2, its exact gradient in theta (adjoint), y). ``weight`` = 1/sigma_k^2."""
        fwd, adj = ((mk.forward_numba, mk.adjoint_numba) if self.backend == "numba"
                    else (mk.forward_numpy, mk.adjoint_numpy))
        par = self.physical(theta)
        fixed = self.toe == "fixed"
        states = self._states(self.steps)
        y = fwd(*par, fixed, self.force, self.dt, *states)
        r = y - data
        g = adj(*par, fixed, self.force, self.dt, *states, weight * r)
        return 0.5 * float(np.sum(weight * r * r)), self._chain(theta, *g), y

    def jacobian(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(y, J) with J[k, p] = dy_k / dtheta_p from the forward sensitivities (tangent mode)."""
        n = self.n
        P = self.size
        T = n * self.dt
        Z, c, k, kt, ct = par = self.physical(theta)
        tZ = np.zeros((P, n))
        tZ[np.arange(n), np.arange(n)] = Z
        tc = np.zeros((P, n + 1))
        tk = np.zeros((P, n + 1))
        tc[n, 1:n] = self.z_ref / (n - 1)
        tk[n + 1, 1:n] = self.z_ref / T / (n - 1)
        tkt = np.zeros(P)
        tct = np.zeros(P)
        tkt[n + 2] = self.z_ref / T
        tct[n + 3] = self.z_ref
        return mk.tangent_numba(*par, self.toe == "fixed", self.force, self.dt, tZ, tc, tk, tkt, tct)


# ------------------------------------------------------------------------------------------------ penalty
@dataclass(frozen=True)
class Penalty:
    """R(m) on the log-impedances: ``kind`` ``"tv"`` (smoothed total variation with ``eps``) or ``"smooth"``
    (second differences). :meth:`value_gradient` and :meth:`hessian` are exact."""

    kind: str = "tv"
    eps: float = 0.02

    def __post_init__(self) -> None:
        if self.kind not in ("tv", "smooth"):
            raise ValueError(f"penalty: must be 'tv' or 'smooth', got {self.kind!r}")
        if not (np.isfinite(self.eps) and self.eps > 0):
            raise ValueError(f"Penalty.eps: must be > 0 (the TV smoothing, in ln Z), got {self.eps!r}")

    def value_gradient(self, m: np.ndarray) -> tuple[float, np.ndarray]:
        g = np.zeros_like(m)
        if self.kind == "tv":
            dm = np.diff(m)
            s = np.sqrt(dm * dm + self.eps ** 2)
            q = dm / s
            g[1:] += q
            g[:-1] -= q
            return float(np.sum(s - self.eps)), g
        d2 = m[2:] - 2.0 * m[1:-1] + m[:-2]
        g[2:] += d2
        g[1:-1] -= 2.0 * d2
        g[:-2] += d2
        return 0.5 * float(np.sum(d2 * d2)), g

    def hessian(self, m: np.ndarray) -> np.ndarray:
        n = m.size
        if self.kind == "tv":
            dm = np.diff(m)
            w = self.eps ** 2 / (dm * dm + self.eps ** 2) ** 1.5      # d^2/d(dm)^2 of sqrt(dm^2 + eps^2)
            D = np.zeros((n - 1, n))
        else:
            w = np.ones(n - 2)
            D = np.zeros((n - 2, n))
            D[np.arange(n - 2), np.arange(n - 2) + 2] = 1.0
            D[np.arange(n - 2), np.arange(n - 2) + 1] = -2.0
            D[np.arange(n - 2), np.arange(n - 2)] = 1.0
            return D.T @ (w[:, None] * D)
        D[np.arange(n - 1), np.arange(n - 1) + 1] = 1.0
        D[np.arange(n - 1), np.arange(n - 1)] = -1.0
        return D.T @ (w[:, None] * D)


# ------------------------------------------------------------------------------------------------ one fit
@dataclass
class Fit:
    """One regularised fit: theta, the record y, misfit chi2 = sum r_k^2 (whitened), penalty R, alpha."""

    theta: np.ndarray
    y: np.ndarray
    chi2: float
    penalty: float
    alpha: float
    iterations: int
    history: list = field(default_factory=list)


def fit(model: PileModel, data: np.ndarray, sigma: float, alpha: float, penalty: Penalty, theta0: np.ndarray,
        bounds: list[tuple[float, float]], max_iterations: int = 400, tolerance: float = 1e-9) -> Fit:
    """Minimise Phi(theta) = 1/2 chi2 + alpha R(m) with L-BFGS-B from ``theta0`` within ``bounds``."""
    n = model.n
    weight = np.full(data.size, 1.0 / sigma ** 2)

    def fun(theta):
        f, g, _ = model.misfit_gradient(theta, data, weight)
        r, gr = penalty.value_gradient(theta[:n])
        g = g.copy()
        g[:n] += alpha * gr
        return f + alpha * r, g

    res = minimize(fun, theta0, jac=True, method="L-BFGS-B", bounds=bounds,
                   options={"maxiter": max_iterations, "ftol": tolerance, "gtol": 1e-8, "maxcor": 20})
    theta = np.clip(res.x, [b[0] for b in bounds], [b[1] for b in bounds])
    y = model.simulate(theta)
    chi2 = float(np.sum(((y - data) / sigma) ** 2))
    return Fit(theta, y, chi2, penalty.value_gradient(theta[:n])[0], alpha, int(res.nit))


def choose_weight(model: PileModel, data: np.ndarray, sigma: float, penalty: Penalty, theta0: np.ndarray,
                  bounds: list[tuple[float, float]], *, rule: str = "discrepancy", tau: float = 1.0,
                  alpha_start: float = 1e4, max_fits: int = 12,
                  progress: Optional[Callable[[str], None]] = None) -> Fit:
    """The fit at the penalty weight chosen by ``rule``: ``"discrepancy"`` (chi2 <= tau K, the largest such
    alpha, located by halving decades then bisection in log alpha) or ``"lcurve"`` (largest curvature of
    (log chi2, log R) over a grid of alpha, decade steps). Every fit starts from the previous one."""
    K = data.size
    target = tau * K
    fits: list[Fit] = []

    def run(alpha, start):
        f = fit(model, data, sigma, alpha, penalty, start, bounds)
        fits.append(f)
        if progress is not None:
            progress(f"alpha={alpha:.3g} chi2/K={f.chi2 / K:.3f} R={f.penalty:.4g} iterations={f.iterations}")
        return f

    if rule == "discrepancy":
        alpha = alpha_start
        cur = run(alpha, theta0)
        hi = lo = None                      # hi: an alpha whose chi2 > target; lo: one that fits (chi2 <= target)
        if cur.chi2 > target:
            hi = cur
            while len(fits) < max_fits:
                cur = run(hi.alpha / 10.0, hi.theta)
                if cur.chi2 <= target:
                    lo = cur
                    break
                hi = cur
        else:
            lo = cur
            while len(fits) < max_fits:
                cur = run(lo.alpha * 10.0, lo.theta)
                if cur.chi2 > target:
                    hi = cur
                    break
                lo = cur
        if lo is None:                      # nothing fits to the noise level: the closest fit
            return min(fits, key=lambda f: f.chi2)
        while hi is not None and len(fits) < max_fits and hi.alpha / lo.alpha > 1.5:
            cur = run(np.sqrt(hi.alpha * lo.alpha), lo.theta)
            if cur.chi2 <= target:
                lo = cur
            else:
                hi = cur
        return lo
    if rule == "lcurve":
        alphas = alpha_start * 10.0 ** -np.arange(max(max_fits, 4))
        start = theta0
        for a in alphas:
            start = run(a, start).theta
        x = np.log(np.array([f.chi2 for f in fits]))
        y = np.log(np.maximum([f.penalty for f in fits], 1e-300))
        t = np.log(alphas)
        dx, dy = np.gradient(x, t), np.gradient(y, t)
        ddx, ddy = np.gradient(dx, t), np.gradient(dy, t)
        kappa = (dx * ddy - ddx * dy) / np.maximum((dx * dx + dy * dy) ** 1.5, 1e-300)
        return fits[int(np.argmax(kappa[1:-1])) + 1]
    raise ValueError(f"weight rule: must be 'discrepancy' or 'lcurve', got {rule!r}")


def baseline_noise(record: np.ndarray, force: np.ndarray, fraction: float = 0.01, minimum: int = 8
                   ) -> Optional[float]:
    """The noise standard deviation (units of the record) from its pre-trigger baseline: the samples before the
    force first exceeds ``fraction`` of its largest magnitude (the pile is at rest there, so the record is noise
    alone). ``None`` if fewer than ``minimum`` such samples."""
    a = np.abs(force)
    first = int(np.argmax(a > fraction * a.max()))
    if first < minimum:
        return None
    base = record[:first]
    return float(np.std(base - base.mean()))


def summary_of(theta: np.ndarray, model: PileModel) -> dict[str, Any]:
    """The soil parameters of theta in SI units."""
    Z, c, k, kt, ct = model.physical(theta)
    n = model.n
    return {"shaft_damping": float(np.sum(c[1:n])), "shaft_stiffness": float(np.sum(k[1:n])),
            "toe_stiffness": float(kt), "toe_damping": float(ct)}
