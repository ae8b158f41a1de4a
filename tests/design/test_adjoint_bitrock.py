"""The transpose of one bit-rock end step (end_vjp) equals central finite differences of the forward step
(end_solve) in every input (a, Z, delta, delta_max), for paths inside one piece of the bilinear law and for
paths that cross the release point and the largest penetration inside the step (loading, unloading,
release, reloading), on the compiled and the numpy path."""

import numpy as np
import pytest

from rodimpact.design._adjoint_kernels import end_vjp
from rodimpact.direct.boundary import BITROCK, end_solve

DT = 1e-6
Z = 4e4
K1 = 2e10
K2 = 6e10
PM = 1e-4                         # largest penetration so far, m; release point r = PM (1 - K1/K2)
R = PM * (1.0 - K1 / K2)


def step(x, solve):
    """Outputs of one step (N, w, delta', delta_max') for inputs x = (a, Z, delta, delta_max)."""
    a, z, delta, dmax = x
    w, n, dm = solve(BITROCK, a, z, 0.0, K1, K2, delta, dmax, DT)
    return np.array([n, w, delta + w * DT, dm])


def a_for_path(delta, s):
    """The element value a that makes the step's path run from delta to delta + s: a = -Z s/dt - mean F over the
    path, the mean computed by fine midpoint quadrature of the bilinear law (independent of end_solve)."""
    x = delta + s * (np.arange(200000) + 0.5) / 200000
    f = np.where(x > PM, K1 * x, np.maximum(K1 * PM + K2 * (x - PM), 0.0))
    return -Z * s / DT - float(np.mean(f))


# (start delta, path length s): the pieces crossed inside the step. A start below the maximum keeps the
# perturbed states valid (delta <= delta_max) for the unloading paths
PATHS = {
    "virgin loading": (PM, 2e-5),
    "reloading below the maximum": (0.9 * PM, 0.05 * PM),
    "reloading into virgin loading": (0.9 * PM, 0.2 * PM),
    "from released through unloading line into virgin": (0.5 * PM, 0.7 * PM),
    "unloading on k2": (0.99 * PM, -0.1 * PM),
    "unloading through release": (0.99 * PM, -0.5 * PM),
    "released moving in": (0.3 * PM, 0.2 * PM),
    "released moving out": (0.5 * PM, -0.2 * PM),
}


@pytest.mark.parametrize("path", sorted(PATHS))
@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_bitrock_step_transpose_equals_finite_differences(path, backend):
    delta, s = PATHS[path]
    x0 = np.array([a_for_path(delta, s), Z, delta, PM])
    solve = end_solve if backend == "numba" else end_solve.py_func
    vjp = end_vjp if backend == "numba" else end_vjp.py_func
    out = step(x0, solve)
    assert out[1] * DT == pytest.approx(s, rel=1e-6)          # the path is the intended one
    rng = np.random.default_rng(len(path))
    for _ in range(3):
        seed = rng.standard_normal(4) / np.array([abs(x0[0]), abs(s) / DT, PM, PM])   # natural scales
        got = np.array(vjp(BITROCK, x0[0], x0[1], 0.0, K1, K2, x0[2], x0[3], DT, *seed))
        fd = np.empty(4)
        for i in range(4):
            h = 1e-6 * (abs(x0[i]) if x0[i] != 0 else 1.0)
            xp, xm = x0.copy(), x0.copy()
            xp[i] += h
            xm[i] -= h
            fd[i] = seed @ (step(xp, solve) - step(xm, solve)) / (2 * h)
        scale = np.abs(fd) * np.abs(x0)
        np.testing.assert_allclose(got * np.abs(x0), fd * np.abs(x0), rtol=0, atol=2e-6 * np.max(scale))
