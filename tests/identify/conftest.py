"""Simulated head records of known rods for the identification tests: the exact lattice (rodimpact.simulate)
driven at the head, the numpy path (no compilation)."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.identify import HeadRecord


def head_record(impedance, dt, force, steps, right="nonreflecting", every=2):
    """The head force and velocity of a rod of element impedances ``impedance`` (travel time ``dt`` each) driven
    by ``force(t)`` (N, tension positive) at its left end, sampled every ``every`` steps."""
    rod = ri.Rod.from_impedance(list(impedance), dt=dt)
    tk = dt * np.arange(steps + 1)
    system = ri.System([rod], [0.0], left=ri.ForceEnd((tk, force(tk)), interpolation="previous"), right=right)
    res = ri.simulate(ri.Problem.of(system, steps=steps, dt=dt), backend="numpy")
    n = np.asarray(res.end_force["left"], dtype=float)
    v = np.asarray(res.end_velocity["left"], dtype=float)
    return HeadRecord(res.time[::every], n[::every], v[::every]), rod


@pytest.fixture
def simulated_head():
    return head_record
