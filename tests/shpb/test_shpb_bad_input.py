"""Bad input to the split-Hopkinson-bar reduction is refused with a message that names the argument."""

import numpy as np
import pytest
from shpb_synthetic import SPECIMEN, build_shot, ti_bar

from rodimpact import TITANIUM_TI6AL4V
from rodimpact.shpb import (Bar, GaugeSignals, PulseWindows, SpecimenGeometry, Window, find_windows,
                            reduce_shot)
from rodimpact.signals import Recording


@pytest.fixture(scope="module")
def shot():
    return build_shot(ti_bar(), ti_bar("transmitted"), SPECIMEN)


@pytest.mark.parametrize("kwargs, error, match", [
    ({"diameter": -9e-3, "gauge_distance": 0.3}, ValueError, r"Bar.diameter: must be > 0, got -0.009"),
    ({"diameter": 9e-3, "area": 6e-5, "gauge_distance": 0.3}, ValueError, "Bar: give exactly one of diameter and area"),
    ({"gauge_distance": 0.3}, ValueError, "Bar: give exactly one of diameter and area, got neither"),
    ({"diameter": 9e-3, "gauge_distance": -0.3}, ValueError, "Bar.gauge_distance: must be >= 0"),
    ({"diameter": "9 kg", "gauge_distance": 0.3}, ValueError, r"Bar.diameter: expected a quantity in m"),
    ({"diameter": 9e-3, "gauge_distance": 0.3, "poisson_ratio": 0.6}, ValueError,
     r"Bar.poisson_ratio: must lie in \[0, 0.5\)"),
])
def test_bad_bars(kwargs, error, match):
    with pytest.raises(error, match=match):
        Bar(material=TITANIUM_TI6AL4V, **kwargs)


def test_bad_bar_material_and_specimen():
    with pytest.raises(ValueError, match="Bar.material: unknown material preset 'titanum'"):
        Bar(material="titanum", diameter=9e-3, gauge_distance=0.3)
    with pytest.raises(ValueError, match="SpecimenGeometry.length: must be > 0, got 0"):
        SpecimenGeometry(length=0, diameter=6e-3)
    with pytest.raises(ValueError, match="SpecimenGeometry: give exactly one of diameter and area"):
        SpecimenGeometry(length=3e-3)
    assert Bar(material="ti-6al-4v", diameter="9.47 mm", gauge_distance="381 mm").area == pytest.approx(
        np.pi * 9.47e-3 ** 2 / 4, rel=1e-14)


def test_a_specimen_wider_than_a_bar_is_refused(shot):
    wide = SpecimenGeometry(length=3e-3, diameter=10e-3)
    with pytest.raises(ValueError, match=r"specimen.diameter: 10 mm is wider than the incident_bar \(9.47 mm\)"):
        reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, wide)
    thin = Bar(material=TITANIUM_TI6AL4V, diameter=5e-3, gauge_distance=shot.transmitted_bar.gauge_distance)
    with pytest.raises(ValueError, match="specimen.diameter: 6.34 mm is wider than the transmitted_bar"):
        reduce_shot(shot.signals, shot.incident_bar, thin, SPECIMEN)


@pytest.mark.parametrize("change, error, match", [
    ({"signals": "shot.csv"}, TypeError, "signals: must be rodimpact.shpb.GaugeSignals"),
    ({"incident_bar": TITANIUM_TI6AL4V}, TypeError, "incident_bar: must be a rodimpact.shpb.Bar"),
    ({"specimen": 3.2e-3}, TypeError, "specimen: must be a rodimpact.shpb.SpecimenGeometry"),
    ({"windows": (0.0, 1e-5)}, TypeError, "windows: must be a rodimpact.shpb.PulseWindows"),
    ({"bands": (0.1, 0.05)}, ValueError, "bands: the pass limit must be below the review limit"),
])
def test_bad_arguments_of_reduce_shot(shot, change, error, match):
    args = {"signals": shot.signals, "incident_bar": shot.incident_bar, "transmitted_bar": shot.transmitted_bar,
            "specimen": shot.specimen, **change}
    with pytest.raises(error, match=match):
        reduce_shot(**args)


def test_windows_outside_the_record_and_bad_window_settings(shot):
    late = PulseWindows(shot.windows.incident, Window(shot.signals.time[-1] - 1e-6, shot.windows.reflected.duration),
                        shot.windows.transmitted)
    with pytest.raises(ValueError, match="windows.reflected: .* reaches beyond the record"):
        reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=late)
    with pytest.raises(ValueError, match="Window.duration: must be > 0"):
        Window(0.0, -1e-6)
    with pytest.raises(TypeError, match="PulseWindows.reflected: must be a Window"):
        PulseWindows(shot.windows.incident, (0.0, 1e-5), shot.windows.transmitted)
    bars = (shot.incident_bar, shot.transmitted_bar)
    with pytest.raises(ValueError, match="threshold: must be < 1"):
        find_windows(shot.signals, *bars, threshold=1.5)
    with pytest.raises(ValueError, match=r"foot: must lie in \[0, threshold"):
        find_windows(shot.signals, *bars, foot=0.2)
    with pytest.raises(TypeError, match="reflected: must be a real number in s"):
        find_windows(shot.signals, *bars, reflected="soon")


