"""The CSV recording reader reads its table with pandas and converts units with pint (issue 14, item 12): a large
file gives exactly the numbers a plain cell-by-cell ``float()`` parse gives; a bad line anywhere is reported with
the file, line and column as before; time and metadata units go through pint."""

import math

import numpy as np
import pytest

from rodimpact.io import hoppybar_bar, read_csv_recording

ROWS, CHANNELS = 20_000, 10


def table_text(rng, fmt, sep):
    """A header with units, comment and blank lines in between, and ROWS rows of time + CHANNELS channels."""
    time = (np.arange(ROWS) * 1e-2).tolist()                      # ms
    values = (rng.standard_normal((ROWS, CHANNELS)) * 10.0 ** rng.integers(-9, 6, (ROWS, CHANNELS))).tolist()
    names = sep.join(["time [ms]"] + [f"ch{c} [V]" for c in range(CHANNELS)]) if sep != " " else \
        " ".join(["time"] + [f"ch{c}" for c in range(CHANNELS)])
    lines = ["# a comment before the header", names]
    for r in range(ROWS):
        lines.append(sep.join(fmt(v) for v in [time[r]] + values[r]))
        if r % 5000 == 17:
            lines += ["", "   # a comment inside the table", "   "]
    return "\n".join(lines) + "\n"


def plain_parse(text, sep):
    """The baseline: every non-comment, non-blank line after the header split and read with float()."""
    rows = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")][1:]
    return np.array([[float(f) for f in (ln.split() if sep == " " else ln.split(sep))] for ln in rows])


@pytest.mark.parametrize("fmt, sep", [(repr, ","), (lambda v: f"{v:.6e}", ";"), (lambda v: f"{v:.9g}", "\t"),
                                      (lambda v: f"{v:.17g}", " ")])
def test_a_large_file_gives_the_numbers_of_a_plain_parse(tmp_path, fmt, sep):
    rng = np.random.default_rng(14)
    text = table_text(rng, fmt, sep)
    path = tmp_path / "large.csv"
    path.write_text(text)
    rec = read_csv_recording(path, time_unit=None if sep != " " else "ms")
    expected = plain_parse(text, sep)
    assert rec.n_samples == ROWS and rec.channel_names == [f"ch{c}" for c in range(CHANNELS)]
    np.testing.assert_array_equal(rec.time, expected[:, 0] * 1e-3)
    for c in range(CHANNELS):
        np.testing.assert_array_equal(rec[f"ch{c}"], expected[:, c + 1])       # bit for bit
    if sep != " ":
        assert rec.units["ch3"] == "V"


def numbered(n_rows, bad_line=None, bad_text=None):
    """'time,a,b' and n_rows rows; row i sits on file line i + 2. ``bad_line`` replaces that file line."""
    lines = ["time,a,b"] + [f"{i * 1e-6!r},{i},{-i}" for i in range(n_rows)]
    if bad_line is not None:
        lines[bad_line - 1] = bad_text
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("bad_line, bad_text, match", [
    (5001, "5e-3,1", r"line 5001: missing columns: expected 3 \(time, a, b\), found 2"),
    (5001, "5e-3,1,2,3", r"line 5001: extra columns: expected 3, found 4"),
    (7000, "7e-3,1,x2", r"line 7000: column 3 \(b\): expected a number, found 'x2'"),
    (8000, "8e-3,,2", r"line 8000: column 2 \(a\): expected a number, found ''"),
    (9000, "9e-3,nan,2", r"line 9000: column 2 \(a\): value 'nan' is not finite"),
    (9000, "9e-3,1,-inf", r"line 9000: column 3 \(b\): value '-inf' is not finite"),
    (10001, "0.01", r"line 10001: missing columns: expected 3"),                      # a truncated last line
    (2, "0,1", r"line 2: missing columns: expected 3"),
])
def test_a_bad_line_in_a_large_file_is_named(tmp_path, bad_line, bad_text, match):
    path = tmp_path / "bad.csv"
    path.write_text(numbered(10_000, bad_line, bad_text))
    with pytest.raises(ValueError, match=match) as info:
        read_csv_recording(path)
    assert str(path) in str(info.value)


