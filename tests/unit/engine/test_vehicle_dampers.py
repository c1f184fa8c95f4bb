"""Every damper model at the corners of the vehicle (the quarter car's damper kernels)."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.control import Passive
from mrsuspension.dampers import DAMPERS, make_damper
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import Harmonic, WheelRoads
from mrsuspension.vehicle import FullCar, HalfCar, QuarterCar


@pytest.mark.parametrize("model", sorted(DAMPERS))
def test_each_damper_model_at_decoupled_corners_is_the_quarter_car(model: str) -> None:
    qc = QuarterCar()
    car = HalfCar.from_quarter_car(qc)
    exc = Harmonic(2.0, 0.02)
    damper = make_damper(model)
    controller = Passive(0.2)
    road = WheelRoads.from_excitation(exc, car, speed_kmh=72.0)
    res = VehicleSimulation(car, road, dampers=damper, controllers=controller).run(road.duration)
    ref = Simulation(exc, vehicle=qc, damper=damper, controller=controller).run().measures()
    for c in car.corners:
        m = res.corner(c).measures()
        for key in ("T_as", "DLC"):
            assert m[key] == pytest.approx(ref[key], rel=5e-3), (c, key)


def test_mixed_damper_models_run_side_by_side() -> None:
    car = FullCar()
    dampers = {
        "front_left": make_damper("wang-symmetric"),
        "front_right": make_damper("wang-asymmetric"),
        "rear_left": make_damper("spencer"),
        "rear_right": make_damper("bingham"),
    }
    road = WheelRoads.from_excitation(Harmonic(1.5, 0.02), car, speed_kmh=72.0)
    res = VehicleSimulation(car, road, dampers=dampers, controllers=Passive(0.2)).run(2.0)
    forces = [res[f"F_d.{c}"] for c in car.corners]
    assert all(np.all(np.isfinite(f)) for f in forces)
    # different dampers left and right: the body rolls
    assert np.abs(res.roll).max() > 1e-5
