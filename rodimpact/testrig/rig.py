"""The thesis test rig (Secs. 5.1-5.4) as a model: pistons, rod, strain-gauge stations, measuring chain,
and the wave-path explanation of the steps seen at the gauges.

The rig (thesis Figs. 5.1, 5.5, 5.7, 5.8; Tabs. 5.1-5.3)
--------------------------------------------------------
* **Rod**: steel (E = 210 GPa, rho = 7840 kg/m^3, Tab. 5.2; c = 5175.5 m/s), d = 50 mm, L = 1800 mm,
  free right end (the stop is not reached during the measurement).
* **Strain-gauge positions** (SGP), measured from the rod's impact face: SGP1 110 mm, SGP2 900 mm,
  SGP3 1690 mm. Opposite gauges at 0 deg / 180 deg (SGP2 also 90 deg / 270 deg); the 1D model has no
  bending, so N_k,0 = N_k,180 = N_k and the bending-compensated force of eq. (5.1) is the probe force
  itself. Filtering is linear, so averaging before or after the chain gives the same N_k.
* **Piston 1** (Fig. 5.3): symmetric, 40 mm diameter at both ends, 50 mm in the middle, about 0.5 m long.
  The figure's lengths are not in the text; chosen here (as in ``rodimpact/examples/test-rig.toml``):
  100 mm (40 mm) + 300 mm (50 mm) + 100 mm (40 mm) = 500 mm, so that t* = 2 l_Pis / c = 0.1932 ms
  (eq. 5.4). The thesis prints t* = 1.93e-3 s, a slip of a factor 10: 2 x 0.5 m / 5175.5 m/s = 1.93e-4 s,
  and only that value fits the time points of Fig. 5.13 (t5 and t6 each join two events that coincide only
  for l_Pis ~ 0.5 m).
* **Piston 2** (Fig. 5.4): "several steps and one cone", "a conical increase at the beginning"; no
  dimensions in the text. Chosen here to reproduce the wave-path narrative of Sec. 5.4.2, listed from the
  impact face: cone 80 mm (30 -> 50 mm), neck 100 mm (36 mm), middle block 120 mm (50 mm), shaft 120 mm
  (36 mm), small block 40 mm (44 mm), tail 30 mm (36 mm); 490 mm in all, no part wider than the 50 mm of
  piston 1 (the gun's bore). These are **assumed** dimensions, not the thesis's.
* **Impact velocities** (Tab. 5.3): :data:`IMPACT_VELOCITIES`.
* **Measuring chain** (Tab. 5.1): :class:`~rodimpact.signals.filters.MeasuringChain` (analog Bessel,
  5th order, 100 kHz -> 1 MHz sampling -> digital IIR Bessel, 4th order, 40 kHz), causal as the real one.

Geometry and signs
------------------
The piston is rod 0 and occupies [-l_Pis, 0]; its **right** end is the impact face. Piston profiles are
given here from the impact face backwards (the order in which an incident wave meets them) and mirrored
into the left-to-right order of :class:`~rodimpact.rods.rod.Rod`. The rod is rod 1, on [0, L]; gauge
positions are distances from its impact face. t = 0 is the instant of impact (the thesis's plots start
earlier, by the pretrigger of the recorder). Normal forces are positive in tension; the impact gives
negative forces.

Wave paths (thesis Figs. 5.14, 5.15b, 5.17c)
--------------------------------------------
While piston and rod are in contact, the contact face is an impedance step Z_face | Z_rod. A force wave
meeting a step from impedance Z_near into Z_far is transmitted with factor 2 Z_far / (Z_near + Z_far) and
reflected with R = (Z_far - Z_near) / (Z_near + Z_far); a free end reflects with -1. A compressive wave
reflected where the piston widens (R > 0) returns compressive: the force at the gauges drops further;
where it narrows (R < 0) the force rises. Every reflection of the incident wave inside the piston at a
distance s from the impact face reaches a gauge at x after x/c + 2 theta_Pis(s), theta_Pis being the travel
time from the impact face (2 s / c for steel). :func:`wave_paths` lists these times.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Mapping, Optional, Sequence

import numpy as np

from .._validate import finite, positive
from ..direct.result import Probe, SimulationResult
from ..direct.recording import Outputs
from ..direct.simulate import simulate
from ..rods.material import STEEL, Material
from ..rods.rod import Rod
from ..rods.segments import Cone, Cylinder, Segment, Tube
from ..rods.system import System
from ..signals.filters import MeasuringChain

__all__ = [
    "GAUGE_ANGLES",
    "GAUGE_POSITIONS",
    "IMPACT_VELOCITIES",
    "ROD_DIAMETER",
    "ROD_LENGTH",
    "RigSetup",
    "RigSignals",
    "WavePathEvent",
    "build_rig",
    "piston_from_face",
    "piston_1",
    "piston_2",
    "rig_rod",
    "rig_time_step",
    "simulate_rig",
    "wave_paths",
]

#: Rod of the test rig (Fig. 5.5): diameter and length in m.
ROD_DIAMETER = 0.050
ROD_LENGTH = 1.800

#: Strain-gauge positions (Fig. 5.5), m from the rod's impact face.
GAUGE_POSITIONS: Mapping[str, float] = {"SGP1": 0.110, "SGP2": 0.900, "SGP3": 1.690}

#: Circumferential gauge angles per station (Sec. 5.1), degrees; opposite pairs compensate bending (eq. 5.1).
GAUGE_ANGLES: Mapping[str, tuple[int, ...]] = {"SGP1": (0, 180), "SGP2": (0, 90, 180, 270), "SGP3": (0, 180)}

#: Impact velocities of thesis Tab. 5.3, m/s (experiment -> velocities; setup 1 = piston 1, setup 2 = piston 2).
IMPACT_VELOCITIES: Mapping[str, tuple[float, ...]] = {
    "repeatability": (4.57, 4.58, 4.60),
    "circumferential SGP": (4.60,),
    "impact velocity": (3.47, 4.60, 5.60),
    "piston bearings": (4.60, 4.61, 4.62),
    "standard piston": (4.60,),
    "complex piston": (4.58,),
}

#: Piston 1 from the impact face: (length, diameter) in m. Lengths chosen (Fig. 5.3 is not in the text).
_PISTON_1 = ((0.100, 0.040), (0.300, 0.050), (0.100, 0.040))


# ------------------------------------------------------------------------------------------- geometry
def _mirrored(segment: Segment) -> Segment:
    """The same segment seen from its other end (cones swap their diameters)."""
    if isinstance(segment, (Cylinder, Tube)):
        return segment
    if isinstance(segment, Cone):
        return dataclasses.replace(segment, diameter_start=segment.diameter_end,
                                   diameter_end=segment.diameter_start)
    raise TypeError(f"piston segments: only Cylinder, Tube and Cone can be mirrored, got {type(segment).__name__}; "
                    "build a Rod left to right (impact face at its right end) instead")


def piston_from_face(segments: Sequence[Segment], material: Material = STEEL, name: Optional[str] = None) -> Rod:
    """A piston given **from its impact face backwards** (Cylinder/Tube/Cone; a Cone's ``diameter_start`` is
    the diameter on the impact side) as a :class:`Rod` listed left to right, impact face at its right end."""
    segs = list(segments)
    if not segs:
        raise ValueError("segments: a piston needs at least one segment")
    for i, s in enumerate(segs):
        if not isinstance(s, Segment):
            raise TypeError(f"segments[{i}]: must be a Segment (Cylinder, Tube, Cone), got {type(s).__name__}")
    return Rod(tuple(_mirrored(s) for s in reversed(segs)), material, name)


def piston_1() -> Rod:
    """Piston 1 (thesis Fig. 5.3): 40 / 50 / 40 mm diameter, 100 / 300 / 100 mm long (lengths chosen,
    0.5 m in all, t* = 2 l_Pis / c = 0.1932 ms); steel."""
    return piston_from_face([Cylinder(length, d) for length, d in _PISTON_1], STEEL, "piston 1")


def piston_2() -> Rod:
    """Piston 2 (thesis Fig. 5.4; dimensions **assumed**, see the module docstring), from the impact face:
    cone 80 mm (30 -> 50 mm), 100 mm (36 mm), middle block 120 mm (50 mm), 120 mm (36 mm), small block
    40 mm (44 mm), 30 mm (36 mm); steel."""
    return piston_from_face([Cone(0.080, 0.030, 0.050), Cylinder(0.100, 0.036), Cylinder(0.120, 0.050),
                             Cylinder(0.120, 0.036), Cylinder(0.040, 0.044), Cylinder(0.030, 0.036)],
                            STEEL, "piston 2")


def rig_rod() -> Rod:
    """The struck rod (Fig. 5.5): steel cylinder, 50 mm x 1800 mm."""
    return Rod((Cylinder(ROD_LENGTH, ROD_DIAMETER),), STEEL, "rod")


# ------------------------------------------------------------------------------------------- setup
@dataclass(frozen=True, eq=False)
class RigSetup:
    """A piston hitting the rig's rod at ``velocity`` (m/s, > 0 towards the rod) with gauges on the rod.

    ``gauges`` are (name, position) pairs, positions in m from the rod's impact face.
    """

    piston: Rod
    rod: Rod
    velocity: float
    gauges: tuple[tuple[str, float], ...] = field(default_factory=lambda: tuple(GAUGE_POSITIONS.items()))

    def __post_init__(self) -> None:
        for what in ("piston", "rod"):
            if not isinstance(getattr(self, what), Rod):
                raise TypeError(f"RigSetup.{what}: must be a Rod, got {type(getattr(self, what)).__name__}")
        v = positive("RigSetup.velocity (impact velocity of the piston towards the rod)", self.velocity, "m/s")
        object.__setattr__(self, "velocity", v)
        gauges = tuple(dict(self.gauges).items()) if isinstance(self.gauges, Mapping) else tuple(self.gauges)
        if not gauges:
            raise ValueError("RigSetup.gauges: give at least one (name, position) pair")
        names = set()
        clean = []
        for i, item in enumerate(gauges):
            if not (isinstance(item, tuple) and len(item) == 2 and isinstance(item[0], str) and item[0]):
                raise TypeError(f"RigSetup.gauges[{i}]: must be a (name, position in m) pair, got {item!r}")
            name, pos = item
            if name in names:
                raise ValueError(f"RigSetup.gauges: gauge name {name!r} appears twice")
            if name == "contact":
                raise ValueError("RigSetup.gauges: 'contact' is reserved for the impact face in the wave-path table")
            names.add(name)
            pos = finite(f"RigSetup.gauges[{name!r}] position", pos, "m")
            if not 0.0 < pos < self.rod.length:
                raise ValueError(f"RigSetup.gauges[{name!r}]: position must lie inside the rod, "
                                 f"0 < x < {self.rod.length:.6g} m, got {pos!r} m")
            clean.append((name, pos))
        object.__setattr__(self, "gauges", tuple(clean))

    # -- derived model objects -------------------------------------------------------------
    @property
    def rods(self) -> tuple[Rod, Rod]:
        """(piston, rod), left to right."""
        return (self.piston, self.rod)

    @property
    def velocities(self) -> tuple[float, float]:
        """Initial velocities (piston, rod) in m/s."""
        return (self.velocity, 0.0)

    @property
    def probes(self) -> tuple[Probe, ...]:
        """One :class:`~rodimpact.Probe` per gauge station, on rod 1."""
        return tuple(Probe(name, 1, pos) for name, pos in self.gauges)

    @property
    def system(self) -> System:
        """The :class:`~rodimpact.System`: piston and rod in unilateral contact, both outer ends free."""
        return System(self.rods, self.velocities, left="free", right="free")

    def with_velocity(self, velocity: float) -> "RigSetup":
        """The same rig at another impact velocity (m/s)."""
        return dataclasses.replace(self, velocity=velocity)

    # -- travel times and closed forms -----------------------------------------------------------
    @property
    def piston_travel_time(self) -> float:
        """theta_Pis: travel time of a wavefront through the piston, s (l_Pis / c for a uniform material)."""
        return self.piston.total_travel_time

    @property
    def pulse_duration(self) -> float:
        """t* = 2 l_Pis / c (thesis eq. 5.4), in travel-time form 2 theta_Pis, s."""
        return 2.0 * self.piston_travel_time

    @property
    def rod_wave_speed(self) -> float:
        """Wave speed at the rod's impact face, m/s."""
        return float(self.rod.wave_speed(0.0))

    def gauge_travel_time(self, position: float) -> float:
        """Travel time from the rod's impact face to ``position`` (m), s."""
        x = finite("position", position, "m")
        if not 0.0 <= x <= self.rod.length:
            raise ValueError(f"position: must lie on the rod, 0 <= x <= {self.rod.length:.6g} m, got {position!r} m")
        return float(self.rod.travel_time(x))

    @property
    def face_impedance(self) -> float:
        """Impedance of the piston at its impact face, N s/m."""
        return float(self.piston.impedance(self.piston.length))

    @property
    def rod_impedance(self) -> float:
        """Impedance of the rod at its impact face, N s/m."""
        return float(self.rod.impedance(0.0))

    @property
    def incident_plateau(self) -> float:
        """First force level of the incident wave, N: -Z_face Z_rod v / (Z_face + Z_rod) (contact of two
        impedances; negative = compression). It holds until the first reflection inside the piston returns."""
        a, b = self.face_impedance, self.rod_impedance
        return -a * b * self.velocity / (a + b)

    @property
    def piston_energy(self) -> float:
        """Initial kinetic energy of the piston, m v^2 / 2, J."""
        return 0.5 * self.piston.mass * self.velocity**2


