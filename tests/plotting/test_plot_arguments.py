"""Bad arguments to the plotting functions get a clear error naming the argument (never a ZeroDivisionError,
IndexError or AttributeError from inside matplotlib), and nothing is written when they are refused."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.output_folders import write_simulation
from rodimpact.plotting import (animate_force, plot_energy, plot_energy_comparison, plot_forces, plot_profile,
                                plot_snapshots, plot_strain, plot_xt, save_plots)

NOT_A_RESULT = r"result: must be a SimulationResult \(from rodimpact.simulate or rodimpact.io.load\), got NoneType"


@pytest.fixture(scope="module")
def result():
    """0.1 ms, snapshots every 10 steps of 1 us: recorded at 0, 10, ..., 100 us."""
    return ri.simulate([ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(0.5, 0.04)])], [1.0, 0.0], duration=1e-4,
                       dt=1e-6, outputs=ri.Outputs(probes=[ri.Probe("SG", 1, 0.1)], snapshot_every=10))


@pytest.mark.parametrize("kwargs, error, match", [
    ({"fps": 0}, ValueError, "fps: must lie in"),
    ({"fps": -5}, ValueError, "fps: must lie in"),
    ({"fps": float("nan")}, ValueError, "fps: must be finite"),
    ({"fps": 1000}, ValueError, "fps: must lie in"),
    ({"max_frames": 0}, ValueError, "max_frames: must be an integer >= 2"),
    ({"max_frames": 1}, ValueError, "max_frames: must be an integer >= 2"),
    ({"max_frames": 10.5}, TypeError, "max_frames: must be an integer"),
])
def test_animation_frame_rate_and_frame_count(result, tmp_path, kwargs, error, match):
    with pytest.raises(error, match=match):
        animate_force(result, tmp_path / "n.gif", **kwargs)
    assert not (tmp_path / "n.gif").exists()


def test_animation_path_must_be_a_file(result, tmp_path):
    with pytest.raises(ValueError, match="path: .* is a folder, not a file"):
        animate_force(result, tmp_path, overwrite=True)
    (tmp_path / "a.txt").write_text("x")
    with pytest.raises(ValueError, match="path: .*a.txt.* is a file, not a folder"):
        animate_force(result, tmp_path / "a.txt" / "n.gif")


def test_animation_with_two_frames(result, tmp_path):
    from PIL import Image

    path = animate_force(result, tmp_path / "n.gif", max_frames=2, fps=0.5)
    with Image.open(path) as im:
        assert im.n_frames == 2


@pytest.mark.parametrize("dpi, error, match", [
    (0, ValueError, "dpi: must be > 0"),
    (-100, ValueError, "dpi: must be > 0"),
    (float("inf"), ValueError, "dpi: must be finite"),
    ("high", TypeError, "dpi: must be a real number"),
    (1e-3, ValueError, "dpi: .* less than one pixel"),
    (1e7, ValueError, "dpi: .* pixels; matplotlib draws fewer than"),
])
def test_save_plots_dpi(result, tmp_path, dpi, error, match):
    with pytest.raises(error, match=match):
        save_plots(result, tmp_path / "pq", which=["forces"], dpi=dpi)
    assert not (tmp_path / "pq").exists()


def test_save_plots_folder_that_is_a_file(result, tmp_path):
    (tmp_path / "afile.txt").write_text("x")
    with pytest.raises(ValueError, match="folder: '.*afile.txt' is a file, not a folder"):
        save_plots(result, tmp_path / "afile.txt")
    with pytest.raises(ValueError, match="folder: '.*afile.txt' .* is a file, not a folder"):
        save_plots(result, tmp_path / "afile.txt" / "sub")
    assert (tmp_path / "afile.txt").read_text() == "x"


def test_save_plots_checks_every_name_before_writing(result, tmp_path):
    with pytest.raises(ValueError, match="plots: unknown plot 'pie'"):
        save_plots(result, tmp_path / "p", ["forces", "pie"])
    assert not (tmp_path / "p").exists()
    written, _ = save_plots(result, tmp_path / "q", "forces")          # a single name, not its letters
    assert [p.name for p in written] == ["forces.png"]


@pytest.mark.parametrize("plot", [plot_forces, plot_strain, plot_energy, plot_snapshots, plot_xt])
def test_plot_functions_need_a_result(plot):
    with pytest.raises(TypeError, match=NOT_A_RESULT):
        plot(None)


def test_file_writers_and_comparison_need_results(result, tmp_path):
    with pytest.raises(TypeError, match=NOT_A_RESULT):
        animate_force(None, tmp_path / "n.gif")
    with pytest.raises(TypeError, match=NOT_A_RESULT):
        save_plots(None, tmp_path / "p")
    assert not (tmp_path / "p").exists()
    with pytest.raises(TypeError, match=r"obj: must be a System or a SimulationResult .* got NoneType"):
        plot_profile(None)
    with pytest.raises(TypeError, match=r"results\[1\]: must be a SimulationResult .* got str"):
        plot_energy_comparison([result, "b"], ["a", "b"])
    with pytest.raises(ValueError, match="results: give at least one result"):
        plot_energy_comparison([], [])
    plot_profile(result.system)                                         # a System is fine


def test_synthesis_plots_need_a_synthesis_result():
    from rodimpact.plotting.synthesis import plot_existence, plot_impedance, plot_shape

    with pytest.raises(TypeError, match="result: must be a SynthesisResult"):
        plot_impedance(None)
    with pytest.raises(TypeError, match="result: must be a SynthesisResult"):
        plot_existence(object())
    with pytest.raises(TypeError, match="shape: must be a StrikerShape or a SynthesisResult"):
        plot_shape(None)


@pytest.mark.parametrize("times, match", [
    ([1.0], r"times: 1 s \(entry 0\) lies outside the recorded snapshots, 0 to 0.0001 s"),
    ([0.5e-4, 2e-4], r"times: 0.0002 s \(entry 1\) lies outside the recorded snapshots"),
    ([-1e-5], r"times: -1e-05 s \(entry 0\) lies outside"),
    ([float("nan")], "times: must be finite, entry 0 is nan"),
    ([[1e-5, 2e-5]], "times: must be a 1-d sequence"),
])
def test_snapshot_times_outside_the_recorded_range(result, times, match):
    with pytest.raises(ValueError, match=match):
        plot_snapshots(result, times)


def test_snapshot_times_within_a_step_of_the_range_are_fine(result):
    s = result.snapshots
    fig = plot_snapshots(result, [-0.5e-6, 1e-4 + 0.9e-6, 4.2e-5])
    titles = [ax.get_title(loc="left") for ax in fig.axes[::2]]
    assert titles == [f"t = {s.time[k] * 1e3:.4g} ms" for k in (0, 10, 4)]
    assert len(plot_snapshots(result, 5e-5).axes) == 2                   # one time as a number


def test_saving_snapshot_plots_at_unrecorded_times_is_refused(result, tmp_path):
    with pytest.raises(ValueError, match=r"snapshot_times: 5 s \(entry 0\) lies outside the recorded snapshots"):
        save_plots(result, tmp_path / "p", ["forces", "snapshots"], snapshot_times=[5.0])
    assert not (tmp_path / "p").exists()
    with pytest.raises(ValueError, match="snapshot_times: 5 s"):
        write_simulation(result, tmp_path / "out", plots=["snapshots"], snapshot_times=[5.0])
    assert not (tmp_path / "out").exists()
    write_simulation(result, tmp_path / "ok", plots=["snapshots"], snapshot_times=[2e-5, 8e-5])
    assert (tmp_path / "ok" / "plots" / "snapshots.png").exists()


def test_other_plot_arguments(result):
    with pytest.raises(ValueError, match="limit: must be > 0"):
        plot_xt(result, limit=0.0)
    with pytest.raises(ValueError, match="cmap: must be a matplotlib colormap"):
        plot_xt(result, cmap="no-such-map")
    with pytest.raises(ValueError, match="probes: 'SG2' was not recorded; recorded probes: 'SG'"):
        plot_forces(result, probes=["SG2"])
    ax = plot_forces(result, probes="SG")                                # a single name, not its letters
    assert any(ln.get_label().startswith("SG (") for ln in ax.get_lines())
    with pytest.raises(ValueError, match="samples: must be an integer from 2"):
        plot_profile(result, samples=0)
    with pytest.raises(ValueError, match="round_trip_time: must be > 0"):
        plot_energy_comparison([result], ["a"], round_trip_time=-1.0)
    with pytest.raises(ValueError, match=r"axes: need 4 Axes \(2 row\(s\) of 2"):
        plot_snapshots(result, [2e-5, 8e-5], axes=np.empty(2, dtype=object))
    with pytest.raises(TypeError, match="ax: must be a matplotlib Axes"):
        plot_energy(result, ax="left")
