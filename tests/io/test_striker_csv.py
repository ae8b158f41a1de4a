"""The striker profile CSV (`striker.csv` of `rodimpact synthesize` and `rodimpact design`) read back as a rod by a
model file: the round trip through files reproduces the synthesized force, the file's theta column sets and
checks dt, and files that are not rods get errors naming the key path."""

import numpy as np
import pandas as pd
import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.inverse import academic_example
from rodimpact.io.quantities import ModelError

MODEL = """
[[rods]]
name = "striker"
velocity = "6 m/s"
[rods.elements]
file = "out/striker.csv"
{extra}
[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "1.0 m"
diameter = "50 mm"

[ends]
right = "nonreflecting"

[simulation]
dt = "1.93 us"
steps = 200
"""


def test_synthesize_csv_model_simulate_reproduces_the_synthesized_force(tmp_path, monkeypatch):
    """`rodimpact synthesize` (the init template: thesis academic example 1, 100 elements on a 50 mm steel bar)
    -> out/striker.csv -> a model file's [rods.elements] file -> `rodimpact simulate`: the contact force of the
    simulation, read from its result folder, equals the synthesized window values at every step of every window
    to 1e-12 of the peak."""
    monkeypatch.chdir(tmp_path)
    assert cli.main(["init", "synthesize", "--quiet"]) == 0
    assert cli.main(["synthesize", "synthesis.toml", "-o", "out", "--no-plots", "--quiet"]) == 0
    res = ri.load(tmp_path / "out" / "synthesis.nc")
    assert res.n_feasible == 100
    (tmp_path / "model.toml").write_text(MODEL.format(extra=""))
    assert cli.main(["simulate", "model.toml", "-o", "sim", "--no-plots", "--quiet"]) == 0
    run = ri.load(tmp_path / "sim")
    striker = run.system.rods[0]
    assert striker.native.dt == pytest.approx(1.93e-6, rel=1e-15)          # from the file's theta column
    np.testing.assert_array_equal(striker.native.impedance, res.impedance[::-1])   # impact face on the right
    target = np.repeat(res.window_values, 2)
    assert np.max(np.abs(run.contact_force - target)) < 1e-12 * np.max(np.abs(target))


@pytest.fixture
def profile(tmp_path):
    """A synthesized striker (academic example 1, 20 elements of 1.93 us) written as out/striker.csv."""
    (tmp_path / "out").mkdir()
    res = academic_example(1, n=20).solve()
    res.shape().to_csv(tmp_path / "out" / "striker.csv")
    return res


def _load(tmp_path, extra="", **replace):
    text = MODEL.format(extra=extra)
    for old, new in replace.items():
        text = text.replace(old, new)
    return ri.loads_model(text, base_dir=tmp_path)


def test_the_rod_is_read_left_to_right_with_the_files_dt(tmp_path, profile):
    rod = _load(tmp_path).system.rods[0]
    assert np.array_equal(rod.native.impedance, profile.impedance[::-1])
    assert rod.native.dt == pytest.approx(profile.dt, rel=1e-15)
    # the same dt given explicitly, or as an element length, is accepted
    rod = _load(tmp_path, extra='dt = "1.93 us"').system.rods[0]
    assert rod.native.dt == pytest.approx(1.93e-6, rel=1e-15)
    rod = _load(tmp_path, extra=f"element_length = {1.93e-6 * ri.STEEL.wave_speed!r}").system.rods[0]
    assert rod.native.dt == pytest.approx(1.93e-6, rel=1e-15)


def test_a_dt_that_contradicts_the_files_theta_column_is_refused(tmp_path, profile):
    with pytest.raises(ModelError, match=r"^rods\[0\]\.elements\.dt: gives an element travel time of 2e-06 s, but "
                                         r"the theta column of out/striker\.csv is spaced by 1\.93e-06 s"):
        _load(tmp_path, extra='dt = "2 us"')
    with pytest.raises(ModelError, match=r"^rods\[0\]\.elements\.element_length: .* spaced by 1\.93e-06 s"):
        _load(tmp_path, extra='element_length = "5 mm"')


def test_an_unevenly_spaced_theta_column_is_refused(tmp_path, profile):
    path = tmp_path / "out" / "striker.csv"
    df = pd.read_csv(path, comment="#")
    df.loc[5, "theta [s]"] *= 1.01
    df.to_csv(path, index=False)
    with pytest.raises(ModelError, match=r"^rods\[0\]\.elements\.file: the theta column of out/striker\.csv must be "
                                         r"evenly spaced .* rows 5 and 6 of its data"):
        _load(tmp_path)


def test_files_without_a_theta_column_keep_the_old_rules(tmp_path):
    """A plain impedance column (no theta): dt from [rods.elements] dt or simulation.dt, as before."""
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "striker.csv").write_text("# my striker\nimpedance [kN s/m]\n50\n60\n")
    rod = _load(tmp_path).system.rods[0]
    assert np.array_equal(rod.native.impedance, [50e3, 60e3]) and rod.native.dt == pytest.approx(1.93e-6, rel=1e-15)


def test_a_profile_given_as_a_table_shape_points_to_rods_elements(tmp_path, profile):
    text = ('[[rods]]\n[[rods.segments]]\nshape = "table"\nfile = "out/striker.csv"\n'
            '[simulation]\nsteps = 3\n')
    with pytest.raises(ModelError, match=r"^rods\[0\]\.segments\[0\]\.file: needs a column x and exactly one of "
                                         r"diameter, area; found .*is read as a rod with \[rods\.elements\] "
                                         r"file = 'out/striker\.csv'"):
        ri.loads_model(text, base_dir=tmp_path)


def test_design_and_synthesis_write_one_format(tmp_path):
    """DesignResult.to_csv writes through StrikerShape.to_csv: same columns, same orientation, velocity noted."""
    dt = 2e-6
    bar = ri.Rod.from_impedance([1.27e4] * 6, dt)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -60e3 * np.sin(np.pi * t / (16 * dt)), duration=16 * dt)
    d = ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 12.0, n=8, dt=dt,
                  limits=ri.StrikerLimits(impedance_bounds=(500.0, 1e5)),
                  search=ri.SearchOptions(max_iterations=3, starts=1))
    d.to_csv(tmp_path / "design.csv")
    d.shape().to_csv(tmp_path / "shape.csv")
    a = pd.read_csv(tmp_path / "design.csv", comment="#")
    b = pd.read_csv(tmp_path / "shape.csv", comment="#")
    pd.testing.assert_frame_equal(a, b)
    np.testing.assert_array_equal(a["impedance [N s/m]"], d.impedance[::-1])
    assert "impact velocity 12.0 m/s" in (tmp_path / "design.csv").read_text()
