"""The HiL loop's ticks: pacing on the clock and the hot loop itself.

Part of the loop (:mod:`mrsuspension.hil.loop`, which prepares the run and calls
:func:`_loop`): each tick reads the rig, lets the supervisor check it, advances the
model (the quarter car's compiled step, or a vehicle's whole tick,
:class:`~mrsuspension.hil.vehicle.CornerPlant`), regulates the current, commands the
rig and records the row; any ending takes the safe path (current 0, back to
mid-stroke). Ticks are released at ``t0 + k T`` (:func:`_wait_until`).
"""

from __future__ import annotations

import contextlib
import gc
import math
import sys
import time
from collections.abc import Iterator
from typing import Any

import numpy as np

from mrsuspension.engine.simulate import SimulationDiverged
from mrsuspension.errors import ValidationError
from mrsuspension.hil._process import _SETTLE, _Abort
from mrsuspension.hil._result import (
    _STOPPED,
    STATE_RETURN,
    STATE_RUN,
    STATE_STARTUP,
    STATE_TRIPPED,
    STOP_REASON,
    STOP_REASONS,
    TickStats,
)
from mrsuspension.hil.driver import PICurrentDriver
from mrsuspension.hil.live import LoopHooks, _apply_settings, _live_status, _Road
from mrsuspension.hil.recorder import Recorder
from mrsuspension.hil.rig import Rig, RigSample
from mrsuspension.hil.safety import SafetySupervisor, StartUp
from mrsuspension.hil.vehicle import BODY_CHANNELS, CornerPlant

__all__: list[str] = []

#: spin (busy-wait) for the last part of each wait [s], at most this fraction of a period
_SPIN = 3e-4
_SPIN_FRACTION = 0.25
#: first release after the clock starts [s]
_START_DELAY = 2e-3
#: how often the loop checks its recorder's writer and its parent process [s]
_WATCH_PERIOD = 0.02
#: how long the loop keeps trying to command a rig that refuses every command [s]
_COMMAND_GIVE_UP = 0.1


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
