"""The monitor's ASGI application (Starlette): page, JSON API, WebSocket stream.

Routes: ``GET /`` (the page), ``/static/...`` (its JS and CSS, package data),
``POST /api/start`` (validated settings -> a new HiL run; a :class:`ValidationError`
comes back as ``400 {"error": ...}``), ``POST /api/apply`` (validated settings -> the
running loop, applied between ticks), ``POST /api/stop`` (STOP), ``POST /api/record``
(record start/stop), ``POST /api/acquisition`` (period, trigger, display rate),
``GET /api/controllers`` (the controller laws the page offers and their options,
derived from the controller registry: :func:`~mrsuspension.monitor.settings.controller_forms`),
``GET /api/vehicles`` (the vehicle models, their sets and corners, and the sensing
fields, derived from the plant registry and the scenario:
:func:`~mrsuspension.monitor.settings.vehicle_forms`), ``GET /api/status``, ``GET /api/recording`` (CSV of the acquired rows of the HiL
recording) and ``WS /ws`` (JSON frames at 25 Hz: new samples at the display rate, loop
status, live measures).

Every request passes :class:`~mrsuspension.monitor.security.MonitorGate` first (Host,
Origin, content type, body size, access token: :mod:`mrsuspension.monitor.security`).
One run goes at a time: a start while a run goes (or while another start is being
handled) is refused with 409; STOP always reaches the running loop. Each run records
into the next free ``run-NNN`` folder of the work directory, so a new session never
writes over an earlier one's runs.
"""

from __future__ import annotations

import asyncio
import contextlib
import gc
import math
import tempfile
import threading
import time
from collections import deque
from collections.abc import AsyncIterator, Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, HTMLResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.websockets import WebSocket, WebSocketDisconnect

from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.hil.loop import CHANNELS, LiveChange, load_result
from mrsuspension.hil.realtime import check_isolate, normalise_mode
from mrsuspension.hil.recorder import META_FILE, load_recording
from mrsuspension.hil.vehicle import BODY_CHANNELS, check_corner, has_corners
from mrsuspension.measures.steady import T_as, T_au, T_dr, T_ds, T_du, dlc
from mrsuspension.monitor.acquisition import Acquisition, acquisition_from_settings
from mrsuspension.monitor.runner import TAP_RATE, LoopHandle
from mrsuspension.monitor.security import MAX_BODY, MonitorGate, check_token, loads_json
from mrsuspension.monitor.settings import (
    MonitorSettings,
    controller_forms,
    page_fields,
    scenario_from_settings,
    vehicle_forms,
)

__all__ = [
    "DISPLAY_CHANNELS",
    "AttachedRun",
    "MonitorState",
    "RunBusyError",
    "create_app",
    "live_measures",
]

#: channels shown by the page (loop channels plus the derived z_r'' and model force F_dmod;
#: a half or full car run's body heave, pitch and roll, NaN in a quarter-car run)
DISPLAY_CHANNELS: tuple[str, ...] = (
    "time", "state", "z_r", "z_r_dot", "z_r_ddot", "z_s", "z_s_ddot", "z_u", "z_u_ddot",
    "x_d", "x_m", "F_dm", "F_dmod", "F_T", "i_d", "i_cmd", "i_dm", "heave", "pitch", "roll",
)  # fmt: skip
#: columns of a tapped row: the loop's channels, then a vehicle run's body channels
_COL = {name: j for j, (name, _) in enumerate(CHANNELS + BODY_CHANNELS)}
#: longest wait for a stopped loop to bring the actuator back to mid-stroke and end [s]
_RETURN_WAIT = 15.0
#: live measures are recomputed this often [s]
_MEASURE_PERIOD = 0.2
#: rows kept for the model force and z_r'' (contiguous tail of the tap stream)
_DERIVE_KEEP = 400

