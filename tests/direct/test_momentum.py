"""The compiled mean velocity (momentum / lattice mass) against the plain numpy expression."""

import numpy as np

from rodimpact.direct._momentum import mean_velocities


def test_mean_velocities_equal_momentum_over_mass():
    rng = np.random.default_rng(4)
    z = rng.uniform(1e4, 9e4, (5, 37))
    v = rng.normal(0.0, 3.0, (5, 37))
    bounds = np.array([0, 1, 12, 30, 37])
    got = mean_velocities(z, v, bounds)
    want = np.array([[np.dot(z[d, a:b], v[d, a:b]) / z[d, a:b].sum() for a, b in zip(bounds[:-1], bounds[1:])]
                     for d in range(5)])
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=1e-13 * np.abs(v).max())


def test_a_rod_moving_as_a_whole_has_its_velocity():
    """Every element at 4.25 m/s: the mean is 4.25 m/s whatever the impedances."""
    z = np.random.default_rng(5).uniform(1e4, 9e4, (1, 50))
    np.testing.assert_allclose(mean_velocities(z, np.full((1, 50), 4.25), np.array([0, 50])), 4.25, rtol=1e-14)
