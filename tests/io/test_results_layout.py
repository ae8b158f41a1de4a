"""One xarray layout (issue 14, item 8): ``SimulationResult.to_xarray()`` and ``result.nc`` are the same dataset,
with ``probe``, ``junction``, ``end`` and time coordinates, so that ``.sel(probe="SG1")`` works on both; the
columns of ``to_dataframe()`` are its variables per coordinate; result folders of format 2 (probe names in a JSON
attribute, written by rodimpact before the change: tests/data/result-format2) still load."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import rodimpact as ri
from rodimpact.io.model import load_model
from rodimpact.io import load, save

OLD = Path(__file__).resolve().parents[1] / "data" / "result-format2"
ENGINES = ["scipy"] + [e for e, mod in (("netcdf4", "netCDF4"), ("h5netcdf", "h5py")) if importlib.util.find_spec(mod)]


@pytest.fixture(scope="module")
def result():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)], name="striker"), ri.Rod([ri.Cylinder(0.3, 0.05)], name="adapter"),
            ri.Rod([ri.Cylinder(0.6, 0.04)], name="bar")]
    return ri.simulate(ri.System(rods, [5.0, 0.0, 0.0], junctions=[ri.Contact(), ri.Contact()]), duration=0.3e-3,
                       dt=1e-6, outputs=ri.Outputs(probes=[ri.Probe("SG1", 2, 0.1), ri.Probe("SG 2", 2, 0.3)],
                                                   snapshot_every=50))


def open_nc(path):
    return xr.load_dataset(path, engine="scipy" if path.read_bytes()[:3] == b"CDF" else "h5netcdf")


def check_selections(ds, res):
    np.testing.assert_array_equal(ds.probe_force.sel(probe="SG1").values, res.probe("SG1").force)
    np.testing.assert_array_equal(ds.probe_strain.sel(probe="SG 2").values, res.probe("SG 2").strain)
    assert float(ds.probe_node_position.sel(probe="SG1")) == res.probe("SG1").node_position
    np.testing.assert_array_equal(ds.junction_force.sel(junction=1).values, res.junction_force[1])
    np.testing.assert_array_equal(ds.end_velocity.sel(end="right").values, res.end_velocity["right"])
    np.testing.assert_array_equal(ds.kinetic_energy.sel(rod=2).values, res.energy.kinetic[2])
    k = 3
    t = res.snapshots.time[k]
    np.testing.assert_array_equal(ds.force_field.sel(snapshot_time=t).values, res.snapshots.force[:, k])
    np.testing.assert_array_equal(ds.node_x.values, res.lattice.node_x)
    assert list(ds.probe.values) == ["SG1", "SG 2"] and list(ds["end"].values) == ["left", "right"]
    assert list(ds.junction.values) == [0, 1]


def test_to_xarray_has_coordinates_to_select_with(result):
    ds = result.to_xarray()
    check_selections(ds, result)
    assert ds.attrs["format_version"] == 3
    assert not [v for v in ds.data_vars if v.startswith("probe_SG")]        # no per-probe variables


@pytest.mark.parametrize("engine", ENGINES)
def test_result_file_has_the_layout_of_to_xarray(result, tmp_path, engine):
    save(result, tmp_path / "out", engine=engine, csv=False)
    ds = open_nc(tmp_path / "out" / "result.nc")
    check_selections(ds, result)
    mem = result.to_xarray()
    assert set(ds.data_vars) == set(mem.data_vars) and set(ds.coords) == set(mem.coords)
    for name in mem.variables:
        assert ds[name].dims == mem[name].dims, name
        assert ds[name].attrs.get("units") == mem[name].attrs.get("units"), name


def test_single_rod_has_no_junction_coordinate(tmp_path):
    res = ri.simulate(ri.System([ri.Rod([ri.Cylinder(0.5, 0.04)])], [1.0], right="fixed"), steps=50, dt=1e-6)
    ds = res.to_xarray()
    assert "junction" not in ds.dims and "probe" not in ds.dims
    np.testing.assert_array_equal(ds.end_force.sel(end="right").values, res.end_force["right"])


def test_dataframe_columns_are_the_dataset_variables_per_coordinate(result):
    ds, df = result.to_xarray(), result.to_dataframe()
    np.testing.assert_array_equal(df.index.values, ds.time.values)
    for name in ("SG1", "SG 2"):
        for q in ("force", "velocity", "displacement", "strain"):
            np.testing.assert_array_equal(df[f"{name}_{q}"].values, ds[f"probe_{q}"].sel(probe=name).values)
    for j in (0, 1):
        np.testing.assert_array_equal(df[f"contact_force_{j}"].values, ds.junction_force.sel(junction=j).values)
    for side in ("left", "right"):
        np.testing.assert_array_equal(df[f"{side}_end_force"].values, ds.end_force.sel(end=side).values)


def test_format_2_folder_still_loads():
    """The folder was written by rodimpact at commit ffe50d1 (format 2, probe names in a JSON attribute, probe rows
    in that order): loading it maps every name to its row of the file, and the arrays are those of a fresh run of
    its model.toml (to 1e-12 of the peak force: solver versions may differ in the last bits)."""
    import json

    old = open_nc(OLD / "result.nc")
    assert old.attrs["format_version"] == 2 and "probe" not in old.coords
    names = json.loads(old.attrs["probe_names"])
    assert names == ["SG1", "SG2"]
    back = load(OLD)
    assert list(back.probes) == names
    for i, name in enumerate(names):
        for q in ("force", "velocity", "displacement", "strain"):
            np.testing.assert_array_equal(getattr(back.probe(name), q), old[f"probe_{q}"].values[i])
        assert back.probe(name).node_position == float(old.probe_node_position.values[i])
    np.testing.assert_array_equal(back.contact_force, old.junction_force.values[0])
    fresh = load_model(OLD / "model.toml").simulate()
    scale = np.max(np.abs(fresh.contact_force))
    for name in names:
        np.testing.assert_allclose(back.probe(name).force, fresh.probe(name).force, rtol=0, atol=1e-12 * scale)
        assert back.probe(name).node_position == fresh.probe(name).node_position
    np.testing.assert_allclose(back.contact_force, fresh.contact_force, rtol=0, atol=1e-12 * scale)
    columns = [int(np.flatnonzero(fresh.snapshots.time == t)[0]) for t in back.snapshots.time]
    np.testing.assert_allclose(back.snapshots.force, fresh.snapshots.force[:, columns], rtol=0, atol=1e-12 * scale)
    # and in the new layout from then on
    np.testing.assert_array_equal(back.to_xarray().probe_force.sel(probe="SG2").values, back.probe("SG2").force)


def test_a_newer_format_is_refused(result, tmp_path):
    save(result, tmp_path / "out", engine="scipy", csv=False)
    ds = open_nc(tmp_path / "out" / "result.nc")
    ds.attrs["format_version"] = 4
    ds.to_netcdf(tmp_path / "out" / "result.nc", engine="scipy")
    with pytest.raises(ValueError, match="written by a newer rodimpact"):
        load(tmp_path / "out")
