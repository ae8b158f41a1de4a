"""The compiled set-up of the wave loop (:func:`rodimpact.direct._kernels.wave_setup`) equals the readable numpy
functions it stands for (waves, reflection factors, touch elements, quiet front), bit for bit, on random systems
with loads, probes and every kind of far end."""

import numpy as np
from hypothesis import given, settings, strategies as st

import rodimpact as ri
from rodimpact.direct import _kernels as K
from rodimpact.direct.problem import Problem, TimeGrid
from rodimpact.direct.simulate import passive_right, quiet_front

DT = 1e-6


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), n_rods=st.integers(1, 3), right=st.sampled_from(["free", "fixed",
       "nonreflecting", "force"]), moving_struck=st.booleans(), loaded=st.booleans(), n_probes=st.integers(0, 3))
def test_compiled_setup_equals_the_numpy_functions(seed, n_rods, right, moving_struck, loaded, n_probes):
    rng = np.random.default_rng(seed)
    rods = [ri.Rod.from_impedance(rng.choice([3e4, 5e4, 7e4], size=int(rng.integers(2, 25))), dt=DT)
            for _ in range(n_rods)]
    velocities = [4.0] + [float(rng.uniform(-1, 1)) if moving_struck else 0.0 for _ in range(n_rods - 1)]
    loads = []
    if loaded and rods[-1].length > 3 * 5175.5 * DT:
        loads.append(ri.NodalForce(n_rods - 1, rods[-1].length * 0.5, lambda t: 10.0 * t))
        loads.append(ri.Bearings(0, [(0.0, rods[0].length)], friction_coefficient=0.2, normal_load=50.0))
    end = ri.ForceEnd(lambda t: 0.0 * t) if right == "force" else right
    system = ri.System(rods, velocities, right=end, loads=loads)
    probes = [ri.Probe(f"p{i}", int(rng.integers(0, n_rods)), 0.0) for i in range(n_probes)]
    probes = [ri.Probe(p.name, p.rod, float(rng.uniform(0, rods[p.rod].length))) for p in probes]
    compiled = Problem(system, TimeGrid(DT, 10), ri.Outputs(probes=probes)).compile()
    lat, N, v, arrays = compiled.lattice, compiled.N, compiled.v, compiled.arrays

    f, g, R, touch, quiet = K.wave_setup(N, v, lat.impedance, arrays["rod_start"], arrays["sp_elem"],
                                         arrays["sp_loaded"], arrays["pr_rod"], arrays["pr_local"],
                                         passive_right(arrays))

    f_ref, g_ref = K.waves(N, v, lat.impedance)
    R_ref, touch_ref = compiled.wave_arrays()
    quiet_ref = quiet_front(N, v, 0, passive_right(arrays), arrays["sp_elem"][arrays["sp_loaded"]])
    for got, ref in ((f, f_ref), (g, g_ref), (R, R_ref), (touch, touch_ref)):
        assert np.array_equal(got, ref)
    assert quiet == quiet_ref
