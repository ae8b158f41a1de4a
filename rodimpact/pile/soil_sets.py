"""Published sets of Smith's soil quakes and damping factors: small TOML files in ``rodimpact/pile/soils/``, one per
source, every number with the place it was read (``[sources]``: key -> citation) and a ``status`` saying how it
was read. :func:`soil_set` loads one, :meth:`rodimpact.pile.SoilDynamics.published` turns it into the
:class:`~rodimpact.pile.SoilDynamics` of a job.

A set holds the shaft quake (m), the Smith damping factors of the shaft by soil (s/m) and of the toe (s/m), and
rules for the toe quake: a length, or the toe diameter divided by a number (GRLWEAP's D/120 and D/60). The
damping factors are Smith's J in R = R_s (1 + J V), so a set always gives ``damping_kind = "smith"``. Nothing is
taken from a set silently: :class:`~rodimpact.pile.SoilDynamics` has no defaults, the user names the set and the
soil.

Shipped sets (docs/pile-driving.md, "Soil parameters and their sources"): ``gec12`` (FHWA GEC-12,
FHWA-NHI-16-009, Vol. II, Ch. 12) and ``grlweap`` (Rausche, GRLWEAP Fundamentals). Both were read from verbatim
quotations in a third-party report, not from the documents themselves; each file's ``status`` says so. Smith's
(1960) own values could not be read at all and are not shipped.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, Optional

from .._units import to_si
from .._validate import positive

#: folder of the shipped sets, inside the package
_FOLDER = "soils"


@dataclass(frozen=True)
class SoilParameterSet:
    """A published set of Smith soil parameters (SI): ``shaft_quake`` (m), ``shaft_damping`` (soil -> Smith J,
    s/m), ``toe_damping`` (s/m), ``toe_quakes`` (rule -> length in m) and ``toe_quake_divisors`` (rule -> n: the
    toe quake is the toe diameter / n), ``sources`` (key -> citation; keys ``shaft_quake``, ``toe_damping``,
    ``shaft_damping.SOIL``, ``toe_quake.RULE``) and ``status`` (how the numbers were read)."""

    name: str
    title: str
    status: str
    shaft_quake: float
    toe_damping: float
    shaft_damping: dict[str, float]
    toe_quakes: dict[str, float] = field(default_factory=dict)
    toe_quake_divisors: dict[str, float] = field(default_factory=dict)
    sources: dict[str, str] = field(default_factory=dict)

    @property
    def toe_quake_rules(self) -> list[str]:
        """Names of the toe quake rules of the set (lengths and diameter divisors)."""
        return sorted({**self.toe_quakes, **self.toe_quake_divisors})

    def toe_quake(self, rule: str, toe_diameter: Optional[float] = None) -> float:
        """The toe quake (m) of ``rule``: its length, or ``toe_diameter`` (m) / n for a diameter rule."""
        if rule in self.toe_quakes:
            return self.toe_quakes[rule]
        if rule not in self.toe_quake_divisors:
            rules = ", ".join(map(repr, self.toe_quake_rules)) or "none: give the toe quake as a length"
            raise ValueError(f"toe_quake: {rule!r} is not a toe quake rule of the {self.name!r} set; its rules: "
                             f"{rules}")
        n = self.toe_quake_divisors[rule]
        if toe_diameter is None:
            raise ValueError(f"toe_diameter: missing; the {self.name!r} toe quake rule {rule!r} is the toe "
                             f"diameter / {n:g}")
        return positive("toe_diameter", toe_diameter, "m") / n

    def resolve_toe_quake(self, toe_quake: Any, toe_diameter: Optional[float] = None) -> Any:
        """``toe_quake`` as the job states it: a rule of the set (its quake in m, with ``toe_diameter`` for a rule
        D / n), or a length (m or a quantity such as ``"2.5 mm"``) returned as given for the caller to check."""
        if isinstance(toe_quake, str) and not _is_quantity(toe_quake):
            return self.toe_quake(toe_quake, toe_diameter)       # a rule name (an unknown one lists the rules)
        if toe_diameter is not None:
            raise ValueError("toe_diameter: only with a toe quake rule of the set, not with a toe quake length")
        return toe_quake


def _is_quantity(text: str) -> bool:
    """True when ``text`` reads as a quantity with a unit (``"2.5 mm"``), not as a rule name."""
    try:
        to_si("toe_quake", text, "m")
    except TypeError:
        return False
    except ValueError:                                       # a quantity of another dimension: SoilDynamics says so
        return True
    return True


def soil_set_names() -> list[str]:
    """Names of the shipped sets, sorted."""
    folder = resources.files(__package__).joinpath(_FOLDER)
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def soil_set(name: str) -> SoilParameterSet:
    """The shipped set ``name`` (:func:`soil_set_names`); every number of its file must have a source."""
    names = soil_set_names()
    if name not in names:
        raise ValueError(f"parameter_set: no soil parameter set {name!r}; shipped: {', '.join(names)}")
    where = f"pile/{_FOLDER}/{name}.toml"
    data = tomllib.loads(resources.files(__package__).joinpath(_FOLDER, f"{name}.toml").read_text(encoding="utf-8"))
    sources = data.get("sources", {})

    def value(key: str, text: Any, unit: str) -> float:
        if key not in sources:
            raise ValueError(f"{where}: {key} has no source")
        x = to_si(f"{where}: {key}", text, unit)
        if x is None or not math.isfinite(x) or x <= 0:
            raise ValueError(f"{where}: {key} must be a positive quantity in {unit}, got {text!r}")
        return x

    shaft = {soil: value(f"shaft_damping.{soil}", j, "s/m") for soil, j in data["shaft_damping"].items()}
    lengths, divisors = {}, {}
    for rule, v in data.get("toe_quake", {}).items():
        if isinstance(v, dict):
            if f"toe_quake.{rule}" not in sources:
                raise ValueError(f"{where}: toe_quake.{rule} has no source")
            divisors[rule] = positive(f"{where}: toe_quake.{rule}.diameter_divisor", v["diameter_divisor"])
        else:
            lengths[rule] = value(f"toe_quake.{rule}", v, "m")
    return SoilParameterSet(data["name"], data["title"], data["status"], value("shaft_quake", data["shaft_quake"], "m"),
                            value("toe_damping", data["toe_damping"], "s/m"), shaft, lengths, divisors,
                            dict(sources))
