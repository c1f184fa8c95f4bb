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

A second part times the issue-15 field campaign (:func:`field_campaign`: 30 tests,
0.1-5 Hz, 2-25 mm, 200 Hz / 1 kHz, offsets, 2 % noise, a damper far from the start):
``identify()`` end to end with its default 8 starts (median of 3 runs, ``--field-repeats``), beside the
baseline of the issue: a plain ``least_squares`` (finite differences) on one
mid-record cycle of raw samples per test, ``v_m`` = that cycle's peak ``|v|``, from the
same scaled start.

Run: ``python benchmarks/bench_identify.py [--tests N] [--starts S] [--field-repeats R]
[--no-field] [--json]``.
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


def one_cycle_baseline(manifest: Path, problem: FitProblem) -> dict[str, float]:
    """Plain least_squares on one mid-record cycle per test (issue 15's comparison)."""
    from mrsuspension.identify import read_manifest, read_test
    from mrsuspension.identify.preprocess import detect_frequency

    cycles = []
    for e in read_manifest(manifest).entries:
        r = read_test(e.file, e.columns, e.units)
        assert r.displacement is not None
        assert r.velocity is not None
        period = 1.0 / detect_frequency(r.time, r.displacement, hint=e.frequency).frequency
        mid = 0.5 * (r.time[0] + r.time[-1])
        sel = (r.time >= mid - period / 2) & (r.time < mid + period / 2)
        v, f = r.velocity[sel], r.force[sel]
        cycles.append((r.displacement[sel], v, np.gradient(v, r.time[sel]), f, e.current,
                       float(np.max(np.abs(v)))))  # fmt: skip

    def resid(theta: np.ndarray) -> np.ndarray:
        d = problem.spec.build(problem.values(theta), problem.max_current)
        out = [(d.force(x, v, a, i, peak_velocity=vm) - f) / (np.ptp(f) * math.sqrt(f.size))
               for x, v, a, f, i, vm in cycles]  # fmt: skip
        r = np.concatenate(out)
        return np.where(np.isfinite(r), r, 1e3)

    t0 = time.perf_counter()
    with blas_threads(1):
        sol = least_squares(resid, problem.scaled(problem.x_start),
                            bounds=(problem.lower, problem.upper), x_scale="jac")  # fmt: skip
    seconds = time.perf_counter() - t0
    r = resid(sol.x)
    per, k = [], 0
    for c in cycles:
        per.append(math.sqrt(float(np.sum(r[k : k + c[3].size] ** 2))))
        k += c[3].size
    return {"seconds": seconds, "nfev": float(sol.nfev), "mean_nrmse": float(np.mean(per)),
            "max_nrmse": float(np.max(per))}  # fmt: skip


def field(repeats: int = 3) -> dict[str, object]:
    """The issue-15 campaign: identify() median of ``repeats`` runs and the baseline."""
    from mrsuspension.identify.synthetic import field_campaign

    with tempfile.TemporaryDirectory() as tmp:
        manifest = field_campaign(Path(tmp))
        times, result = [], None
        for _ in range(repeats):
            t0 = time.perf_counter()
            result = identify(manifest)
            times.append(time.perf_counter() - t0)
        assert result is not None
        fit = result.fits[0].result
        assert fit is not None
        problem = FitProblem([t.loop for t in result.tests if t.loop is not None])
        base = one_cycle_baseline(manifest, problem)
    return {
        "seconds_median": float(np.median(times)),
        "seconds": times,
        "mean_nrmse": result.mean_nrmse,
        "max_nrmse": result.max_nrmse,
        "evidence": fit.evidence,
        "baseline_one_cycle": base,
        "warnings": sum(t.status != "ok" for t in result.tests),
    }


def rms(problem: FitProblem, x: np.ndarray) -> float:
    r = problem.residuals(x)
    return math.sqrt(float(r @ r) / len(problem.data.loops))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tests", type=int, default=30, help="tests in the campaign (<= 30)")
    ap.add_argument("--starts", type=int, default=8, help="multi-start count")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--no-field", action="store_true", help="skip the issue-15 field campaign")
    ap.add_argument("--field-repeats", type=int, default=3, help="runs of the field campaign")
    args = ap.parse_args()
    if args.field_repeats < 1:
        ap.error(f"--field-repeats must be 1 or more, got {args.field_repeats}")
    field_out = None if args.no_field else field(args.field_repeats)

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
        "field": field_out,
    }
    if args.json:
        print(json.dumps(out))
        return
    if field_out is not None:
        ev, base = field_out["evidence"], field_out["baseline_one_cycle"]
        print(f"field campaign (issue 15, 30 tests): identify() median of "
              f"{len(field_out['seconds'])} "
              f"{field_out['seconds_median']:.2f} s ({', '.join(f'{t:.2f}' for t in field_out['seconds'])});"
              f" NRMSE mean {100 * field_out['mean_nrmse']:.2f} %, max "
              f"{100 * field_out['max_nrmse']:.2f} %; {ev['starts_within_1pct']} of {ev['starts']} "
              f"starts within 1 % of the best cost; tests not ok: {field_out['warnings']}")  # fmt: skip
        print(f"  baseline least_squares on one raw cycle per test: {base['seconds']:.2f} s, "
              f"{base['nfev']:.0f} evaluations, NRMSE mean {100 * base['mean_nrmse']:.2f} %, "
              f"max {100 * base['max_nrmse']:.2f} %")  # fmt: skip
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
