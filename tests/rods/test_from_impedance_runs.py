"""Rod.from_impedance builds its cylinders on demand: the same rod as one built cylinder by cylinder (the way
it was built before), down to the last bit of every geometric quantity and of simulate()."""

import dataclasses
import math
import pickle

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.rods.material import STEEL, Material
from rodimpact.rods.rod import ImpedanceProfile
from rodimpact.rods.segments import Cylinder


def _old_from_impedance(z, dt, c=STEEL.wave_speed, rho=STEEL.density, name=None):
    """Reference: one validated Cylinder per run of equal impedance, constructed explicitly."""
    z = np.asarray(z, dtype=float)
    mat = Material(rho * c * c, rho, "impedance-level")
    segs, a = [], 0
    for b in range(1, z.size + 1):
        if b == z.size or z[b] != z[a]:
            segs.append(Cylinder((b - a) * c * dt, math.sqrt(4.0 * z[a] / (rho * c) / math.pi), material=mat))
            a = b
    return ri.Rod(tuple(segs), mat, name, ImpedanceProfile(z.copy(), dt, c))


def _profile(n, seed=0):
    """An impedance changing at every element, with a few runs of equal values."""
    rng = np.random.default_rng(seed)
    z = 8e4 * np.exp(np.cumsum(rng.normal(0.0, 0.05, n)))
    z[10:14] = z[10]
    z[-3:] = z[-3]
    return z


@pytest.mark.parametrize("c, rho", [(None, None), (4900.0, 7200.0)])
def test_same_rod_as_built_cylinder_by_cylinder(c, rho):
    z = _profile(500)
    dt = 1.3e-7
    new = ri.Rod.from_impedance(z, dt, c, density=rho, name="s")
    old = _old_from_impedance(z, dt, c or STEEL.wave_speed, rho or STEEL.density, name="s")
    assert len(new.segments) == len(old.segments) == 500 - 3 - 2
    assert new == old and old == new
    assert tuple(new.segments) == old.segments
    assert new.segments[7] == old.segments[7] and new.segments[-1] == old.segments[-1]
    assert new.segments[3:6] == old.segments[3:6]
    assert [new.segment_material(i) for i in (0, 99)] == [old.segment_material(i) for i in (0, 99)]
    np.testing.assert_array_equal(new.segment_bounds, old.segment_bounds)
    np.testing.assert_array_equal(new.segment_travel_times, old.segment_travel_times)
    assert new.length == old.length and new.total_travel_time == old.total_travel_time
    x = np.unique(np.concatenate([np.linspace(0.0, old.length, 2001), old.segment_bounds]))
    for q in ("area", "impedance", "wave_speed", "travel_time"):
        np.testing.assert_array_equal(getattr(new, q)(x), getattr(old, q)(x), err_msg=q)
        assert getattr(new, q)(x[77]) == getattr(old, q)(x[77])          # a number for a number
    assert new.mass == pytest.approx(old.mass, rel=1e-13)
    assert new.mass == pytest.approx(float(z.sum() * dt), rel=1e-12)      # sum Z_j dt
    assert repr(new) == repr(old)


def test_copies_and_pickles_are_equal():
    rod = ri.Rod.from_impedance(_profile(50), 1e-7)
    assert pickle.loads(pickle.dumps(rod)) == rod
    renamed = dataclasses.replace(rod, name="x")
    assert renamed.name == "x" and renamed.segments == rod.segments and renamed.length == rod.length
    assert ri.Rod.from_impedance(_profile(50, seed=1), 1e-7) != rod
    with pytest.raises(IndexError):
        rod.segments[len(rod.segments)]


@pytest.mark.parametrize("dt_factor", [1.0, 0.5, 0.7])
def test_simulate_bit_identical_to_cylinder_by_cylinder(dt_factor):
    """A striker whose impedance changes at every element hits a bar: contact force, end values, probes
    (strain uses the area) and energies are bit-identical; dt_factor 0.7 takes the geometric discretisation
    (not a divisor of the native dt), which walks the cylinders."""
    dt = 1e-6
    z = _profile(120, seed=2)
    runs = {}
    for build in (ri.Rod.from_impedance, _old_from_impedance):
        striker = build(z, dt)
        bar = ri.Rod.from_impedance(np.full(200, 9e4), dt)
        runs[build] = ri.simulate([striker, bar], [6.0, 0.0], steps=600, dt=dt * dt_factor,
                                  outputs=ri.Outputs(probes=[ri.Probe("s", 0, 0.3 * striker.length),
                                                             ri.Probe("b", 1, 0.2)]))
    a, b = runs.values()
    np.testing.assert_array_equal(a.contact_force, b.contact_force)
    assert np.any(a.contact_force != 0.0)
    for name in ("s", "b"):
        for q in ("force", "velocity", "displacement", "strain"):
            np.testing.assert_array_equal(getattr(a.probes[name], q), getattr(b.probes[name], q))
    np.testing.assert_array_equal(a.energy.kinetic, b.energy.kinetic)
    np.testing.assert_array_equal(a.energy.strain, b.energy.strain)
    np.testing.assert_array_equal(a.lattice.impedance, b.lattice.impedance)


def test_unphysical_sizes_are_refused():
    with pytest.raises(ValueError, match="impedances: element 0 .* element length"):
        ri.Rod.from_impedance([1e5, 2e5], 1e200, wave_speed=1e150)
    with pytest.raises(ValueError, match="impedances: element 1 .* equivalent diameter"):
        ri.Rod.from_impedance([1e5, 1e-320], 1e-6)
