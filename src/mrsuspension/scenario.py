"""Scenario files: a quarter-, half- or full-car study described in TOML, validated on load.

A scenario has five tables, whose section and key names are public interface::

    [vehicle]       # QuarterCar: sprung_mass, unsprung_mass, suspension_stiffness,
                    # tire_stiffness, tire_damping, skyhook_damping; or model = "half-car"
                    # | "full-car" (HalfCar, FullCar), set = a published set, body fields
    [damper]        # model, parameters, hysteresis, force_gain, max_current, damping, ...
    [controller]    # law, mode, gain, order, current, p, xi, p_c, xi_c, lambda, eps, ...
    [excitation]    # kind (harmonic | swept | pulse | road; a half or full car also
                    # two-track | crg | bump | pothole) and its options
    [simulation]    # duration, dt, output_rate

A half or full car takes per-corner sub-tables ``[damper.<corner>]`` and
``[controller.<corner>]`` over the main tables (see ``docs/scenarios.md``).

Every key is optional except ``[excitation] kind`` and the excitation's required options;
defaults are those of the classes (:class:`~mrsuspension.vehicle.QuarterCar`,
:func:`~mrsuspension.dampers.make_damper`, :func:`~mrsuspension.control.make_controller`,
:class:`~mrsuspension.engine.simulate.Simulation`), i.e. the model reference's. Unknown sections or
keys, wrong types and out-of-range values raise :class:`~mrsuspension.errors.ValidationError`
naming ``[section] key`` (with a did-you-mean for misspelt names).

Examples
--------
>>> scenario = Scenario.from_dict(
...     {
...         "controller": {"law": "skyhook-hilo", "mode": "ACM"},
...         "excitation": {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.025},
...     }
... )
>>> scenario.controller.law, len(scenario.simulations())
('skyhook-hilo', 1)
>>> Scenario.from_dict({"vehicle": {"sprung_mas": 500.0}, "excitation": {"kind": "pulse"}})
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: unknown key [vehicle] sprung_mas. Did you mean 'sprung_mass'? Valid: model, skyhook_damping, sprung_mass, suspension_stiffness, tire_damping, tire_stiffness, unsprung_mass.
"""

from __future__ import annotations

import copy
import dataclasses
import inspect
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mrsuspension._inputs import read_toml
from mrsuspension.control import CONTROLLERS, Controller, HiLo, law_options, make_controller
from mrsuspension.control.modal import VehicleLaw
from mrsuspension.control.registry import VEHICLE_LAWS as LAW_PLUGINS
from mrsuspension.control.sensing import BandPassObserver, LeakyIntegrator, Sensing, StrokeSensor
from mrsuspension.control.user import is_law_spec, load_law
from mrsuspension.dampers import DAMPERS, ESTIMATORS, DamperModel, damper_options, make_damper
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine.batch import run_batch
from mrsuspension.engine.plants import PLANTS, Plant, RunModel, RunParts, plant
from mrsuspension.engine.result import SimulationResult
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import Simulation
from mrsuspension.engine.vehicle_result import BODY_MEASURES
from mrsuspension.errors import ValidationError, did_you_mean
from mrsuspension.excitation import (
    EXCITATION_OPTIONS,
    EXCITATIONS,
    PRESET_ROADS,
    Excitation,
    SteppedSweep,
    WheelRoads,
    make_excitation,
)
from mrsuspension.excitation.base import positive
from mrsuspension.excitation.deterministic import REFERENCE_SPEED_KMH
from mrsuspension.vehicle import QuarterCar
from mrsuspension.vehicle.body import FullCar, HalfCar, VehicleBody

if TYPE_CHECKING:
    from mrsuspension.engine.vehicle import VehicleSimulation

__all__ = [
    "BODY_MEASURES",
    "SCENARIO_KEYS",
    "WHEEL_KINDS",
    "Scenario",
    "run_measures",
]

#: :meth:`Scenario.current_note`: a law whose mean current stays below this share of
#: ``max_current`` in every run is noted as leaving the damper near 0 A
LOW_CURRENT_SHARE = 0.05

# -- the public keys -----------------------------------------------------------------------
# Value kinds: "number", "integer", "bool", "string", "numbers" (a list of numbers),
# "text" (a string; a number is accepted and turned into its text, e.g. vh_variant = 2.12).


def _model_keys(model: Plant) -> tuple[str, ...]:
    """``[vehicle]`` keys of a model: ``model``, ``set`` (a model with published sets) and
    its parameter fields."""
    return (
        ("model",)
        + (() if model.sets is None else ("set",))
        + tuple(f.name for f in dataclasses.fields(model.params))
    )


class _VehicleKeys(Mapping[str, str]):
    """``[vehicle]`` keys of every registered model (:data:`~mrsuspension.engine.plants.PLANTS`,
    read live: a model registered later has its keys) -> value kind."""

    def _keys(self) -> dict[str, str]:
        return {
            k: "string" if k in ("model", "set") else "number"
            for p in PLANTS.values()
            for k in _model_keys(p)
        }

    def __getitem__(self, key: str) -> str:
        return self._keys()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._keys())

    def __len__(self) -> int:
        return len(self._keys())


_VEHICLE_KEYS: Mapping[str, str] = _VehicleKeys()

#: every ``[damper]`` key of any model (each model's own: :func:`damper_options`)
_DAMPER_KEYS: dict[str, str] = {k: v for m in DAMPERS for k, v in damper_options(m).items()}


#: controller-table key -> constructor keyword, by law (the model reference's symbols)
_SLIDING_ALIASES = {
    "lambda": "slope",
    "eps": "boundary_layer",
    "m_s0": "nominal_mass",
    "c_s": "skyhook_damping",
    "c_0": "passive_damping",
}
_CONTROLLER_ALIASES: dict[str, dict[str, str]] = {
    "sliding-mode": _SLIDING_ALIASES,
    "ideal-skyhook": {"c_s": "skyhook_damping", "damping": "skyhook_damping"},
    "ideal-onoff": {"c_s": "damping"},
}
_CONTROLLER_TEXT = {"law": "string", "mode": "string", "inverse": "string"}


def _law_keywords(law: str) -> list[str]:
    """Constructor keywords of a controller law (from its signature: no numbers copied)."""
    target = CONTROLLERS[law]
    # the hi-lo policies are registered as small builders around HiLo
    source = target if isinstance(target, type) else HiLo
    params = inspect.signature(source).parameters
    return [n for n in params if n not in ("self", "policy")]


