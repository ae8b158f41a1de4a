"""What a blow did to the soil (:class:`SoilOutcome`), and the next blow from a result's final soil state
(:func:`next_blow`). Conventions of :mod:`rodimpact.rods.soil`: displacements and sets +x along the shaft,
outward at the toe; the resistance R > 0 opposes them."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Optional, Sequence

import numpy as np

from ..lattice.lattice import Lattice
from ..rods.soil import ShaftResistance, SoilToe
from ..rods.system import InitialState, System
from . import soil as S


@dataclass(frozen=True, repr=False)
class SoilOutcome:
    """The soil at the end of a run.

    Shaft nodes (one entry each, left to right over the system's lattice nodes that carry
    :class:`~rodimpact.rods.soil.ShaftResistance`): ``rod``, ``node`` (the rod's interior node m, between its
    elements m and m + 1, counted from 0), ``position`` (m from the rod's left end),
    ``ultimate`` R_u (N), ``displacement`` u (m), ``resistance`` R_s (N), ``plastic_set`` u_p (m, from the start
    position), ``work`` (J, done by the pile on the soil node in the run) and ``dissipated`` (J): the work minus
    the energy the soil spring still holds and would give back on unloading, R_s^2 / (2 k_u) (k_u the
    unloading stiffness; a run that starts loaded counts its initial spring energy as given).

    The toe (``toe_end`` "left"/"right", or None without a :class:`~rodimpact.rods.soil.SoilToe`): ``toe_*`` the
    same quantities. ``toe_set`` is the permanent set u_p of the toe, from the toe's start position: where the toe
    is once the pile has come to rest (R_s = 0; otherwise the displacement after a full unloading of the toe
    spring). ``toe_start_set`` is the u_p the run started with (a gap or preload left by the previous blow), and
    :attr:`set_per_blow` the difference: the permanent set of this blow.
    """

    rod: np.ndarray
    node: np.ndarray
    position: np.ndarray
    ultimate: np.ndarray
    displacement: np.ndarray
    resistance: np.ndarray
    plastic_set: np.ndarray
    work: np.ndarray
    dissipated: np.ndarray
    toe_end: Optional[str] = None
    toe_ultimate: float = 0.0
    toe_displacement: float = 0.0
    toe_resistance: float = 0.0
    toe_set: float = 0.0
    toe_work: float = 0.0
    toe_dissipated: float = 0.0
    toe_start_set: float = 0.0

    def __repr__(self) -> str:
        toe = f", toe set {self.toe_set:.4g} m" if self.toe_end else ""
        return (f"SoilOutcome({self.rod.size} shaft nodes, {float(self.dissipated.sum()):.6g} J dissipated along "
                f"the shaft{toe})")

    @property
    def set_per_blow(self) -> float:
        """The toe's permanent set in this blow, m: ``toe_set - toe_start_set``."""
        return self.toe_set - self.toe_start_set

    @property
    def total_dissipated(self) -> float:
        """Work dissipated by the shaft and the toe, J."""
        return float(self.dissipated.sum()) + self.toe_dissipated


def _stored(par: np.ndarray, state: np.ndarray) -> np.ndarray:
    """R_s^2 / (2 k_u) of the rows, J."""
    k_u = np.where(par[:, S.K_UNLOAD] > 0.0, par[:, S.K_UNLOAD], np.inf)
    return state[:, S.R_S] ** 2 / (2.0 * k_u)


def soil_outcome(system: System, lat: Lattice, arrays: dict, initial_state: np.ndarray) -> Optional[SoilOutcome]:
    """The :class:`SoilOutcome` of a run from its kernel arrays (``soil_state`` as the run left it,
    ``initial_state`` as it started); None without soil."""
    if not arrays["has_soil"]:
        return None
    par, st = arrays["soil_par"], arrays["soil_state"]
    n_sp = arrays["sp_elem"].size
    rows = np.flatnonzero(par[:n_sp, S.ACTIVE])
    a = arrays["sp_elem"][rows]
    rod = np.searchsorted(lat.rod_start, a, side="right") - 1
    position = lat.node_x[a + 1 + rod] - system.rod_offsets()[rod] if rows.size else np.zeros(0)
    dissipated = st[:, S.WORK] - (_stored(par, st) - _stored(par, initial_state))
    out = dict(rod=rod, node=a - lat.rod_start[rod], position=np.asarray(position, dtype=float),
               ultimate=par[rows, S.R_U],
               displacement=st[rows, S.U], resistance=st[rows, S.R_S], plastic_set=st[rows, S.U_P],
               work=st[rows, S.WORK], dissipated=dissipated[rows])
    for side, name in ((1, "right"), (0, "left")):
        row = n_sp + side
        if par[row, S.ACTIVE]:
            out.update(toe_end=name, toe_ultimate=float(par[row, S.R_U]), toe_displacement=float(st[row, S.U]),
                       toe_resistance=float(st[row, S.R_S]), toe_set=float(st[row, S.U_P]),
                       toe_work=float(st[row, S.WORK]), toe_dissipated=float(dissipated[row]),
                       toe_start_set=float(initial_state[row, S.U_P]))
            break
    return SoilOutcome(**out)


def next_blow(result: Any, velocities: Optional[Sequence[float]] = None, residual: bool = True) -> System:
    """The system of the next blow: that of ``result`` (a :class:`~rodimpact.SimulationResult`) with the soil in
    the state the blow left it (each node's static resistance R_s and plastic set u_p, now measured from the
    node's new start position: u_p - u), the rods at the ``velocities`` given (default those of the first
    blow) and, with ``residual``, the rods that carry soil starting with their final element forces (the
    residual forces that balance a loaded soil; their velocities are the given ones)."""
    soil: Optional[SoilOutcome] = result.soil
    system: System = result.system
    if soil is None or system is None:
        raise ValueError("result: has no soil state to carry over (a run with ShaftResistance or SoilToe, its "
                         "system kept)")
    loads = []
    for ld in system.loads:
        if isinstance(ld, ShaftResistance):
            on = soil.rod == ld.rod
            n_nodes = int(result.lattice.rod_start[ld.rod + 1] - result.lattice.rod_start[ld.rod]) - 1
            r_s, u_p = np.zeros(n_nodes), np.zeros(n_nodes)
            r_s[soil.node[on]] = soil.resistance[on]
            u_p[soil.node[on]] = soil.plastic_set[on] - soil.displacement[on]
            loads.append(dataclasses.replace(ld, resistance=tuple(r_s), plastic_set=tuple(u_p)))
        else:
            loads.append(ld)
    ends = {}
    for side in ("left", "right"):
        cond = getattr(system, side)
        if isinstance(cond, SoilToe) and soil.toe_end == side:
            ends[side] = dataclasses.replace(cond, resistance=max(soil.toe_resistance, 0.0),
                                             plastic_set=soil.toe_set - soil.toe_displacement)
    initial = list(system.initial)
    if residual:
        rs = result.lattice.rod_start
        for r in sorted(set(soil.rod.tolist()) | ({0} if soil.toe_end == "left" else set())
                        | ({system.n_rods - 1} if soil.toe_end == "right" else set())):
            initial[r] = InitialState(force=result.final_force[rs[r]:rs[r + 1]].copy())
    return dataclasses.replace(system, velocities=tuple(system.velocities if velocities is None else velocities),
                               loads=tuple(loads), initial=tuple(initial), **ends)


#: the shaft nodes' fields stored as ``soil_<field>`` along ``soil_node`` (units; integers as int32)
SHAFT_FIELDS = {"rod": "", "node": "", "position": "m", "ultimate": "N", "displacement": "m", "resistance": "N",
                "plastic_set": "m", "work": "J", "dissipated": "J"}
#: the toe's fields stored as ``soil_toe_<field>`` along ``soil_toe`` (one entry, its coordinate names the end)
TOE_FIELDS = {"ultimate": "N", "displacement": "m", "resistance": "N", "set": "m", "work": "J", "dissipated": "J",
              "start_set": "m"}


def soil_variables(soil: Optional[SoilOutcome]) -> tuple[dict, dict]:
    """The data variables and coordinates of a result file that hold ``soil`` (none without soil; no variable
    along an empty dimension)."""
    data: dict = {}
    coords: dict = {}
    if soil is None:
        return data, coords
    if soil.rod.size:
        for name, unit in SHAFT_FIELDS.items():
            values = getattr(soil, name)
            data[f"soil_{name}"] = (("soil_node",), values.astype(np.int32) if not unit else values,
                                    {"units": unit} if unit else {})
    if soil.toe_end is not None:
        coords["soil_toe"] = ("soil_toe", np.array([soil.toe_end]), {"long_name": "outer end with a soil toe"})
        for name, unit in TOE_FIELDS.items():
            data[f"soil_toe_{name}"] = (("soil_toe",), np.array([getattr(soil, f"toe_{name}")]), {"units": unit})
    return data, coords


def soil_from_variables(v: Any, coords: Any) -> Optional[SoilOutcome]:
    """The :class:`SoilOutcome` of a result file's variables ``v`` and coordinates (None if it holds none: no soil,
    or a file written before soil existed)."""
    has_shaft, has_toe = "soil_rod" in v, "soil_toe" in coords
    if not (has_shaft or has_toe):
        return None
    shaft = {name: (np.asarray(v[f"soil_{name}"], dtype=np.int64 if not unit else float) if has_shaft
                    else np.zeros(0, dtype=np.int64 if not unit else float)) for name, unit in SHAFT_FIELDS.items()}
    toe = {f"toe_{name}": float(v[f"soil_toe_{name}"][0]) for name in TOE_FIELDS} if has_toe else {}
    return SoilOutcome(**shaft, toe_end=str(coords["soil_toe"].values[0]) if has_toe else None, **toe)
