"""Controller optimisation: tune scenario fields for a weighted objective over several roads.

An optimisation problem is a scenario file (the ``[vehicle]``, ``[damper]``,
``[controller]``, ``[excitation]`` and ``[simulation]`` tables of
:mod:`mrsuspension.scenario`: the *base*) plus:

``[problem]``
    ``name``, ``description``, ``seed`` (0), ``max_evaluations`` (candidate
    controllers to try, 200), ``population`` (candidates per generation, 6 per parameter
    and at least 5), ``tolerance`` (stop early when the spread of the population's
    objectives falls below this fraction of their mean; 0, the default, spends the whole
    budget) and ``workers`` (processes; default one per core).
``[[parameters]]``
    One table per tuned field: ``field`` (a dotted numeric scenario field of the
    vehicle, damper, controller or simulation, e.g. ``"controller.gain"``), ``lower``,
    ``upper``, optionally ``integer = true`` (e.g. ``controller.order``) and
    ``log = true`` (search ``log10(value)``: gains spanning decades).
``[[roads]]``
    One table per road: the road options of ``[excitation]`` (``profile`` = a preset
    name or a CSV file, or ``iso_class`` with ``seed``/``length``; ``speed`` [km/h],
    ``scale``, ...) plus an optional ``name`` and ``weight`` (1). The base
    ``[excitation]`` table, if any, holds options shared by every road.
``[objective]``
    ``weights``: measure -> weight over the road measures of
    :meth:`~mrsuspension.engine.result.SimulationResult.measures`
    (``wk_rms_body_acceleration``, ``DLC``, ``rms_stroke``, ...; a half or full car:
    its body's ``heave_ddot_rms``, ..., every corner's ``"<measure>.<corner>"`` and the
    seat's ISO 2631-1 ``seat_total``, ``seat_z``, ...,
    :data:`~mrsuspension.engine.vehicle_result.SEAT_MEASURES`);
    ``reference``: tables that replace those of the base for the reference controller
    (default ``{controller = {law = "passive", current = 0.0}}``).

The objective of a candidate is the weighted mean, over measures and roads, of its
measures divided by the reference controller's on the same road::

    J = sum_m (w_m / W) sum_r (v_r / V) q_m,r / q_m,r(reference)

(``W``, ``V``: the sums of the measure and road weights), so every measure counts in
units of the reference, the weights are comparable, and the reference scores J = 1.

Search: :func:`scipy.optimize.differential_evolution` (bounded, seeded, derivative
free, with ``integrality`` for integer fields). The objective is not smooth (hi-lo
switching, current saturation, integer orders) and may have several minima, which rules
out gradient methods; each generation is evaluated as one batch (``vectorized``), so
its ``population x roads`` runs share the cores. No gradient polish is applied.

Every candidate's scenario is checked when the problem is loaded (each parameter at its
bounds, every road), so a bad file fails before any computation.

Examples
--------
>>> problem = OptimizationProblem.from_dict({
...     "controller": {"law": "passive"},
...     "simulation": {"dt": 5e-4},
...     "parameters": [{"field": "controller.current", "lower": 0.0, "upper": 0.5}],
...     "roads": [{"iso_class": "C", "length": 30.0, "speed": 50.0}],
...     "objective": {"weights": {"wk_rms_body_acceleration": 1.0}},
... })
>>> [p.field for p in problem.parameters], [r.name for r in problem.roads]
(['controller.current'], ['ISO 8608 C, seed 0, 30 m, 50 km/h'])
>>> OptimizationProblem.from_dict({**problem.to_dict(), "objective": {"weights": {"DLX": 1.0}}})
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: [objective] weights: unknown measure 'DLX'. Did you mean 'DLC'? Valid: DLC, mean_current, rms_body_acceleration, rms_stroke, vdv, wk_rms_body_acceleration.
"""

from __future__ import annotations

import copy
import json
import math
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension._batch import job_of, process_pool, run_jobs
from mrsuspension._docs import doc
from mrsuspension._inputs import read_toml
from mrsuspension.engine.plants import PLANTS
from mrsuspension.engine.vehicle_result import SEAT_MEASURES
from mrsuspension.errors import (
    ValidationError,
    check_keys,
    check_tables,
    did_you_mean,
)
from mrsuspension.excitation import EXCITATION_OPTIONS, FULL_CAR_CORNERS, HALF_CAR_CORNERS
from mrsuspension.scenario import SCENARIO_KEYS, WHEEL_KINDS, Scenario
from mrsuspension.studies.study import MEASURES, merge_scenario_tables

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

__all__ = [
    "OBJECTIVE_MEASURES",
    "OptimizationProblem",
    "OptimizationResult",
    "Parameter",
    "Road",
    "objective_value",
    "optimize",
]

#: Measures an objective may weight (the road measures of ``SimulationResult.measures()``).
OBJECTIVE_MEASURES: tuple[str, ...] = tuple(
    m
    for m in MEASURES["road"]
    if m != "vm_clamp_fraction"  # a diagnostic, not a goal
)

