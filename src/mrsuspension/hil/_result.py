"""A HiL run's outcome: the recorded channels, the tick statistics, the result.

Part of the loop (:mod:`mrsuspension.hil.loop`, which re-exports every name here): the
channel layout of the recording (:data:`CHANNELS`, loop states ``STATE_*``), how a run
ends (:data:`ENDINGS`, the STOP reasons), :class:`TickStats`, :class:`HilResult` and
:func:`load_result` (a finished run rebuilt from its recording directory).
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.errors import MRSuspensionError
from mrsuspension.hil.recorder import Recording, load_recording

__all__ = [
    "CHANNELS",
    "ENDINGS",
    "STATE_RETURN",
    "STATE_RUN",
    "STATE_STARTUP",
    "STATE_TRIPPED",
    "STOP_REASON",
    "STOP_REASONS",
    "HilResult",
    "TickStats",
    "check_recording_memory",
    "load_result",
]

#: the stop reason recorded when the operator presses STOP (the safety path, not a trip
#: of a limit)
STOP_REASON = "STOP pressed"
#: the reason of a stop asked through the hooks' stop flag, by its code
#: (:meth:`~mrsuspension.hil.tap.StopFlag.code`; a flag without codes gives STOP_REASON)
STOP_REASONS = {1: STOP_REASON, 2: "the monitor shut down"}
_STOPPED = frozenset(STOP_REASONS.values())

#: how a run ended (``HilResult.ending``, ``stop.json``'s ``ending``)
ENDINGS = (
    "completed",  # ran its duration and returned to mid-stroke
    "stopped",  # the operator's STOP
    "tripped",  # a safety limit, an interlock, the rig watchdog (a dead link), a diverged model
    "failed",  # an exception in a tick, or the rig could not be commanded
    "recording failed",  # the recorder's writer ended (a full disk)
    "interrupted",  # SIGINT, SIGTERM or SIGHUP (``signal``)
    "orphaned",  # the process that started the loop ended (bind_to_parent)
)

#: loop states (the ``state`` channel)
STATE_STARTUP, STATE_RUN, STATE_RETURN, STATE_TRIPPED = 0, 1, 2, 3

#: recorded channels and their units, in column order
CHANNELS: tuple[tuple[str, str], ...] = (
    ("time", "s"),  # loop time of the tick (release k T)
    ("state", "-"),  # 0 start-up, 1 running, 2 returning after the run, 3 tripped
    ("z_r", "m"),
    ("z_r_dot", "m/s"),
    ("z_s", "m"),
    ("z_u", "m"),
    ("z_s_dot", "m/s"),
    ("z_u_dot", "m/s"),
    ("z_s_ddot", "m/s^2"),
    ("z_u_ddot", "m/s^2"),
    ("x_d", "m"),  # model stroke (compression positive)
    ("v_d", "m/s"),
    ("F_dm", "N"),  # measured (load-cell) force
    ("F_d", "N"),  # force applied to the model (F_dm + start-up damping)
    ("F_T", "N"),
    ("i_d", "A"),  # controller's drive-current demand
    ("i_cmd", "A"),  # regulator output (D/A) to the amplifier
    ("i_dm", "A"),  # measured coil current
    ("x_cmd", "m"),  # stroke command to the actuator
    ("x_m", "m"),  # measured actuator displacement
    ("rig_time", "s"),
    ("compute", "s"),  # compute time of the tick
    ("lateness", "s"),  # release lateness of the tick
)
_NAMES = tuple(n for n, _ in CHANNELS)


def check_recording_memory(duration: float, rate: float, *, name: str = "duration") -> None:
    """Refuse a run whose recording (``duration`` x ``rate`` rows of every channel, 8
    bytes each) would not fit in memory when read back: more than half the RAM
    (:func:`mrsuspension.engine.settings.check_memory`).

    Raises
    ------
    ValidationError
        Naming ``name``, the duration, the estimate and the limit.

    Examples
    --------
    >>> check_recording_memory(10.0, 1000.0)  # 10 000 rows: a few MB
    >>> check_recording_memory(1e5, 1e5)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: duration = 100000 s needs about ... GiB of memory ...
    """
    from mrsuspension.engine.settings import check_memory

    check_memory(
        duration,
        float(duration) * float(rate) * len(_NAMES),
        name=name,
        hint="shorten the duration or lower the loop rate",
    )


@dataclass(frozen=True)
class TickStats:
    """Deadline statistics of a run (times in seconds).

    Attributes
    ----------
    ticks : int
        Ticks run.
    period : float
        Nominal period [s].
    misses : int
        Ticks that ended after their deadline (the next release).
    in_deadline : float
        Fraction of ticks that met their deadline.
    compute_p50, compute_p99, compute_max : float
        Per-tick compute time.
    lateness_p50, lateness_p99, lateness_max : float
        Release lateness (start of the tick after its scheduled release).
    jitter : float
        Standard deviation of the start-to-start interval.
    realtime : bool
        Whether the loop was paced (False: ticks back to back, as fast as possible).
    jitter_max : float
        Largest deviation of a start-to-start interval from the period.
    scheduling : str
        How the loop was scheduled (:meth:`~mrsuspension.hil.realtime.RealtimeSession.label`:
        mode, policy, core, and any step the system refused).
    """

    ticks: int
    period: float
    misses: int
    in_deadline: float
    compute_p50: float
    compute_p99: float
    compute_max: float
    lateness_p50: float
    lateness_p99: float
    lateness_max: float
    jitter: float
    realtime: bool = True
    jitter_max: float = 0.0
    scheduling: str = ""

    @classmethod
    def from_arrays(
        cls,
        compute: np.ndarray,
        lateness: np.ndarray,
        period: float,
        realtime: bool,
        scheduling: str = "",
    ) -> TickStats:
        """Statistics of per-tick compute times and lateness.

        Examples
        --------
        >>> s = TickStats.from_arrays(np.full(4, 1e-4), np.array([0, 0, 2e-3, 0.0]), 1e-3, True)
        >>> s.misses, round(s.jitter_max, 6)
        (1, 0.002)
        """
        n = int(compute.size)
        if n == 0:
            nan = math.nan
            return cls(
                0, period, 0, 1.0, nan, nan, nan, nan, nan, nan, nan, realtime, nan, scheduling
            )
        end = lateness + compute
        misses = int(np.count_nonzero(end > period)) if realtime else 0
        starts = np.arange(n) * period + lateness
        intervals = np.diff(starts)
        jitter = float(np.std(intervals)) if n > 2 else 0.0
        jitter_max = float(np.max(np.abs(intervals - period))) if n > 1 and realtime else 0.0
        c50, c99 = np.percentile(compute, [50, 99])
        l50, l99 = np.percentile(lateness, [50, 99])
        return cls(
            ticks=n,
            period=period,
            misses=misses,
            in_deadline=1.0 - misses / n,
            compute_p50=float(c50),
            compute_p99=float(c99),
            compute_max=float(compute.max()),
            lateness_p50=float(l50),
            lateness_p99=float(l99),
            lateness_max=float(lateness.max()),
            jitter=jitter,
            realtime=realtime,
            jitter_max=jitter_max,
            scheduling=scheduling,
        )

    def describe(self) -> dict[str, Any]:
        """The statistics as plain data."""
        return dataclasses.asdict(self)

    def summary(self) -> str:
        """One human-readable paragraph (microseconds)."""
        us = 1e6
        if not self.realtime:
            return (
                f"{self.ticks} ticks at {1.0 / self.period:g} Hz UNPACED (as fast as possible, "
                f"not real time); compute p50 {self.compute_p50 * us:.1f} us, "
                f"p99 {self.compute_p99 * us:.1f} us, max {self.compute_max * us:.1f} us"
            )
        sched = f"; scheduling {self.scheduling}" if self.scheduling else ""
        return (
            f"{self.ticks} ticks at {1.0 / self.period:g} Hz: {100 * self.in_deadline:.3f} % "
            f"in deadline ({self.misses} misses); compute p50 {self.compute_p50 * us:.1f} us, "
            f"p99 {self.compute_p99 * us:.1f} us, max {self.compute_max * us:.1f} us; "
            f"lateness p50 {self.lateness_p50 * us:.1f} us, p99 {self.lateness_p99 * us:.1f} us, "
            f"max {self.lateness_max * us:.1f} us; jitter {self.jitter * us:.1f} us "
            f"(max {self.jitter_max * us:.1f} us){sched}"
        )


@dataclass
class HilResult:
    """Outcome of :func:`run_hil`.

    Attributes
    ----------
    recording : Recording
        Every channel at loop rate (:data:`CHANNELS`).
    stats : TickStats
        Deadline statistics.
    reason : str
        Why the run stopped (``"completed"`` or the trip reason).
    tripped : bool
        True when the safety supervisor stopped the run.
    out : Path or None
        The recording directory (None when recorded to a temporary one and removed).
    meta : dict
        The recording's metadata.
    ending : str
        How the run ended, one of :data:`ENDINGS` (``"completed"``, ``"tripped"``,
        ``"interrupted"``...).
    signal : int or None
        The signal that stopped the run (SIGINT, SIGTERM, SIGHUP), if any.
    """

    recording: Recording
    stats: TickStats
    reason: str
    tripped: bool
    out: Path | None = None
    meta: dict[str, Any] = field(default_factory=dict)
    ending: str = "completed"
    signal: int | None = None

    def running(self) -> np.ndarray:
        """Mask of the rows recorded while the model ran (start-up and running)."""
        return self.recording["state"] <= STATE_RUN

    def rms(self, channel: str) -> float:
        """RMS of a channel over the running part of the run."""
        x = self.recording[channel][self.running()]
        return float(np.sqrt(np.mean(x * x))) if x.size else math.nan

    @property
    def corner(self) -> str | None:
        """The rig corner of a half or full car run (None: a quarter car)."""
        vehicle = self.meta.get("vehicle")
        return str(vehicle["corner"]) if isinstance(vehicle, dict) else None

    def describe(self) -> dict[str, Any]:
        """Plain-data summary (for ``--json``); a vehicle run adds its rig ``corner`` and
        the RMS heave acceleration (``rms_body_acceleration`` is the body's at that corner)."""
        out = {
            "reason": self.reason,
            "tripped": self.tripped,
            "ending": self.ending,
            "signal": self.signal,
            "rows": len(self.recording),
            "out": str(self.out) if self.out else None,
            "stats": self.stats.describe(),
            "rms_body_acceleration": self.rms("z_s_ddot"),
        }
        if self.corner is not None:
            out["corner"] = self.corner
            out["rms_heave_acceleration"] = self.rms("heave_ddot")
        return out


def load_result(out: str | Path) -> HilResult:
    """The :class:`HilResult` of a finished run from its recording directory.

    What :func:`run_hil` returns, rebuilt from the recording (its stop record holds the
    reason and the tick statistics): used for runs in their own process.

    Raises
    ------
    MRSuspensionError
        When the recording is incomplete (the run has not finished or its process died).

    Examples
    --------
    >>> import tempfile
    >>> from mrsuspension.engine.simulate import Simulation
    >>> from mrsuspension.excitation import Harmonic
    >>> from mrsuspension.hil.loop import run_hil
    >>> out = Path(tempfile.mkdtemp()) / "rec"
    >>> run = run_hil(Simulation(Harmonic(1.5, 0.01)), duration=0.05, realtime="unpaced", out=out)
    >>> again = load_result(out)
    >>> again.reason, again.stats == run.stats, again.describe()["rows"] == len(run.recording)
    ('completed', True, True)
    """
    out = Path(out)
    recording = load_recording(out)
    stop = recording.stop
    if not recording.complete:
        raise MRSuspensionError(
            f"the HiL run in {out} did not finish; its recording holds {len(recording)} rows"
        )
    if "stats" not in stop:
        raise MRSuspensionError(
            f"the HiL run in {out} failed: {stop.get('reason', 'no reason recorded')}; "
            f"its recording holds {len(recording)} rows"
        )
    stats = TickStats(**stop["stats"])
    meta = json.loads((out / "meta.json").read_text()) if (out / "meta.json").exists() else {}
    signum = stop.get("signal")
    return HilResult(
        recording=recording,
        stats=stats,
        reason=str(stop.get("reason", "")),
        tripped=bool(stop.get("tripped", False)),
        out=out,
        meta=meta,
        ending=str(stop.get("ending", "tripped" if stop.get("tripped") else "completed")),
        signal=None if signum is None else int(signum),
    )
