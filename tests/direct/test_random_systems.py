"""Property-based checks on random systems: every end condition, junction type and load combination keeps the
energy bookkeeping exact, stays finite and gives the same answer on both kernel paths."""

import numpy as np
from hypothesis import given, settings, strategies as st

import rodimpact as ri

DT = 1e-6

ends = st.sampled_from(["free", "fixed", "nonreflecting", "spring", "bitrock", "force", "velocity"])


def make_end(kind: str, rng: np.random.Generator):
    if kind == "spring":
        return ri.SpringEnd(float(rng.uniform(1e6, 1e9)), float(rng.uniform(0.0, 1e3)))
    if kind == "bitrock":
        k1 = float(rng.uniform(1e7, 1e9))
        return ri.BitRockEnd(k1, float(k1 * rng.uniform(1.0, 10.0)))
    if kind == "force":
        amp = float(rng.uniform(-1e4, 1e4))
        return ri.ForceEnd(lambda t: amp * np.sin(3e4 * t))
    if kind == "velocity":
        amp = float(rng.uniform(-2.0, 2.0))
        return ri.VelocityEnd(lambda t: amp * np.cos(2e4 * t))
    return kind


@settings(max_examples=30, deadline=None)
@given(n_rods=st.integers(1, 3), left=ends, right=ends, seed=st.integers(0, 2**31 - 1),
       bonded=st.lists(st.booleans(), min_size=2, max_size=2), friction=st.booleans())
def test_random_systems_balance_energy_and_agree_across_backends(n_rods, left, right, seed, bonded, friction):
    rng = np.random.default_rng(seed)
    rods = [ri.Rod.from_impedance(rng.uniform(1e4, 1e5, size=int(rng.integers(3, 30))), dt=DT) for _ in range(n_rods)]
    velocities = list(rng.uniform(-5.0, 5.0, size=n_rods))
    junctions = [ri.Bonded() if b else ri.Contact(gap=float(rng.uniform(0.0, 1e-6))) for b in bonded[: n_rods - 1]]
    loads = []
    if friction:
        r = int(rng.integers(0, n_rods))
        loads.append(ri.Bearings(r, [(0.0, rods[r].length)], friction_coefficient=0.3,
                                 normal_load=float(rng.uniform(1e2, 1e5))))
    system = ri.System(rods, velocities, junctions=junctions, left=make_end(left, rng), right=make_end(right, rng),
                       loads=loads)
    kw = dict(steps=400, outputs=ri.Outputs(energy_every=1, probes=[ri.Probe("p", 0, rods[0].length / 2)]))
    fast = ri.simulate(system, backend="numba", **kw)
    ref = ri.simulate(system, backend="numpy", **kw)
    e = fast.energy
    assert np.all(np.isfinite(fast.final_force)) and np.all(np.isfinite(fast.final_velocity))
    scale = max(np.max(np.abs(e.total)), np.max(np.abs(e.exchanged)), 1e-30)
    assert np.max(np.abs(e.total - e.total[0] - e.exchanged)) <= 1e-11 * scale
    assert np.all(np.diff(e.work_friction) <= 1e-12 * scale)
    # scales of the problem: forces Z v and the prescribed end force (1e4 N), velocities v and 1e4 N / Z
    z_max = max(float(np.max(r.native.impedance)) for r in rods)
    z_min = min(float(np.min(r.native.impedance)) for r in rods)
    v_scale = max(abs(x) for x in velocities) + 2.0 + 1e4 / z_min
    n_scale = z_max * v_scale
    np.testing.assert_allclose(fast.final_force, ref.final_force, rtol=0, atol=1e-12 * n_scale)
    np.testing.assert_allclose(fast.probe("p").velocity, ref.probe("p").velocity, rtol=0, atol=1e-12 * v_scale)
    np.testing.assert_array_equal(fast.junction_contact, ref.junction_contact)
