"""Stepped strikers: at most K constant-impedance steps (machinable as K cylinders).

1. The free optimum Z is segmented optimally into <= K contiguous groups (least squares in Z, by dynamic
   programming: :func:`~rodimpact.design.optimize.segment`).
2. The K levels are re-optimised with the chained gradient dJ/du_i = sum over the group of dJ/dZ_q
   (L-BFGS-B, mass and bounds as for the free profile).
3. Local search of the breakpoints: each breakpoint is moved by one element either way while that lowers the
   objective (levels kept, projected onto the mass), then the levels are re-optimised once more.
"""

from __future__ import annotations

from dataclasses import dataclass


import numpy as np

from .constraints import Constraints
from .optimize import Evaluator, Levels, Run, minimise, segment

#: passes of the breakpoint local search
SEARCH_PASSES = 3


@dataclass
class SteppedRun:
    impedance: np.ndarray
    breaks: np.ndarray
    run: Run


def _levels_for(z: np.ndarray, breaks: np.ndarray) -> np.ndarray:
    return np.add.reduceat(z, breaks[:-1]) / np.diff(breaks)


def stepped_design(ev: Evaluator, cons: Constraints, z_free: np.ndarray, v: float, k: int, *,
                   max_iterations: int, tolerance: float) -> SteppedRun:
    """A striker of at most ``k`` steps near the free optimum ``z_free`` (see the module docstring)."""
    breaks = segment(z_free, k)
    lv = Levels.stepped(cons, breaks)
    run = minimise(ev, cons, lv, lv.project(_levels_for(z_free, breaks), cons), v, max_iterations=max_iterations,
                   tolerance=tolerance)
    best_val, best_breaks, best_u = run.value, breaks, run.levels
    for _ in range(SEARCH_PASSES):
        improved = False
        for i in range(1, best_breaks.size - 1):
            for shift in (-1, 1):
                b = best_breaks.copy()
                b[i] += shift
                if not b[i - 1] < b[i] < b[i + 1]:
                    continue
                try:
                    trial = Levels.stepped(cons, b)
                except ValueError:
                    continue
                u = trial.project(np.clip(best_u, trial.lower, trial.upper), cons)
                val, _ = ev.value(trial.expand(u), run.velocity)
                if val < best_val:
                    best_val, best_breaks, best_u, improved = val, b, u, True
        if not improved:
            break
    if best_breaks is not breaks:
        lv = Levels.stepped(cons, best_breaks)
        again = minimise(ev, cons, lv, best_u, run.velocity, max_iterations=max_iterations, tolerance=tolerance)
        again.iterations += run.iterations
        again.history = run.history + again.history
        run = again
    return SteppedRun(lv.expand(run.levels), best_breaks, run)


