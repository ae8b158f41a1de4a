"""The force-equilibrium ratio R(t) = 2 |F1 - F2| / |F1 + F2|: zero for a specimen in equilibrium, the known value
for a known imbalance, the bands and the time from which equilibrium holds."""

import numpy as np
import pytest
from shpb_synthetic import DT, SAMPLES, SPECIMEN, build_shot

from rodimpact.shpb import PASS_LIMIT, REVIEW_LIMIT, check_equilibrium, reduce_shot


def _reduce(shot):
    return reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen, windows=shot.windows)


def test_ratio_is_zero_in_equilibrium(bars):
    red = _reduce(build_shot(*bars, SPECIMEN))
    eq = red.equilibrium
    loaded = ~np.isnan(eq.ratio)
    assert loaded.sum() > 0.9 * SAMPLES
    assert np.max(eq.ratio[loaded]) < 1e-12
    # undefined only where the mean face force is below 1 % of its peak (the start of the ramp)
    mean = 0.5 * np.abs(eq.front_force + eq.back_force)
    assert np.all(mean[~loaded] < 0.01 * mean.max()) and np.all(mean[loaded] >= 0.01 * mean.max())
    assert eq.equilibrium_time == red.time[np.argmax(loaded)]        # from the first loaded sample on
    assert eq.loading_end == red.time[-1]                            # the hardening specimen loads to the end
    assert set(np.unique(eq.band)) == {-1, 0}


def test_ratio_of_a_known_imbalance(bars):
    """F1 = (1 + d) F2 gives R = 2 d / (2 + d); with d = 0.3 exp(-t / tau) the pass band (5 %) holds from
    t = tau ln(0.3 / d5), d5 = 2 * 0.05 / (2 - 0.05), and the review band (10 %) from the same with 10 %."""
    tau = 80 * DT
    shot = build_shot(*bars, SPECIMEN, imbalance=lambda k: 0.3 * np.exp(-k * DT / tau))
    red = _reduce(shot)
    eq = red.equilibrium
    d = 0.3 * np.exp(-np.arange(SAMPLES) * DT / tau)
    loaded = ~np.isnan(eq.ratio)
    np.testing.assert_allclose(eq.ratio[loaded], (2 * d / (2 + d))[loaded], rtol=0, atol=1e-11)
    for limit, found in ((PASS_LIMIT, eq.equilibrium_time), (REVIEW_LIMIT, eq.review_time)):
        t_limit = tau * np.log(0.3 / (2 * limit / (2 - limit)))
        assert red.time[0] + t_limit <= found < red.time[0] + t_limit + DT        # the first sample after it
    # the 3-wave stress is the mean of the face forces over A0: (1 + d/2) times the back-face (2-wave) stress
    np.testing.assert_allclose(red.three_wave.stress, red.two_wave.stress * (1 + d / 2), rtol=1e-12)
    np.testing.assert_allclose(red.one_wave.stress, red.two_wave.stress * (1 + d), rtol=1e-12)


def test_bands_and_the_loading_end():
    """Hand-made forces: R = 0.02, 0.08, 0.2 are pass, review, fail; the loading part ends at the peak of the
    mean force (after it the specimen unloads and R may grow without moving the equilibrium time)."""
    time = np.arange(8) * 1e-6
    back = -np.array([0.0, 100.0, 200.0, 300.0, 400.0, 500.0, 200.0, 50.0])
    r = np.array([0.0, 0.2, 0.08, 0.02, 0.02, 0.02, 0.5, 1.0])
    front = back * (2 + r) / (2 - r)                       # 2 (F1 - F2) / (F1 + F2) = r
    eq = check_equilibrium(time, front, back)
    np.testing.assert_allclose(eq.ratio[1:], r[1:], rtol=1e-12)
    assert np.isnan(eq.ratio[0])
    assert list(eq.band) == [-1, 2, 1, 0, 0, 0, 2, 2]
    assert eq.loading_end == time[5]
    assert eq.equilibrium_time == time[3] and eq.review_time == time[2]
    never = check_equilibrium(time, front * np.array([1, 1, 1, 1, 1, 1.2, 1, 1]), back)
    assert never.equilibrium_time is None and never.review_time is None     # out of both bands at the peak
    wide = check_equilibrium(time, front, back, bands=(0.1, 0.3))
    assert wide.equilibrium_time == time[2] and wide.review_time == time[1]


@pytest.mark.parametrize("bands, match", [((0.1, 0.05), "pass limit must be below"), ((0.05,), "pass and the review"),
                                          ((0.0, 0.1), "bands: must be > 0")])
def test_bad_bands_are_refused(bands, match):
    with pytest.raises(ValueError, match=match):
        check_equilibrium(np.arange(3.0), -np.ones(3), -np.ones(3), bands)
