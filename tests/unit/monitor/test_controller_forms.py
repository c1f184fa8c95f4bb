"""The monitor's controller choices and fields derive from the controller registry."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import Path
from typing import ClassVar

import numpy as np
import numpy.typing as npt
import pytest

from _helpers import raises_validation
from mrsuspension.control import CONTROLLERS, Controller
from mrsuspension.control import kernel as CK
from mrsuspension.control.base import option
from mrsuspension.monitor.settings import (
    controller_forms,
    monitor_laws,
    page_fields,
    scenario_from_settings,
)
from mrsuspension.scenario import SCENARIO_KEYS

PAGE = Path(__file__).resolve().parents[3] / "src" / "mrsuspension" / "monitor" / "static"


@dataclass(frozen=True)
class Hold(Controller):
    """A throwaway law (a constant current scaled by a weight), registered by the tests only."""

    level: float = option(0.05, unit="A", low=0.0, high=10.0, symbol="i_h")
    weight: float = option(1.0, low=0.0, high=2.0, symbol="w", label="weight w")
    law: ClassVar[str] = "test-hold"
    code: ClassVar[int] = CK.C_PASSIVE

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[CK.P_CURRENT] = self.level * self.weight


@dataclass(frozen=True)
class IdealHold(Controller):
    """A throwaway law acting through an ideal damper (not for the rig)."""

    damping: float = option(1000.0, unit="N s/m", low=0.0, high=1e7, symbol="c_h")
    law: ClassVar[str] = "test-ideal-hold"
    code: ClassVar[int] = CK.C_IDEAL_SKYHOOK
    force_source: ClassVar[int] = CK.F_SKYHOOK

    def _fill(self, p: npt.NDArray[np.float64]) -> None:
        p[CK.P_CS] = self.damping


@pytest.fixture
def registered(monkeypatch: pytest.MonkeyPatch) -> None:
    """The throwaway laws in the registry (nothing in monitor/ edited).

    The scenario layer takes its ``[controller]`` keys from the registry once, at import
    (a law registered in ``control/registry.py`` is in them); registered here after the
    import, the new law's keys are added to that table as the import would have.
    """
    monkeypatch.setitem(CONTROLLERS, "test-hold", Hold)
    monkeypatch.setitem(CONTROLLERS, "test-ideal-hold", IdealHold)
    for key in ("level", "weight", "damping"):
        monkeypatch.setitem(SCENARIO_KEYS["controller"], key, "number")


def _forms_by_law(forms: dict) -> dict:  # type: ignore[type-arg]
    return {c["law"]: {o["name"]: o for o in c["options"]} for c in forms["controllers"]}


def test_a_registered_law_appears_in_the_route(registered: None) -> None:
    starlette = pytest.importorskip("starlette.testclient")
    from mrsuspension.monitor.app import create_app

    with starlette.TestClient(create_app(), base_url="http://127.0.0.1:8765") as client:
        r = client.get("/api/controllers")
    assert r.status_code == 200
    laws = _forms_by_law(r.json())
    assert "test-ideal-hold" not in laws  # an ideal damper: nothing for the rig to drive
    hold = laws["test-hold"]
    assert list(hold) == ["level", "weight"]
    assert hold["level"] == {
        "name": "level",
        "label": "i_h [A]",
        "symbol": "i_h",
        "unit": "A",
        "default": 0.05,
        "min": 0.0,
        "max": 0.3,
        "min_open": False,
        "max_open": False,
        "choices": None,
    }  # fmt: skip  (capped at the HiL current limit)
    assert (hold["weight"]["label"], hold["weight"]["max"]) == ("w", 2.0)


def test_a_registered_law_validates_through_the_settings(registered: None) -> None:
    s = scenario_from_settings({"controller": "test-hold", "level": "0.2", "weight": "1.5"})
    sim = s.simulation()
    assert isinstance(sim.controller, Hold)
    assert (sim.controller.level, sim.controller.weight) == (0.2, 1.5)
    assert s.tables["controller"] == {"law": "test-hold", "level": 0.2, "weight": 1.5}
    assert page_fields(sim)["level"] == 0.2
    blank = scenario_from_settings({"controller": "test-hold", "level": "", "w": "0.5"})
    assert blank.simulation().controller == Hold(level=0.05, weight=0.5)  # by its symbol
    raises_validation(
        lambda: scenario_from_settings({"controller": "test-hold", "weight": 3}),
        "weight w", "[0, 2]", "got 3",
    )  # fmt: skip
    raises_validation(
        lambda: scenario_from_settings({"controller": "test-hold", "level": 0.5}),
        "level", "[0, 0.3]", "got 0.5",
    )  # fmt: skip
    raises_validation(
        lambda: scenario_from_settings({"controller": "test-hold", "level": "lots"}),
        "level", "number", "'lots'",
    )  # fmt: skip
    raises_validation(
        lambda: scenario_from_settings({"controller": "test-ideal-hold"}),
        "unknown controller 'test-ideal-hold'", "test-hold",
    )  # fmt: skip


def test_the_monitor_laws_are_the_damper_driving_ones() -> None:
    laws = monitor_laws()
    for law in ("passive", "skyhook-hilo", "inverse-hilo", "sliding-mode"):  # the page's before
        assert law in laws
    assert "ideal-skyhook" not in laws
    assert "ideal-onoff" not in laws
    forms = controller_forms()
    json.dumps(forms, allow_nan=False)  # plain JSON
    assert forms["default"] == "skyhook-hilo"
    by_law = _forms_by_law(forms)
    assert by_law["skyhook-hilo"]["mode"]["default"] == "ACM"  # the HiL demonstration's
    assert by_law["policy-iv"]["gain"]["default"] == 300.0  # each policy's own gain
    assert by_law["sliding-mode"]["slope"]["label"] == "lambda [1/s]"


def test_option_names_do_not_collide_with_the_other_page_fields() -> None:
    html = (PAGE / "index.html").read_text(encoding="utf-8")
    static = set(re.findall(r'name="([^"]+)"', html))
    assert {"controller", "sprung_mass", "frequency", "ramp_time"} <= static
    for law in controller_forms()["controllers"]:
        for o in law["options"]:
            assert o["name"] not in static, (law["law"], o["name"])
            assert o["symbol"] not in static, (law["law"], o["symbol"])


def test_settings_keep_the_old_form_keys_and_messages() -> None:
    sim = scenario_from_settings({"controller": "sliding-mode", "lambda": 0.7, "eps": 0.1})
    assert (sim.simulation().controller.slope, sim.tables["controller"]["boundary_layer"]) == (
        0.7,
        0.1,
    )
    assert sim.simulation().controller.p == 0.0  # ACM by default on the page
    raises_validation(
        lambda: scenario_from_settings({"controller": "skyhook-hilo", "gain": -1}),
        "gain k_c", "[0, 1e+09]", "got -1",
    )  # fmt: skip
    raises_validation(
        lambda: scenario_from_settings({"controller": "skyhook-hilo", "mode": "XCM"}),
        "control mode", "'XCM'", "ACM, SCM",
    )  # fmt: skip
    raises_validation(
        lambda: scenario_from_settings({"controller": "passive-zero"}),
        "unknown controller 'passive-zero'", "passive",
    )  # fmt: skip
