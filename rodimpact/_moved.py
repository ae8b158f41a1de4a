"""Keywords that a public function no longer takes because their value now lives in an object it receives, and
methods that are gone (:class:`removed_method`).

A call that still gives one gets a ``TypeError`` that says where the value went (``right: give the ends in the
System: ri.System(rods, velocities, right=...)``), not Python's bare "unexpected keyword argument"; so does a
call that gives by position an argument that is now keyword-only. The wrapped function keeps its own signature
(``inspect.signature`` follows ``__wrapped__``), so the catch adds no parameter.
"""

from __future__ import annotations

import functools
import inspect
from typing import Any, Callable, Mapping, Optional, Sequence, TypeVar

F = TypeVar("F", bound=Callable[..., Any])


def moved(where: Mapping[str, str], positional: Sequence[str] = ()) -> Callable[[F], F]:
    """Decorate a function so that the keywords of ``where`` (name -> message saying where the value went) raise
    a ``TypeError`` with that message. ``positional``: the old positional parameters in order; an argument given
    by position beyond those the function still takes positionally is reported by its old name (with its
    message in ``where``, or "give it by name")."""

    def wrap(fn: F) -> F:
        params = inspect.signature(fn).parameters.values()
        n_pos = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in params)
        assert not set(where) & {p.name for p in params}, "a moved keyword is still a parameter"
        removed = frozenset(where)

        @functools.wraps(fn)
        def call(*args: Any, **kwargs: Any) -> Any:
            if len(args) > n_pos:
                name = positional[n_pos] if len(positional) > n_pos else None
                if name is not None:
                    hint = where.get(name, f"{name}: give it by name ({name}=...)")
                    raise TypeError(f"{fn.__name__}() takes at most {n_pos} positional arguments, got {len(args)}; "
                                    f"{hint}")
            if removed.intersection(kwargs):
                name = next(k for k in kwargs if k in removed)
                raise TypeError(where[name])
            return fn(*args, **kwargs)

        call.moved_keywords = dict(where)      # type: ignore[attr-defined]
        return call  # type: ignore[return-value]

    return wrap


class removed_method:
    """A method that is gone: looking it up on the class or an instance raises an ``AttributeError`` that says
    what replaces it (``SynthesisResult.save: removed; ...``), not Python's bare "has no attribute"; ``hasattr``
    is False, as for any missing attribute."""

    def __init__(self, instead: str) -> None:
        self.instead = instead
        self.name = ""

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = f"{owner.__name__}.{name}"

    def __get__(self, obj: Any, owner: Optional[type] = None) -> Any:
        raise AttributeError(f"{self.name}: removed; {self.instead}")
