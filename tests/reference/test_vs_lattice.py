"""The lattice solver (rodimpact.simulate) against the independent references of rodimpact.reference.

Piecewise-constant impedance with travel times that are multiples of dt: the lattice is exact, so the
closed forms and the wave trains must agree to rounding (1e-12 relative). Continuous profiles (Lundberg-Lesser
striker, thesis Setup 3 exponential horn): agreement within stated, shrinking tolerances.
"""

import math

import numpy as np
import pytest

import rodimpact as ri
import rodimpact.reference as rr

Z = 79.7e3  # N s/m
V = 6.0
DT = 1e-6  # s
C0 = ri.STEEL.wave_speed


def lattice_force(striker_z, rod_z, n_steps, right="nonreflecting", velocity=V):
    """Contact force per step of impedance-level rods (each element = one dt)."""
    rods = [ri.Rod.from_impedance(striker_z, DT), ri.Rod.from_impedance(rod_z, DT)]
    res = ri.simulate(ri.System(rods, [velocity, 0.0], right=right), steps=n_steps, dt=DT)
    return res.time, res.contact_force


def mid(t):
    return t + 0.5 * DT  # inside the step: node values are constant on [k dt, (k+1) dt)


@pytest.mark.parametrize("ratio", [0.4, 1.0, 2.5])
def test_uniform_striker_on_semi_infinite_rod(ratio):
    t, f = lattice_force([ratio * Z] * 20, [Z] * 5, 400)
    ref = rr.uniform_striker_force(mid(t), ratio * Z, Z, 20 * DT, V)
    np.testing.assert_allclose(f, ref, rtol=1e-12, atol=1e-12 * Z * V)


def test_stepped_striker_on_semi_infinite_rod():
    """Exact up to the first re-contact that falls between lattice steps: the lattice can only re-establish
    contact at a step boundary (its mid-step gap rule), so from then on it is O(dt) off in time."""
    z = [1.7 * Z] * 7 + [0.6 * Z] * 3 + [2.2 * Z] * 11 + [Z] * 5  # free end first, impact face last
    t, f = lattice_force(z, [0.9 * Z] * 3, 600)
    steps = np.array([1.7, 0.6, 2.2, 1.0]) * Z
    taus = np.array([7, 3, 11, 5]) * DT
    ref = rr.stepped_striker_force(mid(t), steps, taus, 0.9 * Z, V)
    exact = rr.solve_wave_trains([rr.UniformPiece(a, b) for a, b in zip(steps, taus)],
                                 [rr.UniformPiece(0.9 * Z, 600 * DT)], V, 600 * DT)
    t_re = exact.recontacts[1]
    assert exact.separations[0] < t_re and abs(t_re / DT - round(t_re / DT)) > 0.1  # separated, off-grid return
    early = t + DT <= t_re
    np.testing.assert_allclose(f[early], ref[early], rtol=1e-12, atol=1e-12 * Z * V)
    first_return = t[np.flatnonzero((f < 0) & (t > exact.separations[0]))[0]]
    assert 0 < first_return - t_re <= DT  # the lattice re-contacts at the next step boundary


def test_stepped_striker_without_recontact():
    z = [2.0 * Z] * 10 + [Z] * 5 + [0.5 * Z] * 5
    t, f = lattice_force(z, [Z] * 3, 800)
    steps = np.array([2.0, 1.0, 0.5]) * Z
    taus = np.array([10, 5, 5]) * DT
    exact = rr.solve_wave_trains([rr.UniformPiece(a, b) for a, b in zip(steps, taus)],
                                 [rr.UniformPiece(Z, 800 * DT)], V, 800 * DT)
    assert exact.recontacts.size == 1 and exact.separations.size == 1
    np.testing.assert_allclose(f, rr.stepped_striker_force(mid(t), steps, taus, Z, V), rtol=1e-12, atol=1e-12 * Z * V)


