"""Readers for gauge recordings: generic CSV/text, LANL ``.raw``, Tektronix CSV, HopPyBar
input sheets and TDMS (via npTDMS). Every reader returns a :class:`rodimpact.signals.Recording`
with time in s.

Malformed files raise :class:`RecordingError` (a ``ValueError``) with the file name and the (1-based) line number:
missing columns, text where a number belongs, time that does not increase.

Formats
-------
* **CSV/text** (:func:`read_csv_recording`): one time column and any number of channel
  columns, optional header line of names (a unit in brackets, ``"force [N]"`` or
  ``"time (ms)"``, is recognised; the time unit, any time unit pint knows such as s, ms, us or ns, is
  converted to s). The table is read by pandas; a line it cannot read is checked on its own for the error
  message.
* **LANL .raw** (:func:`read_lanl_raw`): tab-separated. Columns 1-2 hold a metadata sheet
  (name, value); columns 3-4 hold the incident/reflected and transmitted bar voltages. The
  first row of columns 3-4 names the waveforms, the second gives each waveform's start time
  (s), the third its sample increment (s), the samples follow.
* **Tektronix CSV** (:func:`read_tektronix_csv`): five comma-separated columns; columns 1-3
  of the first rows hold header fields (name, value, unit: record length, sample interval,
  trigger point, ...), columns 4-5 hold time (s) and value (V). One file per channel.
* **HopPyBar input sheet** (:func:`read_hoppybar_input`): tab-separated name/value(/unit)
  lines such as ``PMMA_13_Input.dat``; :func:`hoppybar_bar` turns one bar's entries into a
  :class:`rodimpact.signals.GaugedBar` in SI units.
* **TDMS** (:func:`read_tdms`): one group of equally long channels; time from the
  waveform properties ``wf_start_offset``/``wf_increment`` or from a named time channel.
"""

from __future__ import annotations

import csv
import io
import math
import os
import re
import stat
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from ..signals.gauges import Bridge, GaugedBar
from ..signals.recording import Recording
from ._files import read_bytes_limited

__all__ = [
    "RecordingError",
    "hoppybar_bar",
    "hoppybar_gains",
    "read_csv_recording",
    "read_hoppybar_input",
    "read_lanl_raw",
    "read_tdms",
    "read_tektronix_csv",
]

PathLike = str | os.PathLike

def _regular_file(path: PathLike) -> None:
    """Refuse what is not a regular file (a folder, FIFO or device) before a binary reader opens it."""
    try:
        st = os.stat(path)
    except OSError as exc:
        raise _fail(path, None, f"cannot be read ({exc.strerror or exc})") from None
    if not stat.S_ISREG(st.st_mode):
        raise _fail(path, None, "not a regular file (a folder, device, pipe or socket)")


def _recording(path: PathLike, *args: Any) -> Recording:
    """``Recording(*args)``; its checks (non-finite samples, lengths, time order) fail with the file's name."""
    try:
        return Recording(*args)
    except (ValueError, TypeError) as exc:
        raise _fail(path, None, str(exc)) from None


class RecordingError(ValueError):
    """A malformed recording or input sheet; the message starts with the file's name and, where it applies, the
    (1-based) line: ``shot.csv, line 12: ...``. ``path`` and ``line`` hold them."""

    def __init__(self, message: str, path: str = "", line: int | None = None) -> None:
        super().__init__(message)
        self.path, self.line = path, line


def _fail(path: PathLike, line: int | None, message: str) -> RecordingError:
    where = f"{os.fspath(path)}" + (f", line {line}" if line is not None else "")
    return RecordingError(f"{where}: {message}", os.fspath(path), line)


def _csv_error(path: PathLike, line: int, exc: csv.Error) -> RecordingError:
    """A :class:`RecordingError` for a line the csv module refuses (e.g. a field longer than its limit)."""
    text = str(exc)
    if "field larger than field limit" in text:
        text = (f"a field longer than {csv.field_size_limit():,} characters (the csv module's limit); no "
                f"recording has such fields: the file is damaged or not of this format")
    return _fail(path, line, f"cannot be read as CSV: {text}")


