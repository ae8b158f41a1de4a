"""Plots a report can take as they are (issue 20, item 14): titles on the synthesis plots, the target and the
achieved force drawn as steps (not pairs of dots), an existence plot in plain words, a 3 mm specimen visible on a
2.5 m profile, and the profile legend beside the data instead of on it."""

import math
import re
import warnings

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.patches import StepPatch

import rodimpact as ri
from rodimpact.plotting import plot_existence, plot_force, plot_impedance, plot_profile, plot_shape

V = 5.0
BAR = ri.Rod([ri.Cylinder(1.0, 0.03)])


@pytest.fixture(scope="module")
def synthesis():
    x = -5e4 * np.exp(-np.arange(12) / 6.0)
    res = ri.synthesize(x, BAR, V, dt=1e-6)
    return res, res.verify()


@pytest.fixture(scope="module")
def infeasible():
    with pytest.warns(UserWarning):
        return ri.synthesize(np.array([-1e4, -1e6, -1e4]), BAR, V, dt=1e-6)


def test_synthesis_plots_have_titles(synthesis):
    res, ver = synthesis
    assert plot_force(res, ver).get_title() == "Impact force: target and achieved"
    assert plot_force(res).get_title() == "Impact force: target"
    assert plot_impedance(res).get_title() == "Impedance of the synthesized striker (12 elements)"
    assert plot_shape(res).get_title().startswith("Striker shape: length")


def test_target_and_achieved_force_are_steps_not_dots(synthesis):
    res, ver = synthesis
    ax = plot_force(res, ver)
    dotted = [ln for ln in ax.get_lines() if ln.get_linestyle() in ("None", "none", "") and ln.get_marker()]
    assert dotted == []
    steps = {p.get_label(): p for p in ax.patches if isinstance(p, StepPatch)}
    target, achieved = steps["target impact force (per window of 2 dt)"], steps["achieved (direct solver)"]
    values, edges = target.get_data()[:2]
    np.testing.assert_allclose(edges, 2e-3 * np.arange(13))            # windows of 2 dt = 2 us, in ms
    np.testing.assert_allclose(values, res.window_values / 1e3)
    values, edges = achieved.get_data()[:2]
    np.testing.assert_allclose(values, ver.achieved / 1e3)
    np.testing.assert_allclose(edges[:-1], ver.time * 1e3)
    # the achieved force lies on the target: each window's two steps carry the window value
    np.testing.assert_allclose(ver.achieved, np.repeat(res.window_values, 2), rtol=1e-9)


JARGON = re.compile(r"\$|K_q|N_0|Delta|\bq\b|exist(s)? from|reserve")


def test_existence_plot_speaks_plainly(infeasible, synthesis):
    for res in (infeasible, synthesis[0]):
        ax = plot_existence(res)
        texts = [ax.get_title(), ax.get_xlabel(), ax.get_ylabel()] + [t.get_text() for t in ax.get_legend().get_texts()]
        for text in texts:
            assert not JARGON.search(text), text
    ax = plot_existence(infeasible)
    assert "1 of 3 elements" in ax.get_title() and "0.002 ms" in ax.get_title()
    assert ax.get_xlabel() == "striker element, counted from the impact face [-]"


@pytest.fixture(scope="module")
def shpb():
    with warnings.catch_warnings():     # whether a specimen shorter than its diameter warns is not tested here
        warnings.simplefilter("ignore")
        rods = [ri.Rod([ri.Cylinder(0.5, 0.02)], name="striker"),
                ri.Rod([ri.Cylinder(1.0, 0.02)], name="incident"),
                ri.Rod([ri.Cylinder(0.003, 0.01)], name="specimen"),
                ri.Rod([ri.Cylinder(1.0, 0.02)], name="transmitted")]
        return ri.System(rods, [10.0, 0.0, 0.0, 0.0])


def test_a_3_mm_specimen_is_visible_on_a_2_5_m_profile(shpb):
    fig = plot_profile(shpb)
    ax_z, ax_d = fig.axes[:2]
    span = 2.503
    z_specimen = ri.STEEL.impedance(math.pi / 4 * 0.01**2) / 1e3
    wide = [ln for ln in ax_z.get_lines()
            if np.allclose(ln.get_ydata(), z_specimen) and np.ptp(ln.get_xdata()) >= 0.02 * span]
    assert len(wide) == 1
    centre = np.mean(wide[0].get_xdata())
    assert centre == pytest.approx(1.0015, abs=1e-9)          # on the specimen: 1.000 to 1.003 m
    notes = [t.get_text() for t in ax_d.texts]
    assert any(n.startswith("specimen: 3 mm long (drawn") for n in notes), notes


def test_the_profile_legend_covers_no_data(shpb):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    fig = plot_profile(shpb)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    ax_z = fig.axes[0]
    legend_box = ax_z.get_legend().get_window_extent(canvas.get_renderer())
    axes_box = ax_z.get_window_extent(canvas.get_renderer())
    assert legend_box.x0 >= axes_box.x1                     # beside the Axes, not over the curves
    assert legend_box.x1 <= fig.bbox.x1 + 1                 # and still inside the image
