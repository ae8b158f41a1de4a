"""The Python examples in README.md, examples/README.md and docs/*.md run as written.

Every fenced ```python block of a markdown file is executed, in the order of the file, in one fresh namespace
per file (a later block may use names an earlier one defined), with the working directory set to ``tmp_path``
so that the files the examples write land there. Tracebacks point at the markdown file and line.

A block may be left out only by a marker on the line right before its fence that says why::

    <!-- doc-test: skip (needs the user's own recording file) -->

Input files an example reads are prepared in ``tmp_path`` by the per-file setup functions below (``SETUP``).
"""

import re
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOC_FILES = [ROOT / "README.md", ROOT / "examples" / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LANL = ROOT / "tests" / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"

FENCE = re.compile(r"^\s*(`{3,}|~{3,})\s*([\w+-]*)")
MARKER = re.compile(r"<!--\s*doc-test:")
SKIP = re.compile(r"^\s*<!--\s*doc-test:\s*skip\s*\((?P<reason>.*\S.*)\)\s*-->\s*$")


def python_blocks(path: Path) -> list[tuple[int, str, str | None]]:
    """``(line, code, skip_reason)`` for every ```python block of ``path``; ``line`` is the 1-based line of the
    first code line. A malformed ``doc-test`` marker, or one not right before a python fence, is an error."""
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if MARKER.search(lines[i]) and not (i + 1 < len(lines) and (n := FENCE.match(lines[i + 1]))
                                           and n.group(2) == "python" and SKIP.match(lines[i])):
            raise ValueError(f"{path.name}:{i + 1}: a doc-test marker must read '<!-- doc-test: skip (reason) -->'"
                             " and stand on the line right before a ```python fence")
        if not m:
            i += 1
            continue
        fence, start = m.group(1), i + 1
        end = next((k for k in range(start, len(lines)) if lines[k].strip() == fence), None)
        if end is None:
            raise ValueError(f"{path.name}:{i + 1}: unclosed code fence")
        if m.group(2) == "python":
            skip = SKIP.match(lines[i - 1]) if i > 0 else None
            indent = len(lines[i]) - len(lines[i].lstrip())
            code = "\n".join(line[indent:] for line in lines[start:end])
            blocks.append((start + 1, code, skip.group("reason").strip() if skip else None))
        i = end + 1
    return blocks


# ============================================================================================ per-file setup
def _user_guide(tmp_path: Path) -> None:
    """Section 2 has the reader run ``rodimpact init`` (writes ``model.toml``); section 3 loads that file."""
    from rodimpact import cli

    assert cli.main(["init", "--quiet"]) == 0
    assert (tmp_path / "model.toml").is_file()


def _measurement(tmp_path: Path) -> None:
    """The session reads the reader's LANL recording ``shot.raw``; the LANL shot of the test data stands in."""
    shutil.copy(LANL, tmp_path / "shot.raw")


SETUP = {"docs/user-guide.md": _user_guide, "docs/measurement.md": _measurement}


# ============================================================================================ tests
def _name(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


WITH_PYTHON = [p for p in DOC_FILES if python_blocks(p)]


def test_doc_files_are_found():
    assert ROOT / "README.md" in WITH_PYTHON
    assert set(SETUP) <= {_name(p) for p in WITH_PYTHON}


@pytest.mark.parametrize("path", WITH_PYTHON, ids=_name)
def test_doc_examples_run(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    if _name(path) in SETUP:
        SETUP[_name(path)](tmp_path)
    namespace = {"__name__": "__doc_example__"}
    for line, code, skip in python_blocks(path):
        if skip:
            continue
        # padded so that tracebacks give the line in the markdown file
        exec(compile("\n" * (line - 1) + code, str(path), "exec"), namespace)