def _law_keys(law: str) -> dict[str, str]:
    """Scenario keys accepted by ``[controller]`` for ``law``, mapped to constructor keywords."""
    keys = {"law": "law"}
    for kw in _law_keywords(law):
        keys[kw] = kw
    for alias, kw in _CONTROLLER_ALIASES.get(law, {}).items():
        keys[alias] = kw
    return keys


_CONTROLLER_KEYS: dict[str, str] = {}
for _law in CONTROLLERS:
    #: vector and matrix options (e.g. the LQ laws' gain K): TOML arrays
    _arrays = {o.name for o in law_options(_law) if o.shape is not None}
    for _key in _law_keys(_law):
        _CONTROLLER_KEYS[_key] = (
            "array" if _key in _arrays else _CONTROLLER_TEXT.get(_key, "number")
        )


def _excitation_keys() -> dict[str, str]:
    """Every ``[excitation]`` key with its value kind, from the kinds' declared options."""
    keys = {"kind": "string"}
    for kind, cls in EXCITATIONS.items():
        for opt in cls.options:
            # one key, one value kind across kinds (a new kind's declaration bug otherwise)
            if keys.setdefault(opt.name, opt.kind) != opt.kind:  # pragma: no cover
                raise ValidationError(
                    f"excitation {kind!r} declares option {opt.name!r} as {opt.kind!r}; "
                    f"another kind has it as {keys[opt.name]!r}"
                )
    return keys


#: Excitation kinds that give a road per wheel (half and full car only): kind -> key ->
#: (value kind, required). ``speed`` [km/h] and the geometry come from the scenario.
WHEEL_KINDS: dict[str, dict[str, tuple[str, bool]]] = {
    "two-track": {
        "iso_class": ("string", False),
        "profile": ("string", False),
        "seed": ("integer", False),
        "length": ("number", False),
        "spacing": ("number", False),
        "speed": ("number", False),
        "fade_in": ("number", False),
    },
    "crg": {
        "file": ("string", True),
        "speed": ("number", False),
        "lateral_offset": ("number", False),
        "absolute": ("bool", False),
        "fade_in": ("number", False),
    },
    "bump": {
        "side": ("string", True),
        "height": ("number", True),
        "length": ("number", True),
        "position": ("number", False),
        "speed": ("number", False),
    },
    "pothole": {
        "side": ("string", True),
        "depth": ("number", True),
        "length": ("number", True),
        "position": ("number", False),
        "edge": ("number", False),
        "speed": ("number", False),
    },
}
#: single-track kinds without a speed of their own: ``speed`` [km/h] is accepted on a
#: half or full car (the rear wheels' delay wheelbase/speed); 50 km/h by default
_SPEEDLESS_KINDS = ("harmonic", "swept")


def _all_excitation_keys() -> dict[str, str]:
    keys = _excitation_keys()
    for options in WHEEL_KINDS.values():
        for key, (kind, _) in options.items():
            if keys.setdefault(key, kind) != kind:  # pragma: no cover
                raise ValidationError(f"excitation key {key!r} has two value kinds")
    return keys


_EXCITATION_KEYS: dict[str, str] = _all_excitation_keys()

#: ``[simulation]``: the fields of :class:`~mrsuspension.engine.settings.RunSettings`
_SIMULATION_KEYS = {f.name: "number" for f in dataclasses.fields(RunSettings)}

#: Laws over the whole vehicle (half and full car): ``[controller] law`` -> the keys it
#: takes (:mod:`mrsuspension.control.modal`); every corner's current comes from it.
VEHICLE_LAWS: dict[str, tuple[str, ...]] = {
    name: cls.options() for name, cls in LAW_PLUGINS.items()
}
for _law_name, _keys in VEHICLE_LAWS.items():
    for _key in _keys:
        _CONTROLLER_KEYS.setdefault(_key, "number")

#: ``[sensing]`` (half and full car): what the controllers measure
#: (:class:`~mrsuspension.control.sensing.Sensing`): the body-velocity estimator of every
#: corner and the stroke sensor.
_SENSING_KEYS: dict[str, str] = {
    "velocity": "string",  # ideal | leaky-integrator | band-pass
    "tau": "number",  # s, leaky integrator time constant
    "corner": "number",  # Hz, band-pass corner frequency
    "zeta": "number",  # band-pass damping ratio
    "fs": "number",  # Hz, the estimator's sample rate
    "stroke_fs": "number",  # Hz: a stroke sensor at this rate (absent: the true stroke)
    "stroke_resolution": "number",  # m
    "stroke_noise": "number",  # m, noise standard deviation
    "stroke_seed": "integer",
}
#: ``[sensing] velocity`` -> the keys of that estimator (given with another, refused)
_VELOCITY_ESTIMATORS: dict[str, tuple[str, ...]] = {
    "ideal": (),
    "leaky-integrator": ("tau", "fs"),
    "band-pass": ("corner", "zeta", "fs"),
}

#: Every section of a scenario file and the keys it accepts (with their value kind).
SCENARIO_KEYS: dict[str, Mapping[str, str]] = {
    "vehicle": _VEHICLE_KEYS,
    "damper": _DAMPER_KEYS,
    "controller": _CONTROLLER_KEYS,
    "excitation": _EXCITATION_KEYS,
    "simulation": _SIMULATION_KEYS,
    "sensing": _SENSING_KEYS,
}

_DEFAULT_MAX_CURRENT: float = next(
    f.default for f in dataclasses.fields(Simulation) if f.name == "max_current"
)  # type: ignore[assignment]


# -- checking helpers ---------------------------------------------------------------------
def _where(section: str, key: str) -> str:
    return f"[{section}] {key}"


@contextmanager
def _in_section(section: str) -> Iterator[None]:
    """Prefix a ValidationError raised while building ``section`` with ``[section]``."""
    try:
        yield
    except ValidationError as exc:
        text = str(exc)
        if text.startswith("["):
            raise
        raise ValidationError(f"[{section}] {text}") from None


def _unknown_key(section: str, key: str, valid: Iterable[str], extra: str = "") -> ValidationError:
    names = sorted(valid)
    return ValidationError(
        f"unknown key {_where(section, key)}{extra}.{did_you_mean(key, names)} "
        f"Valid: {', '.join(names)}."
    )


