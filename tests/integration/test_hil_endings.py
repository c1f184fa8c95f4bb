"""Every way a HiL run ends leaves the rig home, the current at 0 and the recording kept.

Issue 26, section 1: for each ending (completion, trip, Ctrl-C, SIGTERM, SIGHUP, the
command killed, an exception in a tick, a full disk, a dead link) over the simulated rig
and over the UDP rig, the rig is last commanded to mid-stroke with zero current, the
recording up to that moment is complete (committed to ``--out``, or a visible
``NAME.recovered``) and ``mrsus hil run`` exits with the stated code and one line.

``mrsus hil run`` runs in its own process group (a terminal's foreground job), started
with SIGINT at its default (a child of a non-interactive shell would inherit it
ignored). Over UDP the rig server runs in a thread of this process around a
:class:`Witness` rig that remembers the last command it was given (its watchdog is off,
so every command it applies came from the loop); over the simulated rig the recording's
last rows say what was commanded and measured.
"""

from __future__ import annotations

import contextlib
import json
import os
import resource
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mrsuspension.cli.hil import EXIT_CODES
from mrsuspension.hil import SafetyLimits, load_recording, run_hil
from mrsuspension.hil.loop import STATE_RETURN
from mrsuspension.hil.network import UdpRig, serve_rig
from mrsuspension.hil.rig import Rig, RigSample, SimulatedRig, ideal_rig
from mrsuspension.scenario import Scenario

psutil = pytest.importorskip("psutil")

ROOT = Path(__file__).resolve().parents[2]
#: the passive damper at 0.1 A (after the 0.5 s start-up, which holds the current at 0)
SCENARIO = ROOT / "examples" / "scenarios" / "passive-harmonic.toml"
#: loop rate of these runs: low, the point is the ending, not the timing
RATE = 200
#: seconds a command may take to start its loop (imports, a numba cache load) on a loaded machine
START = 60.0
#: a harmonic road far beyond the commanded stroke rate limit (1.5 m/s): the loop trips
TRIP_SCENARIO = """
[vehicle]
sprung_mass = 563.0
unsprung_mass = 90.0

[damper]
model = "wang-symmetric"
parameters = "wang-symmetric-low"

[controller]
law = "passive"
current = 0.1

[excitation]
kind = "harmonic"
frequency = 12.0
amplitude = 0.04
"""


class Witness(Rig):
    """The served rig: the ideal rig, remembering the last command it was given."""

    def __init__(self) -> None:
        self.rig = ideal_rig()
        self.ideal_current = True
        self.last = (math_nan := float("nan"), math_nan)
        self.commands = 0
        self.driven = False  # given a non-zero current at least once

    def reset(self, period: float) -> None:
        self.rig.reset(period)

    def command(self, stroke: float, current_command: float, velocity: float = 0.0) -> None:
        self.last = (stroke, current_command)
        self.commands += 1
        self.driven = self.driven or current_command > 0.0
        self.rig.command(stroke, current_command, velocity)

    def read(self) -> RigSample:
        return self.rig.read()


@dataclass
class Server:
    witness: Witness
    port: int


@contextlib.contextmanager
def rig_server(**kw: Any) -> Iterator[Server]:
    """``serve_rig`` around a :class:`Witness` in a thread, watchdog off, on a free port."""
    witness = Witness()
    stop = threading.Event()
    ports: list[int] = []
    thread = threading.Thread(
        target=serve_rig,
        args=(witness,),
        kwargs={"port": 0, "ready": ports.append, "should_stop": stop.is_set, "watchdog": 0.0,
                "realtime": "off", **kw},
        daemon=True,
    )  # fmt: skip
    thread.start()
    deadline = time.monotonic() + 30
    while not ports:
        assert thread.is_alive(), "the rig server ended"
        assert time.monotonic() < deadline, "the rig server did not start"
        time.sleep(0.01)
    try:
        yield Server(witness, ports[0])
    finally:
        stop.set()
        thread.join(10)


def _recording_dir(tmp: Path, name: str = "rec") -> Path | None:
    """The run's recording folder while it runs (staged beside ``--out``) or after."""
    for d in [*tmp.glob(f".{name}.*.tmp"), tmp / name, tmp / f"{name}.recovered"]:
        if (d / "meta.json").is_file():
            return d
    return None


def _driven(tmp: Path) -> bool:
    """The loop has commanded a coil current (after the start-up)."""
    d = _recording_dir(tmp)
    if d is None:
        return False
    with contextlib.suppress(Exception):
        return bool(np.any(load_recording(d)["i_cmd"] > 0.0))
    return False


