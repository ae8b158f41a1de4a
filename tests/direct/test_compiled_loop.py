"""The whole time loop in one compiled call: results bit-identical to the per-chunk kernel it replaced (kept
here, frozen, as the baseline), independent of what is recorded, and every recorded quantity equal to the numpy
reference path and to direct definitions."""

import numpy as np
import pytest
from numba import njit

import rodimpact as ri
from rodimpact.direct import recording as recording_module
from rodimpact.direct._kernels import boundaries
from rodimpact.direct.result import junction_events_from_history
from rodimpact.direct.simulate import _initial_state, _kernel_arrays, _wave_arrays

DT = 1e-6


@njit(cache=True, error_model="numpy")
def frozen_run_waves(n_steps, N, v, Z, R, touch, rod_start, ends, junctions, sp_elem, sp_cap, sp_force, probes,
                     outputs, acc, dt):
    """The compiled kernel before the loop moved inside (commit 5518828), one call for the whole run: scalar
    interior sweep, waves rebuilt from (N, v) at the start of the call."""
    n_rods = rod_start.size - 1
    rod_nodes = (np.empty(n_rods), np.empty(n_rods), np.empty(n_rods), np.empty(n_rods))
    rod_NL, rod_VL, rod_NR, rod_VR = rod_nodes
    sp_F = np.zeros(sp_elem.size)
    sp_V = np.zeros(sp_elem.size)
    specials = (sp_elem, sp_cap, sp_force, sp_F, sp_V)
    n_sp = sp_elem.size
    f = 0.5 * (N - Z * v)
    g = 0.5 * (N + Z * v)
    for i in range(n_steps):
        for t in touch:
            N[t] = f[t] + g[t]
            v[t] = (g[t] - f[t]) / Z[t]
        boundaries(i, dt, N, v, Z, rod_start, ends, junctions, specials, probes, outputs, acc, rod_nodes)
        ptr = 0
        for r in range(n_rods):
            s = rod_start[r]
            e = rod_start[r + 1]
            f_first = rod_NL[r] - g[s]
            g_last = rod_NR[r] - f[e - 1]
            fa = f[s]
            j = s
            while j < e - 1:
                stop = e - 1
                if ptr < n_sp and sp_elem[ptr] < e - 1:
                    stop = sp_elem[ptr]
                for jj in range(j, stop):
                    gb = g[jj + 1]
                    fb = f[jj + 1]
                    sc = R[jj] * (fa - gb)
                    g[jj] = gb + sc
                    f[jj + 1] = fa + sc
                    fa = fb
                if stop < e - 1:
                    gb = g[stop + 1]
                    fb = f[stop + 1]
                    n_plus = N[stop] + Z[stop] * (sp_V[ptr] - v[stop])
                    g[stop] = n_plus - fa
                    f[stop + 1] = n_plus - sp_F[ptr] - gb
                    fa = fb
                    ptr += 1
                j = stop + 1
            f[s] = f_first
            g[e - 1] = g_last
    for j in range(N.size):
        N[j] = f[j] + g[j]
        v[j] = (g[j] - f[j]) / Z[j]


def baseline(system, dt, n_steps, probes=()):
    """Contact force, end values, probe histories and final state of the frozen kernel in one call."""
    lat = ri.build_lattice(system, dt)
    state = _initial_state(system, lat)
    a = _kernel_arrays(system, lat, state, list(probes))
    out = {key: np.zeros((a[key].shape[0], n_steps))
           for key in ("pr_N", "pr_V", "pr_u", "junction_N", "junction_contact", "end_N", "end_V")}
    end_value, sp_force = a["step_inputs"](0, n_steps)
    reflection, touch = _wave_arrays(lat, a)
    frozen_run_waves(n_steps, state["N"], state["v"], lat.impedance, reflection, touch, a["rod_start"],
                     (a["end_code"], a["end_par"], a["end_state"], end_value),
                     (a["junction_code"], a["junction_state"], a["gap"], a["gap_tol"], a["u_end"]),
                     a["sp_elem"], a["sp_cap"], sp_force,
                     (a["pr_rod"], a["pr_local"], a["pr_sp"], out["pr_N"], out["pr_V"], out["pr_u"], a["pr_disp"]),
                     (out["junction_N"], out["junction_contact"], out["end_N"], out["end_V"]), a["acc"], dt)
    return out, state, a["acc"]


