"""Bad input to the measurement side gets a clear error naming the quantity, never a NaN, a silently empty result or
a traceback from deep inside numpy/scipy; and the analog-filter simulation stays exact where it used to fail."""

import numpy as np
import pytest
from scipy import signal

import rodimpact as ri
import rodimpact.signals as S
import rodimpact.testrig as RIG
from rodimpact.signals.filters import MAX_ORDER

NAN = float("nan")
T = np.arange(0, 50e-6, 1e-7)
#: a compressive trapezoid: 0 -> -1 on [10, 12] us, back to 0 on [30, 34] us
Y = -np.clip((T - 10e-6) / 2e-6, 0, 1) + np.clip((T - 30e-6) / 4e-6, 0, 1)


# ----------------------------------------------------------------------------------------------- compare
def test_shifted_needs_a_finite_delay():
    with pytest.raises(ValueError, match="delay: must be finite"):
        S.shifted(T, Y, NAN)
    with pytest.raises(ValueError, match="delay: must be finite"):
        S.shifted(T, Y, float("inf"))


@pytest.mark.parametrize("ddof, error", [(2, ValueError), (3, ValueError), (-1, ValueError), (0.5, TypeError),
                                         (True, TypeError), (None, TypeError)])
def test_shot_statistics_ddof_is_an_integer_below_the_number_of_shots(ddof, error):
    with pytest.raises(error, match="ddof"):
        S.shot_statistics([Y, Y + 0.1], ddof=ddof)


def test_shot_statistics_other_bad_shots():
    stats = S.shot_statistics([Y, Y + 0.1, Y + 0.2], ddof=2)      # ddof < 3 shots is fine
    assert np.all(np.isfinite(stats.std))
    with pytest.raises(ValueError, match="shots: the shots hold no samples"):
        S.shot_statistics([[], []])
    with pytest.raises(ValueError, match="shots: must be finite, shot 1 sample 0"):
        S.shot_statistics([[1.0, 2.0], [NAN, 2.0]])
    with pytest.raises(TypeError, match="shots"):
        S.shot_statistics(None)
    with pytest.raises(ValueError, match="k: must be finite"):
        stats.band(NAN)


def test_level_must_be_finite_on_every_crossing_path():
    with pytest.raises(ValueError, match="level: must be finite"):
        S.crossing_times(T, Y, NAN)
    with pytest.raises(ValueError, match="level: must be finite"):
        S.trigger_time(T, Y, NAN)
    with pytest.raises(ValueError, match="level: must be finite"):
        S.delay_by_trigger(T, Y, Y, NAN)
    with pytest.raises(ValueError, match="level: must be finite"):
        S.align(T, Y, Y, method="trigger", level=NAN)
    with pytest.raises(ValueError, match="level: must be finite"):
        S.step_timing_errors(T, Y, Y, [-0.5, NAN])
    with pytest.raises(TypeError, match="level"):
        S.crossing_times(T, Y, None)
    with pytest.raises(ValueError, match="after: must be finite"):
        S.trigger_time(T, Y, -0.5, after=NAN)


def test_other_compare_arguments():
    with pytest.raises(ValueError, match="max_delay"):
        S.delay_by_xcorr(T, Y, Y, max_delay=NAN)
    with pytest.raises(ValueError, match="max_delay"):
        S.delay_by_xcorr(T, Y, Y, max_delay=-1e-6)
    with pytest.raises(ValueError, match="method"):
        S.align(T, Y, Y, method="fft")
    with pytest.raises(ValueError, match="level"):
        S.align(T, Y, Y, method="trigger")
    with pytest.raises(ValueError, match="slope"):
        S.trigger_time(T, Y, -0.5, slope="down")
    with pytest.raises(ValueError, match="window start: must be finite"):
        S.peak_error(T, Y, Y, window=(NAN, 1e-5))
    with pytest.raises(ValueError, match="window: start must be before stop"):
        S.normalized_rms_error(T, Y, Y, window=(2e-5, 1e-5))
    with pytest.raises(TypeError, match="window: must be a pair"):
        S.peak_error(T, Y, Y, window=1e-5)
    with pytest.raises(ValueError, match="window: .* contains no samples"):
        S.peak_error(T, Y, Y, window=(1.0, 2.0))
    with pytest.raises(ValueError, match="levels: give at least one level"):
        S.step_timing_errors(T, Y, Y, [])
    with pytest.raises(ValueError, match="time and values must be 1-D arrays of equal length"):
        S.crossing_times(T, Y[:-1], -0.5)


