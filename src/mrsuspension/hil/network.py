"""The network rig: a binary UDP protocol, a client :class:`UdpRig` and a server.

A rig controller on another machine (or another process) serves a rig over UDP; the
real-time loop talks to it through :class:`UdpRig`, an ordinary :class:`~mrsuspension.hil.rig.Rig`.
:func:`serve_rig` serves any :class:`~mrsuspension.hil.rig.Rig` (e.g. a
:class:`~mrsuspension.hil.rig.SimulatedRig`) so the real network path is exercised on
loopback (``mrsus rig-emulator``).

Protocol (version 2)
--------------------
Every datagram is one little-endian ``struct`` message starting with the common header
``<IHHI``: ``magic`` (``0x5553524D``, the bytes ``b"MRSU"``), ``version`` (2), ``type``
and ``seq`` (uint32, wrapping). Types:

=============  ====  =================  ============================================
message        type  format             fields after the header
=============  ====  =================  ============================================
command        1     ``<IHHIdddd``      t_send [s], stroke [m], velocity [m/s],
                                        current_command [A]
sample         2     ``<IHHIddddI``     t_rig [s], force [N], displacement [m],
                                        measured current [A], status (bits)
heartbeat      3     ``<IHHId``         t_send [s] (sender's clock)
reset          4     ``<IHHIdd``        t_send [s], period [s]
heartbeat ack  5     ``<IHHIdd``        t_echo [s] (the heartbeat's t_send), t_send [s]
=============  ====  =================  ============================================

- The client sends a **command** each tick (``seq`` increasing by one); the server applies
  it to its rig (one period) and answers with a **sample** echoing ``seq``: the state
  reached under that command, stamped with the rig's time ``t_rig``.
- **reset** puts the rig at mid-stroke with the coil off for the given tick period; the
  server answers with a sample (same ``seq``) whose status has :data:`STATUS_RESET` set
  (and :data:`STATUS_IDEAL_CURRENT` when the coil follows its command at once). A reset
  whose period is not in (0, 0.1] s (0, negative, NaN, huge) is refused: the reply has
  :data:`STATUS_RESET` and :data:`STATUS_FAULT` set, the server keeps its state (client,
  watchdog) and serves on. The sender of the last accepted reset is **the client**: only
  its commands are applied; commands from any other address are dropped (not answered)
  and counted (``strangers``).
- **heartbeat**: both sides send one every heartbeat period (their own ``seq`` counter,
  apart from the commands'; the server to the client of the last reset); the receiver
  answers with a **heartbeat ack** echoing ``seq`` and ``t_send`` (liveness and
  round-trip time on both sides).
- **server watchdog**: armed by the first command after a reset; when no command has
  come from the client for the server's watchdog timeout, the server puts its rig in the
  safe state by itself: coil off, actuator ramped back to mid-stroke. Until the next
  reset it ignores commands and answers them with samples carrying :data:`STATUS_SAFE`,
  which the client does not take as fresh (so the loop's own watchdog trips). A command
  with a NaN or infinite value puts the rig in the safe state the same way (answered
  with :data:`STATUS_FAULT`), and so does the server's own end (Ctrl-C, ``duration``,
  ``should_stop``): it ramps a driven rig home before it returns.
- Status bits of a sample: :data:`STATUS_RESET` (reply to a reset),
  :data:`STATUS_IDEAL_CURRENT`, :data:`STATUS_FAULT` (the rig raised; the sample repeats
  the last good one), :data:`STATUS_SAFE` (the server's watchdog tripped).

Version 2 differs from version 1 by the heartbeat ack (version 1 echoed type 3), the
periodic heartbeats and the server watchdog.

Datagrams with a wrong magic, version, type or size are ignored (counted as ``invalid``);
no datagram and no socket error ends the server. Nothing is retransmitted:
the client keeps the last good sample when a reply is late or lost, so its timestamp
stops advancing and the safety supervisor's watchdog trips after its timeout.
"""

from __future__ import annotations

import contextlib
import heapq
import math
import random
import select
import socket
import struct
import time
from collections.abc import Callable
from typing import Any

from mrsuspension.errors import MRSuspensionError, ValidationError, check_range
from mrsuspension.hil.rig import Rig, RigSample

__all__ = [
    "COMMAND",
    "HEARTBEAT",
    "HEARTBEAT_ACK",
    "MAGIC",
    "RESET",
    "SAMPLE",
    "STATUS_FAULT",
    "STATUS_IDEAL_CURRENT",
    "STATUS_RESET",
    "STATUS_SAFE",
    "VERSION",
    "UdpRig",
    "parse_udp_spec",
    "serve_rig",
]

