"""Readers for damper test records: delimited text and MATLAB ``.mat`` files.

A test record holds sampled signals of one damper test: ``time``, ``displacement``
(stroke ``x_d``), ``velocity``, ``force``, and optionally ``current`` and
``acceleration``. Everything is converted to SI (model reference, section 1) on reading.

Which column is which
    Files with a header are matched by name, case-insensitively, against the aliases in
    :data:`ROLE_ALIASES` (``Time``, ``Disp``, ``stroke``, ``Load``, ``current``...); a
    unit in brackets or after an underscore (``Force [kN]``, ``disp_mm``) is read too.
    Otherwise a :class:`ColumnSpec` says it: positionally, one role per file column
    (``"t,x,v,F"``, ``_`` skips a column), or by name or 1-based index
    (``"t=Time,x=3,F=Load"``). A leading ``-`` on a role flips that signal's sign
    (``"-F"``: a rig measuring tension positive; the damper convention is compression
    positive).

Units
    ``"s,mm,mm/s,kN"``: each unit names its own signal by its dimension, so the order does
    not matter; ``"x=mm,F=kN"`` names the signal explicitly. See :data:`UNITS`.

Examples
--------
>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "run.csv"
>>> _ = path.write_text("Time [s],Disp [mm],Load [kN]\\n0,0,0\\n0.001,0.5,0.02\\n0.002,1.0,0.03\\n")
>>> rec = read_test(path)
>>> rec.roles, float(rec.displacement[-1]), float(rec.force[-1])
(('time', 'displacement', 'force'), 0.001, 30.0)
"""

from __future__ import annotations

import io
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, did_you_mean

__all__ = [
    "DATA_SUFFIXES",
    "ROLES",
    "ROLE_ALIASES",
    "UNITS",
    "VOLTAGE_UNITS",
    "ColumnSpec",
    "RawTest",
    "TestDataError",
    "UnitSpec",
    "parse_columns",
    "parse_units",
    "read_test",
]

FloatArray = npt.NDArray[np.float64]

#: Signals a test record can hold, with their SI unit.
ROLES: dict[str, str] = {
    "time": "s",
    "displacement": "m",
    "velocity": "m/s",
    "acceleration": "m/s^2",
    "force": "N",
    "current": "A",
}

#: Header names (lower case, without units) recognised for each signal.
ROLE_ALIASES: dict[str, tuple[str, ...]] = {
    "time": ("t", "time", "times", "zeit", "sec", "seconds", "timestamp"),
    "displacement": (
        "x", "xd", "x_d", "disp", "displacement", "stroke", "position", "pos", "travel",
        "deflection", "piston_displacement",
    ),
    "velocity": ("v", "vd", "v_d", "vel", "velocity", "speed", "piston_velocity"),
    "acceleration": ("a", "ad", "a_d", "acc", "accel", "acceleration"),
    "force": ("f", "fd", "f_d", "force", "load", "loadcell", "load_cell", "damper_force"),
    "current": ("i", "id", "i_d", "current", "curr", "amps", "coil_current", "drive_current"),
}  # fmt: skip

_ALIAS_TO_ROLE = {alias: role for role, names in ROLE_ALIASES.items() for alias in names}

#: Accepted units (lower case): their signal and the factor to SI.
UNITS: dict[str, tuple[str, float]] = {
    "s": ("time", 1.0),
    "ms": ("time", 1e-3),
    "m": ("displacement", 1.0),
    "mm": ("displacement", 1e-3),
    "cm": ("displacement", 1e-2),
    "in": ("displacement", 0.0254),
    "m/s": ("velocity", 1.0),
    "mm/s": ("velocity", 1e-3),
    "cm/s": ("velocity", 1e-2),
    "in/s": ("velocity", 0.0254),
    "m/s^2": ("acceleration", 1.0),
    "m/s2": ("acceleration", 1.0),
    "mm/s^2": ("acceleration", 1e-3),
    "mm/s2": ("acceleration", 1e-3),
    "g": ("acceleration", 9.81),
    "n": ("force", 1.0),
    "kn": ("force", 1e3),
    "lbf": ("force", 4.4482216152605),
    "a": ("current", 1.0),
    "ma": ("current", 1e-3),
    "v": ("current", 1.0),  # a coil-driver command voltage: times the gain [A/V]
    "mv": ("current", 1e-3),
}

