"""Compiled tick of a half or full car with one corner's damper on the rig.

One call advances the vehicle by one loop tick: ``n_sub`` steps of the vehicle's compiled
step (:func:`mrsuspension.engine.vehicle_kernel.step`, the physics of
:meth:`~mrsuspension.engine.vehicle.VehicleSimulation.run`), the rig corner's damper
force given from outside (``F_EXTERNAL``: the measured force plus the start-up damping
on the corner's stroke rate, held over each step, as the quarter car's loop does), and
the signals the loop records written into ``out`` (``OUT_*``). One call instead of one
per engine step: a call from Python with the vehicle's 21 arrays costs about 5 us, so
the loop pays it once per tick.

The vehicle's arrays come as one tuple, in the order of
:meth:`~mrsuspension.engine.vehicle.VehicleArrays.args`.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numba import njit

from mrsuspension._numba_cache import DEPENDENCIES, invalidate_if_changed
from mrsuspension.dampers.kernels import NO_REFCOUNT
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import vehicle_kernel as VX

__all__ = ["OUT_NAMES", "OUT_SIZE", "corner_tick"]

# the cached tick inlines the vehicle's step (and everything it inlines)
invalidate_if_changed(__file__, VX.__file__, *DEPENDENCIES.get(VX.__file__, ()))

#: ``out`` of :func:`corner_tick`: the rig corner's quarter-car signals (the names of the
#: quarter car's loop channels), the corner's road at the tick's end, then the body's
(
    OUT_ZS, OUT_ZU, OUT_VS, OUT_VU, OUT_AS, OUT_AU, OUT_XD, OUT_VD, OUT_FT, OUT_ID, OUT_ZR,
    OUT_VR, OUT_FD, OUT_HEAVE, OUT_PITCH, OUT_ROLL, OUT_AHEAVE, OUT_APITCH, OUT_AROLL,
) = range(19)  # fmt: skip
OUT_SIZE = 19
OUT_NAMES = (
    "z_s", "z_u", "z_s_dot", "z_u_dot", "z_s_ddot", "z_u_ddot", "x_d", "v_d", "F_T", "i_d",
    "z_r", "z_r_dot", "F_d", "heave", "pitch", "roll", "heave_ddot", "pitch_ddot", "roll_ddot",
)  # fmt: skip


@njit(cache=True, **NO_REFCOUNT)
def corner_tick(
    y: np.ndarray,
    dt: float,
    n_sub: int,
    zr: np.ndarray,
    zrd: np.ndarray,
    j0: int,
    ext: int,
    force: float,
    damping: float,
    args: tuple[Any, ...],
    scratch: np.ndarray,
    work: np.ndarray,
    out: np.ndarray,
) -> tuple[int, int, float, int]:
    """Advance ``y`` by ``n_sub`` steps of ``dt``; the roads from column ``j0`` of ``zr``/``zrd``.

    Corner ``ext``'s damper force at each step is ``force + damping * v_d`` with its
    stroke rate ``v_d`` at the step's start. Returns ``(status, index, value, steps)``:
    ``VX.D_OK`` or the first limit the state left (``VX.check_limits``) and the steps
    done; ``out`` holds the signals at the end (``OUT_*``).
    """
    (vp, cvp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces, mem, sk, sp, ss, noise,
     mdist, mbuf) = args  # fmt: skip
    o = VX.B_SIZE + ext * VX.CORNER_SIZE
    cx = vp[o + VX.C_X]
    cy = vp[o + VX.C_Y]
    q = VX.NB + VX.NQ * ext
    j = j0
    for s in range(n_sub):
        vs = y[3] - cx * y[4] + cy * y[5]
        mem[ext, EK.M_FEXT] = force + damping * (y[q + 1] - vs)
        VX.step(
            y, dt, zr, zrd, j, vp, cvp, fk, dk, dp, ds, dek, dep, des, ck, cp, cek, cep, ces,
            mem, sk, sp, ss, noise, mdist, mbuf, scratch, work,
        )  # fmt: skip
        j += 2
        status, idx, value = VX.check_limits(y, vp, mem, VX.LIMITS)
        if status != VX.D_OK:
            return status, idx, value, s + 1
    zs = y[0] - cx * y[1] + cy * y[2]
    vs = y[3] - cx * y[4] + cy * y[5]
    out[OUT_ZS] = zs
    out[OUT_ZU] = y[q]
    out[OUT_VS] = vs
    out[OUT_VU] = y[q + 1]
    out[OUT_AS] = mem[ext, EK.M_AS]
    out[OUT_AU] = mem[ext, EK.M_AU]
    out[OUT_XD] = y[q] - zs
    out[OUT_VD] = y[q + 1] - vs
    out[OUT_FT] = mem[ext, EK.M_FT]
    out[OUT_ID] = mem[ext, EK.M_ID]
    out[OUT_ZR] = zr[ext, j]
    out[OUT_VR] = zrd[ext, j]
    out[OUT_FD] = mem[ext, EK.M_FD]
    out[OUT_HEAVE] = y[0]
    out[OUT_PITCH] = y[1]
    out[OUT_ROLL] = y[2]
    out[OUT_AHEAVE] = scratch[1, 3]
    out[OUT_APITCH] = scratch[1, 4]
    out[OUT_AROLL] = scratch[1, 5]
    return VX.D_OK, 0, 0.0, n_sub
