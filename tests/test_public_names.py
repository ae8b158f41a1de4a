"""One class per name (issue 21): no two public classes of the package share a name, so that ``Outputs`` (what a
run records) and ``signals.Recording`` (a measured recording) cannot be confused in a notebook or a traceback."""

import importlib
import inspect
import pkgutil

import rodimpact


def public_classes():
    """(qualified place, class) of every class a public module of the package defines."""
    for info in pkgutil.walk_packages(rodimpact.__path__, "rodimpact."):
        if any(part.startswith("_") for part in info.name.split(".")[1:]):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if (inspect.isclass(obj) and not name.startswith("_") and obj.__module__ == module.__name__):
                yield f"{module.__name__}.{name}", obj


def test_no_two_public_classes_share_a_name():
    seen: dict[str, str] = {}
    clashes = []
    for place, cls in public_classes():
        if cls.__name__ in seen and seen[cls.__name__] != place:
            clashes.append(f"{cls.__name__}: {seen[cls.__name__]} and {place}")
        seen.setdefault(cls.__name__, place)
    assert not clashes, "\n".join(clashes)


def test_the_check_sees_a_clash():
    assert {c.__name__ for _, c in public_classes()} >= {"Outputs", "Recording", "Problem", "TimeGrid"}