#: Units of the current column that are voltages: they need the driver's gain [A/V].
VOLTAGE_UNITS = ("v", "mv")

#: File name suffixes read as test records (a folder given as manifest is scanned for them).
DATA_SUFFIXES = (".csv", ".tsv", ".txt", ".dat", ".asc", ".mat")

_SHORT_ROLE = {"t": "time", "x": "displacement", "v": "velocity", "a": "acceleration",
               "f": "force", "i": "current"}  # fmt: skip


class TestDataError(ValidationError):
    """A problem with one test's data; the campaign reports it for that test and goes on."""

    __test__ = False  # not a pytest test class


def _role(token: str, context: str) -> str:
    key = token.strip().lower()
    if key in _SHORT_ROLE:
        return _SHORT_ROLE[key]
    if key in ROLES:
        return key
    if key in _ALIAS_TO_ROLE:
        return _ALIAS_TO_ROLE[key]
    choices = [*_SHORT_ROLE, *ROLES]
    raise ValidationError(
        f"{context}: unknown signal {token.strip()!r}.{did_you_mean(key, choices)} "
        "Valid: t, x, v, a, F, i (or time, displacement, velocity, acceleration, force, "
        "current), '_' to skip a column"
    )


@dataclass(frozen=True)
class ColumnSpec:
    """Which file column holds which signal.

    Either ``positional`` (one role or ``None`` per file column, in order) or ``named``
    (role -> header name, variable name or 1-based column number). ``flipped`` lists
    the roles whose sign is reversed. Build one with :func:`parse_columns`.
    """

    positional: tuple[str | None, ...] | None = None
    named: Mapping[str, str | int] = field(default_factory=dict)
    flipped: frozenset[str] = frozenset()
    text: str = ""

    def __str__(self) -> str:
        return self.text


def parse_columns(text: str | ColumnSpec | None, context: str = "--columns") -> ColumnSpec | None:
    """Parse a column mapping: ``"t,x,v,F"`` (positional) or ``"t=Time,x=3,-F=Load"``.

    Examples
    --------
    >>> parse_columns("t,_,x,-F").positional
    ('time', None, 'displacement', 'force')
    >>> spec = parse_columns("t=Time,x=3,F=Load")
    >>> dict(spec.named)
    {'time': 'Time', 'displacement': 3, 'force': 'Load'}
    >>> parse_columns("t,x,speed,F").positional[2]
    'velocity'
    """
    if text is None or isinstance(text, ColumnSpec):
        return text
    tokens = [tok.strip() for tok in str(text).split(",")]
    if not any(tokens):
        raise ValidationError(f"{context} is empty; e.g. t,x,v,F")
    flipped: set[str] = set()
    named = [("=" in tok) for tok in tokens]
    if any(named) and not all(named):
        raise ValidationError(
            f"{context} {text!r} mixes positional and name=column entries; use one form, "
            "e.g. t,x,v,F or t=Time,x=Disp,F=Load"
        )
    if all(named):
        mapping: dict[str, str | int] = {}
        for tok in tokens:
            key, _, col = tok.partition("=")
            key, col = key.strip(), col.strip()
            flip = key.startswith("-")
            role = _role(key.lstrip("-"), context)
            if role in mapping:
                raise ValidationError(f"{context} {text!r} names {role!r} twice")
            if not col:
                raise ValidationError(f"{context} {text!r}: no column given for {key!r}")
            if col.isdigit():
                if int(col) < 1:
                    raise ValidationError(f"{context}: column numbers start at 1; got {col}")
                mapping[role] = int(col)
            else:
                mapping[role] = col
            if flip:
                flipped.add(role)
        return ColumnSpec(named=mapping, flipped=frozenset(flipped), text=str(text))
    roles: list[str | None] = []
    for tok in tokens:
        if tok in ("_", "skip", ""):
            roles.append(None)
            continue
        flip = tok.startswith("-")
        role = _role(tok.lstrip("-"), context)
        if role in roles:
            raise ValidationError(f"{context} {text!r} names {role!r} twice")
        roles.append(role)
        if flip:
            flipped.add(role)
    return ColumnSpec(positional=tuple(roles), flipped=frozenset(flipped), text=str(text))


