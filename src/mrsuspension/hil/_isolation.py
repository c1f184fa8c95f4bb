"""Isolating a CPU for the HiL loop: move every movable task off it, and back afterwards.

Standard library only, so that the **guard process** of :func:`isolate_cpu` (this file run
by path: ``python -I -S _isolation.py``, reading the moved tasks on its standard input)
starts in a few tens of milliseconds. Used through
:func:`mrsuspension.hil.realtime.isolate_cpu` and ``realtime_session(isolate=True)``.
"""

from __future__ import annotations

import contextlib
import dataclasses
import json
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from typing import Any, NamedTuple

__all__ = ["IsolationReport", "isolate_cpu"]

#: ``PF_KTHREAD`` in the flags of ``/proc/PID/stat``
_PF_KTHREAD = 0x00200000
#: scans of ``/proc`` per isolation: later ones catch tasks started during the first
_ISOLATE_PASSES = 3


@dataclass(frozen=True)
class IsolationReport:
    """What :func:`isolate_cpu` did.

    Attributes
    ----------
    cpu : int
        The core isolated.
    moved : int
        Tasks (threads) moved off the core, kernel threads included.
    kernel_threads : int
        How many of the ``moved`` tasks are kernel threads.
    fixed : int
        Tasks left on the core because they may run on it alone or the kernel refused
        to move them (per-CPU kernel threads: ``EINVAL``).
    denied : int
        Tasks left on the core for want of permission (other users' tasks).
    note : str or None
        Why nothing was done (another platform, one CPU); None when the core was
        isolated.
    """

    cpu: int
    moved: int = 0
    kernel_threads: int = 0
    fixed: int = 0
    denied: int = 0
    note: str | None = None

    def label(self) -> str:
        """One line for the statistics.

        Examples
        --------
        >>> IsolationReport(1, moved=143, kernel_threads=12, fixed=9).label()
        'isolated cpu 1 (moved 143 tasks, 12 of them kernel threads; 9 bound to the core)'
        >>> IsolationReport(1, note="one CPU").label()
        'cpu 1 not isolated (one CPU)'
        """
        if self.note is not None:
            return f"cpu {self.cpu} not isolated ({self.note})"
        text = f"isolated cpu {self.cpu} (moved {self.moved} task{'s' if self.moved != 1 else ''}"
        if self.kernel_threads:
            text += f", {self.kernel_threads} of them kernel thread"
            text += "s" if self.kernel_threads != 1 else ""
        if self.fixed:
            text += f"; {self.fixed} bound to the core"
        if self.denied:
            text += f"; {self.denied} not permitted"
        return text + ")"

    def describe(self) -> dict[str, Any]:
        """Plain data."""
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class _Moved:
    old: frozenset[int]
    new: frozenset[int]
    start: int | None


class _TaskInfo(NamedTuple):
    kernel: bool  # a kernel thread
    ppid: int  # parent process
    start: int  # start time [clock ticks after boot]


def _stat(tid: int) -> _TaskInfo | None:
    """A task's line of ``/proc/TID/stat``, in part; None if unreadable (ended)."""
    try:
        with open(f"/proc/{tid}/stat", encoding="ascii", errors="replace") as f:
            text = f.read()
    except OSError:
        return None
    fields = text[text.rfind(")") + 2 :].split()  # after "pid (comm) "; comm may hold ")"
    try:
        ppid, flags, start = int(fields[1]), int(fields[6]), int(fields[19])
    except (IndexError, ValueError):
        return None
    kernel = bool(flags & _PF_KTHREAD) or tid == 2 or ppid == 2
    return _TaskInfo(kernel, ppid, start)


def _boot_ticks() -> int:
    """Now, in the clock ticks after boot of ``/proc/PID/stat``'s start times."""
    return int(time.clock_gettime(time.CLOCK_BOOTTIME) * os.sysconf("SC_CLK_TCK"))


def _all_tasks() -> list[tuple[int, int]]:
    """Every task of the machine as (process id, thread id): ``/proc/[0-9]*/task/[0-9]*``."""
    tasks: list[tuple[int, int]] = []
    try:
        pids = [int(e.name) for e in os.scandir("/proc") if e.name.isdigit()]
    except OSError:
        return tasks
    for pid in pids:
        try:
            tasks.extend(
                (pid, int(e.name)) for e in os.scandir(f"/proc/{pid}/task") if e.name.isdigit()
            )
        except OSError:  # ended meanwhile
            continue
    return tasks