def _read_lines(path: PathLike, complete: bool = False) -> list[str]:
    """Text lines of a file (UTF-8, falling back to Windows-1252), BOM and line ends removed. The file must be a
    regular file within the input size limit (:func:`rodimpact.io._files.read_bytes_limited`). ``complete``: the
    format ends every line with a line end, so a last line without one means the file was cut off."""
    raw = read_bytes_limited(Path(path), os.fspath(path), "recording")
    if complete and raw and not raw.endswith((b"\n", b"\r")):
        n = raw.count(b"\n") + 1
        raise _fail(path, n, "the file ends in the middle of this line: it is truncated (the format ends every line "
                             "with a line end); copy it again from the original")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        text = raw.decode("cp1252", errors="replace")
    return text.splitlines()


def _number(path: PathLike, line: int, text: str, what: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise _fail(path, line, f"{what}: expected a number, found {_clip(text.strip())!r}") from None
    if not math.isfinite(value):
        raise _fail(path, line, f"{what}: value {_clip(text.strip())!r} is not finite")
    return value


def _clip(text: str, n: int = 40) -> str:
    return text if len(text) <= n else text[:n - 3] + "..."


def _value(text: str) -> float | str:
    """A metadata value: a float if it parses as one, else the stripped string (quotes removed)."""
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] == '"':
        text = text[1:-1]
    try:
        value = float(text)
    except ValueError:
        return text
    return value if math.isfinite(value) else text


def _check_increasing(path: PathLike, time: np.ndarray, lines: Sequence[int]) -> None:
    bad = np.flatnonzero(np.diff(time) <= 0)
    if bad.size:
        i = int(bad[0]) + 1
        raise _fail(
            path,
            lines[i],
            f"time {float(time[i])!r} s does not increase (previous sample at line {lines[i - 1]}: {float(time[i - 1])!r} s)",
        )


# -- generic CSV -----------------------------------------------------------------------------
def _split_name_unit(label: str) -> tuple[str, str]:
    match = re.fullmatch(r"\s*(.*?)\s*[\[(]\s*([^\])]*?)\s*[\])]\s*", label)
    if match:
        return match.group(1), match.group(2)
    return label.strip(), ""


def _sniff_delimiter(line: str) -> str | None:
    for delimiter in ("\t", ";", ","):
        if delimiter in line:
            return delimiter
    return None  # whitespace


def _split(line: str, delimiter: str | None, path: PathLike = "", line_no: int = 0) -> list[str]:
    if delimiter is None:
        return line.split()
    try:
        return next(csv.reader([line], delimiter=delimiter))
    except csv.Error as exc:
        raise _csv_error(path, line_no, exc) from None


def _row_values(path: PathLike, line_no: int, line: str, delimiter: str | None, col_names: list[str]) -> list[float]:
    """The numbers of one data line; ``ValueError`` naming the file, the line and the column if a column is
    missing or extra, or a field is no finite number."""
    n_cols = len(col_names)
    fields = _split(line, delimiter, path, line_no)
    if len(fields) < n_cols:
        raise _fail(path, line_no, f"missing columns: expected {n_cols} ({', '.join(col_names)}), found {len(fields)}")
    if len(fields) > n_cols:
        raise _fail(path, line_no, f"extra columns: expected {n_cols}, found {len(fields)}")
    return [_number(path, line_no, text, f"column {c + 1} ({col_names[c]})") for c, text in enumerate(fields)]


def _read_table(text: str, delimiter: str | None, dtype: Any):
    """``text`` as a pandas DataFrame without header (C parser; fields split like :func:`_split`)."""
    import pandas as pd

    options: dict[str, Any] = {"sep": r"\s+", "quoting": csv.QUOTE_NONE} if delimiter is None else \
        {"sep": delimiter, "skipinitialspace": True}
    if dtype is not str and int(pd.__version__.split(".")[0]) < 3:
        options["float_precision"] = "round_trip"     # correctly rounded, as float() (the default from pandas 3)
    return pd.read_csv(io.StringIO(text), header=None, dtype=dtype, engine="c", **options)


