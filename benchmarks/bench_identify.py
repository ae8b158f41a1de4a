"""Identification benchmark (issue 24): random synthetic piles identified by regularised matching, by layer peeling
and by the beta method on the same records; results in docs/validation-identification.md, timings in
docs/performance.md.

Piles: 64-256 elements over their length (wave speed 4000 m/s, diameter 0.5 m, length 10 m), 0-3 anomalies of
10-50 % area change (necking or bulging, 0.5-2 diameters long, apart by at least a diameter), shaft damping from
none to strong (total C_s / Z in [0, 1]), shaft and toe springs, a toe dashpot. The record is computed on a lattice
twice as fine (dt/2, anomaly edges anywhere on it) and averaged over pairs of samples, so the truth is not the
identification's own model. Hammer: a half-sine of 2 D / c (known force). Noise: white or 1/f (power ~ 1/f), its
energy 1 %, 3 % or 10 % of the signal's energy over the record after the onset, also in the 50-sample
pre-trigger baseline. The methods get the nominal head impedance and a pile length off by up to 10 %. Peeling
runs on the deconvolved record (the half-sine is too smooth to be peeled as it is).

    python benchmarks/bench_identify.py --quick          # 6 small piles (what tests/identify runs)
    python benchmarks/bench_identify.py --piles 1000 --write
    python benchmarks/bench_identify.py --piles 1000 --shard 0/2 --rows a.jsonl --threads 1   # and 1/2, b.jsonl,
    python benchmarks/bench_identify.py --merge a.jsonl b.jsonl --write                      # on two cores
    python benchmarks/bench_identify.py --calibrate --piles 36 --seed 7   # the band factor, on other seeds
    python benchmarks/bench_identify.py --timing         # one 256-element pile into docs/performance.md

The matching runs use the band factor BAND_SCALE, calibrated with ``--calibrate`` on piles of seed 7 (disjoint from
the benchmark's seed 2024); the page also shows the coverage without it and with white-noise bands.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Optional

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "validation-identification.md"

C_WAVE = 4000.0
DIAMETER = 0.5
LENGTH = 10.0
DENSITY = 2400.0
Z_NOMINAL = DENSITY * C_WAVE * np.pi * DIAMETER ** 2 / 4
NOISE_LEVELS = (0.01, 0.03, 0.10)
PRE = 50
METHODS = ("matching", "peeling", "beta")
THRESHOLD = 0.08             # the same detection threshold (share) for every method


@dataclass
class Pile:
    n: int                   # elements of the identification lattice over the true length
    dt: float                # its element travel time = sample interval (s)
    zf: np.ndarray           # true impedance on the fine lattice (2 n elements), N s/m
    anomalies: list          # (top depth m, length m, relative change)
    soil: np.ndarray         # [C_s / Z, K_s T / Z, k_t T / Z, c_t / Z] of the fine model
    noise: float
    colour: str
    expected_length: float


def make_pile(rng: np.random.Generator, i: int, quick: bool) -> Pile:
    n = int(rng.integers(64, 97)) if quick else int(rng.integers(64, 257))
    dt = LENGTH / (C_WAVE * n)
    nf = 2 * n
    hf = LENGTH / nf
    zf = np.full(nf, Z_NOMINAL)
    anomalies = []
    for _ in range(int(rng.integers(0, 4))):
        for _try in range(50):
            ln = rng.uniform(0.5, 2.0) * DIAMETER
            top = rng.uniform(0.1 * LENGTH, 0.85 * LENGTH - ln)
            if all(top + ln + DIAMETER < a[0] or a[0] + a[1] + DIAMETER < top for a in anomalies):
                break
        else:
            continue
        share = rng.uniform(0.1, 0.5)
        change = -share if rng.uniform() < 0.5 else share
        a, b = int(round(top / hf)), int(round((top + ln) / hf))
        zf[a:b] *= 1.0 + change
        anomalies.append((a * hf, (b - a) * hf, change))
    soil = np.array([rng.uniform(0.0, 1.0), rng.uniform(0.0, 1.0), rng.uniform(1.0, 20.0), rng.uniform(0.2, 1.0)])
    return Pile(n, dt, zf, sorted(anomalies), soil, NOISE_LEVELS[i % 3], ("white", "1/f")[(i // 3) % 2],
                LENGTH * (1.0 + rng.uniform(-0.1, 0.1)))


def coloured_noise(rng: np.random.Generator, size: int, colour: str) -> np.ndarray:
    w = rng.standard_normal(size)
    if colour == "white":
        return w
    f = np.fft.rfftfreq(size)
    spec = np.fft.rfft(w)
    spec[1:] /= np.sqrt(f[1:] / f[1])
    spec[0] = 0.0
    x = np.fft.irfft(spec, n=size)
    return x / x.std()


def make_record(pile: Pile, rng: np.random.Generator):
    from rodimpact.identify import HeadRecord
    from rodimpact.identify.matching import PileModel, half_sine

    steps = PRE + 2 * int(np.ceil(1.4 * pile.n)) + 20
    dtf = pile.dt / 2
    tf = np.arange(2 * steps) * dtf
    ff = half_sine(tf, 10e3, 2 * DIAMETER / C_WAVE, PRE * pile.dt)
    fine = PileModel(dtf, pile.zf.size, ff, Z_NOMINAL)
    yf = fine.simulate(np.r_[np.log(pile.zf / Z_NOMINAL), pile.soil])
    y = yf.reshape(-1, 2).mean(axis=1)
    force = ff.reshape(-1, 2).mean(axis=1)
    t = np.arange(steps) * pile.dt
    signal = np.mean(y[PRE:] ** 2)
    noise = coloured_noise(rng, steps, pile.colour) * np.sqrt(pile.noise * signal)
    return HeadRecord(t, force, y + noise), PRE


def true_profile(pile: Pile, depth_mid: np.ndarray) -> np.ndarray:
    hf = LENGTH / pile.zf.size
    j = np.clip((depth_mid / hf).astype(int), 0, pile.zf.size - 1)
    return pile.zf[j]


def run_method(method: str, record, onset: int, pile: Pile, band_scale: float = 1.0, threads: Optional[int] = None,
               threshold: float = THRESHOLD):
    from rodimpact.identify import identify_by_beta, identify_by_peeling
    from rodimpact.identify.matching import identify_by_matching

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if method == "matching":
            return identify_by_matching(record, Z_NOMINAL, C_WAVE, length=pile.expected_length,
                                        min_change=THRESHOLD, band_scale=band_scale, threads=threads)
        rec = record.from_onset(onset)
        if method == "peeling":        # deconvolved first: the hammer's half-sine is too smooth to peel as it is
            return identify_by_peeling(rec, Z_NOMINAL, C_WAVE, threshold=threshold, deconvolve=True,
                                       length=pile.expected_length)
        return identify_by_beta(rec, Z_NOMINAL, C_WAVE, threshold=threshold, length=pile.expected_length)


def score(pile: Pile, res) -> dict[str, Any]:
    """Match found anomalies to the true ones (same sign, top within one diameter, nearest first); a found
    anomaly of the opposite sign within one diameter of a true anomaly's bottom is that anomaly's lower edge,
    neither a hit nor a false alarm. Band coverage of the matching result's bands and, under ``cmp``, of the
    comparison bands it carries (``"white"``: white noise at the baseline's level; ``"uncalibrated"``: before
    the band factor)."""
    found = [i for i, a in enumerate(res.anomalies) if res.toe is None or a.depth < res.toe - 0.5 * DIAMETER]
    comparison = res.diagnostics.get("comparison_bands", {})
    depth_err, size_err, depth_cov, depth_cov_allow, size_cov = [], [], [], [], []
    cmp = {name: {"depth_cov": [], "size_cov": []} for name in comparison}
    used = set()
    missed = 0

    def depth_in(band, top, allowance=0.0):
        return band[0] - allowance - 1e-9 <= top <= band[1] + allowance + 1e-9

    hits = {}                       # index of the true anomaly (a string, as in JSON) -> (depth error, size error)
    for t_index, (top, ln, change) in enumerate(pile.anomalies):
        best = None
        for i in found:
            a = res.anomalies[i]
            if i in used or np.sign(a.relative_change) != np.sign(change):
                continue
            if abs(a.depth - top) <= DIAMETER and (best is None or abs(a.depth - top)
                                                   < abs(res.anomalies[best].depth - top)):
                best = i
        if best is None:
            missed += 1
            continue
        used.add(best)
        a = res.anomalies[best]
        depth_err.append(abs(a.depth - top))
        size_err.append(abs(a.relative_change - change))
        hits[str(t_index)] = (depth_err[-1], size_err[-1])
        if a.depth_band is not None:
            depth_cov.append(depth_in(a.depth_band, top))
            depth_cov_allow.append(depth_in(a.depth_band, top, DIAMETER / 8))
        if a.size_band is not None:
            size_cov.append(a.size_band[0] <= change <= a.size_band[1])
        for name, bands in comparison.items():
            db, sb = bands["anomaly_bands"][best]
            if db is not None:
                cmp[name]["depth_cov"].append(depth_in(db, top))
                cmp[name]["size_cov"].append(sb[0] <= change <= sb[1])
    false = 0
    for i in found:
        if i in used:
            continue
        a = res.anomalies[i]
        edge = any(np.sign(a.relative_change) == -np.sign(c) and abs(a.depth - (t + ln)) <= DIAMETER
                   for t, ln, c in pile.anomalies)
        if not edge:
            false += 1
    out = {"depth_err": depth_err, "size_err": size_err, "hits": hits, "missed": missed, "false": false,
           "true_count": len(pile.anomalies), "depth_cov": depth_cov, "depth_cov_allow": depth_cov_allow,
           "size_cov": size_cov, "toe_err": None if res.toe is None else abs(res.toe - LENGTH), "toe_cov": None,
           "z_cov": None}
    toe_in = lambda band: bool(band[0] - 1e-9 <= LENGTH <= band[1] + 1e-9)
    if res.toe_band is not None:
        out["toe_cov"] = toe_in(res.toe_band)
    for name in ("uncalibrated", "white"):
        band = res.diagnostics.get(f"toe_band_{name}")
        if band is not None:
            cmp.setdefault(name, {"depth_cov": [], "size_cov": []})["toe_cov"] = toe_in(band)
    if res.lower is not None:
        mid = 0.5 * (res.depth[1:] + res.depth[:-1])
        keep = mid < min(LENGTH, res.depth[-1])
        zt = true_profile(pile, mid[keep])
        out["z_cov"] = float(np.mean((res.lower[keep] <= zt) & (zt <= res.upper[keep])))
        # |ln Z_true - ln Z| over the band's half width (ln): the profile covered at a band factor k where <= k
        half = 0.5 * np.log(res.upper[keep] / res.lower[keep])
        out["z_ratio"] = (np.abs(np.log(zt / res.impedance[keep])) / np.maximum(half, 1e-300)).tolist()
        for name, bands in comparison.items():
            lo, up = np.asarray(bands["lower"])[keep], np.asarray(bands["upper"])[keep]
            cmp[name]["z_cov"] = float(np.mean((lo <= zt) & (zt <= up)))
    out["cmp"] = cmp
    return out


def summarise(rows: list[dict]) -> dict[tuple, dict]:
    table = {}
    by_pile: dict[int, list[dict]] = {}
    for r in rows:
        by_pile.setdefault(r["pile"], []).append(r)
    # the anomalies every method found (on piles all three ran): errors on the same anomalies
    common = {p: set.intersection(*(set(r["hits"]) for r in rs)) for p, rs in by_pile.items()
              if len(rs) == len(METHODS)}
    for level in NOISE_LEVELS:
        for method in METHODS:
            sel = [r for r in rows if r["noise"] == level and r["method"] == method]
            if not sel:
                continue
            cat = lambda k: [x for r in sel for x in r[k]]
            toe = [r["toe_err"] for r in sel if r["toe_err"] is not None]
            true_count = sum(r["true_count"] for r in sel)
            table[(level, method)] = {
                "piles": len(sel), "true": true_count,
                "found": true_count - sum(r["missed"] for r in sel),
                "depth_err": float(np.mean(cat("depth_err"))) if cat("depth_err") else float("nan"),
                "size_err": float(np.mean(cat("size_err"))) if cat("size_err") else float("nan"),
                "false_per_pile": sum(r["false"] for r in sel) / len(sel),
                "toe_err": float(np.median(toe)) if toe else float("nan"),
                "toe_err_mean": float(np.mean(toe)) if toe else float("nan"),
                "no_toe": sum(r["toe_err"] is None for r in sel),
                "z_cov": _mean([r["z_cov"] for r in sel]),
                "depth_cov": _mean(cat("depth_cov")), "size_cov": _mean(cat("size_cov")),
                "depth_cov_allow": _mean([x for r in sel for x in r.get("depth_cov_allow", [])]),
                "toe_cov": _mean([r["toe_cov"] for r in sel]),
                "seconds": float(np.mean([r["seconds"] for r in sel])),
                "common": sum(len(common[r["pile"]]) for r in sel if r["pile"] in common),
                "depth_err_common": _mean([r["hits"][i][0] for r in sel if r["pile"] in common
                                           for i in common[r["pile"]]]),
                "size_err_common": _mean([r["hits"][i][1] for r in sel if r["pile"] in common
                                          for i in common[r["pile"]]]),
                "cmp": {name: {"z_cov": _mean([r["cmp"][name].get("z_cov") for r in sel if name in r["cmp"]]),
                               "depth_cov": _mean([x for r in sel if name in r["cmp"]
                                                   for x in r["cmp"][name]["depth_cov"]]),
                               "size_cov": _mean([x for r in sel if name in r["cmp"]
                                                  for x in r["cmp"][name]["size_cov"]]),
                               "toe_cov": _mean([r["cmp"][name].get("toe_cov") for r in sel if name in r["cmp"]])}
                        for name in ("uncalibrated", "white")}}
    return table


def _mean(values) -> float:
    v = [float(x) for x in values if x is not None]
    return float(np.mean(v)) if v else float("nan")


def run(piles: int, seed: int = 2024, quick: bool = False, progress: bool = True,
        write_every: Optional[int] = None, band_scale: float = 1.0, methods: tuple = METHODS,
        shard: tuple[int, int] = (0, 1), rows_file: Optional[Path] = None,
        threads: Optional[int] = None) -> tuple[list[dict], dict]:
    """Identify ``piles`` random piles with every method; with ``write_every``, the page is rewritten after every
    so many piles (a long run that is stopped keeps what it has, with its count). ``shard = (k, m)``: only the
    piles i with i mod m = k (all piles are drawn, so each keeps its record). ``rows_file``: every pile's rows
    are appended to it as JSON lines, and piles found there are not run again (a stopped run resumes)."""
    rng = np.random.default_rng(seed)
    done: dict[int, list[dict]] = {}
    if rows_file is not None and rows_file.exists():
        for row in load_rows([rows_file], repair=True):
            done.setdefault(row["pile"], []).append(row)
        partial = [i for i, rs in done.items() if len(rs) < len(methods)]
        if partial:                  # a pile stopped between its methods: run again, its rows dropped
            for i in partial:
                del done[i]
            rows_file.write_text("".join(json.dumps(r, default=_plain) + "\n" for i in sorted(done)
                                         for r in done[i]))
    rows = [r for i in sorted(done) for r in done[i]]
    t0 = time.perf_counter()
    mine = [i for i in range(piles) if i % shard[1] == shard[0]]
    for i in range(piles):
        pile = make_pile(rng, i, quick)
        record, onset = make_record(pile, rng)
        if i % shard[1] != shard[0] or i in done:
            continue
        new = []
        for method in methods:
            w0 = time.perf_counter()
            try:
                res = run_method(method, record, onset, pile, band_scale, threads)
            except ValueError as err:        # a method that refuses the record scores nothing found, no toe
                res = None
                why = str(err)
            s = score(pile, res) if res is not None else {
                "depth_err": [], "size_err": [], "hits": {}, "missed": len(pile.anomalies), "false": 0,
                "true_count": len(pile.anomalies), "depth_cov": [], "size_cov": [], "toe_err": None,
                "toe_cov": None, "z_cov": None, "cmp": {}, "refused": why}
            new.append({"pile": i, "method": method, "noise": pile.noise, "colour": pile.colour, "n": pile.n,
                        "seed": seed, "quick": quick, "band_scale": band_scale,
                        "seconds": time.perf_counter() - w0, **s})
        rows += new
        if rows_file is not None:
            with open(rows_file, "a") as fh:
                fh.write("".join(json.dumps(r, default=_plain) + "\n" for r in new))
        if write_every and (i + 1) % write_every == 0:
            DOC.write_text(report(summarise(rows), len({r["pile"] for r in rows}), seed, band_scale,
                                  CALIBRATION if band_scale == BAND_SCALE else " (given on the command line)"))
        if progress:
            count = sum(1 for q in mine if q <= i)
            el = time.perf_counter() - t0
            print(f"pile {i + 1}/{piles} ({count} of this shard's {len(mine)}; n={pile.n}, noise {pile.noise:.0%} "
                  f"{pile.colour}, {len(pile.anomalies)} anomalies) {el:.0f} s", file=sys.stderr, flush=True)
    return rows, summarise(rows)


def _plain(value: Any) -> Any:
    """numpy scalars (the scores' booleans and floats) as Python ones, for JSON."""
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(f"not JSON serializable: {type(value).__name__}")


#: detection thresholds of the sweep of the two fast methods (:func:`threshold_sweep`)
SWEEP = (0.08, 0.12, 0.16, 0.20, 0.25, 0.30)


def threshold_sweep(piles: int, seed: int = 2024, quick: bool = False,
                    thresholds: tuple = SWEEP) -> dict[tuple, tuple[int, int, float]]:
    """Peeling and beta on the same piles and records as :func:`run` at several detection thresholds:
    ``(noise, method, threshold) -> (found, present, false alarms per pile)``. A method that reports more
    anomalies finds more and alarms more; the sweep shows what each finds at the false-alarm rate of another."""
    rng = np.random.default_rng(seed)
    acc: dict[tuple, list[int]] = {}
    for i in range(piles):
        pile = make_pile(rng, i, quick)
        record, onset = make_record(pile, rng)
        for method in ("peeling", "beta"):
            for th in thresholds:
                try:
                    s = score(pile, run_method(method, record, onset, pile, threshold=th))
                except ValueError:
                    s = {"missed": len(pile.anomalies), "true_count": len(pile.anomalies), "false": 0}
                a = acc.setdefault((pile.noise, method, th), [0, 0, 0, 0])
                a[0] += s["true_count"] - s["missed"]
                a[1] += s["true_count"]
                a[2] += s["false"]
                a[3] += 1
    return {key: (a[0], a[1], a[2] / a[3]) for key, a in acc.items()}


def load_rows(paths: list[Path], repair: bool = False) -> list[dict]:
    """The rows saved by :func:`run` with ``rows_file`` (JSON lines), in pile order. A last line cut short (a
    run stopped while writing) is dropped, and with ``repair`` removed from its file; a row given twice (the same
    pile and method in two files) is an error."""
    rows = []
    for p in paths:
        lines = [line for line in Path(p).read_text().splitlines() if line.strip()]
        for k, line in enumerate(lines):
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:
                if k != len(lines) - 1:
                    raise SystemExit(f"{p}: line {k + 1} is not a row (JSON); the file is damaged")
                print(f"{p}: its last line was cut short (a stopped run); dropped", file=sys.stderr)
                if repair:
                    Path(p).write_text("".join(x + "\n" for x in lines[:-1]))
    seen = set()
    for r in rows:
        key = (r["pile"], r["method"])
        if key in seen:
            raise SystemExit(f"pile {r['pile']}, method {r['method']}: given twice (overlapping shards or the "
                             f"same rows file twice)")
        seen.add(key)
    return sorted(rows, key=lambda r: (r["pile"], METHODS.index(r["method"])))


def report(table: dict, piles: int, seed: int, band_scale: float = 1.0, calibration: str = "",
           sweep: Optional[dict] = None) -> str:
    """The page docs/validation-identification.md from the :func:`summarise` table of ``piles`` piles."""
    lines = ["# Validation: identification benchmark", "",
             "Generated by `python benchmarks/bench_identify.py --piles N --write` (do not edit by hand; a long run "
             "in shards: `--shard K/M --rows FILE`, then `--merge FILE ... --write`). The set-up is in the script's "
             "docstring and in [identification-matching.md](identification-matching.md).",
             "", f"{piles} random piles (seed {seed}), each identified by the three methods on the same record; "
             "noise levels assigned in turn (1 %, 3 %, 10 % of the signal energy), white and 1/f alternating "
             "every three piles. `s/pile` is the compute time of one identification on the shared 2-core machine. "
             "Methods: `matching` (regularised matching with Laplace bands, "
             "[identification-matching.md](identification-matching.md)); `peeling` (layer peeling after "
             "deconvolving the hammer's blow, `identify_by_peeling(deconvolve=True)`: the half-sine is too smooth "
             "to be peeled as it is); `beta` (reflectogram and integrity factors). All read anomalies at the same "
             "threshold of 8 % and get the expected length, off by up to 10 %.", "",
             "Columns: anomalies found / present (top within one diameter, same sign); depth error (m, mean over "
             "found); size error (mean |relative change - true|); false alarms per pile; toe error (m, median and "
             "mean; `no toe` counts results without a toe); coverage of the 90 % bands (matching only): the "
             "profile (share of elements whose true Z lies in the band), anomaly depth (true top within the band) "
             "and size, toe.", "",
             "| noise | method | piles | found | depth err | size err | false/pile | toe err med | toe err mean "
             "| no toe | Z cov | depth cov | size cov | toe cov | s/pile |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    f = lambda x, p=3: "-" if x != x else f"{x:.{p}g}"
    for (level, method), r in table.items():
        lines.append(f"| {level:.0%} | {method} | {r['piles']} | {r['found']}/{r['true']} | {f(r['depth_err'])} | "
                     f"{f(r['size_err'])} | {f(r['false_per_pile'])} | {f(r['toe_err'])} | {f(r['toe_err_mean'])} | "
                     f"{r['no_toe']} | {f(r['z_cov'], 2)} | {f(r['depth_cov'], 2)} | {f(r['size_cov'], 2)} | "
                     f"{f(r['toe_cov'], 2)} | {f(r['seconds'], 2)} |")
    lines += ["", "## Errors on the same anomalies", "",
              "The errors above are means over the anomalies each method found, and a method that finds fewer "
              "finds the larger ones. Here: the mean errors over the anomalies all three methods found.", "",
              "| noise | method | anomalies | depth err | size err |", "|---|---|---|---|---|"]
    for (level, method), r in table.items():
        lines.append(f"| {level:.0%} | {method} | {r['common']} | {f(r['depth_err_common'])} | "
                     f"{f(r['size_err_common'])} |")
    if sweep:
        ths = sorted({k[2] for k in sweep})
        lines += ["", "## Found against false alarms", "",
                  "Matching reports an anomaly only where its band excludes the local baseline, so it reports fewer. "
                  "Peeling and beta on the same piles at higher detection thresholds (`threshold_sweep`): found / "
                  "present, and false alarms per pile, at each threshold; matching's own row (threshold 0.08 and "
                  "its band) is in the first table.", "",
                  "| noise | method | " + " | ".join(f"{t:g}" for t in ths) + " |",
                  "|---|---|" + "---|" * len(ths)]
        for level in NOISE_LEVELS:
            for method in ("peeling", "beta"):
                cells = [sweep.get((level, method, t)) for t in ths]
                lines.append(f"| {level:.0%} | {method} | " + " | ".join(
                    "-" if c is None else f"{c[0]}/{c[1]}, {c[2]:.2f}" for c in cells) + " |")
    lines += ["", "## Band coverage before the calibration and with white noise", "",
              "The matching bands assume the noise of an autoregressive model of the final fit's residual (its level "
              "with the fit's degrees of freedom and its colour) and carry an empirical band factor "
              f"k = {band_scale:g} on their widths{calibration}. The toe band is the profile-likelihood interval "
              "of the truncated models under the same noise model, tempered by the same factor (2 Delta <= "
              "2.71 k^2: a band k times wider is a likelihood tempered by 1 / k^2). On the same fits and anomalies: "
              "the coverage with that model before the factor (`uncal.`), and with white noise at the baseline's "
              "level, no factor (`white`: the bands of the earlier version). The depth band is the "
              "profile-likelihood interval of the step's depth under the same noise model, not tempered (so "
              "`depth uncal.` is the same; its `white` column is the interval with white noise at the baseline's "
              "level); `depth +-D/8` is its coverage by the measure of the earlier version, the band widened by "
              "D/8 = 62.5 mm (that version read the depth band off the Laplace draws in whole elements and "
              "covered 0.97 at every level by that measure).", "",
              "| noise | piles | Z cov | Z uncal. | Z white | depth cov | depth uncal. | depth white | depth +-D/8 "
              "| size cov | size uncal. | size white | toe cov | toe uncal. | toe white |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (level, method), r in table.items():
        if method != "matching":
            continue
        u, w = r["cmp"]["uncalibrated"], r["cmp"]["white"]
        if band_scale == 1.0:
            u = {k: r[k] for k in ("z_cov", "depth_cov", "size_cov", "toe_cov")}
        lines.append(f"| {level:.0%} | {r['piles']} | {f(r['z_cov'], 2)} | {f(u['z_cov'], 2)} | {f(w['z_cov'], 2)} "
                     f"| {f(r['depth_cov'], 2)} | {f(u['depth_cov'], 2)} | {f(w['depth_cov'], 2)} "
                     f"| {f(r['depth_cov_allow'], 2)} "
                     f"| {f(r['size_cov'], 2)} | {f(u['size_cov'], 2)} | {f(w['size_cov'], 2)} "
                     f"| {f(r['toe_cov'], 2)} | {f(u['toe_cov'], 2)} | {f(w['toe_cov'], 2)} |")
    return "\n".join(lines) + "\n"


def calibrate(rows: list[dict], coverage: float = 0.90) -> float:
    """The band factor k that makes the pooled profile coverage of ``rows`` (run with k = 1) equal ``coverage``:
    the ``coverage`` quantile of |ln Z_true - ln Z| / band half width over all elements of all piles."""
    ratios = np.concatenate([r["z_ratio"] for r in rows if r["method"] == "matching" and "z_ratio" in r])
    return float(np.quantile(ratios, coverage))


def timing_section() -> str:
    """One 256-element pile: matching with Laplace bands (wall and CPU time, per phase) and with sampling, and the
    two fast methods."""
    from _report import best_time
    from rodimpact.identify.matching import identify_by_matching

    rng = np.random.default_rng(7)
    pile = make_pile(rng, 0, False)
    pile.n = 256
    pile.dt = LENGTH / (C_WAVE * 256)
    pile.zf = np.full(512, Z_NOMINAL)
    pile.zf[200:230] *= 0.7
    record, onset = make_record(pile, rng)
    run_method("matching", record, onset, pile)            # compile
    runs = []
    for _ in range(3):
        w0, c0 = time.perf_counter(), time.process_time()
        res = run_method("matching", record, onset, pile)
        runs.append((time.perf_counter() - w0, time.process_time() - c0, res.diagnostics))
    lap, lap_cpu, d0 = min(runs, key=lambda r: r[0])
    peel = best_time(lambda: run_method("peeling", record, onset, pile), 3)
    beta = best_time(lambda: run_method("beta", record, onset, pile), 3)
    w0, c0 = time.perf_counter(), time.process_time()
    res = identify_by_matching(record, Z_NOMINAL, C_WAVE, length=pile.expected_length, bands="sampling")
    samp, samp_cpu = time.perf_counter() - w0, time.process_time() - c0
    d = res.diagnostics
    load = os.getloadavg()[0]
    return ("## Identification (benchmarks/bench_identify.py)\n\n"
            f"One 256-element pile (model {d['elements_model']} elements incl. the 25 % extension, "
            f"{record.time.size} samples), on the shared 2-core machine (load average {load:.1f} from other work "
            "while measured); matching best of 3, its toe scan on the 2 cores (CPU time above wall time; other "
            "work on the machine makes wall times longer); peeling after deconvolution:\n\n"
            "| method | wall s | CPU s |\n|---|---|---|\n"
            f"| matching, Laplace bands (weight search, toe scan, covariance) | {lap:.2f} | {lap_cpu:.2f} |\n"
            f"| ... of which the weight search | {d0['time_weight_s']:.2f} | |\n"
            f"| ... the toe scan ({d0['toe_fits']} truncated models, {d0['toe_iterations']} L-BFGS-B iterations) "
            f"| {d0['time_toe_s']:.2f} | |\n"
            f"| ... the relaxed refit and the bands | {d0['time_bands_s']:.2f} | |\n"
            f"| matching, pCN sampling bands ({d.get('sampling_draws')} draws, R-hat "
            f"{d.get('sampling_rhat', float('nan')):.3f}, ESS {d.get('sampling_ess', float('nan')):.0f}, converged "
            f"{d.get('sampling_converged')}) | {samp:.2f} | {samp_cpu:.2f} |\n"
            f"| layer peeling, deconvolved (baseline) | {peel:.4f} | |\n| beta method (baseline) | {beta:.4f} | |\n")


#: the band factor of the benchmark's matching runs, from ``--calibrate --piles 36 --seed 7`` (seeds disjoint from the
#: benchmark's 2024): see docs/validation-identification.md
BAND_SCALE = 1.624
CALIBRATION = (" calibrated on 36 other piles (`--calibrate --piles 36 --seed 7`, seeds disjoint from the "
               "benchmark's 2024) to give 90 % profile coverage there")


def main(argv: Optional[list[str]] = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--piles", type=int, default=30)
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--quick", action="store_true", help="6 small piles")
    ap.add_argument("--write", action="store_true", help="write docs/validation-identification.md")
    ap.add_argument("--timing", action="store_true", help="measure one 256-element pile into docs/performance.md")
    ap.add_argument("--calibrate", action="store_true",
                    help="matching only, band factor 1: print the factor that gives 90 %% profile coverage")
    ap.add_argument("--band-scale", type=float, default=BAND_SCALE, help="band factor of the matching runs")
    ap.add_argument("--shard", default="0/1", help="K/M: run only the piles i with i mod M = K (default 0/1)")
    ap.add_argument("--rows", type=Path, help="append every pile's rows to this JSON-lines file; piles in it are "
                                              "skipped (resume)")
    ap.add_argument("--merge", type=Path, nargs="+", help="no runs: the page from these rows files")
    ap.add_argument("--threads", type=int, help="threads of each matching run (default: the cores available)")
    args = ap.parse_args(argv)
    if args.timing:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from _report import write_section
        write_section("identify", timing_section())
        return
    calibration = CALIBRATION if args.band_scale == BAND_SCALE else " (given on the command line)"
    if args.merge:
        rows = load_rows(args.merge)
        piles = len({r["pile"] for r in rows})
        if sorted({r["pile"] for r in rows}) != list(range(piles)):
            ap.error("--merge: the rows files do not hold piles 0 .. N-1 (a shard missing or unfinished)")
        for key, given in (("seed", args.seed), ("quick", args.quick), ("band_scale", args.band_scale)):
            stored = {r[key] for r in rows if key in r}
            if stored and stored != {given}:
                ap.error(f"--merge: the rows were run with {key} {sorted(stored)}, not {given} (give the same "
                         f"--{key.replace('_', '-')} as the runs)")
        text = report(summarise(rows), piles, args.seed, args.band_scale, calibration,
                      threshold_sweep(piles, args.seed, args.quick))
        print(text)
        if args.write:
            DOC.write_text(text)
        return
    try:
        k, m = (int(x) for x in args.shard.split("/"))
        if not 0 <= k < m:
            raise ValueError
    except ValueError:
        ap.error(f"--shard: must be K/M with 0 <= K < M, got {args.shard!r}")
    if m > 1 and args.write:
        ap.error("--write with --shard: write the page once, with --merge, from the shards' --rows files")
    piles = 6 if args.quick else args.piles
    if args.calibrate:
        rows, table = run(piles, args.seed, args.quick, methods=("matching",), threads=args.threads)
        print(report(table, piles, args.seed))
        print(f"band factor for 90 % profile coverage on {piles} piles of seed {args.seed}: {calibrate(rows):.4g}")
        return
    rows, table = run(piles, args.seed, args.quick, write_every=3 if args.write else None,
                      band_scale=args.band_scale, shard=(k, m), rows_file=args.rows, threads=args.threads)
    text = report(table, len({r["pile"] for r in rows}), args.seed, args.band_scale, calibration,
                  threshold_sweep(piles, args.seed, args.quick) if m == 1 else None)
    print(text)
    if args.write:
        DOC.write_text(text)


if __name__ == "__main__":
    main()
