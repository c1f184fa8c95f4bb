"""A user-defined law's cost beside a built-in law's:
``python benchmarks/bench_user_law.py [--steps N] [--repeat N] [--json]``.

Per engine step of a quarter-car run (``Simulation.run``, dt = 1e-4 s, output at
100 Hz, best of ``--repeat`` runs after a warm-up): the built-in passive and skyhook hi-lo
laws, and an on-off skyhook written in plain Python (``mrsuspension.control.law``) on
the numba path and on the Python path; then the law's call alone (``UserLaw.cost``) and
the time to build a law's numba entry (first and second law of the process).
"""

from __future__ import annotations

import argparse
import json
import time
from typing import Any

from mrsuspension.control import HiLo, Passive, law
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic

DT = 1e-4


def onoff(z_s_dot: float, v_d: float, high: float = 0.5) -> float:
    """On-off skyhook: high current when the damper can push against the body's velocity."""
    return high if z_s_dot * v_d < 0.0 else 0.0


def constant(current: float = 0.2) -> float:
    """A constant current (the passive law)."""
    return current


def _per_step(controller: Any, steps: int, repeat: int) -> float:
    sim = Simulation(Harmonic(1.5, 0.02), controller=controller)
    sim.run(DT * 100, dt=DT)  # warm-up (and the law's entry)
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        sim.run(DT * steps, dt=DT, output_rate=100.0)
        best = min(best, (time.perf_counter() - t0) / steps)
    return best


def run_benchmark(steps: int = 50_000, repeat: int = 5) -> dict[str, float]:
    """Per-step times [ns], the law's call [ns] and the entry build times [s]."""
    numba_law = law(onoff)
    python_law = law(numba=False)(onoff)
    t0 = time.perf_counter()
    first = numba_law.entry().compile_seconds
    second = law(constant).entry().compile_seconds
    build = time.perf_counter() - t0
    out = {
        "passive_ns_per_step": _per_step(Passive(0.2), steps, repeat) * 1e9,
        "skyhook_hilo_ns_per_step": _per_step(HiLo(1), steps, repeat) * 1e9,
        "user_numba_ns_per_step": _per_step(numba_law(), steps, repeat) * 1e9,
        "user_python_ns_per_step": _per_step(python_law(), steps, repeat) * 1e9,
        "user_numba_call_ns": numba_law.cost() * 1e9,
        "user_python_call_ns": python_law.cost() * 1e9,
        "first_law_build_s": first,
        "second_law_build_s": second,
        "both_builds_s": build,
    }
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=50_000)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    out = run_benchmark(args.steps, args.repeat)
    if args.json:
        print(json.dumps(out))
        return
    for key, value in out.items():
        print(f"{key:28s} {value:10.3f}" if key.endswith("_s") else f"{key:28s} {value:10.0f}")


if __name__ == "__main__":
    main()
