"""User-error handling shared by the ``mrsus`` commands (one line on stderr, exit code 2)."""

from __future__ import annotations

import re
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from typing import Any

import typer

from mrsuspension.errors import MRSuspensionError

__all__ = ["option_named", "user_errors"]

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
