"""Striker design when the exact inverse fails (a layer above :mod:`rodimpact.direct` and
:mod:`rodimpact.inverse`, see docs/design.md): :func:`design` finds the best striker that can exist and be
machined under bounds, a mass and step limits, with exact adjoint gradients. What is asked is one objective
(:class:`MatchObjective`, :class:`EfficiencyObjective`, :class:`StrainRateObjective`), the striker's :class:`StrikerLimits` and the
:class:`SearchOptions`."""

from .constraints import StrikerLimits
from .design import SearchOptions, design
from .objectives import EfficiencyObjective, MatchObjective, StrainRateObjective
from .result import DesignResult, DesignVerification

__all__ = ["design", "DesignResult", "DesignVerification", "MatchObjective", "EfficiencyObjective", "StrikerLimits",
           "SearchOptions", "StrainRateObjective"]
