"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on its own source file only. Our entry points inline kernels
from other modules, so an edit to :mod:`mrsuspension.dampers.kernels` would otherwise
leave a stale compiled engine in ``__pycache__`` (an editable install keeps the files).
:func:`invalidate_if_changed` removes a module's cache files when any of its
dependencies' source changed since they were written.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["DEPENDENCIES", "invalidate_if_changed"]

#: module file -> the source files its cached kernels inline (as registered by
#: :func:`invalidate_if_changed`; checked by ``tests/unit/engine/test_numba_deps.py``)
DEPENDENCIES: dict[str, tuple[str, ...]] = {}


def invalidate_if_changed(module_file: str, *dependencies: str) -> None:
    """Delete ``module_file``'s numba cache when a dependency's source changed.

    The digest of the dependencies is kept in ``__pycache__/<stem>.deps``; failures to
    read or write (a read-only install) are ignored, numba then simply recompiles or uses
    its own fallback cache location.

    Examples
    --------
    >>> import mrsuspension.engine.kernel as EK
    >>> import mrsuspension.control.kernel as CK
    >>> CK.__file__ in DEPENDENCIES[EK.__file__]
    True
    """
    DEPENDENCIES[str(module_file)] = tuple(str(d) for d in dependencies)
    module = Path(module_file)
    cache = module.parent / "__pycache__"
    digest = hashlib.sha256()
    for dep in dependencies:
        try:
            digest.update(Path(dep).read_bytes())
        except OSError:
            return
    stamp = cache / f"{module.stem}.deps"
    value = digest.hexdigest()
    try:
        if stamp.exists() and stamp.read_text() == value:
            return
        for stale in cache.glob(f"{module.stem}.*.nb[ic]"):
            stale.unlink(missing_ok=True)
        cache.mkdir(exist_ok=True)
        stamp.write_text(value)
    except OSError:
        return
