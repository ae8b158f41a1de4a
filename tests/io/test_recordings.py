"""Recording readers: the real HopPyBar files (copies in tests/data/hoppybar) and malformed files."""

import math
from pathlib import Path

import numpy as np
import pytest

from rodimpact.io import (
    RecordingError,
    hoppybar_gains,
    hoppybar_bar,
    read_csv_recording,
    read_hoppybar_input,
    read_lanl_raw,
    read_tdms,
    read_tektronix_csv,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "hoppybar"
LANL = DATA / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"
MINI = DATA / "mini-Kolsky-PMMA-13"


# -- real files ----------------------------------------------------------------------------------
def test_lanl_raw_time_channels_and_metadata():
    rec = read_lanl_raw(LANL)
    # 5003 lines: names, start time, increment, then 5000 samples
    assert rec.n_samples == 5000
    assert rec.time[0] == pytest.approx(-5.0e-5)  # row 2: -5.00E-05
    assert rec.sample_interval == pytest.approx(1.0e-7)  # row 3: 1.00E-07
    assert rec.time[-1] == pytest.approx(-5.0e-5 + 4999e-7)
    # first and last data rows of the file
    assert (rec["incident"][0], rec["transmitted"][0]) == (-0.011292, -0.003967)
    assert (rec["incident"][-1], rec["transmitted"][-1]) == (-0.064089, 0.096744)
    assert rec.units == {"incident": "V", "transmitted": "V"}
    assert rec.metadata["Striker Length(mm)"] == 127.0
    assert rec.metadata["Incident Bar Calibrated Gage Factor"] == 2.061
    assert rec.metadata["Sample Material"] == "Cu"
    assert rec.metadata["channel_labels"]["incident"] == "Incident/Reflected Waveform"


def test_lanl_bar_from_metadata_resolves_the_density_unit():
    bar = hoppybar_bar(read_lanl_raw(LANL).metadata, "incident", bridge="half-axial", polarity=-1)
    # the sheet's density column says kg/m^3 but holds 4.416 (g/cm^3): the stated rod sound speed
    # 4974.964141 m/s = sqrt(109.297184e9 / 4416) decides
    assert bar.density == pytest.approx(4416.0)
    assert bar.youngs_modulus == pytest.approx(109.297184e9)
    assert bar.area == pytest.approx(math.pi * 0.00947**2 / 4)
    assert (bar.gauge_factor, bar.gain, bar.excitation_voltage) == (2.061, 200.0, 8.0)
    assert bar.poisson_ratio == pytest.approx(0.330302)


def test_tektronix_excerpt():
    rec = read_tektronix_csv([MINI / "180303_171828_Ch1.csv", MINI / "180303_171828_Ch2.csv"])
    assert rec.channel_names == ["Ch1", "Ch2"]
    assert rec.n_samples == 15000
    assert rec.time[0] == pytest.approx(-2.0e-5)
    assert rec.time[2500] == 0.0  # "Trigger Point", 2500
    assert rec.sample_interval == pytest.approx(8e-9)
    assert rec["Ch1"][0] == pytest.approx(-3.10624999e-02)
    assert rec.metadata["headers"]["Ch1"]["Trigger Point"] == 2500.0
    assert rec.metadata["header_units"]["Ch1"]["Sample Interval"] == "s"
    assert rec.units["Ch2"] == "V"


def test_hoppybar_input_sheet_and_square_bar():
    meta = read_hoppybar_input(MINI / "PMMA_13_Input.dat")
    assert meta["Striker Length (mm)"] == 25.4
    assert meta["Incident Bar Strain Gage Location (mm)"] == 102.02
    assert meta["Incident Bar Description"] == "Aluminum alloy (7075-T6) bars, 2.1 mm SQUARE"
    bar = hoppybar_bar(meta, "incident", bridge="quarter")
    assert bar.density == pytest.approx(2810.0)  # given in g/cm^3
    assert bar.youngs_modulus == pytest.approx(71.7e9)
    # area-equivalent diameter of the 2.11 mm square bar
    assert bar.area == pytest.approx(2.11e-3**2, rel=1e-8)
    assert bar.wave_speed == pytest.approx(5051.306803, rel=1e-4)  # sheet: rod sound speed


def test_hoppybar_bar_needs_the_bridge_and_known_bar():
    meta = read_hoppybar_input(MINI / "PMMA_13_Input.dat")
    with pytest.raises(TypeError):
        hoppybar_bar(meta, "incident")  # bridge is keyword-only and required
    with pytest.raises(ValueError, match="'incident' or 'transmitted'"):
        hoppybar_bar(meta, "striker", bridge="quarter")
    with pytest.raises(ValueError, match="no entry"):
        hoppybar_bar({"Incident Bar Density (g/cm^3)": 2.8}, "incident", bridge="quarter")


# -- generic CSV ----------------------------------------------------------------------------------
def test_csv_with_header_units_and_time_in_ms(tmp_path):
    path = tmp_path / "shot.csv"
    path.write_text("# comment line\ntime (ms),force [N],strain\n0.0,0.0,0\n0.5,-10.0,-1e-5\n1.0,-20.0,-2e-5\n")
    rec = read_csv_recording(path)
    np.testing.assert_allclose(rec.time, [0.0, 0.5e-3, 1.0e-3])
    assert rec.channel_names == ["force", "strain"]
    assert rec.units == {"force": "N", "strain": ""}
    np.testing.assert_allclose(rec["force"], [0.0, -10.0, -20.0])


def test_csv_without_header_whitespace_and_named_time_column(tmp_path):
    path = tmp_path / "shot.txt"
    path.write_text("1.0 0.0\n2.0 1e-6\n3.0 2e-6\n")
    rec = read_csv_recording(path, time_column=1, names=["v", "t"], units={"v": "V"})
    np.testing.assert_allclose(rec.time, [0.0, 1e-6, 2e-6])
    np.testing.assert_allclose(rec["v"], [1.0, 2.0, 3.0])
    assert rec.units["v"] == "V"
    semi = tmp_path / "semi.csv"
    semi.write_text("t;a;b\n0;1;2\n1;3;4\n")
    assert read_csv_recording(semi, time_column="t").channel_names == ["a", "b"]


# -- malformed files: ValueError naming file and line ---------------------------------------------
@pytest.mark.parametrize(
    ("content", "match"),
    [
        ("time,a,b\n0,1,2\n1,2,3\n2,3\n", r"line 4: missing columns: expected 3"),
        ("time,a\n0,1\n1,x1.5\n", r"line 3: column 2 \(a\): expected a number, found 'x1.5'"),
        ("time,a\n0,1\n1,2\n1,3\n", r"line 4: time 1.0 s does not increase"),
        ("time,a\n0,1\n2,2\n1,3\n", r"line 4: time 1.0 s does not increase"),
        ("time (kg),a\n0,1\n1,2\n", r"line 1: time unit 'kg' not understood; expected a unit of time"),
        ("time (xyz),a\n0,1\n1,2\n", r"line 1: time unit 'xyz' not understood"),
    ],
)
def test_malformed_csv(tmp_path, content, match):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=match) as info:
        read_csv_recording(path)
    assert str(path) in str(info.value)


