"""Measures of a half or full vehicle: seat vibration (ISO 2631-1), per-wheel and per-corner.

Plain functions on arrays in SI units with an explicit sampling rate ``fs`` [Hz], like the
rest of :mod:`mrsuspension.measures`; nothing here knows about the engine. Per-wheel and
per-corner functions take a mapping from corner name (e.g. ``"front_left"``) to signal
and return a dict with the same keys.

Body motion, for small angles (ISO 8855 axes; model reference, section 1: ``x`` forward,
``y`` left, ``z`` up): heave acceleration ``a_z`` [m/s^2] up, pitch acceleration
``theta''`` [rad/s^2] positive nose down, roll acceleration ``phi''`` [rad/s^2] positive
left side up (the conventions of :mod:`mrsuspension.control.modal`). A seat at ``(x, y)``
[m] from the CG and ``height`` [m] above the pitch and roll axes then has

* vertical ``a_z,seat = a_z - x theta'' + y phi''``,
* fore-aft ``a_x,seat = height theta''`` and lateral ``a_y,seat = -height phi''``
  (the tilt components of gravity that a seat accelerometer would also read are left out),
* rotational ``r_x = phi''`` (roll) and ``r_y = theta''`` (pitch); yaw is not modelled.

ISO 2631-1:1997 weights each axis with its frequency weighting (Tables 1 and 2: Wk for
``z``, Wd for ``x`` and ``y``, We for the rotations; constants Table A.2,
:mod:`mrsuspension.measures.iso2631`) and combines the weighted RMS values ``a_wj`` with
axis multiplying factors ``k_j`` into the vibration total value (clause 6.5)
``a_v = sqrt(sum k_j^2 a_wj^2)``. Factors (:data:`AXIS_FACTORS`), seated person, seat
surface: health (clause 7.2.3) ``k_x = k_y = 1.4``, ``k_z = 1`` (rotations not used);
comfort (clause 8.2.2) ``k_x = k_y = k_z = 1``, ``k_rx = 0.63``, ``k_ry = 0.4`` m/rad
(``k_rz = 0.2`` m/rad, yaw).

Examples
--------
>>> fs = 1000.0
>>> t = np.arange(0.0, 60.0, 1 / fs)
>>> heave = np.sin(2 * np.pi * 4.0 * t)
>>> sv = seat_vibration(heave, np.zeros_like(t), np.zeros_like(t), fs)
>>> round(sv.weighted_rms["z"] * math.sqrt(2), 2), round(sv.total, 4) == round(sv.weighted_rms["z"], 4)
(0.97, True)
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_finite, check_range
from mrsuspension.measures._checks import FloatArray, rate, same_length, signal
from mrsuspension.measures.iso2631 import weighted_rms
from mrsuspension.measures.steady import dlc, rms

__all__ = [
    "AXIS_FACTORS",
    "AXIS_WEIGHTINGS",
    "COIL_RESISTANCE",
    "PURPOSES",
    "SeatVibration",
    "SuspensionTravel",
    "coil_energy",
    "lift_off_time",
    "seat_acceleration",
    "seat_vibration",
    "suspension_travel",
    "wheel_coil_energy",
    "wheel_dlc",
    "wheel_lift_off_time",
    "wheel_suspension_travel",
]

#: ISO 2631-1 frequency weighting of each seat-surface axis (Tables 1 and 2)
AXIS_WEIGHTINGS: dict[str, str] = {"x": "Wd", "y": "Wd", "z": "Wk", "rx": "We", "ry": "We"}

#: axis multiplying factors k (seated, seat surface): health clause 7.2.3 (translations
#: only), comfort clause 8.2.2 (rotations in m/rad)
AXIS_FACTORS: dict[str, dict[str, float]] = {
    "health": {"x": 1.4, "y": 1.4, "z": 1.0},
    "comfort": {"x": 1.0, "y": 1.0, "z": 1.0, "rx": 0.63, "ry": 0.4},
}
#: the purposes of :func:`seat_vibration`
PURPOSES = tuple(AXIS_FACTORS)

#: Default coil resistance [ohm]: 12 V / 0.5 A = 24 ohm, the largest resistance the
#: dissertation's drive ("a direct current limited to 0.5 A at 12 V", section 2.1) can
#: serve; an upper bound, so the energy it gives is an upper bound too. Give the measured
#: resistance of your damper's coil where you know it.
COIL_RESISTANCE = 24.0


def _position(name: str, value: float) -> float:
    return float(check_finite(name, value))


def seat_acceleration(
    heave_acc: npt.ArrayLike,
    pitch_acc: npt.ArrayLike,
    roll_acc: npt.ArrayLike | None = None,
    *,
    x: float = 0.0,
    y: float = 0.0,
    height: float = 0.0,
) -> dict[str, FloatArray]:
    """Accelerations at a seat on the rigid body, per ISO 2631-1 axis (module docstring).

    Parameters
    ----------
    heave_acc : array_like
        Body heave acceleration ``a_z`` at the CG [m/s^2], up.
    pitch_acc : array_like
        Pitch acceleration ``theta''`` [rad/s^2], nose down.
    roll_acc : array_like, optional
        Roll acceleration ``phi''`` [rad/s^2], left side up (zero for a half car).
    x, y : float
        Seat position forward of and left of the CG [m].
    height : float
        Seat height above the pitch and roll axes [m] (0: no fore-aft or lateral motion).

    Returns
    -------
    dict of str to ndarray
        ``"x"``, ``"y"``, ``"z"`` [m/s^2] and ``"rx"``, ``"ry"`` [rad/s^2].

    Examples
    --------
    >>> acc = seat_acceleration([1.0], [2.0], [3.0], x=0.5, y=0.4)
    >>> acc["z"].tolist()  # 1 - 0.5 * 2 + 0.4 * 3
    [1.2]
    """
    az = signal("heave_acc", heave_acc)
    pitch = signal("pitch_acc", pitch_acc)
    roll = np.zeros_like(az) if roll_acc is None else signal("roll_acc", roll_acc)
    same_length(heave_acc=az, pitch_acc=pitch, roll_acc=roll)
    xs, ys, h = _position("x", x), _position("y", y), _position("height", height)
    return {
        "x": h * pitch,
        "y": -h * roll,
        "z": az - xs * pitch + ys * roll,
        "rx": roll.copy(),
        "ry": pitch.copy(),
    }


@dataclass(frozen=True)
class SeatVibration:
    """ISO 2631-1 seat vibration: weighted RMS per axis and the vibration total value.

    Attributes
    ----------
    weighted_rms : dict of str to float
        ``a_wj`` per axis: ``"x"``, ``"y"``, ``"z"`` [m/s^2], ``"rx"``, ``"ry"`` [rad/s^2].
    factors : dict of str to float
        The axis factors ``k_j`` used (m/rad for rotations); axes not listed do not count.
    total : float
        Vibration total value ``a_v = sqrt(sum k_j^2 a_wj^2)`` [m/s^2] (clause 6.5).
    purpose : str
        ``"comfort"`` or ``"health"``.
    """

    weighted_rms: dict[str, float]
    factors: dict[str, float]
    total: float
    purpose: str


def seat_vibration(
    heave_acc: npt.ArrayLike,
    pitch_acc: npt.ArrayLike,
    roll_acc: npt.ArrayLike | None,
    fs: float,
    *,
    x: float = 0.0,
    y: float = 0.0,
    height: float = 0.0,
    purpose: str = "comfort",
) -> SeatVibration:
    """Weighted seat vibration of a body motion record sampled at ``fs`` [Hz].

    Each axis of :func:`seat_acceleration` is weighted (:data:`AXIS_WEIGHTINGS`) with
    :func:`~mrsuspension.measures.weighted_rms` and combined with the ``purpose``'s
    factors (:data:`AXIS_FACTORS`) into the total value.

    Examples
    --------
    >>> fs = 1000.0
    >>> t = np.arange(0.0, 60.0, 1 / fs)
    >>> roll = np.sin(2 * np.pi * 1.0 * t)  # 1 rad/s^2 at 1 Hz; |We(1 Hz)| = 0.880
    >>> sv = seat_vibration(np.zeros_like(t), np.zeros_like(t), roll, fs)
    >>> round(sv.weighted_rms["rx"] * math.sqrt(2), 2), round(sv.total / sv.weighted_rms["rx"], 2)
    (0.88, 0.63)
    """
    if purpose not in AXIS_FACTORS:
        raise ValidationError(f"purpose must be one of {', '.join(PURPOSES)}; got {purpose!r}")
    fs = rate("fs", fs)
    acc = seat_acceleration(heave_acc, pitch_acc, roll_acc, x=x, y=y, height=height)
    weighted = {
        axis: (0.0 if not np.any(a) else weighted_rms(a, fs, weighting=AXIS_WEIGHTINGS[axis]))
        for axis, a in acc.items()
    }
    factors = dict(AXIS_FACTORS[purpose])
    total = math.sqrt(sum((k * weighted[axis]) ** 2 for axis, k in factors.items()))
    return SeatVibration(weighted, factors, total, purpose)


def _per_wheel(name: str, signals: Mapping[str, npt.ArrayLike]) -> Mapping[str, npt.ArrayLike]:
    if not isinstance(signals, Mapping) or not signals:
        raise ValidationError(
            f"{name} must be a mapping from corner name to signal, e.g. "
            f"{{'front_left': [...], ...}}; got {type(signals).__name__}"
        )
    return signals


def wheel_dlc(
    tire_forces: Mapping[str, npt.ArrayLike], static_loads: Mapping[str, float] | None = None
) -> dict[str, float]:
    """Dynamic load coefficient per wheel, ``std(F_T) / load`` (quarter car's :func:`dlc`).

    ``tire_forces`` [N] per corner; ``static_loads`` [N] per corner for harmonic runs, by
    default each wheel's mean force (the random-road definition, model reference, section 9).

    Examples
    --------
    >>> f = 3000.0 + 300.0 * np.sin(np.linspace(0.0, 2 * np.pi, 1000, endpoint=False))
    >>> {k: round(v, 6) for k, v in wheel_dlc({"front": f, "rear": 2 * f}).items()}
    {'front': 0.070711, 'rear': 0.070711}
    """
    forces = _per_wheel("tire_forces", tire_forces)
    if static_loads is not None:
        missing = sorted(set(forces) - set(static_loads))
        if missing:
            raise ValidationError(f"static_loads has no entry for {', '.join(missing)}")
    return {
        corner: dlc(f, None if static_loads is None else static_loads[corner])
        for corner, f in forces.items()
    }


def lift_off_time(tire_force: npt.ArrayLike, fs: float) -> float:
    """Time [s] a wheel spends off the ground: samples with ``F_T <= 0`` over ``fs`` [Hz].

    The engine's tire force is exactly 0 in lift-off (model reference, section 4).

    Examples
    --------
    >>> lift_off_time([100.0, 0.0, 0.0, 50.0, 0.0], 100.0)
    0.03
    """
    f = signal("tire_force", tire_force)
    return float(np.count_nonzero(f <= 0.0)) / rate("fs", fs)


def wheel_lift_off_time(tire_forces: Mapping[str, npt.ArrayLike], fs: float) -> dict[str, float]:
    """:func:`lift_off_time` [s] per wheel.

    Examples
    --------
    >>> wheel_lift_off_time({"front": [0.0, 1.0], "rear": [1.0, 1.0]}, 10.0)
    {'front': 0.1, 'rear': 0.0}
    """
    return {k: lift_off_time(f, fs) for k, f in _per_wheel("tire_forces", tire_forces).items()}


@dataclass(frozen=True)
class SuspensionTravel:
    """Suspension travel (stroke ``x_d``, compression positive) of one corner.

    Attributes
    ----------
    rms : float
        RMS stroke [m] about static equilibrium.
    peak_to_peak : float
        ``max(x_d) - min(x_d)`` [m], the travel used.
    """

    rms: float
    peak_to_peak: float


def suspension_travel(stroke: npt.ArrayLike) -> SuspensionTravel:
    """RMS and peak-to-peak of a suspension stroke record [m].

    Examples
    --------
    >>> suspension_travel([0.01, -0.01, 0.01, -0.01])
    SuspensionTravel(rms=0.01, peak_to_peak=0.02)
    """
    x = signal("stroke", stroke)
    return SuspensionTravel(rms=rms(x), peak_to_peak=float(np.max(x) - np.min(x)))


def wheel_suspension_travel(strokes: Mapping[str, npt.ArrayLike]) -> dict[str, SuspensionTravel]:
    """:func:`suspension_travel` per corner.

    Examples
    --------
    >>> wheel_suspension_travel({"rear": [0.0, 0.02]})["rear"].peak_to_peak
    0.02
    """
    return {k: suspension_travel(x) for k, x in _per_wheel("strokes", strokes).items()}


def coil_energy(current: npt.ArrayLike, fs: float, resistance: float = COIL_RESISTANCE) -> float:
    """Energy [J] drawn by a damper coil: ``integral R i^2 dt`` (trapezoidal) at ``fs`` [Hz].

    ``current`` [A] sampled at ``fs`` over the record (its duration is
    ``(n - 1) / fs``); ``resistance`` [ohm], by default :data:`COIL_RESISTANCE` (an
    upper bound from the dissertation's 12 V / 0.5 A drive). The coil power is ``R i^2``
    (model reference, section 9); the coil's inductance stores energy but draws none on average.

    Examples
    --------
    >>> coil_energy(np.full(1001, 0.5), 1000.0, resistance=5.0)  # 5 * 0.25 * 1 s
    1.25
    """
    i = signal("current", current)
    r = float(check_range("resistance", resistance, 0.0, None, unit="ohm"))
    dt = 1.0 / rate("fs", fs)
    p = i * i
    return r * float(np.sum(p[1:] + p[:-1]) * 0.5 * dt)


def wheel_coil_energy(
    currents: Mapping[str, npt.ArrayLike], fs: float, resistance: float = COIL_RESISTANCE
) -> dict[str, float]:
    """:func:`coil_energy` [J] per corner (one coil resistance [ohm] for all).

    Examples
    --------
    >>> wheel_coil_energy({"front": [1.0, 1.0], "rear": [0.0, 0.0]}, 1.0, resistance=2.0)
    {'front': 2.0, 'rear': 0.0}
    """
    return {k: coil_energy(i, fs, resistance) for k, i in _per_wheel("currents", currents).items()}
