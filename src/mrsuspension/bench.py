"""Engine benchmarks (``mrsus bench``): figures as ratios against baselines run in the same process.

Model of every timed run: the nominal quarter car with the dissertation's hysteretic
damper (Table 2.2 low set, v_h of (2.13), the 1 s ``cycle-rms`` estimator clamped to
[1e-3, 0.75] m/s: the vehicle defaults) under skyhook hi-lo
policy I (SCM, k_c = 3, n = 2, p_c = 0, xi_c = 10), road ``0.025 sin(2 pi 1.5 t)``.

Baselines are written here in plain Python, independent of the package's kernels:

* ``scipy``: :func:`scipy.integrate.solve_ivp` (RK45, rtol 1e-6, atol 1e-9) on a right-hand
  side that evaluates the controller continuously, with ``v_m = sqrt(2 mean(v_d^2))`` over
  the right-hand-side calls of the last 1 s and ``sgn(a_d)`` from the previous call (what
  a researcher would write); ``LSODA`` likewise;
* ``python_rk4``: the engine's own algorithm (fixed-step RK4, zero-order hold of the
  controller, previous-step ``a_d``) in plain Python; it must agree with the engine to
  round-off, which the benchmark checks.

The sweep (60 frequencies x 4 controllers) runs as :func:`~mrsuspension.engine.run_many`
runs it (runs of one model in lanes, measures reduced in the kernels), against the
run-by-run baseline (each run recorded, then post-processed: ``lanes=False`` with
:func:`post_processed`), in alternation; both must give the same measures
(``sweep_measures_max_relative_difference``).

Times are the best of three interleaved rounds (each: the engine four times, then plain
Python, scipy RK45 and LSODA once): on a virtual machine the host takes the CPU now and
then and the speed drifts, which only ever adds time, and interleaving keeps the drift
out of the ratios.
"""

from __future__ import annotations

import math
import os
import time
from collections import deque
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["max_relative_difference", "post_processed", "run_benchmarks"]

F, A = 1.5, 0.025
W = 2.0 * math.pi * F


class _Plain:
    """Quarter car + Wang model + policy I, in plain Python (math module)."""

    def __init__(self) -> None:
        from mrsuspension import parameters

        p = dict(parameters.get("wang-symmetric-low").items())
        self.p = p
        self.sa2 = 1.0 / (1.0 + math.exp(-p["a2"] * p["I0"]))
        self.sa3 = 1.0 / (1.0 + math.exp(-p["a3"] * p["I1"]))
        self.ms, self.mu, self.ks, self.kt, self.ct = 563.0, 90.0, 57_000.0, 285_000.0, 100.0
        self.g = 9.81
        self.dxu = (self.ms + self.mu) * self.g / self.kt

    def force(self, v: float, sgn_a: float, i: float, vm: float) -> float:
        p = self.p
        ci = 1 + p["k2"] * (1 / (1 + math.exp(-p["a2"] * (i + p["I0"]))) - self.sa2)
        ft = p["F0"] * (1 + math.exp(p["a1"] * vm))
        alpha = p["a0"] / (1 + p["k0"] * vm)
        kv = p["k1"] * math.exp(-p["a4"] * vm)
        vh = sgn_a * p["k4"] * vm  # (2.13), the vehicle default
        return ci * ft * math.tanh(0.5 * alpha * (v + vh)) * (1 + kv * abs(v))

    @staticmethod
    def current(vs: float, vd: float) -> float:
        iz = 3.0 * vs * vs
        zc = vs * vd
        s = 0.0 if zc >= 0 else 1.0
        mc = 0.5 + (2 / math.pi) * (s - 0.5) * abs(math.atan(10.0 * zc))
        return min(max(mc * iz, 0.0), 0.5)

    def rates(self, y: list[float], t: float, i: float, vm: float, sgn_a: float) -> list[float]:
        zs, vs, zu, vu = y
        zr, zrd = A * math.sin(W * t), A * W * math.cos(W * t)
        xd, vd = zu - zs, vu - vs
        fd = self.force(vd, sgn_a, i, vm)
        delta = zr - zu + self.dxu
        ft = max(0.0, self.kt * delta + self.ct * (zrd - vu)) if delta > 0 else 0.0
        return [
            vs,
            (self.ks * xd + fd) / self.ms,
            vu,
            (ft - (self.ms + self.mu) * self.g - self.ks * xd - fd) / self.mu,
        ]


#: clamp of the estimate [m/s]: 1e-3 and the set's identified 0.75
V_MIN, V_MAX = 1e-3, 0.75


