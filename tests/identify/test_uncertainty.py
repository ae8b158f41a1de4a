"""Uncertainty (rodimpact.identify.uncertainty): the Laplace covariance against a direct inverse and its coverage
on a linear Gaussian problem, the pCN sampler against exact moments, R-hat and ESS against known cases, and the
reading of anomalies off a profile."""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.identify import uncertainty as unc


def test_laplace_covariance_is_the_inverse_gauss_newton_hessian():
    rng = np.random.default_rng(0)
    J = rng.normal(size=(40, 6))
    P = np.diag([1.0, 2.0, 0.5, 0.0])[:4, :4]
    free = np.array([True, True, False, True, True, True])
    C = unc.laplace_covariance(J, 0.3, P, 2.0, free)
    H = J.T @ J / 0.09
    H[:4, :4] += 2.0 * P
    idx = np.flatnonzero(free)
    ref = np.linalg.inv(H[np.ix_(idx, idx)])
    np.testing.assert_allclose(C[np.ix_(idx, idx)], ref, rtol=1e-10, atol=1e-14)
    assert np.all(C[2] == 0) and np.all(C[:, 2] == 0)


def test_laplace_bands_cover_90_percent_on_a_linear_gaussian_problem():
    """y = J theta + e, e ~ N(0, sigma^2), flat prior: the band theta_hat +- 1.645 sqrt(C_jj) holds the truth in 90 %
    of repetitions (binomial: 2000 x 8 trials, 3 sigma = 0.7 %)."""
    rng = np.random.default_rng(1)
    J = rng.normal(size=(30, 8))
    sigma = 0.2
    theta = rng.normal(size=8)
    C = unc.laplace_covariance(J, sigma, np.zeros((8, 8)), 0.0, np.ones(8, dtype=bool))
    hits = 0
    for _ in range(2000):
        y = J @ theta + sigma * rng.normal(size=30)
        est = np.linalg.lstsq(J, y, rcond=None)[0]
        lo, up = unc.log_bands(est, C)
        hits += np.sum((lo <= np.exp(theta)) & (np.exp(theta) <= up))
    assert abs(hits / 16000 - 0.90) < 0.007


def _ar_series(rng, a, size, burn=500):
    """x_k = sum a_i x_{k-i} + e_k (e standard normal), from rest, the first ``burn`` samples dropped."""
    from scipy.signal import lfilter

    return lfilter([1.0], np.r_[1.0, -np.asarray(a)], rng.normal(size=size + burn))[burn:]


def test_ar_noise_model_recovers_the_generating_process():
    """Yule-Walker/Levinson with the order by AIC on 40000 samples of an AR(2) process: the coefficients and
    the innovation variance of the generator to 0.02, the stationary variance of an AR(1) process equal to the
    closed form s2 / (1 - a^2), and the degrees-of-freedom factor K / (K - fitted) on the innovation."""
    rng = np.random.default_rng(3)
    x = _ar_series(rng, [0.6, -0.2], 40000)
    m = unc.ar_noise_model(x)
    assert m.order >= 2
    np.testing.assert_allclose(m.a[:2], [0.6, -0.2], atol=0.02)
    assert np.all(np.abs(m.a[2:]) < 0.02) and abs(m.innovation - 1.0) < 0.02
    assert unc.NoiseModel(np.array([0.8]), 2.0).variance() == pytest.approx(2.0 / (1.0 - 0.64), rel=1e-12)
    m10 = unc.ar_noise_model(x, fitted=10000)
    assert m10.innovation == pytest.approx(m.innovation * 40000 / 30000, rel=1e-12)
    with pytest.raises(ValueError, match="residual"):
        unc.ar_noise_model(np.ones(30))
    with pytest.raises(ValueError, match="fitted"):
        unc.ar_noise_model(x, fitted=-1)


