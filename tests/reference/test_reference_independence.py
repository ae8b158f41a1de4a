"""rodimpact.reference must not use the code it checks (lattice, direct solver, rods, inverse problem).

The guard parses every module of the reference package with :mod:`ast` and resolves every import, at any
depth (module level or inside functions), to an absolute module name:

* ``import a.b`` and ``from a.b import c`` (``c`` may be a module or a name in ``a.b``);
* relative imports, ``from . import x``, ``from ..lattice import y``, ``from .. import direct``;
* dynamic imports whose module name is a string literal: ``importlib.import_module("...")`` (also with a
  relative name and ``package=``) and ``__import__("...")``.

Within rodimpact only the reference package itself and the shared input checks (``rodimpact._validate``)
are allowed; ``from rodimpact import simulate`` is refused like ``import rodimpact.direct`` (the top-level
package re-exports the solver).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import rodimpact.reference

PACKAGE = "rodimpact.reference"
ALLOWED = ("rodimpact.reference", "rodimpact._validate")


def _allowed(name: str) -> bool:
    if name.startswith("<"):
        return False                                  # an import the guard cannot resolve
    if name != "rodimpact" and not name.startswith("rodimpact."):
        return True                                   # numpy, scipy, the standard library, ...
    return any(name == a or name.startswith(a + ".") for a in ALLOWED)


def _resolve(module: str | None, level: int, current: str) -> str:
    """Absolute name of ``from <level dots><module> import ...`` written in module ``current`` (a package's
    ``__init__`` counts as a module inside the package, as for the interpreter)."""
    if level == 0:
        return module or ""
    parts = current.split(".")
    base = parts[:len(parts) - level]
    if not base:
        return "<relative import beyond the top-level package>"
    return ".".join(base + ([module] if module else []))


def _string(node: ast.AST) -> str | None:
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) else None


def imported_names(source: str, current: str) -> list[tuple[int, str]]:
    """Every module (or module.name) that ``source`` imports, resolved to absolute names, with line numbers."""
    out: list[tuple[int, str]] = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(node.module, node.level, current)
            out.append((node.lineno, base))
            out += [(node.lineno, f"{base}.{a.name}") for a in node.names if a.name != "*"]
            if any(a.name == "*" for a in node.names) and base in ("rodimpact",):
                out.append((node.lineno, "rodimpact.*"))
        elif isinstance(node, ast.Call):
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
            if name not in ("import_module", "__import__") or not node.args:
                continue
            target = _string(node.args[0])
            if target is None:
                out.append((node.lineno, "<dynamic import of a computed name>"))
                continue
            package = next((_string(k.value) for k in node.keywords if k.arg == "package"), None)
            if len(node.args) > 1 and name == "import_module":
                package = _string(node.args[1])
            if target.startswith("."):
                level = len(target) - len(target.lstrip("."))
                target = _resolve(target[level:] or None, level, (package or current) + ".x")
            out.append((node.lineno, target))
    return out


def violations(source: str, current: str) -> list[str]:
    return [f"line {line}: {name}" for line, name in imported_names(source, current) if not _allowed(name)]


def test_reference_modules_import_no_solver_code():
    root = Path(rodimpact.reference.__file__).parent
    files = sorted(root.glob("*.py"))
    assert len(files) >= 6
    for path in files:
        current = f"{PACKAGE}.{path.stem}"
        assert violations(path.read_text(encoding="utf-8"), current) == [], path.name


@pytest.mark.parametrize("statement", [
    "from rodimpact import simulate",
    "from rodimpact import lattice",
    "from .. import lattice",
    "from ..direct import simulate",
    "from ..direct.simulate import simulate",
    "from ...rodimpact import rods",
    "import rodimpact.direct",
    "import rodimpact.direct.simulate as s",
    "import rodimpact",
    "from rodimpact import *",
    "from rodimpact.inverse import synthesize",
    "import importlib\nimportlib.import_module('rodimpact.lattice')",
    "from importlib import import_module\nimport_module('..direct', package='rodimpact.reference')",
    "__import__('rodimpact.rods')",
    "import importlib\nimportlib.import_module(name)",
    "def f():\n    from rodimpact import simulate\n    return simulate",
    "class A:\n    def m(self):\n        import rodimpact.lattice",
])
def test_guard_catches_every_import_form(statement):
    assert violations(statement, f"{PACKAGE}.modal"), statement


@pytest.mark.parametrize("statement", [
    "import numpy as np",
    "from scipy import optimize",
    "from rodimpact._validate import finite",
    "from rodimpact.reference.families import AnalyticProfile",
    "from .families import AnalyticProfile",
    "from . import wavetrains",
    "from .._validate import positive",
    "import importlib\nimportlib.import_module('.modal', package='rodimpact.reference')",
])
def test_guard_allows_the_reference_package_and_the_input_checks(statement):
    assert violations(statement, f"{PACKAGE}.modal") == [], statement
