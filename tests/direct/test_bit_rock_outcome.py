"""What a blow does to the rock (SimulationResult.bit_rock, summary.json's bit_rock, the printed summary): energy into
the rock, drilling efficiency and penetration per blow, against the closed form of a rectangular wave driven into
a bilinear rock, against the bilinear law along the bit's path, and through model file, results folder and CLI.

Closed form (derived in tests/direct/test_bitrock_order.py): a uniform piston of n elements and impedance Z at
velocity v hits a rod of the same impedance, so a rectangular wave F_I = -Z v / 2 of duration T = 2 n dt reaches
the rock (loading stiffness k1, unloading k2). While loading, Z delta' + k1 delta = -2 F_I, so the largest
penetration is delta_max = (Z v / k1) (1 - exp(-x)), x = k1 T / Z; the rock then unloads to its release point
delta_max (1 - k1/k2) (the permanent penetration) and keeps k1 delta_max^2 / 2 (1 - k1/k2), which is the fraction
eta(x) (1 - k1/k2), eta(x) = 2 (1 - exp(-x))^2 / x, of the piston's kinetic energy Z n dt v^2 / 2.
"""

import json

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.io.results import format_summary, summarize

Z = 50e3        # N s/m
V = 10.0        # m/s
DT = 1e-6       # s
RATIO = 1e6     # k2 / k1: a rock that keeps (almost) all the work


def closed_form(x, n):
    """(efficiency, largest penetration m, permanent penetration m) for the piston of n elements."""
    k1 = x * Z / (2 * n * DT)
    eta = 2.0 * (1.0 - np.exp(-x)) ** 2 / x * (1.0 - 1.0 / RATIO)
    delta_max = Z * V / k1 * (1.0 - np.exp(-x))
    return eta, delta_max, delta_max * (1.0 - 1.0 / RATIO)


def blow(x, n, steps=None, mirrored=False, outputs=None):
    """The piston on a rod of 4 n elements with the rock at its far end, run for 9 n steps: the rock has unloaded
    and no reflection has come back to it (the first would arrive at 12 n). ``mirrored``: the same system
    reflected, rock at the left end, the piston coming from the right."""
    k1 = x * Z / (2 * n * DT)
    piston = ri.Rod.from_impedance([Z] * n, DT, name="piston")
    rod = ri.Rod.from_impedance([Z] * (4 * n), DT, name="rod")
    rock = ri.BitRockEnd(k1, RATIO * k1)
    if mirrored:
        return ri.simulate(ri.System([rod, piston], [0.0, -V], left=rock), steps=steps or 9 * n, dt=DT, outputs=outputs)
    return ri.simulate(ri.System([piston, rod], [V, 0.0], right=rock), steps=steps or 9 * n, dt=DT, outputs=outputs)


@pytest.mark.parametrize("x", [0.5, 1.2564, 2.0])
def test_energy_efficiency_and_penetration_against_the_closed_form(x):
    n = 200
    eta, delta_max, permanent = closed_form(x, n)
    (o,) = blow(x, n).bit_rock
    assert o.end == "right" and o.striker == 0
    assert o.striker_energy == pytest.approx(0.5 * Z * n * DT * V ** 2, rel=1e-14)
    assert o.efficiency == pytest.approx(eta, rel=1e-5)
    assert o.energy == pytest.approx(eta * 0.5 * Z * n * DT * V ** 2, rel=1e-5)
    assert o.max_penetration == pytest.approx(delta_max, rel=1e-5)
    assert o.penetration == pytest.approx(permanent, rel=1e-5)
    # released: the bit rests at (within one step's motion below) the release point, no force on it
    assert not o.in_contact and o.final_force == 0.0
    assert permanent * (1 - 1e-4) < o.final_penetration <= o.penetration


def test_penetration_converges_at_second_order():
    x = 1.2564
    ns = np.array([100, 200, 400])
    errors = [abs(blow(x, int(n)).bit_rock[0].max_penetration / closed_form(x, int(n))[1] - 1.0) for n in ns]
    assert -np.polyfit(np.log(ns), np.log(errors), 1)[0] >= 1.9


