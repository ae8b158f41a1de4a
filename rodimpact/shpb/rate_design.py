"""Strikers and pulse shapers designed for a constant specimen strain rate in a Kolsky bar (issue 22).

For a constant engineering strain rate r the specimen's strain history is known, eps(t) = r t, so with its law
the force it transmits is known too, F_T(t) = -sigma(r t, r) A(t), and the face relations of the incident bar
give the incident wave that produces it: F_I = F_T - Z L0 r / 2, i.e. eps_I = eps_T - L0 r / (2 c0) (Chen and
Song, Split Hopkinson (Kolsky) Bar, Springer 2011, sec. 2.4; :func:`~rodimpact.shpb.kolsky.incident_for_constant_rate`).

* :func:`design_striker` designs the striker's impedance profile whose incident wave at the specimen face
  matches that pulse (:func:`rodimpact.design` with the exact adjoint gradients of the lattice, the specimen law
  entering through the target), then runs the whole bar with the specimen in the loop to report the achieved
  flatness. With ``method="law"`` the specimen's law is in the loop instead: the objective is the specimen's
  simulated strain rate itself (:class:`~rodimpact.design.objectives.StrainRateObjective`, its mean square
  deviation from the requested rate over the window), minimised from a uniform striker with exact gradients
  through the specimen's law (docs/adjoint.md, "Law joints"); no target pulse is involved.
* :func:`design_shaper` chooses a pulse shaper's thickness and diameter and the striker's velocity for a given
  striker and shaper law, with the whole bar simulated at each trial: a bounded three-parameter Nelder-Mead
  search in log space (thickness / diameter, diameter, velocity) that first minimises the root-mean-square
  deviation of the specimen's rate over the strain window, then polishes the largest one.

Flatness is the largest |rate / r - 1| while the specimen's strain is inside the ``strain_window``; the time of
equilibrium is estimated by the rule of about four elastic transits of the specimen (Ravichandran and Subhash
1994), since the massless specimen of the model is in equilibrium at every instant by construction.
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
from dataclasses import dataclass, field
from typing import Any, Optional, Sequence

import numpy as np
from scipy.optimize import minimize, minimize_scalar

from .._validate import integer, positive, real_number
from ..design.constraints import StrikerLimits
from ..design.design import SearchOptions, design
from ..design.objectives import MatchObjective, StrainRateObjective
from ..design.result import DesignResult
from ..rods.conditions import PulseShaper
from ..rods.laws import FREW, Law
from ..rods.rod import Rod
from ..rods.system import System
from .kolsky import TRANSITS_FOR_EQUILIBRIUM, KolskyBar, KolskyPrediction, incident_for_constant_rate


@dataclass(frozen=True)
class RateDesign:
    """A striker (and shaper) for a constant strain rate, with what the whole bar achieves.

    ``striker`` and ``striker_velocity`` (m/s); ``shaper`` (or None); ``rate`` (1/s) and ``strain_window`` the
    request; ``flatness`` the largest |rate / requested - 1| inside the window; ``uniform_flatness`` that of
    a uniform striker of the same length (at its best velocity) for comparison (None if not computed);
    ``equilibrium_time`` (s from the start of loading) by the four-transit rule (None without the specimen's
    density); ``prediction`` the whole-bar run; ``design`` the impedance design (striker designs only);
    ``wall_time`` (s); ``method`` how it was designed ("target", "law" or "shaper").
    """

    striker: Rod
    striker_velocity: float
    shaper: Optional[PulseShaper]
    rate: float
    strain_window: tuple[float, float]
    flatness: float
    uniform_flatness: Optional[float]
    equilibrium_time: Optional[float]
    prediction: KolskyPrediction = field(repr=False)
    design: Optional[DesignResult] = field(default=None, repr=False)
    wall_time: float = 0.0
    method: str = "target"


def _window_part(strain: np.ndarray, strain_window: tuple[float, float]) -> Optional[slice]:
    """The steps from the specimen's first entry into the window until it first leaves it (None if never)."""
    lo, hi = strain_window
    inside = np.flatnonzero(strain >= lo)
    if inside.size == 0:
        return None
    first = int(inside[0])
    beyond = np.flatnonzero(strain[first:] > hi)
    return slice(first, first + int(beyond[0]) if beyond.size else strain.size)


