"""Serving the HiL browser monitor with uvicorn (``mrsus monitor``, ``mrsus hil run --monitor``).

Library code behind those commands: the bind check (loopback unless an access token),
the rig check and :func:`serve`. The command functions live in :mod:`mrsuspension.cli`.
The web security (Host, Origin, content type, body size, token) is
:mod:`mrsuspension.monitor.security`.
"""

from __future__ import annotations

import errno
import ipaddress
import secrets
import signal
import sys
import threading
import webbrowser
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mrsuspension._output import check_output_folder
from mrsuspension.errors import (
    ValidationError,
    check_input_folder,
    check_port,
)

if TYPE_CHECKING:
    from mrsuspension.monitor.app import AttachedRun

__all__ = ["ServeEnd", "check_bind", "check_free", "check_rig", "is_loopback", "serve"]


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
            "--token-file FILE or the environment variable MRSUS_MONITOR_TOKEN (at least "
            "16 characters; e.g. python -c 'import secrets; print(secrets.token_urlsafe(24))')"
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


def check_free(host: str, port: int) -> None:
    """Refuse a ``host``/``port`` the monitor cannot bind (in use, or no such address).

    Probed with the options uvicorn binds with (``SO_REUSEADDR``), before the server
    starts, so that the error is one line rather than uvicorn's log and exit code 3.

    Examples
    --------
    >>> import socket
    >>> with socket.socket() as taken:
    ...     taken.bind(("127.0.0.1", 0))
    ...     taken.listen()
    ...     check_free("127.0.0.1", taken.getsockname()[1])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: --port ...: cannot listen on 127.0.0.1: ...
    """
    import socket

    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    except OSError as exc:
        raise ValidationError(f"--host {host!r}: no such address ({exc})") from None
    family, kind, proto, _, address = infos[0]
    try:
        with socket.socket(family, kind, proto) as probe:
            probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            probe.bind(address)
            probe.listen()
    except OSError as exc:
        why = "the port is in use" if exc.errno == errno.EADDRINUSE else exc.strerror
        raise ValidationError(
            f"--port {port}: cannot listen on {host}: {why}; choose another --port"
        ) from None


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
    on_serve: Callable[[Path], None] | None = None,
) -> ServeEnd:
    """Serve the monitor with uvicorn until Ctrl-C (checks the bind and the rig first).

    The monitor's address is printed on stdout (on stderr with ``url_to_stderr``, when
    stdout carries JSON). ``on_serve`` is called with the folder the runs record into
    once every check has passed, before the server starts.

    Returns
    -------
    ServeEnd
        The signal that shut the server down, and whether a run was stopped by it.
    """
    check_bind(host, token)
    if token:
        from mrsuspension.monitor.security import check_token

        check_token(token)
    check_port("--port", port)
    rig = check_rig(rig)
    if road_dir is not None:
        check_input_folder("--road-dir", road_dir)
    if workdir is not None:
        check_output_folder("--workdir", workdir)
    import uvicorn

    from mrsuspension.monitor.app import create_app

    # the app checks --realtime/--isolate: every option is judged before the port's use
    app = create_app(
        token=token, workdir=workdir, rig=rig, attach=attach, road_dir=road_dir,
        realtime=realtime, isolate=isolate, host=host,
    )  # fmt: skip
    check_free(host, port)
    shown = "localhost" if is_loopback(host) else host
    url = f"http://{shown}:{port}/" + (f"?token={token}" if token else "")
    print(
        f"mrsus monitor ({rig} rig): {url}",
        file=sys.stderr if url_to_stderr else sys.stdout,
        flush=True,
    )
    kwargs: dict[str, Any] = {
        "host": host,
        "port": port,
        "log_level": "warning",
        "ws_max_size": 64 * 1024,  # the page sends keep-alives only
        "server_header": False,
        "proxy_headers": False,  # no X-Forwarded-* from anyone: the monitor is not proxied
    }
    from mrsuspension.hil.realtime import yield_loop_cpu

    # the server (and a browser it opens) keep off the core the loop pins itself to;
    # the loop processes it starts get every core back and pin themselves there
    if on_serve is not None:
        on_serve(app.state.monitor.workdir)
    with yield_loop_cpu() as cpus:
        app.state.monitor.loop_cpus = cpus
        if open_browser:
            # a browser's command line is public (ps): it gets a one-time login code,
            # never the token
            opened = url
            if token:
                code = secrets.token_urlsafe(24)
                app.state.logins.add(code)
                opened = f"http://{shown}:{port}/?login={code}"
            webbrowser.open(opened)
        signum = _run_server(_server(uvicorn.Config(app, **kwargs)))
    return ServeEnd(signum, app.state.monitor.stopped_by_shutdown)


@dataclass(frozen=True)
class ServeEnd:
    """How :func:`serve` ended.

    Attributes
    ----------
    signum : int or None
        The signal that shut the server down (SIGINT, SIGTERM, SIGHUP); None when it
        stopped on its own.
    stopped_run : bool
        A run was going when the server shut down; its loop was stopped the safe way
        (rig to mid-stroke, current 0, recording kept).
    """

    signum: int | None
    stopped_run: bool


def _server(config: Any) -> Any:
    """A uvicorn server that remembers which signals shut it down."""
    import uvicorn

    class Server(uvicorn.Server):
        signals: list[int]

        def handle_exit(self, sig: int, frame: Any) -> None:
            self.signals.append(sig)
            super().handle_exit(sig, frame)

    server = Server(config)
    server.signals = []
    return server


def _run_server(server: Any) -> int | None:
    """Run a uvicorn server until a signal shuts it down; the first such signal, or None.

    uvicorn handles SIGINT and SIGTERM: it stops serving, runs the app's shutdown (which
    stops a running loop the safe way) and raises the signal again when done. Here that
    second delivery is taken (the command decides what the signal means: a run stopped,
    or only a server closed) and so is SIGHUP, which a closed terminal or a dropped SSH
    session sends and which would otherwise kill the server without its shutdown (unless
    it is ignored: ``nohup``).
    """
    main = threading.current_thread() is threading.main_thread()
    previous = signal.getsignal(signal.SIGHUP) if main else signal.SIG_IGN
    if previous != signal.SIG_IGN:
        signal.signal(signal.SIGHUP, server.handle_exit)
    try:
        server.run()
    except KeyboardInterrupt:  # the signal raised again once the server has stopped
        pass
    finally:
        if previous != signal.SIG_IGN:
            signal.signal(signal.SIGHUP, previous if previous is not None else signal.SIG_DFL)
    return server.signals[0] if server.signals else None
