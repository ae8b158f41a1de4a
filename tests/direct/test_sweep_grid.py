"""Sweep grids (issue 20, item 13): quantity strings become SI numbers with a unit attribute, text stays text, and
a grid too large to run is refused before anything is built or run, naming ``grid`` and the limit."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct.sweep import MAX_SWEEP_POINTS, grid_coordinate

C = ri.STEEL.wave_speed
DT = 0.002 / C
Z = ri.STEEL.impedance(np.pi * 0.02**2)


def bars(velocity, end="nonreflecting"):
    """A 0.1 m striker on a 0.5 m bar of the same section; ``velocity`` a number (m/s) or a string with a unit."""
    v = float(velocity) if not isinstance(velocity, str) else {"3 m/s": 3.0, "4000 mm/s": 4.0, "5": 5.0}[velocity]
    return dict(rods=[ri.Rod([ri.Cylinder(0.1, 0.04)]), ri.Rod([ri.Cylinder(0.5, 0.04)])],
                velocities=[v, 0.0], duration=0.2e-3, dt=DT, right=end)


def test_quantity_strings_become_si_numbers_with_their_unit():
    ds = ri.sweep(bars, {"velocity": ["3 m/s", "4000 mm/s", 5.0], "end": ["nonreflecting", "fixed"]}, workers=1,
                  batch=False)
    v = ds["velocity"]
    assert v.dtype.kind == "f"
    np.testing.assert_array_equal(v.values, [3.0, 4.0, 5.0])
    assert v.attrs["units"] == "m/s"
    assert ds["end"].values.tolist() == ["nonreflecting", "fixed"]        # text stays text
    # the metric at each coordinate is the run at that velocity: -Z v / 2 against the non-reflecting end
    np.testing.assert_allclose(ds["peak_contact_force"].sel(end="nonreflecting"), -Z * np.array([3, 4, 5]) / 2,
                               rtol=1e-12)
    assert ds["peak_contact_force"].sel(velocity=4.0, end="fixed") < 0


@pytest.mark.parametrize("values, expected, unit", [
    (["1.2 m", "800 mm"], [1.2, 0.8], "m"),
    (["0.5 us", "1 us"], [0.5e-6, 1e-6], "s"),
    (["300 MN/m", 4e8], [3e8, 4e8], "N/m"),
    (["30 %", "50 %"], [0.3, 0.5], "1"),
    ([4, 5], [4, 5], ""),
])
def test_grid_coordinate_numbers(values, expected, unit):
    coordinate, u = grid_coordinate("k", values)
    np.testing.assert_allclose(coordinate, expected, rtol=1e-12)
    assert u == unit


@pytest.mark.parametrize("values", [["free", "fixed"], ["m", "s"], ["5 m/s", "5 kg"], ["true", "false"]])
def test_grid_coordinate_keeps_text_that_is_no_quantity_of_one_dimension(values):
    coordinate, unit = grid_coordinate("k", values)
    assert coordinate.tolist() == values and unit == ""


def test_values_equal_in_si_units_are_refused_before_any_run():
    calls = []
    with pytest.raises(ValueError, match=r"grid\['velocity'\].*repeat"):
        ri.sweep(lambda velocity: calls.append(velocity), {"velocity": ["4 m/s", "4000 mm/s"]})
    assert calls == []


def test_a_grid_too_large_is_refused_before_anything_is_built():
    calls = []
    n = 10_000
    with pytest.raises(ValueError) as info:
        ri.sweep(lambda a, b: calls.append((a, b)), {"a": list(range(n)), "b": list(range(n))})
    message = str(info.value)
    assert message.startswith("grid:")
    assert "10,000 x 10,000" in message and "100,000,000 points" in message and f"{MAX_SWEEP_POINTS:,}" in message
    assert calls == []