def test_noise_model_covariance_is_that_of_the_ar_process_from_rest():
    """J^T Sigma J against Sigma built as a matrix: the AR(2) process from rest is n = W^-1 e with W the lower
    triangular Toeplitz whitening matrix (first column 1, -a_1, -a_2), so Sigma = s2 W^-1 W^-T."""
    from scipy.linalg import toeplitz

    rng = np.random.default_rng(6)
    K = 60
    a = np.array([0.5, -0.3])
    W = toeplitz(np.r_[1.0, -a, np.zeros(K - 3)], np.zeros(K))
    Wi = np.linalg.inv(W)
    J = rng.normal(size=(K, 4))
    ref = J.T @ (1.7 * Wi @ Wi.T) @ J
    np.testing.assert_allclose(unc.NoiseModel(a, 1.7).jt_sigma_j(J), ref, rtol=1e-10)


def test_noise_model_misfit_is_the_gaussian_negative_log_likelihood():
    """1/2 r^T Sigma^-1 r with Sigma = s2 W^-1 W^-T built as a matrix (the AR(2) process from rest), against the
    filter form; for the white model (no coefficients) 1/2 |r|^2 / s2."""
    from scipy.linalg import toeplitz

    rng = np.random.default_rng(9)
    K = 50
    a = np.array([0.6, -0.25])
    W = toeplitz(np.r_[1.0, -a, np.zeros(K - 3)], np.zeros(K))
    Wi = np.linalg.inv(W)
    r = rng.normal(size=K)
    ref = 0.5 * r @ np.linalg.solve(2.3 * Wi @ Wi.T, r)
    assert unc.NoiseModel(a, 2.3).misfit(r) == pytest.approx(ref, rel=1e-10)
    assert unc.NoiseModel(np.zeros(0), 2.3).misfit(r) == pytest.approx(0.5 * r @ r / 2.3, rel=1e-14)


def test_noise_model_draws_are_the_stationary_process():
    """Draws of AR(1) (a = 0.9, innovation 2): variance s2 / (1 - a^2) = 10.53 and lag-1 correlation a, from the
    first sample on (stationary, not started from rest), over 400 draws of 50 samples."""
    model = unc.NoiseModel(np.array([0.9]), 2.0)
    x = np.array([model.draw(np.random.default_rng(i), 50) for i in range(400)])
    assert np.var(x[:, 0]) == pytest.approx(2.0 / (1 - 0.81), rel=0.15)
    assert np.mean(x[:, 1:] * x[:, :-1]) / np.mean(x * x) == pytest.approx(0.9, abs=0.03)
    assert np.var(unc.NoiseModel(np.zeros(0), 2.0).draw(np.random.default_rng(0), 20000)) == pytest.approx(2.0,
                                                                                                          rel=0.03)


def test_sandwich_with_white_noise_model_is_the_laplace_covariance():
    rng = np.random.default_rng(4)
    J = rng.normal(size=(50, 5))
    free = np.ones(5, dtype=bool)
    white = unc.NoiseModel(np.zeros(0), 0.3 ** 2)
    np.testing.assert_allclose(unc.laplace_covariance(J, 0.3, np.zeros((5, 5)), 0.0, free, noise=white),
                               unc.laplace_covariance(J, 0.3, np.zeros((5, 5)), 0.0, free), rtol=1e-10)
    # a model of twice the variance: the covariance of the least-squares estimate doubles, whatever sigma says
    double = unc.NoiseModel(np.zeros(0), 2 * 0.3 ** 2)
    np.testing.assert_allclose(unc.laplace_covariance(J, 0.7, np.zeros((5, 5)), 0.0, free, noise=double),
                               2 * unc.laplace_covariance(J, 0.3, np.zeros((5, 5)), 0.0, free), rtol=1e-10)


