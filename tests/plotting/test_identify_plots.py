"""The identification plots draw what they are given: the profile's steps at the element boundaries, the band,
the reflectogram's depth axis c t / 2."""

import numpy as np
import pytest

from rodimpact.identify import Anomaly, HeadRecord, IdentificationResult
from rodimpact.plotting import plot_identified_profile, plot_matched, plot_reflectogram


def test_profile_steps_and_band():
    z = np.array([4.0e5, 2.8e5])
    r = IdentificationResult(np.array([0.0, 1.0, 3.0]), z, 0.9 * z, 1.1 * z,
                             anomalies=(Anomaly(1.0, 2.0, -0.3, 0.7, "damage"),), method="beta")
    ax = plot_identified_profile(r)
    corners = ax.patches[0].get_path().vertices
    assert np.isclose(corners[:, 0].min(), 0.0) and np.isclose(corners[:, 0].max(), 3.0)
    assert np.isclose(corners[:, 1].max(), 400.0)                            # kN s/m
    assert len(ax.patches) == 2                                              # the profile and its band


def test_reflectogram_depth_axis():
    t = np.arange(10) * 1e-6
    n = np.r_[-1.0, np.zeros(9)]
    v = -n / 2.0
    v[4] = 0.25                                                             # an up wave at t = 4 us
    ax = plot_reflectogram(HeadRecord(t, n, v), 2.0, 4000.0)
    x, y = ax.lines[0].get_data()
    assert np.allclose(x, 0.5 * 4000.0 * t, rtol=1e-12) and np.isclose(y[4], -0.25)


def test_matched_refuses_an_unknown_name():
    r = IdentificationResult(np.array([0.0, 1.0]), np.array([1.0]), matched={"v": (np.arange(3.0),) * 3})
    with pytest.raises(ValueError, match="name: one of v, got 'x'"):
        plot_matched(r, "x")


def test_reflectogram_of_a_beta_result_is_amplified():
    """From a result: its reflectogram and primaries, each times exp(rate t) (t >= 0)."""
    t = np.arange(4) * 1e-3
    r = IdentificationResult(np.array([0.0, 1.0]), np.array([1.0]), wave_speed=2000.0, method="beta",
                             matched={"reflectogram": (t, np.ones(4), np.full(4, 0.5))})
    ax = plot_reflectogram(r, amplification=100.0)
    x, y = ax.lines[0].get_data()
    assert np.allclose(x, 1000.0 * t) and np.allclose(y, np.exp(100.0 * t), rtol=1e-14)
    assert np.allclose(ax.lines[1].get_data()[1], 0.5 * np.exp(100.0 * t), rtol=1e-14)
    with pytest.raises(ValueError, match="source: a 'striker' result holds no reflectogram"):
        plot_reflectogram(IdentificationResult(np.array([0.0, 1.0]), np.array([1.0]), method="striker"))
