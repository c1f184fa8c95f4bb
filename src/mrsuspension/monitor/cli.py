"""``mrsus monitor``: serve the HiL browser monitor with uvicorn."""

from __future__ import annotations

import ipaddress
import secrets
import webbrowser
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any

import typer

from mrsuspension.errors import ValidationError

if TYPE_CHECKING:
    from mrsuspension.monitor.app import AttachedRun

__all__ = ["check_bind", "check_rig", "is_loopback", "monitor_command", "serve"]


def is_loopback(host: str) -> bool:
    """Whether ``host`` is a loopback address (``localhost`` counts)."""
    if host.strip().lower() == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def check_bind(host: str, token: str | None) -> None:
    """Refuse to bind off loopback without an access token.

    Raises
    ------
    ValidationError
        When ``host`` is not loopback and ``token`` is empty or missing.
    """
    if not is_loopback(host) and not token:
        raise ValidationError(
            f"binding the monitor to {host!r} (not loopback) needs an access token: "
            f"--token {secrets.token_urlsafe(16)} (then open the page with ?token=...)"
        )


def check_rig(spec: str) -> str:
    """Validate a ``--rig`` spec (a UDP rig is pinged); returns it normalised.

    Raises
    ------
    ValidationError
        For an unknown rig, a bad ``udp://HOST:PORT`` or a UDP rig that does not answer.
    """
    from mrsuspension.dampers import WangSymmetric
    from mrsuspension.hil.cli import make_rig

    rig = make_rig(spec, WangSymmetric())
    rig.close()
    spec = spec.strip()
    return spec if spec.lower().startswith("udp://") else spec.lower()


def serve(
    host: str,
    port: int,
    token: str | None,
    *,
    rig: str = "simulated",
    attach: AttachedRun | None = None,
    road_dir: Path | None = None,
    open_browser: bool = False,
    workdir: Path | None = None,
    url_to_stderr: bool = False,
    realtime: str = "auto",
    isolate: bool = False,
) -> None:
    """Serve the monitor with uvicorn until Ctrl-C (checks the bind and the rig first).

    The monitor's address is printed on stdout (on stderr with ``url_to_stderr``, when
    stdout carries JSON).
    """
    check_bind(host, token)
    rig = check_rig(rig)
    if road_dir is not None and not road_dir.is_dir():
        raise ValidationError(f"--road-dir {road_dir} is not a directory")
    import uvicorn

    from mrsuspension.monitor.app import create_app

    app = create_app(
        token=token, workdir=workdir, rig=rig, attach=attach, road_dir=road_dir,
        realtime=realtime, isolate=isolate,
    )  # fmt: skip
    shown = "localhost" if is_loopback(host) else host
    url = f"http://{shown}:{port}/" + (f"?token={token}" if token else "")
    typer.echo(f"mrsus monitor ({rig} rig): {url}", err=url_to_stderr)
    kwargs: dict[str, Any] = {"host": host, "port": port, "log_level": "warning"}
    from mrsuspension.hil.realtime import yield_loop_cpu

    # the server (and a browser it opens) keep off the core the loop pins itself to;
    # the loop processes it starts get every core back and pin themselves there
    with yield_loop_cpu() as cpus:
        app.state.monitor.loop_cpus = cpus
        if open_browser:
            webbrowser.open(url)
        uvicorn.run(app, **kwargs)


def monitor_command(
    host: Annotated[str, typer.Option(help="address to bind (loopback unless --token)")] = (
        "127.0.0.1"
    ),
    port: Annotated[int, typer.Option(help="TCP port")] = 8765,
    token: Annotated[
        str | None,
        typer.Option(help="access token required in the URL (?token=...); needed off loopback"),
    ] = None,
    open_browser: Annotated[bool, typer.Option(help="open the page in a browser")] = False,
    rig: Annotated[
        str, typer.Option(help="rig in the loop: simulated | ideal | udp://HOST:PORT")
    ] = "simulated",
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
            "back afterwards (needs --realtime auto, fifo or spin; docs/hil.md)",
        ),
    ] = False,
) -> None:
    """Serve the HiL browser monitor (live plots, measures, STOP, recording).

    Runs started from the page are HiL runs (`run_hil`) with the --rig rig in the loop,
    in their own process; settings changed on the page are applied between ticks.
    """
    from mrsuspension._cli_errors import _user_errors

    with _user_errors():
        serve(
            host, port, token, rig=rig, road_dir=road_dir, open_browser=open_browser,
            workdir=workdir, realtime=realtime, isolate=isolate,
        )  # fmt: skip