@dataclass(frozen=True)
class UnitSpec:
    """Unit of each signal, as factors to SI, with the names the user gave."""

    factors: Mapping[str, float]
    names: Mapping[str, str]
    text: str = ""

    def __str__(self) -> str:
        return self.text


def _unit(token: str, context: str) -> tuple[str, float]:
    key = token.strip().lower().replace(" ", "")
    if key in UNITS:
        return UNITS[key]
    raise ValidationError(
        f"{context}: unknown unit {token.strip()!r}.{did_you_mean(key, UNITS)} "
        f"Valid: {', '.join(UNITS)}"
    )


def parse_units(text: str | UnitSpec | None, context: str = "--units") -> UnitSpec | None:
    """Parse units: ``"s,mm,mm/s,kN"`` (each unit names its signal) or ``"x=mm,F=kN"``.

    Examples
    --------
    >>> u = parse_units("ms,mm,mm/s,kN")
    >>> u.factors["time"], u.factors["displacement"], u.factors["force"]
    (0.001, 0.001, 1000.0)
    >>> parse_units("x=cm").factors
    mappingproxy({'displacement': 0.01})
    >>> parse_units("mm,cm")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --units 'mm,cm' gives two units for displacement ('mm' and 'cm'); ...
    """
    if text is None or isinstance(text, UnitSpec):
        return text
    from types import MappingProxyType

    factors: dict[str, float] = {}
    names: dict[str, str] = {}
    for tok in (t.strip() for t in str(text).split(",")):
        if not tok or tok == "_":
            continue
        if "=" in tok:
            key, _, unit = tok.partition("=")
            role = _role(key.strip().lstrip("-"), context)
            dim, factor = _unit(unit, context)
            if dim != role:
                raise ValidationError(
                    f"{context}: {unit.strip()!r} is a unit of {dim}, not of {role}"
                )
        else:
            unit = tok
            role, factor = _unit(tok, context)
        if role in factors:
            raise ValidationError(
                f"{context} {text!r} gives two units for {role} ({names[role]!r} and "
                f"{unit.strip()!r}); e.g. s,mm,mm/s,N or x=mm,F=kN"
            )
        factors[role] = factor
        names[role] = unit.strip()
    if not factors:
        raise ValidationError(f"{context} is empty; e.g. s,mm,mm/s,N")
    return UnitSpec(MappingProxyType(factors), MappingProxyType(names), str(text))


@dataclass(frozen=True)
class RawTest:
    """One test record in SI units, as read from a file (before pre-processing).

    Signals absent from the file are ``None``; ``current`` may also be a scalar (a
    ``.mat`` variable). ``notes`` says what the reader did (columns matched, units,
    sign flips, columns ignored); ``units`` the unit each signal was declared in.
    """

    source: str
    time: FloatArray
    displacement: FloatArray | None
    velocity: FloatArray | None
    force: FloatArray
    current: FloatArray | float | None = None
    acceleration: FloatArray | None = None
    notes: tuple[str, ...] = ()
    units: Mapping[str, str] = field(default_factory=dict)

    __test__ = False

    @property
    def roles(self) -> tuple[str, ...]:
        """The signals present, in the order of :data:`ROLES`."""
        return tuple(r for r in ROLES if getattr(self, r) is not None)

    def __len__(self) -> int:
        return int(self.time.size)


