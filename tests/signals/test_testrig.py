"""The thesis test-rig model (Secs. 5.1-5.4) against hand-derived wave paths and closed forms.

References are written out here from the geometry (E = 210 GPa, rho = 7840 kg/m^3, diameters and lengths),
not taken from the module: impedances Z = rho c pi d^2 / 4, contact of two impedances, transmission
2 Z_far / (Z_near + Z_far) and reflection (Z_far - Z_near) / (Z_near + Z_far) of force waves at steps.
With dt = 10 mm / c every step of piston 1, every gauge and the rod end lie on lattice nodes, so the
lattice solution is exact and the comparisons are to rounding.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import signal

import rodimpact as ri
from rodimpact.signals import MeasuringChain, normalize_by_global_minimum
from rodimpact.testrig import (
    GAUGE_POSITIONS,
    IMPACT_VELOCITIES,
    RigSetup,
    build_rig,
    piston_from_face,
    rig_time_step,
    simulate_rig,
    wave_paths,
)

E, RHO = 210e9, 7840.0
C = math.sqrt(E / RHO)
X1, X2, X3, L = 0.110, 0.900, 1.690, 1.800
V = 4.60
DT10 = 0.010 / C                        # all lengths of piston 1, rod and gauges are multiples of 10 mm


def impedance(d: float) -> float:
    return RHO * C * math.pi * d**2 / 4


Z40, Z50 = impedance(0.040), impedance(0.050)
F0 = -Z40 * Z50 * V / (Z40 + Z50)      # first plateau: 40 mm piston face on the 50 mm rod
R = (Z50 - Z40) / (Z50 + Z40)           # reflection 40 -> 50 mm; 50 -> 40 mm is -R; transmissions 1 +- R
TAU = 0.100 / C                          # travel time of the 100 mm end parts; the middle part takes 3 TAU


def piston_1_incident(t_after_arrival: np.ndarray, v: float = V) -> np.ndarray:
    """Hand-derived incident force of piston 1 (0.1 / 0.3 / 0.1 m, 40 / 50 / 40 mm) on the rod.

    Waves return from the piston to the contact face at multiples of 2 TAU; each is transmitted into the rod
    with 1 + R. Paths (sum of round trips, R at the contact face between them):
      2 TAU: reflect at step 1                                   R
      4, 6 TAU: two / three round trips in the face part         R^3, R^5
      8 TAU: four round trips; or through step 1, reflect at step 2 (-R), back (1 - R):
             R^7 + (1 + R)(-R)(1 - R) = R^7 - R (1 - R^2)
    At 10 TAU = t* the free-end reflection arrives and the contact force would turn tensile (checked in
    test_piston_1_separates_at_t_star): the bodies separate and the incident wave ends.
    """
    f0 = -Z40 * Z50 * v / (Z40 + Z50)
    increments = [1.0, (1 + R) * R, (1 + R) * R**3, (1 + R) * R**5, (1 + R) * (R**7 - R * (1 - R**2))]
    levels = np.cumsum(increments) * f0
    m = np.floor(np.round(t_after_arrival / TAU, 9) / 2).astype(int)
    out = np.zeros(t_after_arrival.shape)
    inside = (m >= 0) & (m < 5)
    out[inside] = levels[m[inside]]
    return out


@pytest.fixture(scope="module")
def piston_1_run():
    return simulate_rig(build_rig(1, V), duration=1.2e-3, dt=DT10)


@pytest.fixture(scope="module")
def piston_2_run():
    rig = build_rig(2)
    return simulate_rig(rig, duration=0.45e-3)


# ------------------------------------------------------------------------------------------- data
def test_rig_data_match_the_thesis():
    assert dict(GAUGE_POSITIONS) == {"SGP1": 0.110, "SGP2": 0.900, "SGP3": 1.690}
    # SGP1 and SGP3 are 110 mm from their ends, SGP2 in the middle (Sec. 5.1)
    assert GAUGE_POSITIONS["SGP1"] == pytest.approx(L - GAUGE_POSITIONS["SGP3"], abs=1e-12)
    assert GAUGE_POSITIONS["SGP2"] == pytest.approx(L / 2, abs=1e-12)
    assert IMPACT_VELOCITIES["repeatability"] == (4.57, 4.58, 4.60)
    assert IMPACT_VELOCITIES["impact velocity"] == (3.47, 4.60, 5.60)
    assert IMPACT_VELOCITIES["standard piston"] == (4.60,)
    assert IMPACT_VELOCITIES["complex piston"] == (4.58,)
    rig = build_rig(1)
    assert rig.velocity == 4.60 and build_rig(2).velocity == 4.58
    assert rig.rod.length == pytest.approx(L) and rig.rod.area(0.5) == pytest.approx(math.pi * 0.05**2 / 4)
    assert rig.piston.length == pytest.approx(0.5)
    assert rig.piston.mass == pytest.approx(RHO * math.pi / 4 * (0.04**2 * 0.2 + 0.05**2 * 0.3), rel=1e-12)
    # impact face = right end of the piston: 40 mm there
    assert rig.piston.area(rig.piston.length) == pytest.approx(math.pi * 0.04**2 / 4)
    assert [p.rod for p in rig.probes] == [1, 1, 1]


def test_t_star_is_0_193_ms_not_1_93_ms():
    rig = build_rig(1)
    t_star = 2 * 0.5 / C                          # eq. (5.4)
    assert rig.pulse_duration == pytest.approx(t_star, rel=1e-12)
    assert abs(rig.pulse_duration - 0.193e-3) < 0.0005e-3       # the thesis's 1.93 to three digits ...
    assert abs(rig.pulse_duration - 1.93e-3) > 1e-3             # ... times 1e-4 s, not 1e-3 s


def test_piston_from_face_mirrors_a_cone():
    p = piston_from_face([ri.Cone(0.08, 0.030, 0.050), ri.Cylinder(0.1, 0.036)])
    # the 30 mm end of the cone is the impact face = the rod's right end
    assert p.area(p.length) == pytest.approx(math.pi * 0.030**2 / 4)
    assert p.area(0.1 + 1e-9) == pytest.approx(math.pi * 0.050**2 / 4, rel=1e-6)
    assert p.area(0.0) == pytest.approx(math.pi * 0.036**2 / 4)


# ------------------------------------------------------------------------------------------- (a) steps
def test_wave_path_times_for_piston_1():
    rows = [r for r in wave_paths(build_rig(1)) if r.gauge == "SGP1"]
    times = {r.event: [] for r in rows}
    for r in rows:
        times[r.event].append(r.time)
    t1 = X1 / C
    assert times["incident front"] == [pytest.approx(t1, rel=1e-12)]
    assert times["step reflection"] == [pytest.approx(t1 + 2 * 0.100 / C, rel=1e-12),
                                        pytest.approx(t1 + 2 * 0.400 / C, rel=1e-12)]
    assert times["face-segment echo"] == [pytest.approx(t1 + 4 * 0.100 / C, rel=1e-12)]
    assert times["piston free end"] == [pytest.approx(t1 + 2 * 0.500 / C, rel=1e-12)]
    assert times["rod free end"] == [pytest.approx((2 * L - X1) / C, rel=1e-12)]
    assert times["second pass"] == [pytest.approx((2 * L + X1) / C, rel=1e-12)]
    labels = {r.label: r.time for r in wave_paths(build_rig(1)) if r.label}
    # thesis Fig. 5.13: t5 and t6 each join two events (incident passes SGP2 / reflection reaches SGP3, ...)
    assert labels["t3"] == pytest.approx(X1 / C + 1.0 / C)
    assert labels["t8"] == pytest.approx((2 * L - X1) / C)
    assert labels["t10"] - labels["t3"] == pytest.approx(2 * L / C)   # the period: twice along the rod
    sep = [r for r in wave_paths(build_rig(1)) if r.gauge == "contact" and r.event == "separation"]
    assert sep[0].time == pytest.approx(1.0 / C)


def test_piston_1_incident_wave_is_the_hand_derived_staircase(piston_1_run):
    sig = piston_1_run
    n1 = sig.raw["SGP1"]
    k_reflection = round((2 * L - X1) / C / DT10)           # 349: reflection from the rod end arrives
    t = sig.time[:k_reflection]
    expected = piston_1_incident(t - X1 / C)
    assert expected[round(X1 / C / DT10)] == pytest.approx(F0)
    assert sig.setup.incident_plateau == pytest.approx(F0, rel=1e-12)
    np.testing.assert_allclose(n1[:k_reflection], expected, rtol=0, atol=1e-12 * abs(F0))
    # every table event before the rod-end reflection is a jump of N1 with the tabulated sign
    events = [r for r in wave_paths(sig.setup) if r.gauge == "SGP1" and r.time < (2 * L - X1) / C]
    assert [r.event for r in events] == ["incident front", "step reflection", "face-segment echo",
                                         "step reflection", "piston free end"]
    for r in events:
        k = r.time / DT10
        assert abs(k - round(k)) < 1e-6                       # dt divides the travel times
        jump = n1[round(k)] - n1[round(k) - 1]
        assert np.sign(jump) == r.sign and abs(jump) > 1e-3 * abs(F0), r


def test_piston_1_separates_at_t_star(piston_1_run):
    # the level the contact would need after the free-end reflection at 10 TAU: paths AAAAA, AB, BA, C
    w4 = 1 + (1 + R) * (R + R**3 + R**5 + R**7 - R * (1 - R**2))
    w5 = w4 + (1 + R) * (R**9 - 2 * R**3 * (1 - R**2) - (1 - R**2) ** 2)
    assert w5 < 0 < w4            # F0 * w5 > 0 would be tension: the unilateral contact opens instead
    assert piston_1_run.separation_time == pytest.approx(1.0 / C, rel=1e-12)


# ------------------------------------------------------------------------------------------- (b) duration
def test_pulse_duration_at_sgp1_is_t_star(piston_1_run):
    n1 = piston_1_run.raw["SGP1"][: round((2 * L - X1) / C / DT10)]
    on = np.flatnonzero(np.abs(n1) > 1e-9 * abs(F0))
    duration = (on[-1] + 1 - on[0]) * DT10                    # node values hold for one step
    assert on[0] * DT10 == pytest.approx(X1 / C, rel=1e-12)
    assert duration == pytest.approx(2 * 0.5 / C, rel=1e-12)


# ------------------------------------------------------------------------------------------- (c) scaling
def test_normalised_filtered_n1_is_independent_of_the_impact_velocity():
    rig = build_rig(1)
    runs = {v: simulate_rig(rig.with_velocity(v), duration=0.6e-3, dt=DT10)
            for v in IMPACT_VELOCITIES["impact velocity"]}
    curves = [normalize_by_global_minimum(s.filtered["SGP1"]) for s in runs.values()]
    for other in curves[1:]:
        np.testing.assert_allclose(other, curves[0], rtol=0, atol=1e-12)
    # and the unnormalised signals scale with v
    np.testing.assert_allclose(runs[5.60].filtered["SGP1"] / 5.60, runs[3.47].filtered["SGP1"] / 3.47,
                               rtol=0, atol=1e-12 * abs(F0) / V)
    assert np.min(runs[4.60].raw["SGP1"]) == pytest.approx(F0 * (1 + (1 + R) * (R + R**3 + R**5)), rel=1e-12)


# ------------------------------------------------------------------------------------------- (d) other SGPs
def test_sgp2_and_sgp3_see_the_delayed_incident_wave_and_the_reflection(piston_1_run):
    sig = piston_1_run
    n1, n2, n3 = (sig.raw[k] for k in ("SGP1", "SGP2", "SGP3"))
    k_refl1 = round((2 * L - X1) / C / DT10)
    incident = np.concatenate([n1[:k_refl1], np.zeros(n1.size)])   # the wave passing SGP1 before reflection
    d2 = round((X2 - X1) / C / DT10)                        # 79 steps
    d3 = round((X3 - X1) / C / DT10)                        # 158 steps
    r3 = round((2 * L - X3 - X1) / C / DT10)                # 180 steps: x1 -> free end -> x3
    assert abs((X2 - X1) / C / DT10 - d2) < 1e-9 and abs((2 * L - X3 - X1) / C / DT10 - r3) < 1e-9
    k2 = np.arange(d2, round((2 * L - X2) / C / DT10))
    np.testing.assert_allclose(n2[k2], incident[k2 - d2], rtol=0, atol=1e-12 * abs(F0))
    assert np.all(n2[:d2] == 0)
    k3 = np.arange(r3, round((2 * L + X3) / C / DT10))
    np.testing.assert_allclose(n3[k3], incident[k3 - d3] - incident[k3 - r3], rtol=0, atol=1e-12 * abs(F0))
    # the reflected front reaches SGP3 at (2L - x3)/c with the opposite sign of the incident front
    k_front = round((2 * L - X3) / C / DT10)
    assert n3[k_front] - n3[k_front - 1] == pytest.approx(-F0, rel=1e-12)
    assert n3[d3 + round(X1 / C / DT10)] - n3[d3 + round(X1 / C / DT10) - 1] == pytest.approx(F0, rel=1e-12)


# ------------------------------------------------------------------------------------------- (e) delay
def chain_dc_group_delay() -> float:
    """Group delay at f -> 0 of the thesis chain, from scipy's designs: analog all-pole filter
    sum(-1/p); digital b/a: first moment of b minus that of a (in samples)."""
    _, p, _ = signal.bessel(5, 2 * np.pi * 100e3, analog=True, output="zpk", norm="mag")
    analog = float(np.sum(np.real(-1.0 / p)))
    b, a = signal.bessel(4, 40e3, fs=1e6, norm="mag")
    k = np.arange(b.size)
    digital = (np.dot(k, b) / b.sum() - np.dot(k, a) / a.sum()) / 1e6
    return analog + digital


def test_filtered_delay_is_the_chains_group_delay(piston_1_run):
    """For a linear filter with unit DC gain the centroid of a pulse moves by the DC group delay.

    The chain puts the lattice signal (piecewise constant, steps at k dt) on its 20 MHz analog grid
    (h = 50 ns, 'previous') and treats those samples as piecewise linear (docs/measurement.md): a step at t
    becomes a ramp over [ceil(t/h) h - h, ceil(t/h) h], whose first moment is that of a step at
    ceil(t/h) h - h/2. So (1) against the raw lattice signal the delay is the group delay within +-h/2, and
    (2) against the input the chain actually sees it is the group delay up to the 1 MHz sampling of a
    smooth signal."""
    sig = piston_1_run
    assert sig.chain == MeasuringChain()
    k_end = round((2 * L - X1) / C / DT10)
    n1 = sig.raw["SGP1"][:k_end]
    centroid_raw = np.sum(n1 * (np.arange(k_end) + 0.5) * DT10) / np.sum(n1)
    window = sig.filtered_time < (2 * L - X1) / C               # causal: the reflection is not in yet
    y, t = sig.filtered["SGP1"][window], sig.filtered_time[window]
    assert abs(y[-1]) < 1e-6 * abs(F0)                           # the filtered pulse has died out
    centroid_filtered = np.sum(y * t) / np.sum(y)
    expected = chain_dc_group_delay()
    assert 12e-6 < expected < 12.5e-6
    h = 1 / 20e6
    assert abs(centroid_filtered - centroid_raw - expected) <= h / 2
    # (2) the input as the chain holds it: edges moved to ceil(t/h) h - h/2
    padded = np.concatenate([[0.0], n1, [0.0]])
    j = np.flatnonzero(np.diff(padded) != 0)                    # an edge at t = j dt; level after it
    edges = np.ceil(j * DT10 / h - 1e-9) * h - h / 2
    level = padded[j + 1][:-1]
    impulse = np.sum(level * np.diff(edges))
    centroid_held = np.sum(level * np.diff(edges**2) / 2) / impulse
    assert abs(centroid_filtered - centroid_held - expected) < 1e-10
    # the filter keeps the pulse's impulse (DC gain 1)
    assert np.sum(y) * 1e-6 == pytest.approx(impulse, rel=1e-6)


# ------------------------------------------------------------------------------------------- piston 2
def test_piston_2_steps_follow_the_wave_path_narrative(piston_2_run):
    sig = piston_2_run
    rig = sig.setup
    dt = sig.dt
    n1 = sig.raw["SGP1"]
    f0 = rig.incident_plateau
    assert f0 == pytest.approx(-impedance(0.030) * Z50 * 4.58 / (impedance(0.030) + Z50), rel=1e-12)
    rows = [r for r in wave_paths(rig) if r.gauge == "SGP1" and r.time < (2 * L - X1) / C]
    # from the impact face: cone 80 mm, 100 mm, middle block 120 mm, 120 mm, small block 40 mm, 30 mm
    steps = [r for r in rows if r.event == "step reflection"]
    expected_s = [0.080, 0.180, 0.300, 0.420, 0.460]
    assert [r.time for r in steps] == pytest.approx([X1 / C + 2 * s / C for s in expected_s], rel=1e-12)
    # 50 -> 36 (rises), 36 -> 50 (drops), 50 -> 36 (rises), 36 -> 44 (drops), 44 -> 36 (rises)
    assert [r.sign for r in steps] == [1, -1, 1, -1, 1]
    for r in steps + [x for x in rows if x.event == "piston free end"]:
        k = r.time / dt
        assert abs(k - round(k)) < 1e-6
        jump = n1[round(k)] - n1[round(k) - 1]
        assert np.sign(jump) == r.sign and abs(jump) > 0.02 * abs(f0), r
    # first lattice level: the face element (1 mm of cone, dt = 1 mm / c) has the cone's mean impedance
    # over 30.00 -> 30.25 mm, Z ~ mean(d^2) = d0^2 + d0 dd + dd^2 / 3
    assert dt == pytest.approx(1e-3 / C, rel=1e-12)
    d0, dd = 0.030, 0.020 * 1e-3 / 0.080
    z_el = RHO * C * math.pi / 4 * (d0**2 + d0 * dd + dd**2 / 3)
    k0, k1 = round(X1 / C / dt), round((X1 + 2 * 0.080) / C / dt)
    assert n1[k0] == pytest.approx(-z_el * Z50 * 4.58 / (z_el + Z50), rel=1e-12)
    assert n1[k0] == pytest.approx(f0, rel=0.01)
    # over the cone (widening away from the face) the force falls monotonically; on the lattice each element
    # boundary of the cone sends a small reflection, arriving every 2 dt
    assert np.all(np.diff(n1[k0:k1]) <= 1e-9 * abs(f0))
    assert np.all(np.diff(n1[k0:k1:2]) < 0)
    assert n1[k1 - 1] < 1.5 * n1[k0]
    # thesis 5.4.2: the bodies separate shortly after the free-end reflection reaches the contact face
    assert sig.separation_time > rig.pulse_duration + dt
    with_ts = wave_paths(rig, separation_time=sig.separation_time)
    end = [r for r in with_ts if r.gauge == "SGP1" and r.event == "incident pulse passed"][0]
    k_end = round(end.time / dt)
    assert abs(n1[k_end - 1]) > 1e-3 * abs(f0)
    assert np.all(np.abs(n1[k_end:round((2 * L - X1) / C / dt)]) < 1e-12 * abs(f0))


# ------------------------------------------------------------------------------------------- efficiency
def test_efficiency_equals_the_energy_carried_by_the_incident_wave(piston_1_run):
    sig = piston_1_run
    n1 = sig.raw["SGP1"][: round((2 * L - X1) / C / DT10)]
    flux = np.sum(n1**2) * DT10 / Z50                  # a right-going wave carries N^2 / Z per unit time
    mass = RHO * math.pi / 4 * (0.04**2 * 0.2 + 0.05**2 * 0.3)
    assert sig.efficiency == pytest.approx(flux / (0.5 * mass * V**2), rel=1e-9)
    assert sig.efficiency_time == pytest.approx(2 * L / C, rel=1e-9)
    assert 0 < sig.efficiency < 1


# ------------------------------------------------------------------------------------------- time step
def test_rig_time_step_puts_steps_and_gauges_on_nodes():
    for number in (1, 2):
        rig = build_rig(number)
        dt = rig_time_step(rig)
        assert dt <= 1e-3 / C * (1 + 1e-12)
        times = list(rig.piston.segment_travel_times) + [rig.rod.total_travel_time]
        times += [x / C for x in GAUGE_POSITIONS.values()]
        for t in times:
            assert abs(t / dt - round(t / dt)) < 1e-9
    # all lengths of both rigs are multiples of 10 mm: the largest exact step is 10 mm / c, finer ones divide it
    assert rig_time_step(build_rig(1), 1.0) == pytest.approx(0.010 / C, rel=1e-12)
    assert rig_time_step(build_rig(2), 0.3e-3 / C) == pytest.approx(0.010 / 34 / C, rel=1e-12)
    odd = RigSetup(ri.Rod([ri.Cylinder(0.1234567, 0.04)]), build_rig(1).rod, 4.6)
    assert rig_time_step(odd, 2e-7) == 2e-7


# ------------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, message", [
    ({"piston": 3}, "piston"),
    ({"piston": "hammer"}, "piston"),
    ({"piston": 1, "velocity": -4.6}, "velocity"),
    ({"piston": 1, "velocity": float("nan")}, "velocity"),
    ({"piston": ri.Rod([ri.Cylinder(0.3, 0.05)])}, "velocity"),
    ({"piston": 1, "gauges": {"SG": 2.0}}, "position"),
    ({"piston": 1, "gauges": {"contact": 0.5}}, "contact"),
])
def test_bad_input_names_the_quantity(kwargs, message):
    with pytest.raises(ValueError, match=message):
        build_rig(**kwargs)


def test_bad_types():
    with pytest.raises(TypeError, match="setup"):
        simulate_rig("piston 1")
    with pytest.raises(TypeError, match="setup"):
        wave_paths(None)
    with pytest.raises(TypeError, match="chain"):
        simulate_rig(build_rig(1), chain="bessel")
    with pytest.raises(ValueError, match="duration"):
        simulate_rig(build_rig(1), duration=0.0)
    with pytest.raises(ValueError, match="separation_time"):
        wave_paths(build_rig(1), separation_time=-1.0)
