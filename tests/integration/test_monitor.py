"""Monitor end to end: load test against an unmonitored run, CLI (monitor, hil run --monitor)."""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from mrsuspension.cli import app
from mrsuspension.monitor.loadtest import measure

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"
MRSUS = [sys.executable, "-m", "mrsuspension.cli"]


@pytest.mark.realtime
@pytest.mark.slow
def test_deadlines_with_a_page_attached() -> None:
    """Issue 7: with a client consuming frames at >= 20 Hz the loop keeps its deadlines.

    An unmonitored and a monitored run (same scenario, rig, rate and seconds; the phase
    runs alone, so one pair: two were 10 s more of the CI's serial phase). On a
    shared machine the misses are the OS's release lateness, so the monitored miss rate
    is held against the unmonitored one; on a quiet machine (load average < 0.5) also
    against the HiL bound (90 % in deadline, docs/hil.md).
    """
    pytest.importorskip("websockets")
    quiet = os.getloadavg()[0] < 0.5
    d = measure(duration=3.0, rate=1000.0, rig="simulated", pairs=1)  # run alone: one pair
    for kind in ("plain", "monitored"):
        for r in d[kind]:
            print(kind, json.dumps(r))
    print(
        f"miss rate: unmonitored {d['miss_plain']:.4f}, monitored {d['miss_monitored']:.4f}; "
        f"client frames >= {d['frame_rate_min']:.1f} Hz; load average {d['loadavg']}"
    )
    for r in d["monitored"]:
        assert r["reason"] == "completed"
        assert r["frame_rate"] >= 20.0
        assert r["rows"] >= 0.9 * 100 * 3.0  # the display stream (100 Hz) arrived
        assert r["ticks"] >= 3000
    assert d["miss_monitored"] <= d["miss_plain"] * 1.5 + 0.15
    if quiet:
        assert d["miss_monitored"] <= 0.10


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _get(url: str) -> dict:  # type: ignore[type-arg]
    with urllib.request.urlopen(url, timeout=5) as r:
        return dict(json.loads(r.read()))


