"""Notebook views of a :class:`~rodimpact.inverse.result.SynthesisResult`: its per-element table as a pandas
DataFrame and a compact HTML summary (mixed into the result class)."""

from __future__ import annotations

from typing import Any

from .._html import key_table

#: Units of the per-element columns (thesis Tabs. 4.3/4.4).
ELEMENT_UNITS = {"q": "-", "theta": "s", "s": "m", "impedance": "N s/m", "K": "-", "dN": "N", "reserve": "N",
                 "margin": "N"}


class SynthesisTables:
    """``to_dataframe()`` and ``_repr_html_()`` for :class:`~rodimpact.inverse.result.SynthesisResult`."""

    def to_dataframe(self) -> Any:
        """The per-element table (:meth:`table`, thesis Tabs. 4.3/4.4) as a :class:`pandas.DataFrame` indexed by
        the element number ``q`` (1 at the impact face): ``theta`` (s), ``s`` (m), ``impedance`` (N s/m), ``K``,
        ``dN`` (N), ``reserve`` (N), ``margin`` (N); a failing element is the last row with impedance NaN. Units
        in ``df.attrs["units"]``."""
        import pandas as pd

        rows = self.table()
        df = pd.DataFrame(rows, columns=list(ELEMENT_UNITS)).set_index("q")
        df.attrs["units"] = dict(ELEMENT_UNITS)
        return df

    def _repr_html_(self) -> str:
        z = self.impedance
        rows = [("elements", f"{self.n_feasible} of {self.n_requested} requested"),
                ("status", "feasible" if self.feasible else
                 f"stopped: {self.failure.reason} at element {self.failure.element}" if self.failure is not None
                 else "incomplete"),
                ("dt", f"{self.dt:.4g} s"), ("striker velocity", f"{self.striker_velocity:.4g} m/s")]
        if z.size:
            rows += [("impedance", f"{z.min():.4g} .. {z.max():.4g} N s/m"),
                     ("length", f"{self.length:.4g} m ({self.material.name or 'material'})"),
                     ("mass", f"{self.mass:.4g} kg")]
        return key_table("SynthesisResult", rows)
