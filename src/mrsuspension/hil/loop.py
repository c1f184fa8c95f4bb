"""The real-time HiL loop: rig <-> quarter car (or one corner of a half or full car,
:mod:`~mrsuspension.hil.vehicle`), tick by tick, with deadline tracking.

Each tick (default 1 kHz):

1. read the rig (load-cell force, actuator displacement, measured coil current) and let
   the safety supervisor check it;
2. advance the quarter car minus its damper with the measured force held over the tick,
   through the engine's compiled step (:class:`~mrsuspension.engine.simulate.Stepper`,
   ``external_force=True``: the same physics and the same compiled controller as an
   offline :meth:`~mrsuspension.engine.simulate.Simulation.run`, in ``n_sub`` engine
   steps of at most ``model_dt`` per tick);
3. regulate the drive current (:class:`~mrsuspension.hil.driver.PICurrentDriver`);
4. command the actuator to the new stroke ``x_d`` (with ``v_d`` as feed-forward);
5. record every channel (:class:`~mrsuspension.hil.recorder.Recorder`).

Timing: each tick is released at ``t0 + k T`` (sleep until shortly before, then spin on
:func:`time.perf_counter`); its deadline is the next release. Compute time, lateness of
the release and misses are kept per tick; garbage collection is off during the run and
the recorder's writer runs in another process, behind a shared-memory ring (no second
thread in the loop's process).

On a trip (or at the end of the run) the drive current goes to 0 in the same tick and
the actuator is ramped back to mid-stroke before the loop stops.

Every ending takes that path (docs/hil.md, "Endings"): a safety trip, the operator's
STOP, an exception anywhere in a tick (reading the rig, the model, the controller,
commanding the rig, recording), a failed recording (a full disk: the recorder's writer
ended), SIGINT, SIGTERM or SIGHUP (their handlers, installed while the loop runs, only
request the stop, which the next tick takes) and, for a loop in a process of its own,
the death of the process that started it (:func:`bind_to_parent`). The stop record
(``stop.json``) says which (``ending``, ``reason``, ``signal``). When the rig cannot be
commanded at all (a dead link), the loop tries a bounded number of ticks, then ends and
leaves the rig to its own watchdog. A signal that stopped the loop is delivered again,
to the handler there was before, once the recording is closed.

Optional live hooks (:class:`~mrsuspension.hil.live.LoopHooks`, used by the browser
monitor; None keeps the loop as it is): a **tap** (decimated rows and status into a bounded queue, dropped when full),
an external **stop** event (the safety path: current 0 in the tick it is seen, actuator
back to mid-stroke, reason recorded) and a **settings** queue of new
:class:`~mrsuspension.hil.live.LiveChange` configurations applied between ticks (a
controller change ramps the drive current, an excitation change cross-fades the road).
"""

from __future__ import annotations

import contextlib
import dataclasses
import gc
import json
import math
import multiprocessing
import os
import shutil
import signal
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension._pool import descendants, ensure_resource_tracker
from mrsuspension.engine.settings import MAX_DURATION, RunSettings
from mrsuspension.engine.simulate import DEFAULT_DT, Simulation, SimulationDiverged
from mrsuspension.errors import MRSuspensionError, ValidationError, check_range
from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.live import (
    LiveChange,
    LoopHooks,
    _apply_settings,
    _live_status,
    _Road,
    live_chunk,
    tick_step,
)
from mrsuspension.hil.realtime import (
    check_isolate,
    normalise_mode,
    realtime_session,
    yield_loop_cpu,
)
from mrsuspension.hil.recorder import META_FILE, Recorder, Recording, load_recording
from mrsuspension.hil.rig import Rig, RigSample, SimulatedRig
from mrsuspension.hil.safety import SafetyLimits, SafetySupervisor, StartUp
from mrsuspension.hil.vehicle import BODY_CHANNELS, CornerPlant, check_corner, is_vehicle_simulation

__all__ = [
    "CHANNELS",
    "STATE_RETURN",
    "STATE_RUN",
    "STATE_STARTUP",
    "STATE_TRIPPED",
    "HilResult",
    "LiveChange",
    "LoopHooks",
    "TickStats",
    "bind_to_parent",
    "check_recording_memory",
    "load_result",
    "run_hil",
]

#: the stop reason recorded when the operator presses STOP (the safety path, not a trip
#: of a limit)
STOP_REASON = "STOP pressed"
#: the reason of a stop asked through the hooks' stop flag, by its code
#: (:meth:`~mrsuspension.hil.tap.StopFlag.code`; a flag without codes gives STOP_REASON)
STOP_REASONS = {1: STOP_REASON, 2: "the monitor shut down"}
_STOPPED = frozenset(STOP_REASONS.values())

#: signals that stop a running loop the safe way (their handlers only request the stop)
LOOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
#: the stop reason of each of them
SIGNAL_REASONS: dict[int, str] = {
    signal.SIGINT: "interrupted (SIGINT, Ctrl-C)",
    signal.SIGTERM: "terminated (SIGTERM)",
    signal.SIGHUP: "terminal hung up (SIGHUP)",
}

#: how a run ended (``HilResult.ending``, ``stop.json``'s ``ending``)
ENDINGS = (
    "completed",  # ran its duration and returned to mid-stroke
    "stopped",  # the operator's STOP
    "tripped",  # a safety limit, an interlock, the rig watchdog (a dead link), a diverged model
    "failed",  # an exception in a tick, or the rig could not be commanded
    "recording failed",  # the recorder's writer ended (a full disk)
    "interrupted",  # SIGINT, SIGTERM or SIGHUP (``signal``)
    "orphaned",  # the process that started the loop ended (bind_to_parent)
)

#: loop states (the ``state`` channel)
STATE_STARTUP, STATE_RUN, STATE_RETURN, STATE_TRIPPED = 0, 1, 2, 3

