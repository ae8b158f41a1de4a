"""Unit conversions and blow counts of pile driving: SI inside, US customary on request.

Exact definitions: 1 ft = 0.3048 m and 1 in = 0.0254 m (international yard and pound agreement, 1959); 1 lbf =
0.45359237 kg x 9.80665 m/s^2 = 4.4482216152605 N, so 1 kip = 1000 lbf = 4448.2216152605 N (NIST Special
Publication 811, 2008, appendix B.8). The standard acceleration of gravity g_n = 9.80665 m/s^2 (3rd CGPM, 1901).

Blow counts: a blow that sets the pile permanently by ``s`` metres needs ``L / s`` blows to advance it by L, so
blows per 0.25 m = 0.25 / s, blows per foot = 0.3048 / s and blows per inch = 0.0254 / s. A blow without
permanent set is refusal: the blow count is infinite. A set below :data:`REFUSAL_SET` (1 nm, 2.5e8 blows per
0.25 m) counts as none: it is the rounding of a plastic set that did not grow, not penetration.
"""

from __future__ import annotations

import math

from .._validate import finite

#: standard acceleration of gravity, m/s^2 (3rd CGPM, 1901)
STANDARD_GRAVITY = 9.80665
#: one international foot, m (exact)
FOOT = 0.3048
#: one inch, m (exact)
INCH = 0.0254
#: one pound-force, N (exact: 0.45359237 kg x g_n)
POUND_FORCE = 0.45359237 * STANDARD_GRAVITY
#: one kip (1000 lbf), N
KIP = 1000.0 * POUND_FORCE
#: one kip per square inch (ksi), Pa
KSI = KIP / INCH**2
#: one foot-kip (ft-kip), J
FOOT_KIP = FOOT * KIP
#: the SI blow-count length: blows per 0.25 m
QUARTER_METRE = 0.25
#: sets below this (m) are refusal (rounding of a plastic set that did not grow)
REFUSAL_SET = 1e-9

#: display units: system -> quantity -> (size of the unit in SI, its label)
UNIT_SYSTEMS = {
    "si": {"force": (1e3, "kN"), "stress": (1e6, "MPa"), "energy": (1e3, "kJ"), "length": (1.0, "m"),
           "set": (1e-3, "mm"), "velocity": (1.0, "m/s"), "blows": (QUARTER_METRE, "blows/0.25 m")},
    "us": {"force": (KIP, "kips"), "stress": (KSI, "ksi"), "energy": (FOOT_KIP, "ft-kips"), "length": (FOOT, "ft"),
           "set": (INCH, "in"), "velocity": (FOOT, "ft/s"), "blows": (FOOT, "blows/ft")},
}


def blows_per(length: float, permanent_set: float) -> float:
    """Blows needed to drive the pile ``length`` metres at ``permanent_set`` metres per blow; ``math.inf`` for a
    blow without permanent set (below :data:`REFUSAL_SET`: refusal)."""
    s = finite("permanent_set", permanent_set, "m")
    return length / s if s > REFUSAL_SET else math.inf


def blows_per_quarter_metre(permanent_set: float) -> float:
    """Blows per 0.25 m of penetration: 0.25 / set (set in m)."""
    return blows_per(QUARTER_METRE, permanent_set)


def blows_per_foot(permanent_set: float) -> float:
    """Blows per foot of penetration: 0.3048 / set (set in m)."""
    return blows_per(FOOT, permanent_set)


def blows_per_inch(permanent_set: float) -> float:
    """Blows per inch of penetration: 0.0254 / set (set in m)."""
    return blows_per(INCH, permanent_set)


def units_system(name: str) -> dict[str, tuple[float, str]]:
    """The display units ``"si"`` or ``"us"`` (quantity -> (size of the unit in SI, its label))."""
    if name not in UNIT_SYSTEMS:
        raise ValueError(f"units: must be one of {', '.join(map(repr, UNIT_SYSTEMS))}, got {name!r}")
    return UNIT_SYSTEMS[name]
