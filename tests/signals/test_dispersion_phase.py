"""The sign of the dispersive phase in ``propagate_dispersive``, checked against independent references (the
propagate-then-correct round trips cannot see it: a wrong sign cancels in the round trip).

Convention: a wave exp(i(k z - omega t)) that has travelled a distance L carries the extra phase k L; the
signal at z = L is the signal at z = 0 delayed by L / c(f) for each component, and relative to the travel time
L / c0 of the 1D rod by L (1/c(f) - 1/c0) >= 0, since in a Pochhammer-Chree bar every phase velocity of the
first mode is below c0.
"""

from __future__ import annotations

import numpy as np
import pytest

from rodimpact.signals.dispersion import PochhammerChree, phase_velocity_at_frequency, propagate_dispersive

NU, RADIUS, C0 = 0.30, 0.01, 5000.0
MODEL = PochhammerChree(NU, radius=RADIUS, bar_wave_speed=C0)     # one instance: its table is built once


@pytest.mark.parametrize("fbar", [0.05, 0.15, 0.3])
def test_wave_train_phase_after_a_distance(fbar):
    """A long tone burst of carrier f0 (narrow band): the Fourier transform of the output at f0 is that of the
    input times exp(-i 2 pi f0 L (1/c(f0) - 1/c0)), i.e. the phase changes by -(k - omega/c0) L. The phase
    velocity comes from the exact root of the frequency equation, not from the model's table."""
    f0 = fbar * C0 / RADIUS
    dt = 1e-6                                     # Nyquist at f a / c0 = 1
    t = np.arange(0, 4e-3, dt)
    x = np.exp(-0.5 * ((t - 2e-3) / 300e-6) ** 2) * np.cos(2 * np.pi * f0 * t)
    distance = 0.7
    y = propagate_dispersive(t, x, distance, MODEL)
    probe = np.exp(-2j * np.pi * f0 * t)
    ratio = np.sum(y * probe) / np.sum(x * probe)
    c = float(phase_velocity_at_frequency(NU, fbar)) * C0
    phase = 2 * np.pi * f0 * distance * (1 / c - 1 / C0)
    assert abs(np.exp(-1j * phase) - np.exp(1j * phase)) > 0.05          # the sign is visible at this f0
    assert abs(ratio - np.exp(-1j * phase)) < 1e-6


def test_dispersive_ringing_trails_the_front():
    """All first-mode phase and group velocities are below c0: after a distance, nothing arrives before the 1D
    front (at the same time in the co-moving frame) except the smeared edge, while the slow high frequencies
    ring behind it (the Pochhammer oscillations on the plateau)."""
    model = PochhammerChree(0.29, radius=0.00475, bar_wave_speed=4975.0)
    dt = 0.1e-6
    t = np.arange(0, 600e-6, dt)
    pulse = -0.5 * (np.tanh((t - 100e-6) / 0.3e-6) - np.tanh((t - 151e-6) / 0.3e-6))
    change = propagate_dispersive(t, pulse, 0.39, model) - pulse
    ahead = (t > 50e-6) & (t < 97e-6)
    behind = (t > 103e-6) & (t < 140e-6)
    assert np.max(np.abs(change[ahead])) < 0.1
    assert np.max(np.abs(change[behind])) > 0.2
