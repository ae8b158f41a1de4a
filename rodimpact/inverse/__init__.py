"""Inverse problem: impactor synthesis by the recursive method (thesis chapter 4).

* :func:`synthesize` -- striker impedance profile for a prescribed impact force, or for a force prescribed at a
  position inside the struck system, with the existence check of eq. 4.20 at every element;
* :func:`transform_force` -- the transformation of a force at a position into the impact force (Sec. 4.1.2);
* :class:`StrikerShape` / :func:`impedance_to_shape` -- diameters, length and mass for a material;
* targets: :class:`ForceTarget` and the thesis's force histories;
* :func:`peel_layers` -- the layer peeling of a face's force and velocity history (eqs. 4.4-4.9; O(n^2) or the
  superfast Schur recursion by size), which :func:`synthesize` runs and :mod:`rodimpact.identify` uses on
  measured records.
"""

from .recursive import SynthesisWarning, synthesize
from .reference import ReferenceSynthesis, synthesize_by_resimulation
from .result import ExistenceFailure, SynthesisResult, VerificationReport
from .shape import StrikerShape, impedance_to_shape
from .targets import (ExponentialDecay, ExponentialGrowth, ForceTarget, LinearRamp, as_target,
                      lundberg_lesser_impedance)
from .transform import ForceTransformation, transform_force
from .examples import SynthesisProblem, academic_example, percussion_drilling_example
from ._schur import peel as peel_layers

__all__ = [
    "synthesize", "SynthesisResult", "ExistenceFailure", "VerificationReport", "SynthesisWarning",
    "transform_force", "ForceTransformation",
    "StrikerShape", "impedance_to_shape",
    "ForceTarget", "as_target", "ExponentialDecay", "LinearRamp", "ExponentialGrowth", "lundberg_lesser_impedance",
    "synthesize_by_resimulation", "ReferenceSynthesis",
    "SynthesisProblem", "academic_example", "percussion_drilling_example", "peel_layers",
]
