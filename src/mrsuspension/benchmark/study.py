"""The benchmark of semi-active laws: tuned on one road, scored on others, against the optimum.

Every law of a set is tuned by the toolkit's optimiser (:func:`~mrsuspension.optimize.optimize`,
one option per law) on a *training* road on each vehicle (the quarter car, and the full
car for its own rows), then scored with that option on the *scoring* roads (ISO 8608
classes, the dissertation's presets, a bump) at each speed, on the quarter car and on the
full car (the law at every corner). Each run gives

* comfort: the Wk-weighted rms body acceleration (quarter car) or the seat's ISO 2631-1
  vibration total value (full car) [m/s^2];
* road holding: the DLC (the mean over the corners on the full car);
* rattle space: the rms stroke [m] (the mean over the corners);
* coil power: ``R <i^2>`` [W] (summed over the corners), ``R`` =
  :data:`~mrsuspension.measures.vehicle.COIL_RESISTANCE`;

each of the first three as a ratio to the passive car (the same damper at 0 A, whose coil
power is 0: the coil power is given in watts), and the benchmark cost

``J = w_c r_c^2 + w_r r_r^2 + w_s r_s^2``

of those ratios: the objective of :class:`~mrsuspension.benchmark.BenchmarkProblem` (the
passive car costs ``w_c + w_r + w_s``). On the quarter car the semi-active optimum of the
same road record and weights (:func:`~mrsuspension.benchmark.semi_active_optimum`) is the
lower bound; ``distance = J / J* - 1``.

Which cost is compared with the optimum's, and why: the law's engine run, scored by its
ratios to the engine's passive run on the same record, against the optimum's cost, which
is its ratios to the model's passive car. Not :meth:`BenchmarkProblem.evaluate` of the
law's recorded force: the engine's damper has hysteresis and a peak-velocity estimator
that the band (the mean branch at a fixed ``v_m``) leaves out, so the recorded force is
not a force of the band and its open-loop replay on the model drifts from the run. Taking
each side's ratios to its own passive car removes the common offset of the two models,
not the difference in how each responds to a law: the optimum is the bound of the band's
model. Each record's *model gap* (:func:`model_gap`: the engine's passive car scored on
the model's, 0.7-18 % on the default set) is the tolerance of the check: a law whose cost
falls below the optimum's by more than that (and more than :data:`BOUND_TOLERANCE`) is
reported in :attr:`BenchmarkResult.violations` (a model or solver error to look at).
``band = "envelope"`` solves the optimum over every force of the engine's hysteretic
damper instead (:class:`~mrsuspension.benchmark.band.MREnvelopeBand`, scaled by the
engine's passive car): a strict but loose bound, held within the solver's tolerance. The
laws through an ideal damper (``ideal-skyhook``: zero force when not dissipative, outside
the MR band) are scored but not held to the bound.

The law set is a list of names; :data:`LAW_TABLE` says which option of each is tuned and
over which range (a law it does not list: its first positive numeric option, a decade
either side of its default). The default set is the table's laws registered in
:data:`~mrsuspension.control.CONTROLLERS` or
:data:`~mrsuspension.control.registry.VEHICLE_LAWS` at call time. A per-corner law
(``CONTROLLERS``) runs on every vehicle of the spec (on the full car at every corner); a
whole-vehicle law (``VEHICLE_LAWS``: ``vehicle-lq``, ``modal-skyhook``, ..., from the
body's heave, pitch and roll) is tuned and scored on the full car only: the quarter car
has no rows of it.

Examples
--------
>>> spec = BenchmarkSpec.quick()
>>> spec.laws[:2], [r.name for r in spec.roads]
(('passive', 'skyhook-hilo'), ['ISO C', 'bump 3 cm'])
>>> BenchmarkSpec.quick().replace(laws=("skyhook-hi-lo",))
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: laws: unknown controller law 'skyhook-hi-lo'. Did you mean 'skyhook-hilo'? Valid: ...
"""

from __future__ import annotations

import dataclasses
import math
import sys
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.errors import MRSuspensionError, ValidationError, check_keys, did_you_mean

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = [
    "LAW_TABLE",
    "BenchmarkResult",
    "BenchmarkRoad",
    "BenchmarkSpec",
    "TunedOption",
    "bound_violations",
    "default_laws",
    "model_gap",
    "run_benchmark",
]

VEHICLES = ("quarter", "full")
#: the engine's step per vehicle [s] (the full car's stiffest corner needs <= 0.235 ms)
ENGINE_DT = {"quarter": 5e-4, "full": 2e-4}
#: every run is recorded at every step: a hi-lo law can switch its current from one step to
#: the next, and a record taking one step in two samples only one of its phases (its
#: measures alias: ``mpc-hilo``'s Wk rms on the bump at 50 km/h is 0.223 m/s^2 from a 1 kHz
#: record of 0.5 ms steps and 0.380 m/s^2 from every step)
OUTPUT_RATE = {vehicle: 1.0 / dt for vehicle, dt in ENGINE_DT.items()}
#: ``(w_c, w_r, w_s)``: comfort, road holding, rattle space (the optimum's default weights)
DEFAULT_WEIGHTS = (1.0, 1.0, 0.1)
#: a cost this far below the optimum's (relative) is a violation of the bound: the
#: solver's tolerance; with the ``"mean"`` band the measured model gap of the record
#: when larger (:func:`bound_violations`)
BOUND_TOLERANCE = 1e-3
#: the optimum's band: ``"mean"`` (:class:`~mrsuspension.benchmark.band.MRBand`, the mean
#: model at a fixed ``v_m``) or ``"envelope"`` (:class:`~mrsuspension.benchmark.band.MREnvelopeBand`:
#: every force of the engine's hysteretic damper over the record's ``v_m`` range)
BANDS = ("mean", "envelope")


def _law_options(law: str) -> list[Any]:
    """The options of a per-corner law (:func:`~mrsuspension.control.registry.law_options`)
    or of a whole-vehicle law (its dataclass fields, unbounded: the law checks them)."""
    from mrsuspension.control.base import ControlOption
    from mrsuspension.control.registry import VEHICLE_LAWS, law_options

    cls = VEHICLE_LAWS.get(law)
    if cls is None:
        return list(law_options(law))
    return [
        ControlOption(f.name, f.default if f.default is not dataclasses.MISSING else None)
        for f in dataclasses.fields(cls)  # type: ignore[arg-type]
    ]


@dataclass(frozen=True)
class TunedOption:
    """The option of a law the benchmark tunes, and its search range.

    ``option`` None: the law's first option with a positive numeric default, over a decade
    either side of it (clipped to the option's valid range), searched in ``log10``.
    """

    option: str | None
    lower: float = math.nan
    upper: float = math.nan
    log: bool = False

    def resolve(self, law: str) -> TunedOption:
        """The option and range for ``law`` (checked against the law's options)."""
        options = {o.name: o for o in _law_options(law) if o.shape is None}
        if self.option is None:
            for o in options.values():
                d = o.default
                if isinstance(d, int | float) and not isinstance(d, bool) and d > 0:
                    lo, hi = float(d) / 10.0, float(d) * 10.0
                    if o.low is not None:
                        lo = max(lo, float(o.low) + (1e-9 if o.low_open else 0.0))
                    if o.high is not None:
                        hi = min(hi, float(o.high))
                    return TunedOption(o.name, lo, hi, log=lo > 0.0)
            raise ValidationError(f"law {law!r} has no positive numeric option to tune")
        if self.option not in options:
            raise ValidationError(
                f"law {law!r} has no option {self.option!r} to tune"
                f"{did_you_mean(self.option, options)}. Valid: {', '.join(options)}."
            )
        if not (
            math.isfinite(self.lower) and math.isfinite(self.upper) and self.lower < self.upper
        ):
            raise ValidationError(
                f"law {law!r}: the range of {self.option!r} must be finite with lower < upper; "
                f"got {self.lower:g} to {self.upper:g}"
            )
        if self.log and self.lower <= 0.0:
            raise ValidationError(
                f"law {law!r}: a log range of {self.option!r} needs lower > 0; got {self.lower:g}"
            )
        return self


