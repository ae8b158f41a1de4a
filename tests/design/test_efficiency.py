"""The efficiency objective: work done on the rock per blow / striker kinetic energy.

Closed form (rectangular incident wave of duration T into a loading-only rock spring k at the end of a rod of
impedance Z, i.e. a uniform piston of the rod's impedance, T = its round-trip time): the bit force is
F(t) = 2 F_i (1 - exp(-k t / Z)), the work F(T)^2 / (2 k) and the incident energy F_i^2 T / Z, so
eta(x) = 2 (1 - exp(-x))^2 / x with x = k T / Z; its maximum is 0.8145 at x = 1.2564.
"""

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.design.objectives import EfficiencyCost


def eta_closed_form(x):
    return 2.0 * (1.0 - np.exp(-x)) ** 2 / x


def test_closed_form_maximum():
    res = minimize_scalar(lambda x: -eta_closed_form(x), bounds=(0.1, 10.0), method="bounded",
                          options={"xatol": 1e-10})
    assert res.x == pytest.approx(1.2564, abs=1e-4)
    assert -res.fun == pytest.approx(0.8145, abs=1e-4)


def _lattice_eta(n, x, z=50e3, v=10.0, dt=1e-6):
    """A uniform piston of n elements on a long rod of the same impedance ending on BitRockEnd(k, 1e6 k): run
    until the incident wave has passed into the rock (before any reflection returns)."""
    k = x * z / (2 * n * dt)
    s = ri.System.struck(ri.Rod.from_impedance([z] * (4 * n), dt), far_end=ri.BitRockEnd(k, 1e6 * k))
    steps = 8 * n
    fw = ImpactProblem(s, dt, n, steps).forward(np.full(n, z), v)
    return EfficiencyCost(dt, steps).efficiency(fw, np.full(n, z), v)


@pytest.mark.parametrize("x", [0.5, 1.2564, 3.0])
def test_lattice_efficiency_converges_to_the_closed_form(x):
    """The lattice's efficiency converges to eta(x) (at first order when the spring is integrated per step with
    the end force of the step's start, to rounding when the step is integrated exactly): the error at n = 200
    is below 3e-3 and below the error at n = 50, and the Richardson extrapolation of n = 200, 400 agrees."""
    ns = np.array([50, 100, 200])
    err = np.array([abs(_lattice_eta(n, x) - eta_closed_form(x)) for n in ns])
    assert err[-1] < 3e-3 and err[-1] < err[0], err
    richardson = 2 * _lattice_eta(400, x) - _lattice_eta(200, x)
    assert richardson == pytest.approx(eta_closed_form(x), rel=2e-5)


def _drilling(n=12, mass_factor=1.0):
    dt = 2e-6
    z_rod = 60e3
    rod = ri.Rod.from_impedance([z_rod] * 40, dt)
    k = 1.0 * z_rod / (2 * n * dt)           # x = kT/Z = 1 for the uniform piston of the rod's impedance
    m = mass_factor * n * dt * z_rod
    return rod, ri.BitRockEnd(k, 3 * k), dt, m


def test_design_beats_the_uniform_piston_of_the_same_mass_and_length():
    """Over pistons of n elements (fixed length) and fixed mass inside diameter bounds, the efficiency found
    beats the only uniform piston of that mass (computed independently with simulate)."""
    n = 10
    rod, end, dt, m = _drilling(n)
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=end), 10.0, n, dt,
                  limits=ri.StrikerLimits(diameter_bounds=(0.02, 0.08), mass=m),
                  search=ri.SearchOptions(max_iterations=8, starts=1))
    assert d.mass == pytest.approx(m, rel=1e-10)
    assert d.constraint_report["mass_active"] == "prescribed"
    uniform = ri.Rod.from_impedance(np.full(n, m / (n * dt)), dt)
    sim = ri.simulate(ri.System([uniform, rod], [10.0, 0.0], right=end), steps=d.time.size, dt=dt)
    work = -dt * np.dot(sim.end_force["right"], sim.end_velocity["right"])
    eta_uniform = work / (0.5 * m * 10.0 ** 2)
    assert d.efficiency > eta_uniform + 0.01
    assert d.verify().efficiency == pytest.approx(d.efficiency, rel=1e-12)
    # the incident wave at the bit is recorded for the comparison with the reflection-free exponential wave
    assert d.achieved.shape == d.time.shape and np.min(d.achieved) < 0


def test_efficiency_needs_a_bit_rock_end():
    rod = ri.Rod.from_impedance([50e3] * 10, 1e-6)
    with pytest.raises(ValueError, match=r"struck.right: .*needs a BitRockEnd far end, e.g. "
                                         r"ri.System.struck\(rods, far_end=ri.BitRockEnd\(k1, k2\)\); got FreeEnd"):
        ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end="free"), 10.0, n=5, dt=1e-6)
