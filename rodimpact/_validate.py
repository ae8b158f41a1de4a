"""Small input checks shared by the model classes.

Every check raises ``ValueError``/``TypeError`` whose message names the quantity and says what would be valid,
so that bad input never reaches the numerical kernels as NaN.
"""

from __future__ import annotations

import math
import numbers
import os
import sys
from typing import Any

import numpy as np

from ._units import array_to_si, to_si

_PACKAGE = os.path.dirname(os.path.abspath(__file__))


def positive(name: str, value: Any, unit: str = "") -> float:
    """Return ``value`` as a float after checking it is a finite number > 0."""
    x = finite(name, value, unit)
    if x <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {value!r}{_unit(unit)}")
    return x


def non_negative(name: str, value: Any, unit: str = "") -> float:
    """Return ``value`` as a float after checking it is a finite number >= 0."""
    x = finite(name, value, unit)
    if x < 0.0:
        raise ValueError(f"{name}: must be >= 0, got {value!r}{_unit(unit)}")
    return x


def finite(name: str, value: Any, unit: str = "") -> float:
    """Return ``value`` as a float after checking it is a finite real number; with a ``unit`` (SI), a unit
    string (``"300 mm"``) or a pint Quantity is converted to it (:func:`rodimpact._units.to_si`)."""
    if type(value) is float and math.isfinite(value):       # the common case, without the conversions below
        return value
    converted = to_si(name, value, unit)
    if converted is not None:
        value = converted
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: must be a real number{_unit(unit, ' in ')}, got {type(value).__name__} {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ValueError(f"{name}: must be finite, got {value!r}")
    return x


def integer(name: str, value: Any, minimum: int, what: str = "") -> int:
    """Return ``value`` as an int after checking it is an integer (not a bool) >= ``minimum``; ``what`` (what the
    number counts) is said in the message."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < minimum:
        raise ValueError(f"{name}: must be an integer >= {minimum}{f' ({what})' if what else ''}, got {value!r}")
    return int(value)


def real_number(name: str, value: Any, valid: str, ok: Any) -> float:
    """``value`` as a float if it is a real number (int or float, not bool, no string or sequence coerced),
    finite and ``ok(value)``; otherwise a TypeError (wrong type) or ValueError (wrong value) naming ``name`` and
    saying what is ``valid``."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name}: must be {valid}, got {type(value).__name__} {value!r}")
    x = float(value)
    if not (np.isfinite(x) and ok(x)):
        raise ValueError(f"{name}: must be {valid}, got {value!r}")
    return x


def finite_array(name: str, values: Any, *, ndim: int = 1, min_size: int = 1, unit: str = "") -> np.ndarray:
    """Return ``values`` as a float array after checking shape and finiteness; with a ``unit`` (SI), a pint
    Quantity array or entries given as unit strings / Quantities are converted to it."""
    values = array_to_si(name, values, unit)
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name}: must be an array of real numbers ({exc})") from None
    if arr.ndim != ndim:
        raise ValueError(f"{name}: must be {ndim}-dimensional, got shape {arr.shape}")
    if arr.size < min_size:
        raise ValueError(f"{name}: needs at least {min_size} value(s), got {arr.size}")
    bad = ~np.isfinite(arr)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"{name}: must be finite, entry {i} is {arr.ravel()[i]!r}")
    return arr


def positive_array(name: str, values: Any, *, min_size: int = 1, unit: str = "") -> np.ndarray:
    """Return a 1-d float array after checking every entry is finite and > 0 (``unit``: as :func:`finite_array`)."""
    arr = finite_array(name, values, min_size=min_size, unit=unit)
    if (arr <= 0).any():
        i = int(np.flatnonzero(arr <= 0)[0])
        raise ValueError(f"{name}: every entry must be > 0, entry {i} is {arr[i]!r}")
    return arr


def _unit(unit: str, sep: str = " ") -> str:
    return f"{sep}{unit}" if unit else ""


#: allocations up to this size (bytes) are not checked against the installed memory
_SMALL_ALLOCATION = 8.0 * 2**20


def physical_memory() -> float | None:
    """Installed memory in bytes (psutil on every platform, else POSIX ``sysconf``), or ``None`` where neither
    can read it."""
    try:
        import psutil

        return float(psutil.virtual_memory().total)
    except Exception:    # psutil missing or unable to read the platform's numbers
        pass
    try:
        return float(os.sysconf("SC_PAGE_SIZE")) * float(os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, OSError, ValueError):
        return None


def fits_in_memory(name: str, n_bytes: float, what: str, hint: str = "") -> None:
    """Raise ``ValueError`` naming ``name`` if an allocation of ``n_bytes`` for ``what`` cannot fit in this machine's
    memory (so that the user gets a message instead of a MemoryError deep in numpy or the process being killed)."""
    if n_bytes <= _SMALL_ALLOCATION:       # no need to ask the operating system (it costs ~0.1 ms)
        return
    total = physical_memory()
    if total is not None and n_bytes > 0.8 * total:
        raise ValueError(f"{name}: {what} would need {n_bytes / 2**30:.3g} GiB, more than this machine's memory "
                         f"({total / 2**30:.3g} GiB)" + (f"; {hint}" if hint else ""))


def finite_values(name: str, values: Any, what: str, max_ndim: int | None = None) -> np.ndarray:
    """``values`` (a number or an array of any shape, or at most ``max_ndim`` dimensions) as a float array of the
    same shape after checking that it holds at least one value, all real and finite; ``what`` describes them
    (e.g. "times (s)") for the error messages, which name ``name``."""
    try:
        arr = np.asarray(values)
        if arr.dtype.kind == "O":  # e.g. a list of Fractions (None would become nan: refused)
            if not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in arr.ravel()):
                raise TypeError
            arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.dtype.kind not in "iuf":
        text = repr(values)
        text = text if len(text) <= 60 else text[:57] + "..."
        raise TypeError(f"{name}: {what} must be real numbers, got {type(values).__name__} {text}")
    if max_ndim is not None and arr.ndim > max_ndim:
        raise ValueError(f"{name}: {what} must be a number or a {max_ndim}-d array, got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{name}: got an empty array of shape {arr.shape}; give at least one value ({what})")
    arr = arr.astype(float)
    bad = ~np.isfinite(arr)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        where = f", entry {i} is" if arr.ndim else ", got"
        raise ValueError(f"{name}: {what} must be finite{where} {float(arr.ravel()[i])!r}")
    return arr


def caller_stacklevel() -> int:
    """The ``stacklevel`` for a ``warnings.warn`` in the function that calls this one: that of the first frame
    outside rodimpact, skipping dataclass-generated ``__init__`` methods, so that warnings point at the user's line."""
    frame, level = sys._getframe(2), 2
    while frame is not None and (frame.f_code.co_filename.startswith(_PACKAGE)
                                 or (frame.f_code.co_filename == "<string>" and frame.f_code.co_name == "__init__")):
        frame, level = frame.f_back, level + 1
    return level
