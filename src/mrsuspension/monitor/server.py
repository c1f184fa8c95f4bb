"""Serving the HiL browser monitor with uvicorn (``mrsus monitor``, ``mrsus hil run --monitor``).

Library code behind those commands: the bind check (loopback unless an access token),
the rig check and :func:`serve`. The command functions live in :mod:`mrsuspension.cli`.
"""

from __future__ import annotations

import ipaddress
import secrets
import sys
import webbrowser
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mrsuspension.errors import ValidationError

if TYPE_CHECKING:
    from mrsuspension.monitor.app import AttachedRun

__all__ = ["check_bind", "check_rig", "is_loopback", "serve"]


def is_loopback(host: str) -> bool:
    """Whether ``host`` is a loopback address (``localhost`` counts).

    Examples
    --------
    >>> is_loopback("localhost"), is_loopback("::1"), is_loopback("0.0.0.0")
    (True, True, False)
    """
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

    Examples
    --------
    >>> check_bind("127.0.0.1", None)
    >>> check_bind("0.0.0.0", "secret")
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

    Examples
    --------
    >>> check_rig(" Ideal ")
    'ideal'
    """
    from mrsuspension.dampers import WangSymmetric
    from mrsuspension.hil.rigs import make_rig, normalise_rig_spec

    rig = make_rig(spec, WangSymmetric())
    rig.close()
    return normalise_rig_spec(spec)


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
    print(
        f"mrsus monitor ({rig} rig): {url}",
        file=sys.stderr if url_to_stderr else sys.stdout,
        flush=True,
    )
    kwargs: dict[str, Any] = {"host": host, "port": port, "log_level": "warning"}
    from mrsuspension.hil.realtime import yield_loop_cpu

    # the server (and a browser it opens) keep off the core the loop pins itself to;
    # the loop processes it starts get every core back and pin themselves there
    with yield_loop_cpu() as cpus:
        app.state.monitor.loop_cpus = cpus
        if open_browser:
            webbrowser.open(url)
        uvicorn.run(app, **kwargs)
