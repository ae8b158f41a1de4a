"""simulate() rejects bad input with messages that name the quantity."""

import numpy as np
import pytest

import rodimpact as ri
from rodimpact._validate import physical_memory

DT = 1e-6


@pytest.fixture
def rods():
    return [ri.Rod.from_impedance([5e4] * 20, dt=DT), ri.Rod.from_impedance([5e4] * 40, dt=DT)]


@pytest.mark.parametrize("run, match", [
    (lambda rods: ri.simulate(rods, [1.0]), "velocities: need one initial velocity per rod"),
    (lambda rods: ri.simulate(rods, [1.0, float("nan")]), r"velocities\[1\]: must be finite"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=-1.0), "duration: must be > 0"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, steps=10), "exactly one of duration"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, dt=0.0), "dt: must be > 0"),
    (lambda rods: ri.simulate(ri.System(rods, [1.0, 0.0], right="sticky"), duration=1e-4),
     "right: must be an end condition"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, outputs=ri.Outputs(probes=[ri.Probe("p", 1, 5.0)])),
     r"probes\[0\].position: must lie within rod 1"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, outputs=ri.Outputs(probes=[ri.Probe("p", 3, 0.0)])),
     "rod index 3 does not exist"),
    (lambda rods: ri.simulate(ri.System(rods, [1.0, 0.0], junctions=[ri.Bonded(), ri.Bonded()]), duration=1e-4),
     "junctions: need one"),
    (lambda rods: ri.simulate(ri.System(rods, [1.0, 0.0], loads=[ri.NodalForce(1, 9.0, 1.0)]), duration=1e-4),
     r"loads\[0\].position: must lie inside rod 1"),
    (lambda rods: ri.simulate(ri.System(rods, [1.0, 0.0], loads=[ri.Bearings(1, [(0.0, 9.0)], 0.3)]), duration=1e-4),
     r"loads\[0\].spans: span \(0.0, 9.0\) m lies outside rod 1"),
    (lambda rods: ri.simulate(ri.System(rods, [1.0, 0.0],
                                        left=ri.ForceEnd(lambda t: np.where(t > 1e-5, np.nan, 0.0))), duration=1e-4),
     "ForceEnd.force: evaluates to nan"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, backend="fortran"), "backend: must be"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, outputs=ri.Outputs(snapshot_times=[1.0])),
     "snapshot_times: must lie in"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], steps=10**12), "steps: at most"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e308), "duration: .* steps of dt"),
    (lambda rods: ri.simulate(rods, [1.0, 0.0], duration=1e-4, outputs=ri.Outputs(probes=[ri.Probe("p", "nope", 0.0)])),
     r"probes\[0\].rod: no rod is named 'nope'"),
    (lambda rods: ri.simulate(ri.Problem.of(rods, [1.0, 0.0], steps=2, elements=(True, 10))), "elements: rod index"),
    (lambda rods: ri.System(rods, [1.0, 0.0], loads=[ri.NodalForce("nope", 0.5, 1.0)]),
     r"loads\[0\].rod: no rod is named 'nope'"),
    (lambda rods: ri.System(rods, [1.0, 0.0], loads=[ri.NodalForce(2, 0.5, 1.0)]),
     r"loads\[0\].rod: rod index 2 does not exist"),
])
def test_bad_simulation_input(rods, run, match):
    with pytest.raises((ValueError, TypeError), match=match):
        run(rods)


def test_dt_that_cannot_resolve_a_segment():
    rod = ri.Rod([ri.Cylinder(0.5, 0.05), ri.Cylinder(0.001, 0.04), ri.Cylinder(0.5, 0.05)])
    with pytest.raises(ValueError, match=r"dt: the time step .* cannot resolve rod 0 .* segment 1"):
        ri.simulate([rod], velocities=[1.0], duration=1e-4, dt=1e-6)


def test_bearing_span_without_nodes():
    rod = ri.Rod([ri.Cylinder(0.5, 0.05)])
    with pytest.raises(ValueError, match="no lattice node"):
        ri.simulate(ri.System([rod], [1.0], loads=[ri.Bearings(0, [(0.22, 0.25)], 0.3)]), duration=1e-4,
                    dt=rod.total_travel_time / 5)    # nodes every 0.1 m


