"""The reduction against a shot built in closed form from the 1-D bar relations (tests/shpb/shpb_synthetic.py): a
specimen with an elastic-linear-hardening law, in exact force equilibrium, loaded at a strain rate that rises
linearly and then stays constant. Every analysis must give back the law, the strain and the rate to rounding."""

import numpy as np
import pytest
from shpb_synthetic import DT, RATE, SAMPLES, SPECIMEN, build_shot, law, prescribed_rate, prescribed_strain

from rodimpact.shpb import ANALYSES, find_windows, reduce_shot, specimen_responses


def test_the_synthetic_pulses_have_the_signs_of_a_compression_test(bars):
    shot = build_shot(*bars, SPECIMEN)
    k = np.arange(1, SAMPLES)
    eps_i = shot.signals.incident[shot.start + k]
    eps_t = shot.signals.transmitted[shot.start + 2800 + k]
    assert np.all(eps_i < 0) and np.all(eps_t < 0)          # compressive pulses, tension positive


@pytest.mark.parametrize("analysis", ANALYSES)
def test_every_analysis_recovers_the_law_the_strain_and_the_rate(bars, analysis):
    shot = build_shot(*bars, SPECIMEN)
    red = reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=shot.windows)
    k = np.arange(SAMPLES)
    r = red.response(analysis)
    assert red.time.size == SAMPLES
    np.testing.assert_allclose(r.strain_rate, prescribed_rate(k), rtol=0, atol=1e-9 * RATE)
    np.testing.assert_allclose(r.strain, prescribed_strain(k), rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.stress, law(r.strain), rtol=0, atol=1e-9 * law(r.strain).max())
    assert r.stress[-1] > 0 and r.strain[-1] > 0                        # compression positive
    # the face time axis: the incident window's start moved on by the incident bar's travel time
    assert red.time[0] == pytest.approx(shot.signals.time[shot.start] + shot.incident_bar.travel_time, abs=1e-15)
    np.testing.assert_allclose(np.diff(red.time), DT, rtol=1e-9)


def test_the_true_measures_of_incompressible_flow():
    """eps_true = -ln(1 - eps), sigma_true = sigma (1 - eps), rate_true = rate / (1 - eps): hand values at
    eps = 0.1 and 0.2 (compression positive)."""
    shot = build_shot(*_equal_bars(), SPECIMEN)
    r = reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen,
                    windows=shot.windows).three_wave
    k = int(np.argmin(np.abs(r.strain - 0.1)))
    eps, sigma, rate = r.strain[k], r.stress[k], r.strain_rate[k]
    assert r.true_strain[k] == pytest.approx(-np.log(1.0 - eps), rel=1e-14)
    assert r.true_stress[k] == pytest.approx(sigma * (1.0 - eps), rel=1e-14)
    assert r.true_strain_rate[k] == pytest.approx(rate / (1.0 - eps), rel=1e-14)
    # the same formulas at hand-computed points: ln(1/0.9) = 0.10536051565782628, ln(1/0.8) = 0.2231435513142097
    from rodimpact.shpb import SpecimenResponse
    hand = SpecimenResponse(np.array([300e6, 400e6]), np.array([0.1, 0.2]), np.array([1000.0, 2000.0]))
    np.testing.assert_allclose(hand.true_strain, [0.10536051565782628, 0.2231435513142097], rtol=1e-15)
    np.testing.assert_allclose(hand.true_stress, [270e6, 320e6], rtol=1e-15)
    np.testing.assert_allclose(hand.true_strain_rate, [1111.111111111111, 2500.0], rtol=1e-15)