def rate_flatness(prediction: KolskyPrediction, rate: float, strain_window: tuple[float, float]) -> float:
    """The largest |strain rate / ``rate`` - 1| while the specimen's engineering strain is inside
    ``strain_window`` (before it first leaves it); ``inf`` if the specimen does not reach the window's end."""
    part = _window_part(prediction.strain, strain_window)
    if part is None or prediction.strain.max() < strain_window[1]:
        return math.inf
    return float(np.abs(prediction.strain_rate[part] / rate - 1.0).max())


def _search_cost(prediction: KolskyPrediction, rate: float, strain_window: tuple[float, float],
                 norm: str = "max") -> float:
    """The largest (``norm="max"``: the flatness) or the root-mean-square (``"rms"``) |rate / ``rate`` - 1| over
    the part of the window the specimen reaches, plus a penalty growing with the part it does not reach:
    continuous where :func:`rate_flatness` jumps to ``inf``, so that a search can climb."""
    lo, hi = strain_window
    reached = min(float(prediction.strain.max()), hi)
    if reached <= lo:
        return 10.0 + (lo - reached) / lo if lo > 0.0 else 10.0
    part = _window_part(prediction.strain, strain_window)
    deviation = np.abs(prediction.strain_rate[part] / rate - 1.0)
    size = float(deviation.max()) if norm == "max" else float(np.sqrt(np.mean(deviation ** 2)))
    return size + 5.0 * (hi - reached) / hi


def _window(strain_window: Any) -> tuple[float, float]:
    try:
        lo, hi = (float(x) for x in strain_window)
    except (TypeError, ValueError):
        raise TypeError(f"strain_window: must be (start, end) engineering strains, got {strain_window!r}") from None
    if not 0.0 <= lo < hi < 1.0:
        raise ValueError(f"strain_window: must satisfy 0 <= start < end < 1, got ({lo}, {hi})")
    return lo, hi


def _equilibrium_time(bar: KolskyBar) -> Optional[float]:
    sp = bar.specimen
    if sp.density is None:
        return None
    return TRANSITS_FOR_EQUILIBRIUM * sp.length / math.sqrt(sp.law.modulus / sp.density)


def _uniform_flatness(bar: KolskyBar, length: float, rate: float, window: tuple[float, float], dt: float,
                      duration: float) -> float:
    """The flatness of a uniform striker of the incident bar's section and ``length`` at its best velocity."""
    seg = bar.incident.segments[0]
    striker = Rod([dataclasses.replace(seg, length=length)], material=bar.incident.material, name="uniform")
    trial = dataclasses.replace(bar, striker=striker, shaper=None)

    def cost(log_v: float) -> float:
        return _search_cost(trial.predict(math.exp(log_v), dt=dt, duration=duration), rate, window)

    z = float(bar.incident.impedance(bar.incident.length))
    v0 = 2.0 * abs(incident_for_constant_rate(bar.specimen, rate, [0.5 * window[1] / rate], z)[0]) / z
    best = minimize_scalar(cost, bounds=(math.log(0.2 * v0), math.log(5.0 * v0)), method="bounded",
                           options={"xatol": 1e-3})
    return rate_flatness(trial.predict(math.exp(best.x), dt=dt, duration=duration), rate, window)


#: the law-in-the-loop window starts at this fraction of the time the requested rate needs to reach the strain
#: window's start (after the rise of the pulse) and ends when it reaches LAW_WINDOW_END x the window's end
LAW_WINDOW_START, LAW_WINDOW_END = 0.1, 1.02
#: the law-in-the-loop search stops when its objective improved by less than this fraction over 10 iterations
LAW_IMPROVEMENT = 0.01
METHODS = ("target", "law")


