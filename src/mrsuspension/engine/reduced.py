"""Measures reduced inside the kernels: runs that write no time history.

A sweep, a study or the optimiser wants each run's measures (model reference, section 9), not its
record. Here the kernels accumulate, at each output sample and in O(1) memory per run,
what the measures need: sums of squares over the steady-state window (its first sample
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

:func:`run_measures` is the scalar path (any damper and controller);
:func:`mrsuspension.engine.lanes.run_lanes` with ``measures=True`` the lane path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numba import njit

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import INLINED, announce_compile, invalidate_if_changed
from mrsuspension.control import kernel as CK
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.engine import kernel as EK
from mrsuspension.engine.arrays import KernelArrays
from mrsuspension.engine.result import (
    SimulationDiverged,
    SimulationResult,
    measures_context,
    pulse_measures,
    road_measures,
)
from mrsuspension.engine.settings import RunPlan, RunSettings, run_settings
from mrsuspension.errors import ValidationError
from mrsuspension.vehicle import kernel as VK

if TYPE_CHECKING:
    from mrsuspension.measures import RoadPeak

# run_reduced inlines the step and what it inlines
invalidate_if_changed(
    __file__, EK.__file__, DK.__file__, _shaping.__file__, CK.__file__, VK.__file__
)

__all__ = ["N_ACC", "Reduction", "accumulate", "new_accumulators", "reduction_of", "run_measures"]

# accumulators of one run (a row of N_ACC floats)
(
    A_N,  # output samples
    A_I1,  # sum i_d
    A_FT1, A_FT2,  # sums of F_T - shift and its square
    A_XD1, A_XD2,  # sums of x_d and x_d^2
    A_PZS, A_PZU, A_PZR, A_PAS, A_PAU, A_PXD,  # max |z_s|, |z_u|, |z_r|, |z_s''|, |z_u''|, |x_d|
    A_FTMAX,  # max F_T
    A_CLAMP,  # samples with v_m at its clamp
    A_NW,  # samples in the steady window
    A_WAS2, A_WAU2, A_WXD2, A_WZS2, A_WZU2, A_WZR2,  # window sums of squares
    A_WFT1, A_WFT2,  # window sums of F_T - shift and its square
    A_WFDMAX, A_WFDNEG,  # window max F_d and max -F_d
    A_WI1, A_WI2,  # window sums of i_d and i_d^2
) = range(27)  # fmt: skip
N_ACC = 27
_MAXIMA = (A_FTMAX, A_WFDMAX, A_WFDNEG)


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


# compiled once and inlined by LLVM (numba's IR inlining of its two call sites here and
# two in the lane kernel cost compile time); whether the sample is in the steady window
# comes as a bool: a literal row number would compile a specialisation of its own
@njit(cache=True, **INLINED)
def accumulate(
    acc: np.ndarray,
    in_window: bool,
    shift: float,
    threshold: float,
    y: np.ndarray,
    zr: float,
    mem: np.ndarray,
) -> None:
    """Add an output sample (state ``y``, road ``zr``, outputs in ``mem``) to ``acc``.

    ``in_window``: whether the sample is in the steady window (its row at or after
    :attr:`Reduction.window_start`).

    The signals are those :meth:`~mrsuspension.engine.Simulation.result_from_record`
    reads from a record row, computed the same way.
    """
    zs = y[0]
    zu = y[2]
    xd = zu - zs
    a_s = mem[EK.M_AS]
    a_u = mem[EK.M_AU]
    fd = mem[EK.M_FD]
    i = mem[EK.M_ID]
    d = mem[EK.M_FT] - shift
    acc[A_N] += 1.0
    acc[A_I1] += i
    acc[A_FT1] += d
    acc[A_FT2] += d * d
    acc[A_XD1] += xd
    acc[A_XD2] += xd * xd
    acc[A_PZS] = max(acc[A_PZS], abs(zs))
    acc[A_PZU] = max(acc[A_PZU], abs(zu))
    acc[A_PZR] = max(acc[A_PZR], abs(zr))
    acc[A_PAS] = max(acc[A_PAS], abs(a_s))
    acc[A_PAU] = max(acc[A_PAU], abs(a_u))
    acc[A_PXD] = max(acc[A_PXD], abs(xd))
    acc[A_FTMAX] = max(acc[A_FTMAX], mem[EK.M_FT])
    if mem[EK.M_VM] >= threshold:
        acc[A_CLAMP] += 1.0
    if in_window:
        acc[A_NW] += 1.0
        acc[A_WAS2] += a_s * a_s
        acc[A_WAU2] += a_u * a_u
        acc[A_WXD2] += xd * xd
        acc[A_WZS2] += zs * zs
        acc[A_WZU2] += zu * zu
        acc[A_WZR2] += zr * zr
        acc[A_WFT1] += d
        acc[A_WFT2] += d * d
        acc[A_WFDMAX] = max(acc[A_WFDMAX], fd)
        acc[A_WFDNEG] = max(acc[A_WFDNEG], -fd)
        acc[A_WI1] += i
        acc[A_WI2] += i * i


@njit(cache=True, **NO_REFCOUNT)
def run_reduced(
    y: np.ndarray,
    n_steps: int,
    dt: float,
    zr: np.ndarray,
    zrd: np.ndarray,
    vp: np.ndarray,
    fk: int,
    dk: int,
    dp: np.ndarray,
    ds: np.ndarray,
    dek: int,
    dep: np.ndarray,
    des: np.ndarray,
    ck: int,
    cp: np.ndarray,
    cek: int,
    cep: np.ndarray,
    ces: np.ndarray,
    mem: np.ndarray,
    decimate: int,
    acc: np.ndarray,
    window_start: int,
    shift: float,
    threshold: float,
    trace: np.ndarray,
    limits: np.ndarray,
    scratch: np.ndarray,
) -> tuple[int, int, int, float]:
    """:func:`~mrsuspension.engine.kernel.run` accumulating instead of recording.

    Every ``decimate`` steps (and at the start) the output sample goes to
    :func:`accumulate`; with a non-empty ``trace`` its ``z_s''`` is also kept there.
    Returns what :func:`~mrsuspension.engine.kernel.run` returns.
    """
    EK.start(
        y, zr[0], zrd[0], vp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces, mem, scratch
    )
    accumulate(acc, window_start <= 0, shift, threshold, y, zr[0], mem)
    keep = trace.size > 0
    if keep:
        trace[0] = mem[EK.M_AS]
    row = 1
    for k in range(n_steps):
        j = 2 * k
        EK.step(
            y, dt, zr[j], zrd[j], zr[j + 1], zrd[j + 1], zr[j + 2], zrd[j + 2], vp, fk, dk, dp,
            ds, dek, dep, des, ck, cp, cek, cep, ces, mem, scratch,
        )  # fmt: skip
        status, q, value = EK.check_limits(y, mem, limits)
        if status != EK.D_OK:
            return status, k + 1, q, value
        if (k + 1) % decimate == 0:
            accumulate(acc, row >= window_start, shift, threshold, y, zr[j + 2], mem)
            if keep:
                trace[row] = mem[EK.M_AS]
            row += 1
    return EK.D_OK, n_steps, 0, 0.0


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
        nw = acc[A_NW]
        acc_r = np.asarray(road_acceleration(r.time()), dtype=float)[r.window_start :]
        squares = {
            "acc_s": acc[A_WAS2] / nw,
            "acc_u": acc[A_WAU2] / nw,
            "acc_r": float(np.mean(acc_r**2)),
            "x_d": acc[A_WXD2] / nw,
            "z_s": acc[A_WZS2] / nw,
            "z_u": acc[A_WZU2] / nw,
            "z_r": acc[A_WZR2] / nw,
        }
        mean_d = acc[A_WFT1] / nw
        mean_i = acc[A_WI1] / nw
        out = harmonic_from_moments(
            squares,
            tire_force_variance=max(acc[A_WFT2] / nw - mean_d * mean_d, 0.0),
            static_load=float(measures_context(r.scenario)[2]),
            compression_peak=float(acc[A_WFDMAX]),
            rebound_peak=float(acc[A_WFDNEG]),
            current=(float(mean_i), float(acc[A_WI2] / nw)),
        )
    elif r.kind == "pulse":
        peaks = {
            "z_s": acc[A_PZS], "z_u": acc[A_PZU], "z_r": acc[A_PZR], "acc_s": acc[A_PAS],
            "acc_u": acc[A_PAU], "x_d": acc[A_PXD],
        }  # fmt: skip
        road = np.asarray(road_acceleration(r.time()), dtype=float)
        if peaks["z_r"] == 0.0:
            raise ValidationError("z_r is zero over the whole record: shock ratios undefined")
        ratios = shock_from_peaks(
            {k: float(v) for k, v in peaks.items()}, road_acceleration_peak(road, road_peak)
        )
        out = pulse_measures(ratios, float(acc[A_FTMAX]), road_peak)
    else:
        n = acc[A_N]
        mean_d = acc[A_FT1] / n
        mean_x = acc[A_XD1] / n
        out = road_measures(
            tire_force_mean=float(mean_d + r.shift),
            tire_force_variance=float(max(acc[A_FT2] / n - mean_d * mean_d, 0.0)),
            body_acceleration=trace,
            fs=1.0 / r.interval,
            stroke_variance=float(max(acc[A_XD2] / n - mean_x * mean_x, 0.0)),
            mean_current=float(acc[A_I1] / n),
        )
    out["vm_clamp_fraction"] = float(acc[A_CLAMP] / acc[A_N])
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
    announce_compile(__file__, "run_reduced")
    red = reduction_of(simulation, plan)
    dt, n, decimate = plan
    zr, zrd = simulation.road_samples(n, dt)
    a = simulation.kernel_arrays(dt, check_stability=False)
    y = np.array([zr[0], 0.0, zr[0], 0.0, zr[0], 0.0])
    acc = new_accumulators(1)
    trace = np.zeros(red.rows if red.trace else 0)
    status, k, idx, value = run_reduced(
        y, n, dt, zr, zrd, *a.args(), decimate, acc[0], red.window_start, red.shift,
        red.threshold, trace, EK.LIMITS, np.zeros(EK.SCRATCH_SIZE),
    )  # fmt: skip
    if status != EK.D_OK:
        raise simulation.divergence(status, k * dt, idx, value, dt)
    return finish(red, acc[0], trace, simulation.excitation.acceleration, how)
