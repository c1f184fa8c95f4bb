"""The half and full car's compiled step: an MR damper and a controller at every corner.

The vehicle's equations are those of :mod:`mrsuspension.vehicle.body` (a rigid body on
a suspended wheel at every corner, tire lift-off at every wheel). A step follows the
quarter car's (:mod:`mrsuspension.engine.kernel`) corner by corner:

1. at every corner, latch the damper internals from the sampled stroke and velocity with
   the previous step's ``a_d``, update the controller's peak velocity and run the
   controller on the corner's quarter-car view ``[z_s,i, z_s,i', z_u,i, z_u,i', z_0,i,
   z_0,i']`` (the body's motion at the corner; :func:`~mrsuspension.engine.kernel.apply_control`),
   so every controller family acts per corner; the drive current is held over the step;
2. classical RK4 over the step with each wheel's road at ``t``, ``t + dt/2``, ``t + dt``;
3. evaluate the rates at the new state (record, next step's ``a_d``) and advance every
   damper's internal dynamics.

With sensing (``sk``/``sp``/``ss``, :class:`~mrsuspension.control.sensing.Sensing`), step 1
gives each corner's controller the body velocity estimated from the corner's acceleration
at the step's start (:func:`~mrsuspension.control.sensing.leaky_integrator_update` or
:func:`~mrsuspension.control.sensing.band_pass_update`, sampled every ``SK_ACC_EVERY``
steps and held) and the stroke sensor's reading
(:func:`~mrsuspension.control.sensing.stroke_sensor_update`); with a vehicle-level law
(``SK_LAW``) the corners' currents then come from
:func:`~mrsuspension.control.modal.modal_forces` (or ``F_i = -c_s v_i``) and
:func:`~mrsuspension.control.modal.modal_hilo`, or from the whole-vehicle LQ and LQG's
``F = -K x`` (:func:`~mrsuspension.control.vehicle_lq.lq_forces`: the state as seen, or
a Kalman estimate; or ``vehicle-mpc``'s QP through its entry,
:func:`~mrsuspension.control.vehicle_lq.mpc_forces`, held between solves; hi-lo on
Dyke's ``(F_i - F_d) F_d > 0``, a continuous current from each corner's inverse damper
model, :func:`~mrsuspension.control.kernel.track_force`, or ``F`` itself by an ideal
actuator). Ideal
sensing and no law leave the step exactly as before.

The damper kernels (:mod:`mrsuspension.dampers.kernels`) and the control laws
(:mod:`mrsuspension.control.kernel`) are the quarter car's; the sliding-mode reference
model (3.18) is integrated per corner with the corner's wheel.

Arrays of the compiled step (numba compiles over arrays; :class:`~mrsuspension.engine.vehicle.VehicleArrays` names
them): ``vp`` the vehicle (``B_*`` then ``CORNER_SIZE`` values per corner, ``C_*``);
``cvp`` every corner's quarter-car parameters (rows: :mod:`mrsuspension.vehicle.kernel`
``V_*``, for the control laws); per corner rows of the damper's, estimators' and
controller's arrays (padded to the longest); ``mem`` one row per corner with the quarter
car's layout (``engine.kernel.M_*``). State ``y``: ``[z, theta, phi, z', theta', phi']``
then ``[z_u, z_u', z_0, z_0']`` per corner.

:func:`run` is the one drive loop (start, step, limit checks, decimation), resumable so
that a run takes its road a piece at a time: each output sample fills a row of the record
or, reduced (``VehicleSimulation.run_measures``), goes to every corner's accumulators
(the quarter car's :func:`~mrsuspension.engine.kernel.accumulate` on the corner's
quarter-car view) and the body's sums of squared accelerations (:func:`output`).

:mod:`mrsuspension.engine.vehicle` runs it (``VehicleSimulation``); the step is kept apart
so that editing the Python side does not recompile it (about 20 s).

Compile time: :func:`rates`, :func:`step`, :func:`start`, :func:`_finish` and
:func:`check_limits` are compiled once each and inlined by LLVM
(:data:`~mrsuspension._numba_cache.INLINED`), and the RK4 stages share one call site of
:func:`rates`, as in the quarter car's kernel. With numba's own ``inline="always"`` and
the five calls written out, a cold compile took (CPU s, each alone on a fresh cache) 40 s
for the run loop, 19 s for the vehicle stepper and 32 s for the HiL tick with its vehicle
tick; now 20, 12 and 17 s. The results are bit for bit the same (the records of the
example vehicles and eight laws on the full car), the full car's step as fast (median
ratio 0.99 of 8 alternated runs of ``benchmarks/bench_vehicle.py``).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import INLINED, invalidate_if_changed
from mrsuspension.control import kernel as CK
from mrsuspension.control import modal as SM
from mrsuspension.control import sensing as SN
from mrsuspension.control import signals as SG
from mrsuspension.control import vehicle_lq as VL
from mrsuspension.control.kernel import EST_SHARED, F_EXTERNAL, F_MODEL, F_TARGET, P_C0, P_CS, P_MS0
from mrsuspension.control.modal import LAW_CORNERS, LAW_LQ, LAW_LQG, LAW_MODAL, LAW_MPC
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.engine import kernel as EK
from mrsuspension.vehicle import kernel as VK
from mrsuspension.vehicle.kernel import V_KS

__all__ = ["check_limits", "output", "rates", "record", "run", "start", "step"]

# the cached entry points inline the damper, shaping, controller, vehicle and engine kernels
invalidate_if_changed(
    __file__, DK.__file__, _shaping.__file__, CK.__file__, VK.__file__, EK.__file__,
    SM.__file__, SN.__file__, SG.__file__, VL.__file__,
)  # fmt: skip

# vp: body then corners; reciprocal masses and inertias (they leave the divisions off the
# chain of dependent operations from one RK4 stage to the next, as in engine/kernel.py)
B_INV_M, B_INV_IY, B_INV_IX, B_NC = 0, 1, 2, 3
B_SIZE = 4
# per corner (at B_SIZE + c * CORNER_SIZE): x, y from the CG [m], 1/m_u, k_s, k_t, c_t,
# static tire deflection dx_u, static tire load W, anti-roll rate k_bar/t^2, partner
C_X, C_Y, C_INV_MU, C_KS, C_KT, C_CT, C_DXU, C_W, C_BAR, C_PARTNER = range(10)
CORNER_SIZE = 10
NB = 6  # body states: z, theta, phi and their rates
NQ = 4  # states per corner: z_u, z_u', z_0, z_0'

# recorded signals: body columns, then REC_CORNER columns per corner
RB_Z, RB_PITCH, RB_ROLL, RB_VZ, RB_VPITCH, RB_VROLL, RB_AZ, RB_APITCH, RB_AROLL = range(9)
REC_BODY = 9
RC_ZS, RC_VS, RC_AS, RC_ZU, RC_VU, RC_AU, RC_ZR, RC_VR, RC_FD, RC_FT = range(10)
RC_ID, RC_IZ, RC_ZC, RC_TARGET, RC_VM, RC_Z0, RC_VSENSE = range(10, 17)
REC_CORNER = 17

# sensing and vehicle-level control (VehicleSimulation's ``sensing`` and ``control``):
# sk (int64): estimator kind, steps per accelerometer sample, steps per stroke-sensor
# sample (0: the true stroke), vehicle-level law (0: the corners' own controllers)
SK_KIND, SK_ACC_EVERY, SK_STROKE_EVERY, SK_LAW = range(4)
SK_SIZE = 4
SENSE_IDEAL, SENSE_LEAKY, SENSE_BAND_PASS = 0, 1, 2
# the law codes: one home, the laws' own (control/modal.py, VehicleLaw.kernel_code)
# sp (float): estimator coefficients (leaky: decay, gain; band-pass: Phi, Gamma), the
# stroke sensor's resolution [m] and rate [Hz], the law's params() (ModalSkyhook's
# MP_SIZE values; the whole-vehicle LQ's more: sp then is longer than SP_SIZE)
SP_COEF, SP_RES, SP_SFS, SP_MP = 0, 6, 7, 8
SP_SIZE = SP_MP + SM.MP_SIZE
# ss (2 nc + 1 rows, SS_WIDTH): row c the estimator's state (SS_VSENSE: the velocity the
# controller saw), row nc + c the stroke sensor's (control.sensing.STROKE_SIZE), last row
# the step count
SS_VSENSE = 2
SS_ASENSE = 3  # the accelerometer's held sample (the z_s'' signal with sensing)
SS_WIDTH = 4

#: Divergence limits: |z| [m] (and |angle| [rad]), |rate| [m/s, rad/s], |F_d| [N], F_T [N].
LIMITS = np.array([10.0, 100.0, 1e6, 1e7])
D_OK, D_STATE, D_FORCE, D_TIRE = EK.D_OK, EK.D_STATE, EK.D_FORCE, EK.D_TIRE


@njit(cache=True, inline="always")
def _corner_body(y: np.ndarray, x: float, yy: float) -> tuple[float, float]:
    """The body's displacement and velocity at a corner ``(x, y)``: ``z - x theta + y phi``."""
    return y[0] - x * y[1] + yy * y[2], y[3] - x * y[4] + yy * y[5]