#: protocol magic (the bytes ``b"MRSU"`` read as a little-endian uint32)
MAGIC = 0x5553524D
#: protocol version
VERSION = 2
#: message types
COMMAND, SAMPLE, HEARTBEAT, RESET, HEARTBEAT_ACK = 1, 2, 3, 4, 5
#: sample status bits
STATUS_RESET, STATUS_IDEAL_CURRENT, STATUS_FAULT, STATUS_SAFE = 1, 2, 4, 8
#: default heartbeat period [s] (both sides)
DEFAULT_HEARTBEAT = 0.02

_HEADER = struct.Struct("<IHHI")
_COMMAND = struct.Struct("<IHHIdddd")
_SAMPLE = struct.Struct("<IHHIddddI")
_HEARTBEAT = struct.Struct("<IHHId")
_RESET = struct.Struct("<IHHIdd")
_HEARTBEAT_ACK = struct.Struct("<IHHIdd")
_SIZES = {COMMAND: _COMMAND.size, SAMPLE: _SAMPLE.size, HEARTBEAT: _HEARTBEAT.size}
_SIZES[RESET] = _RESET.size
_SIZES[HEARTBEAT_ACK] = _HEARTBEAT_ACK.size
_SEQ_MASK = 0xFFFFFFFF
_BUF = 256


def _kind(data: bytes) -> int:
    """Message type of a datagram, or 0 when it is not a valid version-1 message."""
    if len(data) < _HEADER.size:
        return 0
    magic, version, kind, _ = _HEADER.unpack_from(data)
    if magic != MAGIC or version != VERSION or _SIZES.get(kind) != len(data):
        return 0
    return int(kind)


def parse_udp_spec(spec: str) -> tuple[str, int]:
    """``udp://HOST:PORT`` -> ``(host, port)``.

    Raises
    ------
    ValidationError
        When the spec is not of that form.
    """
    s = spec.strip()
    if not s.lower().startswith("udp://"):
        raise ValidationError(f"not a UDP rig address: {spec!r} (expected udp://HOST:PORT)")
    rest = s[6:].rstrip("/")
    host, sep, port_s = rest.rpartition(":")
    host = host.strip("[]")
    if not sep or not host or not port_s.isdigit() or not 0 < int(port_s) < 65536:
        raise ValidationError(f"bad UDP rig address {spec!r}; expected udp://HOST:PORT")
    return host, int(port_s)


