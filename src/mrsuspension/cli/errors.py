"""User-error and interrupt handling shared by the ``mrsus`` commands.

A user error is one ``error:`` line on stderr and exit code 2 (:func:`user_errors`); an
interrupt (Ctrl-C, SIGTERM) is one ``interrupted:`` line and exit code 130 or 143
(:func:`interrupts`).
"""

from __future__ import annotations

import os
import re
import signal
import sys
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any

import typer

from mrsuspension.errors import MRSuspensionError

__all__ = [
    "interrupted_message",
    "interrupts",
    "keep_on_interrupt",
    "option_named",
    "permission_message",
    "user_errors",
]

#: the field a library message starts with: ``peak_velocity must ...``, ``drive current
#: must ...``, ``target_force must ...``
_FIELD = re.compile(r"^([A-Za-z][A-Za-z_ ]*?)(\[\d+\])? (must|=)")
#: a run of blanks, as the one-line message folds them
_BLANKS = re.compile(r"\s+")


def _context() -> Any:
    """The running command's click context, or None (typer vendors click privately)."""
    try:
        from typer._click.globals import get_current_context
    except ImportError:  # pragma: no cover - another typer layout: messages stay as they are
        return None
    return get_current_context(silent=True)


def option_named(message: str, aliases: Mapping[str, str] | None = None) -> str:
    """``message`` with its leading library field replaced by the option the user gave.

    A library error names its field (``peak_velocity must be in [0, 5] m/s``); on the
    command line the user typed ``--peak-velocity``. The field is replaced when it is
    (after ``aliases``, field -> option) an option of the running command that was given
    on the command line, so that a value taken from a file keeps the file's name. Outside
    a command, or when no option matches, the message is returned unchanged.

    Examples
    --------
    >>> option_named("peak_velocity must be > 0 m/s; got 0 m/s")  # no command running
    'peak_velocity must be > 0 m/s; got 0 m/s'
    """
    ctx = _context()
    match = _FIELD.match(message)
    if ctx is None:
        return message
    if match is None:
        return _by_value(message, ctx)
    field = match.group(1)
    option = (aliases or {}).get(field, "--" + field.replace("_", "-").replace(" ", "-"))
    if option in message.split(":", 1)[0]:
        return message
    from typer._click.core import ParameterSource

    for param in ctx.command.params:
        given = param.name is not None and (
            ctx.get_parameter_source(param.name) == ParameterSource.COMMANDLINE
        )
        if given and option in getattr(param, "opts", ()):
            return option + message[len(field) :]
    return message


def _given(ctx: Any) -> list[tuple[str, Any]]:
    """(long option, value) of the options given on the command line."""
    from typer._click.core import ParameterSource

    given = []
    for param in ctx.command.params:
        opts = [o for o in getattr(param, "opts", ()) if o.startswith("--")]
        if (
            param.name
            and opts
            and ctx.get_parameter_source(param.name) == ParameterSource.COMMANDLINE
        ):
            given.append((max(opts, key=len), ctx.params.get(param.name)))
    return given


def _by_value(message: str, ctx: Any) -> str:
    """``message`` prefixed with the option whose value it quotes (``unknown damper model
    'x'`` -> ``--model: unknown damper model 'x'``), when it names no option itself and
    exactly one given option has that value."""
    given = _given(ctx)
    if any(option in message for option, _ in given):
        return message
    quoting = [
        option
        for option, value in given
        if isinstance(value, str)
        and any(f"'{v}'" in message for v in (value, _BLANKS.sub(" ", value)))
    ]
    return f"{quoting[0]}: {message}" if len(quoting) == 1 else message


@contextmanager
def user_errors(aliases: Mapping[str, str] | None = None) -> Iterator[None]:
    """Turn a :class:`~mrsuspension.errors.MRSuspensionError` into one line and exit code 2.

    Covers :class:`~mrsuspension.errors.ValidationError` and
    :class:`~mrsuspension.engine.simulate.SimulationDiverged`; anything else is a bug and
    keeps its traceback. A message that starts with a library field the user gave as an
    option names the option instead (:func:`option_named`; ``aliases`` maps fields whose
    option is spelled differently, e.g. ``{"target_force": "--force"}``).

    Examples
    --------
    >>> from mrsuspension.errors import ValidationError
    >>> try:
    ...     with user_errors():
    ...         raise ValidationError("--rate must be > 0 Hz; got -1 Hz")
    ... except typer.Exit as exc:
    ...     print("exit", exc.exit_code)
    exit 2
    """
    try:
        yield
    except MRSuspensionError as exc:
        message = option_named(" ".join(str(exc).split()), aliases)
        typer.echo(f"error: {message}", err=True)
        raise typer.Exit(2) from None
    except PermissionError as exc:  # a file or folder the user may not read or write
        typer.echo(f"error: {permission_message(exc)}", err=True)
        raise typer.Exit(2) from None


