"""Safety supervisor and start-up sequence of the HiL loop (model reference, section 11).

Limits are checked every tick on the commands and the measurements. On a trip the drive
current goes to 0 in the same tick, the actuator is ramped back to mid-stroke, the run
stops and the reason is recorded.

The checks are interlocks in the industrial sense: every comparison is written so that a
reading or a command that is not a number (NaN) or infinite fails it, and a reading
that no healthy rig can give (a negative current from a unipolar driver, a stroke beyond
the actuator's travel, a rig clock going backwards) trips as well, each with a one-line
reason naming the channel and the value:

>>> sup = SafetySupervisor()
>>> sup.check_sample(0.0, 120.0, 0.01, 0.1, 0.0)
False
>>> sup.check_sample(1e-3, 120.0, 0.01, float("nan"), 1e-3)
True
>>> sup.reason
"measured current is nan A: the rig's reading is not a number"
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

from mrsuspension.errors import ValidationError, check_range

__all__ = ["SafetyLimits", "SafetySupervisor", "StartUp"]

_INF = math.inf


@dataclass(frozen=True)
class SafetyLimits:
    """Trip limits.

    Parameters
    ----------
    current : float
        Drive current [A]: the controller's demand and the measured coil current (with
        ``current_tolerance``) must stay at or below it (0.3 A).
    current_tolerance : float
        Allowance on the measured current over ``current`` [A] (noise, A/D steps); for a
        unipolar driver also how far below 0 A a reading may go (sense offset and noise)
        before it counts as impossible.
    stroke : float
        |stroke| about mid-stroke [m], commanded or measured (the damper's 200 mm: 0.1 m).
    velocity : float
        |stroke rate| commanded [m/s].
    force : float
        |load-cell force| [N] (the load cell's 8.8 kN).
    watchdog : float
        Largest time [s] without a fresh rig sample (timestamp not advancing).
    return_rate : float
        Speed [m/s] of the ramp back to mid-stroke after a trip.
    travel : float
        The actuator's travel about mid-stroke [m] (the LVDT's +/-100 mm): a measured
        stroke beyond it is an impossible reading (a sensor or wiring fault).
    unipolar : bool
        The current driver can only drive current one way (the platform's amplifier, and
        :class:`~mrsuspension.hil.driver.PICurrentDriver`, give 0 to ``current``): a
        measured current below ``-current_tolerance`` is impossible and trips. False for
        a bipolar driver (the measured ``|current|`` is checked instead).
    """

    current: float = 0.3
    current_tolerance: float = 0.02
    stroke: float = 0.1
    velocity: float = 1.5
    force: float = 8800.0
    watchdog: float = 0.05
    return_rate: float = 0.05
    travel: float = 0.1
    unipolar: bool = True

    def __post_init__(self) -> None:
        for name in ("current", "stroke", "velocity", "force", "watchdog", "return_rate"):
            check_range(name, getattr(self, name), 0.0, None, low_inclusive=False)
        check_range("current_tolerance", self.current_tolerance, 0.0, None)
        check_range("travel", self.travel, 0.0, None, unit="m", low_inclusive=False)
        if not isinstance(self.unipolar, bool):
            raise ValidationError(f"unipolar must be True or False; got {self.unipolar!r}")

    def describe(self) -> dict[str, Any]:
        """The limits as plain data."""
        return asdict(self)


@dataclass(frozen=True)
class StartUp:
    """Start-up sequence (section 7.2.3): current 0, mid-stroke, extra light damping.

    During the first ``duration`` seconds the drive current is held at 0 and a viscous
    force ``c(t) v_d`` with ``c`` fading linearly from ``damping`` to 0 is added to the
    measured damper force given to the vehicle model (it resists the stroke rate, as the
    damper does); after it, the loop runs undisturbed.

    Parameters
    ----------
    duration : float
        Length of the start-up ramp [s] (0: none).
    damping : float
        Extra viscous damping at the start [N s/m].
    hold_current : bool
        Hold the drive current at 0 during the ramp.
    """

    duration: float = 0.5
    damping: float = 500.0
    hold_current: bool = True

    def __post_init__(self) -> None:
        check_range("duration", self.duration, 0.0, 60.0, unit="s")
        check_range("damping", self.damping, 0.0, None, unit="N s/m")

    def damping_at(self, t: float) -> float:
        """Extra damping [N s/m] at loop time ``t``."""
        if t >= self.duration or self.duration == 0.0:
            return 0.0
        return self.damping * (1.0 - t / self.duration)

    @classmethod
    def none(cls) -> StartUp:
        """No start-up ramp (for comparisons with offline runs)."""
        return cls(duration=0.0, damping=0.0, hold_current=False)


class SafetySupervisor:
    """Checks the limits each tick; remembers the first trip and its reason.

    Parameters
    ----------
    limits : SafetyLimits
        The trip limits.
    link_status : callable, optional
        Called when the watchdog trips; its text (e.g. the network rig's heartbeat state,
        :meth:`~mrsuspension.hil.rig.Rig.link_status`) is added to the reason.

    Notes
    -----
    :meth:`check_sample` and :meth:`check_command` run every tick of the hot loop: a
    healthy reading passes one chained comparison per channel (false for NaN, so a
    reading that is not a number always takes the slow path, which names the fault).
    """

    def __init__(
        self,
        limits: SafetyLimits | None = None,
        link_status: Callable[[], str | None] | None = None,
    ) -> None:
        self.limits = limits or SafetyLimits()
        self.link_status = link_status
        lim = self.limits
        # the healthy ranges, precomputed for the hot path (all finite: inf fails them)
        i_hi = lim.current + lim.current_tolerance
        self._f_hi = lim.force
        self._x_hi = min(lim.stroke, lim.travel)
        self._i_lo = -lim.current_tolerance if lim.unipolar else -i_hi
        self._i_hi = i_hi
        self._c_hi = lim.current + 1e-12
        self._s_hi = lim.stroke
        self._v_hi = lim.velocity
        self._watchdog = lim.watchdog
        self.reset()

    def reset(self) -> None:
        """Clear the trip; arm the watchdog."""
        self.tripped = False
        self.reason = ""
        self.trip_time = float("nan")
        self._last_stamp = float("-inf")
        self._last_fresh = 0.0

    def trip(self, reason: str, t: float) -> None:
        """Record a trip (the first reason wins)."""
        if not self.tripped:
            self.tripped = True
            self.reason = reason
            self.trip_time = t

    def check_sample(
        self, t: float, force: float, displacement: float, current: float, stamp: float
    ) -> bool:
        """Check a rig reading at loop time ``t``; True when it trips.

        Trips on a non-finite value of any channel (force, displacement, current,
        timestamp), a rig timestamp going backwards, no fresh sample (timestamp not
        advancing) for ``limits.watchdog``, ``|force|`` over ``limits.force``, a stroke
        beyond ``limits.travel`` (impossible) or ``limits.stroke``, a current below
        ``-current_tolerance`` with a unipolar driver (impossible) or over ``current +
        current_tolerance``.

        Examples
        --------
        >>> sup = SafetySupervisor()
        >>> sup.check_sample(0.0, 100.0, 0.0, -5.0, 0.0)
        True
        >>> sup.reason
        'measured current -5 A is below -0.02 A: impossible from a unipolar driver (a sensor or wiring fault)'
        """
        fh = self._f_hi
        xh = self._x_hi
        # the hot path: NaN fails every comparison, inf the finite bounds
        if -fh <= force <= fh and -xh <= displacement <= xh and self._i_lo <= current <= self._i_hi:
            if self._last_stamp < stamp < _INF:  # a fresh sample
                self._last_stamp = stamp
                self._last_fresh = t
                return False
            if stamp == self._last_stamp and t - self._last_fresh <= self._watchdog:
                return False  # a stale sample, within the watchdog's timeout
        return self._check_sample_slow(t, force, displacement, current, stamp)

    def _check_sample_slow(
        self, t: float, force: float, displacement: float, current: float, stamp: float
    ) -> bool:
        """The reading failed the hot path: stale, or a fault to name."""
        lim = self.limits
        for name, value, unit in (
            ("load-cell force", force, "N"),
            ("measured stroke", displacement, "m"),
            ("measured current", current, "A"),
            ("rig timestamp", stamp, "s"),
        ):
            if value != value:
                self.trip(f"{name} is nan {unit}: the rig's reading is not a number", t)
                return True
            if value in (_INF, -_INF):
                self.trip(f"{name} is {value} {unit}: the rig's reading is not finite", t)
                return True
        if stamp > self._last_stamp:
            self._last_stamp = stamp
            self._last_fresh = t
        elif stamp < self._last_stamp:
            self.trip(
                f"rig timestamp went backwards: {stamp:.6g} s after {self._last_stamp:.6g} s "
                "(the rig was reset or its clock is faulty)",
                t,
            )
            return True
        elif t - self._last_fresh > lim.watchdog:
            link = self.link_status() if self.link_status is not None else None
            self.trip(
                f"rig watchdog: no fresh sample for {t - self._last_fresh:.4f} s "
                f"(limit {lim.watchdog:g} s)" + (f"; {link}" if link else ""),
                t,
            )
            return True
        if abs(force) > lim.force:
            self.trip(f"load-cell force {force:.1f} N exceeds {lim.force:g} N", t)
            return True
        if abs(displacement) > lim.travel:
            self.trip(
                f"measured stroke {displacement:.4g} m is beyond the actuator's travel "
                f"+/-{lim.travel:g} m: impossible reading (a sensor or wiring fault)",
                t,
            )
            return True
        if abs(displacement) > lim.stroke:
            self.trip(f"measured stroke {displacement:.4f} m exceeds +/-{lim.stroke:g} m", t)
            return True
        if current < self._i_lo and lim.unipolar:
            self.trip(
                f"measured current {current:.4g} A is below {self._i_lo:g} A: impossible "
                "from a unipolar driver (a sensor or wiring fault)",
                t,
            )
            return True
        if abs(current) > self._i_hi:
            self.trip(
                f"measured drive current {current:.4f} A exceeds {lim.current:g} A "
                f"(+{lim.current_tolerance:g} A tolerance)",
                t,
            )
            return True
        return False  # a stale sample, within the watchdog's timeout

    def check_command(self, t: float, stroke: float, velocity: float, current: float) -> bool:
        """Check the commands computed this tick; True when it trips.

        Trips on a non-finite command, a current demand over ``limits.current``, a stroke
        over ``limits.stroke`` or a stroke rate over ``limits.velocity``.

        Examples
        --------
        >>> sup = SafetySupervisor()
        >>> sup.check_command(0.0, 0.01, 0.2, 0.1)
        False
        >>> sup.check_command(1e-3, float("nan"), 0.2, 0.1)
        True
        >>> sup.reason
        'stroke command is nan m: the vehicle model gave a value that is not a number'
        """
        sh = self._s_hi
        vh = self._v_hi
        if -_INF < current <= self._c_hi and -sh <= stroke <= sh and -vh <= velocity <= vh:
            return False
        lim = self.limits
        for name, value, unit, source in (
            ("drive current command", current, "A", "the controller"),
            ("stroke command", stroke, "m", "the vehicle model"),
            ("stroke velocity command", velocity, "m/s", "the vehicle model"),
        ):
            if not math.isfinite(value):
                what = "is not a number" if value != value else "is not finite"
                self.trip(f"{name} is {value} {unit}: {source} gave a value that {what}", t)
                return True
        if current > self._c_hi:
            self.trip(f"drive current command {current:.4f} A exceeds {lim.current:g} A", t)
            return True
        if abs(stroke) > lim.stroke:
            self.trip(f"stroke command {stroke:.4f} m exceeds +/-{lim.stroke:g} m", t)
            return True
        self.trip(f"stroke velocity {velocity:.3f} m/s exceeds {lim.velocity:g} m/s", t)
        return True

    def describe(self) -> dict[str, Any]:
        """Trip state as plain data."""
        return {"tripped": self.tripped, "reason": self.reason, "trip_time": self.trip_time}
