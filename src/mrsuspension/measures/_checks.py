"""Input checks shared by the measures: named 1-D signals, equal lengths, windows, rates."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError

FloatArray = npt.NDArray[np.float64]

#: A window: ``None`` (everything), a ``slice`` of indices, ``(t_start, t_end)`` time
#: limits [s] (half-open, needs ``time``) or a boolean mask of the signal's length.
Window = slice | tuple[float, float] | npt.ArrayLike | None


def signal(name: str, value: object) -> FloatArray:
    """``value`` as a non-empty, finite 1-D float array (errors name the argument)."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValidationError(f"{name} must be an array of numbers; got {value!r}") from None
    if arr.ndim != 1:
        raise ValidationError(f"{name} must be a one-dimensional array; got shape {arr.shape}")
    if arr.size == 0:
        raise ValidationError(f"{name} must not be empty")
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        i = int(bad[0])
        raise ValidationError(f"{name} must be finite; got {arr[i]} at index {i}")
    return arr


def same_length(**arrays: FloatArray) -> int:
    """The common length of named arrays, or an error listing each length."""
    sizes = {k: v.size for k, v in arrays.items()}
    if len(set(sizes.values())) > 1:
        listed = ", ".join(f"{k} {n}" for k, n in sizes.items())
        raise ValidationError(f"signals must have the same length; got {listed}")
    return next(iter(sizes.values()))


def rate(name: str, value: object, unit: str = "Hz") -> float:
    """A sampling rate: a finite number > 0."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ValidationError(f"{name} must be a number > 0 {unit}; got {value!r}")
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValidationError(f"{name} must be finite and > 0 {unit}; got {v:g} {unit}")
    return v


def time_axis(name: str, value: object, n: int | None = None) -> FloatArray:
    """A strictly increasing, finite time array (of length ``n`` if given)."""
    t = signal(name, value)
    if n is not None and t.size != n:
        raise ValidationError(f"{name} must have the signals' length {n}; got {t.size}")
    steps = np.diff(t)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise ValidationError(
            f"{name} must be strictly increasing; {t[i + 1]:g} s at index {i + 1} follows {t[i]:g} s"
        )
    return t


def selection(n: int, window: Window, time: npt.ArrayLike | None) -> slice | npt.NDArray[np.bool_]:
    """An index selection (slice or boolean mask) of ``n`` samples for ``window``."""
    if window is None:
        return slice(None)
    if isinstance(window, slice):
        if len(range(*window.indices(n))) == 0:
            raise ValidationError(f"window {window} selects no samples of {n}")
        return window
    if (
        isinstance(window, tuple)
        and len(window) == 2
        and not isinstance(window[0], bool | np.bool_)
    ):
        if time is None:
            raise ValidationError("a window given as time limits (t_start, t_end) needs time")
        t = time_axis("time", time, n)
        lo, hi = (float(w) for w in window)
        if not (math.isfinite(lo) and math.isfinite(hi) and hi > lo):
            raise ValidationError(
                f"window must be (t_start, t_end) with finite t_end > t_start [s]; got {window!r}"
            )
        mask = (t >= lo) & (t < hi)
        if not mask.any():
            raise ValidationError(
                f"window [{lo:g}, {hi:g}) s holds no samples; time runs {t[0]:g}-{t[-1]:g} s"
            )
        return mask
    mask = np.asarray(window)
    if mask.dtype != bool or mask.shape != (n,):
        raise ValidationError(
            "window must be None, a slice, (t_start, t_end) in s, or a boolean mask of "
            f"length {n}; got {type(window).__name__} "
            f"{'of shape ' + str(mask.shape) + ' ' if mask.ndim else ''}{mask.dtype}"
        )
    if not mask.any():
        raise ValidationError("window mask selects no samples")
    return mask
