"""Design plots: return the Axes, draw on a given Axes, refuse other objects, show what they promise."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.plotting import plot_convergence, plot_design_force, plot_design_profile, plot_incident_wave
from rodimpact.plotting._common import new_axes


@pytest.fixture(scope="module")
def match():
    bar = ri.Rod.from_impedance([1.27e4] * 4, 2e-6)
    return ri.design(-np.linspace(10e3, 30e3, 4), ri.System.struck(bar, far_end="nonreflecting"), 12.0, dt=2e-6,
                     limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                     search=ri.SearchOptions(max_iterations=2, starts=1))


def test_force_profile_convergence(match):
    ax = plot_design_force(match)
    (target,) = [line for line in ax.get_lines() if line.get_label().startswith("target")]
    assert np.allclose(target.get_ydata()[:-1], match.target / 1e3)     # the target's steps, kN
    _, ax2 = new_axes(None)
    a2 = plot_design_profile(match, ax=ax2)
    assert a2 is ax2
    ax3 = plot_convergence(match)
    assert ax3.get_ylabel() == "misfit [-]"


def test_incident_wave_needs_an_efficiency_design(match):
    with pytest.raises(ValueError, match="incident wave"):
        plot_incident_wave(match, 1e9, 1e4)


def test_wrong_object():
    with pytest.raises(TypeError, match="DesignResult"):
        plot_design_force(object())


def test_incident_wave_beside_the_exponential():
    rod = ri.Rod.from_impedance([60e3] * 6, 2e-6)
    k = 60e3 / (2 * 3 * 2e-6)
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=ri.BitRockEnd(k)), 10.0, n=3, dt=2e-6,
                  limits=ri.StrikerLimits(impedance_bounds=(2e4, 2e5)),
                  search=ri.SearchOptions(max_iterations=1, starts=1))
    ax = plot_incident_wave(d, k, 60e3)
    step, expo = ax.get_lines()[:2]
    t = expo.get_xdata() / 1e3
    assert t.size == 6                                                   # the pulse: 2 n steps
    f0 = d.achieved[d.location.node]
    assert np.allclose(expo.get_ydata(), f0 * np.exp(k * t / 60e3) / 1e3, rtol=1e-12)
