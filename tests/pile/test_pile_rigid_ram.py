"""A rigid ram on the pile head, against the closed form and the energy bookkeeping.

Closed form: a rigid mass M at V0 striking the head of a pile of impedance Z that does not reflect gives
F(t) = -Z V0 exp(-Z t / M) and head velocity V0 exp(-Z t / M) (docs/architecture.md, point masses), so the energy
through the head is ENTHRU(T) = M V0^2 (1 - exp(-2 Z T / M)) / 2. The chain's implicit-midpoint step makes it
converge at order 2 in dt; the chain's own bookkeeping (kinetic energy lost by the ram) equals ENTHRU to
rounding, since both are the work of the same face force.

With a hammer cushion, a helmet and soil: what the ram loses is what went through the head plus what the chain
holds and dissipated, and what went through the head is what the pile holds plus the soil's work."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.pile import CapacitySoil, DrivingSystem, SoilDynamics, drive_blow
from rodimpact.rods.conditions import Cushion, NonReflectingEnd

RHO, E = 7840.0, 210e9
C = np.sqrt(E / RHO)
Z = RHO * C * np.pi * 0.3**2 / 4
PILE = ri.Rod([ri.Cylinder(30.0, 0.3)])


def test_rigid_ram_enthru_converges_at_order_2():
    mass, v0 = 2000.0, 4.0
    period = 3 * mass / Z
    exact = 0.5 * mass * v0**2 * (1 - np.exp(-2 * Z * period / mass))
    errors = []
    for n in (20, 40, 80):
        blow = drive_blow(PILE, DrivingSystem(v0, ram_mass=mass), toe=NonReflectingEnd(), dt=mass / Z / n,
                          duration=period)
        chain = blow.result.lumped[0]
        assert blow.enthru[-1] == pytest.approx(chain.initial_kinetic_energy - chain.kinetic_energy, rel=1e-12)
        errors.append(blow.enthru[-1] - exact)
    orders = np.log2(np.abs(errors[:-1]) / np.abs(errors[1:]))
    assert np.all((orders > 1.95) & (orders < 2.05)), orders


def test_ram_energy_goes_to_the_chain_the_pile_and_the_soil():
    driving = DrivingSystem.dropped(1.5, 0.8, ram_mass=3000.0, hammer_cushion=Cushion(1.5e9, 0.8), helmet_mass=600.0,
                                    pile_cushion=Cushion(3e9, 0.5))
    soil = CapacitySoil(2e6, 0.5, SoilDynamics(2.54e-3, 2.54e-3, 0.164, 0.492)).resistance(20.0,
                                                                                           np.linspace(0, 20, 21))
    blow = drive_blow(PILE, driving, soil)
    chain, e = blow.result.lumped[0], blow.result.energy
    assert chain.initial_kinetic_energy == pytest.approx(driving.kinetic_energy, rel=1e-15)
    held = chain.kinetic_energy + chain.stored_energy + chain.dissipated_energy
    assert blow.enthru[-1] + held == pytest.approx(driving.kinetic_energy, rel=1e-10)
    pile = e.kinetic[0] + e.strain[0]
    assert blow.enthru[-1] == pytest.approx(pile[-1] - pile[0] - e.work_soil[-1] - e.work_right[-1], rel=1e-10)
    assert chain.dissipated_energy > 0 and blow.permanent_set > 0