def _is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _typed(section: str, key: str, value: object, kind: str) -> Any:
    """Check a value's type; return it converted (ints to floats for numbers)."""
    where = _where(section, key)
    if kind == "number":
        if not _is_number(value):
            raise ValidationError(f"{where} must be a number; got {value!r}")
        return float(value)  # type: ignore[arg-type]
    if kind == "integer":
        if not isinstance(value, int) or isinstance(value, bool):
            raise ValidationError(f"{where} must be an integer; got {value!r}")
        return value
    if kind == "bool":
        if not isinstance(value, bool):
            raise ValidationError(f"{where} must be true or false; got {value!r}")
        return value
    if kind == "string":
        if not isinstance(value, str):
            raise ValidationError(f"{where} must be a string; got {value!r}")
        return value
    if kind == "text":
        if _is_number(value):
            return f"{value:g}"
        if not isinstance(value, str):
            raise ValidationError(f"{where} must be a string; got {value!r}")
        return value
    if kind == "array":  # a vector or matrix option: its shape is checked by the law
        return _user_value(section, key, value)
    if kind == "numbers":
        if not isinstance(value, list) or not all(_is_number(v) for v in value):
            raise ValidationError(f"{where} must be a list of numbers; got {value!r}")
        return [float(v) for v in value]
    raise AssertionError(kind)  # pragma: no cover


#: sections that take per-corner sub-tables (``[damper.front_left]``, ``[controller.rear]``)
_CORNER_SECTIONS = ("damper", "controller")


def _user_value(section: str, key: str, value: object) -> Any:
    """A user law's option (``[controller] law = "module:function"``): a string (``law``),
    a number, or a vector or matrix of numbers (TOML arrays), checked by the law."""
    if key == "law":
        return _typed(section, key, value, "string")
    if _is_number(value):
        return float(value)  # type: ignore[arg-type]
    flat = value if isinstance(value, list) else None
    if flat is not None and all(isinstance(v, list) for v in flat) and flat:
        flat = [v for row in flat for v in row]
    if flat is None or not all(_is_number(v) for v in flat):
        raise ValidationError(
            f"{_where(section, key)} must be a number or an array of numbers (a vector, or "
            f"a matrix as an array of rows); got {value!r}"
        )
    return value


def _table(data: Mapping[str, Any], section: str) -> dict[str, Any]:
    """The section's table, typed and with known keys only (a user law's ``[controller]``
    keys are its options: numbers and arrays, checked by the law)."""
    raw = data.get(section, {})
    if not isinstance(raw, Mapping):
        raise ValidationError(f"[{section}] must be a table; got {raw!r}")
    keys = SCENARIO_KEYS[section]
    user = section == "controller" and is_law_spec(raw.get("law"))
    out: dict[str, Any] = {}
    for key, value in raw.items():
        if section in _CORNER_SECTIONS and isinstance(value, Mapping):
            # a per-corner table [damper.front_left]: its keys are the section's
            corner = {}
            corner_user = user or (section == "controller" and is_law_spec(value.get("law")))
            for sub, item in value.items():
                if corner_user and not isinstance(item, Mapping):
                    corner[sub] = _user_value(f"{section}.{key}", str(sub), item)
                    continue
                if sub not in keys:
                    raise _unknown_key(f"{section}.{key}", str(sub), keys)
                if isinstance(item, Mapping):
                    raise ValidationError(
                        f"[{section}.{key}.{sub}]: per-corner tables hold keys, not tables"
                    )
                corner[sub] = _typed(f"{section}.{key}", sub, item, keys[sub])
            out[key] = corner
            continue
        if user:
            out[key] = _user_value(section, str(key), value)
            continue
        if key not in keys:
            if section in ("excitation", "vehicle"):  # reported for the kind or model
                out[key] = value
                continue
            raise _unknown_key(section, str(key), keys)
        out[key] = _typed(section, key, value, keys[key])
    return out


def _choice(section: str, key: str, value: str, choices: Mapping[str, Any]) -> str:
    if value not in choices:
        names = sorted(choices)
        raise ValidationError(
            f"{_where(section, key)}: unknown {key} {value!r}.{did_you_mean(value, names)} "
            f"Valid: {', '.join(names)}."
        )
    return value


