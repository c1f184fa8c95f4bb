"""Half- and full-vehicle ride models: a rigid body on a suspended wheel at every corner.

The conventions of the quarter car (model reference, section 4) hold at every corner:
coordinates are positive **up** from static equilibrium, the stroke ``x_d = z_u - z_s``
is positive in compression, a positive damper force pushes the body up, and a tire
carries load only while it is compressed (``delta = z_r - z_u + dx_u > 0``; it never
pulls). The body axes are ISO 8855's: ``x`` forward, ``y`` to the left, ``z`` up, so a
positive pitch ``theta`` lowers the nose and a positive roll ``phi`` raises the left
side. For small angles the body moves at a corner at ``(x_i, y_i)`` from the centre of
gravity by::

    z_s,i = z - x_i theta + y_i phi

and the equations of motion are, with ``F_i = k_s,i x_d,i + F_d,i + F_bar,i`` the
suspension force on the body at corner ``i`` (preloads cancel gravity)::

    m_s z''       = sum F_i
    I_y theta''   = -sum x_i F_i
    I_x phi''     = sum y_i F_i
    m_u,i z_u,i'' = F_T,i - W_i - F_i

``W_i`` is the static tire load (the corner's share of the sprung weight plus
``m_u,i g``). An anti-roll bar of torsional rate ``k_bar`` [N m/rad] on an axle of track
``t`` adds ``F_bar = k_bar / t^2 (x_d,left - x_d,right)`` on the left corner and the
opposite on the right. The half car has the heave and pitch of the body and one wheel per
axle (corners ``front`` and ``rear``).

Examples
--------
>>> car = FullCar()
>>> car.corners
('front_left', 'front_right', 'rear_left', 'rear_right')
>>> round(car.wheelbase, 3), [round(w) for w in car.static_tire_loads()]
(2.348, [3256, 3256, 3169, 3169])
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, fields, replace
from importlib import resources
from typing import Any, ClassVar, NamedTuple

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_finite, check_range, unknown_name
from mrsuspension.excitation.wheels import FULL_CAR_CORNERS, HALF_CAR_CORNERS
from mrsuspension.vehicle import GRAVITY, QuarterCar

__all__ = [
    "CORNERS_FULL",
    "CORNERS_HALF",
    "FullCar",
    "HalfCar",
    "LinearModel",
    "VehicleBody",
    "available_sets",
    "delay_phasors",
]

#: Corner names and order of the full car (left = +y): the same tuple as
#: :data:`mrsuspension.excitation.FULL_CAR_CORNERS` (one home, in the lower layer).
CORNERS_FULL: tuple[str, ...] = FULL_CAR_CORNERS
#: Corner names and order of the half car (one wheel per axle):
#: :data:`mrsuspension.excitation.HALF_CAR_CORNERS`.
CORNERS_HALF: tuple[str, ...] = HALF_CAR_CORNERS

_SET_FILE = "full-car-kalman-2023"

#: field -> (low, high, unit): the quarter car's limits for the corner quantities
_LIMITS: dict[str, tuple[float, float, str]] = {
    "sprung_mass": (1.0, 1e5, "kg"),
    "pitch_inertia": (0.0, 1e7, "kg m^2"),
    "roll_inertia": (0.0, 1e7, "kg m^2"),
    "cg_to_front": (-50.0, 50.0, "m"),
    "cg_to_rear": (-50.0, 50.0, "m"),
    "front_track": (0.0, 20.0, "m"),
    "rear_track": (0.0, 20.0, "m"),
    "front_unsprung_mass": (0.1, 1e4, "kg"),
    "rear_unsprung_mass": (0.1, 1e4, "kg"),
    "front_suspension_stiffness": (1.0, 1e8, "N/m"),
    "rear_suspension_stiffness": (1.0, 1e8, "N/m"),
    "front_tire_stiffness": (1.0, 1e9, "N/m"),
    "rear_tire_stiffness": (1.0, 1e9, "N/m"),
    "front_tire_damping": (0.0, 1e6, "N s/m"),
    "rear_tire_damping": (0.0, 1e6, "N s/m"),
    "front_anti_roll_stiffness": (0.0, 1e8, "N m/rad"),
    "rear_anti_roll_stiffness": (0.0, 1e8, "N m/rad"),
}
#: fields that must be strictly positive (the low end excluded)
_POSITIVE = {"pitch_inertia", "roll_inertia", "front_track", "rear_track"}


class LinearModel(NamedTuple):
    """``M q'' + C q' + K q = K_r z_r + C_r z_r'``: the vehicle with linear dampers.

    ``q`` has the order of ``dofs`` (body first, then the wheels), ``z_r`` one road
    input per corner.
    """

    #: degree-of-freedom names (``heave``, ``pitch``, [``roll``], ``z_u.<corner>``...)
    dofs: tuple[str, ...]
    #: mass matrix [kg, kg m^2]
    M: npt.NDArray[np.float64]
    #: damping matrix
    C: npt.NDArray[np.float64]
    #: stiffness matrix
    K: npt.NDArray[np.float64]
    #: road stiffness input (dofs x corners) [N/m]
    K_road: npt.NDArray[np.float64]
    #: road damping input (dofs x corners) [N s/m]
    C_road: npt.NDArray[np.float64]


def delay_phasors(frequency: npt.ArrayLike, delays: Sequence[float]) -> np.ndarray:
    """Road phasors ``exp(-j w tau_i)`` of a unit road reaching corner ``i`` ``tau_i`` late.

    Parameters
    ----------
    frequency : array_like
        Frequencies [Hz].
    delays : sequence of float
        Delay of every corner [s] (e.g. ``(0, wheelbase / speed)`` for a half car).

    Returns
    -------
    ndarray
        Complex phasors, shape ``(len(frequency), len(delays))``.

    Examples
    --------
    >>> p = delay_phasors([1.0], [0.0, 0.25])
    >>> np.round(p, 12).tolist()
    [[(1+0j), -1j]]
    """
    f = np.atleast_1d(check_finite("frequency", frequency))
    tau = np.asarray(check_finite("delays", delays), dtype=float)
    return np.exp(-2j * np.pi * f[:, None] * tau[None, :])


@dataclass(frozen=True)
class VehicleBody:
    """What the half and full cars share: corners, geometry, loads, linear model.

    Not used on its own; see :class:`HalfCar` and :class:`FullCar`.
    """

    corners: ClassVar[tuple[str, ...]] = ()
    #: body degrees of freedom
    body_dofs: ClassVar[tuple[str, ...]] = ()

    sprung_mass: float = 1150.0
    pitch_inertia: float = 861.8
    cg_to_front: float = 1.116
    cg_to_rear: float = 1.232
    front_unsprung_mass: float = 30.2
    rear_unsprung_mass: float = 49.7
    front_suspension_stiffness: float = 30_000.0
    rear_suspension_stiffness: float = 32_500.0
    front_tire_stiffness: float = 181_000.0
    rear_tire_stiffness: float = 181_000.0
    front_tire_damping: float = 0.0
    rear_tire_damping: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            lo, hi, unit = _LIMITS[f.name]
            value = getattr(self, f.name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValidationError(f"{f.name} must be a number in {unit}; got {value!r}")
            low_inclusive = f.name not in _POSITIVE
            check_range(f.name, value, lo, hi, unit=unit, low_inclusive=low_inclusive)
            object.__setattr__(self, f.name, float(value))
        if self.wheelbase <= 0.0:
            raise ValidationError(
                f"wheelbase cg_to_front + cg_to_rear must be > 0 m; got {self.cg_to_front:g} + "
                f"{self.cg_to_rear:g} = {self.wheelbase:g} m"
            )

    # -- construction ---------------------------------------------------------------
    def with_(self, **changes: float) -> Any:
        """A copy with some parameters changed (validated).

        Examples
        --------
        >>> HalfCar().with_(sprung_mass=600.0).sprung_mass
        600.0
        """
        names = [f.name for f in fields(self)]
        for key in changes:
            if key not in names:
                raise unknown_name("vehicle parameter", key, names)
        return replace(self, **changes)

    def describe(self) -> dict[str, Any]:
        """Plain-data description (the parameters and the model kind).

        Examples
        --------
        >>> HalfCar().describe()["model"]
        'half-car'
        """
        return {"model": self.model_name, **asdict(self)}

    @property
    def model_name(self) -> str:
        """``"half-car"`` or ``"full-car"``."""
        return "half-car" if len(self.corners) == 2 else "full-car"

    # -- geometry and loads ---------------------------------------------------------------
    @property
    def wheelbase(self) -> float:
        """``a + b`` [m]."""
        return self.cg_to_front + self.cg_to_rear

    def _axle(self, corner: int) -> str:
        return "front" if self.corners[corner].startswith("front") else "rear"

    def _per_corner(self, name: str) -> np.ndarray:
        return np.array(
            [getattr(self, f"{self._axle(c)}_{name}") for c in range(len(self.corners))]
        )

    def corner_positions(self) -> tuple[np.ndarray, np.ndarray]:
        """``(x, y)`` of every corner from the centre of gravity [m] (x forward, y left).

        Examples
        --------
        >>> x, y = FullCar().corner_positions()
        >>> x.tolist(), y.tolist()
        ([1.116, 1.116, -1.232, -1.232], [0.621, -0.621, 0.621, -0.621])
        """
        x = np.array([self.cg_to_front if self._axle(c) == "front" else -self.cg_to_rear
                      for c in range(len(self.corners))])  # fmt: skip
        return x, self._lateral()

    def modal_positions(self) -> tuple[np.ndarray, np.ndarray | None]:
        """``(x, y)`` of every corner [m] over the body's motions: ``y`` is None for a body
        that does not roll (a half car).

        What a law over the body's modes takes
        (:func:`~mrsuspension.control.modal.distribution_matrix`,
        :meth:`ModalSkyhook.corner_equivalent
        <mrsuspension.control.modal.ModalSkyhook.corner_equivalent>`): the roll column
        only where there is a roll.

        Examples
        --------
        >>> HalfCar(cg_to_front=1.0, cg_to_rear=1.5).modal_positions()
        (array([ 1. , -1.5]), None)
        >>> x, y = FullCar().modal_positions()
        >>> y.tolist()
        [0.621, -0.621, 0.621, -0.621]
        """
        x, y = self.corner_positions()
        return x, (y if "roll" in self.body_dofs else None)

    def _lateral(self) -> np.ndarray:
        return np.zeros(len(self.corners))

    @property
    def unsprung_masses(self) -> np.ndarray:
        """``m_u`` of every corner [kg]."""
        return self._per_corner("unsprung_mass")

    @property
    def suspension_stiffnesses(self) -> np.ndarray:
        """``k_s`` of every corner [N/m]."""
        return self._per_corner("suspension_stiffness")

    @property
    def tire_stiffnesses(self) -> np.ndarray:
        """``k_t`` of every corner [N/m]."""
        return self._per_corner("tire_stiffness")

    @property
    def tire_dampings(self) -> np.ndarray:
        """``c_t`` of every corner [N s/m]."""
        return self._per_corner("tire_damping")

    def static_sprung_loads(self) -> np.ndarray:
        """Static share of the sprung weight at every corner [N].

        An axle carries ``m_s g b / L`` (front) or ``m_s g a / L`` (rear), split equally
        between its wheels (the centre of gravity on the centre line).

        Examples
        --------
        >>> HalfCar.from_quarter_car(QuarterCar()).static_sprung_loads().round(1).tolist()
        [5523.0, 5523.0]
        """
        share = {
            "front": self.cg_to_rear / self.wheelbase,
            "rear": self.cg_to_front / self.wheelbase,
        }
        per_axle = len(self.corners) // 2
        return np.array(
            [self.sprung_mass * GRAVITY * share[self._axle(c)] / per_axle
             for c in range(len(self.corners))]
        )  # fmt: skip

    def static_tire_loads(self) -> np.ndarray:
        """Static tire load of every corner (sprung share plus ``m_u g``) [N]."""
        return self.static_sprung_loads() + self.unsprung_masses * GRAVITY

    def static_tire_deflections(self) -> np.ndarray:
        """``W_i / k_t,i`` [m]: the tire's static compression (lift-off below it).

        Examples
        --------
        >>> (HalfCar.from_quarter_car(QuarterCar()).static_tire_deflections() * 100).round(2).tolist()
        [2.25, 2.25]
        """
        return self.static_tire_loads() / self.tire_stiffnesses

    def corner_quarter_car(self, corner: str) -> QuarterCar:
        """The quarter car of one corner: its static sprung share, wheel, spring and tire.

        With a decoupled mass distribution (:meth:`HalfCar.decoupled`) a corner moves as
        this quarter car when the road does not twist the body.

        Examples
        --------
        >>> qc = HalfCar.from_quarter_car(QuarterCar()).corner_quarter_car("rear")
        >>> qc == QuarterCar()
        True
        """
        c = self.corner_index(corner)
        return QuarterCar(
            sprung_mass=float(self.static_sprung_loads()[c] / GRAVITY),
            unsprung_mass=float(self.unsprung_masses[c]),
            suspension_stiffness=float(self.suspension_stiffnesses[c]),
            tire_stiffness=float(self.tire_stiffnesses[c]),
            tire_damping=float(self.tire_dampings[c]),
        )

    def corner_index(self, corner: str) -> int:
        """Position of ``corner`` in :attr:`corners` (unknown name: ``ValidationError``).

        Examples
        --------
        >>> FullCar().corner_index("rear_left")
        2
        >>> FullCar().corner_index("rear_lft")
        Traceback (most recent call last):
        ...
        mrsuspension.errors.ValidationError: unknown corner 'rear_lft'. Did you mean 'rear_left'? Valid: front_left, front_right, rear_left, rear_right.
        """
        if corner not in self.corners:
            raise unknown_name("corner", str(corner), self.corners)
        return self.corners.index(corner)

    def anti_roll_rates(self) -> np.ndarray:
        """``k_bar / t^2`` of every corner's axle [N/m] (0 without anti-roll bars)."""
        return np.zeros(len(self.corners))

    def body_transform(self) -> np.ndarray:
        """``T`` with ``z_s = T q_body``: the body's motion at the corners (corners x body).

        Examples
        --------
        >>> HalfCar(cg_to_front=1.0, cg_to_rear=1.5).body_transform().tolist()
        [[1.0, -1.0], [1.0, 1.5]]
        """
        x, y = self.corner_positions()
        cols = [np.ones_like(x), -x, y][: len(self.body_dofs)]
        return np.column_stack(cols)

    def body_inertia(self) -> np.ndarray:
        """Mass and inertias of the body DOFs [kg, kg m^2]."""
        return np.array([self.sprung_mass, self.pitch_inertia])

    # -- linear model ---------------------------------------------------------------------
    @property
    def dofs(self) -> tuple[str, ...]:
        """Degree-of-freedom names of :meth:`linear_matrices` (body, then the wheels)."""
        return (*self.body_dofs, *(f"z_u.{c}" for c in self.corners))

    def _damping_per_corner(
        self, damping: float | Sequence[float] | Mapping[str, float]
    ) -> np.ndarray:
        n = len(self.corners)
        if isinstance(damping, Mapping):
            rates = np.zeros(n)
            for key, value in damping.items():
                rates[self.corner_index(key)] = value
            missing = [c for c in self.corners if c not in damping]
            if missing:
                raise ValidationError(f"damping has no value for corner(s) {', '.join(missing)}")
        else:
            rates = np.broadcast_to(np.asarray(damping, dtype=float), (n,)).copy()
        return check_range("damping", rates, 0.0, 1e7, unit="N s/m")

    def linear_matrices(
        self, damping: float | Sequence[float] | Mapping[str, float]
    ) -> LinearModel:
        """``M, C, K`` and the road input matrices with a linear damper at every corner.

        Parameters
        ----------
        damping : float, sequence or mapping
            Damping rate ``c`` [N s/m] of every corner's damper (``F_d = c v_d``): one
            value for all, one per corner in :attr:`corners` order, or ``{corner: c}``.

        Returns
        -------
        LinearModel
            ``dofs, M, C, K, K_road, C_road`` (tire in contact, no lift-off).

        Examples
        --------
        >>> m = HalfCar().linear_matrices(1500.0)
        >>> m.dofs, m.K.shape, m.K_road.shape
        (('heave', 'pitch', 'z_u.front', 'z_u.rear'), (4, 4), (4, 2))
        >>> bool(np.allclose(m.K, m.K.T))
        True
        """
        c = self._damping_per_corner(damping)
        n = len(self.corners)
        nb = len(self.body_dofs)
        T = self.body_transform()
        D = np.zeros((n, nb + n))  # x_d = D q
        D[:, :nb] = -T
        D[:, nb:] = np.eye(n)
        K = D.T @ np.diag(self.suspension_stiffnesses) @ D
        C = D.T @ np.diag(c) @ D
        kbar = self.anti_roll_rates()
        for i in range(0, n - 1, 2):  # (left, right) pairs of the full car
            if kbar[i] > 0.0:
                r = D[i] - D[i + 1]
                K += kbar[i] * np.outer(r, r)
        kt, ct = self.tire_stiffnesses, self.tire_dampings
        K[nb:, nb:] += np.diag(kt)
        C[nb:, nb:] += np.diag(ct)
        Kr = np.zeros((nb + n, n))
        Cr = np.zeros((nb + n, n))
        Kr[nb:, :] = np.diag(kt)
        Cr[nb:, :] = np.diag(ct)
        M = np.diag(np.concatenate([self.body_inertia(), self.unsprung_masses]))
        return LinearModel(self.dofs, M, C, K, Kr, Cr)

    def frequency_response(
        self,
        frequency: npt.ArrayLike,
        damping: float | Sequence[float] | Mapping[str, float],
        road: npt.ArrayLike | None = None,
    ) -> dict[str, np.ndarray]:
        """Exact steady state of the linear vehicle to a harmonic road at every corner.

        Solves ``(-w^2 M + j w C + K) X = (K_road + j w C_road) Z_r`` at every frequency
        (closed form, no lift-off).

        Parameters
        ----------
        frequency : array_like
            Frequencies [Hz] (> 0).
        damping : float, sequence or mapping
            Linear damping rate of every corner [N s/m] (as :meth:`linear_matrices`).
        road : array_like, optional
            Complex road phasors ``Z_r`` per corner [m], shape ``(corners,)`` or
            ``(len(frequency), corners)`` (default: 1 at every corner, in phase). See
            :func:`delay_phasors` for a road reaching the rear wheels later.

        Returns
        -------
        dict of str to ndarray
            Complex amplitudes per frequency: every DOF (``heave`` [m], ``pitch`` and
            ``roll`` [rad], ``z_u.<corner>`` [m]), ``z_s.<corner>`` (the body at the
            corner), ``x_d.<corner>`` (stroke) and ``F_T.<corner>`` (tire force
            variation [N]).

        Examples
        --------
        The decoupled half car with the quarter car's corner is the quarter car:

        >>> from mrsuspension.vehicle import linear_frequency_response
        >>> car = HalfCar.from_quarter_car(QuarterCar())
        >>> r = car.frequency_response([1.5], 2500.0)
        >>> q = linear_frequency_response(QuarterCar(), 2500.0, [1.5])
        >>> bool(np.isclose(abs(r["z_s.front"][0]), q["T_as"][0], rtol=1e-12))
        True
        """
        f = np.atleast_1d(check_finite("frequency", frequency)).astype(float)
        if np.any(f <= 0.0):
            raise ValidationError(f"frequency must be > 0 Hz; got {float(f.min()):g} Hz")
        n = len(self.corners)
        if road is None:
            zr = np.ones((f.size, n), dtype=complex)
        else:
            zr = np.asarray(road, dtype=complex)
            if zr.shape == (n,):
                zr = np.broadcast_to(zr, (f.size, n))
            if zr.shape != (f.size, n):
                raise ValidationError(
                    f"road must have one phasor per corner ({n}), or per frequency and "
                    f"corner ({f.size}, {n}); got shape {np.shape(road)}"
                )
        lin = self.linear_matrices(damping)
        X = np.empty((f.size, len(lin.dofs)), dtype=complex)
        for k, fk in enumerate(f):
            w = 2.0 * math.pi * fk
            A = -(w**2) * lin.M + 1j * w * lin.C + lin.K
            X[k] = np.linalg.solve(A, (lin.K_road + 1j * w * lin.C_road) @ zr[k])
        out = {name: X[:, j] for j, name in enumerate(lin.dofs)}
        nb = len(self.body_dofs)
        zs = X[:, :nb] @ self.body_transform().T
        w = 2.0 * np.pi * f
        for i, c in enumerate(self.corners):
            zu = X[:, nb + i]
            out[f"z_s.{c}"] = zs[:, i]
            out[f"x_d.{c}"] = zu - zs[:, i]
            out[f"F_T.{c}"] = (self.tire_stiffnesses[i] + 1j * w * self.tire_dampings[i]) * (
                zr[:, i] - zu
            )
        return out

    def natural_frequencies(self) -> np.ndarray:
        """Undamped natural frequencies [Hz], ascending.

        Examples
        --------
        >>> HalfCar.from_quarter_car(QuarterCar()).natural_frequencies().round(2).tolist()
        [1.46, 1.46, 9.83, 9.83]
        """
        lin = self.linear_matrices(0.0)
        w2 = np.sort(np.linalg.eigvals(np.linalg.solve(lin.M, lin.K)).real)
        return np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi)


