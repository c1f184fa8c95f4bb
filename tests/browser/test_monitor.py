"""HiL browser monitor in headless Debian chromium (Playwright sync API)."""

from __future__ import annotations

import json
import math
import socket
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from typing import Any

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.monitor.server import check_bind

pytestmark = pytest.mark.browser


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    uvicorn = pytest.importorskip("uvicorn")
    from mrsuspension.monitor.app import create_app

    port = _free_port()
    app = create_app(workdir=tmp_path_factory.mktemp("monitor"), rig="simulated")
    config = uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning")
    srv = uvicorn.Server(config)
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.time() + 10
    while not srv.started and time.time() < deadline:
        time.sleep(0.05)
    assert srv.started
    yield f"http://127.0.0.1:{port}/"
    srv.should_exit = True
    thread.join(10)


def test_token_rule() -> None:
    check_bind("127.0.0.1", None)
    check_bind("localhost", None)
    check_bind("::1", None)
    check_bind("0.0.0.0", "secret-secret-secret")
    with pytest.raises(ValidationError, match="token"):
        check_bind("0.0.0.0", None)
    with pytest.raises(ValidationError, match="token"):
        check_bind("192.168.1.5", "")


def test_token_gate() -> None:
    from starlette.testclient import TestClient

    from mrsuspension.monitor.app import create_app

    token = "s3cret-s3cret-s3cret"
    with TestClient(create_app(token=token), base_url="http://127.0.0.1:8765") as client:
        assert client.get("/").status_code == 403
        assert client.get("/?token=wrong").status_code == 403
        r = client.get(f"/?token={token}", follow_redirects=False)
        assert r.status_code == 303  # the cookie, then the clean URL
        assert client.get("/").status_code == 200  # with the cookie


def _status(server: str) -> dict[str, Any]:
    with urllib.request.urlopen(server + "api/status") as r:
        return dict(json.loads(r.read()))


def _wait(page: Any, js: str, timeout: float = 30000) -> None:
    page.wait_for_function(js, timeout=timeout)


def _posts(page: Any) -> list[str]:
    return list(page.evaluate("() => window.monitorState.posts"))


