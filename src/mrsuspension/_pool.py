"""The one owner of worker processes and of interrupts: a local process pool that stops fast.

:func:`pool_map` maps a picklable function over tasks, results in order. It is used by
:func:`~mrsuspension.engine.simulate.run_many` (and through it by scenarios and studies)
and by :mod:`mrsuspension._batch` (the optimiser and the trade-off search, which keep one
pool open across batches with :func:`process_pool`); the report's runner uses
:func:`process_pool` directly.

Interrupts: the workers ignore SIGINT (a terminal's Ctrl-C reaches the whole process
group), so only the parent decides. When the block of :func:`process_pool` ends with any
exception (a ``KeyboardInterrupt``, :class:`Interrupted`, a task's error), the pending
tasks are cancelled and the workers and their children are terminated (SIGTERM, then
SIGKILL after :data:`STOP_TIMEOUT`), never waited for: ``shutdown(wait=True)`` would let
every running and queued task finish first (about 40 s on a sweep), and
``shutdown(cancel_futures=True)`` still lets the running ones finish. Signals arriving
during that cleanup are held back, so a second Ctrl-C cannot interrupt it half way.
:func:`handle_signals` turns SIGINT and SIGTERM into :class:`Interrupted` once, for the
``mrsus`` command. It imports nothing from the package, so the engine may use it.

Workers never outlive their parent and never hold its locks: each asks the kernel for
SIGTERM when its parent dies (Linux ``prctl(PR_SET_PDEATHSIG)``; a kill -9 or a hang-up
of the parent ends them at once), and closes the file descriptors registered with
:func:`close_in_workers` (the ``--out`` lock of :mod:`mrsuspension._output`: an
``flock`` lock lives as long as any process holds a descriptor of it, and a forked
worker holds a copy of each). The kernel sends the signal when the *thread* that
started the worker ends; a pool is used within one block of one thread, so that is its
parent's end.
"""

from __future__ import annotations

import functools
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager, suppress
from types import FrameType
from typing import TYPE_CHECKING, Any, TypeVar

if TYPE_CHECKING:
    from concurrent.futures import Executor, Future, ProcessPoolExecutor

__all__ = [
    "STOP_TIMEOUT",
    "InterruptState",
    "Interrupted",
    "Progress",
    "close_in_workers",
    "descendants",
    "ensure_resource_tracker",
    "handle_signals",
    "pool_map",
    "process_pool",
    "raise_if_interrupted",
    "stop_pool",
    "worker_count",
]

T = TypeVar("T")
R = TypeVar("R")

#: ``progress(done, total)``, called as tasks finish
Progress = Callable[[int, int], None]

#: seconds a terminated worker gets to exit before it is killed (measured: a worker
#: inside a numba kernel exits on SIGTERM in a few milliseconds)
STOP_TIMEOUT = 0.5

#: what stops a command: Ctrl-C, ``kill``, and a terminal's hang-up (a closed terminal, a
#: dropped SSH session)
_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)

#: file descriptors a forked worker closes first (:func:`close_in_workers`)
_PARENT_ONLY: set[int] = set()

#: ``prctl`` option: the signal sent to this process when its parent dies (Linux)
_PR_SET_PDEATHSIG = 1


class Interrupted(KeyboardInterrupt):
    """SIGINT (Ctrl-C), SIGTERM or SIGHUP received by the parent process.

    A ``KeyboardInterrupt``, so code that stops cleanly on Ctrl-C stops on SIGTERM too.

    Examples
    --------
    >>> import signal
    >>> Interrupted(signal.SIGTERM).exit_code
    143
    """

    def __init__(self, signum: int = signal.SIGINT) -> None:
        super().__init__(signum)
        self.signum = int(signum)

    @property
    def exit_code(self) -> int:
        """The shell's exit status for this signal: 128 + its number (130, 143)."""
        return 128 + self.signum


class InterruptState:
    """What :func:`handle_signals` received: ``signum`` (None until a signal arrives)."""

    def __init__(self) -> None:
        self.signum: int | None = None


def _in_main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


