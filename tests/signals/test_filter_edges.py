"""Zero-phase filtering at the record edges, with inputs that do NOT vanish at the ends (where the padding
matters: an even instead of an odd extension changes the edges by several per cent).

Independent reference for the analog stage: scipy discretises the same analog Bessel low-pass for a
piecewise-linear input (``cont2discrete(..., method="foh")``, a first-order hold, i.e. linear interpolation
between samples, which is what the modal simulation integrates exactly) and filters it forward and backward
with ``sosfiltfilt`` using the same odd extension (``padtype="odd"``) and length (3 (2 n_sections + 1)
samples, ``sosfiltfilt``'s default for n_sections second-order sections) with a steady-state start on each
pass. The conversion of the hold-equivalent to second-order sections is itself ill-conditioned for poles
close to z = 1 (h = omega_c dt small), which limits the agreement to about 1e-13 (order 2), 1e-10 (order 4)
and 3e-8 (order 5) of the signal; the tolerances below are those reference limits.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal

from rodimpact.signals import MeasuringChain, bessel_analog, bessel_digital, simulate_analog_filter

RATE = 1e7
CORNER = 100e3
T = np.arange(0.0, 60e-6, 1 / RATE)
# a ramp plus a sine: 1 at the start, about 2.4 at the end, neither value nor slope zero at the edges
X = 1.0 + 2e4 * T + 0.3 * np.sin(2 * np.pi * 4e4 * T + 0.7)


def hold_equivalent_sos(order: int) -> np.ndarray:
    z, p, k = bessel_analog(order, CORNER)
    a, b, c, d = signal.zpk2ss(z, p, k)
    ad, bd, cd, dd, _ = signal.cont2discrete((a, b, c, d), 1 / RATE, method="foh")
    return signal.zpk2sos(*signal.ss2zpk(ad, bd, cd, dd))


@pytest.mark.parametrize("order, tol", [(2, 1e-12), (4, 1e-9), (5, 1e-7)])
def test_zero_phase_analog_filter_matches_scipy_at_the_edges(order, tol):
    grid, y = simulate_analog_filter(T, X, order=order, corner=CORNER, simulation_rate=RATE, zero_phase=True)
    np.testing.assert_array_equal(grid, T)
    padlen = 3 * (2 * ((order + 1) // 2) + 1)
    reference = signal.sosfiltfilt(hold_equivalent_sos(order), X, padtype="odd", padlen=padlen)
    scale = np.max(np.abs(X))
    edges = np.r_[0:padlen, T.size - padlen:T.size]
    assert np.max(np.abs(y[edges] - reference[edges])) <= tol * scale
    assert np.max(np.abs(y - reference)) <= tol * scale
    # the comparison is sensitive to the padding: an even extension differs by per cent at the edges
    even = signal.sosfiltfilt(hold_equivalent_sos(order), X, padtype="even", padlen=padlen)
    assert np.max(np.abs(even - reference)) > 1e-2 * scale


def test_measuring_chain_zero_phase_digital_stage_at_the_edges():
    """Digital stage alone (no analog stage): the chain samples the input at its rate and runs the digital
    Bessel forward and backward with the odd extension of scipy's filtfilt on the transfer function."""
    chain = MeasuringChain(analog_order=None, digital_order=2, digital_corner=40e3, sampling_rate=1e6)
    t = np.arange(200) / 1e6                           # the chain's own sample times t0 + k / rate
    x = 1.0 + 1e4 * t + 0.2 * np.cos(2 * np.pi * 2e4 * t)
    t_k, y = chain.apply(t, x, zero_phase=True)
    np.testing.assert_array_equal(t_k, t)
    b, a = signal.sos2tf(bessel_digital(2, 40e3, 1e6))
    reference = signal.filtfilt(b, a, x, padtype="odd", padlen=3 * 3)
    np.testing.assert_allclose(y, reference, rtol=0, atol=1e-12 * np.max(np.abs(x)))
