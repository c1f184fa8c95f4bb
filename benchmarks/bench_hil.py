"""HiL loop timing: ``python benchmarks/bench_hil.py [--duration S] [--rates 1000,2000,5000]``.

Runs the skyhook hi-lo example scenario in the real-time loop with the simulated rig, in
this process, and prints per-tick compute time (p50/p99/max), lateness, jitter and the
share of ticks that met their deadline at each rate.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from mrsuspension.hil import SimulatedRig, run_hil
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=60.0, help="seconds per rate")
    ap.add_argument("--rates", default="1000,2000,5000", help="loop rates [Hz]")
    args = ap.parse_args()
    sim = Scenario.load(ROOT / "examples/scenarios/skyhook-hilo-acm-harmonic.toml").simulations()[0]
    for rate in (float(r) for r in args.rates.split(",")):
        result = run_hil(sim, SimulatedRig(sim.damper), duration=args.duration, rate=rate)
        print(f"{rate:6.0f} Hz: {result.stats.summary()}")


if __name__ == "__main__":
    main()
