"""Deterministic road inputs: harmonic (3.36), two-stage stepped sweep (3.37), rounded pulse (3.38).

All displacements are road inputs ``z_r`` [m], positive up (model reference, sections 1 and 8).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.errors import ValidationError, check_count, check_range
from mrsuspension.excitation.base import (
    Configurable,
    Excitation,
    FloatArray,
    Option,
    grid_args,
    non_negative,
    number,
    positive,
    time_array,
)

__all__ = [
    "DEFAULT_SWEEP_POINTS",
    "HIL_FREQUENCIES",
    "HIL_TRANSITION_FREQUENCY",
    "MAX_FREQUENCIES",
    "MIN_CYCLES",
    "MIN_MEASURE_TIME",
    "OMEGA0_REFERENCE",
    "PULSE_SETTLING_TIME",
    "REFERENCE_SPEED_KMH",
    "SETTLE_TIME",
    "TRANSITION_FREQUENCY",
    "Harmonic",
    "RoundedPulse",
    "SteppedSweep",
    "log_frequencies",
    "two_stage_amplitude",
]

# -- model reference, section 9: steady state of a harmonic run ---------------------------------
#: settle for at least this long [s] before measuring (model reference, section 9)
SETTLE_TIME = 5.0
#: ... and at least this many cycles; measure over at least this many cycles too
MIN_CYCLES = 10
#: measure over at least this long [s] (model reference, section 9)
MIN_MEASURE_TIME = 2.0

# -- model reference, section 8 -----------------------------------------------------------------
#: transition frequency f_T [Hz] of the two-stage sweep, section 3.5.1 (~ sqrt(2) f_n)
TRANSITION_FREQUENCY = 2.1
#: f_T [Hz] used on the hardware-in-the-loop rig (Chapter 7)
HIL_TRANSITION_FREQUENCY = 2.0
#: the discrete frequencies [Hz] of the hardware-in-the-loop sweeps (Chapter 7)
HIL_FREQUENCIES: tuple[float, ...] = (
    0.75, 1.0, 1.25, 1.75, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 15.0,
)  # fmt: skip
#: fundamental frequency w0 [rad/s] of the rounded pulse at the reference speed (erratum 9)
OMEGA0_REFERENCE = 10.4
#: the speed [km/h] at which w0 = 10.4 rad/s; w0 scales linearly with speed (erratum 9)
REFERENCE_SPEED_KMH = 50.0
#: time [s] left after a pulse for the response to settle (a simulation-length default)
PULSE_SETTLING_TIME = 2.0
#: number of log-spaced frequencies (0.5-15 Hz) of a sweep given without ``frequencies``
DEFAULT_SWEEP_POINTS = 30
#: the pulse's default delay [s] before it starts
PULSE_DELAY = 0.5

#: points per block of :func:`_harmonic_grid` (exact sin/cos at each block's start)
_GRID_BLOCK = 64


@njit(cache=True)
def _harmonic_grid(a: float, w: float, h: float, t0: float, z: np.ndarray, v: np.ndarray) -> None:
    """``z[k] = a sin(w (t0 + k h))``, ``v[k] = a w cos(w (t0 + k h))`` by blockwise angle addition."""
    n = z.shape[0]
    nb = min(_GRID_BLOCK, n)  # a short grid (a HiL tick's) needs only its own offsets
    sb = np.empty(nb)
    cb = np.empty(nb)
    for j in range(nb):
        sb[j] = math.sin(w * (j * h))
        cb[j] = math.cos(w * (j * h))
    aw = a * w
    for start in range(0, n, _GRID_BLOCK):
        th = w * (t0 + start * h)
        sa = math.sin(th)
        ca = math.cos(th)
        for j in range(min(_GRID_BLOCK, n - start)):
            z[start + j] = a * (sa * cb[j] + ca * sb[j])
            v[start + j] = aw * (ca * cb[j] - sa * sb[j])


@njit(cache=True)
def _pulse_grid(
    c0: float, rate: float, delay: float, step: float, t0: float, z: np.ndarray, v: np.ndarray
) -> None:
    """The rounded pulse at ``t = t0 + k step``: ``z = C x^2``, ``v = C mu w0 (2x - x^2)``.

    ``x = mu w0 (t - delay)``, ``C = c0 e^-x`` (``c0 = 0.25 a e^2``); 0 before the pulse.
    The same operations in the same order as :meth:`RoundedPulse.displacement` and
    :meth:`RoundedPulse.velocity`.
    """
    for k in range(z.shape[0]):
        x = rate * ((t0 + k * step) - delay)
        if x >= 0.0:
            c = c0 * math.exp(-x)
            z[k] = c * x * x
            v[k] = c * rate * (2.0 * x - x * x)
        else:
            z[k] = 0.0
            v[k] = 0.0


_MAX_FREQUENCY = 1000.0  # Hz; far above anything a quarter car responds to
#: most frequencies a sweep may hold: each is a steady-state run of several seconds
MAX_FREQUENCIES = 10_000
_WHY = " (a sweep runs one steady-state simulation per frequency)"
_MAX_AMPLITUDE = 1.0  # m


@dataclass(frozen=True)
class Harmonic(Excitation):
    """Harmonic road input ``z_r = a sin(2 pi f t)``, eq. (3.36).

    Parameters
    ----------
    frequency : float
        Excitation frequency ``f`` [Hz], in (0, 1000].
    amplitude : float
        Displacement amplitude ``a`` [m], in (0, 1].

    Notes
    -----
    :attr:`duration` leaves the settling time (model reference, section 9: at least 5 s
    and 10 cycles) followed by the measuring window of :meth:`measure_window` (a whole number
    of cycles, at least 10 cycles and 2 s).

    Examples
    --------
    >>> z = Harmonic(frequency=1.5, amplitude=0.025)
    >>> float(z.displacement(1 / 6))  # a quarter period: the crest
    0.025
    >>> [round(t, 4) for t in z.measure_window()]  # settle 10 cycles, measure 10 cycles
    [6.6667, 13.3333]
    >>> round(z.duration, 3)
    13.333
    """

    frequency: float
    amplitude: float

    name: ClassVar[str] = "harmonic"
    measures_kind: ClassVar[str] = "harmonic"
    options: ClassVar[tuple[Option, ...]] = (
        Option("frequency", "number", "Hz", "excitation frequency [Hz] (required)",
               required=True, low=0.0, high=_MAX_FREQUENCY, low_inclusive=False),
        Option("amplitude", "number", "m", "displacement amplitude [m] (required)",
               required=True, low=0.0, high=_MAX_AMPLITUDE, low_inclusive=False),
    )  # fmt: skip
    example_options: ClassVar[dict[str, Any]] = {"frequency": 1.5, "amplitude": 0.025}

    def __post_init__(self) -> None:
        f = positive("frequency", self.frequency, "Hz", high=_MAX_FREQUENCY)
        a = positive("amplitude", self.amplitude, "m", high=_MAX_AMPLITUDE)
        object.__setattr__(self, "frequency", f)
        object.__setattr__(self, "amplitude", a)

    @property
    def angular_frequency(self) -> float:
        """``omega = 2 pi f`` [rad/s]."""
        return 2.0 * math.pi * self.frequency

    @property
    def highest_frequency(self) -> float:
        """The highest frequency in the input [Hz] (for the record's Nyquist check)."""
        return self.frequency

    @property
    def peak_acceleration(self) -> float:
        """Acceleration amplitude ``a omega^2`` [m/s^2]."""
        return self.amplitude * self.angular_frequency**2

    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """``z_r = a sin(omega t)`` [m]."""
        return self.amplitude * np.sin(self.angular_frequency * time_array(t))

    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """``dz_r/dt = a omega cos(omega t)`` [m/s]."""
        w = self.angular_frequency
        return self.amplitude * w * np.cos(w * time_array(t))

    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """``d2z_r/dt2 = -a omega^2 sin(omega t)`` [m/s^2]."""
        w = self.angular_frequency
        return -self.amplitude * w * w * np.sin(w * time_array(t))

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """``(z_r, dz_r/dt)`` at ``start + k * step``, ``k < n``, by angle addition (about 10x faster).

        Exact sines and cosines at every 64th point, and of the (up to) 64 offsets within
        a block, combined by ``sin(A + B) = sin A cos B + cos A sin B``: a few ulp from
        :meth:`displacement` (whose own argument ``omega t`` rounds to a relative 1e-16),
        without the error growth of a recurrence.

        Examples
        --------
        >>> z = Harmonic(2.0, 0.02)
        >>> zr, vr = z.sample_grid(10001, 5e-5)
        >>> t = np.arange(10001) * 5e-5
        >>> bool(np.allclose(zr, z.displacement(t), rtol=0, atol=1e-15))
        True
        >>> bool(np.allclose(vr, z.velocity(t), rtol=0, atol=1e-14))
        True
        >>> zr, vr = z.sample_grid(21, 5e-5, start=12.3)  # a HiL tick at 12.3 s
        >>> bool(np.allclose(zr, z.displacement(12.3 + np.arange(21) * 5e-5), rtol=0, atol=1e-15))
        True
        """
        n, step, start = grid_args(n, step, start)
        z = np.empty(n)
        v = np.empty(n)
        _harmonic_grid(self.amplitude, self.angular_frequency, step, start, z, v)
        return z, v

    def measure_window(self) -> tuple[float, float]:
        """Steady-state window ``(t_start, t_end)`` [s] (model reference, section 9).

        ``t_start = max(5 s, 10 cycles)``; the window is the smallest whole number of
        cycles lasting at least 10 cycles and 2 s.
        """
        period = 1.0 / self.frequency
        start = max(SETTLE_TIME, MIN_CYCLES * period)
        cycles = max(MIN_CYCLES, math.ceil(MIN_MEASURE_TIME * self.frequency - 1e-9))
        return (start, start + cycles * period)

    @property
    def duration(self) -> float:
        """Settling time plus the measuring window [s] (model reference, section 9)."""
        return self.measure_window()[1]

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, frequency [Hz], amplitude [m] and derived values."""
        start, end = self.measure_window()
        return {
            "kind": self.name,
            "frequency": self.frequency,
            "amplitude": self.amplitude,
            "peak_acceleration": self.peak_acceleration,
            "duration": self.duration,
            "measure_window": [start, end],
        }


def two_stage_amplitude(
    frequency: npt.ArrayLike,
    amplitude: float,
    transition_frequency: float = TRANSITION_FREQUENCY,
) -> float | FloatArray:
    """Amplitude of the two-stage sweep, eq. (3.37) corrected (erratum 2).

    ``a`` up to the transition frequency ``f_T``, ``a (f_T/f)^2`` above it, so the road
    acceleration amplitude stays at ``(2 pi f_T)^2 a`` (constant displacement at low
    frequencies, constant acceleration at high ones).

    Parameters
    ----------
    frequency : float or array_like
        Excitation frequencies [Hz], each > 0.
    amplitude : float
        Low-frequency displacement amplitude ``a`` [m].
    transition_frequency : float, optional
        ``f_T`` [Hz]; 2.1 Hz (section 3.5.1) by default, 2 Hz on the HiL rig.

    Returns
    -------
    float or ndarray
        A float for a scalar ``frequency``, else an array of its shape [m].

    Examples
    --------
    >>> two_stage_amplitude([1.0, 2.1, 4.2], 0.025)
    array([0.025  , 0.025  , 0.00625])
    >>> a = two_stage_amplitude(10.0, 0.015)
    >>> round(a * (2 * math.pi * 10.0) ** 2, 2)  # constant acceleration [m/s^2]
    2.61
    """
    f = check_range("frequency", frequency, 0.0, _MAX_FREQUENCY, unit="Hz", low_inclusive=False)
    a = positive("amplitude", amplitude, "m", high=_MAX_AMPLITUDE)
    f_t = positive("transition_frequency", transition_frequency, "Hz", high=_MAX_FREQUENCY)
    out = np.where(f <= f_t, a, a * (f_t / f) ** 2)
    return float(out) if out.ndim == 0 else out


def log_frequencies(n: int, f_min: float = 0.5, f_max: float = 15.0) -> FloatArray:
    """``n`` log-spaced frequencies [Hz] from ``f_min`` to ``f_max`` (both included).

    The defaults are the dissertation's range for frequency responses, 0.5-15 Hz
    (section 3.5.1).

    Examples
    --------
    >>> log_frequencies(3, 1.0, 100.0)
    array([  1.,  10., 100.])
    """
    check_count("n", int(n) if isinstance(n, np.integer) else n, 1, MAX_FREQUENCIES, why=_WHY)
    lo = positive("f_min", f_min, "Hz", high=_MAX_FREQUENCY)
    hi = positive("f_max", f_max, "Hz", high=_MAX_FREQUENCY)
    if n > 1 and hi <= lo:
        raise ValidationError(f"f_max must be > f_min = {lo:g} Hz; got {hi:g} Hz")
    return np.geomspace(lo, hi, int(n))


@dataclass(frozen=True)
class SteppedSweep(Configurable):
    """Two-stage stepped sweep: one steady-state harmonic run per frequency (3.37).

    As in the dissertation, a "swept" test is a set of separate harmonic runs, each at
    the two-stage amplitude :func:`two_stage_amplitude` of its frequency.

    Parameters
    ----------
    frequencies : sequence of float
        Excitation frequencies [Hz], each in (0, 1000], no duplicates.
    amplitude : float
        Low-frequency amplitude ``a`` [m] (the dissertation uses 0.015, 0.025, 0.035).
    transition_frequency : float, optional
        ``f_T`` [Hz], 2.1 Hz by default (section 3.5.1).

    Examples
    --------
    >>> sweep = SteppedSweep([1.0, 4.2], amplitude=0.025)
    >>> [(h.frequency, h.amplitude) for h in sweep]
    [(1.0, 0.025), (4.2, 0.00625)]
    >>> hil = SteppedSweep.hil(0.01)
    >>> len(hil), hil.transition_frequency
    (14, 2.0)
    """

    frequencies: tuple[float, ...]
    amplitude: float
    transition_frequency: float = TRANSITION_FREQUENCY

    name: ClassVar[str] = "swept"
    measures_kind: ClassVar[str] = "harmonic"  # one harmonic run per frequency
    options: ClassVar[tuple[Option, ...]] = (
        Option("amplitude", "number", "m", "low-frequency displacement amplitude a [m] (required)",
               required=True, low=0.0, high=_MAX_AMPLITUDE, low_inclusive=False),
        Option("transition_frequency", "number", "Hz",
               "f_T [Hz], 2.1 by default (2.0 on the HiL rig)",
               default=TRANSITION_FREQUENCY, low=0.0, high=_MAX_FREQUENCY, low_inclusive=False),
        Option("frequencies", "numbers", "Hz",
               f"list of frequencies [Hz]; {DEFAULT_SWEEP_POINTS} log-spaced in 0.5-15 Hz by default",
               low=0.0, high=_MAX_FREQUENCY, low_inclusive=False),
    )  # fmt: skip
    example_options: ClassVar[dict[str, Any]] = {"amplitude": 0.025, "frequencies": [1.0, 4.2]}

    def __post_init__(self) -> None:
        freqs = self.frequencies
        if isinstance(freqs, str) or not isinstance(freqs, Sequence | np.ndarray):
            raise ValidationError(
                f"frequencies must be a sequence of numbers [Hz]; got {self.frequencies!r}"
            )
        if len(freqs) > MAX_FREQUENCIES:
            raise ValidationError(
                f"frequencies: {len(freqs)} frequencies are more than the {MAX_FREQUENCIES} a "
                f"sweep may hold{_WHY}"
            )
        values = tuple(number(f"frequencies[{k}]", f) for k, f in enumerate(freqs))
        if not values:
            raise ValidationError("frequencies must hold at least one frequency [Hz]; got none")
        for k, f in enumerate(values):
            check_range(f"frequencies[{k}]", f, 0.0, _MAX_FREQUENCY, unit="Hz", low_inclusive=False)
        seen: dict[float, int] = {}
        for k, f in enumerate(values):
            if f in seen:
                raise ValidationError(
                    f"frequencies must not repeat; {f:g} Hz is at indices {seen[f]} and {k}"
                )
            seen[f] = k
        object.__setattr__(self, "frequencies", values)
        object.__setattr__(
            self, "amplitude", positive("amplitude", self.amplitude, "m", high=_MAX_AMPLITUDE)
        )
        object.__setattr__(
            self,
            "transition_frequency",
            positive("transition_frequency", self.transition_frequency, "Hz", high=_MAX_FREQUENCY),
        )

    @classmethod
    def from_options(
        cls, options: Mapping[str, Any], *, base_dir: str | Path | None = None
    ) -> SteppedSweep:
        """Build from scenario options; no ``frequencies``: 30 log-spaced in 0.5-15 Hz."""
        if options.get("frequencies") is None:
            options = {**options, "frequencies": tuple(log_frequencies(DEFAULT_SWEEP_POINTS))}
        return super().from_options(options, base_dir=base_dir)

    @property
    def highest_frequency(self) -> float:
        """The highest sweep frequency [Hz] (for the record's Nyquist check)."""
        return max(self.frequencies)

    @classmethod
    def hil(cls, amplitude: float) -> SteppedSweep:
        """The hardware-in-the-loop sweep: f_T = 2 Hz and the 14 discrete frequencies."""
        return cls(HIL_FREQUENCIES, amplitude, HIL_TRANSITION_FREQUENCY)

    @property
    def amplitudes(self) -> FloatArray:
        """Two-stage amplitude [m] at each frequency."""
        out = two_stage_amplitude(
            np.array(self.frequencies), self.amplitude, self.transition_frequency
        )
        return np.atleast_1d(np.asarray(out, dtype=float))

    def excitations(self) -> tuple[Harmonic, ...]:
        """One :class:`Harmonic` per frequency, at its two-stage amplitude."""
        return tuple(
            Harmonic(f, float(a)) for f, a in zip(self.frequencies, self.amplitudes, strict=True)
        )

    def __iter__(self) -> Iterator[Harmonic]:
        return iter(self.excitations())

    def __len__(self) -> int:
        return len(self.frequencies)

    @property
    def duration(self) -> float:
        """Total simulated time of all runs [s]."""
        return float(sum(h.duration for h in self.excitations()))

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, amplitude, transition frequency, frequencies and amplitudes."""
        return {
            "kind": self.name,
            "amplitude": self.amplitude,
            "transition_frequency": self.transition_frequency,
            "frequencies": list(self.frequencies),
            "amplitudes": [float(a) for a in self.amplitudes],
            "constant_acceleration": self.amplitude
            * (2 * math.pi * self.transition_frequency) ** 2,
            "duration": self.duration,
        }


@dataclass(frozen=True)
class RoundedPulse(Excitation):
    """Rounded pulse (a bump of height ``a``), eq. (3.38).

    ``z_r = 0.25 a e^2 (mu w0 tau)^2 exp(-mu w0 tau)`` for ``tau = t - delay >= 0`` and
    zero before. The peak, ``z_r = a``, is at ``tau = 2/(mu w0)``; the pulse lasts about
    ``3 pi/(mu w0)``. The road acceleration jumps from 0 to ``2 (0.25 a e^2)(mu w0)^2``
    at the onset, which is also its largest magnitude (:attr:`peak_acceleration`); after
    that jump its largest magnitude is ``0.41201 (0.25 a e^2)(mu w0)^2``
    (:attr:`after_onset_peak_acceleration`), 4.854 times smaller. The shock measures
    ``SAR_s`` and ``SAR_u`` divide by one or the other (``road_peak`` in
    :func:`mrsuspension.measures.shock_ratios`).

    Parameters
    ----------
    amplitude : float
        Peak height ``a`` [m], nonzero in [-1, 1] (the dissertation uses 0.02, 0.035,
        0.05 m; a negative value gives a pothole).
    severity : float
        Severity ``mu`` > 0 (the dissertation uses 1, 2, 3).
    omega0 : float, optional
        Fundamental frequency ``w0`` [rad/s]. By default 10.4 rad/s at 50 km/h, scaled
        linearly with ``speed_kmh`` (20.8 rad/s at 100 km/h; erratum 9).
    speed_kmh : float, optional
        Vehicle speed [km/h], 50 by default; sets ``w0`` unless ``omega0`` is given.
    delay : float, optional
        Time [s] before the pulse starts, 0.5 s by default.

    Examples
    --------
    >>> bump = RoundedPulse(amplitude=0.05, severity=2, speed_kmh=100.0)
    >>> bump.omega
    20.8
    >>> round(float(bump.displacement(bump.peak_time)), 12)
    0.05
    >>> round(bump.pulse_duration, 4)  # 3 pi / (mu w0)
    0.2266
    >>> round(bump.peak_acceleration / bump.after_onset_peak_acceleration, 3)
    4.854
    """

    amplitude: float
    severity: float
    omega0: float | None = None
    speed_kmh: float = REFERENCE_SPEED_KMH
    delay: float = PULSE_DELAY

    name: ClassVar[str] = "pulse"
    measures_kind: ClassVar[str] = "pulse"
    options: ClassVar[tuple[Option, ...]] = (
        Option("amplitude", "number", "m", "bump height a [m] (required)",
               required=True, low=-_MAX_AMPLITUDE, high=_MAX_AMPLITUDE),
        Option("severity", "number", "", "severity mu, e.g. 1, 2, 3 (required)",
               required=True, low=0.0, high=1e3, low_inclusive=False),
        Option("speed", "number", "km/h",
               "vehicle speed [km/h], 50 by default; sets w0 = 10.4 rad/s x speed/50",
               default=REFERENCE_SPEED_KMH, low=0.0, high=500.0, low_inclusive=False,
               keyword="speed_kmh"),
        Option("omega0", "number", "rad/s",
               "fundamental frequency w0 [rad/s]; overrides the speed scaling",
               low=0.0, high=1e4, low_inclusive=False),
        Option("delay", "number", "s", "time before the pulse [s], 0.5 by default",
               default=PULSE_DELAY, low=0.0, high=1e4),
    )  # fmt: skip
    example_options: ClassVar[dict[str, Any]] = {"amplitude": 0.05, "severity": 2.0}

    def __post_init__(self) -> None:
        a = number("amplitude", self.amplitude)
        check_range("amplitude", a, -_MAX_AMPLITUDE, _MAX_AMPLITUDE, unit="m")
        if a == 0.0:
            raise ValidationError("amplitude must be nonzero, in [-1, 1] m; got 0 m")
        object.__setattr__(self, "amplitude", a)
        object.__setattr__(self, "severity", positive("severity", self.severity, "", high=1e3))
        if self.omega0 is not None:
            object.__setattr__(self, "omega0", positive("omega0", self.omega0, "rad/s", high=1e4))
        object.__setattr__(
            self, "speed_kmh", positive("speed_kmh", self.speed_kmh, "km/h", high=500.0)
        )
        object.__setattr__(self, "delay", non_negative("delay", self.delay, "s", high=1e4))

    @property
    def omega(self) -> float:
        """The fundamental frequency ``w0`` in use [rad/s]."""
        if self.omega0 is not None:
            return self.omega0
        return OMEGA0_REFERENCE * self.speed_kmh / REFERENCE_SPEED_KMH

    @property
    def rate(self) -> float:
        """``mu w0`` [1/s]."""
        return self.severity * self.omega

    @property
    def peak_time(self) -> float:
        """Time of the peak, ``delay + 2/(mu w0)`` [s]."""
        return self.delay + 2.0 / self.rate

    @property
    def pulse_duration(self) -> float:
        """Approximate pulse duration ``3 pi/(mu w0)`` [s] (section 3.5.1)."""
        return 3.0 * math.pi / self.rate

    @property
    def peak_acceleration(self) -> float:
        """Largest ``|d2z_r/dt2|``, reached at the onset: ``0.5 |a| e^2 (mu w0)^2`` [m/s^2].

        This is ``2 c (mu w0)^2`` with ``c = 0.25 |a| e^2``: ``d2/dx2 (x^2 e^-x) =
        (x^2 - 4x + 2) e^-x`` is 2 at ``x = 0``.
        """
        return 0.5 * abs(self.amplitude) * math.e**2 * self.rate**2

    @property
    def after_onset_time(self) -> float:
        """Time of the after-onset acceleration peak, ``delay + (3 - sqrt 3)/(mu w0)`` [s]."""
        return self.delay + (3.0 - math.sqrt(3.0)) / self.rate

    @property
    def after_onset_peak_acceleration(self) -> float:
        """Largest ``|d2z_r/dt2|`` after the onset jump [m/s^2]: ``0.41201 c (mu w0)^2``.

        With ``x = mu w0 tau`` and ``c = 0.25 |a| e^2``, ``z_r'' = c (mu w0)^2 (x^2 - 4x
        + 2) e^-x`` falls from ``2 c (mu w0)^2`` at the onset through zero at ``x = 2 -
        sqrt 2``; its derivative ``-(x^2 - 6x + 6) e^-x`` vanishes at ``x = 3 -+ sqrt 3``,
        where ``x^2 - 4x + 2 = 2x - 4``. The larger magnitude is at ``x = 3 - sqrt 3``:
        ``(2 sqrt 3 - 2) e^(sqrt 3 - 3) = 0.41201`` (the other, ``x = 3 + sqrt 3``, gives
        0.0482). The onset value :attr:`peak_acceleration` is 4.854 times larger.

        Examples
        --------
        >>> bump = RoundedPulse(amplitude=0.035, severity=3.0)
        >>> c = 0.25 * 0.035 * math.e**2
        >>> round(bump.after_onset_peak_acceleration / (c * bump.rate**2), 5)
        0.41201
        >>> round(float(bump.acceleration(bump.after_onset_time)), 3)  # the extremum, negative
        -25.931
        """
        factor = (2.0 * math.sqrt(3.0) - 2.0) * math.exp(math.sqrt(3.0) - 3.0)  # -(2x - 4) e^-x
        return 0.25 * abs(self.amplitude) * math.e**2 * self.rate**2 * factor

    @property
    def duration(self) -> float:
        """Delay + pulse duration + 2 s of settling [s]."""
        return self.delay + self.pulse_duration + PULSE_SETTLING_TIME

    def _phase(self, t: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
        x = self.rate * (time_array(t) - self.delay)  # x = mu w0 tau
        on = x >= 0.0
        x = np.where(on, x, 0.0)
        return x, np.where(on, 0.25 * self.amplitude * math.e**2 * np.exp(-x), 0.0)

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """``(z_r, dz_r/dt)`` at ``start + k * step``, ``k < n``, in one compiled pass.

        The operations of :meth:`displacement` and :meth:`velocity`, point by point: the
        same values where numba's ``exp`` is numpy's (glibc's), within an ulp elsewhere.

        Examples
        --------
        >>> bump = RoundedPulse(amplitude=0.05, severity=2)
        >>> zr, vr = bump.sample_grid(101, 0.01)
        >>> t = np.arange(101) * 0.01
        >>> bool(np.allclose(zr, bump.displacement(t), rtol=1e-15, atol=0))
        True
        >>> bool(np.allclose(vr, bump.velocity(t), rtol=1e-15, atol=1e-18))
        True
        """
        n, step, start = grid_args(n, step, start)
        z = np.empty(n)
        v = np.empty(n)
        c0 = 0.25 * self.amplitude * math.e**2
        _pulse_grid(c0, self.rate, self.delay, step, start, z, v)
        return z, v

    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """``z_r`` [m]: ``C x^2 e^-x`` with ``x = mu w0 tau``, ``C = 0.25 a e^2``."""
        x, c = self._phase(t)
        return c * x * x

    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """``dz_r/dt = C mu w0 (2x - x^2) e^-x`` [m/s]."""
        x, c = self._phase(t)
        return c * self.rate * (2.0 * x - x * x)

    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """``d2z_r/dt2 = C (mu w0)^2 (2 - 4x + x^2) e^-x`` for ``tau >= 0`` [m/s^2]."""
        x, c = self._phase(t)
        return c * self.rate**2 * (2.0 - 4.0 * x + x * x)

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, amplitude [m], severity, omega0 [rad/s], speed, delay and derived values."""
        return {
            "kind": self.name,
            "amplitude": self.amplitude,
            "severity": self.severity,
            "omega0": self.omega,
            "speed_kmh": self.speed_kmh,
            "delay": self.delay,
            "peak_time": self.peak_time,
            "pulse_duration": self.pulse_duration,
            "peak_acceleration": self.peak_acceleration,
            "after_onset_peak_acceleration": self.after_onset_peak_acceleration,
            "duration": self.duration,
        }
