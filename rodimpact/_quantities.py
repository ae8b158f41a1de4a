"""Quantity strings (``"50 mm"``, ``"210 GPa"``) parsed by pint safely, and the error that names where a bad
value came from. A private base module: used by the model-file layer (:mod:`rodimpact.io.quantities`) and by the
Python API's unit handling (:mod:`rodimpact._units`), so it imports no layer of the package.

pint evaluates number powers exactly and its parser slows down with the square of the length, so strings are
checked first (:func:`_check_text`): at most :data:`MAX_QUANTITY_LENGTH` characters, powers only of units with
small plain exponents.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache


class ModelError(ValueError):
    """Bad input in a model file; the message starts with the key path (``rods[1].segments[2].diameter``).

    Values quoted in the message (``'...'`` or ``"..."``) longer than 80 characters are shortened, so that a
    hostile file cannot make the message itself huge."""

    def __init__(self, message: str = "") -> None:
        if isinstance(message, str) and len(message) > 300:
            message = _LONG_QUOTE.sub(lambda m: m.group()[:60] + "..." + m.group()[0] + f" ({len(m.group()):,} "
                                      f"characters)", message)
        super().__init__(message)


_LONG_QUOTE = re.compile(r"'[^'\n]{80,}'|\"[^\"\n]{80,}\"")


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
    Dimension("temperature", "K", "K", "293.15 K"),
    Dimension("voltage", "V", "V", "10 V"),
    Dimension("dimensionless", "dimensionless", "-", "0.3"),
    # after "stiffness" (the same unit): a unit string of N/m is still named "a stiffness" in messages
    Dimension("force per length", "N/m", "N/m", "60 kN/m"),
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


#: Longest quantity string accepted: pint's parser takes time growing with the square of the length.
MAX_QUANTITY_LENGTH = 200
#: Largest exponent accepted after ``**`` or ``^`` (units such as ``m^2``, ``kg/m^3``, ``m**-1``).
MAX_EXPONENT = 12
_POWER = re.compile(r"\*\*|\^")
_EXPONENT = re.compile(r"\s*([+-]?\s*(?:\d+(?:\.\d*)?|\.\d+))")


def _check_text(text: str, path: str, expected: str) -> str:
    """``text`` stripped, after checking that pint can parse it quickly and safely.

    pint evaluates number powers exactly (``10**10**10`` does not finish) and its parser slows down with the
    square of the length, so a quantity string is limited to :data:`MAX_QUANTITY_LENGTH` characters and a power
    (``**`` or ``^``) must raise a unit (or a parenthesised group of units) to a plain number of at most
    :data:`MAX_EXPONENT` in size; powers of numbers and towers of powers are refused.
    """
    stripped = text.strip()
    if not stripped:
        raise ModelError(f"{path}: expected {expected}, got an empty string")
    if len(stripped) > MAX_QUANTITY_LENGTH:
        raise ModelError(f"{path}: a quantity string may have at most {MAX_QUANTITY_LENGTH} characters, got "
                         f"{len(stripped):,}; expected {expected}")
    for m in _POWER.finditer(stripped):
        before = stripped[:m.start()].rstrip()
        base_ok = bool(before) and (before[-1].isalpha() or before[-1] in "_µμΩ°")
        if before.endswith(")"):
            depth, i = 0, len(before) - 1
            while i >= 0:
                depth += {")": 1, "(": -1}.get(before[i], 0)
                if depth == 0:
                    break
                i -= 1
            base_ok = i >= 0 and not any(c.isdigit() for c in before[i:])
        if not base_ok:
            raise ModelError(f"{path}: \"{_clip(stripped)}\": a power ({m.group()}) may only raise a unit, such as "
                             f"m^2; write numbers in e-notation (1e10, not 10**10); expected {expected}")
        ex = _EXPONENT.match(stripped, m.end())
        rest = stripped[ex.end():].lstrip() if ex else ""
        if ex is None or abs(float(ex.group(1).replace(" ", ""))) > MAX_EXPONENT or _POWER.match(rest):
            raise ModelError(f"{path}: \"{_clip(stripped)}\": a unit power needs a plain number exponent of at most "
                             f"{MAX_EXPONENT} (no towers such as m**2**3); expected {expected}")
    return stripped


def pint_quantity(text: str, path: str, expected: str = "a quantity such as \"50 mm\""):
    """``text`` parsed by pint (a Quantity; a bare number becomes a dimensionless one), after
    :func:`_check_text`; every failure is a :class:`ModelError` starting with ``path``."""
    import pint

    stripped = _check_text(text, path, expected)
    try:
        q = _pint_parse(stripped)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        raise ModelError(f"{path}: cannot read \"{_clip(stripped)}\" as a quantity ({_clip(str(exc))}); "
                         f"expected {expected}") from None
    except OverflowError:
        raise ModelError(f"{path}: \"{_clip(stripped)}\" is too large a number; expected {expected}") from None
    except Exception as exc:  # pint's tokenizer raises assorted errors on garbage
        raise ModelError(f"{path}: cannot read \"{_clip(stripped)}\" as a quantity ({type(exc).__name__}); "
                         f"expected {expected}") from None
    return q


@lru_cache(maxsize=4096)
def _pint_parse(text: str):
    """pint's parse of a checked quantity string (cached: model files repeat their units, and parsing takes
    about a millisecond)."""
    ureg = _registry()
    q = ureg.Quantity(text)
    return q if isinstance(q, ureg.Quantity) else ureg.Quantity(float(q))    # a bare number, e.g. "3"


def si_magnitude(q, target: str, text: str, path: str, expected: str) -> float:
    """The magnitude of pint quantity ``q`` in ``target`` units (or SI base units if ``target`` is ``None``) as a
    finite float; overflow and non-finite values are :class:`ModelError`."""
    try:
        mag = q.to_base_units().magnitude if target is None else q.to(target).magnitude
        x = float(mag)
    except OverflowError:
        x = math.inf
    except (TypeError, ValueError):
        raise ModelError(f"{path}: expected a single value, got \"{_clip(text.strip())}\"") from None
    if not math.isfinite(x):
        raise ModelError(f"{path}: must be finite, got \"{_clip(text.strip())}\" (out of the range of floating "
                         f"point numbers); expected {expected}")
    return x


def _clip(text: str, n: int = 80) -> str:
    return text if len(text) <= n else text[:n - 3] + "..."
