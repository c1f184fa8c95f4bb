"""Pre-processing of a harmonic damper test into one steady-state loop.

The dissertation fitted its models to one steady-state cycle per test, 360 points per
loop (dissertation section 2.7; model reference, section 10). :func:`preprocess` turns a
raw record into such a loop and says what it did:

1. checks the signals (NaN, infinite values, time increasing) and puts a jittery time
   base onto a uniform grid;
2. detects the excitation frequency (windowed FFT peak, refined by a least-squares
   sine fit of the displacement; :func:`detect_frequency`);
3. derives missing signals: velocity and acceleration by a smoothing Savitzky-Golay
   differentiator (cubic, window 1/20 of the excitation period, at least 5 samples;
   :func:`smooth_derivative`), displacement by integrating velocity (drift removed);
4. finds the plateau: cuts the record into whole cycles where they fit its steady
   state best (16 cuts per period are tried) and keeps the longest run of consistent
   cycles, wherever it is: between a ramp-in and a ramp-out, in a record that starts
   or stops mid-ramp, after a first-cycle transient (:mod:`~mrsuspension.identify.
   plateau`); a test with two cycles or more and no two consistent ones is refused.
   Each kept cycle is resampled to ``points_per_cycle`` points starting at the upward
   zero crossing of the displacement (phase 0), as in
   :func:`mrsuspension.characterisation.harmonic_loop`;
5. averages the kept cycles (phase averaging), optionally removes the mean force
   (accumulator preload), and sets the peak velocity ``v_m`` used by the
   dissertation's models: ``2 pi f a_m`` from the manifest when the cycles fitted move
   at it, else the amplitude of the fundamental of their measured velocity. The
   velocity checks (a velocity column must be the stroke's derivative) and the stroke
   amplitude are measured on the cycles fitted.

Examples
--------
>>> import numpy as np
>>> from mrsuspension.identify.readers import RawTest
>>> t = np.arange(0.0, 2.0, 1e-3)
>>> x = 0.01 * np.sin(2 * np.pi * 2.5 * t + 0.3)
>>> raw = RawTest("demo", t, x, None, 2000.0 * np.gradient(x, t))
>>> loop = preprocess(raw, current=0.1)
>>> round(loop.frequency, 4), loop.cycles_used, loop.force.size, round(loop.peak_velocity, 4)
(2.5, 4, 360, 0.1571)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension.dampers.peak_velocity import V_LIMIT
from mrsuspension.errors import ValidationError
from mrsuspension.identify.plateau import (
    PlateauRun,
    choose_plateau,
    consistent_runs,
    no_plateau_message,
)
from mrsuspension.identify.readers import RawTest, TestDataError

__all__ = [
    "HarmonicFit",
    "Loop",
    "PreprocessOptions",
    "detect_frequency",
    "preprocess",
    "smooth_derivative",
]

FloatArray = npt.NDArray[np.float64]

PEAK_VELOCITY_SOURCES = ("auto", "nominal", "measured")

#: Largest force-channel delay [s] :class:`PreprocessOptions` compensates (a load cell's
#: conditioning delays by milliseconds; a tenth of a second is a mistaken unit).
MAX_FORCE_DELAY = 0.1


@dataclass(frozen=True)
class PreprocessOptions:
    """Settings of :func:`preprocess`.

    Parameters
    ----------
    points_per_cycle : int
        Points per resampled loop (360, dissertation section 2.7).
    remove_offset : bool
        Subtract the mean force of the loop (a gas-spring/accumulator preload that the
        symmetric models cannot represent). Do not use it for asymmetric dampers.
    max_cycles : int, optional
        Average at most this many of the last cycles of the plateau (default: all of
        them).
    steady_tolerance : float
        Cycles are consistent (:mod:`~mrsuspension.identify.plateau`) when their force
        ranges (peak to peak) agree within this fraction: the largest exceeds the
        smallest by at most ``steady_tolerance``. Loose: 2 % force noise scatters the
        range by about 1 %.
    stroke_tolerance : float
        ... and their stroke amplitudes (least-squares sines over each cycle) within
        this fraction. Tight: a rig holds the amplitude of a plateau to a fraction of
        a percent, and the cycles of a ramp differ by the ramp's step.
    peak_velocity : {"auto", "nominal", "measured"}
        v_m for the dissertation's models: ``2 pi f a_m`` from the manifest
        (``"nominal"``), the fundamental of the measured velocity over the cycles fitted
        (``"measured"``), or (``"auto"``) nominal when the manifest gives frequency and
        amplitude and the cycles fitted move at that speed (``2 pi f`` times their
        stroke amplitude within :data:`NOMINAL_AGREEMENT`), else measured.
    smoothing : float
        Savitzky-Golay window of the differentiator as a fraction of the period.
    force_delay : float
        Delay of the recorded force behind the motion [s] (a load cell and its
        conditioning, e.g. an anti-aliasing filter's group delay: 1-3 ms is common),
        compensated by reading the force that much later. No model can absorb a delay:
        its phase lag grows with the frequency.
    """

    points_per_cycle: int = 360
    remove_offset: bool = False
    max_cycles: int | None = None
    steady_tolerance: float = 0.05
    stroke_tolerance: float = 0.01
    peak_velocity: str = "auto"
    smoothing: float = 0.05
    force_delay: float = 0.0

    def __post_init__(self) -> None:
        if not (isinstance(self.points_per_cycle, int) and 16 <= self.points_per_cycle <= 100_000):
            raise ValidationError(
                f"points per cycle must be an integer in [16, 100000]; got {self.points_per_cycle!r}"
            )
        if self.max_cycles is not None and not (
            isinstance(self.max_cycles, int) and self.max_cycles >= 1
        ):
            raise ValidationError(f"max_cycles must be an integer >= 1; got {self.max_cycles!r}")
        if not 0.0 < self.steady_tolerance <= 1.0:
            raise ValidationError(
                f"steady_tolerance must be in (0, 1]; got {self.steady_tolerance!r}"
            )
        if not 0.0 < self.stroke_tolerance <= 1.0:
            raise ValidationError(
                f"stroke_tolerance must be in (0, 1]; got {self.stroke_tolerance!r}"
            )
        if self.peak_velocity not in PEAK_VELOCITY_SOURCES:
            raise ValidationError(
                f"peak_velocity must be one of {', '.join(PEAK_VELOCITY_SOURCES)}; "
                f"got {self.peak_velocity!r}"
            )
        if not 0.0 < self.smoothing <= 0.5:
            raise ValidationError(f"smoothing must be in (0, 0.5]; got {self.smoothing!r}")
        if not (
            isinstance(self.force_delay, int | float) and 0.0 <= self.force_delay <= MAX_FORCE_DELAY
        ):
            raise ValidationError(
                f"force_delay must be in [0, {MAX_FORCE_DELAY:g}] s; got {self.force_delay!r}"
            )


@dataclass(frozen=True)
class HarmonicFit:
    """Least-squares sine fit ``y = offset + amplitude sin(2 pi f t + phase)`` (+ trend)."""

    frequency: float
    amplitude: float
    phase: float
    offset: float
    explained: float  # fraction of the variance explained by the fit


@dataclass(frozen=True)
class Loop:
    """One steady-state loop of a test, resampled to ``points_per_cycle`` points.

    Arrays over one period starting at phase 0 (displacement rising through its mean):
    ``time`` [s], ``stroke`` [m], ``velocity`` [m/s], ``acceleration`` [m/s^2],
    ``force`` [N], ``current`` [A]. ``notes`` say what pre-processing did; ``span`` is
    the record time [s] where the first cycle used starts and the last one ends. With
    ``offset_removed`` the loop's mean force was subtracted, and the fit compares it with
    the model loop minus its own mean.
    """

    label: str
    time: FloatArray
    stroke: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    force: FloatArray
    current: FloatArray
    frequency: float
    amplitude: float
    peak_velocity: float
    nominal_frequency: float | None = None
    nominal_amplitude: float | None = None
    cycles_found: int = 1
    cycles_used: int = 1
    cycle_spread: float = 0.0
    force_offset: float = 0.0
    offset_removed: bool = False
    notes: tuple[str, ...] = field(default=())
    span: tuple[float, float] = (0.0, 0.0)

    @property
    def mean_current(self) -> float:
        """Mean drive current over the loop [A]."""
        return float(np.mean(self.current))

    @property
    def force_range(self) -> float:
        """Peak-to-peak force [N], the normaliser of the residuals (model reference, section 10)."""
        return float(np.ptp(self.force))

    def energy_per_cycle(self, force: npt.ArrayLike | None = None) -> float:
        """Energy dissipated over the loop, closed integral of F dx [J].

        Examples
        --------
        >>> import numpy as np
        >>> th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
        >>> x, v = 0.01 * np.sin(th), 0.01 * np.cos(th)
        >>> loop = Loop("c", th, x, v, -x, 1000.0 * v, np.zeros(360), 1 / (2 * np.pi), 0.01, 0.01)
        >>> round(loop.energy_per_cycle(), 3)  # pi c omega a^2 with c omega = 1000
        0.314
        """
        f = self.force if force is None else np.asarray(force, dtype=float)
        x = np.append(self.stroke, self.stroke[0])
        ff = np.append(f, f[0])
        return float(np.sum(0.5 * (ff[1:] + ff[:-1]) * np.diff(x)))


# ----------------------------------------------------------------------------------
def smooth_derivative(signal: npt.ArrayLike, dt: float, window: int, order: int = 1) -> FloatArray:
    """Savitzky-Golay derivative of a uniformly sampled signal (cubic local fits).

    ``window`` (samples, made odd and at least 5) sets the smoothing; the ends use the
    fit over the first/last window (``mode="interp"``).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 1.0, 1e-3)
    >>> v = smooth_derivative(np.sin(2 * np.pi * t), 1e-3, 51)
    >>> bool(np.max(np.abs(v - 2 * np.pi * np.cos(2 * np.pi * t))) < 1e-3)
    True
    """
    from scipy.signal import savgol_filter

    y = np.asarray(signal, dtype=float)
    w = max(5, int(window) | 1)
    if w > y.size:
        w = y.size if y.size % 2 else y.size - 1
    if w < 5:
        return np.gradient(y, dt) if order == 1 else np.gradient(np.gradient(y, dt), dt)
    return np.asarray(savgol_filter(y, w, 3, deriv=order, delta=dt, mode="interp"), dtype=float)


def _sine_fit(t: FloatArray, y: FloatArray, f: float) -> tuple[float, FloatArray]:
    w = 2.0 * math.pi * f
    mid = 0.5 * (t[0] + t[-1])
    span = max(t[-1] - t[0], 1e-12)
    basis = np.column_stack([np.ones_like(t), (t - mid) / span, np.cos(w * t), np.sin(w * t)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    resid = y - basis @ coef
    return float(resid @ resid), coef


def detect_frequency(
    time: npt.ArrayLike, signal: npt.ArrayLike, hint: float | None = None
) -> HarmonicFit:
    """Excitation frequency and phase of a (nearly) harmonic, uniformly sampled signal.

    The Hann-windowed FFT peak (zero-padded, parabolic interpolation) gives a first
    estimate, which a least-squares sine fit (with offset and linear drift) refines;
    ``hint`` (e.g. the manifest's frequency) is tried as a second starting point and
    the better fit wins.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 3.0, 1e-3)
    >>> fit = detect_frequency(t, 0.02 * np.sin(2 * np.pi * 1.37 * t + 1.0) + 0.005)
    >>> round(fit.frequency, 6), round(fit.amplitude, 6), round(fit.phase, 6)
    (1.37, 0.02, 1.0)
    """
    from scipy.optimize import minimize_scalar

    t = np.asarray(time, dtype=float)
    y = np.asarray(signal, dtype=float)
    n = t.size
    duration = float(t[-1] - t[0])
    dt = duration / (n - 1)
    y0 = y - y.mean()
    total = float(y0 @ y0)
    if n < 8 or total == 0.0:
        raise TestDataError("no excitation found: the motion signal is constant")
    detr = y0 - np.polyval(np.polyfit(t - t[0], y0, 1), t - t[0])
    nfft = 1 << (math.ceil(math.log2(n)) + 3)
    spec = np.abs(np.fft.rfft(detr * np.hanning(n), nfft))
    freqs = np.fft.rfftfreq(nfft, dt)
    kmin = max(1, int(np.searchsorted(freqs, 0.5 / duration)))
    k = kmin + int(np.argmax(spec[kmin:-1])) if spec.size > kmin + 1 else kmin
    if 0 < k < spec.size - 1:
        a, b, c = np.log(spec[k - 1 : k + 2] + 1e-300)
        denom = a - 2 * b + c
        shift = 0.5 * (a - c) / denom if denom != 0 else 0.0
        f_fft = float(freqs[k] + np.clip(shift, -1, 1) * (freqs[1] - freqs[0]))
    else:  # pragma: no cover - degenerate spectra
        f_fft = float(freqs[k])
    candidates = [f_fft] + ([float(hint)] if hint else [])
    best: tuple[float, float] | None = None
    for f0 in candidates:
        if not f0 > 0:
            continue
        half = 0.6 / duration + 0.02 * f0
        lo, hi = max(f0 - half, 0.25 * f0), f0 + half
        res = minimize_scalar(
            lambda f: _sine_fit(t, y0, f)[0],
            bounds=(lo, hi),
            method="bounded",
            options={"xatol": 1e-9 * f0},
        )
        if best is None or res.fun < best[1]:
            best = (float(res.x), float(res.fun))
    if best is None:  # pragma: no cover - f_fft is always > 0
        raise TestDataError("no excitation frequency found")
    f = best[0]
    _, coef = _sine_fit(t, y0, f)
    amp = float(math.hypot(coef[2], coef[3]))
    phase = float(math.atan2(coef[2], coef[3]))
    return HarmonicFit(
        frequency=f,
        amplitude=amp,
        phase=phase,
        offset=float(y.mean() + coef[0]),
        explained=1.0 - best[1] / total,
    )


#: Largest share of rows holding NaN/inf that pre-processing drops (with a note) rather
#: than refuses: a few dropped samples are bridged by the uniform-grid interpolation.
MAX_BAD_ROWS = 0.02

#: Fewest samples per excitation period that still resolve a loop (a 5-point
#: derivative window then spans under half a period; 40 per cycle is common at 200 Hz).
MIN_SAMPLES_PER_CYCLE = 12

#: Largest relative difference between the velocity column's amplitude and 2 pi f times
#: the stroke amplitude before a warning (a unit or column mix-up).
VELOCITY_TOLERANCE = 0.05

#: Largest difference [degrees] between the velocity column's phase lead on the stroke
#: and a quarter period before a warning (a flipped sign, a column that is not the
#: stroke's derivative).
VELOCITY_PHASE_TOLERANCE = 20.0

#: ``--peak-velocity auto``: the manifest's ``2 pi f a_m`` is the v_m of a test when the
#: cycles fitted move at it within this fraction (``2 pi f`` times their stroke
#: amplitude); otherwise their measured velocity amplitude is.
NOMINAL_AGREEMENT = 0.02

#: Peak force [N] outside which the declared force unit is implausible for a damper
#: (a kN record declared in N peaks below 1 N; an N record declared in kN above 1 MN).
PLAUSIBLE_FORCE = (1.0, 1e6)


def _drop_bad_rows(raw: RawTest, notes: list[str]) -> RawTest:
    """Drop the rows holding NaN or inf in any signal when they are few
    (:data:`MAX_BAD_ROWS`); leave the record alone otherwise (``_check_signals`` then
    names the first bad value)."""
    import dataclasses

    arrays = {
        role: np.asarray(getattr(raw, role), dtype=float)
        for role in ("time", "displacement", "velocity", "acceleration", "force", "current")
        if isinstance(getattr(raw, role), np.ndarray)
    }
    n = raw.time.size
    if any(a.shape != (n,) for a in arrays.values()):
        return raw
    bad = np.zeros(n, dtype=bool)
    where = []
    for role, a in arrays.items():
        row_bad = ~np.isfinite(a)
        if row_bad.any():
            where.append(role)
        bad |= row_bad
    count = int(bad.sum())
    if count == 0:
        return raw
    share = count / n
    if share > MAX_BAD_ROWS:
        first = int(np.flatnonzero(bad)[0])
        at = f"data row {first + 1}"
        if np.isfinite(raw.time[first]):
            at += f", t = {raw.time[first]:.6g} s"
        raise TestDataError(
            f"{count} of {n} rows ({100 * share:.1f} %) hold NaN or infinite values in "
            f"{', '.join(where)} (first at {at}); more than {100 * MAX_BAD_ROWS:g} % cannot be "
            "bridged: clean or cut the record"
        )
    keep = ~bad
    notes.append(
        f"dropped {count} row{'s' if count > 1 else ''} holding NaN or infinite values in "
        f"{', '.join(where)} ({100 * share:.2g} % of the record)"
    )
    changes: dict[str, Any] = {role: a[keep] for role, a in arrays.items()}
    return dataclasses.replace(raw, **changes)


def _check_force_unit(raw: RawTest) -> None:
    peak = float(np.max(np.abs(raw.force)))
    unit = raw.units.get("force", "N")
    low, high = PLAUSIBLE_FORCE
    if 0 < peak < low:
        hint = "kN" if unit.lower() == "n" else "a larger unit"
        raise TestDataError(
            f"the force peaks at {peak:.3g} N with the force declared in {unit}: implausibly "
            f"small for a damper; is the force column in {hint}? (--units, e.g. F=kN)"
        )
    if peak > high:
        hint = "N" if unit.lower() == "kn" else "a smaller unit"
        raise TestDataError(
            f"the force peaks at {peak:.3g} N with the force declared in {unit}: implausibly "
            f"large for a damper; is the force column in {hint}? (--units, e.g. F=N)"
        )


def _check_signals(raw: RawTest) -> None:
    for role in ("time", "displacement", "velocity", "acceleration", "force", "current"):
        value = getattr(raw, role)
        if value is None:
            continue
        arr = np.asarray(value, dtype=float)
        bad = ~np.isfinite(arr)
        if np.any(bad):
            idx = np.flatnonzero(bad.ravel())
            what = "NaN" if np.isnan(arr.ravel()[idx[0]]) else "infinite"
            at = f"data row {idx[0] + 1}"
            if arr.ndim and role != "time" and np.isfinite(raw.time[idx[0]]):
                at += f", t = {raw.time[idx[0]]:.6g} s"
            raise TestDataError(
                f"{role} has {idx.size} {what} value{'s' if idx.size > 1 else ''} "
                f"(first at {at}); clean or cut the record"
            )
    if raw.time.ndim != 1 or raw.time.size < 16:
        raise TestDataError(f"the record has {raw.time.size} samples; at least 16 are needed")
    steps = np.diff(raw.time)
    back = np.flatnonzero(steps <= 0)
    if back.size:
        k = int(back[0])
        raise TestDataError(
            f"time is not increasing at data row {k + 2} (t = {raw.time[k + 1]:.6g} s after "
            f"{raw.time[k]:.6g} s; {back.size} place{'s' if back.size > 1 else ''}); "
            "sort or split the record"
        )


def _uniform(raw: RawTest, notes: list[str]) -> dict[str, FloatArray | None]:
    t = raw.time
    steps = np.diff(t)
    dt = float(np.median(steps))
    signals: dict[str, FloatArray | None] = {
        role: (None if getattr(raw, role) is None else np.asarray(getattr(raw, role), float))
        for role in ("displacement", "velocity", "acceleration", "force")
    }
    cur = raw.current
    signals["current"] = cur if isinstance(cur, np.ndarray) else None
    jitter = float(np.max(np.abs(steps - dt)) / dt)
    if jitter <= 0.01:
        signals["time"] = t
        return signals
    # the grid step is the mean step: a median of rounded time stamps is biased
    dt = float(t[-1] - t[0]) / (t.size - 1)
    n = math.floor((t[-1] - t[0]) / dt + 1e-9) + 1
    grid = t[0] + dt * np.arange(n)
    notes.append(
        f"time steps vary ({steps.min() * 1e3:.4g}-{steps.max() * 1e3:.4g} ms): resampled "
        f"onto a uniform {dt * 1e3:.4g} ms grid"
    )
    big = np.flatnonzero(steps > 5 * dt)
    if big.size:
        notes.append(
            f"{big.size} gap(s) in the time base, the longest {steps.max():.4g} s at "
            f"t = {t[int(np.argmax(steps))]:.6g} s (bridged by linear interpolation)"
        )
    out: dict[str, FloatArray | None] = {"time": grid}
    for role, value in signals.items():
        out[role] = None if value is None else np.interp(grid, t, value)
    return out


def _cycle_times(fit: HarmonicFit, start: float, n_points: int) -> FloatArray:
    """Times of phases 2 pi j / N inside the cycle window [start, start + T)."""
    period = 1.0 / fit.frequency
    zero = -fit.phase / (2.0 * math.pi * fit.frequency)  # a time of phase 0
    offsets = zero + period * np.arange(n_points) / n_points
    m = np.ceil((start - offsets) / period - 1e-12)
    return offsets + m * period


#: Ways of cutting a record into whole cycles tried per period: the cycles' windows start
#: at the record's end minus ``j / ALIGNMENTS`` of a period, ``j = 0 .. ALIGNMENTS - 1``
#: (``j = 0``: aligned to the end, as a record that is steady throughout is cut).
ALIGNMENTS = 16


def _window_metrics(
    t: FloatArray, x: FloatArray, force: FloatArray, frequency: float, starts: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Stroke amplitude, force range and half-period stroke amplitudes of each
    one-period window ``[s, s + T)``.

    The stroke amplitude is ``sqrt(2)`` times the RMS of the window's raw stroke samples
    about their mean, after the record's offset and linear drift (those of a least-
    squares sine at ``frequency`` over the whole record) are removed; all windows at
    once, from running sums. An RMS, unlike a sine fitted to the window, weighs every
    sample alike: a window overlapping a ramp shows a smaller stroke. The same figure
    over each half of the window (about the whole window's mean; shape ``(n, 2)``)
    shows a stroke that changes within the window. The force range is the peak to peak
    of the window's force samples.
    """
    dt = float(t[1] - t[0])
    period = 1.0 / frequency
    _, coef = _sine_fit(t, x, frequency)
    mid, span = 0.5 * (t[0] + t[-1]), max(float(t[-1] - t[0]), 1e-12)
    y = x - coef[0] - coef[1] * (t - mid) / span
    # each sample stands for the cell [t - dt/2, t + dt/2); a window's sums weigh its
    # two end cells by the fraction inside it, so that every window spans exactly one
    # period (a whole number of samples would not: 40.5 samples per period cut into
    # 40 or 41 would scatter the RMS by half a percent)
    vals = np.vstack([y, y * y])
    cum = np.zeros((2, t.size + 1))
    np.cumsum(vals, axis=1, out=cum[:, 1:])
    last = t.size - 1

    def cell_sums(c0: FloatArray, c1: FloatArray) -> FloatArray:
        """Sums of y and y^2 over cell coordinates [c0, c1) (shape (2, n))."""
        a = np.clip(np.floor(c0).astype(np.intp), 0, last)
        b = np.clip(np.floor(c1).astype(np.intp), 0, last)
        full = cum[:, b] - cum[:, np.minimum(a + 1, b)]
        head = vals[:, a] * np.where(a == b, c1 - c0, a + 1 - c0)
        tail = np.where(a == b, 0.0, vals[:, b] * (c1 - b))
        return np.asarray(full + head + tail, dtype=float)

    c_start = (starts - t[0]) / dt + 0.5
    c_mid = c_start + 0.5 * period / dt
    c_end = c_start + period / dt
    whole = cell_sums(c_start, c_end)
    mean = whole[0] / (c_end - c_start)

    def rms_amplitude(sums: FloatArray, width: FloatArray) -> FloatArray:
        return np.sqrt(2.0 * np.maximum((sums[1] - 2 * mean * sums[0]) / width + mean**2, 0.0))

    amplitudes = rms_amplitude(whole, c_end - c_start)
    halves = np.column_stack(
        [
            rms_amplitude(cell_sums(c_start, c_mid), c_mid - c_start),
            rms_amplitude(cell_sums(c_mid, c_end), c_end - c_mid),
        ]
    )
    i0 = np.searchsorted(t, starts - 0.5 * dt)
    i1 = np.searchsorted(t, starts + period - 0.5 * dt)
    ranges = np.array([np.ptp(force[a:b]) for a, b in zip(i0, i1, strict=True)])
    return amplitudes, ranges, halves


