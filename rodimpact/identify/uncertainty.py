"""Uncertainty of a matched profile: the Laplace (Gauss-Newton) covariance, 90 % bands, sampling by the
preconditioned Crank-Nicolson method, and the reading of anomalies and the toe from a profile or its samples
(docs/identification.md).

* **Laplace**: at the optimum theta* of Phi = 1/2 chi2 + alpha R (:mod:`rodimpact.identify.matching`), the
  posterior exp(-Phi) is approximated by the Gaussian N(theta*, H^-1) with the Gauss-Newton Hessian
  H = J^T J / sigma^2 + alpha nabla^2 R (Vogel 2002, ch. 3.4; Kaipio and Somersalo 2005, ch. 3), J_kp = dy_k /
  dtheta_p from the forward sensitivities. Parameters on an active bound are held fixed (their rows dropped).
  The 90 % band of ln Z_j is m_j +- 1.645 sqrt(C_jj), mapped to Z by exp.
* **Residual noise model** (:func:`ar_noise_model`): the noise the bands assume is read off the final fit's
  residual as an autoregressive process (Yule-Walker, order by AIC), its variance with the fit's degrees of
  freedom: coloured noise (1/f) and the misfit the model leaves enter the bands, not only the baseline's white
  level. The covariance of the least-squares estimate is then the sandwich G^-1 J^T Sigma J G^-1 / sigma^4
  (:func:`laplace_covariance` with ``noise``; Huber 1967, White 1982).
* **Sampling** (:func:`sample`): the pCN proposal theta' = mu + sqrt(1 - b^2) (theta - mu) + b xi, xi ~ N(0, C)
  (Cotter, Roberts, Stuart and White 2013, "MCMC methods for functions", Stat. Sci. 28) with mu = theta* and C
  the Laplace covariance; the proposal is reversible with respect to N(mu, C), so the Metropolis-Hastings ratio
  for the target exp(-Phi) is exp(-Phi(theta') + Phi(theta)) N(theta; mu, C) / N(theta'; mu, C) (the
  "generalised" pCN; Rudolf and Sprungk 2018). Several chains, b adapted towards 25 % acceptance during the
  burn-in (Roberts and Rosenthal 2001), stopped when the split R-hat (Gelman et al. 2013, BDA3 ch. 11.4) of every
  watched quantity is below 1.01 and its effective sample size (Geyer's initial positive sequence) exceeds a
  target.
* **Anomalies** (:func:`find_anomalies`): contiguous elements where the profile departs from the local baseline
  (running median) by more than ``min_change`` and the 90 % band excludes the baseline.
* **A step's depth** (:func:`edge_profiles`, :func:`profile_interval`): the profile with the step moved to
  depths x between element edges (partial volume), and the profile-likelihood interval 2 (crit(x) - min) <=
  2.71 (Wilks 1938; Pawitan 2001, "In all likelihood", ch. 2.6) of a criterion evaluated at each x.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

Z90 = 1.6448536269514722      # standard normal quantile of 0.95: a two-sided 90 % band


# ------------------------------------------------------------------------------------------------ Laplace
def laplace_covariance(J: np.ndarray, sigma: float, penalty_hessian: np.ndarray, alpha: float,
                       free: np.ndarray, noise: Optional["NoiseModel"] = None) -> np.ndarray:
    """The covariance (full size, zero rows and columns for the parameters not ``free``) of the estimate, with
    G = J^T J / sigma^2 + alpha P (P the penalty Hessian padded to the size of theta): G^-1 for white noise of
    standard deviation ``sigma`` (the Laplace posterior covariance), or, given the ``noise`` model of the residual
    (:func:`ar_noise_model`), the sandwich G^-1 (J^T Sigma J / sigma^4) G^-1: the covariance of the estimate
    linearised, delta theta = G^-1 J^T n / sigma^2, when the noise n has the covariance Sigma (coloured, or of
    another level than ``sigma``; Huber 1967, White 1982). With Sigma = sigma^2 I and alpha = 0 the two agree."""
    P = J.shape[1]
    G = J.T @ J / sigma ** 2
    m = penalty_hessian.shape[0]
    G[:m, :m] += alpha * penalty_hessian
    idx = np.flatnonzero(free)
    Gi = _spd_inverse(G[np.ix_(idx, idx)])
    if noise is not None:
        Jf = J[:, idx]
        Gi = Gi @ (noise.jt_sigma_j(Jf) / sigma ** 4) @ Gi
        Gi = 0.5 * (Gi + Gi.T)
    C = np.zeros((P, P))
    C[np.ix_(idx, idx)] = Gi
    return C


def _spd_inverse(H: np.ndarray) -> np.ndarray:
    """Symmetric inverse through the Cholesky factor of the diagonally scaled matrix; a tiny ridge only if
    rounding makes it indefinite."""
    scale = np.sqrt(np.maximum(np.diag(H), 1e-300))
    Hs = H / scale[:, None] / scale[None, :]
    try:
        L = np.linalg.cholesky(Hs)
    except np.linalg.LinAlgError:
        L = np.linalg.cholesky(Hs + 1e-10 * np.eye(H.shape[0]))
    Li = np.linalg.inv(L)
    return (Li.T @ Li) / scale[:, None] / scale[None, :]


@dataclass(frozen=True)
class NoiseModel:
    """A stationary autoregressive noise model n_k = sum_{i=1..p} a_i n_{k-i} + e_k, e white of variance
    ``innovation`` (units of the record squared): covariance Sigma = s2 W^-1 W^-T with W the whitening filter
    e = W n (lower triangular Toeplitz, first column [1, -a_1, .., -a_p]); the process starts at rest at k = 0."""

    a: np.ndarray
    innovation: float

    @property
    def order(self) -> int:
        return int(self.a.size)

    def variance(self) -> float:
        """The stationary variance of n: s2 sum h_k^2 over the impulse response h of 1 / (1 - sum a_i z^-i)."""
        from scipy.signal import lfilter

        h = lfilter([1.0], np.r_[1.0, -self.a], np.r_[1.0, np.zeros(4095)])
        return float(self.innovation * np.sum(h * h))

    def draw(self, rng: np.random.Generator, size: int) -> np.ndarray:
        """``size`` samples of the stationary process: the recursion run from rest over a burn-in of 4096 samples
        (the span :meth:`variance` sums the impulse response over), which is then dropped."""
        from scipy.signal import lfilter

        burn = 4096 if self.a.size else 0
        e = rng.normal(0.0, np.sqrt(self.innovation), size + burn)
        return lfilter([1.0], np.r_[1.0, -self.a], e)[burn:]

    def whiten(self, x: np.ndarray) -> np.ndarray:
        """W x / sqrt(s2) along the first axis (time): the filter e_k = x_k - sum_i a_i x_{k-i} from rest, scaled
        so that whitened noise has unit variance and 1/2 r^T Sigma^-1 r = 1/2 |whiten(r)|^2."""
        from scipy.signal import lfilter

        return lfilter(np.r_[1.0, -self.a], [1.0], np.asarray(x, dtype=float), axis=0) / np.sqrt(self.innovation)

    def misfit(self, residual: np.ndarray) -> float:
        """1/2 r^T Sigma^-1 r = 1/2 |W r|^2 / s2: the negative log-likelihood of the residual r under the model
        (up to a constant), with W r the filter e_k = r_k - sum_i a_i r_{k-i} from rest."""
        e = self.whiten(residual)
        return 0.5 * float(e @ e)

    def jt_sigma_j(self, J: np.ndarray) -> np.ndarray:
        """J^T Sigma J = s2 (W^-T J)^T (W^-T J); W^-T J is the synthesis filter 1 / (1 - sum a_i z^-i) run
        backwards in time over the columns of J."""
        from scipy.signal import lfilter

        X = lfilter([1.0], np.r_[1.0, -self.a], J[::-1], axis=0)[::-1]
        return self.innovation * (X.T @ X)


def ar_noise_model(residual: np.ndarray, fitted: int = 0, max_order: int = 20) -> NoiseModel:
    """The AR noise model of a residual series: Yule-Walker equations on the biased sample autocovariance
    (solved by the Levinson-Durbin recursion, which keeps the filter stable), the order p <= ``max_order`` that
    minimises Akaike's (1974) AIC, K ln s2_p + 2 p. The innovation variance is scaled by K / (K - ``fitted``) for
    the degrees of freedom the fit took from the residual (``fitted`` parameters; Draper and Smith ch. 2)."""
    r = np.asarray(residual, dtype=float)
    K = r.size
    if K < 4 * max_order or not np.all(np.isfinite(r)):
        raise ValueError(f"residual: needs >= {4 * max_order} finite samples for an AR({max_order}) model, "
                         f"got {K}")
    if not 0 <= fitted < K:
        raise ValueError(f"fitted: must be in [0, {K}), got {fitted!r}")
    x = r - r.mean()
    f = np.fft.rfft(x, n=2 * K)
    gamma = np.fft.irfft(f * np.conj(f))[:max_order + 1] / K
    if gamma[0] <= 0:
        return NoiseModel(np.zeros(0), 0.0)
    a = np.zeros(0)
    err = gamma[0]
    best = (K * np.log(err), a, err)
    for p in range(1, max_order + 1):                # Levinson-Durbin
        kappa = (gamma[p] - a @ gamma[p - 1:0:-1]) / err if p > 1 else gamma[1] / err
        a = np.r_[a - kappa * a[::-1], kappa]
        err *= 1.0 - kappa * kappa
        aic = K * np.log(err) + 2 * p
        if aic < best[0]:
            best = (aic, a.copy(), err)
    return NoiseModel(best[1], float(best[2] * K / (K - fitted)))


def log_bands(m: np.ndarray, C: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """90 % bands (lower, upper) of exp(m_j) from the covariance of m."""
    sd = np.sqrt(np.maximum(np.diag(C)[:m.size], 0.0))
    return np.exp(m - Z90 * sd), np.exp(m + Z90 * sd)


# ------------------------------------------------------------------------------------------------ features
@dataclass(frozen=True)
class Feature:
    """An anomaly read off a profile: elements [start, stop), ``change`` = extreme Z / baseline - 1."""

    start: int
    stop: int
    change: float


def local_baseline(Z: np.ndarray, window: int) -> np.ndarray:
    """The running median of Z over ``window`` elements (odd, reflected at the ends): the level a local anomaly
    departs from (a slow drift of the whole profile, which shaft resistance and impedance trade, is not an
    anomaly)."""
    w = max(3, int(window) | 1)
    pad = np.pad(Z, w // 2, mode="reflect")
    view = np.lib.stride_tricks.sliding_window_view(pad, w)
    return np.median(view, axis=1)


def find_anomalies(Z: np.ndarray, lower: Optional[np.ndarray], upper: Optional[np.ndarray], *, window: int,
                   min_change: float = 0.08, min_elements: int = 2) -> list[Feature]:
    """Contiguous runs of elements where |Z / b - 1| > ``min_change`` with one sign and, when bands are given,
    the band excludes the baseline b (lower > b for a bulge, upper < b for a neck); runs shorter than
    ``min_elements`` are dropped."""
    b = local_baseline(Z, window)
    rel = Z / b - 1.0
    up = rel > min_change
    down = rel < -min_change
    if lower is not None:
        up &= lower > b
        down &= upper < b
    out: list[Feature] = []
    for mask, sign in ((up, 1.0), (down, -1.0)):
        j = 0
        n = Z.size
        while j < n:
            if mask[j]:
                s = j
                while j < n and mask[j]:
                    j += 1
                if j - s >= min_elements:
                    seg = rel[s:j]
                    out.append(Feature(s, j, float(seg.max() if sign > 0 else seg.min())))
            else:
                j += 1
    return sorted(out, key=lambda f: f.start)


def match_feature(features: list[Feature], ref: Feature) -> Optional[Feature]:
    """The feature of ``features`` of the same sign overlapping ``ref`` most (None if none overlaps)."""
    best, over = None, 0
    for f in features:
        if np.sign(f.change) != np.sign(ref.change):
            continue
        o = min(f.stop, ref.stop) - max(f.start, ref.start)
        if o > over:
            best, over = f, o
    return best


def edge_profiles(m: np.ndarray, start: int, top: int, bottom: int,
                  substeps: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """The log-profile ``m`` with its step at element ``start`` (from a = m[start - 1] above to b = m[start]
    below) moved to the depths x (in elements, continuous) from ``top`` to ``bottom`` (top <= start <= bottom),
    ``substeps`` per element: returns (x, profiles). Moved up to x < start, the elements between x and the step
    take b; moved down, those between the step and x take a; the element that holds x takes the level by its
    share (partial volume, mixed in ln Z): element k < start becomes (1 - q) m_k + q b with q = clip(k + 1 - x,
    0, 1) its share below x, element k >= start becomes (1 - p) m_k + p a with p = clip(x - k, 0, 1) its share
    above x. Every other element keeps m; at x = start the profile is ``m`` itself. A step reached through a
    transition element (an intermediate level between a and b, as a fit makes of a step inside an element) moves
    across it."""
    if not 0 <= top <= start <= bottom <= m.size:
        raise ValueError(f"edge_profiles: need 0 <= top <= start <= bottom <= {m.size}, got {top}, {start}, "
                         f"{bottom}")
    a, b = m[start - 1], m[start]
    x = np.arange(top * substeps, bottom * substeps + 1) / substeps
    profiles = np.repeat(m[None, :], x.size, axis=0)
    k = np.arange(top, start)
    q = np.clip(k[None, :] + 1 - x[:, None], 0.0, 1.0)
    profiles[:, k] = (1.0 - q) * m[k] + q * b
    k = np.arange(start, bottom)
    p = np.clip(x[:, None] - k[None, :], 0.0, 1.0)
    profiles[:, k] = (1.0 - p) * m[k] + p * a
    return x, profiles


def profile_interval(x: np.ndarray, crit: np.ndarray, limit: float, at: float) -> tuple[float, float, float]:
    """The best x (lowest ``crit``; of equal ones, the nearest to ``at``) and the profile-likelihood interval: the
    smallest one holding every x with 2 (crit - min) <= ``limit`` (2.71 for 90 %, Wilks; the toe's rule too), so
    a second basin within the limit widens it: (best, lo, hi). It ends at the ends of x at the most."""
    i = min(range(x.size), key=lambda j: (crit[j], abs(x[j] - at)))
    inside = x[2.0 * (crit - crit[i]) <= limit]
    return float(x[i]), float(inside.min()), float(inside.max())


# ------------------------------------------------------------------------------------------------ sampling
def split_rhat(chains: np.ndarray) -> np.ndarray:
    """Split R-hat (BDA3 eq. 11.4) of each column of ``chains`` (n_chains, n_draws, n_quantities)."""
    c, d, q = chains.shape
    h = d // 2
    x = np.concatenate([chains[:, :h], chains[:, h:2 * h]], axis=0)      # 2c chains of h draws
    means = x.mean(axis=1)
    W = x.var(axis=1, ddof=1).mean(axis=0)
    B = h * means.var(axis=0, ddof=1)
    var = (h - 1) / h * W + B / h
    return np.sqrt(var / np.maximum(W, 1e-300))


def effective_sample_size(chains: np.ndarray) -> np.ndarray:
    """ESS of each quantity: c d / (1 + 2 sum rho_t), the autocorrelations averaged over the chains and summed
    in pairs while positive (Geyer 1992, initial positive sequence)."""
    c, d, q = chains.shape
    x = chains - chains.mean(axis=1, keepdims=True)
    f = np.fft.rfft(x, n=2 * d, axis=1)
    ac = np.fft.irfft(f * np.conj(f), axis=1)[:, :d] / d
    ac = ac.mean(axis=0)
    rho = ac / np.maximum(ac[0], 1e-300)
    ess = np.empty(q)
    for i in range(q):
        s = 0.0
        t = 1
        while t + 1 < d:
            pair = rho[t, i] + rho[t + 1, i]
            if pair <= 0:
                break
            s += pair
            t += 2
        ess[i] = c * d / (1.0 + 2.0 * s)
    return ess


@dataclass
class Samples:
    """Draws of theta after burn-in (n_chains, n_draws, P), acceptance rate, R-hat and ESS of the watched
    quantities, and whether the stopping rule was met."""

    draws: np.ndarray
    acceptance: float
    rhat: float
    ess: float
    converged: bool
    evaluations: int


def sample(phi: Callable[[np.ndarray], float], mu: np.ndarray, C: np.ndarray, lower: np.ndarray,
           upper: np.ndarray, *, chains: int = 4, target_ess: float = 400.0, max_rhat: float = 1.01,
           check_every: int = 250, burn_in: int = 250, max_draws: int = 20000, seed: int = 0,
           watch: Optional[Callable[[np.ndarray], np.ndarray]] = None,
           progress: Optional[Callable[[str], None]] = None) -> Samples:
    """Generalised pCN chains for exp(-phi(theta)) started at draws of N(mu, C) (see the module docstring).

    ``watch(theta)`` gives the quantities whose R-hat and ESS decide convergence (default: theta itself).
    Proposals outside [lower, upper] are rejected (the target is zero there)."""
    rng = np.random.default_rng(seed)
    P = mu.size
    idx = np.flatnonzero(np.diag(C) > 0)
    Cf = C[np.ix_(idx, idx)]
    L = np.linalg.cholesky(Cf + 1e-14 * np.max(np.diag(Cf)) * np.eye(idx.size))
    Linv = np.linalg.inv(L)

    def gauss(theta):          # -log N(theta; mu, C) up to a constant
        z = Linv @ (theta[idx] - mu[idx])
        return 0.5 * float(z @ z)

    def draw():
        return L @ rng.standard_normal(idx.size)

    watch = watch or (lambda t: t)
    b = 0.3
    cur = []
    for _ in range(chains):
        for _try in range(100):
            t = mu.copy()
            t[idx] += draw()
            if np.all(t >= lower) and np.all(t <= upper):
                break
        else:
            t = mu.copy()
        cur.append(t)
    cur_phi = np.array([phi(t) for t in cur])
    cur_g = np.array([gauss(t) for t in cur])
    kept: list[list[np.ndarray]] = [[] for _ in range(chains)]
    accepted = 0
    proposed = 0
    evaluations = chains
    step = 0
    rhat = ess = np.nan
    converged = False
    window_acc = 0
    while True:
        step += 1
        for ci in range(chains):
            prop = cur[ci].copy()
            prop[idx] = mu[idx] + np.sqrt(1.0 - b * b) * (cur[ci][idx] - mu[idx]) + b * draw()
            proposed += 1
            if np.all(prop >= lower) and np.all(prop <= upper):
                p_phi = phi(prop)
                evaluations += 1
                p_g = gauss(prop)
                if np.log(rng.uniform()) < -(p_phi - cur_phi[ci]) + (p_g - cur_g[ci]):
                    cur[ci], cur_phi[ci], cur_g[ci] = prop, p_phi, p_g
                    accepted += 1
                    window_acc += 1
            if step > burn_in:
                kept[ci].append(cur[ci].copy())
        if step <= burn_in and step % 25 == 0:          # adapt b towards 25 % acceptance
            rate = window_acc / (25 * chains)
            b = float(np.clip(b * np.exp(rate - 0.25), 1e-3, 1.0))
            window_acc = 0
        if step == burn_in:
            accepted = proposed = 0
        d = step - burn_in
        if d > 0 and d % check_every == 0:
            arr = np.array(kept)
            w = np.array([[watch(t) for t in ch] for ch in arr])
            rh = split_rhat(w)
            es = effective_sample_size(w)
            rhat, ess = float(np.max(rh)), float(np.min(es))
            converged = rhat < max_rhat and ess > target_ess
            if progress is not None:
                progress(f"draws {d * chains}: R-hat {rhat:.3f}, ESS {ess:.0f}, acceptance "
                         f"{accepted / max(proposed, 1):.2f}, pCN b {b:.3g}")
            if converged or d * chains >= max_draws:
                break
    return Samples(np.array(kept), accepted / max(proposed, 1), rhat, ess, converged, evaluations)
