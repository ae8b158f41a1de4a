"""Checks before a model file's run (the command line's ``simulate`` and ``sweep``): the element-update limit, the
memory the run and the writing need, and the disk space of the files written, with messages that name the model
file's keys.
The numbers come from :mod:`rodimpact.direct.guards`."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Optional, Sequence

from ..direct.guards import PLOT_BYTES_PER_POINT, check_element_updates, check_output, output_bytes, run_bytes
from .quantities import ModelError


def run_size(model: Any) -> tuple[int, int]:
    """(elements, steps) of a :class:`~rodimpact.io.model.Model`'s run, the element count estimated from the rods'
    travel times (as the lattice counts it)."""
    dt = model.time_step
    n_el_float = sum(r.total_travel_time for r in model.system.rods) / dt
    if not n_el_float < 2**62:
        raise ModelError(f"simulation.dt: the rods would need {n_el_float:.3g} elements of travel time {dt:.3g} s; "
                         f"use a larger dt")
    return max(1, int(round(n_el_float))), model.n_steps


def check_run(model: Any, folder: Optional[Path], plots: Sequence[str],
              max_element_updates: Optional[float] = None) -> None:
    """Before a :class:`~rodimpact.io.model.Model` runs (the command line's ``simulate`` and ``sweep``): the
    element-update limit and, when results are written into ``folder``, the memory the run and the writing need
    and the disk space of the files. Messages name the model file's keys."""
    n_el, n_steps = run_size(model)
    try:
        check_element_updates(n_el, n_steps, max_element_updates, "simulation.duration")
    except ValueError as exc:
        raise ModelError(str(exc).replace("max_element_updates= (command line: --max-element-updates)",
                                          "--max-element-updates")) from None
    if folder is None:          # the run itself checks its memory
        return
    n_rods, n_probes = model.system.n_rods, len(model.probes)
    rows = 2 * (n_rods - 1) + 4 + 4 * n_probes
    stride = model.output.record_every
    every = model.snapshot_every()
    n_snap = len(model.output.snapshot_times) + (n_steps // every + 1 if every else 0)
    memory = run_bytes(n_el, n_steps, rows, stride, n_snap)
    memory["writing"] = memory["histories"]            # the NetCDF dataset stacks the histories once more
    # a history plot draws every recorded step of its signals (at most all of them)
    memory["plots"] = PLOT_BYTES_PER_POINT * rows * -(-n_steps // stride) if set(plots) - {"profile"} else 0.0
    files = output_bytes(n_el, n_steps, rows, rows + 1, stride, n_snap if model.output.fields else 0,
                         model.output.csv, model.output.fields, plots)
    try:
        check_output(folder.parent if not folder.exists() else folder, files, memory)
    except ValueError as exc:
        raise ModelError(str(exc)) from None