@pytest.mark.skipif(physical_memory() is None, reason="the platform does not report its memory (no sysconf)")
def test_runs_too_large_for_the_memory_are_refused_before_allocating():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(1.0, 0.04)])]
    with pytest.raises(ValueError, match="dt: .* lattice elements .* more than this machine's memory"):
        ri.simulate(ri.Problem.of(rods, [1.0, 0.0], steps=2, elements=10**12))
    with pytest.raises(ValueError, match="dt: .* lattice elements"):
        ri.simulate(ri.Problem.of(rods, [1.0, 0.0], steps=2, resolution=1e-13))
    with pytest.raises(ValueError, match=r"steps: the run would need about .* GiB of memory \(histories .*\), more than the .* available now; keep every n-th step with record_every"):
        ri.simulate(ri.Problem.of(rods, [1.0, 0.0], steps=1_999_000_000, elements=2,
                                  outputs=ri.Outputs(probes=[ri.Probe(f"p{i}", 1, 0.5) for i in range(20)])))


def test_probe_fields_are_checked_and_rods_may_be_named():
    with pytest.raises(ValueError, match="Probe.position: expected a quantity in m, got \"110 ms\" \\(a time\\)"):
        ri.Probe("p", 1, "110 ms")
    with pytest.raises(TypeError, match="Probe.position"):
        ri.Probe("p", 1, None)
    with pytest.raises(ValueError, match="Probe.rod: must be a rod index >= 0 or a rod name"):
        ri.Probe("p", True, 0.1)
    assert ri.Probe("p", np.int64(1), np.float32(0.5)).rod == 1
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)], name="striker"), ri.Rod([ri.Cylinder(1.0, 0.04)], name="bar")]
    by_name = ri.simulate(rods, [5.0, 0.0], duration=3e-4, outputs=ri.Outputs(probes=[ri.Probe("g", "bar", 0.5)]))
    by_index = ri.simulate(rods, [5.0, 0.0], duration=3e-4, outputs=ri.Outputs(probes=[ri.Probe("g", 1, 0.5)]))
    assert by_name.probes["g"].probe == by_index.probes["g"].probe
    assert np.array_equal(by_name.probes["g"].force, by_index.probes["g"].force)


def test_elements_accepts_numpy_integers():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(1.0, 0.04)])]
    res = ri.simulate(ri.Problem.of(rods, [5.0, 0.0], steps=10, elements=(np.int64(1), np.int32(10))))
    assert res.lattice.rod_start[2] - res.lattice.rod_start[1] == 10


def test_a_rock_that_unloads_less_stiffly_than_it_loads_is_refused():
    """A passive rock needs k2 >= k1: unloading along k2 < k1 from the largest force F returns F^2 / (2 k2) of
    work, more than the F^2 / (2 k1) that loading put in (issue 20, item 1: k1 = 1600 MN/m with k2 = 1200 MN/m
    reported -18.5 % energy into the rock and a negative penetration)."""
    with pytest.raises(ValueError, match=r"unloading_stiffness: must be >= BitRockEnd.loading_stiffness .*"
                                         r"1\.2e\+09 N/m < loading_stiffness = 1\.6e\+09 N/m"):
        ri.BitRockEnd(1.6e9, 1.2e9)
    assert ri.BitRockEnd(1.6e9, 1.6e9).unloading_stiffness == 1.6e9      # equal stiffnesses: elastic rock


@pytest.mark.parametrize("make", [
    lambda: ri.SpringEnd(-1e6), lambda: ri.SpringEnd(1e6, -5.0), lambda: ri.NonReflectingEnd(-1e4),
    lambda: ri.NonReflectingEnd(0.0), lambda: ri.Contact(-1e-3), lambda: ri.BitRockEnd(-1e6),
    lambda: ri.Bearings(0, [(0.0, 0.1)], -0.2),
], ids=["negative spring", "negative dashpot", "negative impedance", "zero impedance", "negative gap",
        "negative rock", "negative friction"])
def test_end_and_junction_laws_that_would_create_energy_are_refused(make):
    """Audit of item 1: every end or junction parameter whose sign decides whether the law absorbs or creates
    energy is refused on the creating side."""
    with pytest.raises(ValueError, match="must be"):
        make()


def test_loads_name_their_rod():
    """A load may name its rod, in Python as in model files: the same run as with the index."""
    named = [ri.Rod.from_impedance([5e4] * 20, dt=DT, name="striker"),
             ri.Rod.from_impedance([5e4] * 40, dt=DT, name="bar")]
    by_name = ri.System(named, [1.0, 0.0], loads=[ri.NodalForce("bar", 0.01, 100.0)])
    by_index = ri.System(named, [1.0, 0.0], loads=[ri.NodalForce(1, 0.01, 100.0)])
    assert by_name.loads[0].rod == 1
    a = ri.simulate(by_name, duration=5e-5).to_xarray()
    b = ri.simulate(by_index, duration=5e-5).to_xarray()
    np.testing.assert_array_equal(a["junction_force"].values, b["junction_force"].values)
    np.testing.assert_array_equal(a["kinetic_energy"].values, b["kinetic_energy"].values)
