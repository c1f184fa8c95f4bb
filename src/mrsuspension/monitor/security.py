"""The monitor's web security: who may talk to it, and what it reads.

A browser lets any page it shows send requests to a server on ``127.0.0.1``; the
monitor drives a rig, so every request passes :class:`MonitorGate` (an ASGI middleware)
before it reaches a route:

- **Host** must be a loopback name (``127.0.0.1``, ``localhost``, ``[::1]``) with the
  port the server listens on; with an access token and a non-loopback bind, also the
  bound address (any name when bound to a wildcard address such as ``0.0.0.0``: the
  token guards it). A page on ``evil.example`` whose name its owner re-points to
  127.0.0.1 (DNS rebinding) sends ``Host: evil.example:PORT`` and is refused.
- **Origin**, when a request carries one, must be the monitor's own
  (``http://`` + its Host); a WebSocket handshake from another origin is refused
  (HTTP 403, before the socket is accepted).
- **Fetch metadata**: a request for anything but the page itself (``/``) marked
  ``Sec-Fetch-Site: cross-site`` or ``same-site`` by the browser is refused.
- **State changes** (every method but GET, HEAD, OPTIONS) need an ``Origin`` or a
  ``Referer`` of the monitor's own origin (403), ``Content-Type: application/json``
  (415: a ``text/plain`` or form body is never read) and a body of at most
  :data:`MAX_BODY` bytes (413, read in chunks; never buffered beyond the limit).
- **Access token** (when set): every request carries it in the cookie the page gets
  on its first load (``GET /?token=...`` sets an HttpOnly, SameSite=Strict cookie and
  redirects to the clean URL, so the page's script, styles, API calls and WebSocket
  carry it) or as ``?token=...`` (scripts); compared in constant time. A browser the
  server opens itself gets a one-time ``?login=...`` instead (:meth:`MonitorGate`'s
  ``logins``), so that the token never shows in that browser's command line. A token comes
  from a file (``--token-file``) or the environment (:data:`TOKEN_ENV`), has at least
  :data:`MIN_TOKEN_LENGTH` characters and is checked by :func:`check_token`.

Refusals are one line of JSON, ``{"error": "..."}``, naming what was refused and why.
:func:`loads_json` parses request bodies: at most :data:`MAX_DEPTH` levels of nesting,
finite numbers only, integers of at most 18 digits; anything else is a
:class:`~mrsuspension.errors.ValidationError` (400), never a 500.
"""

from __future__ import annotations

import hmac
import ipaddress
import json
import math
import os
import re
import stat
from collections.abc import Mapping
from http.cookies import SimpleCookie
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlsplit

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from mrsuspension.errors import ValidationError

__all__ = [
    "LOOPBACK_NAMES",
    "MAX_BODY",
    "MAX_DEPTH",
    "MIN_TOKEN_LENGTH",
    "TOKEN_ENV",
    "MonitorGate",
    "check_token",
    "cookie_name",
    "loads_json",
    "resolve_token",
]

#: environment variable an access token may come from
TOKEN_ENV = "MRSUS_MONITOR_TOKEN"
#: shortest access token accepted [characters]
MIN_TOKEN_LENGTH = 16
#: largest request body accepted [bytes] (the page's settings are well under 2 KiB)
MAX_BODY = 64 * 1024
#: deepest nesting of a JSON request body (the page sends a flat object)
MAX_DEPTH = 16
#: Host names the monitor answers to on any bind
LOOPBACK_NAMES = frozenset({"127.0.0.1", "localhost", "::1"})
#: the characters of a token (URL-unreserved: safe in a URL, a cookie and a file)
_TOKEN_CHARS = re.compile(r"[A-Za-z0-9._~-]+")
_SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})
_MAX_INT_DIGITS = 18
_WILDCARDS = frozenset({"", "0.0.0.0", "::"})