#: recorded channels and their units, in column order
CHANNELS: tuple[tuple[str, str], ...] = (
    ("time", "s"),  # loop time of the tick (release k T)
    ("state", "-"),  # 0 start-up, 1 running, 2 returning after the run, 3 tripped
    ("z_r", "m"),
    ("z_r_dot", "m/s"),
    ("z_s", "m"),
    ("z_u", "m"),
    ("z_s_dot", "m/s"),
    ("z_u_dot", "m/s"),
    ("z_s_ddot", "m/s^2"),
    ("z_u_ddot", "m/s^2"),
    ("x_d", "m"),  # model stroke (compression positive)
    ("v_d", "m/s"),
    ("F_dm", "N"),  # measured (load-cell) force
    ("F_d", "N"),  # force applied to the model (F_dm + start-up damping)
    ("F_T", "N"),
    ("i_d", "A"),  # controller's drive-current demand
    ("i_cmd", "A"),  # regulator output (D/A) to the amplifier
    ("i_dm", "A"),  # measured coil current
    ("x_cmd", "m"),  # stroke command to the actuator
    ("x_m", "m"),  # measured actuator displacement
    ("rig_time", "s"),
    ("compute", "s"),  # compute time of the tick
    ("lateness", "s"),  # release lateness of the tick
)
_NAMES = tuple(n for n, _ in CHANNELS)


def check_recording_memory(duration: float, rate: float, *, name: str = "duration") -> None:
    """Refuse a run whose recording (``duration`` x ``rate`` rows of every channel, 8
    bytes each) would not fit in memory when read back: more than half the RAM
    (:func:`mrsuspension.engine.settings.check_memory`).

    Raises
    ------
    ValidationError
        Naming ``name``, the duration, the estimate and the limit.

    Examples
    --------
    >>> check_recording_memory(10.0, 1000.0)  # 10 000 rows: a few MB
    >>> check_recording_memory(1e5, 1e5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: duration = 100000 s needs about ... GiB of memory ...
    """
    from mrsuspension.engine.settings import check_memory

    check_memory(
        duration,
        float(duration) * float(rate) * len(_NAMES),
        name=name,
        hint="shorten the duration or lower the loop rate",
    )


#: settling allowance after the return ramp [s]
_SETTLE = 1.0
#: spin (busy-wait) for the last part of each wait [s], at most this fraction of a period
_SPIN = 3e-4
_SPIN_FRACTION = 0.25
#: first release after the clock starts [s]
_START_DELAY = 2e-3
#: the recorder's ring holds this long a stretch of rows (how far its writer may lag) [s]
_RING_SECONDS = 10.0
#: how often the loop checks its recorder's writer and its parent process [s]
_WATCH_PERIOD = 0.02
#: how long the loop keeps trying to command a rig that refuses every command [s]
_COMMAND_GIVE_UP = 0.1


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


@dataclass(frozen=True)
class TickStats:
    """Deadline statistics of a run (times in seconds).

    Attributes
    ----------
    ticks : int
        Ticks run.
    period : float
        Nominal period [s].
    misses : int
        Ticks that ended after their deadline (the next release).
    in_deadline : float
        Fraction of ticks that met their deadline.
    compute_p50, compute_p99, compute_max : float
        Per-tick compute time.
    lateness_p50, lateness_p99, lateness_max : float
        Release lateness (start of the tick after its scheduled release).
    jitter : float
        Standard deviation of the start-to-start interval.
    realtime : bool
        Whether the loop was paced (False: ticks back to back, as fast as possible).
    jitter_max : float
        Largest deviation of a start-to-start interval from the period.
    scheduling : str
        How the loop was scheduled (:meth:`~mrsuspension.hil.realtime.RealtimeSession.label`:
        mode, policy, core, and any step the system refused).
    """

    ticks: int
    period: float
    misses: int
    in_deadline: float
    compute_p50: float
    compute_p99: float
    compute_max: float
    lateness_p50: float
    lateness_p99: float
    lateness_max: float
    jitter: float
    realtime: bool = True
    jitter_max: float = 0.0
    scheduling: str = ""

    @classmethod
    def from_arrays(
        cls,
        compute: np.ndarray,
        lateness: np.ndarray,
        period: float,
        realtime: bool,
        scheduling: str = "",
    ) -> TickStats:
        """Statistics of per-tick compute times and lateness.

        Examples
        --------
        >>> s = TickStats.from_arrays(np.full(4, 1e-4), np.array([0, 0, 2e-3, 0.0]), 1e-3, True)
        >>> s.misses, round(s.jitter_max, 6)
        (1, 0.002)
        """
        n = int(compute.size)
        if n == 0:
            nan = math.nan
            return cls(
                0, period, 0, 1.0, nan, nan, nan, nan, nan, nan, nan, realtime, nan, scheduling
            )
        end = lateness + compute
        misses = int(np.count_nonzero(end > period)) if realtime else 0
        starts = np.arange(n) * period + lateness
        intervals = np.diff(starts)
        jitter = float(np.std(intervals)) if n > 2 else 0.0
        jitter_max = float(np.max(np.abs(intervals - period))) if n > 1 and realtime else 0.0
        c50, c99 = np.percentile(compute, [50, 99])
        l50, l99 = np.percentile(lateness, [50, 99])
        return cls(
            ticks=n,
            period=period,
            misses=misses,
            in_deadline=1.0 - misses / n,
            compute_p50=float(c50),
            compute_p99=float(c99),
            compute_max=float(compute.max()),
            lateness_p50=float(l50),
            lateness_p99=float(l99),
            lateness_max=float(lateness.max()),
            jitter=jitter,
            realtime=realtime,
            jitter_max=jitter_max,
            scheduling=scheduling,
        )

    def describe(self) -> dict[str, Any]:
        """The statistics as plain data."""
        return dataclasses.asdict(self)

    def summary(self) -> str:
        """One human-readable paragraph (microseconds)."""
        us = 1e6
        if not self.realtime:
            return (
                f"{self.ticks} ticks at {1.0 / self.period:g} Hz UNPACED (as fast as possible, "
                f"not real time); compute p50 {self.compute_p50 * us:.1f} us, "
                f"p99 {self.compute_p99 * us:.1f} us, max {self.compute_max * us:.1f} us"
            )
        sched = f"; scheduling {self.scheduling}" if self.scheduling else ""
        return (
            f"{self.ticks} ticks at {1.0 / self.period:g} Hz: {100 * self.in_deadline:.3f} % "
            f"in deadline ({self.misses} misses); compute p50 {self.compute_p50 * us:.1f} us, "
            f"p99 {self.compute_p99 * us:.1f} us, max {self.compute_max * us:.1f} us; "
            f"lateness p50 {self.lateness_p50 * us:.1f} us, p99 {self.lateness_p99 * us:.1f} us, "
            f"max {self.lateness_max * us:.1f} us; jitter {self.jitter * us:.1f} us "
            f"(max {self.jitter_max * us:.1f} us){sched}"
        )


