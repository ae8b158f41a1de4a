"""Smith soil at a pile's toe and along its shaft (issue 23, :mod:`rodimpact.rods.soil`): closed forms, measured
convergence orders, the energy balance and the numpy twin.

Set-up and conventions. A uniform pile of impedance Z (head = left end, toe = right end, x down) is struck at the
head by a prescribed force history (a :class:`~rodimpact.ForceEnd`), so the wave that runs down the pile is that
force exactly: F_i(t) = -F0 (compression) for a duration T. At the toe (an outer right end, thesis eqs.
3.16-3.19) the element side gives N = a + Z w with w the toe's downward velocity and a = N_e - Z v_e; while
only the incident wave is present (N_e = F_i, v_e = -F_i / Z) a = 2 F_i = -2 F0. The soil gives N = -R.

1. Rigid-plastic toe (quake -> 0, no damping, 2 F0 > R_u). While the toe moves (w > 0) R = R_u, so
   w = (N - a) / Z = (2 F0 - R_u) / Z. A toe at rest would need |N| = 2 F0 > R_u, so it moves from the wave's
   arrival to the end of the pulse; then a = 0 and the toe at rest needs N = 0, within [0, R_u]: it stops. The
   set of the first arrival is s = (2 F0 - R_u) T / Z. After the pulse: the toe reflects g = N - F_i =
   F0 - R_u (tension for F0 > R_u), the head (free after the pulse) returns it as the compression -(F0 - R_u)
   after 2 L / c, and the toe, at rest, would need 2 (F0 - R_u) to resist it: with F0 < 1.5 R_u that is below
   R_u, the toe does not move down again. It then reflects that wave as at a fixed end, the head returns it as
   the tension F0 - R_u, and the toe (compression only) lets go: the pile, with no shaft resistance and no
   gravity, leaves the soil upwards (the toe's impulse R_u T + 2 (F0 - R_u) T exceeds the head's F0 T). So
   with R_u < F0 < 1.5 R_u and T < 2 L / c the final set is s = (2 F0 - R_u) T / Z, and the toe ends above it.
   With a quake q > 0 the toe first loads elastically (it reflects a short tension spike of up to F0 that comes
   back as a compression spike, of a length ~ q, which moves the toe again by ~ q) and springs back by ~ q:
   the set differs from s by O(q), measured below as first order.
2. Damping laws (each a closed form that a change of its formula breaks):
   * Case, R_u = 0: the toe is a dashpot of c = J_c Z; N = -c w and N = 2 F_i + Z w give
     N = 2 F_i J_c / (1 + J_c), w = -2 F_i / (Z (1 + J_c)) (the reflection coefficient (J_c - 1)/(J_c + 1)).
     Exact on the lattice (no displacement enters).
   * smith-viscous below yield: a spring k = R_u / q and a dashpot c = J R_u: (Z + c) u' + k u = 2 F0, so
     u = (2 F0 / k)(1 - exp(-k t / (Z + c))); the scheme is the trapezoidal rule: second order.
   * Smith below yield: R = k u (1 + J u'): Z u' + k u (1 + J u') = 2 F0 =: A is separable,
     dt = (Z + J k u) du / (A - k u) = (-J + (Z + J A) / (A - k u)) du, so
     t(u) = -J u - (Z + J A) / k ln(1 - k u / A): the time at which the toe reaches u; second order.
   * Smith on the plastic plateau (the toe starts at R_s = R_u, from a previous blow): R = R_u (1 + J w), so
     w = (2 F0 - R_u) / (Z + J R_u), exact.
"""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.rods.soil import ShaftResistance, SoilToe

Z, C, L = 1.0e6, 5000.0, 5.0
R_U = 1.0e6


def _pile(n: int, dt: float) -> ri.Rod:
    return ri.Rod.from_impedance(np.full(n, Z), dt=dt, wave_speed=C, name="pile")


