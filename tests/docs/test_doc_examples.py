"""The examples in README.md, examples/README.md and docs/*.md run as written.

Every fenced ```python block and every ```sh / ```bash block of a markdown file runs, in the order of the file and
in one working folder per file (``tmp_path``), so that a later block may use what an earlier one wrote -- the
commands of the user guide run in order as on a fresh clone. Python blocks share one fresh namespace per file;
tracebacks point at the markdown file and line.

Shell blocks run line by line. A line is a ``rodimpact`` command (also written ``.venv/bin/rodimpact``), run in
this process through the console script's entry point, optionally piped into other programs (``| jq ...``: run
when installed; a piped ``jq`` must get valid JSON and print more than ``null``). It must exit with 0, or with the
code its comment announces: ``rodimpact simulate model.toml -o results/model   # refused (exit 2): ...``. Any
other command (creating a virtual environment, pip, a script, redirections) is not run: a block holding one must
be left out explicitly.

A block is left out only by a marker on the line right before its fence that says why::

    <!-- doc-test: skip (needs the user's own recording file) -->

Input files an example reads are prepared in ``tmp_path`` by the per-file setup functions below (``SETUP``).
"""

import io
import json
import re
import shlex
import shutil
import subprocess
from contextlib import redirect_stderr, redirect_stdout
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import pytest

from rodimpact import cli