#: code where an exception raised by a signal handler is printed and dropped instead of
#: delivered: finalizers, and numba's LLVM callbacks (ctypes: raising there can crash)
_NO_RAISE_NAMES = frozenset({"__del__"})
_NO_RAISE_PATHS = tuple(f"{os.sep}{pkg}{os.sep}" for pkg in ("llvmlite", "numba"))


def raise_is_lost(frame: FrameType | None) -> bool:
    """Whether an exception raised by a signal handler at ``frame`` would be lost.

    Python runs a handler at the next bytecode of the main thread, which may be inside a
    finalizer (``__del__``: the exception is printed as "Exception ignored" and dropped)
    or inside numba's LLVM callbacks through ctypes (the process may crash). The
    handlers then deliver the signal again a moment later (:func:`deliver_later`).

    Examples
    --------
    >>> import sys
    >>> raise_is_lost(sys._getframe())
    False
    """
    f = frame
    while f is not None:
        code = f.f_code
        if code.co_name in _NO_RAISE_NAMES or any(p in code.co_filename for p in _NO_RAISE_PATHS):
            return True
        f = f.f_back
    return False


def deliver_later(signum: int, delay: float = 0.005) -> None:
    """Send ``signum`` to this process again after ``delay`` [s] (see :func:`raise_is_lost`)."""
    timer = threading.Timer(delay, os.kill, (os.getpid(), signum))
    timer.daemon = True
    timer.start()


@contextmanager
def handle_signals() -> Iterator[InterruptState]:
    """Raise :class:`Interrupted` on the first SIGINT, SIGTERM or SIGHUP; ignore the ones
    after it.

    The first signal stops the work (as ``KeyboardInterrupt`` does); a second Ctrl-C
    while the program cleans up is ignored instead of interrupting the cleanup. A SIGINT
    or SIGHUP that was ignored when the block started (a background job, ``nohup``) stays
    ignored. The
    previous handlers come back when the block ends. Outside the main thread it does
    nothing.

    Yields
    ------
    InterruptState
        ``signum`` of the first signal received, None if none.

    Examples
    --------
    >>> import os, signal, time
    >>> try:
    ...     with handle_signals() as state:
    ...         os.kill(os.getpid(), signal.SIGTERM)
    ...         end = time.monotonic() + 10.0  # the handler runs at a next bytecode
    ...         while time.monotonic() < end:
    ...             pass
    ... except Interrupted as exc:
    ...     print(exc.exit_code, state.signum == signal.SIGTERM)
    143 True
    """
    state = InterruptState()
    if not _in_main_thread():
        yield state
        return

    def on_signal(signum: int, frame: FrameType | None) -> None:
        if state.signum is not None:
            return  # already stopping: cleanup is bounded, a second signal is not needed
        if raise_is_lost(frame):  # a finalizer or numba's LLVM callback: raise it after
            deliver_later(signum)
            return
        state.signum = signum
        _RAISED[:] = [signum]
        raise Interrupted(signum)

    previous = {s: signal.getsignal(s) for s in _SIGNALS}
    for s in _SIGNALS:
        if not (s != signal.SIGTERM and previous[s] == signal.SIG_IGN):
            signal.signal(s, on_signal)
    try:
        yield state
    finally:
        _RAISED.clear()
        for s, handler in previous.items():
            signal.signal(s, handler if handler is not None else signal.SIG_DFL)


#: the signal whose :class:`Interrupted` :func:`handle_signals` raised (cleared when its
#: block ends): for :func:`raise_if_interrupted`
_RAISED: list[int] = []


def raise_if_interrupted() -> None:
    """Raise :class:`Interrupted` again if an interrupt was raised and the work goes on.

    The handler of :func:`handle_signals` raises once, and a Python exception raised in
    a signal handler lands wherever the main thread is: inside a ctypes callback (numba's
    and llvmlite's, while kernels load or compile) it is printed as "Exception ignored"
    and lost, and the command worked on (seen: a report running 30 s past its Ctrl-C).
    Loops that wait for work call this between tasks: after a lost interrupt they stop;
    after one that is unwinding they are not reached.

    Examples
    --------
    >>> import os, signal, time
    >>> with handle_signals():
    ...     try:
    ...         os.kill(os.getpid(), signal.SIGINT)
    ...         end = time.monotonic() + 10.0  # the handler runs at a next bytecode
    ...         while time.monotonic() < end:
    ...             pass
    ...     except KeyboardInterrupt:
    ...         pass  # lost, as in a ctypes callback
    ...     try:
    ...         raise_if_interrupted()
    ...     except Interrupted as exc:
    ...         print("raised again:", exc.exit_code)
    raised again: 130
    """
    if _RAISED:
        raise Interrupted(_RAISED[0])


