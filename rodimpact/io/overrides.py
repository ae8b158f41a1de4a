"""Overrides: set keys of a model or spec file from outside (``rodimpact ... --set KEY=VALUE``, ``--grid``).

A key is a path into the file as the error messages write it: table keys joined by dots, array entries by index
(``rods[1].segments[0].diameter``, ``simulation.dt``) or, in arrays of tables whose entries have a ``name``, by
that name (``rods.piston.velocity``, ``probes.SG1.position``; quote names that are not bare TOML keys:
``rods."bar 2".velocity``). Missing tables are created (``output.record_every`` without an ``[output]`` table).

Keys that exclude each other (:data:`REPLACES`: ``simulation.duration`` and ``steps``, a rod's ``dt`` and
``element_length``, ...): setting one removes the others the file gives, so that ``--set simulation.duration=2ms``
runs a file that gives ``steps`` for 2 ms; the override is then listed as ``simulation.duration = "2 ms"
(replacing the file's simulation.steps = 4000)``. Keys set by two overrides are both kept (the validation then
says they exclude each other).

Values are TOML values (``5``, ``1.5e-6``, ``true``, ``"50 mm"``, ``[1, 2]``, ``{ type = "spring", ... }``); text
that is not a TOML value is taken as a string, so that ``5 m/s`` and ``steel`` need no quotes.

:func:`apply_overrides` works on the parsed file (a dict) before it is validated, so a wrong key or value is
reported by the validation like one in the file, with the key path; :func:`naming_overrides` adds which override
set it.
"""

from __future__ import annotations

import copy
import re
import tomllib
from contextlib import contextmanager
from dataclasses import replace
from typing import Any, Callable, Iterator, Mapping, Optional, TypeVar, Union

from . import _toml
from .quantities import ModelError

_STEP = re.compile(r'(?:(?P<bare>[A-Za-z0-9_-]+)|"(?P<quoted>[^"\\]*)")(?P<index>(?:\[\d+\])*)')

Step = Union[str, int]
Spec = TypeVar("Spec")

#: Keys that exclude each other in one table: the table's place (its key path without array entries; ``ROD``: a
#: rod of a model file's ``[[rods]]`` or of a spec's ``[[struck]]``) -> key set -> the keys it replaces.
REPLACES: dict[tuple[str, ...], dict[str, tuple[str, ...]]] = {
    ("simulation",): {"duration": ("steps",), "steps": ("duration",)},
    ("input",): {"striker_velocity": ("incident_pulse",), "incident_pulse": ("striker_velocity",)},
    ("ROD",): {"segments": ("elements",), "elements": ("segments", "material")},
    ("ROD", "elements"): {"dt": ("element_length",), "element_length": ("dt",), "impedance": ("runs", "file"),
                          "runs": ("impedance", "file"), "file": ("impedance", "runs")},
    ("ROD", "elements", "runs"): {"count": ("length",), "length": ("count",),
                                  "impedance": ("impedance_start", "impedance_end"),
                                  "impedance_start": ("impedance",), "impedance_end": ("impedance",)},
    ("ROD", "segments"): {"file": ("x", "diameter", "area"), "x": ("file",), "diameter": ("area",),
                          "area": ("diameter",)},
    ("striker",): {"diameter_min": ("impedance_min", "impedance_max"),
                   "diameter_max": ("impedance_min", "impedance_max"),
                   "impedance_min": ("diameter_min", "diameter_max"),
                   "impedance_max": ("diameter_min", "diameter_max"),
                   "mass": ("mass_min", "mass_max"), "mass_min": ("mass",), "mass_max": ("mass",)},
}
_ROD_LISTS = ("rods", "struck")


def parse_value(text: str) -> Any:
    """``text`` as a TOML value, or as a string when it is not one (``5 m/s`` -> ``"5 m/s"``)."""
    try:
        doc = tomllib.loads(f"v = {text}")
    except tomllib.TOMLDecodeError:
        return text
    return doc["v"] if set(doc) == {"v"} else text


def parse_assignment(text: str, option: str = "--set") -> tuple[str, str]:
    """Split ``KEY=VALUE`` at the first ``=``; a ``ValueError`` naming ``option`` when there is none."""
    key, sep, value = text.partition("=")
    if not sep or not key.strip():
        raise ValueError(f"{option} {text!r}: expected KEY=VALUE, e.g. {option} rods[0].velocity=\"5 m/s\"")
    return key.strip(), value.strip()


def parse_key(key: str) -> list[Step]:
    """The steps of a key path: names (str) and array indices (int); a ``ModelError`` for malformed keys."""
    steps: list[Step] = []
    pos = 0
    while True:
        m = _STEP.match(key, pos)
        if m is None:
            raise ModelError(f"{key}: not a key path; write table keys joined by dots and array entries as [index] "
                             f"or by name, e.g. rods[0].velocity, rods.piston.velocity, simulation.dt")
        steps.append(m.group("bare") if m.group("bare") is not None else m.group("quoted"))
        steps.extend(int(i) for i in re.findall(r"\d+", m.group("index")))
        pos = m.end()
        if pos == len(key):
            return steps
        if key[pos] != "." or pos + 1 == len(key):
            raise ModelError(f"{key}: not a key path (unexpected {key[pos:]!r}); e.g. rods[0].velocity")
        pos += 1