def check_token(token: str, what: str = "the access token") -> str:
    """``token`` checked: at least 16 URL-unreserved characters.

    Raises
    ------
    ValidationError
        When it is shorter or holds other characters.

    Examples
    --------
    >>> check_token("a" * 16) == "a" * 16
    True
    >>> check_token("short")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: the access token has 5 characters; use at least 16 ...
    """
    hint = (
        "e.g. python -c 'import secrets; print(secrets.token_urlsafe(24))' > token.txt, "
        "then --token-file token.txt"
    )
    if len(token) < MIN_TOKEN_LENGTH:
        raise ValidationError(
            f"{what} has {len(token)} characters; use at least {MIN_TOKEN_LENGTH} ({hint})"
        )
    if not _TOKEN_CHARS.fullmatch(token):
        raise ValidationError(
            f"{what} holds characters other than A-Z a-z 0-9 - . _ ~ (use only those; {hint})"
        )
    return token


def resolve_token(
    token: str | None,
    token_file: str | Path | None,
    environ: Mapping[str, str] | None = None,
) -> tuple[str | None, str | None]:
    """The access token from ``--token-file``, ``--token`` or :data:`TOKEN_ENV`, checked.

    At most one of ``token`` and ``token_file`` may be given; without either, the
    environment variable is read (empty: no token).

    Returns
    -------
    token : str or None
        The checked token (None: no token).
    warning : str or None
        One line to print when the token was given on the command line (where any user
        of the machine can read it, e.g. with ``ps``).

    Raises
    ------
    ValidationError
        For both options, an unreadable or empty file, or a token :func:`check_token`
        refuses.

    Examples
    --------
    >>> resolve_token(None, None, {})
    (None, None)
    >>> resolve_token(None, None, {"MRSUS_MONITOR_TOKEN": "x" * 20})[0] == "x" * 20
    True
    """
    env = os.environ if environ is None else environ
    if token is not None and token_file is not None:
        raise ValidationError("give --token-file or --token, not both (--token-file is safer)")
    if token_file is not None:
        path = Path(token_file)
        try:
            text = path.read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            why = getattr(exc, "strerror", None) or str(exc)
            raise ValidationError(f"--token-file {str(path)!r}: cannot read it ({why})") from None
        value = text.strip()
        if not value:
            raise ValidationError(f"--token-file {str(path)!r} is empty; write the token in it")
        return check_token(value, f"the token in --token-file {str(path)!r}"), None
    if token is not None:
        if not token.strip():
            raise ValidationError("--token must not be empty (omit it for a loopback monitor)")
        warning = (
            "warning: --token on the command line is visible to every user of this machine "
            f"(ps); use --token-file FILE or the environment variable {TOKEN_ENV}"
        )
        return check_token(token, "--token"), warning
    value = env.get(TOKEN_ENV, "").strip()
    if not value:
        return None, None
    return check_token(value, f"the token in {TOKEN_ENV}"), None


def token_file_warning(path: str | Path) -> str | None:
    """A warning when the token file can be read by other users (None: it cannot).

    Examples
    --------
    >>> import tempfile
    >>> f = Path(tempfile.mkdtemp()) / "t"
    >>> _ = f.write_text("x" * 20)
    >>> f.chmod(0o600)
    >>> token_file_warning(f) is None
    True
    """
    try:
        mode = Path(path).stat().st_mode
    except OSError:
        return None
    if mode & (stat.S_IRGRP | stat.S_IROTH):
        return (
            f"warning: --token-file {str(path)!r} can be read by other users; "
            f"chmod 600 {str(path)!r}"
        )
    return None


