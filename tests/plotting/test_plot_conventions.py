"""The plotting conventions (issue 14, item 7): one-Axes functions take and return an Axes, several-Axes functions
return the Figure; every axis label is ``quantity [unit]`` with forces in kN and impedances in kN s/m; the profile
legend lists only what is drawn visibly; the existence plot of an infeasible target shows the elements up to the
failing one; the strain plot is in microstrain; the shape plot exaggerates the radial scale and says so."""

import math
import re

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

import rodimpact as ri
from rodimpact.inverse.shape import StrikerShape
from rodimpact.reference import plot_phase_speed
from rodimpact.plotting import (plot_energy, plot_energy_comparison, plot_forces, plot_profile, plot_snapshots,
                                plot_strain, plot_xt)
from rodimpact.plotting.synthesis import (plot_existence, plot_force, plot_impedance, plot_shape,
                                          plot_synthesis)

C = ri.STEEL.wave_speed
E = ri.STEEL.youngs_modulus
RHO = ri.STEEL.density
BAR_D = 0.03                 # struck bar of the synthesis examples, m
Z_BAR = RHO * C * math.pi / 4 * BAR_D**2
V = 5.0                      # striker velocity, m/s


@pytest.fixture(scope="module")
def result():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04), ri.Cone(0.2, 0.04, 0.05)], name="striker"),
            ri.Rod([ri.Cylinder(1.0, 0.05)], name="bar")]
    return ri.simulate(ri.System(rods, [5.0, 0.0], junctions=[ri.Contact()]), duration=0.6e-3, dt=0.4 / C / 40,
                       outputs=ri.Outputs(probes=[ri.Probe("SG1", 1, 0.3), ri.Probe("SG2", 1, 0.6)], snapshot_every=20))


@pytest.fixture(scope="module")
def infeasible():
    """Window values -10 kN, -1000 kN, -10 kN on a 30 mm bar at 5 m/s: element 1 exists, element 2 does not."""
    with pytest.warns(UserWarning):
        return ri.synthesize(np.array([-1e4, -1e6, -1e4]), ri.Rod([ri.Cylinder(1.0, BAR_D)]), V, dt=1e-6)


@pytest.fixture(scope="module")
def feasible():
    return ri.synthesize(np.array([-5e4, -1e3, -1e3]), ri.Rod([ri.Cylinder(1.0, BAR_D)]), V, dt=1e-6)


def new_ax():
    return Figure().subplots()


def one_axes_plots(result, synthesis):
    return [lambda ax: plot_forces(result, ax=ax), lambda ax: plot_strain(result, ax=ax),
            lambda ax: plot_energy(result, ax=ax), lambda ax: plot_energy_comparison([result], ["a"], ax=ax),
            lambda ax: plot_xt(result, ax=ax), lambda ax: plot_impedance(synthesis, ax=ax),
            lambda ax: plot_force(synthesis, ax=ax), lambda ax: plot_existence(synthesis, ax=ax),
            lambda ax: plot_shape(synthesis, ax=ax), lambda ax: plot_phase_speed(ax=ax)]


def test_one_axes_plots_return_the_given_or_a_new_axes(result, feasible):
    for plot in one_axes_plots(result, feasible):
        ax = new_ax()
        assert plot(ax) is ax
        fresh = plot(None)
        assert isinstance(fresh, Axes) and fresh is not ax and isinstance(fresh.figure, Figure)


def test_several_axes_plots_return_the_figure(result, feasible):
    for fig in (plot_profile(result), plot_snapshots(result, [1e-4, 3e-4]), plot_synthesis(feasible)):
        assert isinstance(fig, Figure)
    fig = Figure()
    axes = fig.subplots(2)
    assert plot_profile(result, axes) is fig


UNIT_LABEL = re.compile(r"^[^\[\]/]+ \[[^\[\]]+\]( \(.*\))?$")     # "quantity [unit]", optionally "(note)"


def all_labels(fig):
    return [label for ax in fig.axes for label in (ax.get_xlabel(), ax.get_ylabel()) if label]


