"""simulate() rejects bad input with messages that name the quantity."""

import numpy as np
import pytest

import rodimpact as ri

DT = 1e-6


@pytest.fixture
def rods():
    return [ri.Rod.from_impedance([5e4] * 20, dt=DT), ri.Rod.from_impedance([5e4] * 40, dt=DT)]


@pytest.mark.parametrize("kwargs, match", [
    (dict(velocities=[1.0]), "velocities: need one initial velocity per rod"),
    (dict(velocities=[1.0, float("nan")]), r"velocities\[1\]: must be finite"),
    (dict(velocities=[1.0, 0.0], duration=-1.0), "duration: must be > 0"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, steps=10), "exactly one of duration"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, dt=0.0), "dt: must be > 0"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, right="sticky"), "right: must be an end condition"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, probes=[ri.Probe("p", 1, 5.0)]),
     r"probes\[0\].position: must lie within rod 1"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, probes=[ri.Probe("p", 3, 0.0)]), "rod index 3 does not exist"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, junctions=[ri.Bonded(), ri.Bonded()]), "junctions: need one"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, loads=[ri.NodalForce(1, 9.0, 1.0)]),
     r"loads\[0\].position: must lie inside rod 1"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, loads=[ri.Bearings(1, [(0.0, 9.0)], 0.3)]),
     r"loads\[0\].spans: span \(0.0, 9.0\) m lies outside rod 1"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, left=ri.ForceEnd(lambda t: np.where(t > 1e-5, np.nan, 0.0))),
     "ForceEnd.force: evaluates to nan"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, backend="fortran"), "backend: must be"),
    (dict(velocities=[1.0, 0.0], duration=1e-4, snapshot_times=[1.0]), "snapshot_times: must lie in"),
])
def test_bad_simulation_input(rods, kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        ri.simulate(rods, **kwargs)


def test_dt_that_cannot_resolve_a_segment():
    rod = ri.Rod([ri.Cylinder(0.5, 0.05), ri.Cylinder(0.001, 0.04), ri.Cylinder(0.5, 0.05)])
    with pytest.raises(ValueError, match=r"dt: the time step .* cannot resolve rod 0 .* segment 1"):
        ri.simulate([rod], velocities=[1.0], duration=1e-4, dt=1e-6)


def test_bearing_span_without_nodes():
    rod = ri.Rod([ri.Cylinder(0.5, 0.05)])
    with pytest.raises(ValueError, match="no lattice node"):
        ri.simulate([rod], velocities=[1.0], duration=1e-4, dt=2e-5,
                    loads=[ri.Bearings(0, [(0.22, 0.25)], 0.3)])
