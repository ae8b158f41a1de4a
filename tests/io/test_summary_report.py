"""summary.json says which lattice node each probe read (and the position it asked for) and carries the lattice
report, as the user guide states; the user documentation names no developer-machine paths or internal documents."""

import json
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import rodimpact as ri
from rodimpact.io.results import format_summary, summarize

ROOT = Path(__file__).parents[2]
C = ri.STEEL.wave_speed
DT = 0.005 / C          # 5 mm elements


@pytest.fixture(scope="module")
def run():
    """A 0.3 m piston on a 1 m bar; gauge SG1 at 112 mm (between the nodes at 110 and 115 mm, nearer 110), SG2 on
    a node (500 mm)."""
    piston = ri.Rod([ri.Cylinder(0.3, 0.04)], name="piston")
    bar = ri.Rod([ri.Cylinder(1.0, 0.05)], name="bar")
    return ri.simulate([piston, bar], [5.0, 0.0], steps=300, dt=DT,
                       outputs=ri.Outputs(probes=[ri.Probe("SG1", 1, 0.112), ri.Probe("SG2", "bar", 0.5)],
                                          snapshot_every=10))


def test_summary_gives_the_node_each_probe_read(run, tmp_path):
    ri.save(run, tmp_path / "out")
    sg1, sg2 = json.loads((tmp_path / "out" / "summary.json").read_text())["probes"]
    assert sg1["position_m"] == 0.112 and sg2["position_m"] == 0.5                 # as requested
    assert sg1["node_position_m"] == pytest.approx(0.110, abs=1e-12)               # 22 elements of 5 mm
    assert sg2["node_position_m"] == pytest.approx(0.5, abs=1e-12)
    # node index into result.nc: the piston's 60 elements have 61 nodes, then the bar's nodes from its left end
    assert sg1["node_index"] == 61 + 22 and sg2["node_index"] == 61 + 100
    ds = xr.load_dataset(tmp_path / "out" / "result.nc")
    for p, name in ((sg1, "SG1"), (sg2, "SG2")):
        bar_start = run.system.rod_offsets()[1]            # global x of the bar's left end (0: the contact face)
        assert float(ds["node_x"][p["node_index"]]) == pytest.approx(bar_start + p["node_position_m"], abs=1e-12)
        # the probe's displacement is that node's displacement in the field snapshots (at the snapshot steps)
        steps = np.round(ds["snapshot_time"].values / DT).astype(int)
        kept = steps < run.n_steps                          # a probe history holds the step starts 0 .. n - 1
        assert kept.sum() == 30
        field = ds["displacement_field"].values
        node = field[p["node_index"]][kept]
        np.testing.assert_allclose(run.probe(name).displacement[steps[kept]], node, rtol=0,
                                   atol=1e-12 * np.abs(field).max())               # to rounding
        assert np.abs(field[p["node_index"] + 1][kept] - node).max() > 1e-3 * np.abs(field).max()   # a neighbour


def test_the_printed_summary_says_where_a_probe_was_moved(run):
    text = format_summary(summarize(run))
    assert "probe SG1: force" in text and "(read at the node 110 mm from the rod's left end; requested 112 mm)" in text
    sg2 = next(line for line in text.splitlines() if line.startswith("probe SG2"))
    assert "requested" not in sg2


def test_summary_json_holds_the_lattice_report_the_user_guide_promises(run, tmp_path):
    ri.save(run, tmp_path / "out")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["lattice_report"] == run.diagnostics["lattice_report"]
    assert "rod 0: 60 elements" in summary["lattice_report"]
    guide = (ROOT / "docs" / "user-guide.md").read_text(encoding="utf-8")
    paragraph = " ".join(guide[guide.index("**Time step.**"):].split("\n\n")[0].split())
    assert "`lattice_report` in `summary.json`" in paragraph
    for key in re.findall(r"`(position_m|node_position_m|node_index)`", paragraph):
        assert key in summary["probes"][0]
    assert len(set(re.findall(r"`(position_m|node_position_m|node_index)`", paragraph))) == 3


def test_inverse_docs_name_no_developer_machine_path_or_internal_document():
    text = (ROOT / "docs" / "inverse.md").read_text(encoding="utf-8")
    assert "/work/" not in text and "shared/thesis" not in text
    assert "architecture.md" not in text and "architecture document" not in text
    assert "J. Burgert, *On direct and inverse problems related to\nlongitudinal impact of non-uniform elastic rods*" \
        in text


# ---- issue 20, item 10: the time of a flat peak is where the plateau begins --------------------------------------
@pytest.fixture(scope="module")
def plateau():
    """A 0.3 m striker on a 1 m bar of the same diameter (non-reflecting far end): the contact force is the flat
    -Z v / 2 from the first step for 2 x 0.3 m / c; the front reaches the gauge SG at 0.5 m (a node) after 100
    elements of 5 mm and holds the same plateau there."""
    rods = [ri.Rod([ri.Cylinder(0.3, 0.03)]), ri.Rod([ri.Cylinder(1.0, 0.03)])]
    return ri.simulate(ri.System(rods, [6.0, 0.0], right="nonreflecting"), steps=300, dt=DT,
                       outputs=ri.Outputs(probes=[ri.Probe("SG", 1, 0.5)]))


def test_plateau_peak_is_reported_where_the_plateau_begins(plateau):
    z = ri.STEEL.density * C * np.pi / 4 * 0.03**2
    s = summarize(plateau)
    (j,) = s["junctions"]
    assert j["peak_compressive_force_N"] == pytest.approx(-z * 6.0 / 2, rel=1e-9)
    assert j["peak_time_s"] == 0.0                    # the contact starts on the plateau
    assert plateau.peak_time(0) == 0.0
    assert "kN at 0 ms" in format_summary(s)
    (sg,) = s["probes"]
    assert sg["time_of_min_s"] == pytest.approx(100 * DT, abs=1e-3 * DT)


def test_plateau_peak_time_with_a_recording_stride(plateau):
    rods = [ri.Rod([ri.Cylinder(0.3, 0.03)]), ri.Rod([ri.Cylinder(1.0, 0.03)])]
    res = ri.simulate(ri.System(rods, [6.0, 0.0], right="nonreflecting"), steps=300, dt=DT,
                      outputs=ri.Outputs(record_every=7))
    assert summarize(res)["junctions"][0]["peak_time_s"] == 0.0


def test_a_peak_that_is_not_flat_keeps_its_own_time():
    from rodimpact.direct.result import first_within_rounding

    assert first_within_rounding(np.array([0.0, -1.0, -2.0, -3.0, -2.5]), -3.0) == 3
    assert first_within_rounding(np.array([0.0, -5.0 + 1e-12, -5.0, -5.0 + 2e-12, -1.0]), -5.0) == 1
    assert first_within_rounding(np.array([0.0, 4.0, 4.0 - 1e-3, 4.0]), 4.0) == 1