# -- the scenario -------------------------------------------------------------------------
@dataclass(frozen=True)
class Scenario:
    """A validated scenario (see the module docstring for the file format).

    Build it with :meth:`load` (a TOML file) or :meth:`from_dict`; the components are
    constructed and checked on load.

    Parameters
    ----------
    vehicle : QuarterCar, HalfCar or FullCar
        The vehicle (``[vehicle]``, ``model``).
    damper : DamperModel
        The damper model (``[damper]``).
    controller : Controller
        The control law (``[controller]``).
    excitation : Excitation, SteppedSweep or WheelRoads
        The road input (``[excitation]``); a stepped sweep gives one run per frequency;
        a wheel-only kind (half or full car) is a :class:`~mrsuspension.excitation.WheelRoads`.
    max_current : float
        Drive-current limit i_max [A] (``[damper] max_current``).
    settings : RunSettings
        ``[simulation]``: the fixed RK4 step ``dt`` [s], the simulated time ``duration``
        [s] of each run (None: the excitation's own, the steady-state rule for harmonic
        runs) and the recorded ``output_rate`` [Hz]; also readable as
        :attr:`dt`, :attr:`duration` and :attr:`output_rate`.
    data : dict
        The scenario as plain tables (see :meth:`to_dict`).
    base_dir : Path
        Folder that relative file paths (parameters, road profiles) are taken from.
    source : Path or None
        The file it was loaded from.
    corner_dampers, corner_controllers : mapping
        A half or full car: every corner's damper and controller (the main table with the
        corner's overrides); empty for the quarter car.
    road_speed : float or None
        A half or full car on a harmonic or swept excitation: the speed [km/h] that
        delays the rear wheels.
    """

    vehicle: QuarterCar | HalfCar | FullCar
    damper: DamperModel
    controller: Controller
    excitation: Excitation | SteppedSweep | WheelRoads
    max_current: float
    settings: RunSettings
    data: dict[str, dict[str, Any]] = field(default_factory=dict, repr=False)
    base_dir: Path = field(default_factory=Path.cwd)
    source: Path | None = None
    #: a half or full car: every corner's damper and controller (main table + overrides)
    corner_dampers: Mapping[str, DamperModel] = field(default_factory=dict, repr=False)
    corner_controllers: Mapping[str, Controller] = field(default_factory=dict, repr=False)
    #: a half or full car on a single-track kind without its own speed: the speed [km/h]
    road_speed: float | None = None
    #: a half or full car: what its controllers measure (``[sensing]``; None: ideal)
    sensing: Sensing | None = None
    #: a half or full car: a law over the whole vehicle (``[controller] law =
    #: "modal-skyhook"`` or ``"corner-skyhook"``), else None
    body_control: VehicleLaw | None = None

    # -- loading ------------------------------------------------------------------------
    @classmethod
    def load(cls, path: str | Path) -> Scenario:
        """Read and validate a scenario TOML file.

        Relative paths inside it (damper ``parameters``, road ``profile``) are taken
        from the file's folder.

        Raises
        ------
        ValidationError
            Missing or unreadable file, TOML syntax errors, unknown sections or keys,
            wrong types and out-of-range values (naming ``[section] key``).
        """
        path = Path(path)
        data = read_toml(path, "scenario")
        scenario = cls.from_dict(data, base_dir=path.resolve().parent)
        return dataclasses.replace(scenario, source=path)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], base_dir: str | Path | None = None) -> Scenario:
        """Validate plain tables (as read from TOML) and build the scenario.

        Parameters
        ----------
        data : mapping
            Section name -> table (``vehicle``, ``damper``, ``controller``,
            ``excitation``, ``simulation``).
        base_dir : str or Path, optional
            Folder for relative file paths; the working directory by default.
        """
        if not isinstance(data, Mapping):
            raise ValidationError(f"a scenario must be a table of sections; got {data!r}")
        for section in data:
            if section not in SCENARIO_KEYS:
                names = sorted(SCENARIO_KEYS)
                raise ValidationError(
                    f"unknown section [{section}].{did_you_mean(str(section), names)} "
                    f"Valid: {', '.join(names)}."
                )
        base = Path.cwd() if base_dir is None else Path(base_dir)
        tables = {section: _table(data, section) for section in SCENARIO_KEYS}

        model, vehicle = _build_vehicle(tables["vehicle"])
        corners = model.corners
        damper_table, damper_corners = _split_corners("damper", tables["damper"], corners)
        controller_table, law_corners = _split_corners("controller", tables["controller"], corners)
        damper, max_current = _build_damper(damper_table, base)
        sensing = _build_sensing(tables["sensing"], corners, tables["simulation"])
        body_control = _build_body_control(controller_table, law_corners, vehicle, corners)
        if body_control is not None:  # the corners run passive at 0 A: the law sets them
            controller_table = {"law": "passive"}
        controller = _build_controller(controller_table, base=base)
        corner_dampers: dict[str, DamperModel] = {}
        corner_controllers: dict[str, Controller] = {}
        for corner in corners:
            section = f"damper.{corner}"
            if "max_current" in damper_corners[corner]:
                raise ValidationError(
                    f"[{section}] max_current: the current limit applies to every corner; "
                    "set it in [damper]"
                )
            merged = _corner_table(damper_table, damper_corners[corner], "model", "wang-symmetric")
            corner_dampers[corner] = _build_damper(merged, base, section)[0]
            merged = _corner_table(controller_table, law_corners[corner], "law", "passive")
            corner_controllers[corner] = _build_controller(merged, f"controller.{corner}", base)
        excitation, road_speed = _build_any_excitation(tables["excitation"], base, model,
                                                       vehicle)  # fmt: skip

        with _in_section("simulation"):
            settings = RunSettings(**tables["simulation"])
            settings.check_for(excitation)
        scenario = cls(
            vehicle=vehicle,
            damper=damper,
            controller=controller,
            excitation=excitation,
            max_current=max_current,
            settings=settings,
            data=copy.deepcopy(tables),
            base_dir=base,
            corner_dampers=corner_dampers,
            corner_controllers=corner_controllers,
            road_speed=road_speed,
            sensing=sensing,
            body_control=body_control,
        )
        # checks the damper/controller combination, then stability (same model every run)
        if body_control is not None and body_control.high_current > max_current:
            raise ValidationError(
                f"[controller] high_current = {body_control.high_current:g} A is above the "
                f"drive-current limit [damper] max_current = {max_current:g} A"
            )
        first = scenario.runs()[0]
        with _in_section("simulation"):
            first.check_dt(settings.dt)
        for corner, law in corner_controllers.items():
            with _in_section(f"controller.{corner}"):
                law.params(max_current)
        with _in_section("controller"):
            controller.params(max_current)  # e.g. a passive current above max_current
        return scenario

    # -- run settings -------------------------------------------------------------------
    @property
    def duration(self) -> float | None:
        """``settings.duration``: simulated time [s] of each run (None: the excitation's)."""
        return self.settings.duration

    @property
    def dt(self) -> float:
        """``settings.dt``: the fixed RK4 step [s]."""
        return self.settings.dt

    @property
    def output_rate(self) -> float:
        """``settings.output_rate``: recorded samples per second [Hz]."""
        return self.settings.output_rate

    # -- building -----------------------------------------------------------------------
    @property
    def is_sweep(self) -> bool:
        """True for a swept excitation (one run per frequency)."""
        return isinstance(self.excitation, SteppedSweep)

    @property
    def model(self) -> str:
        """``[vehicle] model``: ``"quarter-car"``, ``"half-car"``, ``"full-car"`` or a
        registered model's name."""
        name = self.data.get("vehicle", {}).get("model")
        return str(name or getattr(self.vehicle, "model_name", "quarter-car"))

    @property
    def plant(self) -> Plant:
        """The :class:`~mrsuspension.engine.plants.Plant` of ``[vehicle] model``."""
        return plant(self.model)

    @property
    def corners(self) -> tuple[str, ...]:
        """The damper corners (a half or full car's; empty for a one-damper model)."""
        return self.plant.corners

    def measure_names(self) -> tuple[str, ...]:
        """The measures each run reports: the quarter car's of the excitation kind, or a
        half or full car's body and per-corner measures (``"<measure>.<corner>"``).

        Examples
        --------
        >>> s = Scenario.from_dict({"vehicle": {"model": "half-car"},
        ...                         "excitation": {"kind": "bump", "side": "left",
        ...                                        "height": 0.02, "length": 0.5}})
        >>> s.measure_names()[:4]
        ('heave_ddot_rms', 'pitch_ddot_rms', 'DLC.front', 'rms_body_acceleration.front')
        """
        from mrsuspension.engine.result import MEASURES_BY_KIND

        kind = getattr(self.excitations[0], "measures_kind", "road")  # wheel roads: road
        return self.plant.measure_names(MEASURES_BY_KIND[kind])

    @property
    def excitations(self) -> list[Any]:
        """The road inputs of the runs (one, or one harmonic per sweep frequency).

        Single-track excitations (:class:`Excitation`), or the scenario's
        :class:`~mrsuspension.excitation.WheelRoads` for a wheel-only kind.
        """
        if isinstance(self.excitation, SteppedSweep):
            return list(self.excitation.excitations())
        return [self.excitation]

    def wheel_roads(self, excitations: Sequence[Any] | None = None) -> list[WheelRoads]:
        """The road under every wheel of a half or full car, one per run.

        A single-track excitation goes to both sides (the rear wheels wheelbase/speed
        later: :meth:`WheelRoads.from_excitation <mrsuspension.excitation.WheelRoads.from_excitation>`).

        Parameters
        ----------
        excitations : sequence, optional
            Other single-track inputs (e.g. a sweep given on the command line); default:
            the scenario's own.

        Examples
        --------
        >>> s = Scenario.from_dict({"vehicle": {"model": "half-car"},
        ...                         "excitation": {"kind": "harmonic", "frequency": 1.0,
        ...                                        "amplitude": 0.01, "speed": 36.0}})
        >>> s.wheel_roads()[0].corners, round(s.wheel_roads()[0].rear_delay, 4)
        (('front', 'rear'), 0.2348)
        """
        car = self.vehicle
        if not self.plant.wheel_roads:
            raise ValidationError("wheel roads need [vehicle] model = 'half-car' or 'full-car'")
        # a speedless kind's [excitation] speed, else the scenario road's own speed
        speed = self.road_speed
        if speed is None:
            speed = getattr(self.excitation, "speed_kmh", None)
        out = []
        for exc in self.excitations if excitations is None else excitations:
            if isinstance(exc, WheelRoads):
                out.append(exc)
                continue
            with _in_section("excitation"):
                out.append(WheelRoads.from_excitation(exc, car, speed))
        return out

    def vehicle_simulations(
        self, excitations: Sequence[Any] | None = None
    ) -> list[VehicleSimulation]:
        """One :class:`~mrsuspension.engine.vehicle.VehicleSimulation` per run (half/full car).

        Every corner gets its damper and controller (``[damper]``/``[controller]`` with the
        corner's overrides) and the road of :meth:`wheel_roads`.

        Examples
        --------
        >>> s = Scenario.from_dict({"vehicle": {"model": "full-car"},
        ...                         "controller": {"law": "skyhook-hilo", "mode": "ACM",
        ...                                        "rear_left": {"law": "passive"}},
        ...                         "excitation": {"kind": "bump", "side": "left",
        ...                                        "height": 0.03, "length": 0.5}})
        >>> sim = s.vehicle_simulations()[0]
        >>> [sim.corner_simulation(c).controller.law for c in sim.corners]
        ['skyhook-hilo', 'skyhook-hilo', 'passive', 'skyhook-hilo']
        """
        if not self.plant.wheel_roads:
            raise ValidationError(
                "vehicle_simulations needs [vehicle] model = 'half-car' or 'full-car'; "
                f"a {self.model} scenario has runs()"
            )
        return self.runs(excitations)  # type: ignore[return-value]

    def runs(self, excitations: Sequence[Any] | None = None) -> list[RunModel]:
        """One run per road input (one per frequency for a swept excitation), any model.

        Quarter cars give :class:`~mrsuspension.engine.simulate.Simulation` objects, half
        and full cars :class:`~mrsuspension.engine.vehicle.VehicleSimulation` objects (the
        road of :meth:`wheel_roads` under every wheel), a registered model its own; all
        keep the run contract (:class:`~mrsuspension.engine.plants.RunModel`) and go to
        :func:`~mrsuspension.engine.batch.run_batch`.

        Parameters
        ----------
        excitations : sequence, optional
            Other road inputs for this vehicle, damper and controller (e.g. a sweep given
            on the command line); default: the scenario's own.

        Examples
        --------
        >>> s = Scenario.from_dict({"vehicle": {"model": "half-car"},
        ...                         "excitation": {"kind": "swept", "frequencies": [1.0, 2.0],
        ...                                        "amplitude": 0.01}})
        >>> [type(r).__name__ for r in s.runs()], s.runs()[0].model_name
        (['VehicleSimulation', 'VehicleSimulation'], 'half-car')
        """
        model = self.plant
        roads = (
            self.wheel_roads(excitations)
            if model.wheel_roads
            else list(self.excitations if excitations is None else excitations)
        )
        with _in_section("damper"):
            return [
                model.build(
                    self.vehicle,
                    RunParts(
                        road=road,
                        damper=self.damper,
                        controller=self.controller,
                        max_current=self.max_current,
                        corner_dampers=self.corner_dampers,
                        corner_controllers=self.corner_controllers,
                        sensing=self.sensing,
                        body_control=self.body_control,
                    ),
                )
                for road in roads
            ]

    def simulations(self, excitations: Sequence[Excitation] | None = None) -> list[Simulation]:
        """One quarter-car :class:`Simulation` per run (one per frequency for a sweep).

        The quarter car's typed view of :meth:`runs` (a half or full car is refused:
        :meth:`runs` takes any model).

        Parameters
        ----------
        excitations : sequence of Excitation, optional
            Other road inputs for this vehicle, damper and controller (e.g. a sweep
            given on the command line); default: the scenario's own.
        """
        if self.model != "quarter-car":
            raise ValidationError(
                f"this is a {self.model} scenario ([vehicle] model); this use needs a quarter "
                "car (model = 'quarter-car'), or use runs()"
            )
        return self.runs(excitations)  # type: ignore[return-value]

    def run(
        self,
        *,
        duration: float | None = None,
        workers: int | None = 1,
        progress: Callable[[int, int], None] | None = None,
    ) -> list[SimulationResult]:
        """Run every simulation of the scenario; results in order (one per frequency).

        A half or full car gives :class:`~mrsuspension.engine.vehicle_result.VehicleResult`
        objects (with :func:`run_measures` for its body and per-corner measures).

        Parameters
        ----------
        duration : float, optional
            Simulated time of each run [s]; default ``[simulation] duration``, else the
            excitation's own duration.
        workers : int or None
            Processes for a sweep (None: one per core; 1, the default: this process).
        progress : callable, optional
            ``progress(done, total)`` as runs finish.

        Raises
        ------
        SimulationDiverged
            When a run leaves the physical range.
        """
        settings = self.settings
        if duration is not None:
            settings = dataclasses.replace(settings, duration=duration)
        return run_batch(self.runs(), settings=settings, workers=workers, progress=progress)

    def current_note(self, rows: Sequence[Mapping[str, Any]]) -> str | None:
        """A note when the controller left the drive current near zero, else None.

        A gain tuned for one vehicle (the dissertation's quarter car) can leave a law's
        current at a few percent of ``max_current`` on another (a full car), which then
        runs as a passive damper at 0 A. ``rows``: the measures of the scenario's runs;
        the note is given when every run's mean current (every corner's) stays below
        :data:`LOW_CURRENT_SHARE` of ``max_current`` for a law that sets the current.

        Examples
        --------
        >>> s = Scenario.from_dict({"controller": {"law": "skyhook-hilo", "gain": 2.0},
        ...                         "excitation": {"kind": "pulse", "amplitude": 0.02,
        ...                                        "severity": 1.0}})
        >>> print(s.current_note([{"mean_current": 0.004}]))
        skyhook-hilo drew a mean current of 0.004 A at most (0.8 % of max_current = 0.5 A): its gain (gain = 2) may suit another vehicle; tune it (mrsus optimize) or check [controller]
        >>> s.current_note([{"mean_current": 0.2}]) is None
        True
        """
        law = str(self.data.get("controller", {}).get("law", self.controller.law))
        if law == "passive" or self.max_current <= 0.0:
            return None
        currents = [
            float(v)
            for row in rows
            for k, v in row.items()
            if (k == "mean_current" or k.startswith("mean_current.")) and v is not None
        ]
        if not currents or max(currents) >= LOW_CURRENT_SHARE * self.max_current:
            return None
        peak = max(currents)
        table = self.data.get("controller", {})
        gains = [f"{k} = {table[k]:g}" for k in ("gain", "heave", "pitch", "roll") if k in table]
        if not gains and "gain" in self.controller.describe():
            gains = [f"gain = {self.controller.describe()['gain']:g}"]
        what = f"its gain ({', '.join(gains)})" if gains else "its gains"
        return (
            f"{law} drew a mean current of {peak:.3g} A at most "
            f"({100 * peak / self.max_current:.1f} % of max_current = {self.max_current:g} A): "
            f"{what} may suit another vehicle; tune it (mrsus optimize) or check [controller]"
        )

    def to_dict(self) -> dict[str, dict[str, Any]]:
        """The scenario as plain tables (TOML-ready), with the defaults filled in.

        ``Scenario.from_dict(s.to_dict(), s.base_dir)`` rebuilds an equal scenario.
        """
        out = copy.deepcopy(self.data)
        out["vehicle"] = dataclasses.asdict(self.vehicle)
        if self.model != "quarter-car":
            out["vehicle"] = {"model": self.model, **out["vehicle"]}
        out["damper"] = {
            "model": self.damper.name,
            **out["damper"],
            "max_current": self.max_current,
        }
        out["controller"] = {"law": self.controller.law, **out["controller"]}
        if self.body_control is not None:  # the vehicle's law, its gains resolved
            out["controller"] = self.body_control.describe()
        if self.sensing is not None and self.sensing.velocity is not None:
            out["sensing"].setdefault("fs", self.sensing.velocity.fs)
        out["simulation"] = self.settings.to_dict()
        return out


