"""Identification benchmark: a 30-test campaign, end to end, and the fit against baselines.

A synthetic campaign of the dissertation's symmetric model (Table 2.2, 0.5-5 Hz set;
6 frequency/amplitude pairs x 5 currents = 30 tests, 2 % force noise) is written to a
temporary folder, one steady cycle per record (plus a fraction of one, at 1 kHz), in
the four file layouts. Timed in the same process:

* ``end to end``: ``identify(manifest)``: read 30 files, pre-process, fit from a start
  20 % off (4 starts), per-test metrics (no plots);
* the fit alone, from the same starts, three ways:

  - ``ours``: ``least_squares`` (TRF, LSMR trust-region steps) with the analytic Jacobian
    of eqs. (2.7)-(2.15);
  - ``least_squares, finite differences``: the same with ``jac="2-point"``;
  - ``minimize (L-BFGS-B) on the summed squares``: the textbook approach of the
    dissertation's ``fminunc``, gradient by finite differences.

The baselines are reported as time ratios (baseline / ours) and with their final
RMS NRMSE, so a faster method that stops early shows it. All three run with
single-threaded BLAS, as the package's fit does; a last line runs ours with the default
multi-threaded BLAS, whose cost on a busy machine is why the fit limits it.

Run: ``python benchmarks/bench_identify.py [--tests N] [--starts S] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import math
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares, minimize

from mrsuspension import parameters
from mrsuspension.identify import FitProblem, identify, synthetic_campaign
from mrsuspension.identify._threads import blas_threads

PAIRS = [(0.5, 0.025), (1.5, 0.0125), (2.5, 0.0125), (5.0, 0.0025), (2.5, 0.025), (1.0, 0.025)]
CURRENTS = (0.0, 0.1, 0.2, 0.3, 0.4)


def campaign(folder: Path, n_tests: int) -> Path:
    conds = [(f, a, i) for f, a in PAIRS for i in CURRENTS][:n_tests]
    return synthetic_campaign(
        folder, "wang-symmetric", conds, noise=0.02, cycles=1, layout="mixed", seed=3
    )


def rms(problem: FitProblem, x: np.ndarray) -> float:
    r = problem.residuals(x)
    return math.sqrt(float(r @ r) / len(problem.data.loops))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tests", type=int, default=30, help="tests in the campaign (<= 30)")
    ap.add_argument("--starts", type=int, default=4, help="multi-start count")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()

    truth = parameters.get("wang-symmetric-low")
    rng = np.random.default_rng(1)
    start = truth.replace(**{k: v * (1 + rng.uniform(-0.2, 0.2)) for k, v in truth.items()})
    with tempfile.TemporaryDirectory() as tmp:
        manifest = campaign(Path(tmp), args.tests)
        identify(manifest, multistart=1, max_nfev=3)  # warm-up: imports, compiled kernels
        t0 = time.perf_counter()
        result = identify(manifest, start=start, multistart=args.starts)
        end_to_end = time.perf_counter() - t0
        loops = [t.loop for t in result.tests if t.loop is not None]

    problem = FitProblem(loops, start=start)
    starts = problem.starts(args.starts, 0)
    timings: dict[str, dict[str, float]] = {}

    def run(label: str, solve) -> None:  # type: ignore[no-untyped-def]
        t0 = time.perf_counter()
        best = min((solve(x0) for x0 in starts), key=lambda x: rms(problem, x))
        timings[label] = {"seconds": time.perf_counter() - t0, "rms_nrmse": rms(problem, best)}

    bounds = (problem.lower, problem.upper)

    def ours(x0: np.ndarray) -> np.ndarray:
        return least_squares(problem.residuals, x0, jac=problem.jacobian, bounds=bounds,
                             x_scale="jac", tr_solver="lsmr").x  # fmt: skip

    scale = np.abs(problem.x_start) + 1e-3  # minimize works on parameters scaled to ~1

    def summed(z: np.ndarray) -> float:
        r = problem.residuals(z * scale)
        return float(r @ r) if np.all(np.isfinite(r)) else 1e300

    with blas_threads(1):  # as FitProblem.solve does; the baselines get the same
        run("ours", ours)
        run("least_squares, finite differences", lambda x0: least_squares(
            problem.residuals, x0, jac="2-point", bounds=bounds, x_scale="jac",
            tr_solver="lsmr").x)  # fmt: skip
        run("minimize (L-BFGS-B) on the summed squares", lambda x0: minimize(
            summed, x0 / scale, method="L-BFGS-B",
            bounds=list(zip(problem.lower / scale, problem.upper / scale, strict=True)),
            options={"maxiter": 5000, "maxfun": 200000}).x * scale)  # fmt: skip
    run("ours, with the default multi-threaded BLAS", ours)

    ours = timings["ours"]["seconds"]
    out = {
        "tests": len(loops),
        "points": int(problem.data.force.size),
        "starts": args.starts,
        "end_to_end_seconds": end_to_end,
        "mean_nrmse": result.mean_nrmse,
        "max_nrmse": result.max_nrmse,
        "fit": timings,
        "ratios": {k: v["seconds"] / ours for k, v in timings.items() if k != "ours"},
    }
    if args.json:
        print(json.dumps(out))
        return
    print(f"campaign: {out['tests']} tests, one steady cycle each, {out['points']} points, "
          f"{args.starts} starts")  # fmt: skip
    print(f"end to end (read, pre-process, fit, metrics): {end_to_end:.2f} s; "
          f"NRMSE mean {100 * result.mean_nrmse:.2f} %, max {100 * result.max_nrmse:.2f} %")  # fmt: skip
    print(f"{'fit':45} {'seconds':>9} {'RMS NRMSE':>10} {'time / ours':>12}")
    for label, v in timings.items():
        print(f"{label:45} {v['seconds']:9.3f} {100 * v['rms_nrmse']:9.3f}% "
              f"{v['seconds'] / ours:11.1f}x")  # fmt: skip


if __name__ == "__main__":
    main()
