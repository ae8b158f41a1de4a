"""Shared inputs of the robustness tests (issue 13); imported by the test modules of this folder."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: A two-rod impact that runs in milliseconds (about 100 elements, 150 steps).
SMALL_MODEL = '''
title = "{title}"
[[rods]]
name = "striker"
velocity = "5 m/s"
[[rods.segments]]
shape = "cylinder"
length = "0.1 m"
diameter = "40 mm"
[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "0.4 m"
diameter = "40 mm"
[simulation]
steps = 150
dt = "2 us"
[output]
plots = []
snapshot_count = 5
'''

PYTHON = sys.executable
