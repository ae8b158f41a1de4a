"""The studies over blows: what each varies, the trends physics demands of it, progress lines and refusals."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.pile import CapacitySoil, DrivingSystem, SoilDynamics, SoilLayer, SoilProfile
from rodimpact.pile.studies import bearing_graph, drivability, inspector_chart
from rodimpact.rods.conditions import Cushion

PILE = ri.Rod([ri.Tube(15.0, 0.324, 0.300)])
DRIVING = DrivingSystem(4.0, ram_mass=2500.0, hammer_cushion=Cushion(1e9, 0.8), helmet_mass=400.0)
DYN = SoilDynamics(2.54e-3, 2.54e-3, 0.164, 0.492)


def test_bearing_graph_more_capacity_more_blows_and_its_capacities(capsys):
    soil = CapacitySoil(1e6, 0.5, DYN)
    graph = bearing_graph(PILE, DRIVING, soil, [0.4e6, 0.8e6, 1.2e6], 12.0, progress=True)
    assert graph.resistance == pytest.approx([0.4e6, 0.8e6, 1.2e6], rel=1e-12)     # the soil each blow met
    assert np.all(np.diff(graph.blows_per_quarter_metre) > 0)
    assert "bearing graph: 100% (3 of 3 blows" in capsys.readouterr().err


def test_inspector_chart_higher_stroke_fewer_blows():
    soil = CapacitySoil(0.8e6, 0.5, DYN).resistance(12.0)
    chart = inspector_chart(PILE, DRIVING, soil, strokes=[0.5, 1.0, 1.5], efficiency=0.8, progress=False)
    assert np.all(np.diff(chart.blows_per_quarter_metre) < 0)
    with pytest.raises(ValueError, match="efficiency: missing"):
        inspector_chart(PILE, DRIVING, soil, strokes=[0.5], progress=False)


def test_drivability_meets_the_profiles_resistance_and_refuses_a_deeper_profile():
    profile = SoilProfile([SoilLayer(6.0, 20e3, 0.0, 2.0), SoilLayer(15.0, 60e3, 4e6)], 1.02, 0.0824, DYN)
    table = drivability(PILE, DRIVING, profile, [4.0, 10.0], progress=False)
    assert table.resistance == pytest.approx([profile.resistance(4.0).total, profile.resistance(10.0).total])
    deep = SoilProfile([SoilLayer(6.0, 20e3), SoilLayer(16.0, 60e3, 4e6)], 1.02, 0.0824, DYN)
    with pytest.raises(ValueError, match=r"profile.layers\[1\].bottom: the profile reaches 16 m, deeper than the "
                                         r"pile \(15 m long\)"):
        drivability(PILE, DRIVING, deep, [4.0], progress=False)