@dataclass
class HilResult:
    """Outcome of :func:`run_hil`.

    Attributes
    ----------
    recording : Recording
        Every channel at loop rate (:data:`CHANNELS`).
    stats : TickStats
        Deadline statistics.
    reason : str
        Why the run stopped (``"completed"`` or the trip reason).
    tripped : bool
        True when the safety supervisor stopped the run.
    out : Path or None
        The recording directory (None when recorded to a temporary one and removed).
    meta : dict
        The recording's metadata.
    ending : str
        How the run ended, one of :data:`ENDINGS` (``"completed"``, ``"tripped"``,
        ``"interrupted"``...).
    signal : int or None
        The signal that stopped the run (SIGINT, SIGTERM, SIGHUP), if any.
    """

    recording: Recording
    stats: TickStats
    reason: str
    tripped: bool
    out: Path | None = None
    meta: dict[str, Any] = field(default_factory=dict)
    ending: str = "completed"
    signal: int | None = None

    def running(self) -> np.ndarray:
        """Mask of the rows recorded while the model ran (start-up and running)."""
        return self.recording["state"] <= STATE_RUN

    def rms(self, channel: str) -> float:
        """RMS of a channel over the running part of the run."""
        x = self.recording[channel][self.running()]
        return float(np.sqrt(np.mean(x * x))) if x.size else math.nan

    @property
    def corner(self) -> str | None:
        """The rig corner of a half or full car run (None: a quarter car)."""
        vehicle = self.meta.get("vehicle")
        return str(vehicle["corner"]) if isinstance(vehicle, dict) else None

    def describe(self) -> dict[str, Any]:
        """Plain-data summary (for ``--json``); a vehicle run adds its rig ``corner`` and
        the RMS heave acceleration (``rms_body_acceleration`` is the body's at that corner)."""
        out = {
            "reason": self.reason,
            "tripped": self.tripped,
            "ending": self.ending,
            "signal": self.signal,
            "rows": len(self.recording),
            "out": str(self.out) if self.out else None,
            "stats": self.stats.describe(),
            "rms_body_acceleration": self.rms("z_s_ddot"),
        }
        if self.corner is not None:
            out["corner"] = self.corner
            out["rms_heave_acceleration"] = self.rms("heave_ddot")
        return out


# -- helpers --------------------------------------------------------------------------------
def _simulation_of(target: Any) -> Any:
    """The one run of ``target``: a quarter car's :class:`Simulation`, or a half or full
    car's :class:`~mrsuspension.engine.vehicle.VehicleSimulation` (the scenario's
    ``[vehicle] model`` says which)."""
    if isinstance(target, Simulation) or is_vehicle_simulation(target):
        return target
    from mrsuspension.scenario import Scenario

    if isinstance(target, str | Path):
        target = Scenario.load(target)
    if isinstance(target, Scenario):
        quarter = target.model == "quarter-car"
        sims = target.simulations() if quarter else target.vehicle_simulations()
        if len(sims) != 1:
            raise ValidationError(
                f"HiL runs one scenario at a time; this one is a sweep of {len(sims)} runs"
            )
        return sims[0]
    raise ValidationError(
        "run_hil needs a Simulation, a VehicleSimulation, a Scenario or a scenario path; "
        f"got {type(target).__name__}"
    )


def _rig_damper(sim: Any, corner: str | None = None) -> Any:
    """The damper model on the rig: the quarter car's, or the rig corner's of a vehicle."""
    if is_vehicle_simulation(sim):
        return sim.corner_simulation(check_corner(sim, corner)).damper
    return sim.damper


def _spin_window(period: float, spin_all: bool) -> float:
    """How long before each release the loop stops sleeping and spins [s].

    At most a quarter period (a SCHED_FIFO loop that never sleeps is throttled by the
    kernel); the whole period with ``spin_all`` (``realtime="spin"``: never sleep).

    Examples
    --------
    >>> _spin_window(1e-3, False), _spin_window(1e-4, False), _spin_window(1e-3, True)
    (0.0003, 2.5e-05, 0.001)
    """
    return period if spin_all else min(_SPIN, _SPIN_FRACTION * period)


@contextlib.contextmanager
def _quiet_interpreter() -> Iterator[float]:
    """Garbage collection off and a short thread switch interval while ticks run.

    Yields the clock time of the first release (2 ms from now); tick ``k`` is released
    at ``t0 + k T`` and its deadline is the next release. Both settings are restored
    on exit.
    """
    old_switch = sys.getswitchinterval()
    gc_was_enabled = gc.isenabled()
    gc.collect()
    gc.disable()
    sys.setswitchinterval(5e-4)
    try:
        yield time.perf_counter() + _START_DELAY
    finally:
        sys.setswitchinterval(old_switch)
        if gc_was_enabled:
            gc.enable()


def _wait_until(deadline: float, spin: float = _SPIN) -> float:
    """Sleep until ``spin`` before ``deadline``, then spin; returns the wake-up time."""
    perf = time.perf_counter
    now = perf()
    rem = deadline - now
    if rem > spin:
        time.sleep(rem - spin)
    now = perf()
    while now < deadline:
        now = perf()
    return now


