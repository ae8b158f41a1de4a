"""The driving system: the impact velocity of a dropped ram, V = sqrt(2 g eta h) (free fall M V^2/2 = eta M g h),
the lumped chain at the pile head and the refusals naming the key."""

import math

import pytest

import rodimpact as ri
from rodimpact.pile import DrivingSystem, hammer, impact_velocity
from rodimpact.rods.conditions import Cushion, LumpedJoint, PointMass


def test_impact_velocity_by_hand():
    # h = 1.2 m, eta = 0.8: V^2 = 2 x 9.80665 x 0.8 x 1.2 = 18.828768 m^2/s^2
    assert impact_velocity(1.2, 0.8) == pytest.approx(math.sqrt(18.828768), rel=1e-15)
    assert impact_velocity("1 ft", 1.0) == pytest.approx(math.sqrt(2 * 9.80665 * 0.3048), rel=1e-15)


def test_drop_height_without_efficiency_names_the_key():
    with pytest.raises(ValueError, match="efficiency: missing; a drop_height needs the hammer efficiency"):
        DrivingSystem.dropped(1.0, ram_mass=1000.0)


@pytest.mark.parametrize("eta", [0.0, -0.1, 1.2])
def test_efficiency_outside_0_1_is_refused(eta):
    with pytest.raises(ValueError, match="efficiency: must"):
        impact_velocity(1.0, eta)


def test_from_hammer_kinetic_energy_is_eta_w_h():
    h = hammer("vulcan-010")
    d = DrivingSystem.from_hammer(h, 0.67)
    assert d.kinetic_energy == pytest.approx(0.67 * h.rated_energy, rel=1e-14)


def test_head_chain_outside_in():
    hc, pc = Cushion(1e9, 0.8), Cushion(5e8, 0.5)
    d = DrivingSystem(3.0, ram_mass=5000.0, hammer_cushion=hc, helmet_mass=800.0, pile_cushion=pc)
    assert list(d.pile_head().items) == [PointMass(5000.0, 3.0), hc, PointMass(800.0, 0.0), pc]
    assert list(DrivingSystem(3.0, ram_mass=5000.0).pile_head().items) == [PointMass(5000.0, 3.0)]
    ram = ri.Rod([ri.Cylinder(2.0, 0.3)])
    assert DrivingSystem(3.0, ram=ram).ram_joint() is None
    assert DrivingSystem(3.0, ram=ram, pile_cushion=pc).ram_joint() == LumpedJoint([pc])


def test_restitution_outside_0_1_is_refused():
    with pytest.raises(ValueError, match="restitution"):
        Cushion(1e9, 1.5)
    with pytest.raises(ValueError, match="restitution"):
        Cushion(1e9, 0.0)


@pytest.mark.parametrize("kwargs, match", [
    ({"ram_mass": 1000.0, "helmet_mass": 100.0}, "DrivingSystem.hammer_cushion: missing; a helmet needs"),
    ({"ram_mass": 1000.0, "hammer_cushion": Cushion(1e9, 0.8), "pile_cushion": Cushion(1e9, 0.5)},
     "DrivingSystem.helmet_mass: must be > 0 between a hammer cushion and a pile cushion"),
    ({}, "DrivingSystem.ram_mass: give exactly one of ram_mass .* got neither"),
    ({"ram_mass": -1.0}, "DrivingSystem.ram_mass: must be > 0"),
    ({"ram_mass": 1.0, "pile_cushion": 3.0}, "DrivingSystem.pile_cushion: must be a Cushion"),
])
def test_refusals_name_the_field(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        DrivingSystem(3.0, **kwargs)