@contextmanager
def _signals_held(replay: bool = True) -> Iterator[None]:
    """Hold SIGINT and SIGTERM back for a short critical section (main thread only).

    The signals are blocked (so a process forked inside, a pool worker, starts with them
    blocked until its initializer ignores SIGINT) and their Python handlers only record
    them; on leaving, the handlers are restored and, with ``replay``, a recorded signal
    is delivered again.
    """
    if not _in_main_thread():
        yield
        return
    caught: list[int] = []
    previous = {s: signal.getsignal(s) for s in _SIGNALS}
    for s in _SIGNALS:
        if previous[s] != signal.SIG_IGN:
            signal.signal(s, lambda signum, _frame: caught.append(signum))
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, _SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        for s, handler in previous.items():
            signal.signal(s, handler if handler is not None else signal.SIG_DFL)
        if replay and caught:
            signal.raise_signal(caught[0])


def ensure_resource_tracker() -> None:
    """Start :mod:`multiprocessing`'s resource tracker, immune to a terminal's hang-up.

    The tracker (one process per program, started on first need) unlinks the named
    semaphores of ``spawn`` queues and events. It ignores SIGINT and SIGTERM but not
    SIGHUP, so a closed terminal (SIGHUP to the process group) killed it while the monitor
    was still stopping its loop, which then printed tracebacks. Started here with SIGHUP
    blocked in this thread, it inherits the block and outlives the hang-up. Call it before
    the first ``spawn`` queue, event or process; any thread may (the mask is the
    thread's).
    """
    from multiprocessing import resource_tracker

    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGHUP})
    try:
        resource_tracker.ensure_running()
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)


@contextmanager
def close_in_workers(fd: int) -> Iterator[None]:
    """Have pool workers forked during the block close ``fd`` as they start.

    For a lock held by the parent (the ``--out`` lock): a forked worker holds a copy of
    every descriptor, and an ``flock`` lock lasts until the last copy is closed, so a
    worker left running would keep it. Closing the copy leaves the parent's lock as it is.

    Examples
    --------
    >>> import os
    >>> r, w = os.pipe()
    >>> with close_in_workers(r), process_pool(2, 2) as pool:
    ...     pool.submit(_is_open, r).result()
    False
    >>> os.close(r), os.close(w)
    (None, None)
    """
    _PARENT_ONLY.add(fd)
    try:
        yield
    finally:
        _PARENT_ONLY.discard(fd)


def _is_open(fd: int) -> bool:
    """Whether ``fd`` is an open descriptor of this process (for tests)."""
    try:
        os.fstat(fd)
    except OSError:
        return False
    return True


def _die_with_parent(parent: int) -> None:
    """Ask for SIGTERM when the parent dies (Linux); exit now if it already has."""
    if sys.platform.startswith("linux"):
        import ctypes

        with suppress(OSError, AttributeError):
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    if os.getppid() != parent:  # died before the request: nobody would send it
        os._exit(1)


def _worker_init(parent: int | None = None) -> None:
    """Pool worker start: close the parent's locks, die with the parent; Ctrl-C is the
    parent's business; SIGTERM ends the worker."""
    for fd in list(_PARENT_ONLY):
        with suppress(OSError):
            os.close(fd)
    _PARENT_ONLY.clear()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if parent is not None:
        _die_with_parent(parent)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _SIGNALS)


def descendants(pid: int) -> list[int]:
    """Process ids of ``pid``'s children, grandchildren, ... (Linux ``/proc``; else none).

    Examples
    --------
    >>> import os
    >>> os.getpid() in descendants(os.getppid())
    True
    """
    found: list[int] = []
    stack = [pid]
    while stack:
        parent = stack.pop()
        try:
            threads = os.listdir(f"/proc/{parent}/task")
        except OSError:
            continue
        for tid in threads:
            try:
                with open(f"/proc/{parent}/task/{tid}/children") as f:
                    kids = [int(k) for k in f.read().split()]
            except (OSError, ValueError):
                continue
            found += kids
            stack += kids
    return found


