"""Run settings and run plans: the one home of planning a run.

:class:`RunSettings` (the fixed step, the simulated time and the recorded rate) travels
wherever a run is asked for (``Simulation.run``, ``run_many``, scenarios, studies, the
optimiser, batches and the HiL loop) instead of positional ``(duration, dt,
output_rate)`` triples. :meth:`RunSettings.plan` turns it into the :class:`RunPlan` of
one model (any :class:`Plannable`: the quarter car, the half and full cars): ``dt``
checked once against the model's stability limit, the duration resolved, the
decimation, the step count and the memory check, in one place. It depends on nothing
but :mod:`mrsuspension.errors`, so any module may import it.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol

import numpy as np

from mrsuspension.errors import ValidationError, check_range

__all__ = [
    "DEFAULT_DT",
    "DEFAULT_OUTPUT_RATE",
    "MAX_DT",
    "MAX_DURATION",
    "RK4_LIMIT",
    "Plannable",
    "RunPlan",
    "RunSettings",
    "check_memory",
    "check_step",
    "memory_limit",
    "run_settings",
]

#: Default fixed RK4 step [s] (model reference, section 7).
DEFAULT_DT = 1e-4
#: Default recorded rate [Hz]; decimation is separate from ``dt`` (model reference, section 7).
DEFAULT_OUTPUT_RATE = 1000.0
#: Largest accepted step [s] (the stability check of a model is usually far tighter).
MAX_DT = 0.01
#: Longest accepted simulated time [s] (about 28 h).
MAX_DURATION = 1e5
#: RK4's stability limit on the negative real axis is about 2.785: a step ``dt`` is stable
#: for a model whose stiffest mode decays at ``rate`` [1/s] when ``dt rate <= RK4_LIMIT``
#: (a margin kept).
RK4_LIMIT = 2.5
#: Relative slack of the ``output_rate <= 1/dt`` check (``1/dt`` rounds).
_RATE_SLACK = 1e-9


class RunPlan(NamedTuple):
    """The checked step, step count and output decimation of one run (:meth:`RunSettings.plan`).

    Examples
    --------
    >>> plan = RunPlan(dt=1e-4, steps=20_000, decimate=10)
    >>> plan.steps * plan.dt, plan.rows, plan.interval
    (2.0, 2001, 0.001)
    >>> float(plan.time()[-1])
    2.0
    """

    #: fixed RK4 step [s]
    dt: float
    #: steps of the run
    steps: int
    #: steps per recorded sample
    decimate: int

    @property
    def rows(self) -> int:
        """Recorded samples: the initial state and one every :attr:`decimate` steps."""
        return self.steps // self.decimate + 1

    @property
    def interval(self) -> float:
        """Time between recorded samples [s]."""
        return self.decimate * self.dt

    def time(self) -> np.ndarray:
        """Times of the recorded samples [s]."""
        return np.arange(self.rows) * self.interval


class Plannable(Protocol):
    """What :meth:`RunSettings.plan` asks of a model (quarter car, half or full car)."""

    @property
    def excitation(self) -> Any: ...

    def check_dt(self, dt: float) -> float:
        """``dt`` if stable for the model, else a :class:`ValidationError` naming the limit."""
        ...

    def record_values(self, plan: RunPlan) -> float:
        """Floats a run of ``plan`` allocates (record and road), for the memory check."""
        ...


@dataclass(frozen=True, init=False)
class RunSettings:
    """How a run is stepped and recorded: ``dt``, ``duration`` and ``output_rate``.

    Parameters
    ----------
    dt : float
        Fixed RK4 step [s], in (0, 0.01]; 1e-4 s by default (model reference, section 7).
        Whether it is stable for a given model is checked by the simulation
        (:meth:`~mrsuspension.engine.simulate.Simulation.check_dt`).
    duration : float or None
        Simulated time [s], in (0, 1e5]; None (default): the excitation's own duration
        (for harmonic runs, the steady-state rule: model reference, section 9).
    output_rate : float or None
        Recorded samples per second [Hz], in (0, 1/dt]; None (default): 1 kHz, at most
        one sample per step. Always a number after construction.

    Raises
    ------
    ValidationError
        A value out of range, naming the field, the value and the valid range.

    Examples
    --------
    >>> RunSettings()
    RunSettings(dt=0.0001, duration=None, output_rate=1000.0)
    >>> RunSettings(dt=2e-3).output_rate  # the 1 kHz default, capped at 1/dt
    500.0
    >>> RunSettings(dt=1e-3, output_rate=2000.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: output_rate must be in (0, 1000] Hz (at most one sample per step of dt = 0.001 s); got 2000 Hz
    """

    dt: float
    duration: float | None
    output_rate: float

    def __init__(
        self,
        dt: float = DEFAULT_DT,
        duration: float | None = None,
        output_rate: float | None = None,
    ) -> None:
        dt = check_step(dt)
        if duration is not None:
            duration = _number("duration", duration)
            duration = float(
                check_range("duration", duration, 0.0, MAX_DURATION, unit="s", low_inclusive=False)
            )
        if output_rate is None:
            rate = min(DEFAULT_OUTPUT_RATE, 1.0 / dt)
        else:
            rate = float(
                check_range(
                    "output_rate",
                    _number("output_rate", output_rate),
                    0.0,
                    None,
                    unit="Hz",
                    low_inclusive=False,
                )
            )
            if rate * dt > 1.0 + _RATE_SLACK:
                raise ValidationError(
                    f"output_rate must be in (0, {1.0 / dt:g}] Hz (at most one sample per "
                    f"step of dt = {dt:g} s); got {rate:g} Hz"
                )
        object.__setattr__(self, "dt", dt)
        object.__setattr__(self, "duration", duration)
        object.__setattr__(self, "output_rate", rate)

    # -- derived -------------------------------------------------------------------------
    @property
    def decimation(self) -> int:
        """Steps per recorded sample, ``round(1 / (output_rate dt))`` (at least 1).

        Examples
        --------
        >>> RunSettings(dt=1e-4, output_rate=1000.0).decimation
        10
        """
        return max(1, round(1.0 / (self.output_rate * self.dt)))

    def duration_for(self, excitation: Any) -> float:
        """The simulated time [s] of a run on ``excitation``: :attr:`duration`, else its own.

        Examples
        --------
        >>> from mrsuspension.excitation import RoundedPulse
        >>> RunSettings(duration=1.5).duration_for(RoundedPulse(0.02, 1.0))
        1.5
        """
        if self.duration is not None:
            return self.duration
        own = getattr(excitation, "duration", None)
        if own is None:
            raise ValidationError("duration is required: the excitation has no duration of its own")
        return float(
            check_range(
                "duration",
                float(own),
                0.0,
                MAX_DURATION,
                unit="s",
                low_inclusive=False,
            )
        )

    def check_for(self, excitation: Any) -> RunSettings:
        """Check that the record resolves the excitation: its highest frequency < output_rate/2.

        Excitations that declare a ``highest_frequency`` [Hz] (harmonic runs and sweeps)
        are checked against the Nyquist frequency of the record; others pass. Returns
        ``self``, for chaining.

        Raises
        ------
        ValidationError
            When the record would alias the excitation.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> RunSettings(output_rate=100.0).check_for(Harmonic(10.0, 0.01)).output_rate
        100.0
        >>> RunSettings(output_rate=100.0).check_for(Harmonic(60.0, 0.001))
        Traceback (most recent call last):
        ...
        mrsuspension.errors.ValidationError: output_rate = 100 Hz cannot record the excitation's 60 Hz (its measures would be aliased): set output_rate > 120 Hz (twice the highest frequency; at most 1/dt = 10000 Hz, else lower dt)
        """
        top = getattr(excitation, "highest_frequency", None)
        if top is not None and not float(top) < 0.5 * self.output_rate:
            raise ValidationError(
                f"output_rate = {self.output_rate:g} Hz cannot record the excitation's "
                f"{float(top):g} Hz (its measures would be aliased): set output_rate > "
                f"{2.0 * float(top):g} Hz (twice the highest frequency; at most 1/dt = "
                f"{1.0 / self.dt:g} Hz, else lower dt)"
            )
        return self

    def plan(self, model: Plannable, *, check_stability: bool = True) -> RunPlan:
        """The :class:`RunPlan` of a run of ``model`` with these settings.

        ``dt`` checked against the model's stability limit (``check_stability=False``
        skips that check: the range check of construction stays), the duration resolved
        (:meth:`duration_for` the model's excitation), the decimation
        (:attr:`decimation`), whole output intervals covering the duration (the record
        ends at or after it), and the memory the run's arrays need
        (:func:`check_memory` of ``model.record_values``), all before anything runs.

        Raises
        ------
        ValidationError
            A ``dt`` too large for the model, no duration, or a run too large for memory.

        Examples
        --------
        >>> from mrsuspension.engine import Simulation
        >>> from mrsuspension.excitation import Harmonic
        >>> RunSettings(duration=2.0).plan(Simulation(Harmonic(1.0, 0.01)))
        RunPlan(dt=0.0001, steps=20000, decimate=10)
        >>> RunSettings(dt=3e-4, duration=0.0125, output_rate=400.0).plan(Simulation(Harmonic(1.0, 0.01)))
        RunPlan(dt=0.0003, steps=48, decimate=8)
        """
        dt = model.check_dt(self.dt) if check_stability else self.dt
        duration = self.duration_for(model.excitation)
        decimate = self.decimation
        steps = max(1, math.ceil(duration / (dt * decimate) - 1e-9)) * decimate
        plan = RunPlan(dt, steps, decimate)
        check_memory(duration, model.record_values(plan))
        return plan

    def to_dict(self) -> dict[str, float]:
        """The ``[simulation]`` table of a scenario (``duration`` only when set).

        Examples
        --------
        >>> RunSettings(dt=5e-5, duration=3.0).to_dict()
        {'dt': 5e-05, 'output_rate': 1000.0, 'duration': 3.0}
        """
        out = {"dt": self.dt, "output_rate": self.output_rate}
        if self.duration is not None:
            out["duration"] = self.duration
        return out


def memory_limit() -> float:
    """Bytes one run may allocate for its arrays: half the machine's RAM (``os.sysconf``).

    Falls back to 8 GiB where the RAM size is not known.

    Examples
    --------
    >>> memory_limit() > 0
    True
    """
    try:
        return 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # pragma: no cover - not POSIX
        return 8.0 * 2**30


def check_memory(
    duration: float,
    values: float,
    *,
    name: str = "duration",
    hint: str = "shorten the duration, raise dt or lower output_rate",
    subject: str | None = None,
) -> None:
    """Refuse a run whose arrays (``values`` floats of 8 bytes) exceed :func:`memory_limit`.

    Checked before anything is allocated, so that a long ``duration`` fails at once with
    the estimate instead of running out of memory. The one home of "estimated memory
    vs what this machine allows": runs, batches of runs, recordings and fits all ask it.
    ``subject`` names what needs the memory when it is not one run of ``duration``
    (e.g. ``"the records of 5000 runs"``).

    Raises
    ------
    ValidationError
        Naming ``name``, the duration, the estimate and the limit, then ``hint`` (how to
        fix it).

    Examples
    --------
    >>> check_memory(10.0, 1e6)  # 8 MB
    >>> check_memory(1e5, 1e15)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: duration = 100000 s needs about 7.45e+06 GiB of memory ...
    """
    need = 8.0 * float(values)
    limit = memory_limit()
    if need > limit:
        who = subject if subject is not None else f"{name} = {duration:g} s"
        raise ValidationError(
            f"{who} needs about {need / 2**30:.3g} GiB of memory (samples x "
            f"signals x 8 bytes), more than the {limit / 2**30:.3g} GiB allowed (half this "
            f"machine's RAM): {hint}"
        )


def check_step(dt: object) -> float:
    """``dt`` [s] as a float in (0, :data:`MAX_DT`]: the range every step is held to.

    Whether a step is stable for a model is the model's own check (``check_dt``), which
    starts from this one.

    Examples
    --------
    >>> check_step(1e-4)
    0.0001
    >>> check_step(0.05)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: dt must be in (0, 0.01] s; got 0.05 s
    """
    return float(check_range("dt", _number("dt", dt), 0.0, MAX_DT, unit="s", low_inclusive=False))


def _number(name: str, value: object) -> float:
    """``value`` as a float; a non-number (or a bool) names the field."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ValidationError(f"{name} must be a number; got {value!r}")
    return float(value)


def run_settings(
    settings: RunSettings | None = None,
    *,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
) -> RunSettings:
    """A :class:`RunSettings` from either a settings object or the three keywords.

    For functions that accept both spellings (``Simulation.run``, ``run_many``): a
    keyword left as None takes the :class:`RunSettings` default.

    Raises
    ------
    ValidationError
        ``settings`` given together with any keyword, or a value out of range.

    Examples
    --------
    >>> run_settings(dt=5e-5, duration=3.0) == run_settings(RunSettings(5e-5, 3.0))
    True
    >>> run_settings(RunSettings(), dt=1e-4)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: give either settings or dt, not both
    """
    given = [
        n
        for n, v in (("duration", duration), ("dt", dt), ("output_rate", output_rate))
        if v is not None
    ]
    if settings is not None:
        if not isinstance(settings, RunSettings):
            raise ValidationError(f"settings must be a RunSettings; got {settings!r}")
        if given:
            raise ValidationError(f"give either settings or {', '.join(given)}, not both")
        return settings
    return RunSettings(DEFAULT_DT if dt is None else dt, duration, output_rate)
