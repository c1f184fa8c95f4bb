"""The monitor's ASGI application (Starlette): page, JSON API, WebSocket stream.

Routes: ``GET /`` (the page), ``/static/...`` (its JS and CSS, package data),
``POST /api/start`` (validated settings -> a new run; a :class:`ValidationError` comes
back as ``400 {"error": ...}``), ``POST /api/stop``, ``GET /api/status``,
``GET /api/recording`` (CSV of the last run) and ``WS /ws`` (JSON frames at about 20 Hz:
new decimated samples, loop status, live measures). When the app has an access token
every request must carry ``?token=...``.
"""

from __future__ import annotations

import asyncio
import contextlib
import hmac
import math
import tempfile
from collections import deque
from collections.abc import AsyncIterator
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np
from starlette.applications import Starlette
from starlette.requests import Request
from starlette.responses import FileResponse, HTMLResponse, JSONResponse, Response
from starlette.routing import Mount, Route, WebSocketRoute
from starlette.staticfiles import StaticFiles
from starlette.types import ASGIApp, Receive, Scope, Send
from starlette.websockets import WebSocket, WebSocketDisconnect

from mrsuspension.errors import ValidationError
from mrsuspension.measures.steady import G, T_as, T_au, T_dr, T_ds, T_du, dlc
from mrsuspension.monitor.runner import DISPLAY_CHANNELS, DISPLAY_RATE, LoopHandle
from mrsuspension.monitor.settings import MonitorSettings, scenario_from_settings

__all__ = ["MonitorState", "create_app", "live_measures"]

#: seconds of display samples kept by the server
_KEEP = 10.0
#: frame period of the WebSocket stream [s]
_FRAME = 0.05


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


class MonitorState:
    """The server's state: current run, display buffers, connected pages.

    Parameters
    ----------
    workdir : path, optional
        Where recordings are written (default: a temporary directory).
    """

    def __init__(self, workdir: Path | None = None) -> None:
        self.workdir = Path(workdir or tempfile.mkdtemp(prefix="mrsus-monitor-"))
        self.handle: LoopHandle | None = None
        self.settings: MonitorSettings | None = None
        self.run_id = 0
        self.status: dict[str, Any] = {"state": "idle", "reason": ""}
        self.recording: Path | None = None
        maxlen = int(_KEEP * DISPLAY_RATE)
        self.buffers: dict[str, deque[float]] = {c: deque(maxlen=maxlen) for c in DISPLAY_CHANNELS}
        self.fresh: list[list[float]] = []
        self.static_load = 0.0

    def start(self, raw: dict[str, Any]) -> dict[str, Any]:
        """Validate ``raw`` settings and start a run (stopping any running one)."""
        settings = scenario_from_settings(raw)  # raises ValidationError
        self.stop()
        if self.handle is not None:
            self.handle.join(2.0)
        self.run_id += 1
        self.settings = settings
        vehicle = settings.scenario().simulations()[0].vehicle
        self.static_load = (vehicle.sprung_mass + vehicle.unsprung_mass) * G
        for buf in self.buffers.values():
            buf.clear()
        self.fresh = []
        out = self.workdir / f"run-{self.run_id:03d}.csv"
        self.recording = None
        self.status = {"state": "starting", "reason": "", "run": self.run_id}
        self.handle = LoopHandle(settings.to_dict(), out)
        return {"run": self.run_id, "tables": settings.tables}

    def stop(self) -> None:
        """Ask the running loop to stop."""
        if self.handle is not None and self.handle.alive():
            self.handle.stop()
            self.status["state"] = "stopping"

    def poll(self) -> None:
        """Take what the loop sent (never blocks)."""
        h = self.handle
        if h is None:
            return
        for kind, msg in h.drain():
            if kind == "data":
                rows = np.asarray(msg, dtype=float)
                for i, name in enumerate(DISPLAY_CHANNELS):
                    self.buffers[name].extend(rows[:, i].tolist())
                self.fresh.extend(rows.tolist())
            elif kind == "status":
                self.status.update(msg)
            elif kind == "end":
                self.status.update(msg)
                self.status["safe"] = True
                if h.out.exists():
                    self.recording = h.out
        if not h.alive() and self.status.get("state") in ("starting", "running", "stopping"):
            if h.out.exists():
                self.recording = h.out
            self.status.update({"state": "ended", "safe": True})

    def frame(self) -> dict[str, Any]:
        """One WebSocket frame: new samples, status and live measures."""
        data = {k: np.fromiter(v, dtype=float) for k, v in self.buffers.items()}
        fresh, self.fresh = self.fresh, []
        return {
            "run": self.run_id,
            "channels": list(DISPLAY_CHANNELS),
            "rows": fresh,
            "status": self.status,
            "measures": live_measures(data, self.static_load) if self.static_load else {},
            "recording": self.recording is not None,
        }