def _first_bad_row(texts: Sequence[str], delimiter: str | None, n_cols: int) -> tuple[np.ndarray | None, int | None]:
    """pandas' reading of the data lines: ``(table, None)`` if every line holds ``n_cols`` finite numbers, else
    ``(None, i)`` with the index of the first line it could not read so (whose check then names the problem)."""
    import pandas as pd

    text = "\n".join(texts)
    try:
        data = _read_table(text, delimiter, np.float64).to_numpy()
    except pd.errors.ParserError as exc:           # a line with more fields than the first one
        match = re.search(r"line (\d+)", str(exc))
        bad = int(match.group(1)) - 1 if match else 0
        earlier = _first_bad_row(texts[:bad], delimiter, n_cols)[1] if bad else None
        return None, bad if earlier is None else earlier
    except ValueError:                              # a field that is no number
        frame = _read_table(text, delimiter, str)
        data = frame.apply(pd.to_numeric, errors="coerce").to_numpy(dtype=float)
    if data.shape[1] != n_cols:
        return None, 0
    finite = np.isfinite(data).all(axis=1)
    return (data, None) if finite.all() else (None, int(np.argmin(finite)))


def _parse_rows(path: PathLike, numbers: Sequence[int], texts: Sequence[str], delimiter: str | None,
                col_names: list[str]) -> np.ndarray:
    """The numbers in the data lines ``texts`` (file line ``numbers``), shape (lines, columns), read by pandas.

    A file pandas cannot read as a table of finite numbers is checked line by line from its first bad line on:
    that line's :func:`_row_values` raises the error naming the file, line and column. Only where those rules
    accept what pandas refused (e.g. ``1_000``) is the whole table read line by line.
    """
    data, bad = _first_bad_row(texts, delimiter, len(col_names))
    if bad is None:
        return data
    _row_values(path, numbers[bad], texts[bad], delimiter, col_names)
    return np.array([_row_values(path, n, t, delimiter, col_names) for n, t in zip(numbers, texts)], dtype=float)


def _content_lines(lines: list[str], comment: str) -> tuple[Sequence[int], list[str]]:
    """Line numbers (1-based) and texts of the lines that are neither blank nor start with ``comment``.
    A regular-expression scan finds files without such lines, whose lines are then taken as they are."""
    if comment and lines and (first := lines[0].lstrip()) and not first.startswith(comment):
        # every later line follows a newline: search for a newline, blanks, then a newline, the end or the comment
        skipped = re.compile(rf"\n[^\S\n]*(?:\n|\Z|{re.escape(comment)})")
        if not skipped.search("\n".join(lines)):
            return range(1, len(lines) + 1), lines
    keep = [i for i, ln in enumerate(lines) if (s := ln.lstrip()) and not s.startswith(comment)]
    return [i + 1 for i in keep], [lines[i] for i in keep]


def _time_factor(path: PathLike, line: int, unit: str) -> float:
    """Seconds per ``unit`` (any time unit pint knows: s, ms, us, µs, ns, min, ...)."""
    from .quantities import ModelError, parse_quantity

    try:
        return parse_quantity(f"1 {unit}", "time", "time unit")
    except ModelError:
        raise _fail(path, line, f"time unit {unit!r} not understood; expected a unit of time such as s, ms, us "
                                f"or ns") from None