# ----------------------------------------------------------------------------------------------- pulses
def test_striker_velocity_from_strain_checks_its_inputs():
    with pytest.raises(ValueError, match="plateau_strain: must be finite"):
        S.striker_velocity_from_strain(NAN, 5000.0)
    with pytest.raises(ValueError, match="wave_speed: must be > 0"):
        S.striker_velocity_from_strain(-1e-3, 0.0)
    with pytest.raises(ValueError, match="wave_speed: must be finite"):
        S.striker_velocity_from_strain(-1e-3, NAN)
    with pytest.raises(TypeError, match="plateau_strain"):
        S.striker_velocity_from_strain(None, 5000.0)


@pytest.mark.parametrize("args, name", [((NAN, 0.1, 1.0), "start"), ((0.0, NAN, 1.0), "duration"),
                                        ((0.0, -0.1, 1.0), "duration"), ((0.0, 0.1, NAN), "amplitude")])
def test_rectangular_pulse_checks_its_parameters(args, name):
    with pytest.raises(ValueError, match=f"{name}: must be"):
        S.rectangular_pulse(T, *args)


def test_rectangular_and_equal_impedance_pulse_other_inputs():
    with pytest.raises(ValueError, match="time: must be finite"):
        S.rectangular_pulse([0.0, NAN], 0.0, 0.1, 1.0)
    with pytest.raises(ValueError, match="velocity: must be finite"):
        S.equal_impedance_pulse(T, 0.2, 5000.0, 1e4, NAN)
    with pytest.raises(ValueError, match="arrival_time: must be finite"):
        S.equal_impedance_pulse(T, 0.2, 5000.0, 1e4, 4.6, arrival_time=NAN)
    np.testing.assert_array_equal(S.rectangular_pulse(0.5, 0.0, 1.0, 2.0), 2.0)   # scalars still work


@pytest.mark.parametrize("trims, error, match", [
    ((), ValueError, "trims: give at least one"),
    ((0.1, 0.7), ValueError, r"trims\[1\]: .* \[0, 0.5\)"),
    ((0.1, -0.1), ValueError, r"trims\[1\]"),
    ((0.1, NAN), ValueError, r"trims\[1\]: must be finite"),
    (0.2, TypeError, "trims: must be a sequence"),
    ("abc", TypeError, "trims: must be a sequence"),
])
def test_striker_velocity_estimate_validates_trims(trims, error, match):
    with pytest.raises(error, match=match):
        S.striker_velocity_estimate(T, Y * 1e-3, 5000.0, trims=trims)


def test_striker_velocity_estimate_single_trim_and_uncertainties():
    est = S.striker_velocity_estimate(T, Y * 1e-3, 5000.0, trims=(0.2,))
    assert est.velocity == pytest.approx(10.0) and est.components["plateau definition"] == 0.0
    with pytest.raises(TypeError, match="relative_uncertainties: must be a mapping"):
        S.striker_velocity_estimate(T, Y * 1e-3, 5000.0, [0.01])
    with pytest.raises(ValueError, match=r"relative_uncertainties\['gauge'\]: must be >= 0"):
        S.striker_velocity_estimate(T, Y * 1e-3, 5000.0, {"gauge": -0.01})
    with pytest.raises(ValueError, match="wave_speed"):
        S.striker_velocity_estimate(T, Y * 1e-3, NAN)


