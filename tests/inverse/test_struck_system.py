"""The struck system as one value (issue 21): ``System.struck`` holds what synthesize, transform_force and design
took as loose keywords, and the old keywords say where they went."""

import numpy as np
import pytest

import rodimpact as ri

DT = 1e-6


def test_struck_system_defaults_and_parts():
    a, b = ri.Rod.from_impedance([4e4] * 6, DT), ri.Rod.from_impedance([8e4] * 4, DT)
    s = ri.System.struck([a, b])
    assert isinstance(s.left, ri.FreeEnd) and isinstance(s.right, ri.FreeEnd)      # the impact face, free far end
    assert s.velocities == (0.0, 0.0) and all(isinstance(j, ri.Bonded) for j in s.junctions)
    s = ri.System.struck([a, b], "nonreflecting", [0.5, -0.5], junctions=[ri.Contact()])
    assert isinstance(s.right, ri.NonReflectingEnd) and s.velocities == (0.5, -0.5)
    assert isinstance(s.junctions[0], ri.Contact)
    with pytest.raises(ValueError, match=r"velocity: need one value per struck rod \(2\), got 1"):
        ri.System.struck([a, b], velocity=[0.0])
    with pytest.raises(TypeError, match="rods: must be a Rod or a list of Rods"):
        ri.System.struck("bar")


def test_synthesis_with_a_struck_system_equals_the_closed_form_of_the_first_element():
    """Thesis eq. 4.4: the first element of a striker at v_in on a bar of face impedance Z gives the first
    window X_1: Z_1 = 1 / (v_in / |X_1| - 1 / Z)."""
    bar = ri.Rod.from_impedance([79.7e3] * 200, DT)
    res = ri.synthesize(-1e5 * np.ones(20), ri.System.struck(bar, far_end="nonreflecting"), 6.0, dt=DT)
    assert res.impedance[0] == pytest.approx(1.0 / (6.0 / 1e5 - 1.0 / 79.7e3), rel=1e-12)


@pytest.mark.parametrize("keyword", ["far_end", "struck_velocity", "junctions", "loads", "initial"])
def test_the_old_struck_keywords_say_where_they_went(keyword):
    bar = ri.Rod.from_impedance([79.7e3] * 20, DT)
    with pytest.raises(TypeError, match=rf"{keyword}: give the struck system as one System: ri.System.struck"):
        ri.synthesize(-1e5 * np.ones(5), bar, 6.0, dt=DT, **{keyword: None})
    with pytest.raises(TypeError, match=rf"{keyword}: give the struck system as one System"):
        ri.transform_force(-1e5 * np.ones(5), bar, 0.0, dt=DT, **{keyword: None})
