"""Plots draw the result's own numbers (checked on the artists' data), write files headlessly, and say clearly
when something cannot be drawn."""

import math
import subprocess
import sys

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import plotting
from rodimpact.plotting import (animate_force, plot_energy, plot_energy_comparison, plot_forces, plot_profile,
                                plot_snapshots, plot_xt, save_plots)

C = ri.STEEL.wave_speed


@pytest.fixture(scope="module")
def result():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04), ri.Cylinder(0.2, 0.05)], name="striker"),
            ri.Rod([ri.Cylinder(1.0, 0.05)], name="bar")]
    return ri.simulate(ri.System(rods, [5.0, 0.0], junctions=[ri.Contact(0.01)]), duration=0.8e-3, dt=0.4 / C / 80,
                       outputs=ri.Outputs(probes=[ri.Probe("SG1", 1, 0.1)], snapshot_times=[0.1e-3, 0.3e-3],
                                          snapshot_every=20))


def test_forces_plot_shows_contact_and_probe_forces_in_kN(result):
    ax = plot_forces(result)
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    contact = lines["contact striker | bar"]
    np.testing.assert_array_equal(contact.get_xdata(), result.time * 1e3)
    np.testing.assert_array_equal(contact.get_ydata(), result.contact_force / 1e3)
    assert contact.get_drawstyle() == "steps-post"           # node values hold during each step
    probe = lines["SG1 (bar, x = 100 mm)"]
    np.testing.assert_array_equal(probe.get_ydata(), result.probe("SG1").force / 1e3)
    assert ax.get_xlabel() == "time [ms]"


def test_profile_plot_against_hand_impedances(result):
    fig = plot_profile(result)
    ax_z, ax_d = fig.axes
    striker, bar = ax_z.get_lines()[:2]
    z40 = 7840 * C * math.pi / 4 * 0.04**2 / 1e3
    z50 = 7840 * C * math.pi / 4 * 0.05**2 / 1e3
    x, y = striker.get_xdata(), striker.get_ydata()
    assert x[0] == pytest.approx(-0.4) and x[-1] == pytest.approx(0.0)
    np.testing.assert_allclose(y[x < -0.21], z40, rtol=1e-12)
    np.testing.assert_allclose(y[x > -0.19], z50, rtol=1e-12)
    assert bar.get_xdata()[0] == pytest.approx(0.01)          # the initial gap
    d = ax_d.get_lines()[0].get_ydata()
    assert set(np.round(d, 9)) == {40.0, 50.0}
    assert any(getattr(p, "get_label", lambda: "")() == "lattice (equal travel time)" for p in ax_z.patches)


def test_snapshot_plot_has_one_row_per_requested_time(result):
    fig = plot_snapshots(result, [0.1e-3, 0.3e-3])
    axes = fig.axes
    assert len(axes) == 4
    s = result.snapshots
    k = int(np.argmin(np.abs(s.time - 0.3e-3)))
    assert axes[2].get_title(loc="left") == f"t = {s.time[k] * 1e3:.4g} ms"
    u_bar = axes[2].get_lines()[1]
    nodes = s.node_rod == 1
    np.testing.assert_array_equal(u_bar.get_xdata(), s.node_x[nodes])
    np.testing.assert_array_equal(u_bar.get_ydata(), s.displacement[nodes, k] * 1e3)
    faces = [ln for ln in axes[3].get_lines() if ln.get_linestyle() == "--"]
    assert [ln.get_xdata()[0] for ln in faces] == [pytest.approx(0.01)]


def test_xt_diagram_colours_are_the_recorded_forces(result):
    mesh = plot_xt(result).collections[0]
    s = result.snapshots
    values = np.ma.getdata(mesh.get_array()).reshape(s.time.size, -1)
    # the gap between the rods is a masked column; the others are the element forces in kN
    mask = np.ma.getmaskarray(mesh.get_array()).reshape(s.time.size, -1)
    lat = result.lattice
    gap_col = lat.rod_start[1]
    assert mask[:, gap_col].all() and not mask[:, :gap_col].any() and not mask[:, gap_col + 1:].any()
    order = np.argsort(s.time)
    np.testing.assert_array_equal(values[:, :gap_col], s.force[:gap_col][:, order].T / 1e3)
    np.testing.assert_array_equal(values[:, gap_col + 1:], s.force[gap_col:][:, order].T / 1e3)
    lo, hi = mesh.get_clim()
    assert lo == -hi == pytest.approx(-np.max(np.abs(s.force)) / 1e3)


def test_energy_plots(result):
    total = [ln for ln in plot_energy(result).get_lines() if ln.get_label().startswith("total E_tot")][0]
    np.testing.assert_array_equal(total.get_ydata(), result.energy.total)
    ax = plot_energy_comparison([result, result], ["a", "b"], round_trip_time=2e-4)
    np.testing.assert_array_equal(ax.get_lines()[0].get_xdata(), result.energy.time / 2e-4)
    with pytest.raises(ValueError, match="labels: need one per result"):
        plot_energy_comparison([result], ["a", "b"])


def test_animation_writes_a_gif_with_one_frame_per_snapshot(result, tmp_path):
    from PIL import Image

    path = animate_force(result, tmp_path / "n.gif", max_frames=10)
    with Image.open(path) as im:
        assert im.n_frames == 10
    with pytest.raises(FileExistsError, match="n.gif: exists"):
        animate_force(result, path, max_frames=10)


def test_save_plots_writes_files_and_notes_what_it_skipped(result, tmp_path, monkeypatch):
    written, notes = save_plots(result, tmp_path, ["forces", "profile", "snapshots", "xt", "energy"])
    assert sorted(p.name for p in written) == ["energy.png", "forces.png", "profile.png", "snapshots.png", "xt.png"]
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in written) and notes == []
    monkeypatch.setattr(plotting.animation, "pillow_available", lambda: False)
    written, notes = save_plots(result, tmp_path / "b", ["animation"])
    assert written == [] and "needs pillow" in notes[0]
    bare = ri.simulate([ri.Rod([ri.Cylinder(0.2, 0.04)])], [1.0], steps=20, dt=1e-6)
    written, notes = save_plots(bare, tmp_path / "c", ["snapshots", "xt"])
    assert written == [] and len(notes) == 2 and "no field snapshots" in notes[0]
    with pytest.raises(ValueError, match="unknown plot 'pie'"):
        save_plots(result, tmp_path, ["pie"])
    before = (tmp_path / "forces.png").read_bytes()
    with pytest.raises(FileExistsError, match="forces.png: exists"):
        save_plots(result, tmp_path, ["forces"])
    assert (tmp_path / "forces.png").read_bytes() == before
    written, _ = save_plots(result, tmp_path, ["forces"], overwrite=True)
    assert written == [tmp_path / "forces.png"]


def test_plots_do_not_need_pyplot_or_a_display(tmp_path):
    code = f"""
import sys, rodimpact as ri
from rodimpact.plotting import save_plots
r = ri.simulate([ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(0.5, 0.04)])], [1.0, 0.0], steps=200,
                dt=1e-6, outputs=ri.Outputs(snapshot_every=10))
save_plots(r, {str(tmp_path)!r}, ["forces", "profile", "snapshots", "xt", "energy"])
assert "matplotlib.pyplot" not in sys.modules, "pyplot was imported"
"""
    env = {"PATH": "/usr/bin:/bin", "MPLBACKEND": "TkAgg"}           # no DISPLAY; an interactive backend requested
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert len(list(tmp_path.glob("*.png"))) == 5
