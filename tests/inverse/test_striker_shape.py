"""Impedance -> striker geometry, export and the rods handed to the direct solver."""

import math

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.inverse import academic_example, impedance_to_shape


def test_diameters_by_hand():
    # steel: rho c = 7840 * sqrt(210e9/7840) = 40.575e6 kg/(m^2 s); Z = 79.67 kN s/m <-> d = 50 mm
    rc = math.sqrt(210e9 * 7840.0)
    z50 = math.pi * 0.05**2 / 4 * rc
    sh = impedance_to_shape([z50, 4 * z50], 1e-6)
    np.testing.assert_allclose(sh.outer_diameter, [0.05, 0.10], rtol=1e-14)
    assert sh.diameter_ratio == pytest.approx(2.0)
    bored = impedance_to_shape([z50], 1e-6, bore=0.03)
    # area of a 50 mm disc = annulus between d_i = 30 mm and d_o = sqrt(50^2 + 30^2) mm
    assert bored.outer_diameter[0] == pytest.approx(math.sqrt(0.05**2 + 0.03**2), rel=1e-14)
    assert sh.element_length == pytest.approx(math.sqrt(210e9 / 7840.0) * 1e-6)
    assert sh.mass == pytest.approx(1e-6 * 5 * z50)          # dt * sum Z
    assert sh.length == pytest.approx(2 * sh.element_length)


def test_impractical_ratio_warns():
    with pytest.warns(UserWarning, match="outer diameter varies by a factor 11"):
        sh = impedance_to_shape([1e4, 121e4], 1e-6)
    assert not sh.practical
    sh = impedance_to_shape([1e4, 121e4], 1e-6, max_diameter_ratio=12)
    assert sh.practical


def test_bad_shape_input():
    with pytest.raises(ValueError, match="impedance: every entry must be > 0"):
        impedance_to_shape([1e4, -1.0], 1e-6)
    with pytest.raises(ValueError, match="bore: must be >= 0"):
        impedance_to_shape([1e4], 1e-6, bore=-0.01)


def test_csv_export(tmp_path):
    """One row per element, listed left to right (impact face last), full precision; the comment lines are plain
    '# ...' lines that pandas skips with comment='#', and they state the orientation and dt."""
    import pandas as pd

    res = academic_example(1, n=20).solve()
    sh = res.shape(bore=0.01)
    path = sh.to_csv(tmp_path / "striker.csv", note="impact velocity 6 m/s")
    lines = path.read_text().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    assert lines[:len(comments)] == comments and len(comments) == 4       # all comments first, none quoted
    assert "LEFT TO RIGHT" in comments[0] and "impact face last" in comments[0]
    assert f"dt = {res.dt!r} s" in comments[1] and comments[2] == "# impact velocity 6 m/s"
    df = pd.read_csv(path, comment="#")
    assert list(df.columns) == ["element_from_face", "s_start [m]", "s_end [m]", "theta [s]", "impedance [N s/m]",
                                "area [m^2]", "outer_diameter [m]", "inner_diameter [m]"]
    assert df.shape == (20, 8)
    face_first = df.iloc[::-1]
    np.testing.assert_array_equal(face_first["element_from_face"], np.arange(1, 21))
    np.testing.assert_array_equal(face_first["impedance [N s/m]"], res.impedance)     # written with full precision
    np.testing.assert_array_equal(face_first["outer_diameter [m]"], sh.outer_diameter)
    np.testing.assert_allclose(face_first["theta [s]"], res.dt * np.arange(20), rtol=1e-15)
    assert face_first["s_start [m]"].iloc[0] == 0.0 and face_first["s_end [m]"].iloc[-1] == pytest.approx(sh.length)
    assert np.all(df["inner_diameter [m]"] == 0.01)
    with pytest.raises(ValueError, match="note: must be a single line"):
        sh.to_csv(tmp_path / "other.csv", note="two\nlines")


@pytest.mark.parametrize("bore", [0.0, 0.012])
def test_geometric_rod_reproduces_the_synthesized_force(bore):
    """The shape's geometric Rod (cylinders/tubes, impact face on the right) and the result's exact
    impedance-level Rod give the same impact force in the direct solver."""
    prob = academic_example(1, n=30)
    res = prob.solve()
    geo = res.shape(bore=bore).to_rod()
    assert geo.length == pytest.approx(res.length)
    assert geo.mass == pytest.approx(res.mass, rel=1e-12)
    assert geo.impedance(geo.length * 0.999) == pytest.approx(res.impedance[0], rel=1e-12)   # impact face right
    exact = res.to_rod()
    assert exact.native is not None and np.array_equal(exact.native.impedance, res.impedance[::-1])
    forces = []
    for rod in (geo, exact):
        sim = ri.simulate(ri.System([rod, prob.struck], [6.0, 0.0], right="nonreflecting"), steps=60, dt=prob.dt)
        forces.append(sim.contact_force)
    np.testing.assert_allclose(forces[0], forces[1], rtol=1e-11)
    np.testing.assert_allclose(forces[1], np.repeat(res.window_values, 2), rtol=1e-13)


def test_exports_never_overwrite_silently(tmp_path):
    """A saved profile or result is refused as a target unless overwrite=True; the old file stays intact."""
    res = academic_example(1).solve()
    csv_path = res.shape().to_csv(tmp_path / "striker.csv")
    before = csv_path.read_text()
    with pytest.raises(FileExistsError, match="striker.csv: exists"):
        res.shape().to_csv(csv_path)
    assert csv_path.read_text() == before
    res.shape().to_csv(csv_path, overwrite=True)
    nc = ri.save(res, tmp_path / "synthesis.nc")
    with pytest.raises(FileExistsError, match="synthesis.nc: exists"):
        ri.save(res, nc)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["striker.csv", "synthesis.nc"]   # no temp files left
