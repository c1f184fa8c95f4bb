"""The named measured signals a control law reads: one vector, one layout, one table.

At every control sample (the start of every engine step) both kernels fill a vector of
:data:`NS` values per corner (the quarter car's step for the laws that read them only,
codes from :data:`~mrsuspension.control.kernel.C_SIGNALS` on: the dissertation's laws read
the state's view and their step costs what it cost before), the **signals** (``S_*`` slots below), with what the
controller sees: the ideal value, or the ``[sensing]`` estimate where sensing is
configured (half and full car: the body velocity from the accelerometer's estimator, the
stroke and its rate from the stroke sensor, the body acceleration from the accelerometer's
held sample). The quarter car and the vehicles' corners fill the same layout, so a law
reads ``z_s_dot`` the same way on every vehicle.

The first six slots are the quarter-car view the built-in laws have always read (``z_s``,
``z_s'``, ``z_u``, ``z_u'`` and the sliding-mode reference ``z_s0``, ``z_s0'``), so the
built-in laws read exactly what they read before (the golden record holds bit for bit).

Accelerations and forces: the engine evaluates the rates at the end of every step, so at
the control sample the newest values are the previous step's last evaluation (at the
present state, with the previous step's current and road): ``z_s''``, ``z_u''``, ``F_d``
and ``i_d`` are **one step old** (``dt``, 0.1 ms by default), as a sampled controller
would see them (the damper's ``a_d`` has the same delay, model reference, section 7).

==================  ======  ========  ======================================================
name                slot    unit      what the controller sees
==================  ======  ========  ======================================================
``z_s``             S_ZS    m         body displacement at the corner (ideal)
``z_s_dot``         S_VS    m/s       body velocity at the corner: ideal, or the
                                      ``[sensing]`` estimate from the accelerometer
``z_u``             S_ZU    m         wheel displacement: ideal, or ``z_s`` + sensed stroke
``z_u_dot``         S_VU    m/s       wheel velocity: ideal, or ``z_s_dot`` + sensed stroke
                                      rate (``z_s_dot`` + true ``v_d`` without a stroke
                                      sensor)
``z_s0``            S_Z0    m         sliding-mode reference model (3.18) (0 otherwise)
``z_s0_dot``        S_V0    m/s       its velocity
``z_s_ddot``        S_AS    m/s^2     body acceleration at the corner, previous step's
                                      (with ``[sensing]``: the accelerometer's held sample)
``z_u_ddot``        S_AU    m/s^2     wheel acceleration, previous step's (ideal)
``x_d``             S_XD    m         stroke ``z_u - z_s`` as seen (sensed with a stroke
                                      sensor)
``v_d``             S_VD    m/s       stroke rate ``z_u' - z_s'`` as seen
``F_d``             S_FD    N         damper force, previous step's (the "load cell")
``i_d``             S_ID    A         drive current held over the previous step
``v_m``             S_VM    m/s       the controller's peak-velocity estimate
``time``            S_T     s         time at the control sample
``heave``           S_HEAVE m         body heave ``z`` (quarter car: ``z_s``)
``pitch``           S_PITCH rad       body pitch (quarter car: 0)
``roll``            S_ROLL  rad       body roll (quarter car and half car: 0)
``heave_dot``       S_VHEAVE m/s      heave velocity: ideal, or from the corners'
                                      estimates (``D^T v``, as modal skyhook; quarter
                                      car: ``z_s_dot``)
``pitch_dot``       S_VPITCH rad/s    pitch rate (likewise; quarter car: 0)
``roll_dot``        S_VROLL rad/s     roll rate (likewise; quarter car, half car: 0)
``heave_ddot``      S_AHEAVE m/s^2    heave acceleration, previous step's (ideal;
                                      quarter car: ``z_s_ddot``)
``pitch_ddot``      S_APITCH rad/s^2  pitch acceleration, previous step's (quarter car: 0)
``roll_ddot``       S_AROLL rad/s^2   roll acceleration, previous step's (quarter car: 0)
``corner``          S_CORNER          the corner's index (0 on a quarter car; the order
                                      of the vehicle's ``corners``)
==================  ======  ========  ======================================================

Examples
--------
>>> SIGNALS["z_s_dot"].slot == S_VS, SIGNALS["z_s_ddot"].unit
(True, 'm/s^2')
>>> len(SIGNALS) == NS
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from mrsuspension._numba_cache import INLINED

__all__ = [
    "NS",
    "SIGNALS",
    "SIGNAL_NAMES",
    "S_AHEAVE",
    "S_APITCH",
    "S_AROLL",
    "S_AS",
    "S_AU",
    "S_CORNER",
    "S_FD",
    "S_HEAVE",
    "S_ID",
    "S_PITCH",
    "S_ROLL",
    "S_T",
    "S_V0",
    "S_VD",
    "S_VHEAVE",
    "S_VM",
    "S_VPITCH",
    "S_VROLL",
    "S_VS",
    "S_VU",
    "S_XD",
    "S_Z0",
    "S_ZS",
    "S_ZU",
    "Signal",
    "fill_corner",
    "markdown_table",
]

# the slots (the first six: the quarter-car view of the built-in laws, unchanged)
(
    S_ZS, S_VS, S_ZU, S_VU, S_Z0, S_V0,
    S_AS, S_AU, S_XD, S_VD, S_FD, S_ID, S_VM, S_T,
    S_HEAVE, S_PITCH, S_ROLL, S_VHEAVE, S_VPITCH, S_VROLL, S_AHEAVE, S_APITCH, S_AROLL,
    S_CORNER,
) = range(24)  # fmt: skip
#: number of signals (the length of a corner's signal vector)
NS = 24


@dataclass(frozen=True)
class Signal:
    """One measured signal: its slot, unit and what the controller sees."""

    name: str
    slot: int
    unit: str
    description: str
    quarter_car: str = ""


#: Every signal by name (the names a user law's parameters take, see
#: :mod:`mrsuspension.control.user`), in slot order.
SIGNALS: dict[str, Signal] = {
    s.name: s
    for s in (
        Signal("z_s", S_ZS, "m", "body displacement at the corner (ideal)"),
        Signal("z_s_dot", S_VS, "m/s", "body velocity at the corner: ideal or [sensing] estimate"),
        Signal("z_u", S_ZU, "m", "wheel displacement: ideal, or z_s + sensed stroke"),
        Signal("z_u_dot", S_VU, "m/s", "wheel velocity: ideal, or z_s_dot + sensed stroke rate"),
        Signal("z_s0", S_Z0, "m", "sliding-mode reference model (3.18); 0 for other laws"),
        Signal("z_s0_dot", S_V0, "m/s", "the reference model's velocity"),
        Signal("z_s_ddot", S_AS, "m/s^2", "body acceleration at the corner, previous step's"),
        Signal("z_u_ddot", S_AU, "m/s^2", "wheel acceleration, previous step's (ideal)"),
        Signal("x_d", S_XD, "m", "stroke z_u - z_s as seen"),
        Signal("v_d", S_VD, "m/s", "stroke rate z_u_dot - z_s_dot as seen"),
        Signal("F_d", S_FD, "N", "damper force, previous step's"),
        Signal("i_d", S_ID, "A", "drive current held over the previous step"),
        Signal("v_m", S_VM, "m/s", "the controller's peak-velocity estimate"),
        Signal("time", S_T, "s", "time at the control sample"),
        Signal("heave", S_HEAVE, "m", "body heave", "z_s"),
        Signal("pitch", S_PITCH, "rad", "body pitch (nose down)", "0"),
        Signal("roll", S_ROLL, "rad", "body roll (left up)", "0"),
        Signal(
            "heave_dot", S_VHEAVE, "m/s", "heave velocity: ideal or from the estimates", "z_s_dot"
        ),
        Signal("pitch_dot", S_VPITCH, "rad/s", "pitch rate: ideal or from the estimates", "0"),
        Signal("roll_dot", S_VROLL, "rad/s", "roll rate: ideal or from the estimates", "0"),
        Signal("heave_ddot", S_AHEAVE, "m/s^2", "heave acceleration, previous step's", "z_s_ddot"),
        Signal("pitch_ddot", S_APITCH, "rad/s^2", "pitch acceleration, previous step's", "0"),
        Signal("roll_ddot", S_AROLL, "rad/s^2", "roll acceleration, previous step's", "0"),
        Signal("corner", S_CORNER, "", "the corner's index (order of the vehicle's corners)", "0"),
    )
}
#: the signal names in slot order
SIGNAL_NAMES: tuple[str, ...] = tuple(SIGNALS)


@njit(cache=True, **INLINED)
def fill_corner(
    sig: np.ndarray,
    zs: float,
    vs: float,
    zu: float,
    vu: float,
    z0: float,
    v0: float,
    a_s: float,
    a_u: float,
    fd: float,
    i_d: float,
    vm: float,
    t: float,
) -> None:
    """Write a corner's signals ``S_ZS`` to ``S_T`` (as seen) into ``sig``.

    The body's signals (``S_HEAVE`` on) are the caller's: the quarter car's follow from
    these, a vehicle's from its body.

    Examples
    --------
    >>> sig = np.zeros(NS)
    >>> fill_corner(sig, 0.0, 0.1, 0.01, 0.3, 0.0, 0.0, 1.0, 2.0, 50.0, 0.2, 0.3, 0.5)
    >>> round(float(sig[S_XD]), 6), round(float(sig[S_VD]), 6), float(sig[S_T])
    (0.01, 0.2, 0.5)
    """
    sig[S_ZS] = zs
    sig[S_VS] = vs
    sig[S_ZU] = zu
    sig[S_VU] = vu
    sig[S_Z0] = z0
    sig[S_V0] = v0
    sig[S_AS] = a_s
    sig[S_AU] = a_u
    sig[S_XD] = zu - zs
    sig[S_VD] = vu - vs
    sig[S_FD] = fd
    sig[S_ID] = i_d
    sig[S_VM] = vm
    sig[S_T] = t


def markdown_table() -> str:
    """The signal table in Markdown (for the docs).

    Examples
    --------
    >>> markdown_table().splitlines()[2].startswith("| `z_s` ")
    True
    """
    rows = ["| name | unit | what the controller sees | quarter car |", "|---|---|---|---|"]
    for s in SIGNALS.values():
        rows.append(f"| `{s.name}` | {s.unit} | {s.description} | {s.quarter_car or 'as named'} |")
    return "\n".join(rows)