def test_acceptance_simulated_rig(
    server: str, browser: Any, tmp_path_factory: pytest.TempPathFactory
) -> None:
    """Issue 7: skyhook hi-lo ACM, 1.5 Hz harmonic, live m_s, invalid entries, STOP."""
    shots = tmp_path_factory.mktemp("artifacts")
    page = browser.new_page(viewport={"width": 1500, "height": 1100})
    page.goto(server)
    page.select_option("#controller", "skyhook-hilo")
    page.select_option("#mode", "ACM")
    page.select_option("#excitation", "harmonic")
    page.fill("#frequency", "1.5")
    page.fill("#amplitude", "0.02")
    page.click("#start")
    # plots update with values in the expected ranges
    _wait(
        page,
        "() => window.monitorState.status.state === 'running' && window.monitorState.points > 400"
        " && typeof window.monitorState.measures.T_as === 'number'",
        60000,
    )
    st = page.evaluate("() => window.monitorState")
    rng, status = st["range"], st["status"]
    assert status["rig"] == "simulated"
    assert -0.0205 < rng["z_r"][0] < -0.015
    assert 0.015 < rng["z_r"][1] < 0.0205
    assert rng["z_r_ddot"][1] == pytest.approx((2 * math.pi * 1.5) ** 2 * 0.02, rel=0.15)
    assert rng["i_cmd"][0] >= 0.0
    assert rng["i_cmd"][1] <= 0.3 + 1e-3
    assert rng["i_cmd"][1] > 0.2  # skyhook hi-lo switches to the high current
    assert rng["i_dm"][0] > -0.03
    assert rng["i_dm"][1] < 0.33
    assert 100.0 < max(abs(rng["F_dm"][0]), abs(rng["F_dm"][1])) < 8800.0
    assert 100.0 < max(abs(rng["F_dmod"][0]), abs(rng["F_dmod"][1])) < 8800.0
    assert -0.1 < rng["x_d"][0] < rng["x_d"][1] < 0.1
    assert 1000.0 < rng["F_T"][0] < rng["F_T"][1] < 15000.0  # about (m_s + m_u) g
    assert max(abs(rng["z_s_ddot"][0]), rng["z_s_ddot"][1]) < 20.0
    t_as = float(page.text_content("#measures-T_as") or "nan")
    assert 0.05 < t_as < 5.0
    dlc = float(page.text_content("#measures-DLC") or "nan")
    assert 0.0 < dlc < 1.0
    drawn = page.evaluate(
        "() => Array.from(document.querySelectorAll('#plots canvas')).map((c) => {"
        " const d = c.getContext('2d').getImageData(0, 30, c.width, c.height - 30).data;"
        " let n = 0; for (let i = 3; i < d.length; i += 4) if (d[i]) n++; return n; })"
    )
    assert len(drawn) == 11
    assert min(drawn[:10]) > 100  # every plot has a trace below its title
    # but the body's (heave, pitch, roll): streamed, NaN for a quarter car, nothing drawn
    assert drawn[10] == 0
    assert all(c in st["data"] for c in ("heave", "pitch", "roll"))
    ticks0 = _status(server)["ticks"]

    # invalid entries are refused in the page and never reach the loop
    posts = len(_posts(page))
    for selector, value, fragment in (
        ("#sprung_mass", "-5", "sprung_mass"),
        ("#frequency", "0", "frequency"),
    ):
        good = page.input_value(selector)
        page.fill(selector, value)
        page.click("#apply")
        _wait(page, "() => document.getElementById('error').textContent.length > 0", 5000)
        error = page.text_content("#error") or ""
        assert fragment in error
        assert "refused" in error
        page.fill(selector, good)
    page.select_option("#excitation", "road")
    page.fill("#profile", "bumpy")
    page.click("#apply")
    _wait(page, "() => document.getElementById('error').textContent.includes('preset')", 5000)
    assert "unknown road preset 'bumpy'" in (page.text_content("#error") or "")
    assert len(_posts(page)) == posts  # nothing was sent
    assert _status(server)["applied"] == 0
    page.fill("#profile", "smooth")
    page.select_option("#excitation", "harmonic")
    page.click("#apply")  # valid: applied (the same harmonic)
    _wait(page, "() => window.monitorState.status.applied >= 1", 30000)
    assert page.text_content("#error") == ""

    # m_s changed live (applied between ticks by the running loop)
    mean_ft = (
        "() => { const d = window.monitorState.data; const t = d.time, f = d.F_T;"
        " const t1 = t[t.length - 1]; let s = 0, n = 0;"
        " for (let i = 0; i < t.length; i++) if (t[i] > t1 - 2 / 1.5) { s += f[i]; n++; }"
        " return s / n; }"
    )
    ft_before = page.evaluate(mean_ft)
    page.fill("#sprung_mass", "700")
    page.click("#apply")
    _wait(page, "() => window.monitorState.status.applied >= 2", 30000)
    status = _status(server)
    assert status["fields"]["sprung_mass"] == 700.0
    assert status["state"] == "running"
    assert status["ticks"] > ticks0
    time.sleep(4.0)  # the body settles on the new static load
    ft_after = page.evaluate(mean_ft)
    dw = (700.0 - 563.0) * 9.81  # the tire carries the heavier body: +1344 N
    print(
        f"mean tire force over 2 cycles: {ft_before:.0f} -> {ft_after:.0f} N (+{dw:.0f} expected)"
    )
    assert ft_after - ft_before == pytest.approx(dw, rel=0.2)

    # record a window of about a second
    page.click("#record")
    _wait(page, "() => window.monitorState.acquisition.recording === true", 5000)
    time.sleep(1.0)
    page.click("#record")
    _wait(page, "() => window.monitorState.acquisition.windows.length === 1 && "
          "!window.monitorState.acquisition.recording", 5000)  # fmt: skip

    # a dropped browser connection does not stop or stall the run
    other = browser.new_page()
    other.goto(server)
    other.wait_for_function("() => window.monitorState.frames > 5", timeout=30000)
    # a page that connects mid-run gets the last seconds at once, then the stream
    assert other.evaluate("() => window.monitorState.points") > 300
    other.close()  # the socket drops without a goodbye
    before = _status(server)
    time.sleep(1.0)
    after = _status(server)
    assert after["state"] == "running"
    assert after["ticks"] - before["ticks"] > 500  # still ticking at about 1 kHz
    _wait(page, "() => window.monitorState.points > 900", 30000)  # page still updated

    # STOP: current 0 at once, safe state shown
    page.click("#stop")
    _wait(page, "() => window.monitorState.status.reason === 'STOP pressed'", 30000)
    assert "safe" in (page.text_content("#state") or "")
    assert "SAFE" in (page.text_content("#safety") or "")
    assert page.evaluate("() => window.monitorState.status.current") == 0.0
    _wait(page, "() => window.monitorState.status.state === 'ended'", 30000)
    assert "safe" in (page.text_content("#state") or "")
    shot = shots / "monitor-stopped.png"
    page.screenshot(path=str(shot), full_page=True)
    assert shot.stat().st_size > 10000
    print(f"screenshot: {shot}")

    # the recording: the acquired window, from the HiL recorder
    page.wait_for_selector("#download:not(.disabled)", timeout=5000)
    href = page.get_attribute("#download", "href")
    assert href
    with urllib.request.urlopen(server + href) as r:
        body = r.read().decode()
    lines = body.splitlines()
    assert lines[0].startswith("time,state,")
    assert 800 < len(lines) - 1 < 2500  # about one second at 1 kHz
    rows = [float(line.split(",")[0]) for line in lines[1:]]
    assert rows == sorted(rows)
    page.close()


