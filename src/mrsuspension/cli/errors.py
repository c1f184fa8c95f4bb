"""User-error handling shared by the ``mrsus`` commands (one line on stderr, exit code 2)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import typer

from mrsuspension.errors import MRSuspensionError

__all__ = ["user_errors"]


@contextmanager
def user_errors() -> Iterator[None]:
    """Turn a :class:`~mrsuspension.errors.MRSuspensionError` into one line and exit code 2.

    Covers :class:`~mrsuspension.errors.ValidationError` and
    :class:`~mrsuspension.engine.simulate.SimulationDiverged`; anything else is a bug and
    keeps its traceback.

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
        message = " ".join(str(exc).split())
        typer.echo(f"error: {message}", err=True)
        raise typer.Exit(2) from None
