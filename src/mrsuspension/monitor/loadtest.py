"""Load test of the monitor: the loop's deadlines with a page attached, against none.

:func:`measure` runs the same HiL scenario alternately **unmonitored** (``run_hil`` in
its own process, as ``mrsus hil run`` does) and **monitored** (started through the
monitor's API with a WebSocket client consuming every frame, as a page does) and reports
each run's deadline statistics, the frame rate the client saw and the ratio of the miss
rates. Alternating the two kinds of run, and comparing them within the same process and
minutes, keeps the comparison fair on a machine shared with other work.

Run it from the command line (``python -m mrsuspension.monitor.loadtest --help``).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import socket
import statistics
import tempfile
import threading
import time
import urllib.request
from pathlib import Path
from typing import Any, cast

__all__ = ["browser_run", "measure", "monitored_run", "unmonitored_run"]

_SETTINGS = {
    "controller": "skyhook-hilo",
    "mode": "ACM",
    "excitation": "harmonic",
    "frequency": 1.5,
    "amplitude": 0.02,
}


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def unmonitored_run(
    duration: float,
    rate: float,
    rig: str,
    workdir: Path,
    realtime: str = "auto",
    isolate: bool = False,
) -> dict[str, Any]:
    """The scenario through ``run_hil`` in its own process; its deadline figures."""
    from mrsuspension.engine.simulate import Simulation
    from mrsuspension.hil.loop import run_hil
    from mrsuspension.hil.rigs import make_rig
    from mrsuspension.monitor.settings import scenario_from_settings

    sim = cast(Simulation, scenario_from_settings({**_SETTINGS, "rate": rate}).simulation())
    out = Path(tempfile.mkdtemp(prefix="plain-", dir=workdir))
    result = run_hil(
        sim, make_rig(rig, sim.damper), duration=duration, rate=rate, out=out, process=True,
        realtime=realtime, isolate=isolate,
    )  # fmt: skip
    s = result.stats
    return {"ticks": s.ticks, "misses": s.misses, "in_deadline": s.in_deadline}


def _json_headers(base: str) -> dict[str, str]:
    """Headers of a state change sent to the monitor at ``base`` (its own origin, JSON)."""
    return {"Content-Type": "application/json", "Origin": base.rstrip("/")}


def monitored_run(
    base: str, duration: float, rate: float, timeout: float = 120.0
) -> dict[str, Any]:
    """The scenario started through the monitor at ``base`` with a WebSocket client.

    The client reads every frame (as a page does) from the start until the run ends.
    """
    from websockets.sync.client import connect

    frames: list[tuple[float, int, str]] = []
    done = threading.Event()

    def client() -> None:
        with connect(base.replace("http://", "ws://") + "ws") as ws:
            while not done.is_set():
                try:
                    msg = json.loads(ws.recv(timeout=1.0))
                except TimeoutError:
                    continue
                frames.append((time.perf_counter(), len(msg["rows"]), msg["status"]["state"]))

    reader = threading.Thread(target=client, daemon=True)
    cpu0, wall0 = time.process_time(), time.perf_counter()
    reader.start()
    body = json.dumps({**_SETTINGS, "rate": rate, "duration": duration}).encode()
    req = urllib.request.Request(base + "api/start", data=body, headers=_json_headers(base))
    with urllib.request.urlopen(req) as r:
        r.read()
    deadline = time.time() + timeout
    status: dict[str, Any] = {}
    while time.time() < deadline:
        time.sleep(0.25)
        with urllib.request.urlopen(base + "api/status") as r:
            status = json.loads(r.read())
        if status.get("state") in ("ended", "error") and "in_deadline" in status:
            break
    done.set()
    reader.join(5.0)
    server_cpu = (time.process_time() - cpu0) / (time.perf_counter() - wall0)
    live = [f for f in frames if f[2] in ("startup", "running")]
    span = live[-1][0] - live[0][0] if len(live) > 1 else 0.0
    return {
        "ticks": status.get("ticks", 0),
        "misses": status.get("misses", 0),
        "in_deadline": status.get("in_deadline", float("nan")),
        "frames": len(live),
        "frame_rate": (len(live) - 1) / span if span > 0 else 0.0,
        "rows": sum(f[1] for f in live),
        "reason": status.get("reason", ""),
        "server_cpu": server_cpu,
    }


def browser_run(
    page: Any, base: str, duration: float, rate: float, timeout: float = 120.0
) -> dict[str, Any]:
    """The scenario started through the monitor with the real page open in ``page``.

    ``page`` is a Playwright page showing the monitor (it draws every frame as a user's
    browser does); the frame rate is counted by the page.
    """
    body = json.dumps({**_SETTINGS, "rate": rate, "duration": duration}).encode()
    req = urllib.request.Request(base + "api/start", data=body, headers=_json_headers(base))
    cpu0, wall0 = time.process_time(), time.perf_counter()
    with urllib.request.urlopen(req) as r:
        r.read()
    deadline = time.time() + timeout
    status: dict[str, Any] = {}
    first: tuple[float, int] | None = None
    last: tuple[float, int] = (0.0, 0)
    while time.time() < deadline:
        time.sleep(0.25)
        with urllib.request.urlopen(base + "api/status") as r:
            status = json.loads(r.read())
        frames = int(page.evaluate("() => window.monitorState.frames"))
        if status.get("state") in ("startup", "running"):
            last = (time.perf_counter(), frames)
            if first is None:
                first = last
        if status.get("state") in ("ended", "error") and "in_deadline" in status:
            break
    server_cpu = (time.process_time() - cpu0) / (time.perf_counter() - wall0)
    span = last[0] - first[0] if first else 0.0
    return {
        "ticks": status.get("ticks", 0),
        "misses": status.get("misses", 0),
        "in_deadline": status.get("in_deadline", float("nan")),
        "frame_rate": (last[1] - first[1]) / span if first and span > 0 else 0.0,
        "reason": status.get("reason", ""),
        "server_cpu": server_cpu,
    }


def measure(
    duration: float = 5.0,
    rate: float = 1000.0,
    rig: str = "simulated",
    pairs: int = 1,
    browser: str | None = None,
    realtime: str = "auto",
    isolate: bool = False,
) -> dict[str, Any]:
    """Alternate ``pairs`` unmonitored and monitored runs; their figures and ratios.

    ``browser``: path of a chromium to attach the real page with (Playwright, headless)
    instead of a bare WebSocket client. ``realtime``: how both kinds of run are
    scheduled (``auto``, ``fifo``, ``spin``, ``off``); ``isolate``: both kinds of run move
    the machine's other movable tasks off the loop's core
    (:func:`~mrsuspension.hil.realtime.isolate_cpu`).

    Returns
    -------
    dict
        ``plain`` and ``monitored`` (lists of per-run figures), the median miss
        fractions ``miss_plain`` / ``miss_monitored``, the lowest client frame rate
        ``frame_rate_min`` [Hz] and the server's ``cpu`` load (``os.getloadavg``) at the
        start and the end.
    """
    import os

    import uvicorn

    from mrsuspension.hil.realtime import yield_loop_cpu
    from mrsuspension.monitor.app import create_app

    work = Path(tempfile.mkdtemp(prefix="mrsus-loadtest-"))
    port = _free_port()
    app = create_app(workdir=work, rig=rig, realtime=realtime, isolate=isolate)
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))

    def serve() -> None:
        # as `mrsus monitor` does: the server thread keeps off the loop's core
        with yield_loop_cpu() as cpus:
            app.state.monitor.loop_cpus = cpus
            server.run()

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    t_end = time.time() + 20
    while not server.started and time.time() < t_end:
        time.sleep(0.05)
    base = f"http://127.0.0.1:{port}/"
    load0 = os.getloadavg()
    plain: list[dict[str, Any]] = []
    monitored: list[dict[str, Any]] = []
    with contextlib.ExitStack() as stack:
        stack.callback(thread.join, 10)
        stack.callback(setattr, server, "should_exit", True)
        page = None
        if browser:
            from playwright.sync_api import sync_playwright

            with yield_loop_cpu():  # the browser's processes keep off the loop's core
                pw = stack.enter_context(sync_playwright())
                chromium = pw.chromium.launch(
                    executable_path=browser, args=["--no-sandbox", "--disable-gpu"]
                )
            stack.callback(chromium.close)
            page = chromium.new_page(viewport={"width": 1500, "height": 1100})
            page.goto(base)
        for k in range(pairs):
            order = ("plain", "monitored") if k % 2 == 0 else ("monitored", "plain")
            for kind in order:
                if kind == "plain":  # (this thread only waits for the loop process)
                    plain.append(unmonitored_run(duration, rate, rig, work, realtime, isolate))
                    continue
                # this thread polls the status (and drives the page) during the run: off
                # the loop's core, as the server and the browser are
                with yield_loop_cpu():
                    if page is not None:
                        monitored.append(browser_run(page, base, duration, rate))
                    else:
                        monitored.append(monitored_run(base, duration, rate))

    def miss(r: dict[str, Any]) -> float:
        return 1.0 - float(r["in_deadline"])

    return {
        "duration": duration,
        "rate": rate,
        "rig": rig,
        "plain": plain,
        "monitored": monitored,
        "miss_plain": statistics.median(miss(r) for r in plain),
        "miss_monitored": statistics.median(miss(r) for r in monitored),
        "frame_rate_min": min(r["frame_rate"] for r in monitored),
        "client": "browser" if browser else "websocket",
        "realtime": realtime,
        "isolate": isolate,
        "loadavg": [load0[0], os.getloadavg()[0]],
    }


def main(argv: list[str] | None = None) -> None:
    """Command line: print :func:`measure`'s figures as JSON."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    parser.add_argument("--duration", type=float, default=10.0, help="run length [s]")
    parser.add_argument("--rate", type=float, default=1000.0, help="loop rate [Hz]")
    parser.add_argument("--rig", default="simulated", help="simulated | ideal | udp://HOST:PORT")
    parser.add_argument("--pairs", type=int, default=3, help="unmonitored/monitored pairs")
    parser.add_argument(
        "--browser",
        default=None,
        help="chromium executable: attach the real page (Playwright) instead of a WebSocket client",
    )
    parser.add_argument(
        "--realtime", default="auto", help="loop scheduling: auto | fifo | spin | off"
    )
    parser.add_argument(
        "--isolate",
        action="store_true",
        help="move every other movable task off the loop's core during each run",
    )
    args = parser.parse_args(argv)
    result = measure(
        args.duration, args.rate, args.rig, args.pairs, args.browser, realtime=args.realtime,
        isolate=args.isolate,
    )  # fmt: skip
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