# -- client ---------------------------------------------------------------------------------
class UdpRig(Rig):
    """A rig served over UDP (the client side of the protocol).

    Each tick, :meth:`read` drains the socket and keeps the newest sample (highest
    ``seq``); when the reply to the last command has not arrived it waits at most
    ``timeout`` for it, then returns the last good sample (counted as a stale read). A
    stale sample keeps its old rig timestamp, so the safety supervisor's watchdog (no
    fresh sample for ``SafetyLimits.watchdog``) trips when the rig stops answering.

    Parameters
    ----------
    host, port : str, int
        The rig server.
    timeout : float, optional
        Longest wait for the reply in :meth:`read` [s] (default: a quarter of the period).
    reset_timeout : float
        Longest wait for the reply to a reset or a heartbeat [s] (retried three times).
    heartbeat : float
        Period of the client's heartbeats [s] (sent with the commands; 0: none).
    spin : bool
        Wait for the reply by polling the socket rather than sleeping in ``select``
        (default: sleep). On a virtual machine a sleeping vCPU can take milliseconds to
        wake; use it with the loop's ``realtime="spin"``. The wait is at most ``timeout``.

    Attributes
    ----------
    sent, received, late, stale_reads : int
        Commands sent; distinct command replies received; replies that arrived after the
        read that wanted them; reads that returned the previous sample.
    rig_safe : bool
        The server's watchdog has put the rig in the safe state (until the next reset).
    """

    def __init__(
        self,
        host: str = "127.0.0.1",
        port: int = 9870,
        timeout: float | None = None,
        reset_timeout: float = 1.0,
        heartbeat: float = DEFAULT_HEARTBEAT,
        spin: bool = False,
    ) -> None:
        self.host = str(host)
        self.spin = bool(spin)
        self.port = int(check_range("port", port, 1, 65535))
        if timeout is not None:
            check_range("timeout", timeout, 0.0, 1.0, unit="s")
        self.timeout = timeout
        self.reset_timeout = float(check_range("reset_timeout", reset_timeout, 0.0, 60.0))
        self.heartbeat = float(check_range("heartbeat", heartbeat, 0.0, 10.0, unit="s"))
        self._hb_seq = 0
        self._next_hb = 0.0
        self._sock: socket.socket | None = None
        self._wait = 0.0
        self._seq = 0
        self._last_seq = 0
        self._sample = RigSample(0.0, 0.0, 0.0, float("-inf"))
        self._zero_counters()

    @classmethod
    def from_spec(cls, spec: str, **kw: Any) -> UdpRig:
        """A client for ``udp://HOST:PORT``."""
        host, port = parse_udp_spec(spec)
        return cls(host, port, **kw)

    def _zero_counters(self) -> None:
        self.sent = 0
        self.received = 0
        self.late = 0
        self.stale_reads = 0
        self.send_errors = 0
        self.heartbeats_sent = 0
        self.heartbeats_received = 0
        self.heartbeat_acks = 0
        self.last_heartbeat = -math.inf
        self.rtt = math.nan
        self.rtt_max = 0.0
        self.rig_safe = False

    # pickling (the loop may run in a spawned process): the socket is re-opened there
    def __getstate__(self) -> dict[str, Any]:
        state = self.__dict__.copy()
        state["_sock"] = None
        return state

    def _socket(self) -> socket.socket:
        if self._sock is None:
            family = socket.AF_INET6 if ":" in self.host else socket.AF_INET
            sock = socket.socket(family, socket.SOCK_DGRAM)
            sock.connect((self.host, self.port))
            sock.setblocking(False)
            self._sock = sock
        return self._sock

    def _next_seq(self) -> int:
        self._seq = (self._seq + 1) & _SEQ_MASK
        return self._seq

    def _drain(self) -> None:
        sock = self._socket()
        while True:
            try:
                sock.recv(_BUF)
            except (BlockingIOError, ConnectionRefusedError):
                return

    def _request(self, payload: bytes, seq: int, want: int) -> bytes:
        """Send a control message; wait for the reply of type ``want`` echoing ``seq``."""
        sock = self._socket()
        for _ in range(3):
            with contextlib.suppress(ConnectionRefusedError):
                sock.send(payload)
            end = time.monotonic() + self.reset_timeout
            while (rem := end - time.monotonic()) > 0:
                ready, _, _ = select.select([sock], [], [], rem)
                if not ready:
                    break
                try:
                    data = sock.recv(_BUF)
                except (BlockingIOError, ConnectionRefusedError):
                    continue
                if _kind(data) == want and _HEADER.unpack_from(data)[3] == seq:
                    return data
        raise MRSuspensionError(
            f"no reply from the rig at udp://{self.host}:{self.port} "
            f"(3 tries, {self.reset_timeout:g} s each)"
        )

    def ping(self) -> float:
        """Send a heartbeat; return the round-trip time [s].

        Raises
        ------
        MRSuspensionError
            When the server does not answer.
        """
        self._hb_seq = seq = (self._hb_seq + 1) & _SEQ_MASK
        t = time.perf_counter()
        self._request(_HEARTBEAT.pack(MAGIC, VERSION, HEARTBEAT, seq, t), seq, HEARTBEAT_ACK)
        return time.perf_counter() - t

    def _beat(self, now: float) -> None:
        """Send a heartbeat (never blocks)."""
        self._hb_seq = seq = (self._hb_seq + 1) & _SEQ_MASK
        self._next_hb = now + self.heartbeat
        with contextlib.suppress(BlockingIOError, ConnectionRefusedError):
            self._socket().send(_HEARTBEAT.pack(MAGIC, VERSION, HEARTBEAT, seq, now))
            self.heartbeats_sent += 1

    def heartbeat_age(self) -> float:
        """Time [s] since the newest heartbeat (or ack) from the server (inf: none yet).

        Counted from when :meth:`read` took it off the socket (every tick in the loop).
        """
        return time.perf_counter() - self.last_heartbeat

    # -- interface ----------------------------------------------------------------------
    def reset(self, period: float) -> None:
        """Reset the served rig for ``period``; wait for its acknowledgement."""
        period = float(check_range("period", period, 0.0, 0.1, unit="s", low_inclusive=False))
        self._wait = self.timeout if self.timeout is not None else 0.25 * period
        self._socket()
        self._drain()
        seq = self._next_seq()
        data = self._request(
            _RESET.pack(MAGIC, VERSION, RESET, seq, time.perf_counter(), period), seq, SAMPLE
        )
        _, _, _, _, t_rig, f, x, i, status = _SAMPLE.unpack(data)
        if status & STATUS_FAULT:
            raise MRSuspensionError(
                f"the rig at udp://{self.host}:{self.port} refused the reset "
                f"(period {period:g} s); it stays in its previous state"
            )
        self.ideal_current = bool(status & STATUS_IDEAL_CURRENT)
        self._sample = RigSample(f, x, i, t_rig)
        self._last_seq = seq
        self._zero_counters()
        self._next_hb = 0.0

    def command(self, stroke: float, current_command: float, velocity: float = 0.0) -> None:
        """Send a command datagram (never blocks)."""
        seq = self._next_seq()
        now = time.perf_counter()
        payload = _COMMAND.pack(
            MAGIC, VERSION, COMMAND, seq, now, stroke, velocity, current_command
        )
        self.sent += 1
        try:
            self._socket().send(payload)
        except (BlockingIOError, ConnectionRefusedError):
            self.send_errors += 1  # its reply never comes: counted as lost too
        if self.heartbeat > 0.0 and now >= self._next_hb:
            self._beat(now)

    def _take(self, data: bytes) -> None:
        kind = _kind(data)
        if kind != SAMPLE:
            if kind == HEARTBEAT:  # the server's beat: acknowledge it
                _, _, _, hseq, t_send = _HEARTBEAT.unpack(data)
                now = time.perf_counter()
                self.heartbeats_received += 1
                self.last_heartbeat = now
                ack = _HEARTBEAT_ACK.pack(MAGIC, VERSION, HEARTBEAT_ACK, hseq, t_send, now)
                with contextlib.suppress(BlockingIOError, ConnectionRefusedError):
                    self._socket().send(ack)
            elif kind == HEARTBEAT_ACK:  # our beat came back: round-trip time
                _, _, _, _, t_echo, _ = _HEARTBEAT_ACK.unpack(data)
                now = time.perf_counter()
                self.heartbeat_acks += 1
                self.last_heartbeat = now
                self.rtt = now - t_echo
                self.rtt_max = max(self.rtt_max, self.rtt)
            return
        _, _, _, seq, t_rig, f, x, i, status = _SAMPLE.unpack(data)
        if status & STATUS_RESET:
            return
        self.received += 1
        # newer than what we hold (modular comparison of the 32-bit sequence numbers)
        if 0 < ((seq - self._last_seq) & _SEQ_MASK) < 0x80000000:
            if seq != self._seq:
                self.late += 1
            self._last_seq = seq
            self.rig_safe = bool(status & STATUS_SAFE)
            if not status & (STATUS_FAULT | STATUS_SAFE):
                self._sample = RigSample(f, x, i, t_rig)
        else:
            self.late += 1

    def read(self) -> RigSample:
        """The newest sample; waits at most ``timeout`` for the reply to the last command."""
        sock = self._socket()
        recv = sock.recv
        take = self._take
        while True:
            try:
                take(recv(_BUF))
            except BlockingIOError:
                break
            except ConnectionRefusedError:
                continue  # a pending ICMP error, reported once: the rest is still queued
        if self._last_seq != self._seq and self.sent:
            end = time.perf_counter() + self._wait
            while self._last_seq != self._seq:
                rem = end - time.perf_counter()
                if rem <= 0:
                    break
                if not self.spin:
                    ready, _, _ = select.select([sock], [], [], rem)
                    if not ready:
                        break
                try:
                    take(recv(_BUF))
                except (BlockingIOError, ConnectionRefusedError):
                    continue
            if self._last_seq != self._seq:
                self.stale_reads += 1
        return self._sample

    def close(self) -> None:
        """Close the socket."""
        if self._sock is not None:
            self._sock.close()
            self._sock = None

    @property
    def lost(self) -> int:
        """Commands whose reply has not been received (so far)."""
        return max(0, self.sent - self.received)

    def counters(self) -> dict[str, int]:
        """Packet accounting: sent, received, lost, late, stale reads."""
        return {
            "sent": self.sent,
            "received": self.received,
            "lost": self.lost,
            "late": self.late,
            "stale_reads": self.stale_reads,
        }

    def link_status(self) -> str:
        """The link as the heartbeats see it (added to a watchdog trip's reason).

        ``"rig in the safe state (server watchdog)"``, ``"link alive (heartbeat ...)"``
        when the server's heartbeats still arrive within three periods (so the rig, not
        the link, stopped answering, or only the replies are lost), ``"link down (...)"``
        when they do not, or ``"heartbeats off"``.
        """
        if self.rig_safe:
            return "rig in the safe state (server watchdog)"
        if self.heartbeat <= 0.0:
            return "heartbeats off"
        age = self.heartbeat_age()
        if age <= 3.0 * self.heartbeat + 0.01:
            return (
                f"link alive (last heartbeat {1e3 * age:.0f} ms ago, rtt {1e3 * self.rtt:.2f} ms)"
            )
        if math.isinf(age):
            return "link down (no heartbeat from the rig since the reset)"
        return f"link down (no heartbeat from the rig for {age:.3f} s)"

    def link(self) -> dict[str, float | int | bool]:
        """Heartbeat accounting: beats sent, received and acknowledged, round-trip times."""
        return {
            "heartbeat": self.heartbeat,
            "heartbeats_sent": self.heartbeats_sent,
            "heartbeats_received": self.heartbeats_received,
            "heartbeat_acks": self.heartbeat_acks,
            "rtt": self.rtt,
            "rtt_max": self.rtt_max,
            "rig_safe": self.rig_safe,
        }

    def describe(self) -> dict[str, Any]:
        """Plain-data description (address, protocol version, timeout, heartbeat)."""
        return {
            "rig": "udp",
            "address": f"udp://{self.host}:{self.port}",
            "protocol_version": VERSION,
            "timeout": self.timeout,
            "heartbeat": self.heartbeat,
        }


