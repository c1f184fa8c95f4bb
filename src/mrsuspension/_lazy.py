"""Lazy package namespaces: a package's public names load on first use (PEP 562).

A package keeps its curated ``__all__`` and ``from package import Name`` keeps working,
but importing the package no longer imports numpy, numba or scipy behind every name;
``mrsus --help`` and ``import mrsuspension`` stay fast.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_namespace"]


def lazy_namespace(
    package: str, names: Mapping[str, str], namespace: dict[str, Any]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of a package whose names load lazily.

    Parameters
    ----------
    package : str
        The package's ``__name__`` (for the error message).
    names : mapping
        Public name to the module that defines it (a name equal to its module's last
        component and defined nowhere else is the submodule itself).
    namespace : dict
        The package's ``globals()``: a loaded name is cached there, so the next look-up
        does not come back here.

    Examples
    --------
    >>> ns: dict[str, Any] = {}
    >>> getattr_, dir_ = lazy_namespace("pkg", {"sqrt": "math"}, ns)
    >>> getattr_("sqrt")(4.0)
    2.0
    >>> "sqrt" in ns
    True
    >>> getattr_("nope")
    Traceback (most recent call last):
    ...
    AttributeError: module 'pkg' has no attribute 'nope'
    """

    def __getattr__(name: str) -> Any:
        module = names.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        loaded = importlib.import_module(module)
        value = loaded if module.rsplit(".", 1)[-1] == name else getattr(loaded, name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
