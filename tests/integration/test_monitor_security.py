"""Issue 26 section 2: the monitor's web security, over a real server (uvicorn, in a thread).

Host (DNS rebinding), Origin, content type, body limits, JSON limits, one run at a time,
the access token, and (section 3) a new session never writing over an earlier one's
runs. The browser's side (a cross-origin page in chromium) is tests/browser.
"""

from __future__ import annotations

import json
import multiprocessing
import socket
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mrsuspension.errors import ValidationError

uvicorn = pytest.importorskip("uvicorn")

TOKEN = "tok-" + "a1b2c3d4" * 3  # 28 characters


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class Served:
    """A monitor app served by uvicorn in a thread."""

    def __init__(self, app: Any) -> None:
        self.app = app
        self.state = app.state.monitor
        self.port = _free_port()
        self.origin = f"http://127.0.0.1:{self.port}"
        config = uvicorn.Config(app, host="127.0.0.1", port=self.port, log_level="warning")
        self.server = uvicorn.Server(config)
        self.thread = threading.Thread(target=self.server.run, daemon=True)
        self.thread.start()
        deadline = time.monotonic() + 20
        while not self.server.started:
            assert time.monotonic() < deadline, "the server did not start"
            time.sleep(0.02)

    def close(self) -> None:
        self.server.should_exit = True
        self.thread.join(30)

    def raw(
        self,
        method: str,
        path: str,
        headers: dict[str, str] | None = None,
        body: bytes = b"",
        *,
        host: str | None = None,
    ) -> tuple[int, dict[str, str], bytes]:
        """One HTTP/1.1 request on a raw socket (any Host header); status, headers, body."""
        head = {"Host": host or f"127.0.0.1:{self.port}", "Connection": "close"}
        head.update(headers or {})
        if body and "Content-Length" not in head and "Transfer-Encoding" not in head:
            head["Content-Length"] = str(len(body))
        lines = [f"{method} {path} HTTP/1.1", *(f"{k}: {v}" for k, v in head.items())]
        with socket.create_connection(("127.0.0.1", self.port), timeout=30) as s:
            s.sendall(("\r\n".join(lines) + "\r\n\r\n").encode() + body)
            data = b""
            while True:
                try:
                    chunk = s.recv(65536)
                except ConnectionResetError:
                    break
                if not chunk:
                    break
                data += chunk
        return _parse(data)

    def post(
        self, path: str, body: Any, **headers: str
    ) -> tuple[int, dict[str, str], dict[str, Any]]:
        """A JSON state change from the monitor's own origin (headers override)."""
        head = {"Origin": self.origin, "Content-Type": "application/json"}
        head.update({k.replace("_", "-"): v for k, v in headers.items()})
        data = body if isinstance(body, bytes) else json.dumps(body).encode()
        code, h, raw = self.raw("POST", path, head, data)
        return code, h, json.loads(raw) if raw else {}

    def wait_idle(self, timeout: float = 90.0) -> None:
        """Until the current run's loop process has ended (and the server has seen it)."""
        deadline = time.monotonic() + timeout
        h = self.state.handle
        while h is not None and (h.alive() or self.state.status.get("state") != "ended"):
            assert time.monotonic() < deadline, f"the run did not end: {self.state.status}"
            time.sleep(0.05)


def _parse(data: bytes) -> tuple[int, dict[str, str], bytes]:
    head, _, body = data.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    code = int(lines[0].split()[1])
    headers: dict[str, str] = {}
    for line in lines[1:]:
        k, _, v = line.partition(":")
        headers[k.strip().lower()] = v.strip()
    if headers.get("transfer-encoding") == "chunked":
        out, rest = b"", body
        while rest:
            size_line, _, rest = rest.partition(b"\r\n")
            size = int(size_line, 16)
            if size == 0:
                break
            out, rest = out + rest[:size], rest[size + 2 :]
        body = out
    return code, headers, body