def build_rig(piston: int | str | Rod = 1, velocity: Optional[float] = None,
              gauges: Optional[Mapping[str, float]] = None, rod: Optional[Rod] = None) -> RigSetup:
    """The thesis test rig with piston 1 or 2 (or any piston :class:`Rod`, impact face at its right end).

    ``velocity`` defaults to the main investigations of Tab. 5.3: 4.60 m/s (piston 1), 4.58 m/s (piston 2);
    it is required for a custom piston. ``gauges`` default to :data:`GAUGE_POSITIONS`, ``rod`` to
    :func:`rig_rod`.
    """
    defaults = {1: (piston_1, IMPACT_VELOCITIES["standard piston"][0]),
                2: (piston_2, IMPACT_VELOCITIES["complex piston"][0])}
    key = {"1": 1, "2": 2, "piston 1": 1, "piston 2": 2}.get(str(piston).strip().lower()) \
        if isinstance(piston, (int, str)) and not isinstance(piston, bool) else None
    if isinstance(piston, Rod):
        if velocity is None:
            raise ValueError("velocity: required (m/s) when the piston is a custom Rod")
        p = piston
    elif key is not None:
        make, v_default = defaults[key]
        p = make()
        velocity = v_default if velocity is None else velocity
    else:
        raise ValueError(f"piston: must be 1, 2, 'piston 1', 'piston 2' or a Rod, got {piston!r}")
    if gauges is not None and not isinstance(gauges, Mapping):
        raise TypeError(f"gauges: must be a mapping name -> position (m from the rod's impact face), e.g. "
                        f"{{'SGP1': 0.110}}, got {type(gauges).__name__} {gauges!r}")
    g = tuple((GAUGE_POSITIONS if gauges is None else gauges).items())
    return RigSetup(p, rig_rod() if rod is None else rod, velocity, g)


