"""Acquisition settings of the monitor: what part of the HiL recording is downloaded.

The HiL loop records every channel at the loop rate through its
:class:`~mrsuspension.hil.recorder.Recorder` (a writer process, never the loop's hot path).
The page's acquisition controls select from that recording: record start/stop windows
(loop time), the acquisition period (every k-th tick), a trigger (the first crossing of a
channel through a level, with a pre-trigger time) and the display sampling rate of the
live stream (which does not affect the recording).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension.errors import ValidationError
from mrsuspension.hil.loop import CHANNELS
from mrsuspension.hil.recorder import Recording

__all__ = ["DISPLAY_RATES", "EDGES", "Acquisition", "acquisition_from_settings"]

#: trigger edges
EDGES = ("rising", "falling", "either")
#: display sampling rates offered by the page [Hz]
DISPLAY_RATES = (20.0, 50.0, 100.0, 200.0)
#: longest acquisition period [ticks] (100 s at 1 kHz)
MAX_PERIOD = 100_000
_NAMES = tuple(n for n, _ in CHANNELS)


@dataclass(frozen=True)
class Acquisition:
    """Which rows of a recording are acquired.

    Parameters
    ----------
    period : int
        Keep every ``period``-th tick (1: all).
    trigger : str, optional
        Channel whose crossing of ``level`` starts the acquisition (None: no trigger).
    level : float
        Trigger level (in the channel's unit).
    edge : {"rising", "falling", "either"}
        Crossing direction.
    pre_trigger : float
        Seconds kept before the trigger.
    windows : tuple of (start, stop)
        Record start/stop pairs in loop time [s] (stop None: still recording); empty:
        the whole run.
    display_rate : float
        Sampling rate of the live display [Hz] (one of :data:`DISPLAY_RATES`).

    Examples
    --------
    >>> import numpy as np
    >>> acq = Acquisition(trigger="z_r", level=0.0, pre_trigger=0.1)
    >>> t = np.arange(0.0, 1.0, 0.01)
    >>> idx = acq.select({"time": t, "z_r": np.where(t < 0.5, -1.0, 1.0)})
    >>> round(float(t[idx[0]]), 2)
    0.4
    """

    period: int = 1
    trigger: str | None = None
    level: float = 0.0
    edge: str = "rising"
    pre_trigger: float = 0.0
    windows: tuple[tuple[float, float | None], ...] = field(default_factory=tuple)
    display_rate: float = 100.0

    def __post_init__(self) -> None:
        if (
            isinstance(self.period, bool)
            or not isinstance(self.period, int)
            or not 1 <= self.period <= MAX_PERIOD
        ):
            raise ValidationError(
                f"acquisition period must be a whole number of ticks in [1, {MAX_PERIOD}]; "
                f"got {self.period!r}"
            )
        if self.trigger is not None and self.trigger not in _NAMES:
            raise ValidationError(
                f"unknown trigger channel {self.trigger!r}; valid: {', '.join(_NAMES)}"
            )
        if self.edge not in EDGES:
            raise ValidationError(f"unknown trigger edge {self.edge!r}; valid: {', '.join(EDGES)}")
        if not math.isfinite(self.level):
            raise ValidationError(f"trigger level must be finite; got {self.level!r}")
        if not (math.isfinite(self.pre_trigger) and 0.0 <= self.pre_trigger <= 60.0):
            raise ValidationError(f"pre-trigger must be in [0, 60] s; got {self.pre_trigger!r}")
        if self.display_rate not in DISPLAY_RATES:
            raise ValidationError(
                f"display rate must be one of {', '.join(f'{r:g}' for r in DISPLAY_RATES)} Hz; "
                f"got {self.display_rate!r}"
            )

    # -- record start/stop ---------------------------------------------------------------
    @property
    def recording(self) -> bool:
        """Whether a record window is open."""
        return bool(self.windows) and self.windows[-1][1] is None

    def start(self, t: float) -> Acquisition:
        """Open a record window at loop time ``t`` (no-op when one is open)."""
        if self.recording:
            return self
        return replace(self, windows=(*self.windows, (float(t), None)))

    def stop(self, t: float) -> Acquisition:
        """Close the open record window at loop time ``t``."""
        if not self.recording:
            return self
        start = self.windows[-1][0]
        return replace(self, windows=(*self.windows[:-1], (start, max(start, float(t)))))

    # -- selection -----------------------------------------------------------------------
    def select(self, data: Mapping[str, np.ndarray] | Recording) -> np.ndarray:
        """Indices of the acquired rows of ``data`` (a recording or channel arrays)."""
        t = np.asarray(data["time"], dtype=float)
        if self.windows:
            keep = np.zeros(t.size, dtype=bool)
            for a, b in self.windows:
                keep |= (t >= a) & (t < (math.inf if b is None else b))
        else:
            keep = np.ones(t.size, dtype=bool)
        if self.trigger is not None:
            x = np.asarray(data[self.trigger], dtype=float) - self.level
            up = (x[:-1] < 0.0) & (x[1:] >= 0.0)
            down = (x[:-1] > 0.0) & (x[1:] <= 0.0)
            hit = {"rising": up, "falling": down, "either": up | down}[self.edge]
            hit &= keep[1:]
            fired = np.flatnonzero(hit)
            if fired.size == 0:
                return np.zeros(0, dtype=int)
            t_trig = t[fired[0] + 1]
            keep = (keep & (t >= t_trig)) | (
                (t >= t_trig - self.pre_trigger - 1e-12) & (t < t_trig)
            )
        idx = np.flatnonzero(keep)
        return idx[:: self.period]

    def export(self, recording: Recording, path: str | Path) -> tuple[Path, int]:
        """Write the acquired rows of ``recording`` as CSV; returns (path, rows)."""
        idx = self.select(recording)
        names = list(recording.channels)
        data = np.column_stack([recording[n][idx] for n in names]) if names else np.zeros((0, 0))
        path = Path(path)
        np.savetxt(path, data, delimiter=",", header=",".join(names), comments="", fmt="%.9g")
        return path, int(idx.size)

    def describe(self) -> dict[str, Any]:
        """Plain data (for the page)."""
        return {
            "period": self.period,
            "trigger": self.trigger,
            "level": self.level,
            "edge": self.edge,
            "pre_trigger": self.pre_trigger,
            "windows": [list(w) for w in self.windows],
            "recording": self.recording,
            "display_rate": self.display_rate,
        }


def _num(raw: Mapping[str, Any], key: str, default: float, label: str) -> float:
    value = raw.get(key, default)
    if value is None or value == "":
        return default
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ValidationError(f"{label} must be a number; got {value!r}") from None
    if not math.isfinite(out):
        raise ValidationError(f"{label} must be finite; got {value!r}")
    return out


def acquisition_from_settings(raw: Mapping[str, Any], current: Acquisition) -> Acquisition:
    """The page's acquisition fields applied to ``current`` (validated).

    Fields: ``acq_period`` (ticks), ``trigger`` (channel, or ``""``/``none``),
    ``trigger_level``, ``trigger_edge``, ``pre_trigger`` [s], ``display_rate`` [Hz].
    """
    period = _num(raw, "acq_period", current.period, "acquisition period")
    if period != int(period) or not 1 <= period <= MAX_PERIOD:
        raise ValidationError(
            f"acquisition period must be a whole number of ticks in [1, {MAX_PERIOD}]; "
            f"got {period:g}"
        )
    trig = raw.get("trigger", current.trigger)
    trigger = None if trig in (None, "", "none") else str(trig)
    return replace(
        current,
        period=int(period),
        trigger=trigger,
        level=_num(raw, "trigger_level", current.level, "trigger level"),
        edge=str(raw.get("trigger_edge", current.edge)),
        pre_trigger=_num(raw, "pre_trigger", current.pre_trigger, "pre-trigger"),
        display_rate=_num(raw, "display_rate", current.display_rate, "display rate"),
    )
