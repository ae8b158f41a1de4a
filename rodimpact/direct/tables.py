"""Notebook views of a :class:`~rodimpact.direct.result.SimulationResult`: a pandas table of its per-step
histories and a compact HTML summary (mixed into the result class)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._html import key_table


class SimulationTables:
    """``to_dataframe()`` and ``_repr_html_()`` for :class:`~rodimpact.direct.result.SimulationResult`."""

    def to_dataframe(self) -> Any:
        """The per-step histories as a :class:`pandas.DataFrame` indexed by ``time`` (s, the step start time; every
        ``record_every``-th step): ``contact_force`` (N, tension positive; ``contact_force_<j>`` per junction when
        there are several) and ``contact_<j>`` flags, ``<left|right>_end_force`` (N) and ``_end_velocity`` (m/s),
        and per probe ``<name>_force`` (N), ``_velocity`` (m/s), ``_displacement`` (m), ``_strain`` (-). The units
        of every column are in ``df.attrs["units"]``."""
        import pandas as pd

        cols: dict[str, np.ndarray] = {}
        units: dict[str, str] = {}
        n_j = self.junction_force.shape[0]
        for j in range(n_j):
            suffix = "" if n_j == 1 else f"_{j}"
            cols[f"contact_force{suffix}"], units[f"contact_force{suffix}"] = self.junction_force[j], "N"
            cols[f"contact{suffix}"], units[f"contact{suffix}"] = self.junction_contact[j].astype(bool), "-"
        for side in ("left", "right"):
            cols[f"{side}_end_force"], units[f"{side}_end_force"] = self.end_force[side], "N"
            cols[f"{side}_end_velocity"], units[f"{side}_end_velocity"] = self.end_velocity[side], "m/s"
        for name, p in self.probes.items():
            for q, unit in (("force", "N"), ("velocity", "m/s"), ("displacement", "m"), ("strain", "-")):
                cols[f"{name}_{q}"], units[f"{name}_{q}"] = getattr(p, q), unit
        df = pd.DataFrame(cols, index=pd.Index(self.time, name="time"))
        df.attrs["units"] = {"time": "s", **units}
        return df

    def _repr_html_(self) -> str:
        rows = [("rods", str(self.system.n_rods)), ("elements", str(self.lattice.n_elements)),
                ("steps", f"{self.n_steps} of dt = {self.dt:.4g} s"
                 + (f" (every {self.record_every}th recorded)" if self.record_every > 1 else "")),
                ("duration", f"{self.n_steps * self.dt:.6g} s")]
        for j, ev in enumerate(self.junction_events or ()):
            rows.append((f"junction {j}", f"peak force {ev.min_force / 1e3:.6g} kN, contact "
                                          f"{self.contact_duration(j) * 1e3:.6g} ms, "
                                          f"{self.separation_times(j).size} separation(s)"))
        rows.append(("rigid-body velocities", ", ".join(f"{v:.4g}" for v in self.rigid_body_velocity) + " m/s"))
        e0 = self.energy.kinetic[0] + self.energy.strain[0]
        if self.system.n_rods > 1 and e0[0] > 0.0:
            rows.append(("energy transfer (rod 0)", f"{self.efficiency:.2%}"))
        for o in self.bit_rock:
            eff = "" if o.efficiency is None else f" = {o.efficiency:.2%} of rod {o.striker}'s initial energy"
            rows.append((f"rock ({o.end} end)",
                         f"energy into the rock {o.energy:.4g} J{eff}; penetration per blow {o.penetration * 1e3:.4g} "
                         f"mm (largest {o.max_penetration * 1e3:.4g} mm)" + ("; bit still in contact" if o.in_contact
                                                                            else "")))
        rows.append(("energy balance error", f"{self.energy.balance_error:.2g}"))
        if self.probes:
            rows.append(("probes", ", ".join(self.probes)))
        for w in self.diagnostics.get("warnings", []):
            rows.append(("warning", str(w)))
        return key_table("SimulationResult", rows)
