"""How a sweep point given as a dict of keywords becomes a :class:`~rodimpact.direct.problem.Problem` and the run
options of :func:`~rodimpact.simulate`.

``build`` of :func:`rodimpact.sweep` may return a dict with the keywords ``simulate`` took before its parameters
moved into the objects it receives (issue 21). The rule, one home per keyword:

* ``rods`` (rods listed left to right, or a ready ``System``), ``velocities``, ``left``, ``right``,
  ``junctions``, ``loads``, ``initial``, the time (``duration`` or ``steps``; ``dt``, ``elements`` or
  ``resolution``) and ``allow_discretization_error`` go to :meth:`Problem.of
  <rodimpact.direct.problem.Problem.of>`;
* ``probes``, ``snapshot_times``, ``snapshot_every``, ``energy_every``, ``record_every`` make one
  :class:`~rodimpact.Outputs` (or give ``outputs=Outputs(...)`` itself, not both);
* ``backend``, ``progress`` and ``max_element_updates`` are passed to :func:`~rodimpact.simulate`.

Both sweep paths (one ``simulate`` per point, and batches of ``simulate_batch`` designs) use this one rule.
"""

from __future__ import annotations

from typing import Any, Mapping

from .problem import Problem
from .recording import Outputs

#: keywords of a point's dict that go to Problem.of
PROBLEM_KEYS = ("rods", "velocities", "left", "right", "junctions", "loads", "initial", "duration", "steps", "dt",
                "elements", "resolution", "allow_discretization_error")
#: keywords that make the point's Outputs
OUTPUT_KEYS = ("probes", "snapshot_times", "snapshot_every", "energy_every", "record_every")
#: keywords passed to simulate as run options
RUN_KEYS = ("backend", "progress", "max_element_updates")
KEYS = frozenset(PROBLEM_KEYS + OUTPUT_KEYS + RUN_KEYS + ("outputs",))


def problem_of(spec: Mapping[str, Any]) -> tuple[Problem, dict[str, Any]]:
    """The :class:`Problem` a point's dict describes and its run options (the rule of this module)."""
    unknown = [key for key in spec if key not in KEYS]
    if unknown:
        raise TypeError(f"build: {unknown[0]!r} is not a keyword of a sweep point; a point's dict takes "
                        f"{', '.join(PROBLEM_KEYS)} (Problem.of), {', '.join(OUTPUT_KEYS)} or outputs (Outputs) and "
                        f"{', '.join(RUN_KEYS)} (simulate); or return a Problem")
    if "rods" not in spec:
        raise TypeError("build: a point's dict needs 'rods' (rods listed left to right, or a System)")
    given = {key: spec[key] for key in OUTPUT_KEYS if spec.get(key) is not None}
    outputs = spec.get("outputs")
    if outputs is not None and given:
        raise ValueError(f"outputs: give the outputs either as outputs=Outputs(...) or as the keywords "
                         f"{', '.join(f'{key}=' for key in given)}, not both")
    if outputs is None and given:
        outputs = Outputs(**given)
    problem = Problem.of(**{key: spec[key] for key in PROBLEM_KEYS if key in spec}, outputs=outputs)
    return problem, {key: spec[key] for key in RUN_KEYS if key in spec}
