"""Issue 28: a half or full car in the monitor's form (model, rig corner, whole-vehicle
laws, sensing), in headless Debian chromium (Playwright sync API)."""

from __future__ import annotations

import json
import math
import socket
import threading
import time
import urllib.request
from collections.abc import Iterator
from typing import Any

import pytest

pytestmark = pytest.mark.browser


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.fixture(scope="module")
def served(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, Any]]:
    """A loopback monitor with the simulated rig: (its address, its MonitorState)."""
    uvicorn = pytest.importorskip("uvicorn")
    from mrsuspension.monitor.app import create_app

    port = _free_port()
    app = create_app(workdir=tmp_path_factory.mktemp("monitor-car"), rig="simulated")
    srv = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, log_level="warning"))
    thread = threading.Thread(target=srv.run, daemon=True)
    thread.start()
    deadline = time.monotonic() + 20
    while not srv.started:
        assert time.monotonic() < deadline, "the monitor did not start"
        time.sleep(0.02)
    yield f"http://127.0.0.1:{port}/", app.state.monitor
    srv.should_exit = True
    thread.join(30)


def _status(server: str) -> dict[str, Any]:
    with urllib.request.urlopen(server + "api/status") as r:
        return dict(json.loads(r.read()))


def _options(page: Any, selector: str, visible_only: bool = False) -> list[str]:
    js = "os => os.filter((o) => !o.hidden).map((o) => o.value)" if visible_only else (
        "os => os.map((o) => o.value)")  # fmt: skip
    return list(page.eval_on_selector_all(selector + " option", js))


def test_full_car_modal_skyhook_band_pass_sensing(served: tuple[str, Any], browser: Any) -> None:
    """Full car, modal skyhook, band-pass sensing (corner 0.1 Hz), rig corner rear_left:
    a bad corner frequency is refused on the page and starts nothing; then the run starts
    with that corner on the rig, the status names it and the body plot receives data;
    STOP leaves the rig at 0 A."""
    server, state = served
    page = browser.new_page(viewport={"width": 1500, "height": 1100})
    page.goto(server)
    page.wait_for_selector("#start:not([disabled])", timeout=20000)
    with urllib.request.urlopen(server + "api/vehicles") as r:
        vehicles = json.loads(r.read())
    # the models from the plant registry; a quarter car has no car laws, set, corner, sensing
    assert _options(page, "#model") == [m["model"] for m in vehicles["models"]]
    assert page.input_value("#model") == "quarter-car"
    assert "modal-skyhook" not in _options(page, "#controller", visible_only=True)
    assert not page.is_visible("#sensing")
    assert not page.is_visible("#rig_corner")
    assert page.is_visible("#sprung_mass")

    page.select_option("#model", "full-car")
    assert _options(page, "#rig_corner") == [
        "front_left", "front_right", "rear_left", "rear_right"
    ]  # fmt: skip
    assert "full-car-kalman-2023" in _options(page, "#set")
    assert not page.is_visible("#sprung_mass")  # a car: its model and set
    assert {"modal-skyhook", "corner-skyhook"} <= set(
        _options(page, "#controller", visible_only=True)
    )
    page.select_option("#set", "full-car-kalman-2023")
    page.select_option("#rig_corner", "rear_left")
    page.select_option("#controller", "modal-skyhook")
    assert page.is_visible("#heave")
    assert page.is_visible("#roll")
    assert page.get_attribute("#heave", "placeholder") == "27000"  # 4 corners x 6750 N s/m
    assert page.get_attribute("#high_current", "placeholder") == "0.3"  # the HiL limit
    assert not page.is_visible("#gain")
    page.select_option("#velocity", "band-pass")
    assert page.is_visible("#corner")
    assert not page.is_visible("#tau")  # the leaky integrator's
    page.select_option("#excitation", "harmonic")
    page.fill("#frequency", "1.5")
    page.fill("#amplitude", "0.02")
    page.fill("#duration", "30")

    # a bad sensing value: refused with one line on the page, no run started
    page.fill("#corner", "-1")
    page.click("#start")
    page.wait_for_function(
        "() => document.getElementById('error').textContent.length > 0", timeout=30000
    )
    error = page.text_content("#error") or ""
    print(f"refused: {error}")
    assert error == "[sensing] corner must be in (0, inf) Hz; got -1 Hz"
    assert state.handle is None
    assert _status(server)["run"] == 0
    assert _status(server)["state"] == "idle"

    # the same with 0.1 Hz: the car runs in the loop, corner rear_left on the rig
    page.fill("#corner", "0.1")
    page.click("#start")
    page.wait_for_function(
        "() => { const m = window.monitorState; return m.status.state === 'running'"
        " && m.status.corner === 'rear_left' && m.points > 200"
        " && m.range.pitch && m.range.pitch[1] > m.range.pitch[0]"
        " && m.range.roll[1] > m.range.roll[0]; }",
        timeout=90000,
    )
    assert page.text_content("#error") == ""
    assert "corner rear_left of the full-car" in (page.text_content("#rig") or "")
    status = _status(server)
    assert (status["model"], status["corner"], status["rig"]) == (
        "full-car",
        "rear_left",
        "simulated",
    )
    settings = state.settings
    assert settings.corner == "rear_left"
    assert settings.tables["sensing"] == {"velocity": "band-pass", "corner": 0.1}
    assert settings.tables["controller"]["law"] == "modal-skyhook"
    car = settings.simulation()
    assert car.sensing.velocity.corner == 0.1
    assert car.body_control.heave == 27000.0
    assert car.body_control.high_current == 0.3
    st = page.evaluate("() => window.monitorState")
    rng = st["range"]
    assert 0.0 < rng["heave"][1] - rng["heave"][0] < 0.1  # the body heaves on the 2 cm road
    assert all(math.isfinite(v) for c in ("heave", "pitch", "roll") for v in rng[c])
    assert -0.0205 < rng["z_r"][0] < rng["z_r"][1] < 0.0205  # the rig corner's road
    assert rng["i_cmd"][0] >= 0.0
    assert rng["i_cmd"][1] <= 0.3 + 1e-3
    # the body plot draws its traces (below its title)
    page.wait_for_function(
        "() => { const c = document.querySelectorAll('#plots canvas')[10];"
        " const d = c.getContext('2d').getImageData(0, 30, c.width, c.height - 30).data;"
        " let n = 0; for (let i = 3; i < d.length; i += 4) if (d[i]) n++; return n > 100; }",
        timeout=30000,
    )

    # a live change is a quarter car's: refused, the run goes on
    page.click("#apply")
    page.wait_for_function(
        "() => document.getElementById('error').textContent.includes('quarter-car')",
        timeout=30000,
    )
    assert _status(server)["applied"] == 0

    # STOP: drive current 0 at once, the actuator home, the run ended safe
    page.click("#stop")
    page.wait_for_function("() => window.monitorState.status.state === 'ended'", timeout=30000)
    status = _status(server)
    assert status["reason"] == "STOP pressed"
    assert status["current"] == 0.0
    assert status["safe"] is True
    assert "safe" in (page.text_content("#state") or "")
    page.close()
