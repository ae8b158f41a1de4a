"""Closed forms and wave trains refuse non-finite or empty positions and times (and other malformed input)
with an error that names the quantity, instead of returning zeros or a constant for NaN."""

import numpy as np
import pytest

import rodimpact.reference as rr
from rodimpact.reference import UniformPiece, solve_wave_trains

Z = 4e4
T = 1e-5
V = 5.0


@pytest.fixture(scope="module")
def sol():
    return solve_wave_trains([UniformPiece(Z, T)], [UniformPiece(Z, T)], V, 10 * T)


NON_FINITE = [np.nan, np.inf, -np.inf]


@pytest.mark.parametrize("bad", NON_FINITE)
def test_rod_against_wall_fields_needs_finite_positions(bad):
    with pytest.raises(ValueError, match=r"x: positions \(m\) must be finite, entry 1 is"):
        rr.rod_against_wall_fields([-0.5, bad], 1e-4, Z, 1.0, 5000.0, V)
    with pytest.raises(ValueError, match=r"x: positions \(m\) must be finite, got"):
        rr.rod_against_wall_fields(bad, 1e-4, Z, 1.0, 5000.0, V)


def test_rod_against_wall_fields_other_positions():
    with pytest.raises(ValueError, match="x: got an empty array"):
        rr.rod_against_wall_fields([], 1e-4, Z, 1.0, 5000.0, V)
    with pytest.raises(TypeError, match=r"x: positions \(m\) must be real numbers, got str"):
        rr.rod_against_wall_fields("-0.5", 1e-4, Z, 1.0, 5000.0, V)
    with pytest.raises(ValueError, match=r"x: positions must lie in \[-1, 0\] m .*got 0\.5"):
        rr.rod_against_wall_fields([-0.2, 0.5], 1e-4, Z, 1.0, 5000.0, V)
    with pytest.raises(ValueError, match="t: must be finite"):
        rr.rod_against_wall_fields([-0.5], np.nan, Z, 1.0, 5000.0, V)


@pytest.mark.parametrize("bad", NON_FINITE)
def test_contact_force_needs_finite_times(sol, bad):
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, entry 0 is"):
        sol.contact_force([bad])
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, got"):
        sol.contact_force(bad)


def test_contact_force_other_times(sol):
    with pytest.raises(ValueError, match="t: got an empty array"):
        sol.contact_force([])
    with pytest.raises(TypeError, match=r"t: times \(s\) must be real numbers"):
        sol.contact_force("1e-5")
    assert sol.contact_force(-1.0) == 0.0 and sol.contact_force([T])[0] == -Z * V / 2


@pytest.mark.parametrize("bad", NON_FINITE)
def test_fields_needs_finite_positions(sol, bad):
    with pytest.raises(ValueError, match=r"x: positions \(m\) must be finite, entry 0 is"):
        sol.fields([bad], T)
    with pytest.raises(ValueError, match="t: must be finite"):
        sol.fields([0.0], bad)


def test_fields_other_positions(sol):
    with pytest.raises(ValueError, match="x: got an empty array"):
        sol.fields([], T)
    with pytest.raises(ValueError, match=r"x: positions \(m\) must be a number or a 1-d array, got shape \(2, 1\)"):
        sol.fields([[0.0], [0.01]], T)
    with pytest.raises(TypeError, match=r"x: positions \(m\) must be real numbers"):
        sol.fields(["a"], T)
    n, v, u = sol.fields(0.0, T)                 # a single position still works
    assert n.shape == v.shape == u.shape == (1,)


TIME_FUNCTIONS = {
    "uniform_striker_force": lambda t: rr.uniform_striker_force(t, Z, Z, T, V),
    "rigid_mass_force": lambda t: rr.rigid_mass_force(t, 1.0, Z, V),
    "rod_against_wall_force": lambda t: rr.rod_against_wall_force(t, Z, T, V),
    "stepped_striker_force": lambda t: rr.stepped_striker_force(t, [2 * Z, Z], [T, T], Z, V),
    "lundberg_lesser_force": lambda t: rr.lundberg_lesser_force(t, 1e3, 1e-4),
}


@pytest.mark.parametrize("name", TIME_FUNCTIONS)
@pytest.mark.parametrize("bad", NON_FINITE)
def test_force_histories_need_finite_times(name, bad):
    f = TIME_FUNCTIONS[name]
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, entry 1 is"):
        f([0.0, bad])
    with pytest.raises(ValueError, match=r"t: times \(s\) must be finite, got"):
        f(bad)


@pytest.mark.parametrize("name", TIME_FUNCTIONS)
def test_force_histories_need_some_real_times(name):
    f = TIME_FUNCTIONS[name]
    with pytest.raises(ValueError, match="t: got an empty array"):
        f([])
    with pytest.raises(TypeError, match=r"t: times \(s\) must be real numbers, got str"):
        f("abc")
    with pytest.raises(TypeError, match=r"t: times \(s\) must be real numbers"):
        f([1e-6, None])
    out = f(np.array([[0.0, 0.5 * T], [1.5 * T, 3 * T]]))   # any shape, kept
    assert out.shape == (2, 2) and np.all(np.isfinite(out))


@pytest.mark.parametrize("bad", NON_FINITE)
def test_lundberg_lesser_impedance_needs_finite_theta(bad):
    with pytest.raises(ValueError, match=r"theta: travel times into the striker \(s\) must be finite"):
        rr.lundberg_lesser_impedance([0.0, bad], Z, 1e3, 1e-4, V)
    with pytest.raises(ValueError, match="theta: got an empty array"):
        rr.lundberg_lesser_impedance([], Z, 1e3, 1e-4, V)
    with pytest.raises(ValueError, match=r"theta: travel times into the striker must be >= 0 s, got -1\.0"):
        rr.lundberg_lesser_impedance([0.0, -1.0], Z, 1e3, 1e-4, V)


def test_stepped_striker_travel_times_must_be_numbers():
    with pytest.raises(TypeError, match=r"travel_times: travel times \(s\) must be real numbers, got str"):
        rr.stepped_striker_force([1e-6], [Z], "1e-5", Z, V)
    with pytest.raises(ValueError, match=r"travel_times: travel times \(s\) must be finite"):
        rr.stepped_striker_force([1e-6], [Z, Z], [T, np.nan], Z, V)


def test_solve_wave_trains_pieces_and_max_fronts():
    piece = UniformPiece(Z, T)
    with pytest.raises(TypeError, match=r"striker: a sequence of UniformPiece .*got UniformPiece"):
        solve_wave_trains(piece, "wall", V, T)
    with pytest.raises(TypeError, match=r"rod: a sequence of UniformPiece .* or 'wall', got int"):
        solve_wave_trains([piece], 3, V, T)
    with pytest.raises(TypeError, match="max_fronts: must be a whole number >= 1, got float nan"):
        solve_wave_trains([piece], "wall", V, T, max_fronts=float("nan"))
    with pytest.raises(ValueError, match="max_fronts: must be a whole number >= 1, got 0"):
        solve_wave_trains([piece], "wall", V, T, max_fronts=0)
    # any iterable of pieces is still accepted
    sol = solve_wave_trains((p for p in [piece]), "wall", V, 3 * T)
    assert sol.contact_force(T) == -Z * V
