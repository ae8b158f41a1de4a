"""Constitutive laws of the deformable joints between rods (specimens, pulse shapers, cushions): stress as a
function of strain, strain rate and internal state, with units, sources and parameter bounds, and no time
stepping (the solver integrates them, :mod:`rodimpact.direct.joints`).

Signs: the laws are written for the SHPB habit, stress and strain POSITIVE IN COMPRESSION (the joint's force on
the rods is N = -F, tension-positive N). Units: stresses and moduli in Pa, strain rates in 1/s.

Each law is a frozen dataclass with declared fields (:mod:`rodimpact.rods.declared`), registered in the family
``law`` so that model files name it by its type (``law = { type = "johnson-cook", ... }``). ``kernel()`` gives
the law's code and parameter vector for the compiled solver (layout in :mod:`rodimpact.direct.joints`).

Plasticity (``elastic-plastic``, ``johnson-cook``, ``cowper-symonds``, ``tabulated``) is the 1-D return mapping
with isotropic hardening: sigma = E (eps - eps_p), yield when |sigma| > sigma_y(alpha, rate) with alpha the
accumulated plastic strain; the viscoplastic laws take the rate of the total strain as their rate argument
(the specimen's strain rate, as SHPB reduction reports it). ``frew`` is a loading curve in total strain (pulse
shapers) with elastic unloading from the largest strain reached.
"""

from __future__ import annotations

from dataclasses import dataclass

from typing import Any, Callable, Optional

import numpy as np

from .._units import to_si
from .._validate import finite_array, positive
from .declared import check, element, path, quantity

#: law codes of the compiled solver (rodimpact.direct.joints)
ELASTIC, PLASTIC, JOHNSON_COOK, COWPER_SYMONDS, FREW, TABULATED = 0, 1, 2, 3, 4, 5

#: number of parameters a law passes to the kernel (unused ones are 0); the last two are the failure strain and
#: the softening strain of the damage extension (:class:`Failure`; 0 = no failure)
N_PARAMS = 10
#: indices of the failure strain eps_f and the softening strain in a law's kernel vector
FAILURE_STRAIN, SOFTENING_STRAIN = 8, 9


class Law:
    """Base class of the constitutive laws."""

    code: int = -1
    #: True if the law describes compression only (a loading curve in compressive strain)
    compression_only: bool = False

    def kernel(self) -> np.ndarray:
        """The parameter vector of the compiled solver (length :data:`N_PARAMS`)."""
        raise NotImplementedError

    @property
    def fails(self) -> bool:
        """True if the law has a failure strain (:class:`Failure`)."""
        return False

    @property
    def modulus(self) -> float:
        """The elastic (unloading) modulus E, Pa."""
        return float(self.youngs_modulus)  # type: ignore[attr-defined]


def _params(*values: float) -> np.ndarray:
    p = np.zeros(N_PARAMS)
    p[:len(values)] = values
    return p


class Failure:
    """Ductile damage of the plastic laws: Johnson and Cook's cumulative damage (G. R. Johnson, W. H. Cook, Eng.
    Fract. Mech. 21 (1985) 31-48, eq. 5) D = sum(d eps_p / eps_f) with their failure strain eps_f = [D1 + D2
    exp(D3 sigma*)][1 + D4 ln eps_dot*][1 + D5 T*] reduced to the constant D1 = ``failure_strain`` (no triaxiality,
    rate or temperature dependence), so D = alpha / eps_f with alpha the accumulated plastic strain. Instead of
    removing the body at D = 1, the stress softens linearly to zero over a further plastic strain
    ``softening_strain``: sigma = (1 - w) sigma_law, w = min(1, max(0, (alpha - eps_f) / softening_strain)), the
    undamaged law's stress sigma_law (effective stress) still following the return mapping. A fully failed body
    (w = 1) carries no force, in compression or tension. Both None (default): no failure. The solver lags w by
    one step (:func:`rodimpact.direct.joints.joint_point`)."""

    failure_strain: Optional[float]
    softening_strain: Optional[float]

    def _check_failure(self) -> None:
        name = type(self).__name__
        if (self.failure_strain is None) != (self.softening_strain is None):
            raise ValueError(f"{name}.softening_strain: failure needs both failure_strain and softening_strain "
                             f"(got failure_strain = {self.failure_strain!r}, softening_strain = "
                             f"{self.softening_strain!r})")

    def _failure_params(self, p: np.ndarray) -> np.ndarray:
        if self.failure_strain is not None:
            p[FAILURE_STRAIN], p[SOFTENING_STRAIN] = self.failure_strain, self.softening_strain
        return p

    @property
    def fails(self) -> bool:
        """True if the law has a failure strain."""
        return self.failure_strain is not None


