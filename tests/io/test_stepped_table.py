"""Stepped profiles in a `table` shape (a repeated x is a step) and `rodimpact.stepped_profile`: the pieces between
steps become segments, so mass and dynamics equal those of the same rod built from cylinders and cones; bad
tables get errors naming the key path."""

import math

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.quantities import ModelError

RHO = ri.STEEL.density
SIM = '[simulation]\nsteps = 3\n'


def _table_model(x, diameter, extra=""):
    return ("[[rods]]\n[[rods.segments]]\nshape = \"table\"\n"
            f"x = {[f'{v} mm' for v in x]}\ndiameter = {[f'{v} mm' for v in diameter]}\n{extra}" + SIM)


def frustum_mass(length, d1, d2):
    """rho pi/4 L (d1^2 + d1 d2 + d2^2) / 3: a cone of linearly varying diameter."""
    return RHO * math.pi / 4 * length * (d1 * d1 + d1 * d2 + d2 * d2) / 3


def test_a_step_and_a_taper_in_one_table():
    """40 mm up to 100 mm, a step to 50 mm, constant to 150 mm, then a taper to 45 mm at 200 mm: two segments
    around the step (the second one holding the taper); the mass of a stepped table by hand."""
    model = ri.loads_model(_table_model([0, 100, 100, 150, 200], [40, 40, 50, 50, 45]))
    rod = model.system.rods[0]
    assert len(rod.segments) == 2
    np.testing.assert_allclose(rod.segment_bounds, [0.0, 0.1, 0.2], rtol=0, atol=1e-15)
    assert rod.area(0.0999) == pytest.approx(math.pi / 4 * 0.04 ** 2, rel=1e-12)
    assert rod.area(0.1001) == pytest.approx(math.pi / 4 * 0.05 ** 2, rel=1e-12)
    assert rod.area(0.2) == pytest.approx(math.pi / 4 * 0.045 ** 2, rel=1e-12)
    step_only = ri.loads_model(_table_model([0, 100, 100, 150], [40, 40, 50, 50])).system.rods[0]
    assert step_only.mass == pytest.approx(frustum_mass(0.1, 0.04, 0.04) + frustum_mass(0.05, 0.05, 0.05),
                                           rel=1e-14)


def test_a_stepped_table_simulates_like_the_same_rod_of_cylinders():
    """A striker given as a stepped table hits a bar: the contact force equals that of the striker built from two
    cylinders (an independent description of the same rod), step by step."""
    dt = 0.005 / ri.STEEL.wave_speed              # 5 mm elements: the step at 100 mm falls on a node
    bar = ri.Rod([ri.Cylinder(1.0, 0.05)])
    tabled = ri.loads_model(_table_model([0, 100, 100, 300], [40, 40, 60, 60])).system.rods[0]
    cylinders = ri.Rod([ri.Cylinder(0.1, 0.04), ri.Cylinder(0.2, 0.06)])
    runs = [ri.simulate(ri.System([s, bar], [5.0, 0.0], right="nonreflecting"), steps=400, dt=dt)
            for s in (tabled, cylinders)]
    np.testing.assert_allclose(runs[0].lattice.impedance, runs[1].lattice.impedance, rtol=1e-13)   # rounding
    z = runs[0].lattice.impedance[:60]
    assert np.allclose(z[:20], ri.STEEL.impedance(math.pi / 4 * 0.04 ** 2), rtol=1e-12)
    assert np.allclose(z[20:], ri.STEEL.impedance(math.pi / 4 * 0.06 ** 2), rtol=1e-12)
    np.testing.assert_allclose(runs[0].contact_force, runs[1].contact_force, rtol=0,
                               atol=1e-12 * np.abs(runs[1].contact_force).max())


def test_a_stepped_table_from_a_csv_file(tmp_path):
    (tmp_path / "profile.csv").write_text("# a collar\nx [mm],diameter [mm]\n0,40\n100,40\n100,50\n150,50\n")
    rod = ri.loads_model('[[rods]]\n[[rods.segments]]\nshape = "table"\nfile = "profile.csv"\n' + SIM,
                         base_dir=tmp_path).system.rods[0]
    assert len(rod.segments) == 2
    assert rod.mass == pytest.approx(frustum_mass(0.1, 0.04, 0.04) + frustum_mass(0.05, 0.05, 0.05), rel=1e-14)


def test_a_stepped_model_survives_the_round_trip_through_a_file():
    model = ri.loads_model(_table_model([0, 100, 100, 150], [40, 40, 50, 50]))
    again = ri.loads_model(ri.dump_model(model))
    assert again.system.rods[0] == model.system.rods[0]


@pytest.mark.parametrize("x, message", [
    ([0, 100, 100, 100, 150], r"x\[1\] = 0\.1 appears three times; a step repeats a position once"),
    ([0, 0, 100, 150], r"x\[0\] = x\[1\] = 0\.0 is a step at the first position"),
    ([0, 100, 150, 150], r"x\[2\] = x\[3\] = 0\.15 is a step at the last position"),
    ([0, 100, 50, 150], r"must not decrease; x\[2\] = 0\.05 < x\[1\] = 0\.1"),
])
def test_bad_tables_name_the_key_path(x, message):
    with pytest.raises(ModelError, match=r"^rods\[0\]\.segments\[0\]: TabulatedProfile\.x: " + message):
        ri.loads_model(_table_model(x, [40] * len(x)))


def test_the_python_api():
    """stepped_profile gives the pieces; a TabulatedProfile itself stays strictly increasing and says where steps
    are made."""
    pieces = ri.stepped_profile([0.0, 0.1, 0.1, 0.15], area=[1e-3, 1e-3, 2e-3, 2e-3])
    assert [p.length for p in pieces] == [0.1, pytest.approx(0.05)]
    assert [p.kind for p in pieces] == ["area", "area"]
    assert ri.stepped_profile([0.0, 0.1], diameter=[0.04, 0.05]) == (ri.TabulatedProfile([0.0, 0.1],
                                                                                         diameter=[0.04, 0.05]),)
    with pytest.raises(ValueError, match="strictly increasing; .*rodimpact.stepped_profile"):
        ri.TabulatedProfile([0.0, 0.1, 0.1, 0.15], diameter=[0.04] * 4)
    with pytest.raises(ValueError, match=r"TabulatedProfile.diameter: every value must be > 0, entry 2"):
        ri.stepped_profile([0.0, 0.1, 0.1, 0.15], diameter=[0.04, 0.04, -0.05, 0.05])