def test_hil_run_monitor_serves_the_attached_run(tmp_path: Path) -> None:
    port = _free_port()
    out = tmp_path / "rec"
    proc = subprocess.Popen(
        [*MRSUS, "hil", "run", str(SCENARIO), "--monitor", "--port", str(port),
         "--duration", "3", "--rate", "1000", "--rig", "ideal", "--out", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        base = f"http://127.0.0.1:{port}/"
        deadline = time.time() + 90
        status: dict = {}  # type: ignore[type-arg]
        while time.time() < deadline:
            time.sleep(0.5)
            try:
                status = _get(base + "api/status")
            except OSError:
                continue
            if status.get("state") == "ended":
                break
        assert status.get("state") == "ended", status
        assert status["rig"] == "ideal"
        assert status["reason"] == "completed"
        assert status["ticks"] >= 3000
        with urllib.request.urlopen(base + "api/recording", timeout=10) as r:
            lines = r.read().decode().splitlines()
        assert lines[0].startswith("time,state,")
        assert len(lines) > 3000
        assert (out / "run-001" / "meta.json").exists()  # written by the HiL recorder
    finally:
        proc.terminate()
        proc.wait(20)
    assert "mrsus monitor (ideal rig): http://localhost:" in (
        proc.stdout.read() if proc.stdout else ""
    )


def test_hil_run_monitor_json_prints_the_result_when_the_run_ends(tmp_path: Path) -> None:
    """Issue 7: ``--json`` with ``--monitor`` prints what ``hil run --json`` prints."""
    proc = subprocess.Popen(
        [*MRSUS, "hil", "run", str(SCENARIO), "--monitor", "--port", str(_free_port()),
         "--duration", "0.5", "--rate", "1000", "--rig", "ideal", "--json"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    lines: list[str] = []
    guard = threading.Timer(90.0, proc.kill)  # never hang on a JSON that does not come
    guard.start()
    try:
        assert proc.stdout is not None
        for line in proc.stdout:  # the JSON object ends with a closing brace at column 0
            lines.append(line)
            if line.rstrip() == "}":
                break
    finally:
        guard.cancel()
        proc.terminate()
        _, err = proc.communicate(timeout=20)
    info = json.loads("".join(lines))  # stdout holds the JSON only
    assert set(info) == {
        *("reason", "tripped", "ending", "signal", "rows", "out", "stats"),
        "rms_body_acceleration",
    }
    assert info["reason"] == "completed"
    assert info["out"] is None  # no --out: as `hil run --json`
    assert info["stats"]["ticks"] >= 500
    assert "mrsus monitor (ideal rig): http://localhost:" in err  # the address on stderr


def _monitored_json(args: list[str]) -> tuple[dict, subprocess.Popen]:  # type: ignore[type-arg]
    """Start ``hil run --monitor --json``, read the result JSON, stop the server."""
    proc = subprocess.Popen(
        [*MRSUS, "hil", "run", *args, "--monitor", "--port", str(_free_port()), "--json"],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    lines: list[str] = []
    guard = threading.Timer(90.0, proc.kill)
    guard.start()
    try:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.append(line)
            if line.rstrip() == "}":
                break
    finally:
        guard.cancel()
        proc.send_signal(signal.SIGINT)  # Ctrl-C: the server shuts down
        proc.communicate(timeout=20)
    return json.loads("".join(lines)), proc


def test_hil_run_monitor_exits_1_when_the_attached_run_trips(tmp_path: Path) -> None:
    """As `hil run`: a safety trip of the attached run is exit code 1 once served."""
    big = tmp_path / "big.toml"
    big.write_text(SCENARIO.read_text().replace("amplitude = 0.025", "amplitude = 0.3"))
    info, proc = _monitored_json([str(big), "--duration", "3", "--rate", "1000", "--rig", "ideal"])
    assert info["tripped"] is True  # 30 cm at 1.5 Hz: a force or stroke limit
    assert info["reason"] != "completed"
    assert proc.returncode == 1


def test_hil_run_monitor_exits_0_when_the_attached_run_completes() -> None:
    info, proc = _monitored_json(
        [str(SCENARIO), "--duration", "0.5", "--rate", "1000", "--rig", "ideal"]
    )
    assert info["reason"] == "completed"
    assert proc.returncode == 0


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["monitor", "--rig", "bogus"], "unknown --rig"),
        (["monitor", "--host", "0.0.0.0"], "token"),
        (["hil", "run", str(SCENARIO), "--monitor", "--rig", "simulatd"], "unknown --rig"),
        (["hil", "run", str(SCENARIO), "--monitor", "--rate", "10"], "rate"),
        (["monitor", "--realtime", "unpaced"], "runs in real time"),
        (["monitor", "--realtime", "spinn"], "spin"),
        (["monitor", "--realtime", "off", "--isolate"], "isolate needs a pinned loop"),
        (["hil", "run", str(SCENARIO), "--monitor", "--realtime", "fast"], "realtime"),
    ],
)
def test_cli_refuses_bad_options(args: list[str], fragment: str) -> None:
    # in-process (a refusal starts nothing; the real process's exit codes are the other
    # tests' here): a process each took 1.4 s of CPU, imports mostly
    res = CliRunner().invoke(app, args)
    assert res.exception is None or isinstance(res.exception, SystemExit), res.exception
    assert res.exit_code == 2, res.stderr
    assert fragment in res.stderr


def _udp_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_monitor_with_a_udp_rig(tmp_path: Path) -> None:
    """The monitor's loop drives a network rig (``mrsus rig-emulator``)."""
    from mrsuspension.monitor.app import MonitorState

    port = _udp_port()
    emu = subprocess.Popen(
        [*MRSUS, "rig-emulator", "--port", str(port)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        assert emu.stdout is not None
        assert "listening" in emu.stdout.readline()
        st = MonitorState(tmp_path, rig=f"udp://127.0.0.1:{port}")
        st.start({"controller": "skyhook-hilo", "excitation": "harmonic", "duration": 2})
        deadline = time.time() + 60
        while time.time() < deadline and st.status.get("state") not in ("ended", "error"):
            st.poll()
            time.sleep(0.05)
        assert st.status["state"] == "ended", st.status
        assert st.status["reason"] == "completed"
        assert st.status["ticks"] >= 2000
        f_dm = list(st.buffers["F_dm"])
        assert max(abs(f) for f in f_dm) > 100.0  # forces measured by the served rig
        assert st.handle is not None
        st.handle.join()
    finally:
        emu.terminate()
        emu.wait(10)


def test_api_acquisition_and_live_changes(tmp_path: Path) -> None:
    from starlette.testclient import TestClient

    from mrsuspension.monitor.app import create_app

    app = create_app(workdir=tmp_path, rig="ideal")
    state = app.state.monitor
    base = "http://127.0.0.1:8765"  # a loopback Host; state changes from its own origin
    with TestClient(app, base_url=base, headers={"Origin": base}) as client:
        # nothing running: a change is refused, no recording
        r = client.post("/api/apply", json={"sprung_mass": 600})
        assert r.status_code == 400
        assert "Start" in r.json()["error"]
        assert client.get("/api/recording").status_code == 404
        r = client.post("/api/acquisition", json={"acq_period": 0})
        assert r.status_code == 400
        assert "period" in r.json()["error"]
        r = client.post("/api/record", json={"action": "pause"})
        assert r.status_code == 400
        r = client.post(
            "/api/acquisition",
            json={"acq_period": 2, "trigger": "z_r", "trigger_level": 0.0, "pre_trigger": 0.1},
        )
        assert r.json()["period"] == 2
        r = client.post(
            "/api/start",
            json={"controller": "passive", "excitation": "harmonic", "frequency": 2.0,
                  "amplitude": 0.01, "duration": 3, "ramp_time": 0.1},
        )  # fmt: skip
        assert r.status_code == 200, r.text
        deadline = time.time() + 60
        while time.time() < deadline and state.status.get("state") != "running":
            time.sleep(0.1)
        time.sleep(0.6)
        r = client.post("/api/apply", json={"controller": "passive", "current": 0.3,
                                            "excitation": "harmonic", "frequency": 2.0,
                                            "amplitude": 0.01, "ramp_time": 0.1})  # fmt: skip
        assert r.status_code == 200, r.text
        r = client.post("/api/apply", json={"controller": "passive", "current": 0.9})
        assert r.status_code == 400  # above the 0.3 A HiL limit: refused by the server
        while time.time() < deadline and state.status.get("state") != "ended":
            time.sleep(0.2)
        assert state.status["state"] == "ended"
        assert state.status["applied"] == 1
        r = client.get("/api/recording")
        assert r.status_code == 200
        lines = r.text.splitlines()
        header = lines[0].split(",")
        data = np.array([[float(x) for x in line.split(",")] for line in lines[1:]])
    t, zr, i_cmd = data[:, 0], data[:, header.index("z_r")], data[:, header.index("i_cmd")]
    np.testing.assert_allclose(np.diff(t), 2e-3, atol=1e-9)  # every 2nd tick
    # the trigger: z_r (a sine from 0 at t = 0) first rises through 0 near t = 0.5 s; the
    # acquired rows start 0.1 s (the pre-trigger) before that crossing
    k = int(np.flatnonzero((zr[:-1] < 0.0) & (zr[1:] >= 0.0))[0]) + 1
    assert t[k] == pytest.approx(0.5, abs=2.5e-3)
    assert t[0] == pytest.approx(t[k] - 0.1, abs=2.5e-3)
    # the switch to 0.3 A ramped over 0.1 s: steps of at most 0.3 A x 2 ms / 0.1 s (+ 1 LSB)
    assert i_cmd.max() == pytest.approx(0.3, abs=1e-3)
    assert np.max(np.diff(i_cmd)) <= 0.3 * 2e-3 / 0.1 + 0.5 / 4096 + 1e-9


def test_a_half_car_run_streams_its_corner_and_the_body(tmp_path: Path) -> None:
    """Issue 28: ``hil run HALF_CAR --monitor``'s attached run (one corner on the rig) is
    streamed as that corner's quarter-car channels plus the body's heave, pitch and roll;
    a live change is refused (the page's form describes a quarter car)."""
    from starlette.testclient import TestClient

    from mrsuspension.hil.loop import _simulation_of
    from mrsuspension.monitor.app import AttachedRun, create_app

    car = _simulation_of(ROOT / "examples" / "vehicles" / "half_car.toml")
    run = AttachedRun(car, rate=1000.0, duration=1.5, corner="rear")
    app = create_app(workdir=tmp_path, rig="ideal", realtime="off", attach=run)
    state = app.state.monitor
    base = "http://127.0.0.1:8765"
    rows: list[list[float | None]] = []
    with TestClient(app, base_url=base, headers={"Origin": base}) as client:
        with client.websocket_connect("ws://127.0.0.1:8765/ws", headers={"Origin": base}) as ws:
            channels = ws.receive_json()["channels"]
            r = client.post("/api/apply", json={"controller": "passive", "current": 0.2})
            assert r.status_code == 400
            assert "half or full car" in r.json()["error"]
            deadline = time.time() + 90
            while time.time() < deadline and state.status.get("state") != "ended":
                rows += ws.receive_json()["rows"]
        assert state.status["state"] == "ended", state.status
        assert state.status["reason"] == "completed"
        assert state.status["corner"] == "rear"
    for name in ("heave", "pitch", "roll", "z_s", "F_dm"):
        assert name in channels
    body = np.array([[r[channels.index(n)] for n in ("heave", "pitch")] for r in rows])
    assert len(rows) > 100
    assert np.all(np.isfinite(body))
    assert np.ptp(body[:, 0]) > 1e-3  # the body heaves on the 1 cm road
    assert all(r[channels.index("roll")] == 0.0 for r in rows)  # a half car does not roll