def design_striker(bar: KolskyBar, rate: float, strain_window: Any = (0.02, 0.15), n: int = 100, *,
                   limits: Optional[StrikerLimits] = None, search: Optional[SearchOptions] = None,
                   compare_uniform: bool = True, progress: Optional[bool] = None,
                   method: str = "target") -> RateDesign:
    """Design the striker of ``bar`` for the constant engineering strain rate ``rate`` (1/s) of its specimen
    over ``strain_window`` (engineering strains), as an ``n``-element impedance profile (element travel time
    dt = t_end / (2 n), t_end = 1.05 x window end / rate). ``limits``: bounds of the design (default: impedances from
    0.05 to 5 times the bar's, velocity 0.1-100 m/s). ``compare_uniform``: also report the best uniform striker
    of the same length. ``method``: "target" (the specimen law enters through the target incident wave) or
    "law" (the specimen law in the loop: from a uniform striker of the bar's impedance, the specimen's simulated
    strain rate is held at ``rate`` over the window from LAW_WINDOW_START x start / rate to LAW_WINDOW_END x
    end / rate after the pulse's arrival, :class:`~rodimpact.design.objectives.StrainRateObjective`, with the
    striker velocity free within ``limits``; default search: one start, stopped when the objective improves by
    less than LAW_IMPROVEMENT over 10 iterations). The whole bar is then run with the designed striker and the
    specimen to report the flatness."""
    wall0 = _time.perf_counter()
    if method not in METHODS:
        raise ValueError(f"method: must be one of {METHODS}, got {method!r}")
    rate = positive("rate", rate, "1/s")
    window = _window(strain_window)
    z = float(bar.incident.impedance(bar.incident.length))
    t_end = 1.05 * window[1] / rate            # a little beyond the window's end: the plateau covers it
    dt = t_end / (2 * n)
    t = np.linspace(0.0, t_end, 8 * n + 1)
    target = (t, incident_for_constant_rate(bar.specimen, rate, t, z))
    v0 = 2.0 * abs(target[1].mean()) / z
    limits = limits or StrikerLimits(impedance_bounds=(0.05 * z, 5.0 * z), velocity_bounds=(0.1, 100.0))
    if method == "target":
        result = design(MatchObjective(target, position=bar.incident.length, quantity="incident"), bar.incident,
                        striker_velocity=v0, n=n, dt=dt, limits=limits, search=search, progress=progress)
    else:
        # from a uniform striker of the bar's impedance at the velocity of the target's mean force: only the
        # simulated specimen (its law in the loop) tells the optimiser how the rate responds
        struck = System.struck([bar.incident, bar.transmitted], junctions=[bar.specimen])
        goal = StrainRateObjective(rate, LAW_WINDOW_START * window[0] / rate, LAW_WINDOW_END * window[1] / rate,
                                   start_impedance=np.full(n, z), start_velocity=v0)
        result = design(goal, struck, striker_velocity=v0, n=n, dt=dt, limits=limits,
                        search=search or SearchOptions(starts=1, improvement=LAW_IMPROVEMENT), progress=progress)
    striker = result.to_rod("striker")
    designed = dataclasses.replace(bar, striker=striker, shaper=None)
    duration = bar.incident.length / float(bar.incident.wave_speed(0.0)) + 1.3 * t_end
    pred = designed.predict(result.striker_velocity, dt=dt, duration=duration)
    # the uniform striker of the same travel time (n elements of dt) in the bar's material
    same_length = n * dt * float(bar.incident.wave_speed(0.0))
    uniform = _uniform_flatness(bar, same_length, rate, window, dt, duration) if compare_uniform else None
    return RateDesign(striker, result.striker_velocity, None, rate, window, rate_flatness(pred, rate, window),
                      uniform, _equilibrium_time(bar), pred, result, _time.perf_counter() - wall0, method)


