"""``mrsus monitor``: serve the HiL browser monitor (:mod:`mrsuspension.monitor.server`)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from mrsuspension._docs import doc
from mrsuspension.cli.errors import user_errors
from mrsuspension.hil.rigs import rig_syntax

__all__ = ["monitor_command", "monitor_token"]


def monitor_token(token: str | None, token_file: Path | None) -> str | None:
    """The monitor's access token from ``--token-file``, ``--token`` or the environment.

    Checked (:func:`~mrsuspension.monitor.security.resolve_token`); a warning goes to
    stderr for a token given on the command line or a file other users can read.
    """
    from mrsuspension.monitor.security import resolve_token, token_file_warning

    value, warning = resolve_token(token, token_file)
    if token_file is not None:
        warning = token_file_warning(token_file)
    if warning:
        typer.echo(warning, err=True)
    return value


def monitor_command(
    host: Annotated[str, typer.Option(help="address to bind (loopback unless --token)")] = (
        "127.0.0.1"
    ),
    port: Annotated[int, typer.Option(help="TCP port")] = 8765,
    token_file: Annotated[
        Path | None,
        typer.Option(
            help="file holding the access token (at least 16 characters; else the "
            "environment variable MRSUS_MONITOR_TOKEN); needed off loopback"
        ),
    ] = None,
    token: Annotated[
        str | None,
        typer.Option(
            help="access token (visible to other users in ps: prefer --token-file or "
            "MRSUS_MONITOR_TOKEN)"
        ),
    ] = None,
    open_browser: Annotated[bool, typer.Option(help="open the page in a browser")] = False,
    rig: Annotated[str, typer.Option(help=f"rig in the loop: {rig_syntax()}")] = "simulated",
    road_dir: Annotated[
        Path | None, typer.Option(help="directory the page may take road profile files from")
    ] = None,
    workdir: Annotated[
        Path | None, typer.Option(help="directory for the recordings (default: a temporary one)")
    ] = None,
    realtime: Annotated[
        str,
        typer.Option(
            help="scheduling of the loop: auto (SCHED_FIFO when permitted) | fifo | spin "
            "(busy-wait on a pinned core; best on a virtual machine) | off"
        ),
    ] = "auto",
    isolate: Annotated[
        bool,
        typer.Option(
            "--isolate",
            help="move every other movable task off the loop's core during each run, and "
            f"back afterwards (needs --realtime auto, fifo or spin; {doc('hil')})",
        ),
    ] = False,
) -> None:
    """Serve the HiL browser monitor (live plots, measures, STOP, recording).

    Runs started from the page are HiL runs (`run_hil`) with the --rig rig in the loop,
    in their own process; settings changed on the page are applied between ticks.
    """
    from mrsuspension.cli.errors import keep_on_interrupt
    from mrsuspension.errors import check_host, require_extra

    with user_errors():
        require_extra("web", "the browser monitor")
    from mrsuspension.monitor.server import serve

    def kept(folder: Path) -> None:  # named in the `interrupted:` line of a Ctrl-C
        keep_on_interrupt(
            f"the runs recorded in {str(folder)!r} (a running loop stopped the safe way)"
        )

    with user_errors():
        check_host("--host", host)
        token = monitor_token(token, token_file)
        end = serve(
            host, port, token, rig=rig, road_dir=road_dir, open_browser=open_browser,
            workdir=workdir, realtime=realtime, isolate=isolate, on_serve=kept,
        )  # fmt: skip
    if end.stopped_run and end.signum is not None:  # one `interrupted:` line, 128 + signal
        from mrsuspension._pool import Interrupted

        raise Interrupted(end.signum)
