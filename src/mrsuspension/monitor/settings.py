"""Monitor page settings -> a validated :class:`~mrsuspension.scenario.Scenario`.

The page sends a flat dictionary of its form fields; :func:`scenario_from_settings` turns
it into scenario tables and validates them with :meth:`Scenario.from_dict` (and by
building the simulation), so an invalid entry raises
:class:`~mrsuspension.errors.ValidationError` before anything reaches the loop.

The controller part of the form is derived from the controller registry
(:data:`~mrsuspension.control.CONTROLLERS`): :func:`monitor_laws` are the registered laws
that drive the MR damper, :func:`controller_forms` their options as the page builds its
fields (``GET /api/controllers``), so a new law needs no edit here.

The vehicle part is derived from the scenario's declarations in the same way: the models
are the plant registry's (:data:`~mrsuspension.engine.plants.PLANTS`: the quarter car,
and the half and full car with their published sets and corners), the whole-vehicle laws
and their keys :data:`~mrsuspension.scenario.VEHICLE_LAWS` (offered for a car beside the
corner laws, their defaults what the scenario builds), and the sensing group the
``[sensing]`` keys (:data:`~mrsuspension.scenario.SCENARIO_KEYS`, the velocity
estimators and their keys). :func:`vehicle_forms` gives the page the models and the
sensing fields (``GET /api/vehicles``). A car runs with one corner's damper on the rig
(``rig_corner``) and the rest of the car simulated in the loop (docs/hil.md).
"""

from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import CONTROLLERS, ControlOption, law_options, make_controller
from mrsuspension.engine.plants import PLANTS
from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import PRESET_ROADS, Excitation
from mrsuspension.excitation.base import grid_args
from mrsuspension.scenario import _VELOCITY_ESTIMATORS, SCENARIO_KEYS, VEHICLE_LAWS, Scenario
from mrsuspension.vehicle import QuarterCar

if TYPE_CHECKING:
    from mrsuspension.engine.vehicle import VehicleSimulation

__all__ = [
    "DEFAULT_LAW",
    "DEFAULT_MODEL",
    "EXCITATIONS",
    "FIELD_SYMBOLS",
    "VEHICLE_FIELDS",
    "MonitorSettings",
    "ZeroRoad",
    "controller_forms",
    "controller_table",
    "monitor_laws",
    "monitor_models",
    "page_fields",
    "page_options",
    "scenario_from_settings",
    "sensing_table",
    "vehicle_forms",
    "vehicle_law_options",
    "vehicle_law_table",
]

#: law the page starts with (the skyhook hi-lo of the HiL demonstration, docs/monitor.md)
DEFAULT_LAW = "skyhook-hilo"
#: the page's defaults where they differ from the law's: the asymmetric mode ACM (p = 0)
#: of the HiL demonstration (the laws default to SCM)
PAGE_DEFAULTS: dict[str, Any] = {"mode": "ACM"}
#: option given on the page -> option it overrides (an explicit p overrides SCM/ACM)
_OVERRIDES = {"p": "mode"}
#: excitation choices of the page
EXCITATIONS = ("zero", "harmonic", "pulse", "road")
#: drive-current limit of the monitored run [A] (the HiL safety limit)
MAX_CURRENT = 0.3
#: placeholder excitation used to validate a "zero input" run (then replaced by ZeroRoad)
_ZERO_PLACEHOLDER = {"kind": "harmonic", "frequency": 1.0, "amplitude": 0.01}
#: vehicle parameters of the page (form field -> QuarterCar field, label)
VEHICLE_FIELDS: dict[str, str] = {
    "sprung_mass": "m_s [kg]",
    "unsprung_mass": "m_u [kg]",
    "suspension_stiffness": "k_s [N/m]",
    "tire_stiffness": "k_t [N/m]",
    "tire_damping": "c_t [N s/m]",
}
#: vehicle model the page starts with
DEFAULT_MODEL = "quarter-car"
#: how the page labels the keys of a whole-vehicle law and of ``[sensing]``: key ->
#: (model-reference symbol, unit). Only the labels: the keys themselves come from the
#: scenario (:data:`~mrsuspension.scenario.VEHICLE_LAWS`, ``SCENARIO_KEYS["sensing"]``),
#: and a key not named here is offered under its own name. A unit ``A`` is a drive
#: current, capped at :data:`MAX_CURRENT` like a corner law's.
FIELD_SYMBOLS: dict[str, tuple[str, str]] = {
    "heave": ("c_z", "N s/m"),
    "pitch": ("c_theta", "N m s/rad"),
    "roll": ("c_phi", "N m s/rad"),
    "damping": ("c_s", "N s/m"),
    "low_current": ("i_low", "A"),
    "high_current": ("i_high", "A"),
    "tau": ("tau", "s"),
    "corner": ("f_c", "Hz"),
    "zeta": ("zeta", ""),
    "fs": ("f_s", "Hz"),
    "stroke_fs": ("stroke f_s", "Hz"),
    "stroke_resolution": ("stroke resolution", "m"),
    "stroke_noise": ("stroke noise sd", "m"),
    "stroke_seed": ("noise seed", ""),
}


