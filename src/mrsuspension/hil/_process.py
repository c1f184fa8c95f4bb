"""The HiL loop's process and signals: a loop in a process of its own, bound to its parent.

Part of the loop (:mod:`mrsuspension.hil.loop`, which re-exports these names): the
signals that stop a running loop the safe way (:data:`LOOP_SIGNALS`; their handlers
only request the stop, :class:`_Abort`, which the next tick takes), the binding of a
loop process to the process that started it (:func:`bind_to_parent`: its death stops
the loop), and starting, joining and stopping the loop's own process
(:func:`start_process`, :func:`_run_in_process`, :func:`_stop_loop`). The loop's entry
point (:func:`~mrsuspension.hil.loop.run_hil`) is passed in (``run``), so this module
does not import the loop.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from mrsuspension._pool import descendants, ensure_resource_tracker
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.hil._result import HilResult, load_result
from mrsuspension.hil.recorder import META_FILE, load_recording
from mrsuspension.hil.rig import Rig
from mrsuspension.hil.safety import SafetyLimits

__all__ = ["DEATH_SIGNAL", "LOOP_SIGNALS", "SIGNAL_REASONS", "STOP_TIMEOUT", "bind_to_parent"]

#: signals that stop a running loop the safe way (their handlers only request the stop)
LOOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
#: the stop reason of each of them
SIGNAL_REASONS: dict[int, str] = {
    signal.SIGINT: "interrupted (SIGINT, Ctrl-C)",
    signal.SIGTERM: "terminated (SIGTERM)",
    signal.SIGHUP: "terminal hung up (SIGHUP)",
}

#: settling allowance after the return ramp [s]
_SETTLE = 1.0


class _Abort:
    """A request to stop the loop the safe way, read by the loop every tick.

    Set by the loop's signal handlers (which never raise) and by its parent watch; the
    first request wins.
    """

    __slots__ = ("ending", "parent", "reason", "signum")

    def __init__(self, parent: int | None = None) -> None:
        self.reason = ""
        self.ending = ""
        self.signum: int | None = None
        self.parent = parent

    def request(self, reason: str, ending: str, signum: int | None = None) -> None:
        if not self.reason:
            self.reason, self.ending, self.signum = reason, ending, signum

    def orphaned(self) -> bool:
        """True (and the request made) when the bound parent process is gone."""
        if self.parent is None or os.getppid() == self.parent:
            return False
        self.request(_orphan_reason(self.parent), "orphaned")
        return True

    def on_signal(self, signum: int, _frame: Any) -> None:
        if signum == DEATH_SIGNAL:  # prctl(PR_SET_PDEATHSIG): the starting thread ended
            self.request(_orphan_reason(self.parent or 0), "orphaned")
        elif not self.orphaned():
            self.request(SIGNAL_REASONS.get(signum, f"signal {signum}"), "interrupted", signum)


def _orphan_reason(parent: int) -> str:
    return f"the command that started the loop ended (parent process {parent} gone)"


#: the signal the kernel sends a bound loop process when its parent ends (Linux)
DEATH_SIGNAL = signal.SIGUSR1
#: the parent process a loop process is bound to (:func:`bind_to_parent`)
_BOUND_PARENT: list[int] = []
#: ``PR_SET_PDEATHSIG`` of Linux ``prctl``
_PR_SET_PDEATHSIG = 1


def bind_to_parent(parent: int, death_signal: bool = True) -> None:
    """Bind this process's loops to ``parent``: when it ends, the loop stops the safe way.

    For a loop in a process of its own (``run_hil(process=True)``, the monitor's loop):
    every run of this process checks ``os.getppid()`` every few milliseconds and trips
    (ending ``"orphaned"``) once ``parent`` is gone, e.g. after a ``kill -9`` of the
    command; with ``death_signal`` (Linux) the kernel also sends :data:`DEATH_SIGNAL`
    (SIGUSR1) at once (``prctl(PR_SET_PDEATHSIG)``), which stops a loop that is still
    starting too. Only for a process started from ``parent``'s main thread (the kernel
    sends it when the starting thread ends).
    """
    _BOUND_PARENT[:] = [int(parent)]
    if death_signal and sys.platform.startswith("linux"):
        import ctypes

        with contextlib.suppress(OSError, AttributeError):
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(DEATH_SIGNAL), 0, 0, 0)


@contextlib.contextmanager
def _stop_requests(abort: _Abort) -> Iterator[None]:
    """SIGINT, SIGTERM and SIGHUP request the safe stop (``abort``) instead of raising.

    Main thread only (elsewhere nothing changes). A signal ignored when the block starts
    (SIGINT in a background job, SIGHUP under ``nohup``) stays ignored. The previous
    handlers come back at the end.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous: dict[int, Any] = {}
    bound = (DEATH_SIGNAL,) if abort.parent is not None else ()
    try:
        for s in (*LOOP_SIGNALS, *bound):
            old = signal.getsignal(s)
            if old == signal.SIG_IGN and s != signal.SIGTERM:
                continue
            previous[s] = signal.signal(s, abort.on_signal)
        yield
    finally:
        for s, old in previous.items():
            signal.signal(s, old if old is not None else signal.SIG_DFL)