def _load_set(name: str) -> dict[str, float]:
    files = resources.files("mrsuspension.vehicle") / "data"
    known = {p.name.removesuffix(".toml"): p for p in files.iterdir() if p.name.endswith(".toml")}
    if name not in known:
        raise unknown_name("vehicle parameter set", name, known)
    data = tomllib.loads(known[name].read_text(encoding="utf-8"))
    return {k: float(v["value"]) for k, v in data["parameters"].items()}


def available_sets() -> list[str]:
    """Names of the published vehicle parameter sets (files in ``vehicle/data``).

    Examples
    --------
    >>> available_sets()
    ['full-car-kalman-2023']
    """
    files = resources.files("mrsuspension.vehicle") / "data"
    return sorted(p.name.removesuffix(".toml") for p in files.iterdir() if p.name.endswith(".toml"))


@dataclass(frozen=True)
class HalfCar(VehicleBody):
    """Half car: body heave and pitch, one wheel per axle (corners ``front``, ``rear``).

    Defaults: one side of the published full car of ``vehicle/data/full-car-kalman-2023.toml``
    (half its sprung mass and pitch inertia).

    Parameters
    ----------
    sprung_mass : float
        m_s [kg] (575).
    pitch_inertia : float
        I_y [kg m^2] (430.9), > 0.
    cg_to_front, cg_to_rear : float
        a and b [m]: centre of gravity to the front and rear axle (1.116, 1.232);
        ``a + b > 0``.
    front_unsprung_mass, rear_unsprung_mass : float
        m_u of the wheel [kg] (30.2, 49.7).
    front_suspension_stiffness, rear_suspension_stiffness : float
        k_s [N/m] (30 000, 32 500).
    front_tire_stiffness, rear_tire_stiffness : float
        k_t [N/m] (181 000).
    front_tire_damping, rear_tire_damping : float
        c_t [N s/m] (0).

    Examples
    --------
    >>> car = HalfCar()
    >>> car.corners, [round(w) for w in car.static_sprung_loads()]
    (('front', 'rear'), [2960, 2681])
    >>> HalfCar(pitch_inertia=-1.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: pitch_inertia must be in (0, 1e+07] kg m^2; got -1 kg m^2
    """

    corners: ClassVar[tuple[str, ...]] = CORNERS_HALF
    body_dofs: ClassVar[tuple[str, ...]] = ("heave", "pitch")

    sprung_mass: float = 575.0
    pitch_inertia: float = 430.9

    @classmethod
    def from_set(cls, name: str = _SET_FILE) -> HalfCar:
        """One side of a published full-car set (half its sprung mass and pitch inertia).

        Examples
        --------
        >>> HalfCar.from_set() == HalfCar()
        True
        """
        p = _load_set(name)
        keep = {f.name for f in fields(cls)}
        values = {k: v for k, v in p.items() if k in keep}
        values["sprung_mass"] = p["sprung_mass"] / 2.0
        values["pitch_inertia"] = p["pitch_inertia"] / 2.0
        return cls(**values)

    @classmethod
    def from_quarter_car(cls, car: QuarterCar, wheelbase: float = 2.348) -> HalfCar:
        """Two copies of a quarter car's corner with a decoupled body (I_y = m_s a b).

        ``m_s`` is twice the quarter car's, the centre of gravity midway (``a = b =
        wheelbase / 2``); each corner then moves as ``car`` under a road that reaches both
        wheels alike or with a delay (the quarter car's 563/90 kg corner as a consistent
        special case). The default wheelbase is the published set's.

        Examples
        --------
        >>> h = HalfCar.from_quarter_car(QuarterCar())
        >>> h.sprung_mass, round(h.pitch_inertia, 1)
        (1126.0, 1551.9)
        """
        half = (
            float(check_range("wheelbase", wheelbase, 0.0, 100.0, unit="m", low_inclusive=False))
            / 2.0
        )
        m = 2.0 * car.sprung_mass
        same = {f"{axle}_{k}": v for axle in ("front", "rear") for k, v in (
            ("unsprung_mass", car.unsprung_mass),
            ("suspension_stiffness", car.suspension_stiffness),
            ("tire_stiffness", car.tire_stiffness),
            ("tire_damping", car.tire_damping),
        )}  # fmt: skip
        return cls(sprung_mass=m, pitch_inertia=m * half * half, cg_to_front=half,
                   cg_to_rear=half, **same)  # fmt: skip

    def decoupled(self) -> HalfCar:
        """This car with ``I_y = m_s a b``: the corners then move independently.

        Examples
        --------
        >>> round(HalfCar().decoupled().pitch_inertia, 1)
        790.6
        """
        return self.with_(pitch_inertia=self.sprung_mass * self.cg_to_front * self.cg_to_rear)


