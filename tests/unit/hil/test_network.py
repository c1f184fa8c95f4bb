"""The UDP rig protocol: message layout, address parsing, a client against a server thread."""

from __future__ import annotations

import math
import random
import socket
import struct
import threading
import time
from collections.abc import Iterator

import numpy as np
import pytest

from _rig_faults import ideal_faulty_rig, served, wait_for
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.hil import SafetyLimits, SafetySupervisor, SimulatedRig, ideal_rig
from mrsuspension.hil import network as N
from mrsuspension.hil.network import UdpRig, parse_udp_spec, serve_rig


def test_message_layout() -> None:
    assert N._COMMAND.size == 44
    assert N._SAMPLE.size == 48
    assert N._HEARTBEAT.size == 20
    assert N._RESET.size == 28
    assert struct.pack("<I", N.MAGIC) == b"MRSU"
    cmd = N._COMMAND.pack(N.MAGIC, N.VERSION, N.COMMAND, 7, 1.0, 0.01, 0.1, 0.2)
    assert N._kind(cmd) == N.COMMAND
    assert N._kind(cmd[:-1]) == 0  # wrong size
    assert N._kind(b"XXXX" + cmd[4:]) == 0  # wrong magic
    bad_version = N._COMMAND.pack(N.MAGIC, 99, N.COMMAND, 7, 1.0, 0.0, 0.0, 0.0)
    assert N._kind(bad_version) == 0


def test_parse_udp_spec() -> None:
    assert parse_udp_spec("udp://127.0.0.1:9870") == ("127.0.0.1", 9870)
    assert parse_udp_spec("UDP://rig.local:5000/") == ("rig.local", 5000)
    assert parse_udp_spec("udp://[::1]:5000") == ("::1", 5000)
    for bad in ("tcp://a:1", "udp://a", "udp://:80", "udp://a:0", "udp://a:x"):
        with pytest.raises(ValidationError):
            parse_udp_spec(bad)


@pytest.fixture
def server() -> Iterator[tuple[int, dict[str, int]]]:
    port: list[int] = []
    started = threading.Event()
    stop = threading.Event()
    counts: dict[str, int] = {}

    def ready(p: int) -> None:
        port.append(p)
        started.set()

    def run() -> None:
        counts.update(serve_rig(ideal_rig(), port=0, ready=ready, should_stop=stop.is_set))

    th = threading.Thread(target=run, daemon=True)
    th.start()
    assert started.wait(30)
    yield port[0], counts
    stop.set()
    th.join(5)


def test_client_against_a_server_thread(server: tuple[int, dict[str, int]]) -> None:
    port, _ = server
    rig = UdpRig("127.0.0.1", port, timeout=0.05)
    assert rig.ping() < 0.5
    rig.reset(1e-3)
    assert rig.ideal_current
    assert rig.read().timestamp == 0.0
    for k in range(1, 6):
        rig.command(0.001 * k, 0.1, 0.0)
        s = rig.read()
        assert s.displacement == pytest.approx(0.001 * k)
        assert s.timestamp == pytest.approx(1e-3 * k)
    # garbage is ignored by both sides
    raw = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    raw.sendto(b"hello", ("127.0.0.1", port))
    raw.close()
    assert rig.counters() == {"sent": 5, "received": 5, "lost": 0, "late": 0, "stale_reads": 0}
    rig.close()
    assert UdpRig("127.0.0.1", port).describe()["address"] == f"udp://127.0.0.1:{port}"


def test_client_without_a_server() -> None:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    rig = UdpRig("127.0.0.1", port, reset_timeout=0.05)
    with pytest.raises(MRSuspensionError, match="no reply"):
        rig.reset(1e-3)
    rig.close()


def test_stale_sample_is_held(server: tuple[int, dict[str, int]]) -> None:
    port, _ = server
    rig = UdpRig("127.0.0.1", port, timeout=0.0)
    rig.reset(1e-3)
    first = rig.read()
    rig._seq += 1  # pretend a command went out whose reply never comes
    rig.sent += 1
    assert rig.read() == first
    assert rig.stale_reads == 1
    rig.close()


