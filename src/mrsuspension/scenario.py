"""Scenario files: a quarter-car study described in TOML and validated on load.

A scenario has five tables, whose section and key names are public interface::

    [vehicle]       # QuarterCar: sprung_mass, unsprung_mass, suspension_stiffness,
                    # tire_stiffness, tire_damping, skyhook_damping
    [damper]        # model, parameters, hysteresis, force_gain, max_current, damping, ...
    [controller]    # law, mode, gain, order, current, p, xi, p_c, xi_c, lambda, eps, ...
    [excitation]    # kind (harmonic | swept | pulse | road) and its options
    [simulation]    # duration, dt, output_rate

Every key is optional except ``[excitation] kind`` and the excitation's required options;
defaults are those of the classes (:class:`~mrsuspension.vehicle.QuarterCar`,
:func:`~mrsuspension.dampers.make_damper`, :func:`~mrsuspension.control.make_controller`,
:class:`~mrsuspension.engine.simulate.Simulation`), i.e. the spec's. Unknown sections or
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
mrsuspension.errors.ValidationError: unknown key [vehicle] sprung_mas. Did you mean 'sprung_mass'? Valid: skyhook_damping, sprung_mass, suspension_stiffness, tire_damping, tire_stiffness, unsprung_mass.
"""

from __future__ import annotations

import copy
import dataclasses
import inspect
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mrsuspension.control import CONTROLLERS, Controller, HiLo, make_controller
from mrsuspension.dampers import DAMPERS, ESTIMATORS, DamperModel, damper_options, make_damper
from mrsuspension.dampers.wang import VEHICLE_VH_VARIANT
from mrsuspension.engine.result import SimulationResult
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import Simulation, run_many
from mrsuspension.errors import ValidationError, did_you_mean, read_toml
from mrsuspension.excitation import (
    EXCITATION_OPTIONS,
    EXCITATIONS,
    PRESET_ROADS,
    Excitation,
    SteppedSweep,
    make_excitation,
)
from mrsuspension.vehicle import QuarterCar

__all__ = ["SCENARIO_KEYS", "Scenario"]

# -- the public keys -----------------------------------------------------------------------
# Value kinds: "number", "integer", "bool", "string", "numbers" (a list of numbers),
# "text" (a string; a number is accepted and turned into its text, e.g. vh_variant = 2.12).

_VEHICLE_KEYS = {f.name: "number" for f in dataclasses.fields(QuarterCar)}

#: every ``[damper]`` key of any model (each model's own: :func:`damper_options`)
_DAMPER_KEYS: dict[str, str] = {k: v for m in DAMPERS for k, v in damper_options(m).items()}


#: controller-table key -> constructor keyword, by law (the spec's symbols)
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
    for _key in _law_keys(_law):
        _CONTROLLER_KEYS[_key] = _CONTROLLER_TEXT.get(_key, "number")


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


_EXCITATION_KEYS: dict[str, str] = _excitation_keys()

#: ``[simulation]``: the fields of :class:`~mrsuspension.engine.settings.RunSettings`
_SIMULATION_KEYS = {f.name: "number" for f in dataclasses.fields(RunSettings)}

