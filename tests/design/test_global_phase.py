"""The global phase of design finds a good optimum of a rugged problem (issue 20, item 4): the half-sine of
docs/design.md (80 kN, 100 us, on a 20 mm steel bar with a non-reflecting end; a 5-60 mm steel striker at 12 m/s,
n = 50). An independent 31-start search by a reviewer found misfit 0.1254 inside the same bounds; design gave
0.1286 when the issue was filed. The benchmark (benchmarks/bench_design.py --global) times it."""

import warnings

import numpy as np
import pytest

import rodimpact as ri

BEST_KNOWN = 0.1254


@pytest.mark.slow
def test_the_half_sine_design_is_within_half_a_percent_of_the_best_known_misfit():
    n, span = 50, 100e-6
    dt = span / (2 * n)
    bar = ri.Rod.from_impedance([ri.STEEL.impedance(np.pi / 4 * 0.020 ** 2)] * 8, dt)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -80e3 * np.sin(np.pi * t / span), duration=span)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 12.0, n, dt,
                      limits=ri.StrikerLimits(diameter_bounds=(0.005, 0.060), material=ri.STEEL))
    assert d.misfit <= 1.005 * BEST_KNOWN, d.misfit
    values = d.diagnostics["local_optima"]["values"]
    assert min(values) == pytest.approx(d.misfit, rel=1e-9) and max(values) > d.misfit    # the spread is reported
    assert d.verify().max_deviation < 1e-9          # the direct solver agrees with the design's own run
