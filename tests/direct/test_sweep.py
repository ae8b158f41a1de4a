"""rodimpact.sweep: a grid of simulate() runs in parallel threads, collected into an xarray Dataset."""

import numpy as np
import pytest

import rodimpact as ri

C = ri.STEEL.wave_speed
DT = 0.001 / C                       # 1 mm elements
AREA = np.pi * 0.02**2
Z = ri.STEEL.impedance(AREA)


def equal_bars(length, velocity):
    """A striker of the bar's section on a long bar with a non-reflecting end: closed form -Z v / 2 for 2 L / c."""
    return dict(rods=[ri.Rod([ri.Cylinder(length, 0.04)]), ri.Rod([ri.Cylinder(1.0, 0.04)])],
                velocities=[velocity, 0.0], duration=1e-3, dt=DT, right="nonreflecting")


GRID = {"length": [0.1, 0.2, 0.3], "velocity": [3.0, 5.0]}


def test_sweep_against_the_closed_form():
    ds = ri.sweep(equal_bars, GRID, workers=2)
    assert ds["peak_contact_force"].dims == ("length", "velocity")
    length, velocity = np.meshgrid(GRID["length"], GRID["velocity"], indexing="ij")
    np.testing.assert_allclose(ds["peak_contact_force"], -Z * velocity / 2, rtol=1e-12)
    np.testing.assert_allclose(ds["contact_time"], 2 * length / C, rtol=1e-12)
    np.testing.assert_allclose(ds["energy_transfer"], 1.0, rtol=1e-12)
    np.testing.assert_allclose(ds["striker_final_velocity"], 0.0, atol=1e-12)
    assert ds["peak_contact_force"].attrs["units"] == "N" and ds.attrs["points"] == 6


def test_each_point_is_the_run_simulate_would_do_alone():
    metrics = {"peak": lambda r: r.contact_force.min(), "last_force": lambda r: r.contact_force[-1],
               "velocity_sum": lambda r: r.final_velocity.sum()}
    serial = ri.sweep(equal_bars, GRID, metrics, workers=1)
    threaded = ri.sweep(equal_bars, GRID, metrics, workers=2)
    for i, length in enumerate(GRID["length"]):
        for j, velocity in enumerate(GRID["velocity"]):
            res = ri.simulate(ri.Problem.of(**equal_bars(length, velocity)))
            for name, f in metrics.items():
                assert serial[name].values[i, j] == f(res) == threaded[name].values[i, j]


def test_build_may_return_a_model():
    from rodimpact.examples import load_example

    ds = ri.sweep(lambda scale: load_example("first-example"), {"scale": [1]}, workers=1)
    alone = load_example("first-example").simulate()
    assert ds["peak_contact_force"].values[0] == alone.junction_events[0].min_force


def test_models_are_batched_and_names_may_be_key_paths():
    """A Model without probes and snapshots is batched like a dict of simulate() arguments; grid names need not be
    identifiers when build takes **point (as the command line's sweep over model-file keys does)."""
    from dataclasses import replace

    from rodimpact.examples import load_example

    base = load_example("first-example")
    bare = replace(base, probes=(), output=replace(base.output, snapshot_times=(), snapshot_count=None))

    def at(**point):
        return replace(bare, system=replace(bare.system, velocities=(point["rods[0].velocity"], 0.0)))

    ds = ri.sweep(at, {"rods[0].velocity": [5.0, 10.0]}, workers=1)
    assert ds.attrs["runner"] == "simulate_batch" and ds["peak_contact_force"].dims == ("rods[0].velocity",)
    alone = load_example("first-example").simulate()
    assert ds["peak_contact_force"].values[1] == alone.junction_events[0].min_force