def _all_tids() -> list[int]:
    """Every task (thread) of the machine."""
    return [tid for _, tid in _all_tasks()]


def _own_tids() -> set[int]:
    """The threads of this process."""
    try:
        return {int(e.name) for e in os.scandir("/proc/self/task") if e.name.isdigit()}
    except OSError:
        return {threading.get_native_id()}


@contextlib.contextmanager
def isolate_cpu(
    cpu: int, *, keep: Iterable[int] | None = None, tasks: Iterable[int] | None = None
) -> Iterator[IsolationReport]:
    """Move every movable task off ``cpu`` for the block; move them back afterwards.

    What ``tuna --isolate`` does: each task (thread) whose affinity contains ``cpu`` gets
    its affinity minus ``cpu`` (:func:`os.sched_setaffinity` on its thread id), kernel
    threads that may move (``kdamond``, ``rcu_preempt``, unbound workers) included. Left
    alone: tasks that may run on ``cpu`` only, those the kernel refuses to move (per-CPU
    kernel threads such as ``ksoftirqd/N``, ``migration/N``, ``kworker/N:*``: counted as
    ``fixed``) and, without root or ``CAP_SYS_NICE``, other users' tasks (``denied``).
    Tasks started during the scan are caught by up to two further scans; tasks started
    later inherit their creator's affinity: off the core when started by a moved task,
    possibly on it when started by one that was not moved.

    At the end each moved task gets its old affinity back, unless its affinity is no
    longer the one set here (someone changed it meanwhile: left as it is). Tasks that
    ended are ignored, and so is a thread id reused by a new task. Tasks started inside
    the block by a moved task (or by such a task's descendants) get the old affinity of
    that moved ancestor, on the same condition (they still have the affinity they
    inherited). A **guard process** (in a session of its own, off ``cpu``) holds the list
    of moved tasks: if the process that isolated the core dies inside the block (a
    SIGKILL, a crash), the guard restores them in its place.

    Parameters
    ----------
    cpu : int
        The core to clear.
    keep : iterable of int, optional
        Thread ids not to touch (default: the calling thread, normally the loop pinned
        to ``cpu``).
    tasks : iterable of int, optional
        Thread ids to consider instead of every task of the machine.

    Yields
    ------
    IsolationReport
        Counts of moved and unmovable tasks; with a ``note`` and nothing done on a
        platform without affinity control or a machine with one CPU.

    Examples
    --------
    >>> with isolate_cpu(0, tasks=[]) as report:  # consider no task: nothing moves
    ...     report.moved
    0
    """
    cpu = int(cpu)
    getaff = getattr(os, "sched_getaffinity", None)
    setaff = getattr(os, "sched_setaffinity", None)
    if getaff is None or setaff is None or not sys.platform.startswith("linux"):
        yield IsolationReport(cpu, note="no CPU affinity control on this platform")
        return
    if (os.cpu_count() or 1) < 2:
        yield IsolationReport(cpu, note="one CPU: nowhere to move the other tasks")
        return
    skip = {threading.get_native_id()} if keep is None else {int(t) for t in keep}
    chosen = None if tasks is None else [int(t) for t in tasks]
    guard: subprocess.Popen[str] | None = None
    moved: dict[int, _Moved] = {}
    counts = {"kernel": 0, "fixed": 0, "denied": 0}
    since = _boot_ticks()
    try:
        seen: set[int] = set(skip)
        for _ in range(_ISOLATE_PASSES if chosen is None else 1):
            fresh = [t for t in (_all_tids() if chosen is None else chosen) if t not in seen]
            if not fresh:
                break
            seen.update(fresh)
            for tid in fresh:
                _move(tid, cpu, moved, counts)
        guard = _start_guard(moved, since, cpu)
        yield IsolationReport(
            cpu,
            moved=len(moved),
            kernel_threads=counts["kernel"],
            fixed=counts["fixed"],
            denied=counts["denied"],
        )
    finally:
        _restore(moved, since)
        if guard is not None:
            _stop_guard(guard)