def test_every_axis_label_is_quantity_with_unit_in_brackets(result, feasible, infeasible):
    figs = [plot(None).figure for plot in one_axes_plots(result, feasible)]
    figs += [plot_existence(infeasible).figure, plot_profile(result), plot_snapshots(result, [1e-4]),
             plot_synthesis(feasible), plot_impedance(feasible, x="theta").figure,
             plot_impedance(feasible, x="q").figure]
    labels = [label for fig in figs for label in all_labels(fig)]
    assert len(labels) > 25
    bad = [label for label in labels if not UNIT_LABEL.match(label)]
    assert bad == []
    assert {label for label in labels if "impedance" in label} == {"impedance [kN s/m]", "impedance Z [kN s/m]"}
    forces = [label for label in labels if "force" in label.split("[")[0]]
    assert forces and all("[kN]" in label for label in forces)


def test_synthesis_impedance_is_drawn_in_kN_s_per_m(feasible):
    # element 1 from the first window by hand: X_1 = -v Z_1 Z~ / (Z_1 + Z~)  =>  Z_1 = -X_1 Z~ / (v Z~ + X_1)
    z1 = 5e4 * Z_BAR / (V * Z_BAR - 5e4)
    steps = plot_impedance(feasible).patches[0]
    assert steps.get_data().values[0] == pytest.approx(z1 / 1e3, rel=1e-12)
    np.testing.assert_array_equal(steps.get_data().values, feasible.impedance / 1e3)


def test_profile_legend_shows_the_rods_and_a_visible_lattice_line(result):
    ax_z = plot_profile(result).axes[0]
    legend = ax_z.get_legend()
    assert [t.get_text() for t in legend.get_texts()] == ["striker", "bar", "lattice (equal travel time)"]
    handle = legend.legend_handles[2]
    assert isinstance(handle, Line2D) and handle.get_linestyle() == ":" and handle.get_linewidth() >= 1.0
    lattice = [p for p in ax_z.patches if p.get_label() == "lattice (equal travel time)"][0]
    assert lattice.get_zorder() > max(ln.get_zorder() for ln in ax_z.get_lines()[:2])    # drawn on top
    assert lattice.get_linestyle() == ":" and lattice.get_alpha() in (None, 1.0)
    # the lattice steps are the element impedances of the striker, kN s/m
    lat = result.lattice
    np.testing.assert_array_equal(lattice.get_data().values, lat.impedance[:lat.rod_start[1]] / 1e3)
    # a System has no lattice: no lattice entry
    system_legend = plot_profile(result.system).axes[0].get_legend()
    assert [t.get_text() for t in system_legend.get_texts()] == ["striker", "bar"]


def test_existence_plot_of_an_infeasible_target_shows_the_elements_up_to_the_failing_one(infeasible):
    f = infeasible.failure
    assert infeasible.n_feasible == 1 and f.element == 2
    ax = plot_existence(infeasible)
    reserve, difference = ax.get_lines()[:2]
    # element 1 by hand (thesis eqs. 4.3, 4.7, 4.20): N_0 = -v Z~ / 2, K_1 = 1, Delta N_1 = X_1 - N_0
    n0 = -V * Z_BAR / 2
    np.testing.assert_array_equal(reserve.get_xdata(), [1, 2])
    np.testing.assert_allclose(reserve.get_ydata(), [abs(n0) / 1e3, f.force_reserve / 1e3], rtol=1e-12)
    np.testing.assert_allclose(difference.get_ydata(), [abs(-1e4 - n0) / 1e3, abs(f.force_difference) / 1e3],
                               rtol=1e-12)
    assert reserve.get_marker() == "o"                      # a short curve is visible as points
    assert abs(f.force_difference) >= f.force_reserve       # the failure: |dN| reaches the reserve
    crosses = [ln for ln in ax.get_lines() if ln.get_label() == "element 2: impossible"]
    assert len(crosses) == 1 and list(crosses[0].get_xdata()) == [2, 2]
    shaded = [p for p in ax.patches if p.get_facecolor()[3] > 0]
    assert shaded, "the failing element is shaded"
    assert ax.get_title().startswith("The striker exists for 1 of 3 elements only: target reached for 0.002 ms\n"
                                     "(element 2: the target asks for more force change than is possible)")
    assert ax.get_ylim()[1] >= abs(f.force_difference) / 1e3


