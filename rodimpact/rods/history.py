"""Time histories for prescribed end forces, end velocities and nodal loads."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Literal, Optional

import numpy as np

from .._units import is_quantity
from .._validate import finite, finite_array


@dataclass(frozen=True, eq=False)
class History:
    """A scalar function of time, given as a constant, a callable ``f(t)`` or samples ``(t, values)``.

    The solver keeps every prescribed quantity constant during a time step (thesis Sec. 3.1: "external forces
    may change in time but are constant during one time step") and takes the value at the step's midpoint
    ``(k + 1/2) dt``. A history that is itself piecewise constant with jumps on multiples of ``dt`` is
    therefore applied exactly.

    Samples are interpolated linearly (``interpolation="linear"``) or held from the last sample at or before
    ``t`` (``"previous"``, a zero-order hold); before the first and after the last sample the end values
    are held.

    With a ``unit`` (the SI unit of the values, e.g. ``"N"``), a constant may also be a unit string or a pint
    Quantity (``"-5 kN"``), and samples may carry units (times in s).
    """

    source: Any
    interpolation: Literal["linear", "previous"] = "linear"
    quantity: str = "history"
    unit: str = ""

    def __post_init__(self) -> None:
        if self.interpolation not in ("linear", "previous"):
            raise ValueError(f"{self.quantity}.interpolation: must be 'linear' or 'previous', "
                             f"got {self.interpolation!r}")
        src = self.source
        if self.unit and (isinstance(src, str) or is_quantity(src)):
            src = finite(self.quantity, src, self.unit)
            object.__setattr__(self, "source", src)
        if callable(src):
            return
        if isinstance(src, (int, float, np.integer, np.floating)) and not isinstance(src, bool):
            finite(self.quantity, src)
            return
        if isinstance(src, (tuple, list)) and len(src) == 2:
            t = finite_array(f"{self.quantity} time samples", src[0], unit="s" if self.unit else "")
            y = finite_array(f"{self.quantity} values", src[1], unit=self.unit)
            if t.shape != y.shape:
                raise ValueError(f"{self.quantity}: time samples ({t.size}) and values ({y.size}) differ in length")
            if np.any(np.diff(t) < 0):
                i = int(np.flatnonzero(np.diff(t) < 0)[0])
                raise ValueError(f"{self.quantity}: time samples must be non-decreasing; t[{i + 1}] = {t[i + 1]} "
                                 f"< t[{i}] = {t[i]}")
            object.__setattr__(self, "source", (t, y))
            return
        raise TypeError(f"{self.quantity}: give a number, a callable f(t) or a pair (t_samples, values); "
                        f"got {type(src).__name__}")

    def __call__(self, t: np.ndarray) -> np.ndarray:
        t = np.asarray(t, dtype=float)
        src = self.source
        if callable(src):
            y = np.broadcast_to(np.asarray(src(t), dtype=float), t.shape).astype(float)
        elif isinstance(src, tuple):
            ts, ys = src
            if self.interpolation == "linear":
                y = np.interp(t, ts, ys)
            else:
                i = np.clip(np.searchsorted(ts, t, side="right") - 1, 0, ts.size - 1)
                y = ys[i]
        else:
            y = np.full(t.shape, float(src))
        if not np.all(np.isfinite(y)):
            i = int(np.flatnonzero(~np.isfinite(y))[0])
            raise ValueError(f"{self.quantity}: evaluates to {float(y[i])} at t = {t[i]:.6g} s; it must be finite")
        return y

    def step_values(self, n_steps: int, dt: float, first_step: int = 0) -> np.ndarray:
        """Values for steps ``first_step .. first_step + n_steps - 1``, taken at the step midpoints."""
        return self((np.arange(first_step, first_step + n_steps) + 0.5) * dt)


def as_history(value: Any, quantity: str, interpolation: str = "linear", unit: str = "") -> Optional[History]:
    """Wrap ``value`` into a :class:`History` (``None`` stays ``None``); ``unit``: the SI unit of its values."""
    if value is None or isinstance(value, History):
        return value
    return History(value, interpolation, quantity, unit)  # type: ignore[arg-type]


HistoryLike = History | float | Callable[[np.ndarray], np.ndarray] | tuple
