"""The compiled quarter-car step: one function shared by offline runs and the HiL loop.

Performance note: the entry points are compiled without numba's reference counting
(``_nrt=False``, so they allocate nothing: work arrays come from the caller) and the
kernels they call are inlined (``inline="always"``). With reference counting on, the
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

Spec sections 4-7. State ``y = [z_s, z_s', z_u, z_u', z_s0, z_s0']`` (the last two are
the sliding-mode controller's single-DOF reference model, integrated with the plant).
A step of length ``dt``:

1. latch the damper internals (peak velocity, ``sgn(a_d)``) and the controller's peak
   velocity from the sampled state, using the **previous step's** acceleration ``a_d``
   (a sampled controller has nothing newer; spec sections 2.4 and 7);
2. run the controller once: drive current ``i_d``, held over the step (zero-order hold);
3. classical RK4 over the step with the road at ``t``, ``t + dt/2`` and ``t + dt``;
4. evaluate the rates at the new state (accelerations, forces for the record and the
   next step's ``a_d``), then advance the damper's internal dynamics.

Arrays (layouts by the index constants below): ``vp`` vehicle, ``cp`` controller,
``mem`` values carried between steps and the step's outputs, ``scratch`` work space
(``SCRATCH_SIZE``; used by :func:`start`, kept in :func:`step`'s signature), plus the damper arrays of :mod:`mrsuspension.dampers.kernels`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import invalidate_if_changed
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.shaping import drive_current_kernel, onoff_kernel

# the cached entry points below inline the damper and shaping kernels
invalidate_if_changed(__file__, DK.__file__, _shaping.__file__)

# vehicle parameters (QuarterCar.params)
V_MS, V_MU, V_KS, V_KT, V_CT, V_CSKY, V_G, V_DXU = range(8)

# controller codes
C_PASSIVE = 0
C_ONOFF_ADFG = 1
C_POLICY = 2
C_INVERSE_HILO = 3
C_SLIDING = 4
C_IDEAL_SKYHOOK = 5
C_IDEAL_ONOFF = 6

# controller parameters
(
    P_CURRENT,  # passive current / on-off high current [A]
    P_GAIN,  # k_c
    P_ORDER,  # n
    P_POLICY,  # 1..4
    P_P,  # ADFG asymmetry p (1: SCM, 0: ACM)
    P_XI,  # ADFG smoothing xi
    P_PC,  # CM asymmetry p_c
    P_XIC,  # CM smoothing xi_c
    P_IMAX,  # i_max [A]
    P_LAMBDA,  # sliding surface slope
    P_EPS,  # boundary layer
    P_PHI,  # sliding condition gain
    P_BETA,  # mass uncertainty bound
    P_MS0,  # nominal sprung mass [kg]
    P_CS,  # skyhook damping c_s [N s/m]
    P_C0,  # passive damping c_0 [N s/m]
    P_INV_HYST,  # inverse controllers: 1 = hysteretic inverse model, 0 = mean (v_h = 0)
) = range(17)
CP_SIZE = 17

# force source in the rates
F_MODEL = 0  # the damper model at the held current
F_SKYHOOK = 1  # ideal skyhook (3.12) through an ideal dissipative damper
F_ONOFF = 2  # Rakheja displacement on-off (3.13) through an ideal dissipative damper
F_EXTERNAL = 3  # a given force held over the step (hardware in the loop)

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
) = range(12)
MEM_SIZE = 12

#: controller estimator code meaning "use the damper's latched v_m" (dissertation's model)
EST_SHARED = -1

NY = 6
SCRATCH_SIZE = 6 * NY  # work space of the callers (rates of start())


@njit(cache=True, inline="always")
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
    elif fk == F_SKYHOOK:
        # (3.12) in the up-positive frame: -c_s z_s' when z_s' v_d < 0, else 0
        fd = -cp[P_CS] * vs if vs * vd < 0.0 else 0.0
    elif fk == F_ONOFF:
        # (3.13): c_s v_d when x_d v_d < 0, else 0
        fd = cp[P_CS] * vd if xd * vd < 0.0 else 0.0
    else:
        fd = mem[M_FEXT]
    # multiply by the reciprocal masses: their divisions depend on parameters only, so
    # they leave the chain of dependent operations from one RK4 stage to the next
    a_s, a_u, a_0, ft = plant_rates(
        zs, vs, zu, vu, z0, v0, zr, zrd, fd, vp[V_KS], vp[V_CSKY], 1.0 / vp[V_MS],
        1.0 / vp[V_MU], (vp[V_MS] + vp[V_MU]) * vp[V_G], vp[V_KT], vp[V_CT], vp[V_DXU],
        reference, cp[P_C0], cp[P_CS], 1.0 / cp[P_MS0] if reference else 0.0,
    )  # fmt: skip
    return a_s, a_u, a_0, fd, ft


@njit(cache=True, inline="always")
def plant_rates(
    zs: float,
    vs: float,
    zu: float,
    vu: float,
    z0: float,
    v0: float,
    zr: float,
    zrd: float,
    fd: float,
    ks: float,
    csky: float,
    inv_ms: float,
    inv_mu: float,
    weight: float,
    kt: float,
    ct: float,
    dxu: float,
    reference: bool,
    c0: float,
    cs: float,
    inv_ms0: float,
) -> tuple[float, float, float, float]:
    """``(z_s'', z_u'', z_s0'', F_T)`` given the damper force: the quarter car of spec 4.

    The one place the vehicle's equations are written, for :func:`accelerations` and the
    lane kernel alike. Branch-free (selects), so that a loop over independent cars
    compiles to vector instructions. ``weight = (m_s + m_u) g``; the tire force is zero
    when the tire has lifted off (``delta <= 0``) and never pulls.
    """
    xd = zu - zs
    delta = zr - zu + dxu
    ft = kt * delta + ct * (zrd - vu)
    ft = 0.0 if ft < 0.0 else ft
    ft = ft if delta > 0.0 else 0.0
    spring = ks * xd
    a_s = (spring + fd - csky * vs) * inv_ms
    a_u = (ft - weight - spring - fd) * inv_mu
    # single-DOF modified-skyhook reference (3.18), driven by the plant's z_u
    a_0 = (-c0 * (v0 - vu) - cs * v0 - ks * (z0 - zu)) * inv_ms0 if reference else 0.0
    return a_s, a_u, a_0, ft


@njit(cache=True, inline="always")
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


@njit(cache=True, inline="always")
def control(
    ck: int,
    cp: np.ndarray,
    vp: np.ndarray,
    dp: np.ndarray,
    y: np.ndarray,
    ad: float,
    vm: float,
    mem: np.ndarray,
) -> None:
    """Controller (spec section 6): sets mem[M_ID], M_IZ, M_ZC, M_TARGET."""
    zs, vs, zu, vu = y[0], y[1], y[2], y[3]
    xd = zu - zs
    vd = vu - vs
    imax = cp[P_IMAX]
    iz = 0.0
    zc = math.nan
    target = math.nan
    if ck == C_PASSIVE:
        mem[M_ID] = min(cp[P_CURRENT], imax)
        mem[M_IZ] = mem[M_ID]
        mem[M_ZC] = zc
        mem[M_TARGET] = target
        return
    if ck == C_ONOFF_ADFG:
        # (2.1): p i_H in compression, i_H otherwise
        i = onoff_kernel(cp[P_CURRENT], vd, cp[P_P])
        mem[M_ID] = min(max(i, 0.0), imax)
        mem[M_IZ] = cp[P_CURRENT]
        mem[M_ZC] = zc
        mem[M_TARGET] = target
        return
    if ck == C_IDEAL_SKYHOOK:
        mem[M_ID] = 0.0
        mem[M_IZ] = 0.0
        mem[M_ZC] = vs * vd
        mem[M_TARGET] = -cp[P_CS] * vs
        return
    if ck == C_IDEAL_ONOFF:
        mem[M_ID] = 0.0
        mem[M_IZ] = 0.0
        mem[M_ZC] = xd * vd
        mem[M_TARGET] = cp[P_CS] * vd
        return
    sgn_a = DK.sign(ad)
    if ck == C_POLICY:
        policy = int(cp[P_POLICY])
        if policy == 1:
            sig = vs
            zc = vs * vd
        elif policy == 2:
            sig = vd
            zc = vs * vd
        elif policy == 3:
            sig = vd
            zc = xd * vd
        else:
            sig = xd
            zc = xd * vd
        n = cp[P_ORDER]
        mag = abs(sig)
        if n == 2.0:
            iz = cp[P_GAIN] * mag * mag  # (3.15), the default order without pow()
        elif n == 1.0:
            iz = cp[P_GAIN] * mag
        else:
            iz = cp[P_GAIN] * mag**n
    elif ck == C_INVERSE_HILO:
        target = vp[V_KS] * xd  # F* = F_k, (3.17)
        sa = sgn_a * cp[P_INV_HYST]  # 0: the mean inverse model (v_h = 0)
        fh = DK.passive_hysteron(dp, vd, sa, vm)
        iz = DK.wang_inverse(dp, target, vd, sa, vm, imax)
        zc = fh * target
    else:  # C_SLIDING, (3.19)-(3.35) in the up-positive frame (erratum 4)
        z0, v0 = y[4], y[5]
        ms0 = cp[P_MS0]
        a0 = (-cp[P_C0] * (v0 - vu) - cp[P_CS] * v0 - vp[V_KS] * (z0 - zu)) / ms0
        e = zs - z0
        ed = vs - v0
        lam = cp[P_LAMBDA]
        s = ed + lam * e
        fd0 = -vp[V_KS] * xd + ms0 * a0 - ms0 * lam * ed
        beta = cp[P_BETA]
        gain = ms0 * beta * cp[P_PHI] + (beta - 1.0) * (
            abs(fd0) + vp[V_KS] * abs(zs) + vp[V_KS] * abs(zu)
        )
        sat = s / cp[P_EPS]
        if sat > 1.0:
            sat = 1.0
        elif sat < -1.0:
            sat = -1.0
        target = fd0 - gain * sat  # (3.34), erratum 5
        sa = sgn_a * cp[P_INV_HYST]
        fh = DK.passive_hysteron(dp, vd, sa, vm)
        iz = DK.wang_inverse(dp, target, vd, sa, vm, imax)
        zc = -fh * target  # (3.35)
    # drive current (3.9)/(3.16)
    mem[M_ID] = drive_current_kernel(iz, vd, vm, zc, cp[P_P], cp[P_XI], cp[P_PC], cp[P_XIC], imax)
    mem[M_IZ] = iz
    mem[M_ZC] = zc
    mem[M_TARGET] = target


@njit(cache=True, inline="always", **NO_REFCOUNT)
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
    control(ck, cp, vp, dp, y, ad, vm, mem)
    reference = ck == C_SLIDING
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


@njit(cache=True, inline="always")
def _record(
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


@njit(cache=True, inline="always", **NO_REFCOUNT)
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
    mem: np.ndarray,
    scratch: np.ndarray,
) -> None:
    """Initial accelerations and forces (for the record and the first step's a_d)."""
    DK.damper_sample(dk, dp, ds, dek, dep, des, y[2] - y[0], y[3] - y[1], 0.0, mem[M_ID])
    fd, ft = rates(y, zr, zrd, vp, fk, dk, dp, ds, cp, mem, ck == C_SLIDING, scratch[0:NY])
    mem[M_AS] = scratch[1]
    mem[M_AU] = scratch[3]
    mem[M_A0] = scratch[5]
    mem[M_FD] = fd
    mem[M_FT] = ft
    mem[M_AD] = scratch[3] - scratch[1]


# divergence limits: which signal ran away
D_OK, D_STATE, D_FORCE, D_TIRE = 0, 1, 2, 3


@njit(cache=True, inline="always")
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
    rec: np.ndarray,
    limits: np.ndarray,
    scratch: np.ndarray,
) -> tuple[int, int, int, float]:
    """``n_steps`` steps with the road sampled every dt/2 (``zr``, ``zrd``: 2 n + 1 values).

    Records row 0 (initial state) and every ``decimate`` steps. Returns
    ``(status, step, index, value)``: status 0 when every state stayed finite and within
    ``limits = [max |z|, max |z'|, max |F_d|, max F_T]``, else the first offence.
    ``scratch`` is work space of ``SCRATCH_SIZE``.
    """
    start(y, zr[0], zrd[0], vp, fk, dk, dp, ds, dek, dep, des, ck, cp, mem, scratch)
    _record(rec, 0, y, zr[0], zrd[0], mem)
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
        if (k + 1) % decimate == 0 and row < rec.shape[0]:
            _record(rec, row, y, zr[j + 2], zrd[j + 2], mem)
            row += 1
    return D_OK, n_steps, 0, 0.0
