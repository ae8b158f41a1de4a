"""Up-front checks of what a simulation will cost, and progress reports for long runs.

Before a run starts, :func:`check_element_updates` and :func:`check_run_memory` estimate from the element and
step counts

* the run time, as the number of element updates (elements x steps): above ``max_element_updates`` (default
  :data:`DEFAULT_MAX_ELEMENT_UPDATES`, about a quarter of an hour at 1e8 updates per second) the run is refused
  with a message saying how to lift the limit (``max_element_updates=`` in Python, ``--max-element-updates`` on
  the command line; ``math.inf`` / ``inf`` switches it off);
* the memory the run holds at once: the lattice, the recorded histories and the field snapshots (twice: they
  are stacked at the end), against the memory available now (:func:`available_memory`).

:func:`check_output` does the same for what saving writes (``result.nc``, the CSV files, the plots) against the
free disk space of the output folder and the memory the writing needs; the command line calls it before a run.

:class:`Progress` reports progress on stderr for runs of more than :data:`PROGRESS_UPDATES` element updates: a
tqdm bar on a terminal, else a plain line every 10 % (so that a run started by a script or a batch system is not
mistaken for a hung one).
"""

from __future__ import annotations

import math
import os
import shutil
import sys
import time
from pathlib import Path
from typing import Any, Optional, Sequence

#: Default limit on elements x steps of one run (lift it with ``max_element_updates=``).
DEFAULT_MAX_ELEMENT_UPDATES = 1e11
#: runs that hold at most this much memory (bytes) are not checked against the available memory
SMALL_BYTES = 8.0 * 2**20
#: Runs with more element updates than this report progress on stderr (a few seconds and more).
PROGRESS_UPDATES = 1e9
#: Bytes per lattice element held during a run (lattice, discretisation, kernel state; as lattice.py counts).
BYTES_PER_ELEMENT = 128.0
#: Bytes per value of a CSV file ("-1.2345678901234567e-05," is 24 characters).
CSV_BYTES_PER_VALUE = 24.0
#: memory matplotlib holds per plotted point of a line (x and y as float64, the path and its transformed copy)
PLOT_BYTES_PER_POINT = 64.0
#: Disk space of one PNG plot and of the GIF animation (upper estimates).
PLOT_BYTES, ANIMATION_BYTES = 4e6, 60e6


def available_memory() -> Optional[float]:
    """Memory available to a new allocation now, bytes (psutil, on every platform; else POSIX ``sysconf``
    physical pages; ``None`` when neither can tell)."""
    try:
        import psutil

        return float(psutil.virtual_memory().available)
    except Exception:   # psutil missing or unable to read the platform's numbers
        pass
    try:
        return float(os.sysconf("SC_PAGE_SIZE")) * float(os.sysconf("SC_AVPHYS_PAGES"))
    except (AttributeError, OSError, ValueError):
        return None


def free_disk(folder: Path) -> Optional[float]:
    """Free bytes on the file system of ``folder`` (or of its nearest existing parent); ``None`` if unknown."""
    p = Path(os.path.abspath(folder))
    while not p.exists() and p.parent != p:
        p = p.parent
    try:
        return float(shutil.disk_usage(p).free)
    except OSError:
        return None


def _parts(parts: dict[str, float]) -> str:
    """The parts of a total as "name size, ...": those of 1 MiB or more, or all of them when none is that large
    (so that the message never shows an empty list)."""
    big = {k: v for k, v in parts.items() if v >= 2**20}
    return ", ".join(f"{k} {_gib(v)}" for k, v in (big or parts).items())


def _gib(n: float) -> str:
    return f"{n / 2**30:.3g} GiB" if n >= 2**28 else f"{n / 2**20:.3g} MiB"


def check_element_updates(n_elements: int, n_steps: int, limit: Optional[float], name: str = "duration") -> float:
    """Raise ``ValueError`` naming ``name`` if ``n_elements * n_steps`` exceeds ``limit`` (``None``: the default
    :data:`DEFAULT_MAX_ELEMENT_UPDATES`); returns the number of element updates."""
    limit = DEFAULT_MAX_ELEMENT_UPDATES if limit is None else limit
    if isinstance(limit, bool) or not isinstance(limit, (int, float)) or math.isnan(limit) or limit <= 0:
        raise ValueError(f"max_element_updates: must be a number > 0 (math.inf: no limit), got {limit!r}")
    updates = float(n_elements) * float(n_steps)
    if updates > limit:
        raise ValueError(
            f"{name}: the run needs {n_elements:,} elements x {n_steps:,} steps = {updates:.3g} element updates, "
            f"more than the limit of {limit:.3g} (roughly {_duration(updates / 1e8)} at 1e8 updates per second); "
            f"use a larger dt or a shorter duration, or lift the limit with max_element_updates= "
            f"(command line: --max-element-updates)")
    return updates


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    if seconds < 3 * 86400:
        return f"{seconds / 3600:.0f} h"
    return f"{seconds / 86400:.3g} days"