#: seconds of display samples kept by the server
_KEEP = 10.0
#: frame period of the WebSocket stream [s] (25 Hz, on a fixed clock: >= 20 Hz under load)
_FRAME = 0.04
#: longest wait of STOP for a start being handled (the loop process being spawned) [s]
_STOP_WAIT = 30.0


class RunBusyError(ValidationError):
    """A start refused because a run goes, or another start is being handled (HTTP 409)."""


def live_measures(data: dict[str, np.ndarray], static_load: float) -> dict[str, float | None]:
    """T_as, T_ds, T_au, T_du, T_dr and DLC over the last whole seconds of ``data``.

    Parameters
    ----------
    data : dict of arrays
        Display channels (``time``, ``z_r``, ``z_r_dot``, ``z_s``, ...).
    static_load : float
        ``(m_s + m_u) g`` [N].

    Returns
    -------
    dict
        The measures (None when undefined, e.g. less than a second of data or a zero road),
        and ``window`` [s].
    """
    names = ("T_as", "T_ds", "T_au", "T_du", "T_dr", "DLC")
    result: dict[str, float | None] = dict.fromkeys(names)
    result["window"] = None
    t = data.get("time")
    if t is None or t.size < 3:
        return result
    span = math.floor(min(t[-1] - t[0], 5.0))
    if span < 1:
        return result
    sel = t >= t[-1] - span
    if np.count_nonzero(sel) < 3:
        return result
    d = {k: v[sel] for k, v in data.items()}
    acc_r = np.gradient(d["z_r_dot"], d["time"])
    zr = d["z_r"] - np.mean(d["z_r"])
    pairs = {
        "T_as": (T_as, d["z_s_ddot"], acc_r),
        "T_au": (T_au, d["z_u_ddot"], acc_r),
        "T_ds": (T_ds, d["z_s"] - np.mean(d["z_s"]), zr),
        "T_du": (T_du, d["z_u"] - np.mean(d["z_u"]), zr),
        "T_dr": (T_dr, d["x_d"] - np.mean(d["x_d"]), zr),
    }
    for name, (fn, num, den) in pairs.items():
        try:
            value = float(fn(num, den))
            result[name] = value if math.isfinite(value) else None
        except (ValidationError, ZeroDivisionError, FloatingPointError):
            result[name] = None
    try:
        result["DLC"] = float(dlc(d["F_T"] - np.mean(d["F_T"]) + static_load, static_load))
    except ValidationError:
        result["DLC"] = None
    result["window"] = float(span)
    return result


def monitor_realtime(realtime: str) -> str:
    """A monitor run's scheduling mode, checked: the monitor always runs in real time.

    Examples
    --------
    >>> monitor_realtime("SPIN")
    'spin'
    """
    mode = normalise_mode(realtime)
    if mode == "unpaced":
        raise ValidationError(
            f"realtime {realtime!r}: the monitor runs in real time; valid: auto, fifo, spin, off"
        )
    return mode


@dataclass
class AttachedRun:
    """A run the server starts by itself (``mrsus hil run SCENARIO --monitor``).

    Attributes
    ----------
    simulation : Simulation
        The scenario's configuration (its damper stays; the page changes the rest live).
    rate, duration : float
        Loop rate [Hz] and run length [s].
    model_dt : float, optional
        Largest engine step [s] per tick (the scenario's ``[simulation] dt``; None: the
        loop's default, :data:`~mrsuspension.engine.settings.DEFAULT_DT`).
    corner : str, optional
        With a half or full car (a :class:`~mrsuspension.engine.vehicle.VehicleSimulation`):
        the corner whose damper is on the rig (default: the first). The page shows that
        corner as a quarter car and the body's heave, pitch and roll; live changes are
        refused (they describe a quarter car).
    on_end : callable, optional
        Called once with the run's result description (what ``mrsus hil run --json``
        prints: :meth:`~mrsuspension.hil.loop.HilResult.describe`) when the run has
        ended, or with ``{"state": "error", "reason": ...}`` when its loop failed.
    """

    simulation: Simulation | Any
    rate: float = 1000.0
    duration: float = 60.0
    model_dt: float | None = None
    on_end: Callable[[dict[str, Any]], None] | None = None
    corner: str | None = None


