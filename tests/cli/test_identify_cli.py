"""``rodimpact identify``: a simulated pile record (CSV, force in kN compression positive as practice writes it)
through the command line; the spec's errors name their key paths."""

import json
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from test_cli import main_in_process as main          # tests/cli/test_cli.py: the console script, in process

DT = 1e-6
LANL = Path(__file__).resolve().parents[1] / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"


def write_head_csv(path, rows, header="time [s],force [N],velocity [m/s]"):
    """A head record as the CSV table `rodimpact identify` reads: a header, then one row per sample."""
    path.write_text(header + "\n" + "\n".join(",".join(repr(float(x)) for x in r) for r in rows) + "\n")


def pile_csv(path):
    """A pile of 50 + 150 elements, impedance 4e5 then 2.8e5 N s/m (beta = 0.7), hit by a half-sine pulse."""
    rod = ri.Rod.from_impedance([4.0e5] * 50 + [2.8e5] * 150, dt=DT)
    tk = DT * np.arange(301)
    f = np.where(tk < 20 * DT, -1.0e3 * np.sin(np.pi * tk / (20 * DT)), 0.0)
    system = ri.System([rod], [0.0], left=ri.ForceEnd((tk, f), interpolation="previous"), right="nonreflecting")
    res = ri.simulate(ri.Problem.of(system, steps=300, dt=DT), backend="numpy")
    rows = np.column_stack([res.time * 1e3, -np.asarray(res.end_force["left"]) / 1e3, res.end_velocity["left"]])
    write_head_csv(path, rows, "time [ms],force [kN],velocity [m/s]")
    m = rod.segments[0].material
    return float(np.sqrt(m.youngs_modulus / m.density))


def test_identify_beta_from_a_csv(tmp_path, capsys, monkeypatch):
    c = pile_csv(tmp_path / "pile.csv")
    (tmp_path / "spec.toml").write_text(f'[identify]\nmethod = "beta"\n[record]\nforce_sign = "compression"\n'
                                        f'[rod]\nimpedance = "400 kN s/m"\nwave_speed = {c!r}\n')
    code, out, err = main(["identify", "pile.csv", "--spec", "spec.toml", "-o", "out", "--json"], tmp_path, capsys,
                          monkeypatch)
    assert code == 0, err
    summary = json.loads(out)
    (a,) = summary["anomalies"]
    assert abs(a["beta"] - 0.7) < 1e-12 and a["beta_class"] == "damage"
    assert abs(a["depth"] - 50 * c * DT) < 1e-9
    back = ri.load(tmp_path / "out" / "identification.nc")
    assert back.anomalies[0].beta == a["beta"]
    assert (tmp_path / "out" / "profile.csv").is_file() and (tmp_path / "out" / "plots" / "profile.png").is_file()
    assert (tmp_path / "out" / "plots" / "reflectogram.png").is_file()


