"""The live road in a paced loop: ``python benchmarks/bench_live_road.py [--duration S]``.

Runs the skyhook hi-lo example scenario with live hooks (``LoopHooks()``, as the browser
monitor does: the road is then computed inside the ticks, see docs/hil.md) and the
simulated rig, in this process, once per excitation (``--excitations
harmonic,road,pulse``: the example's 1.5 Hz harmonic, the rough preset road at 50 % and
50 km/h, a 5 cm rounded pulse), and prints the per-tick compute time of the ticks
``k % 50 == 0`` (where the road used to be computed, 50 ticks at a time) against the
other ticks, and of all ticks, while the model runs (p50/p99/p99.9/max, us), with the CPU
the machine's other processes used meanwhile (``others``, cores).
``--realtime spin|fifo|auto|off`` selects the scheduling (default ``spin``: pinned,
busy-waiting, memory locked where permitted).

Keep runs short on a shared machine::

    python benchmarks/bench_live_road.py --duration 12
"""

from __future__ import annotations

import argparse
import dataclasses
import time
from pathlib import Path

import numpy as np

from mrsuspension.excitation import RoundedPulse, preset_road
from mrsuspension.hil import SimulatedRig, run_hil
from mrsuspension.hil.latency import cpu_times
from mrsuspension.hil.loop import LoopHooks
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[1]


def _cells(x: np.ndarray) -> str:
    p50, p99, p999 = np.percentile(x, [50, 99, 99.9])
    return f"{p50:6.0f} {p99:6.0f} {p999:6.0f} {x.max():6.0f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--duration", type=float, default=12.0, help="seconds per excitation")
    ap.add_argument("--excitations", default="harmonic,road,pulse")
    ap.add_argument("--realtime", default="spin", help="spin | fifo | auto | off (docs/hil.md)")
    args = ap.parse_args()
    base = Scenario.load(ROOT / "examples/scenarios/skyhook-hilo-acm-harmonic.toml")
    sim = base.simulations()[0]
    roads = {
        "harmonic": sim.excitation,
        "road": preset_road("rough", 50.0).scaled(0.5),
        "pulse": RoundedPulse(0.05, 1.0, speed_kmh=50.0, delay=0.5),
    }
    cols = "p50    p99  p99.9    max"
    print(f"compute per tick [us] while the model runs ({args.realtime}, 1 kHz)")
    print(f"{'':9} | {'k % 50 == 0':^27} | {'other ticks':^27} | {'all':^27} | misses others")
    print(f"{'':9} | {cols:>27} | {cols:>27} | {cols:>27} |")
    for name in args.excitations.split(","):
        live = dataclasses.replace(sim, excitation=roads[name])
        busy0, _ = cpu_times()
        cpu0, wall = time.process_time(), time.perf_counter()
        result = run_hil(
            live, SimulatedRig(live.damper), duration=args.duration, realtime=args.realtime,
            hooks=LoopHooks(),
        )  # fmt: skip
        wall = time.perf_counter() - wall
        others = max(0.0, (cpu_times()[0] - busy0) - (time.process_time() - cpu0)) / wall
        rec = result.recording
        c = rec["compute"][rec["state"] <= 1] * 1e6
        k = np.arange(c.size)
        print(
            f"{name:9} | {_cells(c[k % 50 == 0])} | {_cells(c[k % 50 != 0])} | {_cells(c)} | "
            f"{result.stats.misses:6d} {others:6.2f}"
        )
        if result.reason != "completed":
            print(f"          stopped early: {result.reason}")


if __name__ == "__main__":
    main()
