"""The one xarray layout of a :class:`~rodimpact.SimulationResult`: what :meth:`SimulationResult.to_xarray` returns
and what ``result.nc`` holds (:func:`rodimpact.save` writes this dataset as it is).

Dimensions and their coordinates:

* ``time`` (s, step start times of the recorded steps), ``energy_time`` (s), ``snapshot_time`` (s);
* ``probe``: the probe names, so ``ds.probe_force.sel(probe="SG1")`` picks one probe;
* ``junction``: 0 .. n_rods - 2 (junction j joins rod j and rod j + 1; absent for a single rod);
* ``end``: ``"left"``, ``"right"``; ``rod``: 0 .. n_rods - 1;
* ``element`` and ``node`` of the lattice, with the reference positions ``element_x`` and ``node_x`` (m) as
  coordinates; ``phase`` (contact phases of all junctions) and ``rod_bound``.

Variables: ``junction_force``, ``junction_contact`` (junction, time); ``end_force``, ``end_velocity`` (end, time);
``probe_force``, ``probe_velocity``, ``probe_displacement``, ``probe_strain`` (probe, time) and ``probe_rod``,
``probe_position``, ``probe_node_position`` (probe); energies, works and momentum per rod (rod, energy_time); the
lattice (``impedance``, ``element_length``, ``rod_start``, ``rod_*``), the final state and the field snapshots
(``force_field``, ``velocity_field`` (element, snapshot_time), ``displacement_field`` (node, snapshot_time)); the
contact events; with deformable joints their outcomes (``joint_*`` along ``joint``); with lumped chains their
energies (``lumped_*`` along ``lumped``, the per-item values in the attribute ``lumped_items``); with a bit-rock
end, its outcome (``bit_rock_*`` along ``bit_rock``, whose coordinate names the end:
:class:`~rodimpact.direct.result.BitRockOutcome`; absent in files written before it); with soil, the
:class:`~rodimpact.direct.soil_result.SoilOutcome` (``soil_*`` along ``soil_node``, ``soil_toe_*`` along
``soil_toe``). Every variable has a
``units`` attribute. Written so that every NetCDF flavour can hold it: integers as int32/int8, no variables
along empty dimensions (a single rod has no junction), the diagnostics as a JSON attribute. The column names of
:meth:`SimulationResult.to_dataframe` are these variables per coordinate (``contact_force``, ``<probe>_force``,
``left_end_force``, ...).
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np

from .._version import __version__
from .soil_result import soil_variables

#: Version of the layout (``format_version`` attribute of ``result.nc``). 1: histories only; 2: recording stride,
#: steps and contact events; 3: ``probe``, ``junction``, ``end``, ``rod`` and time coordinates (probe names were a
#: JSON attribute ``probe_names`` before).
FORMAT_VERSION = 3


#: The fields of a :class:`~rodimpact.direct.result.BitRockOutcome` stored as ``bit_rock_<field>``, with units.
BIT_ROCK_FIELDS = {"loading_stiffness": "N/m", "unloading_stiffness": "N/m", "max_penetration": "m",
                   "final_penetration": "m", "energy": "J", "striker": "", "striker_energy": "J"}


#: The fields of a :class:`~rodimpact.direct.result.JointOutcome` stored as ``joint_<field>``, with units.
JOINT_FIELDS = {"junction": "", "shortening": "m", "strain": "1", "plastic_strain": "1",
                "accumulated_plastic_strain": "1", "plastic_work": "J", "stored_energy": "J",
                "damage_work": "J", "softening": "1"}


#: The energies of a :class:`~rodimpact.direct.result.LumpedOutcome` stored as ``lumped_<field>`` (J) along
#: ``lumped`` (its coordinate: the chain's place); the mass velocities and cushion compressions of each chain go
#: into the attribute ``lumped_items`` (JSON: [[velocities, max_compressions], ...]).
LUMPED_FIELDS = ("initial_kinetic_energy", "kinetic_energy", "stored_energy", "dissipated_energy", "energy_to_rods")


def json_default(o: Any) -> Any:
    """``json.dumps`` fallback for numpy scalars and arrays, tuples and sets (anything else as its ``str``)."""
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (tuple, set)):
        return list(o)
    return str(o)


def result_dataset(result: Any, fields: bool = True):
    """Everything in ``result`` (except the system) as an :class:`xarray.Dataset` in the layout of this module;
    ``fields=False`` leaves out the field snapshots."""
    import xarray as xr

    lat = result.lattice
    data: dict[str, Any] = {}
    coords: dict[str, Any] = {
        "time": ("time", result.time, {"units": "s"}),
        "energy_time": ("energy_time", result.energy.time, {"units": "s"}),
        "end": ("end", np.array(["left", "right"]), {}),
        "rod": ("rod", np.arange(lat.n_rods, dtype=np.int32), {"long_name": "rod index, left to right"}),
        "element_x": ("element", lat.element_x, {"units": "m", "long_name": "reference centre position"}),
        "node_x": ("node", lat.node_x, {"units": "m", "long_name": "reference node position"}),
    }
    n_j = result.junction_force.shape[0]
    if n_j:
        coords["junction"] = ("junction", np.arange(n_j, dtype=np.int32),
                              {"long_name": "junction j joins rod j and rod j + 1"})
        data["junction_force"] = (("junction", "time"), result.junction_force, {"units": "N"})
        data["junction_contact"] = (("junction", "time"), result.junction_contact.astype(np.int8), {})
    data["end_force"] = (("end", "time"), np.vstack([result.end_force["left"], result.end_force["right"]]),
                         {"units": "N"})
    data["end_velocity"] = (("end", "time"),
                            np.vstack([result.end_velocity["left"], result.end_velocity["right"]]), {"units": "m/s"})
    probes = list(result.probes.values())
    if probes:
        coords["probe"] = ("probe", np.array([p.probe.name for p in probes]), {})
        for q, unit in (("force", "N"), ("velocity", "m/s"), ("displacement", "m"), ("strain", "1")):
            data[f"probe_{q}"] = (("probe", "time"), np.vstack([getattr(p, q) for p in probes]), {"units": unit})
        data["probe_rod"] = (("probe",), np.array([p.probe.rod for p in probes], dtype=np.int32), {})
        data["probe_position"] = (("probe",), np.array([p.probe.position for p in probes]), {"units": "m"})
        data["probe_node_position"] = (("probe",), np.array([p.node_position for p in probes]), {"units": "m"})
    e = result.energy
    data["kinetic_energy"] = (("rod", "energy_time"), e.kinetic, {"units": "J"})
    data["strain_energy"] = (("rod", "energy_time"), e.strain, {"units": "J"})
    data["momentum"] = (("rod", "energy_time"), e.momentum, {"units": "N s"})
    for name in ("work_left", "work_right", "work_loads", "work_friction", "work_joints", "work_soil"):
        data[name] = (("energy_time",), getattr(e, name), {"units": "J"})
    data["impulse"] = (("energy_time",), e.impulse, {"units": "N s"})
    data["impedance"] = (("element",), lat.impedance, {"units": "N s/m"})
    data["element_length"] = (("element",), lat.element_length, {"units": "m"})
    data["rod_start"] = (("rod_bound",), lat.rod_start.astype(np.int32), {})
    for name in ("time_scale", "true_length", "true_mass", "lattice_mass", "true_travel_time",
                 "max_boundary_offset"):
        data[f"rod_{name}"] = (("rod",), np.array([getattr(r, name) for r in lat.rods], dtype=float), {})
    data["rod_exact"] = (("rod",), np.array([r.exact for r in lat.rods], dtype=np.int8), {})
    data["final_force"] = (("element",), result.final_force, {"units": "N"})
    data["final_velocity"] = (("element",), result.final_velocity, {"units": "m/s"})
    s = result.snapshots
    if s is not None and fields:
        coords["snapshot_time"] = ("snapshot_time", s.time, {"units": "s"})
        data["force_field"] = (("element", "snapshot_time"), s.force, {"units": "N"})
        data["velocity_field"] = (("element", "snapshot_time"), s.velocity, {"units": "m/s"})
        data["displacement_field"] = (("node", "snapshot_time"), s.displacement, {"units": "m"})
    events = result.junction_events or ()
    if events:
        data["junction_min_force"] = (("junction",), np.array([e.min_force for e in events]), {"units": "N"})
        data["junction_min_force_step"] = (("junction",), np.array([e.min_force_step for e in events],
                                                                   dtype=np.int32), {})
        data["junction_max_abs_force"] = (("junction",), np.array([e.max_abs_force_run for e in events]),
                                          {"units": "N"})
    if sum(e.start.size for e in events):
        # contact phases of all junctions, one row per phase: [start, stop) in steps
        data["phase_junction"] = (("phase",), np.concatenate([np.full(e.start.size, j, dtype=np.int32)
                                                              for j, e in enumerate(events)]), {})
        data["phase_start"] = (("phase",), np.concatenate([e.start for e in events]).astype(np.int32), {})
        data["phase_stop"] = (("phase",), np.concatenate([e.stop for e in events]).astype(np.int32), {})
        data["phase_max_abs_force"] = (("phase",), np.concatenate([e.max_abs_force for e in events]),
                                       {"units": "N"})
    if result.bit_rock:
        coords["bit_rock"] = ("bit_rock", np.array([o.end for o in result.bit_rock]),
                              {"long_name": "outer end with a bit-rock interaction"})
        for name, unit in BIT_ROCK_FIELDS.items():
            values = np.array([getattr(o, name) for o in result.bit_rock])
            data[f"bit_rock_{name}"] = (("bit_rock",), values.astype(np.int32) if name == "striker" else values,
                                        {"units": unit} if unit else {})
    if result.joints:
        for name, unit in JOINT_FIELDS.items():
            values = np.array([getattr(o, name) for o in result.joints])
            data[f"joint_{name}"] = (("joint",), values.astype(np.int32) if name == "junction" else values,
                                     {"units": unit} if unit else {})
    if result.lumped:
        coords["lumped"] = ("lumped", np.array([o.place for o in result.lumped]),
                            {"long_name": "place of a lumped chain (left, right, junction <r>)"})
        for name in LUMPED_FIELDS:
            data[f"lumped_{name}"] = (("lumped",), np.array([getattr(o, name) for o in result.lumped]),
                                      {"units": "J"})
    soil_data, soil_coords = soil_variables(getattr(result, "soil", None))
    data.update(soil_data)
    coords.update(soil_coords)
    attrs = {"title": "rodimpact simulation result", "rodimpact_version": __version__,
             "format_version": FORMAT_VERSION, "dt": float(result.dt), "steps": int(result.n_steps),
             "record_every": int(result.record_every),
             "rod_methods": json.dumps([r.method for r in lat.rods]),
             "diagnostics": json.dumps(result.diagnostics, default=json_default),
             "conventions": "SI units; normal force positive in tension; node values per step at the step start "
                            "time k*dt, every record_every-th step kept; contact phases [start, stop) in steps"}
    if result.lumped:
        attrs["lumped_items"] = json.dumps([[o.velocities, o.max_compressions] for o in result.lumped])
    return xr.Dataset(data, coords=coords, attrs=attrs)
