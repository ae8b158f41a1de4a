"""Figures of docs/design.md: the worked examples at full size (needs the compiled adjoint engine to be quick).

* design_half_sine.png -- half-sine of 80 kN / 100 us on a 20 mm steel bar, striker 5-60 mm at 12 m/s, n = 50:
  target vs achieved force and the profile;
* design_drilling.png -- drilling piston of fixed mass and length (diameter bounds) on a drill rod ending on
  rock: the incident wave beside the reflection-free exponential f0 exp(k t / Z), efficiency against the
  uniform piston of the same mass;
* design_stepped.png -- the half-sine striker with at most 3 steps beside the free profile.

Run:  python scripts/design_examples.py [--n 50]
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

import rodimpact as ri
from rodimpact.plotting._common import new_axes
from rodimpact.plotting.design import plot_design_force, plot_design_profile, plot_incident_wave

FIG = Path(__file__).resolve().parents[1] / "docs" / "figures"


def half_sine(n: int, max_steps: int | None = None):
    dt = 100e-6 / (2 * n)
    bar = ri.Rod.from_impedance([ri.STEEL.impedance(np.pi / 4 * 0.02 ** 2)] * 8, dt)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -80e3 * np.sin(np.pi * t / 100e-6), duration=100e-6)
    return ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 12.0, n, dt,
                     limits=ri.StrikerLimits(diameter_bounds=(0.005, 0.06), material=ri.STEEL, max_steps=max_steps))


def drilling(n: int):
    dt = 2e-6
    z = 60e3
    rod = ri.Rod.from_impedance([z] * (4 * n), dt)
    k = 1.2564 * z / (2 * n * dt)          # the best x = k T / Z for the uniform piston of the rod's impedance
    rock = ri.BitRockEnd(k, 3 * k)
    m = n * dt * z
    d = ri.design(ri.EfficiencyObjective(), ri.System.struck(rod, far_end=rock), 10.0, n, dt,
                  limits=ri.StrikerLimits(diameter_bounds=(0.02, 0.09), mass=m))
    uniform = ri.simulate(ri.System([ri.Rod.from_impedance([z] * n, dt), rod], [10.0, 0.0], right=rock),
                          steps=d.time.size, dt=dt)
    eta_u = -dt * np.dot(uniform.end_force["right"], uniform.end_velocity["right"]) / (0.5 * m * 100.0)
    return d, k, z, eta_u


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=50)
    n = ap.parse_args().n
    warnings.simplefilter("ignore")
    d = half_sine(n)
    fig, axes = new_axes(None, ncols=2, figsize=(11, 4))
    plot_design_force(d, ax=axes[0])
    plot_design_profile(d, ax=axes[1])
    fig.savefig(FIG / "design_half_sine.png", dpi=100)
    print(f"half-sine: misfit {d.misfit:.4g}, {d.wall_time:.3g} s")

    s = half_sine(n, max_steps=3)
    fig, axes = new_axes(None, ncols=2, figsize=(11, 4))
    plot_design_force(s, ax=axes[0])
    plot_design_profile(s, ax=axes[1])
    fig.savefig(FIG / "design_stepped.png", dpi=100)
    print(f"stepped: {s.steps} steps, misfit {s.misfit:.4g} (free {s.diagnostics['free_profile']['misfit']:.4g})")

    p, k, z, eta_u = drilling(n)
    fig, axes = new_axes(None, ncols=2, figsize=(11, 4))
    plot_incident_wave(p, k, z, ax=axes[0])
    axes[0].set_title(f"efficiency {p.efficiency:.3f} (uniform piston of the same mass {eta_u:.3f})")
    plot_design_profile(p, ax=axes[1])
    fig.savefig(FIG / "design_drilling.png", dpi=100)
    print(f"drilling: efficiency {p.efficiency:.4g}, uniform {eta_u:.4g}")


if __name__ == "__main__":
    main()