def test_existence_plot_of_a_feasible_target_has_no_failure_mark(feasible):
    ax = plot_existence(feasible)
    assert len(ax.get_lines()) == 2 and list(ax.get_lines()[0].get_xdata()) == [1, 2, 3]
    assert ax.get_title().startswith("The striker exists: all 3 elements can be built")


def test_strain_plot_is_the_probe_strain_in_microstrain(result):
    ax = plot_strain(result)
    lines = {ln.get_label(): ln for ln in ax.get_lines() if not ln.get_label().startswith("_")}
    assert set(lines) == {"SG1 (bar, x = 300 mm)", "SG2 (bar, x = 600 mm)"}
    sg1 = lines["SG1 (bar, x = 300 mm)"]
    np.testing.assert_array_equal(sg1.get_xdata(), result.time * 1e3)
    np.testing.assert_array_equal(sg1.get_ydata(), result.probe("SG1").strain * 1e6)
    # independently: N / (E A) of the 50 mm bar, in microstrain
    a = math.pi / 4 * 0.05**2
    np.testing.assert_allclose(sg1.get_ydata(), result.probe("SG1").force / (E * a) * 1e6, rtol=1e-12, atol=1e-9)
    assert ax.get_ylabel() == "strain [µε] (tension > 0)"
    assert min(sg1.get_ydata()) < -100           # the impact is compressive: some hundred microstrain
    only = plot_strain(result, probes="SG2")
    assert [ln.get_label() for ln in only.get_lines() if not ln.get_label().startswith("_")] == \
        ["SG2 (bar, x = 600 mm)"]


def test_strain_plot_needs_probes():
    bare = ri.simulate([ri.Rod([ri.Cylinder(0.2, 0.04)])], [1.0], steps=20, dt=1e-6)
    with pytest.raises(ValueError, match="plot_strain: the result holds no probes"):
        plot_strain(bare)


def test_shape_plot_exaggerates_the_radial_scale_and_says_so():
    # 40 elements of 2 us: a 0.41 m striker (c dt = 10.3 mm each), 20 mm then 22 mm diameter
    area = np.repeat([math.pi / 4 * 0.020**2, math.pi / 4 * 0.022**2], 20)
    shape = StrikerShape(RHO * C * area, 2e-6)
    length = C * 2e-6 * 40
    # largest of 1, 2, 5, 10, ... with 22 mm x scale <= length / 3 (= 138 mm, i.e. scale <= 6.27): 5
    assert 5 <= length / 3 / 0.022 < 10
    ax = plot_shape(shape)
    assert ax.get_aspect() == 5.0
    assert ax.get_ylabel() == "radius [mm] (radial scale x5)"
    outline = ax.patches[0].get_data()
    np.testing.assert_allclose(outline.values, np.repeat([10.0, 11.0], 20), rtol=1e-12)
    np.testing.assert_allclose(outline.edges[-1], length * 1e3, rtol=1e-12)
    true_scale = plot_shape(shape, radial_scale=1)
    assert true_scale.get_aspect() == 1.0 and true_scale.get_ylabel() == "radius [mm]"
    with pytest.raises(ValueError, match="radial_scale: must be > 0"):
        plot_shape(shape, radial_scale=0)


def test_save_plots_writes_the_strain_plot_or_says_why_not(result, tmp_path):
    from rodimpact.plotting import save_plots

    written, notes = save_plots(result, tmp_path / "a", ["strain"])
    assert [p.name for p in written] == ["strain.png"] and notes == []
    bare = ri.simulate([ri.Rod([ri.Cylinder(0.2, 0.04)])], [1.0], steps=20, dt=1e-6)
    written, notes = save_plots(bare, tmp_path / "b", ["strain"])
    assert written == [] and "plot 'strain' skipped: plot_strain: the result holds no probes" in notes[0]
