"""The monitored loop: :func:`~mrsuspension.hil.run_hil` with a rig, in its own process.

The monitor runs the real HiL loop (rig in the loop: ``simulated`` by default, ``ideal``
or ``udp://HOST:PORT``) in a separate process (``spawn``) with the loop's live hooks
(:class:`~mrsuspension.hil.loop.LoopHooks`):

- the **tap**: decimated rows (200 Hz) and the loop status (every 0.2 s) go to the
  server through a lock-free shared-memory ring (:class:`~mrsuspension.hil.tap.TapRing`,
  4096 rows = 20 s): no pickling and no helper thread in the loop's process, and a
  reader that falls behind loses the oldest rows (counted) rather than holding the loop;
  the rare messages (a change applied or refused, the trip, the end) go through a bounded
  :class:`multiprocessing.Queue` with ``put_nowait`` (full: dropped);
- **STOP**: a lock-free shared flag (:class:`~mrsuspension.hil.tap.StopFlag`) checked
  every tick; the loop takes its safety path (drive current 0 in that tick, actuator back to mid-stroke, reason
  ``"STOP pressed"`` recorded);
- **settings**: validated configurations prepared by the server
  (:class:`~mrsuspension.hil.loop.LiveChange`: what changed and the kernel arrays)
  through a bounded queue (4), applied by the loop between two ticks (a controller
  change ramps the current, a road change cross-fades).

Every tick is recorded by the HiL :class:`~mrsuspension.hil.recorder.Recorder` (its writer
process) into the run's recording directory.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import queue as queue_mod
import signal
from pathlib import Path
from typing import Any

from mrsuspension.hil.loop import CHANNELS
from mrsuspension.hil.tap import ChangeQueue, StopFlag, TapRing

__all__ = ["TAP_RATE", "LoopHandle", "loop_main"]

#: rate of the rows the loop sends to the server [Hz]
TAP_RATE = 200.0
#: the loop sends a batch of rows this often [s]
SEND_PERIOD = 0.05
#: and its status this often [s]
STATUS_PERIOD = 0.2


def loop_main(
    sim: Any,
    rig_spec: str,
    rate: float,
    duration: float,
    out: str,
    ramp_time: float,
    tap: Any,
    stop: Any,
    settings: Any,
    ring: Any = None,
    realtime: str = "auto",
    cpus: set[int] | None = None,
    isolate: bool = False,
    model_dt: float | None = None,
    parent: int | None = None,
    corner: str | None = None,
) -> None:
    """Body of the loop process: build the rig and run :func:`run_hil` with the hooks.

    Bound to the server's process (``parent``, :func:`~mrsuspension.hil.loop.bind_to_parent`):
    if the server dies, the loop stops the safe way. SIGINT, SIGTERM and SIGHUP (a
    terminal's Ctrl-C or hang-up reaches this process too) stop the loop the safe way;
    before or after the loop they end this process quietly, the end reported.

    Parameters
    ----------
    sim : Simulation
        The validated configuration to start with.
    rig_spec : str
        ``simulated``, ``ideal`` or ``udp://HOST:PORT``.
    rate, duration : float
        Loop rate [Hz] and run length [s].
    out : str
        Recording directory (the HiL recorder's format).
    ramp_time : float
        Current ramp after a live controller change [s].
    tap, stop, settings
        The bounded queue to the server, the STOP event and the settings queue.
    ring : TapRing, optional
        Shared-memory ring for the rows and the status (else they go through ``tap``).
    realtime : str
        How the loop is scheduled (:func:`~mrsuspension.hil.loop.run_hil`'s ``realtime``:
        ``auto``, ``fifo``, ``spin`` or ``off``).
    cpus : set of int, optional
        CPUs the loop may use, when the server that started it keeps off the loop's core
        (:func:`~mrsuspension.hil.realtime.yield_loop_cpu`).
    isolate : bool
        Move the machine's other movable tasks off the loop's core for the run
        (:func:`~mrsuspension.hil.loop.run_hil`'s ``isolate``).
    model_dt : float, optional
        Largest engine step [s] (:func:`~mrsuspension.hil.loop.run_hil`'s ``model_dt``;
        None: its default).
    corner : str, optional
        A half or full car's rig corner (:func:`~mrsuspension.hil.loop.run_hil`'s
        ``corner``).
    """
    from mrsuspension.engine.settings import DEFAULT_DT
    from mrsuspension.hil.loop import (
        LOOP_SIGNALS,
        LoopHooks,
        _raise_interrupted,
        _rig_damper,
        bind_to_parent,
        load_result,
        run_hil,
    )
    from mrsuspension.hil.realtime import widen_affinity
    from mrsuspension.hil.rigs import make_rig

    if parent is not None:
        bind_to_parent(parent, death_signal=False)  # started from a server thread
    for s in LOOP_SIGNALS:
        if s == signal.SIGINT or signal.getsignal(s) != signal.SIG_IGN:
            signal.signal(s, _raise_interrupted)
    widen_affinity(cpus)

    def end(info: dict[str, Any]) -> None:
        with contextlib.suppress(queue_mod.Full):
            tap.put(("end", info), timeout=2.0)

    try:
        rig = make_rig(rig_spec, _rig_damper(sim, corner))
        every = max(1, round(rate / TAP_RATE))
        hooks = LoopHooks(
            tap=tap,
            ring=ring,
            tap_every=every,
            tap_batch=every * max(1, round(SEND_PERIOD * TAP_RATE)),
            status_every=max(1, round(STATUS_PERIOD * rate)),
            stop=stop,
            settings=settings,
            poll_every=max(1, round(0.01 * rate)),
            ramp_time=ramp_time,
        )
        result = run_hil(
            sim, rig, duration=duration, rate=rate, out=out, hooks=hooks, realtime=realtime,
            isolate=isolate, model_dt=DEFAULT_DT if model_dt is None else model_dt,
            corner=corner,
        )  # fmt: skip
    except KeyboardInterrupt as exc:  # a signal: after the loop's safe stop, or before it
        try:
            stopped = load_result(out)
        except Exception:  # the loop had not started: the rig was only reset
            why = f"interrupted (signal {getattr(exc, 'signum', signal.SIGINT)})"
            end({"state": "error", "reason": why, "safe": True, "current": 0.0})
            return
        end({"state": "ended", "reason": stopped.reason, "tripped": stopped.tripped,
             "ending": stopped.ending, "current": 0.0, "safe": True,
             "summary": stopped.stats.summary()})  # fmt: skip
        return
    except Exception as exc:  # reported to the page, never raised in the server
        end({"state": "error", "reason": f"{type(exc).__name__}: {exc}", "safe": True})
        return
    stats = result.stats
    end(
        {
            "state": "ended",
            "reason": result.reason,
            "tripped": result.tripped,
            "ending": result.ending,
            "ticks": stats.ticks,
            "misses": stats.misses,
            "in_deadline": stats.in_deadline,
            "compute_max": stats.compute_max,
            "compute_mean": stats.compute_p50,
            "dropped": hooks.dropped,
            "current": 0.0,
            "safe": True,
            "summary": stats.summary(),
        }
    )


class LoopHandle:
    """The server's handle on one loop process.

    Parameters
    ----------
    sim : Simulation
        Validated configuration.
    rig : str
        Rig spec (``simulated``, ``ideal``, ``udp://HOST:PORT``).
    rate, duration : float
        Loop rate [Hz] and run length [s].
    out : path
        Recording directory.
    ramp_time : float
        Current ramp after a controller change [s].
    queue_size : int
        Capacity of the tap queue (messages; full -> the loop drops).
    realtime : str
        How the loop process is scheduled (``auto``, ``fifo``, ``spin`` or ``off``).
    cpus : set of int, optional
        CPUs the loop process may use (the server may keep off the loop's core).
    isolate : bool
        Move the machine's other movable tasks off the loop's core for the run.
    corner : str, optional
        A half or full car's rig corner: the tapped rows carry the body's channels too.
    """

    def __init__(
        self,
        sim: Any,
        rig: str,
        rate: float,
        duration: float,
        out: Path,
        ramp_time: float = 0.2,
        queue_size: int = 64,
        realtime: str = "auto",
        cpus: set[int] | None = None,
        isolate: bool = False,
        model_dt: float | None = None,
        corner: str | None = None,
    ) -> None:
        from mrsuspension._pool import ensure_resource_tracker
        from mrsuspension.hil.vehicle import BODY_CHANNELS

        ensure_resource_tracker()  # before the queues: it outlives a terminal's hang-up
        ctx = multiprocessing.get_context("spawn")
        self.out = Path(out)
        self.rate = float(rate)
        self.queue: Any = ctx.Queue(maxsize=queue_size)
        self.settings = ChangeQueue(4, ctx)  # the loop polls it without a system call
        self.stop_event = StopFlag(ctx)  # lock-free: the loop never waits on it
        width = len(CHANNELS) + (len(BODY_CHANNELS) if corner is not None else 0)
        self.ring = TapRing(width, capacity=4096, context=ctx)
        self.lost = 0
        self._seq = 0.0
        self.process = ctx.Process(
            target=loop_main,
            args=(
                sim, rig, float(rate), float(duration), str(self.out), float(ramp_time),
                self.queue, self.stop_event, self.settings, self.ring, realtime, cpus,
                isolate, model_dt, os.getpid(), corner,
            ),
            name="mrsus-monitor-loop",
            daemon=True,
        )  # fmt: skip
        self.process.start()

    def stop(self, code: int = 1) -> None:
        """STOP: the loop zeroes the current in the next tick and returns to mid-stroke
        (``code``: why, :data:`~mrsuspension.hil.loop.STOP_REASONS`)."""
        self.stop_event.set(code)

    def apply(self, change: Any) -> bool:
        """Queue a validated change for the loop; False when the queue is full."""
        try:
            self.settings.put_nowait(change)
        except queue_mod.Full:
            return False
        return True

    def drain(self, limit: int = 1000) -> list[tuple[str, Any]]:
        """New rows and status from the ring, then the queued messages (never blocks)."""
        items: list[tuple[str, Any]] = []
        rows, lost = self.ring.read()
        self.lost += lost
        if len(rows):
            items.append(("data", rows))
        status: dict[str, Any] = dict(self.ring.status())
        if status["seq"] != self._seq:
            self._seq = status["seq"]
            code = int(status.pop("state_code"))
            status["state"] = ("startup", "running", "returning", "tripped")[code]
            status["tripped"] = bool(status["tripped"])
            status["lost"] = self.lost
            for key in ("ticks", "misses", "dropped", "applied"):
                status[key] = int(status[key])
            items.append(("status", status))
        for _ in range(limit):
            try:
                items.append(self.queue.get_nowait())
            except queue_mod.Empty:
                break
        return items

    def alive(self) -> bool:
        """Whether the loop process still runs."""
        return self.process.is_alive()

    def join(self, timeout: float = 5.0) -> None:
        """Wait for the process; kill it when it does not end in time."""
        self.process.join(timeout)
        if self.process.is_alive():
            self.process.kill()
            self.process.join(1.0)