def test_equal_bar_forms_of_the_textbook():
    """With equal bars the general forms reduce to the textbook's (Gray 2000; Chen and Song 2011), written here
    with tension-positive bar strains and compression-positive specimen quantities:
    3-wave rate -(c/L0)(eps_I - eps_R - eps_T), stress -E A (eps_I + eps_R + eps_T) / (2 A0); 2-wave rate
    2 c eps_R / L0, stress -E A eps_T / A0; 1-wave stress -E A (eps_I + eps_R) / A0, rate 2 c eps_R / L0."""
    bar = _equal_bars()[0]
    rng = np.random.default_rng(1)
    eps_i, eps_r, eps_t = -1e-3 * rng.random((3, 50)) * np.array([[1.0], [-0.5], [0.6]])
    one, two, three = specimen_responses(eps_i, eps_r, eps_t, bar, bar, SPECIMEN, DT)
    c, ea, l0, a0 = bar.wave_speed, bar.stiffness, SPECIMEN.length, SPECIMEN.area
    np.testing.assert_allclose(three.strain_rate, -(c / l0) * (eps_i - eps_r - eps_t), rtol=1e-12)
    np.testing.assert_allclose(three.stress, -ea * (eps_i + eps_r + eps_t) / (2 * a0), rtol=1e-12)
    np.testing.assert_allclose(two.strain_rate, 2 * c * eps_r / l0, rtol=1e-12)
    np.testing.assert_allclose(two.stress, -ea * eps_t / a0, rtol=1e-12)
    np.testing.assert_allclose(one.strain_rate, 2 * c * eps_r / l0, rtol=1e-12)
    np.testing.assert_allclose(one.stress, -ea * (eps_i + eps_r) / a0, rtol=1e-12)


def test_windows_found_automatically_on_the_synthetic_shot(bars):
    """The incident pulse starts from zero at record index ``start``: the foot rule finds that sample; the
    reflected and transmitted windows follow by the travel times the shot was built with, and the pulse length
    covers the pulse."""
    shot = build_shot(*bars, SPECIMEN)
    found = find_windows(shot.signals, shot.incident_bar, shot.transmitted_bar)
    for name in ("incident", "reflected", "transmitted"):
        assert getattr(found, name).start == pytest.approx(getattr(shot.windows, name).start, abs=1e-6 * DT)
    assert found.incident.duration >= (SAMPLES - 1) * DT
    auto = reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen)
    k = np.arange(SAMPLES)
    np.testing.assert_allclose(auto.three_wave.stress[:SAMPLES], law(prescribed_strain(k)), rtol=0,
                               atol=1e-9 * law(prescribed_strain(k)).max())


def _equal_bars():
    from shpb_synthetic import ti_bar

    return ti_bar(), ti_bar("transmitted")


def test_dispersion_correction_undoes_pochhammer_chree_dispersion():
    """The face pulses of the closed-form shot dispersed on their way to the gauges (the incident pulse
    propagated back from the face to its gauge, the reflected and transmitted ones on from the face,
    :func:`rodimpact.signals.propagate_dispersive`): ``dispersion=True`` gives the law back to the accuracy of
    propagation and correction as inverses for a pulse with a sharp end (6.4e-4 of the peak stress; the phase
    near the Nyquist frequency limits it, docs/measurement.md); without it the ringing stays in (82 %). The records have 250 us of quiet before and after the pulses: energy travels at the group
    velocity, whose minimum in the first mode is about 0.45 c0, so over the 0.76 m between gauge and face it
    moves by up to 0.76 m (1/(0.45 c0) - 1/c0) = 180 us, and content moved out of the record is lost."""
    from rodimpact.shpb import GaugeSignals
    from rodimpact.signals import PochhammerChree, propagate_dispersive

    shot = build_shot(*_equal_bars(), SPECIMEN, start=2500, tail=2500)   # quiet time for the dispersive shifts
    s, n, t = shot.signals, SAMPLES, shot.signals.time
    bar = shot.incident_bar
    model = PochhammerChree(bar.poisson_ratio, bar.diameter / 2, bar.wave_speed)
    incident_part, reflected_part = np.zeros(t.size), np.zeros(t.size)
    incident_part[shot.start:shot.start + n] = s.incident[shot.start:shot.start + n]
    reflected_part[shot.start + 3000:] = s.incident[shot.start + 3000:]
    a_i, a_t = shot.incident_bar.gauge_distance, shot.transmitted_bar.gauge_distance
    dispersed = GaugeSignals(t, propagate_dispersive(t, incident_part, -a_i, model)
                             + propagate_dispersive(t, reflected_part, a_i, model),
                             propagate_dispersive(t, s.transmitted, a_t, model))
    k = np.arange(SAMPLES)
    expected = law(prescribed_strain(k))
    errors = {}
    for corrected in (True, False):
        red = reduce_shot(dispersed, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=shot.windows,
                          dispersion=corrected)
        errors[corrected] = max(np.max(np.abs(r.stress - expected)) for r in red.responses.values()) / expected.max()
    assert errors[True] < 2e-3          # 6.4e-4 measured
    assert errors[False] > 0.1          # 0.82: the sharp end of the pulse rings
