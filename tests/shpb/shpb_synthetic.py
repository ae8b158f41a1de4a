"""A synthetic split-Hopkinson-bar shot built from the 1-D bar relations for a specimen of known stress-strain law
(shared by tests/shpb and tests/cli; a module of its own name, so that it is never confused with a conftest)."""

from dataclasses import dataclass

import numpy as np

from rodimpact import TITANIUM_TI6AL4V
from rodimpact.shpb import Bar, GaugeSignals, PulseWindows, SpecimenGeometry, Window

DT = 1e-7                     # 10 MHz, as the LANL recorder
RAMP, SAMPLES = 20, 600       # the strain rate rises linearly over 20 samples, the pulse lasts 600
RATE = 2000.0                 # 1/s, the plateau of the specimen's engineering strain rate (compression positive)
E_S, YIELD, HARDENING = 100e9, 200e6, 1e9      # specimen: elastic, then linear hardening (Pa)


def law(strain):
    """The specimen's engineering stress (Pa, compression positive) at an engineering strain."""
    return np.where(strain <= YIELD / E_S, E_S * strain, YIELD + HARDENING * (strain - YIELD / E_S))


def prescribed_rate(k):
    """The specimen's strain rate at face sample k: a linear rise over RAMP samples, then constant."""
    return RATE * np.minimum(k / RAMP, 1.0)


def prescribed_strain(k):
    """The exact integral of :func:`prescribed_rate` (piecewise linear between samples, so the trapezoidal rule
    of the reduction is exact too)."""
    k = np.asarray(k, dtype=float)
    rise = 0.5 * RATE * DT * np.minimum(k, RAMP) ** 2 / RAMP
    return rise + RATE * DT * np.maximum(k - RAMP, 0.0)


@dataclass(frozen=True)
class Shot:
    signals: GaugeSignals
    incident_bar: Bar
    transmitted_bar: Bar
    specimen: SpecimenGeometry
    windows: PulseWindows        # the windows the shot was built with
    start: int                   # gauge-record index of the incident pulse's first sample


def build_shot(incident_bar, transmitted_bar, specimen, imbalance=None, start=100, hops=(1500, 1300), tail=200):
    """A shot whose pulses follow from the 1-D bar relations at the specimen faces (docs/shpb.md):

    the specimen (law, prescribed strain history) carries F = -sigma A0 on its back face and F (1 + imbalance(k))
    on its front face; eps_T = F2 / (E_T A_T), v2 = -c_T eps_T, v1 = v2 + L0 eps_dot; the front face gives
    eps_I + eps_R = F1 / (E_I A_I) and eps_R - eps_I = v1 / c_I. The pulses reach the gauges ``hops`` samples
    from the faces (the gauge distances are those whole numbers of samples)."""
    k = np.arange(SAMPLES)
    stress = law(prescribed_strain(k))
    back = -stress * specimen.area
    front = back * (1.0 + (imbalance(k) if imbalance is not None else 0.0))
    eps_t = back / transmitted_bar.stiffness
    v_back = -transmitted_bar.wave_speed * eps_t
    v_front = v_back + specimen.length * prescribed_rate(k)
    eps_i = 0.5 * (front / incident_bar.stiffness - v_front / incident_bar.wave_speed)
    eps_r = 0.5 * (front / incident_bar.stiffness + v_front / incident_bar.wave_speed)
    hop_i, hop_t = hops
    n = start + 2 * hop_i + SAMPLES + tail
    incident, transmitted = np.zeros(n), np.zeros(n)
    incident[start:start + SAMPLES] = eps_i
    incident[start + 2 * hop_i:start + 2 * hop_i + SAMPLES] = eps_r
    transmitted[start + hop_i + hop_t:start + hop_i + hop_t + SAMPLES] = eps_t
    time = DT * (np.arange(n) - start) - 10e-6
    bars = [Bar(material=b.material, area=b.area, gauge_distance=h * DT * b.wave_speed, poisson_ratio=0.3,
                name=b.name) for b, h in ((incident_bar, hop_i), (transmitted_bar, hop_t))]
    duration = (SAMPLES - 1) * DT
    windows = PulseWindows(Window(time[start], duration), Window(time[start + 2 * hop_i], duration),
                           Window(time[start + hop_i + hop_t], duration))
    return Shot(GaugeSignals(time, incident, transmitted, "synthetic"), bars[0], bars[1], specimen, windows, start)


def ti_bar(name="incident", diameter=9.47e-3):
    return Bar(material=TITANIUM_TI6AL4V, diameter=diameter, gauge_distance=0.381, name=name)


SPECIMEN = SpecimenGeometry(length=3.2e-3, diameter=6.34e-3)