def _lanl_text(rows):
    head = "Test Date\t12/1/2006\tIncident/Reflected Waveform\tTransmitted Waveform\n"
    head += "Test Time\t11:48\t-5.00E-05\t-5.00E-05\nSystem ID\tHE\t1.00E-07\t1.00E-07\n"
    return head + "".join(r + "\n" for r in rows)


@pytest.mark.parametrize(
    ("rows", "match"),
    [
        (["Striker Length(mm)\t127\t0.1\t0.2", "\t\t0.3\t0.4", "\t\t0.5"], r"line 6: missing columns: expected 4"),
        (["Striker Length(mm)\t127\t0.1\t0.2", "\t\t0.3\tabc", "\t\t0.5\t0.6"], r"line 5: column 4 .*found 'abc'"),
    ],
)
def test_malformed_lanl_raw(tmp_path, rows, match):
    path = tmp_path / "bad.raw"
    path.write_text(_lanl_text(rows))
    with pytest.raises(ValueError, match=match) as info:
        read_lanl_raw(path)
    assert str(path) in str(info.value)


def test_lanl_raw_with_non_increasing_time(tmp_path):
    path = tmp_path / "bad.raw"
    text = _lanl_text(["a\t1\t0.1\t0.2", "\t\t0.3\t0.4", "\t\t0.5\t0.6"]).replace("1.00E-07\t1.00E-07", "0\t0")
    path.write_text(text)
    with pytest.raises(ValueError, match=r"bad.raw, line 3: sample increments must be positive"):
        read_lanl_raw(path)


def _tek_lines(times, values):
    header = ['"Record Length",{n},"Points"', '"Sample Interval",1.0e-006,s', '"Trigger Point",0,"Samples"']
    lines = []
    for i, (t, v) in enumerate(zip(times, values)):
        prefix = header[i].format(n=len(times)) if i < len(header) else ",,"
        lines.append(f"{prefix},{t},{v}")
    return "\n".join(lines) + "\n"


