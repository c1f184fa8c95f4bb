"""The package's doctests keep one copy of each module (``--doctest-modules`` with
``--import-mode=importlib``).

pytest imports a module of ``src/mrsuspension`` for its doctests from its file unless
``sys.modules`` already holds it. When the module's package ``__init__`` imports it on the
way, that import from the file then replaces the module with a second copy, and the
modules imported before keep the first: an ``is`` or an ``except`` on one of its classes
fails in a test, depending on which files the process collected first (it did with
``AliasedRecordWarning`` and the whole-vehicle laws' classes). Importing each module the
standard way just before pytest collects it leaves pytest the one copy.
"""

from __future__ import annotations

import contextlib
import importlib
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parent / "src"


def pytest_collect_file(file_path: Path, parent: pytest.Collector) -> None:
    """Import a package module (not ``__main__``, which would run the CLI) before pytest."""
    if file_path.suffix != ".py" or SRC not in file_path.parents or file_path.name == "__main__.py":
        return
    parts = file_path.relative_to(SRC).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    with contextlib.suppress(ImportError):  # pytest's own import then reports it
        importlib.import_module(".".join(parts))
