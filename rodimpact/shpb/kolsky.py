"""The split-Hopkinson (Kolsky) bar as a forward model: striker, optional pulse shaper, incident bar, specimen,
transmitted bar and optional momentum trap, with the gauge signals and the specimen's histories it predicts.

The bars are rods of the exact lattice (thesis ch. 3); the shaper and the specimen are deformable joints whose
constitutive law is solved in every step (:mod:`rodimpact.direct.joints`; massless, i.e. in force
equilibrium). With ``specimen_inertia=True`` the specimen's elastic part is a rod of the lattice instead (its own
impedance and wave speed: the ring-up by multiple reflections is resolved exactly), in series with a massless law
joint that carries its inelastic shortening (:meth:`KolskyBar.system`). The input is either the striker and its impact velocity, or a measured incident pulse, which then
drives the incident bar's free end so that it passes the incident gauge exactly as recorded.

Signs: strains and forces in the bars are tension positive (a compressive pulse is negative), as the gauges
read them; the specimen's stress, strain and strain rate are positive in compression (the SHPB habit).
Gauge ``distance`` is measured from the specimen face of its bar.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from typing import Any, Optional, Sequence

import numpy as np

from .._validate import caller_stacklevel, finite_array, positive
from ..direct.problem import Problem, TimeGrid
from ..direct.recording import Outputs
from ..direct.result import Probe, SimulationResult
from ..direct.simulate import simulate
from ..rods.conditions import Bonded, Contact, ForceEnd, FreeEnd, PulseShaper, Specimen
from ..rods.laws import LinearElastic
from ..rods.material import Material
from ..rods.rod import Rod
from ..rods.segments import Cylinder
from ..rods.system import System
from ..signals.gauges import Bridge

#: equilibrium needs about four elastic transits of the specimen within the pulse's rise (Ravichandran and
#: Subhash, J. Am. Ceram. Soc. 77 (1994) 263-267; Davies and Hunter, J. Mech. Phys. Solids 11 (1963) 155-179)
TRANSITS_FOR_EQUILIBRIUM = 4.0
#: with ``specimen_inertia``, the modulus of the law joint that carries the inelastic shortening, as a multiple of
#: the law's own modulus: the joint's elastic compliance is then 1 % of the specimen rod's
INERTIA_JOINT_STIFFENING = 100.0


@dataclass(frozen=True)
class Gauge:
    """A strain-gauge station on a bar, ``distance`` (m) from the bar's specimen face, with an optional measuring
    chain (bridge, gauge factor, excitation voltage in V, amplifier gain, polarity) that turns the predicted
    strain into the recorded voltage."""

    distance: float
    bridge: Bridge | str = "quarter"
    gauge_factor: Optional[float] = None
    excitation_voltage: Optional[float] = None
    gain: float = 1.0
    polarity: int = 1
    poisson_ratio: Optional[float] = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "distance", positive("Gauge.distance", self.distance, "m"))
        if not isinstance(self.bridge, Bridge):
            object.__setattr__(self, "bridge", Bridge.named(self.bridge, self.poisson_ratio))
        if (self.gauge_factor is None) != (self.excitation_voltage is None):
            raise ValueError("Gauge: give both gauge_factor and excitation_voltage (for volts) or neither")
        if self.gauge_factor is not None:
            object.__setattr__(self, "gauge_factor", positive("Gauge.gauge_factor", self.gauge_factor))
            object.__setattr__(self, "excitation_voltage", positive("Gauge.excitation_voltage",
                                                                    self.excitation_voltage, "V"))
        if self.polarity not in (1, -1):
            raise ValueError(f"Gauge.polarity: must be +1 or -1, got {self.polarity!r}")

    def volts(self, strain: np.ndarray) -> np.ndarray:
        """The voltage the chain records for ``strain`` (tension positive), V."""
        if self.gauge_factor is None:
            raise ValueError("Gauge.volts: needs gauge_factor and excitation_voltage")
        return self.polarity * self.gain * self.excitation_voltage * self.bridge.output_ratio(strain,
                                                                                              self.gauge_factor)


@dataclass(frozen=True)
class KolskyPrediction:
    """What a :class:`KolskyBar` run predicts, on the time base of the run (step start times, s; shifted to the
    measured record's time when the input was a measured pulse).

    Bar strains (tension positive) at the two gauges: ``incident`` and ``reflected`` (the right- and left-running
    parts at the incident gauge, separated exactly from the gauge's force and velocity: eps = (N -+ Z V) /
    (2 E A)), ``incident_gauge`` (their sum, what the gauge reads) and ``transmitted``. Specimen (compression
    positive): ``force`` (N; with ``specimen_inertia`` the mean of the two face forces, as 3-wave reduction
    takes it), ``strain`` and ``strain_rate`` (engineering, from the faces' displacements and
    velocities at the step midpoints), ``true_strain``, ``stress`` (engineering, F / A0) and ``true_stress``
    (F (1 - eps) / A0). ``volts``: the gauges' voltages where their chains are given.
    """

    time: np.ndarray
    incident: np.ndarray
    reflected: np.ndarray
    incident_gauge: np.ndarray
    transmitted: np.ndarray
    force: np.ndarray
    strain: np.ndarray
    strain_rate: np.ndarray
    true_strain: np.ndarray
    stress: np.ndarray
    true_stress: np.ndarray
    volts: dict[str, np.ndarray]
    result: SimulationResult = field(repr=False)

    @property
    def face_delays(self) -> tuple[float, float]:
        """The travel times (s) of a wave from the incident gauge to the specimen face and from the specimen face to
        the transmitted gauge, between the lattice nodes the gauges read (whole steps). At time t the specimen's
        faces see the incident wave of time t - tau_i, the reflected wave of time t + tau_i and the transmitted
        wave of time t + tau_t (the alignment of data reduction)."""
        lattice = self.result.lattice
        gi, gt = (self.result.probe(n).probe for n in ("incident_gauge", "transmitted_gauge"))
        elements_i = int(lattice.rod_start[gi.rod + 1] - lattice.rod_start[gi.rod])
        return ((elements_i - lattice.nearest_node(gi.rod, gi.position)[0]) * lattice.dt,
                lattice.nearest_node(gt.rod, gt.position)[0] * lattice.dt)

    def to_xarray(self) -> Any:
        """The histories as an ``xarray.Dataset`` over ``time`` with units in the attributes."""
        import xarray as xr

        units = {"incident": "1", "reflected": "1", "incident_gauge": "1", "transmitted": "1", "force": "N",
                 "strain": "1", "strain_rate": "1/s", "true_strain": "1", "stress": "Pa", "true_stress": "Pa"}
        data = {k: ("time", getattr(self, k), {"units": u}) for k, u in units.items()}
        data.update({f"{k}_volts": ("time", v, {"units": "V"}) for k, v in self.volts.items()})
        return xr.Dataset(data, coords={"time": ("time", self.time, {"units": "s"})},
                          attrs={"signs": "bar strains tension positive; specimen compression positive"})


@dataclass(frozen=True)
class KolskyBar:
    """A split-Hopkinson (Kolsky) pressure bar.

    ``incident``, ``transmitted``: the bars (geometric rods: their material and area give E A at the gauges);
    ``specimen``: a :class:`~rodimpact.Specimen` between them; ``incident_gauge``, ``transmitted_gauge``:
    :class:`Gauge` stations (distance from the specimen face); ``striker``: the striker rod (for
    :meth:`predict` with an impact velocity); ``shaper``: an optional :class:`~rodimpact.PulseShaper` between
    striker and incident bar; ``momentum_trap``: an optional rod in unilateral contact behind the transmitted bar
    (without one the transmitted bar's far end is free); ``specimen_inertia``: model the specimen with its mass
    (needs ``specimen.density``), see :meth:`system`.
    """

    incident: Rod
    transmitted: Rod
    specimen: Specimen
    incident_gauge: Gauge
    transmitted_gauge: Gauge
    striker: Optional[Rod] = None
    shaper: Optional[PulseShaper] = None
    momentum_trap: Optional[Rod] = None
    specimen_inertia: bool = False

    def __post_init__(self) -> None:
        for name in ("incident", "transmitted", "striker", "momentum_trap"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, Rod):
                raise TypeError(f"KolskyBar.{name}: must be a Rod, got {type(value).__name__}")
            if value is not None and value.native is not None and name in ("incident", "transmitted"):
                raise ValueError(f"KolskyBar.{name}: needs a geometric rod (segments and material), not an "
                                 "impedance-level one: the gauges read strain N / (E A)")
        if not isinstance(self.specimen, Specimen):
            raise TypeError(f"KolskyBar.specimen: must be a Specimen, got {type(self.specimen).__name__}")
        if self.shaper is not None and not isinstance(self.shaper, PulseShaper):
            raise TypeError(f"KolskyBar.shaper: must be a PulseShaper, got {type(self.shaper).__name__}")
        if not isinstance(self.specimen_inertia, bool):
            raise TypeError(f"KolskyBar.specimen_inertia: must be True or False, got {self.specimen_inertia!r}")
        if self.specimen_inertia and self.specimen.density is None:
            raise ValueError("KolskyBar.specimen.density: needed with specimen_inertia=True (the specimen rod's "
                             "mass and wave speed); give Specimen(..., density=...)")
        if self.specimen_inertia and self.specimen.law.compression_only:
            raise ValueError(f"KolskyBar.specimen.law: the {type(self.specimen.law).__name__} law is a loading curve "
                             "in total strain (a pulse shaper's), with no elastic part to give the specimen rod; "
                             "use specimen_inertia=False")
        if self.shaper is not None and self.striker is None:
            raise ValueError("KolskyBar.shaper: a pulse shaper sits on the striker's face; give the striker too")
        for name, joint, left, right in (("specimen", self.specimen, self.incident, self.transmitted),
                                         ("shaper", self.shaper, self.striker, self.incident)):
            if joint is not None:
                joint.check_fits(min(float(left.area(left.length)), float(right.area(0.0))), f"KolskyBar.{name}")
        for name, bar in (("incident_gauge", self.incident), ("transmitted_gauge", self.transmitted)):
            gauge = getattr(self, name)
            if not isinstance(gauge, Gauge):
                raise TypeError(f"KolskyBar.{name}: must be a Gauge, got {type(gauge).__name__}")
            if not gauge.distance < bar.length:
                raise ValueError(f"KolskyBar.{name}.distance: must lie on the bar, < {bar.length:.6g} m from its "
                                 f"specimen face, got {gauge.distance:.6g} m")

    # ------------------------------------------------------------------ the model
    def system(self, striker_velocity: Optional[float] = None, incident_force: Any = None) -> System:
        """The rods and joints as a :class:`~rodimpact.System`: [striker] + incident + transmitted [+ trap]."""
        rods, velocities, junctions = [], [], []
        left: Any = FreeEnd()
        if incident_force is None:
            rods.append(self.striker)
            velocities.append(positive("striker_velocity", striker_velocity, "m/s"))
            junctions.append(self.shaper if self.shaper is not None else Contact())
        else:
            left = ForceEnd(incident_force, interpolation="linear")
        rods.append(self.incident)
        if self.specimen_inertia:
            rods.append(self.specimen_rod())
            junctions += self._specimen_junctions()
        else:
            junctions.append(self.specimen)
        rods.append(self.transmitted)
        velocities += [0.0] * (len(rods) - len(velocities))
        if self.momentum_trap is not None:
            rods.append(self.momentum_trap)
            velocities.append(0.0)
            junctions.append(Contact())
        return System(rods, velocities, junctions, left, "free")

    def specimen_rod(self) -> Rod:
        """The specimen as an elastic rod of the lattice (``specimen_inertia``): length L0, the specimen's area,
        the law's (unloading) modulus E and the specimen's density, so its impedance A0 rho c and wave speed
        c = sqrt(E / rho) are its own (a square or other section enters as the circle of equal area)."""
        sp = self.specimen
        return Rod([Cylinder(sp.length, sp.diameter)], material=Material(sp.law.modulus, sp.density, "specimen"),
                   name="specimen")

    def _specimen_junctions(self) -> list[Any]:
        """The junctions on either side of :meth:`specimen_rod`: contact (or bonded, for a specimen that may pull)
        at the incident face; at the transmitted face the same, or, for an inelastic law, a massless law joint
        with the specimen's law, stiffened by :data:`INERTIA_JOINT_STIFFENING` so that its shortening is the
        inelastic one, L0 its length and the specimen's area and measure."""
        sp = self.specimen
        face = Contact() if sp.compression_only else Bonded()
        if isinstance(sp.law, LinearElastic):
            return [face, face]
        stiff = replace(sp.law, youngs_modulus=INERTIA_JOINT_STIFFENING * sp.law.modulus)
        return [face, replace(sp, law=stiff)]

    def predict(self, striker_velocity: Optional[float] = None, *, incident_pulse: Any = None,
                duration: Optional[float] = None, dt: Optional[float] = None,
                backend: str = "numba") -> KolskyPrediction:
        """Predict the gauge signals and the specimen's histories.

        Either ``striker_velocity`` (m/s, the striker moving towards the incident bar) or ``incident_pulse``, a
        measured incident wave at the incident gauge as samples ``(time, strain)`` (s, tension positive, zero
        outside the pulse): it drives the incident bar's outer end, ahead by the travel time to the gauge, so that
        it passes the gauge as recorded; the prediction's time is then the record's. ``duration`` (s): default
        until the transmitted pulse has passed its gauge. ``dt``: the lattice time step (default: the solver's).
        """
        if (striker_velocity is None) == (incident_pulse is None):
            raise ValueError("predict: give exactly one of striker_velocity (with a striker) or incident_pulse")
        if striker_velocity is not None and self.striker is None:
            raise ValueError("striker_velocity: the KolskyBar has no striker; give one or an incident_pulse")
        c_i = float(self.incident.wave_speed(0.0))
        ea_i = _axial_stiffness(self.incident, self.incident.length - self.incident_gauge.distance)
        to_gauge = (self.incident.length - self.incident_gauge.distance) / c_i
        shift = 0.0
        if incident_pulse is not None:
            t, eps = _samples(incident_pulse)
            shift = t[0] - to_gauge
            pulse = t[-1] - t[0]
            # the solver takes a history at the midpoint of each step, and a step's values carry its start time:
            # the end force leads by half a step so that the gauge reads the record at the record's times
            if dt is None:
                dt = TimeGrid.of(self.system(None, (t - t[0], ea_i * eps)), steps=1).dt
            system = self.system(None, (t - t[0] + 0.5 * dt, ea_i * eps))
        else:
            pulse = 2.0 * self.striker.length / float(self.striker.wave_speed(0.0))
            system = self.system(striker_velocity)
        k_i = 1 if incident_pulse is None else 0           # index of the incident bar
        k_t = k_i + (2 if self.specimen_inertia else 1)   # index of the transmitted bar
        probes = [Probe("incident_gauge", k_i, self.incident.length - self.incident_gauge.distance),
                  Probe("transmitted_gauge", k_t, self.transmitted_gauge.distance),
                  Probe("incident_face", k_i, self.incident.length), Probe("transmitted_face", k_t, 0.0)]
        if duration is None:
            c_t = float(self.transmitted.wave_speed(0.0))
            duration = to_gauge + 2.0 * self.incident_gauge.distance / c_i + pulse * 1.5 \
                + self.transmitted_gauge.distance / c_t
        grid = TimeGrid.of(system, duration=duration, dt=dt)
        result = simulate(Problem(system, grid, Outputs(probes=probes)), backend=backend)
        return self._prediction(result, k_i, shift, pulse)

    def _prediction(self, res: SimulationResult, k_i: int, shift: float, pulse: float) -> KolskyPrediction:
        gi, gt = res.probe("incident_gauge"), res.probe("transmitted_gauge")
        x_i = self.incident.length - self.incident_gauge.distance
        ea_i = _axial_stiffness(self.incident, x_i)
        z_i = float(self.incident.impedance(x_i))
        incident = (gi.force - z_i * gi.velocity) / (2.0 * ea_i)
        reflected = (gi.force + z_i * gi.velocity) / (2.0 * ea_i)
        transmitted = gt.force / _axial_stiffness(self.transmitted, self.transmitted_gauge.distance)
        fa, fb = res.probe("incident_face"), res.probe("transmitted_face")
        dt = res.dt
        rate_length = fa.velocity - fb.velocity                        # shortening rate s, m/s
        delta_mid = fa.displacement - fb.displacement + 0.5 * dt * rate_length
        sp = self.specimen
        strain = delta_mid / sp.length
        force = -res.junction_force[k_i]
        if self.specimen_inertia:                       # the faces differ during the ring-up: their mean (3-wave)
            force = -0.5 * (res.junction_force[k_i] + res.junction_force[k_i + 1])
        stress = force / sp.area
        volts = {name: g.volts(sig) for name, g, sig in (("incident_gauge", self.incident_gauge, gi.strain),
                                                          ("transmitted_gauge", self.transmitted_gauge, gt.strain))
                 if g.gauge_factor is not None}
        self._check_equilibrium_validity(incident, res.time, pulse)
        with np.errstate(divide="ignore", invalid="ignore"):
            true_strain = -np.log1p(-strain)
        return KolskyPrediction(
            time=res.time + shift, incident=incident, reflected=reflected, incident_gauge=gi.strain,
            transmitted=transmitted, force=force, strain=strain, strain_rate=rate_length / sp.length,
            true_strain=true_strain, stress=stress, true_stress=stress * (1.0 - strain), volts=volts, result=res)

    def _check_equilibrium_validity(self, incident: np.ndarray, time: np.ndarray, pulse: float) -> None:
        """Warn, with the numbers, when the specimen's elastic transit time is not small against the incident
        pulse's rise time (10 % to 90 % of its peak): the massless joint assumes equilibrium (not needed with
        ``specimen_inertia``: the specimen rod resolves its ring-up)."""
        if self.specimen.density is None or self.specimen_inertia:
            return
        c_s = math.sqrt(self.specimen.law.modulus / self.specimen.density)
        transit = self.specimen.length / c_s
        rise = _rise_time(time, incident)
        if rise is not None and rise < TRANSITS_FOR_EQUILIBRIUM * transit:
            warnings.warn(f"specimen: its elastic transit time L0 / c = {transit * 1e6:.3g} us (c = {c_s:.4g} m/s) "
                          f"is not small against the incident pulse's rise time {rise * 1e6:.3g} us (10-90 %): "
                          f"equilibrium needs about {TRANSITS_FOR_EQUILIBRIUM:g} transits (Ravichandran and Subhash "
                          "1994), so the massless specimen model is outside its validity during the rise; use a "
                          "shorter specimen or a pulse shaper", UserWarning, stacklevel=caller_stacklevel())


def _axial_stiffness(rod: Rod, x: float) -> float:
    """E A of a geometric rod at ``x`` (m from its left end), N."""
    seg = int(np.clip(np.searchsorted(rod.segment_bounds, x, side="right") - 1, 0, len(rod.segments) - 1))
    return rod.segment_material(seg).youngs_modulus * float(rod.area(x))


def _samples(pulse: Any) -> tuple[np.ndarray, np.ndarray]:
    try:
        t, eps = pulse
    except (TypeError, ValueError):
        raise TypeError("incident_pulse: must be samples (time, strain)") from None
    t = finite_array("incident_pulse time", t, min_size=2)
    eps = finite_array("incident_pulse strain", eps, min_size=2)
    if t.shape != eps.shape:
        raise ValueError(f"incident_pulse: needs one strain per time ({t.size}), got {eps.size}")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError("incident_pulse time: must increase strictly")
    return t, eps


def _rise_time(time: np.ndarray, signal: np.ndarray) -> Optional[float]:
    """Time from 10 % to 90 % of the signal's largest magnitude on its first rise (None for a zero signal)."""
    mag = np.abs(signal)
    peak = mag.max()
    if peak == 0.0:
        return None
    first = int(np.argmax(mag >= 0.1 * peak))
    last = int(np.argmax(mag >= 0.9 * peak))
    return float(time[last] - time[first])


def incident_for_constant_rate(specimen: Specimen, rate: float, time: Sequence[float] | np.ndarray,
                               bar_impedance: float) -> np.ndarray:
    """The incident force at the specimen face (N, tension positive) that gives ``specimen`` the constant
    engineering strain rate ``rate`` (1/s) between two bars of impedance ``bar_impedance`` (N s/m), at the
    ``time`` values (s, from the start of loading). In equilibrium the transmitted force is the specimen's,
    F_T = -sigma(rate t, rate) A(t), and the face relations give the incident force F_I = F_T - Z L0 rate / 2,
    i.e. eps_I = eps_T - L0 rate / (2 c0) with strains (Chen and Song, Split Hopkinson (Kolsky) Bar, Springer
    2011, sec. 2.4; tension-positive strains here)."""
    from ..direct.joints import STATE_COLUMNS, law_stress, softening

    t = finite_array("time", time)
    rate = positive("rate", rate, "1/s")
    z = positive("bar_impedance", bar_impedance, "N s/m")
    law, l0, a0 = specimen.law, specimen.length, specimen.area
    q = np.zeros(STATE_COLUMNS)
    out = np.empty(t.size)
    if specimen.measure == "true" and rate * t.max() >= 1.0:
        raise ValueError(f"time: a constant engineering rate of {rate:.6g} 1/s crushes the specimen at "
                         f"t = {1.0 / rate:.6g} s (strain 1), before the last time {t.max():.6g} s")
    for i, ti in enumerate(t):
        if ti < 0.0:                       # before loading: no incident wave
            out[i] = 0.0
            continue
        e = rate * ti
        strain, r, area = e, rate, a0
        if specimen.measure == "true":
            strain, r, area = -math.log1p(-e), rate / (1.0 - e), a0 / (1.0 - e)
        sigma, ep, al, em = law_stress.py_func(law.code, law.kernel(), strain, r, q)
        sigma *= 1.0 - softening.py_func(law.code, law.kernel(), q[1])   # a failing law, lagged as in the solver
        q[:3] = ep, al, em
        out[i] = -sigma * area - 0.5 * z * l0 * rate
    return out
