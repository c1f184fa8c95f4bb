"""Rig interface of the hardware-in-the-loop platform, and the simulated rig.

A :class:`Rig` is what the real-time loop talks to each tick: it is told a damper stroke
and a coil-current command (:meth:`Rig.command`) and reports the load-cell force, the
actuator displacement (LVDT) and the measured coil current (:meth:`Rig.read`), with the
rig's own timestamp (for the watchdog).

:class:`SimulatedRig` models a servo-hydraulic rig (dissertation section 7.2.2): an
actuator of configurable bandwidth (first or second order) behind a transport delay, a
coil/amplifier first-order lag, load-cell / displacement / current-sense noise (seeded)
and 12-bit A/D quantisation, with any damper model of the toolkit as the "hardware",
advanced through the damper's compiled kernels. :func:`ideal_rig` is the preset with no
delay, no noise, perfect tracking and an instantaneous coil.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from mrsuspension.dampers import DamperModel, WangSymmetric
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.errors import ValidationError, check_range
from mrsuspension.hil import _kernels as RK

__all__ = ["AD_BITS", "Rig", "RigSample", "SimulatedRig", "ideal_rig"]

#: resolution of the DSP board's A/D and D/A converters (section 7.2.2)
AD_BITS = 12
#: load-cell capacity [N] (section 7.2)
LOAD_CELL_CAPACITY = 8800.0
#: LVDT range about mid-stroke [m] (the damper's 200 mm stroke)
LVDT_RANGE = 0.1
#: current-sense full scale [A] (1 ohm sense resistor behind a gain stage)
CURRENT_SENSE_RANGE = 0.5
_NOISE_BLOCK = 4096


class RigSample(NamedTuple):
    """One reading of the rig.

    Attributes
    ----------
    force : float
        Load-cell force F_dm [N], positive resisting compression.
    displacement : float
        Actuator displacement x_m [m] about mid-stroke, compression positive.
    current : float
        Measured coil current i_dm [A] (sense voltage across 1 ohm).
    timestamp : float
        Rig time of the sample [s]; a watchdog trips when it stops advancing.
    """

    force: float
    displacement: float
    current: float
    timestamp: float


class Rig(ABC):
    """What the real-time loop needs from a test rig (simulated, networked or real).

    A tick is ``read()`` (the state reached after the previous command) then
    ``command(...)``. ``reset(period)`` puts the actuator at mid-stroke with the coil off.
    """

    #: True when the coil follows the command at once (the loop then skips the PI regulator)
    ideal_current: bool = False

    @abstractmethod
    def reset(self, period: float) -> None:
        """Mid-stroke, current 0, fresh internals; the loop will tick every ``period`` s."""

    @abstractmethod
    def command(self, stroke: float, current_command: float, velocity: float = 0.0) -> None:
        """Command the actuator to ``stroke`` [m] and the amplifier to ``current_command`` [A].

        ``velocity`` [m/s] is the stroke-rate feed-forward of the servo controller (the
        model's v_d); a rig may ignore it.
        """

    @abstractmethod
    def read(self) -> RigSample:
        """The latest measurement."""

    def close(self) -> None:  # noqa: B027 (optional hook)
        """Release resources (sockets, files); the default does nothing."""

    def link_status(self) -> str | None:
        """State of the link to the rig, for a watchdog trip's reason (None: no link)."""
        return None

    def describe(self) -> dict[str, Any]:
        """Plain-data description for the recording's metadata."""
        return {"rig": type(self).__name__}


def _quantise(value: float, full_scale: float, bits: int) -> float:
    """Bipolar A/D conversion of ``value`` over ``[-full_scale, full_scale)`` (saturating).

    A NaN or infinite value (a simulated state that blew up) is returned as it is, for the
    safety supervisor to trip on, rather than raising (``math.floor(nan)``).

    >>> _quantise(0.1234, 0.5, 12), _quantise(float("nan"), 0.5, 12)
    (0.123291015625, nan)
    """
    if not -math.inf < value < math.inf:
        return value
    lsb = 2.0 * full_scale / (1 << bits)
    q = math.floor(value / lsb + 0.5) * lsb
    if q > full_scale - lsb:
        return full_scale - lsb
    if q < -full_scale:
        return -full_scale
    return q


@dataclass
class SimulatedRig(Rig):
    """A servo-hydraulic rig carrying a damper model, simulated tick by tick.

    Parameters
    ----------
    damper : DamperModel
        The "hardware" (default: the dissertation's symmetric model).
    bandwidth : float
        Actuator bandwidth [Hz] (corner of the first-order, natural frequency of the
        second-order closed loop); 0 means perfect tracking.
    order : int
        1 or 2 (actuator closed-loop order).
    damping_ratio : float
        Damping ratio of the second-order actuator.
    delay : float
        Transport delay of the stroke command [s] (rounded to whole ticks; default 1 ms).
        The loop feeds the measured force of a stiff hysteretic damper back through this
        delay: at 2 ms the skyhook hi-lo example oscillates (body acceleration RMS 14.9
        against 3.13 m/s^2 offline), at 1 ms it is within 7 %, at 0 within 1.5 %.
    coil_time_constant : float
        Coil + amplifier first-order time constant [s]; 0: instantaneous.
    coil_gain : float
        Amplifier gain (1 nominal; other values model a fault, e.g. for the over-current
        trip).
    force_noise, displacement_noise, current_noise : float
        Standard deviations [N], [m], [A] of the sensor noise.
    bits : int
        A/D resolution (default 12; 0 disables quantisation).
    force_range, displacement_range, current_range : float
        A/D full scales [N], [m], [A].
    seed : int
        Noise seed.
    max_substep : float
        Largest internal integration step [s].
    """

    damper: DamperModel | None = None
    bandwidth: float = 40.0
    order: int = 2
    damping_ratio: float = 0.7
    delay: float = 0.001
    coil_time_constant: float = 0.008
    coil_gain: float = 1.0
    force_noise: float = 5.0
    displacement_noise: float = 2e-5
    current_noise: float = 5e-4
    bits: int = AD_BITS
    force_range: float = LOAD_CELL_CAPACITY
    displacement_range: float = LVDT_RANGE
    current_range: float = CURRENT_SENSE_RANGE
    seed: int = 0
    max_substep: float = 1e-4

    def __post_init__(self) -> None:
        if self.damper is None:
            self.damper = WangSymmetric(vh_variant=VEHICLE_VH_VARIANT)
        check_range("bandwidth", self.bandwidth, 0.0, None, unit="Hz")
        if self.order not in (1, 2):
            raise ValidationError(f"order must be 1 or 2; got {self.order!r}")
        check_range("damping_ratio", self.damping_ratio, 0.0, 10.0, low_inclusive=False)
        check_range("delay", self.delay, 0.0, 1.0, unit="s")
        check_range("coil_time_constant", self.coil_time_constant, 0.0, 10.0, unit="s")
        check_range("coil_gain", self.coil_gain, 0.0, 100.0)
        for name in ("force_noise", "displacement_noise", "current_noise"):
            check_range(name, getattr(self, name), 0.0, None)
        if not 0 <= int(self.bits) <= 24:
            raise ValidationError(f"bits must be in 0..24; got {self.bits!r}")
        check_range("max_substep", self.max_substep, 0.0, 0.01, unit="s", low_inclusive=False)
        self.ideal_current = self.coil_time_constant == 0.0 and self.coil_gain == 1.0
        self._period = 0.0

    # -- interface ----------------------------------------------------------------------
    def reset(self, period: float) -> None:
        """Mid-stroke, coil off, fresh damper internals and noise stream."""
        period = float(check_range("period", period, 0.0, 0.1, unit="s", low_inclusive=False))
        assert self.damper is not None
        self._period = period
        if self.bandwidth > 0.0:
            omega = 2.0 * math.pi * self.bandwidth
            # substeps: accurate actuator dynamics and a stable damper integration
            h = min(self.max_substep, 0.2 / omega)
            nsub = max(1, math.ceil(period / h - 1e-9))
        else:
            omega = 0.0
            nsub = (
                max(1, math.ceil(period / self.max_substep - 1e-9)) if self.damper.stateful else 1
            )
        self._nsub = nsub
        kern = self.damper.kernel(period / nsub)
        self._kind = int(kern.kind)
        self._p = kern.params
        self._s = kern.state
        self._ek = int(kern.estimator_code)
        self._ep = kern.estimator_params
        self._es = kern.estimator_state
        nd = round(self.delay / period)
        self._ndelay = nd
        self._rp = np.zeros(RK.RP_SIZE)
        self._rp[RK.RP_OMEGA] = omega
        self._rp[RK.RP_ORDER] = float(self.order)
        self._rp[RK.RP_ZETA] = self.damping_ratio
        self._rp[RK.RP_TAU_COIL] = self.coil_time_constant
        self._rp[RK.RP_COIL_GAIN] = self.coil_gain
        self._rp[RK.RP_NSUB] = float(nsub)
        self._rp[RK.RP_NDELAY] = float(nd)
        self._st = np.zeros(RK.ST_SIZE)
        self._ref_x = np.zeros(nd + 1)
        self._ref_v = np.zeros(nd + 1)
        self._rng = np.random.default_rng(self.seed)
        self._noise = np.empty((_NOISE_BLOCK, 3))
        self._noise_k = _NOISE_BLOCK
        self._noisy = self.force_noise > 0 or self.displacement_noise > 0 or self.current_noise > 0
        # the force of the resting damper at mid-stroke (a first read before any command)
        self._st[RK.ST_T] = 0.0

    def command(self, stroke: float, current_command: float, velocity: float = 0.0) -> None:
        """Advance the simulated hardware by one period under this command."""
        RK.rig_tick(
            self._st, self._rp, self._ref_x, self._ref_v, stroke, velocity, current_command,
            self._period, self._kind, self._p, self._s, self._ek, self._ep, self._es,
        )  # fmt: skip

    def read(self) -> RigSample:
        """Load cell, LVDT and current sense after noise and A/D conversion."""
        st = self._st
        f, x, i = st[RK.ST_F], st[RK.ST_X], st[RK.ST_I]
        if self._noisy:
            k = self._noise_k
            if k >= _NOISE_BLOCK:
                self._rng.standard_normal(out=self._noise)
                k = 0
            row = self._noise[k]
            f += self.force_noise * row[0]
            x += self.displacement_noise * row[1]
            i += self.current_noise * row[2]
            self._noise_k = k + 1
        bits = self.bits
        if bits:
            f = _quantise(f, self.force_range, bits)
            x = _quantise(x, self.displacement_range, bits)
            i = _quantise(i, self.current_range, bits)
        return RigSample(float(f), float(x), float(i), float(st[RK.ST_T]))

    # -- extras -------------------------------------------------------------------------
    @property
    def true_state(self) -> dict[str, float]:
        """Noise-free actuator and coil state (for tests and diagnostics)."""
        st = self._st
        return {
            "time": float(st[RK.ST_T]),
            "displacement": float(st[RK.ST_X]),
            "velocity": float(st[RK.ST_V]),
            "current": float(st[RK.ST_I]),
            "force": float(st[RK.ST_F]),
        }

    @property
    def delay_ticks(self) -> int:
        """Transport delay in whole ticks (after :meth:`reset`)."""
        return int(self._ndelay)

    def describe(self) -> dict[str, Any]:
        """Plain-data description of the rig and its damper."""
        assert self.damper is not None
        return {
            "rig": "simulated",
            "damper": self.damper.describe(),
            "bandwidth": self.bandwidth,
            "order": self.order,
            "damping_ratio": self.damping_ratio,
            "delay": self.delay,
            "coil_time_constant": self.coil_time_constant,
            "coil_gain": self.coil_gain,
            "force_noise": self.force_noise,
            "displacement_noise": self.displacement_noise,
            "current_noise": self.current_noise,
            "bits": self.bits,
            "seed": self.seed,
        }


def ideal_rig(damper: DamperModel | None = None) -> SimulatedRig:
    """The ideal preset: no delay, no noise, no quantisation, perfect tracking, coil instantaneous.

    With it, the HiL loop reproduces the offline simulation (same scenario, same step).
    """
    return SimulatedRig(
        damper=damper,
        bandwidth=0.0,
        delay=0.0,
        coil_time_constant=0.0,
        force_noise=0.0,
        displacement_noise=0.0,
        current_noise=0.0,
        bits=0,
    )
