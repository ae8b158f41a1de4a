"""Throughput of rodimpact.simulate_batch: thesis-scale impacts per second, and scale-out on Dask.

Thesis scale: a 100-element striker (smooth random impedance profiles) on a 400-element bar with a
non-reflecting far end, dt = 1 us, 600 steps. Compares, side by side in one run:

* ``simulate()`` in a Python loop (default options, and with ``energy_every=600``);
* ``simulate_batch`` with 1 and 2 numba threads;
* the same batch of 10^5 designs in-process (all threads) and on a ``dask.distributed.LocalCluster`` of two
  worker processes (one thread each), batches of designs per task; cluster start-up is reported separately.

Every design's contact force is checked against ``simulate()`` (``np.array_equal``) for a few designs.

Run:  python benchmarks/bench_batch.py           (writes the "batch" section of docs/performance.md)
      python benchmarks/bench_batch.py --quick   (small sizes, prints only; checks that the script runs)
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import time

import numba
import numpy as np

import rodimpact as ri
from rodimpact.direct.batch import default_chunk_size

try:
    from _report import write_section
except ImportError:  # run from the repository root
    from benchmarks._report import write_section

DT = 1e-6
STEPS = 600


def designs(n: int, n_elements: int = 100, seed: int = 0) -> np.ndarray:
    """Smooth random striker profiles: a few cosine modes around 4e4 N s/m."""
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 1.0, n_elements)
    k = np.arange(1, 5)
    amp = rng.uniform(-0.3, 0.3, (n, k.size)) / k
    return 4e4 * (1.0 + amp @ np.cos(np.pi * k[:, None] * x[None, :]))


def struck() -> ri.System:
    bar = ri.Rod.from_impedance(np.full(400, 4e4), DT)
    return ri.System([ri.Rod.from_impedance(np.full(100, 4e4), DT), bar], [0.0, 0.0], right="nonreflecting")


def best_of(fn, repeat: int) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def simulate_loop(system: ri.System, zs: np.ndarray, vel: np.ndarray, **kwargs) -> list:
    out = []
    for z, v in zip(zs, vel):
        s = dataclasses.replace(system, rods=(ri.Rod.from_impedance(z, DT), *system.rods[1:]),
                                velocities=(float(v), 0.0))
        out.append(ri.simulate(s, dt=DT, steps=STEPS, progress=False, outputs=ri.Outputs(**kwargs) if kwargs else None))
    return out


def warm_up() -> None:
    """Load the compiled batch kernel in a worker process."""
    ri.simulate_batch(struck(), designs(2), 5.0, ri.TimeGrid(DT, 10), threads=1)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes; print, do not write the docs")
    args = parser.parse_args()
    quick = args.quick
    n_loop, n_batch, n_dask, repeat = (20, 400, 4000, 1) if quick else (300, 20_000, 100_000, 3)
    system = struck()
    zs = designs(max(n_batch, n_dask))
    vel = np.random.default_rng(1).uniform(3.0, 10.0, zs.shape[0])
    cpus = os.cpu_count() or 1
    ri.simulate_batch(system, zs[:4], vel[:4], ri.TimeGrid(DT, STEPS), threads=2)      # compile / load the caches
    ri.simulate_batch(system, zs[:4], vel[:4], ri.TimeGrid(DT, STEPS), threads=1)
    simulate_loop(system, zs[:2], vel[:2])

    # bit-identity spot check
    check = ri.simulate_batch(system, zs[:8], vel[:8], ri.TimeGrid(DT, STEPS))
    runs = simulate_loop(system, zs[:8], vel[:8])
    identical = all(np.array_equal(check.contact_force[d], r.junction_force[0]) for d, r in enumerate(runs))
    print(f"contact force of 8 designs equals simulate() exactly: {identical}")

    rows = []
    for label, kwargs in (("default options", {}), ("energy_every=600", {"energy_every": STEPS})):
        t = best_of(lambda: simulate_loop(system, zs[:n_loop], vel[:n_loop], **kwargs), repeat)
        rows.append((f"`simulate()` loop, {label}", 1, n_loop, n_loop / t))
    for threads in sorted({1, min(2, cpus)}):
        t = best_of(lambda: ri.simulate_batch(system, zs[:n_batch], vel[:n_batch], ri.TimeGrid(DT, STEPS),
                                              threads=threads), repeat)
        rows.append(("`simulate_batch`", threads, n_batch, n_batch / t))
    for r in rows:
        print(f"{r[0]:55s} threads={r[1]}  {r[2]:7d} designs  {r[3]:10.0f} impacts/s")

    # Dask: batches per task against the in-process batch, same designs
    import distributed

    # the designs' scalars only (what a large study keeps), and with the striker's final fields sent back too
    options = {"final_state=False": False, "final_state=True": True}
    kws = {k: dict(time=ri.TimeGrid(DT, STEPS), outputs=ri.BatchOutputs(contact_force=False, final_state=v))
           for k, v in options.items()}
    t_in = {k: best_of(lambda: ri.simulate_batch(system, zs[:n_dask], vel[:n_dask], threads=min(2, cpus), **kw), 2)
            for k, kw in kws.items()}
    t0 = time.perf_counter()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        start = time.perf_counter() - t0
        client.run(warm_up)                                # every worker loads the compiled kernels once
        t_dask = {k: best_of(lambda: ri.simulate_batch(system, zs[:n_dask], vel[:n_dask], executor=client, **kw), 2)
                  for k, kw in kws.items()}
    chunk = default_chunk_size(n_dask)
    scale_rows = [(k, n_dask / t_in[k], n_dask / t_dask[k], t_in[k] / t_dask[k]) for k in kws]
    for r in scale_rows:
        print(f"{r[0]}: in-process, 2 threads: {r[1]:.0f} impacts/s; Dask LocalCluster 2 processes, {chunk} designs "
              f"per task: {r[2]:.0f} impacts/s (ratio {r[3]:.2f})")
    print(f"cluster start {start:.2f} s")
    if quick:
        return
    body = "\n".join([
        "## Batched designs (`benchmarks/bench_batch.py`)",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {cpus} CPUs, Python {platform.python_version()}, "
        f"numpy {np.__version__}, numba {numba.__version__}; load average at the end "
        f"{os.getloadavg()[0]:.2f}. Best of {repeat}.",
        "",
        "Thesis scale: 100-element striker (smooth random impedance profiles), 400-element bar, non-reflecting far "
        f"end, dt = 1 us, {STEPS} steps. The contact force of each design equals `simulate()`'s exactly "
        f"(checked here: {identical}). `energy_every` only sets where `simulate()` samples the energy; the results do "
        "not depend on it.",
        "",
        "| run | threads | designs | impacts/s |",
        "|---|---:|---:|---:|",
        *[f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.0f} |" for r in rows],
        "",
        f"Scale-out, {n_dask} designs without the contact-force history (best of 2): in-process with 2 threads "
        f"against a `dask.distributed.LocalCluster` of 2 worker processes (1 thread each), {chunk} designs per task "
        f"(cluster start-up {start:.2f} s, not included). `final_state=False` leaves the striker's final element "
        "forces and velocities out of the result, so a task sends back its designs' scalars only; with them each "
        f"task sends back 2 x {chunk} x 100 floats more.",
        "",
        "| options | in-process, impacts/s | Dask, impacts/s | Dask / in-process |",
        "|---|---:|---:|---:|",
        *[f"| `{r[0]}` | {r[1]:.0f} | {r[2]:.0f} | {r[3]:.2f} |" for r in scale_rows],
    ])
    write_section("batch", body)


if __name__ == "__main__":
    main()