def _default_rig(sim: Any, corner: str | None = None) -> SimulatedRig:
    return SimulatedRig(damper=_rig_damper(sim, corner))


# -- the loop -------------------------------------------------------------------------------
def run_hil(
    target: Any,
    rig: Rig | None = None,
    duration: float = 10.0,
    rate: float = 1000.0,
    out: str | Path | None = None,
    *,
    model_dt: float = DEFAULT_DT,
    limits: SafetyLimits | None = None,
    startup: StartUp | None = None,
    driver: PICurrentDriver | None = None,
    realtime: bool | str = True,
    isolate: bool = False,
    cap_current: bool = True,
    process: bool = False,
    on_stop: Callable[[HilResult], None] | None = None,
    hooks: LoopHooks | None = None,
    settings: RunSettings | None = None,
    recover: str | Path | None = None,
    corner: str | None = None,
) -> HilResult:
    """Run a scenario in the loop with a rig.

    Parameters
    ----------
    target : Simulation, VehicleSimulation, Scenario or path
        What to run (a scenario file is loaded; sweeps are refused). A half or full car
        (:class:`~mrsuspension.engine.vehicle.VehicleSimulation`, or a scenario with
        ``[vehicle] model = "half-car"`` or ``"full-car"``) runs with the damper of
        ``corner`` on the rig and the rest of the car simulated in the loop
        (:mod:`~mrsuspension.hil.vehicle`); the recording then holds that corner's
        signals under the quarter car's channel names and the body's
        (:data:`~mrsuspension.hil.vehicle.BODY_CHANNELS`).
    rig : Rig, optional
        The rig (default: a :class:`~mrsuspension.hil.rig.SimulatedRig` carrying the
        scenario's damper model, a vehicle's rig corner's).
    duration : float
        Run time [s] (the return to mid-stroke follows).
    rate : float
        Loop rate [Hz] (default 1 kHz).
    out : path, optional
        Recording directory; default: a temporary one, read back and removed.
    model_dt : float
        Largest engine step [s]; each tick runs ``ceil(T / model_dt)`` engine steps with the
        measured force held (default 1e-4, the offline default).
    limits : SafetyLimits, optional
        Trip limits (defaults: 0.3 A, +/-0.1 m, 1.5 m/s, 8.8 kN, 50 ms watchdog).
    startup : StartUp, optional
        Start-up sequence (default: 0.5 s, 500 N s/m fading out, current held at 0);
        :meth:`StartUp.none` to compare with offline runs.
    driver : PICurrentDriver, optional
        Current regulator (default K_P = 1, K_I = 3000, 12-bit, limited to the current
        limit); bypassed (clamp and D/A only) for a rig whose coil is instantaneous.
    realtime : bool or str
        Pacing and scheduling (:mod:`~mrsuspension.hil.realtime`): ``"auto"`` (or True,
        the default) paces the ticks on the clock with SCHED_FIFO, a pinned core and
        locked memory where permitted (noted in the statistics where not); ``"fifo"``
        requires SCHED_FIFO; ``"off"`` paces without touching the scheduling;
        ``"unpaced"`` (or False) runs the ticks back to back, as fast as possible (only
        for a :class:`~mrsuspension.hil.rig.SimulatedRig`: validation and tests).
    isolate : bool
        Move every other movable task of the machine off the loop's core for the run
        and back afterwards (:func:`~mrsuspension.hil.realtime.isolate_cpu`; the loop's
        own process stays as it is); what was moved is in the statistics' scheduling.
        Needs ``realtime`` ``"auto"``, ``"fifo"`` or ``"spin"``. Moving other users'
        tasks needs root or ``CAP_SYS_NICE``; if the loop is killed (SIGKILL), a guard
        process moves them back (docs/hil.md, "Isolating the loop's core").
    cap_current : bool
        Lower the simulation's ``max_current`` to the safety current limit (default), so
        that the controller cannot demand an over-current.
    process : bool
        Run the loop in its own process (``multiprocessing``, spawn); needs ``out``.
    on_stop : callable, optional
        Called with the result before it is returned.
    hooks : LoopHooks, optional
        Live tap, external stop and settings channel (the monitor's); None: none.
    settings : RunSettings, optional
        The run plan instead of ``duration`` and ``model_dt``: its ``duration`` (None:
        the excitation's own) and its ``dt`` as the engine step ``model_dt``. The loop
        rate stays ``rate`` (a property of the rig and its driver, not of the model);
        ``output_rate`` does not apply (every tick is recorded). Giving it with a
        ``duration`` or ``model_dt`` other than the defaults is an error.
    recover : path, optional
        With ``process=True``: where the loop process keeps its recording if this process
        dies during the run (``NAME.recovered`` beside ``recover``, see
        :func:`~mrsuspension._output.keep_recovered`); default: left in ``out``.
    corner : str, optional
        A half or full car's corner whose damper is on the rig (default: the first,
        ``front`` or ``front_left``); an error for a quarter car.

    Returns
    -------
    HilResult
        The recording, the tick statistics and why the run stopped.

    Notes
    -----
    SIGINT, SIGTERM or SIGHUP during the run stop it the safe way (in the main thread:
    current 0, back to mid-stroke, the recording closed with the reason); then the
    signal is delivered again to the handler there was before (Ctrl-C raises
    ``KeyboardInterrupt`` as usual), after ``on_stop``. A temporary recording (no
    ``out``) is then kept, since no result is returned.
    """
    if settings is not None:
        if (duration, model_dt) != (10.0, DEFAULT_DT):
            raise ValidationError("run_hil: give either settings or duration/model_dt, not both")
        model_dt = settings.dt
        duration = settings.duration_for(_simulation_of(target).excitation)
    if process:
        check_isolate(realtime, isolate)  # refused here, not in the child
        if out is None:
            raise ValidationError("run_hil(process=True) needs an output directory (out=...)")
        rate = float(check_range("rate", rate, 1.0, 100000.0, unit="Hz"))
        duration = float(
            check_range("duration", duration, 0.0, MAX_DURATION, unit="s", low_inclusive=False)
        )
        check_recording_memory(duration, rate)  # before the child starts
        return _run_in_process(
            target, rig, duration, rate, Path(out), recover, model_dt=model_dt, limits=limits,
            startup=startup, driver=driver, realtime=realtime, isolate=isolate,
            cap_current=cap_current, hooks=hooks, corner=corner,
        )  # fmt: skip
    mode = normalise_mode(realtime)
    check_isolate(mode, isolate)
    realtime = mode != "unpaced"
    sim = _simulation_of(target)
    vehicle = is_vehicle_simulation(sim)
    if vehicle:
        corner = check_corner(sim, corner)
    elif corner is not None:
        raise ValidationError(
            f"corner = {corner!r}: a quarter-car run has no corners (half and full cars do)"
        )
    limits = limits or SafetyLimits()
    startup = startup if startup is not None else StartUp()
    rate = float(check_range("rate", rate, 1.0, 100000.0, unit="Hz"))
    duration = float(
        check_range("duration", duration, 0.0, MAX_DURATION, unit="s", low_inclusive=False)
    )
    check_recording_memory(duration, rate)
    if cap_current and sim.max_current > limits.current:
        sim = dataclasses.replace(sim, max_current=limits.current)
    rig = rig if rig is not None else _default_rig(sim, corner)
    if not realtime and not isinstance(rig, SimulatedRig):
        raise ValidationError(
            f"realtime='unpaced' needs a rig simulated in this process (simulated or ideal); "
            f"a {type(rig).__name__} runs in real time: use realtime='auto', 'fifo', 'spin' or 'off'"
        )
    driver = driver or PICurrentDriver(current_limit=limits.current)
    period = 1.0 / rate
    dt = tick_step(rate, model_dt)
    n_sub = round(period / dt)
    n_ticks = max(1, round(duration * rate))
    plant: CornerPlant | None = None
    if vehicle:  # the whole car, one corner outside; every wheel's road for the whole run
        assert corner is not None
        plant = CornerPlant(sim, corner, dt, n_sub, n_ticks)
        stepper: Any = plant
        road_src: _Road | None = None  # the plant holds the roads
        z0, zd0 = plant.road_at(0)
        road, road_v = [z0], [zd0]
    else:
        stepper = sim.stepper(dt, external_force=True)
        # the whole run's road at once; with live hooks (the excitation can change between
        # ticks) one tick at a time, or a few for an excitation without a compiled grid
        if hooks is None:
            road_src = _Road(sim.excitation, n_sub, dt, n_ticks)
        else:
            road_src = _Road(sim.excitation, n_sub, dt, live_chunk(n_sub), fast_chunk=1)
        road, road_v = road_src.block(0)
        if hooks is not None:
            road_src.warm_up()
    max_return = limits.stroke / limits.return_rate + 2 * _SETTLE
    n_max = n_ticks + math.ceil(max_return * rate) + 1

    # warm-up: compile (or load) every kernel before the clock starts
    rig.reset(period)
    rig.command(0.0, 0.0, 0.0)
    rig.read()
    if plant is not None:
        plant.tick(0, 0.0)
        plant.reset()
    else:
        stepper.step(road[0], road_v[0], damper_force=0.0)
        stepper.reset(road[0], road_v[0])
    rig.reset(period)
    driver.reset(period)
    supervisor = SafetySupervisor(limits, link_status=rig.link_status)

    tmp_dir: Path | None = None
    if out is None:
        tmp_dir = Path(tempfile.mkdtemp(prefix="mrsus-hil-"))
        rec_dir = tmp_dir
    else:
        rec_dir = Path(out)
    meta = {
        "rate": rate,
        "period": period,
        "duration": duration,
        "model_dt": dt,
        "substeps": n_sub,
        "realtime": mode,
        "isolate": bool(isolate),
        "paced": realtime,
        "scenario": sim.describe(),
        **({"vehicle": plant.describe()} if plant is not None else {}),
        "rig": rig.describe(),
        "limits": limits.describe(),
        "startup": dataclasses.asdict(startup),
        "driver": dataclasses.asdict(driver),
    }
    channels = CHANNELS + BODY_CHANNELS if plant is not None else CHANNELS
    names = tuple(n for n, _ in channels)
    abort = _Abort(_BOUND_PARENT[0] if _BOUND_PARENT else None)
    compute = np.zeros(n_max)
    lateness = np.zeros(n_max)
    # from here on SIGINT, SIGTERM and SIGHUP only request the safe stop
    with _stop_requests(abort):
        with yield_loop_cpu():  # the recorder's writer process keeps off the loop's core
            recorder = Recorder(
                rec_dir,
                names,
                units=dict(channels),
                buffer_rows=max(16384, round(_RING_SECONDS * rate)),
                wait=not realtime,  # unpaced: wait for the writer rather than lose rows
                meta=meta,
            )
        try:
            try:
                if hooks is not None:  # a first message before the clock starts (a queue's feeder)
                    hooks.send("started", {"rate": rate, "ticks": n_ticks})
                # scheduling hook (hil/realtime.py)
                with realtime_session(mode, compute, lateness, isolate=isolate) as rt:
                    if rt.spin and hasattr(rig, "spin"):
                        rig.spin = True  # a network rig polls for its replies too
                    reason, ticks, ending = _loop(
                        stepper, rig, driver, supervisor, startup, recorder, road, road_v,
                        n_ticks, n_max, n_sub, period, realtime, compute, lateness, hooks,
                        road_src, rt.spin, abort, plant,
                    )  # fmt: skip
                stats = TickStats.from_arrays(
                    compute[:ticks], lateness[:ticks], period, realtime, scheduling=rt.label()
                )
            except BaseException as exc:  # outside the ticks: the recording says so
                with contextlib.suppress(MRSuspensionError, OSError):
                    recorder.close(
                        {
                            "reason": f"the loop failed: {type(exc).__name__}: {exc}",
                            "ending": "failed",
                            "tripped": True,
                        }
                    )
                raise
            meta["scheduling"] = rt.describe()
            stop = {
                "reason": reason,
                "ending": ending,
                "signal": abort.signum,
                "tripped": supervisor.tripped,
                "trip_time": supervisor.trip_time if supervisor.tripped else None,
                "stats": stats.describe(),
                "scheduling": rt.describe(),
            }
            try:
                recorder.close(stop)
            except MRSuspensionError:
                if ending != "recording failed":  # the loop saw it: said in the stop record
                    raise
        finally:
            rig.close()
    if hooks is not None:
        hooks.send("status", _status(supervisor, "ended", reason, ticks, stats, hooks))
    recording = load_recording(rec_dir)
    keep = tmp_dir is not None and abort.signum is not None  # the caller gets no result
    if tmp_dir is not None and not keep:
        shutil.rmtree(tmp_dir, ignore_errors=True)
    result = HilResult(
        recording=recording,
        stats=stats,
        reason=reason,
        tripped=supervisor.tripped,
        out=None if tmp_dir is not None and not keep else rec_dir,
        meta=meta,
        ending=ending,
        signal=abort.signum,
    )
    if on_stop is not None:
        on_stop(result)
    if abort.signum is not None:  # the rig is home and the recording closed: deliver it
        signal.raise_signal(abort.signum)
    return result


