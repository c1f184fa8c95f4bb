"""Monitor end to end: load test against an unmonitored run, CLI (monitor, hil run --monitor)."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

from mrsuspension.monitor.loadtest import measure

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"
MRSUS = [sys.executable, "-m", "mrsuspension.cli"]


@pytest.mark.slow
def test_deadlines_with_a_page_attached() -> None:
    """Issue 7: with a client consuming frames at >= 20 Hz the loop keeps its deadlines.

    Unmonitored and monitored runs alternate (same scenario, rig, rate and minutes). On a
    shared machine the misses are the OS's release lateness, so the monitored miss rate
    is held against the unmonitored one; on a quiet machine (load average < 0.5) also
    against the HiL bound (90 % in deadline, docs/hil.md).
    """
    pytest.importorskip("websockets")
    quiet = os.getloadavg()[0] < 0.5
    d = measure(duration=4.0, rate=1000.0, rig="simulated", pairs=2)
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
        assert r["rows"] >= 0.9 * 100 * 4.0  # the display stream (100 Hz) arrived
        assert r["ticks"] >= 4000
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
         "--duration", "3", "--rig", "ideal", "--out", str(out)],
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


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["monitor", "--rig", "bogus"], "unknown --rig"),
        (["monitor", "--host", "0.0.0.0"], "token"),
        (["hil", "run", str(SCENARIO), "--monitor", "--rig", "simulatd"], "unknown --rig"),
        (["hil", "run", str(SCENARIO), "--monitor", "--rate", "10"], "rate"),
    ],
)
def test_cli_refuses_bad_options(args: list[str], fragment: str) -> None:
    res = subprocess.run([*MRSUS, *args], capture_output=True, text=True, timeout=60)
    assert res.returncode == 2, res.stderr
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
