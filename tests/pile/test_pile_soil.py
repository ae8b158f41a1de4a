"""Soil input: distributions of a capacity sum to it with the hand-derived shape, layered profiles give unit
resistance x perimeter and x toe area divided by the setup factor, and bad input names the field."""

import numpy as np
import pytest

from rodimpact.pile import CapacitySoil, SoilDynamics, SoilLayer, SoilProfile

DYN = SoilDynamics(2.54e-3, 2.54e-3, 0.16, 0.5)


def test_uniform_and_triangular_distributions_by_hand():
    """R = 2 MN, shaft 60 %: R_s = 1.2 MN over D = 20 m. Uniform: 60 kN/m. Triangular r(z) = 2 R_s z / D^2:
    on [0, 10] its mean is r(5) = 2 x 1.2e6 x 5 / 400 = 30 kN/m, on [10, 20] r(15) = 90 kN/m."""
    edges = np.array([0.0, 10.0, 20.0])
    u = CapacitySoil(2e6, 0.6, DYN).resistance(20.0, edges)
    assert np.allclose(u.unit_shaft, 60e3, rtol=1e-15) and u.toe == pytest.approx(0.8e6, rel=1e-15)
    t = CapacitySoil(2e6, 0.6, DYN, distribution="triangular").resistance(20.0, edges)
    assert t.unit_shaft == pytest.approx([30e3, 90e3], rel=1e-14)


@pytest.mark.parametrize("kind, ratio", [("uniform", None), ("triangular", None), ("trapezoid", 0.25)])
def test_every_distribution_sums_to_the_capacity(kind, ratio):
    edges = np.sort(np.concatenate([[0.0, 17.3], np.random.default_rng(1).uniform(0, 17.3, 40)]))
    r = CapacitySoil(3.1e6, 0.7, DYN, distribution=kind, top_ratio=ratio).resistance(17.3, edges)
    assert r.shaft == pytest.approx(0.7 * 3.1e6, rel=1e-13)
    assert r.total == pytest.approx(3.1e6, rel=1e-13)


def test_trapezoid_ratio_is_top_over_toe():
    """r(z) = b (rho + (1 - rho) z / D), b = 2 R_s / (D (1 + rho)); rho = 0.5, R_s = 1.5 MN, D = 10 m: b = 200 kN/m,
    r at the midpoint of [0, 2] = 200 (0.5 + 0.5 x 0.1) = 110 kN/m."""
    r = CapacitySoil(1.5e6, 1.0, DYN, distribution="trapezoid", top_ratio=0.5).resistance(10.0, np.array([0, 2, 10.]))
    assert r.unit_shaft[0] == pytest.approx(110e3, rel=1e-14)


def test_custom_distribution_must_sum_to_the_shaft_capacity():
    with pytest.raises(ValueError, match=r"CapacitySoil.shaft_resistances: must sum to shaft_share x capacity = "
                                         r"1\.2e\+06 N, got 1\.1e\+06 N"):
        CapacitySoil(2e6, 0.6, DYN, distribution="custom", depths=[0, 5, 20], shaft_resistances=[0.3e6, 0.8e6])
    ok = CapacitySoil(2e6, 0.6, DYN, distribution="custom", depths=[0, 5, 20], shaft_resistances=[0.3e6, 0.9e6])
    r = ok.resistance(20.0)
    assert r.unit_shaft == pytest.approx([60e3, 60e3], rel=1e-15)


def test_custom_distribution_deeper_than_the_penetration_is_refused():
    soil = CapacitySoil(2e6, 0.6, DYN, distribution="custom", depths=[0, 5, 20], shaft_resistances=[0.3e6, 0.9e6])
    with pytest.raises(ValueError, match="CapacitySoil.depths: the distribution reaches 20 m, deeper than the "
                                         "pile's penetration 15 m"):
        soil.resistance(15.0)


def test_setup_factor_divides_the_static_capacity():
    r = CapacitySoil(2e6, 0.5, DYN, setup_factor=2.0).resistance(10.0)
    assert r.total == pytest.approx(1e6, rel=1e-15)


def test_layered_profile_by_hand():
    """Layer 1 to 4 m: f_s = 20 kPa, setup 2 (clay); layer 2 to 12 m: f_s = 50 kPa, q_t = 5 MPa, relaxation 0.8.
    Perimeter 1.2 m, toe area 0.1 m^2, toe at 10 m: shaft 20e3 x 1.2 / 2 = 12 kN/m on [0, 4], 50e3 x 1.2 / 0.8 =
    75 kN/m on [4, 10]; toe 5e6 x 0.1 / 0.8 = 625 kN. Static: 24 and 60 kN/m, toe 500 kN."""
    profile = SoilProfile([SoilLayer(4.0, 20e3, 0.0, 2.0), SoilLayer(12.0, 50e3, 5e6, 0.8)], 1.2, 0.1, DYN)
    r = profile.resistance(10.0)
    assert r.depths.tolist() == [0.0, 4.0, 10.0]
    assert r.unit_shaft == pytest.approx([12e3, 75e3], rel=1e-15) and r.toe == pytest.approx(625e3, rel=1e-15)
    s = profile.resistance(10.0, static=True)
    assert s.unit_shaft == pytest.approx([24e3, 60e3], rel=1e-15) and s.toe == pytest.approx(500e3, rel=1e-15)
    at_boundary = profile.resistance(4.0)
    assert at_boundary.depths.tolist() == [0.0, 4.0] and at_boundary.toe == 0.0


def test_profile_that_does_not_reach_the_toe_is_refused():
    profile = SoilProfile([SoilLayer(4.0, 20e3)], 1.2, 0.1, DYN)
    with pytest.raises(ValueError, match="penetration: 5 m is below the soil profile, which ends at 4 m"):
        profile.resistance(5.0)


@pytest.mark.parametrize("make, match", [
    (lambda: SoilDynamics(-1e-3, 2e-3, 0.1, 0.1), "SoilDynamics.shaft_quake: must be > 0"),
    (lambda: SoilDynamics(1e-3, 0.0, 0.1, 0.1), "SoilDynamics.toe_quake: must be > 0"),
    (lambda: SoilDynamics(1e-3, 2e-3, 0.1, 0.1, unloading_quake=-1e-3), "SoilDynamics.unloading_quake: must be > 0"),
    (lambda: SoilDynamics(1e-3, 2e-3, 0.1, 0.1, unloading_quake=3e-3),
     "SoilDynamics.unloading_quake: must be <= toe_quake = 0.002 m"),
    (lambda: SoilDynamics(1e-3, 2e-3, 0.1, 0.1, "viscous"), "SoilDynamics.damping_kind: must be one of"),
    (lambda: CapacitySoil(1e6, 1.2, DYN), r"CapacitySoil.shaft_share: must lie in \[0, 1\]"),
    (lambda: CapacitySoil(1e6, 0.5, DYN, distribution="trapezoid"), "CapacitySoil.top_ratio: needed by the trapezoid"),
    (lambda: CapacitySoil(1e6, 0.5, DYN, distribution="parabolic"), "CapacitySoil.distribution: must be one of"),
    (lambda: SoilProfile([SoilLayer(4.0, 1.0), SoilLayer(3.0, 1.0)], 1.0, 1.0, DYN),
     r"SoilProfile.layers\[1\].bottom: must lie below the layer above \(4 m\), got 3 m"),
    (lambda: SoilLayer(4.0, -1.0), "SoilLayer.unit_shaft_resistance: must be >= 0"),
])
def test_refusals_name_the_field(make, match):
    with pytest.raises((ValueError, TypeError), match=match):
        make()