def test_the_incident_pulse_must_be_findable_and_apart_from_the_reflected_one(shot):
    s = shot.signals
    quiet = GaugeSignals(s.time, np.zeros(s.time.size), s.transmitted)
    with pytest.raises(ValueError, match="signals.incident: the incident-bar record is zero everywhere"):
        find_windows(quiet, shot.incident_bar, shot.transmitted_bar)
    near = Bar(material=TITANIUM_TI6AL4V, diameter=9.47e-3, gauge_distance=0.1)      # round trip 39 us < 60 us
    with pytest.raises(ValueError, match="incident_bar.gauge_distance: the incident pulse lasts .* longer than the "
                                         "round trip"):
        find_windows(s, near, shot.transmitted_bar)
    endless = GaugeSignals(s.time, np.where(s.time > s.time[shot.start], -1e-3, 0.0), s.transmitted)
    with pytest.raises(ValueError, match="does not fall back"):
        find_windows(endless, shot.incident_bar, shot.transmitted_bar)


def test_dispersion_needs_the_poisson_ratio(shot):
    bar = Bar(material=TITANIUM_TI6AL4V, diameter=9.47e-3, gauge_distance=shot.incident_bar.gauge_distance)
    with pytest.raises(ValueError, match=r"incident_bar.poisson_ratio: needed for the dispersion correction"):
        reduce_shot(shot.signals, bar, shot.transmitted_bar, shot.specimen, windows=shot.windows, dispersion=True)


def test_bad_gauge_signals():
    t = 1e-7 * np.arange(10)
    with pytest.raises(ValueError, match="GaugeSignals.time: must be uniform"):
        GaugeSignals(t ** 2, np.zeros(10), np.zeros(10))
    with pytest.raises(ValueError, match="GaugeSignals.transmitted: has 9 samples but time has 10"):
        GaugeSignals(t, np.zeros(10), np.zeros(9))
    with pytest.raises(ValueError, match="GaugeSignals.incident: must be finite, entry 3"):
        GaugeSignals(t, np.where(np.arange(10) == 3, np.nan, 0.0), np.zeros(10))


def test_bad_recordings():
    t = 1e-7 * np.arange(200)
    pulse = np.where((t > 5e-6) & (t < 8e-6), 1.0, 0.0)
    volts = Recording(t, {"incident": pulse, "transmitted": pulse}, {"incident": "V", "transmitted": "V"})
    with pytest.raises(ValueError, match="incident_gauge: channel 'incident' is in 'V'; give the GaugedBar"):
        GaugeSignals.from_recording(volts)
    with pytest.raises(ValueError, match=r"channels: no channel 'Ch1' in the recording; channels: \['incident', "):
        GaugeSignals.from_recording(volts, channels=("Ch1", "Ch3"))
    strains = Recording(t, {"incident": pulse, "transmitted": pulse})
    with pytest.raises(ValueError, match="baseline: must be 'auto', a time span"):
        GaugeSignals.from_recording(strains, baseline="mean")
    with pytest.raises(ValueError, match=r"baseline: no sample of channel 'incident' lies in"):
        GaugeSignals.from_recording(strains, baseline=(1.0, 2.0))
    early = Recording(t, {"incident": np.roll(pulse, -48), "transmitted": pulse})
    with pytest.raises(ValueError, match="baseline: channel 'incident' has 2 sample"):
        GaugeSignals.from_recording(early)
    with pytest.raises(TypeError, match="incident_gauge: must be a rodimpact.signals.GaugedBar"):
        GaugeSignals.from_recording(strains, "quarter")
    offset = GaugeSignals.from_recording(Recording(t, {"incident": pulse + 0.5, "transmitted": pulse - 0.25}))
    np.testing.assert_allclose(offset.incident, pulse, atol=1e-15)                    # the offsets are gone
    np.testing.assert_allclose(offset.transmitted, pulse, atol=1e-15)


def test_opposite_gauges_are_averaged_and_volts_converted():
    """Two gauges of one bar read axial strain plus and minus a bending strain: their mean is the axial strain
    (thesis eq. 5.1). A channel in volts goes through its GaugedBar (quarter bridge: eps = 4 V_r / (GF (1 - 2 V_r)),
    V_r = V / (V_exc gain))."""
    from rodimpact.signals import GaugedBar

    t = 1e-7 * np.arange(200)
    axial = np.where((t > 5e-6) & (t < 8e-6), -1e-3, 0.0)
    bending = 2e-4 * np.sin(t / 1e-6)
    rec = Recording(t, {"a": axial + bending, "b": axial - bending, "t": axial})
    signals = GaugeSignals.from_recording(rec, channels=(["a", "b"], "t"), baseline=None)
    np.testing.assert_allclose(signals.incident, axial, atol=1e-18)
    gauge = GaugedBar(youngs_modulus=110e9, density=4400.0, area=7e-5, gauge_factor=2.0, excitation_voltage=10.0,
                      gain=100.0)
    vr = 2.0 * axial / (4 + 2 * 2.0 * axial)                # the quarter bridge's output for that strain
    volts = Recording(t, {"incident": vr * 1000.0, "transmitted": vr * 1000.0}, {"incident": "V", "transmitted": "V"})
    converted = GaugeSignals.from_recording(volts, gauge, gauge)
    np.testing.assert_allclose(converted.incident, axial, rtol=1e-12, atol=1e-18)
    with pytest.raises(ValueError, match="channels: no channel given for the incident bar"):
        GaugeSignals.from_recording(rec, channels=([], "t"))