def test_two_finite_stepped_rods_with_contact_and_wave_trains():
    """Finite rods with free far ends, unilateral contact (separation included): exact wave trains."""
    z1 = [2.0 * Z] * 6 + [0.7 * Z] * 4
    z2 = [Z] * 9 + [3.0 * Z] * 5 + [0.5 * Z] * 2
    rods = [ri.Rod.from_impedance(z1, DT), ri.Rod.from_impedance(z2, DT)]
    res = ri.simulate(ri.System(rods, [V, -1.0], right="free"), steps=300, dt=DT,
                      outputs=ri.Outputs(snapshot_times=[137 * DT, 261 * DT]))
    piece = lambda zz, n: rr.UniformPiece(zz, n * DT)  # noqa: E731
    exact = rr.solve_wave_trains([piece(2 * Z, 6), piece(0.7 * Z, 4)], [piece(Z, 9), piece(3 * Z, 5), piece(0.5 * Z, 2)],
                                 V, 300 * DT, rod_velocity=-1.0, right="free")
    np.testing.assert_allclose(res.contact_force, exact.contact_force(mid(res.time)), rtol=1e-12, atol=1e-12 * Z * V)
    snap = res.snapshots
    for k, t in enumerate(snap.time):
        n_ex, v_ex, _ = exact.fields(snap.element_x, t)
        np.testing.assert_allclose(snap.force[:, k], n_ex, rtol=1e-12, atol=1e-12 * Z * V)
        np.testing.assert_allclose(snap.velocity[:, k], v_ex, rtol=1e-12, atol=1e-12 * V)


def test_rod_against_wall():
    """A wall = a 1e15-times stiffer rod with a fixed far end (unilateral contact): force -Z v for 2T."""
    t, f = lattice_force([Z] * 25, [1e15 * Z] * 2, 200, right="fixed")
    np.testing.assert_allclose(f, rr.rod_against_wall_force(mid(t), Z, 25 * DT, V), rtol=1e-12, atol=1e-12 * Z * V)
    exact = rr.solve_wave_trains([rr.UniformPiece(Z, 25 * DT)], "wall", V, 200 * DT)
    np.testing.assert_allclose(f, exact.contact_force(mid(t)), rtol=1e-12, atol=1e-12 * Z * V)


def test_rigid_mass_limit_of_a_one_element_striker():
    """A one-element striker of mass M = Z1 dt is the T1 = dt staircase (exact), which is within
    eps (1 + 2 eps) Z v of the rigid-mass exponential, eps = Z dt / M."""
    m = 1.5
    t, f = lattice_force([m / DT], [Z] * 3, 300)
    np.testing.assert_allclose(f, rr.uniform_striker_force(mid(t), m / DT, Z, DT, V), rtol=1e-12, atol=1e-12 * Z * V)
    eps = Z * DT / m
    dev = np.max(np.abs(f - rr.rigid_mass_force(t, m, Z, V))) / (Z * V)  # at step starts
    assert dev < eps * (1 + 2 * eps)


def test_lundberg_lesser_striker_from_its_area_function():
    """Eq. (4.26) as a steel AreaFunction striker, discretised by the lattice (travel-time averaged impedance):
    the contact force is constant on 2-step windows and matches -N_hat exp(-t/t0) at window middles with an
    O(dt^2) error up to t = 2 Theta."""
    zr, nh, t0 = 79.7e3, 239e3, 0.383e-3
    rho, c = ri.STEEL.density, C0
    theta_total = 0.2e-3
    length = c * theta_total
    # striker listed left to right: local s = 0 is its free end, the face is at s = length
    area = lambda s: rr.lundberg_lesser_impedance((length - np.asarray(s)) / c, zr, nh, t0, V) / (rho * c)  # noqa: E731
    striker = ri.Rod([ri.AreaFunction(length, area)])
    errs, ns = [], np.array([50, 100, 200])
    for n in ns:
        dt = theta_total / n
        rod = ri.Rod.from_impedance([zr] * 2, dt)
        res = ri.simulate(ri.System([striker, rod], [V, 0.0], right="nonreflecting"), steps=2 * n - 2, dt=dt)
        f = res.contact_force
        np.testing.assert_allclose(f[0::2][: n - 1], f[1::2][: n - 1], rtol=1e-9)  # constant on windows
        t_mid = (2 * np.arange(n - 1) + 1) * dt
        errs.append(np.max(np.abs(f[0::2][: n - 1] - rr.lundberg_lesser_force(t_mid, nh, t0))) / nh)
    slope = np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert errs[-1] < 5e-6  # 3.4e-6 at n = 200: travel-time averaging of a convex Z(theta) costs O(dt^2)
    assert -2.2 < slope < -1.8


