"""Speed of the direct solver: the compiled time loop against the loop it replaced, the interior sweep against a
streaming roof, and full fields at every step.

* ``simulate()`` on the thesis-scale impact (README "In Python": two-part striker 51.0e3 / 28.7e3 N s/m x 50
  elements each, bar 51.0e3 x 400, v = 5 m/s, non-reflecting right end, dt = 1 us, 600 steps) with default
  options: median wall time now and with the old loop (``_old_loop.old_simulate``, frozen), and a cProfile of
  the new call with the share spent inside the compiled kernel;
* element updates per second of the compiled loop for n = 10^3 .. 10^6 elements against a roof measured in the
  same run: a compiled streaming loop with exactly the interior sweep's memory traffic (reads f, g, R; writes
  f, g: 40 bytes per element and step) and trivial arithmetic. The lattice's impedance changes at every
  element: in the frame of the travelling waves a node without reflection costs nothing, so a lattice with
  uniform sections would count updates that are not done;
* ``snapshot_every=1`` (N, v, u at every step) now and with the old loop; elwaspatid on the same impact only
  if it is importable (it is not a dependency: AGPL).

Run:  python benchmarks/bench_kernel.py          (writes the "kernel" section of docs/performance.md)
      python benchmarks/bench_kernel.py --quick  (small sizes, prints only: checks that the script runs)
"""

from __future__ import annotations

import cProfile
import importlib.util
import io
import os
import platform
import pstats
import sys
import time
import tracemalloc

import numba
import numpy as np

import rodimpact as ri
from rodimpact.direct import _kernels as K
from rodimpact.direct import simulate as sim
from rodimpact.direct.problem import Problem, TimeGrid
from rodimpact.direct.recording import Recorder, Outputs

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _old_loop import old_simulate  # noqa: E402
from _report import write_section  # noqa: E402

DT = 1e-6


@numba.njit(cache=True)
def _stream(n_steps, f, g, R):
    """Bandwidth roof: the interior sweep's loads and stores (f, g, R in; f, g out), minimal arithmetic."""
    for _ in range(n_steps):
        for j in range(f.size - 1):
            r = R[j]
            f[j] = f[j] + 1e-30 * r
            g[j] = g[j] - 1e-30 * r


def thesis_impact():
    striker = ri.Rod.from_impedance([51.0e3] * 50 + [28.7e3] * 50, dt=DT)
    bar = ri.Rod.from_impedance([51.0e3] * 400, dt=DT)
    return striker, bar


def _median(fn, repeat: int) -> float:
    fn()
    walls = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        walls.append(time.perf_counter() - t0)
    return float(np.median(walls))


