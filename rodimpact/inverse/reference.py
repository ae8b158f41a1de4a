"""The recursive method exactly as the thesis states it (Sec. 4.1.1, Tab. 4.1): a slow reference.

For every element q the complete impact (striker of q elements with Z_q = Z_{q-1}, plus the struck system) is
simulated from t = 0 with the direct solver, the impact force N_bar_q in window q is read, and
Delta N_q = X_q - N_bar_q, K_q (eq. 4.8) and Z_q (eq. 4.9) follow; Z_1 comes from eq. 4.4. The cost grows
like n^3 (n simulations of up to 2n steps through up to n striker elements). It shares nothing with the fast
path but the direct solver, so the two check each other (tests/inverse/test_resimulation_reference.py), and
it is the baseline of ``benchmarks/bench_synthesis.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..direct.problem import Problem
from ..direct.recording import Outputs
from ..direct.simulate import simulate
from ..lattice.lattice import build_lattice
from ..rods.rod import Rod
from ..rods.system import System
from .struck import with_striker


@dataclass(frozen=True)
class ReferenceSynthesis:
    """Per-element results of the re-simulation reference, elements 1..m from the impact face."""

    impedance: np.ndarray
    transmission_factor: np.ndarray   # K_q, eq. 4.8 (K_1 = 1)
    force_difference: np.ndarray      # Delta N_q = X_q - N_bar_q (q >= 2); X_1 - N_0 for q = 1
    force_reserve: np.ndarray         # |K_q N_0|
    n0: float                         # N_0, eq. 4.3
    n_feasible: int


def synthesize_by_resimulation(window_values: np.ndarray, struck: System, striker_velocity: float, dt: float,
                               backend: str = "numba") -> ReferenceSynthesis:
    """Thesis recursion with a full re-simulation per element.

    ``struck`` is a normalised struck system (see :func:`~rodimpact.inverse.struck.as_struck_system`) whose
    first element is stress-free and moves with the first rod's velocity (eqs. 4.1-4.4 assume this).
    """
    x = np.asarray(window_values, dtype=float)
    n = x.size
    zt = float(build_lattice(struck, dt).impedance[0])
    v_t = float(struck.velocities[0])
    n0 = -(striker_velocity - v_t) * zt / 2.0                                   # eq. 4.3
    z = np.zeros(n)
    kq = np.zeros(n)
    dn = np.zeros(n)
    z[0] = -x[0] * zt / (x[0] + (striker_velocity - v_t) * zt)                  # eq. 4.4
    if not (np.isfinite(z[0]) and z[0] > 0):
        return ReferenceSynthesis(z[:0], kq[:0], dn[:0], kq[:0], n0, 0)
    kq[0] = 1.0
    dn[0] = x[0] - n0
    k11 = 4.0 * z[0] * zt / (z[0] + zt) ** 2                                    # K_{1~,1}, eq. 4.6
    m = n
    for q in range(2, n + 1):
        trial = np.concatenate([[z[q - 2]], z[q - 2::-1]])      # left to right: Z_q = Z_{q-1}, Z_{q-1}, ..., Z_1
        rod = Rod.from_impedance(trial, dt)
        sim = simulate(Problem.of(with_striker(struck, rod, striker_velocity), steps=2 * q - 1, dt=dt,
                                  outputs=Outputs(energy_every=2 * q), allow_discretization_error=True),
                       backend=backend)
        n_bar = float(sim.junction_force[0, 2 * (q - 1)])
        pairs = 4.0 * z[:q - 2] * z[1:q - 1] / (z[:q - 2] + z[1:q - 1]) ** 2     # K_{r,r+1}, r = 1..q-2
        k = k11 * float(np.prod(pairs))                                         # eq. 4.8
        d = x[q - 1] - n_bar                                                    # eq. 4.5
        kq[q - 1] = k
        dn[q - 1] = d
        if not abs(d) < abs(k * n0):                                            # eq. 4.20
            m = q - 1
            break
        z[q - 1] = z[q - 2] * (k * n0 + d) / (k * n0 - d)                       # eq. 4.9
    return ReferenceSynthesis(z[:m], kq[:m], dn[:m], np.abs(kq[:m] * n0), n0, m)
