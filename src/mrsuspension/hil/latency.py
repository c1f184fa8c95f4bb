"""A machine latency check for the HiL loop (``mrsus hil latency``), like ``cyclictest``.

:func:`measure_latency` runs only the loop's *pacing and scheduling*: the same
:func:`~mrsuspension.hil.realtime.realtime_session` as :func:`~mrsuspension.hil.run_hil`
(same modes), ticks released at ``t0 + k T`` by the same waiting rule, and per tick an
optional busy-wait of ``work`` seconds standing in for the loop's compute time (no model,
no rig, no recorder). It reports the loop's deadline statistics
(:class:`~mrsuspension.hil.loop.TickStats`) together with what the machine did meanwhile:
the CPU time the hypervisor stole from this virtual machine, the CPU time other processes
used, the longest stall and the number of stalls longer than one period.

A HiL run and its floor measured with the same rate, duration, mode and ``work`` about
the run's compute p50 tell the two apart: misses the floor has too come from the machine
(scheduling, hypervisor), misses only the loop has come from the loop (docs/hil.md,
"Checking a machine").
"""

from __future__ import annotations

import dataclasses
import math
import multiprocessing
import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.errors import MRSuspensionError, ValidationError, check_range
from mrsuspension.hil.loop import TickStats, _quiet_interpreter, _spin_window, _wait_until
from mrsuspension.hil.realtime import check_isolate, normalise_mode, realtime_session

__all__ = ["LATENCY_MODES", "LatencyResult", "count_stalls", "cpu_times", "measure_latency"]

#: scheduling modes of :func:`measure_latency` (the paced modes of ``run_hil``)
LATENCY_MODES = ("auto", "fifo", "spin", "off")
#: most ticks of one measurement (two float64 arrays of this length are preallocated)
MAX_TICKS = 20_000_000
#: progress is reported this often [s of ticks]
_PROGRESS_EVERY = 0.1

Progress = Callable[[int, int], None]


def cpu_times() -> tuple[float, float]:
    """CPU seconds of the whole machine so far: (busy, stolen by the hypervisor).

    Read from the first line of ``/proc/stat`` (Linux, all cores summed, in clock ticks
    of usually 10 ms): busy is every state but idle, iowait and steal; steal is the time
    a virtual CPU was ready to run but the hypervisor ran something else. NaN when
    ``/proc/stat`` cannot be read (not Linux).

    Examples
    --------
    >>> busy, steal = cpu_times()
    >>> (busy >= 0 and steal >= 0) or (math.isnan(busy) and math.isnan(steal))
    True
    """
    try:
        fields = Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]
        v = [int(x) for x in fields]
    except (OSError, ValueError):
        return math.nan, math.nan
    v += [0] * (8 - len(v))  # old kernels have fewer columns
    hz = os.sysconf("SC_CLK_TCK")
    busy = sum(v) - v[3] - v[4] - v[7]
    return busy / hz, v[7] / hz


def count_stalls(lateness: np.ndarray, period: float) -> int:
    """Stalls longer than one period in a paced run's per-tick release lateness.

    A stall is a time the loop's thread did not run: a start-to-start interval longer
    than two periods (the start more than one period past its spacing), or a first tick
    released more than a period late. Each stall counts once, however many late ticks
    follow it while the loop catches up.

    Examples
    --------
    >>> late = np.array([0, 6, 5, 4, 3, 2, 1, 0, 0, 1.5, 0.5, 0]) * 1e-3   # 2 stalls
    >>> count_stalls(late, 1e-3), int(np.count_nonzero(late > 1e-3))
    (2, 6)
    """
    lateness = np.asarray(lateness, dtype=float)
    if lateness.size == 0:
        return 0
    gaps = np.diff(lateness)  # start-to-start interval minus the period
    return int(np.count_nonzero(gaps > period)) + int(lateness[0] > period)


