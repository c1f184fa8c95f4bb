"""Published and user parameter sets, stored as data with their provenance.

Every published set lives in one TOML file under ``parameters/data`` with its source,
table, units and a description of every key, and is registered by its name::

    >>> from mrsuspension import parameters
    >>> sorted(parameters.available())[:3]
    ['bingham-wang-low', 'linear-2500', 'spencer-1997']
    >>> p = parameters.get("wang-symmetric-low")
    >>> p["F0"], p.units["F0"], p.table
    (68.506, 'N', '2.2')

Users load their own sets from TOML or JSON files with :func:`load` (or pass the path
wherever a set name is accepted); :meth:`ParameterSet.save` writes the same format.
"""

from __future__ import annotations

import json
import math
import tomllib
from collections.abc import ItemsView, Iterator, KeysView, Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from types import MappingProxyType
from typing import Any

from mrsuspension.errors import ValidationError, unknown_name

__all__ = [
    "MAX_MAGNITUDE",
    "ParameterSet",
    "available",
    "check_magnitudes",
    "get",
    "load",
    "resolve",
]

#: Largest |value| accepted for a parameter a user gives (SI units). Five orders of
#: magnitude above the largest registered value (spencer-1997's gamma, 3.63e6 1/m^2), so
#: only a slip (a wrong unit prefix, an exponent typo, 1e308) is refused.
MAX_MAGNITUDE = 1e12


def check_magnitudes(values: Mapping[str, float], units: Mapping[str, str], origin: str) -> None:
    """Refuse a parameter whose magnitude no physical damper parameter has.

    Parameters
    ----------
    values : mapping of str to float
        The parameters (SI units).
    units : mapping of str to str
        Their units, named in the message.
    origin : str
        Where the values come from (a file name, ``"parameter set 'mine'"``).

    Raises
    ------
    ValidationError
        Naming the parameter, the value, its unit and the accepted magnitude.

    Examples
    --------
    >>> check_magnitudes({"c": 1800.0}, {"c": "N s/m"}, "mine.toml")
    >>> check_magnitudes({"F0": 1e308}, {"F0": "N"}, "mine.toml")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: mine.toml: parameter 'F0' = 1e+308 N is beyond any physical damper parameter (|value| <= 1e+12 in SI units); check the value and its unit
    """
    for key, value in values.items():
        if abs(value) > MAX_MAGNITUDE:
            unit = f" {units[key]}" if units.get(key) not in (None, "", "1") else ""
            raise ValidationError(
                f"{origin}: parameter {key!r} = {value:g}{unit} is beyond any physical damper "
                f"parameter (|value| <= {MAX_MAGNITUDE:g} in SI units); check the value and "
                "its unit"
            )