# -- measures of any run --------------------------------------------------------------------
def run_measures(result: SimulationResult, **kwargs: Any) -> dict[str, Any]:
    """The measures of a scenario's run: ``result.measures(**kwargs)``.

    The quarter car's measures, or a half or full car's body RMS accelerations
    (:data:`~mrsuspension.engine.vehicle_result.BODY_MEASURES`) and every corner's measures
    ``"<measure>.<corner>"`` (:meth:`VehicleResult.measures
    <mrsuspension.engine.vehicle_result.VehicleResult.measures>`). A module-level function, so
    it can reduce results in worker processes.

    Examples
    --------
    >>> s = Scenario.from_dict({"vehicle": {"model": "half-car"},
    ...                         "excitation": {"kind": "harmonic", "frequency": 5.0,
    ...                                        "amplitude": 0.005}})
    >>> m = run_measures(s.run()[0])  # the harmonic's steady-state rule: 10 cycles settled
    >>> list(m)[:3], 0.0 < m["T_as.rear"] < 1.0
    (['heave_ddot_rms', 'pitch_ddot_rms', 'T_as.front'], True)
    """
    return result.measures(**kwargs)


# -- section builders ---------------------------------------------------------------------
def _build_vehicle(table: dict[str, Any]) -> tuple[Plant, Any]:
    """``[vehicle]``: ``(the model, its parameters)``: quarter car by default, a published
    set, overrides."""
    name = _choice("vehicle", "model", table.get("model", "quarter-car"), PLANTS)
    model = PLANTS[name]
    allowed = _model_keys(model)
    for key in table:
        if key not in _VEHICLE_KEYS:
            raise _unknown_key("vehicle", key, allowed)
        if key not in allowed:
            valid = sorted(allowed)
            raise ValidationError(
                f"{_where('vehicle', key)} does not apply to model {name!r}."
                f"{did_you_mean(key, valid)} Its keys: {', '.join(valid)}."
            )
    values = {k: v for k, v in table.items() if k not in ("model", "set")}
    with _in_section("vehicle"):
        if "set" in table and model.sets is not None:
            _choice("vehicle", "set", table["set"], dict.fromkeys(model.sets()))
        return model, model.make_params(values, table.get("set"))