@dataclass(frozen=True)
class LatencyResult:
    """Outcome of :func:`measure_latency` (times in seconds).

    Attributes
    ----------
    stats : TickStats
        Deadline statistics of the empty (or ``work``-long) ticks, as a HiL run reports
        them.
    rate : float
        Tick rate [Hz].
    duration : float
        Requested length [s].
    work : float
        Busy work per tick [s] (0: empty ticks).
    wall : float
        Wall-clock length of the measurement [s].
    steal : float
        CPU time the hypervisor stole from this machine's cores during the run [s] (all
        cores; NaN where ``/proc/stat`` is missing).
    others : float
        CPU time used by other processes during the run [s] (all cores, this process's
        own time taken off).
    longest_stall : float
        Largest release lateness [s].
    stalls : int
        Stalls longer than one period (:func:`count_stalls`; each counted once).
    scheduling : dict
        What the real-time session did (:meth:`RealtimeSession.describe`).
    """

    stats: TickStats
    rate: float
    duration: float
    work: float
    wall: float
    steal: float
    others: float
    longest_stall: float
    stalls: int
    scheduling: dict[str, Any] = dataclasses.field(default_factory=dict)

    def describe(self) -> dict[str, Any]:
        """The result as plain data (``mrsus hil latency --json``).

        Examples
        --------
        >>> r = measure_latency(rate=1000, duration=0.02, realtime="off")
        >>> sorted(r.describe())[:4], r.describe()["stats"]["ticks"]
        (['duration', 'longest_stall', 'others', 'rate'], 20)
        """
        return {
            "rate": self.rate,
            "duration": self.duration,
            "work": self.work,
            "wall": self.wall,
            "steal": self.steal,
            "others": self.others,
            "longest_stall": self.longest_stall,
            "stalls": self.stalls,
            "stats": self.stats.describe(),
            "scheduling": dict(self.scheduling),
        }

    def summary(self) -> str:
        """One human-readable paragraph (microseconds and milliseconds).

        Examples
        --------
        >>> r = measure_latency(rate=1000, duration=0.02, realtime="off")
        >>> r.summary().startswith("machine latency at 1000 Hz for 0.02 s, empty ticks")
        True
        """
        s = self.stats
        us, ms = 1e6, 1e3
        load = f"{self.work * us:g} us of busy work per tick" if self.work > 0 else "empty ticks"
        if math.isnan(self.steal):
            cpu = "CPU steal unknown (no /proc/stat)"
        else:
            cores = self.others / self.wall if self.wall > 0 else math.nan
            cpu = (
                f"hypervisor steal {self.steal:.2f} s, other processes {self.others:.2f} s "
                f"of CPU ({cores:.2f} cores)"
            )
        return (
            f"machine latency at {self.rate:g} Hz for {self.duration:g} s, {load} "
            f"(scheduling {s.scheduling}): {100 * s.in_deadline:.3f} % of {s.ticks} ticks in "
            f"deadline ({s.misses} misses); lateness p50 {s.lateness_p50 * us:.1f} us, "
            f"p99 {s.lateness_p99 * us:.1f} us, max {s.lateness_max * us:.1f} us; "
            f"compute p50 {s.compute_p50 * us:.1f} us; {self.stalls} stalls longer than "
            f"one period ({s.period * ms:g} ms), longest {self.longest_stall * ms:.2f} ms; "
            f"{cpu} during the {self.wall:.1f} s run"
        )


def _check(
    rate: float, duration: float, realtime: bool | str, work: float, isolate: bool = False
) -> tuple[str, int]:
    """Validate the inputs; returns (mode, ticks)."""
    rate = float(check_range("rate", rate, 0.0, 100000.0, unit="Hz", low_inclusive=False))
    duration = float(check_range("duration", duration, 0.0, 1e6, unit="s", low_inclusive=False))
    period = 1.0 / rate
    check_range("work", work, 0.0, period, unit="s", high_inclusive=False)
    mode = normalise_mode(realtime)
    if mode not in LATENCY_MODES:
        raise ValidationError(
            f"realtime {realtime!r} has no deadlines to measure; valid: {', '.join(LATENCY_MODES)}"
        )
    check_isolate(mode, isolate)
    n = max(1, round(duration * rate))
    if n > MAX_TICKS:
        raise ValidationError(
            f"rate x duration = {n} ticks is too long for one measurement; "
            f"valid: at most {MAX_TICKS} ticks"
        )
    return mode, n


