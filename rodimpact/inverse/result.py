"""Result objects of :func:`rodimpact.synthesize` (frozen dataclasses, per-element arrays from the impact face)."""

from __future__ import annotations

import numbers
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from ..direct.result import SimulationResult
from ..direct.problem import Problem
from ..direct.recording import Outputs
from ..direct.simulate import simulate
from .._moved import removed_method
from ..rods.material import STEEL, Material
from ..rods.rod import Rod
from ..rods.system import System
from .shape import MAX_DIAMETER_RATIO, StrikerShape
from .struck import Location, position_probe, position_quantity, with_striker
from .tables import SynthesisTables
from .transform import ForceTransformation


@dataclass(frozen=True)
class ExistenceFailure:
    """The first striker element for which no physical impedance exists.

    ``reason`` is ``"existence"`` when |Delta N_q| >= |K_q N_0| (thesis eq. 4.20: the impedance would be
    negative or infinite) and ``"tension"`` when the impact force required in window q is not compressive
    (a contact cannot pull).
    """

    element: int                    # q, 1-based from the impact face
    theta: float                    # travel time of its leading edge, (q-1) dt, s
    transmission_factor: float      # K_q (eq. 4.8)
    force_difference: float         # Delta N_q (eq. 4.7), N
    force_reserve: float            # |K_q N_0|, N
    reflection: float               # the reflection coefficient it would need (|R| >= 1)
    reason: str
    message: str


@dataclass(frozen=True)
class VerificationReport:
    """Outcome of :meth:`SynthesisResult.verify`: the synthesized striker run through the direct solver.

    ``max_deviation`` = max |achieved - target| / max |target| over the compared samples: at the impact face
    both steps of every window; at a position the window starts after the dead time (the samples the
    transformation matches). ``max_deviation_all_steps`` compares every step of every window.
    """

    compared: str
    time: np.ndarray                # times of the compared samples, s
    target: np.ndarray
    achieved: np.ndarray
    max_deviation: float
    max_deviation_all_steps: float
    simulation: SimulationResult = field(repr=False)

    def __repr__(self) -> str:
        return (f"VerificationReport({self.compared}: {self.time.size} samples, max deviation "
                f"{self.max_deviation:.3g} (all steps {self.max_deviation_all_steps:.3g}) relative to max |target|)")