def busy_system():
    """Contact with a gap, a bonded joint, a spring-dashpot and a bit-rock end, a nodal load and bearings."""
    striker = ri.Rod.from_impedance(np.r_[np.full(30, 60e3), np.linspace(20e3, 90e3, 25)], dt=DT)
    middle = ri.Rod.from_impedance(np.linspace(40e3, 80e3, 40), dt=DT)
    bar = ri.Rod.from_impedance(np.full(60, 50e3), dt=DT)
    return ri.System([striker, middle, bar], velocities=[6.0, 0.0, -1.0],
                     junctions=[ri.Contact(gap=1e-6), ri.Bonded()], left=ri.SpringEnd(2e8, 50.0),
                     right=ri.BitRockEnd(3e8, 9e8),
                     loads=(ri.NodalForce(1, 0.1, lambda t: 300 * np.sin(1e4 * t)),
                            ri.Bearings(2, [(0.05, 0.2)], friction_coefficient=0.3)))


def thesis_system():
    """The README's thesis-scale impact: two-part striker 51.0e3/28.7e3 N s/m x 50 elements, bar 51.0e3 x 400."""
    striker = ri.Rod.from_impedance([51.0e3] * 50 + [28.7e3] * 50, dt=DT)
    bar = ri.Rod.from_impedance([51.0e3] * 400, dt=DT)
    return ri.System([striker, bar], velocities=[5.0, 0.0], right="nonreflecting")


BUSY_PROBES = (ri.Probe("a", 1, 0.05), ri.Probe("b", 2, 0.1), ri.Probe("c", 0, 0.0))


@pytest.mark.parametrize("make, steps, probes", [(busy_system, 1500, BUSY_PROBES),
                                                 (thesis_system, 600, (ri.Probe("bar", 1, 0.2),))])
def test_default_run_is_bit_identical_to_the_frozen_kernel(make, steps, probes):
    system = make()
    ref, state, acc = baseline(system, DT, steps, probes)
    res = ri.simulate(system, steps=steps, dt=DT, probes=probes)       # default energy sampling (~256 samples)
    assert np.array_equal(res.junction_force, ref["junction_N"])
    assert np.array_equal(res.junction_contact, ref["junction_contact"] > 0.5)
    assert np.array_equal(np.vstack([res.end_force["left"], res.end_force["right"]]), ref["end_N"])
    assert np.array_equal(np.vstack([res.end_velocity["left"], res.end_velocity["right"]]), ref["end_V"])
    for i, p in enumerate(probes):
        got = res.probe(p.name)
        assert np.array_equal(got.force, ref["pr_N"][i]) and np.array_equal(got.velocity, ref["pr_V"][i])
        assert np.array_equal(got.displacement, ref["pr_u"][i])
    assert np.array_equal(res.final_force, state["N"]) and np.array_equal(res.final_velocity, state["v"])
    work = np.array([res.energy.work_left[-1], res.energy.work_right[-1], res.energy.work_loads[-1],
                     res.energy.work_friction[-1]])
    assert np.array_equal(work, acc[:4])
    assert res.junction_contact.any() and not res.junction_contact.all()