_TOP_LEVEL = ("problem", "parameters", "roads", "objective", *SCENARIO_KEYS)
_PROBLEM_KEYS = (
    "name",
    "description",
    "seed",
    "max_evaluations",
    "population",
    "tolerance",
    "workers",
)
_PARAMETER_KEYS = ("field", "lower", "upper", "integer", "log")
_ROAD_OPTIONS = tuple(EXCITATION_OPTIONS["road"])
#: the road kinds of an objective and their options: one track (every model; a half or
#: full car gets it under both sides, the rear wheels later) or a two-track road (a half
#: or full car: left and right tracks of the same class, correlated as ISO 8608 roads are)
ROAD_KINDS: dict[str, tuple[str, ...]] = {
    "road": _ROAD_OPTIONS,
    "two-track": tuple(WHEEL_KINDS["two-track"]),
}
_ROAD_KEYS = ("name", "weight", "kind", *dict.fromkeys(k for v in ROAD_KINDS.values() for k in v))
_OBJECTIVE_KEYS = ("weights", "reference")
#: road options that select the profile (a road giving one drops the base's others)
_PROFILE_KEYS = {
    "profile": ("iso_class", "seed", "length", "spacing"),
    "iso_class": ("profile", "distance_unit", "elevation_unit"),
}
#: sections whose numeric fields may be tuned (the excitation is what we tune *for*)
_TUNABLE_SECTIONS = ("vehicle", "damper", "controller", "simulation")
#: default reference controller: the passive damper at 0 A (its softest setting)
DEFAULT_REFERENCE: dict[str, dict[str, Any]] = {"controller": {"law": "passive", "current": 0.0}}
DEFAULT_MAX_EVALUATIONS = 200
#: largest evaluation budget (and population): every candidate is a simulation per road
MAX_EVALUATIONS = 100_000
_BUDGET_WHY = " (every candidate runs one simulation per road)"
#: candidates per generation and parameter (scipy suggests 5-10 per dimension)
POPULATION_PER_PARAMETER = 6
#: scipy's smallest differential-evolution population
MIN_POPULATION = 5


# -- checking helpers ---------------------------------------------------------------------
def _is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def _number(where: str, value: object) -> float:
    if not _is_number(value) or not math.isfinite(float(value)):  # type: ignore[arg-type]
        raise ValidationError(f"{where} must be a finite number; got {value!r}")
    return float(value)  # type: ignore[arg-type]


def _int_option(where: str, value: object, low: int, high: int | None = None) -> int:
    if not isinstance(value, int) or isinstance(value, bool) or value < low:
        raise ValidationError(f"{where} must be an integer >= {low}; got {value!r}")
    if high is not None and value > high:
        raise ValidationError(
            f"{where} must be an integer in [{low}, {high}]{_BUDGET_WHY}; got {value!r}"
        )
    return value


def _set(tables: dict[str, dict[str, Any]], dotted: str, value: Any) -> None:
    section, key = dotted.split(".", 1)
    table = tables.setdefault(section, {})
    if "." in key:  # one corner of a half or full car: damper.front_left.force_gain
        corner, key = key.split(".", 1)
        table = table.setdefault(corner, {})
    table[key] = value


def _field_kind(dotted: str) -> str:
    """Value kind of a dotted field (``section.key`` or ``section.corner.key``)."""
    parts = dotted.split(".")
    return SCENARIO_KEYS[parts[0]][parts[-1]]


def _objective_measures(base: Mapping[str, Any]) -> tuple[str, ...]:
    """Measures an objective may weight for the base's vehicle model.

    The quarter car's :data:`OBJECTIVE_MEASURES`; a half or full car's body RMS
    accelerations, every corner's ``"<measure>.<corner>"`` and the seat's measures
    (its plant's ``on_request``).
    """
    model = PLANTS.get(base.get("vehicle", {}).get("model", "quarter-car"))
    if model is None:
        return OBJECTIVE_MEASURES
    return (*model.measure_names(OBJECTIVE_MEASURES), *model.on_request)