def _loop(
    stepper: Any,
    rig: Rig,
    driver: PICurrentDriver,
    supervisor: SafetySupervisor,
    startup: StartUp,
    recorder: Recorder,
    road: list[float],
    road_v: list[float],
    n_ticks: int,
    n_max: int,
    n_sub: int,
    period: float,
    realtime: bool,
    compute: np.ndarray,
    lateness: np.ndarray,
    hooks: LoopHooks | None,
    road_src: _Road | None,
    spin_all: bool = False,
    abort: _Abort | None = None,
    plant: CornerPlant | None = None,
) -> tuple[str, int, str]:
    """The hot loop; returns (stop reason, ticks run, ending).

    Anything a tick raises trips the supervisor (ending ``"failed"``), and the rig is
    still commanded: current 0, back to mid-stroke. So do an abort request (a signal, the
    parent's death) and a failed recording. With a ``plant`` (a half or full car) the
    model advances a whole tick in one call and every row gets the body's channels.
    """
    perf = time.perf_counter
    step: Any = stepper.step if plant is None else None
    read = rig.read
    command = rig.command
    append = recorder.append
    writer_failure = recorder.failure
    check_sample = supervisor.check_sample
    check_command = supervisor.check_command
    lim = supervisor.limits
    direct = rig.ideal_current
    ramp_step = lim.return_rate * period
    settle_ticks = math.ceil(_SETTLE / period)
    startup_ticks = math.ceil(startup.duration / period - 1e-9)
    hold_current = startup.hold_current
    home_tol = max(2e-3, 0.02 * lim.stroke)
    spin = _spin_window(period, spin_all)
    abort = abort if abort is not None else _Abort()
    watch_every = max(1, round(_WATCH_PERIOD / period))
    give_up = max(3, math.ceil(_COMMAND_GIVE_UP / period))

    state = STATE_STARTUP if startup_ticks > 0 else STATE_RUN
    reason = "completed"
    ending = "completed"
    x_cmd = 0.0
    v_cmd = 0.0
    i_out = 0.0
    i_d = 0.0
    fd = 0.0
    settle = 0
    out = {"z_s": 0.0, "z_u": 0.0, "z_s_dot": 0.0, "z_u_dot": 0.0, "z_s_ddot": 0.0}
    out.update({"z_u_ddot": 0.0, "x_d": 0.0, "v_d": 0.0, "F_T": 0.0, "i_d": 0.0})
    plant_tick = plant.tick if plant is not None else None
    body = tuple(n for n, _ in BODY_CHANNELS) if plant is not None else ()
    out.update(dict.fromkeys(body, 0.0))
    v_d = 0.0
    zr_now = road[0]
    zrd_now = road_v[0]
    sample: Any = RigSample(0.0, 0.0, 0.0, math.nan)  # until the first reading
    # live hooks (None: none of this runs)
    hooked = hooks is not None
    hk = hooks if hooks is not None else LoopHooks()
    stop_set = hk.stop.is_set if hk.stop is not None else None
    stop_code = getattr(hk.stop, "code", lambda: 1)
    k_road = 0
    ramp_left = 0
    ramp_step_i = 0.0
    last_demand = 0.0
    demand = 0.0
    pending: list[tuple[float, ...]] = []
    refused = 0  # ticks in a row whose command the rig refused
    recording = True

    def trip(why: str, how: str, t: float) -> None:
        nonlocal state, reason, ending, i_out, last_demand
        if state != STATE_TRIPPED:
            supervisor.trip(why, t)
            state = STATE_TRIPPED
            reason, ending = supervisor.reason, how
        i_out = 0.0  # current to 0 in the tick of the trip
        with contextlib.suppress(Exception):
            driver.off()
        last_demand = 0.0

    k = 0
    with _quiet_interpreter() as t0:
        while k < n_max:
            release = t0 + k * period
            start = _wait_until(release, spin) if realtime else perf()
            t = k * period
            done = False
            try:
                if k % watch_every == 0:
                    abort.orphaned()
                    if recording and (failure := writer_failure()) is not None:
                        recording = False
                        trip(f"recording failed: {failure}", "recording failed", t)
                if abort.reason and state <= STATE_RUN:
                    trip(abort.reason, abort.ending, t)
                if hooked and state <= STATE_RUN and k % hk.poll_every == 0:
                    ramp = _apply_settings(hk, stepper, road_src, supervisor, t, period)
                    if ramp and road_src is not None:
                        ramp_left = ramp
                        ramp_step_i = lim.current * period / hk.ramp_now
                        k_road = -road_src.chunk  # the new road from this tick on
                sample = read()
                active = state <= STATE_RUN
                if active and k >= n_ticks:
                    state = STATE_RETURN
                    active = False
                    i_out = driver.off()
                if active:
                    try:
                        if stop_set is not None and stop_set():
                            supervisor.trip(STOP_REASONS.get(stop_code(), STOP_REASON), t)
                            tripped = True
                        else:
                            tripped = check_sample(
                                t, sample.force, sample.displacement, sample.current,
                                sample.timestamp,
                            )  # fmt: skip
                        if not tripped:
                            c = startup.damping_at(t) if state == STATE_STARTUP else 0.0
                            if plant_tick is not None:  # a vehicle: the whole tick compiled
                                out = plant_tick(k, sample.force, c)
                                v_d = out["v_d"]
                                fd = out["F_d"]
                                zr_now = out["z_r"]
                                zrd_now = out["z_r_dot"]
                            else:
                                if road_src is not None and k - k_road >= road_src.chunk:
                                    k_road = k
                                    road, road_v = road_src.block(k)
                                j = 2 * n_sub * (k - k_road)
                                for _ in range(n_sub):
                                    fd = sample.force + c * v_d
                                    out = step(
                                        road[j], road_v[j],
                                        road_mid=(road[j + 1], road_v[j + 1]),
                                        road_end=(road[j + 2], road_v[j + 2]),
                                        damper_force=fd,
                                    )  # fmt: skip
                                    v_d = out["v_d"]
                                    j += 2
                                zr_now = road[j]
                                zrd_now = road_v[j]
                            i_d = out["i_d"]
                            if state == STATE_STARTUP and k + 1 >= startup_ticks:
                                state = STATE_RUN
                            demand = 0.0 if (state == STATE_STARTUP and hold_current) else i_d
                            if ramp_left:  # after a controller change: slew-limited demand
                                ramp_left -= 1
                                if demand > last_demand + ramp_step_i:
                                    demand = last_demand + ramp_step_i
                                elif demand < last_demand - ramp_step_i:
                                    demand = last_demand - ramp_step_i
                            last_demand = demand
                            tripped = check_command(t, out["x_d"], v_d, demand)
                            if not tripped:
                                x_cmd = out["x_d"]
                                v_cmd = v_d
                                if state == STATE_STARTUP and hold_current:
                                    i_out = driver.off()
                                elif direct:
                                    i_out = driver.direct(demand)
                                else:
                                    i_out = driver.update(
                                        demand, sample.current * driver.sense_resistance
                                    )
                    except SimulationDiverged as exc:
                        supervisor.trip(f"vehicle model diverged: {exc}", t)
                        tripped = True
                    except ValidationError as exc:  # a live excitation gave non-finite values
                        supervisor.trip(str(exc), t)
                        tripped = True
                    if tripped:
                        how = "stopped" if supervisor.reason in _STOPPED else "tripped"
                        trip(supervisor.reason, how, t)
            except Exception as exc:  # anywhere in the tick: a trip, and the rig still goes home
                trip(f"the loop failed at t = {t:.4f} s: {type(exc).__name__}: {exc}", "failed", t)
            if state >= STATE_RETURN:
                # ramp back to mid-stroke at the return rate, coil off
                i_out = 0.0
                if x_cmd > ramp_step:
                    x_cmd -= ramp_step
                    v_cmd = -lim.return_rate
                elif x_cmd < -ramp_step:
                    x_cmd += ramp_step
                    v_cmd = lim.return_rate
                else:
                    x_cmd = 0.0
                    v_cmd = 0.0
                    settle += 1
                    done = abs(sample.displacement) < home_tol or settle >= settle_ticks
            try:
                command(x_cmd, i_out, v_cmd)
                refused = 0
            except Exception as exc:  # a dead link: keep trying, bounded
                refused += 1
                trip(f"the rig could not be commanded: {type(exc).__name__}: {exc}", "failed", t)
                if refused >= give_up:
                    reason += (
                        f"; gave up commanding the rig after {refused} refused commands "
                        "(its own watchdog takes over)"
                    )
                    done = True
            end = perf()
            late = start - release if realtime else 0.0
            row = _row(t, state, zr_now, zrd_now, out, sample, fd, i_d, i_out, x_cmd,
                       end - start, late)  # fmt: skip
            if body:
                row += tuple([out[n] for n in body])
            compute[k] = end - start
            lateness[k] = late
            k += 1
            if recording:
                try:
                    append(row)
                except Exception as exc:  # an unpaced run waits for a writer that ended
                    recording = False
                    trip(f"recording failed: {exc}", "recording failed", t)
            try:
                if hooked:  # the tap: after the tick's work, never waiting
                    if done or k % hk.tap_every == 0:
                        hk.row(row, pending)
                    if (done or k % hk.tap_batch == 0) and pending:
                        hk.send("data", pending)
                        pending = []
                    if not done and (
                        k % hk.status_every == 0 or (state == STATE_TRIPPED and not hk._trip_sent)
                    ):
                        hk.status(_live_status(hk, supervisor, state, k, compute, lateness,
                                               period, i_out))  # fmt: skip
            except Exception as exc:  # the live tap failed: a trip too
                trip(f"the loop failed at t = {t:.4f} s: {type(exc).__name__}: {exc}", "failed", t)
            if done:
                return reason, k, ending
        if state == STATE_TRIPPED:
            return reason, k, ending
        return f"{reason}; actuator did not settle at mid-stroke", k, ending


