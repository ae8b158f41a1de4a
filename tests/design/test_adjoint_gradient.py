"""The adjoint gradient of ImpactProblem equals central finite differences through the forward model on random
systems (contact with separation and re-contact, every far end, force at a position and incident wave) for the
two design objectives; the compiled and numpy paths agree; checkpointing does not change the result."""

import numpy as np
import pytest
from hypothesis import assume, given, settings, strategies as st

import rodimpact as ri
from rodimpact.design._adjoint import ImpactProblem
from rodimpact.inverse.struck import locate

DT = 1e-6
H = 1e-5            # relative finite-difference step
END_KINDS = ["free", "fixed", "nonreflecting", "nonreflecting_z", "bitrock", "spring"]


def make_end(kind, rng):
    if kind == "nonreflecting_z":
        return ri.NonReflectingEnd(impedance=float(rng.uniform(1e4, 6e4)))
    if kind == "bitrock":
        k1 = float(rng.uniform(5e9, 5e10))
        return ri.BitRockEnd(k1, k1 * float(rng.uniform(1.0, 5.0)))
    if kind == "spring":
        return ri.SpringEnd(float(rng.uniform(5e9, 5e10)), float(rng.uniform(0.0, 3e4)))
    return kind


def random_case(seed, end_kind, observe, loads=False):
    """Random struck impedances (one part, or two parts bonded or in contact), random striker with a strong
    impedance step (it separates and hits again), a problem of 5 * (striker + struck) steps."""
    rng = np.random.default_rng(seed)
    parts = [ri.Rod.from_impedance(rng.uniform(1e4, 6e4, size=int(rng.integers(4, 12))), dt=DT)
             for _ in range(int(rng.integers(1, 3)))]
    extra = {}
    if loads:
        extra["loads"] = [ri.NodalForce(0, parts[0].length / 2, lambda t: -3e3 * np.cos(1e5 * t)),
                          ri.Bearings(len(parts) - 1, [(0.0, parts[-1].length)], friction_coefficient=0.3,
                                      normal_load=2e3)]
    junctions = [ri.Contact() if rng.uniform() < 0.5 else ri.Bonded()] * (len(parts) - 1)
    struck = ri.System.struck(parts, make_end(end_kind, rng), float(rng.uniform(-0.5, 0.5)), junctions=junctions,
                              **extra)
    n = int(rng.integers(3, 9))
    z = rng.uniform(1e4, 6e4, size=n)
    z[int(rng.integers(1, n)):] *= rng.uniform(2.0, 6.0)
    v = float(rng.uniform(2.0, 10.0))
    total = sum(p.length for p in parts)
    location = None
    if observe != "face":
        location = locate(struck, float(rng.uniform(0.0, 1.0)) * total, DT)
    steps = 5 * (n + sum(p.native.impedance.size for p in parts))
    quantity = "incident" if observe == "incident" else "force"
    return ImpactProblem(struck, DT, n, steps, location=location, quantity=quantity), z, v, rng


def match_objective(problem, rng, z, v):
    """J = sum w (F - T)^2 / sum w T^2 of the observed quantity over the first 60 % of the steps, T the response
    to another random striker, random positive weights; returns J(fw) and its seeds (None if T = 0 there)."""
    target = problem.forward(z * rng.uniform(0.5, 1.5, size=z.size), v * float(rng.uniform(0.7, 1.3))).observed
    w = np.zeros(problem.steps)
    w[: int(0.6 * problem.steps)] = rng.uniform(0.5, 2.0, size=int(0.6 * problem.steps))
    norm = float(np.sum(w * target ** 2))
    if norm == 0.0:    # e.g. the force at a free far end
        return None

    def J(fw):
        return float(np.sum(w * (fw.observed - target) ** 2)) / norm

    def grad(fw):
        return problem.gradient(fw, observed=2.0 * w * (fw.observed - target) / norm)
    return J, grad