def test_results_do_not_depend_on_what_is_recorded():
    """Energy samples and snapshots at every step leave the motion untouched, bit for bit (the kernel no longer
    stops and rebuilds its wave variables at each sample)."""
    system = busy_system()
    plain = ri.simulate(system, steps=700, dt=DT, energy_every=700)
    dense = ri.simulate(system, steps=700, dt=DT, energy_every=1, snapshot_every=1, record_every=3,
                        probes=BUSY_PROBES)
    assert np.array_equal(dense.junction_force, plain.junction_force[:, ::3])
    assert np.array_equal(dense.final_force, plain.final_force)
    assert np.array_equal(dense.final_velocity, plain.final_velocity)
    assert dense.energy.time.size == 701 and dense.snapshots.time.size == 701
    assert np.array_equal(dense.snapshots.force[:, -1], plain.final_force)
    assert np.array_equal(dense.energy.total[[0, -1]], plain.energy.total)


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_recorded_samples_follow_their_definitions(backend):
    """Energy and momentum per rod are the sums of thesis eq. 3.25 over the snapshot fields; the snapshot
    displacement at a node equals the probe's displacement there (accumulated V dt) to rounding."""
    system = busy_system()
    res = ri.simulate(system, steps=400, dt=DT, energy_every=40, snapshot_every=40, probes=BUSY_PROBES,
                      backend=backend)
    s, e, lat = res.snapshots, res.energy, res.lattice
    assert np.array_equal(s.time, e.time) and np.allclose(s.time, np.arange(0, 401, 40) * DT, rtol=0, atol=1e-18)
    z, rs = lat.impedance[:, None], lat.rod_start
    kin = 0.5 * DT * z * s.velocity ** 2
    pot = 0.5 * DT * s.force ** 2 / z
    for r in range(3):
        a, b = rs[r], rs[r + 1]
        np.testing.assert_allclose(e.kinetic[r], kin[a:b].sum(axis=0), rtol=1e-13, atol=1e-300)
        np.testing.assert_allclose(e.strain[r], pot[a:b].sum(axis=0), rtol=1e-13, atol=1e-12 * e.total.max())
        np.testing.assert_allclose(e.momentum[r], (DT * z * s.velocity)[a:b].sum(axis=0), rtol=0,
                                   atol=1e-13 * 60e3 * 6.0 * 55 * DT)
    assert e.kinetic[0, 0] == pytest.approx(0.5 * DT * lat.impedance[:55].sum() * 36.0, rel=1e-14)
    node = lat.rod_start[1] + 1 + int(round(0.05 / lat.element_length[rs[1]]))    # probe "a": rod 1, 0.05 m
    probe = res.probe("a")
    assert lat.node_x[node] - lat.node_x[rs[1] + 1] == pytest.approx(probe.node_position, abs=1e-12)
    np.testing.assert_allclose(s.displacement[node, :-1], probe.displacement[::40], rtol=0,
                               atol=1e-12 * np.abs(probe.displacement).max())


def test_numba_and_numpy_record_the_same():
    system = busy_system()
    kw = dict(steps=900, dt=DT, energy_every=13, snapshot_times=[1e-4, 3.3e-4], snapshot_every=300,
              record_every=7, probes=BUSY_PROBES)
    fast, ref = ri.simulate(system, backend="numba", **kw), ri.simulate(system, backend="numpy", **kw)
    for q in ("kinetic", "strain", "momentum", "work_left", "work_right", "work_loads", "work_friction", "impulse"):
        a, b = getattr(fast.energy, q), getattr(ref.energy, q)
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-11 * max(np.abs(b).max(), 1e-300))
    np.testing.assert_array_equal(fast.snapshots.time, ref.snapshots.time)
    for q, scale in (("force", 60e3 * 6.0), ("velocity", 6.0), ("displacement", 6.0 * 900 * DT)):
        np.testing.assert_allclose(getattr(fast.snapshots, q), getattr(ref.snapshots, q), rtol=0, atol=1e-12 * scale)
    for ea, eb in zip(fast.junction_events, ref.junction_events):
        np.testing.assert_array_equal(ea.start, eb.start)
        np.testing.assert_array_equal(ea.stop, eb.stop)
        np.testing.assert_allclose(ea.max_abs_force, eb.max_abs_force, rtol=1e-12)
        assert ea.min_force_step == eb.min_force_step
    np.testing.assert_allclose(fast.junction_force, ref.junction_force, rtol=0, atol=1e-12 * 60e3 * 6.0)


def test_many_contact_phases_outgrow_the_event_buffer(monkeypatch):
    """A striker driven back and forth hits the bar again and again: the compiled loop returns to have its phase
    buffer enlarged (here from 1), and the phases equal those taken from the full histories."""
    monkeypatch.setattr(recording_module, "_PHASES", 1)
    z, v0 = 40e3, 2.0
    drive = ri.VelocityEnd(lambda t: v0 * (0.5 + np.sign(np.sin(2 * np.pi * t / (60 * DT)))))
    rods = [ri.Rod.from_impedance(np.full(20, z), dt=DT), ri.Rod.from_impedance(np.full(50, z), dt=DT)]
    for backend in ("numba", "numpy"):
        res = ri.simulate(rods, velocities=[0.0, 0.0], steps=1200, left=drive, right="nonreflecting",
                          backend=backend, junctions=[ri.Contact(gap=1e-5)])
        (ev,) = res.junction_events
        (expected,) = junction_events_from_history(res.junction_force, res.junction_contact)
        assert ev.start.size >= 8, ev.start
        np.testing.assert_array_equal(ev.start, expected.start)
        np.testing.assert_array_equal(ev.stop, expected.stop)
        np.testing.assert_array_equal(ev.max_abs_force, expected.max_abs_force)
        assert (ev.min_force, ev.min_force_step, ev.max_abs_force_run) == \
            (expected.min_force, expected.min_force_step, expected.max_abs_force_run)
