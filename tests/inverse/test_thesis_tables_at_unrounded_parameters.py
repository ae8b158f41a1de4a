"""Issue 14 item 14: thesis Tabs. 4.3/4.4 entry by entry at unrounded parameters.

The tables are transcribed from the thesis text (/work/shared/thesis/burgert-impacting-rods.txt, Sec. 4.2.1).
At the printed parameters of Tab. 4.2 (N^ = 239 kN, dt = 1.93 us, t0 = 0.383 ms) row 77 of Tab. 4.4 is far
off (Z = 1102 vs 2460 MN s/m). The synthesis depends on dt and t0 only through dt / t0 (the window values are
-N^ exp(-2 (j-1) dt / t0)); with N^ = v_in Z~ / 2 = 239.1 kN (the first impedance equals Z~ = 79.7 kN s/m, as
the tables' first rows print) and dt / t0 = 5.0505e-3 (inside the rounding of the printed 1.93 us and
0.383 ms) every printed entry agrees with ours to its printed digits: 83 of the 89 are ours rounded, the other
6 ours with the last printed digit cut (the thesis's value lies within one unit of its last digit below ours).

Mapping (thesis eq. 4.27, Z(theta = q dt) = Z_q): the thesis's rows q = 10, 20, ... are our elements q + 1
(leading edge at theta = q dt); its first row ("1", K = 1, no Delta N) is our element 1; Tab. 4.3's last row
"q = 100" is "the last element", our element 100 of n = 100 (theta = 99 dt).
"""

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import ExponentialDecay, LinearRamp, SynthesisWarning, lundberg_lesser_impedance, synthesize

ZT, V_IN, T0 = 79.7e3, 6.00, 0.383e-3
PEAK = V_IN * ZT / 2                      # 239.1 kN
RATIO = 5.0505e-3                         # dt / t0
DT = RATIO * T0                           # 1.93434 us
ROOT = Path(__file__).resolve().parents[2]

# thesis rows: q -> (K_q, |dN_q| in kN, |K_q N_0| in kN, Z_q); Z in kN s/m (Tab. 4.3), MN s/m (Tab. 4.4)
TABLE_4_3 = {1: ("1.00", None, "239", "79.7"), 10: ("0.999", "2.20", "239", "65.7"),
             20: ("0.998", "2.01", "239", "55.1"), 30: ("0.998", "1.86", "238", "46.9"),
             40: ("0.997", "1.72", "238", "40.4"), 50: ("0.997", "1.60", "238", "35.2"),
             60: ("0.996", "1.50", "238", "30.9"), 70: ("0.996", "1.41", "238", "27.3"),
             80: ("0.996", "1.33", "238", "24.4"), 90: ("0.995", "1.26", "238", "21.9"),
             100: ("0.995", "1.20", "238", "19.9")}
TABLE_4_4 = {1: ("1.00", None, "239", "0.0797"), 10: ("0.996", "4.90", "238", "0.120"),
             20: ("0.992", "5.19", "237", "0.183"), 30: ("0.987", "5.76", "236", "0.291"),
             40: ("0.980", "6.78", "234", "0.496"), 50: ("0.970", "8.67", "232", "0.961"),
             60: ("0.951", "12.7", "227", "2.43"), 70: ("0.893", "26.0", "213", "13.0"),
             75: ("0.765", "56.3", "183", "106"), 76: ("0.693", "73.5", "166", "276"),
             77: ("0.556", "106", "133", "2460"), 78: ("0.202", "191", "48.3", None)}
#: the entries whose last printed digit is cut rather than rounded (ours: 55.161, 238.55, 0.96170, 213.51,
#: 106.51, 276.57)
CUT = {("4.3", 20, "impedance"), ("4.3", 30, "reserve"), ("4.4", 50, "impedance"), ("4.4", 70, "reserve"),
       ("4.4", 75, "impedance"), ("4.4", 76, "impedance")}


def _rows(target, peak, dt, n):
    bar = ri.Rod.from_impedance([ZT] * 4, dt)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SynthesisWarning)      # example 2 stops at its existence limit
        res = synthesize(target(peak, T0), ri.System.struck(bar, far_end="nonreflecting"), V_IN, n=n, dt=dt, rule="start")
    return res, {r["q"]: r for r in res.table()}