def _split_corners(
    section: str, table: dict[str, Any], corners: tuple[str, ...]
) -> tuple[dict[str, Any], dict[str, dict[str, Any]]]:
    """``(main table, {corner: its override table})``; checks the corner names."""
    main = {k: v for k, v in table.items() if not isinstance(v, dict)}
    subs = {k: v for k, v in table.items() if isinstance(v, dict)}
    if subs and not corners:
        first = next(iter(subs))
        raise ValidationError(
            f"[{section}.{first}]: per-corner tables need a half or full car "
            "([vehicle] model = 'half-car' or 'full-car'); a quarter car has one corner"
        )
    for name in subs:
        if name not in corners:
            raise ValidationError(
                f"unknown corner table [{section}.{name}].{did_you_mean(name, corners)} "
                f"Valid corners: {', '.join(corners)}."
            )
    return main, {c: subs.get(c, {}) for c in corners}


def _corner_table(
    main: dict[str, Any], override: dict[str, Any], kind_key: str, default: str
) -> dict[str, Any]:
    """A corner's table: the main table with the corner's keys on top.

    A corner that names another ``model`` (damper) or ``law`` (controller) starts from
    that model's or law's defaults: the main table's other keys are not inherited.
    """
    if kind_key in override and override[kind_key] != main.get(kind_key, default):
        keep = {"max_current": main["max_current"]} if "max_current" in main else {}
        return {**keep, **override}
    return {**main, **override}


