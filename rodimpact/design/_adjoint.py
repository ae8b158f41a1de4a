"""STAND-IN for the forward model and adjoint gradient of striker design (replaced by the real engine at merge).

Same interface as the adjoint engine: :class:`ImpactProblem` runs the striker (impedances Z_1..Z_n from the
impact face, travel time dt each) against the struck system with :func:`rodimpact.simulate`; the gradient is
taken by central finite differences (2 n + 2 forward runs), which is slow and only for development.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..direct.simulate import simulate
from ..inverse.struck import Location, position_probe, position_quantity, with_striker
from ..rods.rod import Rod
from ..rods.system import System


@dataclass(frozen=True)
class Forward:
    """Histories of one forward run, one value per step (forces N tension positive, velocities m/s)."""

    face_force: np.ndarray
    observed: np.ndarray
    end_force: np.ndarray
    end_velocity: np.ndarray
    contact: np.ndarray
    striker_mass: float
    impedance: np.ndarray
    velocity: float


class ImpactProblem:
    """A striker of ``n`` elements against ``struck`` for ``steps`` steps of ``dt`` (stand-in implementation)."""

    def __init__(self, struck: System, dt: float, n: int, steps: int, *, location: Optional[Location] = None,
                 quantity: str = "force", backend: str = "numba", checkpoint_every: Optional[int] = None) -> None:
        self.struck, self.dt, self.n, self.steps = struck, float(dt), int(n), int(steps)
        self.location, self.quantity, self.backend = location, quantity, backend

    def forward(self, impedance: np.ndarray, velocity: float) -> Forward:
        z = np.asarray(impedance, dtype=float)
        system = with_striker(self.struck, Rod.from_impedance(z[::-1], dt=self.dt), float(velocity))
        loc = self.location
        probes = [] if loc is None else [position_probe(loc, 1)]
        snaps = [0.0] if (loc is not None and self.quantity == "incident") else None
        sim = simulate(system, steps=self.steps, dt=self.dt, backend=self.backend, probes=probes,
                       snapshot_times=snaps)
        face = np.asarray(sim.junction_force[0], dtype=float)
        observed = face
        if loc is not None:
            p = sim.probe("synthesis_position")
            k_left = sim.lattice.rod_start[1] + loc.element_left
            n0 = v0 = 0.0
            if self.quantity == "incident":
                n0 = float(sim.snapshots.force[k_left, 0])
                v0 = float(sim.snapshots.velocity[k_left, 0])
            observed = np.asarray(position_quantity(self.quantity, p.force, p.velocity,
                                                    float(sim.lattice.impedance[k_left]), n0, v0), dtype=float)
        return Forward(face, observed, np.asarray(sim.end_force["right"], dtype=float),
                       np.asarray(sim.end_velocity["right"], dtype=float),
                       np.asarray(sim.junction_contact[0], dtype=bool), float(self.dt * z.sum()), z.copy(),
                       float(velocity))

    def gradient(self, fw: Forward, face_force: Optional[np.ndarray] = None, observed: Optional[np.ndarray] = None,
                 end_force: Optional[np.ndarray] = None,
                 end_velocity: Optional[np.ndarray] = None) -> tuple[np.ndarray, float]:
        seeds = dict(face_force=face_force, observed=observed, end_force=end_force, end_velocity=end_velocity)

        def value(f: Forward) -> float:
            return float(sum(np.dot(s, getattr(f, k)) for k, s in seeds.items() if s is not None))

        z, v = fw.impedance, fw.velocity
        dz = np.empty(z.size)
        for i in range(z.size):
            h = 1e-6 * z[i]
            zp, zm = z.copy(), z.copy()
            zp[i] += h
            zm[i] -= h
            dz[i] = (value(self.forward(zp, v)) - value(self.forward(zm, v))) / (2 * h)
        h = 1e-6 * max(abs(v), 1e-3)
        dv = (value(self.forward(z, v + h)) - value(self.forward(z, v - h))) / (2 * h)
        return dz, float(dv)
