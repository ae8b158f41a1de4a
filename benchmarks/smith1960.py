"""Smith's lumped-mass wave-equation method (1960), written out plainly as the baseline of the pile benchmarks.

Source: E. A. L. Smith, "Pile-driving analysis by the wave equation", J. Soil Mech. Found. Div. ASCE 86 (SM4),
1960, 35-61. The same algorithm, with the same symbols, is the core of the Texas A&M / TTI programs (Lowery,
"Pile driving analysis by the wave equation", Wild West Software 1993, which may be copied with credit; T. J.
Hirsch, L. L. Lowery, H. M. Coyle, C. H. Samson, "Pile-driving analysis by one-dimensional wave theory: state of
the art", Highway Research Record 333, 1970) and of FHWA GEC-12 (Hannigan et al., FHWA-NHI-16-009, 2016,
chapter 12). Nothing here is rodimpact: this module imports numpy only, so that it stays an independent check.

The model (Smith 1960): the ram, the helmet (pile cap) and the pile are point masses ``M(m)`` joined
by massless springs ``K(m)`` (spring ``m`` lies between masses ``m`` and ``m + 1``); the hammer cushion (capblock)
and the pile cushion are such springs, the pile of length ``L`` is cut into ``n`` segments, each of mass
``rho A L / n`` lumped in one mass, joined by ``n - 1`` springs of stiffness ``E A / (L / n)``. When a pile
cushion is used its spring joins the helmet to the first pile mass and the last pile mass has no spring below it
(Lowery 1993, "Cushion in pile driving"). The soil acts on each pile mass as an elastic-plastic spring with a
dashpot (side), and under the last mass as a spring that can push but never pull (point).

The recurrence, in Smith's symbols and order (numbered 1-5 here; his paper could not be read, so its own
equation numbers are not given; SI units, so the factors 12 and g of the inch-pound form drop out), for every
time step ``t`` of length ``dt``:

    D(m, t) = D(m, t-1) + V(m, t-1) dt                        displacement, downward positive       (1)
    C(m, t) = D(m, t) - D(m+1, t)                             compression of spring m                (2)
    F(m, t) = C(m, t) K(m)                                    spring force, compression positive      (3)
    R(m, t) = [D(m, t) - D'(m, t)] K'(m) [1 + J(m) V(m, t-1)] soil resistance on mass m              (4)
    V(m, t) = V(m, t-1) + [F(m-1, t) - F(m, t) - R(m, t)] dt / M(m)                                   (5)

with ``K'(m) = R_u(m) / Q(m)`` (ultimate static resistance over the quake) and ``D'(m, t)`` the plastic
displacement of the soil: it follows ``D`` at the distance ``Q`` once ``|D - D'|`` would exceed the quake,
``D' = D - Q`` (loading) or ``D' = D + Q`` (unloading; Smith takes the unloading quake equal to the quake).
``J`` (s/m) is Smith's damping constant: the dashpot multiplies the static spring force.

Special springs and the point, as Smith gives them:

* cushions (capblock, pile cushion) and the ram-on-cap contact push but never pull (F >= 0, Lowery's
  Gamma(I) = 0), load along ``K`` and unload along the steeper line ``K / e**2`` through the largest
  compression reached (``e`` the coefficient of restitution; the energy given back is ``e**2`` of that taken);
* the point (toe) spring pushes only: ``R_p = max(0, (D_p - D'_p) K'_p (1 + J_p V_p))`` and ``D'_p`` only moves
  down (``D'_p = D_p - Q_p`` when ``D_p - D'_p > Q_p``): the soil under the point does not follow the pile up;
* gravity is left out, as in Smith's recurrence (the pile starts at rest with zero spring forces).

The **set per blow** is the permanent displacement of the point at the end of the run, ``D'_p``: the largest
point displacement less the point quake (Smith 1960; Lowery 1993). Stresses are spring forces over the pile
area. Results are returned in the project's convention (``shared/architecture.md``): axial force and stress
**positive in tension**, so the peak compressive stress is the most negative value; displacements and the set
are positive downward (into the ground), as in Smith.

Time step: the lumped chain integrated this way (it is the central-difference scheme) is stable for
``dt <= min_m sqrt(2 M(m) / (K(m-1) + K(m)))`` (for a uniform pile ``L / (n c)``, the travel time of one segment).
``courant = 0.5`` (dt half the critical value) is the customary choice of the programs that follow Smith;
his own rule for dt could not be read here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np


@dataclass(frozen=True)
class SmithModel:
    """A hammer-cushion-pile-soil system as Smith's masses and springs (SI units, downward positive).

    ``mass[m]`` (kg) for m = 0..p-1 (the ram is mass 0, the pile point is the last); ``stiffness[m]`` (N/m) of the
    spring between masses m and m+1; ``restitution[m]`` its coefficient of restitution (1: elastic);
    ``tension[m]`` whether it can pull (pile springs) or only push (cushions, contacts); ``pile_spring[m]`` whether
    its force is a pile force (counted in the pile stresses); ``area`` (m^2) of the pile for stresses.
    Soil on the side of mass m: ``shaft_ultimate[m]`` (N), ``shaft_quake[m]`` (m), ``shaft_damping[m]`` (Smith's
    J, s/m); under the point: ``toe_ultimate`` (N), ``toe_quake`` (m), ``toe_damping`` (s/m).
    ``velocity`` (m/s) is the initial velocity of each mass (the ram's impact velocity, zero elsewhere).
    ``head_mass`` is the index of the first pile mass.
    """

    mass: np.ndarray
    stiffness: np.ndarray
    restitution: np.ndarray
    tension: np.ndarray
    pile_spring: np.ndarray
    area: float
    velocity: np.ndarray
    shaft_ultimate: np.ndarray
    shaft_quake: np.ndarray
    shaft_damping: np.ndarray
    toe_ultimate: float = 0.0
    toe_quake: float = 2.54e-3
    toe_damping: float = 0.0
    head_mass: int = 0

    def critical_time_step(self) -> float:
        """The stability limit of the recurrence, s: ``min_m sqrt(2 M(m) / (K(m-1) + K(m)))``.

        A Gershgorin bound on the largest eigenfrequency of the chain, ``omega^2 <= 2 (K(m-1) + K(m)) / M(m)``;
        the central-difference recurrence is stable for ``dt <= 2 / omega_max``. The cushions are counted with
        their unloading stiffness ``K / e**2`` and the soil springs ``K'`` with their static stiffness.
        """
        k = self.stiffness / self.restitution**2
        around = np.zeros(self.mass.size)
        around[:-1] += k
        around[1:] += k
        with np.errstate(divide="ignore"):
            soil = np.where(self.shaft_quake > 0, self.shaft_ultimate / self.shaft_quake, 0.0)
        around += soil
        if self.toe_quake > 0:
            around[-1] += self.toe_ultimate / self.toe_quake
        loaded = around > 0
        return float(np.min(np.sqrt(2.0 * self.mass[loaded] / around[loaded])))


@dataclass(frozen=True)
class SmithBlow:
    """One blow computed by Smith's recurrence.

    ``time`` (s, the end of each step); ``set`` (m): permanent displacement of the point ``D'_p`` at the end,
    positive downward; ``peak_compression`` / ``peak_tension`` (Pa): the most negative / most positive pile stress
    over all pile springs and times (tension positive; the pile cushion's force counts as the head force);
    ``head_force`` (N, tension positive): force of the spring above the first pile mass at each step;
    ``toe_displacement`` (m): point displacement at each step, ``toe_velocity`` (m/s): its velocity over the
    following step (the recurrence's velocities sit half a step later than its displacements); ``forces`` (N,
    tension positive, steps x springs) when recorded; ``final_displacement`` (m) and ``final_velocity`` (m/s) of
    every mass, downward positive; ``steps`` and ``dt``.
    """

    time: np.ndarray
    set: float
    peak_compression: float
    peak_tension: float
    head_force: np.ndarray
    toe_displacement: np.ndarray
    toe_velocity: np.ndarray
    forces: Optional[np.ndarray]
    final_displacement: np.ndarray
    final_velocity: np.ndarray
    steps: int
    dt: float


def drive(model: SmithModel, dt: float, steps: int, *, record_forces: bool = False,
          external_force=None, shaft_damping: str = "smith") -> SmithBlow:
    """Run Smith's recurrence (module docstring, eqs. 1-5) for ``steps`` steps of ``dt`` seconds.

    ``external_force(t)`` (N, downward positive, optional) is added on mass 0 at each step (used by the elastic
    checks: a prescribed force on the pile head instead of a hammer).

    ``shaft_damping``: ``"smith"`` is eq. (4) as published, R = R_s (1 + J V). After a rebound the static shaft
    force R_s is negative and the product R_s J V then pushes the pile along its motion (it gives energy).
    ``"mirrored"`` uses R = R_s + J |R_s| V instead, the mirror image of the downward law, which rodimpact's
    ``ShaftResistance(damping_kind="smith")`` uses (the two agree while R_s >= 0); the benchmark runs both so
    that the difference of the laws is not mistaken for a difference of the discretisations. The point is the
    same in both (its R_s is never negative).
    """
    if shaft_damping not in ("smith", "mirrored"):
        raise ValueError(f"shaft_damping: must be 'smith' or 'mirrored', got {shaft_damping!r}")
    mirrored = shaft_damping == "mirrored"
    M = np.asarray(model.mass, float)
    K = np.asarray(model.stiffness, float)
    e2 = np.asarray(model.restitution, float) ** 2
    pulls = np.asarray(model.tension, bool)
    cushion = (e2 < 1.0) | ~pulls                       # springs with the cushion law (push only, K/e^2 unloading)
    pile = np.asarray(model.pile_spring, bool)
    Ru = np.asarray(model.shaft_ultimate, float)
    Q = np.asarray(model.shaft_quake, float)
    J = np.asarray(model.shaft_damping, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        Ks = np.where(Q > 0, Ru / np.where(Q > 0, Q, 1.0), 0.0)        # K'(m) = Ru / Q
    Kp = model.toe_ultimate / model.toe_quake if model.toe_quake > 0 else 0.0

    D = np.zeros(M.size)
    V = np.array(model.velocity, float)
    Dplastic = np.zeros(M.size)                          # D'(m)
    Dplastic_toe = 0.0                                   # D'_p
    Cmax = np.zeros(K.size)                              # largest compression reached by each cushion
    head = model.head_mass - 1                           # the spring above the first pile mass (-1: none)

    time = dt * np.arange(1, steps + 1)
    head_force = np.zeros(steps)
    toe_D = np.zeros(steps)
    toe_V = np.zeros(steps)
    forces = np.zeros((steps, K.size)) if record_forces else None
    peak_c = 0.0                                         # largest compressive pile force (compression positive)
    peak_t = 0.0                                         # largest tensile pile force (tension positive)
    counted = pile.copy()
    if head >= 0:
        counted[head] = True
    for i in range(steps):
        V_prev = V
        D = D + V_prev * dt                                                    # (1)
        C = D[:-1] - D[1:]                                                     # (2)
        F = C * K                                                              # (3)
        if cushion.any():
            Cmax = np.where(cushion & (C > Cmax), C, Cmax)
            unloading = Cmax * K - (Cmax - C) * K / e2                          # line K/e^2 through (Cmax, K Cmax)
            F = np.where(cushion, np.maximum(0.0, np.minimum(F, unloading)), F)
        # soil: plastic displacement D' follows D at the quake's distance (loading and unloading)
        Dplastic = np.where(D - Dplastic > Q, D - Q, Dplastic)
        Dplastic = np.where(D - Dplastic < -Q, D + Q, Dplastic)
        Rs = (D - Dplastic) * Ks
        R = Rs + (np.abs(Rs) if mirrored else Rs) * J * V_prev                 # (4)
        # the point: pushes only, its D' only moves down
        if D[-1] - Dplastic_toe > model.toe_quake:
            Dplastic_toe = D[-1] - model.toe_quake
        Rtoe = max(0.0, (D[-1] - Dplastic_toe) * Kp * (1.0 + model.toe_damping * V_prev[-1]))
        net = -R
        net[:-1] -= F
        net[1:] += F
        net[-1] -= Rtoe
        if external_force is not None:
            net[0] += external_force(time[i])
        V = V_prev + net * dt / M                                              # (5)

        Fc = F[counted]
        if Fc.size:
            peak_c = max(peak_c, float(Fc.max()))
            peak_t = max(peak_t, float(-Fc.min()))
        head_force[i] = -F[head] if head >= 0 else 0.0
        toe_D[i] = D[-1]
        toe_V[i] = V[-1]
        if forces is not None:
            forces[i] = -F
    return SmithBlow(time=time, set=float(Dplastic_toe), peak_compression=-peak_c / model.area,
                     peak_tension=peak_t / model.area, head_force=head_force, toe_displacement=toe_D,
                     toe_velocity=toe_V, forces=forces, final_displacement=D, final_velocity=V, steps=steps,
                     dt=dt)


@dataclass(frozen=True)
class Hammer:
    """A drop (single-acting) hammer as Smith models it: the ram, the hammer cushion (capblock), the helmet.

    ``ram_mass`` (kg), ``impact_velocity`` (m/s, downward), ``cushion_stiffness`` (N/m) and
    ``cushion_restitution`` of the hammer cushion, ``helmet_mass`` (kg; 0: no helmet, the hammer cushion sits on
    the pile head), and the pile cushion (``pile_cushion_stiffness`` N/m, 0 for none; ``pile_cushion_restitution``).
    """

    ram_mass: float
    impact_velocity: float
    cushion_stiffness: float
    cushion_restitution: float
    helmet_mass: float
    pile_cushion_stiffness: float = 0.0
    pile_cushion_restitution: float = 1.0


@dataclass(frozen=True)
class Pile:
    """A uniform pile: ``length`` (m), ``area`` (m^2), ``modulus`` E (Pa), ``density`` (kg/m^3)."""

    length: float
    area: float
    modulus: float
    density: float

    @property
    def wave_speed(self) -> float:
        """c = sqrt(E / rho), m/s."""
        return math.sqrt(self.modulus / self.density)

    @property
    def impedance(self) -> float:
        """Z = E A / c, N s/m."""
        return self.modulus * self.area / self.wave_speed


@dataclass(frozen=True)
class Soil:
    """Smith soil: shaft resistance ``shaft_ultimate`` (N, total) spread evenly over the embedded length
    ``embedment`` (m, measured up from the point), quake (m) and damping J (s/m) of the side and of the point."""

    shaft_ultimate: float
    embedment: float
    shaft_quake: float
    shaft_damping: float
    toe_ultimate: float
    toe_quake: float
    toe_damping: float


def pile_model(hammer: Optional[Hammer], pile: Pile, soil: Optional[Soil], segments: int) -> SmithModel:
    """Smith's masses and springs for a hammer on a pile of ``segments`` equal segments in the given soil.

    Without a hammer the pile stands alone (its first mass is mass 0): used with ``external_force`` by the
    elastic checks. The shaft resistance of each pile mass is the share of its segment (length ``L / n``, the
    mass lumped at the segment) lying inside the embedded length.
    """
    n = segments
    dx = pile.length / n
    m_pile = np.full(n, pile.density * pile.area * dx)
    k_pile = np.full(n - 1, pile.modulus * pile.area / dx)
    if hammer is None:
        masses, springs, restitution, pulls = [], [], [], []
    elif hammer.helmet_mass > 0:
        masses = [hammer.ram_mass, hammer.helmet_mass]
        springs, restitution, pulls = [hammer.cushion_stiffness], [hammer.cushion_restitution], [False]
        if hammer.pile_cushion_stiffness > 0:
            springs.append(hammer.pile_cushion_stiffness)
            restitution.append(hammer.pile_cushion_restitution)
        else:   # no pile cushion: the first pile spring joins the helmet to the pile head (Lowery 1993)
            springs.append(pile.modulus * pile.area / dx)
            restitution.append(1.0)
        pulls.append(False)                 # the helmet rests on the pile: it pushes, never pulls
    else:       # no helmet: the hammer cushion sits on the pile head
        masses = [hammer.ram_mass]
        springs, restitution, pulls = [hammer.cushion_stiffness], [hammer.cushion_restitution], [False]
    head = len(masses)
    is_pile = [False] * len(springs)
    mass = np.concatenate([masses, m_pile])
    stiffness = np.concatenate([springs, k_pile])
    restitution = np.concatenate([restitution, np.ones(n - 1)])
    tension = np.concatenate([np.array(pulls, bool), np.ones(n - 1, bool)])
    pile_spring = np.concatenate([np.array(is_pile, bool), np.ones(n - 1, bool)])
    velocity = np.zeros(mass.size)
    if hammer is not None:
        velocity[0] = hammer.impact_velocity
    shaft = np.zeros(mass.size)
    quake = np.full(mass.size, 2.54e-3)
    damping = np.zeros(mass.size)
    toe = dict(toe_ultimate=0.0, toe_quake=2.54e-3, toe_damping=0.0)
    if soil is not None:
        top = pile.length - soil.embedment                  # depth of the ground below the pile head
        seg_top = dx * np.arange(n)
        inside = np.clip(seg_top + dx - np.maximum(seg_top, top), 0.0, dx)
        shaft[head:] = soil.shaft_ultimate * inside / soil.embedment if soil.embedment > 0 else 0.0
        quake[head:] = soil.shaft_quake
        damping[head:] = soil.shaft_damping
        toe = dict(toe_ultimate=soil.toe_ultimate, toe_quake=soil.toe_quake, toe_damping=soil.toe_damping)
    return SmithModel(mass=mass, stiffness=stiffness, restitution=restitution, tension=tension,
                      pile_spring=pile_spring, area=pile.area, velocity=velocity, shaft_ultimate=shaft,
                      shaft_quake=quake, shaft_damping=damping, head_mass=head, **toe)


def blow(hammer: Hammer, pile: Pile, soil: Soil, segments: int, duration: float, *, courant: float = 0.5,
         record_forces: bool = False, shaft_damping: str = "smith") -> SmithBlow:
    """One blow with ``segments`` pile segments, ``dt = courant`` x the critical step, run for ``duration`` s."""
    model = pile_model(hammer, pile, soil, segments)
    dt = courant * model.critical_time_step()
    return drive(model, dt, int(math.ceil(duration / dt)), record_forces=record_forces,
                 shaft_damping=shaft_damping)
