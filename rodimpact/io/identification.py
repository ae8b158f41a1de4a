"""Identification files: the profile of an :class:`~rodimpact.identify.IdentificationResult` as a CSV table
(:func:`save_identification_csv`, :func:`read_identification_csv`; :func:`rodimpact.save` and
:func:`rodimpact.load` call them for a ``.csv`` path) and the plain CSV head record (:func:`read_head_csv`).

The profile table: comment lines ``# key: value`` (value as JSON: method, wave speed, toe, anomalies, ...;
:meth:`IdentificationResult.metadata`), then a header row ``depth_top [m],depth_bottom [m],impedance [N s/m]``
(and ``lower [N s/m],upper [N s/m]`` with bands), then one row per element. The matched signals are not in the
table (the netCDF file holds them).

The head record: a header row naming the columns ``time``, ``force`` and ``velocity`` with their units in
brackets (``time [ms], force [kN], velocity [m/s]``; any unit of the right dimension, converted to SI; no
bracket: SI), then one row per sample. A unit of the wrong dimension is an error naming the column.
"""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path
from typing import Any

import numpy as np

from .._quantities import ModelError
from .._result_files import write_new_file
from ..identify.records import HeadRecord
from ..identify.result import KIND, IdentificationResult
from .quantities import parse_quantity

__all__ = ["read_head_csv", "read_identification_csv", "save_identification_csv"]

_MAGIC = "# rodimpact identification"
_HEAD_COLUMNS = {"time": "time", "force": "force", "velocity": "velocity"}
_PROFILE_UNITS = {"depth_top": "m", "depth_bottom": "m", "impedance": "N s/m", "lower": "N s/m", "upper": "N s/m"}
_HEADER = re.compile(r"^\s*([A-Za-z_]+)\s*(?:\[(.*)\])?\s*$")


def save_identification_csv(result: IdentificationResult, path: str | Path, *, overwrite: bool = False) -> Path:
    """Write the profile of ``result`` as a CSV table (module docstring); refuses an existing file unless
    ``overwrite=True``; written under a temporary name and moved into place."""
    if not isinstance(result, IdentificationResult):
        raise TypeError(f"result: a CSV table holds an IdentificationResult's profile, got {type(result).__name__}; "
                        f"save other results as netCDF (a .nc path)")
    header, columns = result.table()

    def write(tmp: Path) -> None:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(_MAGIC + "\n")
            for key, value in result.metadata().items():
                if key != "kind":
                    fh.write(f"# {key}: {value}\n")
            out = csv.writer(fh, lineterminator="\n")
            out.writerow(header)
            out.writerows(np.column_stack(columns).tolist())

    return write_new_file(path, write, overwrite)


def read_identification_csv(path: str | Path) -> IdentificationResult:
    """The result a :func:`save_identification_csv` table holds (without matched signals). A file that is not
    such a table, or whose header names another unit, is a ``ValueError`` naming the file and line."""
    p = Path(path)
    lines = p.read_text(encoding="utf-8").splitlines()
    if not lines or lines[0].strip() != _MAGIC:
        raise ValueError(f"{p}: not an identification table written by rodimpact.save (first line must be "
                         f"{_MAGIC!r})")
    meta: dict[str, str] = {"kind": KIND}
    i = 1
    while i < len(lines) and lines[i].startswith("#"):
        key, _, value = lines[i][1:].partition(":")
        meta[key.strip()] = value.strip()
        i += 1
    rows = list(csv.reader(lines[i:]))
    if len(rows) < 2:
        raise ValueError(f"{p}: line {i + 1}: a header row and at least one element row are needed")
    names = []
    for k, cell in enumerate(rows[0]):
        name, unit = _column(cell, p, i + 1, k + 1)
        want = _PROFILE_UNITS.get(name)
        if want is None or (unit or want) != want:
            raise ValueError(f"{p}: line {i + 1}, column {k + 1}: expected one of "
                             f"{', '.join(f'{n} [{u}]' for n, u in _PROFILE_UNITS.items())}, got {cell!r}")
        names.append(name)
    try:
        data = np.array(rows[1:], dtype=float)
    except ValueError:
        raise ValueError(f"{p}: the rows after line {i + 1} must hold numbers only") from None
    col = {n: data[:, k] for k, n in enumerate(names)}
    depth = np.append(col["depth_top"], col["depth_bottom"][-1])
    try:
        return IdentificationResult.from_metadata(meta, depth, col["impedance"], col.get("lower"), col.get("upper"))
    except (KeyError, json.JSONDecodeError) as exc:
        raise ValueError(f"{p}: the comment lines miss or garble {exc}; the file was not written by "
                         f"rodimpact.save") from None


def read_head_csv(path: str | Path, *, compression_positive: bool = False) -> HeadRecord:
    """A head record from a plain CSV table of time, force and velocity (module docstring). ``force`` is read as
    tension positive unless ``compression_positive`` (pile practice), velocity positive down the rod."""
    p = Path(path)
    with open(p, encoding="utf-8", newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    if len(rows) < 3:
        raise ValueError(f"{p}: needs a header row (time, force, velocity) and at least 2 samples")
    factors: dict[str, tuple[int, float]] = {}
    for k, cell in enumerate(rows[0]):
        name, unit = _column(cell, p, 1, k + 1)
        if name not in _HEAD_COLUMNS:
            raise ValueError(f"{p}: header column {k + 1} ({cell!r}): expected time, force or velocity with a unit "
                             f"in brackets, e.g. 'force [kN]'")
        try:
            factor = parse_quantity(f"1 {unit}", _HEAD_COLUMNS[name], f"{p}: header column {k + 1} ({name})") \
                if unit else 1.0
        except ModelError as exc:
            raise ValueError(str(exc)) from None
        factors[name] = (k, factor)
    missing = [n for n in _HEAD_COLUMNS if n not in factors]
    if missing:
        raise ValueError(f"{p}: header row: no column {', '.join(missing)} (need time, force, velocity)")
    short = next((i for i, r in enumerate(rows[1:]) if len(r) != len(rows[0])), None)
    if short is not None:
        raise ValueError(f"{p}: data row {short + 1}: every row must have {len(rows[0])} columns like the header, "
                         f"got {len(rows[short + 1])}")
    try:
        data = np.array([[float(x) for x in r] for r in rows[1:]])
    except ValueError as exc:
        raise ValueError(f"{p}: every row after the header must hold numbers ({exc})") from None
    get: Any = {n: data[:, k] * f for n, (k, f) in factors.items()}
    force = -get["force"] if compression_positive else get["force"]
    return HeadRecord(get["time"], force, get["velocity"], source=str(p))


def _column(cell: str, path: Path, line: int, column: int) -> tuple[str, str]:
    m = _HEADER.match(cell)
    if not m:
        raise ValueError(f"{path}: line {line}, column {column}: a header 'name [unit]', got {cell!r}")
    return m.group(1).lower(), (m.group(2) or "").strip()
