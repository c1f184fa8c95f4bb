"""Scenarios with a half or full car: models, sets, per-corner tables, wheel-only kinds."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pyopencrg
import pytest

from mrsuspension.dampers import LinearViscous, WangSymmetric
from mrsuspension.engine.vehicle_result import VehicleResult
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import Harmonic, WheelRoads
from mrsuspension.scenario import Scenario
from mrsuspension.vehicle import FullCar, HalfCar, QuarterCar

HARMONIC = {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.01}
BUMP = {"kind": "bump", "side": "left", "height": 0.03, "length": 0.5, "position": 1.0}


def _error(data: dict[str, Any], base_dir: Path | None = None) -> str:
    with pytest.raises(ValidationError) as info:
        Scenario.from_dict(data, base_dir)
    return str(info.value)


def test_models_sets_and_overrides() -> None:
    assert isinstance(Scenario.from_dict({"excitation": HARMONIC}).vehicle, QuarterCar)
    half = Scenario.from_dict({"vehicle": {"model": "half-car"}, "excitation": HARMONIC})
    assert half.vehicle == HalfCar()
    assert half.corners == ("front", "rear")
    assert half.plant.name == "half-car"
    assert half.model == "half-car"
    full = Scenario.from_dict(
        {
            "vehicle": {"model": "full-car", "set": "full-car-kalman-2023", "sprung_mass": 1300},
            "excitation": HARMONIC,
        }
    )
    assert full.vehicle == FullCar.from_set("full-car-kalman-2023").with_(sprung_mass=1300.0)
    again = Scenario.from_dict(full.to_dict(), full.base_dir)
    assert again.to_dict() == full.to_dict()
    assert again.vehicle == full.vehicle


def test_per_corner_tables() -> None:
    s = Scenario.from_dict(
        {
            "vehicle": {"model": "full-car"},
            "damper": {"hysteresis": False, "rear_left": {"model": "linear", "damping": 1500.0}},
            "controller": {"law": "skyhook-hilo", "mode": "ACM", "front_right": {"mode": "SCM"}},
            "excitation": BUMP,
        }
    )
    sim = s.vehicle_simulations()[0]
    assert isinstance(sim.corner_simulation("rear_left").damper, LinearViscous)
    assert isinstance(sim.corner_simulation("front_left").damper, WangSymmetric)
    laws = {c: sim.corner_simulation(c).controller.describe() for c in s.vehicle.corners}
    assert laws["front_left"] == laws["rear_left"] == laws["rear_right"]
    assert laws["front_right"]["law"] == "skyhook-hilo"
    assert laws["front_right"] != laws["front_left"]  # SCM against ACM
    # each corner has its own controller instance
    assert len({id(sim.corner_simulation(c).controller) for c in sim.corners}) == 4


def test_quarter_car_path_is_unchanged() -> None:
    s = Scenario.from_dict({"excitation": HARMONIC})
    assert s.corners == ()
    assert s.model == "quarter-car"
    assert s.corner_dampers == {}
    assert "model" not in s.to_dict()["vehicle"]
    with pytest.raises(ValidationError, match="quarter-car scenario"):
        s.vehicle_simulations()


@pytest.mark.parametrize(
    ("data", "message"),
    [
        (
            {"vehicle": {"model": "fullcar"}},
            "[vehicle] model: unknown model 'fullcar'. Did you mean 'full-car'?",
        ),
        (
            {"vehicle": {"model": "full-car", "roll_inertia": -1.0}},
            "[vehicle] roll_inertia must be in (0",
        ),
        (
            {"vehicle": {"model": "half-car", "cg_to_front": -2.0, "cg_to_rear": 1.0}},
            "[vehicle] wheelbase",
        ),
        (
            {"vehicle": {"model": "half-car", "roll_inertia": 300.0}},
            "[vehicle] roll_inertia does not apply to model 'half-car'",
        ),
        (
            {"vehicle": {"model": "half-car", "set": "kalman"}},
            "[vehicle] set: unknown set 'kalman'",
        ),
        (
            {"vehicle": {"set": "full-car-kalman-2023"}},
            "[vehicle] set does not apply to model 'quarter-car'",
        ),
        (
            {"vehicle": {"model": "full-car"}, "damper": {"front_lef": {"hysteresis": False}}},
            "unknown corner table [damper.front_lef]. Did you mean 'front_left'?",
        ),
        (
            {"vehicle": {"model": "half-car"}, "controller": {"front_left": {"law": "passive"}}},
            "unknown corner table [controller.front_left].",
        ),
        (
            {"damper": {"front": {"hysteresis": False}}},
            "[damper.front]: per-corner tables need a half or full car",
        ),
        (
            {"vehicle": {"model": "full-car"}, "damper": {"rear_left": {"max_current": 1.0}}},
            "[damper.rear_left] max_current: the current limit applies to every corner",
        ),
        (
            {"vehicle": {"model": "full-car"}, "controller": {"rear_left": {"law": "skyhook"}}},
            "[controller.rear_left] law: unknown law 'skyhook'",
        ),
        (
            {"vehicle": {"model": "full-car"}, "damper": {"rear_left": {"hysteresys": True}}},
            "unknown key [damper.rear_left] hysteresys. Did you mean 'hysteresis'?",
        ),
    ],
)
def test_errors_name_the_table(data: dict[str, Any], message: str) -> None:
    data = {"excitation": HARMONIC, **data}
    assert message in _error(data)


def test_wheel_kinds() -> None:
    full = {"model": "full-car"}
    msg = _error({"excitation": BUMP})
    assert "kind 'bump' gives a road per wheel: it needs [vehicle] model" in msg
    assert "Did you mean 'left'" in _error({"vehicle": full, "excitation": {**BUMP, "side": "lef"}})
    assert "[excitation] depth is required for kind 'pothole'" in _error(
        {"vehicle": full, "excitation": {"kind": "pothole", "side": "left", "length": 0.5}}
    )
    assert "Did you mean 'length'" in _error(
        {"vehicle": full, "excitation": {"kind": "two-track", "iso_class": "C", "lenght": 9.0}}
    )
    s = Scenario.from_dict(
        {
            "vehicle": full,
            "excitation": {"kind": "two-track", "iso_class": "C", "seed": 1, "length": 200.0},
        }
    )
    assert isinstance(s.excitation, WheelRoads)
    assert s.excitation.right is not None
    assert s.excitation.track == FullCar().front_track


def test_single_track_kinds_become_wheel_roads() -> None:
    s = Scenario.from_dict(
        {"vehicle": {"model": "half-car"}, "excitation": {**HARMONIC, "speed": 36.0}}
    )
    (roads,) = s.wheel_roads()
    assert isinstance(roads.left, Harmonic)
    assert roads.rear_delay == pytest.approx(HalfCar().wheelbase / 10.0)
    assert "[excitation] speed" in _error({"excitation": {**HARMONIC, "speed": 36.0}})
    sweep = Scenario.from_dict(
        {"vehicle": {"model": "full-car"},
         "excitation": {"kind": "swept", "amplitude": 0.01, "frequencies": [1.0, 2.0]}}
    )  # fmt: skip
    assert len(sweep.vehicle_simulations()) == 2


def test_crg_file_relative_to_the_scenario(tmp_path: Path) -> None:
    u = np.arange(300) * 0.1
    v = np.linspace(-1.5, 1.5, 31)
    z = 0.01 * np.sin(u)[:, None] * np.ones(v.size)[None, :]
    z[100, 20] = np.nan  # on the left wheel track (v = 0.5 m)
    pyopencrg.CrgRoad(z, u_inc=0.1, v=v).save(tmp_path / "holes.crg", fmt="KDBI")
    (tmp_path / "car.toml").write_text(
        '# a crg road\n[vehicle]\nmodel = "full-car"\nfront_track = 1.0\nrear_track = 1.0\n'
        '[excitation]\nkind = "crg"\nfile = "holes.crg"\n'
    )
    with pytest.raises(ValidationError, match="has no value \\(NaN\\)"):
        Scenario.load(tmp_path / "car.toml")


def test_run_returns_vehicle_results() -> None:
    s = Scenario.from_dict({"vehicle": {"model": "full-car"}, "excitation": BUMP})
    (res,) = s.run(duration=0.5)
    assert isinstance(res, VehicleResult)
    assert float(np.abs(res["roll"]).max()) > 0.0


# -- vehicle-level laws and sensing from the scenario (issue 28, part 6) -------------------------
TWO_TRACK = {"kind": "two-track", "iso_class": "C", "length": 60.0, "speed": 50.0}


def test_modal_skyhook_and_sensing_from_the_scenario_equal_the_engine_built_by_hand() -> None:
    from mrsuspension.control.modal import ModalSkyhook
    from mrsuspension.control.sensing import BandPassObserver, Sensing, StrokeSensor
    from mrsuspension.engine.vehicle import VehicleSimulation

    s = Scenario.from_dict({
        "vehicle": {"model": "full-car"},
        "controller": {"law": "modal-skyhook", "high_current": 0.4},
        "sensing": {"velocity": "band-pass", "corner": 0.2, "stroke_fs": 500.0,
                    "stroke_noise": 2e-5, "stroke_seed": 3},
        "excitation": TWO_TRACK,
        "simulation": {"duration": 1.0},
    })  # fmt: skip
    car = s.vehicle
    x, y = car.corner_positions()
    law = ModalSkyhook.corner_equivalent(x, y, high_current=0.4)
    sensing = Sensing(BandPassObserver(0.2, 1000.0), StrokeSensor(500.0, noise_std=2e-5, seed=3))
    assert s.body_control == law
    assert s.sensing == sensing
    (sim,) = s.vehicle_simulations()
    by_hand = VehicleSimulation(car, s.wheel_roads()[0], sensing=sensing, body_control=law)
    a, b = sim.run(1.0), by_hand.run(1.0)
    np.testing.assert_array_equal(a["i_d.front_left"], b["i_d.front_left"])
    assert a["i_d.front_left"].max() == pytest.approx(0.4)  # the law drives the currents
    # and it round-trips with its gains resolved
    d = s.to_dict()
    assert d["controller"]["heave"] == law.heave
    assert d["sensing"]["fs"] == 1000.0
    again = Scenario.from_dict(d, s.base_dir)
    assert again.body_control == law
    assert again.sensing == sensing


def test_corner_skyhook_and_leaky_integrator() -> None:
    from mrsuspension.control.modal import CornerSkyhook
    from mrsuspension.control.sensing import LeakyIntegrator

    s = Scenario.from_dict({
        "vehicle": {"model": "half-car"},
        "controller": {"law": "corner-skyhook", "damping": 5000.0},
        "sensing": {"velocity": "leaky-integrator", "tau": 0.9, "fs": 500.0},
        "excitation": HARMONIC,
        "simulation": {"dt": 2e-4},
    })  # fmt: skip
    assert s.body_control == CornerSkyhook(5000.0)
    assert s.sensing is not None
    assert s.sensing.velocity == LeakyIntegrator(0.9, 500.0)
    assert s.sensing.stroke is None


@pytest.mark.parametrize(
    ("data", "fragments"),
    [
        ({"controller": {"law": "modal-skyhook"}, "excitation": HARMONIC},
         ("law 'modal-skyhook' drives a whole vehicle", "half-car")),
        ({"sensing": {"velocity": "band-pass", "corner": 0.1}, "excitation": HARMONIC},
         ("[sensing] applies to half and full cars",)),
        ({"vehicle": {"model": "full-car"}, "sensing": {"velocty": "band-pass"},
          "excitation": TWO_TRACK}, ("unknown key [sensing] velocty", "Did you mean 'velocity'")),
        ({"vehicle": {"model": "full-car"}, "sensing": {"velocity": "kalman"},
          "excitation": TWO_TRACK}, ("[sensing] velocity: unknown velocity 'kalman'", "band-pass")),
        ({"vehicle": {"model": "full-car"}, "sensing": {"velocity": "band-pass", "tau": 1.0},
          "excitation": TWO_TRACK}, ("[sensing] tau does not apply to velocity = 'band-pass'",)),
        ({"vehicle": {"model": "full-car"}, "sensing": {"velocity": "leaky-integrator"},
          "excitation": TWO_TRACK}, ("needs tau",)),
        ({"vehicle": {"model": "full-car"}, "sensing": {"stroke_noise": 1e-5},
          "excitation": TWO_TRACK}, ("stroke_noise need stroke_fs",)),
        ({"vehicle": {"model": "full-car"},
          "controller": {"law": "modal-skyhook", "rear_left": {"law": "passive"}},
          "excitation": TWO_TRACK}, ("[controller.rear_left]", "sets every corner's current")),
        ({"vehicle": {"model": "full-car"}, "controller": {"law": "modal-skyhook", "gain": 2.0},
          "excitation": TWO_TRACK}, ("[controller] gain does not apply to law 'modal-skyhook'",)),
        ({"vehicle": {"model": "full-car"}, "controller": {"law": "modal-skyhook", "heave": 2e4},
          "excitation": TWO_TRACK}, ("needs pitch",)),
        ({"vehicle": {"model": "full-car"},
          "controller": {"law": "corner-skyhook", "high_current": 0.8},
          "excitation": TWO_TRACK}, ("[controller] high_current = 0.8 A", "max_current = 0.5 A")),
        ({"vehicle": {"model": "full-car"}, "sensing": {"velocity": "band-pass", "corner": 0.1},
          "excitation": TWO_TRACK, "simulation": {"dt": 0.0}},
         ("[simulation] dt must be in (0, 0.01] s; got 0 s",)),
        ({"vehicle": {"model": "full-car"}, "controller": {"law": "corner-skyhook", "damping": -1.0},
          "excitation": TWO_TRACK}, ("[controller] damping must be in (0, inf) N s/m",)),
    ],
)  # fmt: skip
def test_vehicle_law_and_sensing_errors_name_the_table(
    data: dict[str, Any], fragments: tuple[str, ...]
) -> None:
    message = _error(data)
    for fragment in fragments:
        assert fragment in message, message
