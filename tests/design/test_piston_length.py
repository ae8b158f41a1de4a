"""Efficiency design lets the piston's length vary and reports the best uniform piston of the same mass
(issue 20, item 6)."""

import numpy as np
import pytest

import rodimpact as ri

DT, Z_ROD, V = 2e-6, 60e3, 10.0


def _case():
    """A 40-element rod of 60 kN s/m on rock k2 = 3 k, with x = k T / Z = 3 for the 20-element piston of the
    rod's impedance (T its round trip); the mass is that piston's."""
    rod = ri.Rod.from_impedance([Z_ROD] * 40, DT)
    k = 3.0 * Z_ROD / (2 * 20 * DT)
    return rod, ri.BitRockEnd(k, 3 * k), 20 * DT * Z_ROD


def _uniform_efficiencies(rod, end, mass, counts):
    """Efficiency of the uniform piston of ``mass`` with m elements (run: its pulse plus three round trips through
    the rod, the default efficiency run), simulated here independently."""
    out = {}
    for m in counts:
        z = mass / (m * DT)
        sim = ri.simulate(ri.System([ri.Rod.from_impedance([z] * m, DT), rod], [V, 0.0], right=end),
                          steps=2 * m + 6 * 40, dt=DT)
        out[m] = -DT * np.dot(sim.end_force["right"], sim.end_velocity["right"]) / (0.5 * mass * V * V)
    return out


def test_a_design_over_a_range_of_lengths_beats_every_uniform_piston_of_the_same_mass():
    """At x = 3 a uniform piston of 12 elements beats every 20-element design; with n = (6, 20) the design may
    be shorter and must do at least as well as the best uniform piston, which it reports."""
    rod, end, mass = _case()
    uniform = _uniform_efficiencies(rod, end, mass, range(6, 21))
    m_best = max(uniform, key=uniform.get)
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=end), V, n=(6, 20), dt=DT,
                  limits=ri.StrikerLimits(diameter_bounds=(0.02, 0.08), mass=mass),
                  search=ri.SearchOptions(max_iterations=30, starts=2))
    assert d.mass == pytest.approx(mass, rel=1e-9)
    assert d.efficiency >= uniform[m_best] - 1e-9
    assert d.n_elements < 20
    ref = d.diagnostics["uniform_reference"]
    assert ref["elements"] == m_best
    assert ref["efficiency"] == pytest.approx(uniform[m_best], rel=1e-9)
    assert d.efficiency == pytest.approx(d.verify().efficiency, rel=1e-10)
    assert set(d.diagnostics["lengths"]) >= {m_best, 20}


def test_every_efficiency_design_reports_the_best_uniform_piston_of_its_mass():
    rod, end, mass = _case()
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=end), V, n=14, dt=DT,
                  limits=ri.StrikerLimits(diameter_bounds=(0.02, 0.08), mass=mass),
                  search=ri.SearchOptions(max_iterations=5, starts=1))
    uniform = _uniform_efficiencies(rod, end, mass, range(1, 15))
    admissible = {m: e for m, e in uniform.items()
                  if ri.STEEL.impedance(np.pi / 4 * 0.02 ** 2) <= mass / (m * DT)
                  <= ri.STEEL.impedance(np.pi / 4 * 0.08 ** 2)}
    ref = d.uniform_reference
    assert ref["elements"] == max(admissible, key=admissible.get)
    assert ref["efficiency"] == pytest.approx(max(admissible.values()), rel=1e-9)


def test_a_range_of_lengths_needs_a_prescribed_mass():
    rod, end, _ = _case()
    struck = ri.System.struck(rod, far_end=end)
    with pytest.raises(ValueError, match="StrikerLimits.mass: a range of element counts"):
        ri.design(ri.EfficiencyObjective(), struck, V, n=(6, 20), dt=DT)
    with pytest.raises(ValueError, match="n: give"):
        ri.design(ri.EfficiencyObjective(), struck, V, n=(20, 6), dt=DT, limits=ri.StrikerLimits(mass=0.1))
    with pytest.raises(ValueError, match="StrikerLimits.impedance_bounds: with a range of element counts give one"):
        ri.design(ri.EfficiencyObjective(), struck, V, n=(6, 20), dt=DT,
                  limits=ri.StrikerLimits(mass=0.1, impedance_bounds=([1e4] * 20, 1e5)))