def run_bytes(n_elements: int, n_steps: int, rows: int, stride: int, n_snapshots: int) -> dict[str, float]:
    """Memory a run holds at its peak, bytes, by part: ``lattice``, ``histories`` (``rows`` signals of every
    ``stride``-th step) and ``snapshots`` (force, velocity per element and displacement per node, twice while
    they are stacked at the end)."""
    n_rec = -(-n_steps // stride)
    return {"lattice": BYTES_PER_ELEMENT * n_elements, "histories": 8.0 * rows * n_rec,
            "snapshots": 2.0 * 8.0 * n_snapshots * (3 * n_elements + 2)}


def check_run_memory(n_elements: int, n_steps: int, rows: int, stride: int, n_snapshots: int) -> None:
    """The memory of a run's lattice, histories and snapshots against the available memory, before anything is
    allocated (:func:`rodimpact.simulate` checks the element-update limit first, :func:`check_element_updates`).
    Messages name the argument that changes it."""
    _check_memory(run_bytes(n_elements, n_steps, rows, stride, n_snapshots), _RUN_HINTS, _RUN_NAMES)


_RUN_HINTS = {"histories": "keep every n-th step with record_every=n of the Outputs, or split the run",
              "snapshots": "fewer snapshots (a larger snapshot_every, fewer snapshot_times of the Outputs)",
              "lattice": "a larger dt (fewer elements)"}
_RUN_NAMES = {"histories": "steps", "snapshots": "snapshot_every", "lattice": "dt"}


def _check_memory(parts: dict[str, float], hints: dict[str, str], names: dict[str, str]) -> None:
    total = sum(parts.values())
    if total <= SMALL_BYTES:          # small runs do not ask the operating system (it costs tens of microseconds)
        return
    avail = available_memory()
    if avail is None or total <= 0.9 * avail:
        return
    biggest = max(parts, key=parts.get)
    shown = _parts(parts)
    raise ValueError(f"{names[biggest]}: the run would need about {_gib(total)} of memory ({shown}), more than "
                     f"the {_gib(avail)} available now; {hints[biggest]}")


def output_bytes(n_elements: int, n_steps: int, rows: int, csv_columns: int, stride: int, n_snapshots: int,
                 csv: bool, fields: bool, plots: Sequence[str]) -> dict[str, float]:
    """Disk space the saved result takes, bytes, by file: ``result.nc`` (histories, snapshots when ``fields``,
    lattice), ``signals.csv`` (``csv_columns`` per recorded step) and the plots."""
    n_rec = -(-n_steps // stride)
    out = {"result.nc": 8.0 * (rows + 1) * n_rec + 8.0 * 12 * n_elements
           + (8.0 * n_snapshots * (3 * n_elements + 2) if fields else 0.0)}
    if csv:
        out["signals.csv"] = CSV_BYTES_PER_VALUE * csv_columns * n_rec
    out["plots"] = sum(ANIMATION_BYTES if p == "animation" else PLOT_BYTES for p in plots)
    return out


def check_output(folder: Path, parts: dict[str, float], memory: dict[str, float]) -> None:
    """Refuse (``ValueError``) when the files in ``parts`` (bytes) do not fit the free disk space at ``folder`` or
    the run and the writing (``memory``, bytes) do not fit the available memory."""
    total = sum(parts.values())
    free = free_disk(folder)
    if free is not None and total > 0.95 * free:
        shown = _parts(parts)
        raise ValueError(f"output: the results would take about {_gib(total)} on disk ({shown}), more than the "
                         f"{_gib(free)} free at {folder}; record fewer steps (output.record_every), fewer snapshots "
                         f"(output.snapshot_every/snapshot_count, or output.fields = false), output.csv = false, "
                         f"or choose another output folder")
    _check_memory(memory, {"histories": "keep every n-th step with output.record_every = n, or split the run",
                           "snapshots": "fewer snapshots (output.snapshot_every / snapshot_count)",
                           "lattice": "a larger simulation.dt (fewer elements)",
                           "writing": "keep every n-th step with output.record_every = n",
                           "plots": "keep every n-th step with output.record_every = n, or fewer plots (output.plots)"},
                  {"histories": "output.record_every", "snapshots": "output.snapshot_count",
                   "lattice": "simulation.dt", "writing": "output.record_every", "plots": "output.plots"})


class Progress:
    """Progress of ``n_steps`` steps of a run (or of other units of work, e.g. the runs of a sweep) on stderr: a
    tqdm bar on a terminal, else a line at every 10 %, both labelled ``desc`` and counted in ``unit``."""

    def __init__(self, n_steps: int, stream: Any = None, unit: str = "step", desc: str = "simulate") -> None:
        self.n, self.done, self.stream = n_steps, 0, stream or sys.stderr
        self.unit, self.desc = unit, desc
        self.t0 = time.perf_counter()
        self.next_tenth = 1
        self.bar = None
        if getattr(self.stream, "isatty", lambda: False)():
            from tqdm.auto import tqdm

            self.bar = tqdm(total=n_steps, unit=unit, desc=desc, file=self.stream)

    def update(self, steps: int) -> None:
        self.done += steps
        if self.bar is not None:
            self.bar.update(steps)
            return
        tenths = 10 * self.done // self.n                  # whole tenths done (integers: no rounding)
        if tenths >= self.next_tenth:
            frac = self.done / self.n
            elapsed = time.perf_counter() - self.t0
            left = elapsed * (1 - frac) / frac
            print(f"{self.desc}: {frac:4.0%} ({self.done:,} of {self.n:,} {self.unit}s, {_duration(elapsed)} elapsed, "
                  f"about {_duration(left)} left)", file=self.stream, flush=True)
            self.next_tenth = tenths + 1

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def progress(enabled: Optional[bool], n_steps: int, n_elements: int) -> Optional[Progress]:
    """A :class:`Progress` if ``enabled``, or by default (``None``) for runs of more than :data:`PROGRESS_UPDATES`
    element updates (on a terminal or not); ``None`` otherwise."""
    if enabled is None:
        enabled = float(n_steps) * float(n_elements) > PROGRESS_UPDATES
    return Progress(n_steps) if enabled else None