def plain_warnings() -> None:
    """Show the package's own warnings as one ``warning: ...`` line on stderr.

    A warning raised by mrsuspension code (a :class:`UserWarning` subclass defined in the
    package, e.g. ``RoadBandWarning``) is for the user, not a developer: no file name,
    line number or source line. Other warnings keep Python's format.
    """
    import warnings

    default = warnings.showwarning

    def show(message: Warning | str, category: type[Warning], filename: str, lineno: int,
             file: Any = None, line: str | None = None) -> None:  # fmt: skip
        if issubclass(category, UserWarning) and category.__module__.startswith("mrsuspension"):
            print(f"warning: {message}", file=sys.stderr if file is None else file)
        else:
            default(message, category, filename, lineno, file, line)

    warnings.showwarning = show


def permission_message(exc: PermissionError) -> str:
    """One line for a :class:`PermissionError`: the path and what to do.

    Examples
    --------
    >>> permission_message(PermissionError(13, "Permission denied", "/root/s.toml"))
    "permission denied: '/root/s.toml' (Permission denied): give this user access to it, or use another path"
    """
    where = repr(str(exc.filename)) if exc.filename is not None else "a file or folder"
    if exc.filename2 is not None:
        where += f" or {str(exc.filename2)!r}"
    why = exc.strerror or "Permission denied"
    return f"permission denied: {where} ({why}): give this user access to it, or use another path"


#: what interrupted commands kept, for the ``interrupted:`` line (:func:`keep_on_interrupt`)
_KEPT: list[str] = []


def keep_on_interrupt(what: str) -> None:
    """Name, in the ``interrupted:`` line, something an interrupted command kept on purpose.

    E.g. ``hil run --out``: the recording up to the Ctrl-C (the loop's safe stop included).

    Examples
    --------
    >>> keep_on_interrupt("the recording so far in 'rec'")
    >>> interrupted_message(kept=_KEPT)
    "interrupted: kept the recording so far in 'rec'"
    >>> _KEPT.clear()
    """
    _KEPT.append(what)


def interrupted_message(left: Sequence[str | Path] = (), kept: Sequence[str] = ()) -> str:
    """The line printed when a command is interrupted: what was saved, or not.

    Every ``--out`` is written into a temporary folder and moved into place only when the
    command completes (:mod:`mrsuspension._output`), so an interrupted command names the
    outputs (``left``) it left as they were, and what it ``kept`` on purpose.

    Examples
    --------
    >>> interrupted_message()
    'interrupted: nothing saved'
    >>> interrupted_message(["results"])
    "interrupted: nothing saved; 'results' left as it was"
    """
    said = "; ".join(f"kept {k}" for k in kept) if kept else "nothing saved"
    if left:
        said += "; " + ", ".join(repr(str(p)) for p in dict.fromkeys(left)) + " left as it was"
    return f"interrupted: {said}"


@contextmanager
def interrupts() -> Iterator[None]:
    """Run the ``mrsus`` command so that Ctrl-C and SIGTERM stop it fast and cleanly.

    The first SIGINT or SIGTERM raises :class:`~mrsuspension._pool.Interrupted` (a
    ``KeyboardInterrupt``) in the command: its pools stop their workers at once and its
    output folders are discarded as the exception unwinds; later signals are ignored, so
    a second Ctrl-C cannot break the cleanup. Then one line
    (:func:`interrupted_message`) goes to stderr and the process exits with 130 (SIGINT)
    or 143 (SIGTERM), without a traceback, and without waiting for threads of stopped
    pools (``os._exit``). A command that handles the interrupt itself and ends normally
    keeps its own exit code.

    Examples
    --------
    >>> with interrupts():
    ...     print("runs as usual")
    runs as usual
    """
    from mrsuspension._output import discarded
    from mrsuspension._pool import handle_signals

    before, kept = len(discarded), len(_KEPT)
    with handle_signals() as state:
        try:
            yield
        except KeyboardInterrupt as exc:  # raised outside typer's own handling
            signum = getattr(exc, "signum", state.signum or signal.SIGINT)
            _exit_interrupted(signum, discarded[before:], _KEPT[kept:])
        except SystemExit as exc:  # typer turns KeyboardInterrupt into exit code 130
            signum = state.signum or _raised_signal(exc)
            if signum is None or exc.code != 130:
                raise
            _exit_interrupted(signum, discarded[before:], _KEPT[kept:])


def _raised_signal(exc: BaseException) -> int | None:
    """The signal of an :class:`~mrsuspension._pool.Interrupted` a command raised itself
    (e.g. after stopping a run the safe way), found in ``exc``'s chain of causes."""
    seen: set[int] = set()
    cause: BaseException | None = exc
    while cause is not None and id(cause) not in seen:
        seen.add(id(cause))
        signum = getattr(cause, "signum", None)
        if isinstance(cause, KeyboardInterrupt) and isinstance(signum, int):
            return signum
        cause = cause.__cause__ or cause.__context__
    return None


def _exit_interrupted(signum: int, left: Sequence[Path], kept: Sequence[str]) -> None:
    print(interrupted_message(left, kept), file=sys.stderr)
    for stream in (sys.stdout, sys.stderr):
        with suppress(OSError, ValueError):  # a closed pipe
            stream.flush()
    os._exit(128 + signum)
