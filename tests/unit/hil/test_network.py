"""The UDP rig protocol: message layout, address parsing, a client against a server thread."""

from __future__ import annotations

import socket
import struct
import threading
from collections.abc import Iterator

import pytest

from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.hil import ideal_rig
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