def _earlier_session(work: Path) -> Path:
    """A work directory holding an earlier session's run-001 and a user's run-002.csv."""
    (work / "run-001").mkdir(parents=True)
    (work / "run-001" / "meta.json").write_text('{"earlier": "session"}\n')
    (work / "run-001" / "notes.txt").write_text("my notes on run 1\n")
    (work / "run-002.csv").write_text("time,x\n0,1\n")
    return work


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Served]:
    from mrsuspension.monitor.app import create_app

    work = tmp_path_factory.mktemp("monitor-work")
    s = Served(create_app(workdir=work, rig="ideal", realtime="off"))
    yield s
    s.close()


def _nothing_started(served: Served) -> None:
    assert served.state.handle is None, "a run was started"
    assert served.state.run_id == 0
    assert served.state.status["state"] == "idle"


@pytest.mark.audit("monitor origin")
def test_dns_rebinding_host_is_refused(served: Served) -> None:
    """A page on another name resolved to 127.0.0.1 sends its own Host: refused."""
    evil = f"evil.example:{served.port}"
    code, _, body = served.raw("GET", "/api/status", host=evil)
    assert code == 403
    error = json.loads(body)["error"]
    assert "Host 'evil.example" in error
    assert "DNS rebinding" in error
    code, _, _ = served.raw("GET", "/", host=evil)
    assert code == 403
    code, _, body = served.raw(
        "POST", "/api/start", {"Origin": f"http://{evil}", "Content-Type": "application/json"},
        b'{"duration": 1}', host=evil,
    )  # fmt: skip
    assert code == 403
    # the right name on another port (a proxy's, a rebinding to another port) too
    assert served.raw("GET", "/api/status", host=f"127.0.0.1:{served.port + 1}")[0] == 403
    assert served.raw("GET", "/api/status", host="127.0.0.1")[0] == 403  # port 80
    for ok in (f"127.0.0.1:{served.port}", f"localhost:{served.port}", f"[::1]:{served.port}"):
        assert served.raw("GET", "/api/status", host=ok)[0] == 200, ok
    _nothing_started(served)
    print(f"Host {evil}: 403 {error}")


@pytest.mark.audit("monitor origin")
def test_state_changes_need_the_monitors_own_origin_and_json(served: Served) -> None:
    """Cross-origin, origin-less, text/plain and form requests start nothing."""
    body = {"duration": 1}
    cases = [
        ({"Origin": f"http://127.0.0.1:{served.port + 1}"}, 403, "Origin"),  # another port
        ({"Origin": "http://localhost:" + str(served.port)}, 403, "Origin"),  # another name
        ({"Origin": "null"}, 403, "Origin"),  # a sandboxed frame, a file: page
        ({"Origin": ""}, 403, "Origin"),
        # a text/plain body (a no-cors fetch or a text/plain form) is never read as JSON
        ({"Content-Type": "text/plain;charset=UTF-8"}, 415, "application/json"),
        ({"Content-Type": "application/x-www-form-urlencoded"}, 415, "application/json"),
        ({"Content-Type": "multipart/form-data; boundary=x"}, 415, "application/json"),
    ]
    for path in ("/api/start", "/api/stop", "/api/apply", "/api/record", "/api/acquisition"):
        for headers, code, fragment in cases:
            got, h, info = served.post(path, body, **headers)
            assert (got, fragment in info.get("error", "")) == (code, True), (path, headers, info)
            assert h["content-type"] == "application/json"
    # no Origin and no Referer: not the page
    code, _, raw = served.raw(
        "POST", "/api/start", {"Content-Type": "application/json"}, b'{"duration": 1}'
    )
    assert code == 403
    assert "Origin (or Referer)" in json.loads(raw)["error"]
    # a Referer of another origin is not the page's either
    code, _, raw = served.raw(
        "POST", "/api/start",
        {"Content-Type": "application/json", "Referer": "http://evil.example/x"},
        b'{"duration": 1}',
    )  # fmt: skip
    assert code == 403
    # the browser's fetch metadata: a read of the API from another site is refused
    code, _, _ = served.raw("GET", "/api/status", {"Sec-Fetch-Site": "cross-site"})
    assert code == 403
    code, _, _ = served.raw("GET", "/api/recording", {"Sec-Fetch-Site": "same-site"})
    assert code == 403
    _nothing_started(served)
    # the page itself: its own origin (or Referer) and JSON pass the gate
    code, _, info = served.post("/api/acquisition", {"acq_period": 1})
    assert code == 200, info
    code, _, raw = served.raw(
        "POST", "/api/record",
        {"Content-Type": "application/json; charset=utf-8",
         "Referer": served.origin + "/"},
        b'{"action": "pause"}',
    )  # fmt: skip
    assert code == 400
    assert "unknown record action" in json.loads(raw)["error"]
    # nor can the page be framed by another (clickjacking)
    _, headers, _ = served.raw("GET", "/")
    assert headers["x-frame-options"] == "DENY"
    assert "frame-ancestors 'none'" in headers["content-security-policy"]