class MonitorState:
    """The server's state: current run, display buffers, acquisition.

    Parameters
    ----------
    workdir : path, optional
        Where recordings are written (default: a temporary directory).
    rig : str
        Rig of the runs: ``simulated`` (default), ``ideal`` or ``udp://HOST:PORT``.
    road_dir : path, optional
        Directory the page may take road files from (None: presets only).
    realtime : str
        How the loop processes are scheduled: ``auto`` (default), ``fifo``, ``spin`` or
        ``off`` (:mod:`mrsuspension.hil.realtime`; ``spin`` does best on a virtual machine).
    isolate : bool
        Move the machine's other movable tasks off the loop's core during each run
        (:func:`~mrsuspension.hil.realtime.isolate_cpu`; needs ``auto``, ``fifo`` or
        ``spin``).
    """

    def __init__(
        self,
        workdir: Path | None = None,
        rig: str = "simulated",
        road_dir: Path | None = None,
        realtime: str = "auto",
        isolate: bool = False,
    ) -> None:
        self.realtime = monitor_realtime(realtime)
        check_isolate(self.realtime, isolate)
        self.isolate = bool(isolate)
        #: CPUs the loop processes may use when the server keeps off the loop's core
        self.loop_cpus: set[int] | None = None
        self.workdir = Path(workdir or tempfile.mkdtemp(prefix="mrsus-monitor-"))
        self.rig = rig
        self.road_dir = road_dir
        self.handle: LoopHandle | None = None
        #: the server's shutdown stopped a running loop (the command says so)
        self.stopped_by_shutdown = False
        self.settings: MonitorSettings | None = None
        self.base: Simulation | None = None
        self.simulation: Simulation | None = None
        #: the rig corner of a half or full car run (None: a quarter car)
        self.corner: str | None = None
        self.run_id = 0
        self.status: dict[str, Any] = {"state": "idle", "reason": "", "rig": rig}
        self.recording: Path | None = None
        self.acquisition = Acquisition()
        maxlen = int(_KEEP * TAP_RATE)
        self.buffers: dict[str, deque[float]] = {c: deque(maxlen=maxlen) for c in DISPLAY_CHANNELS}
        self.raw: deque[Any] = deque(maxlen=_DERIVE_KEEP)
        self.fresh: list[list[float | None]] = []
        self.seen = 0
        self.static_load = 0.0
        self.loop_time = 0.0
        self.events: deque[str] = deque(maxlen=20)
        self._measures: dict[str, float | None] = {}
        self._measured_at = 0.0
        self._on_end: Callable[[dict[str, Any]], None] | None = None  # the attached run's
        #: held while a run is launched, changed or stopped: one run at a time
        self.lock = threading.Lock()

    # -- runs ------------------------------------------------------------------------------
    def validate(self, raw: dict[str, Any]) -> tuple[MonitorSettings, Any]:
        """Validate page settings; the run they describe (a quarter car on the attached
        base, or a half or full car: :meth:`MonitorSettings.simulation`)."""
        settings = scenario_from_settings(raw, self.road_dir)  # raises ValidationError
        return settings, settings.simulation(self.base)

    def start(self, raw: dict[str, Any]) -> dict[str, Any]:
        """Validate ``raw`` settings and start a run.

        Raises
        ------
        RunBusyError
            When a run goes (press STOP and let it end first) or another start is
            being handled at the same moment: one run at a time.
        ValidationError
            For invalid settings.
        """
        if not self.lock.acquire(blocking=False):
            raise RunBusyError("another start is being handled; one run at a time")
        try:
            settings, sim = self.validate(raw)
            self._check_idle()
            # a car: its rig corner's damper on the rig, the rest simulated in the loop
            return self._launch(
                sim, settings.rate, settings.duration, settings.ramp_time, settings,
                corner=settings.corner,
            )  # fmt: skip
        finally:
            self.lock.release()

    def attach(self, run: AttachedRun) -> dict[str, Any]:
        """Start the attached run (its scenario's damper is kept for live changes)."""
        with self.lock:
            self._check_idle()
            corner = None
            target: Any = run.simulation
            if has_corners(target):  # the page's runs keep that corner's damper
                corner = check_corner(target, run.corner)
                self.base = target.corner_simulation(corner)
            else:
                self.base = target
            info = self._launch(
                run.simulation, run.rate, run.duration, 0.2, None, model_dt=run.model_dt,
                corner=corner,
            )  # fmt: skip
            self._on_end = run.on_end
        return info

    def _check_idle(self) -> None:
        h = self.handle
        # a loop that has reported its end is leaving: _launch waits for it
        if h is not None and h.alive() and self.status.get("state") not in ("ended", "error"):
            state = self.status.get("state", "running")
            raise RunBusyError(
                f"run {self.run_id} is still going ({state}); press STOP and wait until it "
                "has ended (one run at a time)"
            )

    def _reserve_run(self) -> tuple[int, Path]:
        """The next run number whose folder and CSV are free in the work directory.

        The folder is created here (``mkdir`` without ``exist_ok``), so that no other
        session or run can take it: an earlier session's ``run-NNN`` (or anything a user
        put there under that name) is never written over.
        """
        self.workdir.mkdir(parents=True, exist_ok=True)
        n = self.run_id
        while True:
            n += 1
            out = self.workdir / f"run-{n:03d}"
            csv = self.workdir / f"run-{n:03d}.csv"
            if out.is_symlink() or csv.exists() or csv.is_symlink():
                continue
            try:
                out.mkdir()
            except FileExistsError:
                continue
            return n, out

    def report_end(self) -> None:
        """Give the attached run's result to its ``on_end`` once it has ended (once)."""
        h = self.handle
        if self._on_end is None or h is None or h.alive():
            return
        on_end, self._on_end = self._on_end, None
        try:
            info = load_result(h.out).describe()
        except (MRSuspensionError, OSError, ValueError):  # the loop failed: no result
            reason = self.status.get("reason") or "the loop process ended without a result"
            info = {"state": "error", "reason": reason}
        on_end(info)

    def _launch(
        self,
        sim: Any,
        rate: float,
        duration: float,
        ramp_time: float,
        settings: MonitorSettings | None,
        model_dt: float | None = None,
        corner: str | None = None,
    ) -> dict[str, Any]:
        if self.handle is not None:  # ended (checked by the caller, under the lock)
            self.handle.join(_RETURN_WAIT)
            self.report_end()
        self.run_id, out = self._reserve_run()
        self.settings = settings
        run_sim: Any = sim
        self.corner = corner
        if corner is not None:  # shown as the rig corner's quarter car, plus the body
            sim = run_sim.corner_simulation(corner)
        self.simulation = sim
        self.static_load = sim.vehicle.static_load
        for buf in self.buffers.values():
            buf.clear()
        self.raw.clear()
        self.fresh = []
        self.seen = 0
        self.loop_time = 0.0
        self._measures = {}
        self._measured_at = 0.0
        self.acquisition = Acquisition(
            period=self.acquisition.period,
            trigger=self.acquisition.trigger,
            level=self.acquisition.level,
            edge=self.acquisition.edge,
            pre_trigger=self.acquisition.pre_trigger,
            display_rate=self.acquisition.display_rate,
        )
        self.recording = None
        self.status = {
            "state": "starting", "reason": "", "run": self.run_id, "rig": self.rig,
            "applied": 0, "safe": False, "fields": page_fields(sim), "corner": corner,
            "model": getattr(run_sim, "model_name", "quarter-car"),
        }  # fmt: skip
        self.handle = LoopHandle(
            run_sim, self.rig, rate, duration, out, ramp_time=ramp_time, realtime=self.realtime,
            cpus=self.loop_cpus, isolate=self.isolate, model_dt=model_dt, corner=corner,
        )  # fmt: skip
        return {"run": self.run_id, "rig": self.rig, "fields": self.status["fields"]}

    def apply(self, raw: dict[str, Any]) -> dict[str, Any]:
        """Validate ``raw`` settings and send them to the running loop (between ticks)."""
        settings, sim = self.validate(raw)  # invalid settings never reach the loop
        with self.lock:
            return self._apply(settings, sim)

    def _apply(self, settings: MonitorSettings, sim: Any) -> dict[str, Any]:
        h = self.handle
        if (
            h is None
            or not h.alive()
            or self.status.get("state") not in ("starting", "startup", "running")
        ):
            raise ValidationError("no run is going: press Start first")
        if self.corner is not None:
            raise ValidationError(
                "live changes apply to quarter-car runs; this run is a half or full car "
                f"(corner {self.corner!r} on the rig): stop it and start a new run"
            )
        if settings.corner is not None:
            model = settings.tables["vehicle"].get("model", "car")
            raise ValidationError(
                f"live changes apply to quarter-car runs; the form describes a {model} "
                "(a new run): press STOP, wait for the end, then Start"
            )
        old = self.simulation if self.simulation is not None else sim
        # prepared here: the loop only swaps arrays
        change = LiveChange.prepare(sim, old, h.rate, ramp_time=settings.ramp_time)
        if not h.apply(change):
            raise ValidationError("the loop has not taken the previous change yet; try again")
        self.simulation = sim
        self.static_load = sim.vehicle.static_load
        self.status["fields"] = page_fields(sim)
        return {"queued": True, "fields": self.status["fields"]}

    def stop(self, shutdown: bool = False) -> None:
        """STOP: ask the running loop to take its safety path.

        The running loop is told at once (never behind the lock); then a start being
        handled at that moment is waited for (its loop process being spawned) and its
        loop told too: STOP always stops the run. ``shutdown``: the server is stopping
        (the stop record says so rather than "STOP pressed").
        """
        self._signal_stop(shutdown)
        got = self.lock.acquire(timeout=_STOP_WAIT)
        try:
            self._signal_stop(shutdown)
        finally:
            if got:
                self.lock.release()

    def _signal_stop(self, shutdown: bool = False) -> None:
        h = self.handle
        if h is not None and h.alive():
            h.stop(2 if shutdown else 1)
            if self.status.get("state") not in ("ended", "error"):
                self.status["state"] = "stopping"

    # -- acquisition -----------------------------------------------------------------------
    def record(self, action: str) -> dict[str, Any]:
        """Record start/stop at the loop time last heard of."""
        if action == "start":
            self.acquisition = self.acquisition.start(self.loop_time)
        elif action == "stop":
            self.acquisition = self.acquisition.stop(self.loop_time)
        else:
            raise ValidationError(f"unknown record action {action!r}; valid: start, stop")
        return self.acquisition.describe()

    def set_acquisition(self, raw: dict[str, Any]) -> dict[str, Any]:
        """Validate and set the acquisition period, trigger and display rate."""
        self.acquisition = acquisition_from_settings(raw, self.acquisition)
        return self.acquisition.describe()

    def export(self) -> tuple[Path, int]:
        """The acquired rows of the current run's HiL recording as a CSV file."""
        h = self.handle
        if h is None or not (h.out / META_FILE).exists():
            raise ValidationError("no recording yet: start a run first")
        rec = load_recording(h.out)
        if len(rec) == 0:
            raise ValidationError("the recording holds no rows yet")
        path, rows = self.acquisition.export(rec, self.workdir / f"run-{self.run_id:03d}.csv")
        if rows == 0:
            raise ValidationError(
                "no rows acquired (the trigger did not fire or no record window covers data)"
            )
        return path, rows

    # -- stream ----------------------------------------------------------------------------
    def _derive(self, rows: Any) -> np.ndarray:
        """Display rows of new tap rows: z_r'' and the model damper force added."""
        self.raw.extend(rows)
        tail = np.asarray(self.raw, dtype=float)
        t = tail[:, _COL["time"]]
        # the contiguous part (a dropped batch leaves a gap)
        steps = np.diff(t)
        if steps.size:
            dt = float(np.median(steps))
            gaps = np.flatnonzero(np.abs(steps - dt) > 1e-6 * max(dt, 1e-9) + 1e-12)
            first = int(gaps[-1]) + 1 if gaps.size else 0
        else:
            dt, first = 0.0, 0
        part = tail[first:]
        n = len(rows)
        zr_dd = np.zeros(len(part))
        f_mod = np.full(len(part), math.nan)
        if len(part) >= 3 and dt > 0:
            zr_dd = np.gradient(part[:, _COL["z_r_dot"]], dt)
            sim = self.simulation
            if sim is not None:
                damper = sim.damper
                i = np.clip(part[:, _COL["i_dm"]], 0.0, damper.max_current)
                with contextlib.suppress(ValidationError):
                    f_mod = damper.response(
                        part[:, _COL["time"]], part[:, _COL["x_m"]], current=i
                    ).force
        if len(part) < n:  # fewer contiguous rows than new ones: pad the head
            zr_dd = np.concatenate([np.zeros(n - len(part)), zr_dd])
            f_mod = np.concatenate([np.full(n - len(part), math.nan), f_mod])
        new = tail[-n:]
        out = np.empty((n, len(DISPLAY_CHANNELS)))
        for j, name in enumerate(DISPLAY_CHANNELS):
            if name == "z_r_ddot":
                out[:, j] = zr_dd[-n:]
            elif name == "F_dmod":
                out[:, j] = f_mod[-n:]
            elif _COL[name] < new.shape[1]:
                out[:, j] = new[:, _COL[name]]
            else:  # a body channel of a quarter-car run
                out[:, j] = math.nan
        return out

    def poll(self) -> None:
        """Take what the loop sent (never blocks)."""
        h = self.handle
        if h is None:
            return
        for kind, msg in h.drain():
            if kind == "data" and len(msg):
                rows = self._derive(msg)
                self.loop_time = float(rows[-1, 0])
                step = max(1, round(TAP_RATE / self.acquisition.display_rate))
                for i, name in enumerate(DISPLAY_CHANNELS):
                    self.buffers[name].extend(rows[:, i].tolist())
                for r in rows:
                    if self.seen % step == 0:
                        self.fresh.append([float(x) if math.isfinite(x) else None for x in r])
                    self.seen += 1
            elif kind == "status":
                self.status.update(msg)
                self.status["safe"] = msg.get("state") in (
                    "tripped",
                    "returning",
                    "ended",
                ) and not msg.get("current")
            elif kind == "applied":
                self.status["applied"] = msg.get("count", 0)
                self.events.append(
                    f"t = {msg.get('time', 0):.2f} s: change #{msg.get('count')} applied"
                )
            elif kind == "rejected":
                self.events.append(
                    f"t = {msg.get('time', 0):.2f} s: change refused: {msg.get('error')}"
                )
            elif kind == "end":
                self.status.update(msg)
                self.status["safe"] = True
                self.recording = h.out
        if not h.alive() and self.status.get("state") in (
            "starting",
            "startup",
            "running",
            "stopping",
            "tripped",
            "returning",
        ):
            self.status.update({"state": "ended", "safe": True, "current": 0.0})
            if (h.out / META_FILE).exists():
                self.recording = h.out
        self.report_end()

    def measures(self) -> dict[str, float | None]:
        """Live measures, recomputed at most every 0.2 s (they span seconds)."""
        now = time.monotonic()
        if now - self._measured_at >= _MEASURE_PERIOD or not self._measures:
            names = ("time", "z_r", "z_r_dot", "z_s", "z_u", "z_s_ddot", "z_u_ddot", "x_d", "F_T")
            data = {k: np.fromiter(self.buffers[k], dtype=float) for k in names}
            self._measures = live_measures(data, self.static_load) if self.static_load else {}
            self._measured_at = now
        return self._measures

    def history(self) -> dict[str, Any]:
        """A frame with the buffered rows (last 10 s at the display rate), for a new page."""
        step = max(1, round(TAP_RATE / self.acquisition.display_rate))
        cols = [list(self.buffers[name])[::step] for name in DISPLAY_CHANNELS]
        rows = [
            [float(x) if math.isfinite(x) else None for x in r] for r in zip(*cols, strict=True)
        ]
        return {**self.frame(consume=False), "rows": rows, "history": True}

    def frame(self, consume: bool = True) -> dict[str, Any]:
        """One WebSocket frame: new samples (taken unless ``consume`` is False), status..."""
        fresh: list[list[float | None]] = []
        if consume:
            fresh, self.fresh = self.fresh, []
        return {
            "run": self.run_id,
            "channels": list(DISPLAY_CHANNELS),
            "rows": fresh,
            "status": self.status,
            "measures": self.measures(),
            "recording": self.recording is not None or self.handle is not None,
            "acquisition": self.acquisition.describe(),
            "events": list(self.events),
        }


