"""One progress display for every long command: a bar on a terminal, plain lines in a log.

:func:`progress_bar` yields a ``progress(done, total, note=None)`` callback. On a terminal
it draws a rich bar on stderr; when stderr is not a terminal (a CI log, a file, a pipe)
it writes one plain line at most every few seconds (with the time left, estimated from
the pace so far), and a last line at the end, so a log shows progress without
carriage-return noise.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Protocol, TextIO

__all__ = [
    "PLAIN_EVERY",
    "ProgressCallback",
    "plain_status",
    "progress_bar",
]

#: seconds between two plain progress lines when stderr is not a terminal
PLAIN_EVERY = 5.0


class ProgressCallback(Protocol):
    """``progress(done, total, note=None)``: ``done`` of ``total`` steps, an optional note."""

    def __call__(self, done: int, total: int, note: str | None = None) -> None: ...


@contextmanager
def progress_bar(
    enabled: bool | Callable[..., None],
    label: str,
    *,
    stream: TextIO | None = None,
    every: float = PLAIN_EVERY,
) -> Iterator[Callable[..., None] | None]:
    """A progress display as a ``progress(done, total, note=None)`` callback.

    Parameters
    ----------
    enabled : bool or callable
        ``True``: show progress; ``False``: yield ``None`` (nothing shown); a callable is
        the caller's own callback and is yielded as it is.
    label : str
        What is progressing (``"sweep"``, ``"study s1 (40 runs)"``).
    stream : text stream, optional
        Where to write (default: ``sys.stderr``). A terminal gets a rich bar, anything
        else plain lines.
    every : float
        Seconds between two plain lines (the last state is always written at the end).

    Examples
    --------
    >>> import io
    >>> log = io.StringIO()
    >>> with progress_bar(True, "sweep", stream=log, every=0.0) as progress:
    ...     for k in range(1, 3):
    ...         progress(k, 2)
    >>> print(log.getvalue().strip())
    sweep: 1/2 (50 %), 0 s
    sweep: 2/2 (100 %), 0 s
    """
    if callable(enabled):
        yield enabled
        return
    if not enabled:
        yield None
        return
    out = sys.stderr if stream is None else stream
    if out.isatty():
        with _rich_bar(label, out) as bar:
            yield bar
        return
    start = time.monotonic()
    last: list[float] = [-float("inf")]
    state: list[tuple[int, int, str | None] | None] = [None]
    written: list[tuple[int, int, str | None] | None] = [None]

    def line(done: int, total: int, note: str | None) -> None:
        share = f" ({100 * done / total:.0f} %)" if total else ""
        extra = f", {note}" if note else ""
        elapsed = time.monotonic() - start
        left = ""
        if 0 < done < total and elapsed >= 1.0:  # an estimate once there is something to go by
            left = f", about {elapsed * (total - done) / done:.0f} s left"
        out.write(f"{label}: {done}/{total}{share}, {elapsed:.0f} s{left}{extra}\n")
        out.flush()
        written[0] = (done, total, note)

    def update(done: int, total: int, note: str | None = None) -> None:
        state[0] = (done, total, note)
        now = time.monotonic()
        if now - last[0] >= every:
            last[0] = now
            line(done, total, note)

    yield update
    if state[0] is not None and state[0] != written[0]:
        line(*state[0])


@contextmanager
def _rich_bar(label: str, stream: TextIO) -> Iterator[Callable[..., None]]:
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    with Progress(
        "[progress.description]{task.description}",
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=Console(file=stream),
        transient=False,
    ) as bar:
        task = bar.add_task(label, total=None)

        def update(done: int, total: int, note: str | None = None) -> None:
            description = label if note is None else f"{label}: {note}"
            bar.update(task, completed=done, total=total, description=description)

        yield update


def plain_status(
    stream: TextIO | None = None, *, every: float = PLAIN_EVERY
) -> Callable[[str], None]:
    """A ``status(message)`` callback writing ``"<elapsed> s  message"`` lines.

    For a log (stderr not a terminal): the first message at once, then at most one line
    every ``every`` seconds, so a long job shows it is alive without flooding the log.

    Examples
    --------
    >>> import io
    >>> log = io.StringIO()
    >>> say = plain_status(log, every=3600.0)
    >>> say("chapter 2"); say("chapter 3")
    >>> log.getvalue()
    '0 s  chapter 2\\n'
    """
    out = sys.stderr if stream is None else stream
    start = time.monotonic()
    last = [-float("inf")]

    def status(message: str) -> None:
        now = time.monotonic()
        if now - last[0] >= every:
            last[0] = now
            out.write(f"{now - start:.0f} s  {message}\n")
            out.flush()

    return status
