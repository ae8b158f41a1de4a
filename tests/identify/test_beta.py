"""The integrity factor beta from a reflectogram (rodimpact/identify/reflectors.py) against the exact lattice.

Closed form: a step Z1 -> Z2 at depth x reflects a down-going force wave d(t) as r d(t - 2x/c) with
r = (Z2 - Z1) / (Z2 + Z1); at the echo's peak up / down_peak = r, so beta = (1 + r) / (1 - r) = Z2 / Z1 exactly
(to rounding). A neck (Z1 -> Z2 -> Z1) gives a second primary echo -r (1 - r^2) (down and up through the first
interface: force transmissions 1 + r and 1 - r); dividing the passage out gives its beta = Z1 / Z2 exactly, as
long as the pulse is shorter than the neck's two-way time (the first multiple comes one neck round trip later).
"""

import numpy as np
import pytest

from rodimpact.identify import beta_class, identify_by_beta

DT = 1e-6
WIDTH = 20                       # steps of the half-sine hammer pulse


def hammer(t):
    """A half-sine hammer pulse at the head, WIDTH steps long (compression negative)."""
    return np.where(t < WIDTH * DT, -1.0e3 * np.sin(np.pi * t / (WIDTH * DT)), 0.0)


def test_single_step_gives_beta_exactly(simulated_head):
    z = np.r_[np.full(50, 4.0e5), np.full(150, 0.7 * 4.0e5)]
    record, rod = simulated_head(z, DT, hammer, 300, every=1)
    c = float(np.sqrt(rod.segments[0].material.youngs_modulus / rod.segments[0].material.density))
    out = identify_by_beta(record, z[0], c)
    (step,) = out.anomalies
    assert step.beta == pytest.approx(0.7, rel=1e-12)
    assert step.beta_class == "damage"
    assert step.depth == pytest.approx(50 * c * DT, rel=1e-12)      # echo at 2 x / c = 100 steps after the peak


def test_neck_gives_both_betas_exactly(simulated_head):
    """Recorded up to 200 steps: the first head multiple (the first echo sent down again by the head, whose
    force is held at zero after the blow, and reflected by the neck) arrives 200 steps after the peak."""
    z = np.r_[np.full(50, 4.0e5), np.full(30, 0.7 * 4.0e5), np.full(120, 4.0e5)]
    record, rod = simulated_head(z, DT, hammer, 200, every=1)
    c = float(np.sqrt(rod.segments[0].material.youngs_modulus / rod.segments[0].material.density))
    out = identify_by_beta(record, z[0], c)
    assert [a.beta for a in out.anomalies] == pytest.approx([0.7, 1 / 0.7], rel=1e-12)
    assert out.anomalies[0].length == pytest.approx(30 * c * DT, rel=1e-12)
    assert out.impedance == pytest.approx([4.0e5, 0.7 * 4.0e5, 4.0e5], rel=1e-12)


def test_toe_is_the_reflector_nearest_the_known_length(simulated_head):
    """A free toe (r = -1): with the length given, its echo is the toe, not an anomaly; recorded over 400 steps,
    the toe echo comes back twice more (sent down again by the head, whose force is zero after the blow), at
    twice and three times its depth: multiples, not reflectors of the rod."""
    z = np.full(60, 4.0e5)
    record, rod = simulated_head(z, DT, hammer, 400, right="free", every=1)
    c = float(np.sqrt(rod.segments[0].material.youngs_modulus / rod.segments[0].material.density))
    out = identify_by_beta(record, z[0], c, length=60 * c * DT)
    assert out.anomalies == () and out.toe == pytest.approx(60 * c * DT, rel=1e-12)


@pytest.mark.parametrize("beta, name", [(1.0, "uniform"), (0.95, "slight damage"), (0.8, "slight damage"),
                                        (0.79, "damage"), (0.7, "damage"), (0.6, "damage"), (0.59, "broken"),
                                        (1.2, "increase")])
def test_classes(beta, name):
    """The class table of docs/identification.md (bounds as quoted after Rausche and Goble 1979)."""
    assert beta_class(beta) == name


def test_velocity_only_record_with_a_parametrised_hammer(simulated_head):
    """Low strain: the head velocity alone and the half-sine hammer of known width. Before any echo returns the
    head carries the down-going wave alone (v = -N / Z), which fixes the amplitude; the force is then the
    lattice's own half-sine, so beta is exact again."""
    from rodimpact.identify import HeadRecord, hammer_record

    z = np.r_[np.full(50, 4.0e5), np.full(150, 0.7 * 4.0e5)]
    record, rod = simulated_head(z, DT, hammer, 300, every=1)
    low = hammer_record(record.time, record.velocity, z[0], WIDTH * DT)
    assert np.max(np.abs(low.force - record.force)) < 1e-12 * 1.0e3
    c = float(np.sqrt(rod.segments[0].material.youngs_modulus / rod.segments[0].material.density))
    (step,) = identify_by_beta(low, z[0], c).anomalies
    assert step.beta == pytest.approx(0.7, rel=1e-12)
    assert isinstance(low, HeadRecord)


def test_primaries_fit_the_reflectogram_until_the_first_multiple(simulated_head):
    """The fitted reflectogram (the echoes of the reflectors found, each the down-going pulse delayed and
    scaled) equals the measured one wherever the record holds primaries only: the neck's record up to 200 steps
    (test_neck_gives_both_betas_exactly). The head holds its force at zero after the blow, so the down-going
    wave there is the blow alone; the misfit is rounding."""
    z = np.r_[np.full(50, 4.0e5), np.full(30, 0.7 * 4.0e5), np.full(120, 4.0e5)]
    record, _ = simulated_head(z, DT, hammer, 200, every=1)
    out = identify_by_beta(record, z[0], 5175.5)
    t, measured, fitted = out.matched["reflectogram"]
    assert out.misfit < 1e-12
    assert np.max(np.abs(measured[t >= 0] - fitted[t >= 0])) < 1e-12