def apply_overrides(raw: dict, overrides: Mapping[str, Any]) -> tuple[dict, dict[str, str]]:
    """A copy of the parsed file ``raw`` with every ``key -> value`` of ``overrides`` set, and the key paths that
    were set (written as error messages write them) -> ``"KEY = VALUE"`` as given."""
    out = copy.deepcopy(raw)
    applied: dict[str, str] = {}
    kept: list[tuple[dict, str]] = []          # (table, key) set by an override: never replaced by another
    for key, value in overrides.items():
        path, replaced = _set(out, key, value, kept)
        given = f"{key} = {_shown(value)}"
        if replaced:
            given += " (replacing the file's " + ", ".join(replaced) + ")"
        if path in applied:
            raise ModelError(f"{path}: set twice, by {applied[path]} and by {given}")
        applied[path] = given
    return out, applied


def _shown(value: Any) -> str:
    """A value as TOML text (as a file would give it), or as text where TOML cannot write it."""
    try:
        return _toml.value(value)
    except (TypeError, ValueError):
        return str(value)


def _set(raw: dict, key: str, value: Any, kept: list[tuple[dict, str]]) -> tuple[str, list[str]]:
    """Set ``key`` in ``raw`` to ``value``, removing the keys it replaces (:data:`REPLACES`) unless they are in
    ``kept``; returns the key path with array entries as indices, and the removed keys as ``PATH = VALUE``."""
    steps = parse_key(key)
    node: Any = raw
    path = ""
    names: list[str] = []                       # the table keys passed, without array entries
    replaced: list[str] = []
    for i, step in enumerate(steps):
        last = i == len(steps) - 1
        if isinstance(node, list):
            index = step if isinstance(step, int) else _named_entry(node, step, key, path)
            if index >= len(node):
                raise ModelError(f"{key}: {path} has {len(node)} entries ({path}[0] .. {path}[{len(node) - 1}])"
                                 if node else f"{key}: {path} is empty")
            path = f"{path}[{index}]"
            if last:
                node[index] = value
            node = node[index]
        elif isinstance(node, dict) and isinstance(step, str):
            if last or step not in node:
                replaced += _replace(node, step, names, path, kept)
            path = f"{path}.{_toml.key(step)}" if path else _toml.key(step)
            if last:
                node[step] = value
                kept.append((node, step))
            elif step not in node:
                node[step] = [] if isinstance(steps[i + 1], int) else {}
            node = node[step]
            names.append(step)
        else:
            what = "a table, not an array" if isinstance(node, dict) else f"{node!r}, not a table or an array"
            raise ModelError(f"{key}: {path or 'the file'} is {what}; {step!r} cannot be looked up in it")
    return path, replaced


def _replace(table: dict, key: str, names: list[str], path: str, kept: list[tuple[dict, str]]) -> list[str]:
    """Remove from ``table`` (at ``path``, reached through the table keys ``names``) the keys that ``key``
    replaces and that no override set; returns them as ``PATH = VALUE``."""
    place = tuple("ROD" if j == 0 and n in _ROD_LISTS else n for j, n in enumerate(names))
    removed = []
    for other in REPLACES.get(place, {}).get(key, ()):
        if other in table and not any(t is table and k == other for t, k in kept):
            shown = _shown(table.pop(other))
            removed.append(f"{path}.{_toml.key(other)} = " + (shown if len(shown) <= 60 else shown[:57] + "..."))
    return removed


def _named_entry(entries: list, name: str, key: str, path: str) -> int:
    """The index of the entry of an array of tables whose ``name`` is ``name``."""
    for index, entry in enumerate(entries):
        if isinstance(entry, dict) and entry.get("name") == name:
            return index
    names = [str(e["name"]) for e in entries if isinstance(e, dict) and "name" in e]
    known = f"names: {', '.join(names)}; " if names else ""
    raise ModelError(f"{key}: {path} has no entry named {name!r} ({known}or give an index, e.g. {path}[0])")


@contextmanager
def naming_overrides(applied: Mapping[str, str]) -> Iterator[None]:
    """Re-raise a :class:`ModelError` about a key that an override set with the override named at its end."""
    try:
        yield
    except ModelError as exc:
        text = str(exc)
        for path, given in applied.items():
            if re.match(re.escape(path) + r"(?=[.:\[ ]|$)", text):
                raise ModelError(f"{text} (set by the override {given})") from None
        raise


def spec_with_overrides(raw: dict, overrides: Optional[Mapping[str, Any]], name: str, text: str,
                        build: Callable[[dict, str], Spec]) -> Spec:
    """``build(raw, text)`` for the parsed spec file ``name`` with ``overrides`` applied (errors name the override
    that set a bad key); the result's ``text`` (the spec as it ran, written as ``spec.toml``) is then the
    overridden file as TOML, whose first line names the overrides (the file's comments are not kept)."""
    raw, applied = apply_overrides(raw, overrides or {})
    with naming_overrides(applied):
        spec = build(raw, text)
    if not applied:
        return spec
    head = f"# {name} with the overrides " + "; ".join(applied.values()) + " (comments not kept)\n"
    return replace(spec, text=head + _toml.dumps(raw))