# -- own process ----------------------------------------------------------------------------
#: seconds an interrupted ``hil run`` gives its loop process, beyond the longest return
#: ramp (``stroke / return_rate`` plus the settling allowance, 3 s with the default
#: limits), to write its stop record and end before it is terminated (the rig's own
#: watchdog takes over after that)
STOP_TIMEOUT = 1.5


def _stop_wait(limits: SafetyLimits | None) -> float:
    """How long a loop process may take to stop the safe way [s].

    Examples
    --------
    >>> _stop_wait(None)
    4.5
    """
    lim = limits or SafetyLimits()
    return lim.stroke / lim.return_rate + _SETTLE + STOP_TIMEOUT


#: set when the loop process's run has ended and its cleanup begins: a signal then no
#: longer raises (the safe stop is done; the cleanup keeps the recording)
_CLEANING: list[bool] = [False]


def _raise_interrupted(signum: int, frame: Any) -> None:
    from mrsuspension._pool import Interrupted, deliver_later, raise_is_lost

    if _CLEANING[0]:
        return
    if raise_is_lost(frame):  # e.g. inside Popen.__del__: raised there it is only printed
        deliver_later(signum)
        return
    raise Interrupted(signum)


def _child(
    run: Callable[..., Any],
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: str,
    kw: dict[str, Any],
    parent: int | None = None,
    death_signal: bool = False,
    recover: str | None = None,
) -> None:
    """The loop process: ``run`` (:func:`~mrsuspension.hil.loop.run_hil`) bound to its
    parent, quiet on signals.

    Exit status: 0 when the run ended through the loop (its stop record says how), 128 +
    the signal's number when a signal stopped it (after the safe stop), 2 when the run
    could not start (one ``error:`` line). When the parent is gone at the end (killed),
    the recording is kept where the next run cannot remove it (``recover``'s
    ``NAME.recovered``) and one line on stderr says so.
    """
    try:
        code = _child_run(run, target, rig, duration, rate, out, kw, parent, death_signal, recover)
    except KeyboardInterrupt as exc:  # landed between the run's end and the cleanup's flag
        code = 128 + int(getattr(exc, "signum", signal.SIGINT))
    sys.exit(code)