def test_pulse_features_and_impulse_arguments():
    with pytest.raises(ValueError, match="fraction: must be finite"):
        S.pulse_features(T, Y, fraction=NAN)
    with pytest.raises(ValueError, match="plateau_trim"):
        S.pulse_features(T, Y, plateau_trim=0.5)
    with pytest.raises(ValueError, match="plateau_window: start must be before stop"):
        S.pulse_features(T, Y, plateau_window=(25e-6, 15e-6))
    with pytest.raises(ValueError, match="time and values must be finite"):
        S.pulse_features(T, np.where(T > 40e-6, NAN, Y))
    with pytest.raises(ValueError, match="window start: must be finite"):
        S.striker_velocity_from_impulse(T, Y, 0.3, (NAN, 1.0))
    with pytest.raises(ValueError, match="force: its integral over window"):
        S.striker_velocity_from_impulse(T, np.zeros_like(T), 0.3, (0.0, 1.0))
    with pytest.raises(ValueError, match="striker_mass"):
        S.striker_velocity_from_impulse(T, Y, 0.0, (0.0, 1.0))
    with pytest.raises(ValueError, match="strictly increasing"):
        S.striker_velocity_from_impulse(T[::-1], Y, 0.3, (0.0, 1.0))


# ----------------------------------------------------------------------------------------------- filters
@pytest.mark.parametrize("call, name", [
    (lambda: S.bessel_analog(100, 1e5), "order"),
    (lambda: S.bessel_analog(0, 1e5), "order"),
    (lambda: S.bessel_analog(MAX_ORDER + 1, 1e5), "order"),
    (lambda: S.bessel_digital(MAX_ORDER + 1, 4e4, 1e6), "order"),
    (lambda: S.simulate_analog_filter(T, Y, order=50), "order"),
    (lambda: S.MeasuringChain(analog_order=MAX_ORDER + 1), "analog_order"),
    (lambda: S.MeasuringChain(digital_order=100), "digital_order"),
])
def test_filter_orders_are_limited_to_the_reliable_range(call, name):
    with pytest.raises(ValueError, match=f"{name}: must be an integer from 1 to {MAX_ORDER}"):
        call()


def test_filter_order_must_be_an_integer():
    with pytest.raises(TypeError, match="order: must be an integer"):
        S.bessel_analog(5.0, 1e5)
    with pytest.raises(TypeError, match="analog_order: must be an integer"):
        S.MeasuringChain(analog_order=True)


@pytest.mark.parametrize("norm", ["mag", "phase", "delay"])
def test_every_accepted_order_designs_and_simulates_reliably(norm):
    # the whole accepted range: scipy's design (DC gain 1, -3 dB at the corner for 'mag'), the digital sections,
    # and the analog simulation on a grid 10^4 x finer than the corner (the old cascade gave 1e7 there at order 5)
    t = np.arange(0, 200e-6, 1e-9)                       # uniform at 1 GHz: simulated on the input's own grid
    x = np.where(t > 20e-6, 1.0, 0.0)
    for order in range(1, MAX_ORDER + 1):
        z, p, k = S.bessel_analog(order, 100e3, norm)
        _, h = signal.freqs_zpk(z, p, k, worN=[0.0, 2 * np.pi * 100e3])
        assert abs(h[0]) == pytest.approx(1.0, rel=1e-9)
        if norm == "mag":
            assert abs(h[1]) == pytest.approx(2 ** -0.5, rel=1e-9)
        _, hd = signal.sosfreqz(S.bessel_digital(order, 40e3, 1e6, norm), worN=[0.0], fs=1e6)
        assert abs(hd[0]) == pytest.approx(1.0, rel=1e-9)
        grid, y = S.simulate_analog_filter(t, x, order=order, corner=100e3, norm=norm)
        assert grid.size == t.size and np.all(np.isfinite(y))
        assert np.max(np.abs(y[t < 20e-6])) < 1e-12          # steady state before the step
        assert y[-1] == pytest.approx(1.0, abs=1e-6)          # settled after 180 us
        assert -1e-6 < y.min() and y.max() < 1.02             # Bessel: (almost) no overshoot