def _failure_strain() -> Any:
    return quantity("dimensionless", "Failure strain eps_f: the accumulated plastic strain at which damage D = "
                    "alpha / eps_f reaches 1 and softening starts (Johnson and Cook 1985's D1; None: no failure).",
                    default=None)


def _softening_strain() -> Any:
    return quantity("dimensionless", "Further plastic strain over which the stress of a failing body falls "
                    "linearly to zero (needed with failure_strain).", default=None)


@element("law", "elastic")
@dataclass(frozen=True)
class LinearElastic(Law):
    """Linear elastic: sigma = E eps (Hooke)."""

    youngs_modulus: float = quantity("pressure", "Young's modulus E.")
    code = ELASTIC

    def __post_init__(self) -> None:
        check(self)

    def kernel(self) -> np.ndarray:
        return _params(self.youngs_modulus)


@element("law", "elastic-plastic")
@dataclass(frozen=True)
class ElasticPlastic(Failure, Law):
    """Elastic with linear isotropic hardening: yield stress sigma_y + H alpha (rate independent; H = 0 is
    elastic-perfectly plastic, and a large E approaches the rigid-perfectly-plastic specimen); optional failure:
    damage D = alpha / failure_strain, then the stress falls linearly to 0 over softening_strain (Failure)."""

    youngs_modulus: float = quantity("pressure", "Young's modulus E.")
    yield_stress: float = quantity("pressure", "Initial yield stress sigma_y.")
    hardening: float = quantity("pressure", "Plastic hardening modulus H (slope of stress over plastic strain).",
                                bound="non_negative", default=0.0)
    failure_strain: Optional[float] = _failure_strain()
    softening_strain: Optional[float] = _softening_strain()
    code = PLASTIC

    def __post_init__(self) -> None:
        check(self)
        self._check_failure()

    def kernel(self) -> np.ndarray:
        return self._failure_params(_params(self.youngs_modulus, self.yield_stress, self.hardening))


@element("law", "johnson-cook")
@dataclass(frozen=True)
class JohnsonCook(Failure, Law):
    """Johnson-Cook flow stress (G. R. Johnson, W. H. Cook, Proc. 7th Int. Symp. Ballistics, The Hague 1983,
    pp. 541-547): sigma_y = (A + B alpha^n) (1 + C ln(rate / reference_rate)) (1 - T*^m), T* = (T - T_room) /
    (T_melt - T_room); the rate term is 1 below the reference rate. The temperature is constant during a test
    (no adiabatic heating); below room temperature the thermal factor is 1 (T* <= 0). Optional failure: Johnson and
    Cook's 1985 damage D = alpha / failure_strain (a constant failure strain), then the stress falls linearly to
    0 over softening_strain (Failure)."""

    youngs_modulus: float = quantity("pressure", "Young's modulus E.")
    a: float = quantity("pressure", "Yield stress A.")
    b: float = quantity("pressure", "Hardening modulus B.", bound="non_negative")
    n: float = quantity("dimensionless", "Hardening exponent n.")
    c: float = quantity("dimensionless", "Strain-rate coefficient C.", bound="non_negative", default=0.0)
    reference_rate: float = quantity("rate", "Reference strain rate.", default=1.0)
    m: float = quantity("dimensionless", "Thermal softening exponent m.", default=1.0)
    temperature: float = quantity("temperature", "Test temperature.", default=293.15)
    room_temperature: float = quantity("temperature", "Reference (room) temperature.", default=293.15)
    melting_temperature: float = quantity("temperature", "Melting temperature.", default=1356.0)
    failure_strain: Optional[float] = _failure_strain()
    softening_strain: Optional[float] = _softening_strain()
    code = JOHNSON_COOK

    def __post_init__(self) -> None:
        check(self)
        self._check_failure()
        if not self.room_temperature < self.melting_temperature:
            raise ValueError(f"JohnsonCook.melting_temperature: must be above room_temperature = "
                             f"{self.room_temperature:.6g} K, got {self.melting_temperature:.6g} K")
        if not self.temperature < self.melting_temperature:
            raise ValueError(f"JohnsonCook.temperature: must be below melting_temperature = "
                             f"{self.melting_temperature:.6g} K (a molten specimen has no flow stress), got "
                             f"{self.temperature:.6g} K")

    @property
    def thermal_factor(self) -> float:
        """1 - T*^m."""
        t_star = (self.temperature - self.room_temperature) / (self.melting_temperature - self.room_temperature)
        return 1.0 - t_star ** self.m if t_star > 0.0 else 1.0

    def kernel(self) -> np.ndarray:
        return self._failure_params(_params(self.youngs_modulus, self.a, self.b, self.n, self.c,
                                            self.reference_rate, self.thermal_factor))


