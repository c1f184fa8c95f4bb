"""Real-time scheduling of the HiL loop: the ``realtime=`` option of :func:`run_hil`.

The loop's misses on a busy machine are preemptions: the operating system gives the
core to another process while the loop sleeps or computes. :func:`realtime_session`
prepares the calling thread (the loop) before the clock starts and undoes it after:

- ``SCHED_FIFO`` at a fixed priority (:func:`os.sched_setscheduler`; needs root or
  ``CAP_SYS_NICE`` / an ``RLIMIT_RTPRIO``): the loop preempts every ordinary process
  and is not preempted by them; the kernel's RT throttling (95 % per second by default)
  still keeps the machine alive. The process's other Python threads (the monitor's
  message-queue feeder, if any; the recorder writes from a process of its own) get
  SCHED_FIFO one priority lower: one of them preempted while holding the GIL would
  otherwise stall the loop (priority inversion);
- pinned to one core (:func:`os.sched_setaffinity`, the last allowed one);
  :func:`pick_cpu` gives other processes (the rig emulator, the recorder's writer) a
  different one;
- ``gc.collect()`` + ``gc.freeze()`` (the loop disables the collector itself);
- the process memory locked (``mlockall`` through :mod:`ctypes`) and the given buffers
  touched, so that the hot path takes no page faults;
- optionally (``isolate=True``, :func:`isolate_cpu`) every other movable task of the
  machine moved off the loop's core, and moved back afterwards.

Each step that the system refuses is skipped and noted (``RealtimeSession.notes``); the
notes go into the tick statistics (``TickStats.scheduling``) and the recording.

Modes (``realtime=``):

=============  ==================================================================
``"auto"``     paced; every step above, each falling back with a note (default;
               ``True`` means the same)
``"fifo"``     paced; as ``"auto"`` but SCHED_FIFO is required (an error otherwise)
``"spin"``     paced; pinned core, locked memory, frozen GC, but ordinary priority,
               and the loop busy-waits the whole period instead of sleeping. On a
               virtual machine a sleeping vCPU can take milliseconds to wake, and a
               SCHED_FIFO loop that never sleeps is throttled by the kernel, so this
               mode suits VMs with a core to spare (measured in docs/hil.md)
``"off"``      paced on the clock; the scheduling is left as it is
``"unpaced"``  ticks back to back, as fast as possible (``False`` means the same);
               only for rigs that are simulated in the same process
=============  ==================================================================
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import gc
import os
import resource
import sys
import threading
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mrsuspension.errors import MRSuspensionError, ValidationError, did_you_mean
from mrsuspension.hil._isolation import IsolationReport, _own_tids, isolate_cpu

__all__ = [
    "DEFAULT_PRIORITY",
    "PINNED_MODES",
    "REALTIME_MODES",
    "IsolationReport",
    "RealtimeSession",
    "check_isolate",
    "is_paced",
    "isolate_cpu",
    "normalise_mode",
    "pick_cpu",
    "realtime_session",
    "widen_affinity",
    "yield_loop_cpu",
]

#: accepted values of ``realtime=`` (besides True = "auto" and False = "unpaced")
REALTIME_MODES = ("auto", "fifo", "spin", "off", "unpaced")
#: SCHED_FIFO priority of the loop (1..99; the kernel's own threads run at 50 and 99)
DEFAULT_PRIORITY = 40
#: modes that pin the loop to a core (the ones ``isolate=True`` works with)
PINNED_MODES = ("auto", "fifo", "spin")
_MCL_CURRENT, _MCL_FUTURE = 1, 2


def normalise_mode(realtime: bool | str) -> str:
    """The mode name of a ``realtime=`` value.

    Raises
    ------
    ValidationError
        When the value is not a bool or one of :data:`REALTIME_MODES`.

    Examples
    --------
    >>> normalise_mode(True), normalise_mode(False), normalise_mode("FIFO")
    ('auto', 'unpaced', 'fifo')
    """
    if realtime is True:
        return "auto"
    if realtime is False:
        return "unpaced"
    if isinstance(realtime, str):
        mode = realtime.strip().lower()
        if mode in REALTIME_MODES:
            return mode
        hint = did_you_mean(mode, REALTIME_MODES)
        raise ValidationError(
            f"realtime must be one of {', '.join(REALTIME_MODES)} (or True/False); "
            f"got {realtime!r}.{hint}"
        )
    raise ValidationError(
        f"realtime must be one of {', '.join(REALTIME_MODES)} (or True/False); "
        f"got {type(realtime).__name__} {realtime!r}"
    )


def is_paced(realtime: bool | str) -> bool:
    """True when the ticks are released on the clock (every mode but ``"unpaced"``).

    Examples
    --------
    >>> is_paced("off"), is_paced(False)
    (True, False)
    """
    return normalise_mode(realtime) != "unpaced"


def pick_cpu(role: str = "loop") -> int | None:
    """The core for a role: the loop takes the last allowed core, others the first.

    None when the process may run on one core only (nothing to choose) or the platform
    has no affinity control.

    Examples
    --------
    >>> cpu = pick_cpu("emulator")
    >>> cpu is None or cpu >= 0
    True
    """
    getaff = getattr(os, "sched_getaffinity", None)
    if getaff is None:
        return None
    cpus = sorted(getaff(0))
    if len(cpus) < 2:
        return None
    return cpus[-1] if role == "loop" else cpus[0]


@contextlib.contextmanager
def yield_loop_cpu() -> Iterator[set[int] | None]:
    """Keep the calling thread, and what it starts meanwhile, off the loop's core.

    For the helpers around a loop (the monitor's server, a browser started for it): on a
    machine with few cores they would otherwise be scheduled on the core the loop spins
    or waits on and delay its ticks. Yields the CPUs allowed before (to hand to a loop
    process started from here, see :func:`widen_affinity`), or None when there is
    nothing to do (one core, or no affinity control). Linux applies affinity per
    thread: threads and processes started inside the block inherit it; the calling
    thread gets its old set back at the end.

    Examples
    --------
    >>> with yield_loop_cpu() as before:
    ...     inside = os.sched_getaffinity(0) if before else None
    >>> before is None or (pick_cpu("loop") not in inside and os.sched_getaffinity(0) == before)
    True
    """
    getaff = getattr(os, "sched_getaffinity", None)
    setaff = getattr(os, "sched_setaffinity", None)
    loop = pick_cpu("loop")
    if getaff is None or setaff is None or loop is None:
        yield None
        return
    before = set(getaff(0))
    try:
        setaff(0, before - {loop})
    except OSError:
        yield None
        return
    try:
        yield before
    finally:
        setaff(0, before)


def check_isolate(realtime: bool | str, isolate: bool) -> None:
    """Refuse ``isolate=True`` with a mode that does not pin the loop.

    Raises
    ------
    ValidationError
        When ``isolate`` is true and the mode is ``"off"`` or ``"unpaced"``.

    Examples
    --------
    >>> check_isolate("spin", True)
    >>> check_isolate("off", False)
    """
    if not isolate:
        return
    mode = normalise_mode(realtime)
    if mode not in PINNED_MODES:
        raise ValidationError(
            f"isolate needs a pinned loop: use realtime auto, fifo or spin (got {mode!r})"
        )


def widen_affinity(cpus: set[int] | None) -> None:
    """Allow the calling process the ``cpus`` again; None: no change.

    For a loop process started by a helper that yielded the loop's core
    (:func:`yield_loop_cpu`): it inherits the narrowed set and gets the full one back,
    so that it can pin itself to that core.

    Examples
    --------
    >>> before = os.sched_getaffinity(0) if hasattr(os, "sched_getaffinity") else None
    >>> widen_affinity(None)  # nothing to do
    >>> before is None or os.sched_getaffinity(0) == before
    True
    """
    setaff = getattr(os, "sched_setaffinity", None)
    if cpus and setaff is not None:
        with contextlib.suppress(OSError):
            setaff(0, set(cpus))


@dataclass
class RealtimeSession:
    """What :func:`realtime_session` did to the calling thread (and how to undo it).

    Attributes
    ----------
    mode : str
        The requested mode (:data:`REALTIME_MODES`).
    policy : str
        ``"SCHED_FIFO:<priority>"`` or ``"unchanged"``.
    cpu : int or None
        The core the thread was pinned to.
    memory_locked : bool
        Whether ``mlockall`` succeeded.
    gc_frozen : bool
        Whether ``gc.freeze()`` was applied.
    notes : list of str
        Steps refused by the system (and why).
    spin : bool
        The loop busy-waits for the whole period (``"spin"``).
    isolated : str or None
        With ``isolate=True``: what :func:`isolate_cpu` did to the pinned core
        (:meth:`IsolationReport.label`); None otherwise.
    """

    mode: str
    spin: bool = False
    policy: str = "unchanged"
    cpu: int | None = None
    memory_locked: bool = False
    gc_frozen: bool = False
    notes: list[str] = field(default_factory=list)
    isolated: str | None = None
    _undo: list[Any] = field(default_factory=list, repr=False)

    @property
    def paced(self) -> bool:
        """Whether the ticks are released on the clock."""
        return self.mode != "unpaced"

    def label(self) -> str:
        """One line for the statistics: mode, policy, core, memory lock and notes.

        Examples
        --------
        >>> RealtimeSession("off").label()
        'off (paced; scheduling unchanged)'
        """
        if self.mode == "unpaced":
            return "unpaced (as fast as possible, not real time)"
        if self.mode == "off":
            return "off (paced; scheduling unchanged)"
        parts = [self.policy]
        if self.spin:
            parts.append("busy-wait")
        if self.cpu is not None:
            parts.append(f"cpu {self.cpu}")
        if self.memory_locked:
            parts.append("mlockall")
        if self.gc_frozen:
            parts.append("gc frozen")
        text = f"{self.mode} ({', '.join(parts)})"
        if self.isolated:
            text += "; " + self.isolated
        if self.notes:
            text += "; " + "; ".join(self.notes)
        return text

    def describe(self) -> dict[str, Any]:
        """Plain data (for the recording's metadata)."""
        return {
            "mode": self.mode,
            "paced": self.paced,
            "spin": self.spin,
            "policy": self.policy,
            "cpu": self.cpu,
            "memory_locked": self.memory_locked,
            "gc_frozen": self.gc_frozen,
            "isolated": self.isolated,
            "notes": list(self.notes),
        }

    def restore(self) -> None:
        """Undo every step, most recent first (idempotent)."""
        while self._undo:
            undo = self._undo.pop()
            with contextlib.suppress(OSError):
                undo()


def _set_fifo(session: RealtimeSession, priority: int, required: bool) -> None:
    setsched = getattr(os, "sched_setscheduler", None)
    if setsched is None:
        msg = "SCHED_FIFO not available on this platform"
        if required:
            raise MRSuspensionError(f"realtime='fifo': {msg}; use realtime='auto' or 'off'")
        session.notes.append(msg)
        return
    old_policy = os.sched_getscheduler(0)
    old_param = os.sched_getparam(0)
    lo, hi = os.sched_get_priority_min(os.SCHED_FIFO), os.sched_get_priority_max(os.SCHED_FIFO)
    prio = min(max(int(priority), lo), hi)
    try:
        setsched(0, os.SCHED_FIFO, os.sched_param(prio))
    except OSError as exc:
        msg = f"SCHED_FIFO refused ({exc.strerror or exc}; needs root or CAP_SYS_NICE)"
        if required:
            raise MRSuspensionError(
                f"realtime='fifo': {msg}; use realtime='auto' or 'off'"
            ) from exc
        session.notes.append(msg)
        return
    session.policy = f"SCHED_FIFO:{prio}"
    session._undo.append(lambda: setsched(0, old_policy, old_param))
    # the process's other Python threads (a message-queue feeder...) one step below: a
    # thread preempted by an ordinary process while it holds the GIL would block the loop
    me = threading.get_native_id()
    helpers = 0
    for thread in threading.enumerate():
        tid = thread.native_id
        if tid is None or tid == me or not thread.is_alive():
            continue
        try:
            t_policy, t_param = os.sched_getscheduler(tid), os.sched_getparam(tid)
            setsched(tid, os.SCHED_FIFO, os.sched_param(max(lo, prio - 1)))
        except OSError:
            continue
        helpers += 1
        session._undo.append(lambda t=tid, p=t_policy, q=t_param: setsched(t, p, q))
    if helpers:
        session.policy += f" (+{helpers} thread{'s' if helpers > 1 else ''} at {max(lo, prio - 1)})"


def _pin(session: RealtimeSession, cpu: int | None) -> None:
    setaff = getattr(os, "sched_setaffinity", None)
    if setaff is None:
        session.notes.append("no CPU affinity control on this platform")
        return
    old = os.sched_getaffinity(0)
    target = pick_cpu("loop") if cpu is None else int(cpu)
    if target is None:
        return  # one core allowed: nothing to pin
    if target not in old:
        session.notes.append(f"cpu {target} not allowed (allowed: {sorted(old)})")
        return
    try:
        setaff(0, {target})
    except OSError as exc:
        session.notes.append(f"affinity refused ({exc.strerror or exc})")
        return
    session.cpu = target
    session._undo.append(lambda: setaff(0, old))


def _isolate(session: RealtimeSession) -> None:
    if session.cpu is None:
        session.notes.append("not isolated: the loop is not pinned to a core")
        return
    # the loop's own process stays as it is: its other threads (a message-queue feeder)
    # share the interpreter lock with the loop, and a thread that must take the lock from
    # a busy core delays the loop's handoff (docs/monitor.md: moving the former writer
    # thread off the loop's core made the deadlines worse)
    isolation = isolate_cpu(session.cpu, keep=_own_tids())
    report = isolation.__enter__()
    session._undo.append(lambda: isolation.__exit__(None, None, None))
    if report.note is not None:
        session.notes.append(report.label())
    else:
        session.isolated = report.label()


def _lock_memory(session: RealtimeSession) -> None:
    if not sys.platform.startswith("linux"):
        session.notes.append("mlockall not available on this platform")
        return
    name = ctypes.util.find_library("c")
    try:
        libc = ctypes.CDLL(name, use_errno=True)
    except OSError:
        session.notes.append("mlockall: C library not found")
        return
    soft, _ = resource.getrlimit(resource.RLIMIT_MEMLOCK)
    # future mappings too only when locking is unlimited (root or an infinite rlimit);
    # otherwise later allocations of a locked process could fail
    unlimited = os.geteuid() == 0 or soft == resource.RLIM_INFINITY
    flags = _MCL_CURRENT | _MCL_FUTURE if unlimited else _MCL_CURRENT
    if libc.mlockall(flags) != 0:
        err = ctypes.get_errno()
        session.notes.append(f"mlockall refused ({os.strerror(err)})")
        return
    session.memory_locked = True
    session._undo.append(libc.munlockall)


@contextlib.contextmanager
def realtime_session(
    realtime: bool | str = "auto",
    *buffers: np.ndarray,
    priority: int = DEFAULT_PRIORITY,
    cpu: int | None = None,
    isolate: bool = False,
) -> Iterator[RealtimeSession]:
    """Prepare the calling thread for the real-time loop; undo it on exit.

    Parameters
    ----------
    realtime : bool or str
        The mode (:data:`REALTIME_MODES`; True = ``"auto"``, False = ``"unpaced"``).
    *buffers : numpy.ndarray
        Arrays the loop will write: touched (every page written once) before the clock
        starts.
    priority : int
        SCHED_FIFO priority (clamped to the system's range).
    cpu : int, optional
        Core to pin the thread to (default: :func:`pick_cpu`).
    isolate : bool
        Move every other movable task of the machine off the pinned core for the
        session (:func:`isolate_cpu`; the threads of this process stay as they are),
        and back at the end. Needs a pinning mode (``"auto"``, ``"fifo"``, ``"spin"``);
        when the thread could not be pinned, noted and skipped.

    Yields
    ------
    RealtimeSession
        What was done (``label()`` for the statistics).

    Raises
    ------
    ValidationError
        For an unknown mode, or ``isolate`` with ``"off"`` or ``"unpaced"``.
    MRSuspensionError
        With ``"fifo"`` when SCHED_FIFO is not permitted.

    Examples
    --------
    >>> with realtime_session("off") as rt:
    ...     rt.paced, rt.policy
    (True, 'unchanged')
    """
    mode = normalise_mode(realtime)
    check_isolate(mode, isolate)
    session = RealtimeSession(mode)
    for buf in buffers:
        buf.fill(0.0)  # write every page before the clock starts
    try:
        if mode in ("auto", "fifo", "spin"):
            gc.collect()
            gc.freeze()
            session.gc_frozen = True
            session._undo.append(gc.unfreeze)
            _lock_memory(session)
            _pin(session, cpu)
            if isolate:
                _isolate(session)
            session.spin = mode == "spin"
            if not session.spin:
                _set_fifo(session, priority, required=mode == "fifo")
        yield session
    finally:
        session.restore()
