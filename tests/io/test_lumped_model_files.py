"""Lumped chains (point masses and cushions, issue 23) in model files: read with units, written back exactly, run
bit for bit, refused with key paths when impossible, and listed by the reference page. Their keys come from the
class declarations alone (rodimpact.rods.declared, kind ``parts``)."""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.model import ModelError, dump_model, loads_model
from rodimpact.io.schema import reference_markdown

PILE = """
[[rods]]
name = "pile"
[[rods.segments]]
shape = "cylinder"
length = "5 m"
diameter = "300 mm"
"""

MODEL = PILE + """
[ends.left]
type = "lumped"
items = [{ type = "point-mass", mass = "4536 kg", velocity = "4.236 m/s" },
         { type = "cushion", stiffness = "1 GN/m", restitution = 0.8 },
         { type = "point-mass", mass = "1000 kg" },
         { type = "cushion", stiffness = "2 GN/m", restitution = 0.5 }]

[ends]
right = "nonreflecting"

[simulation]
duration = "2 ms"
dt = "10 us"
"""

JOINT = """
[[rods]]
name = "ram"
velocity = "4 m/s"
[[rods.segments]]
shape = "cylinder"
length = "1 m"
diameter = "300 mm"

""" + PILE + """
[[junctions]]
type = "lumped"
items = [{ type = "cushion", stiffness = "1 GN/m", restitution = 0.8 }, { type = "point-mass", mass = "1 t" },
         { type = "cushion", stiffness = "2 GN/m" }]

[ends]
right = "nonreflecting"

[simulation]
duration = "2 ms"
dt = "9.66092 us"
"""


def test_the_chain_is_read_with_units() -> None:
    end = loads_model(MODEL).system.left
    assert isinstance(end, ri.LumpedEnd)
    assert end.items == (ri.PointMass(4536.0, 4.236), ri.Cushion(1e9, 0.8), ri.PointMass(1000.0),
                         ri.Cushion(2e9, 0.5))
    joint = loads_model(JOINT).system.junctions[0]
    assert joint.items == (ri.Cushion(1e9, 0.8), ri.PointMass(1000.0), ri.Cushion(2e9))


@pytest.mark.parametrize("text", [MODEL, JOINT])
def test_written_back_exactly_and_run_bit_for_bit(text: str) -> None:
    model = loads_model(text)
    out = dump_model(model)
    again = loads_model(out)
    assert (again.system.left, again.system.junctions) == (model.system.left, model.system.junctions)
    assert dump_model(again) == out
    a, b = model.simulate(), again.simulate()
    assert np.array_equal(a.end_force["left"], b.end_force["left"])
    assert np.array_equal(a.junction_force, b.junction_force)
    assert a.lumped == b.lumped and len(a.lumped) == 1
    assert np.min(a.end_force["left"]) < -1e5 or np.min(a.junction_force) < -1e5     # the chain carries the blow


@pytest.mark.parametrize("old, new, message", [
    ('mass = "4536 kg"', 'mass = "-4536 kg"', r"ends\.left\.items\[0\]\.mass: must be > 0, got -4536 kg"),
    ('mass = "1000 kg"', 'mass = "0 kg"', r"ends\.left\.items\[2\]\.mass: must be > 0"),
    ('stiffness = "1 GN/m"', 'stiffness = "0 N/m"', r"ends\.left\.items\[1\]\.stiffness: must be > 0"),
    ("restitution = 0.8", "restitution = 1.5", r"ends\.left\.items\[1\]\.restitution: must be in \(0, 1\]"),
    ("restitution = 0.5", "restitution = 0", r"ends\.left\.items\[3\]\.restitution: must be > 0"),
    ('stiffness = "1 GN/m"', 'stiffness = "1 GN"', r"ends\.left\.items\[1\]\.stiffness: expected a stiffness"),
    ('{ type = "cushion", stiffness = "1 GN/m", restitution = 0.8 },', "",
     r"ends\.left\.items\[1\]: a PointMass next to another PointMass \(items\[0\]\); join them"),
    ('items = [{ type = "point-mass", mass = "4536 kg", velocity = "4.236 m/s" },', "items = [",
     r"ends\.left\.items\[0\]: the outermost item of an end chain must be a PointMass"),
    ('type = "cushion", stiffness = "2 GN/m"', 'type = "cushon", stiffness = "2 GN/m"',
     r"ends\.left\.items\[3\]\.type: unknown type 'cushon' \(did you mean 'cushion'\?\)"),
    ('{ type = "point-mass", mass = "1000 kg" },', '{ type = "point-mass", mas = "1000 kg" },',
     r"ends\.left\.items\[2\]"),
])
def test_impossible_chains_are_refused_by_key_path(old: str, new: str, message: str) -> None:
    assert old in MODEL
    with pytest.raises(ModelError, match=message):
        loads_model(MODEL.replace(old, new))


def test_an_empty_chain_is_refused() -> None:
    with pytest.raises(ModelError, match=r"junctions\[0\]\.items: needs at least 1 entry"):
        loads_model(JOINT.replace(JOINT[JOINT.index("items = ["):JOINT.index("[ends]")], "items = []\n\n"))


def test_the_reference_page_lists_the_chain_and_its_items() -> None:
    page = reference_markdown()
    for title in ('type = "lumped"', 'item type = "point-mass"', 'item type = "cushion"'):
        assert title in page
    assert "| `restitution` | number | 1.0 |" in page


@pytest.mark.parametrize("text", [MODEL, JOINT])
def test_the_chain_outcomes_are_saved_and_loaded(text: str, tmp_path) -> None:
    result = loads_model(text).simulate()
    ri.save(result, tmp_path / "run")
    again = ri.load(tmp_path / "run")
    assert again.lumped == result.lumped and len(again.lumped) == 1