def _serve_in_thread(rig: object, **kw: object) -> tuple[int, dict[str, int], threading.Event]:
    port: list[int] = []
    started = threading.Event()
    stop = threading.Event()
    counts: dict[str, int] = {}

    def run() -> None:
        counts.update(
            serve_rig(
                rig,  # type: ignore[arg-type]
                port=0,
                ready=lambda p: (port.append(p), started.set()),  # type: ignore[func-returns-value]
                should_stop=stop.is_set,
                **kw,  # type: ignore[arg-type]
            )
        )
        counts["done"] = 1

    threading.Thread(target=run, daemon=True).start()
    assert started.wait(30)
    return port[0], counts, stop


def _stopped(counts: dict[str, int], stop: threading.Event) -> dict[str, int]:
    stop.set()
    deadline = time.monotonic() + 5
    while "done" not in counts and time.monotonic() < deadline:
        time.sleep(0.01)
    assert "done" in counts
    return counts


def test_heartbeats_both_directions() -> None:
    port, counts, stop = _serve_in_thread(ideal_rig(), heartbeat=0.005)
    rig = UdpRig("127.0.0.1", port, heartbeat=0.005)
    rig.reset(1e-3)
    t_end = time.perf_counter() + 0.2
    ticks = 0
    while time.perf_counter() < t_end:
        rig.command(0.001, 0.0, 0.0)
        rig.read()
        ticks += 1
        time.sleep(1e-3)
    time.sleep(0.02)
    rig.read()  # drain the last beats and acks
    link = rig.link()
    rig.close()
    counts = _stopped(counts, stop)
    print(f"{ticks} ticks; client {link}; server {counts}")
    # the client beats every 5 ms with its commands; the server every 5 ms on its own
    assert 20 <= link["heartbeats_sent"] <= 45
    assert counts["heartbeats"] == link["heartbeats_sent"]  # every beat arrived
    assert link["heartbeat_acks"] == link["heartbeats_sent"]  # and was acknowledged
    assert 0.0 < link["rtt"] <= link["rtt_max"] < 0.1
    # the server kept beating after the client's last read: it sent at least as many
    assert 20 <= link["heartbeats_received"] <= counts["heartbeats_sent"] <= 60
    assert counts["heartbeat_acks"] == link["heartbeats_received"]
    assert counts["watchdog_trips"] == 0
    assert not link["rig_safe"]
    assert rig.counters()["lost"] == 0  # beats do not disturb the command sequence


def test_server_watchdog_makes_the_rig_safe() -> None:
    served = ideal_rig()
    port, counts, stop = _serve_in_thread(served, watchdog=0.05, return_rate=0.1)
    rig = UdpRig("127.0.0.1", port, timeout=0.05)
    rig.reset(1e-3)
    for _ in range(20):
        rig.command(0.02, 0.2, 0.0)
        rig.read()
    assert served.true_state["displacement"] == pytest.approx(0.02)
    assert served.true_state["current"] == pytest.approx(0.2)
    # the client goes silent: after 50 ms the server turns the coil off and ramps the
    # actuator home at 0.1 m/s (0.2 s for 2 cm)
    time.sleep(0.03)
    assert counts.get("watchdog_trips", 0) == 0
    assert served.true_state["current"] > 0.1
    time.sleep(0.5)
    assert served.true_state["current"] == 0.0
    assert served.true_state["displacement"] == pytest.approx(0.0, abs=1e-9)
    held = rig.read()
    rig.command(0.03, 0.2, 0.0)  # ignored until the next reset
    assert rig.read() == held  # the SAFE sample is not taken as fresh
    assert rig.rig_safe
    assert served.true_state["displacement"] == pytest.approx(0.0, abs=1e-9)
    rig.reset(1e-3)  # a reset re-arms
    rig.command(0.01, 0.1, 0.0)
    assert rig.read().displacement == pytest.approx(0.01)
    assert not rig.rig_safe
    rig.close()
    counts = _stopped(counts, stop)
    assert counts["watchdog_trips"] >= 1


def test_server_options_are_checked() -> None:
    for kw, fragment in (
        ({"heartbeat": -1.0}, "heartbeat"),
        ({"watchdog": float("nan")}, "watchdog"),
        ({"realtime": "unpaced"}, "realtime must be"),
        ({"realtime": "sometimes"}, "'sometimes'"),
    ):
        with pytest.raises(ValidationError, match=fragment):
            serve_rig(ideal_rig(), port=0, duration=0.01, **kw)  # type: ignore[arg-type]
    with pytest.raises(ValidationError, match="heartbeat"):
        UdpRig("127.0.0.1", 9, heartbeat=20.0)


