"""The one-line notice that the engine is being compiled (a cold numba cache).

numba compiles the engine on its first call (about a minute on a slow machine) and keeps
the result in ``engine/__pycache__``; without a word the first ``mrsus simulate``,
``sweep``, ``study`` or ``reproduce`` looks hung. The commands call
:func:`notify_if_compiling` before their first run.
"""

from __future__ import annotations

import sys
from typing import TextIO

__all__ = ["COMPILE_NOTICE", "engine_cache_cold", "notify_if_compiling"]

#: said on stderr before the first run when the engine's numba cache is cold
COMPILE_NOTICE = "compiling the engine (first run only, about a minute)..."


def engine_cache_cold() -> bool:
    """Whether the engine's compiled kernels are missing from numba's on-disk cache.

    Imports :mod:`mrsuspension.engine.kernel` (which drops a stale cache, see
    :mod:`mrsuspension._numba_cache`) and looks for the cache index of its ``run``
    kernel in ``engine/__pycache__`` (or under ``NUMBA_CACHE_DIR`` when set).

    Examples
    --------
    >>> engine_cache_cold() in (True, False)
    True
    """
    import os
    from pathlib import Path

    import mrsuspension.engine.kernel as kernel

    pattern = f"{Path(kernel.__file__).stem}.run-*.nbi"
    root = os.environ.get("NUMBA_CACHE_DIR")
    if root:
        return not any(Path(root).rglob(pattern))
    return not any((Path(kernel.__file__).parent / "__pycache__").glob(pattern))


def notify_if_compiling(stream: TextIO | None = None) -> bool:
    """Write :data:`COMPILE_NOTICE` on stderr when the engine cache is cold; say whether.

    Examples
    --------
    >>> import io
    >>> log = io.StringIO()
    >>> notify_if_compiling(log) == bool(log.getvalue())
    True
    """
    if not engine_cache_cold():
        return False
    out = sys.stderr if stream is None else stream
    out.write(COMPILE_NOTICE + "\n")
    out.flush()
    return True