@pytest.mark.parametrize("kwargs, error, match", [
    (dict(build="bars", grid=GRID), TypeError, "build: must be a function"),
    (dict(grid={}), ValueError, "grid: must be a non-empty mapping"),
    (dict(grid={"length": []}), ValueError, r"grid\['length'\]: must be a non-empty 1-d list"),
    (dict(grid={"length": 0.2}), ValueError, r"grid\['length'\]: must be a non-empty 1-d list"),
    (dict(grid={"length": [0.1, float("nan")]}), ValueError, r"grid\['length'\]: values must be finite"),
    (dict(grid={"length": [0.1, 0.1]}), ValueError, "must not repeat"),
    (dict(grid={"length": [None]}), TypeError, "values must be numbers or strings"),
    (dict(grid={"rods/0": [1]}), ValueError, "parameter names must be non-empty strings without '/'"),
    (dict(grid=GRID, metrics={"x": 3}), TypeError, r"metrics\['x'\]: must be a function"),
    (dict(grid=GRID, workers=0), ValueError, "workers: must be an integer >= 1"),
])
def test_bad_arguments(kwargs, error, match):
    kwargs = {"build": equal_bars, **kwargs}
    with pytest.raises(error, match=match):
        ri.sweep(kwargs.pop("build"), kwargs.pop("grid"), **kwargs)


def test_progress_off_a_terminal_is_a_line_at_every_tenth(capsys):
    ri.sweep(equal_bars, {"length": [0.1, 0.2], "velocity": [3.0]}, workers=1, progress=True, batch=False)
    lines = capsys.readouterr().err.splitlines()
    assert lines[0].startswith("sweep:  50% (1 of 2 runs") and lines[1].startswith("sweep: 100% (2 of 2 runs")


def test_failures_name_the_grid_point():
    with pytest.raises(ValueError, match=r"sweep at length = 0.1, velocity = 3.0: .*metrics\['f'\]: must return "
                                         r"one real number"):
        ri.sweep(equal_bars, GRID, {"f": lambda r: r.contact_force}, workers=1)
    with pytest.raises(ValueError, match=r"sweep at length = -0.1: ValueError: Cylinder.length: must be > 0"):
        ri.sweep(lambda length: equal_bars(length, 1.0), {"length": [-0.1]}, workers=1)
    with pytest.raises(ValueError, match="build: must return the keyword arguments"):
        ri.sweep(lambda length: [length], {"length": [0.1]}, workers=1)
    single = dict(rods=[ri.Rod([ri.Cylinder(0.2, 0.04)])], velocities=[1.0], duration=1e-4)
    with pytest.raises(ValueError, match="the default metrics need a junction"):
        ri.sweep(lambda k: single, {"k": [1]}, workers=1)


def test_metric_names_are_checked_before_any_run():
    calls = []

    def counting(length, velocity):
        calls.append(length)
        return equal_bars(length, velocity)

    with pytest.raises(ValueError, match=r"metrics: the names \['velocity'\] are also grid parameters"):
        ri.sweep(counting, GRID, {"velocity": lambda r: 1.0})
    with pytest.raises(ValueError, match="without '/'"):
        ri.sweep(counting, GRID, {"force/area": lambda r: 1.0})
    assert calls == []


def test_a_striker_at_rest_and_failing_points():
    ds = ri.sweep(equal_bars, {"length": [0.2], "velocity": [0.0, 2.0]}, workers=1)
    assert np.isnan(ds["energy_transfer"].values[0, 0]) and ds["energy_transfer"].values[0, 1] == pytest.approx(1.0)
    assert ds["peak_contact_force"].values[0, 0] == 0.0
    import json

    ds = ri.sweep(lambda length: equal_bars(length, 3.0), {"length": [0.2, -0.1, 0.3]}, errors="nan", workers=2)
    assert np.isnan(ds["contact_time"].values[1]) and not np.isnan(ds["contact_time"].values[[0, 2]]).any()
    (failure,) = json.loads(ds.attrs["failures"])
    assert failure["point"] == {"length": -0.1} and "Cylinder.length: must be > 0" in failure["error"]
    with pytest.raises(ValueError, match="errors: must be 'raise' or 'nan'"):
        ri.sweep(equal_bars, GRID, errors="skip")
