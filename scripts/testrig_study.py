"""Regenerate the test-rig section of docs/validation-measured.md and docs/figures/testrig_*.png.

The thesis test rig (Secs. 5.1-5.4) simulated with :mod:`rodimpact.testrig`: piston 1 and piston 2
on the 50 mm x 1800 mm rod, the gauge forces N1, N2, N3 raw and through the thesis measuring chain, and the
wave-path explanation of the steps (thesis Figs. 5.11, 5.13, 5.15, 5.17).

Usage (from the project root)::

    python scripts/testrig_study.py [--out docs/validation-measured.md]

Only the text between ``<!-- testrig:start -->`` and ``<!-- testrig:end -->`` is replaced (the markers are
appended if missing); the rest of the page belongs to scripts/validate_measured.py. Every number in the
section is computed here.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rodimpact.signals import normalize_by_global_minimum, pulse_features  # noqa: E402
from rodimpact.testrig import (  # noqa: E402
    GAUGE_POSITIONS,
    IMPACT_VELOCITIES,
    ROD_LENGTH,
    RigSignals,
    build_rig,
    simulate_rig,
    wave_paths,
)

ROOT = Path(__file__).resolve().parents[1]
START, END = "<!-- testrig:start -->", "<!-- testrig:end -->"
DURATION = 1.6e-3
US, KN = 1e6, 1e-3


# ------------------------------------------------------------------------------------------- helpers
def jump_at(sig: RigSignals, gauge: str, time: float) -> float:
    """N(k) - N(k-1) at the lattice step of ``time`` (N)."""
    k = int(round(time / sig.dt))
    n = sig.raw[gauge]
    return float(n[k] - n[k - 1])


def piston_1_hand(rig) -> dict:
    """Closed-form path sums for piston 1 (40 | 50 | 40 mm, 100 | 300 | 100 mm) on the 50 mm rod."""
    a, b = rig.face_impedance, rig.rod_impedance
    z_mid = float(rig.piston.impedance(rig.piston.length / 2))
    assert abs(z_mid - b) < 1e-9 * b, "piston 1's middle part has the rod's diameter"
    r = (b - a) / (a + b)
    f0 = -a * b * rig.velocity / (a + b)
    inc = [1.0, (1 + r) * r, (1 + r) * r**3, (1 + r) * r**5, (1 + r) * (r**7 - r * (1 - r**2))]
    levels = np.cumsum(inc) * f0
    after = levels[-1] + f0 * (1 + r) * (r**9 - 2 * r**3 * (1 - r**2) - (1 - r**2) ** 2)
    return {"R": r, "F0": f0, "increments": np.array(inc) * f0, "levels": levels, "after": after}


def splice(path: Path, section: str) -> None:
    text = path.read_text(encoding="utf-8") if path.exists() else ""
    block = f"{START}\n{section.rstrip()}\n{END}"
    if START in text and END in text and text.index(START) < text.index(END):
        head, rest = text.split(START, 1)
        _, tail = rest.split(END, 1)
        text = head + block + tail
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    path.write_text(text, encoding="utf-8")


def vlines_with_labels(ax, rows, ymax, color="0.4") -> None:
    for r in rows:
        ax.axvline(r.time * 1e3, color=color, lw=0.6, ls=":")
        ax.text(r.time * 1e3, ymax, r.label, ha="center", va="bottom", fontsize=8, color=color)


# ------------------------------------------------------------------------------------------- figures
def figure_5_13(sig: RigSignals, path: Path) -> None:
    rows = wave_paths(sig.setup, sig.separation_time)
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    top = 1.15 * max(np.max(np.abs(v)) for v in sig.raw.values()) * KN
    for ax, (name, pos) in zip(axes, sig.setup.gauges):
        ax.plot(sig.time * 1e3, sig.raw[name] * KN, color="0.7", lw=0.8, label="raw (1D lattice)")
        ax.plot(sig.filtered_time * 1e3, sig.filtered[name] * KN, color="C0", lw=1.3,
                label="through the measuring chain")
        vlines_with_labels(ax, [r for r in rows if r.gauge == name and r.label], 0.8 * top)
        ax.set_ylim(-top, top)
        ax.set_ylabel(f"N{name[-1]} (kN)")
        ax.set_title(f"{name}, x = {pos * 1e3:.0f} mm", fontsize=9, loc="left")
        ax.grid(alpha=0.3)
    handles, names = axes[0].get_legend_handles_labels()
    fig.legend(handles, names, loc="upper right", ncol=2, fontsize=8)
    axes[-1].set_xlabel("time after impact (ms)")
    fig.suptitle(f"Piston 1 at {sig.setup.velocity:.2f} m/s (cf. thesis Fig. 5.13; time points t1..t10)",
                 fontsize=10, x=0.3)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _profile(ax, rig, marks) -> None:
    p = rig.piston
    s = np.linspace(0.0, p.length, 2001)
    x = p.length - s                       # rod coordinate of each distance s from the impact face
    d = np.sqrt(4 * np.asarray(p.area(np.clip(x, 0, p.length))) / math.pi) * 1e3
    ax.fill_between(s * 1e3, -d / 2, d / 2, color="0.85", step=None)
    ax.plot(s * 1e3, d / 2, color="k", lw=1)
    ax.plot(s * 1e3, -d / 2, color="k", lw=1)
    for label, dist in marks:
        ax.axvline(dist * 1e3, color="C3", lw=0.8, ls="--")
        ax.text(dist * 1e3, 31, label, color="C3", ha="center", fontsize=8)
    ax.set_xlim(-10, p.length * 1e3 + 10)
    ax.set_ylim(-30, 35)
    ax.set_xlabel("distance from the impact face (mm)")
    ax.set_ylabel("radius (mm)")
    ax.set_title(f"{p.name}: reflection sites", fontsize=9, loc="left")


def _zoom(ax, sig, events, t_max, title) -> None:
    ax.plot(sig.time * 1e6, sig.raw["SGP1"] * KN, color="0.55", lw=1.0, label="raw (1D lattice)")
    ax.plot(sig.filtered_time * 1e6, sig.filtered["SGP1"] * KN, color="C0", lw=1.3, label="through the chain")
    low = 1.12 * np.min(sig.raw["SGP1"]) * KN
    for label, r in events:
        ax.axvline(r.time * 1e6, color="C3", lw=0.8, ls="--")
        ax.text(r.time * 1e6, 0.05 * abs(low), label, color="C3", ha="center", fontsize=8)
    ax.set_xlim(0, t_max * 1e6)
    ax.set_ylim(low, 0.15 * abs(low))
    ax.set_xlabel("time after impact (µs)")
    ax.set_ylabel("N1 (kN)")
    ax.set_title(title, fontsize=9, loc="left")
    ax.legend(loc="lower right", fontsize=8)
    ax.grid(alpha=0.3)


def _numbered_events(sig: RigSignals) -> list[tuple[str, object]]:
    keep = ("incident front", "step reflection", "face-segment echo", "taper end", "piston free end",
            "incident pulse passed")
    rows = [r for r in wave_paths(sig.setup, sig.separation_time) if r.gauge == "SGP1" and r.event in keep
            and r.time < (2 * ROD_LENGTH - GAUGE_POSITIONS["SGP1"]) / sig.setup.rod_wave_speed]
    # one number per instant; where a step and a taper end coincide, the step makes the jump
    priority = {"step reflection": 0}
    rows.sort(key=lambda r: (round(r.time / sig.dt), priority.get(r.event, 1)))
    out, seen = [], set()
    for r in rows:
        key = round(r.time / sig.dt)
        if key in seen:
            continue
        seen.add(key)
        out.append((f"{len(out) + 1}", r))
    return out


def figure_zoom(sig: RigSignals, path: Path, title: str) -> list[tuple[str, object]]:
    events = _numbered_events(sig)
    c = sig.setup.rod_wave_speed
    x1 = GAUGE_POSITIONS["SGP1"]
    sites: dict[float, list[str]] = {}
    for lab, r in events:                # where in the piston each wave was reflected (mm from the face)
        if r.event in ("step reflection", "taper end", "piston free end", "face-segment echo"):
            rounds = 4 if r.event == "face-segment echo" else 2
            sites.setdefault(round((r.time - x1 / c) * c / rounds, 9), []).append(lab)
    marks = [(",".join(labs), dist) for dist, labs in sorted(sites.items())]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2), gridspec_kw={"width_ratios": [3, 2]})
    t_end = x1 / c + (sig.separation_time or sig.setup.pulse_duration) + 60e-6
    _zoom(axes[0], sig, events, t_end, title)
    _profile(axes[1], sig.setup, marks)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return events


def figure_5_11(runs: dict[float, RigSignals], path: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8), gridspec_kw={"width_ratios": [3, 2]})
    for (v, s), style in zip(runs.items(), ("-", "--", ":")):
        y = normalize_by_global_minimum(s.filtered["SGP1"])
        for ax in axes:
            ax.plot(s.filtered_time * 1e3, y, style, lw=1.2, label=f"{v:.2f} m/s")
    axes[0].set_xlim(0, DURATION * 1e3)
    axes[1].set_xlim(0.02, 0.26)
    axes[1].set_ylim(-1.05, -0.6)
    for ax in axes:
        ax.set_xlabel("time after impact (ms)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("N1 / |min N1|")
    axes[0].legend(fontsize=8)
    axes[0].set_title("piston 1, filtered N1 normalised by its global minimum (cf. Fig. 5.11)", fontsize=9, loc="left")
    axes[1].set_title("zoom: the curves coincide", fontsize=9, loc="left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ------------------------------------------------------------------------------------------- numbers
def raw_duration(sig: RigSignals) -> float:
    """Duration of the raw incident pulse at SGP1 (first to last non-zero step, before the rod-end echo), s."""
    k_echo = int(round((2 * ROD_LENGTH - GAUGE_POSITIONS["SGP1"]) / sig.setup.rod_wave_speed / sig.dt))
    n = sig.raw["SGP1"][:k_echo]
    on = np.flatnonzero(np.abs(n) > 1e-9 * abs(sig.setup.incident_plateau))
    return float((on[-1] + 1 - on[0]) * sig.dt)


def residual_velocity(sig: RigSignals) -> float:
    """Piston rigid-body velocity after the first contact: v + (integral of the contact force) / m."""
    k = int(round(sig.efficiency_time / sig.dt))
    return sig.setup.velocity + float(np.sum(sig.contact_force[:k]) * sig.dt) / sig.setup.piston.mass


def site(rig, r, after: float) -> str:
    """Where the wave of event ``r`` was reflected, in words (diameters from the geometry)."""
    p, c = rig.piston, rig.rod_wave_speed

    def diameter(dist: float) -> float:      # at a distance from the impact face
        return math.sqrt(4 * float(p.area(min(max(p.length - dist, 0.0), p.length))) / math.pi) * 1e3

    if r.event == "incident front":
        return f"contact: face {diameter(0.0):.0f} mm on the 50 mm rod"
    if r.event == "piston free end":
        return f"free end, {p.length * 1e3:.0f} mm"
    if r.event == "incident pulse passed":
        return "separation"
    rounds = 4 if r.event == "face-segment echo" else 2
    dist = after * c / rounds
    text = f"{diameter(dist - 1e-4):.0f} -> {diameter(dist + 1e-4):.0f} mm at {dist * 1e3:.0f} mm"
    return text + (", twice" if rounds == 4 else "")


def event_table(sig: RigSignals, events, hand: dict | None = None) -> str:
    c = sig.setup.rod_wave_speed
    x1 = GAUGE_POSITIONS["SGP1"]
    head = "| # | event | reflection site | time after impact | after arrival | from | simulated jump |"
    sep = "| --- | --- | --- | --- | --- | --- | --- |"
    if hand is not None:
        head += " hand-derived jump |"
        sep += " --- |"
    lines = [head, sep]
    hand_jumps = None
    if hand is not None:   # arrival, step 1, echo, step 2, free end (-> separation)
        inc = hand["increments"]
        hand_jumps = [inc[0], inc[1], inc[2], inc[4], -hand["levels"][-1]]
    for i, (lab, r) in enumerate(events):
        after = r.time - x1 / c
        origin = ("x/c" if r.event == "incident front" else
                  "x/c + t*" if r.event == "piston free end" else
                  "x/c + t_s (simulated)" if r.event == "incident pulse passed" else
                  f"x/c + 2·{after * c / 2 * 1e3:.0f} mm/c" if r.event != "face-segment echo" else
                  f"x/c + 4·{after * c / 4 * 1e3:.0f} mm/c")
        row = (f"| {lab} | {r.event} | {site(sig.setup, r, after)} | {r.time * US:.2f} µs | {after * US:.2f} µs "
               f"| {origin} | {jump_at(sig, 'SGP1', r.time) * KN:+.2f} kN |")
        if hand_jumps is not None:
            row += f" {hand_jumps[i] * KN:+.2f} kN |" if i < len(hand_jumps) else " |"
        lines.append(row)
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "validation-measured.md")
    args = parser.parse_args()
    figdir = args.out.parent / "figures"
    figdir.mkdir(parents=True, exist_ok=True)

    rig1, rig2 = build_rig(1), build_rig(2)
    s1, s2 = simulate_rig(rig1, DURATION), simulate_rig(rig2, DURATION)
    c = rig1.rod_wave_speed
    x1 = GAUGE_POSITIONS["SGP1"]
    hand = piston_1_hand(rig1)
    tau = rig1.piston.segment_travel_times[-1]

    # plateau levels of piston 1 (raw, exact lattice) vs the path sums
    k_arr = int(round(x1 / c / s1.dt))
    n_tau = int(round(tau / s1.dt))
    plateau_rows = []
    for j, level in enumerate(hand["levels"]):
        a, b = k_arr + 2 * j * n_tau, k_arr + 2 * (j + 1) * n_tau
        sim = s1.raw["SGP1"][a:b]
        plateau_rows.append((j, level, float(sim.mean()), float(np.ptp(sim))))
    plateau_err = max(abs(sim - lev) / abs(hand["F0"]) for _, lev, sim, _ in plateau_rows)

    # durations
    pf1_raw = pulse_features(s1.time, s1.raw["SGP1"] * (s1.time < (2 * ROD_LENGTH - x1) / c))
    pf1_f = pulse_features(s1.filtered_time, s1.filtered["SGP1"] * (s1.filtered_time < (2 * ROD_LENGTH - x1) / c))
    pf2_f = pulse_features(s2.filtered_time, s2.filtered["SGP1"] * (s2.filtered_time < (2 * ROD_LENGTH - x1) / c))
    dur1, dur2 = raw_duration(s1), raw_duration(s2)
    delay = float(s1.chain.group_delay(0.0)[0])

    # scalability and repeatability (piston 1)
    runs = {v: simulate_rig(rig1.with_velocity(v), DURATION) for v in IMPACT_VELOCITIES["impact velocity"]}
    norm = [normalize_by_global_minimum(r.filtered["SGP1"]) for r in runs.values()]
    scal_dev = max(float(np.max(np.abs(n - norm[0]))) for n in norm[1:])
    rep = {v: float(np.min(simulate_rig(rig1.with_velocity(v), 0.4e-3).filtered["SGP1"]))
           for v in IMPACT_VELOCITIES["repeatability"]}
    rep_spread = (max(rep.values()) - min(rep.values())) / abs(np.mean(list(rep.values())))

    # figures
    figure_5_13(s1, figdir / "testrig_fig5_13.png")
    ev1 = figure_zoom(s1, figdir / "testrig_fig5_15.png",
                      f"piston 1 at {rig1.velocity:.2f} m/s: incident wave at SGP1 (cf. Fig. 5.15)")
    ev2 = figure_zoom(s2, figdir / "testrig_fig5_17.png", f"piston 2 (assumed dimensions) at "
                      f"{rig2.velocity:.2f} m/s: incident wave at SGP1 (cf. Fig. 5.17)")
    figure_5_11(runs, figdir / "testrig_fig5_11.png")

    labels = sorted({(r.label, r.gauge, r.event, r.time) for r in wave_paths(rig1) if r.label},
                    key=lambda x: (int(x[0][1:]), x[1]))
    period = {lab: t for lab, _, _, t in labels}["t10"] - {lab: t for lab, _, _, t in labels}["t3"]
    label_lines = "\n".join(f"| {lab} | {g} | {ev} | {t * US:.1f} µs |" for lab, g, ev, t in labels)
    plateau_lines = "\n".join(
        f"| [{2 * j}τ, {2 * j + 2}τ) | {lev * KN:.3f} kN | {sim * KN:.3f} kN | {spread:.1e} N |"
        for j, lev, sim, spread in plateau_rows)
    sep2 = s2.separation_time
    section = f"""## The thesis test rig, simulated (thesis 5.1-5.4)

