"""Property-based fuzzing of model files and of the synthesis, design and Kolsky-bar specs (issue 13).

The shipped templates and examples are parsed, mutated by hypothesis (values replaced by other types, numbers
at and beyond the float range, unit strings of the wrong dimension or with powers and towers, long strings,
deep nesting, keys deleted or added, file references to devices, FIFOs, folders, binary and foreign files,
broken TOML text) and loaded again. Every case must

* load, or fail with the package's own errors: a ``ValueError``/``TypeError`` (subclass) -- never another
  exception (``OverflowError``, ``RecursionError``, ``KeyError``, ``ZeroDivisionError``, ...);
* fail with a message that starts with a key path of the file (``rods[1].segments[0].diameter: ...``) or the
  file's name for errors of the TOML text itself;
* finish within a bounded time (an alarm after :data:`CASE_SECONDS` s, generous: a hang takes forever; a hang
  inside C code, such as an exact integer power, ends the process after three times that with the tracebacks of
  all threads, via :func:`faulthandler.dump_traceback_later`) and bounded memory: the package's memory checks
  are told the machine has :data:`MACHINE_BYTES` (1 GiB), and the resident memory of the process, sampled every
  few milliseconds, must not grow by that much in any case (reading /dev/zero, a table of 10^9 elements or a
  12 GB snapshot buffer would).

Loaded models also go through the command line's pre-run check (:func:`rodimpact.io.preflight.check_run`).

2,000 cases run in the suite. A longer run (the issue asks for 20,000)::

    RODIMPACT_FUZZ_CASES=20000 python -m pytest tests/robustness/test_fuzz_inputs.py -q
"""

from __future__ import annotations

import copy
import faulthandler
import math
import os
import re
import signal
import sys
import threading
import time
import tomllib
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rodimpact.direct import guards
from rodimpact.io import preflight
from rodimpact.io import _toml
from rodimpact.io.model import loads_model
from rodimpact.io.schema import MODEL
from rodimpact.io.design_spec import DESIGN_SPEC, TEMPLATE as DESIGN_TEMPLATE, loads_spec as loads_design_spec
from rodimpact.io.shpb_spec import SHPB_SPEC, TEMPLATE as SHPB_TEMPLATE, loads_spec as loads_shpb_spec
from rodimpact.io.synthesis_spec import SPEC, TEMPLATE as SPEC_TEMPLATE, loads_spec
from rodimpact.io.templates import TEMPLATES

from robust_inputs import ROOT

CASES = int(os.environ.get("RODIMPACT_FUZZ_CASES", "2000"))
CASE_SECONDS = 20
MACHINE_BYTES = 1024.0 * 2**20

EXAMPLES = sorted((ROOT / "rodimpact" / "examples").glob("*.toml"))
SEEDS: list[tuple[str, str]] = ([("model", TEMPLATES["simulate"][0])] + [("model", p.read_text()) for p in EXAMPLES]
                                + [("spec", SPEC_TEMPLATE), ("design", DESIGN_TEMPLATE), ("shpb", SHPB_TEMPLATE)])
DOCS = [(kind, tomllib.loads(text)) for kind, text in SEEDS]
TOP_KEYS = {"model": {f.name for f in MODEL.fields}, "spec": {f.name for f in SPEC.fields},
            "design": {f.name for f in DESIGN_SPEC.fields}, "shpb": {f.name for f in SHPB_SPEC.fields}}

# a message names a key path: name, name[i], name.sub, name[*] ... then ": " (or " (column ...)" for a file)
KEY_PATH = re.compile(r'^([A-Za-z_][\w\-]*|"[^"]*")((\[(\d+|\*)\])|(\.("[^"]*"|[^.\[\]:\s"]+)))*(: | \()')