#: Every section of a scenario file and the keys it accepts (with their value kind).
SCENARIO_KEYS: dict[str, dict[str, str]] = {
    "vehicle": _VEHICLE_KEYS,
    "damper": _DAMPER_KEYS,
    "controller": _CONTROLLER_KEYS,
    "excitation": _EXCITATION_KEYS,
    "simulation": _SIMULATION_KEYS,
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
    if kind == "numbers":
        if not isinstance(value, list) or not all(_is_number(v) for v in value):
            raise ValidationError(f"{where} must be a list of numbers; got {value!r}")
        return [float(v) for v in value]
    raise AssertionError(kind)  # pragma: no cover


def _table(data: Mapping[str, Any], section: str) -> dict[str, Any]:
    """The section's table, typed and with known keys only."""
    raw = data.get(section, {})
    if not isinstance(raw, Mapping):
        raise ValidationError(f"[{section}] must be a table; got {raw!r}")
    keys = SCENARIO_KEYS[section]
    out: dict[str, Any] = {}
    for key, value in raw.items():
        if key not in keys:
            if section == "excitation":  # reported for the kind in _build_excitation
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
    """A validated quarter-car scenario (see the module docstring for the file format).

    Build it with :meth:`load` (a TOML file) or :meth:`from_dict`; the components are
    constructed and checked on load.

    Parameters
    ----------
    vehicle : QuarterCar
        The vehicle (``[vehicle]``).
    damper : DamperModel
        The damper model (``[damper]``).
    controller : Controller
        The control law (``[controller]``).
    excitation : Excitation or SteppedSweep
        The road input (``[excitation]``); a stepped sweep gives one run per frequency.
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
    """

    vehicle: QuarterCar
    damper: DamperModel
    controller: Controller
    excitation: Excitation | SteppedSweep
    max_current: float
    settings: RunSettings
    data: dict[str, dict[str, Any]] = field(default_factory=dict, repr=False)
    base_dir: Path = field(default_factory=Path.cwd)
    source: Path | None = None

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

        with _in_section("vehicle"):
            vehicle = QuarterCar(**tables["vehicle"])
        damper, max_current = _build_damper(tables["damper"], base)
        controller = _build_controller(tables["controller"])
        excitation = _build_excitation(tables["excitation"], base)

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
        )
        sims = scenario._build_simulations()  # checks the damper/controller combination
        with _in_section("simulation"):
            sims[0].check_dt(settings.dt)  # stability: the same model in every run
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
    def excitations(self) -> list[Excitation]:
        """The road inputs of the runs (one, or one harmonic per sweep frequency)."""
        if isinstance(self.excitation, SteppedSweep):
            return list(self.excitation.excitations())
        return [self.excitation]

    def _build_simulations(
        self, excitations: Sequence[Excitation] | None = None
    ) -> list[Simulation]:
        with _in_section("damper"):
            return [
                Simulation(
                    excitation=exc,
                    vehicle=self.vehicle,
                    damper=self.damper,
                    controller=self.controller,
                    max_current=self.max_current,
                )
                for exc in (self.excitations if excitations is None else excitations)
            ]

    def simulations(self, excitations: Sequence[Excitation] | None = None) -> list[Simulation]:
        """One :class:`Simulation` per run (one per frequency for a swept excitation).

        Parameters
        ----------
        excitations : sequence of Excitation, optional
            Other road inputs for this vehicle, damper and controller (e.g. a sweep
            given on the command line); default: the scenario's own.
        """
        return self._build_simulations(excitations)

    def run(
        self,
        *,
        duration: float | None = None,
        workers: int | None = 1,
        progress: Callable[[int, int], None] | None = None,
    ) -> list[SimulationResult]:
        """Run every simulation of the scenario; results in order (one per frequency).

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
        return run_many(
            self.simulations(),
            settings=settings,
            workers=workers,
            progress=progress,
        )

    def to_dict(self) -> dict[str, dict[str, Any]]:
        """The scenario as plain tables (TOML-ready), with the defaults filled in.

        ``Scenario.from_dict(s.to_dict(), s.base_dir)`` rebuilds an equal scenario.
        """
        out = copy.deepcopy(self.data)
        out["vehicle"] = dataclasses.asdict(self.vehicle)
        out["damper"] = {
            "model": self.damper.name,
            **out["damper"],
            "max_current": self.max_current,
        }
        out["controller"] = {"law": self.controller.law, **out["controller"]}
        out["simulation"] = self.settings.to_dict()
        return out


# -- section builders ---------------------------------------------------------------------
def _build_damper(table: dict[str, Any], base: Path) -> tuple[DamperModel, float]:
    model = _choice("damper", "model", table.get("model", "wang-symmetric"), DAMPERS)
    with _in_section("damper"):
        allowed = tuple(damper_options(model))  # derived from the model class
    for key in table:
        if key not in allowed:
            raise ValidationError(
                f"{_where('damper', key)} does not apply to model {model!r}; "
                f"its keys: {', '.join(allowed)}"
            )
    options = {k: v for k, v in table.items() if k not in ("model", "parameters", "max_current")}
    if model.startswith("wang-") and "vh_variant" not in options:
        options["vh_variant"] = VEHICLE_VH_VARIANT  # the vehicle default (docs/errata.md)
    if "estimator" in options:
        _choice("damper", "estimator", options["estimator"], ESTIMATORS)
    parameters: str | Path | None = None
    if "parameters" in table:
        parameters = _parameter_spec(table["parameters"], base)
    max_current = table.get("max_current", _DEFAULT_MAX_CURRENT)
    with _in_section("damper"):
        damper = make_damper(model, parameters, **options)
    return damper, max_current


def _parameter_spec(text: str, base: Path) -> str | Path:
    """A registered set name stays a name; anything path-like is taken from ``base``."""
    path = Path(text).expanduser()
    candidate = path if path.is_absolute() else base / path
    looks_like_file = text.lower().endswith((".toml", ".json")) or len(path.parts) > 1
    if candidate.is_file():
        return candidate
    if looks_like_file:
        raise ValidationError(
            f"[damper] parameters: no such parameter file {text!r} (looked for {str(candidate)!r})"
        )
    return text


def _build_controller(table: dict[str, Any]) -> Controller:
    law = _choice("controller", "law", table.get("law", "passive"), CONTROLLERS)
    keys = _law_keys(law)
    options: dict[str, Any] = {}
    for key, value in table.items():
        if key == "law":
            continue
        if key not in keys:
            valid = sorted(keys)
            raise ValidationError(
                f"{_where('controller', key)} does not apply to law {law!r}."
                f"{did_you_mean(key, valid)} Its keys: {', '.join(valid)}."
            )
        kw = keys[key]
        if kw in options:
            raise ValidationError(
                f"[controller] {key}: {kw!r} is given twice (as {key!r} and another name)"
            )
        options[kw] = value
    with _in_section("controller"):
        return make_controller(law, **options)


def _build_excitation(table: dict[str, Any], base: Path) -> Excitation | SteppedSweep:
    if "kind" not in table:
        raise ValidationError(
            f"[excitation] kind is required: one of {', '.join(sorted(EXCITATIONS))}"
        )
    kind = _choice("excitation", "kind", table["kind"], EXCITATIONS)
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