def _static_dir() -> Path:
    return Path(str(resources.files("mrsuspension.monitor") / "static"))


def create_app(
    token: str | None = None,
    workdir: Path | None = None,
    *,
    rig: str = "simulated",
    attach: AttachedRun | None = None,
    road_dir: Path | None = None,
    realtime: str = "auto",
    isolate: bool = False,
    host: str = "127.0.0.1",
    max_body: int = MAX_BODY,
) -> Starlette:
    """Build the monitor application.

    Parameters
    ----------
    token : str, optional
        Access token every request must carry, in the cookie the page gets on its first
        load (``/?token=...``) or as ``?token=...`` (required by
        :func:`~mrsuspension.monitor.server.serve` off loopback; at least 16 characters,
        :func:`~mrsuspension.monitor.security.check_token`).
    workdir : path, optional
        Directory for the recordings (default: a temporary one).
    rig : str
        Rig of the runs: ``simulated`` (default), ``ideal`` or ``udp://HOST:PORT``.
    attach : AttachedRun, optional
        A run started with the server (``mrsus hil run ... --monitor``).
    road_dir : path, optional
        Directory the page may take road files from (None: presets only).
    realtime : str
        How the loop processes are scheduled (``auto``, ``fifo``, ``spin``, ``off``).
    isolate : bool
        Move the machine's other movable tasks off the loop's core during each run
        (``run_hil(..., isolate=True)``; refused with ``realtime="off"``).
    host : str
        The address the server binds to: the Host names accepted are the loopback ones,
        and with a token this one too (:class:`~mrsuspension.monitor.security.MonitorGate`).
    max_body : int
        Largest request body [bytes] (413 beyond).

    Returns
    -------
    Starlette
        The ASGI app; ``app.state.monitor`` is its :class:`MonitorState`;
        ``app.state.logins`` the set of one-time login codes (``/?login=CODE`` sets the
        token's cookie once: for a browser the server opens itself).
    """
    if token:
        check_token(token)
    state = MonitorState(workdir, rig=rig, road_dir=road_dir, realtime=realtime, isolate=isolate)
    clients: set[WebSocket] = set()

    async def index(request: Request) -> HTMLResponse:
        return HTMLResponse((_static_dir() / "index.html").read_text(encoding="utf-8"))

    async def _json(request: Request) -> dict[str, Any]:
        # the gate has checked the content type and the size; the parser, the rest
        raw = loads_json(await request.body())
        if not isinstance(raw, dict):
            raise ValidationError("the request body must be a JSON object")
        return raw

    def _call(fn: Any) -> Any:
        async def endpoint(request: Request) -> JSONResponse:
            try:
                raw = await _json(request)
                info = await asyncio.to_thread(fn, raw)
            except RunBusyError as exc:
                return JSONResponse({"error": str(exc)}, status_code=409)
            except ValidationError as exc:
                return JSONResponse({"error": str(exc)}, status_code=400)
            return JSONResponse(info)

        return endpoint

    async def stop(request: Request) -> JSONResponse:
        await asyncio.to_thread(state.stop)
        return JSONResponse({"state": state.status.get("state")})

    async def controllers(request: Request) -> JSONResponse:
        return JSONResponse(await asyncio.to_thread(controller_forms))

    async def vehicles(request: Request) -> JSONResponse:
        return JSONResponse(vehicle_forms())

    async def status(request: Request) -> JSONResponse:
        state.poll()
        return JSONResponse(
            {**state.status, "acquisition": state.acquisition.describe(), "run": state.run_id}
        )

    async def recording(request: Request) -> Response:
        state.poll()
        try:
            path, rows = await asyncio.to_thread(state.export)
        except ValidationError as exc:
            return JSONResponse({"error": str(exc)}, status_code=404)
        return FileResponse(
            path, media_type="text/csv", filename=path.name, headers={"X-Rows": str(rows)}
        )

    async def ws(websocket: WebSocket) -> None:
        await websocket.accept()
        try:  # what happened so far, then the stream
            await websocket.send_json(state.history())
        except Exception:
            return
        clients.add(websocket)
        try:
            while True:
                await websocket.receive_text()  # keep-alive; commands go through HTTP
        except WebSocketDisconnect:
            pass
        finally:
            clients.discard(websocket)

    async def pump() -> None:
        loop = asyncio.get_running_loop()
        due = loop.time()
        while True:
            due += _FRAME
            now = loop.time()
            if due < now - 5 * _FRAME:  # far behind (suspended): do not burst
                due = now
            await asyncio.sleep(max(0.0, due - now))
            try:
                state.poll()
                frame = state.frame()
            except Exception:  # never let the stream die
                continue
            for client in list(clients):
                try:
                    await asyncio.wait_for(client.send_json(frame), timeout=0.5)
                except Exception:  # a dropped page never stops the run
                    clients.discard(client)

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        task = asyncio.create_task(pump())
        if attach is not None:
            await asyncio.to_thread(state.attach, attach)
        try:
            yield
        finally:
            task.cancel()
            state.stopped_by_shutdown = state.handle is not None and state.handle.alive()
            state.stop(shutdown=True)
            if state.handle is not None:
                await asyncio.to_thread(state.handle.join, _RETURN_WAIT)
                state.poll()  # the attached run's end, when the server stops first
                # free the loop's queues now: their named semaphores are released when
                # the objects are, which an interrupted command's os._exit would skip
                # (the resource tracker then warns of "leaked semaphore objects")
                state.handle = None
                gc.collect()

    def record(raw: dict[str, Any]) -> dict[str, Any]:
        return state.record(str(raw.get("action", "")))

    app = Starlette(
        routes=[
            Route("/", index),
            Route("/api/start", _call(state.start), methods=["POST"]),
            Route("/api/apply", _call(state.apply), methods=["POST"]),
            Route("/api/stop", stop, methods=["POST"]),
            Route("/api/record", _call(record), methods=["POST"]),
            Route("/api/acquisition", _call(state.set_acquisition), methods=["POST"]),
            Route("/api/controllers", controllers),
            Route("/api/vehicles", vehicles),
            Route("/api/status", status),
            Route("/api/recording", recording),
            WebSocketRoute("/ws", ws),
            Mount("/static", StaticFiles(directory=_static_dir()), name="static"),
        ],
        lifespan=lifespan,
    )
    app.state.monitor = state
    logins: set[str] = set()
    app.state.logins = logins
    app.add_middleware(MonitorGate, token=token, bind_host=host, max_body=max_body, logins=logins)
    return app