def loads_json(body: bytes, max_depth: int = MAX_DEPTH) -> Any:
    """Parse a request body: UTF-8 JSON, nested at most ``max_depth`` levels, finite numbers.

    Raises
    ------
    ValidationError
        For anything else (bad JSON, too deep, ``NaN``/``Infinity``, a number that
        overflows a float, an integer of more than 18 digits), with the reason.

    Examples
    --------
    >>> loads_json(b'{"a": [1, 2.5]}')
    {'a': [1, 2.5]}
    >>> loads_json(b'{"a": 1e999}')
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: bad request: number 1e999 is not finite ...
    >>> loads_json(b"[" * 40 + b"]" * 40)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: bad request: JSON nested deeper than 16 levels ...
    """
    try:
        text = body.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ValidationError(f"bad request: the body is not UTF-8 ({exc.reason})") from None
    depth = _depth(text)
    if depth > max_depth:
        raise ValidationError(
            f"bad request: JSON nested deeper than {max_depth} levels (found {depth}); "
            "send a flat object of the form's fields"
        )

    def number(s: str) -> float:
        value = float(s)
        if not math.isfinite(value):
            raise ValueError(f"number {s[:40]} is not finite (it overflows a float)")
        return value

    def integer(s: str) -> int:
        if len(s.lstrip("-")) > _MAX_INT_DIGITS:
            raise ValueError(
                f"integer {s[:24]}... has more than {_MAX_INT_DIGITS} digits; "
                "give a number within range"
            )
        return int(s)

    def constant(s: str) -> Any:
        raise ValueError(f"{s} is not a number; give a finite value")

    try:
        return json.loads(text, parse_float=number, parse_int=integer, parse_constant=constant)
    except (ValueError, RecursionError) as exc:
        raise ValidationError(f"bad request: {exc}") from None


def _depth(text: str) -> int:
    """Deepest bracket nesting of a JSON text (outside strings), without parsing it."""
    depth = deepest = 0
    in_string = escaped = False
    for ch in text:
        if in_string:
            if escaped:
                escaped = False
            elif ch == "\\":
                escaped = True
            elif ch == '"':
                in_string = False
        elif ch == '"':
            in_string = True
        elif ch in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif ch in "]}":
            depth -= 1
    return deepest


def cookie_name(port: int | None) -> str:
    """Name of the access cookie of the monitor on ``port`` (cookies ignore the port).

    Examples
    --------
    >>> cookie_name(8765)
    'mrsus_monitor_8765'
    """
    return f"mrsus_monitor_{port or 0}"


def _split_host(value: str) -> tuple[str, int | None] | None:
    """``(name, port)`` of a Host header (IPv6 in brackets); None when malformed."""
    value = value.strip().lower()
    if not value:
        return None
    if value.startswith("["):
        end = value.find("]")
        if end < 0:
            return None
        name, rest = value[1:end], value[end + 1 :]
        if rest and not rest.startswith(":"):
            return None
        port_text = rest[1:] if rest else ""
    else:
        name, _, port_text = value.partition(":")
    if port_text:
        if not port_text.isdigit() or len(port_text) > 5:
            return None
        return name.rstrip("."), int(port_text)
    return name.rstrip("."), None


def _origin_of(url: str) -> tuple[str, str, int] | None:
    """``(scheme, name, port)`` of an Origin or Referer value (None: ``null`` or malformed)."""
    try:
        parts = urlsplit(url.strip())
        port = parts.port
    except ValueError:
        return None
    if parts.scheme not in ("http", "https") or not parts.hostname:
        return None
    default = 443 if parts.scheme == "https" else 80
    return parts.scheme, parts.hostname.lower().rstrip("."), port or default


def _bind_names(bind_host: str) -> frozenset[str] | None:
    """Extra Host names of a non-loopback bind (None: any, a wildcard address)."""
    host = bind_host.strip().strip("[]").lower()
    if host in _WILDCARDS:
        return None
    try:
        if ipaddress.ip_address(host).is_unspecified:
            return None
    except ValueError:
        pass
    return frozenset({host})