# ------------------------------------------------------------------------------------------- time step
def rig_time_step(setup: RigSetup, max_step: float = 1e-3 / STEEL.wave_speed) -> float:
    """The largest time step <= ``max_step`` (s) that makes every segment travel time and every gauge travel
    time an integer number of steps, so that cylinders, steps and gauges sit exactly on lattice nodes and
    the lattice solution is exact for stepped cylinders.

    Works on lengths on a 1 um grid when all segments share one wave speed; otherwise returns ``max_step``
    (the lattice then approximates the step positions, see docs/method.md).
    """
    if not isinstance(setup, RigSetup):
        raise TypeError(f"setup: must be a RigSetup (see build_rig), got {type(setup).__name__}")
    max_step = positive("max_step", max_step, "s")
    speeds = {round(setup.piston.segment_material(i).wave_speed, 9) for i in range(len(setup.piston.segments))}
    speeds |= {round(setup.rod.segment_material(i).wave_speed, 9) for i in range(len(setup.rod.segments))}
    if len(speeds) != 1:
        return max_step
    c = speeds.pop()
    lengths = [s.length for s in setup.piston.segments] + [s.length for s in setup.rod.segments]
    lengths += [pos for _, pos in setup.gauges]
    microns = [x * 1e6 for x in lengths]
    if any(abs(m - round(m)) > 1e-6 for m in microns):
        return max_step
    g = 0
    for m in microns:
        g = math.gcd(g, int(round(m)))
    quantum = g * 1e-6 / c
    return quantum / math.ceil(quantum / max_step * (1 - 1e-12))


