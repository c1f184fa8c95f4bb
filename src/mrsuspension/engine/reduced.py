"""Measures reduced inside the kernels: runs that write no time history.

A sweep, a study or the optimiser wants each run's measures (model reference, section 9), not its
record. Here the kernels accumulate, at each output sample and in O(1) memory per run,
what the measures need (:func:`~mrsuspension.engine.kernel.accumulate`, in the drive
loops' output step): sums of squares over the steady-state window (its first sample
chosen before the run by :func:`~mrsuspension.measures.steady_window`, the rule the
post-processing uses), shifted sums for variances, peaks, the time at the peak-velocity
clamp. The road's own quantities (its acceleration, a pure function of time) are
computed here from the excitation, as :meth:`~mrsuspension.engine.Simulation.result_from_record`
computes them. A road-profile run also keeps its body acceleration (one signal): the
ISO 2631 weighting filters it (:func:`~mrsuspension.measures.weighted_rms`).

The final formulas are shared with the post-processing
(:func:`~mrsuspension.measures.steady.harmonic_from_moments`,
:func:`~mrsuspension.measures.shock.shock_from_peaks`,
:func:`~mrsuspension.engine.result.road_measures`), so there is one definition of each
measure; the results equal ``Simulation.run(...).measures()`` to round-off (sums in a
different order: relative differences measured below 1e-12).

:func:`run_measures` is the scalar path (any damper and controller: the quarter car's
one drive loop, :func:`mrsuspension.engine.kernel.run`, reducing);
:func:`mrsuspension.engine.lanes.run_lanes` with ``measures=True`` the lane path; the
half and full cars reduce every corner with the same accumulators
(:func:`mrsuspension.engine.vehicle.measure_vehicles`). This module plans a reduction
(:func:`reduction_of`) and finishes it (:func:`finish`); the accumulators' layout and
:func:`~mrsuspension.engine.kernel.accumulate` live beside the step.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from mrsuspension._numba_cache import announce_compile
from mrsuspension.control.user import raise_failure
from mrsuspension.engine import kernel as EK
from mrsuspension.engine.arrays import KernelArrays
from mrsuspension.engine.kernel import N_ACC, accumulate
from mrsuspension.engine.result import (
    SimulationDiverged,
    SimulationResult,
    drop_unused_currents,
    measures_context,
    pulse_measures,
    road_measures,
)
from mrsuspension.engine.settings import RunPlan, RunSettings, run_settings
from mrsuspension.errors import ValidationError

if TYPE_CHECKING:
    from mrsuspension.measures import RoadPeak

__all__ = ["N_ACC", "Reduction", "accumulate", "new_accumulators", "reduction_of", "run_measures"]

_MAXIMA = (EK.A_FTMAX, EK.A_WFDMAX, EK.A_WFDNEG)


def new_accumulators(runs: int) -> np.ndarray:
    """Fresh accumulators for ``runs`` runs (maxima start at -inf).

    Examples
    --------
    >>> new_accumulators(2).shape
    (2, 27)
    """
    acc = np.zeros((runs, N_ACC))
    acc[:, list(_MAXIMA)] = -np.inf
    return acc


@dataclass(frozen=True)
class Reduction:
    """What a run's kernel needs to reduce it to its measures, and how to finish them.

    Built by :func:`reduction_of` before the run (an impossible steady window is
    reported then, as the post-processing would report it after the run).
    """

    #: measures kind of the excitation (``harmonic``, ``pulse`` or ``road``)
    kind: str
    #: the scenario's plain-data description (as a result carries it)
    scenario: dict[str, Any]
    #: output samples of the run (row 0 the initial state)
    rows: int
    #: sample interval of the output [s]
    interval: float
    #: first output sample of the steady window (``rows``: no window)
    window_start: int
    #: subtracted from F_T before summing (the static load: sums of small numbers)
    shift: float
    #: v_m at or above this counts as at the clamp (inf: no clamp)
    threshold: float
    #: whether the run keeps its body acceleration (road profiles' ISO 2631 measures)
    trace: bool

    def time(self) -> np.ndarray:
        """The output sample times, as the run's record would have them."""
        return np.arange(self.rows) * self.interval


