"""Road inputs per wheel for the half- and full-vehicle models (issue 19, item 2).

A :class:`WheelRoads` gives the road displacement under every wheel, ``z_r[c](t)`` [m]
for each corner ``c`` of :attr:`WheelRoads.corners`, as a ``(n_corners, len(t))`` array.
Each side of the car follows a *wheel track* (a single-track :class:`Excitation` of time
for the front wheel on that side); the rear wheel on a side sees the same track delayed
by the wheelbase over the speed, exactly::

    z_rear(t) = z_front(t - L/V),   and the track's value at t = 0 (zero velocity) before

(the road has not reached the rear wheel yet: a harmonic or a pulse holds 0, a road
profile its first elevation). The constructors:

=======================================  ==============================================
:meth:`WheelRoads.from_excitation`       any single-track excitation (harmonic, pulse,
                                         road profile, preset, ISO 8608) on both sides
:meth:`WheelRoads.two_track`             a two-track random road: left and right tracks
                                         of one PSD with the isotropic coherence
                                         :func:`isotropic_coherence` between them
:meth:`WheelRoads.from_crg`              the wheel tracks of an OpenCRG file
                                         (:mod:`pyopencrg`)
:meth:`WheelRoads.bump`                  a rounded bump on one side (excites roll)
:meth:`WheelRoads.pothole`               a rounded pothole (:class:`Pothole`) on one side
:meth:`WheelRoads.in_phase`              one excitation at every wheel at once (a
                                         four-poster rig: no delay), or with given
                                         per-wheel delays
=======================================  ==============================================

Corner names and order: :data:`FULL_CAR_CORNERS` and :data:`HALF_CAR_CORNERS` (their one
home; :mod:`mrsuspension.vehicle` re-exports them as ``CORNERS_FULL`` and ``CORNERS_HALF``).
A half car rides the left wheel track.

The geometry is a pair ``(wheelbase, track)`` or a vehicle: a
:class:`~mrsuspension.vehicle.HalfCar` (no track; its corners are taken) or a
:class:`~mrsuspension.vehicle.FullCar`, whose ``track`` is its front track: the rear
wheels follow the front wheels' tracks, so with ``rear_track != front_track`` they get
the road at the front track's lateral spacing (the body still uses each axle's track).

Examples
--------
>>> from mrsuspension.excitation import preset_road
>>> roads = WheelRoads.from_excitation(preset_road("rough"), (2.7, 1.5), speed_kmh=54.0)
>>> roads.corners
('front_left', 'front_right', 'rear_left', 'rear_right')
>>> roads.rear_delay  # 2.7 m at 15 m/s
0.18
>>> roads.displacement([0.5, 1.0]).shape
(4, 2)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, is_dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_input_file, check_range, unknown_name
from mrsuspension.excitation.base import (
    Excitation,
    FloatArray,
    Option,
    grid_args,
    non_negative,
    number,
    positive,
    time_array,
)
from mrsuspension.excitation.deterministic import (
    PULSE_SETTLING_TIME,
    REFERENCE_SPEED_KMH,
    RoundedPulse,
)
from mrsuspension.excitation.road import (
    ISO8608_BAND,
    ISO8608_CLASSES,
    PRESET_LENGTH,
    PRESET_ROADS,
    RoadBandWarning,
    RoadProfile,
    RoadSpectrum,
    synthesise_road,
)

__all__ = [
    "CORNER_LAYOUTS",
    "FULL_CAR_CORNERS",
    "HALF_CAR_CORNERS",
    "SIDES",
    "Pothole",
    "WheelRoads",
    "isotropic_coherence",
]

#: Corners of a full car, in the order of :meth:`WheelRoads.displacement`'s rows.
FULL_CAR_CORNERS: tuple[str, ...] = ("front_left", "front_right", "rear_left", "rear_right")
#: Corners of a half car (heave and pitch; it rides the left wheel track).
HALF_CAR_CORNERS: tuple[str, ...] = ("front", "rear")
#: The corner layouts by vehicle model name (``[vehicle] model`` in issue 19).
CORNER_LAYOUTS: dict[str, tuple[str, ...]] = {
    "full-car": FULL_CAR_CORNERS,
    "half-car": HALF_CAR_CORNERS,
}
#: The sides a one-sided event can be on.
SIDES: tuple[str, ...] = ("left", "right", "both")

#: the stream (with the seed) of the two-track road's random phase-shift signs
_SIGN_STREAM = 8608
#: (side, on the rear axle) of each corner
_CORNER_PLACES: dict[str, tuple[str, bool]] = {
    "front_left": ("left", False),
    "front_right": ("right", False),
    "rear_left": ("left", True),
    "rear_right": ("right", True),
    "front": ("left", False),
    "rear": ("left", True),
}
_MAX_SPEED_KMH = 500.0  # as the single-track excitations
_MAX_WHEELBASE = 100.0  # m; far beyond any road vehicle
_MAX_TRACK = 10.0  # m
#: default rounding length [m] of a pothole's edges: of the order of a passenger-car
#: tyre's contact-patch length, over which a tyre smooths a sharp edge (modelling choice)
POTHOLE_EDGE = 0.1


# -- arguments ------------------------------------------------------------------------------
def _speed(speed_kmh: object) -> float:
    return positive("speed_kmh", speed_kmh, "km/h", high=_MAX_SPEED_KMH)


def _corners(corners: object) -> tuple[str, ...]:
    """A corner layout: ``"full-car"``, ``"half-car"`` or one of their tuples of names."""
    if isinstance(corners, str):
        if corners not in CORNER_LAYOUTS:
            raise unknown_name("corner layout", corners, CORNER_LAYOUTS)
        return CORNER_LAYOUTS[corners]
    if not isinstance(corners, tuple | list) or not corners:
        raise ValidationError(
            f"corners must be 'full-car', 'half-car' or a tuple of corner names; got {corners!r}"
        )
    for name in corners:
        if not isinstance(name, str) or name not in _CORNER_PLACES:
            raise unknown_name("corner", str(name), _CORNER_PLACES)
    names = tuple(corners)
    for layout in CORNER_LAYOUTS.values():
        if names == layout:
            return layout
    raise ValidationError(
        f"corners must be {FULL_CAR_CORNERS} (full car) or {HALF_CAR_CORNERS} (half car), "
        f"in that order; got {names}"
    )


def _layout_of(corners: object, geometry: object) -> object:
    """``corners`` as given, else the geometry object's own corners, else the full car."""
    if corners is not None:
        return corners
    own = getattr(geometry, "corners", None)
    if isinstance(own, tuple) and own in CORNER_LAYOUTS.values():
        return own
    return "full-car"