@pytest.mark.parametrize("order", [2, 5, 8, 12])
def test_analog_simulation_on_a_fine_grid_matches_lsim(order):
    t = np.arange(0, 40e-6, 1e-9)                         # 10^4 samples per corner period (100 kHz)
    x = np.where(t > 5e-6, 1.0, 0.0) * np.sin(2 * np.pi * 3e4 * t)
    _, y = S.simulate_analog_filter(t, x, order=order, corner=100e3)
    _, y_lsim, _ = signal.lsim(S.bessel_analog(order, 100e3), x, t)
    assert np.max(np.abs(y - y_lsim)) < 1e-9


def test_simulation_rate_that_cannot_fit_in_memory_is_named():
    with pytest.raises(ValueError, match="simulation_rate: .* GiB"):
        S.simulate_analog_filter(T, Y, simulation_rate=1e15)
    with pytest.raises(ValueError, match="analog_rate: .* GiB"):
        S.MeasuringChain(analog_rate=1e15).apply(T, Y)
    with pytest.raises(ValueError, match="sampling_rate: .* GiB"):
        S.MeasuringChain(analog_order=None, digital_order=None, sampling_rate=1e15).apply(T, Y)


def test_other_filter_arguments():
    chain = S.MeasuringChain()
    with pytest.raises(ValueError, match="frequency: must be finite"):
        chain.response([1e3, NAN])
    with pytest.raises(ValueError, match="frequency: must be finite"):
        chain.group_delay(NAN)
    with pytest.raises(TypeError, match="zero_phase: must be True or False"):
        chain.apply(T, Y, zero_phase="yes")
    with pytest.raises(ValueError, match="interpolation"):
        chain.apply(T, Y, interpolation="cubic")
    with pytest.raises(ValueError, match="time: the signal spans .* shorter than one sample interval"):
        chain.apply(T[:5], Y[:5])
    with pytest.raises(ValueError, match="time and values: need at least 2 samples"):
        S.simulate_analog_filter([0.0], [1.0])
    with pytest.raises(ValueError, match="values: must be finite"):
        S.simulate_analog_filter(T, np.where(T > 1e-5, NAN, 0.0))
    with pytest.raises(ValueError, match="corner: must be > 0"):
        S.bessel_analog(5, -1.0)
    with pytest.raises(ValueError, match="zero_phase: zero-phase filtering needs more than"):
        S.simulate_analog_filter(T[:10], Y[:10], simulation_rate=1e7, zero_phase=True)
    rec = S.Recording(T, {"a": Y, "b": 2 * Y})
    out = chain.apply_recording(rec, "b")                    # one name, not its characters
    assert out.channel_names == ["b"]
    with pytest.raises(ValueError, match="channels: name at least one channel"):
        chain.apply_recording(rec, [])
    with pytest.raises(KeyError, match="no channel 'c'"):
        chain.apply_recording(rec, ["c"])
    with pytest.raises(TypeError, match="recording: must be a Recording"):
        chain.apply_recording({"a": Y})


def test_zero_phase_analog_stage_matches_scipys_forward_backward_filter():
    # sosfiltfilt of the same (well-conditioned at 10 MHz) filter: same padding, same start-up
    t = np.arange(0, 200e-6, 1e-7)
    x = np.exp(-0.5 * ((t - 100e-6) / 10e-6) ** 2)
    _, y = S.simulate_analog_filter(t, x, order=5, corner=100e3, simulation_rate=1e7, zero_phase=True)
    z, p, k = signal.bessel(5, 2 * np.pi * 100e3, analog=True, output="zpk", norm="mag")
    zd, pd, kd = signal.bilinear_zpk(z, p, k, fs=1e7)       # not the same discretisation: shape check only
    y_ref = signal.sosfiltfilt(signal.zpk2sos(zd, pd, kd), x)
    assert np.max(np.abs(y - y_ref)) < 2e-3
    assert abs(t[np.argmax(y)] - 100e-6) <= 1e-7              # no delay