@pytest.mark.audit("monitor origin")
def test_websocket_from_another_origin_is_refused(served: Served) -> None:
    pytest.importorskip("websockets")
    from websockets.exceptions import InvalidStatus
    from websockets.sync.client import connect

    url = f"ws://127.0.0.1:{served.port}/ws"
    for origin in (f"http://127.0.0.1:{served.port + 1}", "http://evil.example", "null"):
        with pytest.raises(InvalidStatus) as info:
            connect(url, origin=origin, open_timeout=10)  # type: ignore[arg-type]
        assert info.value.response.status_code == 403, origin
    with pytest.raises(InvalidStatus):  # DNS rebinding on the WebSocket
        connect(url, additional_headers={"Host": f"evil.example:{served.port}"}, open_timeout=10)
    with connect(url, origin=served.origin, open_timeout=10) as ws:  # type: ignore[arg-type]
        frame = json.loads(ws.recv(timeout=10))
    assert frame["status"]["state"] == "idle"


@pytest.mark.audit("monitor limits")
def test_body_size_is_limited_without_reading_it_whole(served: Served) -> None:
    from mrsuspension.monitor.security import MAX_BODY

    head = {"Origin": served.origin, "Content-Type": "application/json"}
    # a 400 MB body announced: refused before a byte of it is read
    t0 = time.monotonic()
    code, _, raw = served.raw("POST", "/api/start", {**head, "Content-Length": str(400 << 20)})
    assert code == 413
    assert "at most 65536 bytes" in json.loads(raw)["error"]
    assert time.monotonic() - t0 < 10
    # streamed (chunked, no length): refused once past the limit, 1 MB offered
    chunk = b" " * 8192
    payload = b"".join(b"%x\r\n%s\r\n" % (len(chunk), chunk) for _ in range(128)) + b"0\r\n\r\n"
    code, _, raw = served.raw(
        "POST", "/api/apply", {**head, "Transfer-Encoding": "chunked"}, payload
    )
    assert code == 413
    # just within the limit: read, and judged by the parser (400, not 413)
    body = b'{"sprung_mass": -5, "pad": "' + b"x" * (MAX_BODY - 40) + b'"}'
    assert len(body) <= MAX_BODY
    code, _, info = served.post("/api/start", body)
    assert code == 400, info
    assert "sprung_mass" in info["error"]
    _nothing_started(served)


@pytest.mark.audit("monitor limits")
def test_deep_nesting_and_huge_numbers_are_400_not_500(served: Served) -> None:
    bodies = {
        "nested 20000 deep": b'{"a": ' + b"[" * 20000 + b"]" * 20000 + b"}",
        "nested objects": b'{"a": ' + b'{"b": ' * 5000 + b"1" + b"}" * 5000 + b"}",
        "1e999": b'{"sprung_mass": 1e999}',
        "-1e400": b'{"duration": -1e400}',
        "NaN": b'{"sprung_mass": NaN}',
        "Infinity": b'{"frequency": Infinity}',
        "4000 digits": b'{"sprung_mass": ' + b"9" * 4000 + b"}",
        "5000 digits": b'{"acq_period": ' + b"9" * 5000 + b"}",
        "not UTF-8": b'{"a": "\xff\xfe"}',
        "not an object": b"[1, 2]",
        "broken": b'{"a": ',
    }
    for name, body in bodies.items():
        for path in ("/api/start", "/api/apply", "/api/acquisition", "/api/record"):
            code, _, info = served.post(path, body)
            assert code == 400, (name, path, code, info)
            assert info["error"], (name, path)
    # finite but absurd: the validators' ranges (400 with the field named)
    for path, body in (
        ("/api/start", b'{"sprung_mass": 1e300}'),
        ("/api/start", b'{"duration": 999999999999999999}'),
        ("/api/acquisition", b'{"acq_period": 1e300}'),
        ("/api/acquisition", b'{"pre_trigger": -1e300}'),
    ):
        code, _, info = served.post(path, body)
        assert code == 400, (path, body, info)
    code, _, info = served.post("/api/start", bodies["nested 20000 deep"])
    print(f"nested: {info['error']}")
    code, _, info = served.post("/api/start", bodies["1e999"])
    print(f"1e999: {info['error']}")
    _nothing_started(served)