def _pack_sample(seq: int, s: RigSample, status: int) -> bytes:
    return _SAMPLE.pack(
        MAGIC, VERSION, SAMPLE, seq, s.timestamp, s.force, s.displacement, s.current, status
    )


# -- server ---------------------------------------------------------------------------------
def serve_rig(
    rig: Rig,
    host: str = "127.0.0.1",
    port: int = 9870,
    *,
    rate: float = 1000.0,
    drop: float = 0.0,
    delay: float = 0.0,
    delay_probability: float = 1.0,
    drop_after: int = 0,
    seed: int = 0,
    duration: float | None = None,
    ready: Callable[[int], None] | None = None,
    should_stop: Callable[[], bool] | None = None,
    heartbeat: float = DEFAULT_HEARTBEAT,
    watchdog: float = 0.25,
    return_rate: float = 0.05,
    realtime: bool | str = "off",
    log: Callable[[str], None] | None = None,
) -> dict[str, int]:
    """Serve ``rig`` over UDP until stopped (Ctrl-C, ``duration`` or ``should_stop``).

    Only the client of the last accepted reset drives the rig; a reset with a bad period
    is refused and the server serves on; no datagram ends it; when the client's commands
    stop for ``watchdog`` seconds, or one is not a number, the rig goes to the safe state
    (coil off, ramped to mid-stroke); when the server stops, it ramps a driven rig home
    first.

    Parameters
    ----------
    rig : Rig
        The rig served (e.g. a :class:`~mrsuspension.hil.rig.SimulatedRig`).
    host : str
        Address to bind (default loopback only).
    port : int
        UDP port (0: an ephemeral port, passed to ``ready``).
    rate : float
        Tick rate [Hz] assumed until a client resets the rig with its own period.
    drop : float
        Probability of dropping the reply to a command (fault injection for tests).
    delay : float
        Extra delay of a reply [s] (fault injection; the rig keeps processing commands).
    delay_probability : float
        Probability that a reply is delayed by ``delay`` (default: every reply).
    drop_after : int
        Commands answered normally before ``drop`` applies (0: from the start).
    seed : int
        Seed of the fault injection.
    duration : float, optional
        Stop after this many seconds.
    ready : callable, optional
        Called with the bound port once the socket listens.
    should_stop : callable, optional
        Polled about every 50 ms; the server returns when it is true.
    heartbeat : float
        Period [s] of the server's heartbeats to the client of the last reset (0: none).
    watchdog : float
        Server watchdog [s]: with no command from the client for this long, once it has
        sent one after its reset, the rig goes to the safe state (coil off, actuator
        ramped to mid-stroke at ``return_rate``) until the next reset; 0 disables it.
    return_rate : float
        Stroke rate [m/s] of the safe-state return.
    realtime : bool or str
        Scheduling of the server (``"auto"``, ``"fifo"`` or ``"off"``, as for
        :func:`~mrsuspension.hil.loop.run_hil`; the server pins itself to a core other
        than the loop's). With ``"spin"`` the server polls its socket instead of sleeping
        in ``select`` (it keeps one core busy; a sleeping virtual CPU can take
        milliseconds to wake).
    log : callable, optional
        Called with one line for each event worth an operator's eye: a refused reset, a
        new client, the first command from each stranger, a command that is not a
        number, a watchdog trip, a socket error, the return home at the end.

    Returns
    -------
    dict
        Counters: commands (applied or answered, from the client), replies, dropped,
        delayed, resets (accepted), heartbeats (received), invalid, heartbeats_sent,
        heartbeat_acks (received), watchdog_trips, refused_resets, strangers (commands
        from another address, dropped), bad_commands (not a number), errors (socket
        errors survived).

    Notes
    -----
    Resets and heartbeats are always answered at once (the faults apply to command
    replies only).
    """
    check_range("drop", drop, 0.0, 1.0)
    check_range("delay", delay, 0.0, 10.0, unit="s")
    check_range("delay_probability", delay_probability, 0.0, 1.0)
    rate = float(check_range("rate", rate, 1.0, 100000.0, unit="Hz"))
    heartbeat = float(check_range("heartbeat", heartbeat, 0.0, 10.0, unit="s"))
    watchdog = float(check_range("watchdog", watchdog, 0.0, 60.0, unit="s"))
    return_rate = float(
        check_range("return_rate", return_rate, 0.0, 10.0, unit="m/s", low_inclusive=False)
    )
    from mrsuspension.hil.realtime import normalise_mode, pick_cpu, realtime_session

    mode = normalise_mode(realtime)
    if mode == "unpaced":
        raise ValidationError(
            "the rig server runs in real time: realtime must be 'auto', 'fifo', 'spin' or 'off'; "
            f"got {realtime!r}"
        )
    with realtime_session(mode, cpu=pick_cpu("emulator")) as rt:
        return _serve(
            rig, host, port, rate, drop, delay, delay_probability, drop_after, seed, duration,
            ready, should_stop, heartbeat, watchdog, return_rate, rt.spin, log,
        )  # fmt: skip