def _blow(toe, *, n: int = 500, steps: int | None = None, f0: float = 1.25 * R_U, pulse: float = 1e-3,
          loads=(), backend: str = "numba", probes=()):
    """The pile (length L, n elements) struck by a rectangular force -f0 of duration ``pulse`` at the head."""
    dt = L / C / n
    k_pulse = round(pulse / dt)
    head = ri.ForceEnd(lambda t: np.where(t < k_pulse * dt, -f0, 0.0))
    system = ri.System([_pile(n, dt)], [0.0], None, head, toe, tuple(loads))
    steps = steps if steps is not None else 4 * n
    out = ri.Outputs(probes=list(probes))
    return ri.simulate(ri.Problem.of(system, steps=steps, dt=dt, outputs=out), backend=backend)


def _arrival(n: int) -> int:
    return n      # the wave leaves the head in step 0 and reaches the toe's node in step n


# ------------------------------------------------------------------------------------------------ 1. set
def test_rigid_plastic_toe_gives_the_textbook_set_with_first_order_convergence_in_the_quake() -> None:
    f0, pulse, n = 1.25 * R_U, 1e-3, 500
    expected_set = (2 * f0 - R_U) * pulse / Z
    errors = []
    quakes = (2e-4, 1e-4, 5e-5, 2.5e-5)
    for q in quakes:
        res = _blow(SoilToe(R_U, q, damping=0.0), n=n, f0=f0, pulse=pulse, steps=8 * n)
        errors.append(abs(res.soil.toe_set - expected_set) / expected_set)
        assert res.soil.toe_displacement < res.soil.toe_set         # the toe has left the soil
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured: errors 0.102, 0.0511, 0.0255, 0.0128 (the set falls short by ~0.77 q), orders 1.000, 1.000, 1.000
    assert np.all(np.abs(orders - 1.0) < 0.05), (errors, orders)
    assert errors[-1] < 0.015


def test_toe_velocity_during_the_pulse_is_the_characteristics_one() -> None:
    # plastic flow from the second step after arrival on (the quake of 1 um is passed within one step)
    n, f0 = 500, 1.25 * R_U
    res = _blow(SoilToe(R_U, 1e-7, damping=0.0), n=n, f0=f0, steps=2 * n)
    w = res.end_velocity["right"]
    np.testing.assert_allclose(w[n + 2: 2 * n - 2], (2 * f0 - R_U) / Z, rtol=1e-12)


# ------------------------------------------------------------------------------------------------ 2. damping
@pytest.mark.parametrize("j_c", [0.4, 1.0, 2.5])
def test_case_damping_alone_is_a_dashpot_of_jc_z(j_c: float) -> None:
    n, f0 = 200, 0.8e6
    res = _blow(SoilToe(0.0, 1e-3, damping=j_c, damping_kind="case"), n=n, f0=f0, steps=2 * n)
    f_i = -f0
    np.testing.assert_allclose(res.end_force["right"][n + 1: 2 * n - 1], 2 * f_i * j_c / (1 + j_c), rtol=1e-12)
    np.testing.assert_allclose(res.end_velocity["right"][n + 1: 2 * n - 1], -2 * f_i / (Z * (1 + j_c)),
                               rtol=1e-12)


