"""The Smith-baseline pile benchmark runs (its --quick form: three segment counts, two resistances; prints only)."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_the_pile_baseline_benchmark_runs_quickly() -> None:
    out = subprocess.run([sys.executable, str(ROOT / "benchmarks" / "bench_pile_baseline.py"), "--quick"],
                         capture_output=True, text=True, timeout=600, cwd=ROOT / "benchmarks")
    assert out.returncode == 0, out.stderr[-2000:]
    assert "| segments | segment length | Smith set |" in out.stdout
    assert "| ultimate resistance | Smith, 10 segments |" in out.stdout