@element("law", "cowper-symonds")
@dataclass(frozen=True)
class CowperSymonds(Law):
    """Cowper-Symonds rate enhancement of a linearly hardening yield stress (G. R. Cowper, P. S. Symonds, Brown
    University Tech. Rep. 28, 1957; N. Jones, Structural Impact, 2nd ed., Cambridge 2012, eq. 8.3):
    sigma_y = (sigma_0 + H alpha) (1 + (rate / D)^(1/q))."""

    youngs_modulus: float = quantity("pressure", "Young's modulus E.")
    yield_stress: float = quantity("pressure", "Static yield stress sigma_0.")
    d: float = quantity("rate", "Rate constant D (mild steel: 40.4 1/s, Jones 2012).")
    q: float = quantity("dimensionless", "Rate exponent q (mild steel: 5).")
    hardening: float = quantity("pressure", "Plastic hardening modulus H.", bound="non_negative", default=0.0)
    code = COWPER_SYMONDS

    def __post_init__(self) -> None:
        check(self)

    def kernel(self) -> np.ndarray:
        return _params(self.youngs_modulus, self.yield_stress, self.hardening, self.d, self.q)


@element("law", "frew")
@dataclass(frozen=True)
class FrewShaper(Law):
    """Pulse-shaper loading law of Frew, Forrestal and Chen (Exp. Mech. 42 (2002) 93-106, eq. 9):
    sigma = sigma_0 eps^n / (1 - eps^m) in compression (engineering measures: the law's fit includes the area
    change), elastic unloading with E from the largest strain reached; compression only."""

    stress: float = quantity("pressure", "Stress constant sigma_0 (fitted per shaper material, Frew et al. 2002).")
    n: float = quantity("dimensionless", "Exponent n.")
    m: float = quantity("dimensionless", "Exponent m.")
    youngs_modulus: float = quantity("pressure", "Unloading modulus E (default: copper, 117 GPa).", default=117e9)
    code = FREW
    compression_only = True

    def __post_init__(self) -> None:
        check(self)

    def kernel(self) -> np.ndarray:
        return _params(self.youngs_modulus, self.stress, self.n, self.m)


@element("law", "tabulated")
@dataclass(frozen=True, eq=False)
class TabulatedLaw(Law):
    """Flow stress tabulated against the accumulated plastic strain, optionally one curve per strain rate
    (interpolated linearly in the plastic strain and in log(rate), held beyond the table), with elastic modulus
    E: for flow curves measured in earlier tests. From a CSV ``file`` (first column the plastic strain, then one
    stress column per rate, headed ``stress [MPa]`` for a single curve or ``<rate> 1/s [MPa]``; lines starting
    with ``#`` are comments) or from arrays (``plastic_strain``, ``stress`` rate by rate, ``rates`` in 1/s).
    Every curve must start at plastic strain 0 and must not decrease, and a faster rate must not give a lower
    stress: otherwise the joint's equation would have several solutions."""

    youngs_modulus: float = quantity("pressure", "Young's modulus E (elastic loading and unloading).")
    file: Optional[str] = path("CSV file: plastic strain, then one flow-stress column per strain rate.")
    plastic_strain: Any = None
    stress: Any = None
    rates: Any = None
    code = TABULATED

    def __post_init__(self) -> None:
        check(self)
        if (self.file is None) == (self.plastic_strain is None):
            raise ValueError("TabulatedLaw: give either file or plastic_strain with stress")
        if self.file is not None:
            strain, stress, rates = _read_flow_table(self.file)
        else:
            strain = finite_array("TabulatedLaw.plastic_strain", self.plastic_strain, min_size=2)
            stress = np.atleast_2d(finite_array("TabulatedLaw.stress", self.stress, ndim=np.ndim(self.stress),
                                                unit="Pa"))
            rates = np.ones(1) if self.rates is None else finite_array("TabulatedLaw.rates", self.rates,
                                                                        unit="1/s")
        _check_flow_table(strain, stress, rates)
        object.__setattr__(self, "plastic_strain", strain)
        object.__setattr__(self, "stress", stress)
        object.__setattr__(self, "rates", rates)

    @classmethod
    def from_function(cls, youngs_modulus: Any, flow_stress: Callable[[np.ndarray, float], Any],
                      max_plastic_strain: float = 1.0, rates: Any = None, points: int = 2001) -> "TabulatedLaw":
        """A user's flow-stress function ``flow_stress(plastic_strain, rate)`` (plastic strains as an array, the
        rate in 1/s; stresses in Pa) sampled at ``points`` plastic strains from 0 to ``max_plastic_strain`` at each
        of ``rates`` (default: one curve, called with rate 1 1/s). The compiled solver then interpolates the
        samples (linear: an error of order (max_plastic_strain / points)^2 times the curve's second derivative),
        and the samples are checked like any table (monotone in strain and rate)."""
        e_max = positive("TabulatedLaw.from_function max_plastic_strain", max_plastic_strain)
        if isinstance(points, bool) or not isinstance(points, int) or points < 2:
            raise ValueError(f"TabulatedLaw.from_function points: must be an integer >= 2, got {points!r}")
        if not callable(flow_stress):
            raise TypeError(f"TabulatedLaw.from_function flow_stress: must be a callable f(plastic_strain, rate), "
                            f"got {type(flow_stress).__name__}")
        strain = np.linspace(0.0, e_max, points)
        rate_values = np.ones(1) if rates is None else finite_array("TabulatedLaw.from_function rates", rates)
        stress = []
        for r in rate_values:
            values = np.broadcast_to(np.asarray(flow_stress(strain, float(r)), dtype=float), strain.shape)
            stress.append(finite_array(f"TabulatedLaw.from_function flow_stress(eps_p, {r:g})", values))
        return cls(youngs_modulus, plastic_strain=strain, stress=np.array(stress), rates=rate_values)

    def kernel(self) -> np.ndarray:
        head = _params(self.youngs_modulus, self.plastic_strain.size, self.rates.size)
        return np.concatenate([head, self.rates, self.plastic_strain, self.stress.ravel()])