@pytest.mark.parametrize("K, trials, estimated", [(400, 1500, False), (1600, 600, True)])
def test_residual_noise_bands_cover_90_percent_under_coloured_noise(K, trials, estimated):
    """y = J theta + n with strongly correlated AR(1) noise (a = 0.9) and slowly varying columns, least squares.
    With the generator's noise model the sandwich band holds the truth in 90 % of the trials (3 x 1500: within
    1.5 %, about 3 binomial sigma): the formula is right. With the model estimated from each residual (the
    way identify_by_matching uses it) coverage is a little lower, as for every spectral estimate at low
    frequencies from a short record (0.82 at K = 400, 0.88 at K = 1600 in a trial run): 0.85-0.93 at K = 1600.
    White-noise bands at the residual's own level hold it far less often."""
    rng = np.random.default_rng(5)
    P = 3
    t = np.linspace(0.0, 1.0, K)
    J = np.column_stack([np.ones(K), np.sin(2 * np.pi * t), np.cos(3 * np.pi * t)])
    theta = np.array([0.2, -0.1, 0.3])
    free = np.ones(P, dtype=bool)
    generator = unc.NoiseModel(np.array([0.9]), 0.05 ** 2)
    hits = white_hits = 0
    for _ in range(trials):
        y = J @ theta + 0.05 * _ar_series(rng, [0.9], K)
        est, *_ = np.linalg.lstsq(J, y, rcond=None)
        r = J @ est - y
        model = unc.ar_noise_model(r, fitted=P) if estimated else generator
        C = unc.laplace_covariance(J, 1.0, np.zeros((0, 0)), 0.0, free, noise=model)
        lo, up = unc.log_bands(est, C)
        hits += np.sum((lo <= np.exp(theta)) & (np.exp(theta) <= up))
        s = np.sqrt(r @ r / (K - P))
        lo, up = unc.log_bands(est, unc.laplace_covariance(J, s, np.zeros((0, 0)), 0.0, free))
        white_hits += np.sum((lo <= np.exp(theta)) & (np.exp(theta) <= up))
    share = hits / (P * trials)
    if estimated:
        assert 0.85 <= share <= 0.93, share
    else:
        assert abs(share - 0.90) < 0.015, share
    assert white_hits / (P * trials) < 0.6


def test_rhat_and_ess_on_known_chains():
    rng = np.random.default_rng(2)
    iid = rng.normal(size=(4, 2000, 2))
    assert np.all(np.abs(unc.split_rhat(iid) - 1) < 0.01)
    assert np.all(np.abs(unc.effective_sample_size(iid) / 8000 - 1) < 0.15)
    shifted = iid + np.array([0.0, 0.0, 0.0, 3.0])[:, None, None]
    assert np.all(unc.split_rhat(shifted) > 1.3)
    # AR(1) with rho = 0.8: ESS = N (1 - rho) / (1 + rho)
    rho = 0.8
    x = np.empty((4, 20000, 1))
    x[:, 0] = rng.normal(size=(4, 1))
    for t in range(1, 20000):
        x[:, t] = rho * x[:, t - 1] + np.sqrt(1 - rho ** 2) * rng.normal(size=(4, 1))
    assert abs(unc.effective_sample_size(x)[0] / (80000 * (1 - rho) / (1 + rho)) - 1) < 0.15


def test_pcn_samples_a_gaussian_target_with_a_wrong_reference():
    """Target N(m, A^-1), reference (proposal) covariance 2 A^-1 and mean shifted: the generalised pCN ratio
    corrects both; sample mean and covariance match the target within Monte-Carlo error."""
    rng = np.random.default_rng(3)
    M = rng.normal(size=(3, 3))
    A = M @ M.T + 3 * np.eye(3)
    m = np.array([0.5, -1.0, 2.0])
    cov = np.linalg.inv(A)
    phi = lambda t: 0.5 * (t - m) @ A @ (t - m)
    res = unc.sample(phi, m + 0.3 * np.sqrt(np.diag(cov)), 2 * cov, np.full(3, -50.0), np.full(3, 50.0),
                     target_ess=1500, max_draws=200000, seed=4)
    assert res.converged and res.rhat < 1.01 and res.ess > 1500
    d = res.draws.reshape(-1, 3)
    se = np.sqrt(np.diag(cov) / res.ess)
    assert np.all(np.abs(d.mean(axis=0) - m) < 4 * se)
    np.testing.assert_allclose(np.cov(d.T), cov, rtol=0.12, atol=0.12 * np.max(np.diag(cov)))