@dataclass
class Ended:
    code: int
    stdout: str
    stderr: str
    seconds: float  # from the signal (or the start) to the end of every process
    left: list[int]


def _restore_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # as a terminal's foreground job


def run_cli(
    args: list[str],
    cwd: Path,
    how: str | None = None,
    ready: Callable[[], bool] | None = None,
    preexec: Callable[[], None] | None = None,
) -> Ended:
    """Run ``mrsus hil run ARGS`` in its own process group; signal it once ``ready()``.

    ``how``: None (let it end), ``sigint`` / ``sighup`` (to the process group, as a
    terminal does), ``sigterm`` (to the command only, as ``kill PID``) or ``kill9`` (the
    command killed, its loop left alone).
    """

    def start() -> None:
        _restore_sigint()
        if preexec is not None:
            preexec()

    proc = subprocess.Popen(
        [sys.executable, "-m", "mrsuspension", "hil", "run", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        start_new_session=True,
        preexec_fn=start,
        env={**os.environ, "COLUMNS": "200"},
    )
    parent = psutil.Process(proc.pid)
    tree: list[Any] = [parent]
    t0 = time.monotonic()
    try:
        if how is not None:
            assert ready is not None
            deadline = time.monotonic() + START
            while not ready():
                assert proc.poll() is None, f"ended before the signal: {proc.communicate()}"
                assert time.monotonic() < deadline, "the loop did not start driving the rig"
                time.sleep(0.02)
            with contextlib.suppress(psutil.NoSuchProcess):
                tree = [parent, *parent.children(recursive=True)]
            t0 = time.monotonic()
            sig = {"sigint": signal.SIGINT, "sighup": signal.SIGHUP}.get(how)
            if sig is not None:
                os.killpg(proc.pid, sig)
            elif how == "sigterm":
                os.kill(proc.pid, signal.SIGTERM)
            else:
                os.kill(proc.pid, signal.SIGKILL)
        out, err = proc.communicate(timeout=60)  # EOF: every process holding the pipes ended
        seconds = time.monotonic() - t0
        time.sleep(0.1)
        left = [p.pid for p in tree if p.is_running() and p.status() != psutil.STATUS_ZOMBIE]
        return Ended(proc.returncode, out, err, seconds, left)
    finally:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        for p in tree:
            with contextlib.suppress(psutil.NoSuchProcess):
                p.kill()
        proc.wait()


def _check_home(rec_dir: Path, witness: Witness | None, driven: bool = True) -> dict[str, Any]:
    """The recording is complete and ends with the rig home and the current at 0."""
    rec = load_recording(rec_dir)
    assert rec.complete, rec.stop
    assert len(rec) > 0
    assert rec.stop["rows"] == len(rec)
    assert rec["x_cmd"][-1] == 0.0
    assert rec["i_cmd"][-1] == 0.0
    assert rec["state"][-1] >= STATE_RETURN
    if witness is None:  # the simulated rig measured it
        assert abs(rec["x_m"][-1]) < 2e-3
        assert abs(rec["i_dm"][-1]) < 0.02
    else:  # the last command the rig applied
        assert witness.driven or not driven, "the rig was never driven: the case shows nothing"
        assert witness.last == (0.0, 0.0), witness.last
    return rec.stop


def _one_line(ended: Ended, prefix: str) -> str:
    """The last non-empty line of the command's stderr (or stdout) starting with ``prefix``."""
    assert "Traceback" not in ended.stderr, ended.stderr
    lines = [ln for ln in (ended.stderr + ended.stdout).splitlines() if ln.startswith(prefix)]
    assert len(lines) == 1, (ended.stdout, ended.stderr)
    return lines[0]


# -- the endings of `mrsus hil run`, over both rigs ------------------------------------------
SIGNALLED = {
    "sigint": (130, "interrupted (SIGINT"),
    "sigterm": (143, "terminated (SIGTERM)"),
    "sighup": (129, "terminal hung up (SIGHUP)"),
}


@pytest.mark.audit("hil endings")
@pytest.mark.parametrize("rig", ["simulated", "udp"])
@pytest.mark.parametrize("how", ["completion", "trip", "sigint", "sigterm", "sighup", "kill9"])
def test_every_ending_leaves_the_rig_home(tmp_path: Path, rig: str, how: str) -> None:
    scenario = SCENARIO
    duration = "0.8" if how == "completion" else "30"
    if how == "trip":
        scenario = tmp_path / "trip.toml"
        scenario.write_text(TRIP_SCENARIO)
    args = [str(scenario), "--duration", duration, "--rate", str(RATE), "--realtime", "off"]
    args += ["--out", "rec"]
    with contextlib.ExitStack() as stack:
        witness = None
        if rig == "udp":
            server = stack.enter_context(rig_server())
            witness = server.witness
            args += ["--rig", f"udp://127.0.0.1:{server.port}"]
        signalled = how in ("sigint", "sigterm", "sighup", "kill9")

        def ready() -> bool:
            # this run's own recording shows a commanded current (a witness alone could
            # count a stray datagram from another test's loop to a reused port: the
            # signal would then hit a command whose loop has not started)
            return _driven(tmp_path) and (witness is None or witness.driven)

        ended = run_cli(args, tmp_path, how if signalled else None, ready if signalled else None)
    print(f"{how} over {rig}: exit {ended.code} in {ended.seconds:.2f} s; {ended.stderr[-300:]}")
    assert ended.left == [], f"processes left: {ended.left}"
    if how == "kill9":  # the loop finished the safe stop alone and kept its recording
        assert ended.code == -signal.SIGKILL
        kept = tmp_path / "rec.recovered"
        stop = _check_home(kept, witness)
        assert stop["ending"] == "orphaned"
        assert "parent process" in stop["reason"]
        assert not list(tmp_path.glob(".rec.*.tmp"))  # nothing a next run would remove
        line = _one_line(ended, "hil run: ")
        assert str(kept.name) in line
        assert "mid-stroke" in line
        assert ended.seconds < 10.0  # the loop stopped at once, not after its 30 s
        return
    stop = _check_home(tmp_path / "rec", witness, driven=how != "trip")  # trips in the start-up
    if how in SIGNALLED:
        code, reason = SIGNALLED[how]
        assert ended.code == code, ended.stderr
        assert stop["ending"] == "interrupted"
        assert stop["reason"].startswith(reason)
        line = _one_line(ended, "interrupted: ")
        assert line.startswith("interrupted: kept the recording in 'rec' (loop stopped: " + reason)
        assert ended.seconds < 10.0
    elif how == "completion":
        assert ended.code == 0, ended.stderr
        assert stop["ending"] == "completed"
        assert _one_line(ended, "stopped: ") == "stopped: completed"
    else:
        assert ended.code == EXIT_CODES["tripped"] == 1, ended.stderr
        assert stop["ending"] == "tripped"
        assert "exceeds" in stop["reason"]
        assert _one_line(ended, "stopped: ") == f"stopped: {stop['reason']}"


#: a half car, the rear damper (passive 0.1 A) on the rig, the rest of the car simulated
HALF_CAR = ROOT / "examples" / "vehicles" / "half_car.toml"
#: a half car on a harmonic road far beyond the commanded stroke rate limit: it trips
TRIP_HALF_CAR = """
[vehicle]
model = "half-car"

[damper]
model = "wang-symmetric"
parameters = "wang-symmetric-low"

[controller]
law = "passive"
current = 0.1

[excitation]
kind = "harmonic"
frequency = 12.0
amplitude = 0.06
speed = 54.0
"""


@pytest.mark.audit("hil endings")
@pytest.mark.parametrize("how", ["trip", "sigint"])
def test_a_half_car_run_ends_with_the_rig_home(tmp_path: Path, how: str) -> None:
    """Issue 28: a half car with one corner on the rig ends as a quarter car does: a trip
    exits 1, Ctrl-C to the process group exits 130, the rig home at 0 A either way."""
    scenario = HALF_CAR
    if how == "trip":
        scenario = tmp_path / "trip.toml"
        scenario.write_text(TRIP_HALF_CAR)
    args = [str(scenario), "--corner", "rear", "--duration", "30", "--rate", str(RATE)]
    args += ["--realtime", "off", "--out", "rec"]
    signalled = how == "sigint"
    ended = run_cli(args, tmp_path, how if signalled else None, (lambda: _driven(tmp_path)))
    print(f"half car, {how}: exit {ended.code} in {ended.seconds:.2f} s; {ended.stderr[-300:]}")
    assert ended.left == [], f"processes left: {ended.left}"
    stop = _check_home(tmp_path / "rec", None, driven=signalled)
    meta = json.loads((tmp_path / "rec" / "meta.json").read_text())
    assert meta["vehicle"]["corner"] == "rear"
    assert "heave" in meta["channels"]
    if signalled:
        assert ended.code == 130, ended.stderr
        assert stop["ending"] == "interrupted"
        assert _one_line(ended, "interrupted: ").startswith(
            "interrupted: kept the recording in 'rec' (loop stopped: interrupted (SIGINT"
        )
        assert ended.seconds < 10.0
    else:
        assert ended.code == 1, ended.stderr
        assert stop["ending"] == "tripped"
        assert "exceeds" in stop["reason"]
        assert _one_line(ended, "stopped: ") == f"stopped: {stop['reason']}"


@pytest.mark.audit("hil endings")
def test_a_dead_link_trips_and_the_rig_is_left_home(tmp_path: Path) -> None:
    """The rig server stops answering (every reply lost after 1.5 s): the loop's watchdog
    trips, the loop ramps the rig home (the commands still reach it) and exits 1."""
    with rig_server(drop=1.0, drop_after=round(1.5 * RATE)) as server:
        args = [str(SCENARIO), "--duration", "30", "--rate", str(RATE), "--realtime", "off"]
        args += ["--out", "rec", "--rig", f"udp://127.0.0.1:{server.port}"]
        ended = run_cli(args, tmp_path)
    print(f"dead link: exit {ended.code}; {ended.stdout[:200]}")
    stop = _check_home(tmp_path / "rec", server.witness)
    assert ended.code == 1
    assert stop["ending"] == "tripped"
    assert "rig watchdog" in stop["reason"]
    assert _one_line(ended, "stopped: ").startswith("stopped: rig watchdog")


@contextlib.contextmanager
def small_disk(where: Path, size: str) -> Iterator[Callable[[], None] | None]:
    """A full-able file system at ``where``: a tmpfs of ``size`` when this process may
    mount one (yields None), else a file-size limit for the command (yields its preexec).
    """
    where.mkdir()
    mounted = (
        os.geteuid() == 0
        and subprocess.run(
            ["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(where)],
            capture_output=True,
        ).returncode
        == 0
    )
    try:
        if mounted:
            yield None
        else:
            limit = int(size.rstrip("k")) * 1024

            def limited() -> None:
                signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # EFBIG instead of a kill
                resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

            yield limited
    finally:
        if mounted:
            subprocess.run(["umount", "-l", str(where)], capture_output=True)


@pytest.mark.audit("hil endings")
def test_a_full_disk_trips_and_keeps_the_rows_recorded(tmp_path: Path) -> None:
    """The recorder's writer fails (no space left): the loop trips at once ("recording
    failed"), ramps the rig home, and the rows written so far are kept as a visible
    ``rec.recovered`` (the staged folder is not committed on a full disk); exit 1."""
    disk = tmp_path / "disk"
    with small_disk(disk, "96k") as preexec:
        args = [str(SCENARIO), "--duration", "30", "--rate", "1000", "--realtime", "off"]
        ended = run_cli([*args, "--out", "rec"], disk, preexec=preexec)
        print(f"full disk ({'tmpfs' if preexec is None else 'RLIMIT_FSIZE'}): exit {ended.code}")
        print(ended.stdout[:300], ended.stderr[-300:])
        assert ended.code == 1, ended.stderr
        kept = disk / "rec.recovered"
        rec = load_recording(kept)
        assert rec.complete
        assert rec.stop["ending"] == "recording failed"
        assert "recording failed" in rec.stop["reason"]
        assert len(rec) > 100  # the rows written before the disk filled
        assert not (disk / "rec").exists()
        assert _one_line(ended, "stopped: ").startswith("stopped: recording failed")
        assert _one_line(ended, "recording: ").endswith("rec.recovered (not committed to --out)")
        assert ended.seconds < 20.0  # tripped at once, not after the 30 s


# -- in the loop's own process: an exception in a tick, a rig that refuses commands ---------
def _sim() -> Any:
    return Scenario.load(SCENARIO).simulations()[0]


class _Faulty:
    """Raises from ``method`` at its ``at``-th call (``every``: at every call from then on)."""

    def __init__(self, method: str, at: int, every: bool = False) -> None:
        self.method, self.at, self.every, self.calls = method, at, every, 0

    def wrap(self, rig: Any) -> Any:
        original = getattr(rig, self.method)

        def faulty(*a: Any, **kw: Any) -> Any:
            self.calls += 1
            if self.calls == self.at or (self.every and self.calls > self.at):
                raise OSError(101, "Network is unreachable")
            return original(*a, **kw)

        setattr(rig, self.method, faulty)
        return rig


@pytest.mark.audit("hil endings")
@pytest.mark.parametrize("rig", ["simulated", "udp"])
@pytest.mark.parametrize("where", ["read", "command"])
def test_an_exception_in_a_tick_trips_and_returns_home(rig: str, where: str) -> None:
    """rig.read or rig.command raises once while the rig is driven: the loop trips
    (ending ``failed``, exit code 1 for ``hil run``), current 0, back to mid-stroke."""
    limits = SafetyLimits(watchdog=0.2)
    fault = _Faulty(where, at=round(0.8 * RATE))
    if rig == "udp":
        with rig_server() as server:
            the_rig = fault.wrap(UdpRig("127.0.0.1", server.port))
            result = run_hil(_sim(), the_rig, duration=30, rate=RATE, realtime="off",
                             limits=limits)  # fmt: skip
        witness: Witness | None = server.witness
    else:
        result = run_hil(_sim(), fault.wrap(SimulatedRig(damper=_sim().damper)), duration=30,
                         rate=RATE, realtime="unpaced", limits=limits)  # fmt: skip
        witness = None
    rec = result.recording
    print(f"exception in rig.{where} over {rig}: {result.reason}")
    assert result.ending == "failed"
    assert result.tripped
    assert EXIT_CODES[result.ending] == 1
    assert "OSError: [Errno 101] Network is unreachable" in result.reason
    assert rec["x_cmd"][-1] == 0.0
    assert rec["i_cmd"][-1] == 0.0
    assert np.all(rec["i_cmd"][rec["state"] == 3] == 0.0)
    assert len(rec) < 2 * RATE  # stopped at the fault (0.8 s), not after 30 s
    if witness is not None:
        assert witness.driven
        assert witness.last == (0.0, 0.0)
    else:
        assert abs(rec["x_m"][-1]) < 2e-3


@pytest.mark.audit("hil endings")
def test_a_rig_that_refuses_every_command_is_given_up_bounded() -> None:
    """A dead link on the sending side (every send fails): the loop trips, keeps trying to
    command the rig home for 0.1 s, then ends and leaves the rig to its own watchdog."""
    fault = _Faulty("command", at=round(0.8 * RATE), every=True)
    rig = fault.wrap(SimulatedRig(damper=_sim().damper))
    t = time.monotonic()
    result = run_hil(_sim(), rig, duration=30, rate=RATE, realtime="off")
    seconds = time.monotonic() - t
    print(f"refused commands: {result.reason} ({seconds:.2f} s)")
    assert result.ending == "failed"
    assert "the rig could not be commanded" in result.reason
    assert "gave up commanding the rig after" in result.reason
    assert fault.calls - fault.at <= round(0.1 * RATE) + 2  # bounded tries
    assert result.recording.complete
    assert result.recording["i_cmd"][-1] == 0.0


@pytest.mark.audit("hil endings")
def test_a_signal_in_process_stops_the_loop_safely_then_is_delivered() -> None:
    """In the caller's own process (no ``process=True``): Ctrl-C during the wait for a tick
    trips the loop, which ramps home and closes its recording; then KeyboardInterrupt is
    raised as usual. The temporary recording is kept (no result is returned)."""
    seen: list[Any] = []
    rig = SimulatedRig(damper=_sim().damper)
    command = rig.command

    calls = [0]

    def ctrl_c_once_driven(stroke: float, current: float, velocity: float = 0.0) -> None:
        command(stroke, current, velocity)
        calls[0] += 1
        # once driven (or, failing that, after 3 s of ticks: the check below then says so),
        # it lands in the tick, then the wait
        if (current > 0.0 or calls[0] > 3 * RATE) and not hasattr(rig, "sent"):
            rig.sent = True  # type: ignore[attr-defined]
            os.kill(os.getpid(), signal.SIGINT)

    rig.command = ctrl_c_once_driven  # type: ignore[method-assign]
    with pytest.raises(KeyboardInterrupt):
        run_hil(_sim(), rig, duration=10, rate=RATE, realtime="off", on_stop=seen.append)
    (result,) = seen
    print(f"in-process Ctrl-C: {result.reason}; kept in {result.out}")
    assert result.ending == "interrupted"
    assert result.signal == signal.SIGINT
    assert result.recording["x_cmd"][-1] == 0.0
    assert result.recording["i_cmd"][-1] == 0.0
    assert np.any(result.recording["i_cmd"] > 0.0)  # driven before the signal
    assert result.out is not None
    assert load_recording(result.out).complete
    json.loads((result.out / "stop.json").read_text())  # a plain JSON stop record
