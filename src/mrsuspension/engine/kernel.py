"""The compiled quarter-car step: one function shared by offline runs and the HiL loop.

Performance note: the entry points are compiled without numba's reference counting
(``_nrt=False``, so they allocate nothing: work arrays come from the caller) and the
kernels they call are compiled once each and inlined by LLVM
(:data:`~mrsuspension._numba_cache.INLINED`; numba's own ``inline="always"`` made the
first compile of :func:`run` take 17 s instead of 6). With reference counting on, the
branches over model kinds kept numba from pruning the per-call reference counts of the
array arguments, which cost ~30x in the step (measured: 3 ns against 90-110 ns per
rates evaluation).

The RK4 stages run in scalars (:func:`accelerations` takes and returns floats): the
stage values stay in registers instead of round trips through a work array. The four
stages and the evaluation at the new state share one call site in a loop: writing them
out gave no measurable gain and doubled the compile time (54 s against 26 s). The damper's tanh is :func:`~mrsuspension.dampers.kernels.fast_tanh` (one exp;
libm's went through expm1) and the rates multiply by reciprocal masses, which takes the
divisions off the chain of dependent operations from one stage to the next. Measured
per step (same process, min of 11): 0.58x (passive), 0.63x (hi-lo policy I) and
0.68x (sliding mode) the time of the previous array-based step with libm's tanh.

Model reference, sections 4-7. State ``y = [z_s, z_s', z_u, z_u', z_s0, z_s0']`` (the last
two are the sliding-mode controller's single-DOF reference model, integrated with the
plant).
A step of length ``dt``:

1. latch the damper internals (peak velocity, ``sgn(a_d)``) and the controller's peak
   velocity from the sampled state, using the **previous step's** acceleration ``a_d``
   (a sampled controller has nothing newer; model reference, sections 2.4 and 7);
2. run the controller once: drive current ``i_d``, held over the step (zero-order hold);
3. classical RK4 over the step with the road at ``t``, ``t + dt/2`` and ``t + dt``;
4. evaluate the rates at the new state (accelerations, forces for the record and the
   next step's ``a_d``), then advance the damper's internal dynamics.

:func:`run` is the one drive loop of an offline run (start, step, limit checks,
decimation): each output sample either fills a row of the record or, for a run reduced
to its measures (:mod:`mrsuspension.engine.reduced`), goes to the accumulators
(:func:`accumulate`, also the lanes' and every vehicle corner's), behind one flag
(:func:`output`; :func:`recording` and :func:`reducing` give the arguments of either).

Arrays: the state ``y`` and the vehicle's ``vp`` have the layouts of
:mod:`mrsuspension.vehicle.kernel`, the controller's ``cp`` (and the codes ``ck``,
``fk``) those of :mod:`mrsuspension.control.kernel`, the damper's and the estimators'
those of :mod:`mrsuspension.dampers.kernels`; ``mem`` (``M_*`` below) holds the values
carried between steps and the step's outputs, ``scratch`` is work space
(``SCRATCH_SIZE``; used by :func:`start`, kept in :func:`step`'s signature). The entry
points take them positionally (numba needs arrays);
:class:`~mrsuspension.engine.arrays.KernelArrays` names them and unpacks them in one
place (:meth:`~mrsuspension.engine.arrays.KernelArrays.args`).

The layouts belong to their families (the engine only inlines their kernels): adding a
controller touches :mod:`mrsuspension.control` only.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import INLINED, invalidate_if_changed
from mrsuspension.control import kernel as CK
from mrsuspension.control import signals as SG
from mrsuspension.control.kernel import EST_SHARED, F_EXTERNAL, F_MODEL, F_TARGET, P_C0, P_CS, P_MS0
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.vehicle import kernel as VK
from mrsuspension.vehicle.kernel import (
    NY,
    V_CSKY,
    V_CT,
    V_DXU,
    V_G,
    V_KS,
    V_KT,
    V_MS,
    V_MU,
    plant_rates,
)

# the cached entry points below inline the damper, shaping, controller and vehicle kernels
invalidate_if_changed(
    __file__, DK.__file__, _shaping.__file__, CK.__file__, VK.__file__, SG.__file__
)

# mem: carried between steps and outputs of the last step
(
    M_AD,  # previous a_d [m/s^2]
    M_ID,  # drive current i_d [A] (held)
    M_IZ,  # controller current i_z [A]
    M_ZC,  # switching condition z_c
    M_TARGET,  # target force F* [N] (NaN: none)
    M_VM,  # controller's peak velocity v_m [m/s]
    M_FEXT,  # external force [N] for F_EXTERNAL
    M_AS,  # z_s'' at the end of the step
    M_AU,  # z_u'' at the end of the step
    M_FD,  # F_d at the end of the step
    M_FT,  # F_T at the end of the step
    M_A0,  # z_s0'' (reference) at the end of the step
    M_STEP,  # steps done since start() (the control sample's time: M_STEP dt)
) = range(13)
M_PH = 13  # first of DK.PH_SIZE slots: the control laws' memo of the damper's v_m terms
#: first of SG.NS slots: the signals the law saw at the last control sample
#: (:mod:`mrsuspension.control.signals`)
M_SIG = M_PH + DK.PH_SIZE
#: the drive current's chatter (:func:`note_current`): the previous step's current [A],
#: its last change [A] (0 when smaller than :data:`CHATTER_CURRENT`) and the count of
#: steps whose change reversed the one before (a current that alternates at the step rate)
M_IPREV = M_SIG + SG.NS
M_DI = M_IPREV + 1
M_NREV = M_IPREV + 2
MEM_SIZE = M_IPREV + 3
#: a change of the drive current [A] that counts towards its chatter (1 % of 0.5 A)
CHATTER_CURRENT = 0.005

SCRATCH_SIZE = 6 * NY  # work space of the callers (rates of start())


@njit(cache=True, **INLINED)
def accelerations(
    zs: float,
    vs: float,
    zu: float,
    vu: float,
    z0: float,
    v0: float,
    zr: float,
    zrd: float,
    vp: np.ndarray,
    fk: int,
    dk: int,
    dp: np.ndarray,
    ds: np.ndarray,
    cp: np.ndarray,
    mem: np.ndarray,
    reference: bool,
) -> tuple[float, float, float, float, float]:
    """``(z_s'', z_u'', z_s0'', F_d, F_T)`` at a state (the other rates are velocities).

    Scalars in and out, so that the RK4 stages of :func:`step` stay in registers.
    """
    xd = zu - zs
    vd = vu - vs
    if fk == F_MODEL:
        fd = DK.damper_force(dk, dp, ds, xd, vd, mem[M_ID])
    elif fk == F_EXTERNAL:
        fd = mem[M_FEXT]
    elif fk == F_TARGET:  # an ideal actuator: the law's force (C_USER_ACTIVE)
        fd = mem[M_TARGET]
    else:  # an ideal dissipative damper (the ideal reference laws)
        fd = CK.ideal_force(fk, cp, vs, xd, vd)
    # multiply by the reciprocal masses: their divisions depend on parameters only, so
    # they leave the chain of dependent operations from one RK4 stage to the next
    a_s, a_u, a_0, ft = plant_rates(
        zs, vs, zu, vu, z0, v0, zr, zrd, fd, vp[V_KS], vp[V_CSKY], 1.0 / vp[V_MS],
        1.0 / vp[V_MU], (vp[V_MS] + vp[V_MU]) * vp[V_G], vp[V_KT], vp[V_CT], vp[V_DXU],
        reference, cp[P_C0], cp[P_CS], 1.0 / cp[P_MS0] if reference else 0.0,
    )  # fmt: skip
    return a_s, a_u, a_0, fd, ft


@njit(cache=True, **INLINED)
def rates(
    y: np.ndarray,
    zr: float,
    zrd: float,
    vp: np.ndarray,
    fk: int,
    dk: int,
    dp: np.ndarray,
    ds: np.ndarray,
    cp: np.ndarray,
    mem: np.ndarray,
    reference: bool,
    dy: np.ndarray,
) -> tuple[float, float]:
    """Time derivatives of ``y`` into ``dy``; returns (F_d, F_T)."""
    a_s, a_u, a_0, fd, ft = accelerations(
        y[0], y[1], y[2], y[3], y[4], y[5], zr, zrd, vp, fk, dk, dp, ds, cp, mem, reference
    )
    dy[0] = y[1]
    dy[1] = a_s
    dy[2] = y[3]
    dy[3] = a_u
    dy[4] = y[5] if reference else 0.0
    dy[5] = a_0
    return fd, ft


@njit(cache=True, **INLINED)
def apply_control(
    ck: int,
    cp: np.ndarray,
    vp: np.ndarray,
    dp: np.ndarray,
    y: np.ndarray,
    ad: float,
    vm: float,
    mem: np.ndarray,
) -> None:
    """Run the control law (:func:`mrsuspension.control.kernel.control`) into ``mem``.

    ``y``: the signals the law sees (:mod:`mrsuspension.control.signals`; the built-in
    laws read the first six, the quarter-car view). A user law (``C_USER_*``) runs
    through :func:`~mrsuspension.control.kernel.user_control` and needs every signal.
    Sets ``mem[M_ID]`` (held over the step), ``M_IZ``, ``M_ZC`` and ``M_TARGET``, and
    keeps the law's memo at ``M_PH`` (emptied by :func:`start`).
    """
    memo = mem[M_PH : M_PH + DK.PH_SIZE]
    if ck >= CK.C_USER_CURRENT:  # (reads every signal: C_SIGNALS and up)
        i_d, i_z, z_c, target = CK.user_control(ck, cp, dp, y, ad, vm, memo)
    else:
        i_d, i_z, z_c, target = CK.control(ck, cp, vp, dp, y, ad, vm, memo)
    mem[M_ID] = i_d
    mem[M_IZ] = i_z
    mem[M_ZC] = z_c
    mem[M_TARGET] = target


@njit(cache=True, **INLINED)
def chatter(i: float, previous: float, change: float, count: float) -> tuple[float, float]:
    """This step's change of the drive current and the updated count of reversals.

    ``i``: this step's current (the law's, final) [A]; ``previous``: the step before's;
    ``change``: the step before's change (0 when it was at most :data:`CHATTER_CURRENT`);
    ``count``: the steps so far whose change reversed the step before's. A change of
    more than :data:`CHATTER_CURRENT` opposite to ``change`` adds one. A law that
    alternates its current at every step counts about one per step; a record that keeps
    one step in several then aliases it (:func:`~mrsuspension.engine.result.warn_if_aliased`).
    The callers keep the state in ``mem[M_IPREV]``, ``mem[M_DI]``, ``mem[M_NREV]``
    (:func:`note_current`).

    Examples
    --------
    >>> chatter(0.5, 0.0, -0.5, 3.0)  # up after a step down: a reversal
    (0.5, 4.0)
    >>> chatter(0.501, 0.5, 0.5, 4.0)  # 1 mA: no change, and the alternation is broken
    (0.0, 4.0)
    """
    d = i - previous
    if abs(d) > CHATTER_CURRENT:
        return d, count + 1.0 if d * change < 0.0 else count
    return 0.0, count


@njit(cache=True, **INLINED)
def note_current(mem: np.ndarray) -> None:
    """:func:`chatter` on a quarter-car ``mem`` (after the law set ``mem[M_ID]``).

    Examples
    --------
    >>> mem = np.zeros(MEM_SIZE)
    >>> for i in (0.0, 0.5, 0.0, 0.5, 0.5, 0.0):
    ...     mem[M_ID] = i
    ...     note_current(mem)
    >>> float(mem[M_NREV])  # 0 -> 0.5 -> 0 -> 0.5 reverses twice; then held, then down
    2.0
    """
    i = mem[M_ID]
    mem[M_DI], mem[M_NREV] = chatter(i, mem[M_IPREV], mem[M_DI], mem[M_NREV])
    mem[M_IPREV] = i


@njit(cache=True, **INLINED)
def step(
    y: np.ndarray,
    dt: float,
    zr0: float,
    zrd0: float,
    zr1: float,
    zrd1: float,
    zr2: float,
    zrd2: float,
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
    scratch: np.ndarray,
) -> None:
    """Advance ``y`` by one step; road at t (0), t + dt/2 (1), t + dt (2)."""
    xd = y[2] - y[0]
    vd = y[3] - y[1]
    ad = mem[M_AD]
    DK.damper_sample(dk, dp, ds, dek, dep, des, xd, vd, ad, mem[M_ID])
    # EST_SHARED: the damper's own estimate (same estimator, same samples)
    vm = ds[DK.WS_VM] if cek == EST_SHARED else DK.estimator_update(cek, cep, ces, xd, vd, ad)
    mem[M_VM] = vm
    count = mem[M_STEP]
    mem[M_STEP] = count + 1.0
    if ck >= CK.C_SIGNALS:  # the signals at this control sample (the previous step's
        # rates, force and current); the laws below C_SIGNALS read the state's view
        sig = mem[M_SIG : M_SIG + SG.NS]
        SG.fill_corner(
            sig, y[0], y[1], y[2], y[3], y[4], y[5], mem[M_AS], mem[M_AU], mem[M_FD],
            mem[M_ID], vm, count * dt,
        )  # fmt: skip
        sig[SG.S_HEAVE] = y[0]
        sig[SG.S_VHEAVE] = y[1]
        sig[SG.S_AHEAVE] = mem[M_AS]
        apply_control(ck, cp, vp, dp, sig, ad, vm, mem)
    else:
        apply_control(ck, cp, vp, dp, y, ad, vm, mem)
    note_current(mem)
    reference = CK.needs_reference(ck)
    # classical RK4 in scalars; the four stages and the evaluation at the new state share
    # one call site of accelerations() (small inlined code, short compile). k_j is
    # (velocities, accelerations) at stage j; acc = k1 + 2 k2 + 2 k3 + k4 accumulated in
    # that order. The reference model's rates are zero unless sliding mode uses it.
    zs, vs, zu, vu, z0, v0 = y[0], y[1], y[2], y[3], y[4], y[5]
    # stage state and its rates
    tzs, tvs, tzu, tvu, tz0, tv0 = zs, vs, zu, vu, z0, v0
    kas = kau = ka0 = 0.0
    azs = avs = azu = avu = az0 = av0 = 0.0
    fd = ft = 0.0
    c = dt / 6.0
    for st in range(5):
        if st == 0:
            zr, zrd = zr0, zrd0
        elif st < 3:
            zr, zrd = zr1, zrd1
        else:
            zr, zrd = zr2, zrd2
        if st > 0:
            h = dt if st >= 3 else 0.5 * dt
            w = tv0 if reference else 0.0
            if st < 4:
                tzs, tvs, tzu, tvu = zs + h * tvs, vs + h * kas, zu + h * tvu, vu + h * kau
                tz0, tv0 = z0 + h * w, v0 + h * ka0
            else:
                zs += c * azs
                vs += c * avs
                zu += c * azu
                vu += c * avu
                z0 += c * az0
                v0 += c * av0
                tzs, tvs, tzu, tvu, tz0, tv0 = zs, vs, zu, vu, z0, v0
        kas, kau, ka0, fd, ft = accelerations(
            tzs, tvs, tzu, tvu, tz0, tv0, zr, zrd, vp, fk, dk, dp, ds, cp, mem, reference
        )
        w = tv0 if reference else 0.0
        if st == 0:
            azs, avs, azu, avu, az0, av0 = tvs, kas, tvu, kau, w, ka0
        elif st < 3:
            azs += 2.0 * tvs
            avs += 2.0 * kas
            azu += 2.0 * tvu
            avu += 2.0 * kau
            az0 += 2.0 * w
            av0 += 2.0 * ka0
        elif st == 3:
            azs += tvs
            avs += kas
            azu += tvu
            avu += kau
            az0 += w
            av0 += ka0
    y[0], y[1], y[2], y[3], y[4], y[5] = zs, vs, zu, vu, z0, v0
    s5, u5, r5 = kas, kau, ka0
    mem[M_AS] = s5
    mem[M_AU] = u5
    mem[M_A0] = r5
    mem[M_FD] = fd
    mem[M_FT] = ft
    mem[M_AD] = u5 - s5
    DK.damper_advance(dk, dp, ds, xd, vd, mem[M_ID], dt)


# recorded signals (columns of the record)
(
    R_ZS, R_VS, R_ZU, R_VU, R_ZR, R_VR, R_AS, R_AU, R_FD, R_FT,
    R_ID, R_IZ, R_ZC, R_TARGET, R_VM, R_ZS0,
) = range(16)  # fmt: skip
N_REC = 16


# inlined by numba: called with literal row numbers, as a function of its own it would be
# compiled once per literal
@njit(cache=True, inline="always")
def record(
    rec: np.ndarray, row: int, y: np.ndarray, zr: float, zrd: float, mem: np.ndarray
) -> None:
    rec[row, R_ZS] = y[0]
    rec[row, R_VS] = y[1]
    rec[row, R_ZU] = y[2]
    rec[row, R_VU] = y[3]
    rec[row, R_ZR] = zr
    rec[row, R_VR] = zrd
    rec[row, R_AS] = mem[M_AS]
    rec[row, R_AU] = mem[M_AU]
    rec[row, R_FD] = mem[M_FD]
    rec[row, R_FT] = mem[M_FT]
    rec[row, R_ID] = mem[M_ID]
    rec[row, R_IZ] = mem[M_IZ]
    rec[row, R_ZC] = mem[M_ZC]
    rec[row, R_TARGET] = mem[M_TARGET]
    rec[row, R_VM] = mem[M_VM]
    rec[row, R_ZS0] = y[4]


@njit(cache=True, **INLINED)
def start(
    y: np.ndarray,
    zr: float,
    zrd: float,
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
    scratch: np.ndarray,
) -> None:
    """Initial accelerations and forces (for the record and the first step's a_d).

    Takes the arrays of :func:`step` (the controller estimator's are not used here).
    Empties the control law's memo (a new run, perhaps of another damper).
    """
    mem[M_PH + DK.PH_FT] = 0.0
    mem[M_STEP] = 0.0
    mem[M_IPREV] = mem[M_ID]  # the chatter count of this run (note_current)
    mem[M_DI] = 0.0
    mem[M_NREV] = 0.0
    if fk == F_TARGET:  # an ideal actuator starts with no force (the law acts from step 1)
        mem[M_TARGET] = 0.0
    for q in range(SG.NS):  # the quarter car's pitch, roll and corner stay 0
        mem[M_SIG + q] = 0.0
    DK.damper_sample(dk, dp, ds, dek, dep, des, y[2] - y[0], y[3] - y[1], 0.0, mem[M_ID])
    fd, ft = rates(y, zr, zrd, vp, fk, dk, dp, ds, cp, mem, CK.needs_reference(ck), scratch[0:NY])
    mem[M_AS] = scratch[1]
    mem[M_AU] = scratch[3]
    mem[M_A0] = scratch[5]
    mem[M_FD] = fd
    mem[M_FT] = ft
    mem[M_AD] = scratch[3] - scratch[1]


# divergence limits: which signal ran away
D_OK, D_STATE, D_FORCE, D_TIRE = 0, 1, 2, 3
#: Divergence limits (``limits`` of :func:`check_limits`): |z| [m], |z'| [m/s], |F_d| [N], F_T [N].
LIMITS = np.array([10.0, 100.0, 1e6, 1e7])


@njit(cache=True, **INLINED)
def check_limits(y: np.ndarray, mem: np.ndarray, limits: np.ndarray) -> tuple[int, int, float]:
    """``(status, index, value)`` of the first state or force out of ``limits`` (D_OK: none).

    ``limits = [max |z|, max |z'|, max |F_d|, max F_T]``; a non-finite state is out.
    """
    for q in range(NY):
        if not math.isfinite(y[q]):
            return D_STATE, q, y[q]
    for q in (0, 2, 4):
        if abs(y[q]) > limits[0]:
            return D_STATE, q, y[q]
        if abs(y[q + 1]) > limits[1]:
            return D_STATE, q + 1, y[q + 1]
    if not abs(mem[M_FD]) <= limits[2]:
        return D_FORCE, 0, mem[M_FD]
    if not mem[M_FT] <= limits[3]:
        return D_TIRE, 0, mem[M_FT]
    return D_OK, 0, 0.0


# accumulators of one reduced run (a row of N_ACC floats; engine.reduced plans and
# finishes the reduction)
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


# compiled once and inlined by LLVM (numba's IR inlining of its call sites here, in the
# vehicle kernel and in the lane kernel cost compile time); whether the sample is in the
# steady window comes as a bool: a literal row number would compile a specialisation
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
    :attr:`~mrsuspension.engine.reduced.Reduction.window_start`); ``shift`` is subtracted
    from ``F_T`` before summing; ``v_m >= threshold`` counts as at the clamp.

    The signals are those :meth:`~mrsuspension.engine.Simulation.result_from_record`
    reads from a record row, computed the same way (``y`` in the quarter car's layout:
    a vehicle corner passes its quarter-car view).
    """
    zs = y[0]
    zu = y[2]
    xd = zu - zs
    a_s = mem[M_AS]
    a_u = mem[M_AU]
    fd = mem[M_FD]
    i = mem[M_ID]
    d = mem[M_FT] - shift
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
    acc[A_FTMAX] = max(acc[A_FTMAX], mem[M_FT])
    if mem[M_VM] >= threshold:
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


# inlined by numba: called with literal row numbers (see record)
@njit(cache=True, inline="always")
def output(
    reduced: bool,
    rec: np.ndarray,
    acc: np.ndarray,
    trace: np.ndarray,
    row: int,
    in_window: bool,
    shift: float,
    threshold: float,
    y: np.ndarray,
    zr: float,
    zrd: float,
    mem: np.ndarray,
) -> None:
    """Output sample ``row``: a record row, or (``reduced``) the accumulators ``acc``
    (:func:`accumulate`) and, with a non-empty ``trace``, ``z_s''`` into ``trace[row]``."""
    if reduced:
        accumulate(acc, in_window, shift, threshold, y, zr, mem)
        if trace.size > 0:
            trace[row] = mem[M_AS]
    elif row < rec.shape[0]:
        record(rec, row, y, zr, zrd, mem)


@njit(cache=True, **NO_REFCOUNT)
def run(
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
    limits: np.ndarray,
    scratch: np.ndarray,
    reduced: bool,
    rec: np.ndarray,
    acc: np.ndarray,
    window_start: int,
    shift: float,
    threshold: float,
    trace: np.ndarray,
) -> tuple[int, int, int, float]:
    """``n_steps`` steps with the road sampled every dt/2 (``zr``, ``zrd``: 2 n + 1 values).

    The quarter car's one drive loop. The output samples are the initial state and every
    ``decimate`` steps; each is a row of the record ``rec`` or, with ``reduced``, goes to
    the accumulators ``acc`` (:data:`N_ACC` values; steady window from output row
    ``window_start``, ``shift`` and ``threshold`` as :func:`accumulate` takes them) and,
    when ``trace`` is not empty, its ``z_s''`` to ``trace`` (see :func:`output`; the
    unused ones may be empty). Returns ``(status, step, index, value)``: status 0 when
    every state stayed finite and within ``limits = [max |z|, max |z'|, max |F_d|, max
    F_T]``, else the first offence. ``scratch`` is work space of ``SCRATCH_SIZE``.
    """
    start(y, zr[0], zrd[0], vp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces, mem, scratch)
    output(reduced, rec, acc, trace, 0, window_start <= 0, shift, threshold, y, zr[0], zrd[0], mem)
    row = 1
    for k in range(n_steps):
        j = 2 * k
        step(
            y, dt, zr[j], zrd[j], zr[j + 1], zrd[j + 1], zr[j + 2], zrd[j + 2], vp, fk, dk, dp,
            ds, dek, dep, des, ck, cp, cek, cep, ces, mem, scratch,
        )  # fmt: skip
        status, q, value = check_limits(y, mem, limits)
        if status != D_OK:
            return status, k + 1, q, value
        if (k + 1) % decimate == 0:
            output(
                reduced, rec, acc, trace, row, row >= window_start, shift, threshold, y,
                zr[j + 2], zrd[j + 2], mem,
            )  # fmt: skip
            row += 1
    return D_OK, n_steps, 0, 0.0


def recording(rec: np.ndarray) -> tuple[Any, ...]:
    """The output arguments of :func:`run` (``reduced`` to ``trace``) that fill the record
    ``rec`` (rows of :data:`N_REC` columns)."""
    return (False, rec, np.zeros(N_ACC), 0, 0.0, math.inf, np.zeros(0))


def reducing(
    acc: np.ndarray, window_start: int, shift: float, threshold: float, trace: np.ndarray
) -> tuple[Any, ...]:
    """The output arguments of :func:`run` (``reduced`` to ``trace``) that reduce the run
    into the accumulators ``acc`` (and ``trace``, possibly empty) instead of recording."""
    return (True, np.zeros((0, N_REC)), acc, window_start, shift, threshold, trace)