#: law name -> the option the benchmark tunes and its range (a law not listed: its first
#: positive option, a decade either side of it). The on-off laws of the literature tune
#: their high current, the LQ laws their force weight r (a lower r: a firmer law; two
#: decades either side of the default 1e-6 1/kg^2, ``LQ_WEIGHTS``). The whole-vehicle
#: laws (full car only) likewise: the LQ, LQG and MPC laws their ``force_weight``; the two
#: skyhook laws their ``high_current``, since their gains set only the sign of each
#: corner's desired force (hi-lo: ``corner-skyhook``'s ``damping`` scales every corner's
#: force alike and changes nothing, ``modal-skyhook``'s three gains only by their ratios)
_ONOFF = TunedOption("i_max", 0.05, 0.5, log=True)
_LQ_R = TunedOption("w_force", 1e-8, 1e-4, log=True)
_VEHICLE_R = TunedOption("force_weight", 1e-8, 1e-4, log=True)
_VEHICLE_HIGH = TunedOption("high_current", 0.05, 0.5, log=True)
LAW_TABLE: dict[str, TunedOption] = {
    "passive": TunedOption("current", 0.0, 0.5),
    "skyhook-hilo": TunedOption("gain", 0.3, 30.0, log=True),
    "policy-ii": TunedOption("gain", 0.1, 100.0, log=True),
    "policy-iii": TunedOption("gain", 0.1, 100.0, log=True),
    "policy-iv": TunedOption("gain", 30.0, 3000.0, log=True),
    "onoff-adfg": TunedOption("current", 0.0, 0.5),
    "inverse-hilo": TunedOption("xi", 2.0, 100.0, log=True),
    "sliding-mode": TunedOption("skyhook_damping", 1000.0, 30000.0, log=True),
    "ideal-skyhook": TunedOption("skyhook_damping", 500.0, 30000.0, log=True),
    "ideal-onoff": TunedOption("damping", 500.0, 30000.0, log=True),
    "skyhook-onoff": _ONOFF,
    "groundhook": _ONOFF,
    "groundhook-continuous": TunedOption("groundhook_damping", 500.0, 30000.0, log=True),
    "hybrid-skyhook-groundhook": TunedOption("alpha", 0.0, 1.0),
    "add": _ONOFF,
    "sh-add": TunedOption("alpha", 2.0, 60.0, log=True),
    "pdd": TunedOption("c_max", 3000.0, 30000.0, log=True),
    "pdd-current": TunedOption("c_max", 3000.0, 30000.0, log=True),
    "clipped-lq": _LQ_R,
    "lq-force": _LQ_R,
    "clipped-lqg": _LQ_R,
    "lq-active": _LQ_R,
    "lqg-active": _LQ_R,
    "mpc": _LQ_R,
    "mpc-hilo": _LQ_R,
    # whole-vehicle laws (VEHICLE_LAWS): the full car only
    "modal-skyhook": _VEHICLE_HIGH,
    "corner-skyhook": _VEHICLE_HIGH,
    "vehicle-lq": _VEHICLE_R,
    "vehicle-lq-active": _VEHICLE_R,
    "vehicle-lq-force": _VEHICLE_R,
    "vehicle-lqg": _VEHICLE_R,
    "vehicle-lqg-active": _VEHICLE_R,
    "vehicle-lqg-force": _VEHICLE_R,
    "vehicle-mpc": _VEHICLE_R,
    "vehicle-mpc-active": _VEHICLE_R,
    "vehicle-mpc-force": _VEHICLE_R,
}


def is_vehicle_law(law: str) -> bool:
    """Whether ``law`` is a whole-vehicle law (full car only; not a per-corner law).

    Examples
    --------
    >>> is_vehicle_law("vehicle-lq"), is_vehicle_law("clipped-lq")
    (True, False)
    """
    from mrsuspension.control.registry import VEHICLE_LAWS

    return law in VEHICLE_LAWS


def _registered() -> list[str]:
    """Every law a spec may name: the per-corner and the whole-vehicle laws."""
    from mrsuspension.control import CONTROLLERS
    from mrsuspension.control.registry import VEHICLE_LAWS

    return [*CONTROLLERS, *VEHICLE_LAWS]


def default_laws() -> tuple[str, ...]:
    """The default law set: :data:`LAW_TABLE`'s laws that are registered now (per-corner
    laws and whole-vehicle laws)."""
    registered = set(_registered())
    return tuple(name for name in LAW_TABLE if name in registered)


def drives_damper(law: str) -> bool:
    """Whether ``law`` acts through the MR damper (held to the optimum's bound, counted as
    best law).

    A per-corner law whose force source is the damper model; a whole-vehicle law that is
    not ``active`` (an ideal actuator at every corner: the ``-active`` references).

    Examples
    --------
    >>> drives_damper("vehicle-lq"), drives_damper("vehicle-lq-active")
    (True, False)
    >>> drives_damper("skyhook-hilo"), drives_damper("ideal-skyhook")
    (True, False)
    """
    from mrsuspension.control import kernel as CK
    from mrsuspension.control.registry import VEHICLE_LAWS, controller_class

    if law in VEHICLE_LAWS:
        return not VEHICLE_LAWS[law].active
    return bool(getattr(controller_class(law), "force_source", CK.F_MODEL) == CK.F_MODEL)


