"""User-error handling shared by the ``mrsus`` commands (one line on stderr, exit code 2)."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import typer

from mrsuspension.errors import MRSuspensionError

__all__ = ["_user_errors"]


@contextmanager
def _user_errors() -> Iterator[None]:
    """Turn a :class:`~mrsuspension.errors.MRSuspensionError` into one line and exit code 2.

    Covers :class:`~mrsuspension.errors.ValidationError` and
    :class:`~mrsuspension.engine.simulate.SimulationDiverged`; anything else is a bug and
    keeps its traceback.
    """
    try:
        yield
    except MRSuspensionError as exc:
        message = " ".join(str(exc).split())
        typer.echo(f"error: {message}", err=True)
        raise typer.Exit(2) from None