# -- the parts of a problem ---------------------------------------------------------------
@dataclass(frozen=True)
class Parameter:
    """A tuned scenario field and its bounds.

    Parameters
    ----------
    field : str
        Dotted scenario field, e.g. ``"controller.gain"``.
    lower, upper : float
        Bounds (``lower < upper``).
    integer : bool
        Only whole values (e.g. ``controller.order``).
    log : bool
        Search ``log10(value)`` (needs ``lower > 0``; not with ``integer``).

    Examples
    --------
    >>> p = Parameter("controller.gain", 1.0, 1000.0, log=True)
    >>> p.search_bounds, p.value(2.0)
    ((0.0, 3.0), 100.0)
    >>> Parameter("controller.gain", 5.0, 1.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: [[parameters]] controller.gain: lower = 5 must be below upper = 1
    """

    field: str
    lower: float
    upper: float
    integer: bool = False
    log: bool = False

    def __post_init__(self) -> None:
        where = f"[[parameters]] {self.field}:"
        if not self.lower < self.upper:
            raise ValidationError(
                f"{where} lower = {self.lower:g} must be below upper = {self.upper:g}"
            )
        if self.log and self.integer:
            raise ValidationError(f"{where} choose integer or log, not both")
        if self.log and self.lower <= 0.0:
            raise ValidationError(f"{where} log = true needs lower > 0; got {self.lower:g}")
        if self.integer and math.ceil(self.lower) > math.floor(self.upper):
            raise ValidationError(
                f"{where} no whole number between lower = {self.lower:g} and upper = {self.upper:g}"
            )

    @property
    def search_bounds(self) -> tuple[float, float]:
        """Bounds of the search variable (``log10`` of the bounds when ``log``)."""
        if self.log:
            return (math.log10(self.lower), math.log10(self.upper))
        if self.integer:
            return (float(math.ceil(self.lower)), float(math.floor(self.upper)))
        return (self.lower, self.upper)

    def value(self, x: float) -> float:
        """The field value of a search variable ``x`` (clipped to the bounds)."""
        lo, hi = self.search_bounds
        x = min(max(float(x), lo), hi)
        if self.log:
            return float(min(max(10.0**x, self.lower), self.upper))
        if self.integer:
            return float(round(x))
        return x

    def to_dict(self) -> dict[str, Any]:
        """The ``[[parameters]]`` table."""
        return {
            "field": self.field,
            "lower": self.lower,
            "upper": self.upper,
            "integer": self.integer,
            "log": self.log,
        }


def _parameter(index: int, table: object) -> Parameter:
    where = f"[[parameters]] #{index + 1}"
    t = check_keys(where, table, _PARAMETER_KEYS)
    for key in ("field", "lower", "upper"):
        if key not in t:
            raise ValidationError(f"{where} needs {key!r}")
    name = t["field"]
    tunable = [
        f"{s}.{k}"
        for s in _TUNABLE_SECTIONS
        for k, kind in SCENARIO_KEYS[s].items()
        if kind in ("number", "integer")
    ] + [  # one corner of a half or full car
        f"{s}.{c}.{k}"
        for s in ("damper", "controller")
        for c in (*FULL_CAR_CORNERS, *HALF_CAR_CORNERS)
        for k, kind in SCENARIO_KEYS[s].items()
        if kind in ("number", "integer")
    ]
    if not isinstance(name, str) or name not in tunable:
        extra = ""
        if isinstance(name, str) and name.startswith("excitation."):
            extra = " Roads are set in [[roads]], not tuned."
        raise ValidationError(
            f"{where} field: {name!r} is not a numeric scenario field of "
            f"{', '.join(_TUNABLE_SECTIONS)}.{did_you_mean(str(name), tunable)}{extra} "
            f"See {doc('scenarios')} for the keys."
        )
    flags = {}
    for key in ("integer", "log"):
        value = t.get(key, False)
        if not isinstance(value, bool):
            raise ValidationError(f"{where} {key} must be true or false; got {value!r}")
        flags[key] = value
    if _field_kind(name) == "integer":
        flags["integer"] = True
    return Parameter(
        name,
        _number(f"{where} lower", t["lower"]),
        _number(f"{where} upper", t["upper"]),
        **flags,
    )


@dataclass(frozen=True)
class Road:
    """One road of the objective: excitation options, a name and a weight.

    ``kind`` is ``"road"`` (one track; default) or ``"two-track"`` (a half or full car:
    its own track under each side, :data:`ROAD_KINDS`).

    Examples
    --------
    >>> Road.from_dict({"profile": "rough", "speed": 80.0}).name
    'rough, 80 km/h'
    >>> Road.from_dict({"kind": "two-track", "iso_class": "C", "length": 200.0}).name
    'two-track ISO 8608 C, seed 0, 200 m, 50 km/h'
    """

    name: str
    options: dict[str, Any]
    weight: float = 1.0
    kind: str = "road"

    @classmethod
    def from_dict(
        cls, table: Mapping[str, Any], shared: Mapping[str, Any] | None = None, index: int = 0
    ) -> Road:
        """A ``[[roads]]`` table over the base ``[excitation]`` options ``shared``."""
        where = f"[[roads]] #{index + 1}"
        t = check_keys(where, table, _ROAD_KEYS)
        kind = t.get("kind", (shared or {}).get("kind", "road"))
        if kind not in ROAD_KINDS:
            raise ValidationError(
                f"{where} kind: {kind!r} is not a road kind of an objective."
                f"{did_you_mean(str(kind), list(ROAD_KINDS))} Valid: {', '.join(ROAD_KINDS)}."
            )
        for key in t:
            if key not in ("name", "weight", "kind") and key not in ROAD_KINDS[kind]:
                valid = ["name", "weight", "kind", *ROAD_KINDS[kind]]
                raise ValidationError(
                    f"{where} {key} does not apply to kind {kind!r}."
                    f"{did_you_mean(str(key), valid)} Valid: {', '.join(valid)}."
                )
        options = {k: v for k, v in (shared or {}).items() if k != "kind" and k in ROAD_KINDS[kind]}
        for key, dropped in _PROFILE_KEYS.items():
            if key in t:
                for other in dropped:
                    options.pop(other, None)
        options.update({k: v for k, v in t.items() if k not in ("name", "weight", "kind")})
        if "profile" not in options and "iso_class" not in options:
            raise ValidationError(
                f"{where} needs 'profile' (a preset name or a CSV file) or 'iso_class' (ISO 8608 A-H)"
            )
        weight = _number(f"{where} weight", t.get("weight", 1.0))
        if weight < 0.0:
            raise ValidationError(f"{where} weight must be >= 0; got {weight:g}")
        name = t.get("name")
        if name is None:
            name = ("" if kind == "road" else f"{kind} ") + _road_name(options)
        elif not isinstance(name, str) or not name:
            raise ValidationError(f"{where} name must be a non-empty string; got {name!r}")
        return cls(name, options, weight, kind)

    def excitation(self) -> dict[str, Any]:
        """The ``[excitation]`` table of this road."""
        return {"kind": self.kind, **copy.deepcopy(self.options)}

    def to_dict(self) -> dict[str, Any]:
        """The ``[[roads]]`` table."""
        kind = {} if self.kind == "road" else {"kind": self.kind}
        return {"name": self.name, "weight": self.weight, **kind, **self.options}


