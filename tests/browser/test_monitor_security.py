"""Issue 26 section 2 in chromium: a page of another origin cannot drive or read the monitor.

Two monitors are served (uvicorn, in threads): one on loopback without a token, one with
an access token whose page the browser has opened (so the browser holds its cookie).
An attacker's page is served by a third server on another port, i.e. another origin
(same site: 127.0.0.1, so a SameSite=Strict cookie still goes with its requests). It
tries what the audit did: no-cors POSTs with text/plain JSON, CORS POSTs, form POSTs
(text/plain and urlencoded), reading the status, a WebSocket. A recording wrapper around
each app notes what reached it and what it answered. DNS rebinding: chromium resolves
``rebind.example`` to 127.0.0.1 (conftest), so a page of that name reaches the monitor
with ``Host: rebind.example:PORT``.
"""

from __future__ import annotations

import http.server
import json
import socket
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

pytestmark = pytest.mark.browser

TOKEN = "browser-token-" + "0123456789abcdef"

ATTACK_PAGE = """<!doctype html><html><body><iframe name="sink"></iframe><script>
async function attack(t, wsUrl) {
  const out = {};
  const body = JSON.stringify({duration: 5, excitation: "harmonic", controller: "passive"});
  for (const p of ["api/start", "api/apply", "api/stop", "api/record", "api/acquisition"]) {
    try {
      const r = await fetch(t + p, {method: "POST", mode: "no-cors", credentials: "include",
                                    headers: {"Content-Type": "text/plain"}, body});
      out["no-cors " + p] = r.type + " " + r.status + " " + (await r.text()).length;
    } catch (e) { out["no-cors " + p] = "failed"; }
    try {
      const r = await fetch(t + p, {method: "POST", credentials: "include",
                                    headers: {"Content-Type": "application/json"}, body});
      out["cors " + p] = "READ " + r.status + " " + await r.text();
    } catch (e) { out["cors " + p] = "blocked"; }
  }
  try { const r = await fetch(t + "api/status", {credentials: "include"});
        out["read status"] = "READ " + await r.text(); }
  catch (e) { out["read status"] = "blocked"; }
  try { const r = await fetch(t + "api/status", {mode: "no-cors", credentials: "include"});
        out["no-cors status"] = r.type + " " + (await r.text()).length; }
  catch (e) { out["no-cors status"] = "failed"; }
  out.ws = await new Promise((resolve) => {
    let got = 0;
    const ws = new WebSocket(wsUrl);
    ws.onmessage = () => { got++; };
    ws.onclose = (ev) => resolve("closed " + ev.code + " after " + got + " messages");
    setTimeout(() => { resolve("open after " + got + " messages"); ws.close(); }, 5000);
  });
  for (const enc of ["text/plain", "application/x-www-form-urlencoded"]) {
    await new Promise((resolve) => {
      const f = document.createElement("form");
      f.method = "POST"; f.enctype = enc; f.target = "sink"; f.action = t + "api/start";
      const i = document.createElement("input");
      i.name = '{"duration": 5, "x": "'; i.value = '"}';
      f.appendChild(i); document.body.appendChild(f);
      const frame = document.querySelector("iframe");
      frame.onload = () => resolve(); setTimeout(resolve, 5000);
      f.submit();
    });
    out["form " + enc] = "sent";
  }
  return out;
}
</script></body></html>
"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class Recorded:
    """ASGI wrapper noting (method, path, status, cookie sent, origin) of each request."""

    def __init__(self, app: Any) -> None:
        self.app = app
        self.state = app.state.monitor
        self.seen: list[dict[str, Any]] = []

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        if scope["type"] not in ("http", "websocket"):
            await self.app(scope, receive, send)
            return
        headers = {k.decode().lower(): v.decode("latin-1") for k, v in scope["headers"]}
        entry = {
            "kind": scope["type"], "method": scope.get("method", "WS"), "path": scope["path"],
            "origin": headers.get("origin"), "cookie": "mrsus_monitor_" in headers.get("cookie", ""),
            "status": None,
        }  # fmt: skip
        self.seen.append(entry)

        async def noting(message: Any) -> None:
            if message["type"] == "http.response.start":
                entry["status"] = message["status"]
            elif message["type"] == "websocket.close" and entry["status"] is None:
                entry["status"] = 403  # closed before accept: the handshake is refused
            elif message["type"] == "websocket.accept":
                entry["status"] = 101
            await send(message)

        await self.app(scope, receive, noting)


class Served:
    def __init__(self, app: Any) -> None:
        uvicorn = pytest.importorskip("uvicorn")
        self.app = Recorded(app)
        self.state = self.app.state
        self.port = _free_port()
        self.base = f"http://127.0.0.1:{self.port}/"
        self.server = uvicorn.Server(
            uvicorn.Config(self.app, host="127.0.0.1", port=self.port, log_level="warning")
        )
        self.thread = threading.Thread(target=self.server.run, daemon=True)
        self.thread.start()
        deadline = time.monotonic() + 20
        while not self.server.started:
            assert time.monotonic() < deadline, "the monitor did not start"
            time.sleep(0.02)

    def close(self) -> None:
        self.server.should_exit = True
        self.thread.join(30)


@pytest.fixture(scope="module")
def monitors(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Served]]:
    from mrsuspension.monitor.app import create_app

    work = tmp_path_factory.mktemp("monitors")
    served = {
        "plain": Served(create_app(workdir=work / "plain", rig="ideal", realtime="off")),
        "token": Served(
            create_app(token=TOKEN, workdir=work / "token", rig="ideal", realtime="off")
        ),
    }
    yield served
    for s in served.values():
        s.close()


@pytest.fixture(scope="module")
def attacker() -> Iterator[str]:
    """The attacker's page, served on another port: another origin."""
    page = ATTACK_PAGE.encode()

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self) -> None:
            self.send_response(200)
            self.send_header("Content-Type", "text/html")
            self.send_header("Content-Length", str(len(page)))
            self.end_headers()
            self.wfile.write(page)

        def log_message(self, *args: Any) -> None:
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/"
    server.shutdown()
    thread.join(10)