def test_pcn_respects_bounds_and_matches_a_non_gaussian_target():
    """phi = theta^4 on [0, 2] (a half of exp(-theta^4)): E theta = Gamma(1/2) / Gamma(1/4) by quadrature."""
    phi = lambda t: float(t[0] ** 4)
    res = unc.sample(phi, np.array([0.5]), np.array([[0.1]]), np.array([0.0]), np.array([2.0]),
                     target_ess=2000, max_draws=400000, seed=5)
    d = res.draws.reshape(-1)
    assert d.min() >= 0.0 and d.max() <= 2.0
    x = np.linspace(0, 2, 200001)
    w = np.exp(-x ** 4)
    mean = np.trapezoid(x * w, x) / np.trapezoid(w, x)
    sd = np.sqrt(np.trapezoid((x - mean) ** 2 * w, x) / np.trapezoid(w, x))
    assert abs(d.mean() - mean) < 4 * sd / np.sqrt(res.ess)


def test_sampler_reports_progress_and_stops_at_max_draws_when_not_converged():
    lines = []
    res = unc.sample(lambda t: 0.5 * float(t @ t), np.zeros(2), np.eye(2), np.full(2, -9.0), np.full(2, 9.0),
                     target_ess=1e9, max_draws=4000, check_every=100, seed=6, progress=lines.append)
    assert not res.converged
    assert res.draws.shape[0] * res.draws.shape[1] >= 4000
    assert lines and "R-hat" in lines[-1] and "ESS" in lines[-1]


def test_find_anomalies_reads_runs_off_a_profile():
    Z = np.ones(60)
    Z[10:15] = 0.7          # neck
    Z[30:33] = 1.3          # bulge
    Z[45] = 0.8             # a single element: shorter than min_elements
    f = unc.find_anomalies(Z, None, None, window=21, min_change=0.08, min_elements=2)
    assert [(a.start, a.stop) for a in f] == [(10, 15), (30, 33)]
    assert f[0].change == pytest.approx(-0.3) and f[1].change == pytest.approx(0.3)
    # a band that holds the baseline vetoes the run
    lower, upper = Z * 0.9, Z * 1.1
    upper[10:15] = 1.05
    f = unc.find_anomalies(Z, lower, upper, window=21)
    assert [(a.start, a.stop) for a in f] == [(30, 33)]


def test_local_baseline_follows_a_drift_but_not_an_anomaly():
    Z = np.linspace(1.0, 1.3, 80)
    Z[40:44] *= 0.6
    b = unc.local_baseline(Z, 21)
    np.testing.assert_allclose(b[40:44], np.linspace(1.0, 1.3, 80)[40:44], rtol=0.02)


def test_match_feature_prefers_the_largest_overlap_of_the_same_sign():
    ref = unc.Feature(10, 16, -0.3)
    cands = [unc.Feature(8, 11, -0.2), unc.Feature(11, 17, -0.25), unc.Feature(10, 16, 0.3)]
    assert unc.match_feature(cands, ref) is cands[1]
    assert unc.match_feature([unc.Feature(20, 25, -0.3)], ref) is None


def test_whitened_residual_gives_the_misfit_and_unit_variance_noise():
    """|whiten(r)|^2 / 2 is the misfit; the AR process's own draws whiten to unit variance; columns (a Jacobian)
    are whitened one by one."""
    rng = np.random.default_rng(4)
    nm = unc.NoiseModel(np.array([0.7, -0.2]), 0.5)
    r = rng.normal(size=300)
    assert 0.5 * float(unc.NoiseModel.whiten(nm, r) @ nm.whiten(r)) == pytest.approx(nm.misfit(r), rel=1e-13)
    assert np.var(nm.whiten(nm.draw(rng, 200_000))) == pytest.approx(1.0, rel=0.02)
    J = rng.normal(size=(300, 3))
    np.testing.assert_allclose(nm.whiten(J)[:, 1], nm.whiten(J[:, 1]), rtol=1e-14)