def test_the_first_bad_line_is_reported_whatever_its_kind(tmp_path):
    lines = numbered(3000).splitlines()
    lines[99] = "1e-4,text,1"           # line 100: not a number
    lines[1999] = "2e-3,1,2,3"          # line 2000: extra columns (pandas stops tokenizing here)
    path = tmp_path / "two.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=r"line 100: column 2 \(a\): expected a number, found 'text'"):
        read_csv_recording(path)


def test_numbers_python_reads_but_pandas_does_not_are_still_read(tmp_path):
    path = tmp_path / "underscore.csv"
    path.write_text("time,a\n0,1_000\n1,2\n")
    rec = read_csv_recording(path)
    np.testing.assert_array_equal(rec["a"], [1000.0, 2.0])


@pytest.mark.parametrize("header, time_unit, seconds", [
    ("time [min]", None, 60.0), ("t (µs)", None, 1e-6), ("t (us)", None, 1e-6), ("t", "ns", 1e-9),
    ("t [s]", "ms", 1e-3),                                           # the argument wins over the header
])
def test_time_units_by_pint(tmp_path, header, time_unit, seconds):
    path = tmp_path / "t.csv"
    path.write_text(f"{header},a\n0,1\n2,2\n")
    rec = read_csv_recording(path, time_unit=time_unit)
    assert list(rec.time) == [0.0, 2.0 * seconds]


def test_metadata_units_by_pint():
    sheet = {"Incident Bar Young's Modulus (MPa)": 71.7e3, "Incident Bar Density (g/cm3)": 2.81,
             "Incident Bar Diameter (m)": 0.002, "Incident Bar Calibrated Gage Factor": 2.0,
             "Incident Bar Excitation Voltage (V)": 10.0, "Incident/Reflected Bar Gain": 1.0,
             "Incident Bar Poisson Ratio": 0.33}
    bar = hoppybar_bar(sheet, bridge="quarter")
    assert bar.youngs_modulus == pytest.approx(71.7e9, rel=1e-15)
    assert bar.density == pytest.approx(2810.0, rel=1e-15)
    assert bar.area == pytest.approx(math.pi * 0.002**2 / 4, rel=1e-15)
    sheet["Incident Bar Density (kg/m3)"] = sheet.pop("Incident Bar Density (g/cm3)") * 1e3
    assert hoppybar_bar(sheet, bridge="quarter").density == pytest.approx(2810.0, rel=1e-15)
    sheet["Incident Bar Diameter (kg)"] = sheet.pop("Incident Bar Diameter (m)")
    with pytest.raises(ValueError, match=r"'Incident Bar Diameter \(kg\)': unit 'kg' not understood; expected a "
                                         r"length unit such as mm or m"):
        hoppybar_bar(sheet, bridge="quarter")


@pytest.mark.parametrize("text", ["time,a\n0,1\n1,2\n   \n", "time,a\n0,1\n\t# note\n1,2\n", "  # c\ntime,a\n0,1\n1,2",
                                  "time,a\n\n0,1\n1,2\n", "time,a\n0,1\n1,2\n \t"])
def test_blank_and_comment_lines_anywhere_are_skipped(tmp_path, text):
    path = tmp_path / "c.csv"
    path.write_text(text)
    rec = read_csv_recording(path)
    np.testing.assert_array_equal(rec["a"], [1.0, 2.0])


def test_line_numbers_count_skipped_lines(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("# 1\ntime,a\n\n0,1\n# 5\n1,x\n")
    with pytest.raises(ValueError, match=r"line 6: column 2 \(a\): expected a number, found 'x'"):
        read_csv_recording(path)


@pytest.mark.parametrize("delimiter", ["||", "", 3])
def test_a_delimiter_must_be_one_character(tmp_path, delimiter):
    path = tmp_path / "d.csv"
    path.write_text("time,a\n0,1\n1,2\n")
    with pytest.raises(ValueError, match="delimiter: must be one character, 'auto' or None"):
        read_csv_recording(path, delimiter=delimiter)
    assert read_csv_recording(path, delimiter=",").channel_names == ["a"]
