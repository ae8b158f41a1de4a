"""Key paths of model and spec files for errors raised by the Python API.

The loaders hand the values of a file to :func:`rodimpact.simulate`, :func:`rodimpact.synthesize` and
:func:`rodimpact.design` (and the objects they take), whose errors name their Python arguments or fields (``dt:
must be > 0``, ``initial[1].force: must be finite``, ``n: ...``, ``StrikerLimits.mass: ...``). A user of a file
knows only its keys, so :func:`translated` rewrites the leading argument name of such a message into the key path
of the file (``synthesis.dt``, ``rods[1].initial.force``, ``striker.elements``, ``striker.mass``) and returns a :class:`~rodimpact.io.quantities.ModelError`.
"""

from __future__ import annotations

import re
from typing import Callable, Union

from .quantities import ModelError

Rule = Union[str, Callable[[re.Match], str]]

#: API argument of :func:`rodimpact.simulate` -> key path in a model file.
MODEL_KEYS: dict[str, Rule] = {
    "dt": "simulation.dt", "duration": "simulation.duration", "steps": "simulation.steps",
    "backend": "simulation.backend", "energy_every": "simulation.energy_every",
    "snapshot_times": "output.snapshot_times", "snapshot_every": "output.snapshot_every",
    "record_every": "output.record_every", "velocities": "rods[*].velocity", "left": "ends.left",
    "right": "ends.right", "initial": "rods[*].initial",
    r"initial\[(\d+)\]": lambda m: f"rods[{m.group(1)}].initial",
}

#: API argument of :func:`rodimpact.synthesize` -> key path in a synthesis spec.
SPEC_KEYS: dict[str, Rule] = {
    "dt": "synthesis.dt", "n": "striker.elements", "backend": "synthesis.backend",
    "striker_velocity": "striker.velocity", "material": "striker.material", "target": "target",
    "position": "target.position", "quantity": "target.quantity", "rule": "target.rule",
    "struck_velocity": "struck[*].velocity", "far_end": "far_end", "struck.left": "struck[0]",
    "struck.right": "far_end", "initial": "struck[*].initial",
    r"initial\[(\d+)\]": lambda m: f"struck[{m.group(1)}].initial",
    r"rods\[(\d+)\]": lambda m: f"struck[{m.group(1)}]",
}


def translate(message: str, keys: dict[str, Rule]) -> str:
    """``message`` with its leading API argument (``name:``, ``name[i]:`` or ``name.sub:``) replaced by the key
    path ``keys`` gives for it (keys holding ``(`` are regular expressions, others plain names); unchanged when it
    starts with no known argument."""
    for pattern, rule in sorted(keys.items(), key=lambda kv: -len(kv[0])):
        regex = pattern if "(" in pattern else re.escape(pattern)
        m = re.match(f"(?:{regex})(?=[.:\\[ ])", message)
        if m:
            return (rule(m) if callable(rule) else rule) + message[m.end():]
    return message


def translated(exc: BaseException, keys: dict[str, Rule]) -> ModelError:
    """A :class:`ModelError` with the message of ``exc`` translated by :func:`translate`."""
    return ModelError(translate(str(exc), keys))


#: API argument of :func:`rodimpact.design`, or field of the objects it takes (``StrikerLimits.mass``,
#: ``SearchOptions.starts``, ``MatchObjective.position``, ...) -> key path in a design spec (the struck-system keys
#: as in :data:`SPEC_KEYS`).
DESIGN_KEYS: dict[str, Rule] = {
    **{k: v for k, v in SPEC_KEYS.items() if k not in ("dt", "n", "backend")},
    "dt": "design.dt", "n": "design.elements", "backend": "design.backend", "MatchObjective.target": "target",
    **{f"MatchObjective.{k}": f"target.{k}" for k in ("position", "quantity", "rule")},
    "EfficiencyObjective.reloading": "design.reloading", "EfficiencyObjective.duration": "design.duration",
    **{f"SearchOptions.{k}": f"design.{k}" for k in ("starts", "max_iterations", "improvement", "hops")},
    **{f"StrikerLimits.{k}": f"design.{k}" for k in ("max_steps", "smoothness")},
    **{f"StrikerLimits.{k}": f"striker.{k}" for k in ("material", "bore", "mass")},
    r"StrikerLimits\.(impedance|diameter|velocity)_bounds(?:\[([01])\])?":
        lambda m: f"striker.{m.group(1)}_{'max' if m.group(2) == '1' else 'min'}",
}

#: Argument of :meth:`rodimpact.shpb.KolskyBar.predict`, or field of :class:`~rodimpact.shpb.KolskyBar` -> key path
#: in a Kolsky-bar spec (the bars as rods of the run: by :meth:`rodimpact.io.shpb_spec.ShpbSpec.predict`).
SHPB_KEYS: dict[str, Rule] = {
    "dt": "simulation.dt", "duration": "simulation.duration", "backend": "simulation.backend",
    "striker_velocity": "input.striker_velocity", "incident_pulse": "input.incident_pulse.file",
    **{f"KolskyBar.{k}": f"bars.{k}" for k in ("incident", "transmitted", "striker", "momentum_trap")},
    **{f"KolskyBar.{k}_gauge": f"gauges.{k}" for k in ("incident", "transmitted")},
    "KolskyBar.specimen": "specimen", "KolskyBar.shaper": "shaper",
    "KolskyBar.specimen_inertia": "simulation.specimen_inertia",
}
