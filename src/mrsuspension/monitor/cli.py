"""``mrsus monitor``: serve the HiL browser monitor with uvicorn."""

from __future__ import annotations

import ipaddress
import secrets
import webbrowser
from typing import Annotated

import typer

from mrsuspension.errors import ValidationError

__all__ = ["check_bind", "is_loopback", "monitor_command"]


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
) -> None:
    """Serve the HiL browser monitor (live plots, measures, STOP, recording)."""
    check_bind(host, token)
    import uvicorn

    from mrsuspension.monitor.app import create_app

    app = create_app(token=token)
    shown = "localhost" if is_loopback(host) else host
    url = f"http://{shown}:{port}/" + (f"?token={token}" if token else "")
    typer.echo(f"mrsus monitor: {url}")
    if open_browser:
        webbrowser.open(url)
    uvicorn.run(app, host=host, port=port, log_level="warning")