# -- header parsing ------------------------------------------------------------------
_BRACKET = re.compile(r"^\s*(?P<name>.*?)\s*[\[(](?P<unit>[^\])]*)[\])]\s*$")


def split_name_unit(header: str) -> tuple[str, str | None]:
    """Split ``"Force [kN]"``, ``"disp (mm)"`` or ``"load_kN"`` into a name and a unit.

    Examples
    --------
    >>> split_name_unit("Force [kN]"), split_name_unit("disp_mm"), split_name_unit("x_d")
    (('force', 'kN'), ('disp', 'mm'), ('x_d', None))
    """
    text = header.strip().strip('"').strip("'")
    m = _BRACKET.match(text)
    if m and m.group("name"):
        return _norm(m.group("name")), m.group("unit").strip()
    for sep in ("_", " "):
        if sep in text:
            head, _, tail = text.rpartition(sep)
            if tail.lower() in UNITS and head.strip():
                return _norm(head), tail
    return _norm(text), None


def _norm(name: str) -> str:
    out = re.sub(r"[^0-9a-z_]+", "_", name.strip().lower()).strip("_")
    return re.sub(r"_+", "_", out)


def _match_header(names: Sequence[str]) -> tuple[dict[str, int], list[str], dict[str, str]]:
    """Map header names to roles; return (role -> column index, ignored names, header units)."""
    found: dict[str, int] = {}
    units: dict[str, str] = {}
    ignored: list[str] = []
    for col, header in enumerate(names):
        name, unit = split_name_unit(header)
        role = _ALIAS_TO_ROLE.get(name) or _ALIAS_TO_ROLE.get(name.replace("_", ""))
        if role is None or role in found:
            ignored.append(header.strip())
            continue
        found[role] = col
        if unit:
            units[role] = unit
    return found, ignored, units


# -- delimited text ------------------------------------------------------------------
def _split(line: str, delimiter: str | None) -> list[str]:
    if delimiter is None:
        return line.split()
    if '"' in line:  # quoted fields ("Force, kN"): the csv module keeps them whole
        import csv

        return [f.strip() for f in next(csv.reader([line], delimiter=delimiter))]
    return [f.strip() for f in line.split(delimiter)]


def _trailing_empty(fields: list[str]) -> int:
    n = 0
    for f in reversed(fields):
        if f:
            break
        n += 1
    return n


def _is_number(field_: str) -> bool:
    try:
        float(field_)
    except ValueError:
        return False
    return True


def _detect_delimiter(line: str) -> str | None:
    if "\t" in line:
        return "\t"
    if ";" in line:
        return ";"
    if "," in line:
        return ","
    return None


_COMMENT = ("#", "%", "//")


def _numeric_line(line: str, delimiter: str | None) -> bool:
    fields = _split(line.rstrip().rstrip(delimiter or " "), delimiter)
    if delimiter == ";":
        fields = [f.replace(",", ".") for f in fields]
    return bool(fields) and all(_is_number(f) for f in fields if f) and any(fields)


def _units_line(fields: list[str]) -> bool:
    stripped = [f.strip("[]() ").lower() for f in fields]
    return any(stripped) and all(f in UNITS or f in ("", "-", "1") for f in stripped)


