"""plot_sweep: every metric against every grid key (issue 20, item 13), from a fresh sweep and from a sweep.nc
written before grid values were stored as numbers."""

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
import xarray as xr
from matplotlib.figure import Figure

import rodimpact as ri
from rodimpact.plotting import plot_sweep

C = ri.STEEL.wave_speed
DT = 0.002 / C
Z = ri.STEEL.impedance(np.pi * 0.02**2)


def bars(velocity, end):
    return dict(rods=[ri.Rod([ri.Cylinder(0.1, 0.04)]), ri.Rod([ri.Cylinder(0.5, 0.04)])],
                velocities=[velocity, 0.0], duration=0.2e-3, dt=DT, right=end)


@pytest.fixture(scope="module")
def ds():
    return ri.sweep(bars, {"velocity": [3.0, 4.0, 5.0], "end": ["nonreflecting", "fixed"]}, workers=1)


def panels(fig):
    """The Axes that carry curves, by (y label, x label)."""
    return {(ax.get_ylabel(), ax.get_xlabel()): ax for ax in fig.axes if ax.lines}


def test_one_panel_per_metric_and_key(ds):
    fig = plot_sweep(ds)
    assert isinstance(fig, Figure)
    p = panels(fig)
    assert len(p) == 4 * 2
    ax = p[("peak contact force [kN]", "velocity")]
    # against the numeric key: one curve per end, at the velocities, -Z v / 2 for the non-reflecting end
    curves = {line.get_label(): line for line in ax.lines}
    assert set(curves) == {"nonreflecting", "fixed"}
    np.testing.assert_array_equal(curves["nonreflecting"].get_xdata(), [3.0, 4.0, 5.0])
    np.testing.assert_allclose(curves["nonreflecting"].get_ydata(), -Z * np.array([3.0, 4.0, 5.0]) / 2 / 1e3,
                               rtol=1e-12)
    # against the text key: the names as tick labels, one curve per velocity
    ax = p[("contact time [ms]", "end")]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["nonreflecting", "fixed"]
    assert len(ax.lines) == 3
    assert "3 runs" not in fig.get_suptitle() and "6 runs" in fig.get_suptitle()


def test_legends_sit_outside_the_data(ds):
    fig = plot_sweep(ds)
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert legends
    for legend in legends:
        assert not legend.axes.lines          # on a panel of its own, covering no curve


def test_a_sweep_nc_with_text_coordinates_still_plots(ds, tmp_path):
    """sweep.nc files written before stored the grid values as text, e.g. "4 m/s"."""
    old = ds.assign_coords(velocity=["3 m/s", "4 m/s", "5 m/s"])
    old.to_netcdf(tmp_path / "sweep.nc")
    with xr.open_dataset(tmp_path / "sweep.nc") as loaded:
        assert loaded["velocity"].dtype.kind in "USO"
        fig = plot_sweep(loaded)
    ax = panels(fig)[("peak contact force [kN]", "velocity [m/s]")]
    np.testing.assert_array_equal(ax.lines[0].get_xdata(), [3.0, 4.0, 5.0])


def test_choices_and_bad_arguments(ds):
    fig = plot_sweep(ds, metrics=["contact_time"], keys="velocity")
    assert list(panels(fig)) == [("contact time [ms]", "velocity")]     # plain numbers: no unit known
    with pytest.raises(ValueError, match="metrics: 'peak' is not in the sweep; available: peak_contact_force"):
        plot_sweep(ds, metrics=["peak"])
    with pytest.raises(TypeError, match="ds: must be the xarray.Dataset of rodimpact.sweep"):
        plot_sweep({"a": 1})
    with pytest.raises(ValueError, match="axes: need 8 Axes"):
        plot_sweep(ds, axes=[Figure().subplots()])