def measure_latency(
    rate: float = 1000.0,
    duration: float = 10.0,
    realtime: bool | str = "auto",
    work: float = 0.0,
    progress: Progress | None = None,
    *,
    process: bool = False,
    isolate: bool = False,
) -> LatencyResult:
    """Pace empty ticks as the HiL loop does and measure their deadlines.

    Parameters
    ----------
    rate : float
        Tick rate [Hz], in (0, 100000].
    duration : float
        Length [s], > 0 (at most :data:`MAX_TICKS` ticks).
    realtime : bool or str
        Scheduling, as for :func:`~mrsuspension.hil.run_hil`: ``"auto"`` (default;
        True), ``"fifo"``, ``"spin"`` or ``"off"`` (:data:`LATENCY_MODES`).
    work : float
        Busy-wait per tick [s], in [0, 1/rate): a stand-in for the loop's compute time
        (e.g. a HiL run's compute p50); 0 measures empty ticks.
    progress : callable, optional
        Called as ``progress(ticks_done, ticks_total)`` about every 0.1 s, between ticks
        (its own time shows as lateness of the next tick when it is longer than the
        slack; with ``process=True`` it runs in the calling process and costs the
        ticks nothing).
    process : bool
        Measure in a separate process (``spawn``), as ``mrsus hil run`` runs its loop.
    isolate : bool
        Move every other movable task off the measuring thread's core meanwhile, as
        ``run_hil(..., isolate=True)`` does (:func:`~mrsuspension.hil.realtime.isolate_cpu`);
        needs ``"auto"``, ``"fifo"`` or ``"spin"``.

    Returns
    -------
    LatencyResult
        Tick statistics, stolen and other CPU time, stalls.

    Raises
    ------
    ValidationError
        For a rate, duration or work out of range or an unknown or unpaced mode, or
        ``isolate`` with ``"off"``.
    MRSuspensionError
        With ``"fifo"`` when SCHED_FIFO is not permitted, or when the measuring process
        dies.

    Examples
    --------
    >>> r = measure_latency(rate=2000, duration=0.05, realtime="off", work=1e-4)
    >>> r.stats.ticks, r.stats.compute_p50 >= 1e-4
    (100, True)
    """
    mode, n = _check(rate, duration, realtime, work, isolate)
    rate, duration, work = float(rate), float(duration), float(work)
    if process:
        return _measure_in_process(rate, duration, mode, work, n, progress, isolate)
    period = 1.0 / rate
    compute = np.zeros(n)
    lateness = np.zeros(n)
    every = max(1, round(_PROGRESS_EVERY * rate))
    perf = time.perf_counter
    with realtime_session(mode, compute, lateness, isolate=isolate) as rt:
        spin = _spin_window(period, rt.spin)
        with _quiet_interpreter() as t0:
            busy0, steal0 = cpu_times()  # the machine's counters over the ticks only
            own0 = time.process_time()
            for k in range(n):
                release = t0 + k * period
                start = _wait_until(release, spin)
                end = start
                if work:
                    until = start + work
                    while end < until:
                        end = perf()
                end = perf()
                compute[k] = end - start
                lateness[k] = start - release
                if progress is not None and (k + 1) % every == 0:
                    progress(k + 1, n)
            wall = perf() - t0
            busy1, steal1 = cpu_times()
            own = time.process_time() - own0
    if progress is not None:
        progress(n, n)
    stats = TickStats.from_arrays(compute, lateness, period, True, scheduling=rt.label())
    return LatencyResult(
        stats=stats,
        rate=rate,
        duration=duration,
        work=work,
        wall=wall,
        steal=steal1 - steal0,
        others=max(0.0, (busy1 - busy0) - own),
        longest_stall=float(lateness.max()),
        stalls=count_stalls(lateness, period),
        scheduling=rt.describe(),
    )


# -- own process ----------------------------------------------------------------------------
def _child(
    conn: Any, counter: Any, rate: float, duration: float, mode: str, work: float, isolate: bool
) -> None:
    def report(done: int, total: int) -> None:
        counter.value = done

    try:
        result = measure_latency(rate, duration, mode, work, report, isolate=isolate)
    except MRSuspensionError as exc:
        conn.send(("error", str(exc)))
    else:
        conn.send(("ok", result))
    finally:
        conn.close()


def _measure_in_process(
    rate: float,
    duration: float,
    mode: str,
    work: float,
    n: int,
    progress: Progress | None,
    isolate: bool = False,
) -> LatencyResult:
    ctx = multiprocessing.get_context("spawn")
    counter = ctx.Value("q", 0, lock=False)
    recv, send = ctx.Pipe(duplex=False)
    proc = ctx.Process(
        target=_child,
        args=(send, counter, rate, duration, mode, work, isolate),
        name="mrsus-hil-latency",
    )
    proc.start()
    send.close()
    try:
        message: tuple[str, Any] | None = None
        while message is None:
            if recv.poll(0.1):
                try:
                    message = recv.recv()
                except EOFError:
                    break
            elif not proc.is_alive() and not recv.poll(0.0):
                break
            if progress is not None:
                progress(int(counter.value), n)
        proc.join()
    finally:
        if proc.is_alive():
            proc.terminate()
            proc.join(5)
        recv.close()
    if message is None:
        raise MRSuspensionError(
            f"the latency measuring process ended with exit code {proc.exitcode} before reporting"
        )
    kind, payload = message
    if kind == "error":
        raise MRSuspensionError(str(payload))
    result: LatencyResult = payload
    if progress is not None:
        progress(n, n)
    return result