def _read_delimited(path: Path) -> tuple[FloatArray, list[str] | None, list[str] | None, list[str]]:
    """Numeric table, header names (or None), a units line (or None) and notes.

    The table starts at the first numeric line; the line before it is the header (or a
    units line below the header); anything above is a preamble (rig metadata), skipped
    with a note. A trailing delimiter on every line is ignored.
    """
    text = path.read_text(encoding="utf-8-sig", errors="replace")
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith(_COMMENT)]
    if not lines:
        raise TestDataError(f"{path.name}: the file holds no data")
    first_data = None
    delimiter: str | None = None
    for k, line in enumerate(lines):
        delimiter = _detect_delimiter(line)
        if _numeric_line(line, delimiter) and len(_split(line, delimiter)) >= 2:
            first_data = k
            break
    if first_data is None:
        raise TestDataError(f"{path.name}: no line of numbers found (is it a data file?)")
    data_lines = lines[first_data:]
    notes: list[str] = []
    if delimiter is not None:
        # trailing empty columns (a spreadsheet export's "1,2,3,,"): drop the empty fields
        # every row ends with
        empty = min(_trailing_empty(_split(ln, delimiter)) for ln in data_lines[:50])
        if empty:
            data_lines = [delimiter.join(_split(ln, delimiter)[:-empty]) for ln in data_lines]
            notes.append(f"ignored {empty} empty trailing column{'s' if empty > 1 else ''}")
    ncol = len(_split(data_lines[0], delimiter))
    header: list[str] | None = None
    units_line: list[str] | None = None
    above = [_split(ln.rstrip(), delimiter) for ln in lines[:first_data]]
    above = [row[: max(ncol, len(row) - _trailing_empty(row))] for row in above]
    if above and len(above[-1]) == ncol and _units_line(above[-1]):
        units_line = [f.strip("[]() ") for f in above.pop()]
    if above and len(above[-1]) == ncol:
        header = above.pop()
    elif above and len(above[-1]) > 1:
        raise TestDataError(
            f"{path.name}: the header line names {len(above[-1])} columns but the rows hold "
            f"{ncol}: {', '.join(above[-1])}"
        )
    if above:
        notes.append(
            f"skipped {len(above)} preamble line{'s' if len(above) > 1 else ''} above the table"
        )
    decimal_comma = delimiter == ";" and any("," in ln for ln in data_lines[:20])
    if decimal_comma:
        data_lines = [ln.replace(",", ".") for ln in data_lines]
        notes.append("read ';'-separated values with decimal commas")
    try:
        table = np.loadtxt(
            io.StringIO("\n".join(data_lines)), delimiter=delimiter, ndmin=2, dtype=float
        )
    except ValueError:
        table = _parse_slowly(path.name, data_lines, delimiter, ncol)
    kind = {None: "whitespace", ",": "comma", "\t": "tab", ";": "semicolon"}[delimiter]
    notes.insert(0, f"{kind}-separated text, {table.shape[0]} rows x {ncol} columns"
                 + ("" if header else ", no header"))  # fmt: skip
    return table, header, units_line, notes


def _parse_slowly(name: str, data_lines: list[str], delimiter: str | None, ncol: int) -> FloatArray:
    """Row by row: empty and 'nan' fields become NaN; anything else names its row."""
    rows = []
    for k, line in enumerate(data_lines):
        fields = _split(line, delimiter)
        if len(fields) != ncol:
            raise TestDataError(
                f"{name}: data row {k + 1} has {len(fields)} fields, the first row has {ncol}: "
                f"{line.strip()[:60]!r}"
            )
        row = []
        for j, f in enumerate(fields):
            if f == "" or f.lower() in ("nan", "na", "n/a", "null"):
                row.append(math.nan)
                continue
            try:
                row.append(float(f))
            except ValueError:
                raise TestDataError(
                    f"{name}: data row {k + 1}, column {j + 1}: {f[:20]!r} is not a number"
                ) from None
        rows.append(row)
    return np.array(rows, dtype=float)


# -- MATLAB ----------------------------------------------------------------------------
def _read_mat(path: Path) -> dict[str, Any]:
    import scipy.io

    try:
        raw = scipy.io.loadmat(str(path), squeeze_me=True, struct_as_record=False)
    except NotImplementedError:
        raise TestDataError(
            f"{path.name}: MATLAB v7.3 (HDF5) files are not supported; save with "
            "save(..., '-v7') or export the record as CSV"
        ) from None
    except Exception as exc:
        raise TestDataError(f"{path.name}: not a readable .mat file ({exc})") from None
    data = {k: v for k, v in raw.items() if not k.startswith("__")}
    # a single struct (e.g. `test.time`, `test.force`): use its fields
    if len(data) == 1:
        (only,) = data.values()
        fieldnames = getattr(only, "_fieldnames", None)
        if fieldnames:
            data = {f: getattr(only, f) for f in fieldnames}
    return data


