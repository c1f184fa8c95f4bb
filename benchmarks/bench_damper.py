"""Damper-force benchmark: evaluations per second, as ratios against plain numpy.

Three implementations of the dissertation's symmetric hysteretic model (2.15) with v_h of
(2.12) evaluate the same random inputs in the same process:

* ``numpy baseline``: the equations written out with numpy array operations, as a
  researcher would (defined below, independent of the package);
* ``vectorised``: the public array API, ``WangSymmetric.force(x, v, a, i, peak_velocity=vm)``
  (input validation, broadcasting, factor-wise numpy expressions updated in place);
* ``compiled``: the scalar kernels called point by point from a compiled loop, as the
  simulation engine and the HiL loop use them: ``wang_latch_motion`` (v_m, sgn(a_d)) then
  ``damper_force``, each point with its own v_m and current;
* ``compiled, engine pattern``: one latch per time step and four evaluations (the RK4
  stages) at the held current, the engine's actual use (evaluations per second).

The three results are compared before timing (they must agree to 1e-9 relative).

Run: ``python benchmarks/bench_damper.py [--points N] [--repeat R] [--json]``.
"""

from __future__ import annotations

import argparse
import json
import time
from collections.abc import Callable

import numpy as np
from numba import njit

from mrsuspension.dampers import WangSymmetric
from mrsuspension.dampers import kernels as K


def numpy_baseline(p: dict[str, float], v, a, i, vm):  # type: ignore[no-untyped-def]
    """Eq. (2.15) written out with numpy, independent of the package's kernels."""
    ci = (
        1
        + p["k2"] / (1 + np.exp(-p["a2"] * (i + p["I0"])))
        - p["k2"] / (1 + np.exp(-p["a2"] * p["I0"]))
    )
    h = (
        1
        + p["k3"] / (1 + np.exp(-p["a3"] * (i + p["I1"])))
        - p["k3"] / (1 + np.exp(-p["a3"] * p["I1"]))
    )
    vh = np.sign(a) * p["k4"] * vm * h
    ft = p["F0"] * (1 + np.exp(p["a1"] * vm))
    alpha = p["a0"] / (1 + p["k0"] * vm)
    kv = p["k1"] * np.exp(-p["a4"] * vm)
    u = alpha * (v + vh)
    return ci * ft * (1 - np.exp(-u)) / (1 + np.exp(-u)) * (1 + kv * np.abs(v))


# no cache=True here: numba's on-disk cache does not notice edits to the kernels it inlines
@njit
def compiled_loop(kind, params, v, a, i, vm, out):  # type: ignore[no-untyped-def]
    """Latch v_m and sgn(a_d), then call the scalar force kernel, point by point."""
    s = np.zeros(K.STATE_SIZE)
    for k in range(v.shape[0]):
        K.wang_latch_motion(params, s, vm[k], K.sign(a[k]))
        out[k] = K.damper_force(kind, params, s, 0.0, v[k], i[k])


@njit
def engine_pattern(kind, params, v, a, i, vm, out):  # type: ignore[no-untyped-def]
    """One latch per step, four stage evaluations at the held current (RK4 in the engine)."""
    s = np.zeros(K.STATE_SIZE)
    for k in range(0, v.shape[0] - 3, 4):
        K.wang_latch_motion(params, s, vm[k], K.sign(a[k]))
        for j in range(4):
            out[k + j] = K.damper_force(kind, params, s, 0.0, v[k + j], i[k])


def best_time(fn: Callable[[], object], repeat: int) -> float:
    """Fastest of ``repeat`` wall-clock runs [s]."""
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def run(points: int, repeat: int) -> dict[str, float]:
    """Time the three paths on ``points`` random inputs; return the figures."""
    rng = np.random.default_rng(0)
    v = rng.uniform(-0.8, 0.8, points)
    a = rng.uniform(-30.0, 30.0, points)
    i = rng.uniform(0.0, 0.5, points)
    vm = np.maximum(np.abs(v), rng.uniform(0.05, 0.8, points))
    x = np.zeros(points)
    model = WangSymmetric(vh_variant="2.12")  # the baseline writes out (2.12)'s H(i)
    p = dict(model.values)
    out = np.empty(points)

    t0 = time.perf_counter()
    f_vec = model.force(x[:10], v[:10], a[:10], i[:10], peak_velocity=vm[:10])
    compiled_loop(model.kind, model.kernel(1e-4).params, v[:10], a[:10], i[:10], vm[:10], out[:10])
    engine_pattern(model.kind, model.kernel(1e-4).params, v[:8], a[:8], i[:8], vm[:8], out[:8])
    first_call = time.perf_counter() - t0

    f_ref = numpy_baseline(p, v, a, i, vm)
    f_vec = model.force(x, v, a, i, peak_velocity=vm)
    compiled_loop(model.kind, model.kernel(1e-4).params, v, a, i, vm, out)
    scale = np.max(np.abs(f_ref))
    err_vec = float(np.max(np.abs(f_vec - f_ref)) / scale)
    err_cmp = float(np.max(np.abs(out - f_ref)) / scale)
    if max(err_vec, err_cmp) > 1e-9:
        raise SystemExit(f"implementations disagree: {err_vec:.2e}, {err_cmp:.2e}")

    params = model.kernel(1e-4).params
    t_np = best_time(lambda: numpy_baseline(p, v, a, i, vm), repeat)
    t_vec = best_time(lambda: model.force(x, v, a, i, peak_velocity=vm), repeat)
    t_cmp = best_time(lambda: compiled_loop(model.kind, params, v, a, i, vm, out), repeat)
    t_eng = best_time(lambda: engine_pattern(model.kind, params, v, a, i, vm, out), repeat)
    return {
        "points": points,
        "numpy_evals_per_s": points / t_np,
        "vectorised_evals_per_s": points / t_vec,
        "compiled_evals_per_s": points / t_cmp,
        "vectorised_vs_numpy": t_np / t_vec,
        "compiled_vs_numpy": t_np / t_cmp,
        "engine_pattern_evals_per_s": points / t_eng,
        "engine_pattern_vs_numpy": t_np / t_eng,
        "max_relative_difference": max(err_vec, err_cmp),
        "first_call_s": first_call,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000, help="inputs per evaluation")
    ap.add_argument("--repeat", type=int, default=5, help="runs per path (best is kept)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()
    res = run(args.points, args.repeat)
    if args.json:
        print(json.dumps(res))
        return
    print(f"damper force, symmetric hysteretic model (2.15), {res['points']:,} points")
    print(f"  numpy baseline : {res['numpy_evals_per_s']:14,.0f} evals/s   (1.00x)")
    print(
        f"  vectorised API : {res['vectorised_evals_per_s']:14,.0f} evals/s   "
        f"({res['vectorised_vs_numpy']:.2f}x numpy)"
    )
    print(
        f"  compiled kernel: {res['compiled_evals_per_s']:14,.0f} evals/s   "
        f"({res['compiled_vs_numpy']:.2f}x numpy)"
    )
    print(
        f"  engine pattern : {res['engine_pattern_evals_per_s']:14,.0f} evals/s   "
        f"({res['engine_pattern_vs_numpy']:.2f}x numpy; 1 latch + 4 RK4 stages per step)"
    )
    print(f"  agreement      : {res['max_relative_difference']:.1e} (relative to peak force)")
    print(f"  first calls (compilation): {res['first_call_s']:.2f} s")


if __name__ == "__main__":
    main()
