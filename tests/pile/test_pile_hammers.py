"""Shipped hammer data: each number has a source, the conversion of the published US values is exact, and diesel
hammers are refused (combustion is not modelled)."""

import pytest

from rodimpact.pile import Hammer, hammer, hammer_names
from rodimpact.pile.units import FOOT, POUND_FORCE, STANDARD_GRAVITY


def test_vulcan_010_ram_and_stroke_from_the_published_us_values():
    h = hammer("vulcan-010")
    assert h.kind == "air-steam"
    assert h.ram_mass == pytest.approx(10000 * POUND_FORCE / STANDARD_GRAVITY, rel=1e-14)   # 4535.9237 kg
    assert h.ram_mass == pytest.approx(4535.9237, rel=1e-14)
    assert h.stroke == pytest.approx(3.25 * FOOT, rel=1e-14)
    assert h.rated_energy == pytest.approx(32500 * POUND_FORCE * FOOT, rel=1e-14)      # 32,500 ft-lb


def test_every_shipped_hammer_cites_its_numbers():
    for name in hammer_names():
        h = hammer(name)
        assert set(h.sources) >= {"ram_weight", "stroke"} and all(h.sources.values())


def test_unknown_hammer_lists_the_shipped_ones():
    with pytest.raises(ValueError, match="hammer: no hammer 'vulcan-9'; shipped: phe-vulcan-3, vulcan-010"):
        hammer("vulcan-9")


def test_diesel_is_out_of_scope():
    with pytest.raises(ValueError, match="Hammer.kind: .*diesel hammers are out of scope"):
        Hammer("d30", "diesel", 3000.0, 2.0)
