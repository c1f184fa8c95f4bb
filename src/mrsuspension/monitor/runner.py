"""The monitored loop: its own process, paced on the clock, streaming decimated samples.

The monitor does not run the rig loop of :func:`mrsuspension.hil.run_hil` (which has no
live tap nor external stop); it runs the **engine's compiled step**
(:meth:`Simulation.stepper <mrsuspension.engine.simulate.Simulation.stepper>`, damper
model included) tick by tick at the loop rate in a separate process (``spawn``), with the
HiL safety supervisor checking stroke, stroke rate and current every tick. Decimated
samples and status go to the server through a bounded :class:`multiprocessing.Queue`;
when it is full the batch is dropped (counted), so a slow or absent browser never blocks
the loop. STOP sets a :class:`multiprocessing.Event` that the loop polls every tick: the
current goes to 0 and the run ends; the full-rate recording is written as CSV.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import queue as queue_mod
import time
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["DISPLAY_CHANNELS", "RECORD_CHANNELS", "LoopHandle"]

#: channels recorded at the loop rate (CSV columns)
RECORD_CHANNELS: tuple[str, ...] = (
    "time", "z_r", "z_r_dot", "z_s", "z_u", "z_s_dot", "z_u_dot", "z_s_ddot", "z_u_ddot",
    "x_d", "v_d", "F_d", "F_T", "i_d", "i_z", "compute", "lateness",
)  # fmt: skip
#: channels streamed to the page (a subset, decimated)
DISPLAY_CHANNELS: tuple[str, ...] = (
    "time", "z_r", "z_r_dot", "z_s", "z_u", "z_s_ddot", "z_u_ddot", "x_d", "F_d", "F_T",
    "i_d", "i_z",
)  # fmt: skip
_DISPLAY_INDEX = [RECORD_CHANNELS.index(c) for c in DISPLAY_CHANNELS]
#: display sampling rate [Hz]
DISPLAY_RATE = 200.0
#: batches are sent this often [s]
SEND_PERIOD = 0.05
#: largest engine step [s] (the offline default)
MODEL_DT = 1e-4
_SPIN = 3e-4


def _wait_until(deadline: float) -> float:
    perf = time.perf_counter
    rem = deadline - perf()
    if rem > _SPIN:
        time.sleep(rem - _SPIN)
    now = perf()
    while now < deadline:
        now = perf()
    return now


def _put(q: Any, item: Any) -> bool:
    try:
        q.put_nowait(item)
    except queue_mod.Full:
        return False
    return True


def loop_main(config: dict[str, Any], q: Any, stop: Any, out: str) -> None:
    """Body of the loop process.

    Parameters
    ----------
    config : dict
        :meth:`MonitorSettings.to_dict <mrsuspension.monitor.settings.MonitorSettings.to_dict>`.
    q : multiprocessing.Queue
        Bounded queue to the server: ``("data", array)``, ``("status", dict)``,
        ``("end", dict)``.
    stop : multiprocessing.Event
        Set by the server to stop the run.
    out : str
        CSV file for the full-rate recording.
    """
    import dataclasses

    from mrsuspension.engine.simulate import SimulationDiverged
    from mrsuspension.hil.safety import SafetySupervisor
    from mrsuspension.scenario import Scenario

    status: dict[str, Any] = {"state": "starting", "reason": "", "ticks": 0, "misses": 0}
    try:
        sim = Scenario.from_dict(config["tables"]).simulations()[0]
        supervisor = SafetySupervisor()
        if sim.max_current > supervisor.limits.current:
            sim = dataclasses.replace(sim, max_current=supervisor.limits.current)
        rate = float(config["rate"])
        period = 1.0 / rate
        n_sub = max(1, math.ceil(period / MODEL_DT - 1e-9))
        dt = period / n_sub
        stepper = sim.stepper(dt)
        zero = bool(config["zero_input"])
        n_max = max(1, round(float(config["duration"]) * rate))
        chunk = max(1, round(rate))  # road computed one second at a time
        decim = max(1, round(rate / DISPLAY_RATE))
        send_every = max(1, round(SEND_PERIOD * rate))
        status_every = max(1, round(0.2 * rate))
        excitation = sim.excitation
    except Exception as exc:  # reported to the page, never raised in the server
        _put(q, ("end", {**status, "state": "error", "reason": f"{type(exc).__name__}: {exc}"}))
        return

    def road_chunk(k0: int) -> tuple[list[float], list[float]]:
        t = (k0 * n_sub + np.arange(2 * n_sub * chunk + 1) * 0.5) * dt
        if zero:
            return [0.0] * t.size, [0.0] * t.size
        return (
            np.asarray(excitation.displacement(t), dtype=float).tolist(),
            np.asarray(excitation.velocity(t), dtype=float).tolist(),
        )

    road, road_v = road_chunk(0)
    stepper.step(road[0], road_v[0])  # warm-up: compile or load the kernels
    stepper.reset(road[0], road_v[0])
    rec = np.zeros((n_max, len(RECORD_CHANNELS)))
    pending: list[int] = []
    dropped = 0
    misses = 0
    reason = "completed"
    state = "running"
    _put(q, ("status", {**status, "state": state, "rate": rate}))
    perf = time.perf_counter
    step = stepper.step
    check = supervisor.check_command
    out_row: dict[str, float] = {}
    k = 0
    k_chunk = 0
    t0 = perf() + 2e-3
    while k < n_max:
        release = t0 + k * period
        start = _wait_until(release)
        if stop.is_set():
            reason = "stopped by the user"
            state = "stopped"
            break
        t = k * period
        if k - k_chunk >= chunk:
            k_chunk = k
            road, road_v = road_chunk(k)
        j = 2 * n_sub * (k - k_chunk)
        try:
            for _ in range(n_sub):
                out_row = step(
                    road[j], road_v[j],
                    road_mid=(road[j + 1], road_v[j + 1]),
                    road_end=(road[j + 2], road_v[j + 2]),
                )  # fmt: skip
                j += 2
            tripped = check(t, out_row["x_d"], out_row["v_d"], out_row["i_d"])
        except SimulationDiverged as exc:
            supervisor.trip(f"vehicle model diverged: {exc}", t)
            tripped = True
        end = perf()
        late = start - release
        if late + end - start > period:
            misses += 1
        o = out_row
        rec[k] = (
            t + period, road[j], road_v[j], o["z_s"], o["z_u"], o["z_s_dot"], o["z_u_dot"],
            o["z_s_ddot"], o["z_u_ddot"], o["x_d"], o["v_d"], o["F_d"], o["F_T"], o["i_d"],
            o["i_z"], end - start, late,
        )  # fmt: skip
        k += 1
        if tripped:
            reason = supervisor.reason
            state = "tripped"
            break
        if k % decim == 0:
            pending.append(k - 1)
        if k % send_every == 0 and pending:
            if not _put(q, ("data", rec[pending][:, _DISPLAY_INDEX])):
                dropped += 1
            pending = []
        if k % status_every == 0:
            window = rec[max(0, k - status_every) : k, RECORD_CHANNELS.index("compute")]
            _put(
                q,
                (
                    "status",
                    {
                        "state": state,
                        "rate": rate,
                        "ticks": k,
                        "misses": misses,
                        "dropped": dropped,
                        "compute_last": float(window[-1]),
                        "compute_max": float(window.max()),
                        "compute_mean": float(window.mean()),
                    },
                ),
            )
    # the coil is off from here on (safe state); write the recording
    rows = rec[:k]
    np.savetxt(out, rows, delimiter=",", header=",".join(RECORD_CHANNELS), comments="")
    compute = rows[:, RECORD_CHANNELS.index("compute")] if k else np.zeros(1)
    final = {
        "state": state,
        "reason": reason,
        "rate": rate,
        "ticks": k,
        "misses": misses,
        "dropped": dropped,
        "compute_max": float(compute.max()),
        "compute_mean": float(compute.mean()),
        "current": 0.0,
    }
    with contextlib.suppress(queue_mod.Full):
        q.put(("end", final), timeout=2.0)


class LoopHandle:
    """The server's handle on one loop process.

    Parameters
    ----------
    config : dict
        Validated settings (:meth:`MonitorSettings.to_dict`).
    out : path
        Where the loop writes its CSV recording.
    queue_size : int
        Capacity of the sample queue (batches; full -> the loop drops).
    """

    def __init__(self, config: dict[str, Any], out: Path, queue_size: int = 64) -> None:
        ctx = multiprocessing.get_context("spawn")
        self.out = Path(out)
        self.queue: Any = ctx.Queue(maxsize=queue_size)
        self.stop_event: Any = ctx.Event()
        self.process = ctx.Process(
            target=loop_main,
            args=(config, self.queue, self.stop_event, str(self.out)),
            name="mrsus-monitor-loop",
            daemon=True,
        )
        self.process.start()

    def stop(self) -> None:
        """Ask the loop to stop (it zeroes the current and ends at the next tick)."""
        self.stop_event.set()

    def drain(self, limit: int = 1000) -> list[tuple[str, Any]]:
        """Messages waiting in the queue (never blocks)."""
        items: list[tuple[str, Any]] = []
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
