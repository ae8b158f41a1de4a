"""``rodimpact identify``: a simulated pile record (CSV, force in kN compression positive as practice writes it)
through the command line; the spec's errors name their key paths."""

import json
from pathlib import Path

import numpy as np

import rodimpact as ri
from test_cli import main_in_process as main          # tests/cli/test_cli.py: the console script, in process

DT = 1e-6
LANL = Path(__file__).resolve().parents[1] / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"


def pile_csv(path):
    """A pile of 50 + 150 elements, impedance 4e5 then 2.8e5 N s/m (beta = 0.7), hit by a half-sine pulse."""
    rod = ri.Rod.from_impedance([4.0e5] * 50 + [2.8e5] * 150, dt=DT)
    tk = DT * np.arange(301)
    f = np.where(tk < 20 * DT, -1.0e3 * np.sin(np.pi * tk / (20 * DT)), 0.0)
    system = ri.System([rod], [0.0], left=ri.ForceEnd((tk, f), interpolation="previous"), right="nonreflecting")
    res = ri.simulate(ri.Problem.of(system, steps=300, dt=DT), backend="numpy")
    rows = np.column_stack([res.time * 1e3, -np.asarray(res.end_force["left"]) / 1e3, res.end_velocity["left"]])
    path.write_text("time [ms],force [kN],velocity [m/s]\n" + "\n".join(",".join(repr(float(x)) for x in r)
                                                                        for r in rows) + "\n")
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
