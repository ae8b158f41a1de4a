"""Plain-language existence diagnosis (rodimpact.inverse.diagnosis): its numbers against hand calculations and
the recursive method itself."""

import math
import re
import warnings

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse.diagnosis import contact_jump, explain_bounds, smallest_start

DT = 1e-6
ZS = 12.7e3          # struck face impedance, N s/m
V = 12.0


def _bar():
    return ri.Rod.from_impedance([ZS] * 4, DT)


def _synth(windows, v=V):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        return ri.synthesize(np.asarray(windows), ri.System.struck(_bar(), far_end="nonreflecting"), v, len(windows), DT)


def _numbers_kn(text):
    return [float(x) for x in re.findall(r"([-\d.e+]+) kN\b", text)]


def test_contact_jump_hand_value():
    # Z1 = 5000, Z~ = 12700, v = 12: 5000 * 12700 * 12 / 17700 = 43050.847... N
    assert contact_jump(5000.0, ZS, V) == pytest.approx(5000 * 12700 * 12 / 17700, rel=1e-15)


def test_smallest_start_is_the_existence_limit_of_the_recursive_method():
    """Hand formula: |X_2| < F_0 (3 - 2 F_0 / (Z~ v)); a first window just above the smallest start F_0 lets
    both elements exist, just below it element 2 fails."""
    x2 = 20e3
    f0 = smallest_start(x2, ZS, V)
    s = ZS * V
    assert f0 * (3 - 2 * f0 / s) == pytest.approx(x2, rel=1e-12)       # the root of the quadratic
    assert f0 == pytest.approx(s * (3 - math.sqrt(9 - 8 * x2 / s)) / 4, rel=1e-15)
    assert _synth([-f0 * (1 + 1e-6), -x2]).feasible
    below = _synth([-f0 * (1 - 1e-6), -x2])
    assert not below.feasible and below.failure.element == 2


def test_smallest_start_none_when_unreachable():
    # |X_2| >= 9/8 Z~ v is beyond any jump
    assert smallest_start(1.2 * ZS * V, ZS, V) is None


def test_half_sine_message_from_synthesize_states_the_jump_and_its_fix():
    """A half-sine from 0 N: the message says why (contact jump) and what would work (the smallest start from
    the formula), and keeps the thesis's eq. 4.20 statement."""
    t = 2 * DT * (np.arange(50) + 0.5)
    x = -80e3 * np.sin(np.pi * t / 100e-6)
    res = _synth(x)
    msg = res.failure.message
    assert "eq. 4.20" in msg
    assert "cannot be produced" in msg and "jump" in msg
    f0 = smallest_start(abs(x[1]), ZS, V)
    assert f"{f0 / 1e3:.4g} kN" in msg
    # the force reserve of window 2 for the first element Z1 = |X1| Z~ / (Z~ v - |X1|): K_2 |N_0| with
    # K_2 = 4 Z1 Z~ / (Z1 + Z~)^2, N_0 = -Z~ v / 2
    z1 = abs(x[0]) * ZS / (ZS * V - abs(x[0]))
    reserve = 4 * z1 * ZS / (z1 + ZS) ** 2 * ZS * V / 2
    assert f"{reserve / 1e3:.4g} kN" in msg
    assert f"Z_1 = {z1:.4g} N s/m" in msg


def test_growth_limit_message_for_a_steep_ramp():
    """A ramp that grows too fast later on: the message gives the largest growth per window = the force reserve
    |K_q N_0| of the failing element, and the rate per ms."""
    res = _synth(ri.LinearRamp(50e3, 10e-6)(2 * DT * np.arange(50)))
    assert not res.feasible
    f = res.failure
    msg = f.message
    assert "must not grow faster than" in msg
    assert f"{f.force_reserve / 1e3:.4g} kN per window" in msg
    assert f"{f.force_reserve / (2 * DT) / 1e6:.4g} kN/ms" in msg


def test_bounds_diagnosis_numbers():
    """design's bound check: jump for the thinnest allowed first element Z1 = 2000 N s/m:
    2000 * 12700 * 12 / 14700 = 20734.69 N, and the Z1 the first window would need."""
    lines = explain_bounds(np.array([-1000.0, -50e3]), V, ZS, 2000.0, 1e6)
    assert len(lines) == 1
    assert "at least 20.73 kN" in lines[0]
    need = 1000 * ZS / (ZS * V - 1000)
    assert f"Z_1 = {need:.4g} N s/m" in lines[0]
    peak = explain_bounds(np.array([-200e3]), V, ZS, 1.0, 1e9)
    assert any(f"{ZS * V / 1e3:.4g} kN" in s for s in peak)
