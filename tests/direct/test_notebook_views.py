"""Issue 14 item 10: notebook views. ``_repr_html_`` of SimulationResult and SynthesisResult (compact tables of
key numbers), ``to_dataframe()`` of the per-step histories and of the per-element synthesis table, and a
Recording repr that does not print the whole metadata sheet."""

import math

import numpy as np
import pandas as pd
import pytest

import rodimpact as ri
from rodimpact.signals.recording import Recording

C = math.sqrt(210e9 / 7840.0)


def _uniform_impact(n_rods=2):
    """Equal steel bars (d = 20 mm); the striker (0.2 m) hits at 5 m/s; exact lattice (dt = 0.2 m / c / 40)."""
    rods = [ri.Rod([ri.Cylinder(0.2, 0.02)], name="striker")] + [ri.Rod([ri.Cylinder(0.6, 0.02)]) for _ in
                                                                 range(n_rods - 1)]
    return ri.simulate(ri.System(rods, [5.0] + [0.0] * (n_rods - 1), junctions=["contact"] + ["bonded"] * (n_rods - 2)),
                       duration=4e-4, dt=0.2 / C / 40, outputs=ri.Outputs(probes=[ri.Probe("SG", 1, 0.3)]))


def test_simulation_dataframe_holds_the_histories_on_a_time_index():
    r = _uniform_impact()
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame) and df.index.name == "time"
    assert np.array_equal(df.index.to_numpy(), r.time)
    assert list(df.columns) == ["contact_force", "contact", "left_end_force", "left_end_velocity",
                                "right_end_force", "right_end_velocity", "SG_force", "SG_velocity",
                                "SG_displacement", "SG_strain"]
    assert np.array_equal(df["contact_force"].to_numpy(), r.contact_force)
    assert np.array_equal(df["SG_strain"].to_numpy(), r.probes["SG"].strain)
    assert df["contact"].dtype == bool
    assert df.attrs["units"]["contact_force"] == "N" and df.attrs["units"]["SG_velocity"] == "m/s"
    # the physics in the table: equal impedances, contact force -Z v / 2 for 2 L / c
    z = 0.25 * math.pi * 0.02**2 * 7840.0 * C
    during = df.index < 2 * 0.2 / C - 1e-9
    assert np.allclose(df.loc[during, "contact_force"], -z * 5.0 / 2, rtol=1e-12)
    three = _uniform_impact(3).to_dataframe()
    assert {"contact_force_0", "contact_force_1", "contact_0", "contact_1"} <= set(three.columns)


def test_simulation_html_shows_the_key_numbers():
    r = _uniform_impact()
    html = r._repr_html_()
    z = 0.25 * math.pi * 0.02**2 * 7840.0 * C
    assert html.startswith("<table>") and html.endswith("</table>")
    assert f"peak force {-z * 5.0 / 2 / 1e3:.6g} kN" in html                # closed form, 1.61 kN class
    assert f"contact {2 * 0.2 / C * 1e3:.6g} ms" in html
    assert "energy transfer (rod 0)</th><td style=\"text-align:left\">100.00%" in html   # equal bars: all of it
    assert "<td style=\"text-align:left\">SG</td>" in html


@pytest.fixture(scope="module")
def synthesis():
    dt = 1.93e-6
    bar = ri.Rod.from_impedance(np.full(200, 79.7e3), dt=dt)
    return ri.synthesize(lambda t: -239.1e3 * np.exp(-t / 0.383e-3), struck=ri.System.struck(bar, far_end="nonreflecting"), striker_velocity=6.0,
                         n=60, dt=dt)


def test_synthesis_dataframe_is_the_per_element_table(synthesis):
    df = synthesis.to_dataframe()
    assert df.index.name == "q" and list(df.index) == list(range(1, synthesis.n_feasible + 1))
    assert np.array_equal(df["impedance"].to_numpy(), synthesis.impedance)
    assert np.array_equal(df["K"].to_numpy(), synthesis.transmission_factor)
    assert np.allclose(df["theta"].to_numpy(), 1.93e-6 * np.arange(synthesis.n_feasible), rtol=0, atol=1e-18)
    assert df.attrs["units"]["impedance"] == "N s/m"


def test_synthesis_html_shows_the_key_numbers(synthesis):
    html = synthesis._repr_html_()
    assert html.startswith("<table>")
    assert f"{synthesis.n_feasible} of 60 requested" in html and "feasible" in html
    z = synthesis.impedance
    assert f"{z.min():.4g} .. {z.max():.4g} N s/m" in html
    assert f"{1.93e-6 * z.sum():.4g} kg" in html                   # mass = dt sum Z


def test_recording_repr_does_not_print_the_metadata_sheet():
    t = np.arange(1000) * 1e-7
    meta = {f"header field {i}": "x" * 50 for i in range(300)}
    rec = Recording(t, {"SG1": np.zeros(1000), "SG2": np.ones(1000)}, {"SG1": "V"}, meta, "shot.csv")
    text = repr(rec)
    assert "x" * 50 not in text and len(text) < 300
    assert text == ("Recording(1000 samples, t = 0 .. 9.99e-05 s at 1e+07 Hz, channels: SG1 [V], SG2; "
                    "metadata: 300 entries (header field 0, header field 1, header field 2, header field 3, "
                    "header field 4, ...), source='shot.csv')")
