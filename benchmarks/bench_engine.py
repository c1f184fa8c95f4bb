"""Engine benchmark: ``python benchmarks/bench_engine.py [--quick] [--json]``.

The same as ``mrsus bench``: a 10 s simulation (hysteretic damper, skyhook policy I,
dt = 1e-4 s) against scipy's solve_ivp (RK45 and LSODA) and against the engine's own
algorithm in plain Python, written independently in :mod:`mrsuspension.bench`; a
60-frequency x 4-controller sweep on all cores; and the numba compile time.
"""

from __future__ import annotations

import argparse
import json

from mrsuspension.bench import run_benchmarks


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="1 s runs and a 6-frequency sweep")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--workers", type=int, default=None, help="processes for the sweep")
    args = ap.parse_args()
    res = run_benchmarks(quick=args.quick, workers=args.workers, say=lambda m: print("..", m))
    if args.json:
        print(json.dumps(res))
        return
    width = max(map(len, res))
    for key, value in res.items():
        shown = f"{value:.4g}" if isinstance(value, float) else str(value)
        print(f"{key:<{width}}  {shown}")


if __name__ == "__main__":
    main()