@dataclass(frozen=True)
class ParameterSet:
    """A named, immutable set of model parameters with provenance.

    Parameters
    ----------
    name : str
        Registry name, e.g. ``"wang-symmetric-low"``.
    model : str
        Damper model family the set belongs to (``"wang-symmetric"``, ``"spencer"``...).
    values : mapping of str to float
        Parameter values in SI units.
    units : mapping of str to str, optional
        Unit of every key (``"1"`` for dimensionless).
    descriptions : mapping of str to str, optional
        One line per key saying what it is and which equation uses it.
    source : str
        Where the numbers come from (publication, table, or a fit).
    table : str
        Table number in the source, or ``"-"``.
    description : str
        Free text about the set.
    frequency_range : tuple of float, optional
        Excitation frequency range [Hz] over which the set was identified.
    max_current : float
        Highest drive current [A] the damper accepts (default 0.5 A, the damper's limit).
    velocity_range : tuple of float, optional
        Peak piston velocities ``v_m`` [m/s] covered by the tests the set was identified
        from. Models that extrapolate badly in ``v_m`` (the dissertation's, through
        ``exp(a1 v_m)``) clamp their peak-velocity estimate to its upper end.

    Examples
    --------
    >>> p = ParameterSet(name="mine", model="linear", values={"c": 1800.0})
    >>> p["c"]
    1800.0
    >>> p.replace(c=2000.0)["c"]
    2000.0
    """

    name: str
    model: str
    values: Mapping[str, float]
    units: Mapping[str, str] = field(default_factory=dict)
    descriptions: Mapping[str, str] = field(default_factory=dict)
    source: str = "user"
    table: str = "-"
    description: str = ""
    frequency_range: tuple[float, float] | None = None
    max_current: float = 0.5
    velocity_range: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ValidationError(
                f"parameter set name must be a non-empty string; got {self.name!r}"
            )
        if not isinstance(self.model, str) or not self.model:
            raise ValidationError(
                f"parameter set {self.name!r}: 'model' must be a non-empty string; got {self.model!r}"
            )
        clean: dict[str, float] = {}
        for key, value in dict(self.values).items():
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValidationError(
                    f"parameter set {self.name!r}: parameter {key!r} must be a number; got {value!r}"
                )
            if not math.isfinite(value):
                raise ValidationError(
                    f"parameter set {self.name!r}: parameter {key!r} must be finite; got {value!r}"
                )
            clean[str(key)] = float(value)
        if not clean:
            raise ValidationError(f"parameter set {self.name!r} has no parameters")
        if not (isinstance(self.max_current, int | float) and 0 < self.max_current <= 10):
            raise ValidationError(
                f"parameter set {self.name!r}: max_current must be in (0, 10] A; "
                f"got {self.max_current!r}"
            )
        if self.velocity_range is not None:
            vr = self.velocity_range
            if (
                not isinstance(vr, list | tuple)
                or len(vr) != 2
                or not all(isinstance(v, int | float) and math.isfinite(v) for v in vr)
                or not 0 < vr[0] < vr[1]
            ):
                raise ValidationError(
                    f"parameter set {self.name!r}: velocity_range must be [low, high] in m/s "
                    f"with 0 < low < high; got {vr!r}"
                )
            object.__setattr__(self, "velocity_range", (float(vr[0]), float(vr[1])))
        object.__setattr__(self, "values", MappingProxyType(clean))
        object.__setattr__(self, "units", MappingProxyType(dict(self.units)))
        object.__setattr__(self, "descriptions", MappingProxyType(dict(self.descriptions)))

    # read-only mapping interface (``values`` is the field holding the numbers) -------
    def __getitem__(self, key: str) -> float:
        try:
            return self.values[key]
        except KeyError:
            raise unknown_name(f"parameter of set {self.name!r}", key, self.values) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self.values)

    def __len__(self) -> int:
        return len(self.values)

    def __contains__(self, key: object) -> bool:
        return key in self.values

    def keys(self) -> KeysView[str]:
        """Parameter names."""
        return self.values.keys()

    def items(self) -> ItemsView[str, float]:
        """(name, value) pairs."""
        return self.values.items()

    def __repr__(self) -> str:
        return f"ParameterSet(name={self.name!r}, model={self.model!r}, {len(self)} parameters)"

    def __reduce__(self) -> tuple[Any, ...]:
        # mapping proxies do not pickle; rebuild from plain dicts (process pools need this)
        return (
            ParameterSet,
            (
                self.name, self.model, dict(self.values), dict(self.units),
                dict(self.descriptions), self.source, self.table, self.description,
                self.frequency_range, self.max_current, self.velocity_range,
            ),
        )  # fmt: skip

    def replace(self, **values: float) -> ParameterSet:
        """Return a copy with some values changed (provenance says so)."""
        for key in values:
            if key not in self.values:
                raise unknown_name(f"parameter of set {self.name!r}", key, self.values)
        check_magnitudes(
            {k: v for k, v in values.items() if isinstance(v, int | float)},
            self.units,
            f"parameter set {self.name!r}",
        )
        new = {**self.values, **values}
        changed = ", ".join(f"{k}={v:g}" for k, v in values.items())
        return ParameterSet(
            name=f"{self.name} (modified)",
            model=self.model,
            values=new,
            units=self.units,
            descriptions=self.descriptions,
            source=f"{self.source}; modified by the user: {changed}",
            table=self.table,
            description=self.description,
            frequency_range=self.frequency_range,
            max_current=self.max_current,
            velocity_range=self.velocity_range,
        )

    def to_dict(self) -> dict[str, Any]:
        """The set as plain data, in the layout of the TOML/JSON files."""
        out: dict[str, Any] = {
            "name": self.name,
            "model": self.model,
            "source": self.source,
            "table": self.table,
            "description": self.description,
            "max_current": self.max_current,
        }
        if self.frequency_range is not None:
            out["frequency_range"] = list(self.frequency_range)
        if self.velocity_range is not None:
            out["velocity_range"] = list(self.velocity_range)
        out["parameters"] = {
            k: {
                "value": v,
                "unit": self.units.get(k, ""),
                "description": self.descriptions.get(k, ""),
            }
            for k, v in self.values.items()
        }
        return out

    def save(self, path: str | Path) -> Path:
        """Write the set to ``path`` as TOML (``.toml``) or JSON (``.json``)."""
        path = Path(path)
        data = self.to_dict()
        if path.suffix.lower() == ".json":
            path.write_text(json.dumps(data, indent=2) + "\n")
        elif path.suffix.lower() == ".toml":
            import tomli_w

            path.write_text(tomli_w.dumps(data))
        else:
            raise ValidationError(
                f"cannot save a parameter set as {path.suffix!r}; use a .toml or .json file name"
            )
        return path


