"""Analytical references: Tab. 2.1 families, modal expansion, closed forms and exact wave trains.

Independent of :mod:`rodimpact.lattice` and :mod:`rodimpact.direct` (numpy/scipy only) so that it can check them.
"""

from rodimpact.reference.closed_forms import (
    lundberg_lesser_face_impedance,
    lundberg_lesser_force,
    lundberg_lesser_impedance,
    rigid_mass_force,
    rod_against_wall_fields,
    rod_against_wall_force,
    stepped_striker_force,
    uniform_striker_force,
)
from rodimpact.reference.families import FAMILIES, STEEL_BAR_SPEED, AnalyticProfile
from rodimpact.reference.horn_impact import HornImpact
from rodimpact.reference.modal import ModalChain, ModalSegment, ModalSolution
from rodimpact.reference.phase_speed import plot_phase_speed
from rodimpact.reference.wavetrains import UniformPiece, WaveTrainSolution, solve_wave_trains

__all__ = [
    "FAMILIES",
    "STEEL_BAR_SPEED",
    "AnalyticProfile",
    "HornImpact",
    "ModalChain",
    "ModalSegment",
    "ModalSolution",
    "UniformPiece",
    "WaveTrainSolution",
    "solve_wave_trains",
    "lundberg_lesser_face_impedance",
    "lundberg_lesser_force",
    "lundberg_lesser_impedance",
    "plot_phase_speed",
    "rigid_mass_force",
    "rod_against_wall_fields",
    "rod_against_wall_force",
    "stepped_striker_force",
    "uniform_striker_force",
]
