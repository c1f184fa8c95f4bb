"""HiL browser monitor in headless Debian chromium (Playwright sync API)."""

from __future__ import annotations

import socket
import threading
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.monitor.cli import check_bind

pytestmark = pytest.mark.browser

CHROMIUM = "/usr/bin/chromium"
ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture(scope="module")
def server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    uvicorn = pytest.importorskip("uvicorn")
    from mrsuspension.monitor.app import create_app

    port = _free_port()
    app = create_app(workdir=tmp_path_factory.mktemp("monitor"))
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


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    sync_api = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.skip("Debian chromium not installed")
    with sync_api.sync_playwright() as pw:
        b = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        yield b
        b.close()


def test_token_rule() -> None:
    check_bind("127.0.0.1", None)
    check_bind("localhost", None)
    check_bind("::1", None)
    check_bind("0.0.0.0", "secret")
    with pytest.raises(ValidationError, match="token"):
        check_bind("0.0.0.0", None)
    with pytest.raises(ValidationError, match="token"):
        check_bind("192.168.1.5", "")


def test_token_gate() -> None:
    from starlette.testclient import TestClient

    from mrsuspension.monitor.app import create_app

    with TestClient(create_app(token="s3cret")) as client:
        assert client.get("/").status_code == 403
        assert client.get("/?token=wrong").status_code == 403
        assert client.get("/?token=s3cret").status_code == 200


def test_run_skyhook_harmonic(server: str, browser: Any, tmp_path: Path) -> None:
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(server)
    page.select_option("#controller", "skyhook-hilo")
    page.select_option("#mode", "ACM")
    page.select_option("#excitation", "harmonic")
    page.fill("#frequency", "1.5")
    page.click("#start")
    # live measures show numbers and the plots hold data
    page.wait_for_function(
        "() => window.monitorState.points > 200 && "
        "typeof window.monitorState.measures.T_as === 'number'",
        timeout=30000,
    )
    state = page.evaluate("() => window.monitorState")
    assert state["status"]["state"] == "running"
    t_as = float(page.text_content("#measures-T_as") or "nan")
    assert 0.05 < t_as < 5.0
    dlc = float(page.text_content("#measures-DLC") or "nan")
    assert 0.0 < dlc < 1.0
    points = page.evaluate(
        "() => { const c = document.querySelector('#plots canvas');"
        " const d = c.getContext('2d').getImageData(0, 30, c.width, c.height - 30).data;"
        " let n = 0; for (let i = 3; i < d.length; i += 4) if (d[i]) n++; return n; }"
    )
    assert points > 100  # something drawn below the title
    page.click("#stop")
    page.wait_for_function(
        "() => ['stopped', 'ended'].includes(window.monitorState.status.state)", timeout=10000
    )
    assert "safe" in (page.text_content("#state") or "")
    page.wait_for_selector("#download:not(.disabled)", timeout=5000)
    shot = tmp_path / "monitor.png"
    page.screenshot(path=str(shot), full_page=True)
    assert shot.stat().st_size > 10000
    href = page.get_attribute("#download", "href")
    assert href
    with urllib.request.urlopen(server + href) as r:
        body = r.read().decode()
    lines = body.splitlines()
    assert lines[0].startswith("time,")
    assert len(lines) > 500
    page.close()


def test_invalid_mass_shows_error(server: str, browser: Any) -> None:
    page = browser.new_page()
    page.goto(server)
    page.fill("#sprung_mass", "-5")
    page.click("#start")
    page.wait_for_function(
        "() => document.getElementById('error').textContent.length > 0", timeout=10000
    )
    assert "sprung_mass" in (page.text_content("#error") or "")
    page.close()