UNITS = ["m", "mm", "um", "km", "s", "ms", "us", "kg", "N", "kN", "MN", "Pa", "GPa", "m/s", "kN s/m", "N*s/m",
         "kg/m^3", "m^2", "mm^2", "1/m", "1/ms", "N/m", "MN/m", "N/kg", "J", "K", "degC", "V", "furlong",
         "m**2", "m^-1", "(m/s)^2", "m**2**3", "m^99", "", "%", "dimensionless", "bogus_unit"]
NUMBERS = ["0", "-0", "1", "-1", "0.5", "1e-3", "5e-324", "2.2e-308", "1e308", "1.797e308", "1e400", "-1e400",
           "10**400", "10**10**10", "2^1024", "nan", "inf", "-inf", "1_000", "0x10", "1e", ".", "+-1", "(1)",
           "9" * 400, "3 * 4", "1/0", "0/0"]
SPECIAL_FILES = ["/dev/zero", "/dev/urandom", "/dev/null", "/etc/passwd", ".", "..", "missing.csv", "FIFO",
                 "binary.bin", "garbage.csv", "big.csv", "good.csv", "units.csv", "", "a" * 5000, "\x00"]


def _toml_value(v: Any) -> str:
    """An inline TOML value (written here, independently of the package's writer; inf and nan allowed)."""
    if isinstance(v, _Deep):
        return v.text()
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "nan" if math.isnan(v) else ("inf" if v > 0 else "-inf") if math.isinf(v) else repr(v)
    if isinstance(v, str):
        return _toml.string(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_toml.key(str(k))} = {_toml_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return _toml.string(str(v))        # dates and times of the seeds: as strings


def to_toml(doc: dict) -> str:
    return "\n".join(f"{_toml.key(str(k))} = {_toml_value(v)}" for k, v in doc.items()) + "\n"


def _paths(node: Any, prefix: tuple = ()) -> list[tuple]:
    """Every path (tuple of keys/indices) into ``node``, containers and leaves, including the root ``()``."""
    out = [prefix]
    if isinstance(node, dict):
        for k, v in node.items():
            out += _paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            out += _paths(v, prefix + (i,))
    return out


def _get(doc: Any, path: tuple) -> Any:
    for k in path:
        doc = doc[k]
    return doc


class _Deep:
    """Arrays or inline tables nested ``depth`` deep, written as text (the nested value itself could overflow the
    stack of a recursive writer)."""

    def __init__(self, depth: int, kind: str) -> None:
        self.depth, self.kind = depth, kind

    def text(self) -> str:
        if self.kind == "list":
            return "[" * self.depth + "1" + "]" * self.depth
        return "{ a = " * self.depth + "1" + " }" * self.depth


scalars = st.one_of(
    st.integers(min_value=-(2**70), max_value=2**70), st.integers(min_value=0, max_value=10**50),
    st.floats(allow_nan=True, allow_infinity=True), st.booleans(), st.text(max_size=30),
    st.sampled_from(NUMBERS),
    st.builds(lambda n, u: f"{n} {u}".strip(), st.sampled_from(NUMBERS), st.sampled_from(UNITS)),
    st.builds(lambda n, u: f"{n} {u}", st.floats(allow_nan=False, allow_infinity=False), st.sampled_from(UNITS)),
    st.sampled_from(SPECIAL_FILES), st.sampled_from(["cylinder", "table", "expression", "force", "free", "file",
                                                     "samples", "windows", "bonded", "contact", "bearings"]),
    st.builds(lambda n: "m" * n, st.sampled_from([201, 5000, 100_000])),
    st.sampled_from(["sin(t)", "1/0", "x**x**x**x", "__import__('os')", "t if t else", "exp(1e5*t)",
                     "-50e3*sin(pi*t/0.2e-3)*(t < 0.2e-3)", "0.001*(1+s/L)", "A0", "[]", "lambda: 0"]),
)
values = st.recursive(scalars, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.sampled_from(
        ["shape", "type", "file", "expression", "time", "value", "length", "diameter", "x", "area", "impedance",
         "count", "runs", "force", "velocity", "name", "rod", "position", "values", "peak", "bogus"]), inner,
        max_size=4)), max_leaves=12)

