"""One blow evaluated against closed forms.

A ram rod of the pile's impedance Z and length L_r striking at V a pile whose toe does not reflect (an impedance-
matched continuation): the head carries N = -Z V / 2 and v = V / 2 for 2 L_r / c, then nothing (the ram comes to
rest, thesis ch. 2), so ENTHRU = (Z V / 2)(V / 2)(2 L_r / c) = rho A L_r V^2 / 2, the ram's whole kinetic energy,
and every pile element sees the compressive stress Z V / (2 A) = rho c V / 2 when the front passes it (t = x / c).
The lattice is exact for uniform rods, so these hold to rounding."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.pile import DrivingSystem, drive_blow, stress_envelope, transferred_energy
from rodimpact.rods.conditions import NonReflectingEnd

RHO, E = 7840.0, 210e9          # the package's steel preset
C = np.sqrt(E / RHO)


@pytest.fixture(scope="module")
def matched_blow():
    ram, pile = ri.Rod([ri.Cylinder(2.0, 0.3)]), ri.Rod([ri.Cylinder(30.0, 0.3)])
    return drive_blow(pile, DrivingSystem(3.0, ram=ram), toe=NonReflectingEnd(), gauges={"g1": 1.5})


def test_matched_ram_transfers_its_whole_kinetic_energy(matched_blow):
    area = np.pi * 0.3**2 / 4
    ke = 0.5 * RHO * area * 2.0 * 3.0**2
    assert matched_blow.emx == pytest.approx(ke, rel=1e-12)
    assert matched_blow.enthru[-1] == pytest.approx(ke, rel=1e-12)


def test_matched_ram_head_force_and_velocity(matched_blow):
    b = matched_blow
    z = RHO * C * np.pi * 0.3**2 / 4
    assert b.head_impedance == pytest.approx(z, rel=1e-12)
    n = int(round(2 * 2.0 / C / b.result.dt))                       # steps of the pulse 2 L_r / c
    assert b.head.force[:n] == pytest.approx(np.full(n, -z * 1.5), rel=1e-12)
    assert b.head.velocity[:n] == pytest.approx(np.full(n, 1.5), rel=1e-12)
    assert np.abs(b.head.force[n:]).max() < 1e-9 * z * 1.5


def test_matched_ram_stress_envelope(matched_blow):
    env = matched_blow.envelope
    assert env.compression == pytest.approx(np.full(env.depth.size, RHO * C * 1.5), rel=1e-12)
    assert np.all(np.abs(env.compression_time - env.depth / C) <= matched_blow.result.dt)
    stress, depth, when = env.max_compression
    assert depth == env.depth[0] and when == env.compression_time[0]     # a plateau: the first element it reaches
    assert env.tension.max() < 1e-9 * RHO * C * 1.5


def test_gauge_below_the_head_sees_the_same_pulse_later(matched_blow):
    g = matched_blow.gauges["g1"]
    lag = int(round(g.node_position / C / matched_blow.result.dt))
    peak = np.abs(matched_blow.head.force).max()
    assert g.force[lag:lag + 50] == pytest.approx(matched_blow.head.force[:50], rel=1e-12, abs=1e-12 * peak)


def test_envelope_and_enthru_of_small_arrays_by_hand():
    stress = np.array([[0.0, -3.0, 2.0, -1.0], [1.0, 0.5, -0.5, 4.0]])
    env = stress_envelope(np.array([0.5, 1.5]), np.array([0.0, 1.0, 2.0, 3.0]), stress)
    assert env.compression.tolist() == [3.0, 0.5] and env.compression_time.tolist() == [1.0, 2.0]
    assert env.tension.tolist() == [2.0, 4.0] and env.tension_time.tolist() == [2.0, 3.0]
    assert env.max_compression == (3.0, 0.5, 1.0) and env.max_tension == (4.0, 1.5, 3.0)
    # -N v dt summed: (-(-2) x 1 + -(-1) x 3 + -(1) x 1) x 0.5 = (2 + 3 - 1) x 0.5
    assert transferred_energy(np.array([-2.0, -1.0, 1.0]), np.array([1.0, 3.0, 1.0]), 0.5).tolist() == [1.0, 2.5, 2.0]


def test_gauge_below_the_toe_is_refused():
    ram, pile = ri.Rod([ri.Cylinder(2.0, 0.3)]), ri.Rod([ri.Cylinder(10.0, 0.3)])
    with pytest.raises(ValueError, match=r"gauges.g: 12 m is below the pile's toe \(10 m\)"):
        drive_blow(pile, DrivingSystem(3.0, ram=ram), gauges={"g": 12.0})


def test_soil_depths_become_positions_below_the_head():
    """A 20 m pile with its toe 15 m below ground: the ground is 5 m below the head, so depths z = 0, 5, 15 m
    are positions x = 5, 10, 20 m; the toe takes the toe resistance and the toe's quakes and damping."""
    from rodimpact.pile import CapacitySoil, SoilDynamics
    from rodimpact.pile.blow import soil_elements

    dyn = SoilDynamics(2e-3, 3e-3, 0.1, 0.4, unloading_quake=1e-3)
    soil = CapacitySoil(1e6, 0.6, dyn).resistance(15.0, np.array([0.0, 5.0, 15.0]))
    (shaft,), toe = soil_elements(soil, 1, 20.0)
    assert list(shaft.depths) == [5.0, 10.0, 20.0] and shaft.rod == 1
    assert list(shaft.unit_resistance) == pytest.approx([40e3, 40e3], rel=1e-15)
    assert (shaft.quake, shaft.damping, shaft.damping_kind) == (2e-3, 0.1, "smith")
    assert (toe.ultimate, toe.quake, toe.unloading_quake, toe.damping) == (pytest.approx(4e5, rel=1e-15), 3e-3,
                                                                          1e-3, 0.4)
