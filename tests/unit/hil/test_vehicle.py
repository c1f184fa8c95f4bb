"""The vehicle's tick in the HiL loop (:mod:`mrsuspension.hil.vehicle`): the vehicle's step."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from _helpers import raises_validation
from mrsuspension.engine.result import SimulationDiverged
from mrsuspension.hil.vehicle import CornerPlant, check_corner
from mrsuspension.scenario import Scenario

ROOT = Path(__file__).resolve().parents[3]
HALF_CAR = ROOT / "examples" / "vehicles" / "half_car.toml"
FULL_CAR = ROOT / "examples" / "vehicles" / "full_car_bump.toml"


def _corner_rate(sim, y: np.ndarray, corner: str) -> float:  # type: ignore[no-untyped-def]
    """The corner's stroke rate z_u' - (z' - x theta' + y phi') from the state."""
    i = sim.corners.index(corner)
    x, yy = (float(v[i]) for v in sim.vehicle.corner_positions())
    return float(y[6 + 4 * i + 1] - (y[3] - x * y[4] + yy * y[5]))


@pytest.mark.parametrize(("scenario", "corner"), [(HALF_CAR, "rear"), (FULL_CAR, "rear_left")])
def test_a_tick_is_n_steps_of_the_vehicle_stepper(scenario: Path, corner: str) -> None:
    """The compiled tick = ``VehicleStepper.step`` n_sub times on the same roads, with the
    external force (plus the start-up damping on the stroke rate) held over each step: bit
    for bit (so the loop runs the physics of ``VehicleSimulation.run``)."""
    sim = Scenario.load(scenario).vehicle_simulations()[0]
    n_sub = 4
    plant = CornerPlant(sim, corner, 1e-4, n_sub, 60)
    ref = sim.stepper(1e-4, external=corner)
    ref.reset(plant.zr[:, 0], plant.zrd[:, 0])
    assert np.array_equal(plant.y, ref.y)
    zr, zrd = plant.zr, plant.zrd
    for k in range(60):
        force, damping = 150.0 * np.sin(0.3 * k), 500.0 * (k < 30)
        out = plant.tick(k, force, damping)
        for s in range(n_sub):
            j = 2 * (n_sub * k + s)
            fd = force + damping * _corner_rate(sim, ref.y, corner)
            last = ref.step(
                zr[:, j], zrd[:, j], road_mid=(zr[:, j + 1], zrd[:, j + 1]),
                road_end=(zr[:, j + 2], zrd[:, j + 2]), damper_force=fd,
            )  # fmt: skip
        assert np.array_equal(plant.y, ref.y), k
    for name in ("F_d", "F_T", "i_d", "z_s_ddot", "z_u"):
        assert out[name] == last[f"{name}.{corner}"], name
    for name in ("heave", "pitch", "roll", "heave_ddot", "pitch_ddot", "roll_ddot"):
        assert out[name] == last[name], name
    assert out["x_d"] == pytest.approx(out["z_u"] - out["z_s"], abs=1e-15)
    assert out["z_r"] == zr[sim.corners.index(corner), 2 * n_sub * 60]
    assert out["heave"] != 0.0


def test_a_diverging_vehicle_and_a_bad_force_are_refused() -> None:
    sim = Scenario.load(HALF_CAR).vehicle_simulations()[0]
    plant = CornerPlant(sim, "front", 1e-4, 10, 5)
    with pytest.raises(SimulationDiverged, match="diverged"):
        plant.tick(0, 1e9)  # a force no damper gives: the state leaves its range
    raises_validation(lambda: plant.tick(0, float("nan")), "must be finite")


def test_check_corner() -> None:
    sim = Scenario.load(FULL_CAR).vehicle_simulations()[0]
    assert check_corner(sim, None) == "front_left"
    assert check_corner(sim, "rear_right") == "rear_right"
    raises_validation(
        lambda: check_corner(sim, "rear", "--corner"),
        "--corner = 'rear' is not a corner of this full car; valid: front_left, "
        "front_right, rear_left, rear_right",
    )
