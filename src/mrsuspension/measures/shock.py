"""Shock measures of rounded-pulse runs, eqs. (3.41) and (3.44) (model reference, section 9).

All peaks are maxima of absolute values over the whole record, except the road
acceleration peak that divides ``SAR_s`` and ``SAR_u``: it has two readings, chosen by
``road_peak`` (model reference, section 9, revised 2026-11-24).

``"after-onset"`` (the default)
    The largest ``|z_r''|`` after the onset lobe (:func:`road_acceleration_peak`). The
    rounded pulse (3.38) ``z_r = c x^2 e^-x`` (``c = 0.25 a e^2``, ``x = mu w0 tau``) has
    ``z_r'' = c (mu w0)^2 (x^2 - 4x + 2) e^-x``; after the jump at the onset it falls
    through zero at ``x = 2 - sqrt(2)`` and reaches its extremum where ``x^2 - 6x + 6 =
    0``, at ``x = 3 - sqrt(3)``: ``|z_r''| = (2 sqrt(3) - 2) e^(sqrt(3) - 3) c (mu w0)^2
    = 0.41201 c (mu w0)^2`` (:data:`AFTER_ONSET_FACTOR`). This reading matches the
    dissertation's SAR_s in Tables 4.1-6.3 (``docs/errata.md``).
``"onset"``
    ``max |z_r''|`` over the whole record: for the pulse the jump from 0 to
    ``2 c (mu w0)^2`` at ``tau = 0``, 4.854 times (:data:`ONSET_TO_AFTER_ONSET`) the
    after-onset peak, so ``SAR_s`` and ``SAR_u`` come out 4.854 times smaller.

The dissertation does not say which it used. The displacement peaks (``SDR_s``,
``SDR_u``, ``RDR``) are the same under both: ``z_r`` is 0 at the onset.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Literal

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, did_you_mean
from mrsuspension.measures._checks import rate, same_length, signal
from mrsuspension.measures.steady import G

__all__ = [
    "AFTER_ONSET_FACTOR",
    "DEFAULT_ROAD_PEAK",
    "ONSET_TO_AFTER_ONSET",
    "ROAD_PEAKS",
    "RoadPeak",
    "check_road_peak",
    "dtr",
    "dtr_ratio",
    "peak",
    "road_acceleration_peak",
    "shock_from_peaks",
    "shock_ratios",
]

#: The definitions of the road acceleration peak that divides SAR_s and SAR_u
RoadPeak = Literal["onset", "after-onset"]
#: Their names, the default first
ROAD_PEAKS: tuple[RoadPeak, ...] = ("after-onset", "onset")
#: The dissertation-matching definition (model reference, section 9, revised 2026-11-24)
DEFAULT_ROAD_PEAK: RoadPeak = "after-onset"
#: ``max_{x > 0 after the onset lobe} |d2/dx2 (x^2 e^-x)| = (2 sqrt 3 - 2) e^(sqrt 3 - 3)``,
#: reached at ``x = 3 - sqrt 3``: the after-onset road acceleration peak of the rounded
#: pulse (3.38) in units of ``c (mu w0)^2``
AFTER_ONSET_FACTOR = (2.0 * math.sqrt(3.0) - 2.0) * math.exp(math.sqrt(3.0) - 3.0)
#: onset peak ``2 c (mu w0)^2`` over the after-onset peak: 4.854
ONSET_TO_AFTER_ONSET = 2.0 / AFTER_ONSET_FACTOR
#: a sample belongs to the record's onset when ``|z_r''|`` first exceeds this fraction of
#: its largest value (below it: the quiet lead-in, zero up to round-off)
ONSET_THRESHOLD = 1e-9


def check_road_peak(value: object) -> RoadPeak:
    """``value`` if it names a road-peak definition, else a ValidationError listing them.

    Examples
    --------
    >>> check_road_peak("onset")
    'onset'
    >>> check_road_peak("after_onset")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: road_peak must be one of 'after-onset', 'onset'; got 'after_onset'. Did you mean 'after-onset'?
    """
    if isinstance(value, str) and value in ROAD_PEAKS:
        return value
    names = ", ".join(repr(p) for p in ROAD_PEAKS)
    hint = did_you_mean(value, ROAD_PEAKS) if isinstance(value, str) else ""
    raise ValidationError(f"road_peak must be one of {names}; got {value!r}.{hint}")


def peak(x: npt.ArrayLike) -> float:
    """Largest absolute value of a signal, ``max |x|``.

    Examples
    --------
    >>> peak([0.1, -0.4, 0.3])
    0.4
    """
    return float(np.max(np.abs(signal("x", x))))


def road_acceleration_peak(acc_r: npt.ArrayLike, road_peak: RoadPeak = DEFAULT_ROAD_PEAK) -> float:
    """Peak road acceleration [m/s^2] of a sampled record, by either definition.

    ``"onset"``: ``max |z_r''|`` over the whole record.

    ``"after-onset"``: ``max |z_r''|`` over the samples after the onset lobe. The onset
    is the first sample whose ``|z_r''|`` exceeds ``1e-9`` of the record's largest (the
    samples before it are the quiet lead-in); the onset lobe ends at the first later
    sample where ``z_r''`` is zero or has the opposite sign to its value at the onset,
    and the peak is taken from that sample to the end. For the rounded pulse (3.38) the
    lobe is the decay from the jump ``2 c (mu w0)^2`` to the zero crossing at ``x = 2 -
    sqrt(2)``, and the peak is :data:`AFTER_ONSET_FACTOR` ``c (mu w0)^2`` at ``x = 3 -
    sqrt(3)``, to the sampling's resolution (an error of second order in the step: at most
    3e-4 relative at 1 kHz for mu = 3 at 50 km/h). The definition needs no model of the
    input: a record that starts smoothly (a sine from rest, a road profile) loses only
    its first half-wave, which for a stationary record does not hold the peak.

    Parameters
    ----------
    acc_r : array_like
        Road acceleration ``z_r''`` [m/s^2] over the record.
    road_peak : {"after-onset", "onset"}
        The definition (see :mod:`mrsuspension.measures.shock`).

    Returns
    -------
    float
        The peak [m/s^2], > 0.

    Raises
    ------
    ValidationError
        A record that is zero throughout, an unknown ``road_peak``, or (``"after-onset"``)
        a record that never leaves its onset lobe.

    Examples
    --------
    >>> from mrsuspension.excitation import RoundedPulse
    >>> bump = RoundedPulse(amplitude=0.035, severity=3.0)  # mu w0 = 31.2 1/s
    >>> t = np.arange(0.0, bump.duration, 1e-4)
    >>> a = bump.acceleration(t)
    >>> c = 0.25 * 0.035 * np.e**2
    >>> round(road_acceleration_peak(a, "onset") / (c * bump.rate**2), 6)
    2.0
    >>> round(road_acceleration_peak(a) / (c * bump.rate**2), 5)  # at x = 3 - sqrt(3)
    0.41201
    >>> round(AFTER_ONSET_FACTOR, 5), round(ONSET_TO_AFTER_ONSET, 3)
    (0.41201, 4.854)
    """
    how = check_road_peak(road_peak)
    a = signal("acc_r", acc_r)
    mag = np.abs(a)
    top = float(np.max(mag))
    if top == 0.0:
        raise ValidationError("acc_r is zero over the whole record: shock ratios undefined")
    if how == "onset":
        return top
    k0 = int(np.argmax(mag > ONSET_THRESHOLD * top))
    ends = np.flatnonzero(a[k0 + 1 :] * np.sign(a[k0]) <= 0.0)
    after = float(np.max(mag[k0 + 1 + int(ends[0]) :])) if ends.size else 0.0
    if after == 0.0:
        raise ValidationError(
            f"acc_r never leaves its onset lobe (it keeps the sign of {a[k0]:.4g} m/s^2 at "
            f"sample {k0}, or is zero after it): the after-onset peak is undefined; use "
            "road_peak='onset'"
        )
    return after


def shock_ratios(
    z_s: npt.ArrayLike,
    z_u: npt.ArrayLike,
    z_r: npt.ArrayLike,
    acc_s: npt.ArrayLike,
    acc_u: npt.ArrayLike,
    acc_r: npt.ArrayLike,
    x_d: npt.ArrayLike,
    *,
    road_peak: RoadPeak = DEFAULT_ROAD_PEAK,
) -> dict[str, float]:
    """Shock displacement and acceleration ratios over the whole record.

    ``SDR_s = max|z_s|/max|z_r|``, ``SAR_s = max|z_s''|/z_r''_peak``, ``SDR_u``,
    ``SAR_u`` likewise for the unsprung mass, and ``RDR = max|x_d|/max|z_r|``, where
    ``z_r''_peak`` is :func:`road_acceleration_peak` under ``road_peak``.

    Parameters
    ----------
    z_s, z_u, z_r : array_like
        Sprung, unsprung and road displacement [m], equal lengths.
    acc_s, acc_u, acc_r : array_like
        Their accelerations [m/s^2].
    x_d : array_like
        Suspension stroke ``z_u - z_s`` [m].
    road_peak : {"after-onset", "onset"}, optional
        The road acceleration peak dividing ``SAR_s`` and ``SAR_u``: after the onset
        lobe (default; it matches the dissertation's SAR_s) or over the whole record,
        the jump at the pulse's onset (4.854 times larger for the rounded pulse).

    Returns
    -------
    dict
        ``{"SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR"}``, dimensionless.

    Examples
    --------
    >>> zr = np.array([0.0, 0.02, 0.05, 0.02, 0.0])
    >>> ar = np.array([10.0, 0.0, -5.0, 0.0, 1.0])  # a jump to 10 at the onset, then -5
    >>> args = (0.6 * zr, zr, zr, 0.3 * ar, -2 * ar, ar, [0.0, -0.01, 0.02, 0.0, 0.0])
    >>> {k: round(v, 6) for k, v in shock_ratios(*args).items()}
    {'SDR_s': 0.6, 'SAR_s': 0.6, 'SDR_u': 1.0, 'SAR_u': 4.0, 'RDR': 0.4}
    >>> {k: round(v, 6) for k, v in shock_ratios(*args, road_peak="onset").items()}
    {'SDR_s': 0.6, 'SAR_s': 0.3, 'SDR_u': 1.0, 'SAR_u': 2.0, 'RDR': 0.4}
    """
    how = check_road_peak(road_peak)
    names = ("z_s", "z_u", "z_r", "acc_s", "acc_u", "acc_r", "x_d")
    arrays = {
        k: signal(k, v)
        for k, v in zip(names, (z_s, z_u, z_r, acc_s, acc_u, acc_r, x_d), strict=True)
    }
    same_length(**arrays)
    pk = {k: float(np.max(np.abs(v))) for k, v in arrays.items() if k != "acc_r"}
    if pk["z_r"] == 0.0:
        raise ValidationError("z_r is zero over the whole record: shock ratios undefined")
    return shock_from_peaks(pk, road_acceleration_peak(arrays["acc_r"], how))


def shock_from_peaks(peaks: Mapping[str, float], road_acc: float) -> dict[str, float]:
    """The shock ratios from the record's peaks (one definition of each).

    :func:`shock_ratios` takes the peaks from time histories; the engine's in-kernel
    reduction (:mod:`mrsuspension.engine.reduced`) tracks them while stepping.

    Parameters
    ----------
    peaks : mapping
        ``max |x|`` over the record of ``z_s``, ``z_u``, ``z_r`` [m], ``acc_s``,
        ``acc_u`` [m/s^2] and ``x_d`` [m].
    road_acc : float
        The road acceleration peak (:func:`road_acceleration_peak`) [m/s^2].

    Examples
    --------
    >>> pk = {"z_s": 0.03, "z_u": 0.05, "z_r": 0.05, "acc_s": 3.0, "acc_u": 20.0, "x_d": 0.02}
    >>> {k: round(v, 6) for k, v in shock_from_peaks(pk, 10.0).items()}
    {'SDR_s': 0.6, 'SAR_s': 0.3, 'SDR_u': 1.0, 'SAR_u': 2.0, 'RDR': 0.4}
    """
    pk = peaks
    if pk["z_r"] == 0.0:
        raise ValidationError("z_r is zero over the whole record: shock ratios undefined")
    return {
        "SDR_s": pk["z_s"] / pk["z_r"],
        "SAR_s": pk["acc_s"] / road_acc,
        "SDR_u": pk["z_u"] / pk["z_r"],
        "SAR_u": pk["acc_u"] / road_acc,
        "RDR": pk["x_d"] / pk["z_r"],
    }


def dtr(
    peak_tire_force_nominal: float,
    peak_tire_force: float,
    nominal_total_mass: float,
    g: float = G,
) -> float:
    """Deviation in peak tire force ratio ``|F_T0,peak - F_T,peak| / ((m_s0 + m_u) g)``, (3.44).

    Parameters
    ----------
    peak_tire_force_nominal : float
        Peak tire force [N] of the run with the nominal sprung mass ``m_s0``.
    peak_tire_force : float
        Peak tire force [N] of the run being assessed.
    nominal_total_mass : float
        ``m_s0 + m_u`` [kg] (563 + 90 kg nominally).
    g : float, optional
        Gravitational acceleration [m/s^2], 9.81.

    Examples
    --------
    >>> round(dtr(9000.0, 8359.407, 653.0), 6)  # 640.593 N / 6405.93 N
    0.1
    """
    values = {}
    for name, value in (
        ("peak_tire_force_nominal", peak_tire_force_nominal),
        ("peak_tire_force", peak_tire_force),
    ):
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise ValidationError(f"{name} must be a number [N]; got {value!r}")
        if not np.isfinite(value):
            raise ValidationError(f"{name} must be finite [N]; got {value}")
        values[name] = float(value)
    mass = rate("nominal_total_mass", nominal_total_mass, "kg")
    gravity = rate("g", g, "m/s^2")
    return abs(values["peak_tire_force_nominal"] - values["peak_tire_force"]) / (mass * gravity)


def dtr_ratio(
    peak_tire_force_nominal: float,
    peak_tire_force: float,
    static_load_nominal: float,
    static_load: float,
) -> float:
    """DTR read as the deviation in the *peak tire force ratio*: each run's peak tire force
    over its own static load, ``|F_T0,peak / W_0 - F_T,peak / W|``.

    (3.44) prints one denominator, the nominal car's static load ``(m_s0 + m_u) g``
    (:func:`dtr`). Both readings agree between runs of one mass (speed, pulse height); over
    the sprung mass they differ. With (3.44) as printed the DTR of a 422 or 703 kg car is
    the static-load change alone (0.216: the peak *dynamic* tire force hardly changes with
    the mass); this reading gives 0.13-0.22, as Tables 5.1 and 6.1 do (0.18/0.14,
    0.16/0.13): the report's shock tables and the findings scorecard use it
    (``docs/excitations-and-measures.md``).

    Parameters
    ----------
    peak_tire_force_nominal, peak_tire_force : float
        Peak tire force [N] (total, with the static load) of the nominal run and of the
        run being assessed.
    static_load_nominal, static_load : float
        ``(m_s + m_u) g`` [N] of each run's car.

    Examples
    --------
    >>> round(dtr_ratio(12000.0, 10500.0, 6405.93, 5022.8), 4)  # 1.8733 - 2.0905
    0.2172
    >>> round(dtr_ratio(9000.0, 8359.407, 6405.93, 6405.93), 6)  # one mass: as (3.44)
    0.1
    """
    values = {}
    for name, value, unit in (
        ("peak_tire_force_nominal", peak_tire_force_nominal, "N"),
        ("peak_tire_force", peak_tire_force, "N"),
    ):
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise ValidationError(f"{name} must be a number [{unit}]; got {value!r}")
        if not np.isfinite(value):
            raise ValidationError(f"{name} must be finite [{unit}]; got {value}")
        values[name] = float(value)
    w0 = rate("static_load_nominal", static_load_nominal, "N")
    w = rate("static_load", static_load, "N")
    return abs(values["peak_tire_force_nominal"] / w0 - values["peak_tire_force"] / w)