def _status(
    supervisor: SafetySupervisor,
    state: str,
    reason: str,
    ticks: int,
    stats: TickStats,
    hooks: LoopHooks,
) -> dict[str, Any]:
    return {
        "state": state,
        "reason": reason,
        "ticks": ticks,
        "misses": stats.misses,
        "in_deadline": stats.in_deadline,
        "compute_mean": stats.compute_p50,
        "compute_max": stats.compute_max,
        "tripped": supervisor.tripped,
        "current": 0.0,
        "safe": True,
        "dropped": hooks.dropped,
        "applied": hooks.applied,
    }


def _row(
    t: float,
    state: int,
    zr: float,
    zrd: float,
    out: dict[str, float],
    sample: Any,
    fd: float,
    i_d: float,
    i_out: float,
    x_cmd: float,
    compute: float,
    late: float,
) -> tuple[float, ...]:
    return (
        t, float(state), zr, zrd, out["z_s"], out["z_u"], out["z_s_dot"], out["z_u_dot"],
        out["z_s_ddot"], out["z_u_ddot"], out["x_d"], out["v_d"], sample.force, fd, out["F_T"],
        i_d, i_out, sample.current, x_cmd, sample.displacement, sample.timestamp, compute, late,
    )  # fmt: skip


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


def _raise_interrupted(signum: int, _frame: Any) -> None:
    from mrsuspension._pool import Interrupted

    raise Interrupted(signum)