Generated by `python scripts/testrig_study.py` (this section only). Model: `rodimpact.testrig`
(`build_rig`, `simulate_rig`, `wave_paths`). The thesis's recordings are not available here, so this section
is the model side of thesis 5.4 - what the 1D model predicts at the three gauge stations and why - and
the checks of those predictions against hand calculations (tests in `tests/signals/test_testrig.py`).

**Rig.** Steel (E = 210 GPa, rho = 7840 kg/m^3, c = {c:.1f} m/s) rod, d = 50 mm, L = 1800 mm, free right
end; gauges SGP1/2/3 at 110/900/1690 mm from the impact face (opposite pairs 0°/180°; the 1D model has no
bending, so the pair average of eq. 5.1 is the probe force). Measuring chain of Tab. 5.1 (`MeasuringChain()`:
analog Bessel 5th order 100 kHz, 1 MHz sampling, digital Bessel 4th order 40 kHz, causal), whose
low-frequency group delay is {delay * US:.2f} µs: the filtered curves arrive that much later. Time 0 is the
impact (the thesis plots include a pretrigger). Lattice: dt = {s1.dt * 1e9:.2f} ns = 1 mm of steel, so every
step of the pistons and every gauge lies on a node; for stepped cylinders the lattice solution is exact.

**Assumed dimensions.** Piston 1 (Fig. 5.3: 40 mm ends, 50 mm middle, about 0.5 m): the lengths are not in
the text; chosen 100/300/100 mm (as `rodimpact/examples/test-rig.toml`). Piston 2 (Fig. 5.4): no dimension is
given in the text; chosen to follow the wave-path narrative of 5.4.2 (a cone at the impact side, a middle
block, a small block near the end), from the impact face: cone 80 mm (30 -> 50 mm), 100 mm (36 mm), middle
block 120 mm (50 mm), 120 mm (36 mm), small block 40 mm (44 mm), 30 mm (36 mm), {rig2.piston.length * 1e3:.0f} mm
in all. **Piston 2's numbers below are those of this assumed geometry, not of the thesis's piston.**

