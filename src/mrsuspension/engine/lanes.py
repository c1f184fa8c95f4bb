"""Lane kernel: many runs of one configuration stepped together in vector instructions.

A frequency sweep runs the same car, damper and controller under many road inputs. The
scalar step (:func:`mrsuspension.engine.kernel.step`) is a chain of dependent operations
(five damper evaluations per step, each waiting for the previous one), so one run leaves
most of the core idle. Here :data:`LANES` runs advance together: each step, the
per-run bookkeeping (peak-velocity estimators, controller, checks, record) runs run by run
with the scalar kernels, and the damper's latching (:func:`lane_latch`) and the RK4
stages of all the runs (where the time goes) run as loops over the lanes that compile to
vector instructions. When a run
ends, its lane takes the next one, so lanes stay busy whatever the run lengths. Lanes
left without a run (a group of fewer runs than lanes, or its tail while the longest runs
go on) cost next to nothing: the busy lanes are packed into slots ``0..m-1`` of the lane
arrays (repacked when a run ends) and the vector loops cover those ``m`` slots, rounded
up to whole vectors (:data:`VECTOR`). A report's frequency-response group of 10 runs
of 7 to 40 s (23 % of the lane steps busy) measured 1.5-1.6x faster than with every lane
computed.

Three things make that loop vectorise: it calls nothing (the damper's tanh uses
:func:`~mrsuspension.dampers.kernels.lane_tanh`, whose exp is plain arithmetic: numba has
no vector exp without Intel's SVML), it cannot raise (compiled with
``error_model="numpy"``: no division-by-zero exits) and it reads one array and writes
another with field offsets known at compile time (so the vectoriser needs one overlap
check instead of one per field pair, over its limit).

The physics is shared, not copied: the force is
:func:`~mrsuspension.dampers.kernels.wang_combine`, the car
:func:`~mrsuspension.vehicle.kernel.plant_rates`, the per-run parts the scalar kernels
themselves. The numerical differences from :meth:`Simulation.run` are that exp, which is
within 1.5 ulp of libm's, and fused multiply-adds in the stages: results agree to
round-off (measured over 3 s runs of every controller, relative to each signal's range:
``z_s`` within 2.2e-13, ``F_d`` within 1.8e-11, ``i_d`` within 3.3e-11; the benchmark
sweep's measures within 5e-12), not bit for bit. The road comes to each lane in chunks
of :data:`ROAD_CHUNK` steps, sampled from the chunk's start time: the same grid up to
round-off in the sample times.

With ``measures=True`` (:func:`run_lanes`) the runs write no time history: the lanes
accumulate their measures (:mod:`~mrsuspension.engine.reduced`).

Eligible: the dissertation's damper model (:class:`~mrsuspension.dampers.WangSymmetric`
and the asymmetric variant) with any controller acting through it; runs that differ only
in their excitation and duration share a lane group (:func:`lane_key`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numba import njit

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import announce_compile, invalidate_if_changed
from mrsuspension.control import kernel as CK
from mrsuspension.control import signals as SG
from mrsuspension.control.kernel import EST_SHARED, F_MODEL, P_C0, P_CS, P_MS0, P_P
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import reduced as RD
from mrsuspension.engine.settings import RunSettings, run_settings
from mrsuspension.errors import ValidationError
from mrsuspension.vehicle import kernel as VK
from mrsuspension.vehicle.kernel import V_CSKY, V_CT, V_DXU, V_G, V_KS, V_KT, V_MS, V_MU

if TYPE_CHECKING:
    from mrsuspension.measures import RoadPeak

# the cached kernels below inline the damper, shaping, controller, vehicle and step kernels
invalidate_if_changed(
    __file__, DK.__file__, EK.__file__, RD.__file__, _shaping.__file__, CK.__file__, VK.__file__,
    SG.__file__,
)  # fmt: skip

__all__ = [
    "LANES",
    "MAX_BATCH_STEPS",
    "MIN_GROUP",
    "ROAD_CHUNK",
    "LaneRun",
    "batch_cost",
    "lane_key",
    "plan_batches",
    "run_lanes",
]


#: What the lanes need of a run: the quarter car's kernel contract (:class:`~.reduced.KernelRun`).
LaneRun = RD.KernelRun


#: runs stepped together (a compile-time constant: the vectoriser needs fixed offsets;
#: with 8 it judged the loop not worth vectorising, 32 measured no faster than 16)
LANES = 16

#: doubles in one vector register as LLVM vectorises the lane loops here (ymm: 4); the
#: loops run over the busy slots rounded up to a multiple of it, so that no slot takes
#: the scalar remainder loop (a scalar slot costs about as much as a vector of 4)
VECTOR = 4


@njit(cache=True, inline="always")
def _vector_count(m: int) -> int:
    """``m`` slots rounded up to whole vectors of :data:`VECTOR` (at most :data:`LANES`)."""
    return min(LANES, (m + VECTOR - 1) // VECTOR * VECTOR)


# fields of the lane input (IN) and output (OUT) arrays, LANES values each
(
    I_ZS, I_VS, I_ZU, I_VU, I_Z0, I_V0,  # state at the start of the step
    I_HA, I_SH, I_FT, I_FB, I_KDCI, I_DEC,  # latched damper terms (WS_* of the kernels)
    I_R0, I_D0, I_R1, I_D1, I_R2, I_D2,  # road and its rate at t, t + dt/2, t + dt
) = range(18)  # fmt: skip
N_IN = 18
O_ZS, O_VS, O_ZU, O_VU, O_Z0, O_V0, O_AS, O_AU, O_A0, O_FD, O_FT = range(11)
N_OUT = 11
# fields of the latch input (what the damper latches from: v_m, sgn(a_d), i_d) and the
# latch's largest exp argument per lane
L_VM, L_SGN, L_I, L_ARG, L_FT, L_HA, L_DEC, L_MARG = range(8)
N_LAT = 8


#: numba options of the functions only the vectorised lane loops call: compiled once each
#: and inlined by LLVM, like :data:`~mrsuspension._numba_cache.INLINED`, but with the
#: lanes' error model and contraction (no division checks, fused multiply-adds), which the
#: vectoriser needs. numba's IR inlining of the four stages and the final rates made
#: ``lane_stages`` take 2.6 s of CPU to compile; inlined by LLVM 0.7 s, at the same speed.
LANE_INLINED: dict[str, Any] = {
    "forceinline": True,
    "_nrt": False,
    "error_model": "numpy",
    "fastmath": {"contract"},
}


@njit(cache=True, **LANE_INLINED)
def _lane_rates(
    zs: float,
    vs: float,
    zu: float,
    vu: float,
    z0: float,
    v0: float,
    zr: float,
    zrd: float,
    ha: float,
    shift: float,
    ftr: float,
    fb: float,
    kdci: float,
    decay: float,
    k1c: float,
    k1e: float,
    c: np.ndarray,
    reference: bool,
) -> tuple[float, float, float, float, float]:
    """:func:`~mrsuspension.engine.kernel.accelerations` for the Wang model, branch-free."""
    vd = vu - vs
    k1 = k1c if vd >= 0.0 else k1e
    fd = DK.wang_combine(kdci, ftr, fb, DK.lane_tanh(ha * (vd + shift)), k1, decay, vd)
    a_s, a_u, a_0, ft = VK.plant_rates(
        zs, vs, zu, vu, z0, v0, zr, zrd, fd, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7],
        reference, c[8], c[9], c[10],
    )  # fmt: skip
    return a_s, a_u, a_0, fd, ft


@njit(cache=True, **LANE_INLINED)
def _lane_stage(
    y: tuple[float, float, float, float, float, float],
    t: tuple[float, float, float, float, float, float],
    acc: tuple[float, float, float, float, float, float],
    weight: float, step: float, zr: float, zrd: float,
    p: tuple[float, float, float, float, float, float, float, float],
    c: np.ndarray, reference: bool,
) -> tuple[
    tuple[float, float, float, float, float, float], tuple[float, float, float, float, float, float]
]:  # fmt: skip
    """One RK4 stage at the stage state ``t``: ``acc + weight k`` and ``y + step k``.

    ``k`` is the rates at ``t`` (velocities, then accelerations; the reference model's
    only with ``reference``); ``p`` the latched damper terms and ``k1c, k1e``.
    """
    s, u, o, _, _ = _lane_rates(
        t[0], t[1], t[2], t[3], t[4], t[5], zr, zrd, p[0], p[1], p[2], p[3], p[4], p[5],
        p[6], p[7], c, reference,
    )  # fmt: skip
    w = t[5] if reference else 0.0
    acc = (
        acc[0] + weight * t[1], acc[1] + weight * s, acc[2] + weight * t[3],
        acc[3] + weight * u, acc[4] + weight * w, acc[5] + weight * o,
    )  # fmt: skip
    nxt = (
        y[0] + step * t[1], y[1] + step * s, y[2] + step * t[3], y[3] + step * u,
        y[4] + step * w, y[5] + step * o,
    )  # fmt: skip
    return acc, nxt


@njit(cache=True, error_model="numpy", fastmath={"contract"}, **NO_REFCOUNT)
def lane_stages(
    lin: np.ndarray, lout: np.ndarray, dt: float, k1c: float, k1e: float, c: np.ndarray,
    reference: bool, m: int = LANES,
) -> None:  # fmt: skip
    """One RK4 step of the first ``m`` slots (the arithmetic of
    :func:`~mrsuspension.engine.kernel.step`).

    ``lin`` holds :data:`N_IN` fields of :data:`LANES` slots (field-major), ``lout``
    :data:`N_OUT`; ``c`` the car's constants (see :func:`_constants`). The kernel packs
    the lanes holding a run into slots ``0..m-1``; slots up to the next multiple of
    :data:`VECTOR` compute on stale values, which nobody reads.
    """
    h = 0.5 * dt
    w6 = dt / 6.0
    n = LANES  # the field stride stays a compile-time constant (fixed offsets); the trip
    # count m is a runtime value, for which the vectoriser adds a remainder loop
    for q in range(_vector_count(m)):  # q: a slot
        zs, vs, zu, vu = lin[I_ZS * n + q], lin[I_VS * n + q], lin[I_ZU * n + q], lin[I_VU * n + q]
        z0, v0 = lin[I_Z0 * n + q], lin[I_V0 * n + q]
        ha, sh, ftr = lin[I_HA * n + q], lin[I_SH * n + q], lin[I_FT * n + q]
        fb, kdci, dec = lin[I_FB * n + q], lin[I_KDCI * n + q], lin[I_DEC * n + q]
        r0, d0, r1 = lin[I_R0 * n + q], lin[I_D0 * n + q], lin[I_R1 * n + q]
        d1, r2, d2 = lin[I_D1 * n + q], lin[I_R2 * n + q], lin[I_D2 * n + q]
        # the stages in the order and grouping of kernel.step, so that only the exp differs
        y = (zs, vs, zu, vu, z0, v0)
        p = (ha, sh, ftr, fb, kdci, dec, k1c, k1e)
        acc = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        acc, t = _lane_stage(y, y, acc, 1.0, h, r0, d0, p, c, reference)
        acc, t = _lane_stage(y, t, acc, 2.0, h, r1, d1, p, c, reference)
        acc, t = _lane_stage(y, t, acc, 2.0, dt, r1, d1, p, c, reference)
        acc, _ = _lane_stage(y, t, acc, 1.0, dt, r2, d2, p, c, reference)
        azs, avs, azu, avu, az0, av0 = acc
        zs += w6 * azs
        vs += w6 * avs
        zu += w6 * azu
        vu += w6 * avu
        z0 += w6 * az0
        v0 += w6 * av0
        s5, u5, o5, fd, ft = _lane_rates(
            zs, vs, zu, vu, z0, v0, r2, d2, ha, sh, ftr, fb, kdci, dec, k1c, k1e, c, reference
        )
        lout[O_ZS * n + q], lout[O_VS * n + q], lout[O_ZU * n + q] = zs, vs, zu
        lout[O_VU * n + q], lout[O_Z0 * n + q], lout[O_V0 * n + q] = vu, z0, v0
        lout[O_AS * n + q], lout[O_AU * n + q], lout[O_A0 * n + q] = s5, u5, o5
        lout[O_FD * n + q], lout[O_FT * n + q] = fd, ft


@njit(cache=True, error_model="numpy", fastmath={"contract"}, **NO_REFCOUNT)
def lane_latch(
    lat: np.ndarray, lin: np.ndarray, dp: np.ndarray, dss: np.ndarray,
    lanes: np.ndarray | None = None, m: int = LANES,
) -> None:  # fmt: skip
    """Latch the damper of the first ``m`` slots from ``lat`` (:data:`N_LAT` fields) into ``lin``.

    The step's part of :func:`~mrsuspension.dampers.kernels.wang_latch_motion` and
    :func:`~mrsuspension.dampers.kernels.wang_latch_current`, as one loop over the slots
    that compiles to vector instructions (their four exps per run and step were the
    largest per-run cost: :func:`~mrsuspension.dampers.kernels.lane_wang_latch`). When
    an exp argument exceeds :data:`~mrsuspension.dampers.kernels.LANE_EXP_LIMIT` (beyond
    any identified set), the slots latch again with the scalar kernels, in the damper
    state ``dss[lanes[p]]`` of the lane that slot ``p`` holds (``lanes`` None: slot ``p``
    is lane ``p``). Slots from ``m`` to the next multiple of :data:`VECTOR` latch stale
    values, which nobody reads.
    """
    n = LANES
    for p in range(_vector_count(m)):
        ha, sh, ft, fb, kdci, dec, arg = DK.lane_wang_latch(
            dp, lat[L_VM * n + p], lat[L_SGN * n + p], lat[L_I * n + p]
        )
        lin[I_HA * n + p], lin[I_SH * n + p], lin[I_FT * n + p] = ha, sh, ft
        lin[I_FB * n + p], lin[I_KDCI * n + p], lin[I_DEC * n + p] = fb, kdci, dec
        lat[L_ARG * n + p] = arg
    largest = 0.0
    for p in range(m):
        largest = max(largest, lat[L_ARG * n + p])
    if largest <= DK.LANE_EXP_LIMIT:
        return
    for p in range(m):
        s = dss[p] if lanes is None else dss[lanes[p]]
        DK.wang_latch_motion(dp, s, lat[L_VM * n + p], lat[L_SGN * n + p])
        DK.wang_latch_current(dp, s, lat[L_I * n + p])
        lin[I_HA * n + p], lin[I_SH * n + p] = s[DK.WS_HALF_ALPHA], s[DK.WS_SHIFT]
        lin[I_FT * n + p], lin[I_FB * n + p] = s[DK.WS_FT], s[DK.WS_FB]
        lin[I_KDCI * n + p], lin[I_DEC * n + p] = dp[DK.W_KD] * s[DK.WS_CI], s[DK.WS_DECAY]


@njit(cache=True, error_model="numpy", fastmath={"contract"}, **NO_REFCOUNT)
def lane_motion(lat: np.ndarray, dp: np.ndarray, m: int) -> None:
    """The passive hysteron's v_m terms of the first ``m`` slots, for the inverse laws.

    :func:`~mrsuspension.dampers.kernels.lane_motion_terms` of ``lat[L_VM]`` into
    ``lat[L_FT]``, ``lat[L_HA]``, ``lat[L_DEC]`` and ``lat[L_MARG]`` (its largest exp
    argument), in one loop that compiles to vector instructions. The cycle-rms v_m
    changes every step, so the laws' memo of these terms
    (:func:`~mrsuspension.dampers.kernels.passive_hysteron_memo`) would compute them
    again, with two scalar exps, in every run at every step; the lanes fill it from here.
    """
    n = LANES
    for p in range(_vector_count(m)):
        ft, half_alpha, decay, largest = DK.lane_motion_terms(dp, lat[L_VM * n + p])
        lat[L_FT * n + p], lat[L_HA * n + p] = ft, half_alpha
        lat[L_DEC * n + p], lat[L_MARG * n + p] = decay, largest


@njit(cache=True, inline="always")
def _busy(lane_run: np.ndarray, slots: np.ndarray) -> int:
    """Pack the lanes holding a run into ``slots`` (in lane order); their count."""
    m = 0
    for q in range(LANES):
        if lane_run[q] >= 0:
            slots[m] = q
            m += 1
    return m


@njit(cache=True, inline="always")
def _output(
    reduced: bool, rec: np.ndarray, rec_row: int, row: int, j: int, acc: np.ndarray,
    starts: np.ndarray, shifts: np.ndarray, thresholds: np.ndarray, trace: np.ndarray,
    y: np.ndarray, zr: float, zrd: float, mem: np.ndarray,
) -> None:  # fmt: skip
    """Output sample ``row`` of run ``j``: a record row, or (``reduced``) its accumulators
    (:func:`~mrsuspension.engine.reduced.accumulate`) and, with a ``trace``, ``z_s''``."""
    if reduced:
        RD.accumulate(acc[j], row >= starts[j], shifts[j], thresholds[j], y, zr, mem)
        if trace.size > 0:
            trace[rec_row] = mem[EK.M_AS]
    else:
        EK.record(rec, rec_row, y, zr, zrd, mem)


@njit(cache=True, inline="always")
def _start_lane(
    j: int, y: np.ndarray, mem: np.ndarray, ds: np.ndarray, des: np.ndarray, ces: np.ndarray,
    ds0: np.ndarray, des0: np.ndarray, ces0: np.ndarray, zr: float, zrd: float, vp: np.ndarray,
    fk: int, dk: int, dp: np.ndarray, dek: int, dep: np.ndarray, ck: int, cp: np.ndarray, cek: int,
    cep: np.ndarray, scratch: np.ndarray,
) -> None:  # fmt: skip
    """Fresh state for run ``j`` on a road starting at ``(zr, zrd)`` and its initial rates
    (then :func:`_output` writes its output row 0; apart because numba inlines calls of
    at most 30 arguments)."""
    y[0], y[1], y[2], y[3], y[4], y[5] = zr, 0.0, zr, 0.0, zr, 0.0
    mem[:] = 0.0
    # element loops: a slice copy would need numba's allocator (for overlapping arrays)
    for m in range(ds.size):
        ds[m] = ds0[m]
    for m in range(des.size):
        des[m] = des0[m]
    for m in range(ces.size):
        ces[m] = ces0[m]
    EK.start(y, zr, zrd, vp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces, mem, scratch)


@njit(cache=True, error_model="numpy", **NO_REFCOUNT)
def run_lanes_kernel(
    n_steps: np.ndarray, base: np.ndarray, zr: np.ndarray, zrd: np.ndarray,
    rec_off: np.ndarray, rec: np.ndarray, decimate: int, status: np.ndarray, dt: float,
    vp: np.ndarray, fk: int, dk: int, dp: np.ndarray, ds0: np.ndarray, dek: int, dep: np.ndarray,
    des0: np.ndarray, ck: int, cps: np.ndarray, cek: int, cep: np.ndarray, ces0: np.ndarray,
    limits: np.ndarray, consts: np.ndarray, ys: np.ndarray, mems: np.ndarray,
    dss: np.ndarray, dess: np.ndarray, cess: np.ndarray, lin: np.ndarray, lout: np.ndarray,
    lat: np.ndarray, lane_run: np.ndarray, lane_k: np.ndarray, scratch: np.ndarray, reduced: bool,
    acc: np.ndarray, starts: np.ndarray, shifts: np.ndarray, thresholds: np.ndarray,
    trace: np.ndarray, need: np.ndarray, ctl: np.ndarray, slots: np.ndarray,
) -> None:  # fmt: skip
    """Every run of one configuration, :data:`LANES` at a time (see the module docstring).

    Resumable: it returns whenever a lane needs road samples, and is called again (same
    arguments) until ``ctl[1]`` (runs in progress) is 0. Each lane ``q`` holds a chunk of
    its run's road (``zr[q]``, ``zrd[q]``: every half step of :data:`ROAD_CHUNK` steps
    from step ``base[q]``); ``need[q] = j`` asks the caller for run ``j``'s chunk from
    step ``base[q]`` (then set it back to -1). ``ctl`` holds the next run to start, the
    runs in progress and whether the lanes were set up.

    Run ``j`` has ``n_steps[j]`` steps and its record rows (every ``decimate`` steps, row
    0 the initial state) at ``rec[rec_off[j]:]``. ``status[j]`` gets ``(status, step,
    index, value)`` as :func:`~mrsuspension.engine.kernel.run` returns them. The rest is
    work space: per-lane state rows (``ys``, ``mems``, ``dss``, ``dess``, ``cess``,
    initialised from ``ds0``, ``des0``, ``ces0``), the lane arrays and the lane
    bookkeeping (``lane_k[q]`` -1: a run waiting for its first chunk; ``slots[:m]`` the
    lanes holding a run, whose values the lane arrays hold at positions ``0..m-1``).

    With ``reduced``, nothing is recorded (``rec`` may be empty): each output sample of
    run ``j`` goes to its accumulators ``acc[j]`` (steady window from row
    ``starts[j]``, tire force less ``shifts[j]``, clamp at ``thresholds[j]``; see
    :mod:`~mrsuspension.engine.reduced`) and, when ``trace`` is not empty, its ``z_s''``
    to ``trace`` at the record's offsets.
    """
    runs = n_steps.shape[0]
    n = LANES
    chunk = (zr.shape[1] - 1) // 2
    reference = CK.needs_reference(ck)
    hysteron = ck == CK.C_INVERSE_HILO or ck == CK.C_SLIDING  # laws with the memo
    k1c, k1e = dp[DK.W_K1C], dp[DK.W_K1E]
    if ctl[2] == 0:  # first call: a run for each lane, whose first chunk the caller fills
        ctl[2] = 1
        for q in range(LANES):
            lane_run[q] = -1
            need[q] = -1
            if ctl[0] < runs:
                lane_run[q] = ctl[0]
                lane_k[q] = -1
                base[q] = 0
                need[q] = ctl[0]
                ctl[0] += 1
                ctl[1] += 1
        return
    nxt = ctl[0]
    active = ctl[1]
    for q in range(LANES):  # runs whose first chunk has come
        j = lane_run[q]
        if j >= 0 and lane_k[q] < 0:
            _start_lane(
                j, ys[q], mems[q], dss[q], dess[q], cess[q], ds0, des0, ces0, zr[q, 0],
                zrd[q, 0], vp, fk, dk, dp, dek, dep, ck, cps[j], cek, cep, scratch,
            )  # fmt: skip
            _output(
                reduced, rec, rec_off[j], 0, j, acc, starts, shifts, thresholds, trace, ys[q],
                zr[q, 0], zrd[q, 0], mems[q],
            )  # fmt: skip
            lane_k[q] = 0
    # the lanes holding a run, packed into slots 0..m-1: the lane arrays (lat, lin, lout)
    # hold slot p's values, and the vectorised loops cover the m busy slots only
    m = _busy(lane_run, slots)
    while active > 0:
        wait = False
        for p in range(m):
            q = slots[p]
            if lane_k[q] - base[q] == chunk:
                base[q] += chunk
                need[q] = lane_run[q]
                wait = True
        if wait:
            break
        for p in range(m):
            q = slots[p]
            y, mem = ys[q], mems[q]
            # kernel.step's part before the stages, run by run: the damper's estimator
            # (as damper_sample feeds it), the controller's; then (below) the control law.
            # The latch itself runs for all busy lanes at once (lane_latch)
            xd = y[2] - y[0]
            vd = y[3] - y[1]
            ad = mem[EK.M_AD]
            vm = DK.estimator_update(dek, dep, dess[q], xd, vd, ad)
            lat[L_VM * n + p] = vm
            lat[L_SGN * n + p] = DK.sign(ad)
            if cek != EST_SHARED:
                vm = DK.estimator_update(cek, cep, cess[q], xd, vd, ad)
            mem[EK.M_VM] = vm
        if hysteron:
            lane_motion(lat, dp, m)
        for p in range(m):
            q = slots[p]
            y, mem = ys[q], mems[q]
            if hysteron and lat[L_MARG * n + p] <= DK.LANE_EXP_LIMIT:
                # the law's memo of the damper's v_m terms, from the vector loop (used
                # when the law's v_m is the damper's, as with a shared estimator)
                mem[EK.M_PH + DK.PH_VM] = lat[L_VM * n + p]
                mem[EK.M_PH + DK.PH_FT] = lat[L_FT * n + p]
                mem[EK.M_PH + DK.PH_HALF_ALPHA] = lat[L_HA * n + p]
                mem[EK.M_PH + DK.PH_DECAY] = lat[L_DEC * n + p]
            EK.apply_control(ck, cps[lane_run[q]], vp, dp, y, mem[EK.M_AD], mem[EK.M_VM], mem)
            lat[L_I * n + p] = mem[EK.M_ID]
            lin[I_ZS * n + p], lin[I_VS * n + p], lin[I_ZU * n + p] = y[0], y[1], y[2]
            lin[I_VU * n + p], lin[I_Z0 * n + p], lin[I_V0 * n + p] = y[3], y[4], y[5]
            o = 2 * (lane_k[q] - base[q])
            lin[I_R0 * n + p], lin[I_D0 * n + p] = zr[q, o], zrd[q, o]
            lin[I_R1 * n + p], lin[I_D1 * n + p] = zr[q, o + 1], zrd[q, o + 1]
            lin[I_R2 * n + p], lin[I_D2 * n + p] = zr[q, o + 2], zrd[q, o + 2]
        lane_latch(lat, lin, dp, dss, slots, m)
        lane_stages(lin, lout, dt, k1c, k1e, consts, reference, m)
        ended = False
        for p in range(m):
            q = slots[p]
            j = lane_run[q]
            y, mem = ys[q], mems[q]
            y[0], y[1], y[2] = lout[O_ZS * n + p], lout[O_VS * n + p], lout[O_ZU * n + p]
            y[3], y[4], y[5] = lout[O_VU * n + p], lout[O_Z0 * n + p], lout[O_V0 * n + p]
            s5, u5 = lout[O_AS * n + p], lout[O_AU * n + p]
            mem[EK.M_AS] = s5
            mem[EK.M_AU] = u5
            mem[EK.M_A0] = lout[O_A0 * n + p]
            mem[EK.M_FD] = lout[O_FD * n + p]
            mem[EK.M_FT] = lout[O_FT * n + p]
            mem[EK.M_AD] = u5 - s5
            # (the dissertation's model has no internal dynamics to advance)
            k = lane_k[q] + 1
            lane_k[q] = k
            code, idx, value = EK.check_limits(y, mem, limits)
            done = code != EK.D_OK or k == n_steps[j]
            if code == EK.D_OK and k % decimate == 0:
                o = 2 * (k - base[q])
                r = k // decimate
                _output(
                    reduced, rec, rec_off[j] + r, r, j, acc, starts, shifts, thresholds, trace,
                    y, zr[q, o], zrd[q, o], mem,
                )  # fmt: skip
            if not done:
                continue
            status[j, 0] = code
            status[j, 1] = k
            status[j, 2] = idx
            status[j, 3] = value
            lane_run[q] = -1
            active -= 1
            ended = True
            if nxt < runs:  # the lane's next run, once the caller has filled its chunk
                lane_run[q] = nxt
                lane_k[q] = -1
                base[q] = 0
                need[q] = nxt
                wait = True
                nxt += 1
                active += 1
        if wait:
            break
        if ended:  # a lane fell idle: pack the slots again (at most LANES entries)
            m = _busy(lane_run, slots)
    ctl[0] = nxt
    ctl[1] = active


#: steps of road each lane holds at a time (every half step: 2 x 16 385 values, 256 kB):
#: the roads of a batch are never held at once (fresh memory measured 0.14-0.86 ms per MB)
ROAD_CHUNK = 16_384


def _constants(vp: np.ndarray, cp: np.ndarray) -> np.ndarray:
    """The car's constants as :func:`~mrsuspension.vehicle.kernel.plant_rates` takes them.

    Computed as :func:`~mrsuspension.engine.kernel.accelerations` computes them, so the
    lane and scalar steps use the same numbers.
    """
    ms, mu = vp[V_MS], vp[V_MU]
    return np.array(
        [
            vp[V_KS], vp[V_CSKY], 1.0 / ms, 1.0 / mu, (ms + mu) * vp[V_G], vp[V_KT],
            vp[V_CT], vp[V_DXU], cp[P_C0], cp[P_CS], 1.0 / cp[P_MS0],
        ]
    )  # fmt: skip


def lane_key(simulation: LaneRun, dt: float) -> tuple[Any, ...] | None:
    """What runs must share to step in one lane group; None when the run is not eligible.

    Eligible: the damper is the dissertation's model and the controller is a built-in
    law acting through it (not an ideal reference force, not a user-defined law: the
    lanes do not fill the signals it reads). The key holds every kernel array except the road and
    the controller's parameters (each run's own: a sweep of gains or currents shares
    lanes), of which it keeps those the lanes' stages share (:func:`_constants`).
    """
    a = simulation.kernel_arrays(dt, check_stability=False)
    if a.force_source != F_MODEL or a.damper_kind != DK.WANG:
        return None
    if a.controller_kind >= CK.C_USER_CURRENT:
        return None
    arrays = tuple(
        np.asarray(v, dtype=float).tobytes()
        for v in (
            a.vehicle, a.damper_params, a.damper_state, a.damper_estimator_params,
            a.damper_estimator_state, _constants(a.vehicle, a.controller_params),
            a.controller_estimator_params, a.controller_estimator_state,
        )
    )  # fmt: skip
    kinds = (a.damper_kind, a.damper_estimator_kind, a.controller_kind, a.controller_estimator_kind)
    return (float(dt), *(int(k) for k in kinds), *arrays)


def run_lanes(
    simulations: Sequence[LaneRun],
    *,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
    settings: RunSettings | None = None,
    check_stability: bool = True,
    measures: bool = False,
    road_peak: RoadPeak = "after-onset",
) -> list[Any]:
    """Run simulations that share a :func:`lane_key` together in the lane kernel.

    Same arguments and results as :meth:`Simulation.run` for each simulation, in order;
    a run that diverges gives its :class:`SimulationDiverged` in its place (not raised,
    so that the others are kept). With ``measures=True`` each run gives its measures
    instead (:meth:`SimulationResult.measures` with ``road_peak``), reduced inside the
    kernel without writing a time history (:mod:`~mrsuspension.engine.reduced`).

    Raises
    ------
    ValidationError
        When the simulations do not share one lane key, or as :meth:`Simulation.run`
        for bad ``duration``, ``dt`` or ``output_rate`` (and, with ``measures``, as
        :meth:`SimulationResult.measures`).

    Examples
    --------
    >>> from mrsuspension.control import HiLo
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> sims = [Simulation(Harmonic(f, 0.02), controller=HiLo(1)) for f in (1.0, 2.0, 4.0)]
    >>> results = run_lanes(sims, duration=1.0)
    >>> single = sims[1].run(1.0)
    >>> bool(abs(results[1].z_s - single.z_s).max() < 1e-12)
    True
    >>> m = run_lanes(sims, duration=20.0, measures=True)
    >>> bool(abs(m[1]["T_as"] / sims[1].run(20.0).measures()["T_as"] - 1.0) < 1e-9)
    True
    """
    sims = list(simulations)
    if not sims:
        return []
    run = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
    plans = [run.plan(s, check_stability=check_stability) for s in sims]
    announce_compile(__file__, "run_lanes_kernel")
    dt = plans[0].dt
    decimate = plans[0].decimate
    keys = {lane_key(s, dt) for s in sims}
    if len(keys) != 1 or None in keys:
        raise ValidationError(
            "run_lanes needs simulations that differ only in their excitation and controller "
            "parameters, with the dissertation's damper model (see lane_key); use run_many "
            "for any mix"
        )
    reductions = (
        [RD.reduction_of(s, p) for s, p in zip(sims, plans, strict=True)] if measures else []
    )
    steps = np.array([n for _, n, _ in plans], dtype=np.int64)
    rows = steps // decimate + 1
    rec_off = np.concatenate([[0], np.cumsum(rows)[:-1]]).astype(np.int64)
    status = np.zeros((len(sims), 4))
    if measures:
        rec = np.zeros((0, EK.N_REC))
        acc = RD.new_accumulators(len(sims))
        starts = np.array([r.window_start for r in reductions], dtype=np.int64)
        shifts = np.array([r.shift for r in reductions])
        thresholds = np.array([r.threshold for r in reductions])
        trace = np.zeros(int(rows.sum()) if any(r.trace for r in reductions) else 0)
    else:
        rec = np.zeros((int(rows.sum()), EK.N_REC))
        acc = np.zeros((0, RD.N_ACC))
        starts = np.zeros(0, dtype=np.int64)
        shifts = thresholds = trace = np.zeros(0)
    a = sims[0].kernel_arrays(dt, check_stability=False)
    # the controller's parameters are each run's own (a gain or current sweep shares lanes)
    cps = np.stack([s.kernel_arrays(dt, check_stability=False).controller_params for s in sims])
    ds0, des0 = a.damper_state, a.damper_estimator_state
    ces0 = a.controller_estimator_state
    w = LANES
    chunk = min(ROAD_CHUNK, int(steps.max()))
    base = np.zeros(w, dtype=np.int64)
    zr = np.zeros((w, 2 * chunk + 1))
    zrd = np.zeros((w, 2 * chunk + 1))
    need = np.full(w, -1, dtype=np.int64)
    ctl = np.zeros(3, dtype=np.int64)
    args = (
        steps, base, zr, zrd, rec_off, rec, decimate, status, dt, a.vehicle, a.force_source,
        a.damper_kind,
        a.damper_params, ds0, a.damper_estimator_kind, a.damper_estimator_params, des0,
        a.controller_kind, cps, a.controller_estimator_kind,
        a.controller_estimator_params, ces0, EK.LIMITS,
        _constants(a.vehicle, a.controller_params), np.zeros((w, VK.NY)),
        np.zeros((w, EK.MEM_SIZE)), np.zeros((w, ds0.size)), np.zeros((w, des0.size)),
        np.zeros((w, ces0.size)), np.zeros(N_IN * w), np.zeros(N_OUT * w), np.zeros(N_LAT * w),
        np.full(w, -1, dtype=np.int64), np.zeros(w, dtype=np.int64), np.zeros(EK.SCRATCH_SIZE),
        measures, acc, starts, shifts, thresholds, trace, need, ctl, np.zeros(w, dtype=np.int64),
    )  # fmt: skip
    while True:
        run_lanes_kernel(*args)
        waiting = np.flatnonzero(need >= 0)
        if waiting.size == 0:
            break
        for q in waiting:  # the road chunks the lanes asked for
            j, start = int(need[q]), int(base[q])
            count = min(chunk, int(steps[j]) - start)
            road = sims[j].road_samples(count, dt, start=start)
            zr[q, : 2 * count + 1], zrd[q, : 2 * count + 1] = road
            need[q] = -1
    out: list[Any] = []
    for j, sim in enumerate(sims):
        code, k, idx, value = status[j]
        if int(code) != EK.D_OK:
            out.append(sim.divergence(int(code), int(k) * dt, int(idx), float(value), dt))
        elif measures:
            red = reductions[j]
            own = trace[rec_off[j] : rec_off[j] + rows[j]] if red.trace else trace[:0]
            out.append(RD.finish(red, acc[j], own, sim.excitation.acceleration, road_peak))
        else:
            block = rec[rec_off[j] : rec_off[j] + rows[j]]
            time = np.arange(rows[j]) * (decimate * dt)
            out.append(sim.result_from_record(time, block, dt))
    return out


#: CPU per step of a run in lanes, relative to passive, by controller kind (kernel codes of
#: :mod:`mrsuspension.control.kernel`; 1 if not listed), and what these laws' ADFG current
#: shaping adds (ACM, ``p != 1``). Measured 2026-11-24, 32 runs of a two-stage sweep
#: (0.5-15 Hz) in lanes with in-kernel measures, ns per run and step: passive 76,
#: skyhook hi-lo SCM 81 / ACM 89, inverse hi-lo SCM 101 / ACM 91, sliding mode SCM 104 /
#: ACM 110
LAW_COST = {CK.C_POLICY: 1.08, CK.C_INVERSE_HILO: 1.25, CK.C_SLIDING: 1.37}
ACM_COST = 0.08
#: a step of a run on its own (the scalar kernel) against a run's step in lanes: measured
#: 170-185 ns (passive, hi-lo) and 212-220 ns (inverse laws) against the figures above
SINGLE_COST = 1.7


def batch_cost(
    simulations: Sequence[LaneRun], batch: Sequence[int], dt: float, duration: float | None
) -> float:
    """Estimated CPU of a batch (:func:`plan_batches`), in steps of a passive run in lanes.

    The runs' steps (``duration``, or each excitation's own) times the controller's
    :data:`LAW_COST` (plus :data:`ACM_COST`), times :data:`SINGLE_COST` for a run on
    its own. Idle lanes cost
    next to nothing, so a lane batch costs the sum over its runs. For ordering batches
    (costliest first), not a prediction of seconds.

    Examples
    --------
    >>> from mrsuspension.control import SlidingMode
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> sims = [Simulation(Harmonic(2.0, 0.01)), Simulation(Harmonic(2.0, 0.01), controller=SlidingMode())]
    >>> batch_cost(sims, [0], 1e-4, 1.0), batch_cost(sims, [1], 1e-4, 1.0)
    (17000.0, 23290.0)
    """
    if not batch:
        return 0.0
    first = simulations[batch[0]]
    try:
        arrays = first.kernel_arrays(first.check_dt(dt), check_stability=False)
    except Exception:  # a bad dt is reported by the run itself
        kind, acm = -1, False
    else:
        kind = int(arrays.controller_kind)
        acm = kind != CK.C_PASSIVE and float(arrays.controller_params[P_P]) != 1.0
    steps = (
        sum(
            float(duration if duration is not None else simulations[j].excitation.duration)
            for j in batch
        )
        / dt
    )
    per_step = LAW_COST.get(kind, 1.0) + (ACM_COST if acm else 0.0)
    return steps * per_step * (SINGLE_COST if len(batch) == 1 else 1.0)


#: fewest runs worth a lane group: idle lanes cost next to nothing, so a few runs already
#: gain. Measured 2026-11-24, 5 s harmonic runs, ns per run and step in lanes against on
#: their own: 2 runs 152-200 against 167-224, 3 runs 118-167 against 165-222, 4 runs
#: 101-151 against 163-222 (passive, skyhook hi-lo, sliding mode)
MIN_GROUP = 3
#: most steps in one lane batch: a batch that records holds its records at once, about
#: 13 bytes per step at the default output rate (130 MB here; the roads come in chunks
#: of ROAD_CHUNK steps per lane); larger groups are split
MAX_BATCH_STEPS = 10_000_000


def plan_batches(
    simulations: Sequence[LaneRun], dt: float, duration: float | None, parts: int
) -> list[list[int]]:
    """Split runs into batches (lane groups and single runs), costliest first.

    Runs that share a :func:`lane_key` and number at least :data:`MIN_GROUP` become lane
    batches. A group is split (into batches of similar total length, at most one per
    :data:`MIN_GROUP` runs) only as far as needed to give each of ``parts`` workers a
    batch (the fewer the batches, the better the lanes are used) and to keep each batch
    under :data:`MAX_BATCH_STEPS` steps (records' memory). Every other run is a batch of its own.
    Each index appears once. The batches come costliest first (:func:`batch_cost`), the
    order to hand them to a pool in: the longest task starts first and the workers end
    together (longest-processing-time scheduling).

    Examples
    --------
    >>> from mrsuspension.engine import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.dampers import LinearViscous
    >>> sims = [Simulation(Harmonic(f, 0.01)) for f in range(1, 21)]
    >>> sims.append(Simulation(Harmonic(1.0, 0.01), damper=LinearViscous(damping=1000.0)))
    >>> batches = plan_batches(sims, 1e-4, None, parts=2)  # two lane batches and one run
    >>> [len(b) for b in batches]
    [11, 9, 1]
    >>> [round(sum(sims[j].excitation.duration for j in b)) for b in batches[:2]]  # seconds
    [82, 76]
    """
    groups: dict[Any, list[int]] = {}
    singles: list[list[int]] = []
    for j, sim in enumerate(simulations):
        try:
            key = lane_key(sim, sim.check_dt(dt))
        except Exception:  # a bad dt is reported by the run itself
            key = None
        if key is None:
            singles.append([j])
        else:
            groups.setdefault(key, []).append(j)
    batches: list[list[int]] = []
    eligible = [m for m in groups.values() if len(m) >= MIN_GROUP]
    # as few parts as keep every worker busy: a lane batch needs many more runs than
    # lanes, else its longest run sets its length while the other lanes idle
    share = -(-parts // max(1, len(eligible)))
    for members in groups.values():
        if len(members) < MIN_GROUP:
            singles.extend([j] for j in members)
            continue
        length = {
            j: float(duration if duration is not None else simulations[j].excitation.duration)
            for j in members
        }
        steps = sum(length.values()) / dt
        wanted = max(share, math.ceil(steps / MAX_BATCH_STEPS))
        n_parts = max(1, min(wanted, len(members) // MIN_GROUP))
        bins: list[list[int]] = [[] for _ in range(n_parts)]
        load = [0.0] * n_parts
        for j in sorted(members, key=lambda m: -length[m]):  # longest first, least loaded
            b = load.index(min(load))
            bins[b].append(j)
            load[b] += length[j]
        batches.extend(bins)  # each longest first: the lanes' tail is the short runs
    batches += singles
    cost = [batch_cost(simulations, b, dt, duration) for b in batches]
    order = sorted(range(len(batches)), key=lambda b: -cost[b])  # stable: ties keep order
    return [batches[b] for b in order]