class MonitorGate:
    """ASGI middleware: the checks of this module on every HTTP request and WebSocket.

    Parameters
    ----------
    app : ASGI app
        The monitor's routes.
    token : str, optional
        Access token (None: none; then only loopback Host names are accepted).
    bind_host : str
        The address the server binds to (with a token, its name is accepted as Host;
        a wildcard bind accepts any name).
    max_body : int
        Largest request body [bytes].
    logins : set of str, optional
        One-time login codes: ``GET /?login=CODE`` sets the token's cookie like
        ``/?token=...`` and removes the code (for a browser the server opens itself,
        whose command line any user can read). Shared with the caller, who adds codes.
    """

    def __init__(
        self,
        app: ASGIApp,
        token: str | None = None,
        bind_host: str = "127.0.0.1",
        max_body: int = MAX_BODY,
        logins: set[str] | None = None,
    ) -> None:
        self.app = app
        self.token = token.encode() if token else None
        self.max_body = int(max_body)
        self.logins = logins if logins is not None else set()
        self.names: frozenset[str] | None = LOOPBACK_NAMES
        if token:
            extra = _bind_names(bind_host)
            self.names = None if extra is None else LOOPBACK_NAMES | extra

    # -- the checks ------------------------------------------------------------------------
    def _host(self, scope: Scope, headers: dict[str, str]) -> tuple[str, int | None] | str:
        """The request's (name, port), or why its Host is refused."""
        raw = headers.get("host", "")
        parsed = _split_host(raw)
        server = scope.get("server")
        served = int(server[1]) if server and server[1] is not None else None
        if self.names is None:
            allowed = "any name (token required)"
        else:
            allowed = ", ".join(
                sorted(f"[{n}]" if ":" in n else n for n in self.names)
            )  # fmt: skip
        where = f" on port {served}" if served is not None else ""
        why = (
            f"Host {raw!r} refused: the monitor answers to {allowed}{where} "
            "(a guard against DNS rebinding)"
        )
        if parsed is None:
            return why
        name, port = parsed
        if port is None:
            port = 443 if scope.get("scheme") in ("https", "wss") else 80
        if self.names is not None and name not in self.names:
            return why
        if served is not None and port != served:
            return why
        return name, port

    def _own(self, scope: Scope, host: tuple[str, int | None], value: str) -> bool:
        origin = _origin_of(value)
        if origin is None:
            return False
        scheme = "https" if scope.get("scheme") in ("https", "wss") else "http"
        return origin == (scheme, host[0], host[1])

    def _token_given(self, scope: Scope, headers: dict[str, str]) -> tuple[bool, bool]:
        """(valid token in the cookie, valid token in the query)."""
        assert self.token is not None
        server = scope.get("server")
        name = cookie_name(int(server[1]) if server and server[1] is not None else None)
        in_cookie = in_query = False
        cookie_header = headers.get("cookie", "")
        if cookie_header:
            jar: SimpleCookie = SimpleCookie()
            try:
                jar.load(cookie_header)
            except Exception:  # a malformed cookie header is no token
                jar = SimpleCookie()
            if name in jar:
                in_cookie = hmac.compare_digest(jar[name].value.encode(), self.token)
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        given = (query.get("token") or [""])[0]
        if given:
            in_query = hmac.compare_digest(given.encode(), self.token)
        return in_cookie, in_query

    def _login(self, scope: Scope) -> bool:
        """Whether the query holds a one-time login code (then used up)."""
        query = parse_qs(scope.get("query_string", b"").decode("latin-1"))
        given = (query.get("login") or [""])[0].encode()
        for code in list(self.logins):
            if given and hmac.compare_digest(given, code.encode()):
                self.logins.discard(code)
                return True
        return False

    # -- ASGI ------------------------------------------------------------------------------
    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        kind = scope["type"]
        if kind not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        if kind == "websocket":
            await self._websocket(scope, receive, send, headers)
            return
        method = scope.get("method", "GET").upper()
        path = scope.get("path", "/")
        host = self._host(scope, headers)
        if isinstance(host, str):
            await _refuse(send, 403, host)
            return
        origin = headers.get("origin")
        if origin is not None and not self._own(scope, host, origin):
            await _refuse(send, 403, f"Origin {origin!r} refused: only the monitor's own page")
            return
        site = headers.get("sec-fetch-site", "").lower()
        if path != "/" and site in ("cross-site", "same-site"):
            await _refuse(send, 403, f"a request from another site ({site}) refused")
            return
        if self.token is not None:
            in_cookie, in_query = self._token_given(scope, headers)
            first = path == "/" and method == "GET"
            if first and (in_query or self._login(scope)):  # first load: cookie, clean URL
                await _redirect_with_cookie(send, scope, self.token.decode())
                return
            if not (in_cookie or in_query):
                await _refuse(
                    send,
                    403,
                    "access token required: open the address mrsus monitor printed "
                    "(http://HOST:PORT/?token=...)",
                )
                return
        send = _with_headers(send)
        if method in _SAFE_METHODS:
            await self.app(scope, receive, send)
            return
        if origin is None:
            referer = headers.get("referer")
            if referer is None or not self._own(scope, host, referer):
                await _refuse(
                    send,
                    403,
                    f"{method} {path} refused: a state change needs an Origin (or Referer) "
                    "header of the monitor's own page",
                )
                return
        ctype = headers.get("content-type", "").split(";", 1)[0].strip().lower()
        if ctype != "application/json":
            await _refuse(
                send,
                415,
                f"Content-Type {ctype or 'none'!r} refused: {method} {path} takes "
                "application/json only",
            )
            return
        length = headers.get("content-length")
        if length is not None and (not length.isdigit() or int(length) > self.max_body):
            await _refuse(send, 413, _too_large(length, self.max_body))
            return
        body = await _read_body(receive, self.max_body)
        if body is None:
            await _refuse(send, 413, _too_large(None, self.max_body))
            return
        await self.app(scope, _replay(body, receive), send)

    async def _websocket(
        self, scope: Scope, receive: Receive, send: Send, headers: dict[str, str]
    ) -> None:
        host = self._host(scope, headers)
        ok = not isinstance(host, str)
        origin = headers.get("origin")
        if ok and origin is not None:
            ok = self._own(scope, host, origin)  # type: ignore[arg-type]
        if ok and self.token is not None:
            ok = any(self._token_given(scope, headers))
        if not ok:  # before accept: the client gets HTTP 403
            await send({"type": "websocket.close", "code": 1008})
            return
        await self.app(scope, receive, send)