@dataclass(frozen=True)
class _Cut:
    """The record cut into whole cycles (window starts), their figures, and the plateau."""

    starts: FloatArray
    amplitudes: FloatArray
    ranges: FloatArray
    run: PlateauRun
    in_record: int  # whole cycles in the record (those of the end-aligned cut)

    @property
    def n_full(self) -> int:
        return int(self.starts.size)


def _plateau_cut(
    t: FloatArray,
    x: FloatArray,
    force: FloatArray,
    frequency: float,
    opts: PreprocessOptions,
) -> _Cut:
    """Cut the record into whole cycles where they fit its plateau best (module
    :mod:`~mrsuspension.identify.plateau`): try :data:`ALIGNMENTS` cuts per period, find
    the longest run of consistent cycles of each, and keep the best run of all."""
    period = 1.0 / frequency
    dt = float(t[1] - t[0])
    t0, t_end = float(t[0]), float(t[-1])
    per_alignment: list[FloatArray] = []
    for j in range(ALIGNMENTS):
        end = t_end - j * period / ALIGNMENTS
        n = math.floor((end - t0 + 0.5 * dt) / period + 1e-9)
        per_alignment.append(end - period * np.arange(n, 0, -1, dtype=float))
    starts_all = np.concatenate(per_alignment)
    amps_all, ranges_all, halves_all = _window_metrics(t, x, force, frequency, starts_all)
    runs: list[PlateauRun] = []
    figures: list[tuple[FloatArray, FloatArray]] = []
    k = 0
    for j, starts in enumerate(per_alignment):
        a, r = amps_all[k : k + starts.size], ranges_all[k : k + starts.size]
        halves = halves_all[k : k + starts.size]
        k += starts.size
        figures.append((a, r))
        runs += consistent_runs(
            a,
            r,
            stroke_tolerance=opts.stroke_tolerance,
            range_tolerance=opts.steady_tolerance,
            alignment=j,
            positions=(starts - t0) / period,
            halves=halves,
        )
    if not runs:
        raise TestDataError("no motion: the stroke amplitude is zero in every cycle")
    best = choose_plateau(runs, stroke_tolerance=opts.stroke_tolerance)
    if best.length < 2 <= per_alignment[0].size:
        a, r = figures[0]
        raise TestDataError(
            no_plateau_message(
                a,
                r,
                stroke_tolerance=opts.stroke_tolerance,
                range_tolerance=opts.steady_tolerance,
                frequency=frequency,
            )
        )
    a, r = figures[best.alignment]
    return _Cut(per_alignment[best.alignment], a, r, best, per_alignment[0].size)


