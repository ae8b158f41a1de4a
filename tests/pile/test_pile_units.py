"""US customary conversions and blow counts against their exact definitions: 1 ft = 0.3048 m, 1 in = 0.0254 m,
1 lbf = 0.45359237 kg x 9.80665 m/s^2, 1 kip = 4448.2216152605 N (NIST SP 811, 2008, B.8); blows per L = L / set."""

import math

import pytest

from rodimpact.pile import units


def test_kip_foot_inch_are_the_exact_definitions():
    assert units.KIP == pytest.approx(4448.2216152605, rel=1e-15)
    assert units.FOOT == 0.3048 and units.INCH == 0.0254
    assert units.KSI == pytest.approx(4448.2216152605 / 0.0254**2, rel=1e-15)      # 6.894757293168361 MPa
    assert units.FOOT_KIP == pytest.approx(0.3048 * 4448.2216152605, rel=1e-15)    # 1355.8179483314004 J


def test_blow_counts_are_length_over_set():
    s = 0.004                                            # 4 mm per blow
    assert units.blows_per_quarter_metre(s) == pytest.approx(62.5, rel=1e-15)
    assert units.blows_per_foot(s) == pytest.approx(76.2, rel=1e-15)
    assert units.blows_per_inch(s) == pytest.approx(6.35, rel=1e-15)


def test_no_set_is_refusal():
    assert units.blows_per_quarter_metre(0.0) == math.inf
    assert units.blows_per_foot(-1e-4) == math.inf
    assert units.blows_per_inch(8.7e-19) == math.inf            # the rounding of a plastic set that did not grow
    assert units.blows_per_quarter_metre(2e-9) == pytest.approx(1.25e8, rel=1e-15)


def test_unknown_unit_system_is_named():
    with pytest.raises(ValueError, match="units: must be one of 'si', 'us', got 'imperial'"):
        units.units_system("imperial")
