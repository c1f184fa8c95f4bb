"""The plant models the engine runs, behind one run contract.

Every model a scenario names in ``[vehicle] model`` (the quarter car, the half car, the
full car, or one a user registers) is a :class:`Plant`: its parameter class, how one run
is built from a scenario's choices (:class:`RunParts`), its batch runners and the names
of the measures its runs report. A run is any object that keeps the :class:`RunModel`
contract (:class:`~mrsuspension.engine.simulate.Simulation` and
:class:`~mrsuspension.engine.vehicle.VehicleSimulation` do). Scenarios, studies, the
optimiser and the command line call runs through this contract and the one batch front
door (:mod:`mrsuspension.engine.batch`) without asking which vehicle they drive.

Adding a model is its own files plus one :func:`register_plant` call
(``docs/develop.md``, "Adding a vehicle model").

Examples
--------
>>> sorted(PLANTS)
['full-car', 'half-car', 'quarter-car']
>>> plant("full-car").corners
('front_left', 'front_right', 'rear_left', 'rear_right')
>>> plant("quarter-car").measure_names(("DLC", "mean_current"))
('DLC', 'mean_current')
>>> plant("half-car").measure_names(("DLC",))
('heave_ddot_rms', 'pitch_ddot_rms', 'DLC.front', 'DLC.rear')
>>> plant("full-car").on_request[:4]  # the seat's ISO 2631-1 measures, when asked
('seat_total', 'seat_x', 'seat_y', 'seat_z')
>>> plant("quarter-cart")
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: unknown vehicle model 'quarter-cart'. Did you mean 'quarter-car'? Valid: full-car, half-car, quarter-car.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from mrsuspension.engine.contract import RunModel
from mrsuspension.errors import ValidationError, unknown_name

__all__ = [
    "PLANTS",
    "Plant",
    "RunModel",
    "RunParts",
    "plant",
    "plant_of",
    "register_plant",
]


@dataclass(frozen=True)
class RunParts:
    """What a scenario chose for one run, for :attr:`Plant.build`.

    ``road`` is one track (an :class:`~mrsuspension.excitation.Excitation`) or, for a plant
    with ``wheel_roads``, a :class:`~mrsuspension.excitation.WheelRoads`. A plant with
    corners takes each corner's damper and controller from ``corner_dampers`` and
    ``corner_controllers``, ``sensing`` and the whole-vehicle law ``body_control``; a
    one-wheel plant takes ``damper`` and ``controller``.
    """

    road: Any
    damper: Any
    controller: Any
    max_current: float
    corner_dampers: Mapping[str, Any] = field(default_factory=dict)
    corner_controllers: Mapping[str, Any] = field(default_factory=dict)
    sensing: Any = None
    body_control: Any = None


#: ``run_many(runs, *, settings, workers, progress, reduce) -> list``: results in order
BatchRunner = Callable[..., list[Any]]
#: ``measure_many(runs, settings_per_run, *, pool, road_peak) -> list``: measures in order
BatchMeasurer = Callable[..., list[Any]]


@dataclass(frozen=True)
class Plant:
    """A model the engine runs: a registry entry of :data:`PLANTS`.

    Parameters
    ----------
    name : str
        ``[vehicle] model`` (e.g. ``"full-car"``).
    params : type
        The parameter dataclass; its fields are the ``[vehicle]`` keys, its class attribute
        ``corners`` (if any) the damper corners (none: one damper, ``[damper]``).
    build : callable
        ``build(params, parts: RunParts) -> RunModel``: one run.
    run_many, measure_many : callable
        The family's batch runners (:mod:`mrsuspension.engine.batch` groups runs by them).
    measure_names : callable
        ``measure_names(per_run) -> names``: the measures a run reports, given the quarter
        car's measures of its excitation kind (:data:`~mrsuspension.engine.result.MEASURES_BY_KIND`).
    make_params : callable
        ``make_params(values, set_name)``: the parameters from ``[vehicle]`` values and an
        optional published set (``[vehicle] set``, when ``sets`` is given).
    sets : callable, optional
        The published parameter sets' names (None: the model has none).
    wheel_roads : bool
        True when a run takes a road per wheel (:class:`~mrsuspension.excitation.WheelRoads`).
    units : mapping, optional
        Units of the model's own measures (name -> unit), where the quarter car's
        (:data:`~mrsuspension.engine.result.MEASURE_UNITS`) do not name them.
    on_request : tuple of str
        Measures a run reports only when asked (a study's ``[study] measures``, an
        objective's weights), not in :attr:`measure_names`' defaults: they need the run's
        time history (a half or full car's seat measures,
        :data:`~mrsuspension.engine.vehicle_result.SEAT_MEASURES`).
    """

    name: str
    params: type
    build: Callable[[Any, RunParts], RunModel]
    run_many: BatchRunner
    measure_many: BatchMeasurer
    measure_names: Callable[[tuple[str, ...]], tuple[str, ...]]
    make_params: Callable[[dict[str, Any], str | None], Any]
    sets: Callable[[], Sequence[str]] | None = None
    wheel_roads: bool = False
    units: Mapping[str, str] = field(default_factory=dict)
    on_request: tuple[str, ...] = ()

    @property
    def corners(self) -> tuple[str, ...]:
        """The damper corners (empty for a one-damper model such as the quarter car)."""
        return tuple(getattr(self.params, "corners", ()))


#: ``[vehicle] model`` -> its :class:`Plant` (:func:`register_plant` adds one)
PLANTS: dict[str, Plant] = {}


def register_plant(model: Plant) -> Plant:
    """Add a model to :data:`PLANTS` (a name taken by another model is refused)."""
    old = PLANTS.get(model.name)
    if old is not None and old != model:
        raise ValidationError(f"vehicle model {model.name!r} is already registered")
    PLANTS[model.name] = model
    return model


def plant(name: str) -> Plant:
    """The registered model ``name``; an unknown name is refused with the valid ones."""
    if name not in PLANTS:
        raise unknown_name("vehicle model", str(name), sorted(PLANTS))
    return PLANTS[name]


def plant_of(run: RunModel) -> Plant:
    """The :class:`Plant` of a run (by its ``model_name``)."""
    return plant(run.model_name)


# -- the built-in models -------------------------------------------------------------------
def _quarter_car(params: Any, parts: RunParts) -> RunModel:
    from mrsuspension.engine.simulate import Simulation

    return Simulation(
        excitation=parts.road,
        vehicle=params,
        damper=parts.damper,
        controller=parts.controller,
        max_current=parts.max_current,
    )


def _vehicle(params: Any, parts: RunParts) -> RunModel:
    from mrsuspension.engine.vehicle import VehicleSimulation

    return VehicleSimulation(
        params,
        parts.road,
        dampers=dict(parts.corner_dampers),
        controllers=dict(parts.corner_controllers),
        max_current=parts.max_current,
        **({} if parts.sensing is None else {"sensing": parts.sensing}),
        body_control=parts.body_control,
    )


def _run_many(runs: Sequence[Any], **kwargs: Any) -> list[Any]:
    from mrsuspension.engine.simulate import run_many

    return run_many(runs, **kwargs)


def _measure_many(runs: Sequence[Any], settings: Sequence[Any], **kwargs: Any) -> list[Any]:
    from mrsuspension.engine.simulate import measure_many

    return measure_many(runs, settings, **kwargs)


def _run_vehicles(runs: Sequence[Any], **kwargs: Any) -> list[Any]:
    from mrsuspension.engine.vehicle import run_vehicles

    return run_vehicles(runs, **kwargs)


def _measure_vehicles(runs: Sequence[Any], settings: Sequence[Any], **kwargs: Any) -> list[Any]:
    from mrsuspension.engine.vehicle import measure_vehicles

    return measure_vehicles(runs, settings, **kwargs)


def _vehicle_measures(
    corners: tuple[str, ...], body_dofs: tuple[str, ...]
) -> Callable[[tuple[str, ...]], tuple[str, ...]]:
    """A vehicle's measures: the body's RMS accelerations, then ``<measure>.<corner>``."""

    from mrsuspension.engine.vehicle_result import BODY_MEASURES

    body = tuple(m for m in BODY_MEASURES if m.split("_ddot")[0] in body_dofs)

    def names(per_run: tuple[str, ...]) -> tuple[str, ...]:
        return body + tuple(f"{m}.{c}" for c in corners for m in per_run)

    return names


def _vehicle_params(cls: Any) -> Callable[[dict[str, Any], str | None], Any]:
    """A half or full car's parameters: a published set (or the default) with overrides."""

    def make(values: dict[str, Any], set_name: str | None) -> Any:
        return (cls.from_set(set_name) if set_name is not None else cls()).with_(**values)

    return make


def _register_builtins() -> None:
    from mrsuspension.engine.vehicle_result import SEAT_MEASURES
    from mrsuspension.vehicle import FullCar, HalfCar, QuarterCar
    from mrsuspension.vehicle.body import available_sets

    register_plant(
        Plant(
            name="quarter-car",
            params=QuarterCar,
            build=_quarter_car,
            run_many=_run_many,
            measure_many=_measure_many,
            measure_names=lambda per_run: tuple(per_run),
            make_params=lambda values, _set: QuarterCar(**values),
        )
    )
    for cls in (HalfCar, FullCar):
        register_plant(
            Plant(
                name="half-car" if cls is HalfCar else "full-car",
                params=cls,
                build=_vehicle,
                run_many=_run_vehicles,
                measure_many=_measure_vehicles,
                measure_names=_vehicle_measures(cls.corners, cls.body_dofs),
                make_params=_vehicle_params(cls),
                sets=available_sets,
                wheel_roads=True,
                units={k: unit for k, (unit, _) in SEAT_MEASURES.items()},
                on_request=tuple(SEAT_MEASURES),
            )
        )


_register_builtins()