def read_csv_recording(
    path: PathLike,
    time_column: int | str = 0,
    delimiter: str | None = "auto",
    comment: str = "#",
    names: Sequence[str] | None = None,
    units: dict[str, str] | None = None,
    time_unit: str | None = None,
) -> Recording:
    """Read a delimited text file with a time column and channel columns.

    Parameters
    ----------
    time_column:
        Index or header name of the time column.
    delimiter:
        ``"auto"`` (tab, ``;`` or ``,`` from the first data line, else whitespace), a
        delimiter character, or ``None`` for whitespace.
    comment:
        Lines starting with this string, and blank lines, are skipped.
    names:
        Column names when the file has no header line (including the time column).
    units:
        Channel units, overriding units given in the header.
    time_unit:
        Unit of the time column (s, ms, us, ns); default: from the header, else s.

    A first non-comment line with any non-numeric field is taken as the header.
    """
    if delimiter != "auto" and delimiter is not None and not (isinstance(delimiter, str) and len(delimiter) == 1):
        raise ValueError(f"delimiter: must be one character, 'auto' or None (whitespace), got {delimiter!r}")
    lines = _read_lines(path)
    numbers, texts = _content_lines(lines, comment)
    if not texts:
        raise _fail(path, None, "no data lines")
    if delimiter == "auto":
        delimiter = _sniff_delimiter(texts[0])
    first_no, first = numbers[0], texts[0]
    first_fields = [f.strip() for f in _split(first, delimiter, path, first_no)]

    def numeric(text: str) -> bool:
        try:
            float(text)
        except ValueError:
            return False
        return True

    if not all(numeric(f) for f in first_fields):
        header = first_fields
        numbers, texts = numbers[1:], texts[1:]
    else:
        header = None
    if names is not None:
        labels = list(names)
    elif header is not None:
        labels = header
    else:
        labels = ["time"] + [f"ch{i}" for i in range(1, len(first_fields))]
    parsed = [_split_name_unit(label) for label in labels]
    col_names = [name for name, _ in parsed]
    col_units = [unit for _, unit in parsed]
    if len(set(col_names)) != len(col_names):
        raise _fail(path, first_no, f"duplicate column names {col_names}")
    n_cols = len(col_names)
    if n_cols < 2:
        raise _fail(path, first_no, f"need a time column and at least one channel, found {n_cols} column(s)")
    if isinstance(time_column, str):
        if time_column not in col_names:
            raise _fail(path, first_no, f"no time column {time_column!r}; columns: {col_names}")
        t_index = col_names.index(time_column)
    else:
        t_index = int(time_column)
        if not -n_cols <= t_index < n_cols:
            raise _fail(path, first_no, f"time_column {time_column} out of range for {n_cols} columns")
        t_index %= n_cols
    if not texts:
        raise _fail(path, first_no, "header but no data lines")
    data = _parse_rows(path, numbers, texts, delimiter, col_names)
    unit_t = time_unit if time_unit is not None else (col_units[t_index] or "s")
    time = data[:, t_index] * _time_factor(path, first_no, unit_t)
    if time.size < 2:
        raise _fail(path, numbers[0], "need at least 2 samples")
    _check_increasing(path, time, numbers)
    channels = {col_names[c]: data[:, c] for c in range(n_cols) if c != t_index}
    channel_units = {col_names[c]: col_units[c] for c in range(n_cols) if c != t_index}
    if units:
        for name, unit in units.items():
            if name not in channels:
                raise ValueError(f"{os.fspath(path)}: unit given for unknown channel {name!r}; channels: {list(channels)}")
            channel_units[name] = unit
    return _recording(path, time, channels, channel_units, {"format": "csv"}, os.fspath(path))


# -- LANL .raw ---------------------------------------------------------------------------------
_LANL_CHANNELS = ("incident", "transmitted")


def read_lanl_raw(path: PathLike) -> Recording:
    """Read a LANL split-Hopkinson-bar ``.raw`` file (module docstring for the layout).

    Channels ``"incident"`` (incident/reflected waveform) and ``"transmitted"`` in V; the
    metadata sheet of columns 1-2 becomes ``metadata`` (numbers as floats), the original
    waveform names are kept under ``metadata["channel_labels"]``.
    """
    lines = _read_lines(path, complete=True)
    while lines and not lines[-1].strip():
        lines.pop()
    if len(lines) < 5:
        raise _fail(path, None, f"too short for a LANL .raw file ({len(lines)} lines)")
    table = []
    for i, line in enumerate(lines):
        fields = line.split("\t")
        if len(fields) < 4:
            raise _fail(
                path,
                i + 1,
                f"missing columns: expected 4 tab-separated columns (name, value, incident, transmitted), found {len(fields)}",
            )
        table.append(fields)
    labels = [table[0][2].strip(), table[0][3].strip()]
    starts = [_number(path, 2, table[1][c], f"start time of {labels[c - 2]!r}") for c in (2, 3)]
    steps = [_number(path, 3, table[2][c], f"sample increment of {labels[c - 2]!r}") for c in (2, 3)]
    if any(s <= 0 for s in steps):
        raise _fail(path, 3, f"sample increments must be positive (time must increase), got {steps}")
    if starts[0] != starts[1] or steps[0] != steps[1]:
        raise _fail(path, 2, f"the two waveforms have different time bases: start {starts}, increment {steps}")
    n = len(table) - 3
    data = np.empty((n, 2))
    for r in range(n):
        line_no = r + 4
        for c in (2, 3):
            data[r, c - 2] = _number(path, line_no, table[r + 3][c], f"column {c + 1} ({labels[c - 2]})")
    time = starts[0] + steps[0] * np.arange(n)
    metadata: dict[str, Any] = {}
    for i, fields in enumerate(table):
        key = fields[0].strip()
        if key and key not in metadata:
            value = _value(fields[1])
            if isinstance(value, str) and _non_finite_number(value):
                raise _fail(path, i + 1, f"{key!r}: value {_clip(value)!r} is not a finite number")
            if value != "":
                metadata[key] = value
    metadata["channel_labels"] = dict(zip(_LANL_CHANNELS, labels))
    metadata["format"] = "lanl-raw"
    return _recording(
        path,
        time,
        {"incident": data[:, 0], "transmitted": data[:, 1]},
        {"incident": "V", "transmitted": "V"},
        metadata,
        os.fspath(path),
    )


