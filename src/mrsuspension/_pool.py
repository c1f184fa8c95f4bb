"""The one local process pool: map a picklable function over tasks, results in order.

Used by :func:`~mrsuspension.engine.simulate.run_many` (and through it by scenarios and
studies) and by :mod:`mrsuspension._batch` (the optimiser and the trade-off search,
which keep one pool open across batches with :func:`process_pool`). It imports nothing
from the package, so the engine may use it.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from typing import Any, TypeVar

__all__ = ["Progress", "pool_map", "process_pool", "worker_count"]

T = TypeVar("T")
R = TypeVar("R")

#: ``progress(done, total)``, called as tasks finish
Progress = Callable[[int, int], None]


def worker_count(workers: int | None, tasks: int) -> int:
    """Processes worth starting: ``workers`` (None: one per core), at most one per task.

    Examples
    --------
    >>> worker_count(8, 3), worker_count(1, 100)
    (3, 1)
    """
    return max(1, min(tasks, workers or os.cpu_count() or 1))


@contextmanager
def process_pool(workers: int | None, tasks: int) -> Iterator[Executor | None]:
    """A process pool for one or several batches of up to ``tasks`` tasks.

    Yields None (run in this process) when only one worker would be used; a pool costs
    about 0.3 s to start, so a caller with several batches keeps one open.

    Examples
    --------
    >>> with process_pool(1, 10) as pool:
    ...     pool is None
    True
    """
    n = worker_count(workers, tasks)
    if n <= 1:
        yield None
        return
    with ProcessPoolExecutor(max_workers=n) as pool:
        yield pool


def pool_map(
    fn: Callable[[T], R],
    tasks: Sequence[T],
    *,
    workers: int | None = None,
    pool: Executor | None = None,
    progress: Progress | None = None,
    weights: Sequence[int] | None = None,
) -> list[R]:
    """``[fn(t) for t in tasks]`` across processes, in the order given.

    Parameters
    ----------
    fn : callable
        A module-level (picklable) function of one task.
    tasks : sequence
        Its arguments (picklable).
    workers : int, optional
        Processes of a pool started for this call (None: one per core; 1: this
        process). Ignored when ``pool`` is given.
    pool : Executor, optional
        An open pool (e.g. from :func:`process_pool`) to use instead of a new one.
    progress : callable, optional
        ``progress(done, total)`` as tasks finish, counted in ``weights``.
    weights : sequence of int, optional
        What each task counts for in ``progress`` (e.g. the runs of a batch); 1 each
        by default.

    Returns
    -------
    list
        ``fn(task)`` for each task, in order. The first exception raised by a task is
        raised here.

    Examples
    --------
    >>> pool_map(abs, [-1, 2, -3], workers=1)
    [1, 2, 3]
    """
    items = list(tasks)
    counts = [1] * len(items) if weights is None else [int(w) for w in weights]
    if len(counts) != len(items):
        raise ValueError(f"weights has {len(counts)} entries for {len(items)} tasks")
    total = sum(counts)
    done = 0
    results: list[Any] = [None] * len(items)

    def finished(k: int, value: R) -> None:
        nonlocal done
        results[k] = value
        done += counts[k]
        if progress is not None:
            progress(done, total)

    if pool is None and worker_count(workers, len(items)) > 1:
        with process_pool(workers, len(items)) as own:
            return pool_map(fn, items, pool=own, progress=progress, weights=counts)
    if pool is None:
        for k, item in enumerate(items):
            finished(k, fn(item))
        return results
    futures = {pool.submit(fn, item): k for k, item in enumerate(items)}
    for fut in as_completed(futures):
        finished(futures[fut], fut.result())
    return results
