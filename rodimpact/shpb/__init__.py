"""The split-Hopkinson (Kolsky) bar (docs/shpb.md): the forward model with specimens and pulse shapers between the
bars, and the data reduction of recorded or simulated gauge signals.

An application layer above the solvers and the measurement layer, below files, figures and the command line
(docs/architecture.md). SI units; bar strains and forces positive in tension, specimen stress, strain and
strain rate positive in compression.

Forward model: :class:`KolskyBar`, :class:`Gauge`, :class:`KolskyPrediction`, :func:`incident_for_constant_rate`.

Data reduction:

* :class:`Bar`, :class:`SpecimenGeometry` - the bars with their gauge distances, the specimen's initial size;
* :class:`GaugeSignals` - the incident-bar and transmitted-bar gauge strains (from arrays or a
  :class:`~rodimpact.signals.Recording`);
* :func:`find_windows`, :class:`PulseWindows`, :class:`Window` - pulse windows, automatic with overrides;
* :func:`reduce_shot` -> :class:`ShpbReduction` - 1-, 2- and 3-wave analyses, engineering and true measures,
  the equilibrium ratio R(t) (:class:`EquilibriumCheck`), CSV and netCDF output.
"""

from .equilibrium import PASS_LIMIT, REVIEW_LIMIT, EquilibriumCheck, check_equilibrium
from .gauge_signals import GaugeSignals
from .kolsky import Gauge, KolskyBar, KolskyPrediction, incident_for_constant_rate
from .parts import Bar, SpecimenGeometry
from .reduction import face_pulses, reduce_shot, specimen_responses
from .result import ANALYSES, ShpbReduction, SpecimenResponse
from .windows import PulseWindows, Window, find_windows

__all__ = [
    "ANALYSES",
    "Bar",
    "EquilibriumCheck",
    "Gauge",
    "GaugeSignals",
    "KolskyBar",
    "KolskyPrediction",
    "PASS_LIMIT",
    "PulseWindows",
    "REVIEW_LIMIT",
    "ShpbReduction",
    "SpecimenGeometry",
    "SpecimenResponse",
    "Window",
    "check_equilibrium",
    "face_pulses",
    "find_windows",
    "incident_for_constant_rate",
    "reduce_shot",
    "specimen_responses",
]