@dataclass(frozen=True)
class BenchmarkRoad:
    """A road of the benchmark: an ISO 8608 class, a preset, or a bump.

    Parameters
    ----------
    name : str
        Label in the tables.
    kind : {"iso", "preset", "bump"}
    iso_class : str
        ISO 8608 class (``kind = "iso"``).
    profile : str
        Preset name (``kind = "preset"``: smooth, medium-rough, rough).
    seed : int
        Random-phase seed (ISO classes).
    height, length, position : float
        The bump's height [m], length [m] and start [m] (``kind = "bump"``: a rounded
        pulse under every wheel).
    """

    name: str
    kind: str = "iso"
    iso_class: str = "C"
    profile: str = ""
    seed: int = 0
    height: float = 0.03
    length: float = 0.5
    position: float = 2.0

    def __post_init__(self) -> None:
        if self.kind not in ("iso", "preset", "bump"):
            raise ValidationError(
                f"road {self.name!r}: kind must be iso, preset or bump; got {self.kind!r}"
            )

    def excitation(self, vehicle: str, speed: float, duration: float) -> dict[str, Any]:
        """The scenario's ``[excitation]`` table on ``vehicle`` at ``speed`` [km/h]."""
        v = speed / 3.6
        if self.kind == "bump":
            if vehicle == "quarter":
                return {
                    "kind": "pulse",
                    "amplitude": self.height,
                    "severity": 1.0,
                    "speed": speed,
                    "omega0": 3.0 * math.pi * v / self.length,
                    "delay": self.position / v,
                }
            return {
                "kind": "bump",
                "side": "both",
                "height": self.height,
                "length": self.length,
                "position": self.position,
                "speed": speed,
            }
        if self.kind == "preset":
            return {"kind": "road", "profile": self.profile, "speed": speed}
        # a record long enough for the run and the full car's rear wheels
        return {
            "kind": "road",
            "iso_class": self.iso_class,
            "seed": self.seed,
            "length": math.ceil(v * duration + 10.0),
            "speed": speed,
        }

    def to_dict(self) -> dict[str, Any]:
        """The TOML table of this road."""
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, table: Mapping[str, Any], where: str = "road") -> BenchmarkRoad:
        """A road from a TOML table (``name`` and ``kind`` and the kind's options)."""
        if not isinstance(table, Mapping):
            raise ValidationError(f"{where} must be a table; got {table!r}")
        check_keys(where, dict(table), [f.name for f in dataclasses.fields(cls)])
        if "name" not in table:
            raise ValidationError(f"{where} needs a name")
        return cls(**dict(table))


def _default_roads() -> tuple[BenchmarkRoad, ...]:
    return (
        BenchmarkRoad("ISO B", "iso", iso_class="B"),
        BenchmarkRoad("ISO C", "iso", iso_class="C"),
        BenchmarkRoad("ISO D", "iso", iso_class="D"),
        BenchmarkRoad("smooth", "preset", profile="smooth"),
        BenchmarkRoad("medium-rough", "preset", profile="medium-rough"),
        BenchmarkRoad("rough", "preset", profile="rough"),
        BenchmarkRoad("bump 3 cm", "bump", height=0.03, length=0.5),
    )


