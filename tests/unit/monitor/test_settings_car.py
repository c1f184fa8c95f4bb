"""Issue 28: the monitor's form for a half or full car -> a validated car scenario."""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.control.modal import CornerSkyhook, ModalSkyhook
from mrsuspension.control.sensing import BandPassObserver, LeakyIntegrator
from mrsuspension.engine.plants import PLANTS
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.monitor.settings import (
    MAX_CURRENT,
    controller_forms,
    monitor_models,
    scenario_from_settings,
    sensing_table,
    vehicle_forms,
)
from mrsuspension.scenario import SCENARIO_KEYS, VEHICLE_LAWS, Scenario

PAGE = Path(__file__).resolve().parents[3] / "src" / "mrsuspension" / "monitor" / "static"

#: the acceptance's form: full car, modal skyhook, band-pass sensing at 0.1 Hz
FULL_CAR = {
    "model": "full-car",
    "set": "full-car-kalman-2023",
    "rig_corner": "rear_left",
    "controller": "modal-skyhook",
    "velocity": "band-pass",
    "corner": "0.1",
    "excitation": "harmonic",
    "frequency": "1.5",
    "amplitude": "0.02",
    # fields of what was not chosen: never read
    "sprung_mass": "-5",
    "tau": "2",
    "gain": "oops",
}


def test_full_car_modal_skyhook_band_pass_maps_to_the_scenario() -> None:
    s = scenario_from_settings(FULL_CAR)
    assert s.corner == "rear_left"
    # the same car as a scenario file with the page's current limit
    expected = Scenario.from_dict(
        {
            "vehicle": {"model": "full-car", "set": "full-car-kalman-2023"},
            "damper": {"max_current": MAX_CURRENT},
            "controller": {"law": "modal-skyhook", "high_current": MAX_CURRENT},
            "sensing": {"velocity": "band-pass", "corner": 0.1},
            "excitation": {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.02},
        }
    )
    assert s.tables["vehicle"] == {"model": "full-car", "set": "full-car-kalman-2023"}
    assert s.tables["sensing"] == {"velocity": "band-pass", "corner": 0.1}
    assert s.tables["controller"] == {
        "law": "modal-skyhook",
        **{
            k: pytest.approx(getattr(expected.body_control, k), rel=1e-12)
            for k in VEHICLE_LAWS["modal-skyhook"]
        },
    }  # the shown defaults: the scenario's to 12 digits
    car = s.simulation()
    assert isinstance(car, VehicleSimulation)
    assert car.model_name == "full-car"
    assert car.corners == ("front_left", "front_right", "rear_left", "rear_right")
    assert dataclasses.astuple(car.body_control) == pytest.approx(
        dataclasses.astuple(expected.body_control), rel=1e-12
    )
    assert isinstance(car.body_control, ModalSkyhook)
    assert car.body_control.heave == 4 * 6750.0  # the corner equivalent of the reference
    assert car.body_control.high_current == MAX_CURRENT
    assert car.sensing.velocity == BandPassObserver(0.1, 1000.0)
    assert car.sensing.stroke is None
    assert car.max_current == MAX_CURRENT
    assert car.vehicle == expected.vehicle
    json.dumps(s.to_dict())  # plain data for the loop process


def test_half_car_corner_law_stroke_sensor_and_zero_road() -> None:
    s = scenario_from_settings(
        {
            "model": "half-car",
            "controller": "corner-skyhook",
            "damping": "5000",
            "velocity": "leaky-integrator",
            "tau": "2",
            "fs": "500",
            "corner": "0.1",  # the band-pass's: not read with a leaky integrator
            "stroke_fs": "500",
            "stroke_noise": "2e-5",
            "stroke_seed": "3",
            "excitation": "zero",
        }
    )
    assert s.corner == "front"  # blank: the first corner
    assert s.tables["vehicle"] == {"model": "half-car"}  # blank set: the model's defaults
    assert s.tables["controller"] == {
        "law": "corner-skyhook", "damping": 5000.0, "low_current": 0.0, "high_current": 0.3
    }  # fmt: skip
    assert s.tables["sensing"] == {
        "velocity": "leaky-integrator", "tau": 2.0, "fs": 500.0,
        "stroke_fs": 500.0, "stroke_noise": 2e-5, "stroke_seed": 3,
    }  # fmt: skip
    car = s.simulation()
    assert car.body_control == CornerSkyhook(5000.0, 0.0, 0.3)
    assert car.sensing.velocity == LeakyIntegrator(2.0, 500.0)
    assert (car.sensing.stroke.fs, car.sensing.stroke.seed) == (500.0, 3)
    # zero input: a zero road under every wheel (the placeholder harmonic replaced)
    z, zd = car.excitation.sample_grid(50, 1e-3)
    assert z.shape == (2, 50)
    assert not np.any(z)
    assert not np.any(zd)