@dataclass(frozen=True)
class FullCar(VehicleBody):
    """Full car: body heave, pitch and roll, four wheels, optional anti-roll bars.

    Defaults: the published passenger car of ``vehicle/data/full-car-kalman-2023.toml``
    (:meth:`from_set`; source and table in the file).

    Parameters
    ----------
    sprung_mass : float
        m_s [kg] (1150).
    pitch_inertia, roll_inertia : float
        I_y and I_x [kg m^2] (861.8, 330.5), > 0.
    cg_to_front, cg_to_rear : float
        a and b [m] (1.116, 1.232); ``a + b > 0``.
    front_track, rear_track : float
        Track widths [m] (1.242), > 0; the centre of gravity on the centre line.
    front_unsprung_mass, rear_unsprung_mass : float
        m_u of each wheel [kg] (30.2, 49.7).
    front_suspension_stiffness, rear_suspension_stiffness : float
        k_s at each wheel [N/m] (30 000, 32 500).
    front_tire_stiffness, rear_tire_stiffness : float
        k_t [N/m] (181 000).
    front_tire_damping, rear_tire_damping : float
        c_t [N s/m] (0).
    front_anti_roll_stiffness, rear_anti_roll_stiffness : float
        Anti-roll bar rate [N m/rad] of the axle (0: none).

    Examples
    --------
    >>> FullCar() == FullCar.from_set("full-car-kalman-2023")
    True
    >>> FullCar(cg_to_front=-1.5, cg_to_rear=1.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: wheelbase cg_to_front + cg_to_rear must be > 0 m; got -1.5 + 1 = -0.5 m
    """

    corners: ClassVar[tuple[str, ...]] = CORNERS_FULL
    body_dofs: ClassVar[tuple[str, ...]] = ("heave", "pitch", "roll")

    roll_inertia: float = 330.5
    front_track: float = 1.242
    rear_track: float = 1.242
    front_anti_roll_stiffness: float = 0.0
    rear_anti_roll_stiffness: float = 0.0

    @classmethod
    def from_set(cls, name: str = _SET_FILE) -> FullCar:
        """A published full-car set by name (:func:`available_sets`).

        Examples
        --------
        >>> FullCar.from_set("full-car-kalman-2023").sprung_mass
        1150.0
        """
        return cls(**_load_set(name))

    @classmethod
    def from_quarter_car(
        cls, car: QuarterCar, wheelbase: float = 2.348, track: float = 1.242
    ) -> FullCar:
        """Four copies of a quarter car's corner on a decoupled body.

        ``m_s`` is four times the quarter car's, the centre of gravity in the middle,
        ``I_y = m_s a b`` and ``I_x = m_s (t/2)^2`` (the body's mass at its four corners),
        no anti-roll bars: under a road that does not twist the body (the same at left and
        right, or the same at front and rear) each corner moves as ``car``.

        Examples
        --------
        >>> fc = FullCar.from_quarter_car(QuarterCar())
        >>> fc.sprung_mass, fc.corner_quarter_car("front_right") == QuarterCar()
        (2252.0, True)
        """
        base = HalfCar.from_quarter_car(car, wheelbase)
        t = float(check_range("track", track, 0.0, 20.0, unit="m", low_inclusive=False))
        m = 2.0 * base.sprung_mass
        values = {k: v for k, v in asdict(base).items()}
        values.update(sprung_mass=m, pitch_inertia=2.0 * base.pitch_inertia,
                      roll_inertia=m * (t / 2.0) ** 2, front_track=t, rear_track=t)  # fmt: skip
        return cls(**values)

    def decoupled(self) -> FullCar:
        """This car with ``I_y = m_s a b``, ``I_x = m_s t_f t_r / 4`` and no anti-roll bars.

        Examples
        --------
        >>> car = FullCar().decoupled()
        >>> round(car.pitch_inertia, 1), round(car.roll_inertia, 1)
        (1581.1, 443.5)
        """
        return self.with_(
            pitch_inertia=self.sprung_mass * self.cg_to_front * self.cg_to_rear,
            roll_inertia=self.sprung_mass * self.front_track * self.rear_track / 4.0,
            front_anti_roll_stiffness=0.0,
            rear_anti_roll_stiffness=0.0,
        )

    @property
    def track(self) -> float:
        """The front track [m]: the lateral spacing of the wheel tracks on the road.

        What :class:`~mrsuspension.excitation.WheelRoads` reads as the car's ``track``.
        The rear wheels follow the front wheels' tracks (delayed by wheelbase/speed), so
        when ``rear_track`` differs from ``front_track`` they are fed the road at the
        front track's spacing; the body's forces and moments still use each axle's own
        track.

        Examples
        --------
        >>> FullCar(front_track=1.5, rear_track=1.45).track
        1.5
        """
        return self.front_track

    def _lateral(self) -> np.ndarray:
        tf, tr = self.front_track / 2.0, self.rear_track / 2.0
        return np.array([tf, -tf, tr, -tr])

    def body_inertia(self) -> np.ndarray:
        """Mass and inertias of heave, pitch and roll [kg, kg m^2]."""
        return np.array([self.sprung_mass, self.pitch_inertia, self.roll_inertia])

    def anti_roll_rates(self) -> np.ndarray:
        """``k_bar / t^2`` of every corner's axle [N/m].

        Examples
        --------
        >>> FullCar(front_anti_roll_stiffness=15_000.0).anti_roll_rates().round(1).tolist()
        [9724.1, 9724.1, 0.0, 0.0]
        """
        f = self.front_anti_roll_stiffness / self.front_track**2
        r = self.rear_anti_roll_stiffness / self.rear_track**2
        return np.array([f, f, r, r])