def test_malformed_tektronix(tmp_path):
    path = tmp_path / "scope_Ch1.csv"
    path.write_text(_tek_lines(["0", "1e-6", "2e-6", "2e-6", "4e-6"], ["0", "1", "2", "3", "4"]))
    with pytest.raises(ValueError, match=r"scope_Ch1.csv, line 4: time 2e-06 s does not increase"):
        read_tektronix_csv(path)
    path.write_text(_tek_lines(["0", "1e-6", "2e-6", "3e-6"], ["0", "1", "--", "3"]))
    with pytest.raises(ValueError, match=r"line 3: value \(column 5\): expected a number, found '--'"):
        read_tektronix_csv(path)
    path.write_text(_tek_lines(["0", "1e-6", "2e-6", "3e-6"], ["0", "1", "2", "3"]).replace(",,,3e-6,3", ",,3e-6"))
    with pytest.raises(ValueError, match=r"line 4: missing columns: expected 5"):
        read_tektronix_csv(path)
    path.write_text(_tek_lines(["0", "2e-6", "4e-6", "6e-6"], ["0", "1", "2", "3"]))
    with pytest.raises(ValueError, match=r"line 2: header Sample Interval 1e-06 s disagrees"):
        read_tektronix_csv(path)


def test_tektronix_channels_must_share_the_time_axis(tmp_path):
    a, b = tmp_path / "x_Ch1.csv", tmp_path / "x_Ch2.csv"
    a.write_text(_tek_lines(["0", "1e-6", "2e-6", "3e-6"], ["0", "1", "2", "3"]))
    b.write_text(_tek_lines(["1e-6", "2e-6", "3e-6", "4e-6"], ["0", "1", "2", "3"]))
    with pytest.raises(ValueError, match="time axis differs"):
        read_tektronix_csv([a, b])
    assert read_tektronix_csv([a]).channel_names == ["Ch1"]


# -- TDMS --------------------------------------------------------------------------------------------
def test_tdms_round_trip(tmp_path):
    from nptdms import ChannelObject, GroupObject, TdmsWriter

    path = tmp_path / "shot.tdms"
    props = {"wf_start_offset": -1e-5, "wf_increment": 1e-6, "unit_string": "V"}
    with TdmsWriter(path) as writer:
        writer.write_segment(
            [
                GroupObject("gauges", properties={"gain": 100.0}),
                ChannelObject("gauges", "SG1", np.array([0.0, -1.0, -2.0, -1.0]), properties=props),
                ChannelObject("gauges", "SG2", np.array([0.0, -0.5, -1.0, -0.5]), properties=props),
            ]
        )
    rec = read_tdms(path)
    np.testing.assert_allclose(rec.time, [-1e-5, -9e-6, -8e-6, -7e-6])
    assert rec.channel_names == ["SG1", "SG2"]
    assert rec.units == {"SG1": "V", "SG2": "V"}
    assert rec.metadata["group_properties"]["gain"] == 100.0
    np.testing.assert_allclose(rec["SG2"], [0.0, -0.5, -1.0, -0.5])


def test_tdms_time_channel_and_errors(tmp_path):
    from nptdms import ChannelObject, TdmsWriter

    path = tmp_path / "timed.tdms"
    with TdmsWriter(path) as writer:
        writer.write_segment(
            [
                ChannelObject("a", "Time", np.array([0.0, 1e-6, 3e-6])),
                ChannelObject("a", "F", np.array([1.0, 2.0, 3.0])),
                ChannelObject("b", "F", np.array([1.0, 2.0, 3.0])),
            ]
        )
    with pytest.raises(ValueError, match="2 groups"):
        read_tdms(path)
    with pytest.raises(ValueError, match="no wf_increment"):
        read_tdms(path, group="a")
    rec = read_tdms(path, group="a", time_channel="Time")
    np.testing.assert_allclose(rec.time, [0.0, 1e-6, 3e-6])
    assert rec.channel_names == ["F"]
    bad = tmp_path / "bad.tdms"
    bad.write_bytes(b"not a tdms file at all")
    with pytest.raises(ValueError, match="bad.tdms"):
        read_tdms(bad)


