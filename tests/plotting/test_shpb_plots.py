"""The split-Hopkinson-bar plots follow the plotting conventions: an optional Axes in, the Axes out, every axis
labelled ``quantity [unit]``, bad arguments named; drawn from the LANL copper shot."""

import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from rodimpact.io import hoppybar_bar, read_lanl_raw
from rodimpact.plotting import plot_equilibrium, plot_pulses, plot_strain_rate, plot_stress_strain
from rodimpact.shpb import Bar, GaugeSignals, SpecimenGeometry, reduce_shot

LANL = Path(__file__).resolve().parents[1] / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"
PLOTS = (plot_pulses, plot_stress_strain, plot_strain_rate, plot_equilibrium)


@pytest.fixture(scope="module")
def reduction():
    rec = read_lanl_raw(LANL)
    gauges = [hoppybar_bar(rec.metadata, b, bridge="half-axial", polarity=-1) for b in ("incident", "transmitted")]
    bars = [Bar.from_gauged(g, 0.381) for g in gauges]
    return reduce_shot(GaugeSignals.from_recording(rec, *gauges), *bars,
                       SpecimenGeometry(length=3.204e-3, diameter=6.34e-3))


@pytest.mark.parametrize("plot", PLOTS, ids=lambda p: p.__name__)
def test_axes_in_axes_out_and_labels_with_units(reduction, plot, tmp_path):
    ax = Figure().subplots()
    assert plot(reduction, ax=ax) is ax
    fresh = plot(reduction)
    assert isinstance(fresh, Axes) and isinstance(fresh.figure, Figure) and fresh is not ax
    for label in (fresh.get_xlabel(), fresh.get_ylabel()):
        assert re.fullmatch(r".+ \[[^\]]+\]", label), label
    assert fresh.get_title() and fresh.get_legend() is not None
    fresh.figure.savefig(tmp_path / "plot.png", dpi=60)


def test_what_the_plots_show(reduction):
    ax = plot_stress_strain(reduction, measure="true", analyses=["3-wave"])
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    assert set(lines) == {"3-wave, true", "equilibrium from here"}
    np.testing.assert_array_equal(lines["3-wave, true"].get_ydata(), reduction.three_wave.true_stress / 1e6)
    ax = plot_pulses(reduction)
    assert ax.get_ylabel() == "bar strain [µε]"
    eq = reduction.equilibrium
    ax = plot_equilibrium(reduction)
    assert ax.get_ylim() == (0.0, 3 * eq.review_limit * 100)
    assert any(f"{eq.equilibrium_time * 1e6:.4g} µs" in ln.get_label() for ln in ax.get_lines())


def test_bad_arguments_are_named(reduction):
    with pytest.raises(TypeError, match="reduction: must be a ShpbReduction"):
        plot_pulses(None)
    with pytest.raises(ValueError, match="analyses: choose from 1-wave, 2-wave, 3-wave"):
        plot_stress_strain(reduction, analyses=["4-wave"])
    with pytest.raises(ValueError, match="measure: must be 'engineering', 'true' or 'both'"):
        plot_stress_strain(reduction, measure="log")
    with pytest.raises(TypeError, match="ax: must be a matplotlib Axes"):
        plot_strain_rate(reduction, ax="left")
