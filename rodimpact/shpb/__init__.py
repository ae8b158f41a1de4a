"""The split-Hopkinson (Kolsky) bar: data reduction of recorded or simulated gauge signals (docs/shpb.md).

An application layer above the solvers and the measurement layer, below files, figures and the command line
(docs/architecture.md). SI units; bar strains and forces positive in tension, specimen stress, strain and
strain rate positive in compression.

* :class:`Bar`, :class:`SpecimenGeometry` - the bars with their gauge distances, the specimen's initial size;
* :class:`GaugeSignals` - the incident-bar and transmitted-bar gauge strains (from arrays or a
  :class:`~rodimpact.signals.Recording`);
* :func:`find_windows`, :class:`PulseWindows`, :class:`Window` - pulse windows, automatic with overrides;
* :func:`reduce_shot` -> :class:`ShpbReduction` - 1-, 2- and 3-wave analyses, engineering and true measures,
  the equilibrium ratio R(t) (:class:`EquilibriumCheck`), CSV and netCDF output.
"""

from .equilibrium import PASS_LIMIT, REVIEW_LIMIT, EquilibriumCheck, check_equilibrium
from .gauge_signals import GaugeSignals
from .parts import Bar, SpecimenGeometry
from .reduction import face_pulses, reduce_shot, specimen_responses
from .result import ANALYSES, ShpbReduction, SpecimenResponse
from .windows import PulseWindows, Window, find_windows

__all__ = [
    "ANALYSES",
    "Bar",
    "EquilibriumCheck",
    "GaugeSignals",
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
    "reduce_shot",
    "specimen_responses",
]
