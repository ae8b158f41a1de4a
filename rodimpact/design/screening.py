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
from .objectives import EfficiencyCost, MatchCost
from .optimize import TV_EPSILON, total_variation

#: candidates simulated per design (named starts, a ladder of uniform strikers, four families of random profiles)
POOL_SIZE = 4096
#: uniform strikers in the pool; cosine modes and relative amplitude of the random variations of a named start
LADDER, MODES, AMPLITUDE = 8, 4, 0.3
#: standard deviation of the first cosine mode of log Z in the log-smooth family (mode k: / k)
LOG_AMPLITUDE = 1.0


@dataclass(frozen=True)
class Screened:
    """The candidates ranked by objective value (best first)."""

    names: list[str]
    impedance: list[np.ndarray]     # face first, N s/m
    values: np.ndarray              # objective value + smoothness penalty of each, ranked


def candidate_pool(named: list[tuple[str, np.ndarray]], cons: Constraints, size: int = POOL_SIZE,
                   seed: int = 0) -> list[tuple[str, np.ndarray]]:
    """The named starts, uniform strikers at impedances spaced evenly in log between the bounds' extremes, and
    four families of random profiles in equal numbers (x = (q - 1/2) / n from the impact face, Z_lo and Z_hi the
    extreme bounds, a peak Z_p drawn log-uniformly between them):

    * *varied*: smooth variations Z (1 + sum_k a_k cos(k pi x)), |a_k| <= AMPLITUDE / k, of the named starts;
    * *log-smooth*: Z_p exp(sum_k a_k cos(k pi x)), a_k normal with deviation LOG_AMPLITUDE / k, k = 1..5;
    * *bump*: Z_lo + (Z_p - Z_lo) sin(pi min(x / L, 1))^p: a hump over a fraction L of the striker, the rest at
      the thin bound (good optima of a force that rises from and falls to 0 N look like this);
    * *ramp*: a linear rise from Z_lo over [0, a), a plateau at Z_p up to L, the thin bound after.

    All are projected onto the constraints and different from each other (a projection can map two candidates
    onto one, e.g. uniform strikers onto the mass bound), ``size`` in all where that many can be drawn. The
    random draws come from a fixed seed, so a design is reproducible."""
    pool: list[tuple[str, np.ndarray]] = []
    seen: set[bytes] = set()

    def add(name: str, z: np.ndarray) -> None:
        z = cons.project(z)
        key = np.round(np.log(np.maximum(z, 1e-300)), 9).tobytes()    # equal to ~1e-9 relative: a duplicate
        if len(pool) < size and key not in seen:
            seen.add(key)
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
    k5 = np.arange(1, 6)
    shapes5 = np.cos(np.pi * k5[:, None] * x[None, :])
    for i in range(4 * size):
        if len(pool) >= size:
            break
        family = i % 4 if named else 1 + i % 3
        peak = float(np.exp(rng.uniform(np.log(lo), np.log(hi))))
        length = rng.uniform(0.2, 1.0)
        if family == 0:
            name, z = named[(i // 4) % len(named)]
            a = rng.uniform(-AMPLITUDE, AMPLITUDE, MODES) / k
            add(f"{name}, varied", z * np.maximum(1.0 + a @ shapes, 0.05))
        elif family == 1:
            a = rng.normal(0.0, LOG_AMPLITUDE, k5.size) / k5
            add("log-smooth random", peak * np.exp(a @ shapes5))
        elif family == 2:
            p = rng.uniform(0.3, 3.0)
            add("bump, thin tail", lo + (peak - lo) * np.sin(np.pi * np.minimum(x / length, 1.0)) ** p)
        else:
            a = rng.uniform(0.0, length)
            z = np.where(x < a, lo + (peak - lo) * x / max(a, 1e-12), peak)
            add("ramp and plateau, thin tail", np.where(x < length, z, lo))
    return pool


def diverse(profiles: list[tuple[str, np.ndarray]], count: int, distance: float = 0.02) -> list[tuple[str, np.ndarray]]:
    """The first ``count`` of ``profiles`` (ranked) that differ from every one taken before by more than
    ``distance`` in root-mean-square log impedance, filled up with the next ranked ones if too few differ."""
    out: list[tuple[str, np.ndarray]] = []
    logs: list[np.ndarray] = []
    for name, z in profiles:
        if len(out) == count:
            break
        lz = np.log(z)
        if all(np.sqrt(np.mean((lz - o) ** 2)) > distance for o in logs):
            out.append((name, z))
            logs.append(lz)
    for name, z in profiles:
        if len(out) == count:
            break
        if not any(z is o for _, o in out):
            out.append((name, z))
    return out


def screen(struck: Any, dt: float, steps: int, objective: MatchCost | EfficiencyCost,
           pool: list[tuple[str, np.ndarray]], velocity: float, smoothness: float, z_ref: float) -> Screened:
    """Objective values (plus the smoothness penalty of :class:`~rodimpact.design.optimize.Evaluator`) of every
    candidate of ``pool`` (face first) from one :func:`rodimpact.simulate_batch` call of ``steps`` steps,
    ranked. A ``match`` objective must observe the impact face."""
    names = [name for name, _ in pool]
    zs = np.array([z for _, z in pool])
    n = zs.shape[1]
    template = with_striker(struck, Rod.from_impedance(np.ones(n), dt=dt), 1.0)
    batch = simulate_batch(template, zs[:, ::-1], np.full(zs.shape[0], velocity), TimeGrid.of(steps=steps, dt=dt),
                           outputs=BatchOutputs(contact_force=isinstance(objective, MatchCost)))
    if isinstance(objective, MatchCost):
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
