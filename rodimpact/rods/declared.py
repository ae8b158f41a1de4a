"""Field declarations of the physical element classes: one home for each parameter's name, physical dimension,
SI unit, bound, default and one-line doc.

An element class (an end condition, a junction, a nodal load, a segment shape) is a frozen dataclass whose
fields are made with :func:`quantity`, :func:`history`, :func:`choice`, :func:`flag`, :func:`rod` or
:func:`spans`, and which is registered under a family and a type name with :func:`element`::

    @element("junction", "spring-dashpot")
    @dataclass(frozen=True)
    class SpringDashpotJoint(Junction):
        stiffness: float = quantity("stiffness", "Spring stiffness k.", bound="non_negative")

:func:`check` (called by the class's ``__post_init__``) validates every declared quantity with a message that
names ``Class.field`` and the valid range; the model-file schema (:mod:`rodimpact.io.schema`), the reader and
the writer (:mod:`rodimpact.io.model`), the reference page and the fuzz test's list of valid keys are generated
from :data:`ELEMENTS` and :func:`declarations`, so a new element kind is one class (docs/architecture.md,
"Adding an element kind").

Why stdlib dataclass metadata and not pydantic models: the element classes are small frozen dataclasses built
in the hot set-up of batched runs, their validation messages carry the project's ``Class.field: must be ... ,
got ...`` form that the model-file reader turns into key paths, and the file side (unit strings, key paths,
did-you-mean, expressions) is already ours. The metadata is read by :func:`dataclasses.fields`, so the
declaration stays a plain dataclass field (docs/architecture.md, "One schema").
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, Callable, Iterator, Optional, TypeVar

import numpy as np

from .._quantities import DIMENSIONS
from .._validate import finite, non_negative, positive
from .history import as_history

#: ``bound`` values of :func:`quantity`: the check applied and its text in messages and the reference
BOUNDS: dict[Optional[str], Callable[[str, Any, str], float]] = {
    "positive": positive, "non_negative": non_negative, None: finite}

_KEY = "rodimpact"
REQUIRED: Any = dataclasses.MISSING


@dataclass(frozen=True)
class Declaration:
    """What a field declares.

    ``kind``: ``quantity`` (a float in SI), ``quantities`` (a list of them), ``history`` (a time history of ``dimension``), ``choice`` (one of
    ``choices``), ``flag`` (true/false), ``text`` (a name), ``rod`` (a rod index or name), ``spans``
    (pairs of lengths), ``path`` (a file name) or ``part`` (an element of the registered ``family``, e.g. a
    specimen's law). ``dimension`` names an entry of :data:`rodimpact._quantities.DIMENSIONS` (``length``,
    ``stiffness``, ...), which gives its SI unit. ``bound``: ``positive``, ``non_negative`` or ``None`` (any
    finite value).
    """

    kind: str
    doc: str
    dimension: Optional[str] = None
    bound: Optional[str] = None
    choices: tuple[str, ...] = ()
    family: Optional[str] = None

    @property
    def unit(self) -> str:
        """The SI unit of the dimension as written in messages (empty for a pure number)."""
        si = DIMENSIONS[self.dimension].si if self.dimension else ""
        return "" if si == "-" else si


def _field(declaration: Declaration, default: Any) -> Any:
    return dataclasses.field(default=default, metadata={_KEY: declaration})


def _dimension(dimension: str) -> str:
    if dimension not in DIMENSIONS:
        raise ValueError(f"dimension: must be one of {sorted(DIMENSIONS)}, got {dimension!r}")
    return dimension


def quantity(dimension: str, doc: str, *, bound: Optional[str] = "positive", default: Any = REQUIRED) -> Any:
    """A physical quantity in the SI unit of ``dimension``, checked against ``bound``; ``default=None`` makes it
    optional (the class says what ``None`` means)."""
    if bound not in BOUNDS:
        raise ValueError(f"bound: must be one of {sorted(b for b in BOUNDS if b)} or None, got {bound!r}")
    return _field(Declaration("quantity", doc, _dimension(dimension), bound), default)


def history(dimension: str, doc: str) -> Any:
    """A required time history (a number, a callable f(t) or samples; :class:`~rodimpact.rods.history.History`)."""
    return _field(Declaration("history", doc, _dimension(dimension)), REQUIRED)


def choice(doc: str, choices: tuple[str, ...], default: str) -> Any:
    """One of the strings ``choices``."""
    return _field(Declaration("choice", doc, choices=choices), default)


def flag(doc: str, default: bool) -> Any:
    """A true/false switch."""
    return _field(Declaration("flag", doc), default)


def rod(doc: str) -> Any:
    """The index of a rod of the system (0 = first); model files write its name or index."""
    return _field(Declaration("rod", doc), REQUIRED)


def quantities(dimension: str, doc: str, default: Any = REQUIRED) -> Any:
    """A list of finite quantities in the SI unit of ``dimension`` (the class checks their bounds)."""
    return _field(Declaration("quantities", doc, _dimension(dimension)), default)


def spans(doc: str) -> Any:
    """A list of (start, end) positions in m along a rod."""
    return _field(Declaration("spans", doc, "length"), REQUIRED)


def text(doc: str) -> Any:
    """A required non-empty string (a name)."""
    return _field(Declaration("text", doc), REQUIRED)


def path(doc: str) -> Any:
    """An optional file name (model files read it relative to the model file's folder). Left out (``None``), the
    element holds the same data as arrays given in Python, which a model file cannot hold: writing such an
    element to a model file is refused."""
    return _field(Declaration("path", doc), None)


def part(family: str, doc: str) -> Any:
    """A required element of the registered ``family`` (a nested table with its ``type`` in model files)."""
    return _field(Declaration("part", doc, family=family), REQUIRED)


def parts(family: str, doc: str) -> Any:
    """A required non-empty list of elements of the registered ``family`` (an array of inline tables, each with
    its ``type``, in model files); :func:`check` makes it a tuple."""
    return _field(Declaration("parts", doc, family=family), REQUIRED)


def declarations(cls: type) -> Iterator[tuple[dataclasses.Field, Declaration]]:
    """The declared fields of an element class, in declaration order (fields without a declaration, such as the
    ``material`` of a segment, are skipped)."""
    for f in dataclasses.fields(cls):
        if _KEY in f.metadata:
            yield f, f.metadata[_KEY]


def has_default(f: dataclasses.Field) -> bool:
    """True if the field may be left out."""
    return f.default is not dataclasses.MISSING


def check(obj: Any) -> None:
    """Validate and normalise the declared quantities of ``obj`` in place (a frozen dataclass): each becomes a
    float after the check of its bound, each history a :class:`~rodimpact.rods.history.History` (sampled with the
    object's ``interpolation``, if it has one); messages name ``Class.field``. ``None`` passes where it is the
    default."""
    owner = type(obj).__name__
    for f, d in declarations(type(obj)):
        value = getattr(obj, f.name)
        if d.kind == "quantity":
            if value is None and f.default is None:
                continue
            object.__setattr__(obj, f.name, BOUNDS[d.bound](f"{owner}.{f.name}", value, d.unit))
        elif d.kind == "history":
            object.__setattr__(obj, f.name, as_history(value, f"{owner}.{f.name}", getattr(obj, "interpolation",
                                                                                            "linear"), d.unit))
        elif d.kind == "choice" and value not in d.choices:
            raise ValueError(f"{owner}.{f.name}: must be one of {', '.join(map(repr, d.choices))}, got {value!r}")
        elif d.kind == "quantities":
            if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
                raise TypeError(f"{owner}.{f.name}: must be a list of numbers ({d.unit}), got {value!r}")
            object.__setattr__(obj, f.name, tuple(finite(f"{owner}.{f.name}[{i}]", x, d.unit)
                                                  for i, x in enumerate(value)))
        elif d.kind == "flag" and not isinstance(value, bool):
            raise TypeError(f"{owner}.{f.name}: must be True or False, got {value!r}")
        elif d.kind == "text" and (not isinstance(value, str) or not value):
            raise ValueError(f"{owner}.{f.name}: must be a non-empty string, got {value!r}")
        elif d.kind == "rod" and isinstance(value, str):
            if not value:
                raise ValueError(f"{owner}.{f.name}: a rod name must not be empty")
        elif d.kind == "rod" and (isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0):
            raise ValueError(f"{owner}.{f.name}: must be a rod index >= 0 or a rod name, got {value!r}")
        elif d.kind == "rod":
            object.__setattr__(obj, f.name, int(value))
        elif d.kind == "path" and value is not None and not isinstance(value, str):
            raise TypeError(f"{owner}.{f.name}: must be a file name (a string), got {type(value).__name__}")
        elif d.kind == "part" and type(value) not in ELEMENTS.get(d.family, {}).values():
            names = ", ".join(cls.__name__ for cls in ELEMENTS.get(d.family, {}).values())
            raise TypeError(f"{owner}.{f.name}: must be one of {names}, got {type(value).__name__}")
        elif d.kind == "parts":
            object.__setattr__(obj, f.name, _parts(f"{owner}.{f.name}", value, d.family))


def _parts(where: str, value: Any, family: str) -> tuple:
    """``value`` as a non-empty tuple of elements of ``family``, refused by name and index otherwise."""
    names = ", ".join(cls.__name__ for cls in ELEMENTS.get(family, {}).values())
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise TypeError(f"{where}: must be a list of {names}, got {type(value).__name__}")
    items = tuple(value)
    if not items:
        raise ValueError(f"{where}: must hold at least one of {names}, got an empty list")
    for i, item in enumerate(items):
        if type(item) not in ELEMENTS.get(family, {}).values():
            raise TypeError(f"{where}[{i}]: must be one of {names}, got {type(item).__name__}")
    return items


#: family ("end", "junction", "load", "segment") -> type name -> class, in registration order
ELEMENTS: dict[str, dict[str, type]] = {}

#: class -> (family, type name)
_NAMES: dict[type, tuple[str, str]] = {}

T = TypeVar("T", bound=type)


def element(family: str, name: str) -> Callable[[T], T]:
    """Register an element class under ``family`` and the type name that model files use."""
    def register(cls: T) -> T:
        kinds = ELEMENTS.setdefault(family, {})
        if name in kinds and kinds[name] is not cls:
            raise ValueError(f"{family} type {name!r} is already {kinds[name].__name__}")
        kinds[name] = cls
        _NAMES[cls] = (family, name)
        return cls
    return register


def type_name(obj: Any) -> str:
    """The registered type name of an element (its class's), e.g. ``"bit-rock"``."""
    try:
        return _NAMES[type(obj)][1]
    except KeyError:
        raise TypeError(f"{type(obj).__name__} is not a registered element class") from None


def summary(cls: type) -> str:
    """The first paragraph of the class docstring, on one line (the reference page's description)."""
    doc = (cls.__doc__ or "").strip().split("\n\n")[0]
    return " ".join(doc.split())
