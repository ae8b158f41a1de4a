"""`rodimpact shpb reduce`: the LANL copper shot from its .raw file, a Tektronix set with the bars in a spec, the
output folder (never overwritten without --force), bad input with exit code 2, and the spec reference."""

import json
from pathlib import Path

import numpy as np
import pytest
import rodimpact as ri
from rodimpact import cli
from rodimpact.io import hoppybar_bar, read_lanl_raw
from rodimpact.io.shpb_reduction_spec import spec_reference_markdown
from rodimpact.shpb import Bar, GaugeSignals, ShpbReduction, SpecimenGeometry, reduce_shot

ROOT = Path(__file__).resolve().parents[2]
LANL = ROOT / "tests" / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"
RAW = [str(LANL), "--bridge", "half-axial", "--polarity", "-1"]


def test_lanl_shot_from_its_raw_file(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["shpb", "reduce", *RAW, "-o", "out", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    out = tmp_path / "out"
    assert sorted(summary["files"]) == sorted(["reduction.csv", "reduction.nc", "spec.toml", "plots/pulses.png",
                                               "plots/stress-strain.png", "plots/strain-rate.png",
                                               "plots/equilibrium.png", "summary.json"])
    assert all((out / f).is_file() for f in summary["files"])
    # the same as the Python API with the sheet's bars and specimen
    rec = read_lanl_raw(LANL)
    gauges = [hoppybar_bar(rec.metadata, b, bridge="half-axial", polarity=-1) for b in ("incident", "transmitted")]
    expected = reduce_shot(GaugeSignals.from_recording(rec, *gauges), *(Bar.from_gauged(g, 0.381) for g in gauges),
                           SpecimenGeometry(length=3.204e-3, diameter=6.34e-3))
    written = ri.load(out)                                   # the output folder's reduction.nc
    assert isinstance(written, ShpbReduction)
    np.testing.assert_allclose(written.three_wave.stress, expected.three_wave.stress, rtol=1e-12)
    assert summary["equilibrium"]["equilibrium_time_s"] == pytest.approx(expected.equilibrium.equilibrium_time)
    assert summary["specimen_length_m"] == pytest.approx(3.204e-3) and summary["bars"]["incident"]["diameter_m"] \
        == pytest.approx(9.47e-3)
    # never over the earlier results without --force
    assert cli.main(["shpb", "reduce", *RAW, "-o", "out"]) == 2
    assert "out: exists and is not empty" in capsys.readouterr().err
    assert cli.main(["shpb", "reduce", *RAW, "-o", "out", "--force", "--no-plots", "--dispersion", "--quiet"]) == 0
    assert not (out / "plots").exists()
    assert ri.load(out / "reduction.nc").dispersion_corrected


def _tektronix(path, time, volts):
    """A Tektronix CSV file: header fields in columns 1-3 of the first rows, time and value in columns 4-5."""
    time, volts = time.tolist(), volts.tolist()
    header = [f'"Record Length",{len(time)},"Points"', f'"Sample Interval",{time[1] - time[0]!r},s',
              '"Trigger Point",0,"Samples"', '"Trigger Time",0,s', '"",,', f'"Horizontal Offset",{time[0]!r},s']
    rows = [(header[i] if i < len(header) else ",,") + f",{t!r},{v!r}" for i, (t, v) in enumerate(zip(time, volts))]
    path.write_text("\r\n".join(rows) + "\r\n", encoding="ascii")


def test_tektronix_set_with_the_bars_in_a_spec(tmp_path, monkeypatch, capsys):
    """The closed-form shot of tests/shpb, recorded through quarter bridges (V = V_exc gain GF eps / (4 + 2 GF eps))
    into two Tektronix files; the spec gives the channels, bars, gauges and specimen: the 3-wave stress comes back
    as the law of the strain over the pulse (the automatic windows run on past its end)."""
    import sys

    sys.path.insert(0, str(ROOT / "tests" / "shpb"))
    try:
        from shpb_synthetic import SAMPLES, SPECIMEN, build_shot, law, ti_bar
    finally:
        sys.path.pop(0)
    shot = build_shot(ti_bar(), ti_bar("transmitted"), SPECIMEN)
    gf, exc, gain = 2.0, 10.0, 100.0
    for name, eps in (("shot_Ch1", shot.signals.incident), ("shot_Ch3", shot.signals.transmitted)):
        _tektronix(tmp_path / f"{name}.csv", shot.signals.time, exc * gain * gf * eps / (4 + 2 * gf * eps))
    bar = shot.incident_bar
    spec = f"""title = "closed-form shot"
[recording]
files = ["shot_Ch1.csv", "shot_Ch3.csv"]
incident_channels = ["Ch1"]
transmitted_channels = ["Ch3"]
[incident_bar]
youngs_modulus = {bar.youngs_modulus!r}
wave_speed = "{bar.wave_speed!r} m/s"
diameter = "9.47 mm"
gauge_distance = {bar.gauge_distance!r}
bridge = "quarter"
gauge_factor = {gf}
excitation_voltage = {exc}
gain = {gain}
[transmitted_bar]
youngs_modulus = {bar.youngs_modulus!r}
density = {bar.material.density!r}
area = {bar.area!r}
gauge_distance = {shot.transmitted_bar.gauge_distance!r}
bridge = "quarter"
gauge_factor = {gf}
excitation_voltage = {exc}
gain = {gain}
[specimen]
length = "3.2 mm"
diameter = "6.34 mm"
[output]
plots = false
"""
    (tmp_path / "shot.toml").write_text(spec)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["shpb", "reduce", "--spec", "shot.toml", "-o", "out"]) == 0
    text = capsys.readouterr().out
    assert text.startswith("closed-form shot\n") and "positive in compression" in text
    three = ri.load(tmp_path / "out").three_wave
    stress, strain = three.stress[:SAMPLES], three.strain[:SAMPLES]
    np.testing.assert_allclose(stress, law(strain), rtol=0, atol=1e-6 * stress.max())
    assert (tmp_path / "out" / "spec.toml").read_text() == spec


@pytest.mark.parametrize("args, message", [
    ([str(LANL)], "incident_bar.bridge: missing; the LANL and HopPyBar sheets do not record the bridge circuit"),
    ([*RAW, "--set", "specimen.diameter=12 mm"], "specimen.diameter: 12 mm is wider than the incident_bar (9.47 mm)"),
    ([*RAW, "--set", "reduction.threshold=2"], "threshold: must be < 1"),
    ([*RAW, "--set", "incident_bar.polarity=2"], "incident_bar.polarity: must be 1 or -1, got 2"),
    ([*RAW, "--set", "specimen.lenght=3 mm"], "specimen.lenght: unknown key (did you mean 'length'?)"),
    (["--bridge", "quarter"], "recording.files: no recording given"),
    (["missing.raw", "--bridge", "quarter"], "missing.raw"),
    (["shot.wav"], "recording.format: shot.wav: unknown file type '.wav'"),
])
def test_bad_input_exits_2_naming_the_key(tmp_path, monkeypatch, capsys, args, message):
    monkeypatch.chdir(tmp_path)
    assert cli.main(["shpb", "reduce", *args, "--no-output"]) == 2
    assert message in capsys.readouterr().err


def test_spec_reference_is_printed_and_in_the_cli_docs(capsys):
    assert cli.main(["docs", "shpb-reduce"]) == 0
    assert capsys.readouterr().out == spec_reference_markdown()
    page = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    assert spec_reference_markdown() in page, "docs/cli.md: regenerate the shpb spec reference section"