# --------------------------------------------------------------------------- thesis Setup 3 (modal)
SETUP3 = rr.HornImpact()
TIMES = (0.145e-3, 0.290e-3, 0.435e-3)
F0 = 0.5 * 7840.0 * C0 * 1.96e-3 * V  # |initial contact force| = Z0 v / 2, N


def setup3_lattice(n_per_rod):
    """Setup 3 on the lattice: bonded contact (as the modal model), dt = (1 m / c0) / n so travel times are exact."""
    d = math.sqrt(4 * SETUP3.area / math.pi)
    rods = [ri.Rod([ri.Cylinder(1.0, d)]), ri.Rod([ri.ExponentialHorn(1.0, SETUP3.area, SETUP3.xi)])]
    dt = (1.0 / C0) / n_per_rod
    return ri.simulate(ri.System(rods, [V, 0.0], right="fixed", junctions=[ri.Bonded()]), duration=0.44e-3, dt=dt,
                       outputs=ri.Outputs(snapshot_times=list(TIMES))), dt


def far_from_fronts(x, t, distance):
    fronts = SETUP3.wavefront_positions(t)
    return np.min(np.abs(x[:, None] - fronts[None, :]), axis=1) > distance


@pytest.fixture(scope="module")
def modal4000():
    return SETUP3.solve(4000)


@pytest.fixture(scope="module")
def contact_reference():
    """Sigma-smoothed 20000-mode series: the contact force (one position) is cheap to sum accurately."""
    return SETUP3.solve(20000).smoothed()


@pytest.mark.parametrize(("n_modes", "n_per_rod"), [(1000, 250), (4000, 1000)])
def test_setup3_modal_vs_lattice_forces_away_from_jumps(modal4000, n_modes, n_per_rod):
    """Raw (thesis-style) series, more than d = 5 cm from every jump, relative to Z0 v/2. Stated tolerance:
    the Gibbs tail of a unit jump, 2 c0 / (pi omega_N d), plus the lattice's odd-even ripple xi dx / 2
    (first order in dx = c0 dt, from the stepwise horn). Both shrink: 1000 modes/250 elements -> 8.1e-3 + 1e-3,
    4000 modes/1000 elements -> 2.0e-3 + 2.5e-4."""
    sol = modal4000.truncated(n_modes)
    res, dt = setup3_lattice(n_per_rod)
    d = 0.05
    tol = 2 * C0 / (math.pi * sol.omega[-1] * d) + SETUP3.xi * C0 * dt / 2
    snap = res.snapshots
    for k, t in enumerate(snap.time):
        x = snap.element_x
        far = far_from_fronts(x, t, d)
        err = np.max(np.abs(sol.force(x[far], t) - snap.force[far, k])) / F0
        assert err < tol, (t, err, tol)
    # the displacement converges much faster (no jumps): 1e-3 of its maximum for both resolutions
    for k, t in enumerate(snap.time):
        u_l = snap.displacement[:, k]
        np.testing.assert_allclose(sol.displacement(snap.node_x, t), u_l, atol=1e-3 * np.max(np.abs(u_l)))