def test_edge_profiles_move_a_step_by_partial_volume():
    """The step between the levels a (5 elements above) and b (3 below) moved to x: the volume at level b,
    sum (m - a) / (b - a) over the elements, is the length below x to the run's end; x = start gives m itself;
    a step reached through a transition element moves across it; bad limits are refused."""
    a, b = 0.1, -0.3
    m = np.r_[np.full(5, a), np.full(3, b), np.full(4, 0.4)]
    x, profiles = unc.edge_profiles(m, 5, 1, 7, substeps=4)
    assert x[0] == pytest.approx(1.0) and x[-1] == pytest.approx(7.0) and x[1] - x[0] == pytest.approx(0.25)
    np.testing.assert_array_equal(profiles[:, 8:], np.broadcast_to(m[8:], (x.size, 4)))
    np.testing.assert_array_equal(profiles[:, 0], np.full(x.size, a))
    volume = ((profiles[:, :8] - a) / (b - a)).sum(axis=1)
    np.testing.assert_allclose(volume, 8.0 - x, rtol=1e-12)
    np.testing.assert_array_equal(profiles[np.flatnonzero(x == 5.0)[0]], m)
    assert profiles[np.flatnonzero(x == 4.5)[0]][4] == pytest.approx(0.5 * (a + b))
    # a transition element (3) between a and b: moved up to x = 3.5, half of element 3 takes b, all of 4
    t = np.r_[np.full(3, a), -0.1, np.full(4, b)]
    x, profiles = unc.edge_profiles(t, 4, 2, 6, substeps=2)
    up = profiles[np.flatnonzero(x == 3.5)[0]]
    np.testing.assert_allclose(up, np.r_[a, a, a, 0.5 * (-0.1 + b), b, b, b, b], rtol=1e-15)
    down = profiles[np.flatnonzero(x == 5.0)[0]]
    np.testing.assert_allclose(down, np.r_[a, a, a, -0.1, -0.1, b, b, b], rtol=1e-15)
    with pytest.raises(ValueError, match="top <= start <= bottom"):
        unc.edge_profiles(m, 5, 6, 7)


def test_profile_interval_is_the_wilks_interval_of_a_quadratic():
    """crit = (x - x0)^2 / (2 s^2): the interval 2 Delta <= 2.71 is x0 +- 1.645 s (to the grid); a second, lower
    basin is found as the best, and the interval spans the first basin too where that is within the limit, not
    where it is above it; of equal values the one nearest ``at`` wins."""
    x = np.arange(0, 2001) / 100
    s = 0.8
    crit = (x - 7.3) ** 2 / (2 * s * s)
    best, lo, hi = unc.profile_interval(x, crit, 2.705543454095404, at=0.0)
    assert best == pytest.approx(7.3)
    assert lo == pytest.approx(7.3 - 1.6449 * s, abs=0.011) and hi == pytest.approx(7.3 + 1.6449 * s, abs=0.011)
    two = np.minimum(crit, (x - 15.0) ** 2 / (2 * 0.1 ** 2) - 1.0)
    best, lo, hi = unc.profile_interval(x, two, 2.705543454095404, at=0.0)
    assert best == pytest.approx(15.0) and hi < 15.3
    assert lo == pytest.approx(7.3 - np.sqrt(2.705543454095404 / 2 - 1.0) * np.sqrt(2) * s, abs=0.011)
    far = np.minimum(crit, (x - 15.0) ** 2 / (2 * 0.1 ** 2) - 2.0)
    best, lo, hi = unc.profile_interval(x, far, 2.705543454095404, at=0.0)
    assert best == pytest.approx(15.0) and lo > 14.7 and hi < 15.3
    flat = np.zeros(x.size)
    assert unc.profile_interval(x, flat, 2.7, at=4.0) == pytest.approx((4.0, 0.0, 20.0))
