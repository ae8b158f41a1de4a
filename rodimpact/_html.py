"""A compact HTML table of key numbers for notebooks (``_repr_html_`` of the result objects)."""

from __future__ import annotations

from html import escape
from typing import Sequence


def key_table(title: str, rows: Sequence[tuple[str, str]]) -> str:
    """An HTML table with a caption ``title`` and one ``(name, value)`` row per entry (text is escaped)."""
    body = "".join(f"<tr><th style=\"text-align:left\">{escape(k)}</th><td style=\"text-align:left\">{escape(v)}</td>"
                   f"</tr>" for k, v in rows)
    return f"<table><caption style=\"text-align:left\"><b>{escape(title)}</b></caption>{body}</table>"