**t\\* (eq. 5.4).** t\\* = 2 l_Pis / c = {rig1.pulse_duration * 1e3:.4f} ms for piston 1. The thesis prints
t\\* = 1.93·10⁻³ s, a slip of a factor 10: 2 × 0.5 m / {c:.1f} m/s = 1.93·10⁻⁴ s. The time points of
Fig. 5.13 confirm the 0.193 ms: t5 joins "the incident wave passes SGP2" (x2/c + t\\*) and "the reflection
reaches SGP3" ((2L - x3)/c), which coincide only for l_Pis ≈ 0.5 m.

![piston 1, N1 N2 N3](figures/testrig_fig5_13.png)

**Time points of Fig. 5.13 from travel times** (piston 1, `wave_paths(build_rig(1))`, label column):

| | gauge | event | time after impact |
| --- | --- | --- | --- |
{label_lines}

t10 - t3 = {period * US:.1f} µs = 2L/c = {2 * ROD_LENGTH / c * US:.1f} µs: the period of the repetition
(thesis: "twice along the rod").

### Piston 1: the steps of the incident wave (Fig. 5.15)

With the contact face an impedance step Z_40 = {rig1.face_impedance:.0f} N s/m | Z_50 = {rig1.rod_impedance:.0f} N s/m
(R = (Z_50 - Z_40)/(Z_50 + Z_40) = {hand['R']:.4f}; transmission 1 ± R), the waves returning from the piston
reach the contact face at multiples of 2τ, τ = 100 mm / c = {tau * US:.2f} µs. Events at SGP1 (the numbers
of the figure):

