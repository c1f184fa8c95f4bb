"""Steady-state measures of harmonic runs and their building blocks (model reference, section 9).

Every function takes plain arrays (SI units) and an optional ``window``: ``None`` (the
whole record), a ``slice`` (e.g. from :func:`steady_window`), time limits
``(t_start, t_end)`` [s] (half-open; needs ``time``) or a boolean mask.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError
from mrsuspension.measures._checks import (
    FloatArray,
    Window,
    rate,
    same_length,
    selection,
    signal,
    time_axis,
)

__all__ = [
    "G",
    "T_as",
    "T_au",
    "T_dr",
    "T_ds",
    "T_du",
    "asymmetry_ratio",
    "current_statistics",
    "dlc",
    "force_tracking_error",
    "harmonic_from_moments",
    "harmonic_measures",
    "rms",
    "steady_window",
    "transmissibility",
]

#: gravitational acceleration [m/s^2] (model reference, section 1)
G = 9.81


def _windowed(
    name: str, x: npt.ArrayLike, window: Window, time: npt.ArrayLike | None
) -> FloatArray:
    arr = signal(name, x)
    return arr[selection(arr.size, window, time)]


def rms(x: npt.ArrayLike, *, window: Window = None, time: npt.ArrayLike | None = None) -> float:
    """Root mean square of ``x`` over ``window``.

    Examples
    --------
    >>> t = np.arange(0.0, 1.0, 1e-3)
    >>> round(rms(2.0 * np.sin(2 * np.pi * 5 * t)), 12)  # 2/sqrt(2)
    1.414213562373
    >>> rms([3.0, -3.0, 0.0, 0.0], window=slice(0, 2))
    3.0
    """
    arr = _windowed("x", x, window, time)
    return float(np.sqrt(np.mean(arr * arr)))


def transmissibility(
    response: npt.ArrayLike,
    reference: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """RMS ratio ``rms(response) / rms(reference)`` over the same window, eq. (3.39).

    Examples
    --------
    >>> x = np.sin(np.linspace(0.0, 20.0, 500))
    >>> transmissibility(-0.3 * x, x)
    0.3
    """
    y = signal("response", response)
    r = signal("reference", reference)
    n = same_length(response=y, reference=r)
    sel = selection(n, window, time)
    den = float(np.sqrt(np.mean(r[sel] ** 2)))
    if den == 0.0:
        raise ValidationError("reference has zero rms over the window: transmissibility undefined")
    return float(np.sqrt(np.mean(y[sel] ** 2))) / den


def T_as(
    acc_s: npt.ArrayLike,
    acc_r: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Sprung-mass acceleration transmissibility ``rms(z_s'') / rms(z_r'')``, eq. (3.39)."""
    return _named_ratio("acc_s", acc_s, "acc_r", acc_r, window, time)