def test_invalid_start_refused_in_the_page(server: str, browser: Any) -> None:
    page = browser.new_page()
    page.goto(server)
    page.wait_for_function("() => window.monitorState.frames > 0", timeout=30000)
    page.fill("#sprung_mass", "-5")
    # a run started elsewhere sends its fields: they fill the form, but never over what
    # the user typed
    _start_short_run(server, sprung_mass=611.0, suspension_stiffness=31234.0)
    page.wait_for_function(
        "() => Number(document.getElementById('suspension_stiffness').value) === 31234",
        timeout=30000,
    )
    assert page.input_value("#sprung_mass") == "-5"
    page.click("#start")
    page.wait_for_function(
        "() => document.getElementById('error').textContent.length > 0", timeout=30000
    )
    assert "sprung_mass" in (page.text_content("#error") or "")
    assert _posts(page) == []
    page.close()


def _start_short_run(server: str, **fields: float) -> None:
    """Start a 0.3 s run through the API (as another page would) and wait for its end."""
    req = urllib.request.Request(
        server + "api/start",
        data=json.dumps({"duration": 0.3, **fields}).encode(),
        headers={"Content-Type": "application/json", "Origin": server.rstrip("/")},
        method="POST",
    )
    urllib.request.urlopen(req).read()
    deadline = time.monotonic() + 60.0
    while _status(server)["state"] not in ("ended", "error"):
        assert time.monotonic() < deadline, "the short run did not end"
        time.sleep(0.1)


def test_server_refuses_what_the_page_would(server: str) -> None:
    """The server validates too (a page bypassed): 400 with the message."""
    for body, fragment in (
        ({"sprung_mass": -5}, "sprung_mass"),
        ({"excitation": "harmonic", "frequency": 0}, "frequency"),
        ({"excitation": "road", "profile": "bumpy"}, "unknown road preset"),
    ):
        req = urllib.request.Request(
            server + "api/start",
            data=json.dumps(body).encode(),
            headers={"Content-Type": "application/json", "Origin": server.rstrip("/")},
            method="POST",
        )
        with pytest.raises(urllib.error.HTTPError) as info:
            urllib.request.urlopen(req)
        assert info.value.code == 400
        assert fragment in json.loads(info.value.read())["error"]


def test_controller_fields_from_the_registry(server: str, browser: Any) -> None:
    """The law select and its fields come from ``GET /api/controllers`` (the registry)."""
    with urllib.request.urlopen(server + "api/controllers") as r:
        forms = json.loads(r.read())
    page = browser.new_page()
    page.goto(server)
    page.wait_for_selector("#start:not([disabled])", timeout=30000)
    laws = page.eval_on_selector_all("#controller option", "os => os.map((o) => o.value)")
    assert laws == [c["law"] for c in forms["controllers"]]
    assert page.input_value("#controller") == forms["default"] == "skyhook-hilo"
    assert page.input_value("#mode") == "ACM"
    assert page.get_attribute("#gain", "placeholder") == "3"
    assert not page.is_visible("#current")
    page.select_option("#controller", "policy-iv")
    assert page.get_attribute("#gain", "placeholder") == "300"  # the law's own default
    page.select_option("#controller", "sliding-mode")
    assert page.is_visible("#slope")
    assert not page.is_visible("#gain")
    page.select_option("#controller", "passive")
    assert page.is_visible("#current")
    assert not page.is_visible("#mode")
    page.fill("#current", "0.9")
    page.click("#start")
    page.wait_for_function(
        "() => document.getElementById('error').textContent.length > 0", timeout=30000
    )
    error = page.text_content("#error") or ""
    assert "current (i [A]) must be in [0, 0.3] A; got 0.9" in error
    assert _posts(page) == []
    page.close()