# ------------------------------------------------------------------------------------------- wave paths
@dataclass(frozen=True)
class WavePathEvent:
    """One row of the wave-path table.

    ``gauge``: gauge name, or ``"contact"`` for the impact face; ``event``: short key; ``time``: s after
    impact; ``explanation``: the wave path in words; ``sign``: +1 if the force jumps up (towards tension),
    -1 if it jumps down (more compression), 0 if only the slope changes (taper ends) or nothing is measured
    there; ``label``: the time point of thesis Fig. 5.13 this event is, if any (standard gauges only).
    """

    gauge: str
    event: str
    time: float
    explanation: str
    sign: int = 0
    label: str = ""


#: Thesis Fig. 5.13 time points (Sec. 5.4.1) as (gauge, event) -> label.
_FIG_5_13 = {
    ("SGP1", "incident front"): "t1", ("SGP2", "incident front"): "t2",
    ("SGP1", "piston free end"): "t3", ("SGP1", "incident pulse passed"): "t3", ("SGP3", "incident front"): "t4",
    ("SGP2", "piston free end"): "t5", ("SGP2", "incident pulse passed"): "t5", ("SGP3", "rod free end"): "t5",
    ("SGP3", "piston free end"): "t6", ("SGP3", "incident pulse passed"): "t6", ("SGP2", "rod free end"): "t6",
    ("SGP3", "reflected pulse passed"): "t7", ("SGP1", "rod free end"): "t8",
    ("SGP1", "second pass passed"): "t10",
}