# -- Tektronix CSV -----------------------------------------------------------------------------
def _tektronix_file(path: PathLike) -> tuple[np.ndarray, np.ndarray, dict[str, Any], dict[str, str], list[int]]:
    lines = _read_lines(path)
    while lines and not lines[-1].strip():
        lines.pop()
    if len(lines) < 2:
        raise _fail(path, None, "too short for a Tektronix CSV file")
    header: dict[str, Any] = {}
    header_units: dict[str, str] = {}
    header_lines: dict[str, int] = {}
    n = len(lines)
    time = np.empty(n)
    values = np.empty(n)
    reader = csv.reader(io.StringIO("\n".join(lines)))
    for i in range(n):
        try:
            fields = next(reader)
        except StopIteration:       # quoted fields spanning lines: fewer records than lines
            raise _fail(path, reader.line_num, "a quoted field runs over several lines; a Tektronix CSV file "
                                               "has one sample a line") from None
        except csv.Error as exc:
            raise _csv_error(path, reader.line_num or i + 1, exc) from None
        line_no = i + 1
        if len(fields) < 5:
            raise _fail(path, line_no, f"missing columns: expected 5 comma-separated columns, found {len(fields)}")
        key = fields[0].strip()
        if key:
            header[key] = _value(fields[1])
            header_lines[key] = line_no
            if fields[2].strip():
                header_units[key] = fields[2].strip()
        time[i] = _number(path, line_no, fields[3], "time (column 4)")
        values[i] = _number(path, line_no, fields[4], "value (column 5)")
    line_numbers = list(range(1, n + 1))
    _check_increasing(path, time, line_numbers)
    length = header.get("Record Length")
    if isinstance(length, float) and int(length) != n:
        raise _fail(path, header_lines["Record Length"], f"header says Record Length {int(length)} but the file has {n} samples")
    interval = header.get("Sample Interval")
    if isinstance(interval, float):
        step = float(np.median(np.diff(time)))
        if abs(step - interval) > 1e-3 * interval:
            raise _fail(
                path, header_lines["Sample Interval"], f"header Sample Interval {interval} s disagrees with the time column step {step} s"
            )
    return time, values, header, header_units, line_numbers


def _channel_name(path: PathLike) -> str:
    stem = Path(path).stem
    match = re.search(r"(?i)(ch\d+)$", stem)
    return match.group(1) if match else stem


def read_tektronix_csv(paths: PathLike | Sequence[PathLike], names: Sequence[str] | None = None) -> Recording:
    """Read one or several Tektronix oscilloscope CSV files (one channel each) into one recording.

    Channel names default to the ``ChN`` suffix of each file name (else the file stem). All
    files must share the time axis. Header fields go to ``metadata["headers"][name]`` and
    their units to ``metadata["header_units"][name]``. Values are in the header's
    ``Vertical Units`` if present, else V.
    """
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    paths = list(paths)
    if not paths:
        raise ValueError("no Tektronix files given")
    if names is None:
        names = [_channel_name(p) for p in paths]
    names = list(names)
    if len(names) != len(paths) or len(set(names)) != len(names):
        raise ValueError(f"need one distinct channel name per file, got {names} for {len(paths)} file(s)")
    channels: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}
    headers: dict[str, dict[str, Any]] = {}
    header_units: dict[str, dict[str, str]] = {}
    time_ref = None
    for name, path in zip(names, paths):
        time, values, header, h_units, _ = _tektronix_file(path)
        if time_ref is None:
            time_ref, ref_path = time, path
        elif time.shape != time_ref.shape or np.max(np.abs(time - time_ref)) > 1e-6 * float(np.median(np.diff(time_ref))):
            raise _fail(path, None, f"time axis differs from that of {os.fspath(ref_path)}")
        channels[name] = values
        vertical = header.get("Vertical Units")
        units[name] = vertical if isinstance(vertical, str) and vertical else "V"
        headers[name] = header
        header_units[name] = h_units
    metadata = {
        "format": "tektronix-csv",
        "source_files": {name: os.fspath(p) for name, p in zip(names, paths)},
        "headers": headers,
        "header_units": header_units,
    }
    return _recording(paths[0], time_ref, channels, units, metadata, os.fspath(paths[0]))


