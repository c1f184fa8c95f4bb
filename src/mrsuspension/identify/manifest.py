"""The manifest of a test campaign: which files, at which current (and excitation).

Three forms are accepted (model reference, section 10: "one file or folder per test"):

CSV
    A header with ``file`` and ``current`` and optionally ``frequency``, ``amplitude``,
    ``columns`` and ``units``; a unit may follow a name in brackets (``current [mA]``,
    ``amplitude [mm]``; default A, Hz and m). Paths are relative to the manifest. Lines
    starting with ``#`` are comments, except the directives ``# columns = t,x,v,F``,
    ``# units = s,mm,mm/s,N`` and ``# current_pattern = ...``, which apply to every test.
TOML
    Top-level ``columns``, ``units``, ``current_pattern`` and one ``[[test]]`` table per
    test with ``file``, ``current`` (or ``current_mA``), ``frequency``, ``amplitude``
    (or ``amplitude_mm``) and optional per-test ``columns``/``units``.
A folder
    Every data file in it (:data:`~mrsuspension.identify.readers.DATA_SUFFIXES`) is a
    test; the current comes from the file (a current column) or from its name.

A current can be parsed from file names with a regular expression: the named group
``current`` (in A) or ``mA`` (in mA), otherwise the first group, e.g.
``_(?P<current>[0-9.]+)A`` for ``run_0.2A.csv``; a ``p`` stands for the decimal point
(``0p2A``). Named groups ``frequency`` (Hz) and ``amplitude_mm`` are read too.

Precedence: ``--columns``/``--units``/``--current-pattern`` given on the command line
win over the manifest; a current written in the manifest wins over the file's current
column, which wins over the file-name pattern.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> _ = (folder / "tests.csv").write_text("file,current [mA],frequency\\nrun1.csv,200,1.5\\n")
>>> m = read_manifest(folder / "tests.csv")
>>> m.entries[0].label, m.entries[0].current, m.entries[0].frequency
('run1.csv', 0.2, 1.5)
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError, did_you_mean
from mrsuspension.identify.readers import (
    DATA_SUFFIXES,
    ColumnSpec,
    UnitSpec,
    parse_columns,
    parse_units,
    split_name_unit,
)

__all__ = [
    "Manifest",
    "TestEntry",
    "parse_current_pattern",
    "read_manifest",
    "values_from_name",
]

_KEYS = {
    "file": ("file", "path", "filename", "file_name", "name"),
    "current": ("current", "i", "i_d", "drive_current"),
    "frequency": ("frequency", "freq", "f"),
    "amplitude": ("amplitude", "amp", "a_m", "am", "stroke_amplitude"),
    "columns": ("columns",),
    "units": ("units",),
}
_KEY_OF = {alias: key for key, names in _KEYS.items() for alias in names}
_FACTORS = {
    "current": {"a": 1.0, "ma": 1e-3},
    "frequency": {"hz": 1.0},
    "amplitude": {"m": 1.0, "mm": 1e-3, "cm": 1e-2},
}


@dataclass(frozen=True)
class TestEntry:
    """One test of a campaign, as the manifest describes it.

    ``current`` [A], ``frequency`` [Hz] and ``amplitude`` [m] are ``None`` when not
    given. ``error`` holds a problem found in the manifest row itself (the campaign
    reports it for this test); ``notes`` say where values came from.
    """

    file: Path
    label: str
    current: float | None = None
    frequency: float | None = None
    amplitude: float | None = None
    columns: ColumnSpec | None = None
    units: UnitSpec | None = None
    current_source: str = ""
    error: str | None = None
    notes: tuple[str, ...] = ()

    __test__ = False


@dataclass(frozen=True)
class Manifest:
    """The tests of one campaign and the settings shared by all of them."""

    path: Path
    entries: tuple[TestEntry, ...]
    columns: ColumnSpec | None = None
    units: UnitSpec | None = None
    current_pattern: re.Pattern[str] | None = None
    notes: tuple[str, ...] = ()

    def __len__(self) -> int:
        return len(self.entries)


def parse_current_pattern(pattern: str | re.Pattern[str] | None) -> re.Pattern[str] | None:
    """Compile a file-name pattern; it needs a group for the current.

    Examples
    --------
    >>> values_from_name(parse_current_pattern(r"_(?P<mA>\\d+)mA"), "run_250mA.csv")
    {'current': 0.25}
    >>> parse_current_pattern("run[")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --current-pattern 'run[' is not a valid regular expression: ...
    """
    if pattern is None or isinstance(pattern, re.Pattern):
        return pattern
    try:
        compiled = re.compile(pattern)
    except re.error as exc:
        raise ValidationError(
            f"--current-pattern {pattern!r} is not a valid regular expression: {exc}"
        ) from None
    if compiled.groups == 0:
        raise ValidationError(
            f"--current-pattern {pattern!r} has no group for the current; e.g. "
            r"'_(?P<current>[0-9.]+)A' or '_(?P<mA>\d+)mA'"
        )
    return compiled


def _number(text: str) -> float:
    cleaned = text.strip().replace(",", ".").strip(".")
    cleaned = re.sub(r"(?<=\d)[pP](?=\d)", ".", cleaned)
    return float(cleaned)


def values_from_name(pattern: re.Pattern[str] | None, name: str) -> dict[str, float]:
    """Current [A] (and frequency [Hz], amplitude [m]) parsed from a file name.

    Examples
    --------
    >>> values_from_name(parse_current_pattern(r"i(?P<current>[0-9p]+)_f(?P<frequency>[0-9p]+)"),
    ...                  "i0p2_f1p5.csv")
    {'current': 0.2, 'frequency': 1.5}
    """
    if pattern is None:
        return {}
    match = pattern.search(name)
    if match is None:
        return {}
    groups = match.groupdict()
    raw: dict[str, tuple[str, float]] = {}
    if groups.get("current") is not None:
        raw["current"] = (groups["current"], 1.0)
    elif groups.get("mA") is not None:
        raw["current"] = (groups["mA"], 1e-3)
    elif 1 not in pattern.groupindex.values() and match.group(1) is not None:
        raw["current"] = (match.group(1), 1.0)
    if groups.get("frequency") is not None:
        raw["frequency"] = (groups["frequency"], 1.0)
    if groups.get("amplitude_mm") is not None:
        raw["amplitude"] = (groups["amplitude_mm"], 1e-3)
    out: dict[str, float] = {}
    for key, (text, factor) in raw.items():
        try:
            out[key] = _number(text) * factor
        except ValueError:
            continue
    return out


def _header_key(text: str) -> tuple[str | None, float, str]:
    """Manifest column name -> (key, factor to SI, unit text)."""
    name, unit = split_name_unit(text)
    key = _KEY_OF.get(name)
    if key is None:
        return None, 1.0, ""
    if unit is None:
        return key, 1.0, ""
    factors = _FACTORS.get(key, {})
    if unit.lower() not in factors:
        raise ValidationError(
            f"manifest column {text.strip()!r}: unit {unit!r} is not accepted for {key} "
            f"(valid: {', '.join(factors) or 'none'})"
        )
    return key, factors[unit.lower()], unit


def _entry(
    base: Path,
    row: Mapping[str, Any],
    factors: Mapping[str, float],
    where: str,
    columns: ColumnSpec | None,
    units: UnitSpec | None,
    cli_columns: ColumnSpec | None,
    cli_units: UnitSpec | None,
) -> TestEntry:
    label = str(row.get("file") or "").strip()
    if not label:
        return TestEntry(file=base, label=f"({where})", error=f"{where}: no file name")
    values: dict[str, Any] = {}
    problems = []
    for key in ("current", "frequency", "amplitude"):
        raw = row.get(key)
        if raw is None or (isinstance(raw, str) and not raw.strip()):
            continue
        try:
            value = _number(raw) if isinstance(raw, str) else float(raw)
        except (TypeError, ValueError):
            problems.append(f"{key} {raw!r} is not a number")
            continue
        if not math.isfinite(value):
            problems.append(f"{key} {raw!r} is not finite")
            continue
        values[key] = value * factors.get(key, 1.0)
    for key in ("frequency", "amplitude"):
        if key in values and values[key] <= 0:
            problems.append(f"{key} must be > 0; got {values[key]:g}")
    try:
        row_columns = parse_columns(row.get("columns") or None, f"{where}: columns")
        row_units = parse_units(row.get("units") or None, f"{where}: units")
    except ValidationError as exc:
        problems.append(str(exc))
        row_columns = row_units = None
    return TestEntry(
        file=(base / label),
        label=label,
        current=values.get("current"),
        frequency=values.get("frequency"),
        amplitude=values.get("amplitude"),
        columns=cli_columns or row_columns or columns,
        units=cli_units or row_units or units,
        current_source="manifest" if "current" in values else "",
        error=f"{where}: " + "; ".join(problems) if problems else None,
    )


_DIRECTIVE = re.compile(r"^\s*#\s*(columns|units|current_pattern)\s*[=:]\s*(.+?)\s*$")


def _read_csv(
    path: Path,
) -> tuple[list[tuple[str, dict[str, Any]]], dict[str, str], list[str], dict[str, float]]:
    from mrsuspension._inputs import read_bytes

    text = read_bytes(path, "manifest").decode("utf-8", errors="replace")
    directives: dict[str, str] = {}
    kept: list[tuple[int, str]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        m = _DIRECTIVE.match(line)
        if m:
            directives[m.group(1)] = m.group(2)
            continue
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        kept.append((number, line))
    if not kept:
        raise ValidationError(f"manifest {path.name} lists no tests")
    delimiter = "\t" if "\t" in kept[0][1] and "," not in kept[0][1] else ","
    if ";" in kept[0][1] and "," not in kept[0][1]:
        delimiter = ";"
    reader = csv.reader(io.StringIO("\n".join(line for _, line in kept)), delimiter=delimiter)
    rows = list(reader)
    header = rows[0]
    keys: list[str | None] = []
    factors: dict[str, float] = {}
    ignored = []
    for col in header:
        key, factor, _ = _header_key(col)
        if key is not None and key in keys:
            raise ValidationError(f"manifest {path.name}: column {key!r} appears twice")
        keys.append(key)
        if key is None:
            ignored.append(col.strip())
        else:
            factors[key] = factor
    if "file" not in keys:
        raise ValidationError(
            f"manifest {path.name}: the header needs a 'file' column (and 'current'); got "
            f"{', '.join(h.strip() for h in header)}.{did_you_mean(header[0].strip().lower(), _KEY_OF)}"
        )
    notes = [f"manifest columns ignored: {', '.join(ignored)}"] if ignored else []
    out: list[tuple[str, dict[str, Any]]] = []
    for (number, _), row in zip(kept[1:], rows[1:], strict=True):
        if len(row) > len(header):
            out.append((f"line {number}", {"file": row[0] if row else "", "_extra": True}))
            continue
        data = {k: v for k, v in zip(keys, row, strict=False) if k is not None}
        out.append((f"line {number}", data))
    return out, directives, notes, factors


def _read_toml(
    path: Path,
) -> tuple[list[tuple[str, dict[str, Any]]], dict[str, str], list[str], list[dict[str, float]]]:
    from mrsuspension._inputs import parse_toml, read_text

    data = parse_toml(read_text(path, "manifest"), f"manifest {path.name}")
    allowed = {"columns", "units", "current_pattern", "test", "tests", "description", "name"}
    for key in data:
        if key not in allowed:
            raise ValidationError(
                f"manifest {path.name}: unknown top-level key {key!r}.{did_you_mean(key, allowed)} "
                f"Valid: {', '.join(sorted(allowed))}"
            )
    tests = data.get("test", data.get("tests"))
    if not isinstance(tests, list) or not tests:
        raise ValidationError(
            f"manifest {path.name} lists no tests: add one [[test]] table per test with "
            "file = ... and current = ..."
        )
    directives: dict[str, str] = {
        k: str(data[k]) for k in ("columns", "units", "current_pattern") if k in data
    }
    rows = []
    factors = []
    for n, test in enumerate(tests, start=1):
        if not isinstance(test, Mapping):
            raise ValidationError(f"manifest {path.name}: test {n} is not a table")
        row: dict[str, Any] = {}
        fac: dict[str, float] = {}
        for key, value in test.items():
            k, factor, _ = _header_key(key)
            if k is None:
                raise ValidationError(
                    f"manifest {path.name}, test {n}: unknown key {key!r}."
                    f"{did_you_mean(key, _KEY_OF)} Valid: file, current, frequency, amplitude, "
                    "columns, units (with a unit suffix such as current_mA, amplitude_mm)"
                )
            row[k] = value
            fac[k] = factor
        rows.append((f"test {n}", row))
        factors.append(fac)
    return rows, directives, [], factors


def read_manifest(
    path: str | Path,
    *,
    columns: str | ColumnSpec | None = None,
    units: str | UnitSpec | None = None,
    current_pattern: str | re.Pattern[str] | None = None,
) -> Manifest:
    """Read a campaign manifest (CSV, TOML or a folder of test files).

    ``columns``, ``units`` and ``current_pattern`` (e.g. from the command line) override
    the manifest's own settings. Problems with a single row are kept in that entry's
    ``error``; a manifest that cannot be read at all raises :class:`ValidationError`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> for name in ("run_0.1A.csv", "run_0.3A.csv"):
    ...     _ = (folder / name).write_text("t,x,F\\n0,0,0\\n")
    >>> m = read_manifest(folder, current_pattern=r"_(?P<current>[0-9.]+)A")
    >>> [(e.label, e.current) for e in m.entries]
    [('run_0.1A.csv', 0.1), ('run_0.3A.csv', 0.3)]
    """
    path = Path(path)
    cli_columns = parse_columns(columns)
    cli_units = parse_units(units)
    cli_pattern = parse_current_pattern(current_pattern)
    if path.is_dir():
        files = sorted(
            p for p in path.iterdir()
            if p.is_file() and p.suffix.lower() in DATA_SUFFIXES
            and not p.stem.lower().startswith("manifest")
        )  # fmt: skip
        if not files:
            raise ValidationError(
                f"folder {str(path)!r} holds no test files ({', '.join(DATA_SUFFIXES)})"
            )
        rows: list[tuple[str, dict[str, Any]]] = [(p.name, {"file": p.name}) for p in files]
        directives: dict[str, str] = {}
        notes = [f"every data file in folder {path.name} is a test"]
        row_factors: list[dict[str, float]] = [{} for _ in rows]
    elif not path.is_file():
        raise ValidationError(f"manifest {str(path)!r} does not exist")
    elif path.suffix.lower() == ".toml":
        rows, directives, notes, row_factors = _read_toml(path)
    else:
        rows, directives, notes, shared = _read_csv(path)
        row_factors = [shared for _ in rows]
    base = path if path.is_dir() else path.parent
    glob_columns = parse_columns(directives.get("columns"), f"manifest {path.name}: columns")
    glob_units = parse_units(directives.get("units"), f"manifest {path.name}: units")
    pattern = cli_pattern or parse_current_pattern(directives.get("current_pattern"))
    entries = []
    for (where, row), factors in zip(rows, row_factors, strict=True):
        if row.get("_extra"):
            entries.append(
                TestEntry(
                    file=base / str(row["file"]),
                    label=str(row["file"]) or f"({where})",
                    error=f"manifest {where}: more fields than the header has columns "
                    '(quote values holding commas, e.g. "t,x,v,F")',
                )
            )
            continue
        entry = _entry(
            base, row, factors, f"manifest {where}", glob_columns, glob_units,
            cli_columns, cli_units,
        )  # fmt: skip
        entries.append(_apply_pattern(entry, pattern))
    return Manifest(
        path=path,
        entries=tuple(entries),
        columns=cli_columns or glob_columns,
        units=cli_units or glob_units,
        current_pattern=pattern,
        notes=tuple(notes),
    )


def _apply_pattern(entry: TestEntry, pattern: re.Pattern[str] | None) -> TestEntry:
    if pattern is None or entry.error:
        return entry
    found = values_from_name(pattern, entry.label)
    changes: dict[str, Any] = {}
    notes = list(entry.notes)
    if "current" in found and entry.current is None:
        changes["current"] = found["current"]
        changes["current_source"] = "file name"
        notes.append(f"current {found['current']:g} A from the file name")
    for key in ("frequency", "amplitude"):
        if key in found and getattr(entry, key) is None:
            changes[key] = found[key]
            notes.append(f"{key} {found[key]:g} from the file name")
    if not found:
        notes.append(f"file name does not match --current-pattern {pattern.pattern!r}")
    return replace(entry, notes=tuple(notes), **changes)
