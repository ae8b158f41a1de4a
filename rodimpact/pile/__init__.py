"""Pile driving (docs/pile-driving.md): the driving system (ram, cushions, helmet; drop, single-acting air/steam and
hydraulic hammers with published data), the soil (a capacity with a shaft share and distribution, or a layered
profile; Smith's model), one blow (permanent set, blow count, stress envelopes, transferred energy, gauges) and
the studies built on blows: the bearing graph, drivability over depth and the inspector's chart.

An application layer above the solvers, below files, figures and the command line (docs/architecture.md). SI
units inside (US customary for display: :mod:`rodimpact.pile.units`); x runs down the pile from its head, forces
are tension positive, downward velocity and set are positive.
"""

from .blow import Blow, StressEnvelope, blow_setup, drive_blow, drive_blows, stress_envelope, transferred_energy
from .driving import DrivingSystem, impact_velocity
from .hammers import HAMMER_KINDS, Hammer, hammer, hammer_names
from .soil import CapacitySoil, SoilDynamics, SoilLayer, SoilProfile, SoilResistance
from .soil_sets import SoilParameterSet, soil_set, soil_set_names

__all__ = [
    "Blow",
    "CapacitySoil",
    "DrivingSystem",
    "HAMMER_KINDS",
    "Hammer",
    "SoilDynamics",
    "SoilLayer",
    "SoilParameterSet",
    "SoilProfile",
    "SoilResistance",
    "StressEnvelope",
    "blow_setup",
    "drive_blow",
    "drive_blows",
    "hammer",
    "hammer_names",
    "soil_set",
    "soil_set_names",
    "impact_velocity",
    "stress_envelope",
    "transferred_energy",
]
