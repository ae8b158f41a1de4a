"""Write a benchmark table into its own marked section of docs/performance.md (other sections untouched)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

PERF = Path(__file__).resolve().parents[1] / "docs" / "performance.md"
HEADER = "# Performance\n\nMeasured by the scripts in `benchmarks/` (re-run them to refresh a section).\n"


def write_section(name: str, body: str, path: Path = PERF, header: str = HEADER) -> None:
    """Replace (or append) the text between ``<!-- name:start -->`` and ``<!-- name:end -->`` of ``path``
    (docs/performance.md unless told; a new file starts with ``header``)."""
    start, end = f"<!-- {name}:start -->", f"<!-- {name}:end -->"
    text = path.read_text() if path.exists() else header
    block = f"{start}\n{body.rstrip()}\n{end}"
    if start in text and end in text:
        text = text[: text.index(start)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip() + "\n\n" + block + "\n"
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    with os.fdopen(fd, "w") as fh:
        fh.write(text)
    os.replace(tmp, path)


def timed(fn, repeat: int) -> tuple[object, float]:
    """The result of ``fn()`` and the shortest wall time of ``repeat`` calls, s."""
    import math
    import time

    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best


def best_time(fn, repeat: int) -> float:
    """The shortest wall time of ``repeat`` calls of ``fn()``, s."""
    return timed(fn, repeat)[1]
