"""The Kolsky-bar design benchmark runs (its --quick form: small sizes, prints only)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_design_benchmark_runs_quickly() -> None:
    out = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_shpb_design.py"), "--quick"],
                         capture_output=True, text=True, timeout=600, cwd=ROOT / "benchmarks")
    assert out.returncode == 0, out.stderr[-2000:]
    assert "| designed striker, target method |" in out.stdout and "| uniform striker (baseline) |" in out.stdout
    assert "| designed striker, law in the loop |" in out.stdout
    assert "| designed shaper, Johnson-Cook OFHC Cu |" in out.stdout and "| designed shaper, Frew" in out.stdout
