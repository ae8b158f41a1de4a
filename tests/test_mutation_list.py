"""The curated mutation list (scripts/mutations.toml, docs/mutation-testing.md) still applies to the code.

Every entry's ``old`` text must occur exactly ``count`` times in its file and its test paths must exist: a
refactor that changes a mutated line shows up here, in the ordinary suite, and the entry is updated in the
same change (the mutation check itself, which recompiles and runs tests per entry, is too slow for every run).
"""

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_spec = importlib.util.spec_from_file_location("mutation_check", ROOT / "scripts" / "mutation_check.py")
mutation_check = importlib.util.module_from_spec(_spec)
sys.modules["mutation_check"] = mutation_check          # dataclasses look their module up while being built
_spec.loader.exec_module(mutation_check)


def test_every_mutation_still_applies_and_names_existing_tests():
    mutations = mutation_check.load_mutations(ROOT / "scripts" / "mutations.toml")
    assert len(mutations) >= 34                      # the 25 of issue 15 and the laws listed there, at least
    for m in mutations:
        assert mutation_check.occurrences(ROOT, m) == m.count, f"{m.name}: stale, update scripts/mutations.toml"
        for t in m.tests:
            assert (ROOT / t.split("::")[0]).exists(), f"{m.name}: test path {t} does not exist"


def test_applying_a_mutation_replaces_exactly_the_old_text(tmp_path):
    m = mutation_check.Mutation("demo", "law.py", "h = 0.5 * dt", "h = dt", ("tests",), count=1)
    (tmp_path / "law.py").write_text("def f(dt):\n    h = 0.5 * dt\n    return h\n")
    assert mutation_check.occurrences(tmp_path, m) == 1
    mutation_check.apply(tmp_path, m)
    assert (tmp_path / "law.py").read_text() == "def f(dt):\n    h = dt\n    return h\n"
    assert mutation_check.occurrences(tmp_path, m) == 0


def test_a_test_module_that_cannot_be_imported_is_no_kill(tmp_path):
    """A subset that fails because a test module does not import (a name moved, a file missing) says nothing
    about the mutated law: the verdict is 'error', not 'killed' (a moved kernel name once made 25 entries look
    killed in 5 s each)."""
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_broken.py").write_text("from nowhere_at_all import law\n\ndef test_law():\n    pass\n")
    (tmp_path / "tests" / "test_fails.py").write_text("def test_law():\n    assert 1 + 1 == 3\n")
    status, why, _ = mutation_check.run_tests(tmp_path, ("tests/test_broken.py",), 120, sys.executable)
    assert (status, why) == ("error", "a test module failed to import (see log)")
    status, killer, _ = mutation_check.run_tests(tmp_path, ("tests/test_fails.py",), 120, sys.executable)
    assert (status, killer) == ("failed", "tests/test_fails.py::test_law")