def T_au(
    acc_u: npt.ArrayLike,
    acc_r: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Unsprung-mass acceleration transmissibility ``rms(z_u'') / rms(z_r'')``, eq. (3.42)."""
    return _named_ratio("acc_u", acc_u, "acc_r", acc_r, window, time)


def T_dr(
    x_d: npt.ArrayLike,
    z_r: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Relative-displacement transmissibility ``rms(x_d) / rms(z_r)`` (erratum 3)."""
    return _named_ratio("x_d", x_d, "z_r", z_r, window, time)


def T_ds(
    z_s: npt.ArrayLike,
    z_r: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Sprung-mass displacement transmissibility ``rms(z_s) / rms(z_r)`` (HiL monitor)."""
    return _named_ratio("z_s", z_s, "z_r", z_r, window, time)


def T_du(
    z_u: npt.ArrayLike,
    z_r: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Unsprung-mass displacement transmissibility ``rms(z_u) / rms(z_r)`` (HiL monitor)."""
    return _named_ratio("z_u", z_u, "z_r", z_r, window, time)


def _named_ratio(
    num_name: str,
    num: npt.ArrayLike,
    den_name: str,
    den: npt.ArrayLike,
    window: Window,
    time: npt.ArrayLike | None,
) -> float:
    y = signal(num_name, num)
    r = signal(den_name, den)
    n = same_length(**{num_name: y, den_name: r})
    sel = selection(n, window, time)
    d = float(np.sqrt(np.mean(r[sel] ** 2)))
    if d == 0.0:
        raise ValidationError(f"{den_name} has zero rms over the window: ratio undefined")
    return float(np.sqrt(np.mean(y[sel] ** 2))) / d


def steady_window(
    time: npt.ArrayLike,
    frequency: float,
    settle: float = 5.0,
    min_cycles: int = 10,
    min_time: float = 2.0,
) -> slice:
    """Index slice of the steady-state part of a harmonic record (model reference, section 9).

    The record must first settle for at least ``settle`` seconds and ``min_cycles``
    cycles; the window is then the largest whole number of cycles that fits between the
    end of settling and the end of the record, and must last at least ``min_cycles``
    cycles and ``min_time`` seconds. It ends at the last sample and holds
    ``round(cycles / (frequency dt))`` samples (a half-open span of whole cycles).

    Parameters
    ----------
    time : array_like
        Strictly increasing sample times [s] (uniform sampling assumed for the count).
    frequency : float
        Excitation frequency [Hz].
    settle, min_cycles, min_time : optional
        The rule of the model reference, section 9: 5 s, 10 cycles, 2 s.

    Examples
    --------
    >>> t = np.arange(0.0, 14.0 + 5e-4, 1e-3)  # 14 s at 1 kHz
    >>> w = steady_window(t, 1.5)  # settle 6.67 s (10 cycles), then 11 whole cycles
    >>> w.stop - w.start, float(t[w.start])
    (7333, 6.668)
    >>> steady_window(t[:13000], 1.5)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: record too short for the steady-state rule at 1.5 Hz: it needs 6.66667 s of settling then 10 cycles (6.66667 s), 13.3333 s in all; got 12.999 s
    """
    t = time_axis("time", time)
    f = rate("frequency", frequency, "Hz")
    for label, value in (("settle", settle), ("min_time", min_time)):
        if isinstance(value, bool) or not isinstance(value, int | float) or not value >= 0:
            raise ValidationError(f"{label} must be a number >= 0 s; got {value!r}")
    if isinstance(min_cycles, bool) or not isinstance(min_cycles, int) or min_cycles < 1:
        raise ValidationError(f"min_cycles must be an integer >= 1; got {min_cycles!r}")
    if t.size < 2:
        raise ValidationError("time must hold at least 2 samples")
    period = 1.0 / f
    dt = float(np.median(np.diff(t)))
    t_settled = t[0] + max(float(settle), min_cycles * period)
    need = max(min_cycles, math.ceil(float(min_time) * f - 1e-9))
    available = math.floor((t[-1] - t_settled + 0.5 * dt) / period)
    if available < need:
        raise ValidationError(
            f"record too short for the steady-state rule at {f:g} Hz: it needs "
            f"{max(float(settle), min_cycles * period):g} s of settling then {need} cycles "
            f"({need * period:g} s), {t_settled - t[0] + need * period:g} s in all; "
            f"got {t[-1] - t[0]:g} s"
        )
    samples = round(available * period / dt)
    return slice(t.size - samples, t.size)


def dlc(
    tire_force: npt.ArrayLike,
    static_load: float | None = None,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """Dynamic load coefficient ``std(F_T) / load``, eqs. (3.45)-(3.46).

    Parameters
    ----------
    tire_force : array_like
        Tire force ``F_T`` [N] (total, including the static load).
    static_load : float, optional
        ``(m_s + m_u) g`` [N] for harmonic runs; by default the mean of ``F_T`` over
        the window (the random-road definition).

    Examples
    --------
    >>> f = 6405.93 + 640.593 * np.sin(np.linspace(0.0, 2 * np.pi, 1000, endpoint=False))
    >>> round(dlc(f, static_load=(563 + 90) * 9.81), 6)  # 0.1 / sqrt(2)
    0.070711
    """
    f = _windowed("tire_force", tire_force, window, time)
    if static_load is None:
        load = float(np.mean(f))
        if load <= 0.0:
            raise ValidationError(
                f"mean tire force must be > 0 N to normalise the DLC; got {load:g} N "
                "(give static_load)"
            )
    else:
        load = rate("static_load", static_load, "N")
    return float(np.std(f)) / load


def asymmetry_ratio(
    force: npt.ArrayLike, *, window: Window = None, time: npt.ArrayLike | None = None
) -> float:
    """``gamma = max rebound force / max compression force`` (model reference, section 9).

    Rebound is negative damper force in our convention (``F_d > 0`` resists
    compression), so ``gamma = max(-F_d) / max(F_d)``.

    Examples
    --------
    >>> asymmetry_ratio([500.0, -1200.0, 200.0, -300.0])
    2.4
    """
    f = _windowed("force", force, window, time)
    compression = float(np.max(f))
    if compression <= 0.0:
        raise ValidationError(
            "force has no compression (positive) sample in the window: gamma undefined"
        )
    return max(float(np.max(-f)), 0.0) / compression


def current_statistics(
    current: npt.ArrayLike, *, window: Window = None, time: npt.ArrayLike | None = None
) -> dict[str, float]:
    """Mean drive current [A] and mean square current [A^2] (coil power is ``R i^2``).

    Examples
    --------
    >>> current_statistics([0.0, 0.5, 0.5, 0.0])
    {'mean_current': 0.25, 'mean_square_current': 0.125}
    """
    i = _windowed("current", current, window, time)
    return {"mean_current": float(np.mean(i)), "mean_square_current": float(np.mean(i * i))}


def force_tracking_error(
    force: npt.ArrayLike,
    target: npt.ArrayLike,
    switching: npt.ArrayLike,
    *,
    window: Window = None,
    time: npt.ArrayLike | None = None,
) -> float:
    """RMS of ``|F_d| - |F*|`` over the samples where the switching condition ``z_c < 0``.

    Raises
    ------
    ValidationError
        If ``z_c`` is never negative in the window (no tracking phase to measure).

    Examples
    --------
    >>> force_tracking_error([100.0, -90.0, 50.0], [110.0, -100.0, 0.0], [-1.0, -1.0, 1.0])
    10.0
    """
    f = signal("force", force)
    ft = signal("target", target)
    zc = signal("switching", switching)
    n = same_length(force=f, target=ft, switching=zc)
    sel = np.zeros(n, dtype=bool)
    sel[selection(n, window, time)] = True
    sel &= zc < 0.0
    if not sel.any():
        raise ValidationError(
            "switching (z_c) is never negative in the window: no tracking phase, error undefined"
        )
    e = np.abs(f[sel]) - np.abs(ft[sel])
    return float(np.sqrt(np.mean(e * e)))


def harmonic_measures(
    time: npt.ArrayLike,
    frequency: float,
    *,
    z_s: npt.ArrayLike,
    z_u: npt.ArrayLike,
    z_r: npt.ArrayLike,
    acc_s: npt.ArrayLike,
    acc_u: npt.ArrayLike,
    acc_r: npt.ArrayLike,
    x_d: npt.ArrayLike,
    F_d: npt.ArrayLike,
    F_T: npt.ArrayLike,
    static_load: float,
    i_d: npt.ArrayLike | None = None,
) -> dict[str, Any]:
    """The harmonic measures over :func:`steady_window`, by name (model reference, section 9).

    Returns ``T_as``, ``T_au``, ``T_dr``, ``T_ds``, ``T_du``, ``DLC`` (against
    ``static_load = (m_s + m_u) g``), ``gamma`` (``None`` when the damper never
    pushes in compression) and, with ``i_d``, ``mean_current`` and ``mean_square_current``.

    Examples
    --------
    >>> t = np.arange(0.0, 14.0, 1e-3)
    >>> zr = 0.025 * np.sin(2 * np.pi * 1.5 * t)
    >>> ar = -(2 * np.pi * 1.5) ** 2 * zr
    >>> m = harmonic_measures(t, 1.5, z_s=2 * zr, z_u=zr, z_r=zr, acc_s=2 * ar, acc_u=ar,
    ...                       acc_r=ar, x_d=-zr, F_d=100 * zr, F_T=6406 + 1e4 * zr,
    ...                       static_load=6406.0)
    >>> round(m["T_as"], 6), round(m["T_dr"], 6), round(m["gamma"], 6)
    (2.0, 1.0, 1.0)
    """
    t = time_axis("time", time)
    w = steady_window(t, frequency)
    sig = {
        k: signal(k, v)
        for k, v in {
            "z_s": z_s, "z_u": z_u, "z_r": z_r, "acc_s": acc_s, "acc_u": acc_u,
            "acc_r": acc_r, "x_d": x_d, "F_d": F_d, "F_T": F_T,
        }.items()
    }  # fmt: skip
    if i_d is not None:
        sig["i_d"] = signal("i_d", i_d)
    same_length(time=t, **sig)
    win = {k: v[w] for k, v in sig.items()}
    squares = {
        k: float(np.mean(win[k] ** 2))
        for k in ("acc_s", "acc_u", "acc_r", "x_d", "z_s", "z_u", "z_r")
    }
    force = win["F_d"]
    current = None
    if i_d is not None:
        stats = current_statistics(win["i_d"])
        current = (stats["mean_current"], stats["mean_square_current"])
    return harmonic_from_moments(
        squares,
        tire_force_variance=float(np.var(win["F_T"])),
        static_load=static_load,
        compression_peak=float(np.max(force)),
        rebound_peak=float(np.max(-force)),
        current=current,
    )


def harmonic_from_moments(
    mean_squares: Mapping[str, float],
    *,
    tire_force_variance: float,
    static_load: float,
    compression_peak: float,
    rebound_peak: float,
    current: tuple[float, float] | None = None,
) -> dict[str, Any]:
    """The harmonic measures from the steady window's moments (one definition of each).

    :func:`harmonic_measures` computes the moments from time histories; the engine's
    in-kernel reduction (:mod:`mrsuspension.engine.reduced`) accumulates them while
    stepping. Both end here.

    Parameters
    ----------
    mean_squares : mapping
        Mean of the square over the window of ``acc_s``, ``acc_u``, ``acc_r``, ``x_d``,
        ``z_s``, ``z_u`` and ``z_r`` (SI units squared).
    tire_force_variance : float
        Variance of ``F_T`` over the window [N^2].
    static_load : float
        ``(m_s + m_u) g`` [N].
    compression_peak, rebound_peak : float
        ``max F_d`` and ``max(-F_d)`` over the window [N].
    current : (float, float), optional
        Mean drive current [A] and mean square current [A^2] over the window.

    Examples
    --------
    >>> ms = {"acc_s": 4.0, "acc_u": 1.0, "acc_r": 1.0, "x_d": 1.0, "z_s": 4.0,
    ...       "z_u": 1.0, "z_r": 1.0}
    >>> m = harmonic_from_moments(ms, tire_force_variance=100.0, static_load=1000.0,
    ...                           compression_peak=50.0, rebound_peak=100.0)
    >>> m["T_as"], m["DLC"], m["gamma"]
    (2.0, 0.01, 2.0)
    """
    rms_of = {k: math.sqrt(v) for k, v in mean_squares.items()}
    out: dict[str, Any] = {}
    for name, num, den in (
        ("T_as", "acc_s", "acc_r"),
        ("T_au", "acc_u", "acc_r"),
        ("T_dr", "x_d", "z_r"),
        ("T_ds", "z_s", "z_r"),
        ("T_du", "z_u", "z_r"),
    ):
        if rms_of[den] == 0.0:
            raise ValidationError(f"{den} has zero rms over the window: ratio undefined")
        out[name] = rms_of[num] / rms_of[den]
    out["DLC"] = math.sqrt(tire_force_variance) / rate("static_load", static_load, "N")
    # gamma (asymmetry_ratio): undefined when the damper never pushes in compression
    out["gamma"] = max(rebound_peak, 0.0) / compression_peak if compression_peak > 0.0 else None
    if current is not None:
        out["mean_current"], out["mean_square_current"] = current
    return out
