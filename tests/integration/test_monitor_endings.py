"""Issue 26, section 1: the monitor's runs end safely whatever stops the server.

``hil run --monitor`` and ``mrsus monitor`` run their loop in a process of their own,
bound to the server. Ctrl-C (SIGINT to the process group, as a terminal sends it), a
terminal's hang-up (SIGHUP to the process group) and ``kill`` (SIGTERM to the command
only) each stop the running loop the safe way: the recording is complete and ends with
the rig commanded to mid-stroke with the current at 0, the command prints one
``interrupted:`` line naming the recording and exits 128 + the signal, without a
traceback, a warning or a process left behind.
"""

from __future__ import annotations

import contextlib
import json
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path
from typing import Any

import psutil
import pytest

from mrsuspension.hil.recorder import load_recording

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
STATE_RETURN = 2  # the loop's state while it returns the rig to mid-stroke


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _request(port: int, path: str, body: dict[str, Any] | None = None) -> dict[str, Any]:
    base = f"http://127.0.0.1:{port}"
    data = None if body is None else json.dumps(body).encode()
    headers = {"Origin": base, "Content-Type": "application/json"} if body is not None else {}
    req = urllib.request.Request(base + path, data=data, headers=headers)
    with urllib.request.urlopen(req, timeout=5) as r:
        return dict(json.loads(r.read()))


def _restore_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # as a terminal's foreground job


def _stopped_by(args: list[str], cwd: Path, how: str, start: dict[str, Any] | None) -> Any:
    """Run ``mrsus ARGS`` (a monitor on a free port), wait for its loop to drive the rig,
    send the signal ``how``; (exit code, stdout, stderr, processes left)."""
    port = _free_port()
    proc = subprocess.Popen(
        [sys.executable, "-m", "mrsuspension", *args, "--port", str(port)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        start_new_session=True,
        preexec_fn=_restore_sigint,
    )
    try:
        deadline = time.monotonic() + 90
        status: dict[str, Any] = {}
        while time.monotonic() < deadline:
            assert proc.poll() is None, proc.communicate()
            time.sleep(0.2)
            try:
                if start is not None:  # a run started from the page
                    _request(port, "/api/start", start)
                    start = None
                status = _request(port, "/api/status")
            except OSError:
                continue
            if status.get("state") == "running" and status.get("ticks", 0) > 1000:
                break
        assert status.get("state") == "running", status
        tree = [psutil.Process(proc.pid), *psutil.Process(proc.pid).children(recursive=True)]
        sig = {"sigint": signal.SIGINT, "sighup": signal.SIGHUP, "sigterm": signal.SIGTERM}[how]
        if how == "sigterm":
            os.kill(proc.pid, sig)  # `kill PID`: the command only
        else:
            os.killpg(proc.pid, sig)  # a terminal: the whole process group
        out, err = proc.communicate(timeout=60)
        time.sleep(0.2)
        left = [p.pid for p in tree if p.is_running() and p.status() != psutil.STATUS_ZOMBIE]
        return proc.returncode, out, err, left
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def _home(run_dir: Path) -> dict[str, Any]:
    rec = load_recording(run_dir)
    assert rec.complete, rec.stop
    assert rec.stop["rows"] == len(rec) > 1000
    assert rec["state"][-1] >= STATE_RETURN
    assert rec["x_cmd"][-1] == 0.0
    assert rec["i_cmd"][-1] == 0.0
    assert abs(rec["x_m"][-1]) < 2e-3  # the simulated rig measured it home
    return dict(rec.stop)


ENDINGS = {
    "sigint": (130, "interrupted (SIGINT"),
    "sighup": (129, "terminal hung up (SIGHUP)"),
    "sigterm": (143, "the monitor shut down"),  # the server's shutdown stops the loop
}


@pytest.mark.audit("hil endings")
@pytest.mark.parametrize("how", sorted(ENDINGS))
def test_hil_run_monitor_stops_its_loop_safely(tmp_path: Path, how: str) -> None:
    args = ["hil", "run", str(SCENARIO), "--monitor", "--duration", "30", "--rate", "1000"]
    args += ["--rig", "simulated", "--out", "rec"]
    code, _out, err, left = _stopped_by(args, tmp_path, how, None)
    expected, reason = ENDINGS[how]
    print(f"hil run --monitor, {how}: exit {code}; {err.strip()}")
    assert left == []
    assert code == expected
    assert "Traceback" not in err
    assert "Warning" not in err
    stop = _home(tmp_path / "rec" / "run-001")
    assert stop["reason"].startswith(reason)
    lines = [ln for ln in err.splitlines() if ln.startswith("interrupted: ")]
    assert len(lines) == 1, err
    assert lines[0].startswith("interrupted: kept the run's recording in 'rec/run-001' (loop")
    assert reason in lines[0]


@pytest.mark.audit("hil endings")
def test_monitor_hang_up_stops_a_run_started_from_the_page(tmp_path: Path) -> None:
    args = ["monitor", "--rig", "simulated", "--workdir", "runs"]
    start = {"controller": "passive", "excitation": "harmonic", "frequency": 2.0}
    start |= {"amplitude": 0.01, "duration": 30}
    code, _out, err, left = _stopped_by(args, tmp_path, "sighup", start)
    print(f"monitor, sighup: exit {code}; {err.strip()}")
    assert left == []
    assert code == 129
    assert "Traceback" not in err
    assert "Warning" not in err
    stop = _home(tmp_path / "runs" / "run-001")
    assert stop["reason"] == "terminal hung up (SIGHUP)"
    assert err.strip().splitlines()[-1] == (
        "interrupted: kept the runs recorded in 'runs' (a running loop stopped the safe way)"
    )
