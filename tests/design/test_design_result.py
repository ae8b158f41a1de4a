"""DesignResult: verify, to_rod, shape, the striker CSV read back by a model file, xarray/netCDF export; the
mass and velocity options and weights."""

import numpy as np
import pytest

import rodimpact as ri

DT = 2e-6
ZS = 1.27e4


def _half_sine(n):
    return ri.inverse.ForceTarget.from_callable(lambda t: -60e3 * np.sin(np.pi * t / (2 * n * DT)),
                                                duration=2 * n * DT)


@pytest.fixture(scope="module")
def small():
    bar = ri.Rod.from_impedance([ZS] * 6, DT)
    return ri.design(_half_sine(8), ri.System.struck(bar, far_end="nonreflecting"), 12.0, n=8, dt=DT,
                     limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                     search=ri.SearchOptions(max_iterations=10, starts=1))


def test_verify_reproduces_the_design_run(small):
    v = small.verify()
    assert v.max_deviation < 1e-12
    assert v.misfit == pytest.approx(small.misfit, rel=1e-10)
    # the misfit by hand: every step of every window against its window value
    x = _half_sine(8).window_values(8, DT)
    y = small.face_force[:16]
    assert small.misfit == pytest.approx(np.linalg.norm(y - np.repeat(x, 2)) / np.linalg.norm(np.repeat(x, 2)),
                                         rel=1e-12)


def test_rod_shape_and_mass(small):
    rod = small.to_rod()
    assert np.allclose(rod.native.impedance, small.impedance[::-1], rtol=0, atol=0)
    s = small.shape(ri.STEEL, bore=0.002)
    area = small.impedance / (ri.STEEL.density * ri.STEEL.wave_speed)
    assert np.allclose(s.outer_diameter, np.sqrt(4 * area / np.pi + 0.002 ** 2), rtol=1e-12)
    assert small.mass == pytest.approx(DT * small.impedance.sum(), rel=1e-15)
    assert "DesignResult(match" in repr(small)


def test_striker_csv_runs_in_a_model_file(small, tmp_path):
    """The exported CSV, read by [rods.elements] file = ..., gives the same contact force as the design."""
    small.to_csv(tmp_path / "striker.csv")
    (tmp_path / "model.toml").write_text(f'''
[[rods]]
name = "striker"
velocity = "12 m/s"
[rods.elements]
dt = "{DT} s"
file = "striker.csv"

[[rods]]
name = "bar"
velocity = "0 m/s"
[rods.elements]
dt = "{DT} s"
impedance = {[ZS] * 6}

[ends]
right = "nonreflecting"

[simulation]
dt = "{DT} s"
steps = {small.time.size}
''')
    model = ri.load_model(tmp_path / "model.toml")
    res = ri.simulate(model.system, steps=model.steps, dt=model.dt)
    assert np.allclose(res.junction_force[0], small.face_force, rtol=0, atol=1e-9 * np.abs(small.face_force).max())


def test_xarray_and_netcdf(small, tmp_path):
    ds = small.to_xarray()
    assert np.array_equal(ds["impedance"].values, small.impedance)
    assert ds.attrs["misfit"] == small.misfit
    p = ri.save(small, tmp_path / "design.nc")
    with pytest.raises(FileExistsError):
        ri.save(small, p)
    back = ri.load(p)                       # the arrays, the report and the diagnostics of a real design
    for name in ("impedance", "time", "achieved", "face_force", "target", "compared", "window_values"):
        assert np.array_equal(getattr(back, name), getattr(small, name)), name
    assert (back.misfit, back.constraint_report, back.material, back.location) == \
        (small.misfit, small.constraint_report, small.material, small.location)
    assert back.convergence == small.convergence


def test_mass_and_velocity_bounds():
    """A prescribed mass is met exactly and reported; a free velocity stays inside its bounds."""
    bar = ri.Rod.from_impedance([ZS] * 6, DT)
    m = 8 * DT * 4000.0
    d = ri.design(_half_sine(8), ri.System.struck(bar, far_end="nonreflecting"), 10.0, n=8, dt=DT,
                  limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5), mass=m, velocity_bounds=(6.0, 14.0)),
                  search=ri.SearchOptions(max_iterations=10, starts=1))
    assert d.mass == pytest.approx(m, rel=1e-12)
    assert d.constraint_report["mass_active"] == "prescribed"
    assert 6.0 <= d.striker_velocity <= 14.0
    assert d.constraint_report["velocity_active"] in ("lower", "upper", "inactive")
    assert d.verify().misfit == pytest.approx(d.misfit, rel=1e-9)


def test_weights_change_the_misfit_definition():
    """Zero weight on the second half: the reported misfit only measures the first half."""
    bar = ri.Rod.from_impedance([ZS] * 6, DT)
    w = np.r_[np.ones(4), np.zeros(4)]
    d = ri.design(ri.MatchObjective(_half_sine(8), weights=w), ri.System.struck(bar, far_end="nonreflecting"), 12.0,
                  n=8, dt=DT, limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                  search=ri.SearchOptions(max_iterations=5, starts=1))
    x = np.repeat(_half_sine(8).window_values(8, DT), 2)[:8]
    assert d.misfit == pytest.approx(np.linalg.norm(d.face_force[:8] - x) / np.linalg.norm(x), rel=1e-12)