HOSTILE = ["10**10**10 m", "10**400 m", "2^1024 mm", "1e400 m", "-1e400 N", "m**2**3", "(10 m)**12", "1 m^99",
           "1 m^-13", "((m**2)**2)**2", "m" * 201, "1 " + "m*" * 99 + "m", "9" * 199 + " m", "1e308 km",
           "5e-324 m", "0x1p10 m", "1 m / 0", "nan m", "inf s", "1 m m m", "1 (", "__import__('os') m", "\x00 m",
           "1_0 m", "1e-320 1/m"]
MUTATIONS = ["replace", "replace", "replace", "delete", "add_key", "deep", "scale_number", "swap_unit", "duplicate",
             "file", "hostile", "hostile"]


@st.composite
def cases(draw) -> tuple[str, str]:
    kind, seed = DOCS[draw(st.integers(0, len(DOCS) - 1))]
    doc = copy.deepcopy(seed)
    for _ in range(draw(st.integers(1, 3))):
        paths = _paths(doc)
        path = paths[draw(st.integers(0, len(paths) - 1))]
        parent, key = (_get(doc, path[:-1]), path[-1]) if path else (None, None)
        how = draw(st.sampled_from(MUTATIONS))
        if parent is None:                                  # the root: add a key
            how = "add_key"
        target = doc if parent is None else parent[key]
        if how == "replace":
            parent[key] = draw(values)
        elif how == "delete":
            del parent[key]
        elif how == "add_key" and isinstance(target, dict):
            target[draw(st.sampled_from(["bogus", "shape", "type", "file", "dt", "elements", "initial",
                                         "parameters", "x" * 300]))] = draw(values)
        elif how == "deep":
            parent[key] = _Deep(draw(st.sampled_from([5, 33, 60, 200, 900])), draw(st.sampled_from(["list", "dict"])))
        elif how == "scale_number" and isinstance(target, (int, float)) and not isinstance(target, bool):
            parent[key] = target * draw(st.sampled_from([0, -1, 1e-320, 1e300, 1e308, math.inf, math.nan]))
        elif how == "swap_unit" and isinstance(target, str) and " " in target:
            number, _, _ = target.partition(" ")
            parent[key] = f"{draw(st.sampled_from([number] + NUMBERS))} {draw(st.sampled_from(UNITS))}"
        elif how == "duplicate" and isinstance(target, list) and target:
            parent[key] = target + target[:1] * draw(st.integers(1, 3))
        elif how == "hostile" and not isinstance(target, (dict, list)):
            parent[key] = draw(st.sampled_from(HOSTILE))
        elif how == "file" and isinstance(target, dict):
            target["file"] = draw(st.sampled_from(SPECIAL_FILES))
        elif how == "file":
            parent[key] = {"file": draw(st.sampled_from(SPECIAL_FILES))}
    text = to_toml(doc)
    cut = draw(st.sampled_from(["none"] * 12 + ["truncate", "garble"]))
    if cut == "truncate":
        text = text[:draw(st.integers(0, len(text)))]
    elif cut == "garble":
        i = draw(st.integers(0, len(text)))
        text = text[:i] + draw(st.sampled_from(["[", "]]", "{", "=", '"', "\\", "\x00", "\ufeff", "=\n=", "'''"])) \
            + text[i:]
    return kind, text


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> Path:
    """The folder the fuzzed files refer to: a FIFO, binary, garbage, oversized and good CSV files."""
    d = tmp_path_factory.mktemp("fuzz-files")
    if hasattr(os, "mkfifo"):
        os.mkfifo(d / "FIFO")
    (d / "binary.bin").write_bytes(bytes(range(256)) * 16)
    (d / "garbage.csv").write_text("x [furlong],diameter [kg]\n1,2,3\nabc,,\n")
    (d / "big.csv").write_text("time,force\n" + "0,0\n" * 400_000)          # above the 1 MiB limit set below
    (d / "good.csv").write_text("time [ms],force [kN]\n0,0\n0.1,-50\n0.2,0\n")
    (d / "units.csv").write_text("x [mm],area [mm^2]\n0,1000\n100,1200\n")
    return d


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