def _ours(table, q):
    if q == 1:
        return 1
    return 100 if (table == "4.3" and q == 100) else q + 1


def _unit_of_last_digit(text):
    """10^(exponent of the last printed digit): "2.20" -> 0.01, "239" -> 1, "2460" -> 10 (3 significant)."""
    digits = text.replace(".", "").lstrip("0")
    value = float(text)
    return 10.0 ** (math.floor(math.log10(value)) - (min(len(digits), 3) - 1))


def _compare(table_name, table, target, z_unit):
    res, rows = _rows(target, PEAK, DT, 100)
    rounded, cut, bad = [], [], []
    for q, printed in table.items():
        for key, text, unit in zip(("K", "dN", "reserve", "impedance"), printed, (1.0, 1e3, 1e3, z_unit)):
            if text is None:
                continue
            ours = abs(rows[_ours(table_name, q)][key]) / unit
            p, u = float(text), _unit_of_last_digit(text)
            if abs(ours - p) <= 0.5 * u * (1 + 1e-9):
                rounded.append((q, key))
            elif p <= ours < p + u:
                cut.append((table_name, q, key))
            else:
                bad.append((q, key, text, ours))
    return res, rounded, cut, bad


def test_tab_4_3_every_printed_entry_at_unrounded_parameters():
    res, rounded, cut, bad = _compare("4.3", TABLE_4_3, ExponentialDecay, 1e3)
    assert bad == []
    assert len(rounded) + len(cut) == 43
    assert res.feasible and res.n_feasible == 100


def test_tab_4_4_every_printed_entry_at_unrounded_parameters():
    res, rounded, cut, bad = _compare("4.4", TABLE_4_4, LinearRamp, 1e6)
    assert bad == []
    assert len(rounded) + len(cut) == 46
    # the existence limit: the thesis's q = 78 (our element 79) fails, 78 elements exist (theta = 77 dt)
    assert res.n_feasible == 78 and res.failure.element == 79


def test_only_the_listed_entries_are_cut_and_the_rest_rounded():
    cut = _compare("4.3", TABLE_4_3, ExponentialDecay, 1e3)[2] + _compare("4.4", TABLE_4_4, LinearRamp, 1e6)[2]
    assert sorted(cut) == sorted(CUT)


def test_at_the_printed_parameters_row_77_of_tab_4_4_is_far_off():
    _, rows = _rows(LinearRamp, 239e3, 1.93e-6, 100)
    z77 = rows[78]["impedance"] / 1e6
    assert abs(z77 / 2460 - 1) > 0.5                          # 1102 vs 2460 MN s/m
    assert z77 == pytest.approx(1102, rel=1e-3)


def _lundberg_lesser_error(peak, dt):
    bar = ri.Rod.from_impedance([ZT] * 4, dt)
    res = synthesize(ExponentialDecay(peak, T0), ri.System.struck(bar, far_end="nonreflecting"), V_IN, n=100, dt=dt, rule="start")
    exact = lundberg_lesser_impedance(dt * np.arange(100), peak, T0, ZT, V_IN)       # theta_q = (q - 1) dt
    return float(np.max(np.abs(res.impedance / exact - 1))) * 100                   # percent


def test_error_against_eq_4_26_and_what_the_docs_say():
    printed = _lundberg_lesser_error(239e3, 1.93e-6)
    unrounded = _lundberg_lesser_error(PEAK, DT)
    assert f"{printed:.3g}" == "0.000845"               # at the printed parameters
    assert f"{unrounded:.3g}" == "0.00106"              # thesis: 1.10e-3 %
    doc = (ROOT / "docs" / "inverse.md").read_text(encoding="utf-8")
    assert f"{printed * 1e3:.3g}e-3 %" in doc and f"{unrounded * 1e3:.3g}e-3 %" in doc
    assert "5.0505e-3" in doc and "239.1 kN" in doc
    # the former claim must not come back: the start rule does not reproduce the tables at the printed
    # parameters, nor the 1.10e-3 %
    assert not re.search(r"reproduces tables 4\.3/4\.4 and the 1\.10e-3", doc)