@dataclass(frozen=True)
class BenchmarkSpec:
    """What the benchmark runs (see the module docstring).

    Parameters
    ----------
    laws : tuple of str
        Registered law names (default: :func:`default_laws`): per-corner laws
        (:data:`~mrsuspension.control.CONTROLLERS`, run on every vehicle) and whole-vehicle
        laws (:data:`~mrsuspension.control.registry.VEHICLE_LAWS`, run on the full car
        only: a spec naming one without ``"full"`` in ``vehicles`` is refused; the
        default set on the quarter car alone leaves them out).
    tuning : dict
        Law name -> :class:`TunedOption` over :data:`LAW_TABLE` (a law in neither: its
        first positive option).
    training : BenchmarkRoad
        The road the laws are tuned on (quarter car), at ``training_speed`` [km/h].
    roads : tuple of BenchmarkRoad
        The scoring roads.
    speeds : tuple of float
        Speeds [km/h] of every scoring road.
    vehicles : tuple of str
        ``"quarter"`` and/or ``"full"``.
    weights : (float, float, float)
        ``(w_c, w_r, w_s)``: comfort, road holding, rattle space, of the cost and of the
        tuning objective.
    duration : float
        Record length of every run [s].
    evaluations, population, seed : int
        The optimiser's budget per law, its population and seed.
    optimum_dt : float
        The optimum's grid step [s].
    band : {"mean", "envelope"}
        The optimum's band (:data:`BANDS`): ``"mean"`` (default) the mean model at
        ``v_m = 0.3 m/s``, its cost over its own passive car, held to the bound within the
        record's model gap; ``"envelope"`` every force of the engine's hysteretic damper
        (a strict lower bound, loose: see ``docs/benchmark.md``), its cost over the
        engine's passive car.
    pareto : tuple of float
        Comfort weights of the optimum's Pareto front (on the first scoring road at the
        first speed; empty: none).
    """

    laws: tuple[str, ...] = field(default_factory=default_laws)
    tuning: Mapping[str, TunedOption] = field(default_factory=dict)
    training: BenchmarkRoad = BenchmarkRoad("ISO C, seed 1", "iso", iso_class="C", seed=1)
    training_speed: float = 50.0
    roads: tuple[BenchmarkRoad, ...] = field(default_factory=_default_roads)
    speeds: tuple[float, ...] = (50.0, 100.0)
    vehicles: tuple[str, ...] = VEHICLES
    weights: tuple[float, float, float] = DEFAULT_WEIGHTS
    duration: float = 4.0
    evaluations: int = 24
    population: int = 6
    seed: int = 0
    optimum_dt: float = 2e-3
    pareto: tuple[float, ...] = (0.1, 0.3, 0.5, 0.7, 0.9)
    band: str = "mean"

    def __post_init__(self) -> None:
        from mrsuspension.errors import unknown_name

        laws = tuple(self.laws)
        if not laws:
            raise ValidationError("laws: give at least one law name")
        registered = _registered()
        for law in laws:
            if law not in registered:
                raise ValidationError(f"laws: {unknown_name('controller law', law, registered)}")
        object.__setattr__(self, "laws", laws)
        for law in self.tuning:
            if law not in laws:
                raise ValidationError(f"tuning: law {law!r} is not in laws ({', '.join(laws)})")
        if not self.roads:
            raise ValidationError("roads: give at least one scoring road")
        names = [r.name for r in self.roads]
        if len(set(names)) != len(names):
            raise ValidationError(f"roads: the names must differ; got {names}")
        for s in (*self.speeds, self.training_speed):
            if not (isinstance(s, int | float) and 5.0 <= s <= 250.0):
                raise ValidationError(f"speeds: each speed must be 5-250 km/h; got {s!r}")
        if not self.speeds:
            raise ValidationError("speeds: give at least one speed [km/h]")
        for v in self.vehicles:
            if v not in VEHICLES:
                raise ValidationError(
                    f"vehicles: unknown vehicle {v!r}. Valid: {', '.join(VEHICLES)}."
                )
        if not self.vehicles:
            raise ValidationError("vehicles: give quarter and/or full")
        if "full" not in self.vehicles:
            if laws == default_laws():  # the default set on the quarter car alone
                laws = tuple(law for law in laws if not is_vehicle_law(law))
            from mrsuspension.control.registry import VEHICLE_LAWS

            for law in laws:
                if is_vehicle_law(law):
                    per_corner = getattr(VEHICLE_LAWS[law], "per_corner", None)
                    instead = f"name its per-corner law {per_corner!r}" if per_corner else "drop it"
                    raise ValidationError(
                        f"laws: {law!r} is a whole-vehicle law (the body's heave, pitch and "
                        'roll): it needs the full car; add "full" to vehicles (got '
                        f"{', '.join(self.vehicles)}), or {instead}"
                    )
        object.__setattr__(self, "laws", laws)
        w = tuple(float(x) for x in self.weights)
        if len(w) != 3 or min(w) < 0.0 or sum(w) <= 0.0:
            raise ValidationError(
                "weights: three weights >= 0 (comfort, road holding, rattle), not all 0; "
                f"got {self.weights!r}"
            )
        object.__setattr__(self, "weights", w)
        if not 0.5 <= self.duration <= 60.0:
            raise ValidationError(f"duration must be 0.5-60 s; got {self.duration!r} s")
        if self.band not in BANDS:
            raise ValidationError(
                f"band: the optimum's band must be {' or '.join(BANDS)}; got {self.band!r}"
            )
        if not 1e-3 <= self.optimum_dt <= 4e-3:
            raise ValidationError(f"optimum_dt must be 1-4 ms; got {self.optimum_dt!r} s")
        if self.evaluations < self.population or self.population < 5:
            raise ValidationError(
                f"tuning: population must be >= 5 and evaluations >= population; got "
                f"{self.population} and {self.evaluations}"
            )
        for lam in self.pareto:
            if not 0.0 <= lam <= 1.0:
                raise ValidationError(f"pareto: comfort weights must be 0-1; got {lam!r}")
        if len(self.pareto) == 1:
            raise ValidationError("pareto: give at least two comfort weights, or none")
        for law in laws:
            self.tuned_option(law)  # every tuned option exists

    def tuned_option(self, law: str) -> TunedOption:
        """The option tuned for ``law`` and its range."""
        entry = self.tuning.get(law) or LAW_TABLE.get(law) or TunedOption(None)
        return entry.resolve(law)

    def replace(self, **changes: Any) -> BenchmarkSpec:
        """A copy with ``changes`` (checked again)."""
        return dataclasses.replace(self, **changes)

    @classmethod
    def quick(cls) -> BenchmarkSpec:
        """A small set that runs in seconds (the tests and the quick report)."""
        laws = tuple(
            law
            for law in ("passive", "skyhook-hilo", "inverse-hilo", "ideal-skyhook", "vehicle-lq")
            if law in default_laws()
        )
        return cls(
            laws=laws,
            roads=(
                BenchmarkRoad("ISO C", "iso", iso_class="C"),
                BenchmarkRoad("bump 3 cm", "bump", height=0.03, length=0.5, position=1.0),
            ),
            speeds=(50.0,),
            duration=1.0,
            evaluations=5,
            population=5,
            optimum_dt=4e-3,
            pareto=(0.2, 0.5, 0.8),
        )

    # -- files ----------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, table: Mapping[str, Any]) -> BenchmarkSpec:
        """A spec from a TOML document's tables (every key optional).

        ``laws`` (names), ``[tuning.<law>]`` (``option``, ``lower``, ``upper``, ``log``),
        ``[training]`` (a road and ``speed``), ``[[roads]]`` (``name``, ``kind`` = iso |
        preset | bump and its options), ``speeds``, ``vehicles``, ``weights`` (``comfort``,
        ``road_holding``, ``rattle``), ``duration``, ``evaluations``, ``population``,
        ``seed``, ``optimum_dt``, ``pareto``, ``band``.
        """
        keys = (
            "laws",
            "tuning",
            "training",
            "roads",
            "speeds",
            "vehicles",
            "weights",
            "duration",
            "evaluations",
            "population",
            "seed",
            "optimum_dt",
            "pareto",
            "band",
        )
        check_keys("benchmark spec", dict(table), keys)
        kw: dict[str, Any] = {}
        if "laws" in table:
            laws = table["laws"]
            if isinstance(laws, str) or not isinstance(laws, Sequence):
                raise ValidationError(f"laws must be a list of law names; got {laws!r}")
            kw["laws"] = tuple(str(x) for x in laws)
        if "tuning" in table:
            tuning = {}
            for law, t in dict(table["tuning"]).items():
                check_keys(f"[tuning.{law}]", dict(t), ("option", "lower", "upper", "log"))
                tuning[law] = TunedOption(
                    t.get("option"),
                    float(t.get("lower", math.nan)),
                    float(t.get("upper", math.nan)),
                    bool(t.get("log", False)),
                )
            kw["tuning"] = tuning
        if "training" in table:
            t = dict(table["training"])
            if "speed" in t:
                kw["training_speed"] = float(t.pop("speed"))
            kw["training"] = BenchmarkRoad.from_dict(t, "[training]")
        if "roads" in table:
            kw["roads"] = tuple(
                BenchmarkRoad.from_dict(r, f"[[roads]] #{i + 1}")
                for i, r in enumerate(table["roads"])
            )
        for key in ("speeds", "vehicles", "pareto"):
            if key in table:
                kw[key] = tuple(table[key])
        if "weights" in table:
            w = dict(table["weights"])
            check_keys("[weights]", w, ("comfort", "road_holding", "rattle"))
            d = DEFAULT_WEIGHTS
            kw["weights"] = (
                float(w.get("comfort", d[0])),
                float(w.get("road_holding", d[1])),
                float(w.get("rattle", d[2])),
            )
        for key in ("duration", "optimum_dt"):
            if key in table:
                kw[key] = float(table[key])
        if "band" in table:
            kw["band"] = str(table["band"])
        for key in ("evaluations", "population", "seed"):
            if key in table:
                kw[key] = int(table[key])
        return cls(**kw)

    @classmethod
    def load(cls, path: str | Path) -> BenchmarkSpec:
        """Read a spec TOML file."""
        from mrsuspension._inputs import read_toml

        return cls.from_dict(read_toml(path, "benchmark spec"))

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the spec's TOML tables, JSON-ready)."""
        return {
            "laws": list(self.laws),
            "tuning": {law: dataclasses.asdict(self.tuned_option(law)) for law in self.laws},
            "training": {**self.training.to_dict(), "speed": self.training_speed},
            "roads": [r.to_dict() for r in self.roads],
            "speeds": list(self.speeds),
            "vehicles": list(self.vehicles),
            "weights": dict(zip(("comfort", "road_holding", "rattle"), self.weights, strict=True)),
            "duration": self.duration,
            "evaluations": self.evaluations,
            "population": self.population,
            "seed": self.seed,
            "optimum_dt": self.optimum_dt,
            "band": self.band,
            "pareto": list(self.pareto),
        }


# -- the tasks (module level: picklable for a process pool or Dask) ---------------------------
def _scenario(
    law: str,
    options: Mapping[str, float],
    vehicle: str,
    excitation: Mapping[str, Any],
    duration: float,
) -> dict[str, Any]:
    return {
        "controller": {"law": law, **options},
        "excitation": dict(excitation),
        **_run_tables(vehicle, duration),
    }


def _run_tables(vehicle: str, duration: float) -> dict[str, Any]:
    """The ``[simulation]`` (and the full car's ``[vehicle]``) table of every benchmark run,
    scored or tuned: the vehicle's engine step, every step recorded (:data:`OUTPUT_RATE`)."""
    tables: dict[str, Any] = {
        "simulation": {
            "duration": duration,
            "dt": ENGINE_DT[vehicle],
            "output_rate": OUTPUT_RATE[vehicle],
        },
    }
    if vehicle == "full":
        tables["vehicle"] = {"model": "full-car"}
    return tables


#: the full car's corners (its measures ``DLC.<corner>``, ``rms_stroke.<corner>``)
FULL_CAR_CORNERS = ("front_left", "front_right", "rear_left", "rear_right")