# ----------------------------------------------------------------------------------------------- gauges, dispersion
def test_gauge_and_dispersion_arguments():
    with pytest.raises(TypeError, match="arms"):
        S.Bridge(("a", 0, 0, 0))
    with pytest.raises(TypeError, match="gain"):
        S.GaugedBar(2e11, 7800.0, 1e-3, 2.0, 5.0, gain=None)
    with pytest.raises(TypeError, match="poisson_ratio"):
        S.Bridge.half_poisson(None)
    with pytest.raises(TypeError, match="model: must be a PochhammerChree"):
        S.gauge_length_average(T, Y, 0.005, model="bancroft")
    with pytest.raises(TypeError, match="poisson_ratio"):
        S.rayleigh_speed_ratio([0.3])
    with pytest.raises(ValueError, match="table_step: at most"):
        S.PochhammerChree(0.29, 0.025, 5175.0, table_step=1.0)
    with pytest.raises(TypeError, match="radius"):
        S.PochhammerChree(0.29, None, 5175.0)
    model = S.PochhammerChree(0.29, 0.025, 5175.0)
    with pytest.raises(ValueError, match="frequency: must be finite"):
        model.group_velocity([1e4, NAN])
    with pytest.raises(ValueError, match="frequency: up to .* Hz .* dispersion table would need"):
        model.phase_velocity(1e10)                            # would take hours of root solving
    t = np.arange(0, 1e-6, 1e-11)
    with pytest.raises(ValueError, match="time: up to .* Nyquist"):
        S.propagate_dispersive(t, np.sin(1e7 * t), 0.5, model)
    with pytest.raises(ValueError, match="distance: must be finite"):
        S.propagate_dispersive(T, Y, NAN, model)
    with pytest.raises(ValueError, match="distance: propagating over"):
        S.propagate_dispersive(T[::10], Y[::10], 1e12, model)


def test_recording_arguments():
    rec = S.Recording(T, {"a": Y, "b": Y})
    with pytest.raises(ValueError, match="start: must be finite"):
        rec.window(NAN, 1e-5)
    assert rec.selected("a").channel_names == ["a"]
    with pytest.raises(ValueError, match="names: select at least one channel"):
        rec.selected([])
    with pytest.raises(TypeError, match="metadata: must be a mapping"):
        S.Recording(T, {"a": Y}, metadata=[1, 2])


# ----------------------------------------------------------------------------------------------- test rig
def test_build_rig_gauges_must_be_a_mapping():
    with pytest.raises(TypeError, match=r"gauges: must be a mapping name -> position \(m"):
        RIG.build_rig(1, gauges=[0.1, 0.2])
    setup = RIG.build_rig(1, gauges={"A": 0.1, "B": 0.2})
    assert setup.gauges == (("A", 0.1), ("B", 0.2))


def test_simulate_rig_names_the_minimum_duration():
    setup = RIG.build_rig(1)
    with pytest.raises(ValueError, match=r"duration: must be at least .*1 / sampling_rate.* got 1e-07 s"):
        RIG.simulate_rig(setup, duration=1e-7)
    dt = RIG.rig_time_step(setup)
    minimum = (1e-6 + dt) * (1 + 1e-6)
    signals = RIG.simulate_rig(setup, duration=minimum)
    assert signals.filtered_time.size == 2
    with pytest.raises(ValueError, match="duration: must be at least"):
        RIG.simulate_rig(setup, duration=0.99 * minimum)


