"""Smoke test of the pile-driving report plots: each draws its data on the given Axes with labelled axes, and
refuses objects of the wrong kind."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.pile import DrivingSystem, drive_blow
from rodimpact.pile.studies import BlowTable
from rodimpact.plotting import new_axes
from rodimpact.plotting.pile import plot_bearing_graph, plot_drivability, plot_head_force, plot_stress_envelope
from rodimpact.rods.conditions import NonReflectingEnd


@pytest.fixture(scope="module")
def blow():
    ram, pile = ri.Rod([ri.Cylinder(2.0, 0.3)]), ri.Rod([ri.Cylinder(20.0, 0.3)])
    return drive_blow(pile, DrivingSystem(3.0, ram=ram), toe=NonReflectingEnd())


def _table(name: str, unit: str) -> BlowTable:
    x = np.array([1.0, 2.0, 3.0])
    return BlowTable(name, unit, x, np.array([0.01, 0.004, 0.0]), np.array([25.0, 62.5, np.inf]),
                     np.array([1e8, 1.2e8, 1.3e8]), np.zeros(3), np.array([1e6, 2e6, 0.0]), np.zeros(3),
                     np.array([4e4, 4.1e4, 4.2e4]), x)


def test_head_force_shows_force_and_z_v(blow):
    _, ax = new_axes(None)
    plot_head_force(blow, ax=ax)
    lines = ax.get_lines()
    assert len(lines) == 2 and "[kN]" in ax.get_ylabel() and ax.get_xlabel() == "time [ms]"
    assert np.allclose(lines[0].get_ydata(), -blow.head.force * 1e-3)
    assert np.allclose(lines[1].get_ydata(), blow.head_impedance * blow.head.velocity * 1e-3)


def test_stress_envelope_depth_downwards(blow):
    ax = plot_stress_envelope(blow)
    assert ax.yaxis_inverted() and len(ax.get_lines()) == 2


def test_bearing_graph_leaves_out_refusal():
    ax = plot_bearing_graph(_table("capacity", "N"))
    x = ax.get_lines()[0].get_xdata()
    assert np.isnan(x[2]) and x[1] == 62.5


def test_drivability_depth_downwards():
    ax = plot_drivability(_table("depth", "m"))
    assert ax.yaxis_inverted() and ax.get_ylabel() == "depth [m]"


def test_wrong_objects_are_refused():
    with pytest.raises(TypeError, match="must be a Blow of rodimpact.pile, got BlowTable"):
        plot_head_force(_table("depth", "m"))
