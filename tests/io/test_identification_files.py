"""Identification results on disk (rodimpact.save / rodimpact.load: netCDF and the CSV profile table,
rodimpact/io/identification.py) and the plain CSV head record."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.identify import Anomaly, IdentificationResult
from rodimpact.io.identification import read_head_csv


def result(bands=True):
    z = np.array([4.0e5, 2.8e5, 4.0e5])
    return IdentificationResult(
        np.array([0.0, 1.5, 2.25, 7.0]), z, 0.9 * z if bands else None, 1.1 * z if bands else None,
        anomalies=(Anomaly(1.5, 0.75, -0.3, 0.7, "damage", (1.4, 1.6), (-0.35, -0.25)),), toe=7.0,
        toe_band=(6.9, 7.1), wave_speed=4000.0, matched={"up": (np.arange(4.0), np.ones(4), np.zeros(4))},
        misfit=0.01, method="beta", diagnostics={"warnings": ["w"], "n": np.int64(3)})


@pytest.mark.parametrize("name", ["r.nc", "r.csv"])
def test_round_trip(tmp_path, name):
    r = result()
    ri.save(r, tmp_path / name)
    back = ri.load(tmp_path / name)
    for field in ("depth", "impedance", "lower", "upper"):
        assert np.array_equal(getattr(back, field), getattr(r, field)), field
    assert back.anomalies == r.anomalies and back.toe == r.toe and back.toe_band == r.toe_band
    assert (back.wave_speed, back.misfit, back.method) == (r.wave_speed, r.misfit, r.method)
    assert back.diagnostics == {"warnings": ["w"], "n": 3}
    if name.endswith(".nc"):
        assert list(back.matched) == ["up"] and all(np.array_equal(a, b) for a, b in
                                                    zip(back.matched["up"], r.matched["up"]))
    with pytest.raises(FileExistsError):
        ri.save(r, tmp_path / name)


def test_dataframe_rows_are_elements():
    df = result(bands=False).to_dataframe()
    assert list(df.columns) == ["depth_top [m]", "depth_bottom [m]", "impedance [N s/m]"]
    assert df["depth_bottom [m]"].tolist() == [1.5, 2.25, 7.0]


def test_csv_with_another_unit_is_refused(tmp_path):
    ri.save(result(), tmp_path / "r.csv")
    text = (tmp_path / "r.csv").read_text().replace("impedance [N s/m]", "impedance [kN s/m]")
    (tmp_path / "bad.csv").write_text(text)
    with pytest.raises(ValueError, match=r"bad.csv: line \d+, column 3: expected one of .*got 'impedance \[kN s/m\]'"):
        ri.load(tmp_path / "bad.csv")


def test_head_csv_converts_units(tmp_path):
    p = tmp_path / "head.csv"
    p.write_text("time [ms],force [kN],velocity [mm/s]\n0,-1,250\n0.001,-2,500\n0.002,-3,750\n")
    rec = read_head_csv(p)
    assert np.allclose(rec.time, [0, 1e-6, 2e-6], rtol=1e-15, atol=0)
    assert np.array_equal(rec.force, [-1e3, -2e3, -3e3]) and np.allclose(rec.velocity, [0.25, 0.5, 0.75])


def test_head_csv_with_a_unit_of_the_wrong_dimension_is_refused(tmp_path):
    p = tmp_path / "head.csv"
    p.write_text("time [s],force [m/s],velocity [m/s]\n0,-1,0.25\n1e-6,-2,0.5\n")
    with pytest.raises(ValueError, match=r"header column 2 \(force\): expected a force"):
        read_head_csv(p)


def test_head_csv_of_different_column_lengths_is_refused(tmp_path):
    p = tmp_path / "head.csv"
    p.write_text("time [s],force [N],velocity [m/s]\n0,-1,0.25\n1e-6,-2\n")
    with pytest.raises(ValueError, match="every row must have 3 columns"):
        read_head_csv(p)