def _road_name(options: Mapping[str, Any]) -> str:
    speed = options.get("speed", 50.0)
    if "profile" in options:
        text = str(options["profile"])
    else:
        text = f"ISO 8608 {options['iso_class']}, seed {options.get('seed', 0)}"
        if "length" in options:
            text += f", {options['length']:g} m"
    return f"{text}, {speed:g} km/h"


def objective_value(
    measures: Sequence[Mapping[str, float]],
    reference: Sequence[Mapping[str, float]],
    weights: Mapping[str, float],
    road_weights: Sequence[float] | None = None,
) -> float:
    """Weighted mean of measures normalised by the reference's on the same road.

    ``J = sum_m (w_m / W) sum_r (v_r / V) q[r][m] / reference[r][m]``.

    Parameters
    ----------
    measures, reference : sequence of mapping
        Per road, measure name -> value (the candidate's and the reference's).
    weights : mapping
        Measure name -> weight (>= 0, not all 0).
    road_weights : sequence of float, optional
        One weight per road (default: equal).

    Raises
    ------
    ValidationError
        A weighted reference value that is zero or not finite (nothing to normalise by).

    Examples
    --------
    >>> objective_value([{"DLC": 0.1, "vdv": 2.0}], [{"DLC": 0.2, "vdv": 1.0}], {"DLC": 3.0, "vdv": 1.0})
    0.875
    """
    n = len(measures)
    if len(reference) != n:
        raise ValidationError(
            f"measures and reference need one entry per road; got {n} and {len(reference)}"
        )
    vw = [1.0] * n if road_weights is None else [float(w) for w in road_weights]
    total_w = float(sum(weights.values()))
    total_v = float(sum(vw))
    if total_w <= 0.0 or total_v <= 0.0:
        raise ValidationError("the measure and road weights must not all be zero")
    value = 0.0
    for m, w in weights.items():
        if w == 0.0:
            continue
        for r in range(n):
            ref = float(reference[r][m])
            if not math.isfinite(ref) or ref == 0.0:
                hint = (
                    " (the same profile under both sides rolls the body by nothing: give "
                    "kind = 'two-track' roads)"
                    if m.startswith("roll_")
                    else ""
                )
                raise ValidationError(
                    f"the reference controller's {m} is {ref:g} on road #{r + 1}: cannot "
                    f"normalise by it{hint}; choose another [objective] reference or drop the "
                    "weight"
                )
            value += (w / total_w) * (vw[r] / total_v) * float(measures[r][m]) / ref
    return value


def _weights(table: object, valid_measures: Sequence[str] = OBJECTIVE_MEASURES) -> dict[str, float]:
    where = "[objective] weights"
    if not isinstance(table, Mapping) or not table:
        raise ValidationError(
            f"{where} must be a non-empty table of measure = weight, e.g. "
            f"{{wk_rms_body_acceleration = 1.0, DLC = 1.0}}; got {table!r}"
        )
    out: dict[str, float] = {}
    for m, w in table.items():
        if m not in valid_measures:
            valid = sorted(valid_measures)
            raise ValidationError(
                f"{where}: unknown measure {m!r}.{did_you_mean(str(m), valid)} "
                f"Valid: {', '.join(valid)}."
            )
        value = _number(f"{where} {m}", w)
        if value < 0.0:
            raise ValidationError(f"{where} {m} must be >= 0; got {value:g}")
        out[m] = value
    if not any(out.values()):
        raise ValidationError(f"{where}: at least one weight must be > 0")
    return out


def _reference(table: object) -> dict[str, dict[str, Any]]:
    where = "[objective] reference"
    t = check_keys(where, table, tuple(s for s in SCENARIO_KEYS if s != "excitation"))
    out: dict[str, dict[str, Any]] = {}
    for section, value in t.items():
        if not isinstance(value, Mapping):
            raise ValidationError(f"{where} {section} must be a table; got {value!r}")
        out[section] = copy.deepcopy(dict(value))
    return out


