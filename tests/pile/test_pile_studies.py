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


def test_batched_blows_equal_blows_run_one_by_one():
    """drive_blow_batch (one lattice for all soils, the driver of the bearing graph and drivability) against
    drive_blow per soil, with a gauge: every history, the envelopes and the set equal to 1e-12."""
    from rodimpact.pile import drive_blow
    from rodimpact.pile.blow import drive_blow_batch

    soils = [CapacitySoil(c, 0.5, DYN, distribution="triangular").resistance(d)
             for c, d in ((0.3e6, 12.0), (0.9e6, 12.0), (2e6, 12.0), (0.9e6, 5.0))]   # the last: other soil nodes
    batched = list(drive_blow_batch(PILE, DRIVING, soils, gauges={"mid": 7.5}))
    assert len(batched) == 4
    for soil, b in zip(soils, batched):
        ref = drive_blow(PILE, DRIVING, soil, gauges={"mid": 7.5})
        assert b.soil is soil
        assert b.permanent_set == pytest.approx(ref.permanent_set, rel=1e-12, abs=1e-15)
        for got, want in ((b.head.force, ref.head.force), (b.gauges["mid"].velocity, ref.gauges["mid"].velocity),
                          (b.enthru, ref.enthru), (b.envelope.compression, ref.envelope.compression),
                          (b.envelope.tension, ref.envelope.tension), (b.result.snapshots.force,
                                                                       ref.result.snapshots.force)):
            assert np.allclose(got, want, rtol=1e-12, atol=1e-12 * np.abs(want).max())
        assert np.array_equal(b.envelope.compression_time, ref.envelope.compression_time)
        assert b.result.soil.toe_set == ref.result.soil.toe_set


def test_bearing_graph_equals_its_blows_one_by_one():
    """The bearing graph (batched) gives the numbers of drive_blow for each capacity's soil."""
    from rodimpact.pile import drive_blow
    from rodimpact.pile.studies import pile_edges

    soil = CapacitySoil(1e6, 0.5, DYN)
    caps = [0.4e6, 1.2e6]
    graph = bearing_graph(PILE, DRIVING, soil, caps, 12.0, progress=False)
    for i, c in enumerate(caps):
        b = drive_blow(PILE, DRIVING, CapacitySoil(c, 0.5, DYN).resistance(12.0, pile_edges(PILE, 12.0)))
        assert graph.permanent_set[i] == pytest.approx(b.permanent_set, rel=1e-12)
        assert graph.max_compression[i] == pytest.approx(b.envelope.max_compression[0], rel=1e-12)
        assert graph.max_tension[i] == pytest.approx(b.envelope.max_tension[0], rel=1e-12)
        assert graph.tension_depth[i] == b.envelope.max_tension[1]
        assert graph.emx[i] == pytest.approx(b.emx, rel=1e-12)