{event_table(s1, ev1, hand)}

The hand-derived jumps are path sums (F0 = first level): 1 first level -Z_40 Z_50 v/(Z_40 + Z_50);
2 R(1+R)·F0; 3 R³(1+R)·F0 (two round trips in the face part, the thesis's "considerably smaller" second
deflection); 4 (1+R)(R⁷ - R(1-R²))·F0 (reflection at the 50 -> 40 mm step, plus four round trips in the face part); 5 the free-end
reflection would need a tensile contact force ({hand['after'] * KN:+.2f} kN), so the bodies separate at
t_s = {s1.separation_time * US:.2f} µs = t\\* and N1 returns to 0. A further step at 6τ, R⁵(1+R)·F0 =
{hand['increments'][3] * KN:+.3f} kN, is too small to list. Plateau levels (raw simulated mean vs path sum):

| window after arrival | path sum | simulated | spread within the window |
| --- | --- | --- | --- |
{plateau_lines}

Largest deviation {plateau_err:.1e} of |F0|. Raw pulse duration at SGP1: {dur1 * 1e3:.4f} ms = t\\*.
Through the chain the edges become ramps with a small overshoot; the duration at 50 % of the mean plateau
(`pulse_features`) is {pf1_f.duration * 1e3:.4f} ms filtered and {pf1_raw.duration * 1e3:.4f} ms raw, the
deepest filtered value {np.min(s1.filtered['SGP1']) * KN:.2f} kN against {np.min(s1.raw['SGP1']) * KN:.2f} kN
raw. The small step 3 ({hand['increments'][2] / hand['F0'] * 100:.1f} % of F0) is smoothed into the plateau by the
40 kHz filter.

