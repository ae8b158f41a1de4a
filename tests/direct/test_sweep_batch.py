"""sweep() over strikers and velocities runs as simulate_batch batches, in-process or on an executor / Dask,
and returns the Dataset of one simulate() run per point."""

import multiprocessing
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import distributed
import numpy as np
import pytest
import xarray as xr

import rodimpact as ri

C = ri.STEEL.wave_speed
DT = 0.002 / C                      # 2 mm elements


def stepped(length, velocity, neck=0.03):
    """A stepped striker (thin front, thick back) on a bar with a bit-rock far end."""
    striker = ri.Rod([ri.Cylinder(length / 2, 0.05), ri.Cylinder(length / 2, neck)])
    return dict(rods=[striker, ri.Rod([ri.Cylinder(0.4, 0.04)])], velocities=[velocity, 0.0], duration=6e-4, dt=DT,
                right=ri.BitRockEnd(5e8, 2e9))


GRID = {"length": [0.1, 0.16, 0.2], "velocity": [3.0, 5.0, 7.0], "neck": [0.02, 0.03]}


def same(a, b):
    """Identical Datasets apart from how they were computed (runner, executor, wall time)."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        for key in ("runner", "executor", "wall_time_s"):
            ds.attrs.pop(key)
    xr.testing.assert_identical(a, b)


def test_batched_sweep_returns_the_dataset_of_the_per_point_runs():
    batched = ri.sweep(stepped, GRID)
    per_point = ri.sweep(stepped, GRID, batch=False)
    assert batched.attrs["runner"] == "simulate_batch" and per_point.attrs["runner"] == "simulate"
    same(batched, per_point)
    assert np.isfinite(batched["energy_transfer"]).all() and (batched["peak_contact_force"] < 0).all()


def test_grids_that_change_the_struck_system_or_the_metrics_run_per_point():
    def longer_bar(length, velocity):
        spec = stepped(0.1, velocity)
        spec["rods"] = [spec["rods"][0], ri.Rod([ri.Cylinder(length, 0.04)])]
        return spec

    grid = {"length": [0.3, 0.4], "velocity": [3.0, 5.0]}
    ds = ri.sweep(longer_bar, grid)
    assert ds.attrs["runner"] == "simulate"
    with pytest.raises(ValueError, match=r"batch: this sweep cannot run as a batch of designs: at length = 0.4, "
                                         r"velocity = 3.0: the struck system .* differs from length = 0.3, velocity = 3.0"):
        ri.sweep(longer_bar, grid, batch=True)
    custom = ri.sweep(stepped, {"length": [0.1], "velocity": [3.0]}, {"last": lambda r: r.contact_force[-1]})
    assert custom.attrs["runner"] == "simulate"
    with pytest.raises(ValueError, match="probes and snapshots"):
        ri.sweep(lambda length: {**stepped(length, 3.0), "probes": [ri.Probe("p", 1, 0.1)]}, {"length": [0.1]},
                 batch=True)
    rough = {"length": [0.1, 0.031], "velocity": [3.0]}          # 0.031 m: 15.5 elements, 16 used
    assert ri.sweep(stepped, rough, errors="nan").attrs["runner"] == "simulate"   # simulate warns or refuses
    with pytest.raises(ValueError, match=r"at length = 0.031, velocity = 3.0: the striker's travel time is "
                                         r"represented with a 3.23% error"):
        ri.sweep(stepped, rough, batch=True)
    with pytest.raises(ValueError, match="batch: must be None"):
        ri.sweep(stepped, GRID, batch="yes")


def test_per_point_runs_on_an_executor_in_chunks():
    metrics = {"last": lambda r: r.contact_force[-1], "peak": lambda r: r.contact_force.min()}
    grid = {"length": [0.1, 0.16], "velocity": [3.0, 5.0, 7.0]}
    with ThreadPoolExecutor(2) as pool:
        pooled = ri.sweep(stepped, grid, metrics, executor=pool, chunk_size=4)
    assert pooled.attrs["executor"] == "ThreadPoolExecutor"
    same(pooled, ri.sweep(stepped, grid, metrics))


def test_process_pool_runs_batches_of_designs():
    grid = {"length": [0.1, 0.16], "velocity": list(np.linspace(2.0, 9.0, 12))}
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(2, mp_context=context) as pool:
        pooled = ri.sweep(stepped, grid, executor=pool, chunk_size=5)
    assert pooled.attrs["runner"] == "simulate_batch"
    same(pooled, ri.sweep(stepped, grid))


def small(length, velocity):
    """10-28 + 40 elements, 150 steps: a thousand of these are quick."""
    striker = ri.Rod([ri.Cylinder(length / 2, 0.012), ri.Cylinder(length / 2, 0.008)])
    return dict(rods=[striker, ri.Rod([ri.Cylinder(0.08, 0.01)])], velocities=[velocity, 0.0], steps=150,
                dt=DT, right="nonreflecting")


def test_dask_local_cluster_of_two_processes_gives_the_in_process_dataset():
    grid = {"length": list(0.004 * np.arange(5, 15)), "velocity": list(np.linspace(1.0, 10.0, 100))}
    in_process = ri.sweep(small, grid)
    assert in_process.attrs["points"] == 1000 and in_process.attrs["runner"] == "simulate_batch"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = ri.sweep(small, grid, executor=client, chunk_size=50)
        # the same tasks again right away (dask gives them the same names as the first call's)
        again = ri.sweep(small, grid, executor=client, chunk_size=50)
    assert on_dask.attrs["executor"] == "Client"
    same(on_dask, in_process)
    same(again, in_process)


def test_finding_out_that_a_grid_cannot_be_batched_builds_one_point_only():
    calls = []

    def with_probe(length):
        calls.append(length)
        return {**stepped(length, 3.0), "probes": [ri.Probe("p", 1, 0.1)]}

    ds = ri.sweep(with_probe, {"length": [0.1, 0.16, 0.2]})
    assert ds.attrs["runner"] == "simulate" and sorted(calls) == [0.1, 0.1, 0.16, 0.2]


def test_drilling_metrics_from_a_batch_equal_the_per_point_runs():
    """Energy into the rock, drilling efficiency and penetration per blow (BitRockOutcome) of every point: the
    batched sweep (one simulate_batch call per striker length) gives the per-point runs' numbers."""
    grid = {"length": [0.1, 0.16], "velocity": [4.0, 8.0]}
    batched = ri.sweep(stepped, grid, ri.drilling_metrics())
    per_point = ri.sweep(stepped, grid, ri.drilling_metrics(), batch=False)
    assert batched.attrs["runner"] == "simulate_batch" and per_point.attrs["runner"] == "simulate"
    same(batched, per_point)
    run = ri.simulate(ri.Problem.of(**stepped(0.16, 8.0)))
    rock = run.bit_rock[0]
    point = batched.sel(length=0.16, velocity=8.0)
    assert float(point["rock_energy"]) == rock.energy > 0.0
    assert float(point["drilling_efficiency"]) == rock.efficiency
    assert float(point["penetration_per_blow"]) == rock.penetration > 0.0
    assert batched["rock_energy"].attrs["units"] == "J"
    plain = ri.sweep(small, {"length": [0.1], "velocity": [3.0]}, ri.drilling_metrics())     # no rock: NaN
    assert np.isnan(plain["rock_energy"]).all()
