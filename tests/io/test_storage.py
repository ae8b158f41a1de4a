"""One way to save and load every kind of result (issue 21): ``rodimpact.save(result, path)`` and
``rodimpact.load(path)`` for simulation, synthesis and design results and sweep datasets; identical arrays after
the round trip, the kind recognised from the file or folder, nothing a user saved replaced silently, and the old
methods gone with a message that says what replaces them."""

import importlib.util

import numpy as np
import pytest
import xarray as xr

import rodimpact as ri
from rodimpact.design.result import DesignResult
from rodimpact.inverse import academic_example
from rodimpact.inverse.struck import Location
from rodimpact.io.results import OutputExistsError

ENGINES = ["scipy"] + [e for e, mod in (("netcdf4", "netCDF4"), ("h5netcdf", "h5py")) if importlib.util.find_spec(mod)]


@pytest.fixture(scope="module")
def simulation():
    rods = [ri.Rod.from_impedance([4e4] * 10, dt=1e-6, name="striker"), ri.Rod.from_impedance([6e4] * 30, dt=1e-6)]
    return ri.simulate(rods, velocities=[2.0, 0.0], steps=60, outputs=ri.Outputs(probes=[ri.Probe("SG", 1, 0.05)]))


@pytest.fixture(scope="module")
def synthesis():
    return academic_example(1, n=20).solve()


@pytest.fixture(scope="module")
def design():
    """An efficiency design observed at a position inside the struck system, of titanium, with diagnostics that
    hold arrays and integer keys: every optional part of the design layout."""
    n, steps = 4, 12
    return DesignResult(
        impedance=np.array([3e4, 2.5e4, 2.5e4, 1e4]), striker_velocity=9.5, dt=2e-6, objective="efficiency",
        time=2e-6 * np.arange(steps), achieved=np.linspace(-5e4, 0.0, steps), face_force=np.linspace(-6e4, 0, steps),
        target=np.zeros(0), compared=np.zeros(0, dtype=np.int64), window_values=np.zeros(0), misfit=None,
        efficiency=0.81, constraint_report={"elements_at_lower_bound": [4], "mass_active": "inactive"},
        iterations=7, wall_time=0.25, location=Location(0.5, 0.4998, 0, 0.4998, 50, 49), quantity="incident",
        material=ri.TITANIUM_TI6AL4V,
        diagnostics={"convergence": [[0.5, 0.7, 0.81]], "lengths": {n: 0.81}, "weights": np.ones(3)})


@pytest.fixture(scope="module")
def study():
    bar = ri.Rod([ri.Cylinder(0.5, 0.02)])

    def build(length, velocity):
        return dict(rods=[ri.Rod([ri.Cylinder(length, 0.02)]), bar], velocities=[velocity, 0.0], duration=3e-4,
                    dt=0.01 / ri.STEEL.wave_speed)

    return ri.sweep(build, {"length": [0.1, 0.2], "velocity": ["4 m/s", "6 m/s"]}, workers=1)


def test_a_simulation_round_trips_through_a_folder(simulation, tmp_path):
    out = ri.save(simulation, tmp_path / "run")
    assert out.is_dir() and (out / "result.nc").is_file()
    for path in (out, out / "result.nc"):          # the folder, or the result file in it (model.toml beside it)
        back = ri.load(path)
        assert isinstance(back, ri.SimulationResult) and back.system is not None
        assert np.array_equal(back.contact_force, simulation.contact_force)
        assert np.array_equal(back.probe("SG").strain, simulation.probe("SG").strain)
        assert np.array_equal(back.energy.total, simulation.energy.total)
    with pytest.raises(OutputExistsError, match="exists and is not empty"):
        ri.save(simulation, out)
    ri.save(simulation, out, overwrite=True)        # a folder rodimpact wrote may be replaced


@pytest.mark.parametrize("engine", ENGINES)
def test_a_synthesis_round_trips(synthesis, tmp_path, engine):
    path = ri.save(synthesis, tmp_path / "syn.nc", engine=engine)
    back = ri.load(path)
    assert isinstance(back, ri.SynthesisResult)
    for name in ("impedance", "reflection", "transmission_factor", "force_difference", "force_reserve",
                 "amplitude_growth", "error_estimate", "window_values", "face_velocity"):
        assert np.array_equal(getattr(back, name), getattr(synthesis, name)), name
    assert (back.dt, back.striker_velocity, back.n_requested, back.material, back.failure) == \
        (synthesis.dt, synthesis.striker_velocity, synthesis.n_requested, synthesis.material, synthesis.failure)


