"""Identification (docs/identification.md): the impedance profile Z(x) of an unknown pile, rod or striker from a
measured record, with bands; the thesis's scattering problem (chapter 1) solved by layer peeling (chapter 4's
recursion run on a measured face response), the Case-method integrity factor beta, and striker identification.

An application layer above the solvers and the measurement layer, below files, figures and the command line
(docs/architecture.md). SI units; forces positive in tension, depth from the measured face along the rod.
"""

from .peeling import identify_by_peeling, peel_waves
from .records import (HeadRecord, amplified, average_blows, band_limited, hammer_record, split_waves,
                      waves_record)
from .reflectors import BETA_CLASSES, beta_class, identify_by_beta, reflectogram
from .striker import identify_striker
from .two_gauge import separate_waves
from .validity import IdentificationWarning, one_dimensional_warnings
from .result import Anomaly, IdentificationResult

__all__ = ["Anomaly", "BETA_CLASSES", "HeadRecord", "IdentificationResult", "IdentificationWarning", "amplified",
           "average_blows", "band_limited", "beta_class", "hammer_record", "identify_by_beta", "identify_by_peeling",
           "identify_striker", "one_dimensional_warnings", "peel_waves", "reflectogram", "separate_waves",
           "split_waves", "waves_record"]
