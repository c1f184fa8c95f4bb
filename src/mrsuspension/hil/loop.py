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

This module prepares a run and holds :func:`run_hil` (the run's settings, the model, the
road, the recorder, the scheduling); the rest is split by concern and re-exported here:
:mod:`~mrsuspension.hil._ticks` (pacing and the hot loop, ``_loop``),
:mod:`~mrsuspension.hil._process` (the signals, :func:`bind_to_parent`, the loop in a
process of its own: :func:`start_process`) and :mod:`~mrsuspension.hil._result` (the
channels, :class:`TickStats`, :class:`HilResult`, :func:`load_result`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import multiprocessing
import shutil
import signal
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.control.user import check_loop_budget
from mrsuspension.engine.settings import MAX_DURATION, RunSettings
from mrsuspension.engine.simulate import DEFAULT_DT, Simulation
from mrsuspension.errors import MRSuspensionError, ValidationError, check_range
from mrsuspension.hil import _process

# the loop's parts, re-exported here (their one public home): the run's outcome, the
# process and signals, the ticks
from mrsuspension.hil._process import _BOUND_PARENT, _SETTLE, _Abort, _stop_requests
from mrsuspension.hil._process import DEATH_SIGNAL as DEATH_SIGNAL
from mrsuspension.hil._process import LOOP_SIGNALS as LOOP_SIGNALS
from mrsuspension.hil._process import SIGNAL_REASONS as SIGNAL_REASONS
from mrsuspension.hil._process import STOP_TIMEOUT as STOP_TIMEOUT
from mrsuspension.hil._process import _child as _child
from mrsuspension.hil._process import _orphaned_recording as _orphaned_recording
from mrsuspension.hil._process import _raise_interrupted as _raise_interrupted
from mrsuspension.hil._process import _stop_loop as _stop_loop
from mrsuspension.hil._process import _stop_wait as _stop_wait
from mrsuspension.hil._process import bind_to_parent as bind_to_parent
from mrsuspension.hil._result import _NAMES as _NAMES
from mrsuspension.hil._result import _STOPPED as _STOPPED
from mrsuspension.hil._result import CHANNELS as CHANNELS
from mrsuspension.hil._result import ENDINGS as ENDINGS
from mrsuspension.hil._result import STATE_RETURN as STATE_RETURN
from mrsuspension.hil._result import STATE_RUN as STATE_RUN
from mrsuspension.hil._result import STATE_STARTUP as STATE_STARTUP
from mrsuspension.hil._result import STATE_TRIPPED as STATE_TRIPPED
from mrsuspension.hil._result import STOP_REASON as STOP_REASON
from mrsuspension.hil._result import STOP_REASONS as STOP_REASONS
from mrsuspension.hil._result import HilResult as HilResult
from mrsuspension.hil._result import TickStats as TickStats
from mrsuspension.hil._result import check_recording_memory as check_recording_memory
from mrsuspension.hil._result import load_result as load_result
from mrsuspension.hil._ticks import _SPIN as _SPIN
from mrsuspension.hil._ticks import _loop, _status
from mrsuspension.hil._ticks import _quiet_interpreter as _quiet_interpreter
from mrsuspension.hil._ticks import _row as _row
from mrsuspension.hil._ticks import _spin_window as _spin_window
from mrsuspension.hil._ticks import _wait_until as _wait_until
from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.live import LiveChange as LiveChange
from mrsuspension.hil.live import LoopHooks as LoopHooks
from mrsuspension.hil.live import _live_status as _live_status
from mrsuspension.hil.live import _Road, live_chunk, tick_step
from mrsuspension.hil.realtime import (
    check_isolate,
    normalise_mode,
    realtime_session,
    yield_loop_cpu,
)
from mrsuspension.hil.recorder import Recorder, load_recording
from mrsuspension.hil.rig import Rig, SimulatedRig
from mrsuspension.hil.safety import SafetyLimits, SafetySupervisor, StartUp
from mrsuspension.hil.vehicle import BODY_CHANNELS, CornerPlant, check_corner, has_corners

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
    "start_process",
]

#: the recorder's ring holds this long a stretch of rows (how far its writer may lag) [s]
_RING_SECONDS = 10.0


