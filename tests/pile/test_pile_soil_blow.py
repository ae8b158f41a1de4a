"""Blows against soil, checked against independent limits.

Toe set, closed form. A ram rod of the pile's impedance Z, length L_r, at V sends F_i = Z V / 2 (compression) for
T = 2 L_r / c down a uniform pile; with toe resistance only (no shaft, no damping) the toe of an elastic-plastic
soil (stiffness k = R_u / q) obeys Z u' + k u = 2 F_i while u < q, so it reaches the quake at
t_1 = -(Z / k) ln(1 - R_u / (2 F_i)), then flows at u' = (2 F_i - R_u) / Z until the pulse has passed:
u(T) = q + (2 F_i - R_u)(T - t_1) / Z. Unloading along the same slope (unloading quake q) leaves the plastic set
u(T) - q. The run ends before the toe's reflection can return from the head (L / c + T + 0.3 L / c < 3 L / c).
The lattice solves the toe's elastic phase with a second-order step: the set converges at order 2.

Energy balance. What went through the head (ENTHRU) is what the pile holds at the end plus the work it did on the
soil (shaft and toe): ENTHRU(T) = E_pile(T) - E_pile(0) - W_soil,shaft(T) - W_toe(T), each from independent
bookkeeping (the head's force and velocity against the energy sums of the solver)."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.pile import CapacitySoil, DrivingSystem, SoilDynamics, drive_blow, drive_blows

RHO, E = 7840.0, 210e9
C = np.sqrt(E / RHO)
Z = RHO * C * np.pi * 0.3**2 / 4
L, LR, V = 20.0, 4.0, 3.0
RAM, PILE = ri.Rod([ri.Cylinder(LR, 0.3)]), ri.Rod([ri.Cylinder(L, 0.3)])


def toe_set_closed_form(ultimate: float, quake: float) -> float:
    fi, period, k = Z * V / 2, 2 * LR / C, ultimate / quake
    t1 = -(Z / k) * np.log(1 - ultimate / (2 * fi))
    assert t1 < period
    return (2 * fi - ultimate) * (period - t1) / Z


def test_toe_set_converges_at_order_2_to_the_closed_form():
    ultimate, quake = 2e6, 0.5e-3
    exact = toe_set_closed_form(ultimate, quake)                 # 3.1226 mm
    soil = CapacitySoil(ultimate, 0.0, SoilDynamics(quake, quake, 0.0, 0.0)).resistance(15.0)
    errors = []
    for n in (20, 40, 80):
        blow = drive_blow(PILE, DrivingSystem(V, ram=RAM), soil, dt=LR / C / n, duration=1.3 * L / C + 2 * LR / C)
        errors.append(blow.permanent_set - exact)
    orders = np.log2(np.abs(errors[:-1]) / np.abs(errors[1:]))
    assert np.all((orders > 1.8) & (orders < 2.2)), orders
    assert abs(errors[-1]) < 1e-8


@pytest.fixture(scope="module")
def soil_blow():
    dyn = SoilDynamics(2.54e-3, 1.0e-3, 0.164, 0.492)
    soil = CapacitySoil(2.5e6, 0.6, dyn, distribution="triangular").resistance(15.0, np.linspace(0, 15, 31))
    return drive_blow(PILE, DrivingSystem(6.0, ram=RAM), soil)


def test_enthru_is_pile_energy_plus_soil_work(soil_blow):
    e = soil_blow.result.energy
    pile = e.kinetic[1] + e.strain[1]
    balance = (pile[-1] - pile[0]) - e.work_soil[-1] - e.work_right[-1]
    assert soil_blow.enthru[-1] == pytest.approx(balance, rel=1e-10)
    assert soil_blow.result.soil.toe_work == pytest.approx(-e.work_right[-1], rel=1e-10)


def test_blow_count_is_quarter_metre_over_the_toe_set(soil_blow):
    s = soil_blow.result.soil.toe_set
    assert s > 0 and soil_blow.permanent_set == s
    assert soil_blow.blows_per_quarter_metre == pytest.approx(0.25 / s, rel=1e-15)


def test_second_blow_starts_from_the_first_blows_soil_and_residual_forces():
    dyn = SoilDynamics(2.54e-3, 2.54e-3, 0.164, 0.492)
    soil = CapacitySoil(2.5e6, 0.6, dyn).resistance(15.0, np.linspace(0, 15, 16))
    first, second = drive_blows(PILE, DrivingSystem(6.0, ram=RAM), soil, 2)
    start = second.result.system
    assert np.array_equal(start.initial[1].force, first.result.final_force[first.result.lattice.rod_start[1]:])
    assert start.right.plastic_set == pytest.approx(first.result.soil.toe_set - first.result.soil.toe_displacement)
    assert second.permanent_set > 0
