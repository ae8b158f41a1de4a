"""Forward model and exact gradient (adjoint, reverse mode) of one striker impact, for striker design.

:class:`ImpactProblem` fixes everything except the striker: the struck system (left end = impact face), the
element travel time dt, the number n of striker elements and the number of steps. :meth:`ImpactProblem.forward`
runs the impact of a striker given by its element impedances Z_1..Z_n (counted from the impact face, as in
:func:`~rodimpact.synthesize`) and velocity; :meth:`ImpactProblem.gradient` returns dJ/dZ_q and dJ/dv for any
scalar J of the outputs, given the seeds dJ/d(output). The derivation is in docs/adjoint.md.

The forward run is the lattice of :func:`rodimpact.simulate` (same arrays, same boundary code, same operation
order) on the system ``with_striker(struck, Rod.from_impedance(Z[::-1], dt=dt), velocity)``: its outputs are
bit-identical to ``simulate``'s. The gradient is exact for the branches taken (contact or separated, friction
stick or slip, bit-rock loading, unloading or released, a law joint's elastic or plastic branch, loading or
unloading, carrying or lifted off): the responses are piecewise smooth in (Z, v). Law joints (specimens, pulse
shapers) are differentiated through their implicit per-step root (:mod:`rodimpact.design._joint_adjoint`);
tabulated laws and spring-dashpot junctions are refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .._validate import finite, fits_in_memory, positive_array
from ..direct.boundary import ACC_SLOTS, LAW_JOINT, law_state
from ..direct.problem import Problem, TimeGrid
from ..direct.recording import Outputs
from ..rods.conditions import Bonded, Contact, DeformableJoint
from ..rods.rod import Rod
from ..rods.soil import ShaftResistance, SoilToe
from ..rods.system import System
from ..inverse.struck import Location, as_struck_system, position_probe, with_striker
from . import _adjoint_kernels as K
from ._joint_adjoint import law_refusal, scratch_array

QUANTITIES = ("force", "incident")


@dataclass(frozen=True, eq=False)
class Forward:
    """Outputs of one impact, one value per step (the step's start time is k dt).

    ``face_force`` (N, compressive < 0) is the contact force at the impact face, ``observed`` the chosen quantity
    at the location (the face force without a location), ``end_force`` / ``end_velocity`` the normal force (N)
    and outward velocity (m/s) at the struck system's far end, ``contact`` whether the striker touches;
    ``striker_mass`` = dt sum Z (kg), ``impedance`` (Z_1 at the face) and ``velocity`` the striker that was run.
    ``shortening`` (junctions x steps, m; None without law joints): the shortening delta of each junction after
    each step (compression positive; for a law joint the body's shortening, whose rate over step k is
    (delta_k - delta_k-1) / dt, delta_-1 = 0); ``junction_force`` (junctions x steps, N, tension positive; None
    without law joints): the force at every junction in every step (0 where a compression-only joint has lifted
    off).
    ``_tape`` holds what :meth:`ImpactProblem.gradient` needs (lattice impedances, checkpoints).
    """

    face_force: np.ndarray
    observed: np.ndarray
    end_force: np.ndarray
    end_velocity: np.ndarray
    contact: np.ndarray
    striker_mass: float
    impedance: np.ndarray
    velocity: float
    _tape: dict = field(repr=False)
    shortening: Optional[np.ndarray] = None
    junction_force: Optional[np.ndarray] = None


class ImpactProblem:
    """The impact of a striker of n elements (travel time ``dt`` each) on ``struck`` during ``steps`` steps.

    Parameters
    ----------
    struck:
        The struck system, its left end the impact face (from :func:`~rodimpact.inverse.struck.as_struck_system`).
    dt:
        Element travel time, s.
    n:
        Number of striker elements.
    steps:
        Number of time steps simulated.
    location:
        ``None`` (observe the impact face) or a :class:`~rodimpact.inverse.struck.Location` in ``struck``.
    quantity:
        ``"force"`` (normal force, tension positive) or ``"incident"`` (force wave arriving from the impact side,
        relative to the initial state of the element left of the node; see
        :func:`~rodimpact.inverse.struck.position_quantity`) at the location; without a location the observed
        quantity is the face force.
    backend:
        ``"numba"`` (compiled) or ``"numpy"`` (readable reference path; slow).
    checkpoint_every:
        The reverse sweep stores the full state every C steps and recomputes each segment of C steps once
        (memory ~ (steps / C + C) states); default C = ceil(sqrt(steps)).
    """

    def __init__(self, struck: System, dt: float, n: int, steps: int, *, location: Optional[Location] = None,
                 quantity: str = "force", backend: str = "numba", checkpoint_every: Optional[int] = None) -> None:
        if not isinstance(struck, System):
            raise TypeError(f"struck: must be a System (see rodimpact.inverse.struck.as_struck_system), "
                            f"got {type(struck).__name__}")
        struck = as_struck_system(struck)
        for i, j in enumerate(struck.junctions):
            if j.code == LAW_JOINT and isinstance(j, DeformableJoint):
                why = law_refusal(int(j.law.code), j.law.fails)
                if why is not None:
                    raise ValueError(f"struck.junctions[{i}].law: {type(j.law).__name__}: {why}")
            elif j.code not in (Bonded.code, Contact.code):
                # the reverse sweep (_adjoint_kernels.reverse) differentiates bonded and contact nodes and law
                # joints (specimens, pulse shapers)
                raise ValueError(f"struck.junctions[{i}]: design's exact gradients cover bonded and contact "
                                 f"junctions and law joints (Specimen, PulseShaper), got {type(j).__name__}; "
                                 "simulate or synthesize take it")
        soil = [f"struck.loads[{i}]" for i, ld in enumerate(struck.loads) if isinstance(ld, ShaftResistance)]
        soil += [f"struck.{side}" for side in ("left", "right") if isinstance(getattr(struck, side), SoilToe)]
        if soil:
            raise ValueError(f"{soil[0]}: design's exact gradients do not cover Smith soil (ShaftResistance, "
                             f"SoilToe); simulate takes it")
        self.n = _count("n", n, "striker elements")
        self.steps = _count("steps", steps, "time steps")
        if quantity not in QUANTITIES:
            raise ValueError(f"quantity: must be one of {QUANTITIES}, got {quantity!r}")
        if location is not None and not isinstance(location, Location):
            raise TypeError(f"location: must be None or a Location (rodimpact.inverse.struck.locate), "
                            f"got {type(location).__name__}")
        if backend not in ("numba", "numpy"):
            raise ValueError(f"backend: must be 'numba' or 'numpy', got {backend!r}")
        c = math.ceil(math.sqrt(self.steps)) if checkpoint_every is None else _count(
            "checkpoint_every", checkpoint_every, "steps")
        self.checkpoint_every = min(c, self.steps)
        self.struck, self.location, self.quantity, self.backend = struck, location, quantity, backend
        # the complete system with a placeholder striker: only the striker's impedances and velocity change
        template = with_striker(struck, Rod.from_impedance(np.ones(self.n), dt=dt), 1.0)
        probes = [position_probe(location, 1)] if location is not None else []
        compiled = Problem(template, TimeGrid(dt, self.steps), Outputs(probes=probes)).compile()
        lat = compiled.lattice
        self.dt = lat.dt
        if int(lat.rod_start[1]) != self.n:   # pragma: no cover - impedance-level rods are exact
            raise ValueError(f"dt: the striker lattice has {lat.rod_start[1]} elements instead of n = {self.n}")
        n_el, n_ck = lat.n_elements, -(-self.steps // self.checkpoint_every)
        # checkpoints (2 waves) + one recorded segment (~1 wave per step) + per-step inputs and outputs
        fits_in_memory("steps", 8.0 * (n_el * (2 * n_ck + self.checkpoint_every) + 16 * self.steps),
                       f"the checkpoints of {self.steps} steps of {n_el} elements",
                       "use fewer steps or fewer, longer elements")
        self._state = {"N": compiled.N, "v": compiled.v}
        arrays = compiled.arrays
        _, self._touch = compiled.wave_arrays()
        self._arrays = arrays
        self._end_value, self._sp_force = (np.ascontiguousarray(x) for x in arrays["step_inputs"](0, self.steps))
        self._z = lat.impedance.copy()
        self._has_joints = bool(np.any(arrays["junction_code"] == LAW_JOINT))
        if location is not None:   # element left of the observed node (the striker's face element at the face)
            self._k_left = self.n + location.element_left

    # ------------------------------------------------------------------ forward
    def forward(self, impedance: Any, velocity: Any) -> Forward:
        """Run the impact of the striker with element impedances ``impedance`` (N s/m, Z_1 at the impact face)
        and initial velocity ``velocity`` (m/s, positive towards the struck system)."""
        zq = positive_array("impedance", impedance)
        if zq.shape != (self.n,):
            raise ValueError(f"impedance: need one value per striker element, shape ({self.n},), got {zq.shape}")
        v_striker = finite("velocity", velocity, "m/s")
        Z = self._z.copy()
        Z[:self.n] = zq[::-1]
        R = (Z[1:] - Z[:-1]) / (Z[1:] + Z[:-1])            # eq. 2.40, as rodimpact.direct.problem.wave_arrays
        N0 = self._state["N"]
        v0 = self._state["v"].copy()
        v0[:self.n] = v_striker
        f = 0.5 * (N0 - Z * v0)
        g = 0.5 * (N0 + Z * v0)
        C = self.checkpoint_every
        ck = _state_store(-(-self.steps // C), Z.size, self._arrays["junction_code"].size)
        buffers = self._buffers()
        run = K.advance_numba if self.backend == "numba" else K.advance_numpy
        jt = self._joint_tape(ck[0].shape[0], 1, buffers[4][0])
        run(0, self.steps, C, f, g, Z, R, self._touch, self._arrays["rod_start"], *buffers, self.dt,
            ck, False, _record(1, Z.size, self._touch.size), jt)
        (jn, jc, en, ev), (pn, pv) = buffers[4], buffers[3][3:5]
        face = jn[0]
        if self.location is None:
            observed = face
        elif self.quantity == "force":
            observed = pn[0]
        else:
            z_left = Z[self._k_left]
            observed = 0.5 * ((pn[0] - N0[self._k_left]) - z_left * (pv[0] - v0[self._k_left]))
        tape = {"Z": Z, "R": R, "v0": v0, "checkpoints": ck, "probe_velocity": pv, "problem": self,
                "joint_checkpoints": None if jt is None else jt[K.JT_CK_Q]}
        return Forward(face, observed, en[1], ev[1], jc[0].astype(bool), float(self.dt * zq.sum()), zq.copy(),
                       v_striker, tape, None if jt is None else jt[K.JT_SHORTENING].copy(),
                       None if jt is None else jn.copy())

    def _joint_tape(self, checkpoints: int, segment: int, junction_force: np.ndarray,
                    ck_q: Optional[np.ndarray] = None) -> Optional[tuple]:
        """The joint tape of the kernels (:data:`rodimpact.design._adjoint_kernels.JT_CK_Q` ...), or None for a
        system without law joints (the kernels then carry no joint code). ``junction_force``: the per-step
        junction forces of the step loop's outputs (the same array)."""
        if not self._has_joints:
            return None
        a = self._arrays
        n_j, width = a["junction_q"].shape
        if ck_q is None:
            ck_q = np.zeros((checkpoints, n_j, width))
        return (ck_q, np.zeros((segment, n_j, width)), np.zeros((segment, n_j)), np.zeros((n_j, self.steps)),
                np.zeros((n_j, 4)), np.zeros((n_j, self.steps)), scratch_array(),
                np.ascontiguousarray(a["junction_code"], dtype=np.int64), np.ascontiguousarray(a["junction_par"]),
                junction_force)

    def _buffers(self) -> tuple:
        """The grouped arrays of :func:`~rodimpact.direct._kernels.boundaries` for a run from the initial state:
        ends, junctions, specials, probes, per-step outputs (junction force, contact, end force, end velocity),
        work accumulator, rod-end node values."""
        a = self._arrays
        n_rods = a["rod_start"].size - 1
        n_j, n_p, n_sp, steps = n_rods - 1, a["pr_rod"].size, a["sp_elem"].size, self.steps
        ends = (a["end_code"], a["end_par"], np.zeros((2, 2)), self._end_value)
        junctions = (a["junction_code"], np.zeros(n_j, dtype=np.int64), a["gap"].copy(), a["gap_tol"],
                     np.zeros((n_rods, 2)), a["junction_par"],
                     law_state(a["junction_code"], np.zeros_like(a["junction_q"])), None)   # design refuses chains
        specials = (a["sp_elem"], a["sp_cap"], self._sp_force, np.zeros(n_sp), np.zeros(n_sp), None)   # no soil
        probes = (a["pr_rod"], a["pr_local"], a["pr_sp"], np.zeros((n_p, steps)), np.zeros((n_p, steps)),
                  np.zeros((n_p, steps)), np.zeros(n_p))
        outputs = (np.zeros((n_j, steps)), np.zeros((n_j, steps)), np.zeros((2, steps)), np.zeros((2, steps)))
        return (ends, junctions, specials, probes, outputs, np.zeros(ACC_SLOTS),
                tuple(np.empty(n_rods) for _ in range(4)))

    # ------------------------------------------------------------------ gradient
    def gradient(self, fw: Forward, face_force: Any = None, observed: Any = None, end_force: Any = None,
                 end_velocity: Any = None, shortening: Any = None) -> tuple[np.ndarray, float]:
        """dJ/dZ_q (shape (n,), Z_1 at the impact face) and dJ/dv for the scalar J whose derivatives with respect
        to the per-step outputs of ``fw`` are the given seeds (each ``None`` or shape (steps,); ``shortening``:
        dJ/d(shortening of each junction after each step), shape (junctions, steps), law joints only)."""
        if not isinstance(fw, Forward) or fw._tape.get("problem") is not self:
            raise ValueError("fw: must be the result of forward() of this ImpactProblem")
        steps, n = self.steps, self.n
        seed = np.zeros((5, steps))
        for name, val, row in (("face_force", face_force, K.SEED_FACE), ("end_force", end_force, K.SEED_END_FORCE),
                               ("end_velocity", end_velocity, K.SEED_END_VELOCITY)):
            if val is not None:
                seed[row] += _seed(name, val, steps)
        tape = fw._tape
        Z, R, v0 = tape["Z"], tape["R"], tape["v0"]
        dZ = np.zeros(Z.size)
        dv = 0.0
        if observed is not None:
            s = _seed("observed", observed, steps)
            if self.location is None:
                seed[K.SEED_FACE] += s
            elif self.quantity == "force":
                seed[K.SEED_PROBE_FORCE] += s
            else:   # N_i = ((N - N0) - Z_left (V - v0)) / 2
                kl = self._k_left
                seed[K.SEED_PROBE_FORCE] += 0.5 * s
                seed[K.SEED_PROBE_VELOCITY] -= 0.5 * Z[kl] * s
                dZ[kl] -= 0.5 * float(np.dot(tape["probe_velocity"][0] - v0[kl], s))
                if kl < n:
                    dv += 0.5 * Z[kl] * float(s.sum())
        lf, lg, les, dR = np.zeros(Z.size), np.zeros(Z.size), np.zeros((2, 2)), np.zeros(R.size)
        segment = _record(self.checkpoint_every, Z.size, self._touch.size)
        buffers = self._buffers()
        jt = self._joint_tape(0, self.checkpoint_every, buffers[4][0], tape["joint_checkpoints"])
        if shortening is not None:
            if jt is None:
                raise ValueError("shortening: the system has no law joint (Specimen, PulseShaper) whose shortening "
                                 "could be seeded")
            arr = np.asarray(shortening, dtype=float)
            if arr.shape != jt[K.JT_SEED].shape or not np.all(np.isfinite(arr)):
                raise ValueError(f"shortening: the seed needs finite values of shape {jt[K.JT_SEED].shape} "
                                 f"(junctions, steps), got shape {arr.shape}")
            jt[K.JT_SEED][:] = arr
        args = (tape["checkpoints"], _state_store(0, Z.size, self._arrays["junction_code"].size), segment,
                np.empty(Z.size), np.empty(Z.size), Z, R, self._touch,
                self._arrays["rod_start"], *buffers, self.dt, self.steps, seed, lf, lg, les, dZ, dR, jt)
        (K.sweep_numba if self.backend == "numba" else K.sweep_numpy)(*args)
        # initial waves f = (N0 - Z v0)/2, g = (N0 + Z v0)/2; the striker's v0 is the velocity
        dZ += 0.5 * v0 * (lg - lf)
        dv += float(np.sum(0.5 * Z[:n] * (lg[:n] - lf[:n])))
        # R_j = (Z_{j+1} - Z_j) / (Z_{j+1} + Z_j)
        s2 = (Z[1:] + Z[:-1]) ** 2
        dZ[1:] += dR * 2.0 * Z[:-1] / s2
        dZ[:-1] -= dR * 2.0 * Z[1:] / s2
        return dZ[:n][::-1].copy(), dv


def _count(name: str, value: Any, what: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ValueError(f"{name}: must be an integer number of {what} >= 1, got {value!r}")
    return int(value)


def _seed(name: str, value: Any, steps: int) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: must be an array of dJ/d({name}) per step, got {type(value).__name__}") from None
    if arr.shape != (steps,):
        raise ValueError(f"{name}: the seed needs one value per step, shape ({steps},), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: the seed must be finite")
    return arr


def _state_store(slots: int, n_el: int, n_j: int) -> tuple[np.ndarray, ...]:
    """Room for ``slots`` lattice states: waves f, g, end state, junction state, gap."""
    return (np.empty((slots, n_el)), np.empty((slots, n_el)), np.empty((slots, 2, 2)),
            np.empty((slots, n_j), dtype=np.int64), np.empty((slots, n_j)))


def _record(slots: int, n_el: int, n_touch: int) -> tuple[np.ndarray, ...]:
    """Room for what the transpose of ``slots`` steps needs: f_j - g_{j+1} of every node, the waves of the
    elements next to ends, joints, loads and probes, the end state."""
    return np.zeros((slots, n_el)), np.empty((slots, n_touch)), np.empty((slots, n_touch)), np.empty((slots, 2, 2))
