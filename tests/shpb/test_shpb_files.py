"""A reduction as an xarray dataset, a netCDF file (rodimpact.save and rodimpact.load) and a CSV table
(rodimpact.io.save_reduction_csv): units and signs in the attributes, exact round trips, never a silent
overwrite."""

import csv

import numpy as np
import pytest
import xarray as xr
from shpb_synthetic import SPECIMEN, build_shot, ti_bar

import rodimpact as ri
from rodimpact.io import save_reduction_csv
from rodimpact.shpb import ANALYSES, ShpbReduction, find_windows, reduce_shot


@pytest.fixture(scope="module")
def reduction():
    shot = build_shot(ti_bar(), ti_bar("transmitted"), SPECIMEN)
    windows = find_windows(shot.signals, shot.incident_bar, shot.transmitted_bar,
                           reflected=shot.windows.reflected.start)
    return reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=windows)


def test_dataset_has_units_and_signs(reduction):
    ds = reduction.to_xarray()
    assert list(ds["analysis"].values) == list(ANALYSES)
    assert ds["time"].attrs["units"] == "s"
    assert ds["stress"].attrs == {"units": "Pa", "long_name": "engineering stress", "sign": "positive in compression"}
    assert ds["true_strain_rate"].attrs["units"] == "1/s"
    assert ds["reflected"].attrs["sign"] == "positive in tension" and ds["front_force"].attrs["units"] == "N"
    np.testing.assert_array_equal(ds["stress"].sel(analysis="2-wave").values, reduction.two_wave.stress)
    np.testing.assert_array_equal(ds["true_stress"].sel(analysis="3-wave").values, reduction.three_wave.true_stress)
    assert ds.attrs["kind"] == "shpb-reduction" and ds.attrs["windows_given"] == "reflected"


def test_netcdf_round_trip_and_no_overwrite(reduction, tmp_path):
    path = ri.save(reduction, tmp_path / "shot.nc")
    back = ri.load(path)
    assert isinstance(back, ShpbReduction)
    for name in ("time", "incident", "reflected", "transmitted"):
        np.testing.assert_array_equal(getattr(back, name), getattr(reduction, name))
    for a in ANALYSES:
        for q in ("stress", "strain", "strain_rate"):
            np.testing.assert_array_equal(getattr(back.response(a), q), getattr(reduction.response(a), q))
    assert back.windows == reduction.windows and back.specimen == reduction.specimen
    assert back.incident_bar == reduction.incident_bar and back.transmitted_bar == reduction.transmitted_bar
    assert back.equilibrium.equilibrium_time == reduction.equilibrium.equilibrium_time
    before = path.read_bytes()
    with pytest.raises(FileExistsError, match="shot.nc: exists; choose another file name or pass overwrite=True"):
        ri.save(reduction, path)
    assert path.read_bytes() == before
    ri.save(reduction, path, overwrite=True)
    with pytest.raises(TypeError, match="csv: an option of a simulation's results folder; a shpb reduction result"):
        ri.save(reduction, tmp_path / "other.nc", csv=True)
    with pytest.raises(ValueError, match="ds: not a split-Hopkinson-bar reduction"):
        ShpbReduction.from_xarray(xr.Dataset())


def test_csv_table_and_no_overwrite(reduction, tmp_path):
    path = save_reduction_csv(reduction, tmp_path / "shot.csv")
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    header = rows[0]
    assert header[:4] == ["time [s]", "incident [-]", "reflected [-]", "transmitted [-]"]
    assert "3-wave.stress [Pa]" in header and "1-wave.true_strain_rate [1/s]" in header
    data = np.array(rows[1:], dtype=float)
    assert data.shape == (reduction.time.size, len(header))
    np.testing.assert_array_equal(data[:, header.index("2-wave.strain [-]")], reduction.two_wave.strain)
    np.testing.assert_array_equal(data[:, 0], reduction.time)
    path.write_text("my notes\n")
    with pytest.raises(FileExistsError, match="shot.csv: exists"):
        save_reduction_csv(reduction, path)
    assert path.read_text() == "my notes\n"
    save_reduction_csv(reduction, path, overwrite=True)
    with pytest.raises(TypeError, match="reduction: must be a rodimpact.shpb.ShpbReduction"):
        save_reduction_csv(reduction.to_xarray(), tmp_path / "x.csv")
    assert path.read_text().startswith("time [s],")


def test_flow_stress_and_summary(reduction):
    r = reduction.three_wave
    k = int(np.argmax(r.strain >= 0.05))
    w = (0.05 - r.strain[k - 1]) / (r.strain[k] - r.strain[k - 1])
    assert reduction.flow_stress(0.05) == pytest.approx(r.stress[k - 1] + w * (r.stress[k] - r.stress[k - 1]),
                                                        rel=1e-14)
    with pytest.raises(ValueError, match="strain: the 3-wave engineering strain reaches at most"):
        reduction.flow_stress(0.9)
    with pytest.raises(ValueError, match="analysis: must be one of 1-wave, 2-wave, 3-wave"):
        reduction.response("4-wave")
    s = reduction.summary()
    assert s["windows"]["reflected"]["given"] and not s["windows"]["incident"]["given"]
    assert s["analyses"]["3-wave"]["mean_strain_rate_per_s"] == pytest.approx(reduction.mean_strain_rate())