# -- public reader -----------------------------------------------------------------------
def read_test(
    path: str | Path,
    columns: str | ColumnSpec | None = None,
    units: str | UnitSpec | None = None,
    *,
    current_gain: float | None = None,
) -> RawTest:
    """Read one test record (delimited text or ``.mat``) into SI units.

    Parameters
    ----------
    path : str or Path
        A ``.csv``, ``.tsv``, ``.txt``, ``.dat``, ``.asc`` (comma, tab, semicolon or
        whitespace separated, with or without a header, ``#``/``%`` comment lines) or
        ``.mat`` file (named vectors, one struct of vectors, or one matrix).
    columns : str or ColumnSpec, optional
        Column mapping (see :func:`parse_columns`); needed for files without a header
        and for ``.mat`` files holding a single matrix.
    units : str or UnitSpec, optional
        Units of the signals (see :func:`parse_units`); they override units found in
        the header. Default: units from the header, else SI.
    current_gain : float, optional
        Gain of the coil driver [A/V] for a current column in V or mV (the command
        voltage of a current-controlled driver); required for such a column.

    Returns
    -------
    RawTest

    Raises
    ------
    TestDataError
        For a problem with this file (missing, unreadable, no force column...).
    ValidationError
        For a malformed ``columns`` or ``units`` text.

    Examples
    --------
    Headerless whitespace text in millimetres:

    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "run.txt"
    >>> _ = p.write_text("0 0 10\\n0.01 2 12\\n")
    >>> r = read_test(p, columns="t,x,F", units="mm")
    >>> float(r.displacement[1]), r.velocity
    (0.002, None)
    """
    cols = parse_columns(columns)
    unit_spec = parse_units(units)
    path = Path(path)
    if not path.is_file():
        raise TestDataError(f"{path.name}: file not found ({path})")
    notes: list[str] = []
    signals: dict[str, Any] = {}
    header_units: dict[str, str] = {}
    if path.suffix.lower() == ".mat":
        signals, header_units, notes = _from_mat(path, cols)
    else:
        table, header, units_line, notes = _read_delimited(path)
        signals, header_units = _from_table(path.name, table, header, units_line, cols, notes)
    return _finish(path, signals, header_units, unit_spec, cols, notes, current_gain)


def _from_table(
    name: str,
    table: FloatArray,
    header: list[str] | None,
    units_line: list[str] | None,
    cols: ColumnSpec | None,
    notes: list[str],
) -> tuple[dict[str, Any], dict[str, str]]:
    ncol = table.shape[1]
    header_units: dict[str, str] = {}
    index: dict[str, int] = {}
    if cols is not None and cols.positional is not None:
        if len(cols.positional) != ncol:
            raise TestDataError(
                f"{name}: --columns {cols.text!r} names {len(cols.positional)} columns but the "
                f"file has {ncol}"
            )
        index = {role: j for j, role in enumerate(cols.positional) if role is not None}
        if header is not None:
            for role, j in index.items():
                unit = split_name_unit(header[j])[1]
                if unit:
                    header_units[role] = unit
        notes.append(f"columns by position: {cols.text}")
    elif cols is not None:
        for role, col in cols.named.items():
            if isinstance(col, int):
                if col > ncol:
                    raise TestDataError(f"{name}: column {col} for {role} but the file has {ncol}")
                index[role] = col - 1
            else:
                if header is None:
                    raise TestDataError(
                        f"{name}: --columns names header {col!r} but the file has no header; "
                        "use column numbers (e.g. t=1,x=2,F=4) or positional roles (t,x,F)"
                    )
                lowered = [h.strip().strip('"').lower() for h in header]
                plain = [split_name_unit(h)[0] for h in header]
                target = col.strip().lower()
                if target in lowered:
                    index[role] = lowered.index(target)
                elif _norm(target) in plain:
                    index[role] = plain.index(_norm(target))
                else:
                    raise TestDataError(
                        f"{name}: no column {col!r} for {role}.{did_you_mean(col, header)} "
                        f"Header: {', '.join(h.strip() for h in header)}"
                    )
                unit = split_name_unit(header[index[role]])[1]
                if unit:
                    header_units[role] = unit
        notes.append(f"columns by name: {cols.text}")
    elif header is not None:
        index, ignored, header_units = _match_header(header)
        matched = ", ".join(f"{header[j].strip()} -> {role}" for role, j in index.items())
        notes.append(f"header matched: {matched}" if matched else "no header name matched")
        if ignored:
            notes.append(f"columns ignored: {', '.join(ignored)}")
    else:
        raise TestDataError(
            f"{name}: the file has no header; say which column is which with --columns "
            f"(e.g. t,x,v,F for its {ncol} columns) or in the manifest"
        )
    if units_line is not None:
        for role, j in index.items():
            if j < len(units_line) and units_line[j].lower() in UNITS:
                header_units.setdefault(role, units_line[j])
    signals = {role: table[:, j] for role, j in index.items()}
    return signals, header_units


