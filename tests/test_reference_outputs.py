"""Behaviour preserved, bit for bit: every shipped example, template and test model file gives the results stored
in tests/data/reference-outputs.json (digests of the arrays the compiled loop writes; see
scripts/reference_outputs.py, which also rewrites the store for an intended change of results)."""

import importlib.util
import json
import warnings
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
_spec = importlib.util.spec_from_file_location("reference_outputs", ROOT / "scripts" / "reference_outputs.py")
ref = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(ref)
STORED = json.loads(ref.STORE.read_text(encoding="utf-8"))
CASES = dict(ref.cases())


def test_every_case_has_a_stored_reference_and_every_reference_a_case():
    assert set(CASES) == set(STORED)


@pytest.mark.parametrize("name", sorted(CASES))
def test_results_are_bit_for_bit_those_stored(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        now = CASES[name]()
    assert now == STORED[name]


def test_the_digest_sees_a_change_in_the_last_bit():
    a = np.linspace(-1.0, 1.0, 7)
    b = a.copy()
    b[3] = np.nextafter(b[3], 1.0)
    assert ref.digest(a) != ref.digest(b) and ref.digest(a) == ref.digest(a.copy())
    assert ref.digest(a.reshape(7, 1)) != ref.digest(a)          # the shape counts too
