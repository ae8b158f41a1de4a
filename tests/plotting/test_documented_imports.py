"""Every plotting function the documentation names imports from ``rodimpact.plotting`` (issue 20, item 9: the user
guide listed ``plot_shape``, which raised ImportError from there)."""

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = sorted((ROOT / "docs").glob("*.md")) + [ROOT / "README.md"]
NAME = re.compile(r"\b(?:plot|animate)_[a-z0-9_]+\b")


def documented_plot_functions() -> list[str]:
    """The ``plot_*`` and ``animate_*`` names written anywhere in README.md and docs/*.md."""
    names: set[str] = set()
    for path in DOCS:
        names.update(NAME.findall(path.read_text(encoding="utf-8")))
    return sorted(names)


def test_the_docs_name_plotting_functions():
    # the scan itself must find what the user guide lists, else the test below checks nothing
    assert {"plot_forces", "plot_shape", "plot_existence", "plot_synthesis"} <= set(documented_plot_functions())


@pytest.mark.parametrize("name", documented_plot_functions())
def test_documented_plotting_function_imports_from_rodimpact_plotting(name):
    plotting = importlib.import_module("rodimpact.plotting")
    exec(f"from rodimpact.plotting import {name}", {})       # the statement a user writes
    assert callable(getattr(plotting, name))
    assert name in plotting.__all__