def _check_flow_table(strain: np.ndarray, stress: np.ndarray, rates: np.ndarray) -> None:
    """Refuse a table whose flow stress could decrease (in plastic strain or with the rate), by name."""
    if strain[0] != 0.0 or np.any(np.diff(strain) <= 0.0):
        raise ValueError("TabulatedLaw.plastic_strain: must start at 0 and increase strictly")
    if stress.shape != (rates.size, strain.size):
        raise ValueError(f"TabulatedLaw.stress: needs {rates.size} curve(s) of {strain.size} values (one per "
                         f"rate and plastic strain), got shape {stress.shape}")
    if np.any(rates <= 0.0) or np.any(np.diff(rates) <= 0.0):
        raise ValueError("TabulatedLaw.rates: must be > 0 and increase strictly")
    for i in range(rates.size):
        if stress[i, 0] <= 0.0:
            raise ValueError(f"TabulatedLaw.stress: the yield stress of curve {i} must be > 0, got {stress[i, 0]:.6g} Pa")
        drops = np.flatnonzero(np.diff(stress[i]) < 0.0)
        if drops.size:
            k = int(drops[0]) + 1
            raise ValueError(f"TabulatedLaw.stress: not monotone: curve {i} (rate {rates[i]:.6g} 1/s) falls from "
                             f"{stress[i, k - 1]:.6g} Pa to {stress[i, k]:.6g} Pa at plastic strain {strain[k]:.6g}; "
                             "a softening table makes the joint's solution ambiguous")
    slower = np.flatnonzero(np.any(np.diff(stress, axis=0) < 0.0, axis=1))
    if slower.size:
        raise ValueError(f"TabulatedLaw.stress: the curve at {rates[slower[0] + 1]:.6g} 1/s lies below the one at "
                         f"{rates[slower[0]]:.6g} 1/s: a faster rate must not give a lower flow stress")


def _read_flow_table(file: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Plastic strains, stresses (rates x points, Pa) and rates (1/s) of a flow-table CSV file."""
    import pandas as pd

    where = f"TabulatedLaw.file: {file!r}"
    try:
        table = pd.read_csv(file, comment="#", skipinitialspace=True)
    except (OSError, ValueError, UnicodeDecodeError) as exc:
        raise ValueError(f"{where}: cannot be read as a CSV table ({type(exc).__name__}: {str(exc)[:200]})") \
            from None
    if table.shape[1] < 2 or table.shape[0] < 2:
        raise ValueError(f"{where}: needs a plastic-strain column and at least one stress column, two rows or more")
    rates, stresses = [], []
    for name in table.columns[1:]:
        head, _, unit = str(name).partition("[")
        unit = unit.rstrip("] ") or "Pa"
        head = head.strip()
        rate = 1.0 if head.lower() == "stress" else _rate(head, where)
        rates.append(rate)
        factor = to_si(f"{where} column {name!r}", f"1 {unit}", "Pa")     # e.g. MPa -> 1e6
        if factor is None:
            raise ValueError(f"{where}: the unit of column {name!r} is not a stress unit, got {unit!r}")
        stresses.append(factor * finite_array(f"{where} column {name!r}",
                                              table[name].to_numpy(dtype=float, na_value=np.nan)))
    strain = finite_array(f"{where} column {table.columns[0]!r}", table.iloc[:, 0].to_numpy(dtype=float,
                                                                                        na_value=np.nan))
    order = np.argsort(rates)
    return strain, np.array(stresses)[order], np.array(rates)[order]


def _rate(head: str, where: str) -> float:
    text = head.replace("1/s", "").strip()
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"{where}: a stress column is headed 'stress [unit]' or '<rate> 1/s [unit]', got "
                         f"{head!r}") from None
