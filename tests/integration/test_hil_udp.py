"""HiL over UDP: the rig emulator in another process, on an ephemeral loopback port."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from mrsuspension.cli.hil import hil_validate_command
from mrsuspension.hil import SafetyLimits, load_recording, run_hil
from mrsuspension.hil.latency import cpu_times
from mrsuspension.hil.loop import STATE_TRIPPED
from mrsuspension.hil.network import UdpRig
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[2]
#: watchdog of these tests: 100 ms, so that a loaded 2-core CI machine does not trip it
#: spuriously (a stalled emulator process); the trip test checks this timeout
WATCHDOG = 0.1
LIMITS = SafetyLimits(watchdog=WATCHDOG)
SCENARIO = ROOT / "examples" / "scenarios" / "skyhook-hilo-acm-harmonic.toml"


class Emulator:
    """A running emulator subprocess: its port and process."""

    def __init__(self, port: int, proc: subprocess.Popen[str]) -> None:
        self.port = port
        self.proc = proc


@contextmanager
def emulator(rig: str = "SimulatedRig()", **kw: object) -> Iterator[Emulator]:
    """``serve_rig`` in a ``python -c`` subprocess on an ephemeral loopback port."""
    args = ", ".join(f"{k}={v!r}" for k, v in kw.items())
    code = (
        "from mrsuspension.hil.network import serve_rig\n"
        "from mrsuspension.hil import SimulatedRig, ideal_rig\n"
        f"serve_rig({rig}, port=0, ready=lambda p: print(p, flush=True), duration=60.0, {args})"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert line.strip().isdigit(), f"emulator did not start: {line!r}"
        yield Emulator(int(line), proc)
    finally:
        proc.kill()
        proc.wait(10)


def _cpu_seconds(pid: int | None = None) -> float:
    """CPU time [s] of the whole machine (busy, all cores) or of one process (Linux /proc)."""
    hz = os.sysconf("SC_CLK_TCK")
    if pid is None:
        v = [int(x) for x in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:9]]
        return (sum(v) - v[3] - v[4]) / hz
    f = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(f[11]) + int(f[12])) / hz


def _sim():  # type: ignore[no-untyped-def]
    return Scenario.load(SCENARIO).simulations()[0]


@pytest.mark.realtime
def test_udp_run_at_1khz() -> None:
    linux = Path("/proc/stat").exists()
    # both sides busy-wait on their own core: on this VM a sleeping vCPU wakes late
    with emulator(realtime="spin") as emu:
        rig = UdpRig("127.0.0.1", emu.port)
        if linux:
            cpu0 = (_cpu_seconds(), time.process_time(), _cpu_seconds(emu.proc.pid))
            steal0 = cpu_times()[1]
        wall = time.perf_counter()
        result = run_hil(_sim(), rig, duration=3.0, rate=1000.0, limits=LIMITS, realtime="spin")
        wall = time.perf_counter() - wall
        if linux:
            busy = _cpu_seconds() - cpu0[0]
            ours = time.process_time() - cpu0[1] + _cpu_seconds(emu.proc.pid) - cpu0[2]
            others = max(0.0, busy - ours) / wall  # cores used by other processes
            stolen = cpu_times()[1] - steal0  # [s] the hypervisor ran something else
    counts = rig.counters()
    print(f"UDP rig: {result.stats.summary()}; packets {counts}")
    target = 0.95 if "busy-wait" in result.stats.scheduling else 0.90
    if linux:
        print(f"other processes used {others:.2f} cores during the run")
        print(f"hypervisor steal {stolen:.2f} s during the run")
        # a spin loop never sleeps: with its own ticks short (median under 0.3 period), a
        # stall of several periods is the machine's (a stolen vCPU), and one such stall
        # makes the loop read stale forces
        st = result.stats
        stalled = max(st.lateness_max, st.compute_max) > 5e-3 and st.compute_p50 < 0.3e-3
        if result.stats.in_deadline < target and (others > 0.25 or stalled):
            # the loop and the emulator need about 1.3 of the 2 cores of the CI machine. On
            # a busy machine the loop falls behind, reads stale forces, and the safety
            # supervisor may stop the run (e.g. on stroke velocity): right, but not asserted.
            pytest.skip(
                f"machine busy ({others:.2f} cores used by other processes, "
                f"{stolen:.2f} s stolen by the hypervisor): "
                f"{result.stats.in_deadline:.1%} in deadline, run ended: {result.reason}"
            )
    assert result.reason == "completed", result.reason
    assert not result.tripped
    assert result.stats.ticks == len(result.recording)
    assert counts["sent"] == result.stats.ticks
    assert counts["received"] + counts["lost"] == counts["sent"]
    assert counts["lost"] <= 0.01 * counts["sent"]
    assert result.meta["rig"]["rig"] == "udp"
    # heartbeats both ways every 20 ms, all acknowledged while the loop ran
    link = rig.link()
    beats = result.stats.ticks * 1e-3 / 0.02
    assert link["heartbeats_sent"] >= 0.9 * beats
    assert link["heartbeat_acks"] >= link["heartbeats_sent"] - 2
    assert link["heartbeats_received"] >= 0.8 * beats
    assert not link["rig_safe"]
    # A regression guard, not the acceptance figure: a 3 s run on a virtual machine loses
    # a few percent to one hypervisor stall (seen here: 96.1 % once in three quiet runs,
    # 99.2 and 99.8 % otherwise). Issue 6's >= 99 % is measured over 60 s with
    # `benchmarks/bench_hil.py --rig udp --realtime spin` (docs/hil.md).
    assert rig.spin
    assert result.stats.in_deadline >= target


def test_watchdog_trips_when_the_rig_stops_replying() -> None:
    # the run's first reply is command 2 (command 1 is run_hil's warm-up): silent from 1.5 s
    with emulator(drop=1.0, drop_after=1501) as emu:
        rig = UdpRig("127.0.0.1", emu.port)
        result = run_hil(_sim(), rig, duration=3.0, rate=1000.0, limits=LIMITS)
    rec = result.recording
    print(f"trip: {result.reason}; packets {rig.counters()}")
    assert result.tripped
    assert "watchdog" in result.reason
    # the server's heartbeats still came: the replies were lost, not the link
    assert "link alive" in result.reason
    t = rec["time"]
    tripped = rec["state"] == STATE_TRIPPED
    k = int(np.argmax(tripped))
    # trips once the rig's timestamp has not advanced for the watchdog timeout
    assert 1.5 + WATCHDOG - 0.005 <= t[k] <= 1.5 + WATCHDOG + 0.02, t[k]
    fresh = rec["rig_time"][:k]
    assert np.all(rec["rig_time"][k - 90 : k] == fresh[-1])  # stale, held sample
    assert np.all(rec["i_cmd"][tripped] == 0.0)  # current 0 from the trip tick on
    assert rec["x_cmd"][-1] == 0.0  # actuator command back at mid-stroke
    assert rig.stale_reads >= 90
    assert rig.lost >= len(rec) - k


def test_short_reply_delays_ride_through() -> None:
    with emulator(delay=0.003, delay_probability=0.03, seed=1) as emu:
        rig = UdpRig("127.0.0.1", emu.port)
        result = run_hil(_sim(), rig, duration=2.0, rate=1000.0, limits=LIMITS)
    print(f"delays: {result.stats.summary()}; packets {rig.counters()}")
    assert result.reason == "completed", result.reason
    assert not result.tripped
    assert rig.late > 10  # the delayed replies came after their tick
    assert rig.stale_reads > 10


# `hil run --rig udp://...` to completion (and every other ending): test_hil_endings.py


def _ignore_sigint() -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # as a background job of a script


@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_rig_emulator_command(stop: signal.Signals) -> None:
    code = (
        "import typer\nfrom mrsuspension.cli.hil import rig_emulator_command\n"
        "typer.run(rig_emulator_command)"
    )
    # started with SIGINT ignored, it still stops on Ctrl-C (and on SIGTERM) with counts
    proc = subprocess.Popen(
        [sys.executable, "-c", code, "--port", "0", "--rig", "ideal"],
        stdout=subprocess.PIPE,
        text=True,
        preexec_fn=_ignore_sigint,
    )
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        assert "listening on udp://127.0.0.1:" in line, line
        port = int(line.rsplit(":", 1)[1])
        rig = UdpRig("127.0.0.1", port)
        assert rig.ping() < 0.5
        rig.reset(1e-3)
        assert rig.ideal_current
        rig.command(0.01, 0.1, 0.0)
        sample = rig.read()
        assert sample.displacement == pytest.approx(0.01)
        rig.close()
        proc.send_signal(stop)
        rest, _ = proc.communicate(timeout=10)
        assert "stopped: commands 1" in rest
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait(10)


def test_hil_validate_with_the_ideal_rig(tmp_path: Path) -> None:
    app = typer.Typer(pretty_exceptions_enable=False)
    app.command("validate")(hil_validate_command)
    app.command("other")(lambda: None)
    out = tmp_path / "validate"
    res = CliRunner().invoke(
        app,
        [
            "validate",
            str(SCENARIO),
            "--what",
            "time",
            "--duration",
            "2.0",
            "--out",
            str(out),
            "--json",
        ],
    )
    assert res.exit_code == 0, res.output
    info = json.loads(res.stdout)
    body = info["rms"]["body_acceleration"]
    print(
        f"validate (ideal rig, 2 s): rms z_s'' HiL {body['hil']:.5f} offline {body['offline']:.5f}"
    )
    assert abs(body["relative_difference"]) < 0.01
    assert info["reason"] == "completed"
    for name in ("time_histories.png", "fv_loop.png", "summary.json"):
        assert (out / name).stat().st_size > 1000
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["rms"]) >= {"body_acceleration", "damper_force", "suspension_travel"}
    assert load_recording(out / "recording").complete
    text = CliRunner().invoke(
        app, ["validate", str(SCENARIO), "--what", "time", "--duration", "0.5"]
    )
    assert text.exit_code == 0, text.output
    assert "body acceleration" in text.stdout