class PeakMemory(threading.Thread):
    """Samples the resident memory of this process every few milliseconds (psutil); :meth:`reset` starts a new
    case, :meth:`grown` is the largest growth over the memory at the reset seen since."""

    def __init__(self) -> None:
        super().__init__(daemon=True)
        import psutil

        self.process = psutil.Process()
        self.base = self.peak = float(self.process.memory_info().rss)
        self.stopped = False
        self.start()

    def run(self) -> None:
        while not self.stopped:
            self.peak = max(self.peak, float(self.process.memory_info().rss))
            time.sleep(0.003)

    def reset(self) -> None:
        self.base = self.peak = float(self.process.memory_info().rss)

    def grown(self) -> float:
        self.peak = max(self.peak, float(self.process.memory_info().rss))
        return self.peak - self.base


WATCH: list[PeakMemory] = []


@pytest.fixture(scope="module", autouse=True)
def _stop_watch():
    yield
    while WATCH:
        WATCH.pop().stopped = True


@settings(max_examples=CASES, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.large_base_example,
                                 HealthCheck.function_scoped_fixture])
@given(case=cases())
def test_mutated_templates_and_examples_give_named_errors_or_load(case, files, monkeypatch):
    kind, text = case
    monkeypatch.setenv("RODIMPACT_MAX_INPUT_MB", "1")
    timer = hasattr(signal, "SIGALRM")
    if timer:
        previous = signal.signal(signal.SIGALRM, _alarm)
        signal.alarm(CASE_SECONDS)
    # the machine "has" MACHINE_BYTES: every allocation the package allows must fit in it
    monkeypatch.setattr("rodimpact._validate.physical_memory", lambda: MACHINE_BYTES)
    monkeypatch.setattr(guards, "available_memory", lambda: MACHINE_BYTES)
    if not WATCH:
        WATCH.append(PeakMemory())
    WATCH[0].reset()
    faulthandler.dump_traceback_later(3 * CASE_SECONDS, exit=True)
    error: BaseException | None = None
    try:
        if kind == "model":
            model = loads_model(text, base_dir=files, name="model")
            preflight.check_run(model, files / "out", model.output.plots)
        elif kind == "design":
            loads_design_spec(text, files, name="design")
        elif kind == "shpb":
            loads_shpb_spec(text, files, name="shpb")
        else:
            loads_spec(text, files, name="spec")
    except _Timeout:
        pytest.fail(f"no answer within {CASE_SECONDS} s for:\n{text[:3000]}")
    except (ValueError, TypeError) as exc:
        error = exc
    finally:
        faulthandler.cancel_dump_traceback_later()
        if timer:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)
    grown = WATCH[0].grown()
    assert grown < MACHINE_BYTES, f"the memory grew by {grown / 2**20:.0f} MiB with:\n{text[:3000]}"
    if error is not None:
        msg = str(error)
        m = KEY_PATH.match(msg)
        assert m, f"no key path in {msg!r} for:\n{text[:3000]}"
        try:                                        # the keys the file has (unknown ones are named too)
            present = {_toml.key(k if len(k) <= 60 else k[:57] + "...") for k in tomllib.loads(text)}
        except Exception:                           # not TOML: the message must name the file
            present = set()
        first = m.group(1)
        assert first in TOP_KEYS[kind] | present | {kind, "RODIMPACT_MAX_INPUT_MB"}, msg
        assert len(msg) < 2000, msg