@pytest.fixture(scope="module")
def context(browser: Any, monitors: dict[str, Served]) -> Iterator[Any]:
    """A browser context that has opened the token monitor's page (it holds the cookie)."""
    ctx = browser.new_context()
    yield ctx
    ctx.close()


def _open_token_page(context: Any, served: Served) -> tuple[Any, list[tuple[str, int]]]:
    page = context.new_page()
    responses: list[tuple[str, int]] = []
    page.on("response", lambda r: responses.append((r.url, r.status)))
    page.goto(served.base + f"?token={TOKEN}")
    page.wait_for_function(
        "() => window.monitorState && window.monitorState.frames > 0", timeout=20000
    )
    page.wait_for_selector("#start:not([disabled])", timeout=20000)
    return page, responses


def _no_run_started(served: Served, before: int) -> None:
    st = served.state
    assert st.run_id == before, f"a run was started: {st.status}"
    assert st.handle is None or not st.handle.alive()


@pytest.mark.audit("monitor origin")
def test_a_cross_origin_page_cannot_start_stop_apply_or_read(
    monitors: dict[str, Served], attacker: str, context: Any
) -> None:
    token_page, _ = _open_token_page(context, monitors["token"])  # the victim's open page
    assert context.cookies()  # the browser holds the monitor's cookie
    before = {name: s.state.run_id for name, s in monitors.items()}
    page = context.new_page()
    page.goto(attacker)
    results = {}
    for name, served in monitors.items():
        n_seen = len(served.app.seen)
        out = page.evaluate(
            "([t, ws]) => attack(t, ws)", [served.base, f"ws://127.0.0.1:{served.port}/ws"]
        )
        results[name] = out
        print(f"{name} monitor, the attacker's page saw: {json.dumps(out, indent=1)}")
        # nothing could be read
        for key, value in out.items():
            assert not str(value).startswith("READ"), (name, key, value)
        assert out["read status"] == "blocked"
        assert out["no-cors status"] == "opaque 0"  # an opaque answer: no byte readable
        assert out["ws"].startswith("closed"), out["ws"]
        assert "after 0 messages" in out["ws"]
        # what reached the monitor: every request refused, none passed to a route
        seen = served.app.seen[n_seen:]
        print(f"{name} monitor, what reached it: {seen}")
        posts = [e for e in seen if e["method"] == "POST"]
        assert len(posts) >= 7  # 5 no-cors fetches and 2 forms reached it
        assert all(e["status"] == 403 for e in seen), seen
        assert any(e["kind"] == "websocket" and e["status"] == 403 for e in seen)
        assert all(e["origin"] == attacker.rstrip("/") for e in posts)
        if name == "token":  # the forms carried the cookie: the Origin check refused them
            assert any(e["cookie"] for e in posts), posts
        _no_run_started(served, before[name])
    # the victim's page is still served and unaffected
    assert token_page.evaluate("() => window.monitorState.status.state") == "idle"
    page.close()
    token_page.close()