class _CycleRms:
    """sqrt(2 mean(v^2)) over the last n samples, clamped (re-summed at each wrap)."""

    def __init__(self, n: int) -> None:
        self.n, self.ring, self.head, self.count, self.sum = n, [0.0] * n, 0, 0, 0.0

    def update(self, v: float) -> float:
        w = v * v
        total = self.sum + w
        if self.count >= self.n:
            total -= self.ring[self.head]
        else:
            self.count += 1
        self.ring[self.head] = w
        self.head += 1
        if self.head == self.n:
            self.head = 0
            total = 0.0
            for u in self.ring:
                total += u
        self.sum = total
        return min(max(math.sqrt(2.0 * max(total, 0.0) / self.count), V_MIN), V_MAX)


def python_rk4(duration: float, dt: float = 1e-4) -> np.ndarray:
    """The engine's algorithm in plain Python; returns z_s at every step."""
    m = _Plain()
    win = _CycleRms(round(1.0 / dt))
    y = [0.0, 0.0, 0.0, 0.0]
    r0 = m.rates(y, 0.0, 0.0, 1e-3, 0.0)
    ad = r0[3] - r0[1]
    win.update(0.0)  # the engine's start() feeds the first sample once before stepping
    n = round(duration / dt)
    out = np.empty(n)
    for k in range(n):
        t = k * dt
        vs, vd = y[1], y[3] - y[1]
        vm = win.update(vd)
        sgn = 1.0 if ad > 0 else (-1.0 if ad < 0 else 0.0)
        i = m.current(vs, vd)
        k1 = m.rates(y, t, i, vm, sgn)
        k2 = m.rates([y[j] + 0.5 * dt * k1[j] for j in range(4)], t + 0.5 * dt, i, vm, sgn)
        k3 = m.rates([y[j] + 0.5 * dt * k2[j] for j in range(4)], t + 0.5 * dt, i, vm, sgn)
        k4 = m.rates([y[j] + dt * k3[j] for j in range(4)], t + dt, i, vm, sgn)
        y = [y[j] + dt / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]) for j in range(4)]
        r = m.rates(y, t + dt, i, vm, sgn)
        ad = r[3] - r[1]
        out[k] = y[0]
    return out


def scipy_baseline(duration: float, method: str = "RK45") -> tuple[np.ndarray, np.ndarray, int]:
    """solve_ivp on a continuous-time right-hand side; returns (t, z_s, evaluations)."""
    from scipy.integrate import solve_ivp

    m = _Plain()
    hist: deque[float] = deque()
    last = {"ad": 0.0, "sum": 0.0, "tick": -1}

    def rhs(t: float, y: np.ndarray) -> list[float]:
        vs, vd = y[1], y[3] - y[1]
        # mean of v_d^2 over the last 1 s on a 0.1 ms clock: each new tick of the clock
        # takes the latest value (calls that step back in time add nothing)
        tick = int(t / 1e-4)
        while last["tick"] < tick or not hist:
            last["tick"] += 1
            hist.append(vd * vd)
            last["sum"] += vd * vd
            if len(hist) > 10_000:
                last["sum"] -= hist.popleft()
        vm = min(max(math.sqrt(2.0 * max(last["sum"], 0.0) / len(hist)), V_MIN), V_MAX)
        ad = last["ad"]
        sgn = 1.0 if ad > 0 else (-1.0 if ad < 0 else 0.0)
        r = m.rates(list(y), t, m.current(vs, vd), vm, sgn)
        last["ad"] = r[3] - r[1]
        return r

    t_eval = np.arange(0.0, duration, 1e-3)
    sol = solve_ivp(
        rhs, (0.0, duration), [0.0] * 4, method=method, rtol=1e-6, atol=1e-9, t_eval=t_eval
    )
    return sol.t, sol.y[0], int(sol.nfev)


#: interleaved timing rounds, and engine runs per round
_ROUNDS = 3
_ENGINE_REPEATS = 4


def _best(fn: Callable[[], Any], repeat: int) -> float:
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _load_average() -> float | None:
    try:
        return os.getloadavg()[0]
    except OSError:  # not available on this platform
        return None


#: the fresh compile's run: the benchmark's model (see the module docstring), 10 steps
_COMPILE_SCRIPT = """
import time
from mrsuspension.control import HiLo
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic
sim = Simulation(Harmonic({f!r}, {a!r}), controller=HiLo(1, mode="SCM"))
t0 = time.perf_counter()
sim.run(1e-3)
print(time.perf_counter() - t0)
"""


#: the fresh compile of the sweep's path: the lane kernel reducing to measures (10 s runs)
_COMPILE_LANES_SCRIPT = """
import time
from mrsuspension.control import HiLo
from mrsuspension.engine import Simulation
from mrsuspension.engine.lanes import run_lanes
from mrsuspension.excitation import Harmonic
sim = Simulation(Harmonic(2.0, {a!r}), controller=HiLo(1, mode="SCM"))
t0 = time.perf_counter()
run_lanes([sim, sim], duration=10.0, measures=True)
print(time.perf_counter() - t0)
"""