class KernelRun(Protocol):
    """What the quarter car's kernels (one run, reduced, the lanes) need of a run.

    :class:`~mrsuspension.engine.Simulation` has it. An interface rather than an import,
    so that :mod:`~mrsuspension.engine.simulate` can use this module and the lanes
    without a cycle.
    """

    @property
    def excitation(self) -> Any: ...

    def describe(self) -> dict[str, Any]: ...

    def check_dt(self, dt: float) -> float: ...

    def record_values(self, plan: RunPlan) -> float: ...

    def road_samples(
        self, n: int, dt: float, *, start: int = 0
    ) -> tuple[np.ndarray, np.ndarray]: ...

    def kernel_arrays(self, dt: float, *, check_stability: bool = True) -> KernelArrays: ...

    def result_from_record(
        self, time: np.ndarray, record: np.ndarray, dt: float
    ) -> SimulationResult: ...

    def divergence(
        self, status: int, t: float, idx: int, value: float, dt: float
    ) -> SimulationDiverged: ...


class Described(Protocol):
    """What :func:`reduction_of` needs of a run: its plain-data description."""

    def describe(self) -> dict[str, Any]: ...


def reduction_of(simulation: Described, plan: RunPlan) -> Reduction:
    """The :class:`Reduction` of ``simulation`` run as ``plan`` says.

    Raises
    ------
    ValidationError
        An excitation without measures, or a harmonic record too short for the
        steady-state rule (as :meth:`SimulationResult.measures` would raise).

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> sim = Simulation(Harmonic(1.5, 0.025))
    >>> r = reduction_of(sim, RunSettings(duration=14.0).plan(sim))
    >>> r.kind, r.rows, r.window_start
    ('harmonic', 14001, 6668)
    """
    from mrsuspension.measures import steady_window

    scenario = simulation.describe()
    kind, exc, static_load = measures_context(scenario)
    rows, interval = plan.rows, plan.interval
    if kind == "harmonic":
        start = steady_window(plan.time(), float(exc["frequency"])).start
    elif kind in ("pulse", "road"):
        start = rows
    else:
        raise ValidationError(f"no measures defined for excitation kind {kind!r}")
    limit = scenario.get("peak_velocity_limit")
    threshold = math.inf if limit is None else float(limit) * (1.0 - 1e-12)
    return Reduction(
        kind=str(kind),
        scenario=scenario,
        rows=rows,
        interval=interval,
        window_start=int(start),
        shift=float(static_load),
        threshold=threshold,
        trace=kind == "road",
    )


