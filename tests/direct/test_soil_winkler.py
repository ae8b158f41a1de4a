"""Elastic shaft soil (quake and ultimate resistance so large that it never yields) along a uniform rod against an
independent reference: the modal solution of a free-free rod on a Winkler foundation, with the measured
convergence order of the lattice (the soil lumped to the nodes).

Reference (derived here). A rod of impedance Z, wave speed c, length L (mass per length m = Z / c, EA = Z c) on
springs of k_w N/m per m (the soil's R_u / q per length), both ends free, is pushed at the head (x = 0) by a
constant force F0 from t = 0 (a head force end N = -F0: compression pushes in +x). m u_tt = EA u_xx - k_w u.
The free-free modes phi_0 = 1, phi_n = sqrt(2) cos(n pi x / L) (int_0^L phi_n phi_m = L delta_nm) have
omega_n^2 = (n pi c / L)^2 + k_w / m; with u = sum phi_n(x) q_n(t), m L q_n'' + m L omega_n^2 q_n =
F0 phi_n(0), so q_n = F0 phi_n(0) / (m L omega_n^2) (1 - cos omega_n t) and

    u(x, t) = F0 / (m L) [ (1 - cos w0 t) / w0^2 + 2 sum_n cos(n pi x / L) (1 - cos wn t) / wn^2 ].

The sum converges like 1/n^2; 200 000 terms leave a relative truncation error ~2 / (pi^2 2e5) = 1e-6.
"""

from __future__ import annotations

import numpy as np

import rodimpact as ri
from rodimpact.rods.soil import ShaftResistance

Z, C, L, F0 = 1.0e6, 5000.0, 5.0, 1.0e6
EA, M = Z * C, Z / C
K_W = 10.0 * EA / L ** 2          # k_w L^2 / EA = 10: the soil changes the response strongly
QUAKE = 0.1                       # u stays ~1e-3 m << q: elastic


def _modal(x: float, t: np.ndarray, modes: int = 200_000) -> np.ndarray:
    n = np.arange(1, modes + 1)[:, None]
    w0 = np.sqrt(K_W / M)
    wn = np.sqrt((n * np.pi * C / L) ** 2 + K_W / M)
    series = (np.cos(n * np.pi * x / L) * (1.0 - np.cos(wn * t[None, :])) / wn ** 2).sum(axis=0)
    return F0 / (M * L) * ((1.0 - np.cos(w0 * t)) / w0 ** 2 + 2.0 * series)


def test_elastic_shaft_soil_matches_the_winkler_modal_solution_second_order() -> None:
    times = np.arange(1, 27) * (L / C) / 10           # on the step grid of every n below (multiples of 10)
    reference = {x: _modal(x, times) for x in (L, L / 2)}
    errors = []
    for n in (50, 100, 200, 400):
        dt = L / C / n
        pile = ri.Rod.from_impedance(np.full(n, Z), dt=dt, wave_speed=C)
        soil = ShaftResistance(0, [0.0, L], [K_W * QUAKE], quake=QUAKE, damping=0.0)
        probes = [ri.Probe("toe", 0, L), ri.Probe("mid", 0, L / 2)]
        problem = ri.Problem.of([pile], [0.0], steps=int(round(times[-1] / dt)) + 1, dt=dt, left=ri.ForceEnd(-F0),
                                loads=[soil], outputs=ri.Outputs(probes=probes))
        res = ri.simulate(problem)
        k = np.rint(times / dt).astype(int)
        err = max(np.abs(res.probes[name].displacement[k] - reference[x]).max() / np.abs(reference[x]).max()
                  for name, x in (("toe", L), ("mid", L / 2)))
        errors.append(err)
        assert np.abs(res.soil.resistance).max() < 0.05 * res.soil.ultimate.min()     # far from yield
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured: errors 4.7e-3, 1.16e-3, 2.9e-4, 7.2e-5; orders 2.009, 2.005, 2.003
    assert np.all(orders > 1.95), (errors, orders)
    assert errors[-1] < 1e-4
