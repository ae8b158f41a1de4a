"""Screening of starting profiles for :func:`~rodimpact.design`: many candidates, one batched run.

A gradient-based optimiser goes to the nearest local optimum, so where it starts matters. Before any gradient
is taken, a pool of candidate strikers (the named starts of :func:`~rodimpact.design` plus uniform strikers at
a ladder of impedances and smooth random variations of each named start, all projected onto the constraints)
is simulated in one compiled call of :func:`rodimpact.simulate_batch` (numba threads over the designs), and
the optimiser starts from the candidates with the best objective values. Each candidate's run equals
:func:`rodimpact.simulate`'s bit for bit, and its objective is evaluated from the batch's outputs exactly as
from a forward run of :class:`~rodimpact.design._adjoint.ImpactProblem`:

* ``match`` at the impact face: the contact force history (junction 0, tension positive) is the observed
  history ``fw.observed``;
* ``efficiency``: the work done on the rock W = -dt sum_k N_k w_k (N_k the far-end force, w_k its outward
  velocity) is minus the batch's ``work_right`` (the work done on the rods by the far end).

A force observed inside the struck system (``position``) is not among the batch's outputs; there the named
starts are used as they are.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..direct.batch import BatchOutputs, simulate_batch
from ..direct.problem import TimeGrid
from ..inverse.struck import with_striker
from ..rods.rod import Rod
from .constraints import Constraints
from .objectives import EfficiencyObjective, MatchObjective
from .optimize import TV_EPSILON, total_variation

#: candidates simulated per design (named starts, a ladder of uniform strikers, random smooth variations)
POOL_SIZE = 64
#: uniform strikers in the pool; cosine modes and relative amplitude of the random variations of a named start
LADDER, MODES, AMPLITUDE = 8, 4, 0.3


@dataclass(frozen=True)
class Screened:
    """The candidates ranked by objective value (best first)."""

    names: list[str]
    impedance: list[np.ndarray]     # face first, N s/m
    values: np.ndarray              # objective value + smoothness penalty of each, ranked


def candidate_pool(named: list[tuple[str, np.ndarray]], cons: Constraints, size: int = POOL_SIZE,
                   seed: int = 0) -> list[tuple[str, np.ndarray]]:
    """The named starts, uniform strikers at impedances spaced evenly in log between the bounds' extremes, and
    smooth random variations Z (1 + sum_k a_k cos(k pi x)), |a_k| <= AMPLITUDE / k, of the named starts; all
    projected onto the constraints and different from each other (a projection can map two candidates onto
    one, e.g. uniform strikers onto the mass bound), ``size`` in all where that many can be drawn. The random
    draws come from a fixed seed, so a design is reproducible."""
    pool: list[tuple[str, np.ndarray]] = []

    def add(name: str, z: np.ndarray) -> None:
        z = cons.project(z)
        if len(pool) < size and not any(np.allclose(z, o, rtol=1e-9, atol=0.0) for _, o in pool):
            pool.append((name, z))

    for name, z in named:
        add(name, z)
    n = cons.lower.size
    lo, hi = float(np.min(cons.lower)), float(np.max(cons.upper))
    for z in np.geomspace(lo, hi, LADDER + 2)[1:-1]:
        add(f"uniform {z:.4g} N s/m", np.full(n, z))
    rng = np.random.default_rng(seed)
    x = (np.arange(n) + 0.5) / n
    k = np.arange(1, MODES + 1)
    shapes = np.cos(np.pi * k[:, None] * x[None, :])
    for i in range(4 * size if named else 0):
        if len(pool) == size:
            break
        name, z = named[i % len(named)]
        a = rng.uniform(-AMPLITUDE, AMPLITUDE, MODES) / k
        add(f"{name}, varied", z * np.maximum(1.0 + a @ shapes, 0.05))
    return pool


def screen(struck: Any, dt: float, steps: int, objective: MatchObjective | EfficiencyObjective,
           pool: list[tuple[str, np.ndarray]], velocity: float, smoothness: float, z_ref: float) -> Screened:
    """Objective values (plus the smoothness penalty of :class:`~rodimpact.design.optimize.Evaluator`) of every
    candidate of ``pool`` (face first) from one :func:`rodimpact.simulate_batch` call of ``steps`` steps,
    ranked. A ``match`` objective must observe the impact face."""
    names = [name for name, _ in pool]
    zs = np.array([z for _, z in pool])
    n = zs.shape[1]
    template = with_striker(struck, Rod.from_impedance(np.ones(n), dt=dt), 1.0)
    batch = simulate_batch(template, zs[:, ::-1], np.full(zs.shape[0], velocity), TimeGrid.of(steps=steps, dt=dt),
                           outputs=BatchOutputs(contact_force=isinstance(objective, MatchObjective)))
    if isinstance(objective, MatchObjective):
        values = np.array([objective.evaluate(_Observed(row), z, velocity)[0]
                           for row, z in zip(batch.contact_force, zs)])
    else:
        kinetic = 0.5 * dt * zs.sum(axis=1) * velocity * velocity       # m v^2 / 2, m = dt sum Z
        values = batch.work_right / kinetic                             # -eta, eta = (-work_right) / E_k
    if smoothness > 0.0 and n > 1:
        values = values + smoothness * np.array([total_variation(z / z_ref, TV_EPSILON)[0] for z in zs])
    order = np.argsort(values, kind="stable")
    return Screened([names[i] for i in order], [zs[i] for i in order], values[order])


@dataclass(frozen=True)
class _Observed:
    """The part of a forward run a face match reads: the observed (contact) force history, N."""

    observed: np.ndarray
