"""HiL loop timing: ``python benchmarks/bench_hil.py [--duration S] [--rates 1000,2000,5000]``.

Runs the skyhook hi-lo example scenario in the real-time loop with the simulated rig, in
this process, and prints a table per rate: the share of ticks that met their deadline,
per-tick compute time (p50/p99/max), release lateness, jitter (standard deviation and
largest deviation of the start-to-start interval), and the CPU time the machine lost
meanwhile (``steal``: taken by the hypervisor, ``others``: cores busy with other
processes, the emulator included with ``--rig udp``), then the highest rate sustained
with >= 99.9 % of ticks in deadline.
``--realtime auto|fifo|spin|off`` selects the scheduling (docs/hil.md); ``--rig udp`` runs
the rig in a ``mrsus rig-emulator`` process (same scheduling option) over loopback UDP.
``--isolate`` moves every other movable task off the loop's core during each run (and
each floor): ``run_hil(..., isolate=True)``, docs/hil.md "Isolating the loop's core".
``--floor`` measures the machine's floor right before each HiL run
(:func:`~mrsuspension.hil.latency.measure_latency`, ``mrsus hil latency``: the same rate,
duration and scheduling with empty ticks, or ``--floor-work-us`` of busy work per tick)
and prints its share of ticks in deadline, stalls longer than a period and steal beside
the loop's row: the machine floor against the loop.

On a quiet machine (the issue-6 acceptance measurements)::

    python benchmarks/bench_hil.py --duration 60 --rates 1000,2000,5000
    python benchmarks/bench_hil.py --duration 60 --rates 1000 --rig udp
"""

from __future__ import annotations

import argparse
import contextlib
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

from mrsuspension.hil import Rig, SafetyLimits, SimulatedRig, UdpRig, run_hil
from mrsuspension.hil.latency import cpu_times, measure_latency
from mrsuspension.hil.loop import TickStats
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[1]
#: the issue-6 target share of ticks in deadline
TARGET = 0.999


@contextlib.contextmanager
def _emulator(realtime: str) -> Iterator[int]:
    """A ``mrsus rig-emulator`` process on an ephemeral loopback port; yields the port."""
    code = (
        "import typer\nfrom mrsuspension.cli.hil import rig_emulator_command\n"
        "typer.run(rig_emulator_command)"
    )
    args = [sys.executable, "-c", code, "--port", "0", "--realtime", realtime]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, text=True)
    try:
        assert proc.stdout is not None
        line = proc.stdout.readline()
        if "listening on udp://" not in line:
            raise SystemExit(f"the rig emulator did not start: {line!r}")
        yield int(line.rsplit(":", 1)[1])
    finally:
        proc.terminate()
        proc.wait(10)


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--duration", type=float, default=60.0, help="seconds per rate")
    ap.add_argument("--rates", default="1000,2000,5000", help="loop rates [Hz]")
    ap.add_argument("--realtime", default="auto", help="auto | fifo | spin | off (docs/hil.md)")
    ap.add_argument(
        "--isolate", action="store_true", help="move other tasks off the loop's core meanwhile"
    )
    ap.add_argument("--rig", default="simulated", choices=("simulated", "udp"))
    ap.add_argument("--watchdog", type=float, default=None, help="rig watchdog [s] (0.05)")
    ap.add_argument(
        "--floor", action="store_true", help="measure the machine floor before each run"
    )
    ap.add_argument(
        "--floor-work-us", type=float, default=0.0, help="busy work per floor tick [us]"
    )
    args = ap.parse_args()
    with contextlib.ExitStack() as stack:
        port = stack.enter_context(_emulator(args.realtime)) if args.rig == "udp" else 0
        _bench(args, port)


def _bench(args: argparse.Namespace, port: int) -> None:
    sim = Scenario.load(ROOT / "examples/scenarios/skyhook-hilo-acm-harmonic.toml").simulations()[0]
    us = 1e6
    head = (
        f"{'rate':>6} {'ticks':>7} {'in dl %':>8} {'miss':>5} {'cmp p50':>8} {'p99':>7} "
        f"{'max':>7} {'late p99':>8} {'max':>7} {'jit sd':>7} {'max':>7} {'steal':>6} "
        f"{'others':>6}"
    )
    if args.floor:
        head += f" | {'floor %':>8} {'stalls':>6} {'steal':>6} {'others':>6}"
    print("times in us; steal [s] and others [cores] over the run")
    if args.floor:
        print(
            "floor: the machine alone right before (mrsus hil latency, "
            f"{args.floor_work_us:g} us of work per tick): % in deadline, stalls > 1 period, "
            "steal [s], others [cores]"
        )
    print(head)
    rows: list[tuple[float, TickStats]] = []
    for rate in (float(r) for r in args.rates.split(",")):
        floor = ""
        if args.floor:  # the machine alone, right before the loop, same rate and mode
            f = measure_latency(
                rate, args.duration, args.realtime, work=args.floor_work_us * 1e-6,
                isolate=args.isolate,
            )  # fmt: skip
            f_others = f.others / f.wall if f.wall > 0 else float("nan")
            floor = (
                f" | {100 * f.stats.in_deadline:8.3f} {f.stalls:6d} {f.steal:6.2f} {f_others:6.2f}"
            )
        busy0, steal0 = cpu_times()
        cpu0 = time.process_time()
        wall = time.perf_counter()
        rig: Rig = UdpRig("127.0.0.1", port) if port else SimulatedRig(sim.damper)
        limits = SafetyLimits() if args.watchdog is None else SafetyLimits(watchdog=args.watchdog)
        result = run_hil(
            sim, rig, duration=args.duration, rate=rate, realtime=args.realtime, limits=limits,
            isolate=args.isolate,
        )  # fmt: skip
        wall = time.perf_counter() - wall
        busy1, steal1 = cpu_times()
        others = max(0.0, (busy1 - busy0) - (time.process_time() - cpu0)) / wall
        s = result.stats
        rows.append((rate, s))
        print(
            f"{rate:6.0f} {s.ticks:7d} {100 * s.in_deadline:8.3f} {s.misses:5d} "
            f"{s.compute_p50 * us:8.1f} {s.compute_p99 * us:7.1f} {s.compute_max * us:7.0f} "
            f"{s.lateness_p99 * us:8.1f} {s.lateness_max * us:7.0f} {s.jitter * us:7.1f} "
            f"{s.jitter_max * us:7.0f} {steal1 - steal0:6.2f} {others:6.2f}{floor}"
        )
        if result.reason != "completed":
            print(f"       stopped early: {result.reason}")
    print(f"rig: {args.rig}; scheduling: {rows[-1][1].scheduling}" if rows else "no rates")
    ok = [rate for rate, s in rows if s.in_deadline >= TARGET]
    best = f"{max(ok):g} Hz" if ok else "none of the rates tried"
    print(f"sustained with >= {100 * TARGET:g} % of ticks in deadline: {best}")


if __name__ == "__main__":
    main()
