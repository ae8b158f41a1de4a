"""Identification (docs/identification.md): the impedance profile Z(x) of an unknown pile, rod or striker from a
measured record, with bands; the thesis's scattering problem (chapter 1) solved by layer peeling (chapter 4's
recursion run on a measured face response), the Case-method integrity factor beta, and striker identification.

An application layer above the solvers and the measurement layer, below files, figures and the command line
(docs/architecture.md). SI units; forces positive in tension, depth from the measured face along the rod.
"""

from .result import Anomaly, IdentificationResult

__all__ = ["Anomaly", "IdentificationResult"]