def _objective_weights(vehicle: str, weights: tuple[float, float, float]) -> dict[str, float]:
    """The tuning objective's measure weights: the benchmark cost's terms on ``vehicle``.

    Quarter car: the Wk rms body acceleration, the DLC and the rms stroke. Full car: the
    seat's ISO 2631-1 total value, and each corner's DLC and rms stroke at a quarter of the
    weight (their mean, as the scoring takes it).
    """
    w_c, w_r, w_s = weights
    if vehicle == "quarter":
        pairs = [("wk_rms_body_acceleration", w_c), ("DLC", w_r), ("rms_stroke", w_s)]
    else:
        pairs = [("seat_total", w_c)]
        pairs += [(f"DLC.{c}", w_r / len(FULL_CAR_CORNERS)) for c in FULL_CAR_CORNERS]
        pairs += [(f"rms_stroke.{c}", w_s / len(FULL_CAR_CORNERS)) for c in FULL_CAR_CORNERS]
    return {k: w for k, w in pairs if w > 0.0}


def _tune_task(
    task: tuple[
        str,
        TunedOption,
        dict[str, Any],
        tuple[float, float, float],
        int,
        int,
        int,
        int | None,
        str,
    ],
) -> dict[str, Any]:
    """Tune one law's option on the training road on one vehicle (the optimiser's API)."""
    from mrsuspension.optimize import OptimizationProblem, optimize

    law, opt, excitation, weights, evaluations, population, seed, workers, vehicle = task
    assert opt.option is not None
    problem = OptimizationProblem.from_dict(
        {
            **_run_tables(vehicle, excitation.pop("duration")),
            "controller": {"law": law},
            "problem": {"population": population, "seed": seed, "name": law},
            "parameters": [
                {
                    "field": f"controller.{opt.option}",
                    "lower": opt.lower,
                    "upper": opt.upper,
                    "log": opt.log,
                }
            ],
            "roads": [excitation],
            "objective": {"weights": _objective_weights(vehicle, weights)},
        }
    )
    result = optimize(problem, max_evaluations=evaluations, workers=workers, progress=False)
    return {
        "law": law,
        "vehicle": vehicle,
        "option": opt.option,
        "value": result.best[f"controller.{opt.option}"],
        "objective": result.objective,
        "evaluations": result.evaluations,
        "run_time": result.run_time,
    }


def _score_task(task: tuple[str, str, dict[str, Any]]) -> dict[str, float] | None:
    """One run's comfort, road holding, rattle and coil power (None: it diverged)."""
    from mrsuspension import measures as M
    from mrsuspension.engine.simulate import SimulationDiverged, run_quietly
    from mrsuspension.engine.vehicle_result import VehicleResult
    from mrsuspension.measures.vehicle import COIL_RESISTANCE
    from mrsuspension.scenario import Scenario

    vehicle, _label, tables = task
    scenario = Scenario.from_dict(tables)
    try:
        res = run_quietly(scenario.runs()[0], scenario.settings)
    except SimulationDiverged:
        return None
    if vehicle == "quarter":
        fs = 1.0 / float(res.time[1] - res.time[0])
        tire = np.asarray(res.F_T)
        i = np.asarray(res.i_d)
        return {
            "comfort": M.weighted_rms(np.asarray(res.z_s_ddot), fs),
            "road_holding": float(np.std(tire) / np.mean(tire)),
            "rattle": float(np.std(np.asarray(res.x_d))),
            "coil_power": COIL_RESISTANCE * float(np.mean(i * i)),
            # the damper's peak-velocity estimate: the optimum's band covers its range
            "peak_velocity_max": float(np.max(np.asarray(res.v_m))),
        }
    assert isinstance(res, VehicleResult)
    corners = [k.split(".", 1)[1] for k in res if k.startswith("F_T.")]
    dlc, stroke, power = [], [], 0.0
    for c in corners:
        tire = np.asarray(res[f"F_T.{c}"])
        dlc.append(float(np.std(tire) / np.mean(tire)))
        stroke.append(float(np.std(np.asarray(res[f"x_d.{c}"]))))
        i = np.asarray(res[f"i_d.{c}"])
        power += COIL_RESISTANCE * float(np.mean(i * i))
    return {
        "comfort": float(res.vehicle_measures()["seat_total"]),
        "road_holding": float(np.mean(dlc)),
        "rattle": float(np.mean(stroke)),
        "coil_power": power,
    }


def _road_object(excitation: Mapping[str, Any], duration: float) -> Any:
    from mrsuspension.scenario import Scenario

    s = Scenario.from_dict({"excitation": dict(excitation), "simulation": {"duration": duration}})
    return s.runs()[0].excitation


def engine_peak_velocity_floor() -> float:
    """The lower clamp ``v_min`` [m/s] of the engine damper's peak-velocity estimator."""
    from mrsuspension.dampers import WangSymmetric

    return float(getattr(WangSymmetric().estimator, "v_min", 1e-3))


def model_gap(
    engine: Mapping[str, float], model: Mapping[str, float], weights: Sequence[float]
) -> float:
    """The engine's passive car scored on the model's: ``sum w (e / m)^2 / sum w - 1``.

    ``engine`` and ``model``: each passive car's ``comfort`` (Wk rms [m/s^2]),
    ``road_holding`` (DLC) and ``rattle`` (rms stroke [m]). 0 when the two agree.

    Examples
    --------
    >>> m = {"comfort": 1.0, "road_holding": 0.1, "rattle": 0.01}
    >>> round(model_gap({**m, "comfort": 1.1}, m, (1.0, 1.0, 0.1)), 6)  # 0.21 / 2.1
    0.1
    """
    terms = ("comfort", "road_holding", "rattle")
    return (
        sum(w * (engine[k] / model[k]) ** 2 for w, k in zip(weights, terms, strict=True))
        / sum(weights)
        - 1.0
    )


def _optimum_task(
    task: tuple[
        str,
        float,
        dict[str, Any],
        float,
        float,
        tuple[float, float, float],
        tuple[float, ...],
        tuple[float, float],
        str,
        dict[str, float],
    ],
) -> dict[str, Any]:
    """The semi-active optimum of one road record (and its Pareto front when asked).

    ``band`` ``"mean"``: over :class:`~mrsuspension.benchmark.band.MRBand`, scaled by its
    own passive car; ``"envelope"``: over
    :class:`~mrsuspension.benchmark.band.MREnvelopeBand` with the range ``vm_range`` of
    ``v_m`` (every force the engine's hysteretic damper gives), scaled by the engine's
    passive car ``engine`` (its ``comfort`` [m/s^2], ``road_holding`` (DLC) and
    ``rattle`` [m]). Either way the *model gap*: the engine's passive car scored on the
    model's passive car, ``sum w (engine / model)^2 / sum w - 1``.
    """
    from mrsuspension.benchmark.band import MRBand, MREnvelopeBand
    from mrsuspension.benchmark.optimum import BenchmarkProblem, Weights, pareto_front

    road, speed, excitation, duration, dt, weights, pareto, vm_range, band, engine = task
    road_input = _road_object(excitation, duration)
    mean = BenchmarkProblem(road_input, duration=duration, dt=dt, weights=Weights(*weights))
    model = mean.passive()
    load = mean.linear.static_load
    model_rms = {k: math.sqrt(model.mean_squares[k]) for k in ("comfort", "road_holding", "rattle")}
    model_rms["road_holding"] /= load  # over the static load, as the DLC
    gap = model_gap(engine, model_rms, weights)
    if band == "envelope":
        scales = (engine["comfort"], engine["road_holding"] * load, engine["rattle"])
        problem = BenchmarkProblem(
            road_input,
            duration=duration,
            dt=dt,
            weights=Weights(*weights),
            band=MREnvelopeBand(vm_range),
            scales=scales,
        )
        tolerance = BOUND_TOLERANCE
    else:
        problem = mean
        tolerance = max(BOUND_TOLERANCE, abs(gap))
    assert isinstance(problem.band, MRBand | MREnvelopeBand)
    best = problem.solve()
    passive = problem.passive()
    out: dict[str, Any] = {
        "road": road,
        "speed": speed,
        "cost": best.cost,
        "status": best.status,
        "success": best.success,
        "iterations": best.iterations,
        "passive_cost": passive.cost,
        "band": band,
        "peak_velocity_range": list(vm_range) if band == "envelope" else [math.nan, math.nan],
        "model_gap": gap,
        "bound_tolerance": tolerance,
        **{  # over the scales' passive car (the model's, or the engine's for the envelope)
            f"{k}_ratio": math.sqrt(best.mean_squares[k]) / problem.scales[j]
            for j, k in enumerate(("comfort", "road_holding", "rattle"))
        },
        "mean_current": float(np.nanmean(best.current)) if best.current is not None else math.nan,
        "band_violation": best.band_violation(problem.band),
    }
    if pareto:
        front = pareto_front(problem, pareto)
        pc = problem.scales[0]
        pr = problem.scales[1] / problem.linear.static_load
        out["front"] = {
            "comfort_weights": [float(x) for x in front.comfort_weights],
            "comfort_ratio": [float(x) / pc for x in front.comfort],
            "road_holding_ratio": [float(x) / pr for x in front.road_holding],
        }
    return out