![piston 1, zoom](figures/testrig_fig5_15.png)

### Piston 2 (assumed dimensions; Fig. 5.17)

{event_table(s2, ev2)}

Numbers as in the figure; the thesis's t1..t6 of Fig. 5.17 correspond to 1 (arrival at the beginning of the
cone), 2 (end of the cone), 3/4 (beginning/end of the middle block), 5 (small block; its end, 6, is a second,
smaller step of this assumed geometry) and 7 (free end). Jump 1 is the lattice's: its face element carries
the cone's mean impedance over the first 1 mm ({s2.raw['SGP1'][k_arr] * KN:.2f} kN; the exact 30 mm face gives
-Z_30 Z_50 v/(Z_30 + Z_50) = {rig2.incident_plateau * KN:.2f} kN); the cone is the only part the lattice approximates. As in the thesis's
narrative: the first level (30 mm face on the 50 mm rod) falls almost linearly while the
reflections from the widening cone arrive, rises when the reflection from the cone's end (50 -> 36 mm)
arrives, drops/rises at the beginning/end of the middle block, drops at the small block and rises most at
the free-end reflection. The bodies do not separate when the free-end reflection reaches the contact face
(t\\* = {rig2.pulse_duration * US:.2f} µs) but at t_s = {sep2 * US:.2f} µs,
{(sep2 - rig2.pulse_duration) * US:.2f} µs later
(thesis 5.4.2: "shortly later, which leads to a wider incident wave"). Raw pulse duration at SGP1:
{dur2 * 1e3:.4f} ms = t_s; filtered, at 50 %: {pf2_f.duration * 1e3:.4f} ms.