def _fresh_compile(script: str = _COMPILE_SCRIPT) -> float:
    """Seconds to compile the engine's run loop, and every kernel it calls, from nothing.

    Timed in a fresh process whose numba cache (``NUMBA_CACHE_DIR``) is an empty folder:
    the kernels are compiled once each (:data:`~mrsuspension._numba_cache.INLINED`), so
    in this process they are already compiled and only a new process shows the cost.
    ``script`` prints the seconds its timed call took (default: a 10-step run; the lane
    kernel's with :data:`_COMPILE_LANES_SCRIPT`).
    """
    import subprocess
    import sys
    import tempfile

    with tempfile.TemporaryDirectory(prefix="mrsus-compile-") as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        done = subprocess.run(
            [sys.executable, "-c", script.format(f=F, a=A)],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
    return float(done.stdout.strip().splitlines()[-1])


def post_processed(result: Any) -> dict[str, Any]:
    """``result.measures()`` from the record: the run-by-run baseline's reducer.

    A function of its own, so that :func:`~mrsuspension.engine.run_many` does not
    recognise it as :func:`~mrsuspension.engine.measures_of` and reduce in the kernels.
    """
    out: dict[str, Any] = result.measures()
    return out


def max_relative_difference(rows: list[dict[str, Any]], reference: list[dict[str, Any]]) -> float:
    """Largest ``|a - b| / |b|`` over the numeric measures of two lists of measures.

    Examples
    --------
    >>> max_relative_difference([{"T_as": 1.0, "gamma": None}], [{"T_as": 2.0, "gamma": None}])
    0.5
    """
    worst = 0.0
    for a, b in zip(rows, reference, strict=True):
        for key, ref in b.items():
            value = a[key]
            if isinstance(ref, int | float) and isinstance(value, int | float) and ref != value:
                worst = max(worst, abs(value - ref) / abs(ref) if ref else math.inf)
    return worst


def run_benchmarks(
    *,
    quick: bool = False,
    workers: int | None = None,
    fresh_compile: bool | None = None,
    say: Callable[[str], None] = lambda _m: None,
) -> dict[str, Any]:
    """Time the engine and its baselines; see the module docstring for what is compared.

    ``quick`` simulates 1 s instead of 10 s and sweeps 6 frequencies instead of 60;
    ``fresh_compile`` (default: not quick) also times, in new processes with an empty
    numba cache, the first 10-step run: the engine's compilation (``compile_s``; None when
    skipped), and the first lane batch with in-kernel measures (``compile_lanes_s``).
    """
    from mrsuspension.control import HiLo, Passive, SlidingMode
    from mrsuspension.dampers import WangSymmetric
    from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
    from mrsuspension.engine import Simulation, measures_of, run_many
    from mrsuspension.engine.simulate import road_grid
    from mrsuspension.excitation import Harmonic, log_frequencies, two_stage_amplitude

    duration = 1.0 if quick else 10.0
    load_before = _load_average()
    sim = Simulation(Harmonic(F, A), controller=HiLo(1, mode="SCM"))
    say("first call (compiles, or loads numba's on-disk cache)")
    t0 = time.perf_counter()
    sim.run(0.01)
    first_call = time.perf_counter() - t0
    from mrsuspension.engine.lanes import run_lanes

    run_lanes([sim, sim], duration=0.01)  # the lane kernel too: timings exclude compiling
    compile_s = compile_lanes_s = None
    if fresh_compile if fresh_compile is not None else not quick:
        compile_s = _fresh_compile()
        compile_lanes_s = _fresh_compile(_COMPILE_LANES_SCRIPT)

    n_single = round(duration / 1e-4)
    # the road samples (z_r, z_r' every dt/2) are computed before the loop
    road_s = _best(lambda: road_grid(sim.excitation, 2 * n_single + 1, 5e-5), 3)
    say("checking the engine against the plain-Python RK4 and scipy")
    engine = sim.run(duration, output_rate=1e4)
    plain = python_rk4(duration)
    rk4_diff = float(np.max(np.abs(plain - engine.z_s[1:])))
    ts, zs, nfev = scipy_baseline(duration, "RK45")
    ref = np.interp(ts, engine.time, engine.z_s)
    scipy_diff = float(np.sqrt(np.mean((zs - ref) ** 2)) / np.sqrt(np.mean(ref**2)))

    # Each timing is the best of several, taken in interleaved rounds: on a virtual
    # machine the host takes the CPU now and then and the speed drifts, which would skew
    # ratios of figures timed one after the other.
    timed: dict[str, Callable[[], Any]] = {
        "engine": lambda: sim.run(duration, output_rate=1000.0),
        "python": lambda: python_rk4(duration),
        "scipy": lambda: scipy_baseline(duration, "RK45"),
        "lsoda": lambda: scipy_baseline(duration, "LSODA"),
    }
    best = dict.fromkeys(timed, math.inf)
    for r in range(_ROUNDS):
        say(f"timing round {r + 1}/{_ROUNDS}: engine ({duration:g} s at dt = 1e-4 s), plain "
            "Python RK4, scipy RK45 (rtol 1e-6, atol 1e-9), LSODA")  # fmt: skip
        for name, fn in timed.items():
            repeat = _ENGINE_REPEATS if name == "engine" else 1
            best[name] = min(best[name], _best(fn, repeat))
    single, python_s, scipy_s, lsoda_s = (best[k] for k in ("engine", "python", "scipy", "lsoda"))

    nf = 6 if quick else 60
    say(f"sweep: {nf} frequencies x 4 controllers on {workers or 'all'} cores")
    fs = log_frequencies(nf, 0.5, 15.0)
    controllers = [Passive(), HiLo(1, mode="SCM"), HiLo(1, mode="ACM"), SlidingMode()]
    sims = [
        Simulation(
            Harmonic(f, float(two_stage_amplitude(f, 0.025))),
            controller=c,
            damper=WangSymmetric(
                force_gain=2.5 if c.needs_inverse else 1.0, vh_variant=VEHICLE_VH_VARIANT
            ),
        )
        for c in controllers
        for f in fs
    ]
    # the sweep as run_many runs it (lanes, measures reduced in the kernels) against the
    # run-by-run baseline (each run recorded, then post-processed), in interleaved rounds
    swept: dict[str, list[float]] = {"sweep": [], "run_by_run": []}
    rows: list[Any] = []
    baseline: list[Any] = []
    for r in range(_ROUNDS):
        say(f"sweep round {r + 1}/{_ROUNDS}: {len(sims)} runs in lanes with in-kernel measures, "
            "then run by run with post-processed measures")  # fmt: skip
        t0 = time.perf_counter()
        rows = run_many(sims, reduce=measures_of, workers=workers)
        swept["sweep"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        baseline = run_many(sims, reduce=post_processed, workers=workers, lanes=False)
        swept["run_by_run"].append(time.perf_counter() - t0)
    sweep_s, run_by_run_s = min(swept["sweep"]), min(swept["run_by_run"])
    difference = max_relative_difference(rows, baseline)
    steps = sum(round(s.excitation.duration / 1e-4) for s in sims)
    cores = min(len(sims), workers or os.cpu_count() or 1)
    return {
        "duration_s": duration,
        "single_run_s": single,
        "single_run_ns_per_step": single / n_single * 1e9,
        "single_run_road_sampling_s": road_s,
        "scipy_baseline_s": scipy_s,
        "speedup_vs_scipy": scipy_s / single,
        "scipy_rhs_evaluations": nfev,
        "scipy_relative_rms_difference": scipy_diff,
        "lsoda_s": lsoda_s,
        "speedup_vs_lsoda": lsoda_s / single,
        "python_rk4_s": python_s,
        "speedup_vs_python_rk4": python_s / single,
        "python_rk4_max_difference_m": rk4_diff,
        "sweep_runs": len(rows),
        "sweep_steps": steps,
        "sweep_s": sweep_s,
        "sweep_s_median": float(np.median(swept["sweep"])),
        # core time per run and step: comparable with single_run_ns_per_step
        "sweep_ns_per_run_step": sweep_s * cores / steps * 1e9,
        "sweep_ns_per_run_step_median": float(np.median(swept["sweep"])) * cores / steps * 1e9,
        "sweep_workers": cores,
        # the same sweep run by run (lanes=False) with post-processed measures: the baseline
        "sweep_run_by_run_s": run_by_run_s,
        "sweep_run_by_run_s_median": float(np.median(swept["run_by_run"])),
        "sweep_speedup": run_by_run_s / sweep_s,
        # in-kernel against post-processed measures, over every run and measure
        "sweep_measures_max_relative_difference": difference,
        # earlier names of the two figures (lanes were opt-in, run by run the default)
        "sweep_lanes_s": sweep_s,
        "lanes_speedup": run_by_run_s / sweep_s,
        "sweep_ns_per_step_per_core": sweep_s * cores / steps * 1e9,
        # the sweep's time if each core ran its share at the single run's cost per step
        "sweep_at_single_run_speed_s": steps * single / n_single / cores,
        "compile_s": compile_s,
        # the same from an empty cache for the sweep's path (lane kernel, in-kernel measures)
        "compile_lanes_s": compile_lanes_s,
        "first_call_s": first_call,
        # 1-minute load average before and after: other processes share the cores
        "load_average": [load_before, _load_average()],
    }