# -- HopPyBar input sheet ------------------------------------------------------------------------
def read_hoppybar_input(path: PathLike) -> dict[str, Any]:
    """Read a HopPyBar/LANL input sheet (``*_Input.dat``): ``{name: value}``.

    Tab-separated lines ``name<TAB>value[<TAB>unit<TAB>note]``; numbers become floats, lines
    without a value (section titles, blank lines) are skipped. Keep the units written in the
    names, e.g. ``"Incident Bar Young's Modulus (GPa)"``; :func:`hoppybar_bar` converts them.

    A value that reads as a number but is not finite (``nan``, ``inf``, ``1e400``) is a
    :class:`RecordingError` naming the file and line, as is a last line with fewer tab-separated
    columns than the sheet's other lines (the sheets write every column on every line, so this
    is a file cut off in the middle of that line: its value may be cut too).
    """
    lines = _read_lines(path)
    while lines and not lines[-1].strip():
        lines.pop()
    counts = [line.count("\t") + 1 for line in lines]
    if len(lines) > 1:
        usual = max(set(counts[:-1]), key=counts[:-1].count)       # the sheet's column count
        if counts[-1] < usual:
            raise _fail(path, len(lines), f"has {counts[-1]} of the {usual} tab-separated columns of the sheet's "
                                          f"other lines: the file is truncated (cut off in this line); copy it "
                                          f"again from the original")
    metadata: dict[str, Any] = {}
    for i, line in enumerate(lines):
        fields = line.split("\t")
        key = fields[0].strip()
        if not key:
            continue
        value = _value(fields[1]) if len(fields) > 1 else ""
        if value == "":
            continue
        if isinstance(value, str) and _non_finite_number(value):
            raise _fail(path, i + 1, f"{key!r}: value {_clip(value)!r} is not a finite number")
        if key in metadata:
            raise _fail(path, i + 1, f"duplicate entry {key!r}")
        metadata[key] = value
    if not metadata:
        raise _fail(path, None, "no name/value entries found")
    return metadata


def _non_finite_number(text: str) -> bool:
    """Whether ``text`` reads as a number that is not finite (``nan``, ``-inf``, ``1e400``)."""
    try:
        return not math.isfinite(float(text))
    except ValueError:
        return False


def _canonical(key: str) -> str:
    name = key.split("(")[0]
    return re.sub(r"\s+", " ", name).strip().lower()


def _entry(metadata: dict[str, Any], name: str) -> tuple[float, str, str]:
    """The numeric entry ``name`` (unit in parentheses ignored when matching): (value, unit, key)."""
    wanted = _canonical(name)
    for key, value in metadata.items():
        if isinstance(key, str) and _canonical(key) == wanted:
            if not isinstance(value, float):
                raise ValueError(f"metadata entry {key!r} must be a number, got {value!r}")
            match = re.search(r"\(([^)]*)\)", key)
            return value, (match.group(1).strip() if match else ""), key
    raise ValueError(f"metadata has no entry {name!r}")


_EXAMPLE_UNITS = {"length": "mm or m", "pressure": "GPa or MPa", "density": "kg/m^3 or g/cm^3"}


def _convert(value: float, unit: str, dimension: str, key: str) -> float:
    """``value`` in ``unit`` converted to SI by pint (:mod:`rodimpact.io.quantities`); a power written without
    ``^`` (``kg/m3``) is read as one."""
    from .quantities import ModelError, parse_quantity

    written = re.sub(r"([A-Za-z])(\d)", r"\1^\2", unit.strip())
    factor = None
    if written:
        try:
            factor = parse_quantity(f"1 {written}", dimension, key)
        except ModelError:
            pass
    if factor is None:
        raise ValueError(f"metadata entry {key!r}: unit {unit!r} not understood; expected a {dimension} unit such "
                         f"as {_EXAMPLE_UNITS[dimension]}")
    return value * factor


#: the two gains of a sheet, per bar: the shot's amplifier gain and the gain of the bar's calibration
_GAIN_KEYS = {"incident": ("Incident/Reflected Bar Gain", "Incident Bar Calibrated Gain"),
              "transmitted": ("Transmitted Bar Gain", "Transmitted Bar Calibrated Gain")}


