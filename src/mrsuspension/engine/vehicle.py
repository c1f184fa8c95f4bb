"""The half and full car in the engine: an MR damper and a controller at every corner.

:class:`VehicleSimulation` runs a :class:`~mrsuspension.vehicle.HalfCar` or
:class:`~mrsuspension.vehicle.FullCar` on a :class:`WheelInput` (a road per wheel, e.g.
:class:`~mrsuspension.excitation.WheelRoads`) with any damper model and controller at every corner; the
compiled step is :mod:`mrsuspension.engine.vehicle_kernel` (the quarter car's damper
kernels and control laws, corner by corner). Results are :class:`VehicleResult`: body
heave, pitch and roll and every corner's quarter-car signals, with units.

Examples
--------
>>> from mrsuspension.excitation import Harmonic, WheelRoads
>>> from mrsuspension.vehicle import FullCar
>>> car = FullCar()
>>> road = WheelRoads.from_excitation(Harmonic(1.5, 0.01), car, speed_kmh=72.0)
>>> res = VehicleSimulation(car, road).run(1.0, dt=2e-4)
>>> float(res.time[-1]), res.corners[0]
(1.0, 'front_left')
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

import numpy as np
import numpy.typing as npt

from mrsuspension._numba_cache import announce_compile
from mrsuspension.control import Controller, Passive
from mrsuspension.control.kernel import F_EXTERNAL, F_TARGET
from mrsuspension.control.modal import VehicleLaw, distribution_matrix
from mrsuspension.control.sensing import (
    BandPassObserver,
    LeakyIntegrator,
    Sensing,
    StrokeSensor,
    band_pass_coefficients,
    leaky_integrator_coefficients,
)
from mrsuspension.control.user import raise_failure
from mrsuspension.dampers import DamperModel, WangSymmetric
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine import kernel as EK
from mrsuspension.engine import vehicle_kernel as VX
from mrsuspension.engine.kernel import N_ACC
from mrsuspension.engine.lanes import ROAD_CHUNK
from mrsuspension.engine.reduced import finish, new_accumulators, reduction_of
from mrsuspension.engine.result import SIGNALS, SimulationDiverged, warn_if_aliased
from mrsuspension.engine.settings import (
    DEFAULT_DT,
    RK4_LIMIT,
    RunPlan,
    RunSettings,
    check_memory,
    check_step,
    run_settings,
)
from mrsuspension.engine.simulate import Reducer, Simulation, _in_kernel, check_inverse_damper
from mrsuspension.engine.vehicle_result import (
    BODY_COLUMNS,
    BODY_MEASURES,
    BODY_SIGNALS,
    CORNER_COLUMNS,
    SENSED_COLUMNS,
    VEHICLE_CORNER_SIGNALS,
    VehicleResult,
)
from mrsuspension.errors import ValidationError, check_range, unknown_name
from mrsuspension.vehicle.body import CORNERS_FULL, CORNERS_HALF, FullCar, HalfCar, VehicleBody

if TYPE_CHECKING:
    pass

__all__ = [
    "CORNERS_FULL",
    "CORNERS_HALF",
    "ROAD_CHUNK",
    "VehicleArrays",
    "VehicleSimulation",
    "VehicleStepper",
    "WheelInput",
    "measure_vehicles",
    "run_vehicles",
]


@runtime_checkable
class WheelInput(Protocol):
    """A road input per wheel: what :class:`VehicleSimulation` needs from an excitation.

    ``corners`` names the wheels (the vehicle's :attr:`~VehicleBody.corners`, in that
    order); ``displacement(t)`` and ``velocity(t)`` return ``(len(corners), len(t))``
    arrays [m, m/s], up positive; ``duration`` is the input's natural length [s] (None:
    unbounded).
    """

    @property
    def corners(self) -> tuple[str, ...]: ...

    def displacement(self, t: npt.ArrayLike) -> np.ndarray: ...
    def velocity(self, t: npt.ArrayLike) -> np.ndarray: ...

    @property
    def duration(self) -> float | None: ...


@dataclass(frozen=True)
class _CornerRoad:
    """One wheel of a :class:`WheelInput` as a quarter-car road input (for checks and
    the per-corner result)."""

    wheels: Any
    index: int

    def displacement(self, t: npt.ArrayLike) -> np.ndarray:
        return np.asarray(self.wheels.displacement(t), dtype=float)[self.index]

    def velocity(self, t: npt.ArrayLike) -> np.ndarray:
        return np.asarray(self.wheels.velocity(t), dtype=float)[self.index]

    def acceleration(self, t: npt.ArrayLike) -> np.ndarray:
        acc = getattr(self.wheels, "acceleration", None)
        if acc is not None:
            return np.asarray(acc(t), dtype=float)[self.index]
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        return np.gradient(self.velocity(tt), tt) if tt.size > 1 else np.zeros(tt.size)

    def describe(self) -> dict[str, Any]:
        base = getattr(self.wheels, "excitation", None)
        if base is not None and hasattr(base, "describe"):
            return dict(base.describe())  # same kind (and measures) as the quarter car's
        describe = getattr(self.wheels, "describe", None)
        # a road per wheel without one quarter-car excitation: the road measures
        return {"kind": "road", "wheels": describe() if describe else repr(self.wheels)}

    @property
    def duration(self) -> float:
        d = self.wheels.duration
        return math.inf if d is None else float(d)


#: the body's accumulator (``vehicle_kernel.BA_*``) of each signal of :data:`BODY_MEASURES`
_BODY_SUMS = {"heave_ddot": VX.BA_AZ2, "pitch_ddot": VX.BA_APITCH2, "roll_ddot": VX.BA_AROLL2}


@dataclass(frozen=True, eq=False)
class VehicleArrays:
    """The vehicle step's arrays by name (rows: corners), in the kernels' order.

    ``vehicle`` (``vp``), ``corner_vehicles`` (``cvp``: every corner's quarter car),
    ``force_source`` (``fk``), ``damper_kind`` (``dk``), ``damper_params`` (``dp``),
    ``damper_state`` (``ds``), the damper estimator's ``dek, dep, des``, the
    controller's ``ck, cp`` and its estimator's ``cek, cep, ces``, ``memory``
    (``mem``, the quarter car's ``M_*`` layout per corner), then sensing and the
    vehicle-level law: ``sensing_kind`` (``sk``), ``sensing_params`` (``sp``),
    ``sensing_state`` (``ss``), ``stroke_noise``, ``modal_distribution`` and
    ``modal_buffer`` (:mod:`~mrsuspension.engine.vehicle_kernel` ``SK_*``, ``SP_*``). See
    :class:`~mrsuspension.engine.arrays.KernelArrays` for the quarter car's.
    """

    vehicle: np.ndarray
    corner_vehicles: np.ndarray
    force_source: np.ndarray
    damper_kind: np.ndarray
    damper_params: np.ndarray
    damper_state: np.ndarray
    damper_estimator_kind: np.ndarray
    damper_estimator_params: np.ndarray
    damper_estimator_state: np.ndarray
    controller_kind: np.ndarray
    controller_params: np.ndarray
    controller_estimator_kind: np.ndarray
    controller_estimator_params: np.ndarray
    controller_estimator_state: np.ndarray
    memory: np.ndarray
    sensing_kind: np.ndarray
    sensing_params: np.ndarray
    sensing_state: np.ndarray
    stroke_noise: np.ndarray
    modal_distribution: np.ndarray
    modal_buffer: np.ndarray

    def args(self) -> tuple[Any, ...]:
        """The arrays in the order of :func:`~mrsuspension.engine.vehicle_kernel.step` and
        :func:`~mrsuspension.engine.vehicle_kernel.run` (``vp`` to ``mem``)."""
        return (
            self.vehicle, self.corner_vehicles, self.force_source, self.damper_kind,
            self.damper_params, self.damper_state, self.damper_estimator_kind,
            self.damper_estimator_params, self.damper_estimator_state, self.controller_kind,
            self.controller_params, self.controller_estimator_kind,
            self.controller_estimator_params, self.controller_estimator_state, self.memory,
            self.sensing_kind, self.sensing_params, self.sensing_state, self.stroke_noise,
            self.modal_distribution, self.modal_buffer,
        )  # fmt: skip


def _stack(rows: Sequence[np.ndarray], dtype: Any = float) -> np.ndarray:
    """Rows of different lengths padded with zeros into one C-contiguous 2-D array."""
    width = max(1, *(np.size(r) for r in rows))
    out = np.zeros((len(rows), width), dtype=dtype)
    for i, r in enumerate(rows):
        out[i, : np.size(r)] = r
    return out


def _per_corner(
    what: str, value: Any, kind: type, corners: tuple[str, ...], default: Any
) -> list[Any]:
    """One object for every corner from an object or a ``{corner: object}`` mapping."""
    if isinstance(value, Mapping):
        for key in value:
            if key not in corners:
                raise unknown_name("corner", str(key), corners)
        chosen = [value.get(c, default) for c in corners]
    else:
        chosen = [value] * len(corners)
    for c, v in zip(corners, chosen, strict=True):
        if not isinstance(v, kind):
            raise ValidationError(
                f"{what} for corner {c!r} must be a {kind.__name__} object; got {v!r}"
            )
    return chosen


@dataclass(frozen=True)
class VehicleSimulation:
    """A half or full car with a damper and a controller at every corner on a wheel input.

    Parameters
    ----------
    vehicle : HalfCar or FullCar
        The vehicle (its :attr:`~VehicleBody.corners` name the wheels).
    excitation : WheelInput
        Road per wheel, e.g. :class:`~mrsuspension.excitation.WheelRoads`; its ``corners`` must be the
        vehicle's, in order.
    dampers : DamperModel or mapping of corner to DamperModel, optional
        One model for every corner or ``{corner: model}`` (corners left out get the
        default): the dissertation's symmetric model with the vehicle ``v_h`` variant, as
        the quarter car's :class:`~mrsuspension.engine.simulate.Simulation`.
    controllers : Controller or mapping of corner to Controller, optional
        Likewise (default: passive at 0 A). Each corner runs its own instance on the
        body's motion at that corner.
    max_current : float
        Drive-current limit i_max [A] of every corner (0.5).
    sensing : Sensing, optional
        What the controllers measure (default: ideal, the true body velocity and
        stroke): :class:`~mrsuspension.control.sensing.Sensing` with a body-velocity
        estimator from each corner's accelerometer and a stroke sensor.
    body_control : VehicleLaw, optional
        A law over the whole vehicle instead of the corners' controllers (which must
        then be left passive), a plug-in of
        :data:`~mrsuspension.control.registry.VEHICLE_LAWS`: e.g. modal skyhook from the
        body's heave, pitch and roll velocities, or on-off skyhook at every corner; hi-lo
        currents per corner (:mod:`mrsuspension.control.modal`), from the sensed
        velocities. It is attached to the vehicle (:meth:`VehicleLaw.for_vehicle
        <mrsuspension.control.modal.VehicleLaw.for_vehicle>`: e.g. modal skyhook's gains
        from the car's geometry when none is given).

    Raises
    ------
    ValidationError
        An unknown corner name, a wheel input for other corners, or a damper or
        controller the quarter car would refuse.

    Examples
    --------
    >>> from mrsuspension.control import HiLo
    >>> from mrsuspension.excitation import Harmonic, WheelRoads
    >>> from mrsuspension.vehicle import FullCar
    >>> car = FullCar()
    >>> road = WheelRoads.from_excitation(Harmonic(1.5, 0.01), car, speed_kmh=54.0)
    >>> sim = VehicleSimulation(car, road, controllers={"front_left": HiLo(1)})
    >>> res = sim.run(1.0, dt=2e-4)
    >>> bool(res["i_d.front_left"].max() > 0.0), float(res["i_d.rear_right"].max())
    (True, 0.0)
    >>> VehicleSimulation(car, road, controllers={"front_lef": HiLo(1)})
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown corner 'front_lef'. Did you mean 'front_left'? Valid: front_left, front_right, rear_left, rear_right.
    """

    vehicle: VehicleBody
    excitation: WheelInput
    dampers: DamperModel | Mapping[str, DamperModel] = field(
        default_factory=lambda: WangSymmetric(vh_variant=VEHICLE_VH_VARIANT)
    )
    controllers: Controller | Mapping[str, Controller] = field(default_factory=Passive)
    max_current: float = 0.5
    sensing: Sensing = field(default_factory=Sensing)
    body_control: VehicleLaw | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.vehicle, HalfCar | FullCar):
            raise ValidationError(
                f"vehicle must be a HalfCar or FullCar object; got {self.vehicle!r}"
            )
        corners = self.vehicle.corners
        wheels = getattr(self.excitation, "corners", None)
        if not isinstance(self.excitation, WheelInput) or wheels is None:
            raise ValidationError(
                "excitation must be a wheel input (corners, displacement(t), velocity(t), "
                "duration), e.g. WheelRoads.from_excitation(Harmonic(1.5, 0.025), vehicle, "
                f"speed_kmh=50.0) or WheelRoads.in_phase(Harmonic(1.5, 0.025), {corners}); "
                f"got {self.excitation!r}"
            )
        for w in wheels:
            if w not in corners:
                raise unknown_name("corner", str(w), corners)
        if tuple(wheels) != corners:
            raise ValidationError(
                f"excitation corners must be the vehicle's, in order {corners}; got {tuple(wheels)}"
            )
        default_damper = WangSymmetric(vh_variant=VEHICLE_VH_VARIANT)
        dampers = _per_corner("damper", self.dampers, DamperModel, corners, default_damper)
        controllers = _per_corner("controller", self.controllers, Controller, corners, Passive())
        # every corner as the quarter car checks it (current limit, inverse-model needs)
        sims = tuple(
            Simulation(_CornerRoad(self.excitation, i), self.vehicle.corner_quarter_car(c),
                       dampers[i], controllers[i], self.max_current)
            for i, c in enumerate(corners)
        )  # fmt: skip
        object.__setattr__(self, "_corners", sims)
        self._check_sensing_and_law(controllers)

    @property
    def model_name(self) -> str:
        """``"half-car"`` or ``"full-car"``: the :class:`~mrsuspension.engine.plants.Plant`
        of this run."""
        return str(self.vehicle.model_name)

    @property
    def corners(self) -> tuple[str, ...]:
        """The vehicle's corner names."""
        return self.vehicle.corners

    def corner_simulation(self, corner: str) -> Simulation:
        """The quarter-car simulation of one corner (its damper, controller, wheel road).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> sim.corner_simulation("rear").vehicle.unsprung_mass
        49.7
        """
        sims: tuple[Simulation, ...] = self.__dict__["_corners"]
        return sims[self.vehicle.corner_index(corner)]

    def max_stable_dt(self) -> float:
        """Largest stable RK4 step [s]: the stiffest corner's (anti-roll bars included).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import FullCar
        >>> sim = VehicleSimulation(FullCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "full-car"))
        >>> sim.max_stable_dt() > 1e-4
        True
        """
        out = math.inf
        bar = self.vehicle.anti_roll_rates()
        for i, c in enumerate(self.corners):
            sim = self.corner_simulation(c)
            car = sim.vehicle
            rate = sim.stiffness_rate()
            omega = math.sqrt(
                (car.suspension_stiffness + 2.0 * bar[i] + car.tire_stiffness) / car.unsprung_mass
            )
            out = min(out, RK4_LIMIT / max(rate, omega))
        return out

    def check_dt(self, dt: float) -> float:
        """Validate ``dt``: positive, at most 10 ms and stable for this vehicle.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> sim.check_dt(1e-4)
        0.0001
        """
        dt = check_step(dt)
        limit = self.max_stable_dt()
        if dt > limit:
            raise ValidationError(
                f"dt = {dt:g} s is too large for stability: the stiffest corner of this vehicle "
                f"needs dt <= {limit:.3g} s"
            )
        return dt

    def describe(self) -> dict[str, Any]:
        """Plain-data description: vehicle, wheel input, and every corner's set-up.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> d = sim.describe()
        >>> d["vehicle"]["model"], d["corners"]["rear"]["controller"]["law"]
        ('half-car', 'passive')
        """
        desc = getattr(self.excitation, "describe", None)
        return {
            "vehicle": self.vehicle.describe(),
            "excitation": desc() if desc is not None else repr(self.excitation),
            "max_current": self.max_current,
            **self._describe_sensing_and_law(),
            "corners": {
                c: {
                    "damper": self.corner_simulation(c).damper.describe(),
                    "controller": self.corner_simulation(c).controller.describe(),
                }
                for c in self.corners
            },
        }

    def _describe_sensing_and_law(self) -> dict[str, Any]:
        """``sensing`` and ``body_control`` of :meth:`describe` (omitted when ideal / none,
        so that earlier descriptions are unchanged)."""
        out: dict[str, Any] = {}
        if not self.sensing.is_ideal:
            out["sensing"] = self.sensing.describe()
        if self.body_control is not None:
            out["body_control"] = self.body_control.describe()
        return out

    def arrays(self, dt: float, *, n_steps: int | None = None) -> VehicleArrays:
        """The compiled step's arrays at step ``dt`` (fresh states), by name.

        ``n_steps``: the run's length, for the stroke sensor's noise (default: 65536
        readings, used cyclically by a stepper).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import FullCar
        >>> sim = VehicleSimulation(FullCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "full-car"))
        >>> a = sim.arrays(1e-4)
        >>> a.memory.shape, a.corner_vehicles.shape
        ((4, 44), (4, 8))
        """
        car = self.vehicle
        n = len(car.corners)
        ka = [
            self.corner_simulation(c).kernel_arrays(dt, check_stability=False) for c in car.corners
        ]
        vp = np.zeros(VX.B_SIZE + VX.CORNER_SIZE * n)
        vp[VX.B_INV_M] = 1.0 / car.sprung_mass
        vp[VX.B_INV_IY] = 1.0 / car.pitch_inertia
        vp[VX.B_INV_IX] = 1.0 / getattr(car, "roll_inertia", 1.0)  # half car: no roll (y = 0)
        vp[VX.B_NC] = n
        x, y = car.corner_positions()
        bar = car.anti_roll_rates()
        dxu = car.static_tire_deflections()
        weight = car.static_tire_loads()
        for i in range(n):
            o = VX.B_SIZE + VX.CORNER_SIZE * i
            vp[o + VX.C_X], vp[o + VX.C_Y] = x[i], y[i]
            vp[o + VX.C_INV_MU] = 1.0 / car.unsprung_masses[i]
            vp[o + VX.C_KS] = car.suspension_stiffnesses[i]
            vp[o + VX.C_KT] = car.tire_stiffnesses[i]
            vp[o + VX.C_CT] = car.tire_dampings[i]
            vp[o + VX.C_DXU] = dxu[i]
            vp[o + VX.C_W] = weight[i]
            vp[o + VX.C_BAR] = bar[i]
            vp[o + VX.C_PARTNER] = i ^ 1 if n == 4 else i  # left/right pairs of the full car
        ints = np.int64
        force_source = np.array([a.force_source for a in ka], dtype=ints)
        if self.body_control is not None and self.body_control.active:
            force_source[:] = F_TARGET  # an ideal actuator at every corner: the law's force
        return VehicleArrays(
            vehicle=vp,
            corner_vehicles=_stack([a.vehicle for a in ka]),
            force_source=force_source,
            damper_kind=np.array([a.damper_kind for a in ka], dtype=ints),
            damper_params=_stack([a.damper_params for a in ka]),
            damper_state=_stack([a.damper_state for a in ka]),
            damper_estimator_kind=np.array([a.damper_estimator_kind for a in ka], dtype=ints),
            damper_estimator_params=_stack([a.damper_estimator_params for a in ka]),
            damper_estimator_state=_stack([a.damper_estimator_state for a in ka]),
            controller_kind=np.array([a.controller_kind for a in ka], dtype=ints),
            controller_params=_stack([a.controller_params for a in ka]),
            controller_estimator_kind=np.array(
                [a.controller_estimator_kind for a in ka], dtype=ints
            ),
            controller_estimator_params=_stack([a.controller_estimator_params for a in ka]),
            controller_estimator_state=_stack([a.controller_estimator_state for a in ka]),
            memory=_stack([a.memory for a in ka]),
            **self._sensing_arrays(dt, n_steps),
        )

    def _check_sensing_and_law(self, controllers: Sequence[Controller]) -> None:
        """Validate ``sensing`` and ``body_control`` (the corners' controllers given)."""
        if not isinstance(self.sensing, Sensing):
            raise ValidationError(
                "sensing must be a Sensing object (mrsuspension.control.sensing), e.g. "
                f"Sensing(LeakyIntegrator(tau=0.92, fs=1000.0)); got {self.sensing!r}"
            )
        law = self.body_control
        if law is None:
            return
        if not isinstance(law, VehicleLaw):
            raise ValidationError(
                "body_control must be a whole-vehicle law (mrsuspension.control.VEHICLE_LAWS: "
                f"ModalSkyhook, CornerSkyhook, VehicleLQ...); got {law!r}"
            )
        law = law.for_vehicle(self.vehicle)  # e.g. gains from the car's geometry
        object.__setattr__(self, "body_control", law)
        if law.needs_inverse:  # every corner's damper through its inverse model
            for c, sim in zip(self.corners, self.__dict__["_corners"], strict=True):
                check_inverse_damper(law.law, sim.damper, f" at corner {c}")
        busy = [
            c for c, k in zip(self.corners, controllers, strict=True) if not isinstance(k, Passive)
        ]
        if busy:
            raise ValidationError(
                f"body_control sets every corner's current: leave the corners' controllers "
                f"passive; got controllers at {', '.join(busy)}"
            )
        if law.high_current > self.max_current:
            raise ValidationError(
                f"body_control high_current must be at most max_current = {self.max_current:g} A; "
                f"got {law.high_current:g} A"
            )

    def _sample_every(self, what: str, fs: float, dt: float) -> int:
        """Steps per sample of a sensor at ``fs`` [Hz]: ``1/(fs dt)``, a whole number."""
        ratio = 1.0 / (fs * dt)
        steps = round(ratio)
        if steps < 1 or abs(ratio - steps) > 1e-6 * ratio:
            raise ValidationError(
                f"{what} fs = {fs:g} Hz must divide the step rate 1/dt = {1.0 / dt:g} Hz "
                f"(a whole number of steps per sample)"
            )
        return int(steps)

    def _sensing_arrays(self, dt: float, n_steps: int | None) -> dict[str, np.ndarray]:
        """The ``sensing_*``, ``stroke_noise`` and ``modal_*`` arrays of :meth:`arrays`."""
        nc = len(self.corners)
        law = self.body_control
        law_params = law.params() if law is not None else np.zeros(0)
        sk = np.zeros(VX.SK_SIZE, dtype=np.int64)
        sp = np.zeros(max(VX.SP_SIZE, VX.SP_MP + law_params.size))  # a law's own params after
        sk[VX.SK_ACC_EVERY] = 1
        est = self.sensing.velocity
        if isinstance(est, LeakyIntegrator):
            sk[VX.SK_KIND] = VX.SENSE_LEAKY
            sp[VX.SP_COEF : VX.SP_COEF + 2] = leaky_integrator_coefficients(est.tau, est.fs)
        elif isinstance(est, BandPassObserver):
            sk[VX.SK_KIND] = VX.SENSE_BAND_PASS
            sp[VX.SP_COEF : VX.SP_RES] = band_pass_coefficients(est.corner, est.fs, est.zeta)
        if est is not None:
            sk[VX.SK_ACC_EVERY] = self._sample_every("the accelerometer's", est.fs, dt)
        noise = np.zeros((nc, 1))
        stroke = self.sensing.stroke
        if stroke is not None:
            every = self._sample_every("the stroke sensor's", stroke.fs, dt)
            sk[VX.SK_STROKE_EVERY] = every
            sp[VX.SP_RES], sp[VX.SP_SFS] = stroke.resolution, stroke.fs
            m = 65536 if n_steps is None else n_steps // every + 1
            noise = np.stack([
                StrokeSensor(stroke.fs, stroke.resolution, stroke.noise_std, stroke.seed + i).noise(m)
                for i in range(nc)
            ])  # fmt: skip
        dist = np.zeros((nc, 3))
        if law is not None:
            sk[VX.SK_LAW] = law.kernel_code
            sp[VX.SP_MP :] = law_params
        if (law is not None and law.uses_body_rates) or est is not None:
            dist = distribution_matrix(*self.vehicle.modal_positions())
        return {
            "sensing_kind": sk,
            "sensing_params": sp,
            "sensing_state": np.zeros((2 * nc + 1, VX.SS_WIDTH)),
            "stroke_noise": np.ascontiguousarray(noise),
            "modal_distribution": np.ascontiguousarray(dist),
            "modal_buffer": np.zeros((4, nc) if law is None else law.buffer_shape(nc)),
        }

    def initial_state(self, zr0: np.ndarray) -> np.ndarray:
        """Static equilibrium on the roads ``zr0`` at the wheels: wheels on their road,
        the body through the axles' mean heights (pitch) and tilted by the mean left-right
        difference (roll, exactly 0 when both sides are the same).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> car = HalfCar(cg_to_front=1.0, cg_to_rear=1.0)
        >>> sim = VehicleSimulation(car, WheelRoads.in_phase(Harmonic(2.0, 0.01), car))
        >>> sim.initial_state(np.array([0.0, 0.02]))[:2].tolist()  # heave, pitch
        [0.01, 0.01]
        """
        car = self.vehicle
        n = len(self.corners)
        y = np.zeros(VX.NB + VX.NQ * n)
        if isinstance(car, FullCar):
            front, rear = 0.5 * (zr0[0] + zr0[1]), 0.5 * (zr0[2] + zr0[3])
            y[2] = 0.5 * ((zr0[0] - zr0[1]) / car.front_track + (zr0[2] - zr0[3]) / car.rear_track)
        else:
            front, rear = zr0[0], zr0[1]
        a, b, wheelbase = car.cg_to_front, car.cg_to_rear, car.wheelbase
        y[0] = (b * front + a * rear) / wheelbase  # z - a theta = front, z + b theta = rear
        y[1] = (rear - front) / wheelbase
        for i in range(n):
            y[VX.NB + VX.NQ * i] = zr0[i]
            y[VX.NB + VX.NQ * i + 2] = zr0[i]
        return y

    def stepper(self, dt: float = DEFAULT_DT, *, external: str | None = None) -> VehicleStepper:
        """Tick-by-tick access to the same compiled step (a real-time or HiL loop).

        ``external`` names a corner whose damper force is given at every tick (the
        measured force of a physical damper on the rig); the other corners are simulated.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> road = WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car")
        >>> st = VehicleSimulation(HalfCar(), road).stepper(1e-4, external="rear")
        >>> out = st.step([0.0, 0.0], [0.1, 0.1], damper_force=120.0)
        >>> out["F_d.rear"], sorted(out)[:3]
        (120.0, ['F_T.front', 'F_T.rear', 'F_d.front'])
        """
        return VehicleStepper(self, dt, external=external)

    def run(
        self,
        duration: float | None = None,
        *,
        dt: float | None = None,
        output_rate: float | None = None,
        settings: RunSettings | None = None,
    ) -> VehicleResult:
        """Simulate for ``duration`` seconds (default: the wheel input's own duration).

        Parameters
        ----------
        duration : float, optional
            Simulated time [s].
        dt : float, optional
            Fixed RK4 step [s] (default 1e-4, model reference, section 7); checked for stability.
        output_rate : float, optional
            Samples per second kept in the result (default 1 kHz; at most 1/dt).
        settings : RunSettings, optional
            ``duration``, ``dt`` and ``output_rate`` in one object (instead of the three
            keywords; giving both is an error), as :meth:`Simulation.run
            <mrsuspension.engine.Simulation.run>`.

        Raises
        ------
        ValidationError
            Settings out of range, a ``dt`` too large for this vehicle, a record that
            would alias the wheel input's excitation, or a wheel input returning arrays of
            the wrong shape or non-finite values.
        SimulationDiverged
            When a state or force leaves the physical range (says when and which).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> res = sim.run(0.5, dt=2e-4, output_rate=100.0)
        >>> res.time.size, res.units["pitch"]
        (51, 'rad')
        >>> sim.run(settings=RunSettings(dt=2e-4, duration=0.5, output_rate=100.0)).time.size
        51
        """
        plan = self._plan(settings, duration, dt, output_rate)
        nc = len(self.corners)
        rec = np.zeros((plan.rows, VX.REC_BODY + VX.REC_CORNER * nc))
        self._drive(plan, (False, rec, np.zeros((0, N_ACC)), np.zeros((0, VX.RED_SIZE)),
                           np.zeros((0, 0))))  # fmt: skip
        return self.result_from_record(plan.time(), rec, plan.dt)

    def run_measures(
        self,
        duration: float | None = None,
        *,
        dt: float | None = None,
        output_rate: float | None = None,
        settings: RunSettings | None = None,
        road_peak: str = "after-onset",
    ) -> dict[str, Any]:
        """``self.run(...).measures(road_peak=...)`` reduced in the kernel: no time history.

        The same arguments as :meth:`run` (``road_peak``: ``"after-onset"`` or ``"onset"``,
        as :meth:`SimulationResult.measures
        <mrsuspension.engine.result.SimulationResult.measures>` takes it) and the same
        measures as :meth:`VehicleResult.measures` (the body's RMS accelerations, then every
        corner's quarter-car measures keyed ``"<measure>.<corner>"``), equal to round-off
        (sums in another order). Every corner accumulates what its measures need at each
        output sample with the quarter car's accumulators
        (:func:`~mrsuspension.engine.kernel.accumulate`, finished by
        :func:`~mrsuspension.engine.reduced.finish`), the body its squared
        accelerations, and the road is sampled a piece at a time: the memory of a run
        does not grow with its duration (but for a road profile's corner body
        accelerations, one signal per corner, which the ISO 2631 weighting filters).

        Raises
        ------
        ValidationError
            As :meth:`run` and :meth:`VehicleResult.measures` (a harmonic run too short
            for the steady-state rule is refused before it runs).
        SimulationDiverged
            As :meth:`run`.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(5.0, 0.005), "half-car"))
        >>> fast = sim.run_measures(dt=2e-4)
        >>> slow = sim.run(dt=2e-4).measures()
        >>> bool(abs(fast["T_as.rear"] / slow["T_as.rear"] - 1.0) < 1e-12), list(fast)[:2]
        (True, ['heave_ddot_rms', 'pitch_ddot_rms'])
        """
        from mrsuspension.measures import check_road_peak

        how = check_road_peak(road_peak)
        plan = self._plan(settings, duration, dt, output_rate)
        nc = len(self.corners)
        reductions = [reduction_of(self.corner_simulation(c), plan) for c in self.corners]
        acc = new_accumulators(nc + 1)
        acc[nc] = 0.0  # the body's sums (VX.BA_*)
        red = np.array([[r.window_start, r.shift, r.threshold] for r in reductions])
        trace = np.zeros((nc, plan.rows if any(r.trace for r in reductions) else 0))
        rec = np.zeros((0, VX.REC_BODY + VX.REC_CORNER * nc))
        self._drive(plan, (True, rec, acc, red, trace))
        body = acc[nc]
        out: dict[str, Any] = {}
        for name, (signal, _) in BODY_MEASURES.items():
            if signal == "roll_ddot" and nc < 4:
                continue  # a half car has no roll (as VehicleResult.measures)
            out[name] = float(np.sqrt(body[_BODY_SUMS[signal]] / body[VX.BA_N]))
        for i, (c, r) in enumerate(zip(self.corners, reductions, strict=True)):
            road = _CornerRoad(self.excitation, i).acceleration
            for k, v in finish(r, acc[i], trace[i], road, how).items():
                out[f"{k}.{c}"] = v
        return out

    def _plan(
        self,
        settings: RunSettings | None,
        duration: float | None,
        dt: float | None,
        output_rate: float | None,
    ) -> RunPlan:
        """The checked plan of a run (:meth:`run`'s arguments); says so when it compiles."""
        run = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
        run.check_for(getattr(self.excitation, "excitation", self.excitation))
        plan = run.plan(self)
        announce_compile(VX.__file__, "run")  # a first run says why it waits
        return plan

    def road_samples(
        self, steps: int, dt: float, *, first: int = 0
    ) -> tuple[np.ndarray, np.ndarray]:
        """Every wheel's road ``(z_r, z_r')`` at every half step of steps ``first`` to
        ``first + steps``: two ``(corners, 2 steps + 1)`` arrays (the wheel input's fast
        grid where it has one).

        Raises
        ------
        ValidationError
            A wheel input returning arrays of the wrong shape or non-finite values.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> zr, zrd = sim.road_samples(10, 1e-3, first=5)  # t = 5 ms to 15 ms
        >>> zr.shape, bool(np.allclose(zr[0, 0], 0.01 * np.sin(2 * np.pi * 2.0 * 5e-3)))
        ((2, 21), True)
        """
        nc = len(self.corners)
        m = 2 * steps + 1
        start = first * dt
        grid = getattr(self.excitation, "sample_grid", None)
        if grid is not None:  # the wheel input's fast grid
            zr, zrd = grid(m, 0.5 * dt) if first == 0 else grid(m, 0.5 * dt, start)
        else:
            t_half = start + np.arange(m) * (0.5 * dt)
            zr, zrd = self.excitation.displacement(t_half), self.excitation.velocity(t_half)
        zr = np.ascontiguousarray(zr, dtype=float)
        zrd = np.ascontiguousarray(zrd, dtype=float)
        if zr.shape != (nc, m) or zrd.shape != zr.shape:
            raise ValidationError(
                f"the wheel input must return ({nc}, len(t)) arrays; got {zr.shape} and {zrd.shape}"
            )
        if not (np.all(np.isfinite(zr)) and np.all(np.isfinite(zrd))):
            raise ValidationError("the wheel input returned a NaN or infinite road value")
        return zr, zrd

    def _drive(self, plan: RunPlan, out: tuple[Any, ...]) -> None:
        """Drive a run of ``plan`` through :func:`~mrsuspension.engine.vehicle_kernel.run`,
        :data:`ROAD_CHUNK` steps of road at a time; ``out`` are its output arguments
        (``reduced`` to ``trace``). Raises the run's :class:`SimulationDiverged`."""
        dt, n, decimate = plan
        nc = len(self.corners)
        a = self.arrays(dt, n_steps=n)
        args = a.args()
        scratch: np.ndarray | None = None
        work = np.zeros((nc + 1, 8))
        first = 0
        while first == 0 or first < n:
            steps = min(ROAD_CHUNK, n - first)
            zr, zrd = self.road_samples(steps, dt, first=first)
            if first == 0:
                y = self.initial_state(zr[:, 0])
                scratch = np.zeros((3, y.size))
            status, k, idx, value = VX.run(
                y, first, steps, dt, zr, zrd, *args, decimate, VX.LIMITS, scratch, work, *out
            )
            raise_failure()  # a Python control law that raised (the run stopped there)
            if status != VX.D_OK:
                raise self._divergence(status, k * dt, idx, value, dt)
            first += steps
        for c, name in enumerate(self.corners):  # a corner's current that chatters
            if warn_if_aliased(a.memory[c, EK.M_NREV], n, decimate, dt, f" at {name}"):
                break

    def record_values(self, plan: RunPlan) -> float:
        """Floats a run of ``plan`` allocates: the record and every wheel's road (sampled
        :data:`ROAD_CHUNK` steps at a time).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> sim = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car"))
        >>> sim.record_values(RunPlan(1e-4, 100, 10))
        1277.0
        """
        nc = len(self.corners)
        road = 2 * nc * (2 * min(plan.steps, ROAD_CHUNK) + 1)
        return float(plan.rows * (VX.REC_BODY + VX.REC_CORNER * nc) + road)

    def _divergence(
        self, status: int, t: float, idx: int, value: float, dt: float
    ) -> SimulationDiverged:
        if status == VX.D_STATE:
            if idx < VX.NB:
                name = tuple(BODY_SIGNALS)[idx]
            else:
                c, q = divmod(idx - VX.NB, VX.NQ)
                name = f"{('z_u', 'z_u_dot', 'z_s0', 'z_s0_dot')[q]}.{self.corners[c]}"
        else:
            name = f"{'F_d' if status == VX.D_FORCE else 'F_T'}.{self.corners[idx]}"
        return SimulationDiverged(
            f"vehicle simulation diverged at t = {t:.4f} s: {name} = {value:.3g} is out of range. "
            f"Check dt (= {dt:g} s; stable limit {self.max_stable_dt():.3g} s) and the inputs.",
            t,
            name,
            value,
        )

    def result_from_record(self, time: np.ndarray, record: np.ndarray, dt: float) -> VehicleResult:
        """The result from the kernels' record (columns ``RB_*``, then ``RC_*`` per corner)."""
        rec = np.ascontiguousarray(record.T)
        signals: dict[str, np.ndarray] = {k: rec[col] for k, col in BODY_COLUMNS.items()}
        units = {"time": "s", **{k: u for k, (u, _) in BODY_SIGNALS.items()}}
        scenario = self.describe()
        corner_scenarios = {}
        acc = getattr(self.excitation, "acceleration", None)
        if acc is not None:
            road_acc = np.asarray(acc(time), dtype=float)
        else:
            road_acc = np.array([_CornerRoad(self.excitation, i).acceleration(time)
                                 for i in range(len(self.corners))])  # fmt: skip
        for i, c in enumerate(self.corners):
            b = VX.REC_BODY + VX.REC_CORNER * i
            sig = {k: rec[b + col] for k, col in CORNER_COLUMNS.items()}
            sig["x_d"] = sig["z_u"] - sig["z_s"]
            sig["v_d"] = sig["z_u_dot"] - sig["z_s_dot"]
            sig["z_r_ddot"] = road_acc[i]
            for k, v in sig.items():
                signals[f"{k}.{c}"] = v
                units[f"{k}.{c}"] = SIGNALS[k][0]
            for k, col in SENSED_COLUMNS.items():
                signals[f"{k}.{c}"] = rec[b + col]
                units[f"{k}.{c}"] = VEHICLE_CORNER_SIGNALS[k][0]
            corner_scenarios[c] = self.corner_simulation(c).describe()
        return VehicleResult(
            time=time, signals=signals, scenario=scenario, dt=dt, units=units,
            corners=self.corners, corner_scenarios=corner_scenarios,
        )  # fmt: skip


class VehicleStepper:
    """The vehicle's compiled step, one tick at a time (the HiL loop's physics).

    The roads at the start, middle and end of the tick are given by the caller, one value
    per wheel (pass the start values only for a road held over the tick). With
    ``external``, that corner's damper force is not computed by its model but given at
    every tick and held over it (one physical damper on the rig, the others simulated).
    Stepping with the roads of :meth:`VehicleSimulation.run` reproduces it bit for bit.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic, WheelRoads
    >>> from mrsuspension.vehicle import FullCar
    >>> road = WheelRoads.in_phase(Harmonic(2.0, 0.01), "full-car")
    >>> st = VehicleSimulation(FullCar(), road).stepper(1e-4)
    >>> out = st.step([0.001] * 4, [0.0] * 4)
    >>> round(st.time, 6), out["heave"] > 0.0
    (0.0001, True)
    """

    def __init__(
        self, simulation: VehicleSimulation, dt: float, *, external: str | None = None
    ) -> None:
        self.simulation = simulation
        self.dt = simulation.check_dt(dt)
        self.external = None if external is None else simulation.vehicle.corner_index(external)
        self.reset()

    def reset(
        self, road: npt.ArrayLike | None = None, road_velocity: npt.ArrayLike | None = None
    ) -> None:
        """Back to static equilibrium on the given wheel roads (default 0); fresh internals.

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic, WheelRoads
        >>> from mrsuspension.vehicle import HalfCar
        >>> st = VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(2.0, 0.01), "half-car")).stepper()
        >>> st.reset([0.01, 0.01])
        >>> round(float(st.y[0]), 6), st.time
        (0.01, 0.0)
        """
        n = len(self.simulation.corners)
        zr = self._wheels("road", road)
        zrd = self._wheels("road_velocity", road_velocity)
        self.arrays = self.simulation.arrays(self.dt)
        if self.external is not None:
            self.arrays.force_source[self.external] = F_EXTERNAL
        self._args = self.arrays.args()
        self.y = self.simulation.initial_state(zr)
        self.time = 0.0
        self._zr = np.zeros((n, 3))
        self._zrd = np.zeros((n, 3))
        self._scratch = np.zeros((3, self.y.size))
        self._work = np.zeros((n + 1, 8))
        self._zr[:, 0], self._zrd[:, 0] = zr, zrd
        a = self.arrays
        VX.start(
            self.y, self._zr, self._zrd, 0, a.vehicle, a.corner_vehicles, a.force_source,
            a.damper_kind, a.damper_params, a.damper_state, a.damper_estimator_kind,
            a.damper_estimator_params, a.damper_estimator_state, a.controller_kind,
            a.controller_params, a.memory, self._scratch, self._work,
        )  # fmt: skip

    def _wheels(self, name: str, value: npt.ArrayLike | None) -> np.ndarray:
        n = len(self.simulation.corners)
        if value is None:
            return np.zeros(n)
        arr = check_range(name, value, -10.0, 10.0, unit="m" if name == "road" else "m/s")
        if arr.shape != (n,):
            raise ValidationError(
                f"{name} must have one value per wheel ({n}); got shape {arr.shape}"
            )
        return arr.astype(float)

    def step(
        self,
        road: npt.ArrayLike,
        road_velocity: npt.ArrayLike,
        *,
        road_mid: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
        road_end: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
        damper_force: float | None = None,
    ) -> dict[str, float]:
        """Advance one tick; returns the body's and every corner's signals by name.

        Raises
        ------
        ValidationError
            For roads of the wrong shape or out of range, or a ``damper_force`` missing
            (with ``external``) or given without it.
        SimulationDiverged
            When the state is no longer finite.
        """
        mem = self.arrays.memory
        if self.external is not None:
            if damper_force is None or not math.isfinite(damper_force):
                raise ValidationError(
                    f"a stepper with an external corner needs a finite damper_force each tick; got {damper_force!r}"
                )
            mem[self.external, EK.M_FEXT] = damper_force
        elif damper_force is not None:
            raise ValidationError("damper_force is only accepted with external=<corner>")
        zr, zrd = self._zr, self._zrd
        zr[:, 0] = self._wheels("road", road)
        zrd[:, 0] = self._wheels("road_velocity", road_velocity)
        mid = road_mid if road_mid is not None else (zr[:, 0], zrd[:, 0])
        zr[:, 1], zrd[:, 1] = self._wheels("road", mid[0]), self._wheels("road_velocity", mid[1])
        end = road_end if road_end is not None else (zr[:, 1], zrd[:, 1])
        zr[:, 2], zrd[:, 2] = self._wheels("road", end[0]), self._wheels("road_velocity", end[1])
        VX.step(self.y, self.dt, zr, zrd, 0, *self._args, self._scratch, self._work)
        raise_failure()  # a Python control law that raised in this step
        self.time += self.dt
        y = self.y
        if not np.all(np.isfinite(y)):
            raise SimulationDiverged(
                f"vehicle stepper diverged at t = {self.time:.4f} s: state is not finite",
                self.time,
                "state",
                math.nan,
            )
        out = {"time": self.time}
        for name, col in VX_BODY_STATE.items():
            out[name] = float(y[col])
        for name, col in (("heave_ddot", 3), ("pitch_ddot", 4), ("roll_ddot", 5)):
            out[name] = float(self._scratch[1, col])
        for i, c in enumerate(self.simulation.corners):
            q = VX.NB + VX.NQ * i
            out[f"z_u.{c}"] = float(y[q])
            out[f"z_u_dot.{c}"] = float(y[q + 1])
            out[f"F_d.{c}"] = float(mem[i, EK.M_FD])
            out[f"F_T.{c}"] = float(mem[i, EK.M_FT])
            out[f"i_d.{c}"] = float(mem[i, EK.M_ID])
            out[f"z_s_ddot.{c}"] = float(mem[i, EK.M_AS])
        return out


#: the body's states in ``y``
VX_BODY_STATE = {"heave": 0, "pitch": 1, "roll": 2, "heave_dot": 3, "pitch_dot": 4, "roll_dot": 5}


def _run_vehicle(args: tuple[VehicleSimulation, RunSettings, Reducer | None]) -> Any:
    sim, plan, reduce = args
    wanted = _in_kernel(reduce)
    if wanted is not None:  # the measures: reduced in the kernel
        return sim.run_measures(settings=plan, road_peak=wanted.road_peak)
    result = sim.run(settings=plan)
    return result if reduce is None else reduce(result)


def run_vehicles(
    simulations: Sequence[VehicleSimulation],
    *,
    duration: float | None = None,
    dt: float | None = None,
    output_rate: float | None = None,
    settings: RunSettings | None = None,
    workers: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    reduce: Reducer | None = None,
) -> list[Any]:
    """Run many vehicle simulations across processes (default: one per core), in order.

    The vehicle counterpart of :func:`~mrsuspension.engine.run_many`: the same
    ``settings`` (or ``duration``, ``dt``, ``output_rate``) for every run,
    ``progress(done, total)`` as runs finish and ``reduce`` (a module-level function)
    applied to each result in its worker; ``workers=1`` runs in this process. Given
    :func:`~mrsuspension.engine.measures_of` or a
    :class:`~mrsuspension.engine.simulate.MeasuresOf` (the measures the quarter car's
    :func:`~mrsuspension.engine.run_many` reduces in its kernels too), each run is
    reduced to its measures in the kernel (:meth:`VehicleSimulation.run_measures`):
    no time history is kept.

    Examples
    --------
    >>> from mrsuspension.engine.simulate import MeasuresOf
    >>> from mrsuspension.excitation import Harmonic, WheelRoads
    >>> from mrsuspension.vehicle import HalfCar
    >>> sims = [VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(f, 0.01), "half-car"))
    ...         for f in (1.0, 2.0)]
    >>> [r.time.size for r in run_vehicles(sims, duration=0.2, workers=1)]
    [201, 201]
    >>> sims = [VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(f, 0.005), "half-car"))
    ...         for f in (5.0, 8.0)]
    >>> rows = run_vehicles(sims, dt=2e-4, workers=1, reduce=MeasuresOf())  # each its own duration
    >>> [round(r["T_as.front"], 3) for r in rows]
    [0.26, 0.142]
    """
    from mrsuspension._pool import pool_map, worker_count

    plan = run_settings(settings, duration=duration, dt=dt, output_rate=output_rate)
    announce_compile(VX.__file__, "run")  # the workers compile quietly: say it here
    sims = list(simulations)
    for sim in sims:
        if not isinstance(sim, VehicleSimulation):
            raise ValidationError(f"run_vehicles takes VehicleSimulation objects; got {sim!r}")
    if not sims:
        return []
    if reduce is None and len(sims) > 1:  # every record is kept: together they must fit
        values = sum(
            plan.plan(sim, check_stability=False).rows
            * (VX.REC_BODY + VX.REC_CORNER * len(sim.corners))
            for sim in sims
        )
        check_memory(
            plan.duration or 0.0,
            values,
            subject=f"keeping the records of {len(sims)} runs",
            hint="run fewer, shorten the duration or lower output_rate",
        )
    return pool_map(
        _run_vehicle,
        [(sim, plan, reduce) for sim in sims],
        workers=worker_count(workers, len(sims)),
        progress=progress,
    )


def _measure_vehicle(
    args: tuple[VehicleSimulation, RunSettings, str],
) -> dict[str, Any] | SimulationDiverged:
    sim, plan, road_peak = args
    try:
        return sim.run_measures(settings=plan, road_peak=road_peak)
    except SimulationDiverged as err:
        return err


def measure_vehicles(
    simulations: Sequence[VehicleSimulation],
    settings: Sequence[RunSettings],
    *,
    pool: Any = None,
    road_peak: str = "after-onset",
) -> list[dict[str, Any] | SimulationDiverged]:
    """The measures of each vehicle run (its own settings), reduced in the kernel, in order.

    The vehicle counterpart of :func:`~mrsuspension.engine.simulate.measure_many`: the
    body's RMS accelerations and every corner's measures, as
    :meth:`VehicleResult.measures` gives them from a record
    (:meth:`VehicleSimulation.run_measures`: no time history is kept); a diverged run
    gives its :class:`SimulationDiverged` in its place. ``pool``: an open process pool
    (e.g. :func:`mrsuspension._pool.process_pool`) to run on; None: this process.

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic, WheelRoads
    >>> from mrsuspension.vehicle import HalfCar
    >>> sims = [VehicleSimulation(HalfCar(), WheelRoads.in_phase(Harmonic(f, 0.005), "half-car"))
    ...         for f in (5.0, 8.0)]
    >>> rows = measure_vehicles(sims, [RunSettings(dt=2e-4)] * 2)  # 10 cycles settled
    >>> [list(r)[:2] for r in rows]
    [['heave_ddot_rms', 'pitch_ddot_rms'], ['heave_ddot_rms', 'pitch_ddot_rms']]
    """
    from mrsuspension._pool import pool_map

    sims = list(simulations)
    plans = list(settings)
    if len(plans) != len(sims):
        raise ValidationError(
            f"measure_vehicles needs one RunSettings per run: {len(sims)} runs, "
            f"{len(plans)} settings"
        )
    announce_compile(VX.__file__, "run")  # the workers compile quietly: say it here
    return pool_map(
        _measure_vehicle,
        [(sim, plan, road_peak) for sim, plan in zip(sims, plans, strict=True)],
        pool=pool,
        workers=1,
    )
