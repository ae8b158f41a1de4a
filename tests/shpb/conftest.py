"""Fixtures of the split-Hopkinson-bar tests: the bar pairs of the synthetic shot (shpb_synthetic.py) and the
LANL copper shot of tests/data/hoppybar."""

from pathlib import Path

import pytest
from shpb_synthetic import ti_bar

from rodimpact import ALUMINIUM_7075
from rodimpact.io import hoppybar_bar, read_lanl_raw
from rodimpact.shpb import Bar, GaugeSignals, SpecimenGeometry

LANL = Path(__file__).resolve().parents[1] / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"


@pytest.fixture(params=["equal bars", "unequal bars"])
def bars(request):
    """Equal titanium bars, or a titanium incident bar and a thicker aluminium transmitted bar (the general forms
    of the analyses must hold as well)."""
    if request.param == "equal bars":
        return ti_bar(), ti_bar("transmitted")
    return ti_bar(), Bar(material=ALUMINIUM_7075, diameter=12.7e-3, gauge_distance=0.5, name="transmitted")


@pytest.fixture(scope="session")
def lanl_signals():
    """The LANL copper shot as gauge strains (half bridges of two axial gauges, compression recorded as positive
    voltage: tests/signals/test_measured_data.py), with its bars: Ti-6Al-4V, d = 9.47 mm, gauges 381 mm from the
    specimen faces (the sheet's values)."""
    rec = read_lanl_raw(LANL)
    gauges = [hoppybar_bar(rec.metadata, bar, bridge="half-axial", polarity=-1) for bar in ("incident", "transmitted")]
    bars = [Bar.from_gauged(g, rec.metadata[f"{b.capitalize()} Bar Strain Gage Location(mm)"] * 1e-3)
            for g, b in zip(gauges, ("incident", "transmitted"))]
    specimen = SpecimenGeometry(length=rec.metadata["Initial Sample Length(mm)"] * 1e-3,
                                diameter=rec.metadata["Initial Sample Diameter(mm)"] * 1e-3)
    return rec, GaugeSignals.from_recording(rec, *gauges), bars[0], bars[1], specimen