def _from_mat(
    path: Path, cols: ColumnSpec | None
) -> tuple[dict[str, Any], dict[str, str], list[str]]:
    data = _read_mat(path)
    notes: list[str] = []
    header_units: dict[str, str] = {}
    arrays = {k: np.asarray(v) for k, v in data.items() if _numeric(v)}
    matrices = {k: a for k, a in arrays.items() if a.ndim == 2 and min(a.shape) > 1}
    if cols is not None and cols.positional is not None:
        if len(matrices) != 1:
            raise TestDataError(
                f"{path.name}: positional --columns needs one matrix in the .mat file; found "
                f"{', '.join(matrices) or 'none'} (use name form, e.g. t=time,x=disp,F=force)"
            )
        (mname, mat), = matrices.items()  # fmt: skip
        if mat.shape[1] != len(cols.positional) and mat.shape[0] == len(cols.positional):
            mat = mat.T
        if mat.shape[1] != len(cols.positional):
            raise TestDataError(
                f"{path.name}: matrix {mname!r} is {mat.shape[0]}x{mat.shape[1]} but --columns "
                f"{cols.text!r} names {len(cols.positional)} columns"
            )
        notes.append(
            f".mat matrix {mname!r} ({mat.shape[0]} x {mat.shape[1]}), columns {cols.text}"
        )
        return (
            {r: mat[:, j].astype(float) for j, r in enumerate(cols.positional) if r is not None},
            header_units,
            notes,
        )
    signals: dict[str, Any] = {}
    if cols is not None:
        for role, col in cols.named.items():
            if isinstance(col, int):
                if len(matrices) != 1:
                    raise TestDataError(
                        f"{path.name}: column numbers need one matrix in the .mat file; "
                        f"found {', '.join(matrices) or 'none'}"
                    )
                (mat,) = matrices.values()
                mat = mat if mat.shape[0] >= mat.shape[1] else mat.T
                if col > mat.shape[1]:
                    raise TestDataError(
                        f"{path.name}: column {col} for {role} but the matrix has {mat.shape[1]}"
                    )
                signals[role] = mat[:, col - 1].astype(float)
                continue
            if col not in arrays:
                raise TestDataError(
                    f"{path.name}: no variable {col!r} for {role}.{did_you_mean(col, arrays)} "
                    f"Variables: {', '.join(sorted(arrays))}"
                )
            signals[role] = arrays[col]
            unit = split_name_unit(col)[1]
            if unit:
                header_units[role] = unit
        notes.append(f".mat variables by name: {cols.text}")
    else:
        vectors = {k: a for k, a in arrays.items() if a.ndim <= 1}
        index, ignored, header_units = _match_header(list(vectors))
        names = list(vectors)
        signals = {role: vectors[names[j]] for role, j in index.items()}
        if not signals and len(matrices) == 1:
            (mname, mat), = matrices.items()  # fmt: skip
            raise TestDataError(
                f"{path.name}: the .mat file holds one matrix {mname!r} ({mat.shape[0]} x "
                f"{mat.shape[1]}); say which column is which with --columns (e.g. t,x,v,F)"
            )
        matched = ", ".join(f"{names[j]} -> {role}" for role, j in index.items())
        notes.append(
            f".mat variables matched: {matched}" if matched else "no .mat variable matched"
        )
        if ignored:
            notes.append(f"variables ignored: {', '.join(ignored)}")
    for role, value in list(signals.items()):
        arr = np.asarray(value, dtype=float)
        if role == "current" and arr.ndim == 0:
            signals[role] = float(arr)
            continue
        if arr.ndim != 1:
            arr = arr.ravel() if 1 in arr.shape else arr
        if arr.ndim != 1:
            raise TestDataError(f"{path.name}: {role} must be a vector; got shape {arr.shape}")
        signals[role] = arr
    return signals, header_units, notes