def _from_mapping(data: Mapping[str, Any], origin: str) -> ParameterSet:
    if not isinstance(data, Mapping):
        raise ValidationError(f"{origin}: expected a table of keys at the top level")
    allowed = {
        "name", "model", "source", "table", "description", "frequency_range",
        "max_current", "velocity_range", "parameters",
    }  # fmt: skip
    unknown = set(data) - allowed
    if unknown:
        key = sorted(unknown)[0]
        raise unknown_name(f"top-level key in {origin}:", key, allowed)
    for required in ("model", "parameters"):
        if required not in data:
            raise ValidationError(f"{origin}: missing required key {required!r}")
    raw = data["parameters"]
    if not isinstance(raw, Mapping) or not raw:
        raise ValidationError(
            f"{origin}: 'parameters' must be a non-empty table of name = value "
            "or name = {{ value = ..., unit = ... }}"
        )
    values: dict[str, float] = {}
    units: dict[str, str] = {}
    descriptions: dict[str, str] = {}
    for key, entry in raw.items():
        if isinstance(entry, Mapping):
            if "value" not in entry:
                raise ValidationError(f"{origin}: parameter {key!r} has no 'value'")
            values[key] = entry["value"]
            units[key] = str(entry.get("unit", ""))
            descriptions[key] = str(entry.get("description", ""))
        else:
            values[key] = entry
    frange = data.get("frequency_range")
    if frange is not None:
        if (
            not isinstance(frange, list | tuple)
            or len(frange) != 2
            or not all(isinstance(f, int | float) for f in frange)
            or not 0 <= frange[0] <= frange[1]
        ):
            raise ValidationError(
                f"{origin}: frequency_range must be [low, high] in Hz with 0 <= low <= high; "
                f"got {frange!r}"
            )
        frange = (float(frange[0]), float(frange[1]))
    try:
        pset = ParameterSet(
            name=str(data.get("name", Path(origin).stem)),
            model=data["model"],
            values=values,
            units=units,
            descriptions=descriptions,
            source=str(data.get("source", f"user file {origin}")),
            table=str(data.get("table", "-")),
            description=str(data.get("description", "")),
            frequency_range=frange,
            max_current=data.get("max_current", 0.5),
            velocity_range=data.get("velocity_range"),
        )
    except ValidationError as exc:
        raise ValidationError(f"{origin}: {exc}") from None
    check_magnitudes(pset.values, pset.units, origin)
    return pset


def load(path: str | Path) -> ParameterSet:
    """Load a parameter set from a TOML or JSON file.

    The file holds ``model`` and a ``parameters`` table (``name = value`` or
    ``name = { value = ..., unit = "...", description = "..." }``), and optionally
    ``name``, ``source``, ``table``, ``description``, ``frequency_range``, ``max_current``,
    ``velocity_range``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "my-damper.toml"
    >>> _ = f.write_text('model = "linear"\\n[parameters]\\nc = 1500.0\\n')
    >>> load(f)
    ParameterSet(name='my-damper', model='linear', 1 parameters)
    """
    from mrsuspension._inputs import parse_json, parse_toml, read_text

    path = Path(path)
    if not _is_file(str(path)):
        raise ValidationError(f"parameter file {str(path)!r} does not exist")
    suffix = path.suffix.lower()
    if suffix not in (".toml", ".json"):
        raise ValidationError(
            f"parameter file {str(path)!r}: unsupported extension {suffix!r}; use .toml or .json"
        )
    text = read_text(path, "parameter file")  # recorded: a study's cache key holds it
    what = f"parameter file {str(path)!r}"
    data = parse_toml(text, what) if suffix == ".toml" else parse_json(text, what)
    return _from_mapping(data, str(path))


def _registry() -> dict[str, resources.abc.Traversable]:
    folder = resources.files("mrsuspension.parameters") / "data"
    return {
        entry.name.removesuffix(".toml"): entry
        for entry in folder.iterdir()
        if entry.name.endswith(".toml")
    }


def available() -> list[str]:
    """Names of the published (registered) parameter sets."""
    return sorted(_registry())


def get(name: str) -> ParameterSet:
    """Return a registered parameter set by name.

    Examples
    --------
    >>> get("wang-symetric-low")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown parameter set 'wang-symetric-low'. Did you mean 'wang-symmetric-low'? Valid: ...
    """
    reg = _registry()
    if name not in reg:
        raise unknown_name("parameter set", name, reg)
    return _from_mapping(tomllib.loads(reg[name].read_text()), f"{name}.toml")


def resolve(spec: str | Path | ParameterSet | Mapping[str, float], model: str) -> ParameterSet:
    """Turn a set name, a file path, a set or a plain dict into a :class:`ParameterSet`.

    Names are looked up in the registry first; anything ending in ``.toml``/``.json`` or
    naming an existing file is loaded from disk. A plain mapping becomes a user set of
    the given ``model``.
    """
    if isinstance(spec, ParameterSet):
        return spec
    if isinstance(spec, Mapping):
        pset = ParameterSet(name="user", model=model, values=dict(spec))
        check_magnitudes(pset.values, pset.units, "parameter set 'user'")
        return pset
    text = str(spec)
    if isinstance(spec, Path) or text.lower().endswith((".toml", ".json")) or _is_file(text):
        return load(text)
    return get(text)


def _is_file(text: str) -> bool:
    """``Path(text).is_file()``, False for a text no file can have (too long, NUL)."""
    try:
        return Path(text).is_file()
    except (OSError, ValueError):
        return False