def efficiency_objective(problem):
    """J = -(sum_k N_k w_k dt) / (1/2 m v^2): the work done on the rock (the rod pushes with -N > 0 while the
    end moves outwards with w) per striker kinetic energy, with the striker mass m = dt sum Z; seeds for the end
    force and velocity plus the explicit dependence on m and v."""
    def J(fw):
        return -float(np.sum(fw.end_force * fw.end_velocity)) * DT / (0.5 * fw.striker_mass * fw.velocity ** 2)

    def grad(fw):
        e = 0.5 * fw.striker_mass * fw.velocity ** 2
        dz, dv = problem.gradient(fw, end_force=-fw.end_velocity * DT / e, end_velocity=-fw.end_force * DT / e)
        j = J(fw)
        return dz - j / fw.striker_mass * DT, dv - 2.0 * j / fw.velocity
    return J, grad


def signature(fw):
    """The discrete history a finite difference must not cross: contact flags, and at the far end whether it
    is loaded (force non-zero) and whether the step's path reaches a new largest penetration (bit-rock: the
    end displacement at the end of the step exceeds every earlier one)."""
    scale = max(float(np.max(np.abs(fw.end_force))), 1e-300)
    pen = np.cumsum(fw.end_velocity * DT)
    new_max = pen > np.maximum.accumulate(np.concatenate([[0.0], pen[:-1]]))
    return np.concatenate([fw.contact, np.abs(fw.end_force) > 1e-9 * scale, new_max])


def finite_differences(problem, J, z, v, h=H):
    """Central differences of J in every Z_q and in v with relative step h; None when a branch switches."""
    base = signature(problem.forward(z, v))
    out = []
    for q in range(z.size + 1):
        runs = []
        for sign in (1.0, -1.0):
            zz, vv = z.copy(), v
            if q < z.size:
                zz[q] += sign * h * z[q]
            else:
                vv += sign * h * v
            fw = problem.forward(zz, vv)
            if not np.array_equal(signature(fw), base):
                return None
            runs.append(J(fw))
        out.append((runs[0] - runs[1]) / (2.0 * h * (z[q] if q < z.size else v)))
    return np.array(out[:-1]), out[-1]


def assert_gradient(grad, fd):
    """Whole vector within 1e-6 relative, and every component above 1 % of the largest within 1e-6."""
    (dz, dv), (fz, fv) = grad, fd
    a, b = np.append(dz, dv), np.append(fz, fv)
    assert np.linalg.norm(a - b) <= 1e-6 * np.linalg.norm(b)
    big = np.abs(b) >= 1e-2 * np.max(np.abs(b))
    np.testing.assert_allclose(a[big], b[big], rtol=1e-6)


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), end=st.sampled_from(END_KINDS),
       observe=st.sampled_from(["face", "force", "incident"]))
def test_match_gradient_equals_finite_differences(seed, end, observe):
    problem, z, v, rng = random_case(seed, end, observe)
    objective = match_objective(problem, rng, z, v)
    assume(objective is not None)
    J, grad = objective
    fd = finite_differences(problem, J, z, v)
    assume(fd is not None)
    assert_gradient(grad(problem.forward(z, v)), fd)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), observe=st.sampled_from(["face", "force"]), loads=st.booleans())
def test_efficiency_gradient_equals_finite_differences(seed, observe, loads):
    problem, z, v, _ = random_case(seed, "bitrock", observe, loads)
    J, grad = efficiency_objective(problem)
    fw = problem.forward(z, v)
    assume(J(fw) > 1e-3)          # energy reaches the rock within the simulated steps
    fd = finite_differences(problem, J, z, v)
    assume(fd is not None)
    assert_gradient(grad(fw), fd)


def test_gradient_through_separation_and_recontact():
    """A thin striker face before a heavy rear part against a long bar: the face separates and the rear hits
    again (two contact periods)."""
    struck = ri.System.struck(ri.Rod.from_impedance(np.linspace(2e4, 3e4, 10), dt=DT), far_end="nonreflecting")
    z = np.array([3e4, 3e4, 1.2e5, 1.2e5, 1.2e5, 1.2e5])
    problem = ImpactProblem(struck, DT, z.size, 120)
    fw = problem.forward(z, 5.0)
    c = fw.contact.astype(int)
    assert c[0] == 1 and np.sum(np.diff(c) == 1) >= 1       # contact, separation, re-contact
    rng = np.random.default_rng(0)
    J, grad = match_objective(problem, rng, z, 5.0)
    fd = finite_differences(problem, J, z, 5.0)
    assert fd is not None
    assert_gradient(grad(fw), fd)