#: added to every response the routes send: no framing by another page (clickjacking)
_PAGE_HEADERS = (
    (b"x-frame-options", b"DENY"),
    (b"content-security-policy", b"frame-ancestors 'none'"),
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"same-origin"),
)


def _with_headers(send: Send) -> Send:
    async def wrapped(message: Message) -> None:
        if message["type"] == "http.response.start":
            message = {**message, "headers": [*message.get("headers", []), *_PAGE_HEADERS]}
        await send(message)

    return wrapped


def _too_large(length: str | None, limit: int) -> str:
    given = f" ({length} bytes)" if length and length.isdigit() else ""
    return f"request body too large{given}: at most {limit} bytes ({limit // 1024} KiB)"


async def _refuse(send: Send, status: int, message: str) -> None:
    body = json.dumps({"error": message}).encode()
    await send(
        {
            "type": "http.response.start",
            "status": status,
            "headers": [
                (b"content-type", b"application/json"),
                (b"content-length", str(len(body)).encode()),
                (b"cache-control", b"no-store"),
            ],
        }
    )
    await send({"type": "http.response.body", "body": body})


async def _redirect_with_cookie(send: Send, scope: Scope, token: str) -> None:
    server = scope.get("server")
    name = cookie_name(int(server[1]) if server and server[1] is not None else None)
    cookie = f"{name}={token}; Path=/; HttpOnly; SameSite=Strict"
    await send(
        {
            "type": "http.response.start",
            "status": 303,
            "headers": [
                (b"location", b"/"),
                (b"set-cookie", cookie.encode()),
                (b"cache-control", b"no-store"),
                (b"referrer-policy", b"no-referrer"),
                (b"content-length", b"0"),
            ],
        }
    )
    await send({"type": "http.response.body", "body": b""})


async def _read_body(receive: Receive, limit: int) -> bytes | None:
    """The request body, read in its chunks; None as soon as it passes ``limit`` bytes."""
    chunks: list[bytes] = []
    size = 0
    while True:
        message = await receive()
        if message["type"] != "http.request":
            return b"".join(chunks)  # a disconnect: the route sees a short body
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > limit:
            return None
        chunks.append(chunk)
        if not message.get("more_body", False):
            return b"".join(chunks)


def _replay(body: bytes, receive: Receive) -> Receive:
    sent = False

    async def replay() -> Message:
        nonlocal sent
        if not sent:
            sent = True
            return {"type": "http.request", "body": body, "more_body": False}
        return await receive()

    return replay