# -- the problem --------------------------------------------------------------------------
@dataclass(frozen=True)
class OptimizationProblem:
    """A validated optimisation problem (see the module docstring for the file format).

    Parameters
    ----------
    name : str
        Problem name (file stem by default).
    base : dict
        The base scenario's tables (without the roads).
    parameters : tuple of Parameter
        The tuned fields.
    roads : tuple of Road
        The roads of the objective.
    weights : dict
        Measure -> weight.
    reference : dict
        Tables replacing the base's for the reference controller.
    seed : int
        Seed of the search.
    max_evaluations : int
        Candidates to evaluate (whole generations; at least one population).
    population : int
        Candidates per generation.
    tolerance : float
        Relative spread of the population's objectives that stops the search early
        (scipy's ``tol``; 0: spend the whole budget).
    workers : int or None
        Processes (None: one per core; 1: this process).
    description : str
        Free text.
    base_dir : Path
        Folder for relative paths (parameter files, road profiles).
    """

    name: str
    base: dict[str, dict[str, Any]]
    parameters: tuple[Parameter, ...]
    roads: tuple[Road, ...]
    weights: dict[str, float]
    reference: dict[str, dict[str, Any]] = field(
        default_factory=lambda: copy.deepcopy(DEFAULT_REFERENCE)
    )
    seed: int = 0
    max_evaluations: int = DEFAULT_MAX_EVALUATIONS
    population: int = MIN_POPULATION
    tolerance: float = 0.0
    workers: int | None = None
    description: str = ""
    base_dir: Path = field(default_factory=Path.cwd)

    # -- loading ------------------------------------------------------------------------
    @classmethod
    def load(cls, path: str | Path) -> OptimizationProblem:
        """Read and validate a problem TOML file (relative paths from its folder)."""
        path = Path(path)
        data = read_toml(path, "optimisation problem")
        problem = data.get("problem", {})
        if isinstance(problem, dict):
            problem.setdefault("name", path.stem)
        return cls.from_dict(data, base_dir=path.resolve().parent)

    @classmethod
    def from_dict(
        cls, data: Mapping[str, Any], base_dir: str | Path | None = None
    ) -> OptimizationProblem:
        """Validate plain tables (as read from TOML); every road and bound is checked.

        Raises
        ------
        ValidationError
            Unknown tables, keys, fields or measures (with a did-you-mean), bad bounds,
            empty parameter or road lists, and any candidate scenario (a parameter at a
            bound, a road, the reference) that fails the scenario checks.
        """
        check_tables("an optimisation problem", data, _TOP_LEVEL)
        base_path = Path.cwd() if base_dir is None else Path(base_dir)
        meta = check_keys("[problem]", data.get("problem", {}), _PROBLEM_KEYS)

        base = merge_scenario_tables({}, data)
        shared = base.pop("excitation", {})
        shared_kind = shared.get("kind", "road")
        if shared_kind not in ROAD_KINDS:
            raise ValidationError(
                f"[excitation] kind must be one of {', '.join(ROAD_KINDS)} in an optimisation "
                f"problem; got {shared_kind!r}"
            )
        for key in shared:
            if key != "kind" and key not in ROAD_KINDS[shared_kind]:
                valid = ["kind", *ROAD_KINDS[shared_kind]]
                raise ValidationError(
                    f"unknown key [excitation] {key} for roads.{did_you_mean(str(key), valid)} "
                    f"Valid: {', '.join(valid)}."
                )

        raw_params = data.get("parameters")
        if not isinstance(raw_params, list) or not raw_params:
            raise ValidationError(
                "[[parameters]] must list at least one field to tune, e.g. "
                '[[parameters]] field = "controller.gain", lower = 1.0, upper = 100.0; '
                f"got {raw_params!r}"
            )
        parameters = tuple(_parameter(k, t) for k, t in enumerate(raw_params))
        fields = [p.field for p in parameters]
        for f in fields:
            if fields.count(f) > 1:
                raise ValidationError(f"[[parameters]] field {f!r} is given twice")

        raw_roads = data.get("roads")
        if not isinstance(raw_roads, list) or not raw_roads:
            raise ValidationError(
                '[[roads]] must list at least one road, e.g. [[roads]] profile = "rough", '
                f"speed = 50.0; got {raw_roads!r}"
            )
        roads = tuple(Road.from_dict(t, shared, k) for k, t in enumerate(raw_roads))
        names = [r.name for r in roads]
        for n in names:
            if names.count(n) > 1:
                raise ValidationError(f"[[roads]] name {n!r} is used twice; give each road a name")
        if not any(r.weight for r in roads):
            raise ValidationError("[[roads]] weights: at least one must be > 0")

        objective = check_keys("[objective]", data.get("objective"), _OBJECTIVE_KEYS)
        weights = _weights(objective.get("weights"), _objective_measures(base))
        reference = _reference(objective.get("reference", DEFAULT_REFERENCE))

        seed = _int_option("[problem] seed", meta.get("seed", 0), 0)
        default_pop = max(MIN_POPULATION, POPULATION_PER_PARAMETER * len(parameters))
        population = _int_option(
            "[problem] population",
            meta.get("population", default_pop),
            MIN_POPULATION,
            MAX_EVALUATIONS,
        )
        max_evaluations = _int_option(
            "[problem] max_evaluations",
            meta.get("max_evaluations", DEFAULT_MAX_EVALUATIONS),
            1,
            MAX_EVALUATIONS,
        )
        tolerance = _number("[problem] tolerance", meta.get("tolerance", 0.0))
        if tolerance < 0.0:
            raise ValidationError(f"[problem] tolerance must be >= 0; got {tolerance:g}")
        workers = meta.get("workers")
        if workers is not None:
            workers = _int_option("[problem] workers", workers, 1)
        problem = cls(
            name=str(meta.get("name", "optimisation")),
            base=base,
            parameters=parameters,
            roads=roads,
            weights=weights,
            reference=reference,
            seed=seed,
            max_evaluations=max_evaluations,
            population=population,
            tolerance=tolerance,
            workers=workers,
            description=str(meta.get("description", "")),
            base_dir=base_path,
        )
        problem.check_budget(max_evaluations)
        problem._check_scenarios()
        return problem

    def _check_scenarios(self) -> None:
        """Build every road at the middle of the bounds, each bound, and the reference."""
        middle = {p.field: p.value(sum(p.search_bounds) / 2.0) for p in self.parameters}
        for road in self.roads:
            self._checked(middle, road, f"road {road.name!r} (parameters at mid-range)")
            self._checked(None, road, f"the reference on road {road.name!r}")
        for p in self.parameters:
            for bound in p.search_bounds:
                values = {**middle, p.field: p.value(bound)}
                self._checked(values, self.roads[0], f"{p.field} = {p.value(bound):g}")

    def _checked(self, values: Mapping[str, float] | None, road: Road, what: str) -> Scenario:
        try:
            return self.scenario(values, road)
        except ValidationError as err:
            raise ValidationError(f"optimisation problem, {what}: {err}") from None

    def check_budget(self, max_evaluations: int) -> int:
        """Validate an evaluation budget; returns the generations after the first.

        Raises
        ------
        ValidationError
            A budget below one population.
        """
        if not isinstance(max_evaluations, int) or max_evaluations < self.population:
            raise ValidationError(
                f"max_evaluations = {max_evaluations!r} is below one population "
                f"({self.population} candidates): give at least {self.population}"
            )
        if max_evaluations > MAX_EVALUATIONS:
            raise ValidationError(
                f"max_evaluations = {max_evaluations!r} is more than the {MAX_EVALUATIONS} "
                f"allowed{_BUDGET_WHY}"
            )
        return max_evaluations // self.population - 1

    # -- building -----------------------------------------------------------------------
    def tables(self, values: Mapping[str, float] | None, road: Road) -> dict[str, dict[str, Any]]:
        """Scenario tables of a candidate (``values``: field -> value; None: the reference)."""
        out = copy.deepcopy(self.base)
        if values is None:
            out.update(copy.deepcopy(self.reference))
        else:
            for name, value in values.items():
                kind = _field_kind(name)
                _set(out, name, round(value) if kind == "integer" else float(value))
        out["excitation"] = road.excitation()
        return out

    def scenario(self, values: Mapping[str, float] | None, road: Road) -> Scenario:
        """The validated :class:`~mrsuspension.scenario.Scenario` of a candidate on a road."""
        return Scenario.from_dict(self.tables(values, road), base_dir=self.base_dir)

    def values(self, x: Sequence[float] | np.ndarray) -> dict[str, float]:
        """Field values of a search vector."""
        return {p.field: p.value(v) for p, v in zip(self.parameters, x, strict=True)}

    def to_dict(self) -> dict[str, Any]:
        """The problem as plain tables (TOML-ready)."""
        out: dict[str, Any] = copy.deepcopy(self.base)
        out["problem"] = {
            "name": self.name,
            "description": self.description,
            "seed": self.seed,
            "max_evaluations": self.max_evaluations,
            "population": self.population,
            "tolerance": self.tolerance,
        }
        if self.workers is not None:
            out["problem"]["workers"] = self.workers
        out["parameters"] = [p.to_dict() for p in self.parameters]
        out["roads"] = [r.to_dict() for r in self.roads]
        out["objective"] = {
            "weights": dict(self.weights),
            "reference": copy.deepcopy(self.reference),
        }
        return out