# -- running --------------------------------------------------------------------------------
def _map(fn: Callable[[Any], Any], tasks: list[Any], workers: int | None, client: Any) -> list[Any]:
    if client is not None:
        return list(client.gather(client.map(fn, tasks, pure=False)))
    from mrsuspension._pool import pool_map

    return pool_map(fn, tasks, workers=workers)


def _say(progress: bool | Callable[[str], None], text: str) -> None:
    if progress is True:
        print(f"benchmark: {text}", file=sys.stderr, flush=True)
    elif callable(progress):
        progress(text)


def run_benchmark(
    spec: BenchmarkSpec | None = None,
    *,
    workers: int | None = None,
    scheduler: Any = None,
    progress: bool | Callable[[str], None] = False,
) -> BenchmarkResult:
    """Tune every law, score it on every road, speed and vehicle, solve the optima.

    Parameters
    ----------
    spec : BenchmarkSpec, optional
        What to run (default: ``BenchmarkSpec()``, the default set).
    workers : int, optional
        Local processes (None: one per core; 1: this process).
    scheduler : str or dask.distributed.Client, optional
        A Dask scheduler address (``tcp://host:port``) or client: the tuning (one task
        per law), the optima and the scoring runs go to the cluster.
    progress : bool or callable
        A line on stderr per stage (True), none (False), or ``progress(text)``.

    Returns
    -------
    BenchmarkResult
    """
    spec = BenchmarkSpec() if spec is None else spec
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise ValidationError(f"workers must be an integer >= 1; got {workers!r}")
    if "quarter" in spec.vehicles:  # before any computing: the optimum needs CasADi
        from mrsuspension.benchmark.optimum import _casadi

        _casadi()
    start = time.perf_counter()
    client, own = None, False
    if scheduler is not None:
        from mrsuspension.errors import require_extra

        require_extra("distributed", "running the benchmark on a Dask scheduler")
        from dask.distributed import Client

        if isinstance(scheduler, str):
            from mrsuspension.studies.study import SCHEDULER_TIMEOUT, check_scheduler

            client = Client(check_scheduler(scheduler), timeout=SCHEDULER_TIMEOUT)
            own = True
        else:
            client = scheduler
    try:
        return _run(spec, workers, client, progress, start)
    finally:
        if own and client is not None:
            client.close(timeout=2.0)


def _run(
    spec: BenchmarkSpec,
    workers: int | None,
    client: Any,
    progress: bool | Callable[[str], None],
    start: float,
) -> BenchmarkResult:
    # 1. tune every law on the training road, on each vehicle
    tasks = []
    for vehicle in spec.vehicles:
        training = {
            **spec.training.excitation(vehicle, spec.training_speed, spec.duration),
            "name": spec.training.name,
            "duration": spec.duration,
        }
        tasks += [
            (
                law,
                spec.tuned_option(law),
                dict(training),
                spec.weights,
                spec.evaluations,
                spec.population,
                spec.seed,
                1 if client is not None else workers,
                vehicle,
            )
            for law in spec.laws
            if vehicle == "full" or not is_vehicle_law(law)
        ]
    tuned: dict[str, dict[str, dict[str, Any]]] = {v: {} for v in spec.vehicles}
    if client is not None:
        _say(progress, f"tuning {len(tasks)} laws and vehicles on {spec.training.name} (Dask)")
        for row in _map(_tune_task, tasks, workers, client):
            tuned[row["vehicle"]][row["law"]] = row
    else:
        for k, task in enumerate(tasks):
            _say(
                progress,
                f"tuning {task[0]} on the {task[8]} car ({k + 1}/{len(tasks)}) on "
                f"{spec.training.name}",
            )
            row = _tune_task(task)
            tuned[task[8]][task[0]] = row
    # 2. score every law (and the passive car at 0 A) on every road, speed and vehicle
    cases = [(road, speed) for road in spec.roads for speed in spec.speeds]
    runs: list[tuple[str, str, dict[str, Any]]] = []
    keys: list[tuple[str, str, str, float]] = []
    for vehicle in spec.vehicles:
        for road, speed in cases:
            exc = road.excitation(vehicle, speed, spec.duration)
            for law in (None, *spec.laws):
                if law is not None and vehicle != "full" and is_vehicle_law(law):
                    continue  # a whole-vehicle law: the full car only
                if law is None:
                    tables = _scenario("passive", {"current": 0.0}, vehicle, exc, spec.duration)
                else:
                    t = tuned[vehicle][law]
                    tables = _scenario(law, {t["option"]: t["value"]}, vehicle, exc, spec.duration)
                runs.append((vehicle, road.name, tables))
                keys.append((law or "", vehicle, road.name, speed))
    _say(progress, f"scoring {len(runs)} runs")
    scored = _map(_score_task, runs, workers, client)
    # 3. the optima on the quarter car, with the model gap of each record (the engine's
    # passive car on the model's); the envelope band covers the peak-velocity estimate
    # of every quarter-car run on the record
    optima: dict[tuple[str, float], dict[str, Any]] = {}
    if "quarter" in spec.vehicles:
        floor = engine_peak_velocity_floor()
        top: dict[tuple[str, float], float] = {}
        engine: dict[tuple[str, float], dict[str, float]] = {}
        for (law, vehicle, road_name, speed), m in zip(keys, scored, strict=True):
            if vehicle == "quarter" and m is not None:
                key = (road_name, speed)
                top[key] = max(top.get(key, floor), float(m["peak_velocity_max"]))
                if law == "":
                    engine[key] = {k: float(m[k]) for k in ("comfort", "road_holding", "rattle")}
        for road, speed in cases:
            if (road.name, speed) not in engine:
                raise MRSuspensionError(
                    f"the passive car diverged on {road.name} at {speed:g} km/h"
                )
        _say(progress, f"solving {len(cases)} optima (quarter car, {spec.optimum_dt * 1e3:g} ms)")
        opt_tasks = [
            (
                road.name,
                speed,
                road.excitation("quarter", speed, spec.duration),
                spec.duration,
                spec.optimum_dt,
                spec.weights,
                spec.pareto if k == 0 else (),
                (floor, max(top.get((road.name, speed), floor), 1.001 * floor)),
                spec.band,
                engine[(road.name, speed)],
            )
            for k, (road, speed) in enumerate(cases)
        ]
        for row in _map(_optimum_task, opt_tasks, workers, client):
            optima[(row["road"], row["speed"])] = row
    rows = _rows(spec, tuned, optima, keys, scored)
    violations = bound_violations(rows)
    front = next((o["front"] for o in optima.values() if "front" in o), None)
    return BenchmarkResult(
        spec=spec,
        rows=rows,
        tuned=tuned.get("quarter", {}),
        optima=list(optima.values()),
        front=front,
        violations=violations,
        run_time=time.perf_counter() - start,
        tuned_full=tuned.get("full", {}),
    )