# -- issue 20, items 15 and 18 ---------------------------------------------------------------------
def test_lanl_sheet_exposes_both_gains_and_the_bar_uses_the_shot_gain():
    # the LANL copper shot: "Transmitted Bar Gain 200" (this shot) and "Transmitted Bar Calibrated Gain 500"
    meta = read_lanl_raw(LANL).metadata
    assert meta["Transmitted Bar Gain"] == 200.0 and meta["Transmitted Bar Calibrated Gain"] == 500.0
    assert hoppybar_gains(meta, "transmitted") == {"shot": 200.0, "calibrated": 500.0}
    assert hoppybar_gains(meta, "incident") == {"shot": 200.0, "calibrated": 200.0}
    assert hoppybar_bar(meta, "transmitted", bridge="quarter").gain == 200.0          # as HopPyBar
    assert hoppybar_bar(meta, "transmitted", bridge="quarter", gain="calibrated").gain == 500.0
    assert hoppybar_bar(meta, "transmitted", bridge="quarter", gain=250.0).gain == 250.0
    with pytest.raises(ValueError, match="gain: must be 'shot', 'calibrated' or a number"):
        hoppybar_bar(meta, "transmitted", bridge="quarter", gain="calibration")
    assert hoppybar_gains({"Transmitted Bar Gain": 100.0}, "transmitted") == {"shot": 100.0, "calibrated": None}


def test_tektronix_field_beyond_the_csv_limit_is_a_recording_error_with_file_and_line(tmp_path):
    # a field over 131,072 characters raised _csv.Error from inside the reader
    lines = (MINI / "180303_171828_Ch1.csv").read_text().splitlines()
    lines[4] = lines[4] + "," + "7" * 200_000
    path = tmp_path / "shot_Ch1.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(RecordingError, match=r"shot_Ch1\.csv, line 5: cannot be read as CSV: a field longer than "
                                             r"131,072 characters") as info:
        read_tektronix_csv(path)
    assert info.value.line == 5 and info.value.path == str(path)


def test_csv_recording_field_beyond_the_csv_limit_names_file_and_line(tmp_path):
    path = tmp_path / "shot.csv"
    path.write_text('time [s],force [N]\n0,1\n1e-6,"' + "1" * 200_000 + '\n2e-6,3\n')
    with pytest.raises(RecordingError, match=r"shot\.csv, line 3: "):
        read_csv_recording(path)


def _sheet_lines() -> list[str]:
    return (MINI / "PMMA_13_Input.dat").read_bytes().decode("cp1252").split("\r\n")


@pytest.mark.parametrize("cut", ["Incident Bar Density (g/cm^3)\t2.8", "Incident Bar Density (g/cm^3)\t2.81\tg/c",
                                 "Incident Bar Den"])
def test_hoppybar_sheet_cut_off_in_a_line_is_refused(tmp_path, cut):
    lines = _sheet_lines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("Incident Bar Density"))
    path = tmp_path / "cut_Input.dat"
    path.write_bytes("\r\n".join(lines[:k] + [cut]).encode("cp1252"))
    with pytest.raises(RecordingError, match=rf"cut_Input\.dat, line {k + 1}: has \d of the 4 tab-separated columns "
                                             r".* truncated"):
        read_hoppybar_input(path)


def test_hoppybar_sheet_cut_at_a_line_end_still_reads():
    # the shipped sheet ends without a line end after a full line: not truncated
    assert read_hoppybar_input(MINI / "PMMA_13_Input.dat")["d_bar_t_equiv (goes to B53)"] == 2.380880043


@pytest.mark.parametrize("value", ["nan", "inf", "-Infinity", "1e400", "NaN"])
def test_hoppybar_sheet_non_finite_numbers_are_refused(tmp_path, value):
    lines = _sheet_lines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("Incident Bar Young's Modulus"))
    lines[k] = f"Incident Bar Young's Modulus (GPa)\t{value}\tGPa\t"
    path = tmp_path / "bad_Input.dat"
    path.write_bytes("\r\n".join(lines).encode("cp1252"))
    with pytest.raises(RecordingError, match=rf"bad_Input\.dat, line {k + 1}: \"Incident Bar Young's Modulus \(GPa\)\": "
                                             rf"value '{value}' is not a finite number"):
        read_hoppybar_input(path)


def test_lanl_metadata_non_finite_numbers_are_refused(tmp_path):
    lines = LANL.read_bytes().decode("cp1252").split("\n")
    k = next(i for i, ln in enumerate(lines) if ln.startswith("Transmitted Bar Gain"))
    fields = lines[k].split("\t")
    lines[k] = "\t".join([fields[0], "1e400"] + fields[2:])
    path = tmp_path / "shot.raw"
    path.write_bytes("\n".join(lines).encode("cp1252"))
    with pytest.raises(RecordingError, match=rf"shot\.raw, line {k + 1}: 'Transmitted Bar Gain': value '1e400' is "
                                             r"not a finite number"):
        read_lanl_raw(path)