@dataclass(frozen=True)
class ZeroRoad(Excitation):
    """Zero road input (the monitor's "zero input" excitation).

    Examples
    --------
    >>> ZeroRoad().displacement([0.0, 1.0]).tolist()
    [0.0, 0.0]
    """

    name: ClassVar[str] = "zero"

    def displacement(self, t: npt.ArrayLike) -> np.ndarray:
        """0 m at every time."""
        return np.zeros(np.shape(t))

    def velocity(self, t: npt.ArrayLike) -> np.ndarray:
        """0 m/s at every time."""
        return np.zeros(np.shape(t))

    def acceleration(self, t: npt.ArrayLike) -> np.ndarray:
        """0 m/s^2 at every time."""
        return np.zeros(np.shape(t))

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Zeros on any grid (the live HiL road takes it one tick at a time).

        Examples
        --------
        >>> ZeroRoad().sample_grid(3, 1e-4, start=2.0)[1].tolist()
        [0.0, 0.0, 0.0]
        """
        n, step, start = grid_args(n, step, start)
        return np.zeros(n), np.zeros(n)

    @property
    def duration(self) -> float:
        """10 s."""
        return 10.0

    def describe(self) -> dict[str, Any]:
        """``{"kind": "zero"}``."""
        return {"kind": "zero"}


@dataclass(frozen=True)
class MonitorSettings:
    """A validated monitor configuration.

    Attributes
    ----------
    tables : dict
        Scenario tables (as for :meth:`Scenario.from_dict`).
    zero_input : bool
        True when the road is held at zero (the tables then carry a placeholder excitation).
    rate : float
        Loop rate [Hz].
    duration : float
        Longest run [s] (STOP ends it earlier).
    ramp_time : float
        Ramp of the drive current after a live controller change [s].
    corner : str, optional
        A half or full car's rig corner (the corner whose damper is on the rig); None for
        a quarter car.
    """

    tables: dict[str, dict[str, Any]]
    zero_input: bool
    rate: float
    duration: float
    ramp_time: float = 0.2
    corner: str | None = None

    def scenario(self) -> Scenario:
        """The scenario of these settings."""
        return Scenario.from_dict(self.tables)

    def simulation(self, base: Simulation | None = None) -> Simulation | VehicleSimulation:
        """The run of these settings (validated): a quarter car's
        :class:`~mrsuspension.engine.simulate.Simulation`, or a half or full car's
        :class:`~mrsuspension.engine.vehicle.VehicleSimulation` (every wheel on the road).

        Parameters
        ----------
        base : Simulation, optional
            A running quarter-car configuration (e.g. a scenario file's) whose damper and
            estimator are kept; its controller, excitation and vehicle are replaced by
            these. Not used for a car: the form gives the whole car.
        """
        # a zero road replaces the placeholder (under every wheel of a car)
        run = self.scenario().runs([ZeroRoad()] if self.zero_input else None)[0]
        if self.corner is not None:
            car: VehicleSimulation = run  # type: ignore[assignment]
            return car
        sim: Simulation = run  # type: ignore[assignment]
        if base is not None:
            sim = dataclasses.replace(
                base,
                controller=sim.controller,
                excitation=sim.excitation,
                vehicle=sim.vehicle,
                max_current=min(base.max_current, MAX_CURRENT),
            )
        return sim

    def to_dict(self) -> dict[str, Any]:
        """Plain data (picklable, for the loop process)."""
        return {
            "tables": self.tables,
            "zero_input": self.zero_input,
            "rate": self.rate,
            "duration": self.duration,
            "ramp_time": self.ramp_time,
            "corner": self.corner,
        }


def _number(settings: Mapping[str, Any], key: str, default: float, label: str) -> float:
    raw = settings.get(key, default)
    if raw is None or raw == "":
        raw = default
    return _as_number(raw, label)


def _as_number(raw: Any, label: str) -> float:
    try:
        value = float(raw)
    except (TypeError, ValueError):
        raise ValidationError(f"{label} must be a number; got {raw!r}") from None
    if not math.isfinite(value):
        raise ValidationError(f"{label} must be finite; got {raw!r}")
    return value


def _text(settings: Mapping[str, Any], key: str) -> str | None:
    """The page's text of ``key``, None when missing or blank."""
    raw = settings.get(key)
    if raw is None or str(raw).strip() == "":
        return None
    return str(raw).strip()


def _choice(settings: Mapping[str, Any], key: str, choices: tuple[str, ...], default: str) -> str:
    value = _text(settings, key) or default  # blank: the default
    if value not in choices:
        raise ValidationError(f"unknown {key} {value!r}; valid: {', '.join(choices)}")
    return value


def monitor_laws() -> tuple[str, ...]:
    """The controller laws the monitor runs: every registered law that drives the MR damper.

    The ideal references (an ideal dissipative damper in place of the MR damper) have no
    drive current for the rig, so they are left out
    (:attr:`~mrsuspension.control.Controller.drives_damper`).

    Examples
    --------
    >>> laws = monitor_laws()
    >>> "skyhook-hilo" in laws, "ideal-skyhook" in laws
    (True, False)
    """
    return tuple(law for law in CONTROLLERS if make_controller(law).drives_damper)


def page_options(law: str) -> list[ControlOption]:
    """The options of ``law`` as the monitor offers them (:func:`law_options`, adapted).

    A drive current (unit ``A``) is capped at the HiL limit :data:`MAX_CURRENT` (its
    default too) and :data:`PAGE_DEFAULTS` replace the law's defaults.

    Examples
    --------
    >>> [(o.name, o.default, o.high) for o in page_options("passive")]
    [('current', 0.0, 0.3)]
    >>> [o.default for o in page_options("skyhook-hilo") if o.name == "mode"]
    ['ACM']
    """
    return [_page_option(opt) for opt in law_options(law)]


def _page_option(opt: ControlOption) -> ControlOption:
    """``opt`` as the page offers it: a current capped at :data:`MAX_CURRENT`, the page's
    defaults."""
    if opt.unit == "A" and (opt.high is None or opt.high >= MAX_CURRENT):
        default = opt.default
        if isinstance(default, int | float) and default > MAX_CURRENT:
            default = MAX_CURRENT
        opt = dataclasses.replace(opt, high=MAX_CURRENT, high_open=False, default=default)
    if opt.name in PAGE_DEFAULTS:
        page = PAGE_DEFAULTS[opt.name]
        if opt.choices is None or page in opt.choices:
            opt = dataclasses.replace(opt, default=page)
    return opt


def _form_field(opt: ControlOption) -> dict[str, Any]:
    """One option as the page builds its field (label: model-reference symbol and unit)."""
    label = opt.symbol or opt.name
    if opt.unit:
        label += f" [{opt.unit}]"
    return {
        "name": opt.name,
        "label": label,
        "symbol": opt.symbol,
        "unit": opt.unit,
        "default": opt.default,
        "min": opt.low,
        "max": opt.high,
        "min_open": opt.low_open,
        "max_open": opt.high_open,
        "choices": None if opt.choices is None else list(opt.choices),
    }


def controller_forms() -> dict[str, Any]:
    """The page's controller choices and their fields (``GET /api/controllers``).

    Returns
    -------
    dict
        ``default`` (the law the page starts with) and ``controllers``: for each of
        :func:`monitor_laws`, ``law``, ``vehicle`` (False: a corner law, for every model)
        and ``options`` (each with ``name``, ``label``, ``symbol``, ``unit``,
        ``default``, ``min``, ``max``, ``min_open``, ``max_open`` and, for a text option,
        ``choices``), as :func:`page_options` gives them; then each whole-vehicle law of
        :data:`~mrsuspension.scenario.VEHICLE_LAWS` (``vehicle``: True, a half or full
        car only) with its options (:func:`vehicle_law_options`, defaults of the first
        car model) and ``defaults``: model -> option -> the default on that model.

    Examples
    --------
    >>> forms = controller_forms()
    >>> forms["default"], [o["label"] for o in forms["controllers"][0]["options"]]
    ('skyhook-hilo', ['i [A]'])
    >>> modal = next(c for c in forms["controllers"] if c["law"] == "modal-skyhook")
    >>> modal["vehicle"], modal["defaults"]["full-car"]["heave"]  # 4 corners x 6750 N s/m
    (True, 27000.0)
    """
    laws = monitor_laws()
    out: list[dict[str, Any]] = [
        {"law": law, "vehicle": False, "options": [_form_field(o) for o in page_options(law)]}
        for law in laws
    ]
    cars = _car_models()
    for law in VEHICLE_LAWS if cars else ():
        out.append(
            {
                "law": law,
                "vehicle": True,
                "options": [_form_field(o) for o in vehicle_law_options(law, cars[0])],
                "defaults": {
                    m: {o.name: o.default for o in vehicle_law_options(law, m)} for m in cars
                },
            }
        )
    return {"default": _default_law(laws), "controllers": out}


def monitor_models() -> tuple[str, ...]:
    """The vehicle models the page offers: every registered plant
    (:data:`~mrsuspension.engine.plants.PLANTS`).

    Examples
    --------
    >>> monitor_models()
    ('quarter-car', 'half-car', 'full-car')
    """
    return tuple(PLANTS)


def _car_models() -> tuple[str, ...]:
    """The models with corners (a damper per corner: the rig takes one of them)."""
    return tuple(m for m in PLANTS if PLANTS[m].corners)


def _symbol_unit(key: str) -> tuple[str, str]:
    return FIELD_SYMBOLS.get(key, ("", ""))


@functools.lru_cache(maxsize=64)
def _vehicle_law_defaults(
    law: str, model: str, set_name: str | None
) -> tuple[tuple[str, Any], ...]:
    """What the scenario builds for a whole-vehicle law's keys without options, on
    ``model`` (its published set ``set_name``, or its default parameters); None for a
    key of a law that cannot be built without options (the scenario then asks for it)."""
    vehicle: dict[str, Any] = {"model": model}
    if set_name is not None:
        vehicle["set"] = set_name
    tables = {"vehicle": vehicle, "controller": {"law": law}, "excitation": _ZERO_PLACEHOLDER}
    try:
        built = Scenario.from_dict(tables).body_control
    except ValidationError:
        built = None
    out = []
    for key in VEHICLE_LAWS[law]:
        value = getattr(built, key, None)
        if isinstance(value, float):  # 37304.28, not 37304.280000000006, on the page
            value = float(f"{value:.12g}")
        out.append((key, value))
    return tuple(out)


def vehicle_law_options(law: str, model: str, set_name: str | None = None) -> list[ControlOption]:
    """The options of the whole-vehicle ``law`` on a car ``model``, as the page offers them.

    The keys are the scenario's (:data:`~mrsuspension.scenario.VEHICLE_LAWS`), their
    defaults what the scenario builds for that car (modal skyhook: the corner equivalent
    of 6750 N s/m), labelled from :data:`FIELD_SYMBOLS`; a drive current is capped at
    :data:`MAX_CURRENT`. The ranges of the gains are the law's to check (through the
    scenario).

    Examples
    --------
    >>> [(o.name, o.default, o.high) for o in vehicle_law_options("corner-skyhook", "half-car")]
    [('damping', 6750.0, None), ('low_current', 0.0, 0.3), ('high_current', 0.3, 0.3)]
    """
    out = []
    for key, default in _vehicle_law_defaults(law, model, set_name):
        symbol, unit = _symbol_unit(key)
        low = 0.0 if unit == "A" else None  # a drive current; the gains: the law checks
        out.append(_page_option(ControlOption(key, default, unit, low=low, symbol=symbol)))
    return out


def vehicle_law_table(
    law: str, model: str, settings: Mapping[str, Any], set_name: str | None = None
) -> dict[str, Any]:
    """The ``[controller]`` table of the whole-vehicle ``law`` from the page's fields.

    Each key of :func:`vehicle_law_options` is read by name; a blank or missing one
    takes the default the page shows (so a modal skyhook with only ``heave`` given keeps
    the corner-equivalent pitch and roll). Numbers are checked here for the current cap,
    by the scenario for the rest.

    Examples
    --------
    >>> vehicle_law_table("modal-skyhook", "half-car", {"heave": "9000"})
    {'law': 'modal-skyhook', 'heave': 9000.0, 'pitch': 18652.14, 'roll': 0.0, 'low_current': 0.0, 'high_current': 0.3}
    """
    table: dict[str, Any] = {"law": law}
    for opt in vehicle_law_options(law, model, set_name):
        raw = _given(settings, dataclasses.replace(opt, symbol=""))  # by name only
        if raw is None:
            if opt.default is not None:
                table[opt.name] = opt.default
        else:
            table[opt.name] = opt.check(_as_number(raw, opt.name))
    return table


def sensing_table(settings: Mapping[str, Any]) -> dict[str, Any]:
    """The ``[sensing]`` table of a car from the page's fields (``{}``: ideal sensing).

    ``velocity`` is one of the scenario's estimators (blank: ``ideal``); then each other
    ``[sensing]`` key is read by name, a blank one left to the scenario's default. A key
    of another estimator (``tau`` with ``band-pass``) is not read, as the page hides it;
    the stroke sensor's keys belong to every estimator. The scenario checks the values.

    Examples
    --------
    >>> sensing_table({"velocity": "band-pass", "corner": "0.1", "tau": "2"})
    {'velocity': 'band-pass', 'corner': 0.1}
    >>> sensing_table({"velocity": "ideal", "corner": "0.1"})
    {}
    """
    kind = _choice(settings, "velocity", tuple(_VELOCITY_ESTIMATORS), "ideal")
    table: dict[str, Any] = {"velocity": kind}
    for key, value_kind in SCENARIO_KEYS["sensing"].items():
        if key == "velocity":
            continue
        owners = _estimators_of(key)
        raw = _text(settings, key)
        if raw is None or (owners and kind not in owners):
            continue
        label = f"[sensing] {key}"
        value = _as_number(raw, label)
        if value_kind == "integer":
            if not value.is_integer():
                raise ValidationError(f"{label} must be a whole number; got {raw!r}")
            table[key] = int(value)
        else:
            table[key] = value
    return {} if table == {"velocity": "ideal"} else table


def _estimators_of(key: str) -> tuple[str, ...]:
    """The velocity estimators a ``[sensing]`` key belongs to (none: every one)."""
    return tuple(kind for kind, keys in _VELOCITY_ESTIMATORS.items() if key in keys)


def vehicle_forms() -> dict[str, Any]:
    """The page's vehicle models and sensing fields (``GET /api/vehicles``).

    Returns
    -------
    dict
        ``default`` (the model the page starts with); ``models``: for each of
        :func:`monitor_models`, ``model``, ``corners`` (the rig corner's choices; empty
        for the quarter car, which has only its own damper) and ``sets`` (the published
        parameter sets; blank: the model's defaults); ``sensing`` (a car's):
        ``velocity`` (the estimators), ``default`` and ``fields`` (the other
        ``[sensing]`` keys: ``name``, ``label``, ``unit``, ``kind`` and ``velocity``, the
        estimators it belongs to, or None for every one).

    Examples
    --------
    >>> forms = vehicle_forms()
    >>> [(m["model"], len(m["corners"])) for m in forms["models"]]
    [('quarter-car', 0), ('half-car', 2), ('full-car', 4)]
    >>> forms["sensing"]["velocity"]
    ['ideal', 'leaky-integrator', 'band-pass']
    >>> next(f for f in forms["sensing"]["fields"] if f["name"] == "corner")["velocity"]
    ['band-pass']
    """
    models = []
    for name, model in PLANTS.items():
        sets = list(model.sets()) if model.sets is not None else []
        models.append({"model": name, "corners": list(model.corners), "sets": sets})
    fields = []
    for key, value_kind in SCENARIO_KEYS["sensing"].items():
        if key == "velocity":
            continue
        symbol, unit = _symbol_unit(key)
        owners = _estimators_of(key)
        fields.append(
            {
                "name": key,
                "label": (symbol or key) + (f" [{unit}]" if unit else ""),
                "unit": unit,
                "kind": value_kind,
                "velocity": list(owners) or None,
            }
        )
    sensing = {"velocity": list(_VELOCITY_ESTIMATORS), "default": "ideal", "fields": fields}
    return {"default": DEFAULT_MODEL, "models": models, "sensing": sensing}


def _default_law(laws: tuple[str, ...]) -> str:
    """:data:`DEFAULT_LAW`, or the first of ``laws`` when it is not registered."""
    return DEFAULT_LAW if DEFAULT_LAW in laws else laws[0]


def _given(settings: Mapping[str, Any], opt: ControlOption) -> Any:
    """The page's value of ``opt`` (by name, else by its model-reference symbol), or None."""
    for key in (opt.name, opt.symbol):
        raw = settings.get(key) if key else None
        if raw is not None and str(raw).strip() != "":
            return raw
    return None


def controller_table(law: str, settings: Mapping[str, Any]) -> dict[str, Any]:
    """The ``[controller]`` table of ``law`` from the page's fields, validated.

    Each option of :func:`page_options` is read by name (or by its model-reference symbol, e.g.
    ``lambda`` for ``slope``); a blank or missing one takes its default. Numbers are
    checked against the option's range, text against its choices.

    Examples
    --------
    >>> controller_table("sliding-mode", {"lambda": "0.7", "mode": "SCM", "p": "0.5"})["slope"]
    0.7
    >>> controller_table("passive", {"current": "0.9"})
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: current must be in [0, 0.3]; got 0.9
    """
    table: dict[str, Any] = {"law": law}
    explicit: set[str] = set()
    for opt in page_options(law):
        raw = _given(settings, opt)
        if raw is None:
            if opt.default is not None:
                table[opt.name] = opt.default
            continue
        explicit.add(opt.name)
        label = opt.label or opt.name
        if opt.choices is None:
            raw = _as_number(raw, label)
        table[opt.name] = opt.check(raw)
    for key, overridden in _OVERRIDES.items():
        if key in explicit:
            table.pop(overridden, None)
    return table


def scenario_from_settings(
    settings: Mapping[str, Any], road_dir: str | Path | None = None
) -> MonitorSettings:
    """Validate the page's settings and build the scenario tables.

    Parameters
    ----------
    settings : mapping
        Form fields: ``model`` (one of :func:`monitor_models`, blank: the quarter car),
        ``controller`` (one of :func:`monitor_laws`, or for a half or full car a
        whole-vehicle law of :data:`~mrsuspension.scenario.VEHICLE_LAWS`), the law's
        options (:func:`controller_table`: by name or model-reference symbol, blank for
        the default; an explicit ``p`` overrides ``mode``; :func:`vehicle_law_table`),
        ``excitation`` (one of :data:`EXCITATIONS`), ``frequency``, ``amplitude``,
        ``height``, ``severity``, ``speed``, ``profile`` (a preset, or ``file`` with
        ``road_file``), ``road_speed``, ``scale``, ``rate``, ``duration``,
        ``ramp_time``; for the quarter car the vehicle parameters of
        :data:`VEHICLE_FIELDS`; for a half or full car ``set`` (a published set, blank:
        the model's defaults), ``rig_corner`` (the corner whose damper is on the rig,
        blank: the first) and the sensing fields (:func:`sensing_table`). A field of
        another model, law or velocity estimator is not read (the page hides it).
    road_dir : path, optional
        Directory that road files (``road_file``) may be taken from; None: road files are
        refused (the page cannot name arbitrary server paths).

    Returns
    -------
    MonitorSettings
        The validated configuration.

    Raises
    ------
    ValidationError
        For an unknown choice, a non-number or a value the scenario layer refuses.
    """
    model_name = _choice(settings, "model", monitor_models(), DEFAULT_MODEL)
    model = PLANTS[model_name]
    laws = monitor_laws()
    law = _choice(settings, "controller", laws + tuple(VEHICLE_LAWS), _default_law(laws))
    vehicle: dict[str, Any]
    sensing: dict[str, Any] = {}
    corner: str | None = None
    if model.corners:
        vehicle = {"model": model_name}
        set_name = _text(settings, "set")
        if set_name is not None:
            sets = tuple(model.sets()) if model.sets is not None else ()
            if set_name not in sets:
                raise ValidationError(
                    f"unknown set {set_name!r} of the {model_name}; valid: "
                    f"{', '.join(sets) or 'none'} (blank: the model's defaults)"
                )
            vehicle["set"] = set_name
        corner = _text(settings, "rig_corner") or model.corners[0]
        if corner not in model.corners:
            raise ValidationError(
                f"rig corner {corner!r} is not a corner of the {model_name}; valid: "
                f"{', '.join(model.corners)}"
            )
        if law in VEHICLE_LAWS:
            controller = vehicle_law_table(law, model_name, settings, set_name)
        else:
            controller = controller_table(law, settings)
        sensing = sensing_table(settings)
    else:
        if law in VEHICLE_LAWS:
            raise ValidationError(
                f"controller {law!r} drives a whole vehicle: choose model "
                f"{' or '.join(_car_models()) or 'half-car or full-car'} (for the "
                f"{model_name}: {', '.join(laws)})"
            )
        controller = controller_table(law, settings)
        nominal = QuarterCar()
        vehicle = {
            key: _number(settings, key, getattr(nominal, key), key) for key in VEHICLE_FIELDS
        }

    kind = _choice(settings, "excitation", EXCITATIONS, "harmonic")
    excitation: dict[str, Any]
    if kind == "zero":
        excitation = dict(_ZERO_PLACEHOLDER)
    elif kind == "harmonic":
        excitation = {
            "kind": "harmonic",
            "frequency": _number(settings, "frequency", 1.5, "frequency"),
            "amplitude": _number(settings, "amplitude", 0.02, "amplitude"),
        }
    elif kind == "pulse":
        excitation = {
            "kind": "pulse",
            "amplitude": _number(settings, "height", 0.05, "pulse height"),
            "severity": _number(settings, "severity", 1.0, "severity"),
            "speed": _number(settings, "speed", 50.0, "speed"),
        }
    else:
        profile = str(settings.get("profile", "smooth"))
        if profile == "file":
            profile = _road_file(settings.get("road_file"), road_dir)
        elif profile not in PRESET_ROADS:
            raise ValidationError(
                f"unknown road preset {profile!r}; valid: {', '.join(PRESET_ROADS)}, file"
            )
        excitation = {
            "kind": "road",
            "profile": profile,
            "speed": _number(settings, "road_speed", 50.0, "road speed"),
            "scale": _number(settings, "scale", 1.0, "scale"),
        }
    tables: dict[str, dict[str, Any]] = {
        "vehicle": vehicle,
        "damper": {"max_current": MAX_CURRENT},
        "controller": controller,
        "excitation": excitation,
    }
    if sensing:
        tables["sensing"] = sensing
    rate = _number(settings, "rate", 1000.0, "loop rate")
    if not 50.0 <= rate <= 5000.0:
        raise ValidationError(f"loop rate must be in [50, 5000] Hz; got {rate:g} Hz")
    duration = _number(settings, "duration", 60.0, "duration")
    if not 0.0 < duration <= 3600.0:
        raise ValidationError(f"duration must be in (0, 3600] s; got {duration:g} s")
    ramp_time = _number(settings, "ramp_time", 0.2, "ramp time")
    if not 0.0 < ramp_time <= 5.0:
        raise ValidationError(f"ramp time must be in (0, 5] s; got {ramp_time:g} s")
    scenario = Scenario.from_dict(tables)
    scenario.runs()  # builds the run: refuses e.g. a current above i_max
    return MonitorSettings(
        tables=tables,
        zero_input=kind == "zero",
        rate=rate,
        duration=duration,
        ramp_time=ramp_time,
        corner=corner,
    )


def _road_file(name: Any, road_dir: str | Path | None) -> str:
    if road_dir is None:
        raise ValidationError(
            "road files are not enabled on this server (start it with --road-dir DIR); "
            f"use a preset: {', '.join(PRESET_ROADS)}"
        )
    base = Path(road_dir).resolve()
    if not name:
        raise ValidationError(f"road file: give the name of a file in {base}")
    path = (base / str(name)).resolve()
    if base not in path.parents or not path.is_file():
        names = sorted(p.name for p in base.iterdir() if p.is_file()) if base.is_dir() else []
        raise ValidationError(
            f"road file {name!r} is not a file in {base}; valid: {', '.join(names) or 'none'}"
        )
    return str(path)


def page_fields(sim: Simulation) -> dict[str, Any]:
    """The page's form values describing ``sim`` (its vehicle and controller options).

    Examples
    --------
    >>> from mrsuspension.excitation import Harmonic
    >>> page_fields(Simulation(Harmonic(1.5, 0.02)))["sprung_mass"]
    563.0
    """
    out: dict[str, Any] = {key: getattr(sim.vehicle, key) for key in VEHICLE_FIELDS}
    desc = sim.controller.describe()
    if desc["law"] in CONTROLLERS:
        for opt in law_options(desc["law"]):
            if opt.name in desc:
                out[opt.name] = desc[opt.name]
    return out