@njit(cache=True, **INLINED)
def rates(
    y: np.ndarray,
    zr: np.ndarray,
    zrd: np.ndarray,
    j: int,
    vp: np.ndarray,
    cvp: np.ndarray,
    fk: np.ndarray,
    dk: np.ndarray,
    dp: np.ndarray,
    ds: np.ndarray,
    ck: np.ndarray,
    cp: np.ndarray,
    mem: np.ndarray,
    dy: np.ndarray,
    work: np.ndarray,
) -> None:
    """Time derivatives of ``y`` into ``dy`` with the road at column ``j`` of ``zr``/``zrd``.

    ``work`` (``corners x 3``) receives every corner's stroke, ``F_d`` and ``F_T``.
    """
    nc = int(vp[B_NC])
    for c in range(nc):  # strokes first: the anti-roll bars couple the corners
        o = B_SIZE + c * CORNER_SIZE
        zs, _ = _corner_body(y, vp[o + C_X], vp[o + C_Y])
        work[c, 0] = y[NB + NQ * c] - zs
    fz = my = mx = 0.0
    for c in range(nc):
        o = B_SIZE + c * CORNER_SIZE
        x, yy = vp[o + C_X], vp[o + C_Y]
        zs, vs = _corner_body(y, x, yy)
        q = NB + NQ * c
        zu, vu, z0, v0 = y[q], y[q + 1], y[q + 2], y[q + 3]
        xd = work[c, 0]
        vd = vu - vs
        f = fk[c]
        if f == F_MODEL:
            fd = DK.damper_force(dk[c], dp[c], ds[c], xd, vd, mem[c, EK.M_ID])
        elif f == F_EXTERNAL:
            fd = mem[c, EK.M_FEXT]
        elif f == F_TARGET:  # an ideal actuator: the corner law's force (C_USER_ACTIVE)
            fd = mem[c, EK.M_TARGET]
        else:  # an ideal dissipative damper (the ideal reference laws)
            fd = CK.ideal_force(f, cp[c], vs, xd, vd)
        partner = int(vp[o + C_PARTNER])
        fs = vp[o + C_KS] * xd + fd + vp[o + C_BAR] * (xd - work[partner, 0])
        # tire: zero when lifted off (delta <= 0), never pulls (model reference, section 4)
        delta = zr[c, j] - zu + vp[o + C_DXU]
        ft = vp[o + C_KT] * delta + vp[o + C_CT] * (zrd[c, j] - vu)
        ft = 0.0 if ft < 0.0 else ft
        ft = ft if delta > 0.0 else 0.0
        dy[q] = vu
        dy[q + 1] = (ft - vp[o + C_W] - fs) * vp[o + C_INV_MU]
        if CK.needs_reference(ck[c]):  # single-DOF reference (3.18) on this corner's wheel
            dy[q + 2] = v0
            dy[q + 3] = (
                -cp[c, P_C0] * (v0 - vu) - cp[c, P_CS] * v0 - cvp[c, V_KS] * (z0 - zu)
            ) / cp[c, P_MS0]
        else:
            dy[q + 2] = 0.0
            dy[q + 3] = 0.0
        fz += fs
        my -= x * fs
        mx += yy * fs
        work[c, 1] = fd
        work[c, 2] = ft
    dy[0] = y[3]
    dy[1] = y[4]
    dy[2] = y[5]
    dy[3] = fz * vp[B_INV_M]
    dy[4] = my * vp[B_INV_IY]
    dy[5] = mx * vp[B_INV_IX]