def _child_run(
    run: Callable[..., Any],
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: str,
    kw: dict[str, Any],
    parent: int | None,
    death_signal: bool,
    recover: str | None,
) -> int:
    """:func:`_child`'s work; its exit status."""
    if parent is not None:
        bind_to_parent(parent, death_signal)
    code = 0
    held = contextlib.ExitStack()
    try:  # (a signal held back while starting lands at the unblock: inside the try)
        for s in (*LOOP_SIGNALS, DEATH_SIGNAL):  # SIGINT was ignored, the others held back
            if s == signal.SIGINT or signal.getsignal(s) != signal.SIG_IGN:
                signal.signal(s, _raise_interrupted)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {*LOOP_SIGNALS, DEATH_SIGNAL})
        if recover is not None:  # a staging folder: no next run may remove it meanwhile
            from mrsuspension._output import staging_in_use

            held.enter_context(staging_in_use(out))
        run(target, rig, duration, rate, out, **kw)
    except KeyboardInterrupt as exc:  # after the safe stop, or before the loop started
        code = 128 + int(getattr(exc, "signum", signal.SIGINT))
    except MRSuspensionError as exc:  # the run could not start (e.g. no reply from the rig)
        print(f"error: {' '.join(str(exc).split())}", file=sys.stderr, flush=True)
        code = 2
    finally:
        _CLEANING[0] = True  # the loop has stopped: a later signal leaves the cleanup be
        if parent is not None and os.getppid() != parent:
            with contextlib.suppress(Exception):
                _orphaned_recording(Path(out), None if recover is None else Path(recover))
        held.close()
    return code


def _orphaned_recording(out: Path, recover: Path | None) -> None:
    """Keep the recording of a loop whose parent died, visibly, and say so on stderr."""
    if not (out / META_FILE).exists():
        return
    kept = out
    if recover is not None and out.resolve() != recover.resolve():
        from mrsuspension._output import keep_recovered

        kept = keep_recovered(out, recover)
    stop = load_recording(kept).stop
    print(
        f"hil run: {stop.get('reason', 'the loop did not finish')}; the rig was commanded to "
        f"mid-stroke with the current at 0; recording kept in {str(kept)!r}",
        file=sys.stderr,
        flush=True,
    )


def _new_process(
    run: Callable[..., Any],
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: Path,
    recover: str | Path | None,
    kw: dict[str, Any],
) -> multiprocessing.process.BaseProcess:
    """The loop's process (spawn), not started yet."""
    main = threading.current_thread() is threading.main_thread()
    return multiprocessing.get_context("spawn").Process(
        target=_child,
        args=(run, target, rig, duration, rate, str(out), kw, os.getpid(), main,
              None if recover is None else str(recover)),
        name="mrsus-hil-loop",
    )  # fmt: skip


def _start(proc: multiprocessing.process.BaseProcess) -> None:
    """Start ``proc`` with the loop's signals held back; a held SIGTERM or SIGHUP is
    raised again once it has started, so the caller stops it the safe way.

    The process starts with SIGINT ignored (kept through exec), so that a Ctrl-C while
    it imports prints no traceback; :func:`_child` handles it again before the loop
    starts. SIGINT, SIGTERM and SIGHUP are blocked meanwhile (the child inherits the
    mask), and SIGTERM's and SIGHUP's handlers here only record them: a signal taken by
    another thread of this process would otherwise run the handler in the middle of
    ``start()`` and cut the child's start-up data short (it then printed an ``EOFError``
    traceback). The resource tracker, which unblocks them when it starts, is started first.
    """
    ensure_resource_tracker()
    if threading.current_thread() is not threading.main_thread():
        proc.start()
        return
    held: list[int] = []
    previous = {s: signal.getsignal(s) for s in LOOP_SIGNALS}
    for s in (signal.SIGTERM, signal.SIGHUP):
        if previous[s] != signal.SIG_IGN:
            signal.signal(s, lambda signum, _frame: held.append(signum))
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {*LOOP_SIGNALS, DEATH_SIGNAL})
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        proc.start()
    finally:
        try:
            # SIGINT's handler back before the unblock: a Ctrl-C to the process group
            # while the child started is pending here too, and would be discarded if
            # SIGINT were still ignored at the unblock (the child then ended with 130 and
            # this process reported a failed start instead of the interruption)
            sigint = previous[signal.SIGINT]
            signal.signal(signal.SIGINT, sigint if sigint is not None else signal.SIG_DFL)
            signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        finally:
            for s in (signal.SIGTERM, signal.SIGHUP):
                handler = previous[s]
                signal.signal(s, handler if handler is not None else signal.SIG_DFL)
    if held:
        signal.raise_signal(held[0])


