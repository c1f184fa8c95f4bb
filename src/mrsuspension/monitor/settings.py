"""Monitor page settings -> a validated :class:`~mrsuspension.scenario.Scenario`.

The page sends a flat dictionary of its form fields; :func:`scenario_from_settings` turns
it into scenario tables and validates them with :meth:`Scenario.from_dict` (and by
building the simulation), so an invalid entry raises
:class:`~mrsuspension.errors.ValidationError` before anything reaches the loop.

The controller part of the form is derived from the controller registry
(:data:`~mrsuspension.control.CONTROLLERS`): :func:`monitor_laws` are the registered laws
that drive the MR damper, :func:`controller_forms` their options as the page builds its
fields (``GET /api/controllers``), so a new law needs no edit here.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import CONTROLLERS, ControlOption, law_options, make_controller
from mrsuspension.engine.simulate import Simulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import PRESET_ROADS, Excitation
from mrsuspension.excitation.base import grid_args
from mrsuspension.scenario import Scenario
from mrsuspension.vehicle import QuarterCar

__all__ = [
    "DEFAULT_LAW",
    "EXCITATIONS",
    "VEHICLE_FIELDS",
    "MonitorSettings",
    "ZeroRoad",
    "controller_forms",
    "controller_table",
    "monitor_laws",
    "page_fields",
    "page_options",
    "scenario_from_settings",
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
    """

    tables: dict[str, dict[str, Any]]
    zero_input: bool
    rate: float
    duration: float
    ramp_time: float = 0.2

    def scenario(self) -> Scenario:
        """The scenario of these settings."""
        return Scenario.from_dict(self.tables)

    def simulation(self, base: Simulation | None = None) -> Simulation:
        """The simulation of these settings (validated).

        Parameters
        ----------
        base : Simulation, optional
            A running configuration (e.g. a scenario file's) whose damper and estimator
            are kept; its controller, excitation and vehicle are replaced by these.
        """
        sim = self.scenario().simulations()[0]
        if self.zero_input:
            sim = dataclasses.replace(sim, excitation=ZeroRoad())
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


def _choice(settings: Mapping[str, Any], key: str, choices: tuple[str, ...], default: str) -> str:
    value = str(settings.get(key, default))
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
    out = []
    for opt in law_options(law):
        if opt.unit == "A" and (opt.high is None or opt.high >= MAX_CURRENT):
            default = opt.default
            if isinstance(default, int | float) and default > MAX_CURRENT:
                default = MAX_CURRENT
            opt = dataclasses.replace(opt, high=MAX_CURRENT, high_open=False, default=default)
        if opt.name in PAGE_DEFAULTS:
            page = PAGE_DEFAULTS[opt.name]
            if opt.choices is None or page in opt.choices:
                opt = dataclasses.replace(opt, default=page)
        out.append(opt)
    return out


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
        :func:`monitor_laws`, ``law`` and ``options`` (each with ``name``, ``label``,
        ``symbol``, ``unit``, ``default``, ``min``, ``max``, ``min_open``, ``max_open``
        and, for a text option, ``choices``), as :func:`page_options` gives them.

    Examples
    --------
    >>> forms = controller_forms()
    >>> forms["default"], [o["label"] for o in forms["controllers"][0]["options"]]
    ('skyhook-hilo', ['i [A]'])
    """
    laws = monitor_laws()
    return {
        "default": _default_law(laws),
        "controllers": [
            {"law": law, "options": [_form_field(o) for o in page_options(law)]} for law in laws
        ],
    }


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
        Form fields: ``controller`` (one of :func:`monitor_laws`), the law's options
        (:func:`controller_table`: by name or model-reference symbol, blank for the default; an
        explicit ``p`` overrides ``mode``), ``excitation``
        (one of :data:`EXCITATIONS`), ``frequency``, ``amplitude``, ``height``,
        ``severity``, ``speed``, ``profile`` (a preset, or ``file`` with ``road_file``),
        ``road_speed``, ``scale``, the vehicle parameters of :data:`VEHICLE_FIELDS`,
        ``rate``, ``duration``, ``ramp_time``.
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
    laws = monitor_laws()
    law = _choice(settings, "controller", laws, _default_law(laws))
    controller = controller_table(law, settings)

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
    nominal = QuarterCar()
    vehicle = {key: _number(settings, key, getattr(nominal, key), key) for key in VEHICLE_FIELDS}
    tables: dict[str, dict[str, Any]] = {
        "vehicle": vehicle,
        "damper": {"max_current": MAX_CURRENT},
        "controller": controller,
        "excitation": excitation,
    }
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
    scenario.simulations()  # builds the simulation: refuses e.g. a current above i_max
    return MonitorSettings(
        tables=tables,
        zero_input=kind == "zero",
        rate=rate,
        duration=duration,
        ramp_time=ramp_time,
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