def test_gradient_with_loads_and_friction():
    """Nodal force and bearing friction (stick/slip) in the struck system, force observed at a position."""
    for seed in range(40):          # the first random cases whose finite differences cross no branch
        problem, z, v, rng = random_case(seed, "spring", "force", loads=True)
        J, grad = match_objective(problem, rng, z, v)
        fw = problem.forward(z, v)
        fd_h = finite_differences(problem, J, z, v)
        fd_q = finite_differences(problem, J, z, v, H / 4)   # a stick/slip switch inside +-h makes them differ
        if fd_h is None or fd_q is None:
            continue
        a, b = np.append(*fd_h), np.append(*fd_q)
        if np.linalg.norm(a - b) <= 1e-7 * np.linalg.norm(b):
            assert_gradient(grad(fw), fd_h)
            return
    pytest.fail("no friction case without a stick/slip switch inside the finite-difference step")


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_numba_and_numpy_gradients_agree(seed):
    for observe, end in (("incident", "bitrock"), ("force", "spring"), ("face", "nonreflecting")):
        problem, z, v, rng = random_case(seed, end, observe, loads=True)
        other = ImpactProblem(problem.struck, DT, problem.n, problem.steps, location=problem.location,
                              quantity=problem.quantity, backend="numpy")
        seeds = {k: rng.standard_normal(problem.steps) for k in ("face_force", "observed", "end_force",
                                                                   "end_velocity")}
        dz, dv = problem.gradient(problem.forward(z, v), **seeds)
        ez, ev = other.gradient(other.forward(z, v), **seeds)
        scale = np.linalg.norm(np.append(dz, dv))
        assert np.linalg.norm(np.append(dz - ez, dv - ev)) <= 1e-10 * scale


def test_checkpoint_interval_does_not_change_the_gradient():
    base, z, v, rng = random_case(11, "bitrock", "incident", loads=True)
    seeds = {k: rng.standard_normal(base.steps) for k in ("face_force", "observed", "end_force", "end_velocity")}
    results = []
    for every in (1, 7, None, base.steps):
        p = ImpactProblem(base.struck, DT, base.n, base.steps, location=base.location, quantity="incident",
                          checkpoint_every=every)
        results.append(p.gradient(p.forward(z, v), **seeds))
    ref = np.append(*results[2])
    for r in results:
        np.testing.assert_array_equal(np.append(*r), ref)     # same operations in the same order


def test_gradient_is_linear_in_the_seeds():
    """Seeds add: the gradient of J1 + 2 J2 is the sum of the gradients (no state leaks between calls)."""
    problem, z, v, rng = random_case(4, "bitrock", "force", loads=True)
    fw = problem.forward(z, v)
    s1, s2 = rng.standard_normal(problem.steps), rng.standard_normal(problem.steps)
    a = problem.gradient(fw, end_force=s1)
    b = problem.gradient(fw, observed=s2)
    c = problem.gradient(fw, end_force=s1, observed=2.0 * s2)
    np.testing.assert_allclose(np.append(*c), np.append(a[0] + 2 * b[0], a[1] + 2 * b[1]),
                               rtol=0, atol=1e-12 * np.linalg.norm(np.append(*c)))


def test_long_run_gradient_equals_finite_differences():
    """700 steps: simulate's compiled calls end every 3 steps (the forward repeats the (N, v) round trip there)
    and the default checkpoints split the run into 27 segments; waves reflect many times in a short rod."""
    struck = ri.System.struck(ri.Rod.from_impedance(np.linspace(3e4, 5e4, 6), dt=DT), far_end=ri.BitRockEnd(2e10, 6e10))
    rng = np.random.default_rng(21)
    z = rng.uniform(2e4, 6e4, size=5)
    problem = ImpactProblem(struck, DT, z.size, 700)
    J, grad = efficiency_objective(problem)
    fw = problem.forward(z, 7.0)
    assert J(fw) > 1e-2
    fd = finite_differences(problem, J, z, 7.0)
    assert fd is not None
    assert_gradient(grad(fw), fd)
