"""Mean (centre-of-mass) velocity of rod segments from element impedances and velocities, compiled.

An element of impedance Z = rho c A and travel time dt has the mass rho A c dt = Z dt, so on the
equal-travel-time lattice the mean velocity of a rod is its momentum over its mass,
sum(Z_i v_i) / sum(Z_i) (m/s). :attr:`SimulationResult.rigid_body_velocity` and
:func:`~rodimpact.simulate_batch` both take it from this one function, so a batch design and its
:func:`~rodimpact.simulate` run agree bit for bit (the sums run left to right in both).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def mean_velocities(z: np.ndarray, v: np.ndarray, bounds: np.ndarray) -> np.ndarray:
    """``out[d, k] = sum(z[d, i] v[d, i]) / sum(z[d, i])`` over ``bounds[k] <= i < bounds[k + 1]``.

    ``z``: element impedances (N s/m), ``v``: element velocities (m/s), both rows x elements; ``bounds``:
    the first element of each segment and the end of the last. Returns rows x segments, m/s.
    """
    out = np.empty((z.shape[0], bounds.size - 1))
    for d in range(z.shape[0]):
        for k in range(bounds.size - 1):
            momentum = 0.0
            mass = 0.0
            for i in range(bounds[k], bounds[k + 1]):
                momentum += z[d, i] * v[d, i]
                mass += z[d, i]
            out[d, k] = momentum / mass
    return out