def test_rig_helpers_check_their_arguments():
    with pytest.raises(TypeError, match="setup: must be a RigSetup"):
        RIG.rig_time_step(None)
    setup = RIG.build_rig(1)
    with pytest.raises(ValueError, match="position: must be finite"):
        setup.gauge_travel_time(NAN)
    with pytest.raises(ValueError, match="position: must lie on the rod"):
        setup.gauge_travel_time(5.0)
    assert setup.gauge_travel_time(0.9) == pytest.approx(0.9 / ri.STEEL.wave_speed)


@pytest.mark.parametrize("corner", [1e300, 1e80, 1e-300, 1e-80])
def test_bessel_analog_refuses_a_corner_whose_gain_is_not_a_normal_float(corner):
    # (2 pi corner)^4 overflows above ~1e76 Hz and is subnormal below ~1e-78 Hz: a ValueError naming corner
    # and the valid range, not an OverflowError from inside scipy or a gain of 0
    with pytest.raises(ValueError, match=r"corner: must lie between .* Hz and .* Hz for order 4"):
        S.bessel_analog(4, corner)


def test_bessel_analog_still_designs_extreme_but_representable_corners():
    for corner in (1e-60, 1e60):
        z, p, k = S.bessel_analog(4, corner)
        # the -3 dB point (norm "mag") stays at the corner and the gain is finite and nonzero
        w = 2 * np.pi * corner
        h = k / np.prod(1j * w - p)
        assert np.isfinite(k) and k > 0
        assert abs(abs(h) - 2**-0.5) < 1e-9


_BAR = dict(youngs_modulus=200e9, density=7850.0, area=2e-4, gauge_factor=2.0, excitation_voltage=10.0)


@pytest.mark.parametrize("key, value", [("gauge_factor", "5"), ("gauge_factor", True), ("area", "2e-4"),
                                        ("excitation_voltage", None), ("density", [7850.0]), ("gain", "200")])
def test_gauged_bar_refuses_wrong_types_instead_of_coercing(key, value):
    # issue 20 item 12: a gauge factor "5" was read as 5.0 by float()
    with pytest.raises(TypeError, match=rf"^{key}: must be a real number"):
        S.GaugedBar(**{**_BAR, key: value})


def test_gauged_bar_polarity_and_bridge_arms_are_numbers_not_coerced():
    with pytest.raises(TypeError, match="polarity must be"):
        S.GaugedBar(**_BAR, polarity=True)
    for arms in (("1", 0, 0, 0), (True, 0, 0, 0), 5, "1000"):
        with pytest.raises(TypeError, match="arms: must be four strain factors"):
            S.Bridge(arms)


@pytest.mark.parametrize("call", [
    lambda: S.strain_to_force(["1e-3", "2e-3"], 200e9, 2e-4),
    lambda: S.strain_to_force([True, False], 200e9, 2e-4),
    lambda: S.bridge_to_strain(np.array(["0.001"]), 10.0, 2.0),
    lambda: S.Bridge.quarter().strain(["0.001"], 2.0),
    lambda: S.Bridge.quarter().strain([0.001], "2"),
])
def test_gauge_functions_refuse_strings_and_bools(call):
    with pytest.raises(TypeError):
        call()


def test_gauged_bar_still_takes_numbers_and_quantities_with_units():
    bar = S.GaugedBar(**{**_BAR, "youngs_modulus": "200 GPa", "excitation_voltage": "10 V", "gauge_factor": 2})
    assert bar.youngs_modulus == 200e9 and bar.excitation_voltage == 10.0 and bar.gauge_factor == 2.0
    assert S.GaugedBar(**{**_BAR, "gauge_factor": np.float32(2.0)}).gauge_factor == 2.0


@pytest.mark.parametrize("time, samples", [(["0", "1e-6"], [1.0, 2.0]), ([0.0, 1e-6], ["1", "2"]),
                                           ([0.0, 1e-6], [True, False])])
def test_recording_refuses_strings_and_bools_instead_of_converting(time, samples):
    with pytest.raises(TypeError, match="must be an array of real numbers"):
        S.Recording(time, {"a": samples})