@dataclass
class OptimizationResult:
    """The best candidate, its measures on every road, and the search history.

    Parameters
    ----------
    problem : OptimizationProblem
        The problem solved.
    best : dict
        Field -> best value found.
    objective : float
        Its objective (the reference scores 1).
    measures : dict
        Road name -> the best candidate's measures.
    reference : dict
        Road name -> the reference controller's measures.
    history : list of dict
        Every evaluated candidate in order: ``evaluation``, ``generation``, the field
        values and ``objective`` (inf when a run diverged or the scenario was refused).
    generations : int
        Generations run (the first population included).
    run_time : float
        Wall time [s].
    message : str
        The optimiser's stop reason.
    """

    problem: OptimizationProblem
    best: dict[str, float]
    objective: float
    measures: dict[str, dict[str, float]]
    reference: dict[str, dict[str, float]]
    history: list[dict[str, Any]]
    generations: int
    run_time: float
    message: str = ""

    @property
    def evaluations(self) -> int:
        """Candidates evaluated (repeated candidates count once)."""
        return len(self.history)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON-ready; inf objectives become None)."""

        def clean(v: Any) -> Any:
            if isinstance(v, float) and not math.isfinite(v):
                return None
            if isinstance(v, dict):
                return {k: clean(x) for k, x in v.items()}
            if isinstance(v, list):
                return [clean(x) for x in v]
            return v

        return clean(
            {
                "problem": self.problem.name,
                "best": dict(self.best),
                "objective": self.objective,
                "reference_objective": 1.0,
                "measures": copy.deepcopy(self.measures),
                "reference": copy.deepcopy(self.reference),
                "weights": dict(self.problem.weights),
                "evaluations": self.evaluations,
                "generations": self.generations,
                "run_time_s": round(self.run_time, 3),
                "message": self.message,
                "history": copy.deepcopy(self.history),
                "definition": self.problem.to_dict(),
            }
        )

    def to_pandas(self) -> pd.DataFrame:
        """The history: one row per evaluated candidate."""
        import pandas as pd

        return pd.DataFrame(self.history)

    def plot(self) -> Figure:
        """Convergence: every candidate's objective and the best so far, by evaluation."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        obj = np.array([h["objective"] for h in self.history], dtype=float)
        k = np.arange(1, obj.size + 1)
        finite = np.isfinite(obj)
        best = np.minimum.accumulate(np.where(finite, obj, np.inf))
        fig, ax = plt.subplots(figsize=(6.5, 3.6), layout="constrained")
        ax.plot(k[finite], obj[finite], "o", ms=3, alpha=0.5, label="candidate")
        ax.step(k, best, where="post", color="C3", label="best so far")
        ax.axhline(1.0, color="0.5", ls="--", lw=0.8, label="reference (J = 1)")
        ax.set_xlabel("evaluation")
        ax.set_ylabel("objective J")
        ax.set_title(f"{self.problem.name}: J = {self.objective:.4g}", fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return fig

    def save(self, folder: str | Path) -> list[Path]:
        """Write ``optimization.json`` and ``convergence.png`` to ``folder``."""
        import matplotlib.pyplot as plt

        folder = Path(folder)
        folder.mkdir(parents=True, exist_ok=True)
        data = folder / "optimization.json"
        data.write_text(json.dumps(self.to_dict(), indent=2) + "\n")
        png = folder / "convergence.png"
        fig = self.plot()
        fig.savefig(png, dpi=110)
        plt.close(fig)
        return [data, png]


Progress = Callable[[int, int, float], None]


@contextmanager
def _bar(enabled: bool | Progress, label: str) -> Iterator[Progress | None]:
    """A rich progress bar on stderr as ``progress(generation, total, best)``."""
    if callable(enabled):
        yield enabled
        return
    if not enabled:
        yield None
        return
    from mrsuspension._progress import progress_bar

    with progress_bar(True, label) as bar:
        assert bar is not None

        def update(done: int, total: int, best: float) -> None:
            bar(done, total, f"best J = {best:.4g}")

        yield update


def optimize(
    problem: OptimizationProblem | str | Path,
    *,
    max_evaluations: int | None = None,
    workers: int | None = None,
    progress: bool | Progress = True,
) -> OptimizationResult:
    """Tune the problem's parameters by differential evolution (see the module docstring).

    Parameters
    ----------
    problem : OptimizationProblem or path
        A problem, or a problem TOML file to load.
    max_evaluations : int, optional
        Candidate budget (default the problem's); whole generations of
        ``problem.population`` candidates, at least one.
    workers : int, optional
        Processes (default the problem's, else one per core; 1: this process).
    progress : bool or callable
        A rich progress bar on stderr (True), none (False), or
        ``progress(generation, generations, best_objective)``.

    Returns
    -------
    OptimizationResult

    Raises
    ------
    ValidationError
        A bad problem or budget, a reference measure of zero, or no candidate that runs.

    Examples
    --------
    >>> problem = OptimizationProblem.from_dict({
    ...     "controller": {"law": "passive"},
    ...     "simulation": {"dt": 5e-4},
    ...     "problem": {"population": 5, "seed": 1},
    ...     "parameters": [{"field": "controller.current", "lower": 0.0, "upper": 0.5}],
    ...     "roads": [{"iso_class": "C", "length": 30.0}],
    ...     "objective": {"weights": {"rms_stroke": 1.0}},
    ... })
    >>> result = optimize(problem, max_evaluations=10, workers=1, progress=False)
    >>> result.evaluations, bool(result.objective < 1.0)  # a harder damper, less stroke
    (10, True)
    """
    from scipy.optimize import differential_evolution
    from scipy.stats import qmc

    if not isinstance(problem, OptimizationProblem):
        problem = OptimizationProblem.load(problem)
    budget = problem.max_evaluations if max_evaluations is None else max_evaluations
    maxiter = problem.check_budget(budget)
    n_workers = problem.workers if workers is None else workers
    if n_workers is not None and (not isinstance(n_workers, int) or n_workers < 1):
        raise ValidationError(f"workers must be an integer >= 1; got {n_workers!r}")
    roads = problem.roads
    road_weights = [r.weight for r in roads]
    bounds = [p.search_bounds for p in problem.parameters]
    integrality = [p.integer for p in problem.parameters]
    start = time.perf_counter()
    history: list[dict[str, Any]] = []
    cache: dict[tuple[float, ...], tuple[float, list[dict[str, Any]] | None]] = {}
    generation = 0

    seat = bool(set(problem.weights) & set(SEAT_MEASURES))  # from the time history
    with process_pool(n_workers, problem.population * len(roads)) as pool:
        ref_rows = _measure_runs([problem.scenario(None, r) for r in roads], pool, seat)
        if any(row is None for row in ref_rows):
            raise ValidationError("the reference controller's run diverged; check the problem")
        reference = [dict(row or {}) for row in ref_rows]
        # fail now, not after the search, when a reference value cannot normalise
        objective_value(reference, reference, problem.weights, road_weights)

        def evaluate(x: np.ndarray) -> np.ndarray:
            nonlocal generation
            columns = np.asarray(x, dtype=float).reshape(len(bounds), -1)  # (N, S)
            candidates = [problem.values(columns[:, s]) for s in range(columns.shape[1])]
            keys = [tuple(c.values()) for c in candidates]
            new = [k for k in dict.fromkeys(keys) if k not in cache]
            batch: list[Scenario] = []
            owners: list[tuple[float, ...]] = []
            for key in new:
                values = dict(zip((p.field for p in problem.parameters), key, strict=True))
                try:
                    scenarios = [problem.scenario(values, r) for r in roads]
                except ValidationError:
                    cache[key] = (math.inf, None)
                    continue
                batch.extend(scenarios)
                owners.extend([key] * len(roads))
            rows = _measure_runs(batch, pool, seat)
            by_key: dict[tuple[float, ...], list[dict[str, Any] | None]] = {}
            for key, row in zip(owners, rows, strict=True):
                by_key.setdefault(key, []).append(row)
            for key, runs in by_key.items():
                if any(r is None for r in runs):
                    cache[key] = (math.inf, None)
                    continue
                got = [dict(r or {}) for r in runs]
                cache[key] = (objective_value(got, reference, problem.weights, road_weights), got)
            for key in new:
                values = dict(zip((p.field for p in problem.parameters), key, strict=True))
                history.append(
                    {
                        "evaluation": len(history) + 1,
                        "generation": generation,
                        **values,
                        "objective": cache[key][0],
                    }
                )
            generation += 1
            if tick is not None:
                best = min((h["objective"] for h in history), default=math.inf)
                tick(generation, maxiter + 1, best)
            return np.array([cache[k][0] for k in keys])

        sampler = qmc.LatinHypercube(d=len(bounds), rng=problem.seed)
        lo = np.array([b[0] for b in bounds])
        hi = np.array([b[1] for b in bounds])
        init = lo + sampler.random(problem.population) * (hi - lo)
        with _bar(progress, f"optimising {problem.name}") as tick:
            res = differential_evolution(
                evaluate,
                bounds,
                maxiter=maxiter,
                init=init,
                rng=problem.seed,
                polish=False,
                tol=problem.tolerance,
                atol=0.0,
                updating="deferred",
                vectorized=True,
                integrality=integrality if any(integrality) else None,
            )
    finite = [h for h in history if math.isfinite(h["objective"])]
    if not finite:
        raise ValidationError(
            "no candidate could be evaluated (every run diverged or was refused); "
            "narrow the parameter bounds"
        )
    best_row = min(finite, key=lambda h: h["objective"])
    best = {p.field: float(best_row[p.field]) for p in problem.parameters}
    best_runs = cache[tuple(best.values())][1] or []
    names = [r.name for r in roads]
    return OptimizationResult(
        problem=problem,
        best=best,
        objective=float(best_row["objective"]),
        measures={n: _floats(m) for n, m in zip(names, best_runs, strict=True)},
        reference={n: _floats(m) for n, m in zip(names, reference, strict=True)},
        history=history,
        generations=generation,
        run_time=time.perf_counter() - start,
        message=str(res.message),
    )


def _measure_runs(
    scenarios: Sequence[Scenario], pool: Any, seat: bool = False
) -> list[dict[str, Any] | None]:
    """Measures of each single-run scenario of any model, in order (None for a diverged
    run): :func:`~mrsuspension._batch.run_jobs` (the engine's
    :func:`~mrsuspension.engine.batch.measure_batch`) on the open pool; ``seat``: with
    the seat's ISO 2631-1 measures (each run keeps its time history)."""
    return run_jobs([job_of(s) for s in scenarios], pool, seat=seat)


def _floats(row: Mapping[str, Any]) -> dict[str, float]:
    return {k: float(v) for k, v in row.items()}