def _dropped_text(
    side: str, idx: range, cut: _Cut, ref_amp: float, ref_range: float, tol: float
) -> str:
    """``"3 leading cycles dropped as not steady (ramp-in: stroke 2.1-8.9 mm)"``."""
    n = len(idx)
    what = f"{n} {side} cycle{'s' if n > 1 else ''} dropped as not steady"
    amps = cut.amplitudes[idx.start : idx.stop]
    ranges = cut.ranges[idx.start : idx.stop]
    dev_a = amps / ref_amp - 1
    dev_r = ranges / ref_range - 1
    if np.all(np.abs(dev_a) <= tol):  # same stroke: a force transient
        worst = int(np.argmax(np.abs(dev_r)))
        return (
            f"{what} (cycle {idx.start + worst + 1}: stroke {100 * dev_a[worst]:+.1f} %, force "
            f"range {100 * dev_r[worst]:+.1f} % off the plateau's)"
        )
    ramp = {"leading": "ramp-in", "trailing": "ramp-out"}[side]
    kind = ramp if np.all(amps < ref_amp) else "stroke amplitude off the plateau's"
    lo, hi = 1e3 * float(amps.min()), 1e3 * float(amps.max())
    strokes = f"{lo:.3g} mm" if n == 1 else f"{lo:.3g}-{hi:.3g} mm"
    return f"{what} ({kind}: stroke {strokes})"