def _mm(x: float) -> str:
    return f"{x * 1e3:.4g} mm"


def _piston_features(setup: RigSetup) -> list[tuple[str, float, str, int]]:
    """Impedance features of the piston from the impact face: (event, theta from face, text, sign)."""
    p = setup.piston
    segs = p.segments
    bounds = p.segment_bounds
    total = p.total_travel_time
    n = len(segs)
    out: list[tuple[str, float, str, int]] = []

    def z_at(i: int, local: float) -> float:
        m = p.segment_material(i)
        return float(segs[i].area(np.array([local]))[0]) * m.density * m.wave_speed

    def diameter(i: int, local: float) -> float:
        return float(segs[i].equivalent_diameter(np.array([local]))[0])

    def uniform(i: int) -> bool:
        return isinstance(segs[i], (Cylinder, Tube))

    # walk from the impact face (segment n-1, local s = length) towards the free end (segment 0, s = 0)
    for i in range(n - 1, 0, -1):
        near, far = i, i - 1                      # the incident wave goes from `near` into `far`
        theta = total - float(p.travel_time(bounds[i]))
        dist = p.length - bounds[i]
        z_near, z_far = z_at(near, 0.0), z_at(far, segs[far].length)
        d_near, d_far = diameter(near, 0.0), diameter(far, segs[far].length)
        if not uniform(near):
            out.append(("taper end", theta,
                        f"end of the taper ({type(segs[near]).__name__}) {_mm(dist)} from the impact face: the "
                        "continuous reflection from the taper stops, the force ramp ends", 0))
        if abs(z_far - z_near) > 1e-9 * max(z_far, z_near):
            r = (z_far - z_near) / (z_far + z_near)
            kind = "widens" if r > 0 else "narrows"
            effect = ("returns compressive: the force drops" if r > 0 else "returns tensile: the force rises")
            out.append(("step reflection", theta,
                        f"reflection at the step {_mm(dist)} from the impact face, where the piston {kind} from "
                        f"{d_near * 1e3:.4g} mm to {d_far * 1e3:.4g} mm (R = {r:+.4f}); it {effect}",
                        -1 if r > 0 else 1))
        if not uniform(far):
            zs, ze = z_at(far, segs[far].length), z_at(far, 0.0)
            trend = "widens" if ze > zs else "narrows"
            ramp = "falls (more compression)" if ze > zs else "rises"
            out.append(("taper start", theta,
                        f"beginning of the taper ({type(segs[far]).__name__}) {_mm(dist)} from the impact face: "
                        f"the piston {trend} continuously, the force {ramp} almost linearly from here", 0))
    # the face segment: a second round trip between the impact face and the first step (thesis Fig. 5.15b)
    face = n - 1
    if n > 1 and uniform(face):
        z_face, z_rod = z_at(face, 0.0), setup.rod_impedance
        z_next = z_at(face - 1, segs[face - 1].length)
        if abs(z_face - z_rod) > 1e-9 * z_rod and abs(z_next - z_face) > 1e-9 * z_face:
            r_face = (z_rod - z_face) / (z_rod + z_face)   # seen from inside the piston, towards the rod
            theta1 = segs[face].length / p.segment_material(face).wave_speed
            out.append(("face-segment echo", 2.0 * theta1,
                        f"the wave reflected at the first step is reflected again at the contact face "
                        f"(Z_piston -> Z_rod, R = {r_face:+.4f}) and once more at the first step: "
                        "two round trips in the face segment (the second deflection of thesis Fig. 5.15b)",
                        -1 if r_face > 0 else 1))
    if not uniform(face):
        out.append(("taper start", 0.0,
                    f"the piston begins with a taper ({type(segs[face]).__name__}) at the impact face: "
                    "the force ramps from the first arrival on", 0))
    out.append(("piston free end", total,
                f"the incident wave reflected as tension at the piston's free end ({_mm(p.length)} from the impact "
                "face); t* = 2 l_Pis / c after the arrival (eq. 5.4): the end of the incident pulse if the bodies "
                "separate then", 1))
    return out


