"""Physical quantities in model files: ``"50 mm"``, ``"210 GPa"``, ``"4.6 m/s"`` or bare numbers (SI).

Every quantity is converted once, here, to a float in SI base units (m, s, kg, N, Pa, N s/m, ...); the rest
of the package never sees units. Unit strings are parsed by :mod:`pint` (its own tokenizer, never Python
``eval``). A string whose dimension does not match the expected one is an error naming the key path, the
value and what would be valid, e.g. ``rods[0].segments[1].diameter: expected a length such as "50 mm" (or a
number in m), got "5 kg" (a mass)``.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from typing import Any, Optional

from .._quantities import (DIMENSIONS, MAX_EXPONENT, MAX_QUANTITY_LENGTH, Dimension, ModelError,  # noqa: F401
                           _check_text, _clip, _dimension_name, _registry, pint_quantity, si_magnitude)


def parse_quantity(value: Any, dimension: str, path: str) -> float:
    """Return ``value`` in SI units as a float.

    ``value`` is a number (taken as SI) or a string with a unit (``"50 mm"``). The result must be finite;
    sign constraints are checked by the caller (so that messages can show the value as written).
    """
    dim = DIMENSIONS[dimension]
    if isinstance(value, bool):
        raise ModelError(f"{path}: expected {_expected(dim)}, got the boolean {str(value).lower()}")
    if isinstance(value, (int, float)):
        try:
            x = float(value)
        except OverflowError:          # an integer beyond the float range
            x = math.inf
    elif isinstance(value, str):
        x = _parse_string(value, dim, path)
    else:
        raise ModelError(f"{path}: expected {_expected(dim)}, got {_describe(value)}")
    if not math.isfinite(x):
        raise ModelError(f"{path}: must be finite, got {_show(value)}")
    return x


#: "<number> <unit>": a plain decimal number, whitespace, then a unit made of names, ``*``, ``/``, spaces and
#: integer powers (no numbers of its own, so that pint's evaluation order cannot differ from number * factor)
_NUMBER_UNIT = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s+"
                          r"((?:[A-Za-zµμΩ_]+(?:\s*(?:\*\*|\^)\s*-?\d+)?)"
                          r"(?:\s*[*/ ]\s*[A-Za-zµμΩ_]+(?:\s*(?:\*\*|\^)\s*-?\d+)?)*)\s*")


@lru_cache(maxsize=1024)
def _unit_factor(unit: str, dimension: str) -> Optional[float]:
    """The factor that converts a number in ``unit`` to the SI unit of ``dimension`` (pint's own conversion of
    ``1 unit``), or ``None`` where the fast path must not be used (unknown unit, wrong dimension, offset
    units such as degC): the full parse then gives the error message or the value."""
    dim = DIMENSIONS[dimension]
    try:
        q = _registry().Quantity("1 " + unit)
        ureg = _registry()
        if not isinstance(q, ureg.Quantity) or not q._is_multiplicative:
            return None
        ok = q.dimensionless if dim.name == "dimensionless" else q.check(dim.pint)
        if not ok:
            return None
        factor = float(q.to("dimensionless" if dim.name == "dimensionless" else dim.pint).magnitude)
    except Exception:        # anything unusual: the full parse decides
        return None
    return factor if math.isfinite(factor) and factor > 0.0 else None


def _parse_string(text: str, dim: Dimension, path: str) -> float:
    # Fast path (model files repeat a few units over arrays of 10^5 values; pint's conversion costs ~0.1 ms a
    # value): number * the cached factor of its unit, the same product pint's conversion computes (equal bit for
    # bit, tests/io/test_model_scaling.py). Anything else, and every error, takes pint's full parse below.
    m = _NUMBER_UNIT.fullmatch(text) if len(text) <= MAX_QUANTITY_LENGTH else None
    if m is not None:
        factor = _unit_factor(m.group(2), dim.name)
        if factor is not None:
            x = float(m.group(1)) * factor
            if math.isfinite(x):
                return x
    q = pint_quantity(text, path, _expected(dim))
    ok = q.dimensionless if dim.name == "dimensionless" else q.check(dim.pint)
    if not ok:
        raise ModelError(f"{path}: expected {_expected(dim)}, got \"{_clip(text.strip())}\" ({_dimension_name(q)})")
    return si_magnitude(q, "dimensionless" if dim.name == "dimensionless" else dim.pint, text, path, _expected(dim))


def _expected(dim: Dimension) -> str:
    if dim.name == "dimensionless":
        return f"a pure number such as {dim.example}"
    return f"a {dim.name} such as \"{dim.example}\" (or a number in {dim.si})"


def _describe(value: Any) -> str:
    kinds = {list: "a list", dict: "a table", tuple: "a list"}
    return f"{kinds.get(type(value), type(value).__name__)} {_show(value)}"


def _show(value: Any) -> str:
    """The value as the user wrote it (strings quoted, numbers plain)."""
    text = f'"{value}"' if isinstance(value, str) else _repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _repr(value: Any) -> str:
    """``repr(value)`` that never fails: huge integers and deeply nested lists give a short description."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > 10**80:
        return f"an integer of about {len(str(value)) if value.bit_length() < 10_000 else 'many'} digits"
    if isinstance(value, (list, dict)):
        try:
            return _clip(repr(value), 200)
        except (RecursionError, ValueError):
            return f"a deeply nested {'list' if isinstance(value, list) else 'table'}"
    return repr(value)


def show_as_written(value: Any) -> str:
    """A value for error messages: a unit string without quotes (``-5 mm``), numbers as they are."""
    return _clip(value.strip()) if isinstance(value, str) else _clip(_repr(value))


def check_sign(x: float, rule: str | None, value: Any, path: str) -> float:
    """Apply a sign rule ("positive", "non_negative" or None) to the SI value ``x`` of ``value``."""
    if rule == "positive" and not x > 0.0:
        raise ModelError(f"{path}: must be > 0, got {show_as_written(value)}")
    if rule == "non_negative" and not x >= 0.0:
        raise ModelError(f"{path}: must be >= 0, got {show_as_written(value)}")
    return x
