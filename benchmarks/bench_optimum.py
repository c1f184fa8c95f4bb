"""The semi-active optimum on a 10 s ISO 8608 class C record at 50 km/h (issue 29's acceptance).

``python benchmarks/bench_optimum.py [--duration S] [--dt S] [--seed N] [--json] [--quiet]``

Builds the quarter car's optimal control problem on the road (the toolkit's ISO 8608
generator, fixed seed), evaluates the passive car (0 A and 0.5 A) and the skyhook through
the band on the same discretised model, solves the optimum with IPOPT (its iterations
printed unless ``--quiet``), checks the optimal force against the band on every interval
and replays it in the toolkit's engine. Prints the status, the cost, the times, the
largest band violation and the optimum's ratios to the passive car (docs/benchmark.md
quotes them). Needs CasADi (``pip install "mrsuspension[optimal]"``); about a minute or
two at the defaults on one core.
"""

from __future__ import annotations

import argparse
import json
import time

from mrsuspension.benchmark import BenchmarkProblem, replay
from mrsuspension.excitation import iso8608


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10.0, help="record length [s]")
    parser.add_argument("--dt", type=float, default=1e-3, help="grid step [s]")
    parser.add_argument("--seed", type=int, default=0, help="ISO 8608 random-phase seed")
    parser.add_argument("--speed", type=float, default=50.0, help="vehicle speed [km/h]")
    parser.add_argument("--json", action="store_true", help="print one JSON object (quiet)")
    parser.add_argument("--quiet", action="store_true", help="no IPOPT iteration lines")
    parser.add_argument("--half-car", action="store_true", help="the half car (quiet)")
    args = parser.parse_args()
    if args.half_car:
        half_car(args)
        return

    length = args.speed / 3.6 * args.duration + 5.0
    road = iso8608("C", length=length, seed=args.seed, speed_kmh=args.speed)
    t0 = time.perf_counter()
    problem = BenchmarkProblem(road, dt=args.dt, duration=args.duration)
    passive = problem.passive()
    hard = problem.passive(u=1.0)
    skyhook = problem.skyhook()
    t_refs = time.perf_counter() - t0
    cpu = time.process_time()
    best = problem.solve(progress=not (args.quiet or args.json))
    cpu = time.process_time() - cpu
    t_replay = time.perf_counter()
    engine = replay(best, road, vehicle=problem.vehicle)
    t_replay = time.perf_counter() - t_replay
    peak = float(abs(best.force).max())
    violation = best.band_violation(problem.band)
    names = ("wk_rms_body_acceleration", "DLC", "rms_stroke")
    out = {
        "road": road.source,
        "duration_s": args.duration,
        "dt_s": args.dt,
        "intervals": problem.n,
        "band": problem.band.describe()
        | {"damper": problem.band.describe()["damper"].get("model", "wang-symmetric")},
        "weights": problem.weights.vector,
        "scales": problem.scales,
        "status": best.status,
        "converged": best.success,
        "iterations": best.iterations,
        "build_s": round(best.build_time, 2),
        "solve_s": round(best.wall_time, 2),
        "build_and_solve_cpu_s": round(cpu, 2),
        "references_s": round(t_refs, 2),
        "replay_s": round(t_replay, 2),
        "cost": {
            "optimum": best.cost,
            "passive_0A": passive.cost,
            "passive_imax": hard.cost,
            "skyhook_in_band": skyhook.cost,
        },
        "max_band_violation_N": violation,
        "peak_force_N": peak,
        "ratios_to_passive_terms": best.ratios(passive),
        "ratios_to_passive_measures": {m: best.measures[m] / passive.measures[m] for m in names},
        "skyhook_ratios_to_passive_measures": {
            m: skyhook.measures[m] / passive.measures[m] for m in names
        },
        "optimum_measures": {m: best.measures[m] for m in (*names, "mean_current")},
        "passive_measures": {m: passive.measures[m] for m in names},
        "engine_replay_over_model": {m: engine[m] / best.measures[m] for m in names},
    }
    if args.json:
        print(json.dumps(out, indent=1, default=float))
        return
    print(best.summary())
    for key in (
        "road", "intervals", "build_and_solve_cpu_s", "cost", "max_band_violation_N", "peak_force_N",
        "ratios_to_passive_measures", "skyhook_ratios_to_passive_measures",
        "engine_replay_over_model", "references_s", "replay_s",
    ):  # fmt: skip
        print(f"{key}: {out[key]}")


def half_car(args: argparse.Namespace) -> None:
    """The half car's optimum on the same road (rear wheel wheelbase / V later)."""
    from mrsuspension.benchmark import HalfCarProblem

    length = args.speed / 3.6 * args.duration + 10.0
    road = iso8608("C", length=length, seed=args.seed, speed_kmh=args.speed)
    cpu = time.process_time()
    problem = HalfCarProblem(road, dt=args.dt, duration=args.duration)
    passive = problem.passive()
    best = problem.solve()
    cpu = time.process_time() - cpu
    out = {
        "road": road.source,
        "duration_s": args.duration,
        "dt_s": args.dt,
        "intervals": problem.n,
        "delay_s": problem.delay,
        "status": best.status,
        "converged": best.success,
        "iterations": best.iterations,
        "passive_iterations": passive.iterations,
        "solve_s": round(best.wall_time, 2),
        "cpu_s": round(cpu, 2),
        "cost": {"optimum": best.cost, "passive_0A": passive.cost},
        "max_band_violation_N": best.band_violation(problem.band),
        "ratios_to_passive_terms": best.ratios(passive),
        "ratios_to_passive_measures": {
            m: best.measures[m] / passive.measures[m] for m in best.measures
        },
        "passive_measures": passive.measures,
    }
    print(json.dumps(out, indent=1, default=float))


if __name__ == "__main__":
    main()