def wave_paths(setup: RigSetup, separation_time: Optional[float] = None) -> list[WavePathEvent]:
    """The wave-path table: when the main steps reach each gauge, from travel times only.

    For a gauge at x (travel time theta_x = x / c from the impact face), with theta_Pis(s) the travel time
    from the impact face to a piston feature at distance s and theta_L = L / c:

    * incident front: theta_x;
    * reflection at a piston step / taper end at s: theta_x + 2 theta_Pis(s) (2 s / c after the arrival),
      sign from the reflection factor R = (Z_far - Z_near) / (Z_far + Z_near);
    * second round trip in the face segment (Fig. 5.15b): theta_x + 4 theta_Pis(s_1);
    * piston free end: theta_x + t*, t* = 2 theta_Pis(l_Pis) (eq. 5.4);
    * reflection at the rod's free end: 2 theta_L - theta_x (= (2L - x)/c, opposite sign), the reflected
      pulse has passed at 2 theta_L - theta_x + t*;
    * second pass, after reflection at the rod's impact end (free once the piston has separated):
      2 theta_L + theta_x and 2 theta_L + theta_x + t*.

    ``"contact"`` rows: separation predicted from travel times at t* (thesis 5.4.1: the tensile reflection
    from the piston's free end reaches the contact face) and the return of the rod's reflection at
    2 theta_L. Rows are sorted by gauge, then time.

    ``separation_time`` (s, e.g. :attr:`RigSignals.separation_time`): if the bodies separate later than t*
    (piston 2, thesis 5.4.2), the incident pulse lasts t_s instead of t*: pass the simulated t_s and the
    table gets an "incident pulse passed" row at theta_x + t_s per gauge, and the later rows use t_s.
    ``label`` refers to the analogous time point of thesis Fig. 5.13 (experiment 1, piston 1).
    """
    if not isinstance(setup, RigSetup):
        raise TypeError(f"setup: must be a RigSetup (see build_rig), got {type(setup).__name__}")
    t_star = setup.pulse_duration
    theta_l = setup.rod.total_travel_time
    if separation_time is None:
        pulse, later = t_star, False
    else:
        pulse = positive("separation_time", separation_time, "s")
        later = abs(pulse - t_star) > 1e-9 * t_star
    features = _piston_features(setup)
    rows: list[WavePathEvent] = []
    for name, pos in setup.gauges:
        tx = setup.gauge_travel_time(pos)
        z_text = (f"Z_face = {setup.face_impedance:.5g} N s/m on Z_rod = {setup.rod_impedance:.5g} N s/m: "
                  f"first level -Z_face Z_rod v / (Z_face + Z_rod)")
        gauge_rows = [("incident front", tx,
                       f"the compressive front from the impact reaches {name} at x/c = {_mm(pos)} / c ({z_text})",
                       -1)]
        gauge_rows += [(ev, tx + 2.0 * th, text, s) for ev, th, text, s in features]
        d = "t_s" if later else "t*"
        if later:
            gauge_rows.append(("incident pulse passed", tx + pulse,
                               f"the bodies separated at t_s = {pulse * 1e6:.4g} us, later than t*: the incident "
                               "pulse ends at x/c + t_s", 1))
        gauge_rows += [
            ("rod free end", 2 * theta_l - tx,
             "the incident front returns from the rod's free end as tension, (2L - x)/c; it adds to the incident "
             "wave still passing (opposite sign)", 1),
            ("reflected pulse passed", 2 * theta_l - tx + pulse,
             f"the tail of the reflected (tensile) pulse passes, (2L - x)/c + {d}", -1),
            ("second pass", 2 * theta_l + tx,
             "the reflected pulse, reflected again (compressive) at the rod's impact end, free after separation, "
             "(2L + x)/c", -1),
            ("second pass passed", 2 * theta_l + tx + pulse,
             f"the second pass has gone by, (2L + x)/c + {d}: the state of the incident pulse having passed "
             "repeats with period 2L/c", 1),
        ]
        for ev, t, text, s in sorted(gauge_rows, key=lambda r: r[1]):
            label = "" if (later and ev == "piston free end") else _FIG_5_13.get((name, ev), "")
            rows.append(WavePathEvent(name, ev, float(t), text, s, label))
    if later:
        rows.append(WavePathEvent("contact", "separation", float(pulse),
                                  f"piston and rod separate at t_s = {pulse * 1e6:.4g} us (given), "
                                  f"{(pulse - t_star) * 1e6:+.4g} us after t* = 2 l_Pis / c", 0))
    else:
        rows.append(WavePathEvent("contact", "separation", float(t_star),
                                  "the tensile reflection from the piston's free end reaches the contact face, "
                                  "t_s = t* = 2 l_Pis / c (thesis 5.4.1)", 0))
    rows.append(WavePathEvent("contact", "rod free end", float(2 * theta_l),
                              "the reflection from the rod's free end returns to the impact face, 2L/c", 0))
    return rows