@dataclass(frozen=True)
class SynthesisResult(SynthesisTables):
    """Striker synthesized by the recursive method (thesis chapter 4).

    Per-element arrays have ``n_feasible`` = m entries, element q = 1..m counted from the impact face
    (array index q - 1). Forces in N (tension positive, impact forces negative), impedances in N s/m.

    Attributes
    ----------
    impedance:
        Z_q (eqs. 4.4, 4.9).
    reflection:
        R_q: force reflection coefficient of the wavefront at the interface in front of element q,
        R_1 = (Z_1 - Z~_1)/(Z_1 + Z~_1) towards the struck system, R_q = (Z_q - Z_{q-1})/(Z_q + Z_{q-1}).
    transmission_factor:
        K_q = prod_{r<q} (1 - R_r^2) (eqs. 4.6, 4.8; K_1 = 1).
    force_difference:
        Delta N_q = K_q R_q N_0 (eq. 4.7): the change of the impact force in window q caused by the step from
        Z_{q-1} to Z_q (for q = 1: X_1 - N_0).
    force_reserve:
        |K_q N_0|; the element exists while |Delta N_q| < |K_q N_0| (eq. 4.20).
    amplitude_growth:
        kappa_q, how much larger the peeled wave amplitudes that meet in element q's wavefront are than the
        wavefront (see :mod:`rodimpact.inverse._kernels`).
    error_estimate:
        First-order bound of the relative rounding error of Z_q.
    window_values:
        X_j, j = 1..n, the impact force the striker must produce (after transformation if a position is set).
    face_velocity:
        Struck-system face velocity per step, 2n values, m/s.
    impact_force_n0:
        N_0 of eq. 4.3 generalised to N_0 = X_1 / T_{1~,1} (equal to -(v_in - v~_in) Z~_1 / 2 for a struck
        system at rest in its first element).
    failure:
        :class:`ExistenceFailure` for element m + 1, or None when all n elements exist.
    """

    impedance: np.ndarray
    reflection: np.ndarray
    transmission_factor: np.ndarray
    force_difference: np.ndarray
    force_reserve: np.ndarray
    amplitude_growth: np.ndarray
    error_estimate: np.ndarray
    window_values: np.ndarray
    face_velocity: np.ndarray
    dt: float
    striker_velocity: float
    struck_face_impedance: float
    impact_force_n0: float
    n_requested: int
    struck: Optional[System] = field(default=None, repr=False)
    failure: Optional[ExistenceFailure] = None
    transformation: Optional[ForceTransformation] = field(default=None, repr=False)
    material: Material = STEEL
    diagnostics: dict[str, Any] = field(default_factory=dict, repr=False)

    # ------------------------------------------------------------------ basic properties
    @property
    def n_feasible(self) -> int:
        """Number m of elements for which a physical impedance exists."""
        return int(self.impedance.size)

    @property
    def feasible(self) -> bool:
        """True when all requested elements exist (the target can be produced for its whole duration)."""
        return self.failure is None and self.n_feasible == self.n_requested

    @property
    def element(self) -> np.ndarray:
        """Element numbers q = 1..m."""
        return np.arange(1, self.n_feasible + 1)

    @property
    def theta(self) -> np.ndarray:
        """Travel time theta_q = (q-1) dt of each element's leading edge from the impact face, s (eq. 4.25)."""
        return self.dt * np.arange(self.n_feasible)

    @property
    def element_position(self) -> np.ndarray:
        """Distance s_q = c theta_q of each element's leading edge from the impact face, m (for ``material``)."""
        return self.material.wave_speed * self.theta

    @property
    def margin(self) -> np.ndarray:
        """|K_q N_0| - |Delta N_q| (> 0 for every existing element), N."""
        return self.force_reserve - np.abs(self.force_difference)

    @property
    def travel_time(self) -> float:
        """Travel time through the feasible striker, m dt (s)."""
        return self.n_feasible * self.dt

    @property
    def length(self) -> float:
        """Length of the feasible striker, m (for ``material``)."""
        return self.material.wave_speed * self.travel_time

    @property
    def mass(self) -> float:
        """Mass of the feasible striker, dt sum Z_q (kg, any material)."""
        return float(self.dt * self.impedance.sum())

    @property
    def position(self) -> Optional[Location]:
        """Where the target was prescribed (None: at the impact face)."""
        return None if self.transformation is None else self.transformation.location

    # ------------------------------------------------------------------ reports
    def __repr__(self) -> str:
        status = "feasible" if self.feasible else f"stopped: {self.failure.reason} at element {self.failure.element}"
        z = self.impedance
        rng = f", Z {z.min():.4g}..{z.max():.4g} N s/m" if z.size else ""
        return (f"SynthesisResult({self.n_feasible}/{self.n_requested} elements, {status}{rng}, "
                f"dt = {self.dt:.4g} s)")

    def table(self, elements: Optional[Any] = None) -> list[dict[str, float]]:
        """Rows like thesis tables 4.3/4.4: q, theta (s), s (m), Z_q, K_q, Delta N_q, |K_q N_0|, margin;
        ``elements`` selects q values (default: all): a whole number or a 1-d sequence of them, each in 1..m or
        the failing element m + 1 (when there is one), which is shown with Z = nan (appended by default)."""
        qs = self.element if elements is None else self._element_numbers(elements)
        rows = []
        for q in qs:
            if 1 <= q <= self.n_feasible:
                i = q - 1
                rows.append(dict(q=int(q), theta=float(self.theta[i]), s=float(self.element_position[i]),
                                 impedance=float(self.impedance[i]), K=float(self.transmission_factor[i]),
                                 dN=float(self.force_difference[i]), reserve=float(self.force_reserve[i]),
                                 margin=float(self.margin[i])))
            elif self.failure is not None and q == self.failure.element:
                f = self.failure
                rows.append(dict(q=int(q), theta=f.theta, s=self.material.wave_speed * f.theta,
                                 impedance=float("nan"), K=f.transmission_factor, dN=f.force_difference,
                                 reserve=f.force_reserve, margin=f.force_reserve - abs(f.force_difference)))
            else:  # unreachable after _element_numbers; kept as a guard
                raise ValueError(f"elements: q = {q} was not computed; {self._elements_allowed()}")
        if elements is None and self.failure is not None:
            rows.append(self.table([self.failure.element])[0])
        return rows

    def _elements_allowed(self) -> str:
        m = self.n_feasible
        f = self.failure
        if m == 0:
            return ("no element exists, nothing to select" if f is None
                    else f"the only element that can be shown is the failing element {f.element}")
        return f"must be whole numbers 1..{m}" + ("" if f is None else f" (plus the failing element {f.element})")

    def _element_numbers(self, elements: Any) -> np.ndarray:
        """``elements`` of :meth:`table`/:meth:`report` checked and returned as a 1-d int array: a whole number
        or a 1-d sequence of them, each an existing element 1..m or the failing element."""
        allowed = self._elements_allowed()

        def shown(v: Any) -> str:
            text = repr(v)
            return text if len(text) <= 60 else text[:57] + "..."

        if isinstance(elements, (str, bytes, bool, np.bool_)):
            raise TypeError(f"elements: {allowed}, got {type(elements).__name__} {shown(elements)}")
        try:
            arr = np.asarray(elements)
            if arr.dtype.kind == "O":       # e.g. Python ints beyond int64, or a mix of types
                if not all(isinstance(v, numbers.Real) and not isinstance(v, bool) for v in arr.ravel()):
                    raise TypeError
                arr = np.asarray(elements, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"elements: {allowed}, got {type(elements).__name__} {shown(elements)}") from None
        if arr.dtype.kind not in "iuf":
            raise TypeError(f"elements: {allowed}, got {type(elements).__name__} {shown(elements)} "
                            f"(entries of type {arr.dtype})")
        if arr.ndim > 1:
            raise ValueError(f"elements: a single element number or a 1-d sequence of them, got shape {arr.shape}")
        arr = np.atleast_1d(arr)
        if arr.size == 0:
            raise ValueError(f"elements: got an empty selection; {allowed}, or None for all")
        x = arr.astype(float)
        bad = ~np.isfinite(x) | (x != np.round(x))
        if bad.any():
            raise ValueError(f"elements: {allowed}, got {arr[np.flatnonzero(bad)[0]].item()!r}")
        ok = (x >= 1) & (x <= self.n_feasible)
        if self.failure is not None:
            ok |= x == self.failure.element
        if not ok.all():
            q = arr[np.flatnonzero(~ok)[0]].item()
            raise ValueError(f"elements: q = {int(q)} was not computed; {allowed}")
        return x.astype(int)

    def report(self, elements: Optional[Any] = None) -> str:
        """Text version of :meth:`table` plus a summary (existence, length, mass)."""
        lines = [f"recursive method: {self.n_feasible} of {self.n_requested} elements exist "
                 f"(dt = {self.dt:.6g} s, v_in = {self.striker_velocity:.6g} m/s, N_0 = {self.impact_force_n0:.6g} N, "
                 f"Z~_1 = {self.struck_face_impedance:.6g} N s/m)"]
        if self.failure is not None:
            lines.append(self.failure.message)
        lines.append(f"feasible striker: travel time {self.travel_time:.6g} s, length {self.length:.6g} m "
                     f"({self.material.name or 'custom material'}), mass {self.mass:.6g} kg")
        lines.append(f"{'q':>6} {'theta/s':>12} {'s/m':>10} {'Z_q/(N s/m)':>14} {'K_q':>10} {'dN_q/N':>12} "
                     f"{'|K_q N_0|/N':>12} {'margin/N':>12}")
        for r in self.table(elements):
            lines.append(f"{r['q']:>6d} {r['theta']:>12.5g} {r['s']:>10.4g} {r['impedance']:>14.6g} {r['K']:>10.5g} "
                         f"{r['dN']:>12.5g} {r['reserve']:>12.5g} {r['margin']:>12.5g}")
        return "\n".join(lines)

    # ------------------------------------------------------------------ striker
    def to_rod(self, name: Optional[str] = "striker") -> Rod:
        """The feasible striker as an exact impedance-level :class:`Rod` for :func:`~rodimpact.simulate`,
        elements listed left to right (reversed from the impact-face order), impact face at its right end."""
        if self.n_feasible == 0:
            raise ValueError("to_rod: no striker element exists")
        return Rod.from_impedance(self.impedance[::-1], self.dt, self.material.wave_speed,
                                  density=self.material.density, name=name)

    def shape(self, material: Optional[Material] = None, bore: float = 0.0,
              max_diameter_ratio: float = MAX_DIAMETER_RATIO) -> StrikerShape:
        """Geometry of the feasible striker for ``material`` (default: the result's), solid or with a bore."""
        return StrikerShape(self.impedance, self.dt, material or self.material, bore, max_diameter_ratio)

    # ------------------------------------------------------------------ verification
    def verify(self, backend: str = "numba") -> VerificationReport:
        """Run the direct solver with the synthesized striker against the struck system and compare with the
        target over the feasible windows (see :class:`VerificationReport`)."""
        if self.struck is None:
            raise ValueError("verify: this result carries no struck system (loaded from a file?)")
        m = self.n_feasible
        if m == 0:
            raise ValueError("verify: no striker element exists")
        system = with_striker(self.struck, self.to_rod(), self.striker_velocity)
        tr = self.transformation
        if tr is None:
            sim = simulate(Problem.of(system, steps=2 * m, dt=self.dt, allow_discretization_error=True),
                           backend=backend)
            achieved = np.asarray(sim.junction_force[0], dtype=float)
            target = np.repeat(self.window_values[:m], 2)
            dev = np.max(np.abs(achieved - target)) / np.max(np.abs(target))
            return VerificationReport("impact force at every step of windows 1..m", sim.time, target, achieved,
                                      float(dev), float(dev), sim)
        loc = tr.location
        d = loc.node
        outputs = Outputs(probes=[position_probe(loc, 1)],
                          snapshot_times=[0.0] if tr.quantity == "incident" else None)
        sim = simulate(Problem.of(system, steps=d + 2 * m, dt=self.dt, outputs=outputs,
                                  allow_discretization_error=True), backend=backend)
        p = sim.probe("synthesis_position")
        k_left = sim.lattice.rod_start[1] + loc.element_left
        n0 = v0 = 0.0
        if tr.quantity == "incident":
            n0 = float(sim.snapshots.force[k_left, 0])
            v0 = float(sim.snapshots.velocity[k_left, 0])
        q = position_quantity(tr.quantity, p.force, p.velocity, float(sim.lattice.impedance[k_left]), n0, v0)
        y = tr.target[:m]
        scale = np.max(np.abs(y))
        starts = d + 2 * np.arange(m)
        dev = np.max(np.abs(q[starts] - y)) / scale
        dev_all = np.max(np.abs(q[d:d + 2 * m] - np.repeat(y, 2))) / scale
        return VerificationReport(f"{tr.quantity} at {loc.used:.6g} m at the window starts after the dead time",
                                  sim.time[starts], y, q[starts], float(dev), float(dev_all), sim)

    # ------------------------------------------------------------------ export
    def to_xarray(self):
        """Per-element and per-window arrays as an :class:`xarray.Dataset`."""
        import xarray as xr

        data = {
            "impedance": ("element", self.impedance, {"units": "N s/m"}),
            "reflection": ("element", self.reflection, {"units": "1"}),
            "transmission_factor": ("element", self.transmission_factor, {"units": "1"}),
            "force_difference": ("element", self.force_difference, {"units": "N"}),
            "force_reserve": ("element", self.force_reserve, {"units": "N"}),
            "amplitude_growth": ("element", self.amplitude_growth, {"units": "1"}),
            "error_estimate": ("element", self.error_estimate, {"units": "1"}),
            "window_values": ("window", self.window_values, {"units": "N"}),
            "face_velocity": ("step", self.face_velocity, {"units": "m/s"}),
        }
        if self.transformation is not None:
            data["position_target"] = ("window", self.transformation.target, {"units": "N"})
            data["rectangular_response"] = ("window", self.transformation.rectangular_response, {"units": "1"})
        coords = {"element": ("element", self.element), "theta": ("element", self.theta, {"units": "s"}),
                  "window": ("window", np.arange(1, self.window_values.size + 1)),
                  "step": ("step", np.arange(self.face_velocity.size))}
        attrs = {"dt": self.dt, "striker_velocity": self.striker_velocity,
                 "struck_face_impedance": self.struck_face_impedance, "impact_force_n0": self.impact_force_n0,
                 "n_requested": self.n_requested, "material_E": self.material.youngs_modulus,
                 "material_rho": self.material.density, "material_name": self.material.name}
        if self.failure is not None:
            for k, v in vars(self.failure).items():
                attrs[f"failure_{k}"] = v
        for k, v in self.diagnostics.items():
            attrs[f"diag_{k}"] = str(v)
        return xr.Dataset(data, coords=coords, attrs=attrs)

    save = removed_method("save every result with rodimpact.save(result, path) and read it back with "
                          "rodimpact.load(path)")
    load = removed_method("read a saved result with rodimpact.load(path)")

    @classmethod
    def from_xarray(cls, ds: Any) -> "SynthesisResult":
        """The result in the dataset of :meth:`to_xarray` (what :func:`rodimpact.load` reads from a file). The
        struck system and the transformation are not stored: :meth:`verify` is unavailable on it; the diagnostics
        come back as text."""
        a = ds.attrs
        failure = None
        if "failure_element" in a:
            failure = ExistenceFailure(int(a["failure_element"]), float(a["failure_theta"]),
                                       float(a["failure_transmission_factor"]), float(a["failure_force_difference"]),
                                       float(a["failure_force_reserve"]), float(a["failure_reflection"]),
                                       str(a["failure_reason"]), str(a["failure_message"]))
        diag = {k[5:]: v for k, v in a.items() if k.startswith("diag_")}
        return cls(*(np.asarray(ds[k].values, dtype=float) for k in (
            "impedance", "reflection", "transmission_factor", "force_difference", "force_reserve",
            "amplitude_growth", "error_estimate", "window_values", "face_velocity")),
            dt=float(a["dt"]), striker_velocity=float(a["striker_velocity"]),
            struck_face_impedance=float(a["struck_face_impedance"]), impact_force_n0=float(a["impact_force_n0"]),
            n_requested=int(a["n_requested"]), failure=failure,
            material=Material(float(a["material_E"]), float(a["material_rho"]), str(a["material_name"])),
            diagnostics=diag)