def test_a_car_takes_the_corner_laws_at_every_corner_and_ideal_sensing_is_no_table() -> None:
    s = scenario_from_settings(
        {"model": "full-car", "controller": "skyhook-hilo", "rig_corner": "front_right",
         "velocity": "ideal", "tau": "1"}
    )  # fmt: skip
    assert "sensing" not in s.tables
    car = s.simulation()
    assert car.body_control is None
    assert {car.corner_simulation(c).controller.law for c in car.corners} == {"skyhook-hilo"}
    assert car.corner_simulation("front_right").controller.p == 0.0  # ACM, the page's default


def test_a_modal_gain_given_alone_keeps_the_others_shown() -> None:
    s = scenario_from_settings({"model": "full-car", "controller": "modal-skyhook", "heave": "9e3"})
    shown = _law_form("modal-skyhook")["defaults"]["full-car"]  # the page's placeholders
    assert s.tables["controller"] == {"law": "modal-skyhook", **shown, "heave": 9000.0}
    assert s.simulation().body_control.pitch == shown["pitch"] > 0.0


@pytest.mark.parametrize(
    ("fields", "fragments"),
    [
        ({"model": "full-car", "velocity": "band-pass", "corner": "-1"},
         ("[sensing] corner must be in (0, inf) Hz; got -1 Hz",)),
        ({"model": "full-car", "velocity": "band-pass"}, ("band-pass", "needs corner [Hz]")),
        ({"model": "half-car", "velocity": "leaky-integrator", "tau": "abc"},
         ("[sensing] tau must be a number", "'abc'")),
        ({"model": "half-car", "velocity": "kalman"}, ("unknown velocity 'kalman'", "band-pass")),
        ({"model": "half-car", "stroke_noise": "1e-5"}, ("stroke_noise", "need stroke_fs")),
        ({"model": "half-car", "stroke_fs": "500", "stroke_seed": "1.5"},
         ("stroke_seed must be a whole number", "'1.5'")),
        ({"controller": "modal-skyhook"},
         ("'modal-skyhook' drives a whole vehicle", "half-car or full-car", "skyhook-hilo")),
        ({"model": "full-car", "rig_corner": "rear"},
         ("rig corner 'rear'", "full-car", "front_left, front_right, rear_left, rear_right")),
        ({"model": "half-car", "set": "sedan"}, ("unknown set 'sedan'", "full-car-kalman-2023")),
        ({"model": "truck"}, ("unknown model 'truck'", "quarter-car, half-car, full-car")),
        ({"model": "full-car", "controller": "modal-skyhook", "high_current": "0.5"},
         ("high_current must be in [0, 0.3]", "got 0.5")),
        ({"model": "full-car", "controller": "modal-skyhook", "heave": "-1"},
         ("[controller] heave must be in [0, inf) N s/m",)),
        ({"model": "full-car", "controller": "corner-skyhook", "damping": "x"},
         ("damping must be a number", "'x'")),
    ],
)  # fmt: skip
def test_a_bad_car_entry_is_one_line_naming_it(
    fields: dict[str, str], fragments: tuple[str, ...]
) -> None:
    err = raises_validation(lambda: scenario_from_settings(fields), *fragments)
    assert "\n" not in str(err)


def _law_form(law: str) -> dict:  # type: ignore[type-arg]
    return next(c for c in controller_forms()["controllers"] if c["law"] == law)