def stop_pool(pool: Executor, timeout: float = STOP_TIMEOUT) -> None:
    """Stop a pool now: cancel its pending tasks, terminate its workers and their children.

    Running tasks are not waited for. Workers get SIGTERM, then SIGKILL if still alive
    after ``timeout`` seconds; the whole call takes at most about ``2 * timeout``.
    SIGINT and SIGTERM received meanwhile are dropped (the caller is already stopping).
    Works with :class:`~concurrent.futures.ProcessPoolExecutor` (its worker processes);
    any other executor is only shut down without waiting.

    Examples
    --------
    >>> from concurrent.futures import ProcessPoolExecutor
    >>> pool = ProcessPoolExecutor(2)
    >>> pool.submit(abs, -1).result()
    1
    >>> stop_pool(pool)
    """
    with _signals_held(replay=False):
        workers = list((getattr(pool, "_processes", None) or {}).values())
        children = [k for w in workers if w.pid is not None for k in descendants(w.pid)]
        for w in workers:
            if w.is_alive():
                w.terminate()
        for pid in children:
            with suppress(OSError):  # gone already
                os.kill(pid, signal.SIGKILL)
        queue = getattr(pool, "_call_queue", None)
        if queue is not None:  # its feeder may be blocked on a pipe no worker reads any more
            queue.cancel_join_thread()
        pool.shutdown(wait=False, cancel_futures=True)
        deadline = time.monotonic() + timeout
        for w in workers:
            w.join(max(0.0, deadline - time.monotonic()))
        for w in workers:
            if w.is_alive():
                w.kill()
                w.join(timeout)


@functools.cache
def _pool_class() -> type[ProcessPoolExecutor]:
    """The pool class, built on first use (``concurrent.futures`` is imported lazily)."""
    from concurrent.futures import ProcessPoolExecutor

    class SignalSafePool(ProcessPoolExecutor):
        """Submits with SIGINT/SIGTERM held back: workers fork (on the first submit) with
        them blocked, and an interrupt never lands inside the executor's lock."""

        def submit(self, fn: Callable[..., R], /, *args: Any, **kwargs: Any) -> Future[R]:
            with _signals_held():
                return super().submit(fn, *args, **kwargs)

    return SignalSafePool


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
    about 0.3 s to start, so a caller with several batches keeps one open. The workers
    ignore SIGINT, die with this process and close its registered locks
    (:func:`close_in_workers`). When the block raises (Ctrl-C, SIGTERM under :func:`handle_signals`,
    a task's error), the pool is stopped at once with :func:`stop_pool`; when it ends
    normally, the pool is shut down after its tasks.

    Examples
    --------
    >>> with process_pool(1, 10) as pool:
    ...     pool is None
    True
    >>> with process_pool(2, 2) as pool:
    ...     [f.result() for f in [pool.submit(abs, -1), pool.submit(abs, -2)]]
    [1, 2]
    """
    n = worker_count(workers, tasks)
    if n <= 1:
        yield None
        return
    pool = _pool_class()(max_workers=n, initializer=_worker_init, initargs=(os.getpid(),))
    try:
        yield pool
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown(wait=True)


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
        raised here (the pool of this call is then stopped at once).

    Examples
    --------
    >>> pool_map(abs, [-1, 2, -3], workers=1)
    [1, 2, 3]
    """
    from concurrent.futures import FIRST_COMPLETED, wait

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
            raise_if_interrupted()
        return results
    futures = {pool.submit(fn, item): k for k, item in enumerate(items)}
    pending = set(futures)
    while pending:  # polled, so that an interrupt lost in a callback still stops the wait
        ready, pending = wait(pending, timeout=0.25, return_when=FIRST_COMPLETED)
        for fut in sorted(ready, key=lambda f: futures[f]):
            finished(futures[fut], fut.result())
        raise_if_interrupted()
    return results
