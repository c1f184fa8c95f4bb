"""Full-car benchmark: ``python benchmarks/bench_vehicle.py [--duration S] [--repeat N] [--json]``.

A full car (the published set, the dissertation's hysteretic damper and skyhook hi-lo at
every corner) on a harmonic road with the rear wheels delayed, 10 s at dt = 1e-4 s after
compilation, beside its baseline measured in the same process: four quarter-car runs of
the same length (one per corner, the same damper and controller). The issue's target is
<= 0.2 s for the full car. Times are the median of ``--repeat`` runs, each
:meth:`~mrsuspension.engine.vehicle.VehicleSimulation.run` or
:meth:`~mrsuspension.engine.Simulation.run` (road sampling and result building included).
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

from mrsuspension.control import HiLo
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import Harmonic, WheelRoads
from mrsuspension.vehicle import FullCar

#: the issue-19 target for a 10 s full-car run at dt = 1e-4 s [s]
TARGET = 0.2


def _median_time(fn: object, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()  # type: ignore[operator]
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def run_benchmark(duration: float = 10.0, dt: float = 1e-4, repeat: int = 5) -> dict[str, float]:
    """Full-car and 4x quarter-car run times [s] and their ratio (after compilation)."""
    car = FullCar()
    controller = HiLo(1, mode="ACM")
    exc = Harmonic(1.5, 0.025)
    road = WheelRoads.from_excitation(exc, car, speed_kmh=72.0)
    full = VehicleSimulation(car, road, controllers=controller)
    quarters = [
        Simulation(exc, vehicle=car.corner_quarter_car(c), controller=controller)
        for c in car.corners
    ]
    t0 = time.perf_counter()
    full.run(dt, dt=dt)  # compile (or load from numba's cache)
    for q in quarters:
        q.run(dt, dt=dt)
    warm = time.perf_counter() - t0
    t_full = _median_time(lambda: full.run(duration, dt=dt), repeat)
    t_quarter = _median_time(lambda: [q.run(duration, dt=dt) for q in quarters], repeat)
    return {
        "duration_s": duration,
        "dt_s": dt,
        "first_call_s": warm,
        "full_car_s": t_full,
        "four_quarter_cars_s": t_quarter,
        "ratio_full_to_four_quarter": t_full / t_quarter,
        "target_s": TARGET,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=10.0, help="simulated time [s]")
    ap.add_argument("--repeat", type=int, default=5, help="runs per timing (median)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()
    res = run_benchmark(args.duration, repeat=args.repeat)
    if args.json:
        print(json.dumps(res))
        return
    print(f"full car, {res['duration_s']:g} s at dt = {res['dt_s']:g} s: "
          f"{res['full_car_s']:.3f} s (target <= {TARGET:g} s: "
          f"{'met' if res['full_car_s'] <= TARGET else 'NOT met'})")  # fmt: skip
    print(f"baseline, 4 quarter-car runs of the same length: {res['four_quarter_cars_s']:.3f} s")
    print(f"ratio full car / 4 quarter cars: {res['ratio_full_to_four_quarter']:.2f}")
    print(f"first call (compile or cache load): {res['first_call_s']:.1f} s")


if __name__ == "__main__":
    main()
