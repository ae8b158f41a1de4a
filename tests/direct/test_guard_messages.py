"""The disk-space and memory refusals list the parts of the total, never an empty "()" (issue 20, item 19)."""

from pathlib import Path

import pytest

from rodimpact.direct import guards


def test_disk_message_lists_small_parts_instead_of_empty_parentheses(monkeypatch, tmp_path):
    # every part below 1 MiB but the total above the free space: the old message read "(...) on disk ()"
    monkeypatch.setattr(guards, "free_disk", lambda folder: 1000.0)
    with pytest.raises(ValueError) as info:
        guards.check_output(Path(tmp_path), {"result.nc": 600_000.0, "plots": 300_000.0}, {})
    text = str(info.value)
    assert "()" not in text
    assert "result.nc 0.572 MiB" in text and "plots 0.286 MiB" in text


def test_disk_message_keeps_only_the_large_parts_when_there_are_some(monkeypatch, tmp_path):
    monkeypatch.setattr(guards, "free_disk", lambda folder: 1000.0)
    with pytest.raises(ValueError) as info:
        guards.check_output(Path(tmp_path), {"result.nc": 3 * 2**20, "plots": 100.0}, {})
    assert "(result.nc 3 MiB)" in str(info.value)


def test_memory_message_lists_small_parts_instead_of_empty_parentheses(monkeypatch):
    monkeypatch.setattr(guards, "available_memory", lambda: 1000.0)
    monkeypatch.setattr(guards, "SMALL_BYTES", 0.0)
    with pytest.raises(ValueError) as info:
        guards._check_memory({"histories": 500_000.0, "lattice": 100_000.0}, {"histories": "h", "lattice": "l"},
                             {"histories": "output.record_every", "lattice": "simulation.dt"})
    text = str(info.value)
    assert "()" not in text and "histories 0.477 MiB" in text