def _start_guard(moved: dict[int, _Moved], since: int, cpu: int) -> subprocess.Popen[str] | None:
    """A process that restores ``moved`` if this one dies first (None: nothing moved)."""
    if not moved:
        return None
    try:
        proc = subprocess.Popen(
            [sys.executable, "-I", "-S", os.path.abspath(__file__)],
            stdin=subprocess.PIPE,
            stdout=subprocess.DEVNULL,
            text=True,
            start_new_session=True,  # outlives a kill of this process group
        )
    except OSError:
        return None
    with contextlib.suppress(OSError):  # (it inherits the loop's pinned core)
        os.sched_setaffinity(proc.pid, set(range(os.cpu_count() or 1)) - {cpu})
    rows = [[tid, sorted(m.old), sorted(m.new), m.start] for tid, m in moved.items()]
    assert proc.stdin is not None
    try:
        proc.stdin.write(json.dumps({"since": since, "moved": rows}) + "\n")
        proc.stdin.flush()
    except OSError:  # the guard could not start: the block still restores normally
        return None
    return proc


def _stop_guard(proc: subprocess.Popen[str]) -> None:
    """Tell the guard the tasks are restored, and let it end."""
    assert proc.stdin is not None
    with contextlib.suppress(OSError):
        proc.stdin.write(json.dumps({"done": True}) + "\n")
        proc.stdin.close()
    try:
        proc.wait(30)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()


def _guard_main() -> None:
    """The guard process of :func:`isolate_cpu` (reads its standard input).

    First line: the moved tasks; then either ``{"done": true}`` (restored by the
    isolating process: nothing to do) or the end of the input (that process died:
    restore them here).
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is for the loop
    signal.signal(signal.SIGHUP, signal.SIG_IGN)  # so is a terminal's hang-up
    moved: dict[int, _Moved] = {}
    since = 0
    for line in sys.stdin:
        msg = json.loads(line)
        if msg.get("done"):
            return
        since = int(msg["since"])
        for tid, old, new, start in msg["moved"]:
            moved[int(tid)] = _Moved(frozenset(old), frozenset(new), start)
    _restore(moved, since)


def _move(tid: int, cpu: int, moved: dict[int, _Moved], counts: dict[str, int]) -> None:
    """Take ``cpu`` out of one task's affinity (counted in ``moved`` or ``counts``)."""
    try:
        old = frozenset(os.sched_getaffinity(tid))
    except OSError:  # ended (ProcessLookupError) or unreadable
        return
    if cpu not in old:
        return
    new = old - {cpu}
    if not new:
        counts["fixed"] += 1  # may run on this core only
        return
    info = _stat(tid)
    try:
        os.sched_setaffinity(tid, new)
    except ProcessLookupError:  # ended
        return
    except PermissionError:
        counts["denied"] += 1
        return
    except OSError:  # EINVAL: a per-CPU kernel thread (PF_NO_SETAFFINITY)
        counts["fixed"] += 1
        return
    try:
        now = frozenset(os.sched_getaffinity(tid))  # as the kernel stores it
    except OSError:
        return  # ended right after the move
    moved[tid] = _Moved(old, now, None if info is None else info.start)
    if info is not None and info.kernel:
        counts["kernel"] += 1


def _set_back(tid: int, m: _Moved) -> None:
    """The old affinity of ``m`` for ``tid`` if it still has ``m``'s new one."""
    try:
        if frozenset(os.sched_getaffinity(tid)) == m.new:  # else changed by someone else
            os.sched_setaffinity(tid, m.old)
    except OSError:  # ended, or the old set is no longer allowed
        pass


def _restore(moved: dict[int, _Moved], since: int) -> None:
    """Give the moved tasks, and the tasks they started, their old affinity back."""
    if not moved:
        return
    infos = {tid: (pid, _stat(tid)) for pid, tid in _all_tasks()}

    def same(tid: int, m: _Moved) -> bool:  # not a new task with a reused id
        info = infos.get(tid, (0, None))[1]
        return m.start is None or (info is not None and info.start == m.start)

    def origin(tid: int) -> _Moved | None:
        """The moved task a task descends from, for a task started inside the block."""
        for _ in range(64):  # a chain of tasks started inside the block, never a loop
            if tid in moved and same(tid, moved[tid]):
                return moved[tid]
            pid, info = infos.get(tid, (0, None))
            if info is None or info.start < since:
                return None
            tid = pid if tid != pid else info.ppid  # a thread's process, a process's parent
        return None

    for tid, (pid, info) in infos.items():
        if tid in moved or info is None or info.start < since:
            continue
        m = origin(pid if tid != pid else info.ppid)
        if m is not None:
            _set_back(tid, m)
    for tid, m in moved.items():
        if tid in infos and same(tid, m):
            _set_back(tid, m)
    moved.clear()


if __name__ == "__main__":
    _guard_main()