def test_the_car_fields_derive_from_the_scenario_and_the_plant_registry() -> None:
    forms = controller_forms()
    json.dumps(forms, allow_nan=False)
    cars = [m for m in PLANTS if PLANTS[m].corners]
    car_laws = {c["law"]: c for c in forms["controllers"] if c["vehicle"]}
    assert list(car_laws) == list(VEHICLE_LAWS)
    for law, form in car_laws.items():
        assert [o["name"] for o in form["options"]] == list(VEHICLE_LAWS[law])
        assert sorted(form["defaults"]) == sorted(cars)
    modal = car_laws["modal-skyhook"]
    assert modal["defaults"]["half-car"]["roll"] == 0.0  # a half car does not roll
    assert modal["defaults"]["full-car"]["roll"] > 0.0
    by_name = {o["name"]: o for o in modal["options"]}
    assert by_name["high_current"]["max"] == MAX_CURRENT
    assert by_name["heave"]["label"] == "c_z [N s/m]"
    assert not any(c["vehicle"] for c in forms["controllers"] if c["law"] not in VEHICLE_LAWS)

    vehicles = vehicle_forms()
    json.dumps(vehicles, allow_nan=False)
    assert [m["model"] for m in vehicles["models"]] == list(PLANTS) == list(monitor_models())
    for m in vehicles["models"]:
        assert m["corners"] == list(PLANTS[m["model"]].corners)
    sensing = vehicles["sensing"]
    keys = [k for k in SCENARIO_KEYS["sensing"] if k != "velocity"]
    assert [f["name"] for f in sensing["fields"]] == keys
    owners = {f["name"]: f["velocity"] for f in sensing["fields"]}
    assert owners["tau"] == ["leaky-integrator"]
    assert owners["stroke_fs"] is None  # the stroke sensor goes with any estimator


def test_a_registered_model_and_a_new_sensing_key_appear_without_an_edit(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setitem(
        PLANTS, "test-car", dataclasses.replace(PLANTS["half-car"], name="test-car")
    )
    monkeypatch.setitem(SCENARIO_KEYS["sensing"], "test_rate", "number")  # type: ignore[index]
    assert "test-car" in monitor_models()
    models = {m["model"]: m for m in vehicle_forms()["models"]}
    assert models["test-car"]["corners"] == ["front", "rear"]
    field = vehicle_forms()["sensing"]["fields"][-1]
    assert (field["name"], field["label"], field["velocity"]) == ("test_rate", "test_rate", None)
    assert sensing_table({"velocity": "ideal", "test_rate": "5"}) == {
        "velocity": "ideal", "test_rate": 5.0
    }  # fmt: skip


def test_car_field_names_do_not_collide() -> None:
    """One field per name on the page: the car's fields are neither the page's static
    fields nor a corner law's options (laws sharing an option name share its field)."""
    html = (PAGE / "index.html").read_text(encoding="utf-8")
    static = set(re.findall(r'name="([^"]+)"', html))
    assert {"model", "set", "rig_corner", "velocity"} <= static
    corner_options = {
        name
        for c in controller_forms()["controllers"]
        if not c["vehicle"]
        for o in c["options"]
        for name in (o["name"], o["symbol"])
    }
    sensing = {f["name"] for f in vehicle_forms()["sensing"]["fields"]}
    car_laws = {k for keys in VEHICLE_LAWS.values() for k in keys}
    for name in sensing | car_laws:
        assert name not in static, name
        assert name not in corner_options, name
    assert not sensing & car_laws


def test_a_live_change_to_a_car_is_refused(tmp_path: Path) -> None:
    pytest.importorskip("starlette")
    from mrsuspension.monitor.app import MonitorState

    state = MonitorState(tmp_path, rig="ideal", realtime="off")
    state.handle = SimpleNamespace(alive=lambda: True)  # type: ignore[assignment]
    state.status["state"] = "running"  # a quarter-car run going
    raises_validation(
        lambda: state.apply({"model": "full-car"}),
        "live changes apply to quarter-car runs", "full-car", "Start",
    )  # fmt: skip
