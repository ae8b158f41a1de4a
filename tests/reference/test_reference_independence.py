"""rodimpact.reference must not use the code it checks (rodimpact.lattice, rodimpact.direct)."""

import ast
from pathlib import Path

import rodimpact.reference

FORBIDDEN = ("rodimpact.lattice", "rodimpact.direct", "rodimpact.rods", "rodimpact.inverse")


def test_reference_modules_import_no_solver_code():
    root = Path(rodimpact.reference.__file__).parent
    files = sorted(root.glob("*.py"))
    assert len(files) >= 6
    for path in files:
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                assert node.level == 0 or node.module is None or not node.module.startswith(("lattice", "direct")), path
                names = [node.module or ""]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                continue
            for name in names:
                assert not name.startswith(FORBIDDEN), f"{path.name} imports {name}"
