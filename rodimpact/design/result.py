"""Result of :func:`rodimpact.design`: :class:`DesignResult`."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional

import numpy as np

from .._moved import removed_method
from ..direct.dataset import json_default
from ..direct.result import SimulationResult
from ..inverse.shape import MAX_DIAMETER_RATIO, StrikerShape
from ..inverse.struck import Location, simulate_observed, with_striker
from ..rods.material import STEEL, Material
from ..rods.rod import Rod
from ..rods.system import System


@dataclass(frozen=True)
class DesignVerification:
    """The designed striker run through :func:`rodimpact.simulate`: the achieved per-step quantity and its largest
    deviation from the design's own forward run (relative to max |achieved|), and the objective recomputed."""

    achieved: np.ndarray
    max_deviation: float
    misfit: Optional[float]
    efficiency: Optional[float]
    simulation: SimulationResult = field(repr=False)


@dataclass(frozen=True)
class DesignResult:
    """A striker found by :func:`rodimpact.design` (elements counted from the impact face, N s/m, s, m/s, N).

    Attributes
    ----------
    impedance:
        Z_1..Z_n from the impact face, N s/m, inside the bounds.
    striker_velocity:
        Impact velocity, m/s (optimised when ``StrikerLimits.velocity_bounds`` was given).
    dt:
        Travel time of each element, s.
    objective:
        "match" (a :class:`~rodimpact.MatchObjective`), "efficiency" (an :class:`~rodimpact.EfficiencyObjective`) or
        "strain-rate" (a :class:`~rodimpact.design.objectives.StrainRateObjective`; ``misfit`` is then the RMS
        relative deviation of the specimen's strain rate over the window).
    time:
        Start times k dt of the run's steps, s (from the impact).
    achieved:
        The observed per-step quantity of the design's run: the contact force at the impact face, or the force /
        incident wave at the objective's ``position`` (N, tension positive).
    face_force:
        Contact force per step, N.
    target:
        The target at the compared steps (N; empty for efficiency): the window values X_j at both steps of their
        window at the impact face, at the window starts after the dead time at a position.
    compared:
        The compared step indices (into ``time`` and ``achieved``).
    window_values:
        X_1..X_nw of the target, N (empty for efficiency).
    misfit:
        Relative L2 misfit of the achieved quantity to the target over the target's span (None for efficiency).
    efficiency:
        Work done on the rock per blow / striker kinetic energy (None for match).
    constraint_report:
        Elements at their lower/upper impedance bound, mass and whether it is on a bound, velocity bound activity.
    iterations:
        L-BFGS-B iterations over all starts and stages.
    wall_time:
        Seconds spent in :func:`design`.
    diagnostics:
        Forward/gradient run counts, starts and their values, warm-start outcome, convergence histories,
        existence diagnosis of the exact method, free-profile misfit of a stepped design, etc.
    """

    impedance: np.ndarray
    striker_velocity: float
    dt: float
    objective: str
    time: np.ndarray
    achieved: np.ndarray
    face_force: np.ndarray
    target: np.ndarray
    compared: np.ndarray
    window_values: np.ndarray
    misfit: Optional[float]
    efficiency: Optional[float]
    constraint_report: dict[str, Any]
    iterations: int
    wall_time: float
    struck: Optional[System] = field(default=None, repr=False)
    location: Optional[Location] = None
    quantity: str = "force"
    material: Material = STEEL
    diagnostics: dict[str, Any] = field(default_factory=dict, repr=False)

    def __repr__(self) -> str:
        what = (f"efficiency {self.efficiency:.4g}" if self.objective == "efficiency" else f"misfit {self.misfit:.3g}")
        return (f"DesignResult({self.objective}: {self.n_elements} elements, {what}, v = {self.striker_velocity:.4g} "
                f"m/s, Z {self.impedance.min():.4g}..{self.impedance.max():.4g} N s/m, mass {self.mass:.4g} kg)")

    @property
    def n_elements(self) -> int:
        return int(self.impedance.size)

    @property
    def mass(self) -> float:
        """dt sum Z_q, kg (any material)."""
        return float(self.dt * self.impedance.sum())

    @property
    def theta(self) -> np.ndarray:
        """Travel time (q-1) dt of each element's leading edge from the impact face, s."""
        return self.dt * np.arange(self.n_elements)

    @property
    def steps(self) -> int:
        """Number of distinct impedance levels of the profile (1 + number of impedance jumps)."""
        return 1 + int(np.count_nonzero(np.diff(self.impedance)))

    @property
    def uniform_reference(self) -> Optional[dict[str, Any]]:
        """Efficiency designs: the best uniform piston of the same mass over 1..n elements (``elements``,
        ``impedance`` N s/m, ``efficiency``, ``travel_time_s``, ``by_elements``), to see the gain of the design;
        None for match designs."""
        return self.diagnostics.get("uniform_reference")

    @property
    def convergence(self) -> list[list[float]]:
        """Objective value after every iteration, one list per start/stage."""
        return self.diagnostics.get("convergence", [])

    # ------------------------------------------------------------------ striker
    def to_rod(self, name: Optional[str] = "striker") -> Rod:
        """The striker as an exact impedance-level :class:`Rod`, elements left to right (impact face at the right
        end), for :func:`rodimpact.simulate`."""
        return Rod.from_impedance(self.impedance[::-1], self.dt, self.material.wave_speed,
                                  density=self.material.density, name=name)

    def shape(self, material: Optional[Material] = None, bore: float = 0.0,
              max_diameter_ratio: float = MAX_DIAMETER_RATIO) -> StrikerShape:
        """Geometry for ``material`` (default: the design's), solid or with a central bore of diameter ``bore``."""
        return StrikerShape(self.impedance, self.dt, material or self.material, bore, max_diameter_ratio)

    # ------------------------------------------------------------------ verification
    def verify(self, backend: str = "numba") -> DesignVerification:
        """Simulate the striker against the struck system with :func:`rodimpact.simulate` and compare with the
        design's own run; the objective is recomputed from the simulation."""
        if self.struck is None:
            raise ValueError("verify: this result carries no struck system")
        system = with_striker(self.struck, self.to_rod(), self.striker_velocity)
        sim, y = simulate_observed(system, self.location, self.quantity, self.time.size, self.dt, backend)
        dev = float(np.max(np.abs(y - self.achieved)) / max(np.max(np.abs(self.achieved)), 1e-300))
        misfit = eff = None
        if self.objective == "match":
            seg = y[self.compared]
            w = self.diagnostics.get("weights")
            w = np.ones(self.target.size) if w is None else np.asarray(w)
            misfit = float(np.sqrt(np.sum(w * (seg - self.target) ** 2) / np.sum(w * self.target ** 2)))
        else:
            work = -self.dt * float(np.dot(sim.end_force["right"], sim.end_velocity["right"]))
            eff = work / (0.5 * self.mass * self.striker_velocity ** 2)
        return DesignVerification(np.asarray(y, dtype=float), dev, misfit, eff, sim)

    # ------------------------------------------------------------------ export
    def to_xarray(self):
        """Per-element and per-step arrays as an :class:`xarray.Dataset` (scalars, the material, the observed
        location and, as JSON, the constraint report and the diagnostics as attributes); read back by
        :meth:`from_xarray`."""
        import xarray as xr

        data = {"impedance": ("element", self.impedance, {"units": "N s/m"}),
                "achieved": ("step", self.achieved, {"units": "N"}),
                "face_force": ("step", self.face_force, {"units": "N"}),
                "window_values": ("window", self.window_values, {"units": "N"}),
                "target": ("compared", self.target, {"units": "N"}),
                "compared_step": ("compared", self.compared)}
        coords = {"element": ("element", np.arange(1, self.n_elements + 1)),
                  "theta": ("element", self.theta, {"units": "s"}),
                  "time": ("step", self.time, {"units": "s"}),
                  "window": ("window", np.arange(1, self.window_values.size + 1))}
        attrs = {"objective": self.objective, "dt": self.dt, "striker_velocity": self.striker_velocity,
                 "mass": self.mass, "iterations": self.iterations, "wall_time": self.wall_time,
                 "quantity": self.quantity,
                 "constraint_report": json.dumps(self.constraint_report),
                 "material_E": self.material.youngs_modulus, "material_rho": self.material.density,
                 "material_name": self.material.name,
                 "diagnostics": json.dumps(self.diagnostics, default=json_default)}
        if self.misfit is not None:
            attrs["misfit"] = self.misfit
        if self.efficiency is not None:
            attrs["efficiency"] = self.efficiency
        if self.location is not None:
            attrs.update({f"location_{k}": v for k, v in vars(self.location).items()})
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_xarray(cls, ds: Any) -> "DesignResult":
        """The result in the dataset of :meth:`to_xarray` (what :func:`rodimpact.load` reads from a file). The
        struck system is not stored: :meth:`verify` is unavailable on it. The diagnostics come back from JSON
        (lists for arrays, text keys); files written before the material, the location and the diagnostics were
        stored give steel, no location and no diagnostics."""
        a = ds.attrs
        location = None
        if "location_used" in a:
            location = Location(float(a["location_requested"]), float(a["location_used"]), int(a["location_rod"]),
                                float(a["location_local"]), int(a["location_node"]), int(a["location_element_left"]))
        material = (Material(float(a["material_E"]), float(a["material_rho"]), str(a["material_name"]))
                    if "material_E" in a else STEEL)
        return cls(impedance=np.asarray(ds["impedance"].values, dtype=float),
                   striker_velocity=float(a["striker_velocity"]), dt=float(a["dt"]), objective=str(a["objective"]),
                   time=np.asarray(ds["time"].values, dtype=float),
                   achieved=np.asarray(ds["achieved"].values, dtype=float),
                   face_force=np.asarray(ds["face_force"].values, dtype=float),
                   target=np.asarray(ds["target"].values, dtype=float),
                   compared=np.asarray(ds["compared_step"].values, dtype=np.int64),
                   window_values=np.asarray(ds["window_values"].values, dtype=float),
                   misfit=float(a["misfit"]) if "misfit" in a else None,
                   efficiency=float(a["efficiency"]) if "efficiency" in a else None,
                   constraint_report=json.loads(a["constraint_report"]), iterations=int(a["iterations"]),
                   wall_time=float(a["wall_time"]), location=location, quantity=str(a["quantity"]),
                   material=material, diagnostics=json.loads(a.get("diagnostics", "{}")))

    def to_csv(self, path: str | Path, material: Optional[Material] = None, bore: float = 0.0,
               overwrite: bool = False) -> Path:
        """Write the striker profile for ``material`` (default the design's) and ``bore`` in rodimpact's striker
        CSV format (:meth:`rodimpact.inverse.StrikerShape.to_csv`: elements listed left to right, impact face
        last; a model file reads it back with ``[rods.elements] file = "striker.csv"``, dt from its ``theta``
        column); the impact velocity is noted in its comment lines."""
        return self.shape(material, bore).to_csv(
            path, overwrite, note=f"designed striker ({self.objective}); impact velocity {self.striker_velocity!r} m/s")

    save = removed_method("save every result with rodimpact.save(result, path) and read it back with "
                          "rodimpact.load(path)")
