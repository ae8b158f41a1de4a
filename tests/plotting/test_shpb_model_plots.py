"""Plots of a Kolsky-bar prediction (rodimpact.plotting.shpb_model): the conventions of rodimpact.plotting (take ax=,
return it, a new pyplot-free figure otherwise, labels `quantity [unit]`) and what they draw: the gauge signals moved
to the specimen faces, the stress-strain curves and the strain rate with its plateau mean."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import rodimpact as ri
from rodimpact.plotting import plot_predicted_signals, plot_predicted_strain_rate, plot_predicted_stress_strain
from rodimpact.shpb import Gauge, KolskyBar
from rodimpact.shpb.plateau import rate_plateau

PLOTS = (plot_predicted_signals, plot_predicted_stress_strain, plot_predicted_strain_rate)


@pytest.fixture(scope="module")
def prediction():
    def bar(length: float, name: str) -> ri.Rod:
        return ri.Rod([ri.Cylinder(length, 9.47e-3)], ri.TITANIUM_TI6AL4V, name)

    specimen = ri.Specimen(ri.JohnsonCook(117e9, 90e6, 292e6, 0.31, 0.025), 6.34e-3, 3.204e-3)
    kb = KolskyBar(bar(0.6, "incident"), bar(0.6, "transmitted"), specimen, Gauge(0.2), Gauge(0.2),
                   striker=bar(0.1, "striker"))
    return kb.predict(15.0)


@pytest.mark.parametrize("plot", PLOTS, ids=lambda f: f.__name__)
def test_the_plots_take_and_return_an_axes_with_labels_and_units(plot, prediction):
    ax = Figure().subplots()
    assert plot(prediction, ax=ax) is ax
    fresh = plot(prediction)
    assert isinstance(fresh, Axes) and fresh is not ax and isinstance(fresh.figure, Figure)
    for label in (ax.get_xlabel(), ax.get_ylabel()):
        assert label.split(" [")[0] and "]" in label, label
    assert ax.get_title()
    with pytest.raises(TypeError, match=r"^prediction: must be a KolskyPrediction"):
        plot(prediction.result)


def test_the_signals_are_drawn_at_the_specimen_faces(prediction):
    ax = plot_predicted_signals(prediction)
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    steps = int(round(prediction.face_delays[0] / prediction.result.dt))
    t, y = lines["incident"].get_data()
    assert np.array_equal(t, prediction.time * 1e6)
    assert np.array_equal(y[steps:], prediction.incident[:-steps] * 1e6) and np.isnan(y[:steps]).all()
    front = lines["incident + reflected"].get_ydata()
    transmitted = lines["transmitted"].get_ydata()
    loaded = np.abs(np.nan_to_num(transmitted)) > 0.2 * np.abs(np.nan_to_num(transmitted)).max()
    # in equilibrium the front face's strain is the back face's (equal bars: the 1- and 2-wave forces agree)
    assert np.abs(front[loaded] - transmitted[loaded]).max() < 0.1 * np.abs(transmitted[loaded]).max()
    lo, hi = ax.get_xlim()
    assert lo > 0.0 and hi < prediction.time[-1] * 1e6                # the loading, not the quiet record


def test_the_strain_rate_shows_the_plateau_mean(prediction):
    ax = plot_predicted_strain_rate(prediction)
    plateau = rate_plateau(prediction.time, prediction.force, prediction.strain_rate)
    (segment,) = ax.collections[0].get_segments()
    np.testing.assert_allclose(segment, [[plateau.start * 1e6, plateau.mean], [plateau.end * 1e6, plateau.mean]])
    assert ax.collections[0].get_label().startswith(f"plateau mean {plateau.mean:.4g} 1/s")


def test_the_stress_strain_curves_are_engineering_and_true(prediction):
    ax = plot_predicted_stress_strain(prediction)
    eng, true = ax.get_lines()
    assert np.array_equal(eng.get_xdata(), prediction.strain) and np.array_equal(eng.get_ydata(),
                                                                                prediction.stress / 1e6)
    assert np.array_equal(true.get_xdata(), prediction.true_strain)
    assert ax.get_xlabel() == "specimen strain [-] (compression > 0)"
