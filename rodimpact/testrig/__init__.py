"""The thesis test rig (Secs. 5.1-5.4) as an application of the solvers: pistons, rod, strain-gauge stations, the
measuring chain, and the wave paths behind the steps seen at the gauges (:mod:`rodimpact.testrig.rig`).

It sits above ``direct/`` (it runs :func:`~rodimpact.simulate`) and ``signals/`` (the measuring chain), so that the
measurement layer itself does not depend on the solver (docs/architecture.md, "Layers").
"""

from .rig import (
    GAUGE_ANGLES,
    GAUGE_POSITIONS,
    IMPACT_VELOCITIES,
    RigSetup,
    RigSignals,
    WavePathEvent,
    build_rig,
    piston_1,
    piston_2,
    piston_from_face,
    rig_rod,
    rig_time_step,
    simulate_rig,
    wave_paths,
)

__all__ = [
    "GAUGE_ANGLES",
    "GAUGE_POSITIONS",
    "IMPACT_VELOCITIES",
    "RigSetup",
    "RigSignals",
    "WavePathEvent",
    "build_rig",
    "piston_1",
    "piston_2",
    "piston_from_face",
    "rig_rod",
    "rig_time_step",
    "simulate_rig",
    "wave_paths",
]
