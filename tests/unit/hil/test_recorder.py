"""The HiL recorder: a shared-memory ring in the loop, a writer process behind it."""

from __future__ import annotations

import gc
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import SimulatedRig, load_recording, run_hil
from mrsuspension.hil import _recwriter as rw
from mrsuspension.hil.realtime import pick_cpu
from mrsuspension.hil.recorder import STOP_FILE, Recorder


def _rows(k0: int, k1: int) -> np.ndarray:
    """Rows whose values tell their index: (k, 2k, -k)."""
    k = np.arange(k0, k1, dtype=float)
    return np.column_stack([k, 2 * k, -k])


def test_every_row_written_in_order_through_a_small_ring(tmp_path: Path) -> None:
    rec = Recorder(tmp_path, ["k", "two_k", "minus_k"], buffer_rows=64, wait=True)
    rows = _rows(0, 5000)  # 78 times the ring
    for row in rows:
        rec.append(row)
    rec.close({"reason": "completed"})
    back = load_recording(tmp_path)
    np.testing.assert_array_equal(back["k"], rows[:, 0])
    np.testing.assert_array_equal(back["minus_k"], rows[:, 2])
    assert back.complete
    assert back.stop["rows"] == 5000
    assert back.stop["dropped_rows"] == 0
    assert rec.written_rows == 5000
    assert rec.dropped_rows == 0


def test_a_stalled_writer_costs_counted_rows_never_torn_ones(tmp_path: Path) -> None:
    rec = Recorder(tmp_path, ["k", "two_k", "minus_k"], buffer_rows=100, flush_interval=0.001)
    for row in _rows(0, 50):
        rec.append(row)
    deadline = time.monotonic() + 10
    while rec._head[rw.CONSUMED] < 50 and time.monotonic() < deadline:
        time.sleep(0.001)
    os.kill(rec._proc.pid, signal.SIGSTOP)  # the writer stops; the loop must not wait
    try:
        t0 = time.perf_counter()
        for row in _rows(50, 1050):
            rec.append(row)
        assert time.perf_counter() - t0 < 1.0
    finally:
        os.kill(rec._proc.pid, signal.SIGCONT)
    rec.close({"reason": "completed"})
    back = load_recording(tmp_path)
    k = back["k"]
    np.testing.assert_array_equal(back["two_k"], 2 * k)  # no row mixes two ticks
    np.testing.assert_array_equal(back["minus_k"], -k)
    np.testing.assert_array_equal(k[:50], np.arange(50))  # before the stall: all of them
    np.testing.assert_array_equal(k[50:], np.arange(1050 - len(k) + 50, 1050))  # the newest
    assert rec.dropped_rows == 1050 - len(k) >= 900
    assert back.stop["dropped_rows"] == rec.dropped_rows
    assert back.stop["rows"] == len(k)


def _alive(pid: int) -> bool:
    """Whether a process runs (a zombie waiting to be reaped does not)."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except FileNotFoundError:
        return False
    return "State:\tZ" not in status


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_a_killed_loop_process_loses_no_published_row(tmp_path: Path) -> None:
    script = textwrap.dedent(
        f"""
        import os, signal
        from mrsuspension.hil.recorder import Recorder
        rec = Recorder({str(tmp_path)!r}, ["k", "two_k"], flush_interval=1.0)
        for k in range(3000):
            rec.append((float(k), 2.0 * k))
        print(rec._proc.pid, flush=True)
        os.kill(os.getpid(), signal.SIGKILL)  # before the writer's next flush
        """
    )
    proc = subprocess.run([sys.executable, "-c", script], timeout=120, capture_output=True)
    assert proc.returncode == -signal.SIGKILL
    writer = int(proc.stdout.split()[-1])
    deadline = time.monotonic() + 20  # the orphaned writer drains, then ends
    while time.monotonic() < deadline and _alive(writer):
        time.sleep(0.05)
    assert not _alive(writer)
    back = load_recording(tmp_path)
    assert not back.complete
    np.testing.assert_array_equal(back["k"], np.arange(3000))
    assert json.loads((tmp_path / STOP_FILE).read_text())["status"] == "running"


def test_ctrl_c_to_the_process_group_does_not_stop_the_writer(tmp_path: Path) -> None:
    rec = Recorder(tmp_path, ["k", "two_k", "minus_k"], flush_interval=0.001)
    for row in _rows(0, 100):
        rec.append(row)
    os.kill(rec._proc.pid, signal.SIGINT)
    time.sleep(0.05)
    assert rec._proc.poll() is None
    for row in _rows(100, 200):
        rec.append(row)
    rec.close({"reason": "interrupted by the user"})
    assert len(load_recording(tmp_path)) == 200


def test_a_dead_writer_is_reported_in_the_recording_and_raised(tmp_path: Path) -> None:
    rec = Recorder(tmp_path, ["k", "two_k", "minus_k"])
    rec._proc.kill()
    rec._proc.wait()
    rec.append((1.0, 2.0, -1.0))
    with pytest.raises(MRSuspensionError, match="writer failed"):
        rec.close({"reason": "completed"})
    stop = json.loads((tmp_path / STOP_FILE).read_text())
    assert stop["status"] == "stopped"
    assert "writer failed" in stop["recorder_error"]
    with pytest.raises(MRSuspensionError, match="already closed"):
        rec.close({"reason": "completed"})


def test_an_unclosed_recorder_leaves_no_writer_behind(tmp_path: Path) -> None:
    rec = Recorder(tmp_path, ["k"])
    rec.append((1.0,))
    proc = rec._proc
    del rec
    gc.collect()
    assert proc.poll() == 0
    assert load_recording(tmp_path)["k"].tolist() == [1.0]


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"buffer_rows": 1}, "buffer_rows"),
        ({"flush_interval": 0.0}, "flush_interval"),
        ({"flush_interval": float("nan")}, "flush_interval"),
    ],
)
def test_bad_settings_are_refused(tmp_path: Path, kw: dict[str, float], match: str) -> None:
    with pytest.raises(ValidationError, match=match):
        Recorder(tmp_path, ["k"], **kw)  # type: ignore[arg-type]


class _Watching(SimulatedRig):
    """A simulated rig that looks at its own process while the ticks run."""

    reads = 0

    def read(self):  # type: ignore[no-untyped-def]
        self.reads += 1
        if self.reads == 50:  # while the ticks run (the first read is the warm-up's)
            self.threads = threading.active_count()
            me = os.getpid()
            self.writers = {}
            for child in Path(f"/proc/{me}/task/{me}/children").read_text().split():
                cmdline = Path(f"/proc/{child}/cmdline").read_bytes()
                if b"_recwriter.py" in cmdline:
                    self.writers[int(child)] = os.sched_getaffinity(int(child))
        return super().read()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_the_loop_process_has_no_recorder_thread_and_its_writer_keeps_off_its_core() -> None:
    rig = _Watching()
    before = threading.active_count()
    result = run_hil(Simulation(Harmonic(1.5, 0.01)), rig, duration=0.3, realtime="off")
    assert result.reason == "completed"
    assert rig.threads == before  # nothing started a thread for the recording
    assert len(rig.writers) == 1  # the writer is a child process, running during the ticks
    loop_cpu = pick_cpu("loop")
    if loop_cpu is not None:
        assert loop_cpu not in next(iter(rig.writers.values()))
    assert len(result.recording) == result.recording.stop["rows"] == result.stats.ticks