def _numeric(value: Any) -> bool:
    arr = np.asarray(value)
    return arr.dtype.kind in "fiu" and arr.size > 0


def _finish(
    path: Path,
    signals: dict[str, Any],
    header_units: dict[str, str],
    unit_spec: UnitSpec | None,
    cols: ColumnSpec | None,
    notes: list[str],
    current_gain: float | None = None,
) -> RawTest:
    name = path.name
    if current_gain is not None and not (math.isfinite(current_gain) and current_gain > 0):
        raise ValidationError(f"current gain must be a number > 0 [A/V]; got {current_gain!r}")
    present = ", ".join(signals) or "none"
    for required in ("time", "force"):
        if required not in signals:
            raise TestDataError(
                f"{name}: no {required} column (found: {present}); name it in the header or "
                "with --columns"
            )
    if "displacement" not in signals and "velocity" not in signals:
        raise TestDataError(f"{name}: needs a displacement or a velocity column (found: {present})")
    n = np.asarray(signals["time"]).size
    out: dict[str, Any] = {}
    used_units: list[str] = []
    declared: dict[str, str] = {}
    for role, value in signals.items():
        factor = 1.0
        unit_name = ROLES[role]
        if unit_spec is not None and role in unit_spec.factors:
            factor = unit_spec.factors[role]
            unit_name = unit_spec.names[role]
        elif role in header_units:
            try:
                dim, factor = _unit(header_units[role], f"{name}: header unit")
            except ValidationError as exc:
                raise TestDataError(str(exc)) from None
            if dim != role:
                raise TestDataError(
                    f"{name}: the {role} column is in {header_units[role]!r}, a unit of {dim}"
                )
            unit_name = header_units[role]
        if role == "current" and unit_name.lower() in VOLTAGE_UNITS:
            if current_gain is None:
                raise TestDataError(
                    f"{name}: the current column is in {unit_name}, a voltage; give the coil "
                    "driver's gain in A/V (--gain, e.g. --gain 0.5) to convert it to A"
                )
            factor *= current_gain
            notes.append(f"current from the {unit_name} column times the gain {current_gain:g} A/V")
        declared[role] = unit_name
        sign = -1.0 if cols is not None and role in cols.flipped else 1.0
        if isinstance(value, float):
            out[role] = sign * factor * value
        else:
            arr = np.asarray(value, dtype=float) * (sign * factor)
            if arr.size != n:
                raise TestDataError(f"{name}: {role} has {arr.size} samples but time has {n}")
            out[role] = np.ascontiguousarray(arr)
        if unit_name != ROLES[role]:
            used_units.append(f"{role} in {unit_name}")
        if sign < 0:
            notes.append(f"{role} sign flipped")
    if used_units:
        notes.append("converted to SI: " + ", ".join(used_units))
    return RawTest(
        source=str(path),
        time=out["time"],
        displacement=out.get("displacement"),
        velocity=out.get("velocity"),
        force=out["force"],
        current=out.get("current"),
        acceleration=out.get("acceleration"),
        notes=tuple(notes),
        units=declared,
    )
