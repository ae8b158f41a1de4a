"""Layer-peeling kernel: numba vs numpy path, recovery of known strikers, existence stop, error estimate."""

from decimal import Decimal, getcontext

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import _kernels as K


def _face_history(z_striker, z_bar, v_in, dt=1e-6):
    """Contact force and face velocity (window starts) of a known striker hitting a semi-infinite bar,
    from the direct solver (independent of the peeling)."""
    m = z_striker.size
    striker = ri.Rod.from_impedance(z_striker[::-1], dt)
    bar = ri.Rod.from_impedance(np.full(4, z_bar), dt)
    sim = ri.simulate(ri.System([striker, bar], [v_in, 0.0], right="nonreflecting"), steps=2 * m, dt=dt)
    n = sim.contact_force[0::2]
    v_face = -n / z_bar                      # right-going wave into the bar at rest
    return n, v_face - v_in


def _random_face_data(rng, n):
    z = 8e4 * np.exp(np.cumsum(rng.normal(0.0, 0.05, n)))
    return _face_history(z, 9e4, 7.0) + (z,)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_numba_and_numpy_paths_agree(seed):
    rng = np.random.default_rng(seed)
    x, u, _ = _random_face_data(rng, 150)
    a = K.peel_numba(x, u)
    b = K.peel_numpy(x, u)
    assert a[3] == b[3] == 150
    for i in range(3):
        np.testing.assert_allclose(a[i], b[i], rtol=1e-12, atol=0)


@pytest.mark.parametrize("seed", [3, 4])
def test_peeling_recovers_a_known_striker(seed):
    rng = np.random.default_rng(seed)
    x, u, z_true = _random_face_data(rng, 120)
    z, refl, _, m = K.peel_numba(x, u)
    assert m == 120
    np.testing.assert_allclose(z, z_true, rtol=1e-12)
    # reflection of the wavefront at interface q/q+1 (eq. 4.7): (Z_{q+1} - Z_q) / (Z_{q+1} + Z_q)
    np.testing.assert_allclose(refl[1:], np.diff(z_true) / (z_true[1:] + z_true[:-1]), atol=1e-12)


def test_existence_stop_never_returns_nonphysical_impedance():
    # a force jump larger than the force reserve after 10 windows: eq. 4.20 fails at element 11
    x = np.full(30, -1e5)
    x[10:] = -3.5e5
    u = -x / 8e4 - 5.0
    z, refl, _, m = K.peel_numpy(x, u)
    assert m == 10
    assert np.all(z[:m] > 0) and np.all(np.isfinite(z[:m]))
    assert abs(refl[m]) >= 1.0
    zb, reflb, _, mb = K.peel_numba(x, u)
    assert mb == m and reflb[m] == pytest.approx(refl[m], rel=1e-12)


def test_first_element_eq_4_4():
    # eq. 4.4: Z_1 = -N_1 Z~ / (N_1 + (v_in - v~) Z~); semi-infinite bar at rest, V = -N/Z~
    zt, v, n1 = 79.7e3, 6.0, -150e3
    z, _, _, m = K.peel_numba(np.array([n1, n1]), np.array([-n1 / zt - v] * 2))
    assert z[0] == pytest.approx(-n1 * zt / (n1 + v * zt), rel=1e-15)


def _peel_decimal(x, u, digits=50):
    """The same recursion in 50-digit decimal arithmetic (independent high-precision reference)."""
    getcontext().prec = digits
    n = len(x)
    xs = [Decimal(float(a)) for a in x]
    us = [Decimal(float(a)) for a in u]
    z = xs[0] / us[0]
    g = [(a + z * b) / 2 for a, b in zip(xs, us)]
    f = [(a - z * b) / 2 for a, b in zip(xs, us)]
    out = [z]
    for q in range(1, n):
        r = f[q] / g[0]
        z = z * (1 + r) / (1 - r)
        out.append(z)
        c = 1 / (1 - r)
        for s in range(n - q):
            gs, fs = g[s], f[s + q]
            g[s] = (gs - r * fs) * c
            f[s + q] = (fs - r * gs) * c
    return np.array([float(a) for a in out])


@pytest.mark.parametrize("seed", [5, 6])
def test_error_estimate_bounds_the_rounding_error(seed):
    """The first-order estimate must bound the actual rounding error of the double-precision kernel (the
    same data peeled in 50-digit arithmetic is the reference)."""
    rng = np.random.default_rng(seed)
    n = 120
    t = np.arange(n) / n
    x = -2e5 * (1 + 0.8 * t + 0.02 * rng.standard_normal(n))     # rough, strongly rising target
    u = -x / 8e4 - 6.0
    z, refl, kappa, m = K.peel_numba(x, u)
    exact = _peel_decimal(x[:m], u[:m])
    err = np.abs(z[:m] / exact - 1)
    est = K.error_estimate(refl, kappa, m)
    assert np.all(err <= est)
    assert err.max() > 0        # the comparison is not vacuous


def test_trust_numbers_equal_the_absolute_value_recursion_on_arrays():
    """kappa is defined by MG/MF, the peeling recursion run on absolute values from constant arrays (read at
    MG[0] and MF[q]); both kernels carry them as two numbers. Reference: the recursion on full arrays."""
    rng = np.random.default_rng(5)
    n = 120
    t = np.arange(n) / n
    x = -2e5 * (1 + 0.8 * t + 0.02 * rng.standard_normal(n))
    x[80:] *= 3.5                                    # beyond the force reserve: existence fails at element 81
    u = -x / 8e4 - 6.0
    _, refl, kappa, m = K.peel_numba(x, u)
    z1 = x[0] / u[0]
    mg = np.full(n, np.max(0.5 * (np.abs(x) + np.abs(z1 * u))))
    mf = mg.copy()
    g0 = 0.5 * (x[0] + z1 * u[0])                   # the wavefront wave g[0]
    last = min(m, n - 1)                             # kappa is also given at the failing element
    expected = [1.0]
    for q in range(1, last + 1):
        expected.append((mg[0] + mf[q]) / abs(g0))
        r = refl[q]
        c = 1.0 / (1.0 - r)
        length = n - q
        mgs, mfs = mg[:length].copy(), mf[q:q + length].copy()
        mg[:length] = (mgs + abs(r) * mfs) * abs(c)
        mf[q:q + length] = (mfs + abs(r) * mgs) * abs(c)
        g0 = (g0 - r * (r * g0)) * c                 # g0' = (g0 - R f_q) c with f_q = R g0
    np.testing.assert_allclose(kappa[:last + 1], expected, rtol=1e-13)
    np.testing.assert_allclose(K.peel_numpy(x, u)[2][:last + 1], expected, rtol=1e-13)
    assert m == 80 and max(expected) > 10
