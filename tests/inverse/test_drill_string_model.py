"""Issue 14 item 16: one drill string. The model file percussion-drilling.toml and the Python example
percussion_drilling_example() describe the same struck system (Tab. 4.5, n~ = 400 elements for the whole drill
string) and build the same lattice."""

from pathlib import Path

import numpy as np

import rodimpact as ri
from rodimpact.inverse import percussion_drilling_example
from rodimpact.lattice.lattice import build_lattice

MODEL = Path(ri.__file__).parent / "examples" / "percussion-drilling.toml"
C = np.sqrt(210e9 / 7840.0)


def test_model_file_and_python_example_build_the_same_lattice():
    model = ri.load_model(MODEL)
    prob = percussion_drilling_example()
    string_file, string_py = model.system.rods[1], prob.struck
    assert model.time_step == prob.dt == string_py.native.dt
    dt = prob.dt
    a = build_lattice(ri.System([string_file], [0.0]), dt)
    b = build_lattice(ri.System([string_py], [0.0]), dt)
    assert a.n_elements == b.n_elements == 400                             # Tab. 4.5: n~ = 400
    assert np.array_equal(a.impedance, b.impedance)
    assert np.array_equal(a.element_length, b.element_length)
    assert string_file.length == string_py.length
    # the same struck system in the direct run: rod 1 of the model's lattice is the Python drill string
    full = build_lattice(model.system, model.time_step)
    assert np.array_equal(full.impedance[full.rod_start[1]:], b.impedance)
    assert model.system.velocities[1] == 0.0 and model.system.right.loading_stiffness == 300e6


def test_the_drill_string_follows_tab_45_and_the_stated_reading():
    """Hand-written from Tab. 4.5 and the split stated in the docs: 70 / 30 / 250 / 10 + 40 elements of 5 mm."""
    z = percussion_drilling_example().struck.native.impedance
    expected = np.concatenate([np.full(70, 51.0e3), np.full(30, 115e3), np.full(250, 79.7e3), np.full(10, 156e3),
                               156e3 + (248e3 - 156e3) * np.arange(40) / 39])
    assert np.allclose(z, expected, rtol=1e-15, atol=0)
    prob = percussion_drilling_example()
    assert abs(prob.dt - 0.005 / C) <= 1e-15 * prob.dt
    assert abs(prob.struck.length - 2.0) <= 1e-12                            # 400 x 5 mm
    # the three jumps of Fig. 4.10b in the thesis's order within the target's 2 n dt = 200 dt:
    # coupling sleeve round trip, then bit round trip, then shank-adapter round trip
    sleeve, bit, shank = 2 * 30, 2 * (10 + 40), 2 * 70
    assert sleeve < bit < shank < 200


def test_docs_and_both_files_state_the_reading():
    root = Path(__file__).resolve().parents[2]
    toml = MODEL.read_text(encoding="utf-8")
    py = (root / "rodimpact" / "inverse" / "examples.py").read_text(encoding="utf-8")
    doc = (root / "docs" / "inverse.md").read_text(encoding="utf-8")
    for text in (toml, py, doc):
        assert "whole struck system" in text or "whole drill" in text
    for text in (toml, doc):
        assert "70" in text and "250" in text
    assert "2.0 m (400 elements" not in doc and "drill rod 2.0 m" not in doc     # the former second reading
