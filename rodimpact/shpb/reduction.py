"""Split-Hopkinson (Kolsky) bar data reduction: from the gauge strains to the specimen's stress, strain and
strain rate by the 1-, 2- and 3-wave analyses, with the force-equilibrium check.

**Signs.** Bar strains are positive in tension (x to the right: incident bar, specimen, transmitted bar); the
specimen's stress, strain and strain rate are reported **positive in compression**. With the strains at the
specimen faces, eps_I (incident, travelling +x), eps_R (reflected, -x) and eps_T (transmitted, +x), a wave
travelling +x has particle velocity ``v = -c eps`` and one travelling -x ``v = +c eps``, so

    F1 = E_I A_I (eps_I + eps_R),   v1 = c_I (eps_R - eps_I)      front face (incident bar)
    F2 = E_T A_T eps_T,             v2 = -c_T eps_T               back face (transmitted bar)

and the specimen (initial length L0, area A0) shortens at ``v1 - v2``. The analyses (Gray 2000, the classic
data reduction; Chen and Song 2011, ch. 1, there with the specimen negative in compression):

* **3-wave** (both faces): ``sigma = -(F1 + F2) / (2 A0)``, ``eps_dot = (v1 - v2) / L0``; for equal bars
  ``eps_dot = -(c_b / L0)(eps_I - eps_R - eps_T)`` and ``sigma = -E_b A_b (eps_I + eps_R + eps_T) / (2 A0)``.
* **2-wave** (back face): ``sigma = -F2 / A0``; the rate with eps_I taken from equilibrium (F1 = F2), which
  for equal bars is ``eps_dot = 2 c_b eps_R / L0`` (Chen and Song's ``-2 c_b eps_R / L0`` with their
  compression-negative specimen strain).
* **1-wave** (front face): ``sigma = -F1 / A0``; the rate with eps_T taken from equilibrium, for equal bars
  again ``2 c_b eps_R / L0``.

The strain is the rate integrated over time from the window start (trapezoidal rule); the true measures assume
incompressible flow (:class:`~rodimpact.shpb.SpecimenResponse`). Texts name the analyses differently (some call
the back-face stress from eps_T alone the one-wave stress): compare with other software by the face, not by the
label.

References: G. T. Gray III, "Classic split-Hopkinson pressure bar testing", ASM Handbook Vol. 8, Mechanical
Testing and Evaluation, ASM International (2000), 462-476; W. Chen and B. Song, *Split Hopkinson (Kolsky) Bar:
Design, Testing and Applications*, Springer (2011).
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ..signals.dispersion import PochhammerChree, propagate_dispersive
from .equilibrium import PASS_LIMIT, REVIEW_LIMIT, check_equilibrium
from .gauge_signals import GaugeSignals
from .parts import Bar, SpecimenGeometry
from .result import ShpbReduction, SpecimenResponse
from .windows import PULSES, PulseWindows, _check_types, find_windows

__all__ = ["face_pulses", "reduce_shot", "specimen_responses"]


def reduce_shot(signals: GaugeSignals, incident_bar: Bar, transmitted_bar: Bar, specimen: SpecimenGeometry, *,
                windows: Optional[PulseWindows] = None, dispersion: bool = False,
                bands: tuple[float, float] = (PASS_LIMIT, REVIEW_LIMIT)) -> ShpbReduction:
    """Reduce one shot: pulses moved to the specimen faces, the 1-, 2- and 3-wave responses and R(t).

    ``signals``: the two gauge records as strains (:class:`~rodimpact.shpb.GaugeSignals`, e.g.
    ``GaugeSignals.from_recording``). ``incident_bar``, ``transmitted_bar``: :class:`~rodimpact.shpb.Bar`
    with the gauge distances. ``specimen``: :class:`~rodimpact.shpb.SpecimenGeometry` (L0, A0); a specimen
    wider than a bar is refused. ``windows``: the pulse windows (:func:`~rodimpact.shpb.find_windows`, which
    also takes manual overrides); default: found automatically. ``dispersion``: undo the Pochhammer-Chree
    dispersion between gauge and face (:func:`face_pulses`; needs the bars' Poisson ratios). ``bands``: the
    pass and review limits of R(t) (:mod:`rodimpact.shpb.equilibrium`).
    """
    _check_types(signals, incident_bar, transmitted_bar)
    if not isinstance(specimen, SpecimenGeometry):
        raise TypeError(f"specimen: must be a rodimpact.shpb.SpecimenGeometry, got {type(specimen).__name__}")
    for name, bar in (("incident_bar", incident_bar), ("transmitted_bar", transmitted_bar)):
        if specimen.diameter > bar.diameter:
            raise ValueError(f"specimen.diameter: {specimen.diameter * 1e3:.4g} mm is wider than the {name} "
                             f"({bar.diameter * 1e3:.4g} mm): the 1-D reduction needs the specimen's faces inside "
                             f"the bar faces")
    if windows is None:
        windows = find_windows(signals, incident_bar, transmitted_bar)
    elif not isinstance(windows, PulseWindows):
        raise TypeError(f"windows: must be a rodimpact.shpb.PulseWindows (from find_windows) or None, got "
                        f"{type(windows).__name__}")
    time, eps_i, eps_r, eps_t = face_pulses(signals, incident_bar, transmitted_bar, windows, dispersion)
    one, two, three = specimen_responses(eps_i, eps_r, eps_t, incident_bar, transmitted_bar, specimen, signals.dt)
    worst = max(float(np.max(r.strain)) for r in (one, two, three))
    if worst >= 1.0:
        raise ValueError(f"specimen.length: the specimen strain reaches {worst:.3g}, at least 1 (a specimen "
                         f"compressed to nothing); check the specimen length, the bars and the windows")
    equilibrium = check_equilibrium(time, incident_bar.stiffness * (eps_i + eps_r), transmitted_bar.stiffness * eps_t,
                                    bands)
    return ShpbReduction(time, eps_i, eps_r, eps_t, one, two, three, equilibrium, windows, incident_bar,
                         transmitted_bar, specimen, bool(dispersion), signals.source)


def face_pulses(signals: GaugeSignals, incident_bar: Bar, transmitted_bar: Bar, windows: PulseWindows,
                dispersion: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(time, eps_I, eps_R, eps_T)``: the three pulses at the specimen faces on one time axis.

    Each pulse is read from its window, sample k at ``window.start + k dt`` (linear interpolation between the
    record's samples where the start falls between them), for as many samples as the shortest window holds.
    The time at the faces is the incident window's start plus the incident bar's travel time ``a_I / c_I``
    (the reflected pulse left the face ``a_I / c_I`` before it passed the gauge, the transmitted one
    ``a_T / c_T``), then ``k dt``.

    ``dispersion=True`` first undoes the Pochhammer-Chree dispersion of the first longitudinal mode
    (:func:`rodimpact.signals.propagate_dispersive`, a phase shift per frequency relative to the travel at
    c_b): the incident record is propagated on by ``a_I`` (the incident pulse still travels to the face), the
    incident record is propagated back by ``a_I`` for the reflected pulse and the transmitted record by
    ``a_T`` (both travelled from the face to the gauge). The records should start and end near rest.
    """
    t = signals.time
    records = {"incident": signals.incident, "reflected": signals.incident, "transmitted": signals.transmitted}
    if dispersion:
        for name, bar, distance in (("incident", incident_bar, incident_bar.gauge_distance),
                                    ("reflected", incident_bar, -incident_bar.gauge_distance),
                                    ("transmitted", transmitted_bar, -transmitted_bar.gauge_distance)):
            records[name] = propagate_dispersive(t, records[name], distance, _dispersion_model(bar, name))
    dt = signals.dt
    n = int(np.floor(min(getattr(windows, p).duration for p in PULSES) / dt * (1 + 1e-9))) + 1
    tau = dt * np.arange(n)
    pulses = []
    for name in PULSES:
        start = getattr(windows, name).start
        if start < t[0] - 1e-9 * dt or start + tau[-1] > t[-1] + 1e-9 * dt:
            raise ValueError(f"windows.{name}: {start * 1e6:.6g} to {(start + tau[-1]) * 1e6:.6g} us reaches beyond "
                             f"the record ({t[0] * 1e6:.6g} to {t[-1] * 1e6:.6g} us)")
        pulses.append(np.interp(start + tau, t, records[name]))
    return (windows.incident.start + incident_bar.travel_time + tau, *pulses)


def _dispersion_model(bar: Bar, pulse: str) -> PochhammerChree:
    role = "incident_bar" if pulse != "transmitted" else "transmitted_bar"
    if bar.poisson_ratio is None:
        raise ValueError(f"{role}.poisson_ratio: needed for the dispersion correction (dispersion=True); give "
                         f"Bar(..., poisson_ratio=...)")
    return PochhammerChree(bar.poisson_ratio, bar.diameter / 2.0, bar.wave_speed)


def specimen_responses(eps_i: Any, eps_r: Any, eps_t: Any, incident_bar: Bar, transmitted_bar: Bar,
                       specimen: SpecimenGeometry, dt: float) -> tuple[SpecimenResponse, ...]:
    """The 1-, 2- and 3-wave responses (compression positive) from the bar strains at the faces (tension
    positive) sampled every ``dt`` s; the formulas are in the module docstring."""
    eps_i, eps_r, eps_t = (np.asarray(e, dtype=float) for e in (eps_i, eps_r, eps_t))
    length, area = specimen.length, specimen.area
    c_i, c_t = incident_bar.wave_speed, transmitted_bar.wave_speed
    front = incident_bar.stiffness * (eps_i + eps_r)                       # F1, N, tension positive
    back = transmitted_bar.stiffness * eps_t                               # F2
    v_front = c_i * (eps_r - eps_i)                                        # v1, m/s, +x
    v_back = -c_t * eps_t                                                  # v2
    three = (-(front + back) / (2.0 * area), (v_front - v_back) / length)
    two = (-back / area, (c_i * (2.0 * eps_r - back / incident_bar.stiffness) - v_back) / length)
    one = (-front / area, (v_front + c_t * front / transmitted_bar.stiffness) / length)
    return tuple(SpecimenResponse(stress, cumulative_trapezoid(rate, dx=dt, initial=0.0), rate)
                 for stress, rate in (one, two, three))
