"""Published hammer data: small TOML files in ``rodimpact/pile/hammers/``, one per hammer, each number with its
source (``[sources]``: the key -> where it was published). Numbers that could not be verified in a published
source are left out: the files give the ram weight and the stroke, not an efficiency or cushion properties, which
the user states for the job.

Kinds: ``drop`` (a ram lifted by a winch and released), ``air-steam`` (single-acting air or steam hammer: the
ram is lifted by pressure and falls freely) and ``hydraulic`` (a ram lifted hydraulically, falling freely or
assisted; the impact velocity is then best given directly or measured). In all three the ram's kinetic energy
at impact is eta W h (W the ram weight, h the stroke, eta the hammer efficiency). Diesel hammers are out of
scope: their impact is preceded and followed by combustion pressure on the ram and the anvil, which this model
does not have.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from importlib import resources

from .._units import to_si
from .._validate import positive
from .units import STANDARD_GRAVITY

#: hammer kinds the driving system models (diesel combustion is out of scope)
HAMMER_KINDS = ("drop", "air-steam", "hydraulic")


@dataclass(frozen=True)
class Hammer:
    """A hammer's published data: ``ram_mass`` in kg (the published ram weight / g_n), ``stroke`` (the rated
    drop height of the ram) in m, ``kind`` one of :data:`HAMMER_KINDS`, ``sources``: key -> citation."""

    name: str
    kind: str
    ram_mass: float
    stroke: float
    sources: dict[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.kind not in HAMMER_KINDS:
            extra = " (diesel hammers are out of scope: combustion is not modelled)" if self.kind == "diesel" else ""
            raise ValueError(f"Hammer.kind: must be one of {', '.join(map(repr, HAMMER_KINDS))}, got "
                             f"{self.kind!r}{extra}")
        object.__setattr__(self, "ram_mass", positive("Hammer.ram_mass", self.ram_mass, "kg"))
        object.__setattr__(self, "stroke", positive("Hammer.stroke", self.stroke, "m"))

    @property
    def rated_energy(self) -> float:
        """Potential energy of the ram at its rated stroke, W h = M g_n h, J."""
        return self.ram_mass * STANDARD_GRAVITY * self.stroke


def hammer_names() -> list[str]:
    """The names of the shipped hammer files, sorted."""
    folder = resources.files(__package__).joinpath("hammers")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def hammer(name: str) -> Hammer:
    """The shipped hammer ``name`` (see :func:`hammer_names`); every number of its file has a source."""
    names = hammer_names()
    if name not in names:
        raise ValueError(f"hammer: no hammer {name!r}; shipped: {', '.join(names)}")
    text = resources.files(__package__).joinpath("hammers", f"{name}.toml").read_text(encoding="utf-8")
    data = tomllib.loads(text)
    sources = data.get("sources", {})
    for key in ("ram_weight", "stroke"):
        if key not in sources:
            raise ValueError(f"hammers/{name}.toml: {key} has no source")
    weight = to_si(f"hammers/{name}.toml: ram_weight", data["ram_weight"], "N")
    stroke = to_si(f"hammers/{name}.toml: stroke", data["stroke"], "m")
    return Hammer(data["name"], data["kind"], weight / STANDARD_GRAVITY, stroke, dict(sources))
