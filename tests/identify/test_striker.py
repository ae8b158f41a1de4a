"""Striker identification (rodimpact/identify/striker.py): round trips through the exact lattice and the LANL
copper shot's striker (127 mm long by its data sheet)."""

from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.identify import identify_striker

DT = 1e-6
ZB = 4.0e5
LANL = Path(__file__).resolve().parents[1] / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"


def face_force(striker_impedance, v0, steps):
    """Impact-face force of a striker (elements listed left to right, impact face on the right) hitting a long
    bar of impedance ZB at v0, sampled every second step (one force window), with 20 zero samples before."""
    striker = ri.Rod.from_impedance(list(striker_impedance), dt=DT)
    bar = ri.Rod.from_impedance([ZB] * steps, dt=DT)
    sim = ri.simulate(ri.Problem.of([striker, bar], [v0, 0.0], steps=steps, dt=DT, right="nonreflecting"),
                      backend="numpy")
    f = np.asarray(sim.junction_force[0], dtype=float)[::2]
    return np.r_[-2 * DT * np.arange(20, 0, -1), sim.time[::2]], np.r_[np.zeros(20), f]


def test_stepped_striker_comes_back_exactly():
    """The synthesis is the exact inverse of the lattice: the profile from the impact face is the striker's
    reversed element list, to rounding; the length is c_s times half the pulse duration (half-plateau
    crossings, interpolated: within a quarter sample of c_s T, T = 2 DT)."""
    zs = np.r_[np.full(20, ZB), np.full(20, 0.8 * ZB)]
    t, f = face_force(zs, 8.0, 160)
    out = identify_striker(t, f, ZB, 5000.0, velocity=8.0, window=1, resamples=0)
    assert out.impedance.size == 40
    assert np.max(np.abs(out.impedance / zs[::-1] - 1)) < 1e-10
    assert abs(out.toe - 5000.0 * 40 * DT) < 5000.0 * 2 * DT / 4
    assert out.misfit < 1e-12


def test_velocity_from_the_plateau_of_a_matched_striker():
    """A uniform striker of the bar's impedance: F_p = -Z v0 / 2, so v0 = -2 F_p / Z exactly."""
    t, f = face_force(np.full(30, ZB), 6.5, 120)
    out = identify_striker(t, f, ZB, 5000.0, window=1, resamples=0)
    assert out.diagnostics["striker_velocity_m_per_s"] == pytest.approx(6.5, rel=1e-12)
    assert np.allclose(out.impedance, ZB, rtol=1e-10)


def test_refuses_a_record_without_baseline():
    t = np.arange(50) * DT
    with pytest.raises(ValueError, match="baseline: fewer than 2 pre-trigger samples"):
        identify_striker(t, np.full(50, -1.0e3), ZB, 5000.0)


def test_lanl_copper_striker_length():
    """The LANL shot's striker is 127 mm long (the shot's sheet, 'Striker Length(mm)'); its velocity is not
    recorded. With the striker taken as the bar (Ti-6Al-4V, 9.47 mm) and the calibrated bar speed, the pulse
    duration gives the length within the sheet's spread of wave speeds (4866 m/s calibrated vs 4975 m/s rod
    sound speed: 2.2 %)."""
    rec = ri.io.read_lanl_raw(LANL)
    gauge = ri.io.hoppybar_bar(rec.metadata, "incident", bridge="half-axial", polarity=-1)
    c = rec.metadata["Incident Bar Reflected Time Sound Speed(m/s)"]
    force = gauge.force(rec["incident"])
    keep = rec.time < 150e-6                     # the incident pulse only (the reflected one arrives at 152.9 us)
    out = identify_striker(rec.time[keep], force[keep], gauge.youngs_modulus * gauge.area / c, c, resamples=10)
    assert out.toe == pytest.approx(0.127, rel=0.022)
    lo, hi = out.toe_band
    assert lo <= out.toe <= hi
    assert out.misfit < 1e-10                    # the identified striker re-simulated reproduces its windows


def test_refuses_uneven_sampling_and_bad_windows():
    t = np.arange(50) * DT
    f = np.r_[np.zeros(10), np.full(40, -1.0e3)]
    uneven = t.copy()
    uneven[20] += 0.5 * DT
    with pytest.raises(ValueError, match="time: must be uniformly sampled"):
        identify_striker(uneven, f, ZB, 5000.0)
    with pytest.raises(ValueError, match="window: must be an integer >= 1"):
        identify_striker(t, f, ZB, 5000.0, window=0)


def test_warns_when_the_pulse_outruns_the_striker():
    """At v0 = 1 m/s against Z_b = 4e5 N s/m no striker pushes harder than a rigid one, Z_b v0 = 4e5 N. A pulse
    of 3e5 N for 10 windows, then 5e5 N: the striker exists for the first 10 windows only (thesis eq. 4.20),
    which an IdentificationWarning says."""
    from rodimpact.identify import IdentificationWarning

    t = np.arange(60) * DT
    f = np.r_[np.zeros(20), np.full(10, -3.0e5), np.full(20, -5.0e5), np.zeros(10)]
    with pytest.warns(IdentificationWarning, match="implies a striker only for the first 10 force windows"):
        out = identify_striker(t, f, ZB, 5000.0, velocity=1.0, window=1, resamples=0)
    assert out.impedance.size == 10


def test_bands_follow_the_colour_of_the_baseline_noise():
    """With strongly correlated noise (AR(1), a = 0.95) the 90 % band of the impact velocity matches the spread
    of the estimate over independent noise records (Monte Carlo: 5-95 % of 60 estimates), within a factor 1.6 of
    its width; bands that took the baseline's noise as white, of the same variance, would be about 4 times too
    narrow here (the plateau's mean averages white noise away, not slow noise)."""
    from scipy.signal import lfilter

    t, clean = face_force(np.full(30, ZB), 6.5, 120)
    t = np.r_[t[0] - 2 * DT * np.arange(300, 0, -1), t]           # a baseline of 320 samples
    clean = np.r_[np.zeros(300), clean]
    rng = np.random.default_rng(5)
    level = 0.01 * np.max(-clean)

    def noise():
        x = lfilter([1.0], [1.0, -0.95], rng.normal(size=clean.size + 2000))[2000:]
        return level * x / np.sqrt(1.0 / (1.0 - 0.95 ** 2))

    truth = [identify_striker(t, clean + noise(), ZB, 5000.0, window=4, resamples=0)
             .diagnostics["striker_velocity_m_per_s"] for _ in range(60)]
    true_width = np.subtract(*np.quantile(truth, [0.95, 0.05]))
    out = identify_striker(t, clean + noise(), ZB, 5000.0, window=4, resamples=60, seed=2)
    lo, hi = out.diagnostics["striker_velocity_band"]
    assert out.diagnostics["noise_model_order"] >= 1
    assert 1 / 1.6 < (hi - lo) / true_width < 1.6, (hi - lo, true_width)