# -- helpers --------------------------------------------------------------------------------
def check_drives_damper(sim: Any, corner: str | None = None) -> None:
    """Refuse a run whose law at the rig does not command the damper's current.

    An ideal force (``ideal-*``, ``*-force`` through no inverse), an ideal actuator
    (``lq-active``, ``vehicle-lq-active``, ...) or a whole-vehicle law that puts ideal
    actuators at the corners would leave the rig at 0 A while the run looked controlled.

    Raises
    ------
    ValidationError
        One line naming the law and what a HiL run accepts.

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.control import make_controller
    >>> from mrsuspension.excitation import Harmonic
    >>> def run(law):
    ...     return Simulation(Harmonic(1.5, 0.025), controller=make_controller(law))
    >>> check_drives_damper(run("skyhook-hilo"))
    >>> check_drives_damper(run("ideal-skyhook"))
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: controller law 'ideal-skyhook' does not command the damper's current (an ideal force or actuator): the rig would be sent 0 A. A HiL run needs a law that drives the MR damper (e.g. skyhook-hilo, inverse-hilo, sliding-mode)
    """
    hint = (
        "the rig would be sent 0 A. A HiL run needs a law that drives the MR damper "
        "(e.g. skyhook-hilo, inverse-hilo, sliding-mode)"
    )
    if has_corners(sim):
        body = getattr(sim, "body_control", None)
        if body is not None and getattr(body, "active", False):
            name = body.describe().get("law", type(body).__name__)
            raise ValidationError(
                f"whole-vehicle law {name!r} drives ideal actuators, not the dampers; {hint}"
            )
        if body is not None:
            return  # the whole-vehicle law sets every corner's current
        law = sim.corner_simulation(check_corner(sim, corner)).controller
    else:
        law = sim.controller
    if not law.drives_damper:
        name = law.describe().get("law", type(law).__name__)
        raise ValidationError(
            f"controller law {name!r} does not command the damper's current (an ideal force "
            f"or actuator): {hint}"
        )


def _capped(sim: Any, current: float) -> Any:
    """``sim`` with its ``max_current`` lowered to ``current`` [A] (the safety limit); a
    whole-vehicle law's ``high_current`` above it is lowered with it, as a per-corner law's
    demand is clipped at ``max_current``.

    Examples
    --------
    >>> from mrsuspension.control import VehicleLQ
    >>> from mrsuspension.engine.vehicle import VehicleSimulation
    >>> from mrsuspension.excitation.wheels import WheelRoads
    >>> from mrsuspension.vehicle import FullCar
    >>> car = FullCar()
    >>> road = WheelRoads.two_track("C", (car.wheelbase, car.front_track), length=20.0)
    >>> sim = VehicleSimulation(car, road, body_control=VehicleLQ())
    >>> capped = _capped(sim, 0.3)
    >>> capped.max_current, capped.body_control.high_current
    (0.3, 0.3)
    """
    changes: dict[str, Any] = {"max_current": current}
    body = getattr(sim, "body_control", None)
    if body is not None and getattr(body, "high_current", 0.0) > current:
        changes["body_control"] = dataclasses.replace(body, high_current=current)
    return dataclasses.replace(sim, **changes)


def _simulation_of(target: Any) -> Any:
    """The one run of ``target``: a quarter car's :class:`Simulation`, or a half or full
    car's :class:`~mrsuspension.engine.vehicle.VehicleSimulation` (the scenario's
    ``[vehicle] model`` says which)."""
    if isinstance(target, Simulation) or has_corners(target):
        return target
    from mrsuspension.scenario import Scenario

    if isinstance(target, str | Path):
        target = Scenario.load(target)
    if isinstance(target, Scenario):
        sims = target.runs()  # any model (the run contract); HiL needs one run
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
    if has_corners(sim):
        return sim.corner_simulation(check_corner(sim, corner)).damper
    return sim.damper


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
        if not isinstance(target, str | Path):  # a scenario file is read in the child
            check_drives_damper(_simulation_of(target), corner)
        return _process._run_in_process(
            run_hil, target, rig, duration, rate, Path(out), recover, model_dt=model_dt, limits=limits,
            startup=startup, driver=driver, realtime=realtime, isolate=isolate,
            cap_current=cap_current, hooks=hooks, corner=corner,
        )  # fmt: skip
    mode = normalise_mode(realtime)
    check_isolate(mode, isolate)
    realtime = mode != "unpaced"
    sim = _simulation_of(target)
    vehicle = has_corners(sim)
    if vehicle:
        corner = check_corner(sim, corner)
    elif corner is not None:
        raise ValidationError(
            f"corner = {corner!r}: a quarter-car run has no corners (half and full cars do)"
        )
    check_drives_damper(sim, corner)
    limits = limits or SafetyLimits()
    startup = startup if startup is not None else StartUp()
    rate = float(check_range("rate", rate, 1.0, 100000.0, unit="Hz"))
    duration = float(
        check_range("duration", duration, 0.0, MAX_DURATION, unit="s", low_inclusive=False)
    )
    check_recording_memory(duration, rate)
    if cap_current and sim.max_current > limits.current:
        sim = _capped(sim, limits.current)
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
    check_loop_budget(sim, n_sub, period)  # a Python control law must keep the rate
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
    """Start :func:`run_hil` in its own process (spawn) and return the process (not joined).

    The process is bound to this one (:func:`bind_to_parent`): if this process dies, the
    loop stops the safe way and keeps its recording (moved to ``recover``'s
    ``NAME.recovered`` when given). See :func:`mrsuspension.hil._process.start_process`.
    """
    return _process.start_process(run_hil, target, rig, duration, rate, out, recover=recover, **kw)