@pytest.mark.parametrize("engine", ENGINES)
def test_a_design_round_trips(design, tmp_path, engine):
    back = ri.load(ri.save(design, tmp_path / "design.nc", engine=engine))
    assert isinstance(back, DesignResult)
    for name in ("impedance", "time", "achieved", "face_force", "target", "compared", "window_values"):
        a, b = getattr(back, name), getattr(design, name)
        assert a.dtype == b.dtype and np.array_equal(a, b), name
    for name in ("striker_velocity", "dt", "objective", "misfit", "efficiency", "constraint_report", "iterations",
                 "wall_time", "location", "quantity", "material"):
        assert getattr(back, name) == getattr(design, name), name
    assert back.diagnostics == {"convergence": [[0.5, 0.7, 0.81]], "lengths": {"4": 0.81}, "weights": [1.0] * 3}
    assert back.convergence == design.convergence and back.struck is None
    with pytest.raises(ValueError, match="verify: this result carries no struck system"):
        back.verify()


@pytest.mark.parametrize("engine", ENGINES)
def test_a_sweep_round_trips(study, tmp_path, engine):
    back = ri.load(ri.save(study, tmp_path / "study.nc", engine=engine))
    assert isinstance(back, xr.Dataset)
    xr.testing.assert_identical(back, study)
    assert back["velocity"].attrs["units"] == "m/s"


def test_nothing_saved_is_replaced_silently(simulation, synthesis, design, study, tmp_path):
    for i, result in enumerate((synthesis, design, study)):
        path = tmp_path / f"r{i}.nc"
        path.write_bytes(b"precious")
        with pytest.raises(FileExistsError, match=rf"r{i}.nc: exists; .* overwrite=True"):
            ri.save(result, path)
        assert path.read_bytes() == b"precious"
        ri.save(result, path, overwrite=True)
        assert type(ri.load(path)) is type(result)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep")
    with pytest.raises(OutputExistsError, match="holds files rodimpact did not write"):
        ri.save(simulation, mine, overwrite=True)
    assert [p.name for p in mine.iterdir()] == ["notes.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["mine", "r0.nc", "r1.nc", "r2.nc"]    # no temp files


def test_load_recognises_the_output_folders(synthesis, design, study, tmp_path):
    """A folder of rodimpact synthesize, design or sweep is recognised by the result file it holds."""
    for result, name in ((synthesis, "synthesis.nc"), (design, "design.nc"), (study, "sweep.nc")):
        folder = tmp_path / name.removesuffix(".nc")
        folder.mkdir()
        ri.save(result, folder / name)
        assert type(ri.load(folder)) is type(result)
    (tmp_path / "other").mkdir()
    ri.save(study, tmp_path / "other" / "synthesis.nc")       # a sweep under a synthesis's name
    with pytest.raises(ValueError, match=r"synthesis.nc: not a complete rodimpact synthesis result \(it holds a sweep"):
        ri.load(tmp_path / "other")


def test_foreign_netcdf_files_and_objects_are_refused(design, tmp_path):
    xr.Dataset({"x": ("a", np.arange(3.0))}).to_netcdf(tmp_path / "x.nc", engine="scipy")
    with pytest.raises(ValueError, match="x.nc: a netCDF file, but no rodimpact result"):
        ri.load(tmp_path / "x.nc")
    with pytest.raises(TypeError, match="an xarray.Dataset that rodimpact.sweep did not make"):
        ri.save(xr.Dataset({"x": ("a", np.arange(3.0))}), tmp_path / "y.nc")
    with pytest.raises(TypeError, match="result: must be a SimulationResult, .* got list"):
        ri.save([1.0], tmp_path / "z.nc")
    with pytest.raises(TypeError, match="csv: an option of a simulation's results folder; a design result is saved"):
        ri.save(design, tmp_path / "d.nc", csv=False)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.nc"]


def test_the_old_methods_say_what_replaces_them(synthesis, design):
    with pytest.raises(AttributeError, match=r"SynthesisResult.save: removed; save every result with "
                                             r"rodimpact.save\(result, path\)"):
        synthesis.save("x.nc")
    with pytest.raises(AttributeError, match=r"SynthesisResult.load: removed; read a saved result with "
                                             r"rodimpact.load\(path\)"):
        ri.SynthesisResult.load("x.nc")
    with pytest.raises(AttributeError, match=r"DesignResult.save: removed"):
        design.save("x.nc")
    assert not hasattr(design, "save") and not hasattr(ri.SynthesisResult, "load")