def test_watchdog_reason_tells_link_alive_from_link_down() -> None:
    port, counts, stop = _serve_in_thread(ideal_rig(), heartbeat=0.005)
    rig = UdpRig("127.0.0.1", port, heartbeat=0.005, timeout=0.002)
    assert rig.link_status() == "link down (no heartbeat from the rig since the reset)"
    rig.reset(1e-3)
    for _ in range(30):
        rig.command(0.0, 0.0, 0.0)
        rig.read()
        time.sleep(1e-3)
    assert rig.link_status().startswith("link alive"), rig.link_status()
    _stopped(counts, stop)  # the server is gone: no replies, no heartbeats
    rig.read()  # take what was still queued (the loop reads every tick)
    time.sleep(0.05)
    rig.command(0.0, 0.0, 0.0)
    rig.read()
    assert rig.link_status().startswith("link down (no heartbeat from the rig for 0.0")
    supervisor = SafetySupervisor(SafetyLimits(watchdog=0.01), link_status=rig.link_status)
    assert not supervisor.check_sample(0.0, 0.0, 0.0, 0.0, 1.0)
    assert supervisor.check_sample(0.02, 0.0, 0.0, 0.0, 1.0)
    assert supervisor.reason.startswith("rig watchdog: no fresh sample")
    assert "; link down" in supervisor.reason
    rig.close()
    assert UdpRig("127.0.0.1", port, heartbeat=0.0).link_status() == "heartbeats off"


# -- the rig server survives bad input and drives only its client (issue 26) ----------------
LOCAL = "127.0.0.1"


def _raw() -> socket.socket:
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind((LOCAL, 0))
    sock.settimeout(2.0)
    return sock


def _reset_msg(seq: int, period: float) -> bytes:
    return N._RESET.pack(N.MAGIC, N.VERSION, N.RESET, seq, 0.0, period)


def _command_msg(seq: int, stroke: float, current: float, velocity: float = 0.0) -> bytes:
    return N._COMMAND.pack(N.MAGIC, N.VERSION, N.COMMAND, seq, 0.0, stroke, velocity, current)


def _sample_reply(sock: socket.socket, seq: int) -> tuple[float, ...]:
    """The server's sample echoing ``seq`` (heartbeats skipped)."""
    while True:
        data = sock.recv(256)
        if N._kind(data) == N.SAMPLE and N._HEADER.unpack_from(data)[3] == seq:
            return N._SAMPLE.unpack(data)[4:]


@pytest.mark.audit("rig server")
def test_bad_reset_is_refused_and_the_server_serves_on() -> None:
    rig = ideal_faulty_rig()
    with served(rig, watchdog=0.05, return_rate=0.2) as srv:
        client = UdpRig(LOCAL, srv.port, timeout=0.05)
        client.reset(1e-3)
        client.command(0.02, 0.2)
        assert client.read().displacement == pytest.approx(0.02)
        raw = _raw()
        bad = (0.0, -1e-3, float("nan"), 1e9, float("inf"), 0.2)
        for seq, period in enumerate(bad, 100):
            raw.sendto(_reset_msg(seq, period), (LOCAL, srv.port))
            status = int(_sample_reply(raw, seq)[-1])
            assert status == N.STATUS_RESET | N.STATUS_FAULT, (period, status)
        # nothing changed: the client still drives the rig, the stranger does not
        client.command(0.03, 0.1)
        assert client.read().displacement == pytest.approx(0.03)
        raw.sendto(_command_msg(1, 0.05, 0.3), (LOCAL, srv.port))
        client.command(0.031, 0.1)
        assert client.read().displacement == pytest.approx(0.031)
        assert rig.last_command == (0.031, 0.1)
        # the watchdog runs on: the client goes silent and the rig is sent home, coil off
        assert wait_for(lambda: rig.true_state["displacement"] == 0.0)
        assert rig.true_state["current"] == 0.0
        # a good reset from the stranger is accepted: it becomes the client
        raw.sendto(_reset_msg(200, 1e-3), (LOCAL, srv.port))
        assert int(_sample_reply(raw, 200)[-1]) & N.STATUS_FAULT == 0
        raw.sendto(_command_msg(201, 0.01, 0.1), (LOCAL, srv.port))
        assert _sample_reply(raw, 201)[2] == pytest.approx(0.01)
        raw.close()
        client.close()
        counts = srv.stopped()
    print(f"server counts {counts}; log {srv.lines}")
    assert counts["refused_resets"] == len(bad)
    assert counts["resets"] == 2
    assert counts["watchdog_trips"] >= 1  # the first client's silence (then the stranger's)
    assert "period nan s is not in (0, 0.1] s; serving on" in "\n".join(srv.lines)
    assert sum("refused a reset" in line for line in srv.lines) == len(bad)