#: the longest tick period a reset may ask for [s] (as :meth:`UdpRig.reset` checks)
_MAX_PERIOD = 0.1
#: events of a kind that can repeat (refused resets, strangers, socket errors) logged
#: one by one; the rest are only counted
_MAX_LOGGED = 16


def _finite(*values: float) -> bool:
    return all(-math.inf < v < math.inf for v in values)


def _serve(
    rig: Rig,
    host: str,
    port: int,
    rate: float,
    drop: float,
    delay: float,
    delay_probability: float,
    drop_after: int,
    seed: int,
    duration: float | None,
    ready: Callable[[int], None] | None,
    should_stop: Callable[[], bool] | None,
    heartbeat: float,
    watchdog: float,
    return_rate: float,
    spin: bool = False,
    log: Callable[[str], None] | None = None,
) -> dict[str, int]:
    rng = random.Random(seed)
    perf = time.perf_counter
    sock = socket.socket(socket.AF_INET6 if ":" in host else socket.AF_INET, socket.SOCK_DGRAM)
    counts = dict.fromkeys(
        ("commands", "replies", "dropped", "delayed", "resets", "heartbeats", "invalid"), 0
    )
    counts.update(dict.fromkeys(("heartbeats_sent", "heartbeat_acks", "watchdog_trips"), 0))
    counts.update(dict.fromkeys(("refused_resets", "strangers", "bad_commands", "errors"), 0))
    pending: list[tuple[float, int, bytes, Any]] = []
    period = 1.0 / rate
    client: Any = None  # address of the client of the last accepted reset
    last_rx = 0.0  # when the client's last command came [perf s]
    next_hb = math.inf
    hb_seq = 0
    safe = False  # the rig is in the safe state (watchdog, bad command, failed reset)
    armed = False  # the watchdog runs from the first command after a reset
    next_safe = math.inf  # next tick of the safe-state return
    x_last = 0.0  # last stroke commanded to the rig
    i_last = 0.0  # last current commanded to the rig
    home_at = math.inf  # when the safe-state return reached mid-stroke
    logged: set[Any] = set()  # strangers named in the log

    def note(line: str, count: int = 1, what: str = "") -> None:
        """Log a line; the ``count``-th event of a kind that can repeat (``what``) only
        up to :data:`_MAX_LOGGED` (an unread pipe must not fill up and block the server)."""
        if log is None or count > _MAX_LOGGED + 1:
            return
        if count == _MAX_LOGGED + 1:
            line = f"further {what} are only counted"
        with contextlib.suppress(Exception):
            log(line)

    def send(data: bytes, addr: Any) -> bool:
        try:
            sock.sendto(data, addr)
        except OSError as exc:  # e.g. an unreachable or forbidden address: serve on
            counts["errors"] += 1
            note(f"could not send to {addr}: {exc}", counts["errors"], "socket errors")
            return False
        return True

    def go_safe(t: float) -> None:
        nonlocal safe, next_safe, home_at
        safe = True
        pending.clear()
        next_safe, home_at = t, math.inf

    try:
        sock.bind((host, port))
        # warm up (compile or load the rig's kernels) before announcing the port
        rig.reset(period)
        rig.command(0.0, 0.0, 0.0)
        rig.read()
        rig.reset(period)
        last = rig.read()
        if ready is not None:
            ready(int(sock.getsockname()[1]))
        end = math.inf if duration is None else time.monotonic() + duration
        next_poll = 0.0
        while True:
            now = time.monotonic()
            if now >= end:
                break
            if should_stop is not None and now >= next_poll:
                if should_stop():
                    break
                next_poll = now + 0.05
            wait = min(0.05, end - now)
            t = perf()
            due = min(next_hb, next_safe, pending[0][0] if pending else math.inf)
            if armed and not safe:
                due = min(due, last_rx + watchdog)
            wait = min(wait, max(0.0, due - t))
            if spin:  # poll: a sleeping virtual CPU can take milliseconds to wake
                wait = 0.0
            ready_r, _, _ = select.select([sock], [], [], wait)
            data = b""
            if ready_r:
                try:
                    data, addr = sock.recvfrom(_BUF)
                except OSError as exc:  # a pending ICMP error and the like: serve on
                    counts["errors"] += 1
                    note(f"socket error while receiving: {exc}", counts["errors"], "socket errors")
                    data = b""
            if data:
                kind = _kind(data)
                if kind == COMMAND and (client is None or addr != client):
                    counts["strangers"] += 1  # not the client of the last reset: dropped
                    if addr not in logged and len(logged) <= _MAX_LOGGED:
                        logged.add(addr)
                        owner = "no reset yet" if client is None else f"the client is {client}"
                        note(
                            f"dropped a command from {addr}: not the client ({owner})",
                            len(logged),
                            "strangers",
                        )
                elif kind == COMMAND:
                    _, _, _, seq, _, stroke, velocity, i_cmd = _COMMAND.unpack(data)
                    counts["commands"] += 1
                    last_rx = perf()
                    armed = watchdog > 0.0
                    status = 0
                    if not _finite(stroke, velocity, i_cmd):
                        counts["bad_commands"] += 1
                        status = STATUS_FAULT
                        if not safe:
                            note(
                                f"command from {addr} is not a number (stroke {stroke!r} m, "
                                f"velocity {velocity!r} m/s, current {i_cmd!r} A): coil off, "
                                "returning to mid-stroke until the next reset"
                            )
                            go_safe(perf())
                    elif safe:
                        status = STATUS_SAFE  # ignored until the next reset
                    else:
                        try:
                            rig.command(stroke, i_cmd, velocity)
                            x_last, i_last = stroke, i_cmd
                            last = rig.read()
                        except Exception:  # a faulty rig: report it, keep serving
                            status = STATUS_FAULT
                    reply = _pack_sample(seq, last, status)
                    if drop > 0.0 and counts["commands"] > drop_after and rng.random() < drop:
                        counts["dropped"] += 1
                    elif delay > 0.0 and rng.random() < delay_probability:
                        counts["delayed"] += 1
                        heapq.heappush(pending, (perf() + delay, seq, reply, addr))
                    elif send(reply, addr):
                        counts["replies"] += 1
                elif kind == RESET:
                    _, _, _, seq, _, new_period = _RESET.unpack(data)
                    if not 0.0 < new_period <= _MAX_PERIOD:  # NaN fails too
                        counts["refused_resets"] += 1
                        note(
                            f"refused a reset from {addr}: period {new_period!r} s is not in "
                            f"(0, {_MAX_PERIOD:g}] s; serving on",
                            counts["refused_resets"],
                            "refused resets",
                        )
                        send(_pack_sample(seq, last, STATUS_RESET | STATUS_FAULT), addr)
                        continue
                    pending.clear()
                    try:
                        rig.reset(new_period)
                        last = rig.read()
                    except Exception as exc:  # the rig refused: it goes safe, serve on
                        counts["refused_resets"] += 1
                        note(
                            f"the rig failed its reset ({exc}): coil off, back to mid-stroke",
                            counts["refused_resets"],
                            "refused resets",
                        )
                        go_safe(perf())
                        armed = False
                        send(_pack_sample(seq, last, STATUS_RESET | STATUS_FAULT), addr)
                        continue
                    counts["resets"] += 1
                    period = new_period
                    x_last = i_last = 0.0
                    safe, next_safe, armed = False, math.inf, False
                    if client is not None and addr != client:
                        note(f"new client {addr} (was {client})")
                    client, last_rx = addr, perf()
                    next_hb = last_rx + heartbeat if heartbeat > 0.0 else math.inf
                    ideal = STATUS_IDEAL_CURRENT if rig.ideal_current else 0
                    send(_pack_sample(seq, last, STATUS_RESET | ideal), addr)
                elif kind == HEARTBEAT:
                    _, _, _, seq, t_send = _HEARTBEAT.unpack(data)
                    counts["heartbeats"] += 1
                    ack = _HEARTBEAT_ACK.pack(MAGIC, VERSION, HEARTBEAT_ACK, seq, t_send, perf())
                    send(ack, addr)
                elif kind == HEARTBEAT_ACK:
                    counts["heartbeat_acks"] += 1
                else:
                    counts["invalid"] += 1
            t = perf()
            while pending and pending[0][0] <= t:
                _, _, reply, addr = heapq.heappop(pending)
                if send(reply, addr):
                    counts["replies"] += 1
            if client is not None and t >= next_hb:
                hb_seq = (hb_seq + 1) & _SEQ_MASK
                send(_HEARTBEAT.pack(MAGIC, VERSION, HEARTBEAT, hb_seq, t), client)
                counts["heartbeats_sent"] += 1
                next_hb = max(next_hb + heartbeat, t)
            if armed and not safe and t - last_rx > watchdog:
                # the client went silent: coil off, back to mid-stroke
                counts["watchdog_trips"] += 1
                note(
                    f"watchdog: no command from {client} for {t - last_rx:.3f} s "
                    f"(limit {watchdog:g} s): coil off, returning to mid-stroke"
                )
                go_safe(t)
            if safe and t >= next_safe:
                x_last, last = _safe_tick(rig, x_last, return_rate * period, return_rate, last)
                i_last = 0.0
                if x_last != 0.0:
                    home_at = math.inf
                elif home_at == math.inf:
                    home_at = t
                # tick until home and 0.5 s more (settling); then the rig holds
                next_safe = math.inf if t - home_at > 0.5 else next_safe + period
    except KeyboardInterrupt:
        pass
    finally:
        try:
            if x_last != 0.0 or i_last != 0.0:  # the server stops with its rig driven
                note(f"stopping: coil off, returning the rig to mid-stroke from {x_last:.4g} m")
                _home(rig, x_last, period, return_rate)
        except KeyboardInterrupt:  # a second Ctrl-C: stop at once
            pass
        finally:
            sock.close()
            rig.close()
    return counts


