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
{dt_line}
[output]
plots = []
snapshot_count = 5
'''

PYTHON = sys.executable

#: The time step line of SMALL_MODEL: 1 cm of steel per element, so both rods are whole numbers of elements.
DT_LINE = "dt = 1.932183566158592e-06"


def small_model(title: str) -> str:
    """SMALL_MODEL with this title."""
    return SMALL_MODEL.format(title=title, dt_line=DT_LINE)