def hoppybar_gains(metadata: dict[str, Any], bar: str = "incident") -> dict[str, float]:
    """Both amplifier gains a HopPyBar/LANL sheet gives for ``bar``: ``{"shot": ..., "calibrated": ...}``.

    ``shot`` (``Incident/Reflected Bar Gain``, ``Transmitted Bar Gain``, in the shot's section of the sheet) is
    the gain the recorded voltages were amplified with; :func:`hoppybar_bar` uses it, as HopPyBar does.
    ``calibrated`` (``Incident Bar Calibrated Gain``, ``Transmitted Bar Calibrated Gain``, in the bar's
    section) is the gain of the bar's calibration shot, from which the calibrated gauge factor was found; the
    gauge factor is a property of the gauge, so that gain does not apply to other shots. The LANL copper shot
    of ``tests/data/hoppybar`` recorded its transmitted bar at 200 while the bar was calibrated at 500.
    A sheet without one of the entries gives ``None`` for it.
    """
    if bar not in _GAIN_KEYS:
        raise ValueError(f"bar must be 'incident' or 'transmitted', got {bar!r}")
    out: dict[str, Any] = {}
    for which, name in zip(("shot", "calibrated"), _GAIN_KEYS[bar]):
        try:
            out[which] = _entry(metadata, name)[0]
        except ValueError as exc:
            if "has no entry" not in str(exc):
                raise
            out[which] = None
    return out


def hoppybar_bar(
    metadata: dict[str, Any],
    bar: str = "incident",
    *,
    bridge: Bridge | str,
    polarity: int = 1,
    gain: str | float = "shot",
) -> GaugedBar:
    """The gauged incident or transmitted bar described by a HopPyBar/LANL metadata sheet.

    Uses the bar's Young's modulus, density, Poisson ratio, diameter (area ``pi d^2 / 4``;
    for square bars the sheets give the area-equivalent diameter), calibrated gauge factor,
    excitation voltage and the shot's amplifier gain (``Incident/Reflected Bar Gain`` or
    ``Transmitted Bar Gain``). The sheets do not record the bridge circuit, so ``bridge``
    must be given; ``polarity=-1`` if compression was recorded as positive voltage.

    Gain: the sheets carry two per bar (:func:`hoppybar_gains`). ``gain="shot"`` (default) takes the gain
    of this shot's recording, as HopPyBar does: the voltages were amplified by it. ``gain="calibrated"``
    takes the gain of the bar's calibration shot instead (right only if the shot was recorded at that
    gain); a number sets the gain directly.

    Density: the LANL sheets label the density column ``(kg/m^3)`` but hold g/cm^3 values
    (4.416 for Ti-6Al-4V). The unit is therefore checked against the sheet's own ``Rod Sound
    Speed``: of kg/m^3 and g/cm^3 the one giving ``sqrt(E/rho)`` within 1 % of that speed is
    used; if neither does, ``ValueError``.
    """
    if bar not in ("incident", "transmitted"):
        raise ValueError(f"bar must be 'incident' or 'transmitted', got {bar!r}")
    prefix = "Incident Bar" if bar == "incident" else "Transmitted Bar"
    e_val, e_unit, e_key = _entry(metadata, f"{prefix} Young's Modulus")
    youngs = _convert(e_val, e_unit, "pressure", e_key)
    rho_val, rho_unit, rho_key = _entry(metadata, f"{prefix} Density")
    try:
        c_stated, _, _ = _entry(metadata, f"{prefix} Rod Sound Speed")
    except ValueError:
        c_stated = None
    candidates = [_convert(rho_val, rho_unit, "density", rho_key)]
    candidates += [rho_val * f for f in (1.0, 1e3) if not math.isclose(rho_val * f, candidates[0])]
    if c_stated is not None:
        fitting = [rho for rho in candidates if abs(math.sqrt(youngs / rho) / c_stated - 1) <= 0.01]
        if not fitting:
            raise ValueError(
                f"metadata entry {rho_key!r} = {rho_val}: neither kg/m^3 nor g/cm^3 is consistent with "
                f"the stated rod sound speed {c_stated} m/s"
            )
        density = fitting[0]
    else:
        density = candidates[0]
    d_val, d_unit, d_key = _entry(metadata, f"{prefix} Diameter")
    diameter = _convert(d_val, d_unit, "length", d_key)
    gauge_factor, _, _ = _entry(metadata, f"{prefix} Calibrated Gage Factor")
    exc_val, exc_unit, exc_key = _entry(metadata, f"{prefix} Excitation Voltage")
    if exc_unit not in ("V", ""):
        raise ValueError(f"metadata entry {exc_key!r}: unit {exc_unit!r} not understood (expected V)")
    if isinstance(gain, str):
        if gain not in ("shot", "calibrated"):
            raise ValueError(f"gain: must be 'shot', 'calibrated' or a number, got {gain!r}")
        gain, _, _ = _entry(metadata, _GAIN_KEYS[bar][0 if gain == "shot" else 1])
    nu, _, _ = _entry(metadata, f"{prefix} Poisson Ratio")
    return GaugedBar(
        youngs_modulus=youngs,
        density=density,
        area=math.pi * diameter**2 / 4.0,
        gauge_factor=gauge_factor,
        excitation_voltage=exc_val,
        gain=gain,
        bridge=bridge,
        polarity=polarity,
        poisson_ratio=nu,
        name=f"{bar} bar",
    )