class RefusingRig(SimulatedRig):
    """A rig whose reset fails once ``refuse`` is set (after the server's warm-up)."""

    refuse = False

    def reset(self, period: float) -> None:
        if self.refuse:
            raise RuntimeError("hydraulics not ready")
        super().reset(period)


@pytest.mark.audit("rig server")
def test_a_reset_the_rig_refuses_is_reported_to_the_client() -> None:
    rig = RefusingRig(bandwidth=0.0, delay=0.0, coil_time_constant=0.0, bits=0)
    with served(rig) as srv:
        rig.refuse = True
        client = UdpRig(LOCAL, srv.port)
        with pytest.raises(MRSuspensionError, match=r"refused the reset \(period 0.001 s\)"):
            client.reset(1e-3)
        rig.refuse = False
        client.reset(1e-3)  # the server is still there
        deadline = time.monotonic() + 5.0  # a loaded machine: the sample may lag a tick
        while True:
            client.command(0.01, 0.1)
            shown = client.read().displacement
            if abs(shown - 0.01) <= 1e-4 or time.monotonic() > deadline:
                break
        assert shown == pytest.approx(0.01, abs=1e-4)  # LVDT noise
        client.close()
        counts = srv.stopped()
    assert counts["refused_resets"] == 1
    assert any("the rig failed its reset (hydraulics not ready)" in s for s in srv.lines)


@pytest.mark.audit("rig server")
def test_commands_from_a_stranger_are_not_applied() -> None:
    rig = ideal_faulty_rig()
    with served(rig) as srv:
        stranger = _raw()
        addr = (LOCAL, srv.port)
        stranger.sendto(_command_msg(1, 0.05, 0.3), addr)  # before any reset: nobody's
        client = UdpRig(LOCAL, srv.port, timeout=0.05)
        client.reset(1e-3)
        for k in range(1, 6):
            client.command(0.002 * k, 0.1)
            stranger.sendto(_command_msg(k + 1, 0.05, 0.3), addr)
            stranger.sendto(_command_msg(k + 1, float("nan"), 0.3), addr)
            assert client.read().displacement == pytest.approx(0.002 * k)
        client.command(0.011, 0.12)  # processed after every stranger's datagram
        assert client.read().displacement == pytest.approx(0.011)
        # the rig saw the client's commands only, and the stranger got no reply
        assert rig.commands == [(0.002 * k, 0.1) for k in range(1, 6)] + [(0.011, 0.12)]
        assert rig.true_state["current"] == pytest.approx(0.12)
        stranger.settimeout(0.05)
        with pytest.raises(TimeoutError):
            stranger.recv(256)
        stranger_port = stranger.getsockname()[1]
        stranger.close()
        client.close()
        counts = srv.stopped()
    print(f"server counts {counts}; log {srv.lines}")
    assert counts["strangers"] == 11
    assert counts["commands"] == 6
    assert counts["bad_commands"] == 0  # the stranger's NaN never reached the checks
    named = [s for s in srv.lines if f"dropped a command from ('127.0.0.1', {stranger_port})" in s]
    assert named == [f"dropped a command from ('127.0.0.1', {stranger_port}): not the client "
                     "(no reset yet)"]  # fmt: skip


