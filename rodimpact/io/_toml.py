"""A small TOML writer for model files (reading uses the standard library's :mod:`tomllib`).

Writes the subset model files use: strings, integers, floats (shortest round-trip ``repr``, so that reading
back gives the identical float), booleans, arrays, inline tables, tables and arrays of tables. A value
wrapped in :class:`Commented` gets an end-of-line comment (used for units: ``diameter = 0.04  # m``).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


@dataclass(frozen=True)
class Commented:
    """A value followed by an end-of-line comment."""

    value: Any
    comment: str


def key(name: str) -> str:
    """A TOML key: bare when possible, else a quoted basic string."""
    return name if _BARE_KEY.match(name) else string(name)


def string(text: str) -> str:
    """A TOML basic string with the required escapes."""
    out = []
    for ch in text:
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\r":
            out.append("\\r")
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def value(v: Any) -> str:
    """An inline TOML value."""
    if isinstance(v, Commented):
        raise TypeError("Commented values are only allowed directly in a table")
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"cannot write the non-finite number {v!r} to a model file")
        text = repr(v)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return string(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{key(k)} = {value(x)}" for k, x in v.items()) + " }" if v else "{}"
    if isinstance(v, (list, tuple)):
        return _array(list(v))
    raise TypeError(f"cannot write a {type(v).__name__} to TOML")


def _array(items: list) -> str:
    parts = [value(x) for x in items]
    one_line = "[" + ", ".join(parts) + "]"
    if len(one_line) <= 100 and not any("\n" in p for p in parts):
        return one_line
    if items and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in items):
        lines, line = [], []
        for p in parts:
            if line and len(", ".join(line + [p])) > 96:
                lines.append(", ".join(line) + ",")
                line = []
            line.append(p)
        lines.append(", ".join(line) + ",")
        return "[\n" + "\n".join("    " + ln for ln in lines) + "\n]"
    return "[\n" + "".join(f"    {p},\n" for p in parts) + "]"


def _is_table(v: Any) -> bool:
    return isinstance(v, dict) and not getattr(v, "inline", False)


def _is_table_array(v: Any) -> bool:
    return isinstance(v, list) and bool(v) and all(_is_table(x) for x in v)


class Inline(dict):
    """A dict that is always written as an inline table."""

    inline = True


def dumps(doc: dict, header_comments: dict[str, str] | None = None) -> str:
    """Serialise ``doc``; nested dicts become ``[tables]``, lists of dicts ``[[arrays of tables]]``.

    ``header_comments`` maps a table path (``"rods"``, ``"simulation"``) to a comment written above its first
    header.
    """
    lines: list[str] = []
    _emit(doc, [], lines, header_comments or {}, array_item=False)
    return "\n".join(lines).strip() + "\n"


def _emit(table: dict, path: list[str], lines: list[str], comments: dict[str, str], array_item: bool) -> None:
    simple = [(k, v) for k, v in table.items() if not (_is_table(_raw(v)) or _is_table_array(_raw(v)))]
    nested = [(k, _raw(v)) for k, v in table.items() if _is_table(_raw(v)) or _is_table_array(_raw(v))]
    if path:
        dotted = ".".join(key(p) for p in path)
        if simple or array_item or not nested:
            note = comments.get(".".join(path))
            if lines:
                lines.append("")
            if note and not array_item:
                lines.extend(f"# {ln}".rstrip() for ln in note.splitlines())
            lines.append(f"[[{dotted}]]" if array_item else f"[{dotted}]")
    for k, v in simple:
        if isinstance(v, Commented):
            lines.append(f"{key(k)} = {value(v.value)}  # {v.comment}")
        else:
            lines.append(f"{key(k)} = {value(v)}")
    for k, v in nested:
        sub = path + [k]
        if isinstance(v, dict):
            _emit(v, sub, lines, comments, array_item=False)
        else:
            note = comments.get(".".join(sub))
            if note:
                lines.append("")
                lines.extend(f"# {ln}".rstrip() for ln in note.splitlines())
            for item in v:
                _emit(item, sub, lines, comments, array_item=True)


def _raw(v: Any) -> Any:
    return v.value if isinstance(v, Commented) else v
