"""The thesis's synthesis examples (Sec. 4.2) as ready-made problems.

* :func:`academic_example` -- Setup 4/5 (Tab. 4.2): a semi-infinite uniform bar struck by the unknown striker;
  example 1 prescribes the exponentially decreasing impact force (eq. 4.24), example 2 the linear ramp
  (eq. 4.28). The parameters are the printed ones of Tab. 4.2 and the window rule is the thesis's ("start").
* :func:`percussion_drilling_example` -- Fig. 4.9 / Tab. 4.5: a piston hits a shank adapter, coupling
  sleeve, drill rod and bit ending on rock (bit-rock spring k1 = 300 MN/m); the incident force at the
  bit-rock interface shall be -187 kN exp(5.88 t / ms) (eq. 4.29).

Fig. 4.9 gives the geometry only as a drawing, not in the text. Every impedance and number of Tab. 4.5 is
kept; the section lengths are our plausible choice, stated here and in docs/inverse.md:

=====================  ===========  ========  =========================================
part                   impedance    length    reason for the length
=====================  ===========  ========  =========================================
shank adapter          51.0 kN s/m  0.35 m    its double reflection (2 x 70 dt) is the last of the three
                                              jumps the thesis describes (Fig. 4.10b) within 2 x 100 dt
coupling sleeve        115 kN s/m   0.15 m    the first jump (2 x 30 dt)
drill rod              79.7 kN s/m  2.00 m    400 elements (Tab. 4.5: n~ = 400)
bit, constant part     156 kN s/m   0.05 m    bit round trip (2 x 50 dt) is the second jump
bit, linear increase   156->248     0.20 m    impedance rising linearly to the rock (Fig. 4.9)
=====================  ===========  ========  =========================================

Material steel (E = 210 GPa, rho = 7840 kg/m^3) throughout; the piston of 0.5 m is cut into n = 100 elements,
which sets dt = 0.005 m / c = 0.966 us (so the drill rod has exactly 400 elements).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

from ..rods.conditions import BitRockEnd
from ..rods.material import STEEL
from ..rods.rod import Rod
from ..rods.segments import Cylinder, LinearAreaTaper
from .recursive import synthesize
from .result import SynthesisResult
from .targets import ExponentialDecay, ExponentialGrowth, LinearRamp


@dataclass(frozen=True)
class SynthesisProblem:
    """Everything :func:`~rodimpact.synthesize` needs for one example; :meth:`solve` runs it."""

    name: str
    target: Any
    struck: Rod
    striker_velocity: float
    n: int
    dt: float
    options: dict[str, Any] = field(default_factory=dict)

    def solve(self, **overrides: Any) -> SynthesisResult:
        """Run :func:`~rodimpact.synthesize` (keyword ``overrides`` replace the example's settings)."""
        kw: dict[str, Any] = dict(n=self.n, dt=self.dt, **self.options)
        kw.update(overrides)
        return synthesize(self.target, self.struck, self.striker_velocity, **kw)


#: Tab. 4.2 as printed: struck impedance, peak force, time constant, time step, elements, striker velocity.
ACADEMIC_PARAMETERS = dict(struck_impedance=79.7e3, peak=239e3, time_constant=0.383e-3, dt=1.93e-6, n=100,
                           striker_velocity=6.0)


def academic_example(number: int, n: Optional[int] = None) -> SynthesisProblem:
    """Thesis example 1 (exponential decay, ``number=1``) or 2 (linear ramp, ``number=2``), Tab. 4.2.

    The struck rod is uniform with a matched non-reflecting far end (semi-infinite, Fig. 4.5).
    """
    p = ACADEMIC_PARAMETERS
    if number == 1:
        target = ExponentialDecay(p["peak"], p["time_constant"])
    elif number == 2:
        target = LinearRamp(p["peak"], p["time_constant"])
    else:
        raise ValueError(f"number: the thesis has academic examples 1 and 2, got {number!r}")
    nn = p["n"] if n is None else n
    bar = Rod.from_impedance([p["struck_impedance"]] * 4, p["dt"], name="semi-infinite bar")
    return SynthesisProblem(f"academic example {number}", target, bar, p["striker_velocity"], nn, p["dt"],
                            dict(far_end="nonreflecting", rule="start"))


#: Tab. 4.5 impedances (N s/m) and loads.
DRILLING_IMPEDANCES = dict(shank=51.0e3, sleeve=115e3, rod=79.7e3, bit=156e3, bit_end=248e3)
DRILLING_LENGTHS = dict(shank=0.35, sleeve=0.15, rod=2.0, bit=0.05, bit_taper=0.20)


def drill_string() -> Rod:
    """Shank adapter, coupling sleeve, drill rod and bit (Fig. 4.9, lengths as stated in this module)."""
    rc = STEEL.density * STEEL.wave_speed
    z, ell = DRILLING_IMPEDANCES, DRILLING_LENGTHS

    def dia(imp: float) -> float:
        return math.sqrt(4.0 * imp / rc / math.pi)

    return Rod([Cylinder(ell["shank"], dia(z["shank"])), Cylinder(ell["sleeve"], dia(z["sleeve"])),
                Cylinder(ell["rod"], dia(z["rod"])), Cylinder(ell["bit"], dia(z["bit"])),
                LinearAreaTaper(ell["bit_taper"], z["bit"] / rc, z["bit_end"] / rc)], STEEL, "drill string")


def percussion_drilling_example(n: int = 100) -> SynthesisProblem:
    """Thesis Sec. 4.2.2: the piston (0.5 m, v_in = 9 m/s) that gives the incident force -187 kN exp(C t),
    C = 5.88 /ms, at the bit-rock interface (k1 = 300 MN/m), struck system at rest."""
    dt = 0.5 / 100 / STEEL.wave_speed
    struck = drill_string()
    return SynthesisProblem("percussion drilling", ExponentialGrowth(187e3, 5.88e3), struck, 9.0, n, dt,
                            dict(far_end=BitRockEnd(300e6), position=struck.length, quantity="incident",
                                 rule="start"))
