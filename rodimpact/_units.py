"""Physical quantities with units in the Python API: ``"300 mm"``, ``"210 GPa"`` or a :mod:`pint` Quantity.

Bare numbers stay SI. A string or a pint Quantity is converted to the SI unit the argument expects, with the
same safe pint parsing as model files (:mod:`rodimpact._quantities`); a quantity of the wrong dimension is a
``ValueError`` naming the argument, e.g. ``Cylinder.diameter: expected a quantity in m, got "5 kg" (a mass)``;
a string that is not a quantity with a unit (``"twenty"``, ``"20"``) is a ``TypeError`` as any non-number is.
"""

from __future__ import annotations

import math
from typing import Any, Optional

from ._quantities import _clip


def is_quantity(value: Any) -> bool:
    """True for a pint Quantity of any registry (without importing pint)."""
    return type(value).__module__.split(".")[0] == "pint" and hasattr(value, "magnitude") and hasattr(value, "to")


def to_si(name: str, value: Any, unit: str) -> Optional[float]:
    """``value`` (a unit string or a pint Quantity) in ``unit`` (an SI unit expression such as ``"m"``,
    ``"N s/m"``, ``"kg/m^3"``) as a float; ``None`` when ``value`` is neither (the caller checks numbers) or
    ``unit`` is not a pint unit expression."""
    if not unit or not (isinstance(value, str) or is_quantity(value)):
        return None
    import pint

    from ._quantities import _check_text, _dimension_name, _pint_parse, _registry

    ureg = _registry()
    try:
        target = ureg.Quantity(1.0, unit.replace("^", "**"))
    except Exception:  # the unit is a description pint cannot read: no conversion
        return None
    if isinstance(value, str):
        text = _check_text(value, name, f"a quantity in {unit}")     # length and power limits (never hangs)
        try:
            q = _pint_parse(text)
        except Exception:  # pint's tokenizer raises assorted errors on garbage
            q = None
        if q is None or (q.dimensionless and not target.dimensionless):
            raise TypeError(f"{name}: must be a real number in {unit} or a quantity such as \"1 {unit}\", got str "
                            f"{_clip(value)!r}")
        shown = f"\"{_clip(value.strip())}\""
    else:
        q, shown = value, f"{value:~P}"
    try:
        mag = q.to(unit.replace("^", "**")).magnitude
    except pint.errors.DimensionalityError:
        raise ValueError(f"{name}: expected a quantity in {unit}, got {shown} ({_dimension_name(q)})") from None
    try:
        x = float(mag)
    except OverflowError:
        x = math.inf
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected a single value in {unit}, got {shown}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}: must be finite, got {shown} (out of the range of floating point numbers)")
    return x


def array_to_si(name: str, values: Any, unit: str) -> Any:
    """``values`` with a pint Quantity array, or entries that are unit strings or Quantities, converted to
    ``unit`` (a float array); anything else is returned as it is for the caller's checks."""
    if not unit:
        return values
    if is_quantity(values):
        import pint

        try:
            return values.to(unit.replace("^", "**")).magnitude
        except pint.errors.DimensionalityError:
            from ._quantities import _dimension_name

            raise ValueError(f"{name}: expected quantities in {unit}, got {values.units:~P} "
                             f"({_dimension_name(values)})") from None
    if isinstance(values, (list, tuple)) and any(isinstance(v, str) or is_quantity(v) for v in values):
        return [v if (c := to_si(f"{name}[{i}]", v, unit)) is None else c for i, v in enumerate(values)]
    return values
