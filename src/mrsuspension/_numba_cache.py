"""Keep numba's on-disk cache honest across modules.

numba keys a cached function on its own source file only. Our entry points inline kernels
from other modules, so an edit to :mod:`mrsuspension.dampers.kernels` would otherwise
leave a stale compiled engine in ``__pycache__`` (an editable install keeps the files).
:func:`invalidate_if_changed` removes a module's cache files when any of its
dependencies' source changed since they were written.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path
from typing import Any, TextIO

__all__ = [
    "COMPILE_NOTICE",
    "DEPENDENCIES",
    "INLINED",
    "announce_compile",
    "cache_cold",
    "invalidate_if_changed",
    "quiet_compiles",
]

#: said once on stderr before an entry point compiles (its numba cache is cold)
COMPILE_NOTICE = (
    "compiling the engine (first run only, 5-20 s; `mrsus cache warm` compiles ahead)..."
)
#: entry points ``(module file, name)`` already looked at in this process, and whether
#: the notice was said (once per process, whatever compiles next)
_SEEN: set[tuple[str, str]] = set()
_SAID: list[bool] = [False]

#: numba options of the kernels that the entry points (``engine.kernel.run``, the lane
#: kernel, the damper and HiL loops) call: each is compiled once, as its own function,
#: and LLVM inlines it at every call site (``forceinline``). numba's own inlining
#: (``inline="always"``) copies the callee's IR into every caller, and each copy of a
#: block deep-copies the callee's whole variable scope: the cost grows with the square
#: of the inlined code, and was 11 of the 17 s that compiling ``run`` took. Measured on a
#: fresh cache (harmonic ``mrsus simulate``, CPU s): 17.6 s inlined by numba, 5.7 s
#: inlined by LLVM, with the same step time (133 against 135 ns, min of 800); compiled
#: as plain calls (no ``forceinline``) LLVM left ``accelerations`` un-inlined and the step
#: took 196 ns. The options are explicit, not inherited from the caller (numba keeps the
#: first compiled version of a signature, whoever the caller): no reference counting (the
#: kernels allocate nothing; with it the step was ~30x slower), Python's error model and
#: IEEE arithmetic (no fastmath), as in ``run``, so results do not depend on which entry
#: point compiled a kernel first.
INLINED: dict[str, Any] = {
    "forceinline": True,
    "_nrt": False,
    "error_model": "python",
    "fastmath": False,
}

#: module file -> the source files its cached kernels inline (as registered by
#: :func:`invalidate_if_changed`; checked by ``tests/unit/engine/test_numba_deps.py``)
DEPENDENCIES: dict[str, tuple[str, ...]] = {}


def invalidate_if_changed(module_file: str, *dependencies: str) -> None:
    """Delete ``module_file``'s numba cache when a dependency's source changed.

    The digest of the dependencies (and of :data:`INLINED`, which numba's cache does not
    key on) is kept in ``__pycache__/<stem>.deps``; failures to
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
    digest = hashlib.sha256(repr(sorted(INLINED.items())).encode())
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


def cache_cold(module_file: str, *names: str) -> bool:
    """Whether any entry point ``names`` of ``module_file`` is missing from numba's cache.

    Looks for each cache index (``<stem>.<name>-*.nbi``) in the module's ``__pycache__``,
    or under ``NUMBA_CACHE_DIR`` when set.

    Examples
    --------
    >>> import mrsuspension.engine.kernel as kernel
    >>> cache_cold(kernel.__file__, "run") in (True, False)
    True
    """
    stem = Path(module_file).stem
    root = os.environ.get("NUMBA_CACHE_DIR")
    for name in names:
        pattern = f"{stem}.{name}-*.nbi"
        if root:
            found = any(Path(root).rglob(pattern))
        else:
            found = any((Path(module_file).parent / "__pycache__").glob(pattern))
        if not found:
            return True
    return False


def announce_compile(module_file: str, *names: str, stream: TextIO | None = None) -> bool:
    """Say :data:`COMPILE_NOTICE` on stderr, once per process, before a cold entry point runs.

    Called by the engine before it calls a compiled entry point (the quarter car's and
    the vehicles' loops, the lanes, the reduced loop), so that a first run from Python or
    from any command says why it waits. Each entry point is looked at once per process
    (a glob in ``__pycache__``), the notice is said at most once per process, and only
    the main process speaks (a pool's workers stay quiet). Returns whether it spoke.

    Examples
    --------
    >>> import io, mrsuspension.engine.kernel as kernel
    >>> log = io.StringIO()
    >>> announce_compile(kernel.__file__, "run", stream=log) == bool(log.getvalue())
    True
    >>> announce_compile(kernel.__file__, "run", stream=log)  # once per process
    False
    """
    import multiprocessing

    keys = [(module_file, n) for n in names if (module_file, n) not in _SEEN]
    if not keys:
        return False
    _SEEN.update(keys)
    if _SAID[0] or multiprocessing.parent_process() is not None:
        return False
    if not cache_cold(module_file, *(n for _, n in keys)):
        return False
    _SAID[0] = True
    out = sys.stderr if stream is None else stream
    out.write(COMPILE_NOTICE + "\n")
    out.flush()
    return True


def quiet_compiles() -> None:
    """Say no notice in this process (``mrsus cache warm`` reports each step itself)."""
    _SAID[0] = True
