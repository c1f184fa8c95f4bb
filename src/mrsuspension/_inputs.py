"""Reading a user's input files: one place that reads, bounds and records them.

Every reader of a file a user names (scenario and study TOML, parameter files, road
profiles, OpenCRG roads, identification manifests) goes through :func:`read_bytes` or
:func:`read_text`, so that

* a missing file, a folder or an unreadable file (``PermissionError``, a device error)
  is one :class:`~mrsuspension.errors.ValidationError` line naming the file;
* TOML and JSON documents (:func:`load_toml`, :func:`load_json`, :func:`parse_toml`,
  :func:`parse_json`) nested deeper than :data:`MAX_DEPTH` levels are refused before any
  use, instead of a ``RecursionError`` from the parser or from the code that walks them;
* the content of every file read inside :func:`recording` is recorded (path -> sha256):
  a study keys its cache by that record (:meth:`mrsuspension.studies.Study.canonical`),
  so a new kind of file input cannot be left out of the key.

Examples
--------
>>> import tempfile, pathlib
>>> f = pathlib.Path(tempfile.mkdtemp()) / "road.csv"
>>> _ = f.write_text("0,0\\n1,1\\n")
>>> with recording() as files:
...     _ = read_text(f, "road profile file")
>>> [(pathlib.Path(k).name, v[:12]) for k, v in files.items()]
[('road.csv', 'd2797ea35024')]
"""

from __future__ import annotations

import hashlib
import json
import tomllib
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import Any

from mrsuspension.errors import ValidationError, check_input_file

__all__ = [
    "MAX_DEPTH",
    "check_depth",
    "load_json",
    "load_toml",
    "parse_json",
    "parse_toml",
    "read_bytes",
    "read_text",
    "read_toml",
    "record",
    "recording",
]

#: deepest nesting of tables/arrays (objects/lists) a TOML or JSON input may have
MAX_DEPTH = 32

_RECORDS: ContextVar[tuple[dict[str, str], ...]] = ContextVar("mrsuspension_inputs", default=())


@contextmanager
def recording() -> Iterator[dict[str, str]]:
    """Record every input file read inside the block: ``{resolved path: sha256}``.

    Recordings nest: a file read inside two blocks is recorded in both.
    """
    files: dict[str, str] = {}
    token = _RECORDS.set((*_RECORDS.get(), files))
    try:
        yield files
    finally:
        _RECORDS.reset(token)


def record(path: str | Path, data: bytes) -> None:
    """Record that ``path`` was read with content ``data`` (in every open :func:`recording`)."""
    records = _RECORDS.get()
    if records:
        key = str(Path(path).resolve())
        digest = hashlib.sha256(data).hexdigest()
        for files in records:
            files[key] = digest


def read_bytes(path: str | Path, what: str) -> bytes:
    """The bytes of an input file, recorded; any problem is one :class:`ValidationError`.

    ``what`` names the file in messages (``"scenario file"``, ``"CRG file"``).

    Examples
    --------
    >>> read_bytes(".", "road profile file")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: road profile file '.' is a folder, expected a file
    """
    path = check_input_file(what, path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise ValidationError(f"cannot read {what} {str(path)!r}: {reason}") from None
    record(path, data)
    return data


def read_text(path: str | Path, what: str, encoding: str = "utf-8") -> str:
    """The text of an input file (:func:`read_bytes`, decoded; universal newlines)."""
    data = read_bytes(path, what)
    try:
        text = data.decode(encoding)
    except UnicodeDecodeError as exc:
        raise ValidationError(
            f"cannot read {what} {str(path)!r}: not {encoding} text ({exc.reason} at byte "
            f"{exc.start})"
        ) from None
    return text.replace("\r\n", "\n").replace("\r", "\n")


def check_depth(what: str, data: Any, limit: int = MAX_DEPTH) -> Any:
    """Return ``data`` if its tables/lists nest at most ``limit`` levels, else raise.

    Walked without recursion, so any depth is measured.

    Examples
    --------
    >>> check_depth("study file 's.toml'", {"a": [[1]]})
    {'a': [[1]]}
    >>> deep: dict = {}
    >>> node = deep
    >>> for _ in range(40):
    ...     node["a"] = {}
    ...     node = node["a"]
    >>> check_depth("study file 's.toml'", deep)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: study file 's.toml' nests tables or lists more than 32 levels deep; at most 32 are allowed
    """
    stack: list[tuple[Any, int]] = [(data, 1)]
    while stack:
        node, depth = stack.pop()
        if isinstance(node, dict):
            children: Any = node.values()
        elif isinstance(node, list):
            children = node
        else:
            continue
        if depth > limit:
            raise _too_deep(what, limit)
        stack.extend((child, depth + 1) for child in children)
    return data


def _too_deep(what: str, limit: int) -> ValidationError:
    """The error of an input nested more than ``limit`` levels deep."""
    return ValidationError(
        f"{what} nests tables or lists more than {limit} levels deep; at most {limit} are allowed"
    )


def parse_toml(text: str, what: str, limit: int = MAX_DEPTH) -> dict[str, Any]:
    """Parse TOML text; syntax errors and deep nesting are one :class:`ValidationError`.

    Nesting deep enough to exhaust the parser's recursion is caught as such; anything
    it parses is walked by :func:`check_depth`.

    Examples
    --------
    >>> parse_toml("a = " + "[" * 400 + "]" * 400, "study file 's.toml'")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: study file 's.toml' nests tables or lists more than 32 levels deep; at most 32 are allowed
    """
    deep = _too_deep(what, limit)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValidationError(f"{what} is not valid TOML: {exc}") from None
    except RecursionError:
        raise deep from None
    return check_depth(what, data, limit)


def parse_json(text: str | bytes, what: str, limit: int = MAX_DEPTH) -> Any:
    """Parse JSON text; syntax errors and deep nesting are one :class:`ValidationError`.

    Examples
    --------
    >>> parse_json('{"a": [1, 2]}', "parameter file 'p.json'")
    {'a': [1, 2]}
    >>> parse_json("[" * 1000 + "]" * 1000, "parameter file 'p.json'")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: parameter file 'p.json' nests tables or lists more than 32 levels deep; at most 32 are allowed
    """
    deep = _too_deep(what, limit)
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError as exc:
            raise ValidationError(f"{what} is not UTF-8 text: {exc.reason}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValidationError(f"{what} is not valid JSON: {exc}") from None
    except RecursionError:
        raise deep from None
    return check_depth(what, data, limit)


def load_toml(path: str | Path, what: str) -> dict[str, Any]:
    """A TOML input file (:func:`read_text` + :func:`parse_toml`); ``what`` names it."""
    text = read_text(path, what)
    return parse_toml(text, f"{what} {str(path)!r}")


def load_json(path: str | Path, what: str) -> Any:
    """A JSON input file (:func:`read_text` + :func:`parse_json`); ``what`` names it."""
    text = read_text(path, what)
    return parse_json(text, f"{what} {str(path)!r}")


def read_toml(path: str | Path, what: str) -> dict[str, Any]:
    """The contents of a TOML file; any problem reading it is a :class:`ValidationError`.

    ``what`` names the file in the messages ("scenario", "study", ...). Read through
    :func:`load_toml`: recorded for the study cache, and refused when
    nested more than :data:`MAX_DEPTH` levels deep.

    Examples
    --------
    >>> read_toml("no/such.toml", "scenario")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: scenario file not found: 'no/such.toml'
    """
    return load_toml(path, f"{what} file")