def finish(
    reduction: Reduction,
    acc: np.ndarray,
    trace: np.ndarray,
    road_acceleration: Any,
    road_peak: RoadPeak = "after-onset",
) -> dict[str, Any]:
    """The measures of a run from its accumulators (``acc``, one row) and ``trace``.

    ``road_acceleration(time)`` is the excitation's acceleration. Returns what
    :meth:`SimulationResult.measures` returns for the same run.
    """
    from mrsuspension.measures import road_acceleration_peak
    from mrsuspension.measures.shock import shock_from_peaks
    from mrsuspension.measures.steady import harmonic_from_moments

    r = reduction
    out: dict[str, Any]
    if r.kind == "harmonic":
        nw = acc[EK.A_NW]
        acc_r = np.asarray(road_acceleration(r.time()), dtype=float)[r.window_start :]
        squares = {
            "acc_s": acc[EK.A_WAS2] / nw,
            "acc_u": acc[EK.A_WAU2] / nw,
            "acc_r": float(np.mean(acc_r**2)),
            "x_d": acc[EK.A_WXD2] / nw,
            "z_s": acc[EK.A_WZS2] / nw,
            "z_u": acc[EK.A_WZU2] / nw,
            "z_r": acc[EK.A_WZR2] / nw,
        }
        mean_d = acc[EK.A_WFT1] / nw
        mean_i = acc[EK.A_WI1] / nw
        out = harmonic_from_moments(
            squares,
            tire_force_variance=max(acc[EK.A_WFT2] / nw - mean_d * mean_d, 0.0),
            static_load=float(measures_context(r.scenario)[2]),
            compression_peak=float(acc[EK.A_WFDMAX]),
            rebound_peak=float(acc[EK.A_WFDNEG]),
            current=(float(mean_i), float(acc[EK.A_WI2] / nw)),
        )
    elif r.kind == "pulse":
        peaks = {
            "z_s": acc[EK.A_PZS], "z_u": acc[EK.A_PZU], "z_r": acc[EK.A_PZR], "acc_s": acc[EK.A_PAS],
            "acc_u": acc[EK.A_PAU], "x_d": acc[EK.A_PXD],
        }  # fmt: skip
        road = np.asarray(road_acceleration(r.time()), dtype=float)
        if peaks["z_r"] == 0.0:
            raise ValidationError("z_r is zero over the whole record: shock ratios undefined")
        ratios = shock_from_peaks(
            {k: float(v) for k, v in peaks.items()}, road_acceleration_peak(road, road_peak)
        )
        out = pulse_measures(ratios, float(acc[EK.A_FTMAX]), road_peak)
    else:
        n = acc[EK.A_N]
        mean_d = acc[EK.A_FT1] / n
        mean_x = acc[EK.A_XD1] / n
        out = road_measures(
            tire_force_mean=float(mean_d + r.shift),
            tire_force_variance=float(max(acc[EK.A_FT2] / n - mean_d * mean_d, 0.0)),
            body_acceleration=trace,
            fs=1.0 / r.interval,
            stroke_variance=float(max(acc[EK.A_XD2] / n - mean_x * mean_x, 0.0)),
            mean_current=float(acc[EK.A_I1] / n),
        )
    drop_unused_currents(out, r.scenario)
    out["vm_clamp_fraction"] = float(acc[EK.A_CLAMP] / acc[EK.A_N])
    return out


def run_measures(
    simulation: KernelRun,
    settings: RunSettings | None = None,
    *,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
    road_peak: RoadPeak = "after-onset",
    check_stability: bool = True,
) -> dict[str, Any]:
    """``simulation.run(...).measures()`` without writing the time history.

    Same arguments as :meth:`Simulation.run` (``road_peak`` as
    :meth:`SimulationResult.measures`); the values agree to round-off.

    Raises
    ------
    ValidationError
        As :meth:`Simulation.run` and :meth:`SimulationResult.measures`.
    SimulationDiverged
        As :meth:`Simulation.run`.

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> sim = Simulation(Harmonic(1.5, 0.025))
    >>> fast = run_measures(sim, duration=14.0)
    >>> slow = sim.run(14.0).measures()
    >>> bool(abs(fast["T_as"] / slow["T_as"] - 1.0) < 1e-12)
    True
    """
    from mrsuspension.measures import check_road_peak

    how = check_road_peak(road_peak)
    run = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
    run.check_for(simulation.excitation)
    plan = run.plan(simulation, check_stability=check_stability)
    announce_compile(EK.__file__, "run")
    red = reduction_of(simulation, plan)
    dt, n, decimate = plan
    zr, zrd = simulation.road_samples(n, dt)
    a = simulation.kernel_arrays(dt, check_stability=False)
    y = np.array([zr[0], 0.0, zr[0], 0.0, zr[0], 0.0])
    acc = new_accumulators(1)
    trace = np.zeros(red.rows if red.trace else 0)
    status, k, idx, value = EK.run(
        y, n, dt, zr, zrd, *a.args(), decimate, EK.LIMITS, np.zeros(EK.SCRATCH_SIZE),
        *EK.reducing(acc[0], red.window_start, red.shift, red.threshold, trace),
    )  # fmt: skip
    raise_failure()  # a Python control law that raised (its run stopped there)
    if status != EK.D_OK:
        raise simulation.divergence(status, k * dt, idx, value, dt)
    return finish(red, acc[0], trace, simulation.excitation.acceleration, how)
