"""Striker design when the exact inverse fails (a layer above :mod:`rodimpact.direct` and
:mod:`rodimpact.inverse`, see docs/design.md): :func:`design` finds the best striker that can exist and be
machined under bounds, a mass and step limits, with exact adjoint gradients."""

from .design import design
from .result import DesignResult, DesignVerification

__all__ = ["design", "DesignResult", "DesignVerification"]