#: the shaper search's bounds: thickness / diameter from MIN_ASPECT (a disc) to ``max_aspect``; diameter from
#: MIN_DIAMETER x the largest the faces allow up to that; velocity from VELOCITY_RANGE x that of a matched striker
#: giving the constant-rate pulse's mean force
MIN_ASPECT, MIN_DIAMETER, VELOCITY_RANGE = 0.02, 0.2, (0.2, 5.0)
#: default starts of the shaper search: (thickness / diameter as a fraction of ``max_aspect``, diameter / the
#: largest allowed), at the velocity of a matched striker whose force is START_FORCE x the constant-rate pulse's
#: last (a shaper still climbing there)
SHAPER_STARTS, START_FORCE = ((0.2, 0.95), (0.8, 0.85)), 1.1
#: edges of the start simplex of the root-mean-square stage and of the minimax polish, in log units
SIMPLEX_STEP, POLISH_STEP = 0.2, 0.05


def design_shaper(bar: KolskyBar, rate: float, law: Law, strain_window: Any = (0.02, 0.15), *,
                  measure: Optional[str] = None, max_aspect: float = 0.5,
                  starts: Optional[Sequence[tuple[float, float, float]]] = None, dt: float = 0.5e-6,
                  max_evaluations: int = 100) -> RateDesign:
    """Choose the thickness and diameter of a pulse shaper of ``law`` and the striker velocity, for ``bar``'s
    striker and specimen, so that the specimen's strain rate stays at ``rate`` (1/s) over ``strain_window``.

    The whole bar is simulated at every trial. Variables: log(thickness / diameter) in [log MIN_ASPECT,
    log ``max_aspect``] (the shaper is a disc: the massless joint needs its elastic transit time short against
    the pulse's rise), log diameter from MIN_DIAMETER x to the largest the striker and incident faces cover, and
    log striker velocity within VELOCITY_RANGE x v0, v0 = 2 |mean F_I| / Z the velocity of a matched striker
    giving the mean force of the constant-rate incident pulse (:func:`incident_for_constant_rate`). From each of
    ``starts`` ((thickness m, diameter m, velocity m/s); default SHAPER_STARTS at the velocity of a matched
    striker whose force is START_FORCE x the pulse's last), bounded Nelder-Mead first minimises the
    root-mean-square deviation |rate / ``rate`` - 1| over the window (smooth, so the simplex finds the basin),
    then polishes the largest deviation (the flatness), at most ``max_evaluations`` whole-bar runs per stage;
    the flattest result is kept. The optimum may lie on the ``max_aspect`` bound (the Johnson-Cook copper
    shaper of docs/shpb.md does), so the achieved flatness can depend on it. ``measure``: the shaper's strain
    measure (default "engineering" for :class:`~rodimpact.FrewShaper`, whose fit includes the area change,
    "true" with incompressible area growth A0 / (1 - eps) for the other laws). ``dt``: the lattice step (s)."""
    wall0 = _time.perf_counter()
    if bar.striker is None:
        raise ValueError("bar.striker: the shaper sits on the striker's face; give the KolskyBar a striker")
    if not isinstance(law, Law):
        raise TypeError(f"law: must be a rodimpact law (e.g. ri.FrewShaper, ri.JohnsonCook), got "
                        f"{type(law).__name__}")
    rate = positive("rate", rate, "1/s")
    window = _window(strain_window)
    max_aspect = real_number("max_aspect", max_aspect, f"a number in ({MIN_ASPECT}, 1] (thickness / diameter)",
                             lambda x: MIN_ASPECT < x <= 1.0)
    max_evaluations = integer("max_evaluations", max_evaluations, 1, "whole-bar runs per stage and start")
    dt = positive("dt", dt, "s")
    if measure is None:
        measure = "engineering" if law.code == FREW else "true"
    faces = min(float(bar.striker.area(bar.striker.length)), float(bar.incident.area(0.0)))
    d_max = math.sqrt(4.0 * faces / math.pi)
    z = float(bar.incident.impedance(bar.incident.length))
    t_end = window[1] / rate
    f_target = incident_for_constant_rate(bar.specimen, rate, np.linspace(0.0, t_end, 50), z)
    v0 = 2.0 * abs(f_target.mean()) / z
    bounds = [(math.log(MIN_ASPECT), math.log(max_aspect)), (math.log(MIN_DIAMETER * d_max), math.log(d_max)),
              (math.log(VELOCITY_RANGE[0] * v0), math.log(VELOCITY_RANGE[1] * v0))]
    if starts is None:
        v_start = 2.0 * START_FORCE * abs(f_target[-1]) / z
        starts = [(max(a * max_aspect, MIN_ASPECT) * f * d_max, f * d_max, v_start) for a, f in SHAPER_STARTS]
    points = [_shaper_start(k, start, bounds) for k, start in enumerate(starts)]
    if not points:
        raise ValueError("starts: give at least one (thickness, diameter, velocity)")
    PulseShaper(law, d_max, max_aspect * d_max, measure=measure)          # refuses a bad measure by name
    duration = (bar.incident.length / float(bar.incident.wave_speed(0.0))
                + 2.0 * bar.striker.length / float(bar.striker.wave_speed(0.0)) + t_end)

    def trial(y: np.ndarray) -> tuple[KolskyPrediction, PulseShaper]:
        aspect, diameter, velocity = np.exp(y)
        shaper = PulseShaper(law, diameter, aspect * diameter, measure=measure)
        return dataclasses.replace(bar, shaper=shaper).predict(velocity, dt=dt, duration=duration), shaper

    best = None
    for y0 in points:
        smooth = minimize(lambda y: _search_cost(trial(y)[0], rate, window, "rms"), y0, method="Nelder-Mead",
                          bounds=bounds, options={"maxfev": max_evaluations, "xatol": 1e-3, "fatol": 1e-5,
                                                  "initial_simplex": _simplex(y0, bounds, SIMPLEX_STEP)})
        polish = minimize(lambda y: _search_cost(trial(y)[0], rate, window), smooth.x, method="Nelder-Mead",
                          bounds=bounds, options={"maxfev": max_evaluations, "xatol": 1e-4, "fatol": 1e-5,
                                                  "initial_simplex": _simplex(smooth.x, bounds, POLISH_STEP)})
        if best is None or polish.fun < best.fun:
            best = polish
    pred, shaper = trial(best.x)
    velocity = float(np.exp(best.x[2]))
    return RateDesign(bar.striker, velocity, shaper, rate, window, rate_flatness(pred, rate, window), None,
                      _equilibrium_time(bar), pred, None, _time.perf_counter() - wall0, "shaper")


