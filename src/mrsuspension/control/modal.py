"""Modal skyhook for the half and full car: heave, pitch and roll damping to the sky.

Conventions (model reference, section 1, ISO 8855): ``x`` forward, ``y`` left, ``z`` up from
the body's centre of gravity; heave ``z`` and its velocity ``v_z`` [m/s] up; pitch
``theta`` [rad] and its rate ``q`` [rad/s] positive nose **down** (right-handed about
``+y``); roll ``phi`` [rad] and its rate ``p`` [rad/s] positive with the **left** side up
(right-handed about ``+x``). A body point at ``(x_i, y_i)`` then moves, for small angles,

    z_i = z - x_i theta + y_i phi,      v_i = v_z - x_i q + y_i p      (corner_velocity)

and upward corner forces ``F_i`` on the body give the heave force and the moments

    F_z = sum F_i,    M_theta = -sum x_i F_i,    M_phi = sum y_i F_i,

i.e. ``w = J F`` with the rows of ``J`` being ``1``, ``-x_i`` and ``y_i``.

**Distribution.** Modal skyhook asks for ``F_z = -c_z v_z``, ``M_theta = -c_theta q`` and
``M_phi = -c_phi p``. The corner forces that produce exactly that wrench with the least
``sum F_i^2`` are ``F = J^T (J J^T)^-1 w`` (the minimum-norm solution; for the full car it
puts no force into the warp mode, which no body mode sees; for the half car ``J`` is
2 x 2 and the solution is unique). For a car with each axle symmetric about the centre
line (``y`` = +-track/2), ``sum y_i = sum x_i y_i = 0`` and roll decouples; if moreover
the CG is midway (``sum x_i = 0``), ``J J^T`` is diagonal and

    F_i = -c_z v_z / n + c_theta q x_i / sum x^2 - c_phi p y_i / sum y^2.

With ``c_z = n c_s``, ``c_theta = c_s sum x^2``, ``c_phi = c_s sum y^2`` this is per-corner
skyhook ``F_i = -c_s v_i`` (:meth:`ModalSkyhook.corner_equivalent`).

**Semi-active clipping.** A damper can only push the body up (``F_d > 0``) in
compression (``v_d > 0``) and down in rebound (model reference, section 1), so the corner is
switched to the high current when ``F_i v_d > 0``: the switching condition is ``z_c = -F_i v_d``,
high current when ``z_c < 0`` as in the hi-lo policies (:mod:`mrsuspension.control.hilo`:
skyhook ``F* = -c_s z_s'`` gives ``z_c = c_s z_s' v_d``, the sign of policy I's
``z_s' v_d``) and the sliding-mode law's ``z_c = -F_h F_c``.

Kernels are ``@njit(inline="always")`` scalars over small arrays for the vehicle engine;
:class:`ModalSkyhook` holds the gains and currents with validation.

Examples
--------
>>> sky = ModalSkyhook(heave=4000.0, pitch=3000.0, roll=1000.0)
>>> dist = distribution_matrix([1.2, 1.2, -1.6, -1.6], [0.75, -0.75, 0.75, -0.75])
>>> f = sky.forces(dist, heave_velocity=0.1, pitch_rate=0.0, roll_rate=0.0)
>>> np.round(f, 3).tolist()  # the front, nearer the CG, takes more: no pitch moment
[-114.286, -114.286, -85.714, -85.714]
>>> round(float(f.sum()), 9), round(float(-(f * [1.2, 1.2, -1.6, -1.6]).sum()), 9)
(-400.0, 0.0)
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.errors import ValidationError, check_finite, check_range

__all__ = [
    "CORNERS_FULL",
    "CORNERS_HALF",
    "LAW_CORNERS",
    "LAW_CORNER_SKYHOOK",
    "LAW_LQ",
    "LAW_LQG",
    "LAW_MODAL",
    "LAW_MPC",
    "MP_SIZE",
    "CornerSkyhook",
    "ModalSkyhook",
    "VehicleLaw",
    "clipped_force",
    "corner_velocity",
    "distribution_matrix",
    "hilo_current",
    "modal_forces",
    "modal_hilo",
    "switching_condition",
]

FloatArray = npt.NDArray[np.float64]

#: full-car corner names, in the order of the distribution matrix's rows
CORNERS_FULL = ("front_left", "front_right", "rear_left", "rear_right")
#: half-car corner names
CORNERS_HALF = ("front", "rear")

# modal-skyhook parameter vector (ModalSkyhook.params)
MP_CZ, MP_CTHETA, MP_CPHI, MP_ILOW, MP_IHIGH = range(5)
#: length of :meth:`ModalSkyhook.params`
MP_SIZE = 5
#: the vehicle kernel's law codes (``VehicleLaw.kernel_code``; 0: the corners' own laws;
#: the whole-vehicle LQ, LQG and MPC: :mod:`mrsuspension.control.vehicle_lq`)
LAW_CORNERS, LAW_MODAL, LAW_CORNER_SKYHOOK, LAW_LQ, LAW_LQG, LAW_MPC = 0, 1, 2, 3, 4, 5


# --- kernels ---------------------------------------------------------------------------


@njit(cache=True, inline="always")
def corner_velocity(vz: float, q: float, p: float, x: float, y: float) -> float:
    """Vertical velocity [m/s] of the body point ``(x, y)`` [m]: ``v_z - x q + y p``.

    ``vz`` heave velocity [m/s] (up), ``q`` pitch rate [rad/s] (nose down), ``p`` roll
    rate [rad/s] (left side up); small angles.

    Examples
    --------
    >>> corner_velocity(0.0, 0.1, 0.0, 1.2, 0.75)  # pitching nose down: the front sinks
    -0.12
    """
    return vz - x * q + y * p


@njit(cache=True, inline="always")
def modal_forces(
    out: np.ndarray, dist: np.ndarray, mp: np.ndarray, vz: float, q: float, p: float
) -> None:
    """Write the corner forces [N] (up on the body) of modal skyhook into ``out``.

    ``out[i] = dist[i, 0] F_z + dist[i, 1] M_theta + dist[i, 2] M_phi`` with
    ``(F_z, M_theta, M_phi) = (-c_z v_z, -c_theta q, -c_phi p)``; ``dist`` from
    :func:`distribution_matrix`, ``mp`` from :meth:`ModalSkyhook.params`.

    Examples
    --------
    >>> dist = distribution_matrix([1.3, -1.5])
    >>> out = np.zeros(2)
    >>> modal_forces(out, dist, ModalSkyhook(2000.0, 0.0, 0.0).params(), 0.1, 0.0, 0.0)
    >>> np.round(out, 6).tolist()  # F_z = -200 N split so that 1.3 F_f = 1.5 F_r
    [-107.142857, -92.857143]
    """
    fz = -mp[MP_CZ] * vz
    mt = -mp[MP_CTHETA] * q
    mr = -mp[MP_CPHI] * p
    for i in range(out.size):
        out[i] = dist[i, 0] * fz + dist[i, 1] * mt + dist[i, 2] * mr


@njit(cache=True, inline="always")
def switching_condition(force: float, vd: float) -> float:
    """``z_c = -F v_d``: negative when the damper can produce the desired force ``F`` [N].

    ``vd`` is the damper velocity [m/s] (compression positive); high current when
    ``z_c < 0`` (model reference, section 6).

    Examples
    --------
    >>> switching_condition(100.0, 0.2), switching_condition(100.0, -0.2)
    (-20.0, 20.0)
    """
    return -force * vd


@njit(cache=True, inline="always")
def clipped_optimal_condition(force: float, measured: float) -> float:
    """Dyke et al.'s (1996) clipped-optimal ``z_c = -(F - F_d) F_d``: negative (high
    current) when the damper's measured force ``F_d`` [N] (the load cell) is below the
    desired ``F`` [N] in magnitude and of its sign.

    Examples
    --------
    >>> clipped_optimal_condition(300.0, 200.0), clipped_optimal_condition(100.0, 200.0)
    (-20000.0, 20000.0)
    >>> clipped_optimal_condition(-300.0, 200.0)  # the other sign: low
    100000.0
    """
    return -(force - measured) * measured


@njit(cache=True, inline="always")
def hilo_current(zc: float, low: float, high: float) -> float:
    """``high`` [A] when ``zc < 0`` (the force is achievable), else ``low`` [A].

    Examples
    --------
    >>> hilo_current(-1.0, 0.0, 0.5), hilo_current(0.0, 0.0, 0.5)
    (0.5, 0.0)
    """
    return high if zc < 0.0 else low


@njit(cache=True, inline="always")
def clipped_force(force: float, vd: float) -> float:
    """The desired force [N] through an ideal dissipative damper: ``F`` if ``F v_d > 0``, else 0.

    Examples
    --------
    >>> clipped_force(100.0, 0.2), clipped_force(100.0, -0.2)
    (100.0, 0.0)
    """
    return force if force * vd > 0.0 else 0.0


@njit(cache=True, inline="always")
def modal_hilo(
    current: np.ndarray, zc: np.ndarray, forces: np.ndarray, vd: np.ndarray, mp: np.ndarray
) -> None:
    """Per corner: ``zc[i] = -forces[i] vd[i]`` and the hi-lo ``current[i]`` [A].

    Examples
    --------
    >>> i, z = np.zeros(2), np.zeros(2)
    >>> mp = ModalSkyhook(1.0, 1.0, 1.0, low_current=0.05).params()
    >>> modal_hilo(i, z, np.array([100.0, 100.0]), np.array([0.1, -0.1]), mp)
    >>> i.tolist(), z.tolist()
    ([0.5, 0.05], [-10.0, 10.0])
    """
    for k in range(forces.size):
        z = switching_condition(forces[k], vd[k])
        zc[k] = z
        current[k] = hilo_current(z, mp[MP_ILOW], mp[MP_IHIGH])


# --- Python-facing ---------------------------------------------------------------------


def distribution_matrix(x: npt.ArrayLike, y: npt.ArrayLike | None = None) -> FloatArray:
    """The ``(n, 3)`` matrix taking ``(F_z, M_theta, M_phi)`` to corner forces ``F_i`` [N].

    ``D = J^T (J J^T)^-1`` with rows of ``J``: ``1``, ``-x_i``, ``y_i`` (module docstring);
    without ``y`` (half car) the roll column is zero and ``J`` is 2 x n.

    Parameters
    ----------
    x : array_like
        Corner positions forward of the CG [m] (front positive), in the corner order
        (:data:`CORNERS_FULL` or :data:`CORNERS_HALF`).
    y : array_like, optional
        Corner positions left of the CG [m].

    Examples
    --------
    >>> distribution_matrix([1.3, -1.5]).round(6).tolist()  # half car: exact inverse
    [[0.535714, -0.357143, 0.0], [0.464286, 0.357143, 0.0]]
    """
    xs = check_finite("x", x).ravel()
    rows = [np.ones_like(xs), -xs]
    if y is not None:
        ys = check_finite("y", y).ravel()
        if ys.size != xs.size:
            raise ValidationError(
                f"x and y must give every corner; got {xs.size} x and {ys.size} y positions"
            )
        rows.append(ys)
    if xs.size < len(rows):
        raise ValidationError(f"modal skyhook needs at least {len(rows)} corners; got {xs.size}")
    j = np.vstack(rows)
    gram = j @ j.T
    if np.linalg.cond(gram) > 1e12:
        what = "x positions must differ" if y is None else "corners must not lie on one line"
        raise ValidationError(
            f"corner positions cannot produce every modal force ({what}); "
            f"got x={xs.tolist()}" + ("" if y is None else f", y={ys.tolist()}")
        )
    dist = np.zeros((xs.size, 3))
    dist[:, : len(rows)] = j.T @ np.linalg.inv(gram)
    return dist


class VehicleLaw:
    """A law over the whole vehicle: every corner's current from the body's motion.

    The plug-in contract of a whole-vehicle law (the corner laws' is
    :class:`~mrsuspension.control.base.Controller`): its registry name ``law``, the
    vehicle kernel's ``kernel_code``, whether it reads the body's heave, pitch and roll
    rates (``uses_body_rates``: the engine then builds the distribution matrix), its hi-lo
    currents, its kernel parameters (:meth:`params`, the ``MP_*`` layout) and
    :meth:`for_vehicle`, where a law derives what it needs from the vehicle it is attached
    to (gains from the geometry, a Riccati solve...). Registered once in
    :data:`~mrsuspension.control.registry.VEHICLE_LAWS`; scenarios name it in
    ``[controller] law`` with its fields as keys.
    """

    law: ClassVar[str]
    kernel_code: ClassVar[int]
    uses_body_rates: ClassVar[bool] = False
    #: an ideal actuator at every corner instead of the damper (the force applied as is)
    active: ClassVar[bool] = False
    #: every corner's current from its damper's inverse model (the engine then refuses a
    #: damper that is not ``wang-symmetric``, as for a corner law that uses the inverse)
    needs_inverse: ClassVar[bool] = False

    #: every law switches between two currents [A] (fields of the subclass, a dataclass)
    low_current: float
    high_current: float

    @classmethod
    def options(cls) -> tuple[str, ...]:
        """The law's options (its fields): the scenario's ``[controller]`` keys.

        Examples
        --------
        >>> CornerSkyhook.options()
        ('damping', 'low_current', 'high_current')
        """
        return tuple(f.name for f in dataclasses.fields(cls))  # type: ignore[arg-type]

    def for_vehicle(self, vehicle: Any) -> VehicleLaw:
        """This law attached to ``vehicle`` (a half or full car): by default itself."""
        return self

    def params(self) -> FloatArray:
        """The kernel parameter vector (``MP_*`` layout, :data:`MP_SIZE` values or more)."""
        raise NotImplementedError

    def buffer_shape(self, corners: int) -> tuple[int, int]:
        """The shape of the vehicle kernel's law buffer (``mbuf``): 4 rows of one value per
        corner (desired forces, stroke rates, currents, ``z_c``); a law with a state of
        its own asks for more.

        Examples
        --------
        >>> CornerSkyhook().buffer_shape(4)
        (4, 4)
        """
        return 4, corners

    def describe(self) -> dict[str, Any]:
        """Plain data: ``law`` and every option.

        Examples
        --------
        >>> CornerSkyhook(1000.0).describe()
        {'law': 'corner-skyhook', 'damping': 1000.0, 'low_current': 0.0, 'high_current': 0.5}
        """
        return {"law": self.law, **{k: getattr(self, k) for k in self.options()}}


@dataclass(frozen=True)
class ModalSkyhook(VehicleLaw):
    """Modal skyhook gains and hi-lo currents.

    Parameters
    ----------
    heave : float, optional
        Heave skyhook damping ``c_z`` [N s/m] (>= 0).
    pitch : float, optional
        Pitch skyhook damping ``c_theta`` [N m s/rad] (>= 0).
    roll : float, optional
        Roll skyhook damping ``c_phi`` [N m s/rad] (>= 0; unused by the half car; 0 when
        heave and pitch are given without it).
        With no gain at all, :meth:`for_vehicle` derives them from the car it drives: the
        corner equivalent of the skyhook reference's 6750 N s/m
        (:meth:`corner_equivalent`).
    low_current : float
        Current when the desired force is not achievable [A] (default 0).
    high_current : float
        Current when it is [A] (default 0.5 A, the simulations' ``i_max``, spec
        section 3).

    Notes
    -----
    Hi-lo reads the desired forces only for their signs: scaling all three gains changes
    nothing, only their ratios matter, and the high current is what sets the strength.
    On the published full car and the report's class C road this law rides worse than
    the MR damper at 0 A for every high current from 0.05 to 0.5 A, because the damper's
    0 A force is already more damping than that car wants (docs/vehicles.md, "Why modal
    skyhook loses to passive 0 A on the class C road").

    Examples
    --------
    >>> ModalSkyhook(27000.0, 40000.0, 15000.0).params().tolist()
    [27000.0, 40000.0, 15000.0, 0.0, 0.5]
    >>> ModalSkyhook(-1.0, 0.0, 0.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: heave must be in [0, inf) N s/m; got -1 N s/m
    >>> from mrsuspension.vehicle import HalfCar
    >>> ModalSkyhook().for_vehicle(HalfCar()).heave  # the corner equivalent of 6750 N s/m
    13500.0
    """

    law: ClassVar[str] = "modal-skyhook"
    kernel_code: ClassVar[int] = LAW_MODAL
    uses_body_rates: ClassVar[bool] = True

    heave: float | None = None
    pitch: float | None = None
    roll: float | None = None
    low_current: float = 0.0
    high_current: float = 0.5

    def __post_init__(self) -> None:
        given = [g for g in (self.heave, self.pitch, self.roll) if g is not None]
        missing = [k for k in ("heave", "pitch") if getattr(self, k) is None]
        if given and missing:
            raise ValidationError(
                f"law 'modal-skyhook' needs {' and '.join(missing)} with the other gains "
                "(or no gain at all: the corner equivalent of 6750 N s/m)"
            )
        if given and self.roll is None:
            object.__setattr__(self, "roll", 0.0)
        if given:
            check_range("heave", self.heave, 0.0, None, unit="N s/m")
            check_range("pitch", self.pitch, 0.0, None, unit="N m s/rad")
            check_range("roll", self.roll, 0.0, None, unit="N m s/rad")
        check_range("low_current", self.low_current, 0.0, None, unit="A")
        check_range("high_current", self.high_current, float(self.low_current), None, unit="A")

    def for_vehicle(self, vehicle: Any) -> ModalSkyhook:
        """The gains of ``vehicle`` when none is given (:meth:`corner_equivalent` of the
        skyhook reference at its corners); given gains are kept."""
        if self.heave is not None:
            return self
        x, y = vehicle.modal_positions()  # y None without roll (half car)
        return ModalSkyhook.corner_equivalent(
            x, y, low_current=self.low_current, high_current=self.high_current
        )

    @classmethod
    def corner_equivalent(
        cls,
        x: npt.ArrayLike,
        y: npt.ArrayLike | None = None,
        skyhook_damping: float = 6750.0,
        **currents: float,
    ) -> ModalSkyhook:
        """Gains equal to per-corner skyhook ``c_s`` [N s/m] on a symmetric car.

        ``c_z = n c_s``, ``c_theta = c_s sum x^2``, ``c_phi = c_s sum y^2``; the default
        ``c_s`` is the skyhook reference's 6750 N s/m (model reference, section 5).

        Examples
        --------
        >>> ModalSkyhook.corner_equivalent([1.0, -1.0], skyhook_damping=1000.0).pitch
        2000.0
        """
        c_s = float(check_range("skyhook_damping", skyhook_damping, 0.0, None, unit="N s/m"))
        xs = check_finite("x", x).ravel()
        ys = np.zeros(0) if y is None else check_finite("y", y).ravel()
        return cls(
            heave=c_s * xs.size,
            pitch=c_s * float(np.sum(xs * xs)),
            roll=c_s * float(np.sum(ys * ys)),
            **currents,
        )

    def params(self) -> FloatArray:
        """The kernel parameter vector (``MP_*`` layout, :data:`MP_SIZE` values).

        Examples
        --------
        >>> ModalSkyhook(1.0, 2.0, 3.0).params().size
        5
        """
        if self.heave is None or self.pitch is None or self.roll is None:
            raise ValidationError(
                "modal skyhook has no gains yet: give heave and pitch, or attach it to a car "
                "(for_vehicle) for the corner equivalent"
            )
        out = np.zeros(MP_SIZE)
        out[MP_CZ], out[MP_CTHETA], out[MP_CPHI] = self.heave, self.pitch, self.roll
        out[MP_ILOW], out[MP_IHIGH] = self.low_current, self.high_current
        return out

    def forces(
        self,
        dist: npt.ArrayLike,
        *,
        heave_velocity: float,
        pitch_rate: float,
        roll_rate: float = 0.0,
    ) -> FloatArray:
        """Desired corner forces [N] (up on the body) for body rates (see module docstring).

        ``dist`` from :func:`distribution_matrix`; ``heave_velocity`` [m/s],
        ``pitch_rate`` and ``roll_rate`` [rad/s].

        Examples
        --------
        >>> d = distribution_matrix([1.0, -1.0])
        >>> ModalSkyhook(0.0, 1000.0).forces(d, heave_velocity=0.0, pitch_rate=0.1).tolist()
        [50.0, -50.0]
        """
        d = check_finite("dist", dist)
        if d.ndim != 2 or d.shape[1] != 3:
            raise ValidationError(
                f"dist must be an (n, 3) distribution matrix; got shape {d.shape}"
            )
        rates = check_finite("body rates", [heave_velocity, pitch_rate, roll_rate])
        out = np.zeros(d.shape[0])
        modal_forces(out, np.ascontiguousarray(d), self.params(), *(float(r) for r in rates))
        return out

    def currents(
        self, forces: npt.ArrayLike, damper_velocity: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray]:
        """``(currents [A], z_c)`` per corner for desired ``forces`` [N] and ``v_d`` [m/s].

        Examples
        --------
        >>> i, zc = ModalSkyhook(1.0, 1.0).currents([-50.0, 50.0], [-0.1, -0.1])
        >>> i.tolist()
        [0.5, 0.0]
        """
        f = check_finite("forces", forces).ravel()
        vd = check_finite("damper_velocity", damper_velocity).ravel()
        if f.size != vd.size:
            raise ValidationError(
                f"forces and damper_velocity must have one value per corner; "
                f"got {f.size} and {vd.size}"
            )
        current, zc = np.zeros(f.size), np.zeros(f.size)
        modal_hilo(current, zc, f, vd, self.params())
        return current, zc


@dataclass(frozen=True)
class CornerSkyhook(VehicleLaw):
    """Per-corner on-off skyhook: ``F_i = -c_s v_i`` at every corner, hi-lo by :func:`modal_hilo`.

    The classical skyhook on-off law (high current when ``v_i v_d,i < 0``) at every
    corner of a vehicle, through the same hi-lo kernel as :class:`ModalSkyhook`: on a car
    with a diagonal ``J J^T`` (CG midway, symmetric tracks) it equals
    :meth:`ModalSkyhook.corner_equivalent` with the same ``c_s``.

    Parameters
    ----------
    damping : float
        Skyhook damping ``c_s`` [N s/m] (> 0; default 6750 N s/m, model reference, section 5).
    low_current, high_current : float
        Currents [A] as :class:`ModalSkyhook` (0 and 0.5 A).

    Examples
    --------
    >>> CornerSkyhook().params().tolist()
    [6750.0, 6750.0, 6750.0, 0.0, 0.5]
    """

    law: ClassVar[str] = "corner-skyhook"
    kernel_code: ClassVar[int] = LAW_CORNER_SKYHOOK

    damping: float = 6750.0
    low_current: float = 0.0
    high_current: float = 0.5

    def __post_init__(self) -> None:
        check_range("damping", self.damping, 0.0, None, unit="N s/m", low_inclusive=False)
        check_range("low_current", self.low_current, 0.0, None, unit="A")
        check_range("high_current", self.high_current, float(self.low_current), None, unit="A")

    def params(self) -> FloatArray:
        """The kernel parameter vector (``MP_*`` layout; ``c_s`` in every gain).

        Examples
        --------
        >>> float(CornerSkyhook(1000.0).params()[MP_CZ])
        1000.0
        """
        c = float(self.damping)
        return ModalSkyhook(c, c, c, self.low_current, self.high_current).params()