def _safe_tick(
    rig: Rig, x: float, step: float, return_rate: float, last: RigSample
) -> tuple[float, RigSample]:
    """One tick of the safe-state return: coil off, ``x`` one ``step`` nearer 0."""
    if not abs(x) > step:  # NaN included: straight to mid-stroke
        x = 0.0
    else:
        x -= math.copysign(step, x)
    v = 0.0 if x == 0.0 else -math.copysign(return_rate, x)
    with contextlib.suppress(Exception):
        rig.command(x, 0.0, v)
        last = rig.read()
    return x, last


#: longest return to mid-stroke when the server stops [s] (then mid-stroke is commanded)
_MAX_HOMING = 10.0


def _home(rig: Rig, x: float, period: float, return_rate: float) -> None:
    """Ramp the rig to mid-stroke with the coil off, in real time (the server's end).

    At most :data:`_MAX_HOMING` seconds (a stroke no rig has): then mid-stroke at once.
    """
    step = return_rate * period
    sample = RigSample(0.0, 0.0, 0.0, 0.0)
    next_t = time.perf_counter()
    for _ in range(math.ceil(_MAX_HOMING / period)):
        x, sample = _safe_tick(rig, x, step, return_rate, sample)
        if x == 0.0:
            return
        next_t += period
        time.sleep(max(0.0, next_t - time.perf_counter()))
    _safe_tick(rig, 0.0, step, return_rate, sample)