def bound_violations(rows: Sequence[Mapping[str, Any]]) -> list[str]:
    """The rows of a law that drives the MR damper costing less than the optimum.

    Below by more than the row's ``bound_tolerance`` (relative; :data:`BOUND_TOLERANCE`
    when the row has none): with the ``"mean"`` band the larger of the solver's tolerance
    and the record's model gap (the engine's passive car against the model's), since the
    optimum is the bound of the band's model, not of the engine's hysteretic damper.

    Examples
    --------
    >>> row = {"law": "x", "road": "r", "speed": 50.0, "bounded": True, "cost": 1.0}
    >>> bound_violations([{**row, "optimum_cost": 0.9}, {**row, "optimum_cost": math.nan}])
    []
    >>> bound_violations([{**row, "optimum_cost": 1.2}])
    ["x on r at 50 km/h costs 1.0000, below the optimum's 1.2000 by 16.7 % (tolerance 0.1 %)"]
    >>> bound_violations([{**row, "optimum_cost": 1.02, "bound_tolerance": 0.05}])
    []
    >>> bound_violations([{**row, "optimum_cost": 1.2, "optimum_converged": False}])
    []

    An optimum whose solve did not converge (``optimum_converged`` False: IPOPT stopped at
    its iteration limit or failed) is its last iterate, not a bound: no row is held to it
    (:meth:`BenchmarkResult.summary` names it).
    """
    out = []
    for r in rows:
        j_opt = r["optimum_cost"]
        if not (r["bounded"] and math.isfinite(j_opt) and r.get("optimum_converged", True)):
            continue
        tol = r.get("bound_tolerance", BOUND_TOLERANCE)
        tol = BOUND_TOLERANCE if not math.isfinite(tol) else max(float(tol), BOUND_TOLERANCE)
        if r["cost"] < j_opt * (1.0 - tol):
            out.append(
                f"{r['law']} on {r['road']} at {r['speed']:g} km/h costs {r['cost']:.4f}, below "
                f"the optimum's {j_opt:.4f} by {100 * (1 - r['cost'] / j_opt):.1f} % "
                f"(tolerance {100 * tol:.1f} %)"
            )
    return out


def _rows(
    spec: BenchmarkSpec,
    tuned: Mapping[str, Mapping[str, Mapping[str, Any]]],
    optima: Mapping[tuple[str, float], Mapping[str, Any]],
    keys: Sequence[tuple[str, str, str, float]],
    scored: Sequence[Mapping[str, float] | None],
) -> list[dict[str, Any]]:
    passive: dict[tuple[str, str, float], Mapping[str, float]] = {}
    for (law, vehicle, road, speed), m in zip(keys, scored, strict=True):
        if law == "":
            if m is None:
                raise MRSuspensionError(f"the passive car diverged on {road} at {speed:g} km/h")
            passive[(vehicle, road, speed)] = m
    rows: list[dict[str, Any]] = []
    w = spec.weights
    for (law, vehicle, road, speed), m in zip(keys, scored, strict=True):
        if law == "":
            continue
        p = passive[(vehicle, road, speed)]
        nan = math.nan
        ratios = {
            k: (m[k] / p[k] if m is not None and p[k] > 0 else nan)
            for k in ("comfort", "road_holding", "rattle")
        }
        cost = (
            w[0] * ratios["comfort"] ** 2
            + w[1] * ratios["road_holding"] ** 2
            + w[2] * ratios["rattle"] ** 2
        )
        opt = optima.get((road, speed)) if vehicle == "quarter" else None
        j_opt = float(opt["cost"]) if opt is not None else nan
        tolerance = float(opt["bound_tolerance"]) if opt is not None else nan
        rows.append(
            {
                "law": law,
                "vehicle": vehicle,
                "road": road,
                "speed": speed,
                "option": tuned[vehicle][law]["option"],
                "value": tuned[vehicle][law]["value"],
                "bounded": drives_damper(law),
                **{
                    k: (m[k] if m is not None else nan)
                    for k in ("comfort", "road_holding", "rattle", "coil_power")
                },
                **{f"{k}_ratio": v for k, v in ratios.items()},
                "cost": cost,
                "peak_velocity_max": (
                    float(m.get("peak_velocity_max", nan)) if m is not None else nan
                ),
                "optimum_cost": j_opt,
                "optimum_converged": bool(opt["success"]) if opt is not None else False,
                "bound_tolerance": tolerance,
                "distance": cost / j_opt - 1.0 if math.isfinite(j_opt) else nan,
            }
        )
    return rows