def _build_damper(
    table: dict[str, Any], base: Path, section: str = "damper"
) -> tuple[DamperModel, float]:
    model = _choice(section, "model", table.get("model", "wang-symmetric"), DAMPERS)
    with _in_section(section):
        allowed = tuple(damper_options(model))  # derived from the model class
    for key in table:
        if key not in allowed:
            raise ValidationError(
                f"{_where(section, key)} does not apply to model {model!r}; "
                f"its keys: {', '.join(allowed)}"
            )
    options = {k: v for k, v in table.items() if k not in ("model", "parameters", "max_current")}
    if model.startswith("wang-") and "vh_variant" not in options:
        options["vh_variant"] = VEHICLE_VH_VARIANT  # the vehicle default (docs/errata.md)
    if "estimator" in options:
        _choice(section, "estimator", options["estimator"], ESTIMATORS)
    parameters: str | Path | None = None
    if "parameters" in table:
        parameters = _parameter_spec(table["parameters"], base, section)
    max_current = table.get("max_current", _DEFAULT_MAX_CURRENT)
    with _in_section(section):
        damper = make_damper(model, parameters, **options)
    return damper, max_current


def _parameter_spec(text: str, base: Path, section: str = "damper") -> str | Path:
    """A registered set name stays a name; anything path-like is taken from ``base``."""
    path = Path(text).expanduser()
    candidate = path if path.is_absolute() else base / path
    looks_like_file = text.lower().endswith((".toml", ".json")) or len(path.parts) > 1
    if candidate.is_file():
        return candidate
    if looks_like_file:
        raise ValidationError(
            f"[{section}] parameters: no such parameter file {text!r} "
            f"(looked for {str(candidate)!r})"
        )
    return text


def _build_controller(
    table: dict[str, Any], section: str = "controller", base: Path | None = None
) -> Controller:
    spec = table.get("law", "passive")
    if is_law_spec(spec):  # a user-defined law: its options as keyword arguments
        given = {k: v for k, v in table.items() if k != "law"}
        with _in_section(section):
            cls = load_law(str(spec), base=base)
            try:
                return cls(**given)
            except TypeError:
                names = cls.option_names()
                bad = [k for k in given if k not in names]
                raise ValidationError(
                    f"law {spec!r} has no option {bad[0]!r}.{did_you_mean(bad[0], names)} "
                    f"Its options: {', '.join(names) or 'none'}."
                ) from None
    law = _choice(section, "law", spec, CONTROLLERS)
    keys = _law_keys(law)
    options: dict[str, Any] = {}
    for key, value in table.items():
        if key == "law":
            continue
        if key not in keys:
            valid = sorted(keys)
            raise ValidationError(
                f"{_where(section, key)} does not apply to law {law!r}."
                f"{did_you_mean(key, valid)} Its keys: {', '.join(valid)}."
            )
        kw = keys[key]
        if kw in options:
            raise ValidationError(
                f"[{section}] {key}: {kw!r} is given twice (as {key!r} and another name)"
            )
        options[kw] = value
    with _in_section(section):
        return make_controller(law, **options)


def _build_body_control(
    table: dict[str, Any],
    corner_tables: Mapping[str, Mapping[str, Any]],
    vehicle: Any,
    corners: tuple[str, ...],
) -> VehicleLaw | None:
    """``[controller] law`` = a whole-vehicle law (:data:`~mrsuspension.control.VEHICLE_LAWS`),
    attached to the vehicle (e.g. modal skyhook's gains: the corner equivalent of the
    skyhook reference's 6750 N s/m when none is given); else None.
    """
    law = table.get("law")
    if law not in LAW_PLUGINS:
        return None
    if not corners:
        per_corner = getattr(LAW_PLUGINS[str(law)], "per_corner", None)
        alternative = (
            f"on the quarter car it is the per-corner law {per_corner!r}"
            if per_corner
            else "the quarter car's skyhook laws: skyhook-hilo, ideal-skyhook, ideal-onoff"
        )
        raise ValidationError(
            f"[controller] law {law!r} drives a whole vehicle: it needs [vehicle] model = "
            f"'half-car' or 'full-car' ({alternative})"
        )
    given = [c for c, t in corner_tables.items() if t]
    if given:
        raise ValidationError(
            f"[controller.{given[0]}]: law {law!r} sets every corner's current; per-corner "
            "controller tables do not apply"
        )
    keys = LAW_PLUGINS[str(law)].options()
    options = {k: v for k, v in table.items() if k != "law"}
    for key in options:
        if key not in keys:
            raise ValidationError(
                f"{_where('controller', key)} does not apply to law {law!r}."
                f"{did_you_mean(key, keys)} Its keys: {', '.join(sorted(keys))}."
            )
    with _in_section("controller"):
        return LAW_PLUGINS[str(law)](**options).for_vehicle(vehicle)


