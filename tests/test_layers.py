"""Import direction between the package's layers (docs: architecture): a layer imports only the layers below it,
so that there is no import circle (results know nothing about files or figures).

Bottom to top: rods, lattice, direct, inverse, design, signals, testrig, shpb (the split-Hopkinson-bar
application) and identify (identification: peeling, beta, strikers; beside shpb), then plotting and io side by
side (io writes data files only; neither imports the other),
output_folders (puts io's files and plotting's figures into one output folder for the command line and the
examples), examples, cli (signals, the measurement layer, does not import the solvers: the test rig that simulates
sits above them); ``reference`` is independent of lattice and direct so that it can check them (inverse uses its closed form of eq. 4.26 as the
target of Lundberg and Lesser's example: one copy of the formula). The private helper modules at the top of the package
(``_validate``, ``_permissions``, ...) may be used everywhere and import only each other; the package root is
never imported from inside (``rodimpact._version`` holds the version). Checked twice: statically over every import statement
(also those inside functions, which run only on use), and at run time in a fresh interpreter per layer with every
import recorded as (importing module, imported module).
"""

import ast
import json
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "rodimpact"
BELOW = {
    "rods": set(),
    "lattice": {"rods"},
    "direct": {"rods", "lattice"},
    "inverse": {"rods", "lattice", "direct", "reference"},
    "design": {"rods", "lattice", "direct", "inverse", "reference"},
    "reference": {"rods"},
    "signals": {"rods", "lattice"},             # measurement only: no solver (the test rig sits above)
    "testrig": {"rods", "lattice", "direct", "signals"},
    # the split-Hopkinson-bar application: composes the solvers and the measurement layer, below files and figures
    "shpb": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig"},
    # identification (peeling, beta, striker identification): composes the solvers and the measurement layer
    # like shpb, beside it (neither needs the other), below files and figures
    "identify": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig"},
    # plotting draws and io reads and writes files: side by side, neither imports the other
    "plotting": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig", "shpb",
                 "identify"},
    "io": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig", "shpb",
           "identify"},
    # output folders with figures: io's data files and plotting's figures, put together
    "output_folders": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig", "shpb",
                       "identify", "plotting", "io"},
    "examples": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig", "shpb",
                 "identify", "plotting", "io", "output_folders"},
    "cli": {"rods", "lattice", "direct", "inverse", "design", "reference", "signals", "testrig", "shpb", "identify",
            "plotting", "io", "output_folders", "examples"},
}


def layer(module: str) -> str | None:
    """The layer of a module name inside the package (None for the root and non-package modules)."""
    parts = module.split(".")
    if parts[0] != "rodimpact" or len(parts) == 1:
        return None
    return "cli" if parts[1] in ("cli", "__main__") else parts[1]


def allowed(source: str, target: str, names: tuple[str, ...] = ()) -> bool:
    src, dst = layer(source), layer(target)
    if target == "rodimpact":          # the root imports every layer: only code outside the layers may use it
        return src is None
    if dst is None or src is None or dst == src or dst.startswith("_"):
        return True
    if src.startswith("_"):            # a private helper module imports only its peers
        return False
    return dst in BELOW.get(src, set())


def module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def static_imports(path: Path):
    """(target module, imported names, line) of every import statement outside ``if TYPE_CHECKING:``."""
    tree = ast.parse(path.read_text())
    package = module_name(path) if path.name == "__init__.py" else module_name(path).rpartition(".")[0]
    typing_only = {id(n) for node in ast.walk(tree) if isinstance(node, ast.If) and "TYPE_CHECKING" in
                   ast.unparse(node.test) for n in ast.walk(node)}
    for node in ast.walk(tree):
        if id(node) in typing_only:
            continue
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name, (), node.lineno
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            names = tuple(a.name for a in node.names)
            submodules = [f"{base}.{n}" for n in names if (PACKAGE.parent / f"{base}.{n}".replace(".", "/")).exists()
                          or (PACKAGE.parent / (f"{base}.{n}".replace(".", "/") + ".py")).exists()]
            for target in submodules or [base]:
                yield target, names, node.lineno


def test_every_import_statement_points_down():
    wrong = []
    for path in sorted(PACKAGE.rglob("*.py")):
        source = module_name(path)
        for target, names, line in static_imports(path):
            if not allowed(source, target, names):
                wrong.append(f"{path.relative_to(PACKAGE.parent)}:{line} ({layer(source)}) imports {target} "
                             f"({layer(target)})")
    assert not wrong, "imports against the layers:\n" + "\n".join(wrong)


def test_io_and_plotting_never_import_each_other():
    """io writes data files and plotting draws (issue 21): the command line and the examples compose them
    (``rodimpact.output_folders``). Every import statement of either package, also inside functions."""
    wrong = []
    for own, other in (("io", "plotting"), ("plotting", "io")):
        for path in sorted((PACKAGE / own).rglob("*.py")):
            for target, _, line in static_imports(path):
                if layer(target) == other:
                    wrong.append(f"{path.relative_to(PACKAGE.parent)}:{line} imports {target}")
    assert not wrong, "\n".join(wrong)