def _simplex(y: np.ndarray, bounds: list[tuple[float, float]], step: float) -> np.ndarray:
    """A Nelder-Mead start simplex at ``y`` with one edge of ``step`` per (log) variable, pointing away from
    the nearer bound: equal relative steps in every variable (scipy's default, 5 % of each log value, would step
    a log diameter of about -5 twenty times as far as a log aspect near 0)."""
    simplex = np.tile(y, (y.size + 1, 1))
    for i, (lo, hi) in enumerate(bounds):
        simplex[i + 1, i] += step if y[i] + step <= hi else -step
    return simplex


def _shaper_start(k: int, start: Any, bounds: list[tuple[float, float]]) -> np.ndarray:
    """``starts[k]`` = (thickness, diameter, velocity) as the search's (log aspect, log diameter, log velocity),
    refused by name when outside the search's ``bounds``."""
    try:
        thickness, diameter, velocity = (positive(f"starts[{k}]", x) for x in start)
    except (TypeError, ValueError) as err:
        raise type(err)(f"starts[{k}]: must be (thickness m, diameter m, velocity m/s), all > 0, got "
                        f"{start!r}") from None
    y = np.log([thickness / diameter, diameter, velocity])
    for value, (lo, hi), what in zip(y, bounds, ("thickness / diameter", "diameter", "velocity")):
        if not lo - 1e-12 <= value <= hi + 1e-12:
            raise ValueError(f"starts[{k}]: its {what} {math.exp(value):.6g} lies outside the search's range "
                             f"[{math.exp(lo):.6g}, {math.exp(hi):.6g}]")
    return y
