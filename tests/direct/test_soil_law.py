"""The static part of Smith's soil law along one monotone move (:func:`rodimpact.direct.soil.static_path`, compiled
and as Python), against values worked out by hand from the law (rodimpact.rods.soil): R_u = 100 N, quake
q = 1 mm (k = 1e5 N/m), unloading quake q_u = 0.5 mm (k_u = 2e5 N/m). The path integral int_0^s R dx is the
signed area under R over the move; R_s at the end and the plastic set u_p = x - R_s / k_u follow the pieces.
And the carry-over of the soil state from one blow to the next (:func:`rodimpact.next_blow`)."""

from __future__ import annotations

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.direct.soil import static_path
from rodimpact.rods.soil import ShaftResistance, SoilToe

RU, KL, KU = 100.0, 1e5, 2e5
SHAFT, TOE = -RU, 0.0


@pytest.mark.parametrize("path", [static_path, static_path.py_func])
@pytest.mark.parametrize("r0, up, s, lo, integral, r_end, up_end", [
    # from rest down by 2 mm: loading to R_u over q = 1 mm (area 0.05), plateau 1 mm (0.1); u_p = 2 - 0.5 mm
    (0.0, 0.0, 2e-3, SHAFT, 0.15, RU, 1.5e-3),
    # down by 0.4 mm: elastic, R = 40 N, area 40 * 0.4e-3 / 2; u_p = 0.4 - 40 / 2e5 mm = 0.2 mm
    (0.0, 0.0, 0.4e-3, SHAFT, 0.008, 40.0, 0.2e-3),
    # shaft at R_u, up by 1 mm: unloads along k_u to 0 over 0.5 mm (area under [-0.5, 0]: +0.025), then loads
    # negatively along k to -50 N over 0.5 mm (area -0.0125): int_0^-1mm = -(0.025 - 0.0125); u_p = -1 + 0.25 mm
    (RU, -0.5e-3, -1e-3, SHAFT, -0.0125, -50.0, -0.75e-3),
    # shaft at -R_u, up by 1 mm more: the plateau at -R_u (int = -R_u * -1e-3 ... = +0.1)
    (-RU, 0.5e-3, -1e-3, SHAFT, 0.1, -RU, -1e-3 + 0.5e-3),
    # the toe at R_u, up by 1 mm: unloads to 0 over 0.5 mm (-0.025), then the gap (R = 0); contact resumes at
    # u_p = -0.5 mm
    (RU, -0.5e-3, -1e-3, TOE, -0.025, 0.0, -0.5e-3),
    # the toe in its gap (contact point 0.5 mm below), down by 0.8 mm: free for 0.5 mm, then loads along k to
    # 30 N (area 1e5 * (0.3e-3)^2 / 2 = 0.0045); u_p = 0.8 - 30 / 2e5 mm
    (0.0, 0.5e-3, 0.8e-3, TOE, 0.0045, 30.0, 0.8e-3 - 0.15e-3),
    # the shaft at 60 N on its unloading line, down by 0.5 mm: |R| grows again along k (loading): 60 -> 100 N
    # over 0.4 mm (area 0.032), plateau 0.1 mm (0.01); u_p = 0.5 - 0.5 mm = 0
    (60.0, -0.3e-3, 0.5e-3, SHAFT, 0.042, RU, 0.0),
])
def test_static_path_follows_the_law_piece_by_piece(path, r0, up, s, lo, integral, r_end, up_end) -> None:
    j, r, u_p = path(r0, up, s, RU, KL, KU, lo)
    assert j == pytest.approx(integral, rel=1e-12, abs=1e-18)
    assert r == pytest.approx(r_end, rel=1e-12, abs=1e-12)
    assert u_p == pytest.approx(up_end, rel=1e-12, abs=1e-18)


def test_the_next_blow_starts_from_the_soil_the_last_one_left() -> None:
    """Blow 1 leaves the toe sprung back above its plastic set (a gap of u_p - u) and the shaft loaded; the next
    blow's soil starts in exactly that state, and its toe meets no resistance until it has closed the gap."""
    n, dt = 200, 5.0 / 5000.0 / 200
    pile = ri.Rod.from_impedance(np.full(n, 1e6), dt=dt, wave_speed=5000.0)
    head = ri.ForceEnd(lambda t: np.where(t < 100 * dt, -1.2e6, 0.0))
    system = ri.System([pile], [0.0], None, head, SoilToe(0.8e6, 1e-3, 0.5e-3, damping=0.0),
                       (ShaftResistance(0, [1.0, 5.0], [40e3], quake=1e-3, damping=0.0),))
    first = ri.simulate(ri.Problem.of(system, steps=6 * n, dt=dt))
    soil = first.soil
    gap = soil.toe_set - soil.toe_displacement
    assert gap > 1e-4 and soil.toe_resistance == 0.0 and np.abs(soil.resistance).max() > 0
    following = ri.next_blow(first, velocities=[0.0])
    assert following.right.plastic_set == gap and following.right.resistance == 0.0
    shaft = following.loads[0]
    on = np.array(shaft.resistance) != 0.0
    assert np.array_equal(np.array(shaft.resistance)[soil.node], soil.resistance)
    assert np.array_equal(np.array(shaft.plastic_set)[soil.node], soil.plastic_set - soil.displacement)
    assert on.sum() == np.count_nonzero(soil.resistance)
    second = ri.simulate(ri.Problem(following, ri.TimeGrid(dt, 3 * n), ri.Outputs(probes=[ri.Probe("toe", 0, 5.0)])))
    u_toe = second.probes["toe"].displacement
    force = second.end_force["right"]
    first_contact = int(np.flatnonzero(force != 0.0)[0])
    assert np.all(force[:first_contact] == 0.0)
    assert u_toe[first_contact] <= gap <= u_toe[first_contact + 1] + 1e-15