@pytest.mark.audit("monitor origin")
def test_dns_rebinding_page_is_refused(
    monitors: dict[str, Served], context: Any, rebind_name: str
) -> None:
    """A page whose name now resolves to 127.0.0.1 reaches the monitor with its own Host."""
    served = monitors["plain"]
    before = served.state.run_id
    page = context.new_page()
    response = page.goto(f"http://{rebind_name}:{served.port}/")
    assert response is not None
    assert response.status == 403
    assert "DNS rebinding" in (page.text_content("body") or "")
    # same origin now for the page: its requests still carry Host rebind.example
    out = page.evaluate(
        """async () => {
          const r = await fetch("/api/start", {method: "POST",
            headers: {"Content-Type": "application/json"}, body: '{"duration": 5}'});
          const s = await fetch("/api/status");
          return [r.status, s.status, (await s.text()).includes("DNS rebinding")];
        }"""
    )
    assert out == [403, 403, True]
    _no_run_started(served, before)
    page.close()


@pytest.mark.audit("monitor origin")
def test_the_token_page_loads_its_script_and_styles_and_starts_a_run(
    monitors: dict[str, Served], context: Any, browser: Any
) -> None:
    served = monitors["token"]
    # without the token: refused
    other = browser.new_context()
    page = other.new_page()
    response = page.goto(served.base)
    assert response is not None
    assert response.status == 403
    other.close()
    # with it: the page, its script and styles load (cookie), the address is clean
    page, responses = _open_token_page(context, served)
    assert page.url == served.base  # the token is not left in the address bar
    statuses = {url.split(str(served.port), 1)[1]: code for url, code in responses}
    print(f"the token page's requests: {statuses}")
    assert statuses["/"] == 200
    assert statuses["/static/monitor.js"] == 200
    assert statuses["/static/monitor.css"] == 200
    assert statuses["/api/controllers"] == 200
    assert statuses["/api/vehicles"] == 200
    assert page.evaluate("() => getComputedStyle(document.body).fontFamily") != ""
    cookie = next(c for c in context.cookies() if c["name"] == f"mrsus_monitor_{served.port}")
    assert cookie["httpOnly"] is True
    assert cookie["sameSite"] == "Strict"
    assert page.evaluate("() => document.cookie") == ""  # HttpOnly: no script reads it
    # a run started from the page
    before = served.state.run_id
    page.select_option("#controller", "passive")
    page.click("#start")
    page.wait_for_function(
        "() => document.getElementById('note').textContent === 'run started'", timeout=20000
    )
    assert served.state.run_id == before + 1
    assert served.state.handle is not None
    page.click("#stop")
    deadline = time.monotonic() + 90
    while served.state.handle.alive() or served.state.status.get("state") != "ended":
        assert time.monotonic() < deadline, served.state.status
        time.sleep(0.05)
    assert served.state.status["reason"] == "STOP pressed"
    page.wait_for_function("() => window.monitorState.status.state === 'ended'", timeout=20000)
    page.close()