def _toe_displacement(res, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Times since the wave's arrival and the toe's displacement then (step starts)."""
    u = res.probes["toe"].displacement
    t = res.time - n * res.time[1]
    return t, u


def test_smith_viscous_below_yield_is_a_spring_dashpot_second_order() -> None:
    ru, q, j = 50e6, 2e-3, 0.3            # never yields: k u stays below 2 F0 = 2.5 MN << R_u
    k, c, f0 = ru / q, j * ru, 1.25e6
    errors = []
    for n in (100, 200, 400, 800):
        # loading only: the unloading quake (q / 2) plays no part, the loading stiffness R_u / q does
        res = _blow(SoilToe(ru, q, q / 2, damping=j, damping_kind="smith-viscous"), n=n, f0=f0, pulse=2e-3,
                    steps=2 * n, probes=[ri.Probe("toe", 0, L)])
        t, u = _toe_displacement(res, n)
        on = t > 0
        exact = 2 * f0 / k * (1 - np.exp(-k * t[on] / (Z + c)))
        errors.append(np.abs(u[on] - exact).max() / exact.max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured: errors 9.5e-6, 2.4e-6, 5.9e-7, 1.5e-7; orders 2.003, 2.002, 2.001
    assert np.all(orders > 1.9), (errors, orders)


def test_smith_damping_below_yield_follows_the_separable_closed_form_second_order() -> None:
    ru, q, j, f0 = 50e6, 2e-3, 0.5, 1.25e6
    k, a = ru / q, 2 * f0
    errors = []
    for n in (100, 200, 400, 800):
        res = _blow(SoilToe(ru, q, q / 2, damping=j, damping_kind="smith"), n=n, f0=f0, pulse=2e-3, steps=2 * n,
                    probes=[ri.Probe("toe", 0, L)])
        t, u = _toe_displacement(res, n)
        on = t > 0
        t_exact = -j * u[on] - (Z + j * a) / k * np.log(1 - k * u[on] / a)
        errors.append(np.abs(t[on] - t_exact).max() / t[on].max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured: errors 1.3e-3, 3.2e-4, 7.9e-5, 2.0e-5; orders 2.004, 2.001, 2.000
    assert np.all(orders > 1.9), (errors, orders)


def test_smith_damping_on_the_plastic_plateau_is_the_product_form() -> None:
    """The pile starts in equilibrium with the loaded toe of a previous blow: N = -R_u throughout, R_s = R_u,
    the head holding -R_u; the head force steps to -(R_u + F0). At the toe a = -R_u - 2 F0 and
    N = -R_u (1 + J w) = a + Z w give w = 2 F0 / (Z + J R_u)."""
    n, f0, j = 200, 0.3 * R_U, 0.49
    dt = L / C / n
    toe = SoilToe(R_U, 1e-3, damping=j, damping_kind="smith", resistance=R_U)     # loaded by the last blow
    system = ri.System([_pile(n, dt)], [0.0], None, ri.ForceEnd(lambda t: -R_U - f0), toe,
                       initial=[ri.InitialState(force=-R_U)])
    res = ri.simulate(ri.Problem.of(system, steps=2 * n, dt=dt))
    w = 2 * f0 / (Z + j * R_U)
    assert np.abs(res.end_velocity["right"][:n]).max() < 1e-15 * w    # in equilibrium until the wave arrives
    np.testing.assert_allclose(res.end_velocity["right"][n: 2 * n], w, rtol=1e-12)
    np.testing.assert_allclose(res.end_force["right"][n: 2 * n], -R_U * (1 + j * w), rtol=1e-12)


def test_a_toe_never_pulls() -> None:
    """A tension wave at a toe with a dashpot: the toe leaves the soil and reflects as a free end (N = 0,
    w = 2 F_i / Z upwards... i.e. outward velocity -2 F0 / Z for the incident F_i = +F0)."""
    n, f0 = 200, 0.5e6
    for kind, j in (("smith-viscous", 0.5), ("case", 0.7), ("smith", 0.5)):
        res = _blow(SoilToe(R_U, 1e-3, damping=j, damping_kind=kind), n=n, f0=-f0, steps=2 * n)
        assert np.all(res.end_force["right"][n: 2 * n - 1] == 0.0), kind
        np.testing.assert_allclose(res.end_velocity["right"][n + 1: 2 * n - 1], -2 * f0 / Z, rtol=1e-12)


# ------------------------------------------------------------------------------------------------ 3. energy
def test_energy_head_work_equals_pile_energy_plus_soil_work_to_rounding() -> None:
    shaft = ShaftResistance(0, [0.0, 2.0, L], [100e3, 300e3], quake=2.5e-3, unloading_quake=1.5e-3,
                            damping=0.16, damping_kind="smith")
    toe = SoilToe(0.6e6, 2.5e-3, unloading_quake=1e-3, damping=0.49)
    res = _blow(toe, n=400, steps=3200, loads=[shaft])
    e, soil = res.energy, res.soil
    pile = e.kinetic[0] + e.strain[0]
    head = e.work_left
    into_soil = -(e.work_right + e.work_soil)
    assert np.abs(pile - pile[0] - head + into_soil).max() < 1e-12 * head.max()
    # what the soil took is what its nodes recorded (work = dissipated + still stored)
    assert abs(into_soil[-1] - (soil.work.sum() + soil.toe_work)) < 1e-12 * head.max()
    assert soil.dissipated.min() >= -1e-9 and soil.toe_dissipated > 0 and e.work_soil[-1] < 0
    assert soil.rod.size == 399 and abs(soil.ultimate.sum() - shaft.total) < 1e-9 * shaft.total


def test_toe_dissipation_is_the_plastic_work_r_u_times_the_set() -> None:
    """One loading to R_u, plastic flow and unloading with q_u = q: the work dissipated is R_u u_p (the triangles
    of the elastic loading and unloading cancel); the energy in the pile after the blow is the head work less
    it, to rounding."""
    res = _blow(SoilToe(R_U, 1e-4, damping=0.0), n=500, steps=4000)    # the pile has left the soil by then
    soil, e = res.soil, res.energy
    assert soil.toe_resistance == 0.0
    assert abs(soil.toe_dissipated - R_U * soil.toe_set) < 1e-12 * R_U * soil.toe_set
    pile = e.kinetic[0][-1] + e.strain[0][-1]
    assert abs(pile - (e.work_left[-1] - soil.toe_dissipated)) < 1e-12 * e.work_left[-1]


# ------------------------------------------------------------------------------------------------ 5. twin
def test_numpy_twin_equals_the_compiled_path() -> None:
    shaft = ShaftResistance(0, [0.5, 3.0, L], [150e3, 250e3], quake=2e-3, damping=0.3, damping_kind="smith")
    toe = SoilToe(0.5e6, 2e-3, damping=0.4, damping_kind="case")
    a = _blow(toe, n=200, steps=1200, loads=[shaft], probes=[ri.Probe("mid", 0, 2.5)])
    b = _blow(toe, n=200, steps=1200, loads=[shaft], probes=[ri.Probe("mid", 0, 2.5)], backend="numpy")
    scale = np.abs(a.end_force["left"]).max()
    for x, y in ((a.end_force["right"], b.end_force["right"]), (a.probes["mid"].force, b.probes["mid"].force)):
        assert np.abs(x - y).max() < 1e-12 * scale
    np.testing.assert_allclose(a.soil.plastic_set, b.soil.plastic_set, rtol=1e-10, atol=1e-15)
    assert abs(a.soil.toe_displacement - b.soil.toe_displacement) < 1e-12 * np.abs(a.soil.displacement).max()


# ------------------------------------------------------------------------------------------------ order in dt
def test_yielding_damped_soil_converges_at_second_order_in_dt() -> None:
    """Toe and shaft that yield, unload (q_u = q / 2) and damp within the run: the static part acts with its exact
    mean over each step's path, so yield and reversal inside a step cost no order. Self-convergence of the toe's
    displacement history against n = 3200 elements (no closed form exists for this case)."""
    toe = SoilToe(R_U, 1e-3, 0.5e-3, damping=0.3)
    shaft = ShaftResistance(0, [1.0, L], [100e3], quake=1e-3, damping=0.2)
    probe = [ri.Probe("toe", 0, L)]
    fine = _blow(toe, n=3200, steps=4 * 3200, pulse=L / C, loads=[shaft], probes=probe).probes["toe"].displacement
    errors = []
    for n in (100, 200, 400, 800):
        u = _blow(toe, n=n, steps=4 * n, pulse=L / C, loads=[shaft], probes=probe).probes["toe"].displacement
        errors.append(np.abs(u - fine[np.arange(4 * n) * (3200 // n)]).max() / np.abs(fine).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured: errors 1.4e-5, 3.6e-6, 9.0e-7, 2.2e-7; orders 2.01, 2.00, 2.03
    assert np.all(orders > 1.9), (errors, orders)


def test_a_toe_at_the_left_end_is_the_mirror_image() -> None:
    """The same blow with the pile turned round (toe at the left end, struck at the right): the toe's outward set
    and force history are the same to rounding (the end law is written in outward terms)."""
    n, dt = 300, L / C / 300
    toe = SoilToe(R_U, 2e-4, 1e-4, damping=0.3)

    def head(t):
        return np.where(t < 200 * dt, -1.25 * R_U, 0.0)

    right = ri.System([_pile(n, dt)], [0.0], None, ri.ForceEnd(head), toe)
    left = ri.System([_pile(n, dt)], [0.0], None, toe, ri.ForceEnd(head))
    a = ri.simulate(ri.Problem.of(right, steps=3 * n, dt=dt))
    b = ri.simulate(ri.Problem.of(left, steps=3 * n, dt=dt))
    assert a.soil.toe_end == "right" and b.soil.toe_end == "left" and a.soil.toe_set > 1e-4
    assert abs(a.soil.toe_set - b.soil.toe_set) < 1e-12 * a.soil.toe_set
    assert np.abs(a.end_force["right"] - b.end_force["left"]).max() < 1e-9 * R_U
    np.testing.assert_allclose(a.end_velocity["right"], -b.end_velocity["left"], rtol=0, atol=1e-12)


@pytest.mark.parametrize("kind, j, total", [("case", 0.5, 0.5 * Z), ("smith-viscous", 500.0, 500.0 * 200.0 * L)])
def test_shaft_dashpots_add_up_to_the_laws_total(kind: str, j: float, total: float) -> None:
    """A free pile moving at v0 with only shaft dashpots (the quake so large that the static part is nil): a
    dashpot density c / L that is uniform along the rod keeps the motion uniform (m u_tt = EA u_xx - (c / L) u_t
    with u_t = V(t) everywhere), so the momentum decays as P0 exp(-c t / M), M the pile's mass, c the shaft's
    total: J_c Z for the Case law (shared in proportion to R_u), J_sv R_u,shaft for smith-viscous. The end half
    elements' share sits at the neighbouring nodes: second order in the element length."""
    mass = Z / C * L
    errors = []
    for n in (50, 100, 200):
        dt = L / C / n
        shaft = ShaftResistance(0, [0.0, L], [200.0], quake=1e3, damping=j, damping_kind=kind)
        res = ri.simulate(ri.Problem.of([_pile(n, dt)], [1.0], steps=round(2e-3 / dt), dt=dt, loads=[shaft],
                                        outputs=ri.Outputs(energy_every=1)))
        p = res.energy.momentum[0]
        errors.append(np.abs(p / p[0] - np.exp(-total * res.energy.time / mass)).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    # measured (case): errors 3.7e-6, 8.4e-7, 2.0e-7; orders 2.12, 2.06
    assert np.all(orders > 1.9) and errors[-1] < 1e-6, (errors, orders)


def test_node_resistance_sums_the_layers_as_the_scalar_integral():
    """ShaftResistance.node_resistance (vectorised over the node edges) against the layer-by-layer integral
    _integral at every edge: the same sums in the same order, so equal bit for bit; and the nodes' resistances
    add up to the total."""

    rng = np.random.default_rng(7)
    for _ in range(50):
        n = int(rng.integers(1, 90))
        depths = np.concatenate([[rng.uniform(0.0, 2.0)], rng.uniform(0.01, 1.0, n)]).cumsum()
        unit = rng.uniform(0.0, 1e5, n) * (rng.uniform(size=n) > 0.2)
        shaft = ShaftResistance(0, tuple(depths), tuple(unit))
        length = depths[-1] + rng.uniform(0.0, 1.0)
        x_nodes = np.linspace(0.0, length, int(rng.integers(3, 120)))[1:-1]
        edges = np.concatenate([[0.0], 0.5 * (x_nodes[1:] + x_nodes[:-1]), [length]])
        want = np.diff([shaft._integral(x) for x in edges])
        got = shaft.node_resistance(x_nodes, length)
        assert np.array_equal(got, want)
        assert got.sum() == pytest.approx(shaft.total, rel=1e-12)