![piston 2, zoom](figures/testrig_fig5_17.png)

### Energy transfer, scaling, repeatability

| | piston mass | t\\* | separation t_s | energy-transfer efficiency | piston velocity after contact |
| --- | --- | --- | --- | --- | --- |
| piston 1, {rig1.velocity:.2f} m/s | {rig1.piston.mass:.3f} kg | {rig1.pulse_duration * US:.2f} µs | {s1.separation_time * US:.2f} µs | {s1.efficiency * 100:.2f} % | {residual_velocity(s1):+.3f} m/s |
| piston 2, {rig2.velocity:.2f} m/s | {rig2.piston.mass:.3f} kg | {rig2.pulse_duration * US:.2f} µs | {sep2 * US:.2f} µs | {s2.efficiency * 100:.2f} % | {residual_velocity(s2):+.3f} m/s |

Efficiency = share of the piston's kinetic energy m v²/2 in the rod at t = 2L/c (before the rod's reflection
returns to the impact face); the tests check it against the energy flux of the incident wave, ∫N1²/Z dt.

Scalability (5.3.3): the filtered N1 normalised by its global minimum at {', '.join(f'{v:.2f}' for v in runs)} m/s
differ by at most {scal_dev:.1e} (the model is linear in v, and contact and separation times do not depend
on v). The 1D model thus scales exactly; the small deviations between the thesis's measured curves
(Fig. 5.11) are outside it (noise, 3D effects, small differences between shots).

![scalability](figures/testrig_fig5_11.png)

Repeatability shots (4.57/4.58/4.60 m/s): the velocity alone moves the simulated filtered minimum by
{rep_spread * 100:.2f} % ({', '.join(f'{v:.2f} m/s: {m * KN:.1f} kN' for v, m in rep.items())}).
"""
    splice(args.out, section)
    print(f"wrote the test-rig section of {args.out} and 4 figures testrig_*.png in {figdir}")


if __name__ == "__main__":
    main()
