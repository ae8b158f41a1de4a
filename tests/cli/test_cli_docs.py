"""``rodimpact docs`` (issue 14, item 11): the reference pages come from the installed package itself, also where
no docs/ folder exists (an installed wheel ships the package, not the repository's docs/)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from rodimpact import cli
from rodimpact.io import design_spec, synthesis_spec

ROOT = Path(__file__).resolve().parents[2]


def test_docs_model_prints_the_model_reference_from_a_package_without_docs(tmp_path):
    """A copy of the package alone (as pip installs it) prints the page that docs/model-reference.md holds."""
    site = tmp_path / "site"
    shutil.copytree(ROOT / "rodimpact", site / "rodimpact", ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(ROOT / "rodimpact_cli.py", site)
    env = {**os.environ, "PYTHONPATH": str(site)}
    check = "import rodimpact, sys; assert rodimpact.__file__.startswith(sys.argv[1]), rodimpact.__file__"
    subprocess.run([sys.executable, "-c", check, str(site)], cwd=tmp_path, env=env, check=True)
    p = subprocess.run([sys.executable, "-m", "rodimpact", "docs", "model"], cwd=tmp_path, env=env,
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    assert p.stdout == (ROOT / "docs" / "model-reference.md").read_text(encoding="utf-8")


def test_docs_lists_topics_and_prints_the_spec_references(capsys):
    assert cli.main(["docs"]) == 0
    listing = capsys.readouterr().out
    assert [line.split()[0] for line in listing.splitlines()[:3]] == ["model", "synthesis", "design"]
    assert cli.main(["docs", "synthesis"]) == 0
    assert capsys.readouterr().out == synthesis_spec.spec_reference_markdown()
    assert cli.main(["docs", "design"]) == 0
    assert capsys.readouterr().out == design_spec.spec_reference_markdown()
    assert cli.main(["docs", "modle"]) == 2
    assert "docs: no topic 'modle'; topics: model, synthesis, design" in capsys.readouterr().err


def test_help_points_to_the_docs_command():
    help_text = " ".join(cli.build_parser().format_help().split())
    assert "rodimpact docs model" in help_text and "docs/model-reference.md" not in help_text