def _build_sensing(
    table: dict[str, Any], corners: tuple[str, ...], simulation: Mapping[str, Any]
) -> Sensing | None:
    """``[sensing]``: the body-velocity estimator and the stroke sensor of every corner."""
    if not table:
        return None
    if not corners:
        raise ValidationError(
            "[sensing] applies to half and full cars ([vehicle] model = 'half-car' or "
            "'full-car'); the quarter car's controllers measure ideally"
        )
    kind = _choice("sensing", "velocity", table.get("velocity", "ideal"), _VELOCITY_ESTIMATORS)
    own = _VELOCITY_ESTIMATORS
    for key in ("tau", "corner", "zeta"):
        if key in table and key not in own[kind]:
            raise ValidationError(
                f"[sensing] {key} does not apply to velocity = {kind!r} "
                f"(tau: leaky-integrator; corner, zeta: band-pass)"
            )
    if kind == "ideal" and "fs" in table:
        raise ValidationError("[sensing] fs does not apply to velocity = 'ideal'")
    dt = simulation.get("dt", RunSettings().dt)  # checked with [simulation] later
    fs = float(table.get("fs", min(1000.0, 1.0 / dt) if dt > 0 else 1000.0))
    with _in_section("sensing"):
        velocity: LeakyIntegrator | BandPassObserver | None = None
        if kind == "leaky-integrator":
            if "tau" not in table:
                raise ValidationError("velocity = 'leaky-integrator' needs tau [s]")
            velocity = LeakyIntegrator(table["tau"], fs)
        elif kind == "band-pass":
            if "corner" not in table:
                raise ValidationError("velocity = 'band-pass' needs corner [Hz]")
            velocity = BandPassObserver(table["corner"], fs, **(
                {"zeta": table["zeta"]} if "zeta" in table else {}))  # fmt: skip
        stroke: StrokeSensor | None = None
        extra = [k for k in ("stroke_resolution", "stroke_noise", "stroke_seed") if k in table]
        if "stroke_fs" in table:
            stroke = StrokeSensor(
                table["stroke_fs"],
                resolution=table.get("stroke_resolution", 0.0),
                noise_std=table.get("stroke_noise", 0.0),
                seed=table.get("stroke_seed", 0),
            )
        elif extra:
            raise ValidationError(
                f"{', '.join(extra)} need stroke_fs (the stroke sensor's sample rate [Hz])"
            )
        return Sensing(velocity, stroke)


def _build_any_excitation(
    table: dict[str, Any], base: Path, model: Plant, vehicle: Any
) -> tuple[Excitation | SteppedSweep | WheelRoads, float | None]:
    """``[excitation]`` of any model: ``(excitation, speed [km/h] of a speedless kind)``."""
    kind = table.get("kind")
    if not model.wheel_roads:
        if kind in WHEEL_KINDS:
            raise ValidationError(
                f"[excitation] kind {kind!r} gives a road per wheel: it needs [vehicle] "
                f"model = 'half-car' or 'full-car' (a {model.name} has one road)"
            )
        return _build_excitation(table, base), None
    if kind in WHEEL_KINDS:
        return _build_wheel_roads(str(kind), table, base, vehicle), None
    speed: float | None = None
    if kind in _SPEEDLESS_KINDS:
        table = dict(table)
        speed = table.pop("speed", REFERENCE_SPEED_KMH)
        with _in_section("excitation"):
            positive("speed", speed, "km/h", high=500.0)
    return _build_excitation(table, base, extra_kinds=WHEEL_KINDS), speed


def _build_wheel_roads(
    kind: str, table: dict[str, Any], base: Path, car: VehicleBody
) -> WheelRoads:
    """A wheel-only ``[excitation]`` kind (two-track, crg, bump, pothole) for ``car``."""
    valid = WHEEL_KINDS[kind]
    options = {k: v for k, v in table.items() if k != "kind"}
    for key, value in options.items():
        if key not in valid:
            raise _unknown_key("excitation", key, ["kind", *valid], extra=f" for kind {kind!r}")
        options[key] = _typed("excitation", key, value, valid[key][0])
    for key, (_, required) in valid.items():
        if required and key not in options:
            raise ValidationError(f"[excitation] {key} is required for kind {kind!r}")
    speed = options.pop("speed", REFERENCE_SPEED_KMH)
    with _in_section("excitation"):
        if kind == "two-track":
            if "iso_class" in options and "profile" in options:
                raise ValidationError(
                    "give iso_class (an ISO 8608 class A-H) or profile (a preset), not both"
                )
            road = options.pop("iso_class", None) or options.pop("profile", "rough")
            return WheelRoads.two_track(road, car, speed, **options)
        if kind == "crg":
            path = Path(options.pop("file")).expanduser()
            return WheelRoads.from_crg(path if path.is_absolute() else base / path, car, speed,
                                       **options)  # fmt: skip
        if kind == "bump":
            return WheelRoads.bump(
                options.pop("side"), options.pop("height"), options.pop("length"), car, speed,
                **options,
            )  # fmt: skip
        return WheelRoads.pothole(
            options.pop("side"), options.pop("depth"), options.pop("length"), car, speed, **options
        )


def _build_excitation(
    table: dict[str, Any], base: Path, extra_kinds: Mapping[str, Any] | None = None
) -> Excitation | SteppedSweep:
    kinds = {**EXCITATIONS, **(extra_kinds or {})}
    if "kind" not in table:
        raise ValidationError(f"[excitation] kind is required: one of {', '.join(sorted(kinds))}")
    kind = _choice("excitation", "kind", table["kind"], kinds)
    valid = EXCITATION_OPTIONS[kind]
    options = {k: v for k, v in table.items() if k != "kind"}
    for key in options:
        if key not in valid:
            raise _unknown_key("excitation", key, ["kind", *valid], extra=f" for kind {kind!r}")
    profile = options.get("profile")
    if kind == "road" and isinstance(profile, str) and profile not in PRESET_ROADS:
        path = Path(profile)
        bare = path.suffix == "" and len(path.parts) == 1
        if bare and not (base / path).exists():
            names = sorted(PRESET_ROADS)
            raise ValidationError(
                f"[excitation] profile: unknown road profile {profile!r}: not a preset and no "
                f"such file.{did_you_mean(profile, names)} Presets: {', '.join(names)}."
            )
    with _in_section("excitation"):
        return make_excitation(kind, base_dir=base, **options)