@dataclass
class BenchmarkResult:
    """The benchmark's rows, tuned options, optima and figure data.

    Attributes
    ----------
    spec : BenchmarkSpec
    rows : list of dict
        One per law, vehicle, road and speed: the tuned ``option`` and ``value``,
        ``comfort`` [m/s^2], ``road_holding`` (DLC), ``rattle`` [m], ``coil_power`` [W],
        their ``*_ratio`` to the passive car (0 A), ``cost`` (the benchmark cost),
        ``peak_velocity_max`` (the damper's largest ``v_m`` [m/s]; quarter car),
        ``optimum_cost`` and ``distance`` (``cost / optimum_cost - 1``; quarter car),
        ``bounded`` (the law drives the MR damper: held to the bound).
    tuned : dict
        Law -> the tuning's ``option``, ``value``, ``objective``, ``evaluations`` on the
        quarter car (the quarter car's rows use it).
    tuned_full : dict
        The same on the full car (the full car's rows use it; empty without the full car).
        The whole-vehicle laws are tuned and scored on the full car only: they are here
        and in the full car's rows, not in :attr:`tuned` nor the quarter car's rows.
    optima : list of dict
        Per road and speed: the optimum's ``cost``, ``status``, ratios to its passive car.
    front : dict or None
        The optimum's Pareto front on the first road and speed, in ratios to passive.
    violations : list of str
        Laws that cost less than the optimum (should be empty).
    run_time : float
        Wall time [s].
    """

    spec: BenchmarkSpec
    rows: list[dict[str, Any]]
    tuned: dict[str, dict[str, Any]]
    optima: list[dict[str, Any]]
    front: dict[str, list[float]] | None
    violations: list[str]
    run_time: float
    tuned_full: dict[str, dict[str, Any]] = field(default_factory=dict)

    def to_pandas(self) -> pd.DataFrame:
        """The rows as a DataFrame."""
        import pandas as pd

        return pd.DataFrame(self.rows)

    def best(self) -> list[dict[str, Any]]:
        """The best law (lowest cost; laws that drive the MR damper) per vehicle, road and speed.

        ``passive_cost`` is the passive car's at 0 A (``w_c + w_r + w_s``): the best law
        may cost more (no law gains on that case).
        """
        out: list[dict[str, Any]] = []
        groups: dict[tuple[str, str, float], list[dict[str, Any]]] = {}
        for r in self.rows:
            if r["bounded"] and math.isfinite(r["cost"]):
                groups.setdefault((r["vehicle"], r["road"], r["speed"]), []).append(r)
        for (vehicle, road, speed), rs in groups.items():
            rs = sorted(rs, key=lambda r: r["cost"])
            b = rs[0]
            out.append(
                {
                    "vehicle": vehicle,
                    "road": road,
                    "speed": speed,
                    "best": b["law"],
                    "cost": b["cost"],
                    "passive_cost": sum(self.spec.weights),
                    "comfort_ratio": b["comfort_ratio"],
                    "road_holding_ratio": b["road_holding_ratio"],
                    "distance": b["distance"],
                    "optimum_cost": b["optimum_cost"],
                    "runner_up": rs[1]["law"] if len(rs) > 1 else "",
                }
            )
        return out

    def best_table(self) -> str:
        """:meth:`best` as a plain-text table."""
        head = (
            "vehicle",
            "road",
            "km/h",
            "best law",
            "cost",
            "passive 0 A",
            "comfort",
            "road h.",
            "to optimum",
            "runner-up",
        )
        lines = [head]
        for b in self.best():
            d = b["distance"]
            lines.append(
                (
                    b["vehicle"],
                    b["road"],
                    f"{b['speed']:g}",
                    b["best"],
                    f"{b['cost']:.3f}",
                    f"{b['passive_cost']:.3f}",
                    f"{b['comfort_ratio']:.3f}",
                    f"{b['road_holding_ratio']:.3f}",
                    f"{100 * d:+.1f} %" if math.isfinite(d) else "-",
                    b["runner_up"],
                )
            )
        widths = [max(len(row[j]) for row in lines) for j in range(len(head))]
        return "\n".join(
            "  ".join(c.ljust(w) for c, w in zip(row, widths, strict=True)).rstrip()
            for row in lines
        )

    def summary(self) -> str:
        """The best-law table, the tuned options, the bound check and the time taken."""
        parts = []
        for vehicle, tuned_on in (("quarter", self.tuned), ("full", self.tuned_full)):
            if tuned_on:  # a spec without the quarter car tunes nothing on it
                text = ", ".join(
                    f"{law} {t['option']} = {t['value']:.4g}" for law, t in tuned_on.items()
                )
                parts.append(text if vehicle == "quarter" else f"on the full car: {text}")
        tuned = "; ".join(parts)
        if self.violations:
            check = "BOUND VIOLATED: " + "; ".join(self.violations)
        elif not self.optima:
            check = "no optimum (it is the quarter car's): no law held to the bound"
        else:
            check = (
                "no law that drives the MR damper costs less than the optimum by more than "
                "its record's tolerance (the model gap)"
            )
        unsolved = [o for o in self.optima if not o.get("success", True)]
        if unsolved:
            check += "\nthe optimum did not converge on " + "; ".join(
                f"{o['road']} at {o['speed']:g} km/h ({o['status']}, {o['iterations']} iterations)"
                for o in unsolved
            )
            check += ": its cost there is IPOPT's last iterate, not a bound; no law is held to it"
        return (
            f"{self.best_table()}\n\ntuned on {self.spec.training.name} at "
            f"{self.spec.training_speed:g} km/h: {tuned}\n{check}\n"
            f"{len(self.rows)} scored runs in {self.run_time:.1f} s"
        )

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON-ready: nan becomes None)."""
        from mrsuspension._jsonsafe import to_jsonable

        return dict(
            to_jsonable(
                {
                    "spec": self.spec.to_dict(),
                    "rows": self.rows,
                    "best": self.best(),
                    "tuned": self.tuned,
                    "tuned_full": self.tuned_full,
                    "optima": self.optima,
                    "front": self.front,
                    "violations": self.violations,
                    "run_time": self.run_time,
                }
            )
        )

    def figure(
        self, vehicle: str = "quarter", road: str | None = None, speed: float | None = None
    ) -> Figure:
        """Comfort against road holding (ratios to passive) per law, with the optimum's front.

        On ``road`` at ``speed`` (default: the first scoring road and speed, where the
        front was solved); the front is drawn on the quarter car only.
        """
        from matplotlib.figure import Figure

        road = self.spec.roads[0].name if road is None else road
        speed = self.spec.speeds[0] if speed is None else speed
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        fig = Figure(figsize=(9.0, 5.0))
        FigureCanvasAgg(fig)
        ax = fig.subplots()
        markers = "o^sDvP<>hX"  # with the 10 colours of the cycle: 33 laws stay apart
        k = 0
        for r in self.rows:
            if r["vehicle"] == vehicle and r["road"] == road and r["speed"] == speed:
                marker = markers[(k // 10) % len(markers)] if r["bounded"] else "x"
                ax.plot(r["road_holding_ratio"], r["comfort_ratio"], marker, label=r["law"])
                k += 1
        ax.plot(1.0, 1.0, "ks", label="passive 0 A")
        front = self.front if vehicle == "quarter" and road == self.spec.roads[0].name else None
        if front is not None and speed == self.spec.speeds[0]:
            ax.plot(
                front["road_holding_ratio"],
                front["comfort_ratio"],
                "k--",
                label="optimum (Pareto front)",
            )
            opt = next((o for o in self.optima if o["road"] == road and o["speed"] == speed), None)
            if opt is not None:
                ax.plot(
                    opt["road_holding_ratio"],
                    opt["comfort_ratio"],
                    "k*",
                    ms=10,
                    label="optimum (cost weights)",
                )
        comfort = "seat ISO 2631 total" if vehicle == "full" else "Wk rms body acceleration"
        ax.set_xlabel("road holding: DLC / passive")
        ax.set_ylabel(f"comfort: {comfort} / passive")
        ax.set_title(f"{vehicle} car, {road}, {speed:g} km/h")
        ax.grid(True, alpha=0.3)
        ax.legend(
            fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5), ncol=2 if k > 14 else 1
        )
        fig.tight_layout()
        return fig

    def save(self, folder: str | Path) -> list[Path]:
        """Write ``benchmark.csv``, ``best.csv``, ``benchmark.json`` and a PNG per vehicle."""
        import json

        import pandas as pd

        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        paths = []
        for name, frame in (
            ("benchmark.csv", self.to_pandas()),
            ("best.csv", pd.DataFrame(self.best())),
        ):
            p = out / name
            frame.to_csv(p, index=False)
            paths.append(p)
        p = out / "benchmark.json"
        p.write_text(json.dumps(self.to_dict(), indent=1, allow_nan=False) + "\n")
        paths.append(p)
        for vehicle in self.spec.vehicles:
            p = out / f"tradeoff-{vehicle}.png"
            self.figure(vehicle).savefig(p, dpi=110)
            paths.append(p)
        return paths