def start_process(
    run: Callable[..., Any],
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: Path,
    *,
    recover: str | Path | None = None,
    **kw: Any,
) -> multiprocessing.process.BaseProcess:
    """Start the loop in its own process (spawn) and return the process (not joined).

    The process is bound to this one (:func:`bind_to_parent`): if this process dies, the
    loop stops the safe way and keeps its recording (moved to ``recover``'s
    ``NAME.recovered`` when given).
    """
    proc = _new_process(run, target, rig, duration, rate, out, recover, kw)
    _start(proc)
    return proc


def _run_in_process(
    run: Callable[..., Any],
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: Path,
    recover: str | Path | None = None,
    **kw: Any,
) -> HilResult:
    proc = _new_process(run, target, rig, duration, rate, out, recover, kw)
    try:
        _start(proc)  # a signal held back while it starts is raised here
        proc.join()
    except BaseException as exc:  # Ctrl-C, SIGTERM, SIGHUP here: stop the loop the safe way
        signum = int(getattr(exc, "signum", signal.SIGINT))
        hup: Any = None
        if threading.current_thread() is threading.main_thread():
            hup = signal.signal(signal.SIGHUP, signal.SIG_IGN)  # the stop is bounded: let it end
        try:
            _stop_loop(
                proc, (out / META_FILE).exists(), wait=_stop_wait(kw.get("limits")), signum=signum
            )
        finally:
            if hup is not None:  # the caller's handler back (a Python session goes on)
                signal.signal(signal.SIGHUP, hup)
        raise
    code = proc.exitcode
    if code is not None and code - 128 in LOOP_SIGNALS and not (out / META_FILE).exists():
        # stopped by a Ctrl-C, SIGTERM or SIGHUP before its run began: a signal to the
        # process group whose copy here was lost (taken by another thread while SIGINT was
        # ignored for the child's start): the run was interrupted, not failed
        from mrsuspension._pool import Interrupted

        raise Interrupted(code - 128)
    if code == 2 and not (out / META_FILE).exists():
        raise MRSuspensionError("the HiL loop process could not start the run (see above)")
    try:
        return load_result(out)
    except (MRSuspensionError, ValidationError):
        if not (out / META_FILE).exists():
            raise MRSuspensionError(
                f"the HiL loop process ended with exit code {code} before its recording started"
            ) from None
    recording = load_recording(out)
    raise MRSuspensionError(
        f"the HiL loop process ended with exit code {code} before finishing; "
        f"the recording in {out} holds {len(recording)} rows"
    )


def _stop_loop(
    proc: multiprocessing.process.BaseProcess,
    started: bool,
    wait: float | None = None,
    signum: int = signal.SIGINT,
) -> None:
    """Stop a loop process: ``signum`` (it trips and ramps home), then SIGTERM, then SIGKILL.

    A terminal's Ctrl-C has already reached the loop (same process group); a SIGTERM sent
    to this process only has not, so the loop is asked here, and given ``wait`` seconds
    (default :func:`_stop_wait`: the longest return ramp plus :data:`STOP_TIMEOUT`) once
    it has ``started`` (its recording exists: before that the rig has only been commanded
    to rest, and the process is terminated at once). A loop that returns sooner ends
    sooner.
    """
    if started:
        with contextlib.suppress(OSError):
            if proc.is_alive() and proc.pid is not None:
                os.kill(proc.pid, signum)  # the signal this process got, or SIGINT
        proc.join(_stop_wait(None) if wait is None else wait)
    if proc.is_alive() and proc.pid is not None:
        # its recording writer drains and ends on SIGTERM too
        for pid in [proc.pid, *descendants(proc.pid)]:
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGTERM)
        proc.join(0.5)
    if proc.is_alive():
        proc.kill()
        proc.join(0.5)
