"""The strain-rate plateau rule of the Kolsky-bar summaries and plots (rodimpact.shpb.plateau): the samples around
the specimen's largest force where the force is at least half of it, their mean rate and flatness."""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.shpb.plateau import RatePlateau, rate_plateau


def test_the_plateau_leaves_out_the_elastic_spike_and_the_unloading() -> None:
    t = np.arange(10) * 1e-6
    force = np.array([0.0, 3.0, 6.0, 8.0, 9.0, 10.0, 4.0, 0.0, 6.0, 0.0])     # a later reloading is not joined
    rate = np.array([0.0, 5e3, 1.1e3, 1e3, 0.9e3, 1e3, -2e3, 0.0, 1e3, 0.0])
    assert rate_plateau(t, force, rate) == RatePlateau(t[2], t[5], 1e3, pytest.approx(0.1))
    # at a quarter of the largest force: the spike and the start of the unloading are inside
    assert rate_plateau(t, force, rate, level=0.25) == RatePlateau(t[1], t[6], pytest.approx(7e3 / 6),
                                                                   pytest.approx(5e3 / (7e3 / 6) - 1.0))


def test_a_specimen_never_compressed_has_no_plateau_and_bad_arguments_are_named() -> None:
    t = np.arange(4.0)
    assert rate_plateau(t, -np.ones(4), np.ones(4)) is None
    with pytest.raises(ValueError, match=r"^level: must lie between 0 and 1, got 1\.5$"):
        rate_plateau(t, np.ones(4), np.ones(4), level=1.5)
    with pytest.raises(ValueError, match=r"^force, rate: need one value per time \(4\), got 3 and 4$"):
        rate_plateau(t, np.ones(3), np.ones(4))