def _child(
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
    """The loop process: :func:`run_hil` bound to its parent, quiet on signals.

    Exit status: 0 when the run ended through the loop (its stop record says how), 128 +
    the signal's number when a signal stopped it (after the safe stop), 2 when the run
    could not start (one ``error:`` line). When the parent is gone at the end (killed),
    the recording is kept where the next run cannot remove it (``recover``'s
    ``NAME.recovered``) and one line on stderr says so.
    """
    if parent is not None:
        bind_to_parent(parent, death_signal)
    for s in (*LOOP_SIGNALS, DEATH_SIGNAL):  # SIGINT was ignored, the others held back
        if s == signal.SIGINT or signal.getsignal(s) != signal.SIG_IGN:
            signal.signal(s, _raise_interrupted)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {*LOOP_SIGNALS, DEATH_SIGNAL})
    code = 0
    held = contextlib.ExitStack()
    try:
        if recover is not None:  # a staging folder: no next run may remove it meanwhile
            from mrsuspension._output import staging_in_use

            held.enter_context(staging_in_use(out))
        run_hil(target, rig, duration, rate, out, **kw)
    except KeyboardInterrupt as exc:  # after the safe stop, or before the loop started
        code = 128 + int(getattr(exc, "signum", signal.SIGINT))
    except MRSuspensionError as exc:  # the run could not start (e.g. no reply from the rig)
        print(f"error: {' '.join(str(exc).split())}", file=sys.stderr, flush=True)
        code = 2
    finally:
        if parent is not None and os.getppid() != parent:
            with contextlib.suppress(Exception):
                _orphaned_recording(Path(out), None if recover is None else Path(recover))
        held.close()
    sys.exit(code)


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


