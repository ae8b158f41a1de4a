"""The thesis's synthesis examples (Sec. 4.2) as ready-made problems.

* :func:`academic_example` -- Setup 4/5 (Tab. 4.2): a semi-infinite uniform bar struck by the unknown striker;
  example 1 prescribes the exponentially decreasing impact force (eq. 4.24), example 2 the linear ramp
  (eq. 4.28). The parameters are the printed ones of Tab. 4.2 and the window rule is the thesis's ("start").
* :func:`percussion_drilling_example` -- Fig. 4.9 / Tab. 4.5: a piston hits a shank adapter, coupling
  sleeve, drill rod and bit ending on rock (bit-rock spring k1 = 300 MN/m); the incident force at the
  bit-rock interface shall be -187 kN exp(5.88 t / ms) (eq. 4.29).

One model of the drill string, the same as ``rodimpact/examples/percussion-drilling.toml`` (a test checks that
both build the same lattice). Reading of Tab. 4.5: n~ = 400 is the number of elements of the whole struck system
(shank adapter + coupling sleeve + drill rod + bit), the thesis's "rod" in the sense of its tilde quantities
(Rod 2 of ch. 3, eq. 3.21), as is v~_in = 0, the "initial velocity of the rod", which holds for all parts; the
drill-rod section proper is "the section with constant impedance Z~_3". Fig. 4.9 gives the section lengths only
as a drawing; every impedance and number of Tab. 4.5 is kept and the split of the 400 elements (5 mm each) is
our choice:

=====================  ===========  ==========  ===============================================
part                   impedance    elements    reason
=====================  ===========  ==========  ===============================================
shank adapter          51.0 kN s/m  70 (0.35m)  its double reflection (2 x 70 dt) is the last of the three
                                                jumps the thesis describes (Fig. 4.10b) within 2 x 100 dt
coupling sleeve        115 kN s/m   30 (0.15m)  the first jump (2 x 30 dt)
drill rod              79.7 kN s/m  250 (1.25m) the rest of the 400 elements
bit, constant part     156 kN s/m   10 (0.05m)  bit round trip (2 x 50 dt) is the second jump
bit, linear increase   156->248     40 (0.20m)  impedance rising linearly to the rock (Fig. 4.9), element
                                                values evenly spaced from 156 to 248 kN s/m
=====================  ===========  ==========  ===============================================

Impedance level, steel wave speed; the piston of 0.5 m is cut into n = 100 elements, so dt = 0.005 m / c =
0.966 us and the struck system is 2.0 m long (dead time 400 dt from the impact face to the rock).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from ..rods.conditions import BitRockEnd
from ..rods.material import STEEL
from ..rods.rod import Rod
from ..rods.system import System
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
    far_end: Any = "free"

    @property
    def struck_system(self) -> System:
        """The struck rod with the example's far end (:meth:`System.struck <rodimpact.rods.system.System.struck>`)."""
        return System.struck(self.struck, self.far_end)

    def solve(self, **overrides: Any) -> SynthesisResult:
        """Run :func:`~rodimpact.synthesize` (keyword ``overrides`` replace the example's settings)."""
        kw: dict[str, Any] = dict(n=self.n, dt=self.dt, **self.options)
        kw.update(overrides)
        return synthesize(self.target, self.struck_system, self.striker_velocity, **kw)


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
                            dict(rule="start"), far_end="nonreflecting")


#: Tab. 4.5 impedances (N s/m) and the split of the struck system's n~ = 400 elements: (part, impedance at its
#: first element, impedance at its last element, elements).
DRILLING_SECTIONS = (("shank adapter", 51.0e3, 51.0e3, 70), ("coupling sleeve", 115e3, 115e3, 30),
                     ("drill rod", 79.7e3, 79.7e3, 250), ("bit", 156e3, 156e3, 10),
                     ("bit, linear increase", 156e3, 248e3, 40))
#: Element travel time of the drilling example: 5 mm of steel (piston 0.5 m in n = 100 elements), s.
DRILLING_DT = 0.005 / STEEL.wave_speed


def drill_string() -> Rod:
    """Shank adapter, coupling sleeve, drill rod and bit (Fig. 4.9, Tab. 4.5) at the impedance level:
    :data:`DRILLING_SECTIONS` with element travel time :data:`DRILLING_DT` (400 elements, 2.0 m of steel)."""
    z = np.concatenate([np.full(n, a) if a == b else np.linspace(a, b, n) for _, a, b, n in DRILLING_SECTIONS])
    return Rod.from_impedance(z, DRILLING_DT, name="drill string")


def percussion_drilling_example(n: int = 100) -> SynthesisProblem:
    """Thesis Sec. 4.2.2: the piston (0.5 m, v_in = 9 m/s) that gives the incident force -187 kN exp(C t),
    C = 5.88 /ms, at the bit-rock interface (k1 = 300 MN/m), struck system at rest."""
    dt = DRILLING_DT
    struck = drill_string()
    return SynthesisProblem("percussion drilling", ExponentialGrowth(187e3, 5.88e3), struck, 9.0, n, dt,
                            dict(position=struck.length, quantity="incident", rule="start"), far_end=BitRockEnd(300e6))
