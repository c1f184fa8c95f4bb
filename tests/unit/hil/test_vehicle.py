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


def _full_car(**kw: object) -> object:
    from mrsuspension.engine.vehicle import VehicleSimulation
    from mrsuspension.excitation import Harmonic, WheelRoads
    from mrsuspension.vehicle import FullCar

    return VehicleSimulation(FullCar(), WheelRoads.in_phase(Harmonic(1.5, 0.01), "full-car"), **kw)


@pytest.mark.parametrize(
    ("what", "fragment"),
    [
        ("ideal-skyhook", "controller law 'ideal-skyhook' does not command the damper's current"),
        ("lq-active", "controller law 'lq-active' does not command the damper's current"),
        ("vehicle-lq-active", "whole-vehicle law 'vehicle-lq-active' drives ideal actuators"),
    ],
)
def test_a_law_that_does_not_drive_the_damper_is_refused_before_the_run(
    tmp_path: Path, what: str, fragment: str
) -> None:
    """An ideal force or actuator at the rig would leave it at 0 A while the run looked
    controlled: refused with one line before anything starts or is written (in the process
    mode, in the parent)."""
    from mrsuspension.control import make_controller
    from mrsuspension.control.vehicle_lq import VehicleLQActive
    from mrsuspension.hil import run_hil

    if what == "vehicle-lq-active":
        sim = _full_car(body_control=VehicleLQActive())
    else:
        sim = _full_car(controllers={"rear_left": make_controller(what)})
    out = tmp_path / "rec"
    for process in (False, True):
        raises_validation(
            lambda p=process: run_hil(sim, corner="rear_left", duration=0.1, out=out, process=p),
            fragment,
            "the rig would be sent 0 A",
        )
    assert not out.exists()


def test_laws_that_drive_the_damper_pass_the_check() -> None:
    from mrsuspension.control import make_controller
    from mrsuspension.control.modal import ModalSkyhook
    from mrsuspension.hil.loop import check_drives_damper

    check_drives_damper(_full_car(), "rear_left")
    check_drives_damper(_full_car(body_control=ModalSkyhook()), "rear_left")
    elsewhere = _full_car(controllers={"front_left": make_controller("ideal-skyhook")})
    check_drives_damper(elsewhere, "rear_left")  # the rig's corner drives its damper
    raises_validation(lambda: check_drives_damper(elsewhere, "front_left"), "ideal-skyhook")


@pytest.mark.parametrize("law", ["vehicle-lq", "modal-skyhook"])
def test_a_whole_vehicle_law_runs_in_the_loop_capped_at_the_safety_current(law: str) -> None:
    """The loop lowers the car's ``max_current`` to the safety limit (0.3 A by default); a
    whole-vehicle law's default ``high_current`` (0.5 A) was then refused and no whole-vehicle
    law could run in the loop. Its high current is capped with it, as a per-corner law's
    demand is clipped, and no tick sends more than the limit."""
    from mrsuspension.control.registry import VEHICLE_LAWS
    from mrsuspension.hil import SafetyLimits, run_hil

    body = VEHICLE_LAWS[law]()
    assert body.high_current > SafetyLimits().current
    result = run_hil(
        _full_car(body_control=body), corner="rear_left", duration=0.3, realtime="unpaced"
    )
    assert result.reason == "completed", result.reason
    demand = np.asarray(result.recording["i_d"])
    assert demand.max() <= SafetyLimits().current + 1e-12
    assert demand.max() > 0.0  # the law does drive the rig's damper
