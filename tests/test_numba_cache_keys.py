"""numba's on-disk cache (``cache=True``) is keyed by the Python function (its module, qualified name and source
line), not by the compile options: two dispatchers made from one function load each other's machine code. That
once made ``simulate_batch(threads=1)`` run on every thread (the serial dispatcher loaded the parallel build) and,
with the other compile order, ``threads=2`` run serially. Every cached dispatcher must wrap a function of its own.
"""

import importlib
import pkgutil

from numba.core.registry import CPUDispatcher

import rodimpact


def cached_dispatchers() -> list[tuple[str, CPUDispatcher]]:
    """(module.attribute, dispatcher) for every module-level numba dispatcher of the package that caches."""
    found = []
    for info in pkgutil.walk_packages(rodimpact.__path__, "rodimpact."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if isinstance(obj, CPUDispatcher) and obj.py_func.__module__ == info.name and obj._cache is not None \
                    and type(obj._cache).__name__ != "NullCache":
                found.append((f"{info.name}.{name}", obj))
    return found


def test_every_cached_dispatcher_wraps_a_function_of_its_own():
    found = cached_dispatchers()
    assert len(found) > 20  # the walk sees the kernels
    owners: dict[int, str] = {}
    for where, dispatcher in found:
        other = owners.setdefault(id(dispatcher.py_func), where)
        assert other == where, f"{where} and {other} compile the same Python function with numba's cache on"