def _rates(n: int, n_steps: int, rounds: int) -> tuple[float, float]:
    """Element updates per second of the compiled loop alone (lattice and arrays built outside the timing) and
    of the streaming roof on arrays of the same size, timed alternately (best of ``rounds`` each) so that a
    changing machine load affects both alike."""
    z = 5e4 * (1.0 + 0.5 * np.sin(np.arange(n)))     # every node reflects: nothing is skipped
    rods = [ri.Rod.from_impedance(z[: n // 4], dt=DT), ri.Rod.from_impedance(z[n // 4:], dt=DT)]
    # free ends: the waves stay alive (no denormal decay); both rods move from the start, so no element is at
    # rest ahead of a wave (the loop skips those)
    system = ri.System(rods, velocities=[5.0, -1.0])
    lat = ri.build_lattice(system, DT)
    f, g, R = np.zeros(n), np.zeros(n), np.full(n - 1, 0.1)
    best_kernel = best_roof = np.inf
    for _ in range(rounds):
        compiled = Problem(system, TimeGrid(DT, n_steps)).compile()
        state, arrays = {"N": compiled.N, "v": compiled.v}, compiled.arrays
        recorder = Recorder(Outputs(energy_every=n_steps), lat, arrays, state["N"].copy(), n_steps, n_steps)
        t0 = time.perf_counter()
        sim._advance("numba", n_steps, n_steps, lat, arrays, state, recorder, None)
        best_kernel = min(best_kernel, time.perf_counter() - t0)
        t0 = time.perf_counter()
        _stream(n_steps, f, g, R)
        best_roof = min(best_roof, time.perf_counter() - t0)
    return n * n_steps / best_kernel, n * n_steps / best_roof


def _compiled_share(call, repeat: int) -> tuple[float, str]:
    """Median fraction of a call's wall time spent inside the compiled loop (timed around each compiled call),
    and the top of a cProfile of ``repeat`` calls (which inflates the Python side: it times every Python call)."""
    inner = K.run_numba
    spent = [0.0]

    def timed(*args):
        t0 = time.perf_counter()
        out = inner(*args)
        spent[0] += time.perf_counter() - t0
        return out

    shares = []
    K.run_numba = timed
    try:
        for _ in range(repeat):
            spent[0] = 0.0
            t0 = time.perf_counter()
            call()
            shares.append(spent[0] / (time.perf_counter() - t0))
    finally:
        K.run_numba = inner
    prof = cProfile.Profile()
    prof.enable()
    for _ in range(repeat):
        call()
    prof.disable()
    out = io.StringIO()
    pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(12)
    root = os.path.dirname(os.path.dirname(os.path.abspath(ri.__file__))) + os.sep
    lines = [ln.replace(root, "") for ln in out.getvalue().splitlines() if ln.strip()][3:]
    return float(np.median(shares)), "\n".join(lines)


def _elwaspatid_snapshots(repeat: int):
    """elwaspatid (full x-t fields) on the thesis impact, if importable; else None. Steel rods whose diameters
    give the impedances of the lattice; its own element count per segment (nmin) is set to 50."""
    if importlib.util.find_spec("elwaspatid") is None:
        return None
    import elwaspatid

    WP2 = elwaspatid.WP2
    bar_set = getattr(elwaspatid, "BarSet", None) or getattr(elwaspatid, "Barhete")   # name since 2.0 / before

    E, rho = 210e9, 7800.0
    c = np.sqrt(E / rho)
    diameter = [float(np.sqrt(4 * z / (rho * c) / np.pi)) for z in (51.0e3, 28.7e3, 51.0e3)]
    bars = bar_set([E] * 3, [rho] * 3, [50 * c * DT, 50 * c * DT, 400 * c * DT], diameter, nmin=50)
    return _median(lambda: WP2(bars, nstep=600, left="free", right="infinite", Vinit=5.0), repeat)


def main(quick: bool = False) -> None:
    repeat = 5 if quick else 200
    striker, bar = thesis_impact()
    new = lambda **kw: ri.simulate(ri.System([striker, bar], [5.0, 0.0], right="nonreflecting"),  # noqa: E731
                                   steps=600, dt=DT, outputs=ri.Outputs(**kw) if kw else None)
    old = lambda **kw: old_simulate(ri.System([striker, bar], velocities=[5.0, 0.0],  # noqa: E731
                                              right="nonreflecting"), 600, DT, **kw)
    assert np.array_equal(new().contact_force, old(energy_every=600).contact_force)     # same numbers
    t_old, t_new = _median(old, repeat), _median(new, repeat)
    share, profile = _compiled_share(new, repeat)
    t_old_snap = _median(lambda: old(snapshot_every=1), max(3, repeat // 10))
    t_new_snap = _median(lambda: new(snapshot_every=1), max(3, repeat // 10))
    t_peer = _elwaspatid_snapshots(max(3, repeat // 10))
    print(f"simulate() thesis scale: old loop {t_old * 1e3:.3f} ms, now {t_new * 1e3:.3f} ms (median of {repeat}); "
          f"compiled share {share:.0%}")
    print(profile)
    print(f"snapshot_every=1: old loop {t_old_snap * 1e3:.2f} ms, now {t_new_snap * 1e3:.2f} ms"
          + (f", elwaspatid {t_peer * 1e3:.2f} ms" if t_peer is not None else ", elwaspatid not installed"))
    _rates(100, 10, 1)          # compile / load caches
    rows = []
    for n in ((10**3, 10**4) if quick else (10**3, 10**4, 10**5, 10**6)):
        steps = max(20, int((3e6 if quick else 1e8) // n))
        r_k, r_roof = _rates(n, steps, 3 if quick else 7)
        rows.append((n, r_k, r_roof))
        print(f"n={n:>8}: compiled loop {r_k:.3g}/s  roof {r_roof:.3g}/s  ratio {r_k / r_roof:.2f}")
    if quick:
        return
    peaks = {}
    for stride in (1, 100):
        tracemalloc.start()
        ri.simulate(ri.System([striker, bar], [5.0, 0.0], right="nonreflecting"), steps=1_000_000,
                    outputs=ri.Outputs(probes=[ri.Probe("a", 1, 0.1), ri.Probe("b", 1, 0.5), ri.Probe("c", 1, 1.0)],
                                       snapshot_times=np.linspace(0, 0.9, 10), record_every=stride))
        peaks[stride] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    lines = [
        "## Direct solver (`benchmarks/bench_kernel.py`)",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, Python "
        f"{platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}; one thread; load average "
        f"{os.getloadavg()[0]:.1f} at the end of the run. \"Old loop\" is the loop before the time stepping moved "
        "into compiled code (`benchmarks/_old_loop.py`, frozen): it returned to Python at every energy sample and "
        "snapshot.",
        "",
        "**Thesis-scale impact** (two-part striker 51.0e3 / 28.7e3 N s/m x 50 elements each on a 51.0e3 x 400 bar, "
        "5 m/s, non-reflecting end, 600 steps, default options; the same contact force bit for bit):",
        "",
        "| | old loop | now |",
        "|---|---:|---:|",
        f"| `simulate()` median of {repeat} | {t_old * 1e3:.3f} ms | {t_new * 1e3:.3f} ms |",
        f"| with `snapshot_every=1` (fields at all 601 times) | {t_old_snap * 1e3:.2f} ms | {t_new_snap * 1e3:.2f} ms |",
        "",
        f"Share of the `simulate()` call spent in the compiled loop (timed around it, median): {share:.0%}. Top of a "
        f"cProfile of {repeat} calls (the profiler slows the Python side down; `_run_waves` is the compiled loop):",
        "",
        "```",
        profile,
        "```",
        "",
        ("elwaspatid (pure numpy, fields at every step) on the same impact: "
         f"{t_peer * 1e3:.2f} ms." if t_peer is not None else
         "elwaspatid was not installed for this run (it is not a dependency), so there is no side-by-side number."),
        "",
        "**Interior sweep.** Element updates per second (one update = one element advanced by one step) of the "
        "compiled loop on a two-rod lattice whose impedance changes at every element (every node reflects; a node "
        "without reflection costs nothing in the frame of the travelling waves, so uniform sections would count "
        "updates that are not done), against a roof measured in the same run: a compiled streaming loop "
        "with exactly the sweep's memory traffic per step (reads f, g, R; writes f, g) and trivial arithmetic. "
        "The loop can pass the roof: it updates runs of reflecting nodes two steps per pass (node k in step i "
        "with node k-1 in step i + 1, explicit vectors of 8 nodes), so each slot is loaded and stored once per "
        "two steps (steps before an energy sample or snapshot are done one at a time).",
        "",
        "| elements | compiled loop | streaming roof | loop / roof |",
        "|---:|---:|---:|---:|",
    ]
    lines += [f"| {n:,} | {a:.3g} | {b:.3g} | {a / b:.2f} |" for n, a, b in rows]
    lines += [
        "",
        f"Memory of a long run (10^6 steps, 500 elements, 3 probes, 10 snapshots): peak traced allocation "
        f"{peaks[1] / 2**20:.1f} MiB when every step is recorded -- the node histories (8 bytes x steps x "
        f"(3 values per probe + 2 per junction + 4 end values)) dominate -- and {peaks[100] / 2**20:.1f} MiB with "
        f"`record_every=100`, then bounded by the per-call step buffers (at most 65536 steps); contact events are "
        f"still taken at every step. Fields are kept only at the requested snapshots (preallocated, checked "
        f"against the machine's memory before the run), energy at about 256 samples by default.",
    ]
    write_section("kernel", "\n".join(lines))


if __name__ == "__main__":
    main(quick="--quick" in sys.argv[1:])
