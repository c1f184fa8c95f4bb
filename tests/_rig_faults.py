"""Rig faults for the interlock tests (issue 26): a simulated rig that gives a bad reading
from a chosen tick on and remembers its last command, the checks of a safe stop, and a
rig server in a thread of the test process (importable: ``pythonpath = ["tests"]``)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.hil import HilResult, RigSample, SimulatedRig, load_recording
from mrsuspension.hil.loop import STATE_TRIPPED
from mrsuspension.hil.network import serve_rig

NAN = float("nan")


class FaultyRig(SimulatedRig):
    """Reads ``fault`` (channel, value) from the ``at``-th read after the last reset on,
    and remembers the last command it was given (the rig's side of a safe stop)."""

    fault: tuple[str, float] = ("current", NAN)
    at: int = 200

    def reset(self, period: float) -> None:
        super().reset(period)
        self.reads = 0
        self.last_command: tuple[float, float] | None = None
        self.commands: list[tuple[float, float]] = []  # since the last reset

    def command(self, stroke: float, current_command: float, velocity: float = 0.0) -> None:
        self.last_command = (stroke, current_command)
        self.commands.append(self.last_command)
        super().command(stroke, current_command, velocity)

    def read(self) -> RigSample:
        self.reads += 1
        sample = super().read()
        if self.reads >= self.at:
            return sample._replace(**{self.fault[0]: self.fault[1]})
        return sample


def faulty_rig(damper: object, channel: str, value: float, at: int) -> FaultyRig:
    rig = FaultyRig(damper)  # type: ignore[arg-type]
    rig.fault = (channel, value)
    rig.at = at
    return rig


def check_interlock_stop(result: HilResult, rig: FaultyRig, reason: str, out: Path) -> int:
    """A trip with ``reason``; current 0 from the trip tick; the rig commanded home with
    the coil off (its side); the recording on disk complete. Returns the trip tick."""
    rec = result.recording
    assert result.tripped
    assert result.reason.startswith(reason), result.reason
    trip = int(np.argmax(rec["state"] == STATE_TRIPPED))
    assert np.all(rec["state"][trip:] == STATE_TRIPPED)
    assert rec["i_cmd"][:trip].max() > 0.0  # the rig was driven until then
    assert np.all(rec["i_cmd"][trip:] == 0.0)
    assert rec["x_cmd"][-1] == 0.0
    # the rig's side: its last command is mid-stroke with the coil off, and it went there
    assert rig.last_command == (0.0, 0.0)
    assert abs(rig.true_state["displacement"]) < 3e-3
    back = load_recording(out)
    assert back.complete
    assert back.reason.startswith(reason)
    assert back.stop["tripped"] is True
    assert len(back) == len(rec) == int(back.stop["rows"])
    return trip


def ideal_faulty_rig(channel: str = "current", value: float = NAN, at: int = 10**9) -> FaultyRig:
    """:func:`faulty_rig` with the ideal preset's settings (exact positions and currents)."""
    rig = FaultyRig(
        bandwidth=0.0, delay=0.0, coil_time_constant=0.0, force_noise=0.0,
        displacement_noise=0.0, current_noise=0.0, bits=0,
    )  # fmt: skip
    rig.fault = (channel, value)
    rig.at = at
    return rig


class Served:
    """A rig served in a thread: its port, the counts once stopped, the log lines."""

    def __init__(self) -> None:
        self.port = 0
        self.counts: dict[str, int] = {}
        self.lines: list[str] = []
        self.stop = threading.Event()
        self.done = threading.Event()

    def stopped(self, timeout: float = 10.0) -> dict[str, int]:
        """Stop the server; its counts."""
        self.stop.set()
        assert self.done.wait(timeout), "serve_rig did not stop"
        return self.counts


@contextmanager
def served(rig: Any, **kw: Any) -> Iterator[Served]:
    """``serve_rig(rig, port=0, **kw)`` in a daemon thread, logging into ``Served.lines``."""
    srv = Served()
    started = threading.Event()

    def ready(port: int) -> None:
        srv.port = port
        started.set()

    def run() -> None:
        try:
            counts = serve_rig(
                rig, port=0, ready=ready, should_stop=srv.stop.is_set, log=srv.lines.append, **kw
            )
            srv.counts.update(counts)
        finally:
            srv.done.set()

    threading.Thread(target=run, daemon=True).start()
    assert started.wait(30), "serve_rig did not start"
    try:
        yield srv
    finally:
        srv.stop.set()
        srv.done.wait(10)


def wait_for(cond: Callable[[], bool], timeout: float = 5.0, poll: float = 0.005) -> bool:
    """Poll ``cond`` until it is true (True) or ``timeout`` passes (False)."""
    end = time.monotonic() + timeout
    while not cond():
        if time.monotonic() > end:
            return False
        time.sleep(poll)
    return True