ROOT = Path(__file__).resolve().parents[2]
DOC_FILES = [ROOT / "README.md", ROOT / "examples" / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
LANL = ROOT / "tests" / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"

FENCE = re.compile(r"^\s*(`{3,}|~{3,})\s*([\w+-]*)")
MARKER = re.compile(r"<!--\s*doc-test:")
SKIP = re.compile(r"^\s*<!--\s*doc-test:\s*skip\s*\((?P<reason>.*\S.*)\)\s*-->\s*$")
SHELL = ("sh", "bash")
RUN = ("python",) + SHELL
EXIT = re.compile(r"#.*\(exit (\d+)\)")


@dataclass(frozen=True)
class Block:
    """A fenced code block that the test runs: ``line`` is the 1-based line of its first code line."""

    line: int
    lang: str
    code: str
    skip: Optional[str]


def code_blocks(path: Path) -> list[Block]:
    """The ```python, ```sh and ```bash blocks of ``path``. A malformed ``doc-test`` marker, or one not right
    before such a fence, is an error."""
    lines = path.read_text(encoding="utf-8").splitlines()
    blocks, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if MARKER.search(lines[i]) and not (i + 1 < len(lines) and (n := FENCE.match(lines[i + 1]))
                                           and n.group(2) in RUN and SKIP.match(lines[i])):
            raise ValueError(f"{path.name}:{i + 1}: a doc-test marker must read '<!-- doc-test: skip (reason) -->'"
                             " and stand on the line right before a ```python, ```sh or ```bash fence")
        if not m:
            i += 1
            continue
        fence, start = m.group(1), i + 1
        end = next((k for k in range(start, len(lines)) if lines[k].strip() == fence), None)
        if end is None:
            raise ValueError(f"{path.name}:{i + 1}: unclosed code fence")
        if m.group(2) in RUN:
            skip = SKIP.match(lines[i - 1]) if i > 0 else None
            indent = len(lines[i]) - len(lines[i].lstrip())
            code = "\n".join(line[indent:] for line in lines[start:end])
            blocks.append(Block(start + 1, m.group(2), code, skip.group("reason").strip() if skip else None))
        i = end + 1
    return blocks


# ============================================================================================ shell lines
def pipeline(line: str, where: str) -> list[list[str]]:
    """The commands of a shell line (split at ``|``, comments dropped); a ``ValueError`` for anything this test
    does not run."""
    lexer = shlex.shlex(line, posix=True, punctuation_chars=True)
    lexer.whitespace_split = True
    stages: list[list[str]] = [[]]
    for token in lexer:
        if token == "|":
            stages.append([])
        elif set(token) <= set("();<>|&"):
            raise ValueError(f"{where}: {token!r} is not run by the doc test; mark the block "
                             f"'<!-- doc-test: skip (reason) -->' or write plain commands")
        else:
            stages[-1].append(token)
    if not all(stages) or Path(stages[0][0]).name != "rodimpact":
        raise ValueError(f"{where}: only rodimpact commands run in doc tests, got {line.strip()!r}; mark the block "
                         f"'<!-- doc-test: skip (reason) -->' if it cannot run here")
    return stages


def run_rodimpact(argv: list[str]) -> tuple[int, str, str]:
    """``rodimpact ARGV`` through the console script's entry point, in this process: (exit code, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            code = cli.main(argv)
        except SystemExit as exc:           # argparse: usage errors, --help
            code = exc.code
    return code, out.getvalue(), err.getvalue()


def run_shell_line(line: str, where: str) -> None:
    first, *piped = pipeline(line, where)
    expected = int(m.group(1)) if (m := EXIT.search(line)) else 0
    code, out, err = run_rodimpact(first[1:])
    assert code == expected, f"{where}: {line.strip()}\nexit code {code}, expected {expected}\n{out[-2000:]}\n{err}"
    for command in piped:
        if shutil.which(command[0]) is None:    # not installed here: the rodimpact part has run
            if command[0] == "jq":
                json.loads(out)
            return
        p = subprocess.run(command, input=out, capture_output=True, text=True, timeout=60)
        assert p.returncode == 0 and p.stdout.strip() not in ("", "null"), f"{where}: {line.strip()}\n{p.stderr}"
        out = p.stdout


def run_shell(block: Block, path: Path) -> None:
    for offset, line in enumerate(block.code.splitlines()):
        if line.strip() and not line.lstrip().startswith("#"):
            run_shell_line(line, f"{path.name}:{block.line + offset}")


# ============================================================================================ per-file setup
def _lanl_shot(tmp_path: Path) -> None:
    """The examples read the reader's LANL recording ``shot.raw``; the LANL copper shot of the test data stands in."""
    shutil.copy(LANL, tmp_path / "shot.raw")


SETUP = {"docs/measurement.md": _lanl_shot, "docs/cli.md": _lanl_shot, "docs/shpb.md": _lanl_shot,
         "docs/identification.md": _lanl_shot}


# ============================================================================================ tests
def _name(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


WITH_CODE = [p for p in DOC_FILES if code_blocks(p)]


def test_doc_files_are_found():
    assert ROOT / "README.md" in WITH_CODE
    assert set(SETUP) <= {_name(p) for p in WITH_CODE}
    for name in ("docs/user-guide.md", "docs/cli.md", "README.md"):
        assert any(b.lang in SHELL and not b.skip for b in code_blocks(ROOT / name)), name


def test_unsafe_shell_lines_must_be_marked():
    for line in ("python3 -m venv .venv", "rodimpact init > x.toml", "rodimpact init && ls", "ls | rodimpact"):
        with pytest.raises(ValueError, match="doc-test: skip"):
            pipeline(line, "x.md:1")
    assert pipeline('.venv/bin/rodimpact simulate m.toml --set a.b="5 m/s" | jq ".x[0]"  # (exit 2)',
                    "x.md:1") == [[".venv/bin/rodimpact", "simulate", "m.toml", "--set", "a.b=5 m/s"],
                                  ["jq", ".x[0]"]]


@pytest.mark.parametrize("path", WITH_CODE, ids=_name)
def test_doc_examples_run(path, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("RODIMPACT_DEBUG", raising=False)
    if _name(path) in SETUP:
        SETUP[_name(path)](tmp_path)
    namespace = {"__name__": "__doc_example__"}
    for block in code_blocks(path):
        if block.skip:
            continue
        if block.lang in SHELL:
            run_shell(block, path)
            continue
        # padded so that tracebacks give the line in the markdown file
        exec(compile("\n" * (block.line - 1) + block.code, str(path), "exec"), namespace)
