"""Safety supervisor and start-up sequence of the HiL loop (section 7.2 / spec section 11).

Limits are checked every tick on the commands and the measurements. On a trip the drive
current goes to 0 in the same tick, the actuator is ramped back to mid-stroke, the run
stops and the reason is recorded.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

from mrsuspension.errors import check_range

__all__ = ["SafetyLimits", "SafetySupervisor", "StartUp"]


@dataclass(frozen=True)
class SafetyLimits:
    """Trip limits.

    Parameters
    ----------
    current : float
        Drive current [A]: the controller's demand and the measured coil current (with
        ``current_tolerance``) must stay at or below it (0.3 A).
    current_tolerance : float
        Allowance on the measured current over ``current`` [A] (noise, A/D steps).
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
    """

    current: float = 0.3
    current_tolerance: float = 0.02
    stroke: float = 0.1
    velocity: float = 1.5
    force: float = 8800.0
    watchdog: float = 0.05
    return_rate: float = 0.05

    def __post_init__(self) -> None:
        for name in ("current", "stroke", "velocity", "force", "watchdog", "return_rate"):
            check_range(name, getattr(self, name), 0.0, None, low_inclusive=False)
        check_range("current_tolerance", self.current_tolerance, 0.0, None)

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
    """

    def __init__(
        self,
        limits: SafetyLimits | None = None,
        link_status: Callable[[], str | None] | None = None,
    ) -> None:
        self.limits = limits or SafetyLimits()
        self.link_status = link_status
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
        """Check a rig reading at loop time ``t``; True when it trips."""
        lim = self.limits
        if stamp > self._last_stamp:
            self._last_stamp = stamp
            self._last_fresh = t
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
        if abs(displacement) > lim.stroke:
            self.trip(f"measured stroke {displacement:.4f} m exceeds +/-{lim.stroke:g} m", t)
            return True
        if current > lim.current + lim.current_tolerance:
            self.trip(
                f"measured drive current {current:.4f} A exceeds {lim.current:g} A "
                f"(+{lim.current_tolerance:g} A tolerance)",
                t,
            )
            return True
        return False

    def check_command(self, t: float, stroke: float, velocity: float, current: float) -> bool:
        """Check the commands computed this tick; True when it trips."""
        lim = self.limits
        if current > lim.current + 1e-12:
            self.trip(f"drive current command {current:.4f} A exceeds {lim.current:g} A", t)
            return True
        if abs(stroke) > lim.stroke:
            self.trip(f"stroke command {stroke:.4f} m exceeds +/-{lim.stroke:g} m", t)
            return True
        if abs(velocity) > lim.velocity:
            self.trip(f"stroke velocity {velocity:.3f} m/s exceeds {lim.velocity:g} m/s", t)
            return True
        return False

    def describe(self) -> dict[str, Any]:
        """Trip state as plain data."""
        return {"tripped": self.tripped, "reason": self.reason, "trip_time": self.trip_time}