@pytest.fixture(scope="module")
def session(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    """A new session beside an earlier one's runs: eight starts at once, and STOP.

    STOP is pressed while the start that wins is still being handled (its validation
    made 0.5 s slower here, to widen the window). The work (one real loop process) is
    done once here; the two tests below check what it shows: one run at a time, STOP
    stops it (monitor limits); the earlier session's files are kept (user files).
    """
    from mrsuspension.monitor.app import create_app

    earlier = _earlier_session(tmp_path_factory.mktemp("session") / "work")
    snapshot = {p: p.read_bytes() for p in earlier.rglob("*") if p.is_file()}
    served = Served(create_app(workdir=earlier, rig="ideal", realtime="off"))
    validate = served.state.validate

    def slow_validate(raw: dict[str, Any]) -> Any:
        time.sleep(0.5)
        return validate(raw)

    served.state.validate = slow_validate  # type: ignore[method-assign]
    n = 8
    barrier = threading.Barrier(n)
    results: list[tuple[int, dict[str, Any]]] = []
    lock = threading.Lock()

    def start() -> None:
        barrier.wait()
        code, _, info = served.post("/api/start", {"duration": 30, "excitation": "harmonic"})
        with lock:
            results.append((code, info))

    try:
        threads = [threading.Thread(target=start) for _ in range(n)]
        for t in threads:
            t.start()
        deadline = time.monotonic() + 30
        while not served.state.lock.locked():  # a start is being handled: press STOP
            assert time.monotonic() < deadline, "no start was handled"
            time.sleep(0.002)
        stop = served.post("/api/stop", {})
        for t in threads:
            t.join(60)
        h = served.state.handle
        alive = h is not None and h.alive()
        # a start while that run goes: 409 too (never a second loop)
        again = served.post("/api/start", {"duration": 30})
        served.wait_idle()
        recording = served.raw("GET", "/api/recording")
        loops = [p.name for p in multiprocessing.active_children() if p.name.startswith("mrsus")]
        state = dict(served.state.status)
    finally:
        served.close()
    return {
        "n": n, "results": results, "alive": alive, "handle": h, "again": again,
        "stop": stop, "state": state, "loops": loops, "recording": recording,
        "earlier": earlier, "snapshot": snapshot,
    }  # fmt: skip


@pytest.mark.audit("monitor limits")
def test_concurrent_starts_give_one_run_and_stop_stops_it(session: dict[str, Any]) -> None:
    """Eight starts at once: one run, seven 409; STOP ends that loop; no loop is left."""
    n, results = session["n"], session["results"]
    codes = sorted(code for code, _ in results)
    assert codes == [200] + [409] * (n - 1), results
    started = next(info for code, info in results if code == 200)
    refused = [info["error"] for code, info in results if code == 409]
    assert all("one run at a time" in e for e in refused), refused
    assert session["alive"]  # the one run was going when the next start came
    code, _, info = session["again"]
    assert code == 409
    assert "press STOP" in info["error"]
    # STOP, pressed while that start was being handled, reached the loop it launched
    assert session["stop"][0] == 200
    assert session["stop"][2]["state"] == "stopping"
    assert not session["handle"].alive()
    assert session["state"]["reason"] == "STOP pressed"
    assert session["state"]["ticks"] < 5000  # stopped at once, not after its 30 s
    assert session["loops"] == []  # no loop process left behind
    print(f"{n} concurrent starts: {codes}; run {started['run']} stopped: STOP pressed")


@pytest.mark.audit("user files")
def test_a_new_session_never_writes_over_an_earlier_sessions_runs(
    session: dict[str, Any],
) -> None:
    """``monitor --workdir``: run-001 (an earlier session's) and run-002.csv stay as they are."""
    earlier: Path = session["earlier"]
    started = next(info for code, info in session["results"] if code == 200)
    assert started["run"] == 3  # 1 and 2 are taken (a folder, a CSV)
    code, _, raw = session["recording"]
    assert code == 200
    assert raw.startswith(b"time,")
    out = earlier / "run-003"
    assert (out / "meta.json").exists()  # the new run's recording, in a new folder
    assert (earlier / "run-003.csv").exists()  # and its CSV beside it
    for path, data in session["snapshot"].items():  # nothing the earlier session wrote
        assert path.read_bytes() == data, f"{path} was changed"
    kept = sorted(str(p.relative_to(earlier)) for p in session["snapshot"])
    print(f"earlier files kept: {kept}; the new run: {out.name}")


@pytest.mark.audit("monitor limits")
def test_stop_reaches_a_running_loop_at_once_while_a_start_is_handled(tmp_path: Path) -> None:
    """A start holding the lock (validating slow settings) never delays STOP of the run."""
    from mrsuspension.monitor.app import MonitorState

    class Loop:  # the server's view of a running loop process: alive until stopped
        def __init__(self) -> None:
            self.stopped = threading.Event()

        def alive(self) -> bool:
            return True

        def stop(self, code: int = 1) -> None:
            self.stopped.set()

    st = MonitorState(tmp_path, rig="ideal")
    loop = Loop()
    st.handle = loop  # type: ignore[assignment]
    st.status["state"] = "running"
    st.lock.acquire()  # a start is being handled
    try:
        stopper = threading.Thread(target=st.stop, daemon=True)
        t0 = time.monotonic()
        stopper.start()
        assert loop.stopped.wait(5.0), "STOP waited for the start"
        waited = time.monotonic() - t0
        assert st.status["state"] == "stopping"
    finally:
        st.lock.release()
    stopper.join(5.0)
    assert not stopper.is_alive()
    print(f"STOP reached the running loop in {1e3 * waited:.1f} ms while a start held the lock")


def test_reserving_a_run_skips_taken_names(tmp_path: Path) -> None:
    from mrsuspension.monitor.app import MonitorState

    (tmp_path / "run-001").mkdir()
    (tmp_path / "run-002.csv").write_text("x")
    (tmp_path / "run-003").symlink_to(tmp_path / "elsewhere")  # a dangling link
    st = MonitorState(tmp_path, rig="ideal")
    assert st._reserve_run() == (4, tmp_path / "run-004")
    st.run_id = 4
    assert st._reserve_run() == (5, tmp_path / "run-005")
    assert not (tmp_path / "elsewhere").exists()


# -- the access token ----------------------------------------------------------------------


@pytest.fixture(scope="module")
def tokened(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Served]:
    from mrsuspension.monitor.app import create_app

    s = Served(create_app(token=TOKEN, workdir=tmp_path_factory.mktemp("tok"), rig="ideal"))
    yield s
    s.close()


@pytest.mark.audit("monitor origin")
def test_token_page_sets_a_cookie_that_its_script_styles_and_socket_carry(
    tokened: Served,
) -> None:
    # without the token: the page, its static files, the API and the socket are refused
    for path in ("/", "/static/monitor.js", "/static/monitor.css", "/api/status", "/api/vehicles"):
        assert tokened.raw("GET", path)[0] == 403, path
        assert tokened.raw("GET", path + "?token=" + "x" * len(TOKEN))[0] == 403, path
    # the first load with the token: a cookie (HttpOnly, SameSite=Strict), the clean URL
    code, headers, _ = tokened.raw("GET", f"/?token={TOKEN}")
    assert code == 303
    assert headers["location"] == "/"
    cookie = headers["set-cookie"]
    assert f"mrsus_monitor_{tokened.port}={TOKEN}" in cookie
    assert "HttpOnly" in cookie
    assert "SameSite=Strict" in cookie
    jar = {"Cookie": cookie.split(";", 1)[0]}
    # a browser the server opens itself gets a one-time login code, never the token
    tokened.app.state.logins.add("one-time-code-0123456789")
    code, headers, _ = tokened.raw("GET", "/?login=one-time-code-0123456789")
    assert code == 303
    assert headers["set-cookie"].split(";", 1)[0] == jar["Cookie"]
    assert tokened.raw("GET", "/?login=one-time-code-0123456789")[0] == 403  # used up
    for path in ("/", "/static/monitor.js", "/static/monitor.css", "/api/status", "/api/vehicles"):
        assert tokened.raw("GET", path, jar)[0] == 200, path
    # a state change with the cookie still needs the monitor's own origin
    head = {**jar, "Content-Type": "application/json"}
    code, _, _ = tokened.raw(
        "POST", "/api/stop", {**head, "Origin": f"http://127.0.0.1:{tokened.port + 1}"}, b"{}"
    )
    assert code == 403
    assert tokened.raw("POST", "/api/stop", {**head, "Origin": tokened.origin}, b"{}")[0] == 200
    pytest.importorskip("websockets")
    from websockets.exceptions import InvalidStatus
    from websockets.sync.client import connect

    url = f"ws://127.0.0.1:{tokened.port}/ws"
    with pytest.raises(InvalidStatus):  # no token
        connect(url, origin=tokened.origin, open_timeout=10)  # type: ignore[arg-type]
    with connect(url, origin=tokened.origin, additional_headers=jar, open_timeout=10) as ws:  # type: ignore[arg-type]
        assert "status" in json.loads(ws.recv(timeout=10))


@pytest.mark.audit("monitor origin")
def test_token_from_a_file_or_the_environment_with_a_minimum_length(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from typer.testing import CliRunner

    from mrsuspension.cli import app
    from mrsuspension.cli.monitor import monitor_token
    from mrsuspension.monitor.security import TOKEN_ENV, resolve_token

    good = tmp_path / "token.txt"
    good.write_text(TOKEN + "\n")
    good.chmod(0o600)
    assert resolve_token(None, good, {}) == (TOKEN, None)
    assert resolve_token(None, None, {TOKEN_ENV: TOKEN}) == (TOKEN, None)
    value, warning = resolve_token(TOKEN, None, {})
    assert value == TOKEN
    assert warning is not None
    assert "ps" in warning
    assert monitor_token(None, good) == TOKEN
    assert capsys.readouterr().err == ""  # a private file: no warning
    good.chmod(0o644)
    monitor_token(None, good)
    assert "can be read by other users" in capsys.readouterr().err
    short = tmp_path / "short.txt"
    short.write_text("tooshort\n")
    with pytest.raises(ValidationError, match="has 8 characters; use at least 16"):
        resolve_token(None, short, {})
    with pytest.raises(ValidationError, match=f"the token in {TOKEN_ENV} has 5 characters"):
        resolve_token(None, None, {TOKEN_ENV: "short"})
    with pytest.raises(ValidationError, match="characters other than"):
        resolve_token("a b;c=d" * 4, None, {})
    with pytest.raises(ValidationError, match="not both"):
        resolve_token(TOKEN, good, {})
    # the commands: one line, exit 2, before anything is served
    runner = CliRunner()
    port = str(_free_port())
    for args, env, fragment in (
        (["monitor", "--port", port, "--token", "short"], {}, "--token has 5 characters"),
        (["monitor", "--port", port, "--token-file", str(short)], {}, "has 8 characters"),
        (["monitor", "--port", port, "--token-file", str(tmp_path / "none")], {}, "cannot read"),
        (["monitor", "--port", port], {TOKEN_ENV: "short"}, f"{TOKEN_ENV} has 5"),
        (["monitor", "--port", port, "--host", "0.0.0.0"], {}, "--token-file FILE"),
    ):
        result = runner.invoke(app, args, env=env)
        lines = [ln for ln in result.stderr.splitlines() if ln.strip()]
        assert result.exit_code == 2, (args, result.stderr)
        assert len(lines) == 1, lines
        assert lines[0].startswith("error:")
        assert fragment in lines[0]
