"""Design force plots carry a title that says what is drawn and how good the design is (issue 20, item 14)."""

import numpy as np

import rodimpact as ri
from rodimpact.plotting.design import plot_design_force, plot_incident_wave


def test_match_force_plot_has_a_title_with_the_misfit():
    bar = ri.Rod.from_impedance([1.27e4] * 4, 2e-6)
    d = ri.design(-np.linspace(10e3, 30e3, 4), ri.System.struck(bar, far_end="nonreflecting"), 12.0, dt=2e-6,
                  limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                  search=ri.SearchOptions(max_iterations=2, starts=1))
    title = plot_design_force(d).get_title()
    assert "contact force" in title and "target" in title and f"{d.misfit:.3g}" in title


def test_efficiency_force_plots_have_titles_with_the_efficiency():
    rod = ri.Rod.from_impedance([60e3] * 6, 2e-6)
    k = 60e3 / (2 * 3 * 2e-6)
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=ri.BitRockEnd(k)), 10.0, n=3, dt=2e-6,
                  limits=ri.StrikerLimits(impedance_bounds=(2e4, 2e5)),
                  search=ri.SearchOptions(max_iterations=1, starts=1))
    for ax in (plot_design_force(d), plot_incident_wave(d, k, 60e3)):
        title = ax.get_title()
        assert "incident wave" in title.lower() and f"{d.efficiency:.4g}" in title


def test_the_target_is_drawn_as_window_steps_not_dots():
    """Issue 20, item 14: the target holds its value over each window of 2 dt; it was drawn as a dot per window."""
    bar = ri.Rod.from_impedance([1.27e4] * 4, 2e-6)
    windows = -np.linspace(10e3, 30e3, 4)
    d = ri.design(windows, ri.System.struck(bar, far_end="nonreflecting"), 12.0, dt=2e-6,
                  limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                  search=ri.SearchOptions(max_iterations=2, starts=1))
    ax = plot_design_force(d)
    (target,) = [line for line in ax.get_lines() if line.get_label().startswith("target")]
    assert target.get_drawstyle() == "steps-post" and target.get_marker() in ("None", "", None)
    t, f = target.get_data()
    np.testing.assert_allclose(t, 2e-6 * 1e3 * np.arange(9))       # both steps of every window and the end, ms
    np.testing.assert_allclose(f, np.append(np.repeat(windows, 2), windows[-1]) / 1e3)