def _geometry(geometry: object, corners: tuple[str, ...]) -> tuple[float, float | None]:
    """``(wheelbase, track)`` [m] from a pair or an object with those attributes.

    A half car needs no track (None or missing is allowed; a given one is checked).
    """
    if isinstance(geometry, tuple | list):
        if len(geometry) != 2:
            raise ValidationError(
                f"geometry must be a pair (wheelbase, track) [m]; got {geometry!r}"
            )
        wheelbase, track = geometry
    elif hasattr(geometry, "wheelbase"):
        wheelbase, track = geometry.wheelbase, getattr(geometry, "track", None)
    else:
        raise ValidationError(
            "geometry must be a pair (wheelbase, track) [m] or an object with 'wheelbase' and "
            f"'track' attributes; got {geometry!r}"
        )
    wb = positive("wheelbase", wheelbase, "m", high=_MAX_WHEELBASE)
    if track is None:
        if corners == FULL_CAR_CORNERS:
            raise ValidationError(
                "a full car needs a track (distance between left and right wheels) [m]"
            )
        return wb, None
    return wb, positive("track", track, "m", high=_MAX_TRACK)


def _delays(delays: object, corners: tuple[str, ...]) -> tuple[float, ...]:
    """One delay [s] per corner, each in [0, 1e4]."""
    if isinstance(delays, str) or not isinstance(delays, tuple | list | np.ndarray):
        raise ValidationError(
            f"delays must be a sequence of {len(corners)} delays [s], one per corner "
            f"{corners}; got {delays!r}"
        )
    values = check_range("delays", delays, 0.0, 1e4, unit="s")
    if values.shape != (len(corners),):
        raise ValidationError(
            f"delays must have one value per corner {corners} ({len(corners)}); "
            f"got {[float(v) for v in np.ravel(values)]}"
        )
    return tuple(float(v) for v in values)


def _side(side: object, corners: tuple[str, ...]) -> str:
    if not isinstance(side, str) or side not in SIDES:
        raise unknown_name("side", str(side), SIDES)
    if corners == HALF_CAR_CORNERS and side == "right":
        raise ValidationError(
            "side 'right' leaves a half car unexcited: a half car rides the left wheel track; "
            "use side 'left' or 'both'"
        )
    return side


# -- the coherence model -----------------------------------------------------------------------
def isotropic_coherence(
    spatial_frequency: npt.ArrayLike, track: float, waviness: float = 2.0
) -> FloatArray:
    """Coherency ``gamma(n)`` of two parallel tracks ``track`` apart on an isotropic road.

    For a homogeneous, isotropic random surface whose single-track PSD is the power law
    ``Gd(n) ~ n^-w``, the cross-spectral density of two parallel tracks a distance ``b``
    apart is real and ``G_lr(n) = gamma(n) Gd(n)`` with (Kamash and Robson, 1978; the
    isotropy hypothesis of Dodds and Robson, 1973)::

        gamma(n) = 2 (x/2)^nu K_nu(x) / Gamma(nu),   x = 2 pi n b,   nu = w/2,

    ``K_nu`` the modified Bessel function of the second kind. ISO 8608's ``w = 2`` gives
    ``gamma = x K_1(x)``; the presets' ``w = 1`` give ``gamma = exp(-x)``. ``gamma`` falls
    from 1 at long wavelengths to 0 at wavelengths short against ``b``. The
    magnitude-squared coherence that :func:`scipy.signal.coherence` estimates is
    ``gamma^2``.

    (Derivation: the isotropic 2-D spectrum ``S(k) ~ k^-(w+1)`` integrated across the road
    gives ``Gd``, and weighted by ``cos(k_y b)`` gives ``G_lr``; their ratio is the
    closed form above.)

    Parameters
    ----------
    spatial_frequency : array_like
        Spatial frequency ``n`` >= 0 [cycle/m].
    track : float
        Distance ``b`` between the two tracks [m], > 0.
    waviness : float, optional
        Exponent ``w`` of the PSD, in (0, 5]; 2 (ISO 8608) by default.

    Returns
    -------
    ndarray
        ``gamma(n)`` in [0, 1], the shape of ``spatial_frequency``.

    References
    ----------
    K. M. A. Kamash and J. D. Robson, "The application of isotropy in road surface
    modelling", Journal of Sound and Vibration 57(1), 89-100, 1978.
    C. J. Dodds and J. D. Robson, "The description of road surface roughness", Journal of
    Sound and Vibration 31, 1973.

    Examples
    --------
    >>> isotropic_coherence([0.0, 0.1, 1.0], track=1.5).round(4).tolist()  # x K1(x)
    [1.0, 0.6264, 0.0003]
    >>> bool(np.isclose(isotropic_coherence(0.1, 1.5, waviness=1.0), np.exp(-0.3 * np.pi)))
    True
    """
    from scipy.special import gamma as gamma_function
    from scipy.special import kv

    n = check_range("spatial_frequency", spatial_frequency, 0.0, None, unit="cycle/m")
    b = positive("track", track, "m", high=_MAX_TRACK)
    w = positive("waviness", waviness, "", high=5.0)
    nu = 0.5 * w
    x = 2.0 * math.pi * n * b
    with np.errstate(invalid="ignore", over="ignore"):
        value = 2.0 * (0.5 * x) ** nu * kv(nu, x) / gamma_function(nu)
    value = np.where(x == 0.0, 1.0, np.nan_to_num(value, nan=0.0, posinf=1.0))
    return np.asarray(np.clip(value, 0.0, 1.0), dtype=float)


# -- a rounded pothole -----------------------------------------------------------------------
def _smoothstep(u: FloatArray, order: int) -> FloatArray:
    """The C2 ramp ``S(u) = 6u^5 - 15u^4 + 10u^3`` on [0, 1] (clamped) or its derivatives."""
    inside = (u > 0.0) & (u < 1.0)
    uc = np.clip(u, 0.0, 1.0)
    if order == 0:
        return np.asarray(uc**3 * (10.0 - 15.0 * uc + 6.0 * uc * uc), dtype=float)
    if order == 1:
        return np.where(inside, 30.0 * uc * uc * (1.0 - uc) ** 2, 0.0)
    return np.where(inside, 60.0 * uc * (1.0 - uc) * (1.0 - 2.0 * uc), 0.0)


