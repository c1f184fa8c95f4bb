"""Compiled control laws (model reference, section 6): codes, parameter layout, ``control()``.

Every control law of :mod:`mrsuspension.control` is a code (``C_*``, the class's
``code``) and a parameter vector (``CP_SIZE`` values at the ``P_*`` slots, written by
:meth:`Controller.params <mrsuspension.control.Controller.params>`). The engine's step
(``step`` in ``engine/kernel.py``) calls :func:`control` once per step with the
sampled state and holds the drive current over the step (zero-order hold); the ideal
references act through an ideal dissipative damper instead (:func:`ideal_force`, force
source codes ``F_*``).

Adding a law: a code here, its branch in :func:`control` (and :func:`ideal_force` or
:func:`needs_reference` if it uses them), any new ``P_*`` slot, and its class in
:mod:`mrsuspension.control` (see ``docs/develop.md``).

The state ``y`` and the vehicle parameters ``vp`` have the layouts of
:mod:`mrsuspension.vehicle.kernel`; the damper parameters ``dp`` those of
:mod:`mrsuspension.dampers.kernels`.
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import intrinsic

from mrsuspension import shaping as _shaping
from mrsuspension._numba_cache import INLINED, invalidate_if_changed
from mrsuspension.dampers import kernels as DK
from mrsuspension.shaping import drive_current_kernel, onoff_kernel
from mrsuspension.vehicle import kernel as VK
from mrsuspension.vehicle.kernel import V_KS

# the cached laws below call (LLVM inlines) the damper and shaping kernels (and read
# vehicle layouts)
invalidate_if_changed(__file__, DK.__file__, _shaping.__file__, VK.__file__)

__all__ = [
    "CP_SIZE",
    "C_IDEAL_ONOFF",
    "C_IDEAL_SKYHOOK",
    "C_INVERSE_HILO",
    "C_ONOFF_ADFG",
    "C_PASSIVE",
    "C_POLICY",
    "C_SIGNALS",
    "C_SLIDING",
    "C_USER_ACTIVE",
    "C_USER_CURRENT",
    "C_USER_FORCE",
    "EST_SHARED",
    "F_EXTERNAL",
    "F_MODEL",
    "F_ONOFF",
    "F_SKYHOOK",
    "F_TARGET",
    "P_ADFG_CENTRE",
    "P_BETA",
    "P_C0",
    "P_CS",
    "P_CURRENT",
    "P_EPS",
    "P_GAIN",
    "P_IMAX",
    "P_INV_HYST",
    "P_LAMBDA",
    "P_MS0",
    "P_ORDER",
    "P_P",
    "P_PC",
    "P_PHI",
    "P_POLICY",
    "P_USER_FN",
    "P_XI",
    "P_XIC",
    "call_law",
    "control",
    "ideal_force",
    "needs_reference",
    "track_force",
    "user_control",
]

# controller codes (Controller.code)
C_PASSIVE = 0
C_ONOFF_ADFG = 1
C_POLICY = 2
C_INVERSE_HILO = 3
C_SLIDING = 4
C_IDEAL_SKYHOOK = 5
C_IDEAL_ONOFF = 6
#: the first code of the laws that read every measured signal (:mod:`~mrsuspension.control.signals`,
#: filled for them only: the laws above read the quarter-car view, its first six slots, and
#: the quarter car's step does not pay for the rest); a new law takes a code from here on
C_SIGNALS = 7
#: a user-defined law (:mod:`mrsuspension.control.user`) returning the drive current [A]
C_USER_CURRENT = 7
#: a user-defined law returning a target force [N], tracked through the inverse model
C_USER_FORCE = 8
#: a user-defined law returning a force [N] applied as it is by an ideal actuator
#: (force source :data:`F_TARGET`: a reference, e.g. the active LQR, not a damper)
C_USER_ACTIVE = 9

# controller parameters (Controller.params)
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
    P_ADFG_CENTRE,  # ADFG M_p at v_d = 0, share of the way from p to 1 (0.5: (2.3))
) = range(18)
CP_SIZE = 18
#: a user law's first slot after the fixed ones: the address of its compiled entry
#: ``double law(double *signals, double *options, int64 n_options)`` (a numba ``cfunc``,
#: or a ctypes callback into Python), exact in a float64 (user-space addresses are below
#: 2^48; checked where it is written); the law's options follow it
P_USER_FN = CP_SIZE

# force source of the engine's rates (Controller.force_source)
F_MODEL = 0  # the damper model at the held current
F_SKYHOOK = 1  # ideal skyhook (3.12) through an ideal dissipative damper
F_ONOFF = 2  # Rakheja displacement on-off (3.13) through an ideal dissipative damper
F_EXTERNAL = 3  # a given force held over the step (hardware in the loop; set by the engine)
F_TARGET = 4  # the law's target force F* held over the step: an ideal actuator (C_USER_ACTIVE)

#: controller estimator code meaning "use the damper's latched v_m" (dissertation's model)
EST_SHARED = -1


@njit(cache=True, **INLINED)
def needs_reference(ck: int) -> bool:
    """Whether law ``ck`` tracks the reference model (3.18) integrated with the plant.

    Examples
    --------
    >>> needs_reference(C_SLIDING), needs_reference(C_PASSIVE)
    (True, False)
    """
    return ck == C_SLIDING


@njit(cache=True, **INLINED)
def ideal_force(fk: int, cp: np.ndarray, vs: float, xd: float, vd: float) -> float:
    """Force ``F_d`` [N] of an ideal dissipative damper under force source ``fk``.

    ``F_SKYHOOK``: (3.12) in the up-positive frame, ``-c_s z_s'`` when ``z_s' v_d < 0``,
    else 0; ``F_ONOFF``: (3.13), ``c_s v_d`` when ``x_d v_d < 0``, else 0.

    Examples
    --------
    >>> cp = np.zeros(CP_SIZE)
    >>> cp[P_CS] = 1000.0
    >>> ideal_force(F_SKYHOOK, cp, 0.1, 0.0, -0.2), ideal_force(F_ONOFF, cp, 0.0, 0.01, 0.2)
    (-100.0, 0.0)
    """
    if fk == F_SKYHOOK:
        return -cp[P_CS] * vs if vs * vd < 0.0 else 0.0
    return cp[P_CS] * vd if xd * vd < 0.0 else 0.0


@njit(cache=True, **INLINED)
def control(
    ck: int,
    cp: np.ndarray,
    vp: np.ndarray,
    dp: np.ndarray,
    y: np.ndarray,
    ad: float,
    vm: float,
    memo: np.ndarray,
) -> tuple[float, float, float, float]:
    """The control law ``ck`` at the sampled state (model reference, section 6).

    Parameters
    ----------
    ck : int
        Controller code (``C_*``).
    cp : ndarray
        Controller parameters (``P_*`` layout).
    vp : ndarray
        Vehicle parameters (:mod:`mrsuspension.vehicle.kernel` ``V_*``).
    dp : ndarray
        Damper parameters (for the inverse model of the inverse-model laws).
    y : ndarray
        Sampled state (:mod:`mrsuspension.vehicle.kernel` ``Y_*``).
    ad : float
        Previous step's damper acceleration ``a_d`` [m/s^2] (its sign selects the branch
        of the hysteretic inverse model).
    vm : float
        The controller's peak velocity ``v_m`` [m/s].
    memo : ndarray
        The inverse-model laws' memo of the damper's v_m terms, kept by the caller
        between the steps of a run (``DK.PH_SIZE`` values,
        :func:`~mrsuspension.dampers.kernels.passive_hysteron_memo`; zero-filled at
        the start of a run).

    Returns
    -------
    tuple of float
        ``(i_d, i_z, z_c, F*)``: the drive current [A] (held over the step), the
        controller current [A], the switching condition and the target force [N] (NaN
        where the law has none).

    Examples
    --------
    >>> cp = np.zeros(CP_SIZE)
    >>> cp[P_CURRENT], cp[P_IMAX] = 0.2, 0.5
    >>> control(C_PASSIVE, cp, np.zeros(8), np.zeros(1), np.zeros(6), 0.0, 0.1,
    ...         np.zeros(DK.PH_SIZE))[:2]
    (0.2, 0.2)
    """
    zs, vs, zu, vu = y[0], y[1], y[2], y[3]
    xd = zu - zs
    vd = vu - vs
    imax = cp[P_IMAX]
    iz = 0.0
    zc = math.nan
    target = math.nan
    if ck == C_PASSIVE:
        i = min(cp[P_CURRENT], imax)
        return i, i, zc, target
    if ck == C_ONOFF_ADFG:
        # (2.1): p i_H in compression, i_H otherwise
        i = onoff_kernel(cp[P_CURRENT], vd, cp[P_P])
        return min(max(i, 0.0), imax), cp[P_CURRENT], zc, target
    if ck == C_IDEAL_SKYHOOK:
        return 0.0, 0.0, vs * vd, -cp[P_CS] * vs
    if ck == C_IDEAL_ONOFF:
        return 0.0, 0.0, xd * vd, cp[P_CS] * vd
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
        fh = DK.passive_hysteron_memo(dp, memo, vd, sa, vm)
        iz = DK.wang_inverse_from(dp, target, fh, imax)
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
        fh = DK.passive_hysteron_memo(dp, memo, vd, sa, vm)
        iz = DK.wang_inverse_from(dp, target, fh, imax)
        zc = -fh * target  # (3.35)
    # drive current (3.9)/(3.16)
    i = drive_current_kernel(
        iz, vd, vm, zc, cp[P_P], cp[P_XI], cp[P_PC], cp[P_XIC], imax, cp[P_ADFG_CENTRE]
    )
    return i, iz, zc, target


@intrinsic
def call_law(typingctx, addr, sig, opt):  # type: ignore[no-untyped-def]
    """Call the C entry at ``addr`` (int64) as ``double f(double *sig, double *opt, int64 n)``
    with the data of the 1-D float arrays ``sig`` and ``opt`` (``n = opt.size``).

    The kernels are compiled once for every user law: the law is an address, not a type
    (a numba first-class function argument costs 40-50 us per call of the entry point
    from Python, measured: too slow for a stepper ticking from Python).
    """
    if not (
        isinstance(addr, types.Integer)
        and isinstance(sig, types.Array)
        and isinstance(opt, types.Array)
    ):
        return None

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        a, s, o = args
        sarr = context.make_array(signature.args[1])(context, builder, s)
        oarr = context.make_array(signature.args[2])(context, builder, o)
        dbl = ir.DoubleType()
        fnty = ir.FunctionType(dbl, [dbl.as_pointer(), dbl.as_pointer(), ir.IntType(64)])
        fn = builder.inttoptr(a, fnty.as_pointer())
        n = builder.extract_value(oarr.shape, 0)
        return builder.call(fn, [sarr.data, oarr.data, n])

    return types.float64(addr, sig, opt), codegen


@njit(cache=True, **INLINED)
def user_control(
    ck: int,
    cp: np.ndarray,
    dp: np.ndarray,
    sig: np.ndarray,
    ad: float,
    vm: float,
    memo: np.ndarray,
) -> tuple[float, float, float, float]:
    """A user-defined law (``C_USER_*``) at the signals ``sig``: as :func:`control` returns.

    Calls the law's compiled entry (its address at ``cp[P_USER_FN]``, its options after
    it) with the signals (:mod:`mrsuspension.control.signals`). ``C_USER_CURRENT``: the
    value is the current, clipped to ``[0, i_max]``; ``C_USER_FORCE``: a target force
    tracked through the damper's inverse model (as the inverse-model laws, ``z_c = F_h
    F*``); ``C_USER_ACTIVE``: the value is the force of an ideal actuator (no current;
    the engine applies the target, force source :data:`F_TARGET`). A value that is not
    finite (a Python law that raised) makes the current NaN: the run then stops at the
    limit check and the caller reports the law's error.
    """
    nan = math.nan
    addr = cp[P_USER_FN]
    if addr == 0.0:  # no entry (never written by the Python side): no current
        return 0.0, 0.0, nan, nan
    out: float = call_law(np.int64(addr), sig, cp[P_USER_FN + 1 :])  # type: ignore[call-arg]
    if not math.isfinite(out):
        return nan, nan, nan, nan
    imax = cp[P_IMAX]
    if ck == C_USER_CURRENT:
        return min(max(out, 0.0), imax), out, nan, nan
    if ck == C_USER_ACTIVE:
        return 0.0, 0.0, nan, out
    iz, fh = track_force(dp, memo, out, sig[3] - sig[1], ad, cp[P_INV_HYST], vm, imax)
    return min(max(iz, 0.0), imax), iz, fh * out, out


@njit(cache=True, **INLINED)
def track_force(
    dp: np.ndarray,
    memo: np.ndarray,
    target: float,
    vd: float,
    ad: float,
    hysteretic: float,
    vm: float,
    imax: float,
) -> tuple[float, float]:
    """``(i_z, F_h)``: the current [A] in ``[0, imax]`` at which the damper's inverse model
    gives the target force ``target`` [N] at the stroke rate ``vd`` [m/s], and the
    passive hysteron ``F_h`` there (the condition ``z_c = F_h F*``).

    A target force tracked through the inverse model (model reference, section 2.3), as
    ``C_USER_FORCE`` and the whole-vehicle ``-force`` laws
    (:mod:`~mrsuspension.control.vehicle_lq`) do: the branch from the sign of the previous
    step's damper acceleration ``ad`` times ``hysteretic`` (1: the hysteretic inverse
    model, 0: the mean one, ``P_INV_HYST``), the v_m terms kept in ``memo``
    (:func:`~mrsuspension.dampers.kernels.passive_hysteron_memo`).
    """
    sa = DK.sign(ad) * hysteretic
    fh = DK.passive_hysteron_memo(dp, memo, vd, sa, vm)
    return DK.wang_inverse_from(dp, target, fh, imax), fh
