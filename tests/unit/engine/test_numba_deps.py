"""Every module with cached numba kernels lists the sources they inline.

numba keys its on-disk cache on a function's own file; a module whose kernels inline
kernels of other files registers them with
:func:`~mrsuspension._numba_cache.invalidate_if_changed`. Here, for each registered
module, every other module of the package whose compiled functions it uses (directly or
through those modules, transitively) must be in its list, so that editing e.g.
``control/kernel.py`` or ``vehicle/kernel.py`` drops the engine's cache.
"""

from __future__ import annotations

import importlib
import sys
from types import ModuleType

import pytest
from numba.core.registry import CPUDispatcher

from mrsuspension import _numba_cache

MODULES = [
    "mrsuspension.control.kernel",
    "mrsuspension.dampers.kernels",
    "mrsuspension.engine.kernel",
    "mrsuspension.engine.lanes",
    "mrsuspension.engine.vehicle_kernel",
    "mrsuspension.hil._kernels",
    "mrsuspension.hil._vehicle_kernel",
    "mrsuspension.identify.timedomain",
    "mrsuspension.shaping",
]


def _has_kernels(module: ModuleType) -> bool:
    return any(
        isinstance(v, CPUDispatcher) and v.__module__ == module.__name__
        for v in vars(module).values()
    )


def _kernel_sources(module: ModuleType) -> set[str]:
    """Files of the package's other modules whose compiled functions ``module`` can call."""
    out: set[str] = set()
    for value in vars(module).values():
        if isinstance(value, ModuleType):
            other = value
        elif isinstance(value, CPUDispatcher):
            other = sys.modules[value.__module__]
        else:
            continue
        if other is module or not other.__name__.startswith("mrsuspension."):
            continue
        if _has_kernels(other):
            out.add(str(other.__file__))
    return out


def _closure(module: ModuleType) -> set[str]:
    seen: set[str] = set()
    todo = [module]
    while todo:
        for source in _kernel_sources(todo.pop()):
            if source not in seen:
                seen.add(source)
                todo.extend(
                    m for m in sys.modules.values() if getattr(m, "__file__", None) == source
                )
    return seen


@pytest.mark.parametrize("name", MODULES)
def test_inlined_sources_are_registered(name: str) -> None:
    module = importlib.import_module(name)
    registered = set(_numba_cache.DEPENDENCIES[str(module.__file__)])
    missing = sorted(_closure(module) - registered)
    assert not missing, (
        f"{name} inlines kernels of {missing}: add them to its invalidate_if_changed"
    )


def test_every_registering_module_is_checked() -> None:
    for name in MODULES:
        importlib.import_module(name)
    checked = {str(importlib.import_module(n).__file__) for n in MODULES}
    assert set(_numba_cache.DEPENDENCIES) <= checked