def preprocess(
    raw: RawTest,
    options: PreprocessOptions | None = None,
    *,
    current: float | None = None,
    frequency: float | None = None,
    amplitude: float | None = None,
    label: str | None = None,
) -> Loop:
    """Turn a raw harmonic test record into its steady-state loop (module docstring).

    Parameters
    ----------
    raw : RawTest
        The record, in SI units.
    options : PreprocessOptions, optional
        Settings (default: 360 points, no offset removal, all steady cycles).
    current : float, optional
        Drive current [A] (from the manifest); otherwise the record's current.
    frequency, amplitude : float, optional
        Nominal excitation f [Hz] and a_m [m] (from the manifest).
    label : str, optional
        Name of the test in messages (default: the record's source).

    Raises
    ------
    TestDataError
        When the record cannot give a loop (NaN, time not increasing, no whole cycle,
        no current...).
    """
    opts = options or PreprocessOptions()
    notes: list[str] = []
    raw = _drop_bad_rows(raw, notes)
    _check_signals(raw)
    _check_force_unit(raw)
    sig = _uniform(raw, notes)
    t = sig["time"]
    assert t is not None
    dt = float(t[1] - t[0])
    x, v, a, force = sig["displacement"], sig["velocity"], sig["acceleration"], sig["force"]
    assert force is not None
    if opts.force_delay > 0:
        # the force recorded at t belongs to the motion at t - delay: delay the motion
        # (smooth signals, interpolated by cubic splines) rather than advance the force
        # (a yield knee, which interpolation would round)
        if opts.force_delay > 0.25 * float(t[-1] - t[0]):
            raise TestDataError(
                f"the force delay {1e3 * opts.force_delay:g} ms is more than a quarter of the "
                f"record ({float(t[-1] - t[0]):.4g} s)"
            )
        from scipy.interpolate import CubicSpline

        x, v, a = (
            None if y is None else np.asarray(CubicSpline(t, y)(t - opts.force_delay), dtype=float)
            for y in (x, v, a)
        )
        notes.append(
            f"motion delayed by {1e3 * opts.force_delay:g} ms to meet the force (the load "
            "cell's delay, force_delay)"
        )
    x_from_file, v_from_file = x is not None, v is not None
    motion = x if x is not None else v
    assert motion is not None
    fit = detect_frequency(t, motion, hint=frequency)
    if fit.explained < 0.5:
        raise TestDataError(
            "no harmonic excitation found: the best sine explains only "
            f"{100 * fit.explained:.0f} % of the {'displacement' if x is not None else 'velocity'}"
            " variance"
        )
    if not np.ptp(force) > 0:
        raise TestDataError("the force is constant over the record; nothing to fit")
    f = fit.frequency
    period = 1.0 / f
    duration = float(t[-1] - t[0])
    n_full = math.floor((duration + 0.5 * dt) / period + 1e-9)
    if n_full < 1:
        raise TestDataError(
            f"no whole cycle: the record lasts {duration:.4g} s, {duration * f:.2f} periods of "
            f"the {f:.4g} Hz excitation; at least one whole cycle is needed"
        )
    if frequency is not None and abs(f / frequency - 1) > 0.02:
        notes.append(
            f"warning: detected {f:.4g} Hz but the manifest says {frequency:g} Hz "
            f"({100 * (f / frequency - 1):+.1f} %); cycles are cut at the detected frequency"
        )
    spc = period / dt
    if spc < MIN_SAMPLES_PER_CYCLE:
        raise TestDataError(
            f"{spc:.3g} samples per cycle ({1 / dt:.4g} Hz sampling of a {f:.4g} Hz "
            f"excitation); at least {MIN_SAMPLES_PER_CYCLE} are needed to resolve the loop: "
            "record at a higher sample rate"
        )
    # the derivative window follows the samples per cycle: `smoothing` of a period,
    # at least 5 samples (a cubic fit), so at 40 samples per cycle 5 samples (1/8 period)
    window = max(5, round(opts.smoothing * spc) | 1)
    sg = f"Savitzky-Golay, cubic, {window}-sample window"
    if x is None:
        assert v is not None
        from scipy.integrate import cumulative_trapezoid

        x = cumulative_trapezoid(v, t, initial=0.0)
        # remove offset and drift (a velocity offset integrates to a ramp), not the sine
        _, coef = _sine_fit(t, x, f)
        mid, span = 0.5 * (t[0] + t[-1]), t[-1] - t[0]
        x = x - coef[0] - coef[1] * (t - mid) / span
        notes.append("displacement integrated from velocity (offset and drift removed)")
    if v is None:
        v = smooth_derivative(x, dt, window, 1)
        notes.append(f"velocity derived from displacement ({sg})")
        if a is None:
            a = smooth_derivative(x, dt, window, 2)
            notes.append(f"acceleration derived from displacement ({sg})")
    if a is None:
        a = smooth_derivative(v, dt, window, 1)
        notes.append(f"acceleration derived from velocity ({sg})")
    if spc < opts.points_per_cycle:
        notes.append(f"upsampled from {spc:.0f} samples per cycle (linear interpolation)")

    # whole cycles, cut where they fit the record's plateau best (identify.plateau)
    n_pts = opts.points_per_cycle
    cut = _plateau_cut(t, x, force, f, opts)
    if cut.run.length < cut.n_full:
        # ramps and transients bias the frequency: detect it again on the plateau only
        # and cut again
        span0 = float(cut.starts[cut.run.start])
        sel = (t >= span0 - 0.5 * dt) & (t <= span0 + cut.run.length * period + 0.5 * dt)
        if np.count_nonzero(sel) >= 16:
            refit = detect_frequency(t[sel], motion[sel], hint=f)
            if refit.explained >= 0.5 and abs(refit.frequency / f - 1) < 0.05:
                fit, f, period = refit, refit.frequency, 1.0 / refit.frequency
                cut = _plateau_cut(t, x, force, f, opts)
    run, n_full = cut.run, cut.n_full
    first = run.start
    if opts.max_cycles is not None:
        first = max(first, run.stop - opts.max_cycles)
    kept = list(range(first, run.stop))
    signals = {"x": x, "v": v, "a": a, "F": force}
    if sig["current"] is not None:
        signals["i"] = sig["current"]
    cyc: dict[str, list[FloatArray]] = {key: [] for key in ("x", "v", "a", "F", "i")}
    for k in kept:
        tau = _cycle_times(fit, float(cut.starts[k]), n_pts)
        for key, series in signals.items():
            cyc[key].append(np.interp(tau, t, series))
    span = (float(cut.starts[kept[0]]), float(cut.starts[kept[-1]]) + period)
    plateau_amps = cut.amplitudes[run.start : run.stop]
    plateau_ranges = cut.ranges[run.start : run.stop]
    ref_amp, ref_range = float(np.median(plateau_amps)), float(np.median(plateau_ranges))
    text = f"{cut.in_record} whole cycle{'s' if cut.in_record > 1 else ''} at {f:.4g} Hz"
    if n_full == 1:
        text += "; only one cycle, steady state not verified"
    else:
        of = f"of {n_full}" if n_full == cut.in_record else f"of {n_full} (cut to fit the plateau)"
        text += (
            f"; cycles {kept[0] + 1}-{kept[-1] + 1} {of} used (t = {span[0]:.6g}-{span[1]:.6g} "
            f"s; plateau: stroke {1e3 * plateau_amps.min():.4g}-{1e3 * plateau_amps.max():.4g} "
            f"mm, force range {plateau_ranges.min():.4g}-{plateau_ranges.max():.4g} N"
        )
        if opts.max_cycles is not None and first > run.start:
            text += f"; the last {len(kept)} of its {run.length} cycles (max_cycles)"
        text += ")"
        tol = opts.stroke_tolerance
        if run.start > 0:
            text += "; " + _dropped_text(
                "leading", range(0, run.start), cut, ref_amp, ref_range, tol
            )
        if run.stop < n_full:
            text += "; " + _dropped_text(
                "trailing", range(run.stop, n_full), cut, ref_amp, ref_range, tol
            )
    loop_f = np.mean(cyc["F"], axis=0)
    spread = 0.0
    if len(kept) > 1:
        dev = np.array(cyc["F"]) - loop_f
        spread = float(np.sqrt(np.mean(dev**2)) / max(np.ptp(loop_f), 1e-300))
        text += f"; {len(kept)} averaged (cycle-to-cycle spread {100 * spread:.2g} % of the force range)"
    notes.append(text)
    loop_x = np.mean(cyc["x"], axis=0)
    loop_v = np.mean(cyc["v"], axis=0)
    loop_a = np.mean(cyc["a"], axis=0)
    offset = 0.0
    if opts.remove_offset:
        offset = float(np.mean(loop_f))
        loop_f = loop_f - offset
        notes.append(f"removed a force offset of {offset:.4g} N (mean force of the loop)")
    if not np.ptp(loop_f) > 0:
        raise TestDataError("the force is constant over the loop; nothing to fit")

    # drive current
    loop_i: FloatArray
    if current is not None:
        loop_i = np.full(n_pts, float(current))
        if cyc["i"]:
            measured = float(np.mean(cyc["i"]))
            if abs(measured - current) > max(0.005, 0.05 * abs(current)):
                notes.append(
                    f"warning: the current column averages {measured:.4g} A; the manifest's "
                    f"{current:g} A is used"
                )
    elif cyc["i"]:
        per_point = np.mean(cyc["i"], axis=0)
        mean_i = float(per_point.mean())
        if np.ptp(per_point) > 0.1 * abs(mean_i) + 0.02:
            loop_i = per_point
            notes.append(
                f"current from the file varies {per_point.min():.3g}-{per_point.max():.3g} A "
                "over the loop; the fit uses it point by point"
            )
        else:
            loop_i = np.full(n_pts, mean_i)
            notes.append(f"current {mean_i:.4g} A (mean of the file's current column)")
    elif isinstance(raw.current, float):
        loop_i = np.full(n_pts, raw.current)
        notes.append(f"current {raw.current:.4g} A from the file")
    else:
        raise TestDataError("no drive current for this test")
    if np.min(loop_i) < 0:
        if np.min(loop_i) < -0.02:
            raise TestDataError(
                f"the drive current is negative ({np.min(loop_i):.4g} A); currents must be >= 0"
            )
        loop_i = np.maximum(loop_i, 0.0)
        notes.append("small negative currents (sensor offset) clipped to 0 A")

    # peak velocity v_m for the dissertation's models and the stroke amplitude: least-
    # squares sines (with offset and drift) over the raw samples of the cycles fitted, at
    # the detected frequency. Measured on the samples themselves, not on the resampled,
    # phase-averaged loop, these figures do not depend on the interpolation, the cycle
    # alignment or the sample rate; measured on the cycles fitted, not on the record, they
    # describe the loop the model is compared with (not a ramp).
    sel = (t >= span[0] - 0.5 * dt) & (t <= span[1] + 0.5 * dt)
    _, coef_v = _sine_fit(t[sel], v[sel], f)
    _, coef_x = _sine_fit(t[sel], x[sel], f)
    measured_vm = float(math.hypot(coef_v[2], coef_v[3]))
    loop_amplitude = float(math.hypot(coef_x[2], coef_x[3]))
    how = f"least-squares sine over the {len(kept)} cycle{'s' if len(kept) > 1 else ''} fitted"
    v_what = "of the velocity column" if v_from_file else "of the derived velocity"
    if x_from_file and v_from_file and loop_amplitude > 0:
        # the velocity column must be the derivative of the stroke: amplitude 2 pi f a,
        # leading the stroke by a quarter period
        ratio = measured_vm / (2.0 * math.pi * f * loop_amplitude)
        lead = math.degrees(math.atan2(coef_v[2], coef_v[3]) - math.atan2(coef_x[2], coef_x[3]))
        lead = (lead + 180.0) % 360.0 - 180.0
        if abs(ratio - 1) > VELOCITY_TOLERANCE:
            notes.append(
                f"warning: the velocity column's amplitude {measured_vm:.4g} m/s is "
                f"{100 * (ratio - 1):+.0f} % off 2 pi f times the stroke amplitude "
                f"({2 * math.pi * f * loop_amplitude:.4g} m/s, {how}); check the velocity "
                "unit and column"
            )
        elif abs(lead - 90.0) > VELOCITY_PHASE_TOLERANCE:
            flipped = abs(lead + 90.0) <= VELOCITY_PHASE_TOLERANCE
            notes.append(
                f"warning: the velocity column leads the stroke by {lead:.0f} degrees, not "
                f"90 ({how}): it is not the stroke's derivative; "
                + ("is its sign flipped? (--columns -v)" if flipped else "check the column")
            )
    has_nominal = frequency is not None and amplitude is not None
    if opts.peak_velocity == "nominal" and not has_nominal:
        raise TestDataError(
            "peak velocity 'nominal' needs the frequency and amplitude in the manifest"
        )
    if has_nominal and opts.peak_velocity != "measured":
        assert frequency is not None
        assert amplitude is not None
        nominal_vm = 2.0 * math.pi * frequency * amplitude
        # the manifest's v_m describes the cycles fitted when their motion agrees with it
        motion_vm = 2.0 * math.pi * f * loop_amplitude
        agrees = abs(motion_vm / nominal_vm - 1) <= NOMINAL_AGREEMENT
        if opts.peak_velocity == "nominal" or agrees:
            vm = nominal_vm
            notes.append(f"v_m = 2 pi f a_m = {vm:.4g} m/s (manifest)")
            if abs(measured_vm / vm - 1) > 0.1:
                notes.append(
                    f"warning: the velocity amplitude {measured_vm:.4g} m/s ({how} {v_what}) "
                    f"differs by {100 * (measured_vm / vm - 1):+.0f} % from 2 pi f a_m = "
                    f"{vm:.4g} m/s"
                )
        else:
            vm = measured_vm
            notes.append(
                f"v_m = {vm:.4g} m/s (amplitude {v_what}, {how}): the manifest's 2 pi f a_m "
                f"= {nominal_vm:.4g} m/s is {100 * (nominal_vm / motion_vm - 1):+.1f} % off "
                f"the fitted cycles' 2 pi f a = {motion_vm:.4g} m/s"
            )
    else:
        vm = measured_vm
        notes.append(f"v_m = {vm:.4g} m/s (amplitude {v_what}, {how})")
    if amplitude is not None and abs(loop_amplitude / amplitude - 1) > 0.1:
        notes.append(
            f"warning: stroke amplitude {loop_amplitude * 1e3:.4g} mm ({how}) differs from "
            f"the manifest's {amplitude * 1e3:g} mm"
        )
    if not 0.0 < vm <= V_LIMIT:
        raise TestDataError(
            f"peak velocity {vm:.4g} m/s is outside (0, {V_LIMIT:g}] m/s; check the units"
        )
    return Loop(
        label=label or raw.source,
        time=period * np.arange(n_pts) / n_pts,
        stroke=loop_x,
        velocity=loop_v,
        acceleration=loop_a,
        force=loop_f,
        current=loop_i,
        frequency=f,
        amplitude=loop_amplitude,
        peak_velocity=vm,
        nominal_frequency=frequency,
        nominal_amplitude=amplitude,
        cycles_found=cut.in_record,
        cycles_used=len(kept),
        cycle_spread=spread,
        force_offset=offset,
        offset_removed=opts.remove_offset,
        notes=tuple(raw.notes) + tuple(notes),
        span=span,
    )