def test_spec_errors_name_the_key(tmp_path, capsys, monkeypatch):
    pile_csv(tmp_path / "pile.csv")
    (tmp_path / "spec.toml").write_text('[identify]\nmethod = "beta"\n[rod]\nimpedance = "400 kN"\n')
    code, _, err = main(["identify", "pile.csv", "--spec", "spec.toml", "--no-output"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rod.impedance" in err and "impedance" in err
    (tmp_path / "spec.toml").write_text('[identify]\nmethod = "beta"\n[rod]\nimpedance = "400 kN s/m"\n')
    code, _, err = main(["identify", "pile.csv", "--spec", "spec.toml", "--no-output"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rod.wave_speed: missing" in err


def test_striker_of_the_lanl_shot(tmp_path, capsys, monkeypatch):
    (tmp_path / "spec.toml").write_text('[identify]\nmethod = "striker"\nresamples = 5\n'
                                        '[record]\nbridge = "half-axial"\npolarity = -1\nend = "150 us"\n')
    code, out, err = main(["identify", str(LANL), "--spec", "spec.toml", "--json"], tmp_path, capsys, monkeypatch)
    assert code == 0, err
    summary = json.loads(out)
    assert abs(summary["toe_m"] - 0.127) < 0.022 * 0.127            # the sheet's 127 mm (see test_striker.py)


def test_a_recording_with_named_channels_and_units(tmp_path, capsys, monkeypatch):
    """The same pile as a recording with a time column and named channels, force in kN (compression positive),
    velocity in mm/s (rodimpact.io.read_csv_recording's header units): the units are converted, beta unchanged.
    A channel unit of the wrong dimension names the key."""
    c = pile_csv(tmp_path / "pile.csv")
    rows = (tmp_path / "pile.csv").read_text().splitlines()[1:]
    table = ["time [ms],F [kN],V [mm/s]"] + [",".join([a, b, repr(float(v) * 1e3)]) for a, b, v in
                                                (r.split(",") for r in rows)]
    (tmp_path / "rec.csv").write_text("\n".join(table) + "\n")
    spec = (f'[identify]\nmethod = "beta"\n[record]\nforce_sign = "compression"\nforce_channel = "F"\n'
            f'velocity_channel = "V"\n[rod]\nimpedance = "400 kN s/m"\nwave_speed = {c!r}\n')
    (tmp_path / "spec.toml").write_text(spec)
    code, out, err = main(["identify", "rec.csv", "--spec", "spec.toml", "--json"], tmp_path, capsys, monkeypatch)
    assert code == 0, err
    (a,) = json.loads(out)["anomalies"]
    assert abs(a["beta"] - 0.7) < 1e-12
    (tmp_path / "rec.csv").write_text("\n".join(["time [ms],F [kN],V [kN]"] + table[1:]) + "\n")
    code, _, err = main(["identify", "rec.csv", "--spec", "spec.toml", "--no-output"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "record.velocity_channel (V [kN])" in err


def test_the_spec_reference_in_the_docs_is_current():
    """docs/identification.md holds the generated spec reference (rodimpact docs identify) verbatim."""
    from rodimpact.io.identify_spec import spec_reference_markdown

    page = (Path(__file__).resolve().parents[2] / "docs" / "identification.md").read_text(encoding="utf-8")
    assert spec_reference_markdown() in page, "docs/identification.md: regenerate the spec reference section"


def test_identify_peeling_with_noise_bands(tmp_path, capsys, monkeypatch):
    """A clean record of a two-step pile hit by a mass (sharp front) through the command line: peeling gives the
    profile back to rounding (the CSV keeps every digit), and with `noise` the result carries bands."""
    rod = ri.Rod.from_impedance([4.0e5] * 30 + [3.0e5] * 30, dt=DT)
    tk = DT * np.arange(121)
    head = ri.ForceEnd((tk, -1.0e5 * np.exp(-tk / 60e-6)), interpolation="previous")
    res = ri.simulate(ri.Problem.of(ri.System([rod], [0.0], left=head, right="nonreflecting"), steps=120, dt=DT),
                      backend="numpy")
    rows = np.column_stack([res.time, res.end_force["left"], res.end_velocity["left"]])[::2]
    write_head_csv(tmp_path / "head.csv", rows)
    (tmp_path / "spec.toml").write_text('[identify]\nmethod = "peeling"\nnoise = "1 N"\nresamples = 20\n'
                                        '[rod]\nimpedance = "400 kN s/m"\nwave_speed = "5175.5 m/s"\n')
    code, _, err = main(["identify", "head.csv", "--spec", "spec.toml", "-o", "out", "--no-plots"], tmp_path, capsys,
                        monkeypatch)
    assert code == 0, err
    back = ri.load(tmp_path / "out" / "identification.nc")
    assert np.max(np.abs(back.impedance / np.r_[[4.0e5] * 30, [3.0e5] * 30] - 1)) < 1e-10
    assert back.lower is not None and np.all(back.lower <= back.impedance)
    assert back.anomalies[0].beta == pytest.approx(0.75, rel=1e-10)


@pytest.mark.parametrize("text, message", [
    ('[identify]\nmethod = "peel"\n', "identify.method"),
    ('[identify]\nmethod = "beta"\nthreshhold = 0.1\n', "identify.threshhold"),
    ('[identify]\nmethod = "beta"\n[record]\nstart = "2 ms"\nend = "1 ms"\n', "record.end: must be after record.start"),
    ('[identify]\nmethod = "beta"\n[record]\nlow_pass = "5 kN"\n', "record.low_pass"),
    ('[rod]\nimpedance = "1 kN s/m"\n', "identify: missing"),
    ('[identify]\nmethod = "matching"\nextension = 3\n', "identify.extension: must be a share of the length in [0, 2]"),
    ('[identify]\nmethod = "matching"\nelements = 2\n', "identify.elements"),
    ('[identify]\nmethod = "matching"\nband_scale = 0\n', "identify.band_scale"),
    ('[identify]\nmethod = "matching"\nweight = -1\n', "identify.weight"),
    ('[identify]\nmethod = "matching"\nbands = "mcmc"\n', "identify.bands"),
])
def test_bad_specs_name_the_key(tmp_path, capsys, monkeypatch, text, message):
    pile_csv(tmp_path / "pile.csv")
    (tmp_path / "spec.toml").write_text(text)
    code, _, err = main(["identify", "pile.csv", "--spec", "spec.toml", "--no-output"], tmp_path, capsys, monkeypatch)
    assert code == 2 and message in err, err


def test_identify_matching_from_a_csv(tmp_path, capsys, monkeypatch):
    """Method matching through the command line: a pile of 48 elements with a 30 % neck at 1.5-2.25 m, shaft and
    toe soil, computed on a lattice twice as fine, 2 % noise with a pre-trigger baseline; the neck and the toe
    (6 m) come back, with bands, into the output folder."""
    from rodimpact.identify.matching import PileModel, half_sine

    n, c, length, z0 = 48, 4000.0, 6.0, 3e5
    dt = length / (c * n)
    zf = np.full(2 * n, z0)
    zf[24:36] *= 0.7
    pre, steps = 40, 40 + 2 * 66 + 10
    tf = np.arange(2 * steps) * dt / 2
    ff = half_sine(tf, 1e4, 6 * dt, pre * dt)
    y = PileModel(dt / 2, 2 * n, ff, z0).simulate(np.r_[np.log(zf / z0), 0.4, 0.4, 8.0, 0.4])
    y = y.reshape(-1, 2).mean(axis=1)
    y = y + np.random.default_rng(3).normal(0.0, 0.02 * np.sqrt(np.mean(y[pre:] ** 2)), y.size)
    rows = np.column_stack([np.arange(steps) * dt, ff.reshape(-1, 2).mean(axis=1), y])
    write_head_csv(tmp_path / "pile.csv", rows)
    (tmp_path / "spec.toml").write_text(f'[identify]\nmethod = "matching"\n'
                                        f'[rod]\nimpedance = "300 kN s/m"\nwave_speed = "{c} m/s"\nlength = "6.3 m"\n')
    code, out, err = main(["identify", "pile.csv", "--spec", "spec.toml", "-o", "out", "--json"], tmp_path, capsys,
                          monkeypatch)
    assert code == 0, err
    summary = json.loads(out)
    assert summary["method"] == "matching"
    assert abs(summary["toe_m"] - length) <= c * dt + 1e-9
    assert summary["toe_band"][0] <= summary["toe_m"] <= summary["toe_band"][1]
    neck = [a for a in summary["anomalies"] if a["relative_change"] < 0]
    assert neck and abs(neck[0]["depth"] - 12 * c * dt) <= c * dt and abs(neck[0]["relative_change"] + 0.3) < 0.08
    back = ri.load(tmp_path / "out" / "identification.nc")
    assert back.lower is not None and np.all(back.lower <= back.impedance) and np.all(back.impedance <= back.upper)
    assert (tmp_path / "out" / "profile.csv").is_file() and (tmp_path / "out" / "plots" / "profile.png").is_file()
    # the expected length is required for matching, and named
    (tmp_path / "spec.toml").write_text(f'[identify]\nmethod = "matching"\n[rod]\nwave_speed = "{c} m/s"\n')
    code, _, err = main(["identify", "pile.csv", "--spec", "spec.toml", "--no-output"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rod.length: missing" in err
