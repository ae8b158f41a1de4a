"""Probe legends name the lattice node that was read, in readable units (issue 20, item 11: a legend showed the
requested 819 mm instead of the node read at 822 mm, and another read "x = 1.99e+04 mm")."""

import matplotlib

matplotlib.use("Agg")

import pytest

import rodimpact as ri
from rodimpact.plotting import plot_forces, plot_strain
from rodimpact.plotting._common import format_length

C = ri.STEEL.wave_speed


@pytest.fixture(scope="module")
def result():
    # elements of exactly 10 mm: the nodes of the bar lie at 0, 10, 20, ... mm from its left end
    dt = 0.01 / C
    rods = [ri.Rod([ri.Cylinder(0.2, 0.02)], name="striker"), ri.Rod([ri.Cylinder(20.0, 0.02)], name="bar")]
    return ri.simulate(rods, [5.0, 0.0], steps=20, dt=dt,
                       outputs=ri.Outputs(probes=[ri.Probe("SG1", 1, 0.819), ri.Probe("SG2", 1, 19.9)]))


@pytest.mark.parametrize("plot", [plot_forces, plot_strain])
def test_probe_legend_shows_the_node_read_in_readable_units(result, plot):
    labels = plot(result).get_legend_handles_labels()[1]
    assert "SG1 (bar, x = 820 mm)" in labels          # requested 819 mm; the nearest node is at 820 mm
    assert "SG2 (bar, x = 19.9 m)" in labels          # not "1.99e+04 mm"


@pytest.mark.parametrize("x, text", [(0.003204, "3.204 mm"), (0.8221, "822.1 mm"), (0.999, "999 mm"),
                                     (1.0, "1 m"), (2.5, "2.5 m"), (19.9, "19.9 m"), (12345.0, "12345 m"),
                                     (0.0, "0 mm")])
def test_format_length_uses_mm_below_one_metre_and_m_above(x, text):
    assert format_length(x) == text