def test_setup3_smoothed_modal_pins_the_lattice_error(modal4000, contact_reference):
    """With sigma factors the series is accurate to ~1e-7 away from jumps, exposing the lattice error itself:
    element forces within xi dx / 2 (first order: an odd-even ripple), node displacements converging at
    second order, and the contact force at 2-step-window middles at second order (log-log fits)."""
    ref = modal4000.smoothed()
    ns = np.array([125, 250, 500])
    e_force, e_disp, e_contact = [], [], []
    for n in ns:
        res, dt = setup3_lattice(int(n))
        snap = res.snapshots
        ef = ed = 0.0
        for k, t in enumerate(snap.time):
            far = far_from_fronts(snap.element_x, t, 0.02)
            ef = max(ef, np.max(np.abs(ref.force(snap.element_x[far], t) - snap.force[far, k])) / F0)
            farn = far_from_fronts(snap.node_x, t, 0.02)
            ed = max(ed, np.max(np.abs(ref.displacement(snap.node_x[farn], t) - snap.displacement[farn, k])))
        assert ef < SETUP3.xi * C0 * dt / 2
        j = np.arange(int(40e-6 / dt) // 2, int(0.38e-3 / dt) // 2)  # away from the jumps at t = 0, 2 l / c0
        ec = np.max(np.abs(contact_reference.force(0.0, (2 * j + 1) * dt) - res.contact_force[2 * j])) / F0
        e_force.append(ef), e_disp.append(ed), e_contact.append(ec)
    order = lambda e: -np.polyfit(np.log(ns), np.log(e), 1)[0]  # noqa: E731
    assert 0.9 < order(e_force) < 1.1
    assert 1.8 < order(e_disp) < 2.2
    assert 1.7 < order(e_contact) < 2.3


def test_general_chain_of_table_2_1_pieces_vs_lattice():
    """Striker + a struck rod made of quadratic, cosh^2 and cos^2 pieces (area jumps between them), free-free,
    bonded: the sigma-smoothed modal chain (with its rigid mode) against ri.QuadraticHorn/CoshHorn/CosHorn on
    the lattice. Node displacements away from fronts converge at second order, element forces (neighbour
    means, which still see the kinks of the reflected waves) at first order."""
    a0 = 1e-3
    profiles = [("quadratic", a0, 1.0, 0.4), ("cosh2", 2.5e-3, 1.5, 0.6), ("cos2", 2e-3, 1.0, 0.5)]
    segs = (rr.ModalSegment.uniform(0.5, a0),) + tuple(
        rr.ModalSegment(rr.AnalyticProfile(f, a, xi), length) for f, a, xi, length in profiles)
    chain = rr.ModalChain(segs, "free", "free", origin=-0.5)
    f0 = 0.5 * 7840.0 * C0 * a0 * V  # initial contact force magnitude
    ref = chain.expand((V, 0.0, 0.0, 0.0), 4000).smoothed()
    assert ref.rigid_velocity == pytest.approx(V * 0.5 * a0 / sum(s.mass / 7840.0 for s in segs), rel=1e-12)
    striker = ri.Rod([ri.Cylinder(0.5, math.sqrt(4 * a0 / math.pi))])
    rod = ri.Rod([ri.QuadraticHorn(0.4, a0, 1.0), ri.CoshHorn(0.6, 2.5e-3, 1.5), ri.CosHorn(0.5, 2e-3, 1.0)])
    errors = []
    for n in (50, 100):
        dt = 0.1 / (C0 * n)  # every piece is a whole number of elements
        res = ri.simulate(ri.System([striker, rod], [V, 0.0], right="free", junctions=[ri.Bonded()]), duration=0.36e-3,
                          dt=dt, outputs=ri.Outputs(snapshot_times=[0.2e-3, 0.35e-3]))
        snap = res.snapshots
        eu = ef = 0.0
        for k, t in enumerate(snap.time):
            n_lat = snap.force[:, k]
            jumps = 0.5 * (snap.element_x[1:] + snap.element_x[:-1])[np.abs(np.diff(n_lat)) > 0.01 * f0]
            far_n = np.min(np.abs(snap.node_x[:, None] - jumps[None, :]), axis=1) > 0.02
            far_e = np.min(np.abs(snap.element_x[:, None] - jumps[None, :]), axis=1) > 0.02
            eu = max(eu, np.max(np.abs(ref.displacement(snap.node_x[far_n], t) - snap.displacement[far_n, k])))
            e = ref.force(snap.element_x, t) - n_lat
            pair = 0.5 * (e[1:] + e[:-1])
            ef = max(ef, np.max(np.abs(pair[far_e[1:] & far_e[:-1]])) / f0)
        errors.append((eu, ef))
    (eu1, ef1), (eu2, ef2) = errors
    assert eu2 < 1e-6 * 5e-4 and eu1 / eu2 > 3.5  # |u| reaches 0.5 mm
    assert ef2 < 2e-4 and ef1 / ef2 > 1.8
