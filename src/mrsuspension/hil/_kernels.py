"""Compiled tick of the simulated rig: actuator, coil and damper "hardware".

The damper physics is not copied: the rig drives any damper model through the compiled
kernels of :mod:`mrsuspension.dampers.kernels` (``damper_sample`` / ``damper_force`` /
``damper_advance``), sample by sample. Everything here is compiled without reference
counting and allocates nothing (work arrays come from the caller).

State ``st`` (``ST_*`` layout) and parameters ``rp`` (``RP_*`` layout) are flat arrays.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from mrsuspension._numba_cache import invalidate_if_changed
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers.kernels import NO_REFCOUNT

# the cached rig tick inlines the damper kernels
invalidate_if_changed(__file__, DK.__file__)

# rig state
ST_T, ST_X, ST_V, ST_A, ST_I, ST_F, ST_HEAD = range(7)
ST_SIZE = 7

# rig parameters
(
    RP_OMEGA,  # actuator bandwidth [rad/s] (0: perfect tracking)
    RP_ORDER,  # 1 or 2
    RP_ZETA,  # damping ratio of the second-order actuator
    RP_TAU_COIL,  # coil + amplifier time constant [s] (0: instantaneous)
    RP_COIL_GAIN,  # amplifier gain (1: nominal; a fault otherwise)
    RP_NSUB,  # substeps per tick
    RP_NDELAY,  # transport delay in ticks
) = range(7)
RP_SIZE = 7


@njit(cache=True, **NO_REFCOUNT)
def rig_tick(
    st: np.ndarray,
    rp: np.ndarray,
    ref_x: np.ndarray,
    ref_v: np.ndarray,
    stroke: float,
    velocity: float,
    current: float,
    period: float,
    kind: int,
    p: np.ndarray,
    s: np.ndarray,
    ek: int,
    ep: np.ndarray,
    es: np.ndarray,
) -> None:
    """Advance the rig by one loop period under the command (stroke, velocity, current).

    The stroke command goes through the transport-delay ring buffer (``ref_x``,
    ``ref_v``, length ``n_delay + 1``) and then the actuator's first- or second-order
    dynamics (or perfect tracking when the bandwidth is 0); the coil current follows the
    amplifier command with a first-order lag (or at once). The damper is advanced at every
    substep; ``st[ST_F]`` is the true force at the end of the period.
    """
    nd = int(rp[RP_NDELAY])
    cap = nd + 1
    head = int(st[ST_HEAD])
    ref_x[head] = stroke
    ref_v[head] = velocity
    tail = head - nd
    if tail < 0:
        tail += cap
    r = ref_x[tail]
    rv = ref_v[tail]
    head += 1
    if head == cap:
        head = 0
    st[ST_HEAD] = head
    nsub = int(rp[RP_NSUB])
    h = period / nsub
    omega = rp[RP_OMEGA]
    tau = rp[RP_TAU_COIL]
    i_target = rp[RP_COIL_GAIN] * current
    x = st[ST_X]
    v = st[ST_V]
    i = st[ST_I]
    f = 0.0
    for j in range(nsub):
        v_old = v
        if omega <= 0.0:
            # perfect tracking: the reference moves linearly over the period at rv
            x = r - rv * (period - (j + 1) * h)
            v = rv
        elif rp[RP_ORDER] == 1.0:
            g = 1.0 - math.exp(-omega * h)
            x_new = x + g * (r - x)
            v = (x_new - x) / h
            x = x_new
        else:
            zeta = rp[RP_ZETA]
            acc = omega * omega * (r - x) - 2.0 * zeta * omega * v
            v = v + h * acc
            x = x + h * v
        i = i + (1.0 - math.exp(-h / tau)) * (i_target - i) if tau > 0.0 else i_target
        a = (v - v_old) / h
        if a != 0.0:
            st[ST_A] = a
        DK.damper_sample(kind, p, s, ek, ep, es, x, v, st[ST_A], i)
        f = DK.damper_force(kind, p, s, x, v, i)
        DK.damper_advance(kind, p, s, x, v, i, h)
    st[ST_X] = x
    st[ST_V] = v
    st[ST_I] = i
    st[ST_F] = f
    st[ST_T] += period