def start_process(
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
    ctx = multiprocessing.get_context("spawn")
    main = threading.current_thread() is threading.main_thread()
    proc = ctx.Process(
        target=_child,
        args=(target, rig, duration, rate, str(out), kw, os.getpid(), main,
              None if recover is None else str(recover)),
        name="mrsus-hil-loop",
    )  # fmt: skip
    # the process starts with SIGINT ignored (kept through exec), so that a Ctrl-C while it
    # imports prints no traceback; _child handles it again before the loop starts. Here
    # SIGINT, SIGTERM and SIGHUP are blocked meanwhile, so one arriving during start()
    # waits for the handler instead of cutting the child's start-up data short (the
    # resource tracker, which unblocks them when it starts, is started first).
    ensure_resource_tracker()
    if not main:
        proc.start()
        return proc
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {*LOOP_SIGNALS, DEATH_SIGNAL})
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        proc.start()
    finally:
        signal.signal(signal.SIGINT, previous if previous is not None else signal.SIG_DFL)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
    return proc


def _run_in_process(
    target: Any,
    rig: Rig | None,
    duration: float,
    rate: float,
    out: Path,
    recover: str | Path | None = None,
    **kw: Any,
) -> HilResult:
    proc = start_process(target, rig, duration, rate, out, recover=recover, **kw)
    try:
        proc.join()
    except BaseException as exc:  # Ctrl-C, SIGTERM, SIGHUP here: stop the loop the safe way
        signum = int(getattr(exc, "signum", signal.SIGINT))
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGHUP, signal.SIG_IGN)  # the stop is bounded: let it end
        _stop_loop(
            proc, (out / META_FILE).exists(), wait=_stop_wait(kw.get("limits")), signum=signum
        )
        raise
    code = proc.exitcode
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


def load_result(out: str | Path) -> HilResult:
    """The :class:`HilResult` of a finished run from its recording directory.

    What :func:`run_hil` returns, rebuilt from the recording (its stop record holds the
    reason and the tick statistics): used for runs in their own process.

    Raises
    ------
    MRSuspensionError
        When the recording is incomplete (the run has not finished or its process died).

    Examples
    --------
    >>> import tempfile
    >>> from mrsuspension.excitation import Harmonic
    >>> out = Path(tempfile.mkdtemp()) / "rec"
    >>> run = run_hil(Simulation(Harmonic(1.5, 0.01)), duration=0.05, realtime="unpaced", out=out)
    >>> again = load_result(out)
    >>> again.reason, again.stats == run.stats, again.describe()["rows"] == len(run.recording)
    ('completed', True, True)
    """
    out = Path(out)
    recording = load_recording(out)
    stop = recording.stop
    if not recording.complete:
        raise MRSuspensionError(
            f"the HiL run in {out} did not finish; its recording holds {len(recording)} rows"
        )
    if "stats" not in stop:
        raise MRSuspensionError(
            f"the HiL run in {out} failed: {stop.get('reason', 'no reason recorded')}; "
            f"its recording holds {len(recording)} rows"
        )
    stats = TickStats(**stop["stats"])
    meta = json.loads((out / "meta.json").read_text()) if (out / "meta.json").exists() else {}
    signum = stop.get("signal")
    return HilResult(
        recording=recording,
        stats=stats,
        reason=str(stop.get("reason", "")),
        tripped=bool(stop.get("tripped", False)),
        out=out,
        meta=meta,
        ending=str(stop.get("ending", "tripped" if stop.get("tripped") else "completed")),
        signal=None if signum is None else int(signum),
    )