class TokenGate:
    """ASGI middleware refusing requests without the access token (``?token=``)."""

    def __init__(self, app: ASGIApp, token: str) -> None:
        self.app = app
        self.token = token

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] in ("http", "websocket"):
            from urllib.parse import parse_qs

            query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
            given = (query.get("token") or [""])[0]
            if not hmac.compare_digest(given.encode(), self.token.encode()):
                if scope["type"] == "websocket":
                    await send({"type": "websocket.close", "code": 1008})
                    return
                response = Response("access token required", status_code=403)
                await response(scope, receive, send)
                return
        await self.app(scope, receive, send)


def _static_dir() -> Path:
    return Path(str(resources.files("mrsuspension.monitor") / "static"))


def create_app(token: str | None = None, workdir: Path | None = None) -> Starlette:
    """Build the monitor application.

    Parameters
    ----------
    token : str, optional
        Access token every request must carry as ``?token=...`` (required by
        :func:`~mrsuspension.monitor.cli.monitor_command` off loopback).
    workdir : path, optional
        Directory for the recordings (default: a temporary one).

    Returns
    -------
    Starlette
        The ASGI app; ``app.state.monitor`` is its :class:`MonitorState`.
    """
    state = MonitorState(workdir)
    clients: set[WebSocket] = set()

    async def index(request: Request) -> HTMLResponse:
        return HTMLResponse((_static_dir() / "index.html").read_text(encoding="utf-8"))

    async def start(request: Request) -> JSONResponse:
        try:
            raw = await request.json()
            if not isinstance(raw, dict):
                raise ValidationError("settings must be a JSON object")
            info = await asyncio.to_thread(state.start, raw)
        except ValidationError as exc:
            return JSONResponse({"error": str(exc)}, status_code=400)
        except ValueError as exc:
            return JSONResponse({"error": f"bad request: {exc}"}, status_code=400)
        return JSONResponse(info)

    async def stop(request: Request) -> JSONResponse:
        state.stop()
        return JSONResponse({"state": state.status.get("state")})

    async def status(request: Request) -> JSONResponse:
        state.poll()
        return JSONResponse(state.status)

    async def recording(request: Request) -> Response:
        state.poll()
        if state.recording is None or not state.recording.exists():
            return JSONResponse({"error": "no recording yet (stop a run first)"}, status_code=404)
        return FileResponse(state.recording, media_type="text/csv", filename=state.recording.name)

    async def ws(websocket: WebSocket) -> None:
        await websocket.accept()
        clients.add(websocket)
        try:
            while True:
                await websocket.receive_text()  # keep-alive; commands go through HTTP
        except WebSocketDisconnect:
            pass
        finally:
            clients.discard(websocket)

    async def pump() -> None:
        while True:
            await asyncio.sleep(_FRAME)
            state.poll()
            if not clients:
                state.fresh = []
                continue
            frame = state.frame()
            for client in list(clients):
                try:
                    await asyncio.wait_for(client.send_json(frame), timeout=0.5)
                except Exception:  # a dropped page never stops the run
                    clients.discard(client)

    @contextlib.asynccontextmanager
    async def lifespan(app: Starlette) -> AsyncIterator[None]:
        task = asyncio.create_task(pump())
        try:
            yield
        finally:
            task.cancel()
            state.stop()
            if state.handle is not None:
                state.handle.join(2.0)

    app = Starlette(
        routes=[
            Route("/", index),
            Route("/api/start", start, methods=["POST"]),
            Route("/api/stop", stop, methods=["POST"]),
            Route("/api/status", status),
            Route("/api/recording", recording),
            WebSocketRoute("/ws", ws),
            Mount("/static", StaticFiles(directory=_static_dir()), name="static"),
        ],
        lifespan=lifespan,
    )
    app.state.monitor = state
    if token:
        app.add_middleware(TokenGate, token=token)
    return app
