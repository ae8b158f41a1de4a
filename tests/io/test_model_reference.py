"""docs/model-reference.md is generated from the schema and cannot drift: the page must equal the generated text,
its examples must load, every schema key must be documented, and the `init` template must run as it is."""

import re
import tomllib
from pathlib import Path

import pytest

from rodimpact.io import schema
from rodimpact.io.model import loads_model
from rodimpact.io.templates import template

ROOT = Path(__file__).parents[2]
BASE = """
[[rods]]
name = "bar"
[[rods.segments]]
shape = "cylinder"
length = "1.8 m"
diameter = "50 mm"
"""
SIM = '\n[simulation]\nduration = "1 ms"\n'


def test_reference_page_matches_the_schema():
    page = (ROOT / "docs" / "model-reference.md").read_text(encoding="utf-8")
    assert page == schema.reference_markdown(), \
        "docs/model-reference.md is stale: run  python -m rodimpact.io.schema docs/model-reference.md"


def _all_tables():
    yield schema.MODEL
    seen = set()
    stack = list(schema.MODEL.fields)
    while stack:
        f = stack.pop()
        tables = ([f.table] if f.table else []) + (list(f.variants.options.values()) if f.variants else [])
        for t in tables:
            if id(t) not in seen:
                seen.add(id(t))
                yield t
                stack.extend(t.fields)


def test_every_key_of_the_schema_is_on_the_page():
    page = schema.reference_markdown()
    for table in _all_tables():
        for f in table.fields:
            assert f"| `{f.name}` |" in page, (table.name, f.name)
    for name in list(schema.SEGMENT_SHAPES) + list(schema.END_TYPES) + list(schema.LOAD_TYPES):
        assert f'= "{name}"' in page


def _wrap(table_name: str, snippet: str) -> str:
    if table_name in schema.SEGMENT_SHAPES:
        return '[parameters]\nA0 = "1.26e-3 m^2"\nA1 = "1.96e-3 m^2"\n[[rods]]\n[[rods.segments]]\n' + snippet + SIM
    if table_name == "rods.elements":
        return "[[rods]]\n" + snippet + SIM
    if table_name == "rods":
        return snippet + SIM
    if table_name == "simulation":
        return BASE + "\n" + snippet + "\n"
    return (snippet + "\n" + BASE if table_name == "materials" else BASE + "\n" + snippet) + SIM


@pytest.mark.parametrize("table", [t for t in _all_tables() if t.example], ids=lambda t: t.name)
def test_reference_examples_load(table):
    model = loads_model(_wrap(table.name, table.example))
    assert model.system.n_rods >= 1


def test_toml_blocks_on_the_page_are_valid_toml():
    page = schema.reference_markdown()
    blocks = re.findall(r"```toml\n(.*?)```", page, flags=re.S)
    assert len(blocks) >= 8
    for b in blocks:
        tomllib.loads(b)


def test_simulate_template_runs_as_it_is_and_uses_every_top_level_table():
    text, default_name = template("simulate")
    assert default_name == "model.toml"
    model = loads_model(text)
    data = tomllib.loads(text)
    assert set(data) == {f.name for f in schema.MODEL.fields}
    result = model.simulate()
    assert result.contact_force.min() < 0
    # the template's lines are commented: every table header is preceded or followed by an explanation
    assert sum(1 for ln in text.splitlines() if ln.lstrip().startswith("#")) > 25


def test_user_guide_model_snippet_loads():
    page = (ROOT / "docs" / "user-guide.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```toml\n(.*?)```", page, flags=re.S)
    model = loads_model(blocks[0])
    assert [r.name for r in model.system.rods] == ["piston", "bar"]
    for b in blocks[1:]:
        tomllib.loads(b)
