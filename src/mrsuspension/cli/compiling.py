"""The engine's compiled kernels: the notice while they compile, and warming them early.

numba compiles the engine on its first call (5-10 s; 17-40 s before the kernels were
inlined by LLVM, see :data:`~mrsuspension._numba_cache.INLINED`) and keeps the result in
``__pycache__`` beside the sources; without a word the first ``mrsus simulate``,
``sweep``, ``study``, ``optimize``, ``reproduce`` or ``hil`` command looks hung. The
commands call :func:`notify_if_compiling` before their first run; the engine itself says
the same once per process before a cold entry point runs (the quarter car's and the
vehicles' loops, the lanes, the reduced loop:
:func:`~mrsuspension._numba_cache.announce_compile`), so a first run from Python says it
too. :func:`warm_kernels`
(``mrsus cache warm``, run by ``make`` after installing and before the tests) compiles
every entry point ahead of time, so that the tests' processes share the compiled kernels.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import Any, TextIO

from mrsuspension._numba_cache import COMPILE_NOTICE, cache_cold, quiet_compiles

__all__ = [
    "COMPILE_NOTICE",
    "WARM_SECONDS",
    "WARM_STEPS",
    "engine_cache_cold",
    "notify_if_compiling",
    "warm_kernels",
]


def engine_cache_cold(*kernels: str) -> bool:
    """Whether any of the engine's entry points ``kernels`` is missing from numba's cache.

    ``kernels`` are names in :mod:`mrsuspension.engine.kernel` (default: ``run``, the
    offline loop; ``step`` is the tick-by-tick step of HiL). Imports the module (which
    drops a stale cache, see :mod:`mrsuspension._numba_cache`).

    Examples
    --------
    >>> engine_cache_cold() in (True, False)
    True
    """
    import mrsuspension.engine.kernel as kernel

    return cache_cold(kernel.__file__, *(kernels or ("run",)))


def notify_if_compiling(stream: TextIO | None = None, *kernels: str) -> bool:
    """Say :data:`COMPILE_NOTICE` on stderr when an entry point is cold; say whether.

    ``kernels`` as in :func:`engine_cache_cold` (default: ``run``). A command asks before
    its first run; the engine then does not repeat the notice in this process
    (:func:`~mrsuspension._numba_cache.announce_compile`).

    Examples
    --------
    >>> import io
    >>> log = io.StringIO()
    >>> notify_if_compiling(log) == bool(log.getvalue())
    True
    """
    if not engine_cache_cold(*kernels):
        return False
    out = sys.stderr if stream is None else stream
    out.write(COMPILE_NOTICE + "\n")
    out.flush()
    quiet_compiles()  # said: the engine's own notice stays quiet
    return True


def _warm_engine() -> None:
    import numpy as np

    from mrsuspension.engine import Simulation
    from mrsuspension.excitation import Harmonic, RoadProfile, RoundedPulse

    # run() is one compiled loop for every damper, controller and estimator (codes)
    Simulation(Harmonic(2.0, 0.01)).run(0.01)
    Simulation(RoundedPulse(0.01, 1.0)).run(0.01)
    RoadProfile(np.arange(4.0), np.zeros(4)).sample_grid(3, 1e-4)


def _warm_reduced() -> None:
    from mrsuspension.engine import Simulation
    from mrsuspension.engine.reduced import run_measures
    from mrsuspension.excitation import Harmonic

    # the shortest harmonic run with a steady-state window (5 s settling, 5 s of cycles)
    run_measures(Simulation(Harmonic(2.0, 0.01)), duration=10.0)


def _warm_lanes() -> None:
    from mrsuspension.engine import Simulation
    from mrsuspension.engine.lanes import run_lanes
    from mrsuspension.excitation import Harmonic

    sim = Simulation(Harmonic(2.0, 0.01))
    run_lanes([sim, sim], duration=0.01)
    run_lanes([sim, sim], duration=10.0, measures=True)  # the same kernel, reducing


def _warm_stepper() -> None:
    from mrsuspension.engine import Simulation
    from mrsuspension.excitation import Harmonic
    from mrsuspension.hil.rig import SimulatedRig

    Simulation(Harmonic(1.0, 0.01)).stepper(1e-4).step(0.0, 0.0628)
    rig = SimulatedRig()
    rig.reset(1e-3)
    rig.command(0.0, 0.1)
    rig.read()
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import WheelRoads
    from mrsuspension.hil.vehicle import CornerPlant
    from mrsuspension.vehicle import HalfCar

    car = HalfCar()  # a vehicle's tick with one corner on the rig
    roads = WheelRoads.from_excitation(Harmonic(1.0, 0.01), car, 54.0)
    CornerPlant(VehicleSimulation(car, roads), "front", 1e-4, 2, 1).tick(0, 0.0)


def _warm_dampers() -> None:
    import numpy as np

    from mrsuspension.dampers import WangSymmetric
    from mrsuspension.shaping import drive_current

    damper = WangSymmetric()
    damper.force(0.0, 0.1, current=0.2)
    t = np.linspace(0.0, 0.01, 11)
    damper.response(t, 0.01 * np.sin(t))
    damper.inverse_current(100.0, 0.1)
    drive_current(0.1, velocity=0.1, peak_velocity=0.2, switching=-1.0)


def _warm_identify() -> None:
    from mrsuspension.identify.timedomain import synthetic_record

    synthetic_record(duration=0.1, sample_rate=1000.0)


def _warm_vehicles() -> None:
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import Harmonic, WheelRoads
    from mrsuspension.vehicle import FullCar

    car = FullCar()
    road = WheelRoads.from_excitation(Harmonic(2.0, 0.01), car, speed_kmh=50.0)
    VehicleSimulation(car, road).run(0.01, dt=2e-4)


def _warm_vehicle_stepper() -> None:
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import Harmonic, WheelRoads
    from mrsuspension.vehicle import HalfCar

    car = HalfCar()  # one call of the compiled step from Python (a real-time loop's)
    road = WheelRoads.in_phase(Harmonic(2.0, 0.01), car)
    VehicleSimulation(car, road).stepper(1e-4).step([0.0, 0.0], [0.0, 0.0])


#: what :func:`warm_kernels` compiles: (what, a call that compiles it, or loads it)
WARM_STEPS: tuple[tuple[str, Callable[[], None]], ...] = (
    ("engine run loop (simulate, sweep, study, report)", _warm_engine),
    ("engine run loop reducing to measures (runs of sweeps outside lanes)", _warm_reduced),
    ("lane kernel, recording or reducing to measures (sweeps, studies)", _warm_lanes),
    ("tick-by-tick step, vehicle tick and simulated rig (hil)", _warm_stepper),
    ("damper force, response and inverse (damper)", _warm_dampers),
    ("time-domain record (identify)", _warm_identify),
    ("half- and full-car run loop (vehicle scenarios)", _warm_vehicles),
    ("half- and full-car tick-by-tick step (vehicle steppers)", _warm_vehicle_stepper),
)


#: typical compile time of each of :data:`WARM_STEPS` on one core [s] (a fresh clone on the
#: CI machine): a pool starts the longest first, so two processes finish together
WARM_SECONDS: tuple[float, ...] = (15.0, 0.1, 13.0, 20.0, 1.3, 1.1, 20.0, 14.0)


def _warm_step(k: int) -> float:
    """Run :data:`WARM_STEPS` ``[k]``; its time [s] (a pool's task)."""
    quiet_compiles()
    t0 = time.perf_counter()
    WARM_STEPS[k][1]()
    return time.perf_counter() - t0


def warm_kernels(
    say: Callable[[str], None] = lambda _m: None, workers: int | None = 1
) -> list[dict[str, Any]]:
    """Compile every entry point into numba's on-disk cache (loading it when warm).

    Each step calls public functions on a tiny input, so the signatures compiled are the
    ones real runs use; ``say`` gets a line before and after each (on several processes,
    one when each is done). Returns one row per step, in :data:`WARM_STEPS` order:
    ``what`` and ``seconds``.

    Parameters
    ----------
    say : callable, optional
        Receives the progress lines.
    workers : int, optional
        Processes compiling side by side (None: one per core; 1: this process). The
        steps compile separate kernels, so two processes take about half the time.

    Examples
    --------
    >>> rows = warm_kernels()
    >>> [r["what"].split(" (")[0] for r in rows][:3]
    ['engine run loop', 'engine run loop reducing to measures', 'lane kernel, recording or reducing to measures']
    """
    from mrsuspension._pool import process_pool, worker_count

    quiet_compiles()  # each step is reported here
    n = len(WARM_STEPS)
    seconds = [0.0] * n
    with process_pool(workers, n) as pool:
        if pool is None:
            for k, (what, _call) in enumerate(WARM_STEPS):
                say(f"[{k + 1}/{n}] {what}...")
                seconds[k] = _warm_step(k)
                say(f"[{k + 1}/{n}] {what}: {seconds[k]:.1f} s")
        else:
            from concurrent.futures import as_completed

            say(f"compiling {n} entry points on {worker_count(workers, n)} processes...")
            order = sorted(range(n), key=lambda k: -WARM_SECONDS[k])
            futures = {pool.submit(_warm_step, k): k for k in order}
            for future in as_completed(futures):
                k = futures[future]
                seconds[k] = future.result()
                say(f"[{k + 1}/{n}] {WARM_STEPS[k][0]}: {seconds[k]:.1f} s")
    return [{"what": what, "seconds": s} for (what, _), s in zip(WARM_STEPS, seconds, strict=True)]
