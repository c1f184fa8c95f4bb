"""Every :class:`WheelRoads` constructor feeds a half and a full car (one home for corners)."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pyopencrg
import pytest

from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import FULL_CAR_CORNERS, HALF_CAR_CORNERS, Harmonic, WheelRoads
from mrsuspension.vehicle import CORNERS_FULL, CORNERS_HALF, FullCar, HalfCar
from mrsuspension.vehicle.body import VehicleBody


def test_corner_names_have_one_home() -> None:
    assert CORNERS_FULL is FULL_CAR_CORNERS
    assert CORNERS_HALF is HALF_CAR_CORNERS
    assert FullCar.corners is FULL_CAR_CORNERS
    assert HalfCar.corners is HALF_CAR_CORNERS


def _crg(tmp_path: Path) -> Path:
    u = np.arange(400) * 0.1
    v = np.linspace(-1.5, 1.5, 31)
    z = 0.01 * np.sin(2 * np.pi * u / 4.0)[:, None] * (1.0 + 0.2 * v[None, :])
    path = tmp_path / "road.crg"
    pyopencrg.CrgRoad(z, u_inc=0.1, v=v).save(path, fmt="KDBI")
    return path


BUILDERS: dict[str, Callable[[VehicleBody, Path], WheelRoads]] = {
    "from_excitation": lambda car, _: WheelRoads.from_excitation(Harmonic(1.5, 0.01), car, 50.0),
    "two_track": lambda car, _: WheelRoads.two_track("C", car, 50.0, length=200.0, seed=1),
    "from_crg": lambda car, tmp: WheelRoads.from_crg(_crg(tmp), car, 36.0),
    "bump": lambda car, _: WheelRoads.bump("left", 0.03, 0.5, car, 36.0, position=1.0),
    "pothole": lambda car, _: WheelRoads.pothole("left", 0.03, 0.6, car, 36.0, position=1.0),
}


@pytest.mark.parametrize("car", [HalfCar(), FullCar()], ids=["half-car", "full-car"])
@pytest.mark.parametrize("build", list(BUILDERS), ids=list(BUILDERS))
def test_every_constructor_feeds_a_vehicle(build: str, car: VehicleBody, tmp_path: Path) -> None:
    roads = BUILDERS[build](car, tmp_path)  # the car itself is the geometry
    assert roads.corners == car.corners
    assert roads.wheelbase == pytest.approx(car.wheelbase)
    res = VehicleSimulation(car, roads).run(0.6, dt=2e-4)
    assert res.corners == car.corners
    assert np.all(np.isfinite(res["heave"]))
    moved = [float(np.abs(res[f"z_r.{c}"]).max()) for c in car.corners]
    assert max(moved) > 0.0


def test_full_car_track_is_the_front_track() -> None:
    car = FullCar(front_track=1.5, rear_track=1.4)
    roads = WheelRoads.two_track("B", car, 50.0, length=100.0)
    assert car.track == 1.5
    assert roads.track == 1.5
    assert not hasattr(HalfCar(), "track")
    assert WheelRoads.bump("both", 0.02, 0.5, HalfCar()).track is None
