"""Declarative studies: a base scenario, a grid of fields to vary and the measures to keep.

A study file is a scenario file (the same ``[vehicle]``, ``[damper]``, ``[controller]``,
``[excitation]`` and ``[simulation]`` tables, see :mod:`mrsuspension.scenario`) plus:

``[study]``
    ``name``, ``description``, ``measures`` (list of measure names; default: all of the
    excitation kind's; a half or full car also reports its seat's ISO 2631-1 measures
    ``seat_total``, ``seat_z``, ... when they are listed, see
    :data:`~mrsuspension.engine.vehicle_result.SEAT_MEASURES`), optionally ``scenario`` (a scenario file used as the base; the
    study's own tables override it key by key) and ``road_peak``, the road acceleration
    peak that divides ``SAR_s`` and ``SAR_u`` of pulse runs: ``"after-onset"`` (default,
    it matches the dissertation's SAR_s) or ``"onset"`` (see
    :func:`mrsuspension.measures.road_acceleration_peak`).
``[grid]``
    Dotted scenario fields and the values to try, e.g.
    ``"vehicle.sprung_mass" = [422.0, 563.0, 703.0]``. Every combination is run
    (a Cartesian product, one dimension per field, in file order).
``[cases.NAME]``
    A labelled dimension whose values change several fields together, e.g. a policy with
    its own gain: ``I = {controller = {law = "skyhook-hilo", gain = 3.0}}``.

A frequency list may be written as ``"log:N:f_min:f_max"`` or ``"lin:N:f_min:f_max"``
(in ``[excitation] frequencies`` or a grid value list). A swept excitation adds a
``frequency`` dimension (one steady-state run per frequency).

Every grid point's :class:`~mrsuspension.scenario.Scenario` is built and validated when
the study is loaded, so a bad study fails before any computation, with the message of
the scenario check and the grid point it came from.

Examples
--------
>>> study = Study.from_dict(
...     {
...         "study": {"name": "mass", "measures": ["T_as", "DLC"]},
...         "excitation": {"kind": "swept", "amplitude": 0.025, "frequencies": "log:3:1:4"},
...         "grid": {"vehicle.sprung_mass": [422.0, 563.0]},
...     }
... )
>>> study.dims, study.shape, len(study.simulations())
(('vehicle.sprung_mass', 'frequency'), (2, 3), 6)
>>> Study.from_dict({"excitation": {"kind": "pulse", "amplitude": 0.02, "severity": 1},
...                  "grid": {"vehicle.sprung_mas": [400.0]}})
Traceback (most recent call last):
...
mrsuspension.errors.ValidationError: [grid] unknown field 'vehicle.sprung_mas'. Did you mean 'vehicle.sprung_mass'? ...
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import itertools
import json
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mrsuspension._docs import doc
from mrsuspension._inputs import read_toml
from mrsuspension._progress import progress_bar
from mrsuspension.engine.result import MEASURES_BY_KIND
from mrsuspension.engine.settings import RunSettings
from mrsuspension.errors import (
    ValidationError,
    check_keys,
    check_tables,
    did_you_mean,
)
from mrsuspension.excitation import EXCITATIONS, FULL_CAR_CORNERS, HALF_CAR_CORNERS, log_frequencies
from mrsuspension.excitation.deterministic import DEFAULT_SWEEP_POINTS, MAX_FREQUENCIES
from mrsuspension.measures.shock import DEFAULT_ROAD_PEAK, RoadPeak, check_road_peak
from mrsuspension.scenario import SCENARIO_KEYS, Scenario

__all__ = [
    "MAX_RUNS",
    "MEASURES",
    "Axis",
    "Study",
    "check_scheduler",
    "expand_frequencies",
    "merge_scenario_tables",
]

#: most runs a study may have (grid points x sweep frequencies): refused beyond, on load
MAX_RUNS = 100_000
#: grid points beyond which ``progress=True`` shows their building (about 1 ms each)
PROGRESS_POINTS = 500
#: about how long one grid point takes to build and check [s] (for the refusal's estimate)
_BUILD_SECONDS = 1.3e-3
#: seconds ``check_scheduler`` waits for a Dask scheduler to accept a connection, then
#: again for its handshake (``mrsus study --scheduler-timeout``)
SCHEDULER_TIMEOUT = 10.0
_ADDRESS = re.compile(r"^(?:tcp://)?(\[[^\]]+\]|[^:/\s]+):([0-9]+)/?$")


def check_scheduler(address: str, timeout: float = SCHEDULER_TIMEOUT) -> str:
    """A Dask scheduler address (``tcp://host:port`` or ``host:port``) that answers.

    Parsed, connected to with a ``timeout`` [s] (10 s by default, instead of Dask's own
    30 s and retries), and then given ``timeout`` again for the scheduler's handshake (a
    Dask scheduler greets a new connection at once), before a study is sent to it: a
    server that accepts the connection and never answers is refused in bounded time.
    Returns the ``tcp://host:port`` form.

    Raises
    ------
    ValidationError
        A malformed address, a port out of 1-65535, a timeout out of (0, 3600] s, or a
        scheduler that does not answer.

    Examples
    --------
    >>> check_scheduler("my-cluster")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --scheduler 'my-cluster' is not a Dask scheduler address: expected tcp://host:port or host:port (e.g. tcp://10.0.0.5:8786)
    """
    import socket

    from mrsuspension.errors import check_port, check_range

    timeout = float(
        check_range("--scheduler-timeout", timeout, 0.0, 3600.0, unit="s", low_inclusive=False)
    )
    match = _ADDRESS.match(address.strip())
    if match is None:
        raise ValidationError(
            f"--scheduler {address!r} is not a Dask scheduler address: expected "
            "tcp://host:port or host:port (e.g. tcp://10.0.0.5:8786)"
        )
    host, port = match.group(1), int(match.group(2))
    check_port(f"--scheduler {address!r}: the port", port)
    try:
        with socket.create_connection((host.strip("[]"), port), timeout=timeout) as conn:
            conn.settimeout(timeout)
            try:
                greeting = conn.recv(1)
            except TimeoutError:
                raise ValidationError(
                    f"--scheduler {address!r}: {host}:{port} accepted the connection but sent "
                    f"no Dask handshake within {timeout:g} s (--scheduler-timeout): not a "
                    "Dask scheduler, or a hung one"
                ) from None
            if not greeting:
                raise ValidationError(
                    f"--scheduler {address!r}: {host}:{port} closed the connection without a "
                    "Dask handshake: not a Dask scheduler"
                )
    except OSError as exc:
        why = "no answer" if isinstance(exc, TimeoutError) else exc.strerror or str(exc)
        raise ValidationError(
            f"--scheduler {address!r}: cannot reach a scheduler at {host}:{port} within "
            f"{timeout:g} s ({why})"
        ) from None
    return f"tcp://{host}:{port}"


#: Measures of ``SimulationResult.measures()`` by excitation kind (model reference, section 9): each
#: kind's declared ``measures_kind`` looked up in
#: :data:`~mrsuspension.engine.result.MEASURES_BY_KIND`.
MEASURES: dict[str, tuple[str, ...]] = {
    kind: MEASURES_BY_KIND[cls.measures_kind] for kind, cls in EXCITATIONS.items()
}

_STUDY_KEYS = ("name", "description", "measures", "scenario", "road_peak")
_TOP_LEVEL = ("study", "grid", "cases", *SCENARIO_KEYS)
_SPEC = re.compile(r"^\s*(log|lin)\s*:\s*(\d+)\s*:\s*([^:]+)\s*:\s*([^:]+)\s*$")
#: every corner name a per-corner field may name (half and full car)
_CORNERS: tuple[str, ...] = (*FULL_CAR_CORNERS, *HALF_CAR_CORNERS)
#: sections with per-corner tables: ``damper.front_left.hysteresis``
_CORNER_SECTIONS = ("damper", "controller")


#: every dotted field a grid may vary (``section.key``, or ``section.corner.key`` for the
#: per-corner ``[damper.<corner>]``/``[controller.<corner>]`` tables of a half or full car)
def study_fields() -> tuple[str, ...]:
    """Every dotted field a grid may vary, read live (a registered vehicle model's keys
    included): :data:`FIELDS` as of now."""
    return tuple(f"{s}.{k}" for s, keys in SCENARIO_KEYS.items() for k in keys) + tuple(
        f"{s}.{c}.{k}" for s in _CORNER_SECTIONS for c in _CORNERS for k in SCENARIO_KEYS[s]
    )


FIELDS: tuple[str, ...] = study_fields()


def expand_frequencies(value: Any, where: str = "frequencies") -> Any:
    """Expand a ``"log:N:f_min:f_max"`` / ``"lin:N:f_min:f_max"`` spec; other values unchanged.

    Examples
    --------
    >>> expand_frequencies("log:3:1:100")
    [1.0, 10.0, 100.0]
    >>> expand_frequencies("lin:3:1:2")
    [1.0, 1.5, 2.0]
    >>> expand_frequencies([1.0, 2.0])
    [1.0, 2.0]
    """
    if not isinstance(value, str):
        return value
    m = _SPEC.match(value)
    if not m:
        raise ValidationError(
            f"{where}: {value!r} is not a frequency spec; use 'log:N:f_min:f_max' or "
            "'lin:N:f_min:f_max' (e.g. 'log:12:0.5:15') or a list of numbers"
        )
    kind, n, lo_text, hi_text = m.groups()
    try:
        lo, hi = float(lo_text), float(hi_text)
    except ValueError:
        raise ValidationError(f"{where}: bounds of {value!r} must be numbers") from None
    count = int(n) if len(n) <= 12 else MAX_FREQUENCIES + 1  # int() of 5000 digits raises
    if count < 1:
        raise ValidationError(f"{where}: {value!r} needs at least one point")
    if count > MAX_FREQUENCIES:
        shown = n if len(n) <= 24 else f"{n[:12]}...({len(n)} digits)"
        raise ValidationError(
            f"{where}: N = {shown} points are more than the {MAX_FREQUENCIES} a frequency list "
            "may hold (one steady-state run per frequency)"
        )
    if kind == "log":
        values = log_frequencies(count, lo, hi)
    else:
        if not 0.0 < lo <= hi:
            raise ValidationError(f"{where}: {value!r} needs 0 < f_min <= f_max")
        values = np.linspace(lo, hi, count)
    return [round(float(v), 12) for v in values]


def merge_scenario_tables(
    base: dict[str, dict[str, Any]], data: Mapping[str, Any]
) -> dict[str, dict[str, Any]]:
    """Merge the scenario tables of ``data`` (``[vehicle]``, ``[damper]``, ...) into ``base``.

    Shared by studies and optimisation problems, whose files carry a base scenario's
    tables beside their own. Each table present is deep-copied and updates the same
    section of ``base`` key by key.

    Parameters
    ----------
    base : dict
        Section -> table; updated in place.
    data : mapping
        The file's tables; those not in ``SCENARIO_KEYS`` are ignored.

    Returns
    -------
    dict
        ``base``.

    Raises
    ------
    ValidationError
        A scenario section that is not a table.

    Examples
    --------
    >>> merge_scenario_tables({"vehicle": {"sprung_mass": 422.0}}, {"vehicle": {"tire_damping": 0.0}})
    {'vehicle': {'sprung_mass': 422.0, 'tire_damping': 0.0}}
    >>> merge_scenario_tables({}, {"damper": 3})
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: [damper] must be a table; got 3
    """
    for section in SCENARIO_KEYS:
        table = data.get(section)
        if table is None:
            continue
        if not isinstance(table, Mapping):
            raise ValidationError(f"[{section}] must be a table; got {table!r}")
        base.setdefault(section, {}).update(copy.deepcopy(dict(table)))
    return base


@dataclass(frozen=True)
class Axis:
    """One dimension of a study: a field (``[grid]``) or labelled cases (``[cases]``).

    Parameters
    ----------
    name : str
        Dimension name (``"vehicle.sprung_mass"`` or the case table's name).
    labels : tuple
        Coordinate values (the field values, or the case names).
    patches : tuple of dict
        For each label, the dotted fields it sets.
    """

    name: str
    labels: tuple[Any, ...]
    patches: tuple[dict[str, Any], ...]


def _check_field(name: object, where: str) -> str:
    fields = study_fields()
    if not isinstance(name, str) or name not in fields:
        raise ValidationError(
            f"{where} unknown field {name!r}.{did_you_mean(str(name), fields)} "
            "Fields are 'section.key' with a section of vehicle, damper, controller, "
            "excitation, simulation and a key of that section, or 'damper.<corner>.key' / "
            "'controller.<corner>.key' for one corner of a half or full car "
            f"(see {doc('scenarios')})."
        )
    return name


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """``{"controller": {"law": x}}`` or ``{"controller.law": x}`` -> ``{"controller.law": x}``."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        name = f"{prefix}{key}"
        corner_table = prefix[:-1] in _CORNER_SECTIONS and key in _CORNERS
        if isinstance(value, Mapping) and (name in SCENARIO_KEYS or corner_table):
            out.update(_flatten(value, f"{name}."))
        else:
            out[name] = value
    return out


def _label(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def _grid_axis(name: str, values: Any) -> Axis:
    where = f"[grid] {name}:"
    _check_field(name, "[grid]")
    if name == "excitation.frequencies":
        raise ValidationError(
            f"{where} a swept excitation's frequencies are set in [excitation] frequencies "
            "(they become the 'frequency' dimension), not varied in [grid]"
        )
    if name == "excitation.frequency":
        values = expand_frequencies(values, f"[grid] {name}")
    if not isinstance(values, list):
        raise ValidationError(f"{where} must be a list of values; got {values!r}")
    if not values:
        raise ValidationError(f"{where} empty list: give at least one value")
    seen: set[str] = set()
    for v in values:
        if isinstance(v, list | dict):
            raise ValidationError(f"{where} values must be numbers, strings or booleans; got {v!r}")
        key = json.dumps(v)
        if key in seen:
            raise ValidationError(f"{where} value {v!r} is given twice")
        seen.add(key)
    return Axis(name, tuple(values), tuple({name: v} for v in values))


def _case_axis(name: str, cases: Any) -> Axis:
    where = f"[cases.{name}]"
    if name in study_fields() or name == "frequency":
        raise ValidationError(f"{where}: the name {name!r} is taken; choose another case name")
    if not isinstance(cases, Mapping):
        raise ValidationError(f"{where} must be a table of cases; got {cases!r}")
    if not cases:
        raise ValidationError(f"{where} is empty: give at least one case")
    patches = []
    for label, patch in cases.items():
        if not isinstance(patch, Mapping) or not patch:
            raise ValidationError(
                f"{where} {label}: a case is a non-empty table of fields, e.g. "
                '{controller = {law = "skyhook-hilo", gain = 3.0}}; '
                f"got {patch!r}"
            )
        flat = _flatten(patch)
        for key in flat:
            _check_field(key, f"{where} {label}:")
        patches.append(flat)
    return Axis(name, tuple(str(k) for k in cases), tuple(patches))


def _merge(base: dict[str, dict[str, Any]], patch: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    out = copy.deepcopy(base)
    for dotted, value in patch.items():
        section, key = dotted.split(".", 1)
        table = out.setdefault(section, {})
        if "." in key:  # a per-corner field: damper.front_left.hysteresis
            corner, key = key.split(".", 1)
            table = table.setdefault(corner, {})
        table[key] = value
    return out


def scenario_measures(scenario: Scenario) -> tuple[str, ...]:
    """The measures a scenario's runs report (a half or full car: body and per corner).

    Examples
    --------
    >>> s = Scenario.from_dict({"vehicle": {"model": "half-car"},
    ...                         "excitation": {"kind": "bump", "side": "left",
    ...                                        "height": 0.02, "length": 0.5}})
    >>> scenario_measures(s)[:4]
    ('heave_ddot_rms', 'pitch_ddot_rms', 'DLC.front', 'rms_body_acceleration.front')
    """
    return scenario.measure_names()


def _check_run_count(axes: list[Axis], excitation: Mapping[str, Any]) -> int:
    """The number of grid points; refuses a study of more than :data:`MAX_RUNS` runs
    before any is built (with the time that building them alone would take)."""
    points = math.prod(len(a.labels) for a in axes)
    freqs = excitation.get("frequencies") if excitation.get("kind") == "swept" else None
    if excitation.get("kind") == "swept" and freqs is None:
        freqs = [0.0] * DEFAULT_SWEEP_POINTS  # the sweep's default frequencies
    per_point = len(freqs) if isinstance(freqs, list) else 1
    runs = points * per_point
    if runs > MAX_RUNS:
        sizes = " x ".join(str(len(a.labels)) for a in axes) or "1"
        sweep = f" x {per_point} frequencies" if per_point > 1 else ""
        minutes = points * _BUILD_SECONDS / 60.0
        raise ValidationError(
            f"a study of {runs} runs (grid {sizes}{sweep}) is more than the {MAX_RUNS} runs "
            f"a study may have: checking its grid points alone would take about "
            f"{minutes:.3g} min before the first run; split it into several studies or "
            "use coarser grids"
        )
    return points


def _relative_inputs(files: Mapping[str, str], base: Path) -> tuple[tuple[str, str], ...]:
    """``(path, digest)`` of the files read, sorted; paths inside ``base`` made relative
    (a study moved with its files keeps its cache key)."""
    root = base.resolve()
    out = []
    for name, digest in files.items():
        path = Path(name)
        rel = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.as_posix()
        out.append((rel, digest))
    return tuple(sorted(out))


def _check_duration(scenario: Scenario) -> None:
    """A harmonic run's measures need the steady-state rule's time (model reference, section 9)."""
    if scenario.duration is None:
        return
    for exc in scenario.excitations:
        need = getattr(exc, "measure_window", None)
        harmonic = getattr(exc, "name", None) == "harmonic"
        if harmonic and need is not None and scenario.duration < need()[1]:
            raise ValidationError(
                f"[simulation] duration = {scenario.duration:g} s is too short for the "
                f"harmonic measures at {getattr(exc, 'frequency', 0.0):g} Hz: the steady-state rule needs "
                f"{need()[1]:.4g} s (leave duration out to use each run's own)"
            )


@dataclass(frozen=True)
class Study:
    """A validated study: a base scenario, its axes, the measures, and every grid point.

    Build it with :meth:`load` (a TOML file) or :meth:`from_dict`; every grid point's
    scenario is built (and so validated) on construction.

    Parameters
    ----------
    name : str
        Study name (file stem by default).
    base : dict
        The base scenario's tables.
    axes : tuple of Axis
        The dimensions, in order (``[grid]`` fields, then ``[cases]``).
    measures : tuple of str
        Measures kept in the results.
    scenarios : tuple of Scenario
        One scenario per grid point, in C order of ``axes``.
    frequencies : tuple of float or None
        The sweep frequencies [Hz] when the excitation is swept (a ``frequency``
        dimension), else None.
    description : str
        Free text.
    base_dir : Path
        Folder for relative paths.
    road_peak : {"after-onset", "onset"}
        The road acceleration peak dividing ``SAR_s`` and ``SAR_u`` of pulse runs
        (``[study] road_peak``; see :meth:`SimulationResult.measures
        <mrsuspension.engine.result.SimulationResult.measures>`).
    inputs : tuple of (str, str)
        Every file read to build the study, as ``(path, sha256 of its content)``, sorted;
        paths relative to ``base_dir`` when inside it. Part of :meth:`canonical`, hence of
        the cache key: a changed file misses the cache whatever table names it.
    """

    name: str
    base: dict[str, dict[str, Any]]
    axes: tuple[Axis, ...]
    measures: tuple[str, ...]
    scenarios: tuple[Scenario, ...] = field(repr=False)
    frequencies: tuple[float, ...] | None = None
    description: str = ""
    base_dir: Path = field(default_factory=Path.cwd)
    road_peak: RoadPeak = DEFAULT_ROAD_PEAK
    inputs: tuple[tuple[str, str], ...] = ()

    # -- loading ------------------------------------------------------------------------
    @classmethod
    def load(cls, path: str | Path, *, progress: bool | Callable[..., None] = False) -> Study:
        """Read and validate a study TOML file (relative paths from its folder).

        ``progress`` as in :meth:`from_dict`.
        """
        path = Path(path)
        data = read_toml(path, "study")
        data.setdefault("study", {}).setdefault("name", path.stem)
        return cls.from_dict(data, base_dir=path.resolve().parent, progress=progress)

    @classmethod
    def from_dict(
        cls,
        data: Mapping[str, Any],
        base_dir: str | Path | None = None,
        *,
        progress: bool | Callable[..., None] = False,
    ) -> Study:
        """Validate plain tables (as read from TOML) and build every grid point.

        A study of more than :data:`MAX_RUNS` runs is refused before any grid point is
        built. ``progress``: True shows the building of more than
        :data:`PROGRESS_POINTS` grid points (:func:`~mrsuspension._progress.progress_bar`
        on stderr, with the time left); a callable gets ``(done, total)``.

        Every file read while building (an included ``[study] scenario``, parameter
        files of any ``[damper]`` or ``[damper.<corner>]`` table, road profiles, OpenCRG
        files, ...) is recorded with its content digest in :attr:`inputs`.

        Raises
        ------
        ValidationError
            Unknown tables, fields or measures (with a did-you-mean), empty grids or
            cases, too many runs (:data:`MAX_RUNS`), and any grid point whose scenario
            fails its own checks (the message names the point).
        """
        from mrsuspension._inputs import recording

        base_path = Path.cwd() if base_dir is None else Path(base_dir)
        with recording() as files:
            study = cls._build(data, base_path, progress)
        return dataclasses.replace(study, inputs=_relative_inputs(files, base_path))

    @classmethod
    def _build(
        cls, data: Mapping[str, Any], base_path: Path, progress: bool | Callable[..., None]
    ) -> Study:
        """:meth:`from_dict` without the record of the files read."""
        check_tables("a study", data, _TOP_LEVEL)
        meta = check_keys("[study]", data.get("study", {}), _STUDY_KEYS)
        base: dict[str, dict[str, Any]] = {}
        if "scenario" in meta:
            spath = Path(str(meta["scenario"]))
            spath = spath if spath.is_absolute() else base_path / spath
            if not spath.is_file():
                raise ValidationError(f"[study] scenario: file not found: {str(spath)!r}")
            base = copy.deepcopy(Scenario.load(spath).data)
            base = {k: v for k, v in base.items() if v}
        merge_scenario_tables(base, data)
        exc = base.get("excitation", {})
        if "frequencies" in exc:
            exc["frequencies"] = expand_frequencies(exc["frequencies"], "[excitation] frequencies")

        grid = data.get("grid", {})
        if not isinstance(grid, Mapping):
            raise ValidationError(f"[grid] must be a table of fields; got {grid!r}")
        cases = data.get("cases", {})
        if not isinstance(cases, Mapping):
            raise ValidationError(f"[cases] must hold tables [cases.NAME]; got {cases!r}")
        axes = [_grid_axis(str(k), v) for k, v in _flatten(grid).items()]
        axes += [_case_axis(str(k), v) for k, v in cases.items()]
        names = [a.name for a in axes]
        for a in axes:
            if names.count(a.name) > 1:
                raise ValidationError(f"dimension {a.name!r} is given twice")
        from mrsuspension.studies.units import dimension_name

        fields = {dimension_name(a.name): a.name for a in axes if "." in a.name}
        for a in axes:  # the results name a field's dimension controller_gain, add corner
            if "." not in a.name and (a.name in fields or a.name == "corner"):
                field = f" (the dimension of {fields[a.name]})" if a.name in fields else ""
                raise ValidationError(
                    f"[cases.{a.name}]: the name {a.name!r} is taken{field}; choose another "
                    "case name"
                )

        points = _check_run_count(axes, exc)
        name = str(meta.get("name", "study"))
        # every grid point, validated before anything runs
        scenarios = []
        shown = progress if callable(progress) else progress and points > PROGRESS_POINTS
        with progress_bar(shown, f"study {name}: checking {points} grid points") as tick:
            for combo in itertools.product(*(range(len(a.labels)) for a in axes)):
                patch: dict[str, Any] = {}
                for a, k in zip(axes, combo, strict=True):
                    patch.update(a.patches[k])
                try:
                    scenarios.append(Scenario.from_dict(_merge(base, patch), base_dir=base_path))
                except ValidationError as err:
                    point = ", ".join(
                        f"{a.name}={_label(a.labels[k])}" for a, k in zip(axes, combo, strict=True)
                    )
                    at = f" at grid point {point}" if point else ""
                    raise ValidationError(f"study{at}: {err}") from None
                if tick is not None:
                    tick(len(scenarios), points)
        for s in scenarios:
            _check_duration(s)
        runs = sum(len(s.excitations) for s in scenarios)
        if runs > MAX_RUNS:  # a case that changes the sweep: counted once built
            raise ValidationError(
                f"a study of {runs} runs is more than the {MAX_RUNS} runs a study may have; "
                "split it into several studies or use coarser grids"
            )
        kinds = {s.data["excitation"]["kind"] for s in scenarios}
        sweeps = {s.excitation.frequencies for s in scenarios if s.is_sweep}  # type: ignore[union-attr]
        if sweeps and len(kinds) > 1:
            raise ValidationError(
                f"a study cannot mix swept and other excitation kinds: {', '.join(sorted(kinds))}"
            )
        if len(sweeps) > 1:
            raise ValidationError("every grid point of a swept study must use the same frequencies")
        frequencies = next(iter(sweeps)) if sweeps else None

        available = tuple(dict.fromkeys(m for s in scenarios for m in scenario_measures(s)))
        on_request = tuple(dict.fromkeys(m for s in scenarios for m in s.plant.on_request))
        valid = sorted({*available, *on_request})
        requested = meta.get("measures")
        if requested is None:
            measures = tuple(m for m in dict.fromkeys(available) if m in valid)
        else:
            if isinstance(requested, str):
                requested = [requested]
            if not isinstance(requested, list) or not requested:
                raise ValidationError(
                    f"[study] measures must be a non-empty list of names; got {requested!r}"
                )
            for m in requested:
                if m not in valid:
                    raise ValidationError(
                        f"[study] measures: {m!r} is not a measure of "
                        f"{'/'.join(sorted(kinds))} runs.{did_you_mean(str(m), valid)} "
                        f"Valid: {', '.join(valid)}."
                    )
            measures = tuple(dict.fromkeys(requested))
        try:
            road_peak = check_road_peak(meta.get("road_peak", DEFAULT_ROAD_PEAK))
        except ValidationError as err:
            raise ValidationError(f"[study] {err}") from None
        return cls(
            name=name,
            base=base,
            axes=tuple(axes),
            measures=measures,
            scenarios=tuple(scenarios),
            frequencies=frequencies,
            description=str(meta.get("description", "")),
            base_dir=base_path,
            road_peak=road_peak,
        )

    # -- shape --------------------------------------------------------------------------
    @property
    def has_pulses(self) -> bool:
        """True when some grid point runs a rounded pulse (``road_peak`` applies)."""
        return any(s.data["excitation"]["kind"] == "pulse" for s in self.scenarios)

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimension names of the results (axes, then ``frequency`` for a sweep)."""
        names = tuple(a.name for a in self.axes)
        return names + (("frequency",) if self.frequencies is not None else ())

    @property
    def shape(self) -> tuple[int, ...]:
        """Result shape, one length per dimension."""
        lengths = tuple(len(a.labels) for a in self.axes)
        return lengths + ((len(self.frequencies),) if self.frequencies is not None else ())

    @property
    def coords(self) -> dict[str, list[Any]]:
        """Coordinate values of each dimension."""
        out: dict[str, list[Any]] = {a.name: list(a.labels) for a in self.axes}
        if self.frequencies is not None:
            out["frequency"] = list(self.frequencies)
        return out

    def simulations(self) -> list[Any]:
        """Every run, in C order of :attr:`dims` (grid points, then frequencies)."""
        return [run for s in self.scenarios for run in s.runs()]

    def run_settings(self) -> list[RunSettings]:
        """The :class:`RunSettings` of every run (its grid point's ``[simulation]``),
        aligned with :meth:`simulations`."""
        return [s.settings for s in self.scenarios for _ in s.excitations]

    # -- identity -----------------------------------------------------------------------
    def canonical(self) -> dict[str, Any]:
        """Plain data that fixes the results: every expanded scenario, axes and measures.

        Every file read to build it (:attr:`inputs`: parameter files of any table, road
        profiles, OpenCRG files, an included scenario) is included by content digest, as
        read when the study was built: the results are those of that content.
        """
        out: dict[str, Any] = {
            "dims": list(self.dims),
            "coords": {k: [_label(v) for v in vs] for k, vs in self.coords.items()},
            "measures": list(self.measures),
            "points": [{"scenario": s.to_dict()} for s in self.scenarios],
            "inputs": [list(item) for item in self.inputs],
        }
        if self.has_pulses:  # the SAR denominators: results cached before it was a choice differ
            out["road_peak"] = self.road_peak
        return out

    def content_hash(self) -> str:
        """sha256 of the canonical JSON of :meth:`canonical` and the package version."""
        from mrsuspension import __version__

        text = json.dumps(
            {"study": self.canonical(), "version": __version__},
            sort_keys=True,
            separators=(",", ":"),
            default=str,
        )
        return hashlib.sha256(text.encode()).hexdigest()

    def describe(self) -> dict[str, Any]:
        """Plain data: name, description, base tables, dims, coords, measures."""
        return {
            "name": self.name,
            "description": self.description,
            "base": self.base,
            "dims": list(self.dims),
            "coords": self.coords,
            "cases": {
                a.name: dict(zip(a.labels, a.patches, strict=True))
                for a in self.axes
                if not (len(a.patches[0]) == 1 and a.name in a.patches[0])
            },
            "measures": list(self.measures),
            **({"road_peak": self.road_peak} if self.has_pulses else {}),
            "runs": len(self.run_settings()),
        }

    def __len__(self) -> int:
        return len(self.run_settings())
