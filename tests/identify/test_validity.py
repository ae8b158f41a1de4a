"""The 1D-validity warnings (rodimpact/identify/validity.py): each limit is reported when broken and only then."""

import numpy as np
import pytest

from rodimpact.identify import HeadRecord, IdentificationWarning, identify_by_beta, one_dimensional_warnings


def test_each_limit():
    assert one_dimensional_warnings(None, 0.01, [0.1], 100.0) == []
    assert one_dimensional_warnings(0.1, 0.4, [0.4], 3.0) == []             # exactly at the limits: fine
    short, shallow, slender = (one_dimensional_warnings(0.1, 0.39, [], None),
                               one_dimensional_warnings(0.1, 1.0, [0.39], None),
                               one_dimensional_warnings(0.1, 1.0, [], 3.01))
    assert len(short) == 1 and "shorter than 4 diameters" in short[0]
    assert len(shallow) == 1 and "within 4 diameters" in shallow[0]
    assert len(slender) == 1 and "exceeds 30" in slender[0]


def test_beta_warns_for_a_short_pulse():
    """A pulse 3 samples wide at 1 us and 4000 m/s is 12 mm long: shorter than 4 diameters of a 0.1 m pile."""
    t = np.arange(200) * 1e-6
    n = np.where(t < 3e-6, -1.0, 0.0)
    with pytest.warns(IdentificationWarning, match="shorter than 4 diameters"):
        identify_by_beta(HeadRecord(t, n, -n / 2.0), 2.0, 4000.0, diameter=0.1)


def test_peeling_warns_for_elements_shorter_than_four_diameters(simulated_head):
    """Elements c T / 2 = 5175.5 m/s x 1 us = 5.2 mm long on a 10 mm rod: shorter than 4 diameters."""
    z = np.full(20, 4.0e5)
    record, rod = simulated_head(z, 1e-6, lambda t: -1.0e5 * np.exp(-t / 60e-6), 40)
    from rodimpact.identify import identify_by_peeling

    with pytest.warns(IdentificationWarning, match="shorter than 4 diameters"):
        identify_by_peeling(record, z[0], 5175.5, diameter=0.01)
