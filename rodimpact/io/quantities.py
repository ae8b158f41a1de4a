"""Physical quantities in model files: ``"50 mm"``, ``"210 GPa"``, ``"4.6 m/s"`` or bare numbers (SI).

Every quantity is converted once, here, to a float in SI base units (m, s, kg, N, Pa, N s/m, ...); the rest
of the package never sees units. Unit strings are parsed by :mod:`pint` (its own tokenizer, never Python
``eval``). A string whose dimension does not match the expected one is an error naming the key path, the
value and what would be valid, e.g. ``rods[0].segments[1].diameter: expected a length such as "50 mm" (or a
number in m), got "5 kg" (a mass)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any


class ModelError(ValueError):
    """Bad input in a model file; the message starts with the key path (``rods[1].segments[2].diameter``)."""


@dataclass(frozen=True)
class Dimension:
    """An expected physical dimension: its pint dimensionality, the SI unit it is stored in and an example."""

    name: str           # human name ("length")
    pint: str           # a unit expression with that dimensionality, used for the check
    si: str             # the SI unit numbers are given in, as written in docs and comments
    example: str        # an example value for messages and docs


#: Every dimension a model file uses. Keys are referenced by the schema.
DIMENSIONS: dict[str, Dimension] = {d.name: d for d in (
    Dimension("length", "m", "m", "50 mm"),
    Dimension("area", "m**2", "m^2", "1.26e-3 m^2"),
    Dimension("time", "s", "s", "0.5 ms"),
    Dimension("velocity", "m/s", "m/s", "4.6 m/s"),
    Dimension("force", "N", "N", "-150 kN"),
    Dimension("pressure", "Pa", "Pa", "210 GPa"),
    Dimension("density", "kg/m**3", "kg/m^3", "7840 kg/m^3"),
    Dimension("mass", "kg", "kg", "2.5 kg"),
    Dimension("impedance", "N*s/m", "N s/m", "51.0 kN s/m"),
    Dimension("stiffness", "N/m", "N/m", "300 MN/m"),
    Dimension("damping", "N*s/m", "N s/m", "10 kN s/m"),
    Dimension("acceleration", "m/s**2", "N/kg", "9.81 N/kg"),
    Dimension("wavenumber", "1/m", "1/m", "0.5 1/m"),
    Dimension("rate", "1/s", "1/s", "5.88 1/ms"),
    Dimension("dimensionless", "dimensionless", "-", "0.3"),
)}


@lru_cache(maxsize=1)
def _registry():
    """pint's unit registry; its parsed definitions are cached in the user's cache folder when possible
    (loading them takes ~0.2 s otherwise, noticeable on every command-line call)."""
    import pint

    try:
        return pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # no writable cache folder, or an old pint: parse the definitions each time
        return pint.UnitRegistry()


def _dimension_name(q) -> str:
    """A readable name of the dimension of pint quantity ``q`` ("a mass", "a length", ...)."""
    for d in DIMENSIONS.values():
        if q.check(d.pint) if d.pint != "dimensionless" else q.dimensionless:
            return f"a {d.name}" if d.name != "dimensionless" else "a pure number"
    simple = {"[mass]": "a mass", "[temperature]": "a temperature", "[current]": "a current",
              "[length] ** 3": "a volume", "[mass] * [length] ** 2 / [time] ** 2": "an energy",
              "[mass] * [length] / [time]": "a momentum", "[length] / [time] ** 2": "an acceleration"}
    return simple.get(str(q.dimensionality), f"dimension {q.dimensionality}")


def parse_quantity(value: Any, dimension: str, path: str) -> float:
    """Return ``value`` in SI units as a float.

    ``value`` is a number (taken as SI) or a string with a unit (``"50 mm"``). The result must be finite;
    sign constraints are checked by the caller (so that messages can show the value as written).
    """
    dim = DIMENSIONS[dimension]
    if isinstance(value, bool):
        raise ModelError(f"{path}: expected {_expected(dim)}, got the boolean {str(value).lower()}")
    if isinstance(value, (int, float)):
        x = float(value)
    elif isinstance(value, str):
        x = _parse_string(value, dim, path)
    else:
        raise ModelError(f"{path}: expected {_expected(dim)}, got {_describe(value)}")
    if not math.isfinite(x):
        raise ModelError(f"{path}: must be finite, got {_show(value)}")
    return x


def _parse_string(text: str, dim: Dimension, path: str) -> float:
    import pint

    ureg = _registry()
    stripped = text.strip()
    if not stripped:
        raise ModelError(f"{path}: expected {_expected(dim)}, got an empty string")
    try:
        q = ureg.Quantity(stripped)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        raise ModelError(f"{path}: cannot read \"{text}\" as a quantity ({exc}); expected {_expected(dim)}") from None
    except Exception as exc:  # pint's tokenizer raises assorted errors on garbage
        raise ModelError(f"{path}: cannot read \"{text}\" as a quantity ({type(exc).__name__}); "
                         f"expected {_expected(dim)}") from None
    if not isinstance(q, ureg.Quantity):      # a bare number in a string, e.g. "3"
        q = ureg.Quantity(float(q))
    ok = q.dimensionless if dim.name == "dimensionless" else q.check(dim.pint)
    if not ok:
        raise ModelError(f"{path}: expected {_expected(dim)}, got \"{text}\" ({_dimension_name(q)})")
    target = "dimensionless" if dim.name == "dimensionless" else dim.pint
    mag = q.to(target).magnitude
    try:
        return float(mag)
    except (TypeError, ValueError):
        raise ModelError(f"{path}: expected a single value, got \"{text}\"") from None


def _expected(dim: Dimension) -> str:
    if dim.name == "dimensionless":
        return f"a pure number such as {dim.example}"
    return f"a {dim.name} such as \"{dim.example}\" (or a number in {dim.si})"


def _describe(value: Any) -> str:
    kinds = {list: "a list", dict: "a table", tuple: "a list"}
    return f"{kinds.get(type(value), type(value).__name__)} {_show(value)}"


def _show(value: Any) -> str:
    """The value as the user wrote it (strings quoted, numbers plain)."""
    text = f'"{value}"' if isinstance(value, str) else repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def show_as_written(value: Any) -> str:
    """A value for error messages: a unit string without quotes (``-5 mm``), numbers as they are."""
    return value.strip() if isinstance(value, str) else repr(value)


def check_sign(x: float, rule: str | None, value: Any, path: str) -> float:
    """Apply a sign rule ("positive", "non_negative" or None) to the SI value ``x`` of ``value``."""
    if rule == "positive" and not x > 0.0:
        raise ModelError(f"{path}: must be > 0, got {show_as_written(value)}")
    if rule == "non_negative" and not x >= 0.0:
        raise ModelError(f"{path}: must be >= 0, got {show_as_written(value)}")
    return x
