"""Measurement side (thesis chapter 5): gauges and bridges, measuring-chain filters,
comparison of measured and simulated signals, first-mode dispersion.

No plotting, no file I/O and no solver here; readers for recording files are in
:mod:`rodimpact.io.recordings`, the simulated test rig of thesis chapter 5 in :mod:`rodimpact.testrig`.
"""

from .compare import (
    PeakComparison,
    ShotStatistics,
    align,
    crossing_times,
    delay_by_trigger,
    delay_by_xcorr,
    normalize_by_global_minimum,
    normalized_rms_error,
    peak_error,
    shifted,
    shot_statistics,
    step_timing_errors,
    trigger_time,
)
from .dispersion import (
    PochhammerChree,
    phase_velocity_at_frequency,
    phase_velocity_at_wavelength,
    propagate_dispersive,
    rayleigh_speed_ratio,
)
from .filters import MeasuringChain, bessel_analog, bessel_digital, simulate_analog_filter
from .gauges import (
    Bridge,
    GaugedBar,
    bending_ratio,
    bending_stress,
    bridge_to_strain,
    gauge_length_average,
    opposite_gauge_average,
    strain_to_force,
)
from .pulses import (
    PulseFeatures,
    VelocityEstimate,
    equal_impedance_pulse,
    pulse_features,
    rectangular_pulse,
    striker_velocity_estimate,
    striker_velocity_from_impulse,
    striker_velocity_from_strain,
)
from .recording import Recording

__all__ = [
    "Bridge",
    "GaugedBar",
    "MeasuringChain",
    "PeakComparison",
    "PochhammerChree",
    "PulseFeatures",
    "Recording",
    "ShotStatistics",
    "VelocityEstimate",
    "align",
    "bending_ratio",
    "bending_stress",
    "bessel_analog",
    "bessel_digital",
    "bridge_to_strain",
    "crossing_times",
    "delay_by_trigger",
    "delay_by_xcorr",
    "equal_impedance_pulse",
    "gauge_length_average",
    "normalize_by_global_minimum",
    "normalized_rms_error",
    "opposite_gauge_average",
    "peak_error",
    "phase_velocity_at_frequency",
    "phase_velocity_at_wavelength",
    "propagate_dispersive",
    "pulse_features",
    "rayleigh_speed_ratio",
    "rectangular_pulse",
    "shifted",
    "shot_statistics",
    "simulate_analog_filter",
    "step_timing_errors",
    "strain_to_force",
    "striker_velocity_estimate",
    "striker_velocity_from_impulse",
    "striker_velocity_from_strain",
    "trigger_time",
]