# ------------------------------------------------------------------------------------------- simulation
@dataclass(frozen=True, eq=False)
class RigSignals:
    """Simulated gauge signals of the rig, raw and through the measuring chain.

    ``raw[name]``: the probe's normal force N_k (N, tension positive) at ``time`` (lattice step start times;
    values hold on [k dt, (k+1) dt)). ``filtered[name]``: the same through ``chain`` (causal), sampled at
    ``filtered_time`` (the chain's 1 MHz grid). ``separation_time``: first separation of piston and rod (s;
    ``None`` if still in contact at the end). ``efficiency``: fraction of the piston's initial kinetic energy
    given to the rod by ``efficiency_time`` = min(2 L/c, end of run), before the rod's reflection returns.
    """

    setup: RigSetup
    time: np.ndarray
    raw: dict[str, np.ndarray]
    filtered_time: np.ndarray
    filtered: dict[str, np.ndarray]
    contact_force: np.ndarray
    separation_time: Optional[float]
    efficiency: float
    efficiency_time: float
    chain: MeasuringChain
    result: SimulationResult

    @property
    def dt(self) -> float:
        """Lattice time step, s."""
        return self.result.dt


def simulate_rig(setup: RigSetup, duration: float = 1.6e-3, dt: Optional[float] = None,
                 chain: Optional[MeasuringChain] = None, backend: str = "numba") -> RigSignals:
    """Simulate the rig and pass the gauge forces through the measuring chain.

    ``dt`` defaults to :func:`rig_time_step` (exact lattice for stepped cylinders, <= 1 mm of steel per
    element); ``chain`` to the thesis chain ``MeasuringChain()``. The lattice node values are piecewise
    constant in time, so the chain gets them with ``interpolation="previous"``. ``duration`` must cover one
    sample interval of the chain plus one lattice step.
    """
    if not isinstance(setup, RigSetup):
        raise TypeError(f"setup: must be a RigSetup (see build_rig), got {type(setup).__name__}")
    duration = positive("duration", duration, "s")
    dt = rig_time_step(setup) if dt is None else positive("dt", dt, "s")
    chain = MeasuringChain() if chain is None else chain
    if not isinstance(chain, MeasuringChain):
        raise TypeError(f"chain: must be a MeasuringChain, got {type(chain).__name__}")
    # the recorded forces span (n_steps - 1) dt; the chain needs at least one of its sample intervals
    min_duration = (1.0 / chain.sampling_rate + dt) * (1 + 1e-6)
    if duration < min_duration:
        raise ValueError(f"duration: must be at least {min_duration:.4g} s, one sample interval of the measuring "
                         f"chain (1 / sampling_rate = {1.0 / chain.sampling_rate:.4g} s) plus one lattice step "
                         f"(dt = {dt:.4g} s), got {duration!r} s")
    t_eff = min(2.0 * setup.rod.total_travel_time, duration)
    k_eff = max(1, int(math.floor(t_eff / dt * (1 + 1e-12))))
    res = simulate(setup.system, duration=duration, dt=dt, outputs=Outputs(probes=setup.probes, energy_every=k_eff),
                   backend=backend)
    raw = {name: res.probe(name).force for name, _ in setup.gauges}
    filtered_time = None
    filtered: dict[str, np.ndarray] = {}
    for name, values in raw.items():
        filtered_time, filtered[name] = chain.apply(res.time, values, interpolation="previous")
    sep = res.separation_times()
    e_pis = res.energy.kinetic[0] + res.energy.strain[0]
    i_eff = int(np.argmin(np.abs(res.energy.time - k_eff * dt)))
    efficiency = float((e_pis[0] - e_pis[i_eff]) / e_pis[0])
    return RigSignals(setup=setup, time=res.time, raw=raw, filtered_time=filtered_time, filtered=filtered,
                      contact_force=res.contact_force, separation_time=float(sep[0]) if sep.size else None,
                      efficiency=efficiency, efficiency_time=float(res.energy.time[i_eff]), chain=chain,
                      result=res)
