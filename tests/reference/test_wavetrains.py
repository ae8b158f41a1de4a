"""Exact wave trains: conservation laws, classic results, contact/re-contact, agreement with the modal series."""

import numpy as np
import pytest

import rodimpact.reference as rr
from rodimpact.reference import ModalChain, ModalSegment, STEEL_BAR_SPEED, UniformPiece, solve_wave_trains

C0 = STEEL_BAR_SPEED
Z = 1e5
TAU = 1e-4


def energy_and_momentum(sol, t, n_per_piece=10001):
    """Kinetic + strain energy and momentum from the fields (midpoint rule on a fine grid)."""
    e = p = 0.0
    for piece, x0 in zip(sol.pieces, sol.x_left):
        dx = piece.length / n_per_piece
        x = x0 + (np.arange(n_per_piece) + 0.5) * dx
        n, v, _ = sol.fields(x, t)
        mass_per_length = piece.impedance / piece.wave_speed  # rho A
        stiffness = piece.impedance * piece.wave_speed  # E A
        e += dx * np.sum(0.5 * mass_per_length * v**2 + 0.5 * n**2 / stiffness)
        p += dx * np.sum(mass_per_length * v)
    return e, p


def test_equal_rods_exchange_velocities():
    """Equal uniform rods, free ends: the force is -Z v/2 for 2T, then the striker rests and the rod moves
    with v, both unloaded (classic result, e.g. Graff Sec. 2.3)."""
    sol = solve_wave_trains([UniformPiece(Z, TAU)], [UniformPiece(Z, TAU)], 4.0, 5 * TAU, right="free")
    np.testing.assert_allclose(sol.separations, [2 * TAU], rtol=1e-14)
    np.testing.assert_allclose(sol.contact_force([0.3 * TAU, 1.9 * TAU, 2.1 * TAU]), [-2 * Z, -2 * Z, 0.0])
    x = np.linspace(-0.99, 0.99, 9) * C0 * TAU
    n, v, _ = sol.fields(x, 3 * TAU)
    np.testing.assert_allclose(n, 0.0, atol=1e-9)
    np.testing.assert_allclose(v, np.where(x < 0, 0.0, 4.0), atol=1e-12)


def test_stepped_rods_conserve_energy_and_momentum():
    """Free-free, several steps on both sides, unilateral contact: energy and momentum are invariants."""
    striker = [UniformPiece(2 * Z, 0.7 * TAU), UniformPiece(0.6 * Z, 0.45 * TAU), UniformPiece(1.3 * Z, TAU)]
    rod = [UniformPiece(Z, 0.8 * TAU), UniformPiece(3 * Z, 1.7 * TAU), UniformPiece(0.5 * Z, 0.3 * TAU)]
    sol = solve_wave_trains(striker, rod, 5.0, 12 * TAU, right="free")
    e0, p0 = energy_and_momentum(sol, 0.0)
    for t in (1.3 * TAU, 5.1 * TAU, 11.7 * TAU):
        e, p = energy_and_momentum(sol, t)
        assert e == pytest.approx(e0, rel=2e-4)
        assert p == pytest.approx(p0, rel=2e-4)
    assert np.all(sol.contact_values <= 1e-9 * Z)  # never tensile while in contact


def test_recontact_against_a_wall_is_exact():
    """Heavy back piece + light face piece against a rigid wall: the face loses contact and hits the wall
    again at a time that is not a multiple of the travel times. The face never penetrates the wall, touches it
    exactly at the re-contact time, and the impact is elastic (energy conserved)."""
    striker = [UniformPiece(10 * Z, TAU), UniformPiece(Z, 3 * TAU)]
    sol = solve_wave_trains(striker, "wall", 5.0, 40 * TAU)
    assert sol.separations.size >= 2 and sol.recontacts.size >= 2
    t_re = sol.recontacts[1]
    assert abs(t_re / TAU - round(t_re / TAU)) > 0.05  # off the travel-time grid
    face = [sol.fields(0.0, t)[2][0] for t in np.linspace(0, 40 * TAU, 801)]
    assert max(face) < 1e-12
    assert abs(sol.fields(0.0, t_re)[2][0]) < 1e-15
    scale = sol.fields(0.0, 0.5 * (sol.separations[0] + t_re))[2][0]
    assert scale < -1e-7  # a real gap opened in between
    e0, _ = energy_and_momentum(sol, 0.0)
    e1, _ = energy_and_momentum(sol, 39 * TAU)
    assert e1 == pytest.approx(e0, rel=2e-4)


def test_bonded_wave_trains_match_the_modal_series():
    """Two independent methods on the same problem: uniform striker (A1) bonded to a uniform rod (A2 = 2.5 A1),
    free-fixed. Away from the force jumps the 3000-mode series agrees with the exact wave trains."""
    a1, a2, rho = 1e-3, 2.5e-3, 7840.0
    z1, z2 = rho * C0 * a1, rho * C0 * a2
    chain = ModalChain((ModalSegment.uniform(1.0, a1), ModalSegment.uniform(0.8, a2)), "free", "fixed", origin=-1.0)
    modal = chain.expand((6.0, 0.0), 3000)
    exact = solve_wave_trains([UniformPiece(z1, 1.0 / C0)], [UniformPiece(z2, 0.8 / C0)], 6.0, 1e-3,
                              contact="bonded", right="fixed")
    for t in (0.13e-3, 0.41e-3, 0.77e-3):
        x = np.linspace(-0.999, 0.799, 901)
        n_ex, v_ex, u_ex = exact.fields(x, t)
        jumps = np.flatnonzero(np.diff(n_ex) != 0)
        far = np.ones(x.size, bool)
        for j in jumps:
            far &= np.abs(x - 0.5 * (x[j] + x[j + 1])) > 0.03
        n_mod = modal.force(x, t)
        scale = z1 * 6.0
        assert np.max(np.abs(n_mod - n_ex)[far]) / scale < 5e-3
        np.testing.assert_allclose(modal.displacement(x, t), u_ex, atol=2e-3 * np.max(np.abs(u_ex)))


def test_bad_input():
    with pytest.raises(ValueError, match="impedance"):
        UniformPiece(-1.0, TAU)
    with pytest.raises(ValueError, match="rod"):
        solve_wave_trains([UniformPiece(Z, TAU)], "floor", 1.0, TAU)
    with pytest.raises(ValueError, match="contact"):
        solve_wave_trains([UniformPiece(Z, TAU)], "wall", 1.0, TAU, contact="glued")
    with pytest.raises(ValueError, match="max_fronts"):
        solve_wave_trains([UniformPiece(Z, TAU), UniformPiece(2 * Z, TAU * 2**0.5)], [UniformPiece(Z, TAU)],
                          1.0, 400 * TAU, right="free", max_fronts=1000)
    sol = solve_wave_trains([UniformPiece(Z, TAU)], "wall", 1.0, TAU)
    with pytest.raises(ValueError, match="duration"):
        sol.contact_force(2 * TAU)
    with pytest.raises(TypeError, match="pieces"):
        solve_wave_trains([Z], "wall", 1.0, TAU)
    assert rr.WaveTrainSolution is type(sol)