def bilinear_work(delta, delta_max, k1, k2):
    """Work done on a bilinear rock that has reached delta_max and sits at delta (a state function, independent of
    the path): the virgin work k1 delta_max^2 / 2 less what the unloading line gives back down to the present force
    F, (k1 delta_max)^2 / (2 k2) - F^2 / (2 k2)."""
    force = max(k1 * delta_max + k2 * (delta - delta_max), 0.0)
    return 0.5 * k1 * delta_max ** 2 - (k1 * delta_max) ** 2 / (2.0 * k2) + force ** 2 / (2.0 * k2)


def test_energy_and_penetrations_obey_the_bilinear_law_with_rebounds():
    """A striker bonded to a short drill rod on a soft rock: loading, unloading, release and reloading several
    times. The energy into the rock equals the bilinear law's work at the reported final and largest penetration,
    the energy the rods lost, and (stopped while the bit is loaded) the bit is reported in contact with the
    law's force."""
    n = 20
    k1, k2 = 1.5 * Z / (n * DT), 4.5 * Z / (n * DT)
    striker = ri.Rod.from_impedance(np.full(n, 2.0 * Z), DT)
    rod = ri.Rod.from_impedance(np.full(3 * n, Z), DT)
    run = ri.simulate(ri.System([striker, rod], [8.0, 0.0], right=ri.BitRockEnd(k1, k2), junctions=[ri.Bonded()]),
                      steps=40 * n, dt=DT)
    (o,) = run.bit_rock
    w = run.end_velocity["right"]
    path = np.concatenate([[0.0], np.cumsum(w * DT)])        # the bit's path, step by step
    assert np.sum(np.diff(np.sign(w[np.abs(w) > 1e-9 * np.abs(w).max()])) != 0) >= 3       # rebounds
    assert o.final_penetration == pytest.approx(path[-1], rel=1e-12, abs=1e-15 * path.max())
    assert o.max_penetration == pytest.approx(path.max(), rel=1e-12)
    assert o.energy == pytest.approx(bilinear_work(o.final_penetration, o.max_penetration, k1, k2), rel=1e-11)
    e = run.energy
    assert o.energy == pytest.approx(e.total[0] - e.total[-1], rel=1e-11)
    assert o.efficiency == pytest.approx(o.energy / (0.5 * 2.0 * Z * n * DT * 8.0 ** 2), rel=1e-12)
    loading = next(k for k in range(1, w.size) if w[k] > 0 and path[k + 1] > 0.5 * path.max())
    mid = ri.simulate(ri.System([striker, rod], [8.0, 0.0], right=ri.BitRockEnd(k1, k2), junctions=[ri.Bonded()]),
                      steps=loading + 1, dt=DT).bit_rock[0]
    assert mid.in_contact and mid.final_force > 0.1 * k1 * mid.max_penetration
    assert mid.energy == pytest.approx(bilinear_work(mid.final_penetration, mid.max_penetration, k1, k2), rel=1e-11)


def test_a_rock_at_the_left_end_is_the_mirror_image():
    right = blow(1.2564, 50).bit_rock[0]
    left = blow(1.2564, 50, mirrored=True).bit_rock[0]
    assert left.end == "left" and left.striker == 1
    for name in ("energy", "striker_energy", "max_penetration", "final_penetration"):
        assert getattr(left, name) == pytest.approx(getattr(right, name), rel=1e-12)


def test_independent_of_the_recording_stride_and_kept_by_save_and_load(tmp_path):
    full = blow(1.2564, 50)
    sparse = blow(1.2564, 50, outputs=ri.Outputs(record_every=7, energy_every=13))
    assert sparse.bit_rock == full.bit_rock
    ri.save(sparse, tmp_path / "run")
    assert ri.load(tmp_path / "run").bit_rock == full.bit_rock


