"""SynthesisResult.table/report: the ``elements`` selection is checked (whole numbers 1..m or the failing
element), never truncated, converted into an overflow or passed on as an ambiguous array."""

import warnings

import numpy as np
import pytest

from rodimpact.inverse import SynthesisWarning, academic_example


@pytest.fixture(scope="module")
def feasible():
    return academic_example(1).solve()          # 100 of 100 elements


@pytest.fixture(scope="module")
def failing():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SynthesisWarning)
        return academic_example(2).solve()      # 78 of 100 elements, element 79 fails


BAD_VALUES = [
    ([1.5], ValueError, r"elements: must be whole numbers 1\.\.100, got 1\.5"),
    (2.5, ValueError, r"elements: must be whole numbers 1\.\.100, got 2\.5"),
    ([np.nan], ValueError, r"elements: must be whole numbers 1\.\.100, got nan"),
    ([np.inf], ValueError, r"elements: must be whole numbers 1\.\.100, got inf"),
    ("abc", TypeError, r"elements: must be whole numbers 1\.\.100, got str 'abc'"),
    (["2"], TypeError, r"elements: must be whole numbers 1\.\.100, got list"),
    ([None], TypeError, r"elements: must be whole numbers 1\.\.100, got list \[None\]"),
    ([True], TypeError, r"elements: must be whole numbers 1\.\.100, got list \[True\] \(entries of type bool\)"),
    (True, TypeError, r"elements: must be whole numbers 1\.\.100, got bool True"),
    ([1 + 2j], TypeError, r"elements: must be whole numbers 1\.\.100"),
    ({1, 2}, TypeError, r"elements: must be whole numbers 1\.\.100, got set"),
    ([[1, 2]], ValueError, r"elements: a single element number or a 1-d sequence of them, got shape \(1, 2\)"),
    ([], ValueError, r"elements: got an empty selection; must be whole numbers 1\.\.100, or None for all"),
    ([10**20], ValueError, r"elements: q = 100000000000000000000 was not computed; must be whole numbers 1\.\.100"),
    ([1, 10**20], ValueError, r"elements: q = 100000000000000000000 was not computed"),
    (np.array([2**63 - 1]), ValueError, r"elements: q = 9223372036854775807 was not computed"),
    ([0], ValueError, r"elements: q = 0 was not computed; must be whole numbers 1\.\.100$"),
    (-3, ValueError, r"elements: q = -3 was not computed"),
    (101, ValueError, r"elements: q = 101 was not computed"),
]


@pytest.mark.parametrize("method", ["table", "report"])
@pytest.mark.parametrize(("elements", "error", "match"), BAD_VALUES)
def test_bad_elements_are_refused_with_the_valid_range(feasible, method, elements, error, match):
    with pytest.raises(error, match=match):
        getattr(feasible, method)(elements)


@pytest.mark.parametrize("method", ["table", "report"])
@pytest.mark.parametrize(("elements", "match"), [
    ([1.5], r"elements: must be whole numbers 1\.\.78 \(plus the failing element 79\), got 1\.5"),
    ([np.nan], r"elements: must be whole numbers 1\.\.78 \(plus the failing element 79\), got nan"),
    ([80], r"elements: q = 80 was not computed; must be whole numbers 1\.\.78 \(plus the failing element 79\)"),
    ([10**20], r"elements: q = 100000000000000000000 was not computed; .*failing element 79"),
])
def test_the_failing_element_is_named_as_allowed(failing, method, elements, match):
    with pytest.raises(ValueError, match=match):
        getattr(failing, method)(elements)


def test_whole_numbers_of_any_numeric_type_select_rows(feasible, failing):
    assert [r["q"] for r in feasible.table(3)] == [3]
    assert [r["q"] for r in feasible.table(3.0)] == [3]
    assert [r["q"] for r in feasible.table(np.int64(100))] == [100]
    assert [r["q"] for r in feasible.table((1, 100))] == [1, 100]
    assert [r["q"] for r in feasible.table(np.array([5.0, 2.0]))] == [5, 2]
    rows = failing.table([1, 78.0, np.int32(79)])
    assert [r["q"] for r in rows] == [1, 78, 79] and np.isnan(rows[-1]["impedance"])
    assert failing.report(79).splitlines()[-1].split()[0] == "79"
    # the default still lists every element and appends the failing one
    assert [r["q"] for r in failing.table()] == list(range(1, 80))
    assert [r["q"] for r in feasible.table(None)] == list(range(1, 101))


def test_a_result_without_elements_says_so():
    res = academic_example(1, n=3).solve()
    empty = type(res)(*(a[:0] for a in (res.impedance, res.reflection, res.transmission_factor,
                                        res.force_difference, res.force_reserve, res.amplitude_growth,
                                        res.error_estimate)),
                      res.window_values, res.face_velocity, dt=res.dt, striker_velocity=res.striker_velocity,
                      struck_face_impedance=res.struck_face_impedance, impact_force_n0=res.impact_force_n0,
                      n_requested=res.n_requested)
    with pytest.raises(ValueError, match="elements: q = 1 was not computed; no element exists"):
        empty.table([1])