# -- TDMS --------------------------------------------------------------------------------------
def read_tdms(path: PathLike, group: str | None = None, time_channel: str | None = None) -> Recording:
    """Read one group of a TDMS file (National Instruments; via npTDMS).

    ``group`` may be omitted if the file has a single group. Time comes from
    ``time_channel`` (a channel of that group, in s) if given, else from the channels'
    waveform properties ``wf_start_offset`` and ``wf_increment``. Units from the channel
    property ``unit_string``; file, group and channel properties go to ``metadata``.
    """
    from nptdms import TdmsFile

    _regular_file(path)
    try:
        tdms = TdmsFile.read(os.fspath(path))
    except Exception as exc:  # npTDMS raises various types for corrupt files
        raise _fail(path, None, f"not a readable TDMS file ({exc})") from exc
    groups = tdms.groups()
    if group is None:
        if len(groups) != 1:
            raise _fail(path, None, f"file has {len(groups)} groups; choose one of {[g.name for g in groups]}")
        grp = groups[0]
    else:
        names = [g.name for g in groups]
        if group not in names:
            raise _fail(path, None, f"no group {group!r}; groups: {names}")
        grp = tdms[group]
    chans = grp.channels()
    if not chans:
        raise _fail(path, None, f"group {grp.name!r} has no channels")
    data = {ch.name: np.asarray(ch[:], dtype=float) for ch in chans}
    lengths = {name: arr.size for name, arr in data.items()}
    if len(set(lengths.values())) != 1:
        raise _fail(path, None, f"channels of group {grp.name!r} differ in length: {lengths}")
    if time_channel is not None:
        if time_channel not in data:
            raise _fail(path, None, f"no time channel {time_channel!r} in group {grp.name!r}; channels: {list(data)}")
        time = data.pop(time_channel)
        bad = np.flatnonzero(np.diff(time) <= 0)
        if bad.size:
            raise _fail(path, None, f"time channel {time_channel!r} does not increase at sample {int(bad[0]) + 1}")
    else:
        tracks = {}
        for ch in chans:
            props = ch.properties
            if "wf_increment" not in props:
                raise _fail(
                    path, None, f"channel {ch.name!r} has no wf_increment property; pass time_channel= to name a time channel"
                )
            increment = float(props["wf_increment"])
            if not increment > 0:
                raise _fail(path, None, f"channel {ch.name!r}: wf_increment {increment} must be positive")
            tracks[ch.name] = (float(props.get("wf_start_offset", 0.0)), increment)
        if len(set(tracks.values())) != 1:
            raise _fail(path, None, f"channels of group {grp.name!r} have different time bases: {tracks}")
        start, increment = next(iter(tracks.values()))
        time = start + increment * np.arange(next(iter(lengths.values())))
    units = {ch.name: str(ch.properties.get("unit_string", "")) for ch in chans if ch.name in data}
    metadata = {
        "format": "tdms",
        "file_properties": dict(tdms.properties),
        "group": grp.name,
        "group_properties": dict(grp.properties),
        "channel_properties": {ch.name: dict(ch.properties) for ch in chans},
    }
    return _recording(path, time, data, units, metadata, os.fspath(path))
