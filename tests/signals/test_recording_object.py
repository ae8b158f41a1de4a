"""The Recording container."""

import numpy as np
import pytest

from rodimpact.signals import Recording


def make():
    t = np.arange(5) * 1e-6
    return Recording(t, {"a": np.arange(5.0), "b": -np.arange(5.0)}, {"a": "V"}, {"gain": 100.0}, "x.csv")


def test_access_and_defaults():
    rec = make()
    assert rec.channel_names == ["a", "b"]
    assert rec.units == {"a": "V", "b": ""}
    assert rec.sample_interval == pytest.approx(1e-6)
    assert rec.sampling_rate == pytest.approx(1e6)
    assert rec.is_uniform()
    np.testing.assert_array_equal(rec["b"], [0, -1, -2, -3, -4])
    assert "a" in rec and "c" not in rec
    with pytest.raises(KeyError, match="channels"):
        rec["c"]


def test_arrays_are_read_only_copies():
    values = np.arange(5.0)
    rec = Recording(np.arange(5.0), {"a": values})
    values[0] = 99.0
    assert rec["a"][0] == 0.0
    with pytest.raises(ValueError):
        rec["a"][0] = 1.0


def test_derived_recordings():
    rec = make()
    win = rec.window(1e-6, 3e-6)
    np.testing.assert_array_equal(win["a"], [1, 2, 3])
    assert win.metadata == {"gain": 100.0}
    assert rec.selected(["b"]).channel_names == ["b"]
    rec2 = rec.with_channel("force", np.ones(5), "N")
    assert rec2.units["force"] == "N" and rec.channel_names == ["a", "b"]
    ds = rec.to_xarray()
    assert ds["a"].attrs["units"] == "V"
    np.testing.assert_array_equal(ds["time"].values, rec.time)


@pytest.mark.parametrize(
    ("time", "channels", "match"),
    [
        ([0.0, 1.0, 1.0], {"a": [1.0, 2.0, 3.0]}, "strictly increasing: sample 2"),
        ([0.0, 2.0, 1.0], {"a": [1.0, 2.0, 3.0]}, "strictly increasing"),
        ([0.0, 1.0, 2.0], {"a": [1.0, 2.0]}, "has 2 samples but time has 3"),
        ([0.0, 1.0, 2.0], {"a": [1.0, np.nan, 3.0]}, "non-finite value at sample 1"),
        ([0.0, 1.0, 2.0], {}, "non-empty"),
        ([0.0], {"a": [1.0]}, "at least 2"),
    ],
)
def test_invalid_recordings(time, channels, match):
    with pytest.raises(ValueError, match=match):
        Recording(time, channels)


def test_unit_for_unknown_channel():
    with pytest.raises(ValueError, match="unknown channel 'z'"):
        Recording([0.0, 1.0], {"a": [0.0, 1.0]}, {"z": "V"})