def test_no_rock_no_entry_and_a_force_driven_rod_has_no_efficiency():
    plain = ri.simulate([ri.Rod.from_impedance([Z] * 10, DT), ri.Rod.from_impedance([Z] * 40, DT)], [V, 0.0],
                        steps=50, dt=DT)
    assert plain.bit_rock == () and summarize(plain)["bit_rock"] == []
    assert "rock" not in format_summary(summarize(plain))
    driven = ri.simulate(ri.System([ri.Rod.from_impedance([Z] * 40, DT)], [0.0],
                                   left=ri.ForceEnd(lambda t: np.where(t < 20 * DT, -1e5, 0.0)),
                                   right=ri.BitRockEnd(2e9, 4e9)), steps=120, dt=DT)
    (o,) = driven.bit_rock
    assert o.energy > 0 and o.striker_energy == 0.0 and o.efficiency is None
    text = format_summary(summarize(driven))
    assert "energy into the rock" in text and "drilling efficiency" not in text


MODEL = """
title = "piston on a rod on rock (closed form: x = 1.2564, 100 elements per pulse)"
[[rods]]
name = "piston"
velocity = "10 m/s"
[rods.elements]
dt = "1 us"
runs = [{{ impedance = "50 kN s/m", count = 100 }}]

[[rods]]
name = "rod"
[rods.elements]
dt = "1 us"
runs = [{{ impedance = "50 kN s/m", count = 400 }}]

[ends]
right = {{ type = "bit-rock", loading_stiffness = {k1!r}, unloading_stiffness = {k2!r} }}

[simulation]
steps = {steps}
"""


def test_summary_json_and_the_printed_summary_of_a_model_file(tmp_path, monkeypatch, capsys):
    """`rodimpact simulate` on a drilling model: summary.json reports the energy into the rock, the efficiency and
    the penetration per blow (closed form), and the printed summary shows them; a run that stops during the blow
    says so."""
    monkeypatch.chdir(tmp_path)
    x, n = 1.2564, 100
    k1 = x * Z / (2 * n * DT)
    eta, delta_max, permanent = closed_form(x, n)
    (tmp_path / "drill.toml").write_text(MODEL.format(k1=k1, k2=RATIO * k1, steps=9 * n))
    assert cli.main(["simulate", "drill.toml", "-o", "out", "--no-plots"]) == 0
    printed = capsys.readouterr().out
    (b,) = json.loads((tmp_path / "out" / "summary.json").read_text())["bit_rock"]
    assert b["end"] == "right" and b["striker"] == "piston" and not b["bit_in_contact_at_end"]
    assert b["efficiency"] == pytest.approx(eta, rel=1e-5)
    assert b["energy_into_rock_J"] == pytest.approx(eta * 0.5 * Z * n * DT * V ** 2, rel=1e-5)
    assert b["striker_initial_energy_J"] == pytest.approx(0.5 * Z * n * DT * V ** 2, rel=1e-14)
    assert b["penetration_per_blow_m"] == pytest.approx(permanent, rel=1e-5)
    assert b["max_penetration_m"] == pytest.approx(delta_max, rel=1e-5)
    assert f"energy into the rock  {eta * 0.5 * Z * n * DT * V ** 2:.4g} J = {eta * 100:.2f} % of piston's initial " \
           f"energy (drilling efficiency)" in printed
    assert f"penetration per blow  {permanent * 1e3:.4g} mm (permanent; largest {delta_max * 1e3:.4g} mm" in printed
    assert "still presses" not in printed
    (tmp_path / "short.toml").write_text(MODEL.format(k1=k1, k2=RATIO * k1, steps=5 * n))   # during the loading
    assert cli.main(["simulate", "short.toml", "-o", "short", "--no-plots"]) == 0
    assert "the bit still presses on the rock at the end" in capsys.readouterr().out
    assert json.loads((tmp_path / "short" / "summary.json").read_text())["bit_rock"][0]["bit_in_contact_at_end"]
