"""Errors raised by mrsuspension.

Every error names the offending field, the value it received and what would be valid,
so that a user can fix the input without reading the source.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:  # numpy is imported where used: `import mrsuspension.errors` stays cheap
    import numpy as np

__all__ = [
    "MRSuspensionError",
    "ValidationError",
    "check_count",
    "check_host",
    "check_input_file",
    "check_input_folder",
    "check_keys",
    "check_port",
    "check_tables",
    "did_you_mean",
]


class MRSuspensionError(Exception):
    """Base class of every error raised on purpose by mrsuspension."""


class ValidationError(MRSuspensionError, ValueError):
    """An input (argument, parameter, file content) is outside its valid range."""


#: The optional extras and the modules each brings (``pip install "mrsuspension[extra]"``).
EXTRAS: dict[str, tuple[str, ...]] = {
    "web": ("starlette", "uvicorn", "websockets"),
    "data": ("pyarrow",),
    "distributed": ("distributed",),
    "optimal": ("casadi",),  # the semi-active optimum (mrsuspension.benchmark)
}


def require_extra(extra: str, what: str, alternative: str = "") -> None:
    """Raise a one-line :class:`ValidationError` when an optional extra is not installed.

    The one home of "this needs an extra": names what needs it, the missing modules and
    the ``pip install`` line (and ``alternative``, a way to do without it, if given).

    Examples
    --------
    >>> require_extra("web", "the browser monitor")  # installed here: nothing happens
    >>> EXTRAS["nothing"] = ("surely_not_a_module_xyz",)
    >>> require_extra("nothing", "this feature", "use plain text")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: this feature needs surely_not_a_module_xyz, which is not installed: pip install "mrsuspension[nothing]" (or use plain text)
    >>> del EXTRAS["nothing"]
    """
    import importlib.util

    missing = [m for m in EXTRAS[extra] if importlib.util.find_spec(m) is None]
    if missing:
        raise ValidationError(
            f"{what} needs {', '.join(missing)}, which {'is' if len(missing) == 1 else 'are'} "
            f'not installed: pip install "mrsuspension[{extra}]"'
            + (f" (or {alternative})" if alternative else "")
        )


def did_you_mean(name: str, choices: Iterable[str]) -> str:
    """Return a ``" Did you mean 'x'?"`` hint, or an empty string.

    Examples
    --------
    >>> did_you_mean("wang-symetric-low", ["wang-symmetric-low", "bingham"])
    " Did you mean 'wang-symmetric-low'?"
    """
    close = difflib.get_close_matches(name, list(choices), n=1, cutoff=0.6)
    return f" Did you mean '{close[0]}'?" if close else ""


def unknown_name(kind: str, name: str, choices: Iterable[str]) -> ValidationError:
    """Build the error for a name that is not registered."""
    choices = sorted(choices)
    return ValidationError(
        f"unknown {kind} {name!r}.{did_you_mean(name, choices)} Valid: {', '.join(choices)}."
    )


def check_keys(where: str, table: object, valid: Sequence[str]) -> Mapping[str, Any]:
    """Return ``table`` if it is a table whose keys are all in ``valid``, else raise.

    Parameters
    ----------
    where : str
        The table's name in messages, e.g. ``"[study]"``.
    table : object
        The value read for it (e.g. from TOML).
    valid : sequence of str
        The keys it may hold, in the order the message lists them.

    Returns
    -------
    Mapping
        ``table``, unchanged.

    Raises
    ------
    ValidationError
        ``table`` is not a mapping, or holds a key not in ``valid`` (with a did-you-mean).

    Examples
    --------
    >>> check_keys("[study]", {"name": "a"}, ["name", "seed"])
    {'name': 'a'}
    >>> check_keys("[study]", {"seeed": 1}, ["name", "seed"])
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown key [study] seeed. Did you mean 'seed'? Valid: name, seed.
    """
    return _named(table, valid, f"{where} must be a table", lambda key: f"key {where} {key}")


def check_tables(what: str, data: object, valid: Sequence[str]) -> Mapping[str, Any]:
    """Return ``data`` if it is a table of tables named in ``valid``, else raise.

    Parameters
    ----------
    what : str
        The document in messages, with its article, e.g. ``"a study"``.
    data : object
        The document as read (e.g. from TOML).
    valid : sequence of str
        The top-level tables it may hold.

    Returns
    -------
    Mapping
        The document itself.

    Raises
    ------
    ValidationError
        Not a mapping, or a table name not in ``valid`` (with a did-you-mean).

    Examples
    --------
    >>> check_tables("a study", {"study": {}}, ["study", "grid"])
    {'study': {}}
    >>> check_tables("a study", {"gird": {}}, ["study", "grid"])
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown table [gird] in a study. Did you mean 'grid'? Valid: study, grid.
    """
    return _named(
        data, valid, f"{what} must be a table of tables", lambda key: f"table [{key}] in {what}"
    )


def _named(
    value: object, valid: Sequence[str], not_table: str, subject: Callable[[object], str]
) -> Mapping[str, Any]:
    """``value`` if a mapping with keys in ``valid``; else ``not_table`` or ``unknown <subject>``."""
    if not isinstance(value, Mapping):
        raise ValidationError(f"{not_table}; got {value!r}")
    for key in value:
        if key not in valid:
            raise ValidationError(
                f"unknown {subject(key)}.{did_you_mean(str(key), valid)} Valid: {', '.join(valid)}."
            )
    return value


def check_finite(name: str, value: object, valid: str = "finite") -> np.ndarray:
    """Return ``value`` as a float array, or raise if any element is NaN or infinite.

    ``valid`` says what a valid value is in the message (default ``"finite"``).

    Examples
    --------
    >>> check_finite("velocity", [0.1, float("nan")])
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: velocity must be finite; got nan at index 1
    """
    import numpy as np

    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValidationError(
            f"{name} must be a number or an array of numbers; got {value!r}"
        ) from exc
    if not np.all(np.isfinite(arr)):
        bad = np.flatnonzero(~np.isfinite(arr.ravel()))[0]
        where = f" at index {bad}" if arr.ndim else ""
        raise ValidationError(f"{name} must be {valid}; got {arr.ravel()[bad]}{where}")
    return arr


def check_range(
    name: str,
    value: object,
    low: float | None = None,
    high: float | None = None,
    *,
    unit: str = "",
    low_inclusive: bool = True,
    high_inclusive: bool = True,
) -> np.ndarray:
    """Check that every element of ``value`` is finite and inside ``[low, high]``.

    Examples
    --------
    >>> check_range("drive current", 0.7, 0.0, 0.5, unit="A")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: drive current must be in [0, 0.5] A; got 0.7 A
    """
    import numpy as np

    lo = "-inf" if low is None else f"{low:g}"
    hi = "inf" if high is None else f"{high:g}"
    lb = "[" if low_inclusive and low is not None else "("
    rb = "]" if high_inclusive and high is not None else ")"
    u = f" {unit}" if unit else ""
    # a NaN or infinite value is told the valid range too, not only "finite"
    arr = check_finite(name, value, valid=f"finite and in {lb}{lo}, {hi}{rb}{u}")
    flat = arr.ravel()
    too_low = np.zeros(flat.shape, bool)
    too_high = np.zeros(flat.shape, bool)
    if low is not None:
        too_low = flat < low if low_inclusive else flat <= low
    if high is not None:
        too_high = flat > high if high_inclusive else flat >= high
    bad = too_low | too_high
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        where = f" at index {k}" if arr.ndim else ""
        raise ValidationError(f"{name} must be in {lb}{lo}, {hi}{rb}{u}; got {flat[k]:g}{u}{where}")
    return arr


def check_port(name: str, port: object, *, any_free: bool = False) -> int:
    """A TCP/UDP port number in 1-65535 (0 too with ``any_free``: the system picks one).

    Examples
    --------
    >>> check_port("--port", 8765)
    8765
    >>> check_port("--port", 70000)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --port must be an integer in [1, 65535]; got 70000
    """
    low = 0 if any_free else 1
    if isinstance(port, bool) or not isinstance(port, int) or not low <= port <= 65535:
        note = " (0: any free port)" if any_free else ""
        raise ValidationError(f"{name} must be an integer in [{low}, 65535]{note}; got {port!r}")
    return port


def check_host(name: str, host: str) -> str:
    """A network address to bind or reach: not empty, and one the system resolves.

    Examples
    --------
    >>> check_host("--host", "127.0.0.1")
    '127.0.0.1'
    >>> check_host("--host", " ")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --host must be an address such as 127.0.0.1 (0.0.0.0: every interface); got ' '
    """
    import socket

    if not isinstance(host, str) or not host.strip() or len(host) > 253:
        shown = host if not isinstance(host, str) or len(host) <= 60 else host[:60] + "..."
        raise ValidationError(
            f"{name} must be an address such as 127.0.0.1 (0.0.0.0: every interface); got {shown!r}"
        )
    try:
        socket.getaddrinfo(host, None)
    except (OSError, UnicodeError) as exc:
        raise ValidationError(
            f"{name} {host!r} is not an address this machine knows: {exc}"
        ) from None
    return host


def check_count(
    name: str, value: object, minimum: int = 1, maximum: int | None = None, *, why: str = ""
) -> int:
    """An integer count (workers, points, starts) of at least ``minimum``, at most ``maximum``.

    ``why`` tells, after the limit, what a count beyond it would cost (e.g.
    ``" (one simulation each)"``).

    Examples
    --------
    >>> check_count("--workers", 0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --workers must be an integer >= 1; got 0
    >>> check_count("--max-evaluations", 10**20, 1, 100_000, why=" (one simulation each)")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --max-evaluations must be an integer >= 1 and <= 100000 (one simulation each); got 100000000000000000000
    """
    valid = f">= {minimum}" if maximum is None else f">= {minimum} and <= {maximum}{why}"
    if (
        isinstance(value, bool)
        or not isinstance(value, int)
        or value < minimum
        or (maximum is not None and value > maximum)
    ):
        raise ValidationError(f"{name} must be an integer {valid}; got {value!r}")
    return value


def check_input_file(what: str, path: str | Path) -> Path:
    """``path`` as a :class:`~pathlib.Path` to an existing file (not a folder).

    ``what`` names it in the message (``"scenario file"``, ``"--parameters"``).

    Examples
    --------
    >>> check_input_file("scenario file", ".")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: scenario file '.' is a folder, expected a file
    """
    path = Path(path)
    if path.is_dir():
        raise ValidationError(f"{what} {str(path)!r} is a folder, expected a file")
    if not path.is_file():
        raise ValidationError(f"{what} not found: {str(path)!r}")
    return path


def check_input_folder(what: str, path: str | Path) -> Path:
    """``path`` as a :class:`~pathlib.Path` to an existing folder (not a file).

    Examples
    --------
    >>> check_input_folder("--road-dir", "no/such/folder")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --road-dir not found: 'no/such/folder'
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValidationError(f"{what} {str(path)!r} is a file, expected a folder")
    if not path.is_dir():
        raise ValidationError(f"{what} not found: {str(path)!r}")
    return path
