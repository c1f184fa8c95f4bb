"""Run the fit with single-threaded BLAS (restored afterwards).

The fit multiplies tall, thin Jacobians (10^4 rows x ~13 columns) with vectors thousands
of times. Multi-threaded OpenBLAS gains nothing on such products and, when the other
cores are busy, its threads wait on each other: on the project's 2-core CI machine the
same fit took 5 to 30 times longer, depending on the load (bench_identify.py). Uses
``threadpoolctl`` when installed, else finds the OpenBLAS libraries numpy and scipy
loaded (Linux ``/proc/self/maps``) and calls their ``set_num_threads``; anywhere else it
does nothing.
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

__all__ = ["blas_threads"]

_SUFFIXES = ("", "64_", "_64")
_PREFIXES = ("openblas", "scipy_openblas")


def _openblas_controls() -> list[tuple[Callable[[], int], Callable[[int], None]]]:
    maps = Path("/proc/self/maps")
    if not maps.is_file():
        return []
    paths = set()
    try:
        for line in maps.read_text().splitlines():
            path = line.split()[-1] if line.split() else ""
            if "openblas" in path.lower() and path.startswith("/"):
                paths.add(path)
    except OSError:  # pragma: no cover - unreadable maps
        return []
    controls = []
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)
        except OSError:  # pragma: no cover
            continue
        for prefix in _PREFIXES:
            for suffix in _SUFFIXES:
                get = getattr(lib, f"{prefix}_get_num_threads{suffix}", None)
                put = getattr(lib, f"{prefix}_set_num_threads{suffix}", None)
                if get is not None and put is not None:
                    get.restype, get.argtypes = ctypes.c_int, []
                    put.restype, put.argtypes = None, [ctypes.c_int]
                    controls.append((get, put))
                    break
            else:
                continue
            break
    return controls


@contextmanager
def blas_threads(limit: int | None = 1) -> Iterator[None]:
    """Limit BLAS threads to ``limit`` inside the block (``None``: leave them alone).

    Examples
    --------
    >>> import numpy as np
    >>> with blas_threads(1):
    ...     float((np.ones((1000, 3)).T @ np.ones(1000)).sum())
    3000.0
    """
    if limit is None:
        yield
        return
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        controls = _openblas_controls()
        before = [get() for get, _ in controls]
        for _, put in controls:
            put(limit)
        try:
            yield
        finally:
            for (_, put), n in zip(controls, before, strict=True):
                put(n)
        return
    with threadpool_limits(limits=limit, user_api="blas"):  # pragma: no cover - optional
        yield
