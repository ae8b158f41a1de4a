"""Issue 14 item 13: the non-reflecting end implements the thesis's eq. (3.20) ("energy sink"), not a deviation
from it. The reference here is an independent little lattice written from the thesis equations only: element
borders by eqs. (3.6)-(3.9) (no external forces), incident waves (3.10)-(3.13), superposition (3.14)-(3.15),
and at both outer ends eq. (3.20) N^- = N_1, N^+ = N_n with the velocities from (3.16)/(3.17)."""

import re
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri

ROOT = Path(__file__).resolve().parents[2]


def thesis_lattice(z, n_force, v, steps):
    """Literal eqs. (3.6)-(3.20) on a single rod with energy sinks at both ends; returns (N, v) after ``steps``."""
    z, n_force, v = (np.array(a, dtype=float) for a in (z, n_force, v))
    for _ in range(steps):
        zl, zr, nl, nr, vl, vr = z[:-1], z[1:], n_force[:-1], n_force[1:], v[:-1], v[1:]
        # right border of element j (eqs. 3.6, 3.7) and left border of element j+1 (eqs. 3.8, 3.9), F* = 0
        n_plus = (((vr - vl) * zr + nr) * zl + nl * zr) / (zr + zl)
        v_plus = (zl * vl + zr * vr - nl + nr) / (zr + zl)
        n_minus = (((vr - vl) * zl + nl) * zr + nr * zl) / (zl + zr)
        v_minus = (zr * vr + zl * vl + nr - nl) / (zl + zr)
        N_plus = np.append(n_plus, n_force[-1])               # eq. 3.20 at the right end: N^+ = N
        V_plus = np.append(v_plus, (N_plus[-1] - n_force[-1]) / z[-1] + v[-1])        # eq. 3.17
        N_minus = np.insert(n_minus, 0, n_force[0])            # eq. 3.20 at the left end: N^- = N
        V_minus = np.insert(v_minus, 0, (n_force[0] - N_minus[0]) / z[0] + v[0])      # eq. 3.16
        dN_L, dN_R = N_plus - n_force, N_minus - n_force       # eqs. 3.10, 3.11
        dv_L, dv_R = V_plus - v, V_minus - v                   # eqs. 3.12, 3.13
        n_force, v = n_force + dN_L + dN_R, v + dv_L + dv_R    # eqs. 3.14, 3.15
    return n_force, v


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rodimpact_end_equals_a_literal_implementation_of_eq_3_20(seed):
    rng = np.random.default_rng(seed)
    n, dt = 60, 1e-6
    z = rng.uniform(20e3, 120e3, n)                   # a rough non-uniform rod
    n0 = rng.uniform(-50e3, 50e3, n)                  # random initial prestress, N
    v0 = rng.uniform(-3.0, 3.0, n)                    # random initial velocity, m/s
    rod = ri.Rod.from_impedance(z, dt)
    for steps in (1, 7, 45, 150):
        res = ri.simulate(ri.System([rod], [0.0], left="nonreflecting", right="nonreflecting",
                                    initial=[ri.InitialState(force=n0, velocity=v0)]), steps=steps, dt=dt)
        n_ref, v_ref = thesis_lattice(z, n0, v0, steps)
        scale_n, scale_v = np.abs(n0).max(), np.abs(v0).max()
        assert np.max(np.abs(res.final_force - n_ref)) <= 1e-12 * scale_n
        assert np.max(np.abs(res.final_velocity - v_ref)) <= 1e-12 * scale_v


def test_a_reflecting_end_is_not_mistaken_for_eq_3_20():
    """The comparison can fail: a free end differs from the energy sink by far more than rounding."""
    rng = np.random.default_rng(5)
    z, n0, v0 = rng.uniform(20e3, 120e3, 40), rng.uniform(-5e4, 5e4, 40), rng.uniform(-3, 3, 40)
    res = ri.simulate(ri.System([ri.Rod.from_impedance(z, 1e-6)], [0.0], left="free", right="nonreflecting",
                                initial=[ri.InitialState(force=n0, velocity=v0)]), steps=30, dt=1e-6)
    n_ref, _ = thesis_lattice(z, n0, v0, 30)
    assert np.max(np.abs(res.final_force - n_ref)) > 1e-3 * np.abs(n0).max()


def _places_citing_eq_3_20():
    texts = {p.name: p.read_text(encoding="utf-8") for p in sorted((ROOT / "docs").glob("*.md"))}
    texts["conditions.py"] = (ROOT / "rodimpact" / "rods" / "conditions.py").read_text(encoding="utf-8")
    return texts


def test_docs_do_not_call_the_non_reflecting_end_a_deviation_from_eq_3_20():
    found = 0
    for name, text in _places_citing_eq_3_20().items():
        for m in re.finditer(r"3\.20", text):
            found += 1
            near = text[max(0, m.start() - 400): m.end() + 400].lower()
            assert "deviat" not in near and "differs from" not in near and "zero-gradient" not in near, (
                f"{name}: the non-reflecting end is eq. (3.20) itself, not a deviation from it: {near!r}")
    assert found >= 2       # docs/method.md and the NonReflectingEnd docstring cite it
    method = _places_citing_eq_3_20()["method.md"]
    assert "Non-reflecting end = thesis eq. (3.20)" in method