def test_the_static_check_sees_an_upward_import():
    """The checker itself: a lazy import of io inside a result method (the circle this test guards against)."""
    assert not allowed("rodimpact.direct.result", "rodimpact.io.results", ("save",))
    assert not allowed("rodimpact.reference.modal", "rodimpact.direct.simulate", ("simulate",))
    assert not allowed("rodimpact.direct.simulate", "rodimpact", ("sweep",))
    assert not allowed("rodimpact.io.results", "rodimpact.plotting", ("save_plots",))     # io writes data only
    assert not allowed("rodimpact.plotting.sweep", "rodimpact.io.model_sweep", ("summary",))
    assert allowed("rodimpact.output_folders", "rodimpact.plotting", ("save_plots",))
    assert not allowed("rodimpact.direct.simulate", "rodimpact", ("__version__",))   # rodimpact._version serves
    assert allowed("rodimpact.direct.simulate", "rodimpact._version", ("__version__",))
    assert not allowed("rodimpact._validate", "rodimpact.rods.material", ("Material",))
    assert not allowed("rodimpact.newlayer.x", "rodimpact.direct.result", ())     # a new layer must be placed


RECORDER = """
import builtins, importlib.util, json, sys
edges = []
real = builtins.__import__
def recording(name, globals=None, locals=None, fromlist=(), level=0):
    importer = (globals or {}).get("__name__", "")
    package = (globals or {}).get("__package__") or importer.rpartition(".")[0]
    target = importlib.util.resolve_name("." * level + name, package) if level else name
    if importer.startswith("rodimpact") and target.startswith("rodimpact"):
        for item in (fromlist or ()):
            sub = target + "." + item
            if importlib.util.find_spec(target) and item != "*" and sub.count(".") < 4:
                try:
                    if importlib.util.find_spec(sub):
                        edges.append((importer, sub, []))
                        continue
                except (ImportError, ValueError):
                    pass
            edges.append((importer, target, [item]))
        if not fromlist:
            edges.append((importer, target, []))
    return real(name, globals, locals, fromlist, level)
builtins.__import__ = recording
import importlib
importlib.import_module(sys.argv[1])
print(json.dumps(edges))
"""


@pytest.mark.parametrize("module", ["rodimpact.rods", "rodimpact.lattice", "rodimpact.direct.simulate",
                                    "rodimpact.direct.result", "rodimpact.inverse", "rodimpact.reference",
                                    "rodimpact.signals", "rodimpact.testrig", "rodimpact.shpb", "rodimpact.plotting",
                                    "rodimpact.io.results", "rodimpact.output_folders", "rodimpact.cli"])
def test_importing_a_layer_in_a_fresh_interpreter_imports_downwards(module):
    out = subprocess.run([sys.executable, "-c", RECORDER, module], capture_output=True, text=True, check=True,
                         cwd=PACKAGE.parent)
    edges = json.loads(out.stdout.strip().splitlines()[-1])
    assert any(layer(a) == "direct" for a, _, _ in edges)           # the whole package was loaded (root __init__)
    wrong = sorted({f"{a} imports {b} {names}" for a, b, names in edges if not allowed(a, b, tuple(names))})
    assert not wrong, "\n".join(wrong)


def module_graph() -> dict[str, set[str]]:
    """Module -> the package's modules it imports (every static import statement, also inside functions; imports
    for type checking only are left out)."""
    modules = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}
    return {m: {t for t, _, _ in static_imports(p) if t in modules and t != m} for m, p in modules.items()}


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in graph:
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph[w]))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[v])
                if low[v] == index[v]:
                    component = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        component.append(w)
                        if w == v:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
    return found


def test_no_import_circles():
    """No two modules import each other, directly or through others (issue 21): a circle makes the import order
    matter and hides which module owns what."""
    assert circles(module_graph()) == []


def test_the_circle_check_sees_a_circle():
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert circles({"a": {"b"}, "b": set()}) == []


def crosses_privately(source: str, target: str, names: tuple[str, ...]) -> bool:
    """``source`` imports a private module (``rodimpact.direct._kernels``) or a private name (``_resolve_dt``) of
    another layer. The private helper modules at the top of the package (``rodimpact._validate``, ...) serve
    every layer and are not counted."""
    parts = target.split(".")
    if parts[0] != "rodimpact" or len(parts) < 2 or parts[1].startswith("_") or layer(source) == layer(target):
        return False
    return (any(p.startswith("_") for p in parts[2:])
            or any(n.startswith("_") and not n.startswith("__") for n in names))


def test_nothing_private_is_imported_across_layers():
    """Private kernels, set-up functions and helpers stay inside their package (issue 21): what another layer
    needs is public (``rodimpact.direct.boundary``, ``Problem.compile``, ``inverse.transform.window_count``)."""
    wrong = []
    for path in sorted(PACKAGE.rglob("*.py")):
        source = module_name(path)
        for target, names, line in static_imports(path):
            if crosses_privately(source, target, names):
                wrong.append(f"{path.relative_to(PACKAGE.parent)}:{line} imports {target} {names}")
    assert not wrong, "private imports across layers:\n" + "\n".join(wrong)


def test_the_private_import_check_sees_one():
    assert crosses_privately("rodimpact.design._adjoint_kernels", "rodimpact.direct._kernels", ("end_solve",))
    assert crosses_privately("rodimpact.design.design", "rodimpact.inverse.transform", ("_resolve_dt",))
    assert not crosses_privately("rodimpact.direct.batch", "rodimpact.direct._kernels", ("run_numba",))
    assert not crosses_privately("rodimpact.design.result", "rodimpact._result_files", ("write_new_file",))
