"""Kolsky-bar spec files (issue 22, `rodimpact shpb predict`): a spec builds the KolskyBar one builds in Python and
predicts the same numbers bit for bit; a measured incident pulse is read from CSV with the units of its header;
bad values are refused naming the spec's key path; overrides work as for the other specs."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.quantities import ModelError
from rodimpact.io.shpb_spec import (BAR, GAUGE, INPUT, SHAPER, SIMULATION, SPECIMEN, TEMPLATE, load_spec,
                                    loads_spec)
from rodimpact.shpb import Gauge, KolskyBar

# every part of a Kolsky bar: striker, copper shaper, incident bar, specimen, transmitted bar, momentum trap
SPEC = '''
title = "every part"

[bars.striker]
material = "ti-6al-4v"
[[bars.striker.segments]]
shape = "cylinder"
length = "100 mm"
diameter = "9.47 mm"

[bars.incident]
material = "ti-6al-4v"
[[bars.incident.segments]]
shape = "cylinder"
length = "600 mm"
diameter = "9.47 mm"

[bars.transmitted]
material = "ti-6al-4v"
[[bars.transmitted.segments]]
shape = "cylinder"
length = "600 mm"
diameter = "9.47 mm"

[bars.momentum_trap]
material = "ti-6al-4v"
[[bars.momentum_trap.segments]]
shape = "cylinder"
length = "200 mm"
diameter = "9.47 mm"

[specimen]
diameter = "6.34 mm"
length = "3.204 mm"
density = "8960 kg/m^3"
law = { type = "johnson-cook", youngs_modulus = "117 GPa", a = "90 MPa", b = "292 MPa", n = 0.31, c = 0.025, m = 1.09 }

[shaper]
diameter = "4 mm"
thickness = "1 mm"
law = { type = "frew", stress = "360 MPa", n = 0.3, m = 2.0 }

[gauges.incident]
distance = "200 mm"
bridge = "half-poisson"
poisson_ratio = 0.33
gauge_factor = 2.061
excitation_voltage = "8 V"
gain = 200
polarity = -1

[gauges.transmitted]
distance = "200 mm"

[input]
striker_velocity = "12 m/s"

[simulation]
duration = 3e-4
backend = "numba"
'''


def python_kolsky_bar() -> KolskyBar:
    """The Kolsky bar of SPEC, built in Python (the same unit strings, so the same floats)."""
    def bar(length: str, name: str) -> ri.Rod:
        return ri.Rod([ri.Cylinder(length, "9.47 mm")], ri.TITANIUM_TI6AL4V, name)

    specimen = ri.Specimen(ri.JohnsonCook("117 GPa", "90 MPa", "292 MPa", 0.31, 0.025, m=1.09), "6.34 mm",
                           "3.204 mm", density="8960 kg/m^3")
    shaper = ri.PulseShaper(ri.FrewShaper("360 MPa", 0.3, 2.0), "4 mm", "1 mm")
    return KolskyBar(bar("600 mm", "incident"), bar("600 mm", "transmitted"), specimen,
                     Gauge("200 mm", "half-poisson", 2.061, "8 V", 200.0, -1, 0.33), Gauge("200 mm"),
                     striker=bar("100 mm", "striker"), shaper=shaper, momentum_trap=bar("200 mm", "momentum_trap"))


def test_the_spec_builds_the_python_kolsky_bar_and_predicts_the_same_bit_for_bit() -> None:
    spec = loads_spec(SPEC)
    kb = python_kolsky_bar()
    assert spec.kolsky == kb
    assert (spec.striker_velocity, spec.incident_pulse, spec.dt, spec.duration) == (12.0, None, None, 3e-4)
    from_file = spec.predict()
    from_python = kb.predict(12.0, duration=3e-4)
    for name in ("time", "incident", "reflected", "incident_gauge", "transmitted", "force", "strain", "strain_rate",
                 "true_strain", "stress", "true_stress"):
        assert np.array_equal(getattr(from_file, name), getattr(from_python, name)), name
    assert list(from_file.volts) == ["incident_gauge"]
    assert np.array_equal(from_file.volts["incident_gauge"], from_python.volts["incident_gauge"])
    assert from_file.force.max() > 0.0 and from_file.transmitted.min() < 0.0     # loaded, in compression


def write_pulse(folder: Path) -> tuple[np.ndarray, np.ndarray]:
    """A half-sine incident pulse of -800 microstrain and 60 us on a recording's clock, written with units in the
    header; returns its samples in SI."""
    t_us = 1000.0 + np.arange(301) * 0.2
    strain_micro = -800.0 * np.sin(np.pi * np.arange(301) / 300) ** 2
    rows = "\n".join(f"{float(t)!r},{float(e)!r}" for t, e in zip(t_us, strain_micro))
    (folder / "incident.csv").write_text("# a measured incident pulse\ntime [us],strain [microstrain]\n" + rows + "\n")
    return t_us * 1e-6, strain_micro * 1e-6


def test_a_measured_incident_pulse_is_read_with_its_units_and_passes_the_gauge_as_recorded(tmp_path: Path) -> None:
    t, eps = write_pulse(tmp_path)
    spec = loads_spec(SPEC, tmp_path, overrides={"input.incident_pulse": {"file": "incident.csv"}})
    assert spec.striker_velocity is None                         # replaced by the override
    np.testing.assert_allclose(spec.incident_pulse[0], t, rtol=1e-15)
    np.testing.assert_allclose(spec.incident_pulse[1], eps, rtol=1e-15)
    p = spec.predict()
    assert np.array_equal(p.incident, python_kolsky_bar().predict(incident_pulse=(t, eps), duration=3e-4).incident)
    # the gauge reads the record on its clock (to half a step: the gauge's node lies within half an element of it)
    inside = (p.time >= t[0]) & (p.time <= t[-1])
    assert inside.sum() > 90                                   # 60 us at the default dt, 0.58 us
    assert np.abs(p.incident[inside] - np.interp(p.time[inside], t, eps)).max() <= 0.02 * 800e-6
    assert spec.text.startswith("# spec with the overrides input.incident_pulse = { file = \"incident.csv\" } "
                                "(replacing the file's input.striker_velocity = \"12 m/s\")")


def test_a_tabulated_law_reads_its_file_next_to_the_spec(tmp_path: Path) -> None:
    (tmp_path / "flow.csv").write_text("plastic_strain,stress [MPa]\n0,90\n0.5,300\n")
    law = '{ type = "tabulated", youngs_modulus = "117 GPa", file = "flow.csv" }'
    path = tmp_path / "shot.toml"
    path.write_text(re.sub(r"^law = \{ type = \"johnson-cook\".*$", f"law = {law}", SPEC, count=1, flags=re.M))
    specimen = load_spec(path).kolsky.specimen
    assert isinstance(specimen.law, ri.TabulatedLaw)
    np.testing.assert_array_equal(specimen.law.stress, [[90e6, 300e6]])


def test_the_template_loads_with_its_commented_parts() -> None:
    spec = loads_spec(TEMPLATE)
    kb = spec.kolsky
    assert (kb.incident.length, kb.striker.length, kb.incident_gauge.distance) == (1.0, 0.127, 0.381)
    assert spec.striker_velocity == 10.0 and kb.specimen.law.a == 90e6
    uncommented = re.sub(r"^# (\[shaper\]|\[bars\.momentum_trap\]|\[\[bars\.momentum_trap|"
                         r"(material|shape|length|diameter|thickness|law) = )", r"\1", TEMPLATE, flags=re.M)
    full = loads_spec(uncommented).kolsky
    assert full.shaper.thickness == 1e-3 and full.momentum_trap.length == 0.3


@pytest.mark.parametrize("table, path", [(BAR, "bars.incident"), (SPECIMEN, "specimen"), (SHAPER, "shaper"),
                                         (GAUGE, "gauges.incident"), (INPUT, "input"), (SIMULATION, "simulation")],
                         ids=lambda x: x if isinstance(x, str) else x.name)
def test_the_examples_of_the_reference_load(table, path: str) -> None:
    value = tomllib.loads(table.example)
    for key in path.split("."):
        value = value[key]
    spec = loads_spec(SPEC, overrides={path: value})
    assert spec.kolsky.specimen.area > 0.0


def spec_with(old: str, new: str) -> str:
    assert old in SPEC, old
    return SPEC.replace(old, new)


@pytest.mark.parametrize("text, message", [
    (spec_with('length = "600 mm"', 'length = "-600 mm"'),
     r"^bars\.incident\.segments\[0\]\.length: must be > 0, got -600 mm$"),
    (spec_with('type = "johnson-cook"', 'type = "johnson-cok"'),
     r"^specimen\.law\.type: unknown type 'johnson-cok' \(did you mean 'johnson-cook'\?\); valid: 'elastic', "),
    (spec_with('b = "292 MPa"', 'b = "-292 MPa"'), r"^specimen\.law\.b: must be >= 0, got -292 MPa$"),
    (spec_with('diameter = "6.34 mm"', 'diameter = "12 mm"'),
     r"^specimen\.diameter: the specimen \(12 mm, .*\) is wider than the rod faces it joins \(7\.04352e-05 m\^2\)"),
    (spec_with('diameter = "4 mm"', 'diameter = "10 mm"'), r"^shaper\.diameter: the pulse-shaper \(10 mm"),
    (spec_with('thickness = "1 mm"', 'thickness = "-1 mm"'), r"^shaper\.thickness: must be > 0, got -1 mm$"),
    (spec_with('[input]\nstriker_velocity = "12 m/s"', ''),
     r"^input: missing \(What loads the bars: `striker_velocity` \(with `\[bars\.striker\]`\) or a measured "),
    (spec_with('striker_velocity = "12 m/s"', ''),
     r"^input: give exactly one of striker_velocity .* got neither$"),
    (spec_with('striker_velocity = "12 m/s"', 'striker_velocity = "12 m/s"\nincident_pulse = { file = "p.csv" }'),
     r"^input: give exactly one of striker_velocity .* not both$"),
    (spec_with('striker_velocity = "12 m/s"', 'striker_velocity = "-12 m/s"'),
     r"^input\.striker_velocity: must be > 0, got -12 m/s$"),
    (spec_with('[gauges.transmitted]\ndistance = "200 mm"', '[gauges.transmitted]\ndistance = "0.7 m"'),
     r"^gauges\.transmitted\.distance: must lie on the bar, < 0\.6 m from its specimen face, got 0\.7 m$"),
    (spec_with('gauge_factor = 2.061\n', ''), r"^gauges\.incident\.gauge_factor: missing; give gauge_factor and "),
    (spec_with('poisson_ratio = 0.33\n', ''), r"^gauges\.incident\.poisson_ratio: missing; the 'half-poisson' "),
    (spec_with('polarity = -1', 'polarity = 2'), r"^gauges\.incident\.polarity: must be \+1 or -1, got 2$"),
    (spec_with('excitation_voltage = "8 V"', 'excitation_voltage = "8 m"'),
     r"^gauges\.incident\.excitation_voltage: expected a voltage such as \"10 V\""),
    (spec_with('length = "3.204 mm"', 'lenght = "3.204 mm"'),
     r"^specimen\.lenght: unknown key \(did you mean 'length'\?\)"),
    (spec_with('[bars.incident]\nmaterial = "ti-6al-4v"\n[[bars.incident.segments]]\nshape = "cylinder"\n'
               'length = "600 mm"\ndiameter = "9.47 mm"',
               '[bars.incident.elements]\ndt = "1 us"\nruns = [{ impedance = "30 kN s/m", count = 100 }]'),
     r"^bars\.incident: needs a geometric rod \(segments and material\), not an impedance-level one"),
    (spec_with('[gauges.transmitted]\ndistance = "200 mm"', ''), r"^gauges\.transmitted: missing"),
    (SPEC.split("[bars.incident]")[0] + "[bars.transmitted]" + SPEC.split("[bars.transmitted]")[1],
     r"^bars\.incident: missing"),
])
def test_bad_values_are_refused_with_their_key_path(text: str, message: str) -> None:
    with pytest.raises(ModelError, match=message):
        loads_spec(text)


def test_a_striker_velocity_needs_a_striker() -> None:
    no_striker = re.sub(r"\[bars\.striker\].*?(?=\[bars\.incident\])", "", SPEC, flags=re.S)
    no_striker = re.sub(r"\[shaper\].*?(?=\[gauges\.incident\])", "", no_striker, flags=re.S)
    with pytest.raises(ModelError, match=r"^input\.striker_velocity: needs a striker: give \[bars\.striker\]"):
        loads_spec(no_striker)


@pytest.mark.parametrize("csv, message", [
    ("time [us],strain [-]\n0,0\n1,-1e-4\n1,0\n", r"data rows 2 and 3: the times must increase strictly"),
    ("time [us],force [N]\n0,0\n1,-1\n", r"has no column 'strain'"),
    ("time [us],strain [mm]\n0,0\n1,-1e-4\n", r"column 2: the unit in its header is not a dimensionless unit"),
    ("time [us],strain [-]\n0,0\n", r"needs at least two rows of samples, got 1"),
])
def test_bad_pulse_files_are_refused_naming_the_key_and_the_row(tmp_path: Path, csv: str, message: str) -> None:
    (tmp_path / "p.csv").write_text(csv)
    with pytest.raises(ModelError, match=r"^input\.incident_pulse\.file: .*" + message):
        loads_spec(SPEC, tmp_path, overrides={"input.incident_pulse": {"file": "p.csv"}})


def test_errors_of_the_run_name_the_spec_keys() -> None:
    spec = loads_spec(SPEC, overrides={"simulation.dt": "30 us"})
    with pytest.raises(ModelError, match=r"^simulation\.dt: rod 0 \(striker\) segment 0 .* is shorter than one element"):
        spec.predict()


def test_load_spec_reads_a_file_and_resolves_the_pulse_next_to_it(tmp_path: Path) -> None:
    write_pulse(tmp_path)
    path = tmp_path / "shot.toml"
    path.write_text(SPEC.replace('striker_velocity = "12 m/s"', 'incident_pulse = { file = "incident.csv" }'))
    spec = load_spec(path)
    assert spec.source == path and spec.pulse_file == "incident.csv" and spec.incident_pulse[0].size == 301
    assert spec.text == path.read_text()