@njit(cache=True, **INLINED)
def _finish(
    y: np.ndarray, dy: np.ndarray, vp: np.ndarray, mem: np.ndarray, work: np.ndarray
) -> None:
    """Store the rates and forces at the state ``y`` in ``mem`` (record, next ``a_d``)."""
    for c in range(int(vp[B_NC])):
        o = B_SIZE + c * CORNER_SIZE
        x, yy = vp[o + C_X], vp[o + C_Y]
        q = NB + NQ * c
        a_s = dy[3] - x * dy[4] + yy * dy[5]
        mem[c, EK.M_AS] = a_s
        mem[c, EK.M_AU] = dy[q + 1]
        mem[c, EK.M_A0] = dy[q + 3]
        mem[c, EK.M_FD] = work[c, 1]
        mem[c, EK.M_FT] = work[c, 2]
        mem[c, EK.M_AD] = dy[q + 1] - a_s


@njit(cache=True, **INLINED)
def step(
    y: np.ndarray,
    dt: float,
    zr: np.ndarray,
    zrd: np.ndarray,
    j: int,
    vp: np.ndarray,
    cvp: np.ndarray,
    fk: np.ndarray,
    dk: np.ndarray,
    dp: np.ndarray,
    ds: np.ndarray,
    dek: np.ndarray,
    dep: np.ndarray,
    des: np.ndarray,
    ck: np.ndarray,
    cp: np.ndarray,
    cek: np.ndarray,
    cep: np.ndarray,
    ces: np.ndarray,
    mem: np.ndarray,
    sk: np.ndarray,
    sp: np.ndarray,
    ss: np.ndarray,
    noise: np.ndarray,
    mdist: np.ndarray,
    mbuf: np.ndarray,
    scratch: np.ndarray,
    work: np.ndarray,
) -> None:
    """Advance ``y`` by one step; each wheel's road at columns ``j, j+1, j+2`` of
    ``zr``/``zrd`` (t, t + dt/2, t + dt). ``scratch``: 5 rows of ``len(y)``; ``work``:
    ``corners x 8``. ``sk``, ``sp``, ``ss``, ``noise`` (stroke-sensor noise, ``corners x
    m``, used cyclically), ``mdist`` (the modal distribution matrix) and ``mbuf`` (``4 x
    corners``; the LQ laws' rows after them, ``control.vehicle_lq.MB_*``): sensing and the
    vehicle-level law (``SK_*``, ``SP_*``: its parameters from ``SP_MP`` on, ``SS_*``)."""
    nc = int(vp[B_NC])
    n = y.size
    kind = sk[SK_KIND]
    count = int(ss[2 * nc, 0])
    ss[2 * nc, 0] = count + 1
    sample_acc = kind != SENSE_IDEAL and count % sk[SK_ACC_EVERY] == 0
    stroke_every = sk[SK_STROKE_EVERY]
    sample_stroke = stroke_every > 0 and count % stroke_every == 0
    t = count * dt
    law = sk[SK_LAW]
    full = False  # a corner's law reads every signal (C_SIGNALS and up): else the view only
    for c in range(nc):
        if ck[c] >= CK.C_SIGNALS:
            full = True
    for c in range(nc):
        o = B_SIZE + c * CORNER_SIZE
        zs, vs = _corner_body(y, vp[o + C_X], vp[o + C_Y])
        q = NB + NQ * c
        xd = y[q] - zs
        vd = y[q + 1] - vs
        ad = mem[c, EK.M_AD]
        DK.damper_sample(dk[c], dp[c], ds[c], dek[c], dep[c], des[c], xd, vd, ad, mem[c, EK.M_ID])
        if cek[c] == EST_SHARED:
            vm = ds[c, DK.WS_VM]
        else:
            vm = DK.estimator_update(cek[c], cep[c], ces[c], xd, vd, ad)
        mem[c, EK.M_VM] = vm
        # the body velocity the controller sees: true, or estimated from the corner's
        # acceleration at the step's start (the previous step's last rates), sampled
        # every SK_ACC_EVERY steps and held
        est = ss[c]
        if kind == SENSE_IDEAL:
            est[SS_VSENSE] = vs
            est[SS_ASENSE] = mem[c, EK.M_AS]
        elif sample_acc:
            if kind == SENSE_LEAKY:
                v_hat = SN.leaky_integrator_update(
                    est, mem[c, EK.M_AS], sp[SP_COEF], sp[SP_COEF + 1]
                )
            else:
                v_hat = SN.band_pass_update(est, mem[c, EK.M_AS], sp[SP_COEF:SP_RES])
            est[SS_VSENSE] = v_hat
            est[SS_ASENSE] = mem[c, EK.M_AS]
        v_sense = est[SS_VSENSE]
        if stroke_every > 0:  # the stroke sensor's held reading and rate
            stroke = ss[nc + c]
            if sample_stroke:
                e = noise[c, (count // stroke_every) % noise.shape[1]]
                SN.stroke_sensor_update(stroke, xd, e, sp[SP_RES], sp[SP_SFS])
            zu_seen = zs + stroke[0]
            vu_seen = v_sense + stroke[1]
        else:
            zu_seen = y[q]
            vu_seen = y[q + 1] if kind == SENSE_IDEAL else v_sense + vd
        # the corner's signals (its first six: the quarter-car view of the built-in laws)
        sig = mem[c, EK.M_SIG : EK.M_SIG + SG.NS]
        if full:
            SG.fill_corner(
                sig, zs, v_sense, zu_seen, vu_seen, y[q + 2], y[q + 3], est[SS_ASENSE],
                mem[c, EK.M_AU], mem[c, EK.M_FD], mem[c, EK.M_ID], vm, t,
            )  # fmt: skip
        else:
            sig[SG.S_ZS] = zs
            sig[SG.S_VS] = v_sense
            sig[SG.S_ZU] = zu_seen
            sig[SG.S_VU] = vu_seen
            sig[SG.S_Z0] = y[q + 2]
            sig[SG.S_V0] = y[q + 3]
        work[c, 3] = xd
        work[c, 4] = vd
        work[c, 5] = v_sense
        work[c, 6] = vu_seen - v_sense  # the damper velocity the controller sees
        if law == LAW_LQ or law == LAW_MPC:  # noqa: SIM109 (numba: plain comparisons)
            # the state as seen: e = z_s - z_u and z_u' (control.vehicle_lq)
            mbuf[VL.MB_X, c] = zs - zu_seen
            mbuf[VL.MB_X, 2 * nc + VL.NB + c] = vu_seen
        elif law == LAW_LQG:  # the measurements and the load cells
            mbuf[VL.MB_Y, c] = est[SS_ASENSE]
            mbuf[VL.MB_Y, nc + c] = mem[c, EK.M_AU]
            mbuf[VL.MB_Y, 2 * nc + c] = zu_seen - zs
            mbuf[VL.MB_U, c] = mem[c, EK.M_FD]
    # the body's rates as seen: true, or from the corners' estimates, D^T v = (J J^T)^-1 J v
    seen = full  # rates from the estimates: a corner law reading every signal, or these laws
    if law == LAW_MODAL or law == LAW_LQ or law == LAW_MPC:  # noqa: SIM109 (numba: no tuple)
        seen = True
    if kind == SENSE_IDEAL or not seen:
        vz, pq, pp = y[3], y[4], y[5]
    else:
        vz = pq = pp = 0.0
        for c in range(nc):
            vz += mdist[c, 0] * work[c, 5]
            pq += mdist[c, 1] * work[c, 5]
            pp += mdist[c, 2] * work[c, 5]
    dy0 = scratch[1]  # the rates at y (start's, or the previous step's last)
    for c in range(nc):
        sig = mem[c, EK.M_SIG : EK.M_SIG + SG.NS]
        if not full:
            EK.apply_control(
                ck[c], cp[c], cvp[c], dp[c], sig, mem[c, EK.M_AD], mem[c, EK.M_VM], mem[c]
            )
            continue
        sig[SG.S_HEAVE] = y[0]
        sig[SG.S_PITCH] = y[1]
        sig[SG.S_ROLL] = y[2]
        sig[SG.S_VHEAVE] = vz
        sig[SG.S_VPITCH] = pq
        sig[SG.S_VROLL] = pp
        sig[SG.S_AHEAVE] = dy0[3]
        sig[SG.S_APITCH] = dy0[4]
        sig[SG.S_AROLL] = dy0[5]
        sig[SG.S_CORNER] = c
        EK.apply_control(ck[c], cp[c], cvp[c], dp[c], sig, mem[c, EK.M_AD], mem[c, EK.M_VM], mem[c])
    if law != LAW_CORNERS:  # hi-lo from the desired corner forces (control.modal)
        forces, vds, current, zc = mbuf[0], mbuf[1], mbuf[2], mbuf[3]
        mp = sp[SP_MP:]
        if law < LAW_LQ:  # modal or per-corner skyhook
            if law == LAW_MODAL:
                SM.modal_forces(forces, mdist, mp, vz, pq, pp)
            else:  # per-corner skyhook F_i = -c_s v_i
                for c in range(nc):
                    forces[c] = -mp[SM.MP_CZ] * work[c, 5]
            for c in range(nc):
                vds[c] = work[c, 6]
            SM.modal_hilo(current, zc, forces, vds, mp)
        else:  # the whole-vehicle LQ, LQG and MPC (control.vehicle_lq): F = -K x, or the QP's
            for c in range(nc):
                vds[c] = work[c, 6]
            if law == LAW_MPC:
                VL.mpc_forces(forces, mbuf, mp, nc, vz, pq, pp, vds, t)
            else:
                VL.lq_forces(forces, mbuf, mp, nc, vz, pq, pp, law == LAW_LQG,
                             dt if count > 0 else 0.0)  # fmt: skip
            out = mp[VL.LP_OUTPUT]
            low, high = mp[SM.MP_ILOW], mp[SM.MP_IHIGH]
            for c in range(nc):
                if out == VL.OUT_FORCE:  # through the corner's inverse model, as lq-force
                    i, fh = CK.track_force(
                        dp[c], mem[c, EK.M_PH : EK.M_PH + DK.PH_SIZE], forces[c], vds[c],
                        mem[c, EK.M_AD], 1.0, mem[c, EK.M_VM], high,
                    )  # fmt: skip
                    z = fh * forces[c]
                    i = min(max(i, low), high)
                else:
                    # Dyke et al.'s clipped-optimal rule, as the per-corner clipped-lq (the
                    # load cell's force: the previous step's)
                    z = SM.clipped_optimal_condition(forces[c], mem[c, EK.M_FD])
                    i = 0.0 if out == VL.OUT_ACTIVE else SM.hilo_current(z, low, high)
                zc[c] = z
                current[c] = i
                if z != z:  # a law that failed (its forces NaN): the run stops at the check
                    current[c] = z
        for c in range(nc):
            mem[c, EK.M_ID] = current[c]
            mem[c, EK.M_IZ] = current[c]
            mem[c, EK.M_ZC] = zc[c]
            mem[c, EK.M_TARGET] = forces[c]
    # every corner's final current: its chatter count (EK.note_current's three lines on
    # the row's slots; note_current(mem[c]) on a row view measured 10 % slower per step)
    for c in range(nc):
        final = mem[c, EK.M_ID]
        mem[c, EK.M_DI], mem[c, EK.M_NREV] = EK.chatter(
            final, mem[c, EK.M_IPREV], mem[c, EK.M_DI], mem[c, EK.M_NREV]
        )
        mem[c, EK.M_IPREV] = final
    yt = scratch[0]
    k = scratch[1]
    acc = scratch[2]
    # classical RK4: k1 at t, k2 and k3 at t + dt/2, k4 at t + dt, then the rates at the
    # new state, from one call site of rates()
    c6 = dt / 6.0
    for st in range(5):
        rates(y if st == 0 or st == 4 else yt, zr, zrd, j + (st + 1) // 2, vp, cvp, fk, dk,
              dp, ds, ck, cp, mem, k, work)  # fmt: skip
        if st == 3:
            for i in range(n):
                y[i] += c6 * (acc[i] + k[i])
        elif st < 3:
            h = dt if st == 2 else 0.5 * dt
            w = 1.0 if st == 0 else 2.0
            for i in range(n):
                acc[i] = k[i] if st == 0 else acc[i] + w * k[i]
                yt[i] = y[i] + h * k[i]
    _finish(y, k, vp, mem, work)
    for c in range(nc):
        DK.damper_advance(dk[c], dp[c], ds[c], work[c, 3], work[c, 4], mem[c, EK.M_ID], dt)


@njit(cache=True, **INLINED)
def start(
    y: np.ndarray,
    zr: np.ndarray,
    zrd: np.ndarray,
    j: int,
    vp: np.ndarray,
    cvp: np.ndarray,
    fk: np.ndarray,
    dk: np.ndarray,
    dp: np.ndarray,
    ds: np.ndarray,
    dek: np.ndarray,
    dep: np.ndarray,
    des: np.ndarray,
    ck: np.ndarray,
    cp: np.ndarray,
    mem: np.ndarray,
    scratch: np.ndarray,
    work: np.ndarray,
) -> None:
    """Initial accelerations and forces (for the record and the first step's ``a_d``).

    Empties each corner's control-law memo (a new run, as :func:`EK.start` does).
    """
    for c in range(int(vp[B_NC])):
        mem[c, EK.M_PH + DK.PH_FT] = 0.0
        mem[c, EK.M_IPREV] = mem[c, EK.M_ID]  # the chatter count of this run
        mem[c, EK.M_DI] = 0.0
        mem[c, EK.M_NREV] = 0.0
        if fk[c] == F_TARGET:  # an ideal actuator starts with no force
            mem[c, EK.M_TARGET] = 0.0
        o = B_SIZE + c * CORNER_SIZE
        zs, vs = _corner_body(y, vp[o + C_X], vp[o + C_Y])
        q = NB + NQ * c
        DK.damper_sample(
            dk[c], dp[c], ds[c], dek[c], dep[c], des[c], y[q] - zs, y[q + 1] - vs, 0.0,
            mem[c, EK.M_ID],
        )  # fmt: skip
    rates(y, zr, zrd, j, vp, cvp, fk, dk, dp, ds, ck, cp, mem, scratch[1], work)
    _finish(y, scratch[1], vp, mem, work)


@njit(cache=True, inline="always")
def record(
    rec: np.ndarray,
    row: int,
    y: np.ndarray,
    zr: np.ndarray,
    zrd: np.ndarray,
    j: int,
    vp: np.ndarray,
    mem: np.ndarray,
    ss: np.ndarray,
    dy: np.ndarray,
) -> None:
    """Row ``row`` of the record: body columns ``RB_*``, then ``RC_*`` per corner (``dy``:
    the rates at ``y``, for the body's accelerations)."""
    for i in range(NB):
        rec[row, i] = y[i]
    rec[row, RB_AZ] = dy[3]
    rec[row, RB_APITCH] = dy[4]
    rec[row, RB_AROLL] = dy[5]
    nc = int(vp[B_NC])
    for c in range(nc):
        o = B_SIZE + c * CORNER_SIZE
        zs, vs = _corner_body(y, vp[o + C_X], vp[o + C_Y])
        q = NB + NQ * c
        b = REC_BODY + REC_CORNER * c
        rec[row, b + RC_ZS] = zs
        rec[row, b + RC_VS] = vs
        rec[row, b + RC_AS] = mem[c, EK.M_AS]
        rec[row, b + RC_ZU] = y[q]
        rec[row, b + RC_VU] = y[q + 1]
        rec[row, b + RC_AU] = mem[c, EK.M_AU]
        rec[row, b + RC_ZR] = zr[c, j]
        rec[row, b + RC_VR] = zrd[c, j]
        rec[row, b + RC_FD] = mem[c, EK.M_FD]
        rec[row, b + RC_FT] = mem[c, EK.M_FT]
        rec[row, b + RC_ID] = mem[c, EK.M_ID]
        rec[row, b + RC_IZ] = mem[c, EK.M_IZ]
        rec[row, b + RC_ZC] = mem[c, EK.M_ZC]
        rec[row, b + RC_TARGET] = mem[c, EK.M_TARGET]
        rec[row, b + RC_VM] = mem[c, EK.M_VM]
        rec[row, b + RC_Z0] = y[q + 2]
        rec[row, b + RC_VSENSE] = ss[c, SS_VSENSE] if row > 0 else vs


@njit(cache=True, **INLINED)
def check_limits(
    y: np.ndarray, vp: np.ndarray, mem: np.ndarray, limits: np.ndarray
) -> tuple[int, int, float]:
    """``(status, index, value)`` of the first state (index into ``y``) or force (index:
    the corner) out of ``limits`` (``D_OK``: none)."""
    for i in range(y.size):
        v = y[i]
        rate = i >= 3 if i < NB else (i - NB) % 2 == 1
        if not (abs(v) <= (limits[1] if rate else limits[0])):
            return D_STATE, i, v
    for c in range(int(vp[B_NC])):
        if not abs(mem[c, EK.M_FD]) <= limits[2]:
            return D_FORCE, c, mem[c, EK.M_FD]
        if not mem[c, EK.M_FT] <= limits[3]:
            return D_TIRE, c, mem[c, EK.M_FT]
    return D_OK, 0, 0.0


# body accumulators of a reduced run (the last row of ``acc``, beside the corners' rows
# of engine.kernel.accumulate): output samples, sums of the squared body accelerations
BA_N, BA_AZ2, BA_APITCH2, BA_AROLL2 = range(4)
# a reduced run's per-corner reduction (rows of ``red``): first output row of the steady
# window, F_T shift, v_m clamp threshold (engine.reduced.Reduction)
RED_START, RED_SHIFT, RED_THRESHOLD = range(3)
RED_SIZE = 3


@njit(cache=True, inline="always")
def output(
    reduced: bool,
    rec: np.ndarray,
    acc: np.ndarray,
    red: np.ndarray,
    trace: np.ndarray,
    row: int,
    y: np.ndarray,
    zr: np.ndarray,
    zrd: np.ndarray,
    j: int,
    vp: np.ndarray,
    mem: np.ndarray,
    ss: np.ndarray,
    dy: np.ndarray,
    view: np.ndarray,
) -> None:
    """Output sample ``row`` (road at column ``j``, ``dy`` the rates at ``y``): a record row
    (:func:`record`) or, with ``reduced``, every corner's quarter-car view (``view``: 6
    values of work space) into its accumulators ``acc[c]``
    (:func:`~mrsuspension.engine.kernel.accumulate`, with ``red[c]``: ``RED_*``), its
    ``z_s''`` into ``trace[c, row]`` when ``trace`` has columns, and the body's squared
    accelerations into ``acc[corners]`` (``BA_*``)."""
    if not reduced:
        if row < rec.shape[0]:
            record(rec, row, y, zr, zrd, j, vp, mem, ss, dy)
        return
    nc = int(vp[B_NC])
    keep = trace.shape[1] > 0
    for c in range(nc):
        o = B_SIZE + c * CORNER_SIZE
        zs, vs = _corner_body(y, vp[o + C_X], vp[o + C_Y])
        q = NB + NQ * c
        view[0], view[1], view[2], view[3], view[4], view[5] = (
            zs, vs, y[q], y[q + 1], y[q + 2], y[q + 3]
        )  # fmt: skip
        EK.accumulate(
            acc[c], row >= red[c, RED_START], red[c, RED_SHIFT], red[c, RED_THRESHOLD], view,
            zr[c, j], mem[c],
        )  # fmt: skip
        if keep:
            trace[c, row] = mem[c, EK.M_AS]
    body = acc[nc]
    body[BA_N] += 1.0
    body[BA_AZ2] += dy[3] * dy[3]
    body[BA_APITCH2] += dy[4] * dy[4]
    body[BA_AROLL2] += dy[5] * dy[5]


@njit(cache=True, **NO_REFCOUNT)
def run(
    y: np.ndarray,
    first: int,
    n_steps: int,
    dt: float,
    zr: np.ndarray,
    zrd: np.ndarray,
    vp: np.ndarray,
    cvp: np.ndarray,
    fk: np.ndarray,
    dk: np.ndarray,
    dp: np.ndarray,
    ds: np.ndarray,
    dek: np.ndarray,
    dep: np.ndarray,
    des: np.ndarray,
    ck: np.ndarray,
    cp: np.ndarray,
    cek: np.ndarray,
    cep: np.ndarray,
    ces: np.ndarray,
    mem: np.ndarray,
    sk: np.ndarray,
    sp: np.ndarray,
    ss: np.ndarray,
    noise: np.ndarray,
    mdist: np.ndarray,
    mbuf: np.ndarray,
    decimate: int,
    limits: np.ndarray,
    scratch: np.ndarray,
    work: np.ndarray,
    reduced: bool,
    rec: np.ndarray,
    acc: np.ndarray,
    red: np.ndarray,
    trace: np.ndarray,
) -> tuple[int, int, int, float]:
    """Steps ``first`` to ``first + n_steps - 1`` of a run; every wheel's road sampled every
    dt/2 from step ``first`` on (``2 n_steps + 1`` columns of ``zr``, ``zrd``).

    The vehicles' one drive loop, resumable: a run is driven in pieces of its road (the
    caller keeps ``y`` and the arrays between the calls); the call with ``first == 0``
    starts it. The output samples are the initial state and every ``decimate`` steps
    (sample ``r`` after step ``r * decimate``); each is a row of the record ``rec`` or,
    with ``reduced``, goes to the accumulators (:func:`output`; the unused arrays may be
    empty). Returns ``(status, step, index, value)`` as
    :func:`mrsuspension.engine.kernel.run` (``step`` counted from the run's start).
    """
    dy = scratch[1]  # the rates at y: start's, then every step's last
    view = work[int(vp[B_NC])]
    if first == 0:
        start(y, zr, zrd, 0, vp, cvp, fk, dk, dp, ds, dek, dep, des, ck, cp, mem, scratch, work)
        output(reduced, rec, acc, red, trace, 0, y, zr, zrd, 0, vp, mem, ss, dy, view)
    for s in range(first, first + n_steps):
        j = 2 * (s - first)
        step(
            y, dt, zr, zrd, j, vp, cvp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces,
            mem, sk, sp, ss, noise, mdist, mbuf, scratch, work,
        )  # fmt: skip
        status, q, value = check_limits(y, vp, mem, limits)
        if status != D_OK:
            return status, s + 1, q, value
        if (s + 1) % decimate == 0:
            r = (s + 1) // decimate
            output(reduced, rec, acc, red, trace, r, y, zr, zrd, j + 2, vp, mem, ss, dy, view)
    return D_OK, first + n_steps, 0, 0.0
