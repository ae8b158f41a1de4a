"""rodimpact: longitudinal impact of non-uniform elastic rods.

Direct problem (exact wave propagation method), inverse problem (impactor synthesis by the recursive method),
analytical references and measurement tools, after J. Burgert, *On direct and inverse problems related to
longitudinal impact of non-uniform elastic rods* (KIT).
"""

from ._version import __version__

from .rods.material import ALUMINIUM_7075, MATERIALS, STEEL, TITANIUM_TI6AL4V, Material
from .rods.segments import (AreaFunction, Cone, CoshHorn, CosHorn, Cylinder, ExponentialHorn, LinearAreaTaper,
                            QuadraticHorn, Segment, TabulatedProfile, Tube, stepped_profile)
from .rods.rod import Rod
from .rods.history import History
from .rods.conditions import (BitRockEnd, Bonded, Contact, Cushion, EndCondition, FixedEnd, ForceEnd, FreeEnd,
                              Junction, LumpedEnd, LumpedJoint, NonReflectingEnd, PointMass, PulseShaper, Specimen,
                              SpringDashpot, SpringEnd, VelocityEnd)
from .rods.laws import CowperSymonds, ElasticPlastic, FrewShaper, JohnsonCook, LinearElastic, TabulatedLaw
from .rods.loads import Bearings, NodalForce
from .rods.soil import ShaftResistance, SmithSoil, SoilToe
from .rods.system import InitialState, System
from .lattice.lattice import Lattice, build_lattice
from .direct.result import (BitRockOutcome, EnergyHistory, FieldSnapshots, JointOutcome, JunctionEvents,
                            LumpedOutcome, Probe, ProbeHistory, SimulationResult)
from .direct.recording import Outputs
from .direct.problem import Problem, TimeGrid
from .direct.simulate import simulate
from .direct.soil_result import SoilOutcome, next_blow
from .direct.sweep import drilling_metrics, sweep
from .direct.batch import BatchOutputs, BatchResult, simulate_batch
from .inverse import (ExistenceFailure, ExponentialDecay, ExponentialGrowth, ForceTarget, ForceTransformation,
                      LinearRamp, StrikerShape, SynthesisResult, SynthesisWarning, VerificationReport,
                      impedance_to_shape, synthesize, transform_force)
from .design import (DesignResult, EfficiencyObjective, MatchObjective, SearchOptions, StrainRateObjective,
                     StrikerLimits, design)
from .io.model import Model, dump_model, load_model, loads_model, save_model
from .io.results import summarize
from .io.storage import load, save
from . import inverse, io

_LAZY_SUBPACKAGES = ("identify", "plotting", "reference", "shpb", "signals", "testrig")   # matplotlib, scipy.optimize and scipy.signal are slow to import: load on use


def __getattr__(name: str):
    if name in _LAZY_SUBPACKAGES:
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'rodimpact' has no attribute {name!r}")

__all__ = [
    "__version__",
    "Material", "STEEL", "ALUMINIUM_7075", "TITANIUM_TI6AL4V", "MATERIALS",
    "Segment", "Cylinder", "Tube", "Cone", "LinearAreaTaper", "ExponentialHorn", "QuadraticHorn", "CoshHorn",
    "CosHorn", "TabulatedProfile", "stepped_profile", "AreaFunction",
    "Rod", "History", "System", "InitialState",
    "EndCondition", "FreeEnd", "FixedEnd", "ForceEnd", "VelocityEnd", "NonReflectingEnd", "SpringEnd",
    "BitRockEnd", "Junction", "Contact", "Bonded", "SpringDashpot", "Specimen", "PulseShaper",
    "PointMass", "Cushion", "LumpedEnd", "LumpedJoint",
    "LinearElastic", "ElasticPlastic", "JohnsonCook", "CowperSymonds", "FrewShaper", "TabulatedLaw", "NodalForce", "Bearings",
    "SmithSoil", "ShaftResistance", "SoilToe", "SoilOutcome", "next_blow",
    "Lattice", "build_lattice",
    "Problem", "TimeGrid", "simulate", "Outputs", "sweep", "drilling_metrics", "simulate_batch", "BatchOutputs",
    "BatchResult", "SimulationResult", "Probe", "ProbeHistory",
    "FieldSnapshots", "EnergyHistory",
    "JunctionEvents", "BitRockOutcome", "JointOutcome", "LumpedOutcome",
    "synthesize", "SynthesisResult", "SynthesisWarning", "ExistenceFailure", "VerificationReport",
    "transform_force", "ForceTransformation", "StrikerShape", "impedance_to_shape", "ForceTarget",
    "ExponentialDecay", "LinearRamp", "ExponentialGrowth",
    "design", "DesignResult", "MatchObjective", "EfficiencyObjective", "StrainRateObjective", "StrikerLimits",
    "SearchOptions",
    "Model", "load_model", "loads_model", "dump_model", "save_model", "load", "save", "summarize",
    "identify", "inverse", "io", "plotting", "reference", "shpb", "signals",
]
