"""Interlocks over the UDP rig (issue 26): a faulty reading from the served rig, or a
link that dies, trips a paced loop; the rig is commanded home with the coil off (checked
on the served rig itself) and the recording is complete.

The rig is served by ``serve_rig`` in a thread of the test process on an ephemeral
loopback port; the loop is paced with ``realtime="off"`` (no scheduling changes), its
watchdog at 0.2 s so that a loaded machine does not trip it spuriously.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path

import numpy as np
import pytest

from _rig_faults import NAN, FaultyRig, check_interlock_stop, faulty_rig, served, wait_for
from mrsuspension.control import HiLo
from mrsuspension.engine.simulate import Simulation
from mrsuspension.excitation import Harmonic
from mrsuspension.hil import RigSample, SafetyLimits, StartUp, run_hil
from mrsuspension.hil.network import UdpRig

RATE = 1000.0
LIMITS = SafetyLimits(watchdog=0.2)
AT = 200  # the served rig's read (= the client's command) that goes bad


def _sim() -> Simulation:
    return Simulation(Harmonic(1.5, 0.01), controller=HiLo(1, mode="ACM"), max_current=0.3)


@pytest.mark.audit("rig interlocks")
@pytest.mark.parametrize(
    ("channel", "value", "reason"),
    [
        ("current", NAN, "measured current is nan A: the rig's reading is not a number"),
        ("current", -5.0, "measured current -5 A is below -0.02 A: impossible from a unipolar"),
    ],
    ids=["nan-current", "minus-5A"],
)
def test_udp_rig_fault_trips_and_homes(
    tmp_path: Path, channel: str, value: float, reason: str
) -> None:
    sim = _sim()
    rig = faulty_rig(sim.damper, channel, value, at=AT)
    # no server watchdog: only the loop's own commands can bring the rig home
    with served(rig, watchdog=0.0) as srv:
        client = UdpRig("127.0.0.1", srv.port)
        out = tmp_path / "rec"
        result = run_hil(
            sim, client, duration=0.6, rate=RATE, out=out, limits=LIMITS,
            startup=StartUp.none(), realtime="off",
        )  # fmt: skip
        # the loop's last command (home, coil off) is not answered: wait until it is applied
        assert wait_for(lambda: rig.last_command == (0.0, 0.0), timeout=2.0), rig.last_command
        trip = check_interlock_stop(result, rig, reason, out)
        counts = srv.stopped()
    print(f"trip at tick {trip}: {result.reason}; client {client.counters()}; server {counts}")
    # the server reads its rig once on the reset, then once per command: read AT answers
    # the command of tick AT - 2, read by the loop in tick AT - 1 (later if it came late)
    assert AT - 1 <= trip <= AT + 50
    assert not any(line.startswith("stopping:") for line in srv.lines), srv.lines
    assert counts["bad_commands"] == 0


class LinkCutRig(FaultyRig):
    """Stops its server (the link dies: no replies, no heartbeats) at read ``at``."""

    cut: threading.Event

    def read(self) -> RigSample:
        sample = super().read()
        if self.reads == self.at:
            self.cut.set()
        return sample


@pytest.mark.audit("rig interlocks")
def test_udp_dead_link_trips_and_the_server_homes_its_rig(tmp_path: Path) -> None:
    sim = _sim()
    rig = LinkCutRig(sim.damper)
    rig.fault = ("force", 0.0)  # readings stay healthy until the link dies
    rig.at = AT
    with served(rig, watchdog=0.0, return_rate=0.2) as srv:
        rig.cut = srv.stop
        client = UdpRig("127.0.0.1", srv.port)
        out = tmp_path / "rec"
        result = run_hil(
            sim, client, duration=1.0, rate=RATE, out=out, limits=LIMITS,
            startup=StartUp.none(), realtime="off",
        )  # fmt: skip
        srv.stopped()
    print(f"dead link: {result.reason}; client {client.counters()}; server log {srv.lines}")
    assert result.reason.startswith("rig watchdog: no fresh sample for 0.2")
    assert "; link down (no heartbeat from the rig for " in result.reason
    # the rig's side: the server, at its end, ramped the driven rig home with the coil off
    assert any(line.startswith("stopping: coil off") for line in srv.lines), srv.lines
    trip = check_interlock_stop(result, rig, "rig watchdog", out)
    assert AT + 190 <= trip <= AT + 400  # 0.2 s without a fresh sample (+ the server's poll)
    assert np.all(
        result.recording["rig_time"][trip - 150 : trip] == result.recording["rig_time"][trip]
    )


@pytest.mark.audit("rig server")
def test_rig_emulator_survives_a_bad_reset_and_drops_strangers() -> None:
    """``mrsus rig-emulator``: a bad RESET is answered with an error and the emulator
    serves on (printing what it refused); a stranger's command is dropped; Ctrl-C ends it
    with the counts."""
    import signal
    import socket
    import subprocess
    import sys

    from mrsuspension.hil import network as N

    code = (
        "import typer\nfrom mrsuspension.cli.hil import rig_emulator_command\n"
        "typer.run(rig_emulator_command)"
    )
    proc = subprocess.Popen(
        [sys.executable, "-c", code, "--port", "0", "--rig", "ideal", "--realtime", "off"],
        stdout=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert "listening on udp://127.0.0.1:" in line, line
        port = int(line.rsplit(":", 1)[1])
        raw = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        raw.settimeout(5.0)
        raw.sendto(N._RESET.pack(N.MAGIC, N.VERSION, N.RESET, 9, 0.0, NAN), ("127.0.0.1", port))
        reply = N._SAMPLE.unpack(raw.recv(256))
        assert reply[3] == 9
        assert reply[-1] == N.STATUS_RESET | N.STATUS_FAULT
        assert "refused a reset from" in proc.stdout.readline()
        client = UdpRig("127.0.0.1", port)
        client.reset(1e-3)  # still serving
        cmd = N._COMMAND.pack(N.MAGIC, N.VERSION, N.COMMAND, 1, 0.0, 0.05, 0.0, 0.3)
        raw.sendto(cmd, ("127.0.0.1", port))
        assert "dropped a command from" in proc.stdout.readline()
        client.command(0.01, 0.1)
        deadline = time.monotonic() + 5.0  # the reply may come after a tick's wait (load)
        while client.read().displacement != pytest.approx(0.01):
            assert time.monotonic() < deadline, "the client's command was not applied"
            time.sleep(0.005)
        client.close()
        raw.close()
        proc.send_signal(signal.SIGINT)
        rest, _ = proc.communicate(timeout=20)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(10)
    print(rest)
    assert "stopping: coil off, returning the rig to mid-stroke from 0.01 m" in rest
    assert "stopped: commands 1," in rest
    assert "refused_resets 1, strangers 1," in rest
    assert proc.returncode == 0
