"""Two-gauge wave separation (rodimpact/identify/two_gauge.py) on the exact lattice, where the waves overlap at
both gauges.

Closed form: a striker of the bar's impedance Z (80 elements) hits a bar of 300 elements with a free far end at
v0. The incident strain is -v0 / (2 c) for the striker's two-way time, 160 steps; the free end sends it back with
the opposite sign. At gauge A (250 elements in) the incident wave passes during steps [250, 410), the reflected
one during [350, 510): they overlap over [350, 410), as at gauge B (270 elements in). f must be the incident
rectangle alone and g the reflected one, to rounding.
"""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.identify import separate_waves

DT = 1e-6


def test_overlapping_waves_are_separated_exactly():
    z, v0 = 4.0e5, 5.0
    striker = ri.Rod.from_impedance([z] * 80, dt=DT)
    bar = ri.Rod.from_impedance([z] * 300, dt=DT)
    c = bar.length / (300 * DT)
    probes = [ri.Probe("A", 1, 250 * c * DT), ri.Probe("B", 1, 270 * c * DT)]
    res = ri.simulate(ri.Problem.of([striker, bar], [v0, 0.0], steps=520, dt=DT, outputs=ri.Outputs(probes=probes)),
                      backend="numpy")
    f, g = separate_waves(res.probe("A").strain, res.probe("B").strain, 20)
    k = np.arange(520)
    level = v0 / (2 * c)
    assert np.max(np.abs(f - np.where((k >= 250) & (k < 410), -level, 0.0))) < 1e-12 * level
    assert np.max(np.abs(g - np.where((k >= 350) & (k < 510), level, 0.0))) < 1e-12 * level


def test_refuses_gauges_on_different_time_axes():
    with pytest.raises(ValueError, match=r"strain_b: must have one sample per sample of strain_a \(5\), got 4"):
        separate_waves(np.zeros(5), np.zeros(4), 1)
    with pytest.raises(ValueError, match="delay: must be an integer >= 1"):
        separate_waves(np.zeros(5), np.zeros(5), 0)


def test_the_bar_below_two_gauges_is_peeled_exactly():
    """Record (3), a bar hit by a striker with two gauges: the separated waves at gauge A (times E A) are the
    down- and up-going force waves there, and the bar below A peels like a pile below its head. The bar steps
    to 0.8 Z and back (elements 40 to 60 below A, below gauge B); the profile comes back to rounding."""
    from rodimpact.identify import identify_by_peeling, waves_record

    z, v0 = 4.0e5, 5.0
    profile = np.r_[np.full(140, z), np.full(20, 0.8 * z), np.full(140, z)]        # gauge A at element 100
    striker = ri.Rod.from_impedance([z] * 80, dt=DT)
    bar = ri.Rod.from_impedance(list(profile), dt=DT)
    c = bar.length / (300 * DT)
    probes = [ri.Probe("A", 1, 100 * c * DT), ri.Probe("B", 1, 120 * c * DT)]
    res = ri.simulate(ri.Problem.of([striker, bar], [v0, 0.0], steps=400, dt=DT, right="nonreflecting",
                                    outputs=ri.Outputs(probes=probes)), backend="numpy")
    f, g = separate_waves(res.probe("A").strain, res.probe("B").strain, 20)
    ea = z * c                                                                       # E A = Z c
    onset = 100                                                                      # the front reaches A
    record = waves_record(res.time[onset::2] - res.time[onset], ea * f[onset::2], ea * g[onset::2], z)
    out = identify_by_peeling(record, z, c, depth=100 * c * DT)
    assert np.max(np.abs(out.impedance / profile[100:200] - 1)) < 1e-10