@dataclass(frozen=True)
class Pothole(Excitation):
    """A pothole on one wheel track: a flat-bottomed dip with rounded (C2) edges.

    Over distance ``x = V t`` [m] the road is::

        h(x) = -depth [S((x - p)/e) - S((x - p - length + e)/e)]

    with ``S(u) = 6u^5 - 15u^4 + 10u^3`` clamped to [0, 1]: the wheel drops by ``depth``
    over the edge length ``e`` at the pothole's start ``p``, runs along the bottom and
    climbs out over ``e`` at ``p + length``. Sharp for the suspension, yet twice
    continuously differentiable, so a fixed-step RK4 sees a continuous road acceleration.

    Parameters
    ----------
    depth : float
        Depth [m], in (0, 1].
    length : float
        Length along the road [m], at least ``2 edge``, at most 1000.
    position : float, optional
        Distance [m] the wheel travels before the pothole starts (>= 0), 5 m by default.
    speed_kmh : float, optional
        Vehicle speed [km/h], 50 by default.
    edge : float, optional
        Rounding length of each edge [m], 0.1 m by default (:data:`POTHOLE_EDGE`).

    Examples
    --------
    >>> hole = Pothole(depth=0.04, length=0.6, position=1.0, speed_kmh=36.0)  # 10 m/s
    >>> float(hole.displacement(0.13))  # on the bottom, 1.3 m along
    -0.04
    >>> float(hole.displacement(0.05)), float(hole.velocity(0.05))  # before it
    (0.0, 0.0)
    >>> round(hole.duration, 2)  # until it is passed, plus 2 s of settling
    2.16
    """

    depth: float
    length: float
    position: float = 5.0
    speed_kmh: float = REFERENCE_SPEED_KMH
    edge: float = POTHOLE_EDGE

    name: ClassVar[str] = "pothole"
    measures_kind: ClassVar[str] = "pulse"
    options: ClassVar[tuple[Option, ...]] = (
        Option("depth", "number", "m", "pothole depth [m] (required)",
               required=True, low=0.0, high=1.0, low_inclusive=False),
        Option("length", "number", "m", "pothole length [m] (required)",
               required=True, low=0.0, high=1e3, low_inclusive=False),
        Option("position", "number", "m", "distance before the pothole [m], 5 by default",
               low=0.0, high=1e6),
        Option("speed", "number", "km/h", "vehicle speed [km/h], 50 by default",
               low=0.0, high=_MAX_SPEED_KMH, low_inclusive=False, keyword="speed_kmh"),
        Option("edge", "number", "m", "rounding length of each edge [m], 0.1 by default",
               low=0.0, high=1e3, low_inclusive=False),
    )  # fmt: skip
    example_options: ClassVar[dict[str, Any]] = {"depth": 0.04, "length": 0.6}

    def __post_init__(self) -> None:
        object.__setattr__(self, "depth", positive("depth", self.depth, "m", high=1.0))
        edge = positive("edge", self.edge, "m", high=500.0)
        object.__setattr__(self, "edge", edge)
        length = number("length", self.length)
        check_range("length", length, 2.0 * edge, 1e3, unit="m")
        object.__setattr__(self, "length", length)
        object.__setattr__(self, "position", non_negative("position", self.position, "m", high=1e6))
        object.__setattr__(self, "speed_kmh", _speed(self.speed_kmh))

    @property
    def speed(self) -> float:
        """Vehicle speed ``V`` [m/s]."""
        return self.speed_kmh / 3.6

    def _derivative(self, t: npt.ArrayLike, order: int) -> FloatArray:
        x = self.speed * time_array(t)
        e = self.edge
        u_in = (x - self.position) / e
        u_out = (x - self.position - self.length + e) / e
        slope = (self.speed / e) ** order
        return np.asarray(
            -self.depth * slope * (_smoothstep(u_in, order) - _smoothstep(u_out, order)),
            dtype=float,
        )

    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """``z_r = h(V t)`` [m]."""
        return self._derivative(t, 0)

    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """``dz_r/dt = V h'(V t)`` [m/s]."""
        return self._derivative(t, 1)

    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """``d2z_r/dt2 = V^2 h''(V t)`` [m/s^2]."""
        return self._derivative(t, 2)

    @property
    def duration(self) -> float:
        """Time to pass the pothole plus 2 s of settling [s]."""
        return (self.position + self.length) / self.speed + PULSE_SETTLING_TIME

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, depth, length, position, edge [m], speed [km/h], duration [s]."""
        return {
            "kind": self.name,
            "depth": self.depth,
            "length": self.length,
            "position": self.position,
            "edge": self.edge,
            "speed_kmh": self.speed_kmh,
            "duration": self.duration,
        }


# -- the road under every wheel ---------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class WheelRoads:
    """The road displacement under every wheel of a half or full car.

    Build it with one of the constructors (:meth:`from_excitation`, :meth:`two_track`,
    :meth:`from_crg`, :meth:`bump`, :meth:`pothole`, :meth:`in_phase`) rather than
    directly.

    Parameters
    ----------
    left, right : Excitation or None
        The wheel tracks: the road under the front wheel on each side as a function of
        time. None is a flat track (exactly zero). A half car uses ``left`` only.
    wheelbase : float, optional
        Distance between the axles ``L`` [m], > 0. Required unless ``delays`` is given.
    speed_kmh : float, optional
        Vehicle speed ``V`` [km/h]; the rear wheels see their track ``L/V`` later.
        Required unless ``delays`` is given, and then not allowed (no vehicle speed).
    track : float, optional
        Distance between the left and right wheels [m] (None for a half car, or with
        ``delays``).
    corners : str or tuple of str, optional
        ``"full-car"`` (:data:`FULL_CAR_CORNERS`, the default) or ``"half-car"``
        (:data:`HALF_CAR_CORNERS`), or the tuple itself.
    source : str, optional
        What the road is (shown in :meth:`describe`).
    details : dict, optional
        Plain data about how it was built (shown in :meth:`describe`).
    delays : sequence of float, optional
        Delay ``d_c`` of every corner [s], >= 0, one per corner in the order of
        ``corners``, instead of the geometry's ``0`` (front) and ``L/V`` (rear): a rig's
        actuators rather than a car driving along the road (:meth:`in_phase`).

    Notes
    -----
    Corner ``c`` on side ``s`` sees ``z_r[c](t) = z_s(t - d_c)`` with ``d_c = 0`` on the
    front axle and ``L/V`` on the rear (or the given ``delays``), for ``t >= d_c``, and
    ``z_s(0)`` with zero velocity before. Velocity and acceleration are the track's exact
    derivatives, shifted the same way.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> roads = WheelRoads(Harmonic(1.0, 0.01), None, wheelbase=2.5, speed_kmh=36.0, track=1.5)
    >>> roads.displacement([0.25, 0.5]).round(6)  # rear: 0.25 s later; right: flat
    array([[0.01, 0.  ],
           [0.  , 0.  ],
           [0.  , 0.01],
           [0.  , 0.  ]])
    """

    left: Excitation | None
    right: Excitation | None
    wheelbase: float | None = None
    speed_kmh: float | None = None
    track: float | None = None
    corners: tuple[str, ...] = FULL_CAR_CORNERS
    source: str = "user tracks"
    details: Mapping[str, Any] = field(default_factory=dict)
    delays: tuple[float, ...] | None = None
    #: (track, delay [s]) of every corner
    _places: tuple[tuple[Excitation | None, float], ...] = field(
        init=False, repr=False, compare=False
    )

    def __post_init__(self) -> None:
        corners = _corners(self.corners)
        object.__setattr__(self, "corners", corners)
        if self.delays is None:
            if self.wheelbase is None or self.speed_kmh is None:
                raise ValidationError(
                    "wheelbase [m] and speed_kmh [km/h] are needed (the rear wheels see the "
                    "road wheelbase/speed later), or delays [s] per corner; got wheelbase="
                    f"{self.wheelbase!r}, speed_kmh={self.speed_kmh!r}"
                )
            wheelbase_m, track = _geometry((self.wheelbase, self.track), corners)
            speed = _speed(self.speed_kmh)
            object.__setattr__(self, "speed_kmh", speed)
            wheelbase: float | None = wheelbase_m
            rear = wheelbase_m / (speed / 3.6)  # as rear_delay was, to the bit
        else:
            object.__setattr__(self, "delays", _delays(self.delays, corners))
            if self.speed_kmh is not None:
                raise ValidationError(
                    "give either speed_kmh (the rear wheels trail by wheelbase/speed) or "
                    f"delays per corner, not both; got speed_kmh={self.speed_kmh!r} and "
                    f"delays={list(self.delays)}"
                )
            # the geometry, if given, is recorded (describe) but sets no delay
            wheelbase, track = self.wheelbase, self.track
            if wheelbase is not None:
                wheelbase = positive("wheelbase", wheelbase, "m", high=_MAX_WHEELBASE)
            if track is not None:
                track = positive("track", track, "m", high=_MAX_TRACK)
        object.__setattr__(self, "wheelbase", wheelbase)
        object.__setattr__(self, "track", track)
        for side in ("left", "right"):
            value = getattr(self, side)
            if value is not None and not isinstance(value, Excitation):
                raise ValidationError(
                    f"{side} track must be an Excitation (e.g. a RoadProfile) or None; "
                    f"got {value!r}"
                )
        if not isinstance(self.source, str):
            raise ValidationError(f"source must be a string; got {self.source!r}")
        object.__setattr__(self, "details", dict(self.details))
        places = []
        for row, corner in enumerate(corners):
            side, on_rear = _CORNER_PLACES[corner]
            given = self.delays
            delay = (rear if on_rear else 0.0) if given is None else given[row]
            places.append((getattr(self, side), delay))
        object.__setattr__(self, "_places", tuple(places))

    # -- constructors ------------------------------------------------------------------
    @classmethod
    def from_excitation(
        cls,
        excitation: Excitation,
        geometry: object,
        speed_kmh: float | None = None,
        *,
        corners: str | tuple[str, ...] | None = None,
    ) -> WheelRoads:
        """The same single-track excitation under the left and right wheels, rear delayed.

        Parameters
        ----------
        excitation : Excitation
            A :class:`~mrsuspension.excitation.Harmonic`,
            :class:`~mrsuspension.excitation.RoundedPulse`,
            :class:`~mrsuspension.excitation.RoadProfile` (a CSV file,
            :func:`~mrsuspension.excitation.preset_road`,
            :func:`~mrsuspension.excitation.iso8608`), ...: the road under the front
            wheels.
        geometry : (float, float) or object
            ``(wheelbase, track)`` [m], or an object with ``wheelbase`` and ``track``
            attributes (a half car needs no track: ``(wheelbase, None)``).
        speed_kmh : float, optional
            Vehicle speed [km/h]. By default the excitation's own ``speed_kmh`` (a road,
            a pulse); required for excitations without one (a harmonic). An excitation
            with a ``speed_kmh`` field is driven at this speed (``dataclasses.replace``):
            a road profile keeps its shape over distance.
        corners : str or tuple of str, optional
            ``"full-car"`` or ``"half-car"``; by default the geometry object's own
            ``corners`` (a :class:`~mrsuspension.vehicle.HalfCar` gives ``"half-car"``),
            else ``"full-car"``.

        Raises
        ------
        ValidationError
            Not an excitation, missing or invalid speed, wheelbase or track.

        Examples
        --------
        >>> from mrsuspension.excitation import RoundedPulse
        >>> bump = RoundedPulse(amplitude=0.05, severity=2.0, speed_kmh=72.0)
        >>> roads = WheelRoads.from_excitation(bump, (2.6, None), corners="half-car")
        >>> roads.corners, roads.rear_delay  # 2.6 m at 20 m/s
        (('front', 'rear'), 0.13)
        >>> z = roads.displacement([bump.peak_time, bump.peak_time + 0.13]).round(9)
        >>> z.tolist()  # rows: front, rear; the front's peak reaches the rear 0.13 s later
        [[0.05, 0.008844157], [0.0, 0.05]]
        """
        if not isinstance(excitation, Excitation):
            raise ValidationError(
                "excitation must be a single-track Excitation (harmonic, pulse, road); "
                f"got {excitation!r}"
            )
        layout = _corners(_layout_of(corners, geometry))
        wheelbase, track = _geometry(geometry, layout)
        own = getattr(excitation, "speed_kmh", None)
        if speed_kmh is None:
            if own is None:
                raise ValidationError(
                    f"speed_kmh is needed for a {type(excitation).__name__} excitation, which "
                    "has no speed of its own: the rear wheels are delayed by wheelbase/speed"
                )
            speed = _speed(own)
        else:
            speed = _speed(speed_kmh)
            if own is not None and own != speed:
                if not is_dataclass(excitation):
                    raise ValidationError(
                        f"cannot drive a {type(excitation).__name__} at another speed; give "
                        f"speed_kmh={own!r} (its own) or build it for {speed:g} km/h"
                    )
                excitation = replace(excitation, speed_kmh=speed)
        return cls(
            excitation,
            excitation if layout == FULL_CAR_CORNERS else None,
            wheelbase,
            speed,
            track,
            layout,
            source=f"{excitation.name} on both tracks",
            details={"excitation": excitation.describe(), "single_track": True},
        )

    @classmethod
    def two_track(
        cls,
        road: str | RoadSpectrum,
        geometry: object,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        length: float = PRESET_LENGTH,
        spacing: float | None = None,
        seed: int | None = None,
        corners: str | tuple[str, ...] | None = None,
        fade_in: float = 0.0,
    ) -> WheelRoads:
        """A two-track random road: left and right tracks with isotropic coherence.

        Both tracks have the PSD ``Gd(n)`` of ``road``; their coherency is
        :func:`isotropic_coherence` ``gamma(n)`` for the track width ``b`` (Kamash and
        Robson, 1978). The left track ``L`` is
        :func:`~mrsuspension.excitation.synthesise_road` of the spectrum with ``seed``
        (the very profile of the single-track road of that seed: a sum of cosines with
        random phases). The right track is the same sum with every Fourier line ``n_k``
        shifted in phase by ``+-arccos gamma(n_k)``, the sign drawn at random (from
        ``seed``) for each line::

            R(n_k) = L(n_k) exp(+-i arccos gamma(n_k))

        So each line of ``R`` has exactly the amplitude of ``L`` (the periodogram of both
        tracks is ``Gd(n_k)`` for every seed, as for a single track), and the expected
        cross-spectrum is ``E[R L*] = Gd cos(arccos gamma) = gamma Gd``: the model's.
        (Mixing ``L`` with an independent track, ``gamma L + sqrt(1 - gamma^2) I``, has
        the same expected spectra but random line amplitudes: a 500 m right track then
        misses ISO 8608's level by up to 40 % in an octave band, and on 40 km the measured
        coherence strays up to 0.02-0.05 from the model against 0.012-0.021 here.) Both
        profiles are periodic over their length; a half car rides the left track.

        Parameters
        ----------
        road : str or RoadSpectrum
            An ISO 8608 class ``"A"``-``"H"`` (``Gd(n0)`` of the class, ``n^-2``,
            0.011-2.83 cycle/m), a preset name (``"smooth"``, ``"medium-rough"``,
            ``"rough"``: ``n^-1``, 0.011-2 cycle/m) or any
            :class:`~mrsuspension.excitation.RoadSpectrum` (waviness > 0).
        geometry : (float, float) or object
            ``(wheelbase, track)`` [m] (see :meth:`from_excitation`).
        speed_kmh : float, optional
            Vehicle speed [km/h], 50 by default.
        length, spacing : float, optional
            Profile length and point spacing [m]: 500 m; the preset's 0.3 m, or for a
            class or a spectrum the spacing that holds the whole band
            (:func:`~mrsuspension.excitation.band_spacing`: 0.05 m for ISO 8608's).
        seed : int, optional
            Seed of the random phases, >= 0; 0 for a class or a spectrum, the preset's
            own seed for a preset.
        corners : str or tuple of str, optional
            ``"full-car"`` or ``"half-car"``; by default the geometry object's own
            ``corners`` (a :class:`~mrsuspension.vehicle.HalfCar` gives ``"half-car"``),
            else ``"full-car"``.
        fade_in : float, optional
            Fade-in length [m] of both tracks (see
            :class:`~mrsuspension.excitation.RoadProfile`).

        Examples
        --------
        >>> from mrsuspension.excitation import iso8608
        >>> roads = WheelRoads.two_track("C", (2.7, 1.5), speed_kmh=72.0, seed=3)
        >>> left, right = roads.left, roads.right
        >>> bool(np.array_equal(left.elevation, iso8608("C", seed=3).elevation))
        True
        >>> round(float(np.corrcoef(left.elevation, right.elevation)[0, 1]), 2)
        0.86
        >>> roads.details["coherence"]["model"]
        'isotropic (Kamash and Robson 1978)'
        """
        layout = _corners(_layout_of(corners, geometry))
        wheelbase, track = _geometry(geometry, layout)
        speed = _speed(speed_kmh)
        spectrum, default_seed, label = _two_track_spectrum(road)
        preset = isinstance(road, str) and road in PRESET_ROADS
        if spacing is None and preset:
            spacing = PRESET_ROADS[str(road)].spacing  # the preset's definition
        if seed is None:
            seed = default_seed
        if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0:
            raise ValidationError(f"seed must be an integer >= 0; got {seed!r}")
        seed = int(seed)
        with warnings.catch_warnings():
            if preset:  # 0.3 m is the preset's definition (it holds up to 1.67 cycle/m)
                warnings.simplefilter("ignore", RoadBandWarning)
            left = synthesise_road(
                spectrum,
                length,
                spacing,
                seed,
                speed,
                fade_in=fade_in,
                source=f"{label}, left track, seed {seed}",
            )
        details: dict[str, Any] = {
            "road": label,
            "seed": seed,
            "spectrum": None if left.spectrum is None else left.spectrum.describe(),
        }
        if layout == HALF_CAR_CORNERS or track is None:
            return cls(left, None, wheelbase, speed, track, layout, f"{label} (one track)", details)
        points = left.elevation.size
        dx = float(left.distance[1] - left.distance[0])
        n = np.arange(points // 2 + 1) / (points * dx)
        gamma = isotropic_coherence(n, track, spectrum.waviness)
        rng = np.random.default_rng(np.random.SeedSequence([seed, _SIGN_STREAM]))
        sign = np.where(rng.random(n.size) < 0.5, -1.0, 1.0)
        shifted = np.fft.rfft(left.elevation) * np.exp(1j * sign * np.arccos(gamma))
        right = RoadProfile(
            left.distance,
            np.asarray(np.fft.irfft(shifted, n=points), dtype=float),
            speed,
            fade_in=fade_in,
            source=f"{label}, right track, seed {seed}, isotropic coherence over {track:g} m",
            spectrum=left.spectrum,
        )
        details.update(
            coherence={
                "model": "isotropic (Kamash and Robson 1978)",
                "method": "right = left phase-shifted by +-arccos(gamma) per Fourier line",
                "formula": "gamma(n) = 2 (x/2)^nu K_nu(x) / Gamma(nu), x = 2 pi n b, nu = w/2",
                "track": track,
                "waviness": spectrum.waviness,
            },
        )
        return cls(left, right, wheelbase, speed, track, layout, f"{label} (two tracks)", details)

    @classmethod
    def from_crg(
        cls,
        path: str | Path,
        geometry: object,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        lateral_offset: float = 0.0,
        absolute: bool = True,
        corners: str | tuple[str, ...] | None = None,
        fade_in: float = 0.0,
    ) -> WheelRoads:
        """The left and right wheel tracks of an OpenCRG road file.

        The vehicle drives along the file's reference line at constant speed, its centre
        ``lateral_offset`` to the left of the line; the left and right wheels follow the
        long sections at ``v = lateral_offset +- track/2`` (OpenCRG's ``v`` is positive to
        the left). Each track is sampled at the file's cross sections (every ``u_inc``)
        with :meth:`pyopencrg.CrgRoad.uv_to_z` and interpolated like any
        :class:`~mrsuspension.excitation.RoadProfile` (a C2 spline over the distance
        ``u``). On a curved reference line the offset tracks are sampled at the same
        ``u`` (the difference in their path lengths is neglected). A half car rides the
        left wheel track (``v = lateral_offset + track/2``, or ``lateral_offset`` without
        a track).

        Parameters
        ----------
        path : str or Path
            The ``.crg`` file (KRBI, KDBI, LRFI or LDFI).
        geometry : (float, float) or object
            ``(wheelbase, track)`` [m] (see :meth:`from_excitation`).
        speed_kmh : float, optional
            Vehicle speed [km/h], 50 by default.
        lateral_offset : float, optional
            Lateral position [m] of the vehicle's centre, positive to the left, 0.
        absolute : bool, optional
            True (default): the surface height the wheel touches (grid plus the reference
            line's elevation and banking); False: the grid alone, relative to the
            reference line (no grade).
        corners : str or tuple of str, optional
            ``"full-car"`` or ``"half-car"``; by default the geometry object's own
            ``corners`` (a :class:`~mrsuspension.vehicle.HalfCar` gives ``"half-car"``),
            else ``"full-car"``.
        fade_in : float, optional
            Fade-in length [m] of both tracks.

        Raises
        ------
        ValidationError
            Missing file, a folder, an unreadable or malformed file (pyopencrg's reason),
            wheel tracks outside the road's width, or a NaN on a wheel track (the message
            gives its ``u`` and ``v``).

        Examples
        --------
        >>> import tempfile, os, pyopencrg
        >>> u = np.arange(0.0, 50.0, 0.05)
        >>> v = np.linspace(-1.5, 1.5, 31)
        >>> z = 0.01 * np.sin(0.5 * u)[:, None] * (1.0 + v[None, :] / 1.5)  # rises to the left
        >>> with tempfile.TemporaryDirectory() as d:
        ...     path = os.path.join(d, "road.crg")
        ...     pyopencrg.CrgRoad(z, u_inc=0.05, v=v).save(path, fmt="KDBI")
        ...     roads = WheelRoads.from_crg(path, (2.7, 1.5), speed_kmh=36.0)
        >>> roads.left.elevation[:3].round(6)  # u = 0, 0.05, 0.1 m at v = +0.75 m
        array([0.      , 0.000375, 0.00075 ])
        >>> float(abs(roads.right.elevation).max()) < 0.01 * 0.5 + 1e-12
        True
        """
        layout = _corners(_layout_of(corners, geometry))
        wheelbase, track = _geometry(geometry, layout)
        speed = _speed(speed_kmh)
        offset = number("lateral_offset", lateral_offset)
        check_range("lateral_offset", offset, -100.0, 100.0, unit="m")
        if not isinstance(absolute, bool):
            raise ValidationError(f"absolute must be True or False; got {absolute!r}")
        crg = _read_crg(path)
        name = Path(path).name
        half = 0.0 if track is None else 0.5 * track
        sides = {"left": offset + half}
        if layout == FULL_CAR_CORNERS:
            sides["right"] = offset - half
        u = np.asarray(crg.u, dtype=float)
        v_min, v_max = float(crg.v_min), float(crg.v_max)
        profiles: dict[str, RoadProfile] = {}
        for side, v in sides.items():
            if not v_min <= v <= v_max:
                raise ValidationError(
                    f"CRG file {name!r}: the {side} wheel track at v = {v:g} m lies outside the "
                    f"road, which spans v = {v_min:g} to {v_max:g} m (check track and "
                    "lateral_offset)"
                )
            z = np.asarray(crg.uv_to_z(u, np.full(u.size, v), grid_only=not absolute), dtype=float)
            bad = np.flatnonzero(~np.isfinite(z))
            if bad.size:
                i = int(bad[0])
                raise ValidationError(
                    f"CRG file {name!r}: the elevation grid has no value (NaN) on the {side} "
                    f"wheel track at u = {u[i]:g} m, v = {v:g} m (first of {bad.size}); fill the "
                    "holes (e.g. pyopencrg's fill_holes) or move the tracks (lateral_offset)"
                )
            profiles[side] = RoadProfile(
                u,
                z,
                speed,
                fade_in=fade_in,
                source=f"OpenCRG {name}, {side} wheel track v = {v:g} m",
            )
        return cls(
            profiles["left"],
            profiles.get("right"),
            wheelbase,
            speed,
            track,
            layout,
            source=f"OpenCRG {name}",
            details={
                "file": str(path),
                "lateral_offset": offset,
                "absolute": absolute,
                "v": sides,
                "u_range": [float(u[0]), float(u[-1])],
                "u_inc": float(crg.u_inc),
            },
        )

    @classmethod
    def bump(
        cls,
        side: str,
        height: float,
        length: float,
        geometry: object,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        position: float = 5.0,
        corners: str | tuple[str, ...] | None = None,
    ) -> WheelRoads:
        """A rounded bump under the wheels of one side (it excites roll); the other side flat.

        The bump is the :class:`~mrsuspension.excitation.RoundedPulse` shape (3.38) with
        severity 1 and ``w0 = 3 pi V / length``, so that its nominal duration
        ``3 pi/w0`` covers ``length`` metres; it starts when the front wheel has travelled
        ``position`` metres (``delay = position / V``). The rear wheel on that side meets
        it ``L/V`` later; the other side's wheels see exactly zero.

        Parameters
        ----------
        side : {"left", "right", "both"}
            Side of the car that drives over it (a half car rides the left side).
        height : float
            Bump height [m], nonzero in [-1, 1] (negative: a dip of that shape).
        length : float
            Bump length along the road [m] (the pulse's nominal duration times ``V``).
        geometry : (float, float) or object
            ``(wheelbase, track)`` [m].
        speed_kmh : float, optional
            Vehicle speed [km/h], 50 by default.
        position : float, optional
            Distance [m] to the bump's start, 5 m by default.
        corners : str or tuple of str, optional
            ``"full-car"`` or ``"half-car"``; by default the geometry object's own
            ``corners`` (a :class:`~mrsuspension.vehicle.HalfCar` gives ``"half-car"``),
            else ``"full-car"``.

        Examples
        --------
        >>> roads = WheelRoads.bump("left", 0.05, 0.5, (2.5, 1.5), speed_kmh=36.0, position=2.0)
        >>> roads.left.omega == 3 * np.pi * 10.0 / 0.5, roads.left.delay
        (True, 0.2)
        >>> z = roads.displacement(np.linspace(0.0, 2.0, 2001))
        >>> z.max(axis=1).round(4)  # front_left, front_right, rear_left, rear_right
        array([0.05, 0.  , 0.05, 0.  ])
        >>> WheelRoads.bump("lef", 0.05, 0.5, (2.5, 1.5))
        Traceback (most recent call last):
        ...
        mrsuspension.errors.ValidationError: unknown side 'lef'. Did you mean 'left'? Valid: both, left, right.
        """
        layout = _corners(_layout_of(corners, geometry))
        side = _side(side, layout)
        wheelbase, track = _geometry(geometry, layout)
        speed = _speed(speed_kmh)
        v = speed / 3.6
        ell = positive("length", length, "m", high=1e3)
        omega = 3.0 * math.pi * v / ell
        if omega > 1e4:
            raise ValidationError(
                f"length must be at least {3.0 * math.pi * v / 1e4:.3g} m at {speed:g} km/h "
                f"(a pulse of w0 <= 1e4 rad/s); got {ell:g} m"
            )
        start = non_negative("position", position, "m", high=1e6)
        shape = RoundedPulse(
            amplitude=height, severity=1.0, omega0=omega, speed_kmh=speed, delay=start / v
        )
        return cls._one_sided(shape, side, wheelbase, speed, track, layout, "bump", ell, start)

    @classmethod
    def pothole(
        cls,
        side: str,
        depth: float,
        length: float,
        geometry: object,
        speed_kmh: float = REFERENCE_SPEED_KMH,
        *,
        position: float = 5.0,
        edge: float = POTHOLE_EDGE,
        corners: str | tuple[str, ...] | None = None,
    ) -> WheelRoads:
        """A rounded pothole (:class:`Pothole`) under the wheels of one side.

        Parameters
        ----------
        side : {"left", "right", "both"}
            Side of the car that drives through it (a half car rides the left side).
        depth : float
            Depth [m], in (0, 1].
        length : float
            Length along the road [m], at least ``2 edge``.
        geometry : (float, float) or object
            ``(wheelbase, track)`` [m].
        speed_kmh : float, optional
            Vehicle speed [km/h], 50 by default.
        position : float, optional
            Distance [m] to the pothole's start, 5 m by default.
        edge : float, optional
            Rounding length of each edge [m], 0.1 m by default.
        corners : str or tuple of str, optional
            ``"full-car"`` or ``"half-car"``; by default the geometry object's own
            ``corners`` (a :class:`~mrsuspension.vehicle.HalfCar` gives ``"half-car"``),
            else ``"full-car"``.

        Examples
        --------
        >>> roads = WheelRoads.pothole("right", 0.04, 0.6, (2.5, 1.5), speed_kmh=36.0, position=1.0)
        >>> roads.displacement(0.13).ravel().tolist()  # the front right is in it
        [0.0, -0.04, 0.0, 0.0]
        >>> roads.displacement(0.38).ravel().tolist()  # then the rear right
        [0.0, 0.0, 0.0, -0.04]
        """
        layout = _corners(_layout_of(corners, geometry))
        side = _side(side, layout)
        wheelbase, track = _geometry(geometry, layout)
        speed = _speed(speed_kmh)
        hole = Pothole(depth, length, position, speed, edge)
        return cls._one_sided(
            hole, side, wheelbase, speed, track, layout, "pothole", hole.length, hole.position
        )

    @classmethod
    def in_phase(
        cls,
        excitation: Excitation,
        corners: object = "full-car",
        *,
        delays: npt.ArrayLike | None = None,
    ) -> WheelRoads:
        """One single-track excitation under every wheel at once (or with given delays).

        Every corner ``c`` sees ``z_r[c](t) = z(t - d_c)``: with no ``delays`` all wheels
        move together, as on a four-poster rig driven in phase (no vehicle speed, so no
        wheelbase delay: :meth:`from_excitation` is the car driving along the road).
        With ``delays``, each wheel holds ``z(0)`` with zero velocity until its delay, as
        a rear wheel before the road reaches it. The corners measure as the quarter car
        on ``excitation`` (:attr:`excitation`).

        Parameters
        ----------
        excitation : Excitation
            A single-track excitation (:class:`~mrsuspension.excitation.Harmonic`,
            :class:`~mrsuspension.excitation.RoundedPulse`, a road profile...).
        corners : str, tuple of str or object, optional
            ``"full-car"`` (the default) or ``"half-car"``, the tuple of corner names, or a
            vehicle (its ``corners``).
        delays : sequence of float, optional
            Delay of every corner [s], >= 0 and at most 1e4, one per corner in the order
            of ``corners`` (default: all 0).

        Raises
        ------
        ValidationError
            Not an excitation, an unknown layout, or delays of the wrong length or range.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> roads = WheelRoads.in_phase(Harmonic(1.0, 0.01), "half-car")
        >>> roads.displacement([0.25]).round(12).ravel().tolist()  # in phase: all equal
        [0.01, 0.01]
        >>> roads = WheelRoads.in_phase(Harmonic(1.0, 0.01), "half-car", delays=(0.0, 0.25))
        >>> roads.displacement([0.25, 0.5]).round(12).tolist()  # the rear 0.25 s late
        [[0.01, 0.0], [0.0, 0.01]]
        >>> roads.rear_delay, roads.duration == Harmonic(1.0, 0.01).duration + 0.25
        (0.25, True)
        """
        if not isinstance(excitation, Excitation):
            raise ValidationError(
                "excitation must be a single-track Excitation (harmonic, pulse, road); "
                f"got {excitation!r}"
            )
        layout = _corners(getattr(corners, "corners", corners))
        given = delays is not None
        return cls(
            excitation,
            excitation if layout == FULL_CAR_CORNERS else None,
            corners=layout,
            source=f"{excitation.name} at every wheel" + (", delayed" if given else " in phase"),
            details={"excitation": excitation.describe(), "single_track": True},
            delays=_delays(delays, layout) if given else (0.0,) * len(layout),
        )

    @classmethod
    def _one_sided(
        cls,
        shape: Excitation,
        side: str,
        wheelbase: float,
        speed: float,
        track: float | None,
        layout: tuple[str, ...],
        what: str,
        length: float,
        position: float,
    ) -> WheelRoads:
        left = shape if side in ("left", "both") else None
        right = shape if side in ("right", "both") and layout == FULL_CAR_CORNERS else None
        return cls(
            left,
            right,
            wheelbase,
            speed,
            track,
            layout,
            source=f"{what} under the {side} wheel{'s' if side == 'both' else ' track'}",
            details={"event": what, "side": side, "length": length, "position": position},
        )

    # -- properties ------------------------------------------------------------------------
    @property
    def excitation(self) -> Excitation | None:
        """The single-track excitation of :meth:`from_excitation` (None for other roads).

        The vehicle engine measures each corner of such a road as the quarter car on that
        excitation (a harmonic's transmissibilities, a pulse's shock ratios); other roads
        get the road measures.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> WheelRoads.from_excitation(Harmonic(1.0, 0.01), (2.5, 1.5), 50.0).excitation.name
        'harmonic'
        >>> WheelRoads.bump("left", 0.05, 0.5, (2.5, 1.5)).excitation is None
        True
        """
        return self.left if self.details.get("single_track") else None

    @property
    def speed(self) -> float | None:
        """Vehicle speed ``V`` [m/s] (None for a road of given ``delays``)."""
        return None if self.speed_kmh is None else self.speed_kmh / 3.6

    @property
    def rear_delay(self) -> float:
        """Time ``L/V`` [s] the rear wheels trail the front ones; with given ``delays``
        the largest of them (0 in phase)."""
        return max(delay for _, delay in self._places)

    @property
    def corner_delays(self) -> tuple[float, ...]:
        """Delay of every corner [s], in the order of :attr:`corners`.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> WheelRoads.from_excitation(Harmonic(1.0, 0.01), (2.5, 1.5), 36.0).corner_delays
        (0.0, 0.0, 0.25, 0.25)
        >>> WheelRoads.in_phase(Harmonic(1.0, 0.01), "half-car").corner_delays
        (0.0, 0.0)
        """
        return tuple(delay for _, delay in self._places)

    @property
    def duration(self) -> float:
        """A sensible simulation length [s]: the longest track's, plus the rear delay."""
        own = [t.duration for t in (self.left, self.right) if t is not None]
        return (max(own) if own else 0.0) + self.rear_delay

    def index(self, corner: str) -> int:
        """Row of ``corner`` in :meth:`displacement` (did-you-mean on a wrong name).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> WheelRoads.from_excitation(Harmonic(1.0, 0.01), (2.5, 1.5), 50.0).index("rear_left")
        2
        """
        if not isinstance(corner, str) or corner not in self.corners:
            raise unknown_name("corner", str(corner), self.corners)
        return self.corners.index(corner)

    # -- the signals --------------------------------------------------------------------
    def _signal(self, t: npt.ArrayLike, order: int) -> FloatArray:
        tt = time_array(t)
        out = np.zeros((len(self.corners), *tt.shape))
        for row, (track, delay) in enumerate(self._places):
            if track is None:
                continue
            s = tt - delay if delay else tt
            reached = s >= 0.0
            if order == 0:
                out[row] = track.displacement(np.where(reached, s, 0.0))
            else:
                f = track.velocity if order == 1 else track.acceleration
                out[row] = np.where(reached, f(np.where(reached, s, 0.0)), 0.0)
        return out

    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """Road displacement under every wheel [m], shape ``(n_corners, *t.shape)``."""
        return self._signal(t, 0)

    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """Road velocity under every wheel [m/s], the exact derivative of :meth:`displacement`."""
        return self._signal(t, 1)

    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """Road acceleration under every wheel [m/s^2] (zero before a wheel reaches the road)."""
        return self._signal(t, 2)

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """``(z_r, dz_r/dt)`` of every corner at ``start + k step``, each ``(n_corners, n)``.

        Uses each track's own (compiled) :meth:`Excitation.sample_grid` from the first
        point a corner has reached; agrees with :meth:`displacement` and :meth:`velocity`
        to round-off.

        Examples
        --------
        >>> from mrsuspension.excitation import preset_road
        >>> roads = WheelRoads.from_excitation(preset_road("rough"), (2.7, 1.5))
        >>> z, v = roads.sample_grid(2001, 1e-3)
        >>> t = np.arange(2001) * 1e-3
        >>> bool(np.allclose(z, roads.displacement(t), rtol=0, atol=1e-15))
        True
        >>> bool(np.allclose(v, roads.velocity(t), rtol=1e-9, atol=1e-15))
        True
        """
        n, step, start = grid_args(n, step, start)
        t = start + np.arange(n) * step
        z = np.zeros((len(self.corners), n))
        v = np.zeros((len(self.corners), n))
        for row, (track, delay) in enumerate(self._places):
            if track is None:
                continue
            k0 = int(np.searchsorted(t - delay, 0.0, side="left"))  # first point reached
            z[row, :k0] = track.displacement(0.0)
            if k0 < n:
                zk, vk = track.sample_grid(n - k0, step, float(t[k0] - delay))
                z[row, k0:] = zk
                v[row, k0:] = vk
        return z, v

    def describe(self) -> dict[str, Any]:
        """Plain data: kind, source, corners, geometry [m], speed, delay, duration, tracks.

        ``"tracks"`` holds each side's :meth:`Excitation.describe` (None for a flat side);
        ``"details"`` how the road was built (the coherence model of a two-track road, the
        CRG file and wheel positions...).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> d = WheelRoads.from_excitation(Harmonic(1.0, 0.01), (2.5, 1.5), 36.0).describe()
        >>> d["kind"], d["rear_delay"], d["tracks"]["right"]["kind"]
        ('wheel-roads', 0.25, 'harmonic')
        """
        out: dict[str, Any] = {
            "kind": "wheel-roads",
            "source": self.source,
            "corners": list(self.corners),
            "wheelbase": self.wheelbase,
            "track": self.track,
            "speed_kmh": self.speed_kmh,
            "rear_delay": self.rear_delay,
            "duration": self.duration,
            "tracks": {
                side: None if track is None else track.describe()
                for side, track in (("left", self.left), ("right", self.right))
            },
            "details": dict(self.details),
        }
        if self.delays is not None:  # only then: the other roads' records stay as they were
            out["delays"] = list(self.delays)
        return out

    def __repr__(self) -> str:
        timing = (
            f"delays={list(self.delays)} s"
            if self.delays is not None
            else f"wheelbase={self.wheelbase:g} m, track={self.track}, speed_kmh={self.speed_kmh:g}"
        )
        return f"WheelRoads(source={self.source!r}, corners={self.corners}, {timing})"


# -- helpers --------------------------------------------------------------------------------
def _two_track_spectrum(road: object) -> tuple[RoadSpectrum, int, str]:
    """``(spectrum, default seed, label)`` of an ISO class, a preset or a RoadSpectrum."""
    if isinstance(road, RoadSpectrum):
        spectrum, seed, label = road, 0, f"two-track road, {road.label()}"
    elif (
        isinstance(road, str) and road.strip().upper() in ISO8608_CLASSES and len(road.strip()) == 1
    ):
        key = road.strip().upper()
        spectrum = RoadSpectrum(ISO8608_CLASSES[key], 2.0, ISO8608_BAND)
        seed, label = 0, f"ISO 8608 class {key}"
    elif isinstance(road, str) and road in PRESET_ROADS:
        preset = PRESET_ROADS[road]
        spectrum, seed, label = preset.spectrum, preset.seed, f"preset {road!r}"
    else:
        names = [*ISO8608_CLASSES, *PRESET_ROADS]
        raise unknown_name("road (an ISO 8608 class or a preset)", str(road), names)
    if spectrum.waviness <= 0.0:
        raise ValidationError(
            "the isotropic coherence needs a road spectrum with waviness > 0; "
            f"got {spectrum.waviness:g}"
        )
    return spectrum, seed, label


def _read_crg(path: str | Path) -> Any:
    """The road of an OpenCRG file, or a one-line :class:`ValidationError` naming it."""
    from mrsuspension._inputs import read_bytes

    file = check_input_file("CRG file", path)
    read_bytes(file, "CRG file")  # readable, and recorded: a study's cache key holds it
    import pyopencrg  # here: importing the package stays cheap

    try:
        with warnings.catch_warnings():  # pyopencrg warns about holes; we check the tracks
            warnings.simplefilter("ignore")
            return pyopencrg.read(file)
    except MemoryError:
        raise
    except Exception as exc:  # a malformed file can fail anywhere in a third-party parser
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise ValidationError(f"cannot read CRG file {file.name!r}: {reason}") from None