@pytest.mark.audit("rig server")
def test_server_watchdog_homes_the_rig_when_commands_stop() -> None:
    rig = ideal_faulty_rig()
    with served(rig, watchdog=0.05, return_rate=0.2) as srv:
        client = UdpRig(LOCAL, srv.port, timeout=0.05)
        client.reset(1e-3)
        for _ in range(10):
            client.command(0.02, 0.2)
            client.read()
        silent = time.perf_counter()
        assert rig.true_state["current"] == pytest.approx(0.2)
        # only heartbeats from now on (a hung loop whose socket still answers): no commands
        assert wait_for(lambda: (client.ping(), rig.true_state["current"] == 0.0)[1])
        assert time.perf_counter() - silent >= 0.05
        assert wait_for(lambda: rig.true_state["displacement"] == 0.0)
        assert rig.last_command == (0.0, 0.0)
        trips = [s for s in srv.lines if s.startswith("watchdog: no command from")]
        assert len(trips) == 1, srv.lines  # once, though the heartbeats went on
        # the server goes on serving: the next reset re-arms and the rig is driven again
        client.reset(1e-3)
        client.command(0.01, 0.1)
        assert client.read().displacement == pytest.approx(0.01)
        client.close()
        counts = srv.stopped()
    assert counts["watchdog_trips"] >= 1
    assert counts["heartbeats"] >= 1


@pytest.mark.audit("rig server")
def test_malformed_datagrams_and_nan_commands_never_end_the_server() -> None:
    rig = ideal_faulty_rig()
    with served(rig, return_rate=0.2) as srv:
        addr = (LOCAL, srv.port)
        raw = _raw()
        cmd = _command_msg(1, 0.01, 0.1)
        junk = [
            b"", b"x", cmd[:12], cmd[:-1], cmd + b"\0", b"XXXX" + cmd[4:], b"\xff" * 4000,
            N._COMMAND.pack(N.MAGIC, 1, N.COMMAND, 1, 0.0, 0.01, 0.0, 0.1),  # version 1
            N._HEADER.pack(N.MAGIC, N.VERSION, 99, 1),  # unknown type
            N._SAMPLE.pack(N.MAGIC, N.VERSION, N.SAMPLE, 1, 0.0, 0.0, 0.0, 0.0, 0),
            N._HEARTBEAT_ACK.pack(N.MAGIC, N.VERSION, N.HEARTBEAT_ACK, 1, 0.0, 0.0),
        ]  # fmt: skip
        rng = random.Random(7)
        junk += [rng.randbytes(rng.randrange(1, 300)) for _ in range(50)]
        junk += [_reset_msg(seq, -1.0) for seq in range(40)]  # a flood of bad resets
        for data in junk:
            raw.sendto(data, addr)
        client = UdpRig(LOCAL, srv.port, timeout=0.05)
        client.reset(1e-3)  # the server is still there
        client.command(0.02, 0.2)
        assert client.read().displacement == pytest.approx(0.02)
        # a command that is not a number: not applied, the rig goes home with the coil off
        raw.close()
        client.command(float("nan"), 0.2)
        client.read()
        assert wait_for(lambda: rig.true_state["displacement"] == 0.0)
        assert rig.true_state["current"] == 0.0
        assert all(math.isfinite(x) and math.isfinite(i) for x, i in rig.commands)
        client.close()
        counts = srv.stopped()
    print(f"server counts {counts}")
    assert counts["bad_commands"] == 1
    assert counts["invalid"] >= 50
    assert counts["refused_resets"] == 40
    # a flood is counted, not logged line by line (an unread stdout pipe must not fill up)
    assert sum(s.startswith("refused a reset") for s in srv.lines) == 16
    assert "further refused resets are only counted" in srv.lines
    assert any("is not a number (stroke nan m" in s for s in srv.lines), srv.lines


@pytest.mark.audit("rig server")
def test_server_stop_homes_a_driven_rig() -> None:
    rig = ideal_faulty_rig()
    with served(rig, watchdog=0.0, return_rate=0.2) as srv:
        client = UdpRig(LOCAL, srv.port, timeout=0.05)
        client.reset(1e-3)
        client.command(-0.02, 0.25)
        assert client.read().displacement == pytest.approx(-0.02)
        client.close()
        srv.stopped()
    assert rig.last_command == (0.0, 0.0)
    assert rig.true_state["displacement"] == 0.0
    assert rig.true_state["current"] == 0.0
    steps = np.diff([x for x, _ in rig.commands])
    assert np.all(steps > 0.0)
    assert np.all(steps <= 0.2e-3 + 1e-12)  # a ramp at return_rate, not a jump
    assert any(s.startswith("stopping: coil off") for s in srv.lines), srv.lines
