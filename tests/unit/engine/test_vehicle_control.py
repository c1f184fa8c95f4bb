"""Sensing in the loop and vehicle-level skyhook (modal, per corner) in the vehicle engine."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.control import HiLo
from mrsuspension.control.modal import CornerSkyhook, ModalSkyhook
from mrsuspension.control.sensing import (
    BandPassObserver,
    LeakyIntegrator,
    Sensing,
    StrokeSensor,
    band_pass_corner,
)
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.engine.vehicle_result import VEHICLE_MEASURE_UNITS
from mrsuspension.errors import ValidationError
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar, HalfCar

DT = 1e-4


def _rough(car: FullCar, length: float = 60.0) -> WheelRoads:
    return WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=54.0, length=length, seed=2
    )


@pytest.fixture(scope="module")
def car() -> FullCar:
    return FullCar()


def test_ideal_sensing_is_the_default(car: FullCar) -> None:
    road = _rough(car)
    a = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM")).run(0.3, dt=DT)
    b = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM"), sensing=Sensing()).run(
        0.3, dt=DT
    )
    for k in a:
        np.testing.assert_array_equal(a[k], b[k], err_msg=k)
    assert "sensing" not in a.scenario
    # the sensed velocity is the one at the step's start: the previous step's true one
    c = VehicleSimulation(car, road, controllers=HiLo(1)).run(0.1, dt=DT, output_rate=1 / DT)
    np.testing.assert_array_equal(c["z_s_dot_sensed.rear_left"][1:], c["z_s_dot.rear_left"][:-1])


def test_long_tau_tends_to_ideal(car: FullCar) -> None:
    road = _rough(car)
    ideal = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM")).run(2.0, dt=DT)
    sensing = Sensing(LeakyIntegrator(tau=1e4, fs=1.0 / DT))
    est = VehicleSimulation(car, road, controllers=HiLo(1, mode="ACM"), sensing=sensing).run(
        2.0, dt=DT
    )
    for c in car.corners:
        v, vh = ideal[f"z_s_dot.{c}"], est[f"z_s_dot_sensed.{c}"]
        assert np.max(np.abs(vh - est[f"z_s_dot.{c}"])) < 0.01 * np.max(np.abs(v))
    rms = np.sqrt(np.mean(ideal["heave_ddot"] ** 2))
    rms_est = np.sqrt(np.mean(est["heave_ddot"] ** 2))
    assert abs(rms_est / rms - 1.0) < 0.01
    assert est.scenario["sensing"]["velocity"]["kind"] == "leaky-integrator"


@pytest.mark.parametrize("kind", ["leaky", "band-pass"])
def test_estimate_equals_the_discrete_filter_offline(car: FullCar, kind: str) -> None:
    """Inside the run the controller sees the exact ZOH filter of the sampled acceleration."""
    fs = 1000.0  # every 10 steps
    est: LeakyIntegrator | BandPassObserver
    if kind == "leaky":
        est = LeakyIntegrator(0.92, fs)
    else:
        est = BandPassObserver(band_pass_corner(1.0, 10.0, fs=fs), fs)
    sim = VehicleSimulation(car, _rough(car), controllers=HiLo(1), sensing=Sensing(est))
    res = sim.run(1.0, dt=DT, output_rate=1.0 / DT)
    every = 10
    for c in car.corners:
        acc = res[f"z_s_ddot.{c}"]  # row k: the acceleration at the start of step k
        offline = est.estimate(acc[:-1:every])
        sensed = res[f"z_s_dot_sensed.{c}"][1:]  # row k + 1: what step k used
        expected = np.repeat(offline, every)[: sensed.size]
        np.testing.assert_allclose(sensed, expected, rtol=1e-12, atol=1e-15)


def _symmetric_car() -> FullCar:
    """CG midway, equal tracks: J J^T is diagonal, so modal skyhook can equal per-corner."""
    return FullCar(cg_to_front=1.3, cg_to_rear=1.3, front_track=1.5, rear_track=1.5)


@pytest.mark.parametrize("sensing", ["ideal", "leaky"])
def test_modal_with_corner_gains_equals_per_corner_skyhook(sensing: str) -> None:
    car = _symmetric_car()
    sens = Sensing() if sensing == "ideal" else Sensing(LeakyIntegrator(0.92, 1.0 / DT))
    road = WheelRoads.two_track("C", (car.wheelbase, 1.5), speed_kmh=54.0, length=60.0, seed=5)
    x, y = car.corner_positions()
    modal = ModalSkyhook.corner_equivalent(x, y, skyhook_damping=6750.0)
    a = VehicleSimulation(car, road, sensing=sens, body_control=modal).run(2.0, dt=DT)
    b = VehicleSimulation(car, road, sensing=sens, body_control=CornerSkyhook(6750.0)).run(
        2.0, dt=DT
    )
    for c in car.corners:
        np.testing.assert_array_equal(a[f"i_d.{c}"], b[f"i_d.{c}"])
        np.testing.assert_allclose(a[f"F_target.{c}"], b[f"F_target.{c}"], rtol=1e-9, atol=1e-9)
    for k in ("heave_ddot", "pitch_ddot", "roll_ddot"):
        scale = np.max(np.abs(a[k]))
        np.testing.assert_allclose(a[k], b[k], rtol=0, atol=1e-9 * scale)
    assert np.ptp(a["roll"]) > 0.0  # the tracks differ: roll is excited and controlled
    assert a.scenario["body_control"]["law"] == "modal-skyhook"


def test_corner_skyhook_switches_on_the_skyhook_condition(car: FullCar) -> None:
    res = VehicleSimulation(car, _rough(car), body_control=CornerSkyhook()).run(1.0, dt=DT)
    for c in car.corners:
        on = res[f"i_d.{c}"] > 0.0
        vs, vd = res[f"z_s_dot_sensed.{c}"], res[f"v_d.{c}"]
        assert on.any()
        assert (~on).any()
        # the current is decided at the step's start; at the record (the step's end) the
        # sign of v_s v_d agrees except near its zero crossings
        assert np.mean(on == (vs * vd < 0.0)) > 0.95


def test_half_car_modal_runs() -> None:
    car = HalfCar()
    road = WheelRoads.two_track(
        "C", (car.wheelbase, None), speed_kmh=54.0, length=40.0, corners="half-car"
    )
    x, _ = car.corner_positions()
    law = ModalSkyhook.corner_equivalent(x)
    res = VehicleSimulation(car, road, body_control=law).run(0.5, dt=DT)
    assert res["i_d.front"].max() == 0.5


def test_stroke_sensor_noise_is_seeded(car: FullCar) -> None:
    road = _rough(car)

    def run(seed: int) -> np.ndarray:
        sens = Sensing(stroke=StrokeSensor(1000.0, resolution=1e-5, noise_std=2e-4, seed=seed))
        sim = VehicleSimulation(car, road, sensing=sens, body_control=CornerSkyhook())
        return sim.run(0.5, dt=DT)["i_d.front_left"]

    a, b, c = run(1), run(1), run(2)
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_bad_sensing_and_law_options(car: FullCar) -> None:
    road = _rough(car)
    with pytest.raises(ValidationError, match="fs = 3000 Hz must divide"):
        VehicleSimulation(car, road, sensing=Sensing(LeakyIntegrator(1.0, 3000.0))).run(0.1, dt=DT)
    with pytest.raises(ValidationError, match="leave the corners' controllers passive"):
        VehicleSimulation(car, road, controllers=HiLo(1), body_control=CornerSkyhook())
    with pytest.raises(ValidationError, match="sensing must be a Sensing"):
        VehicleSimulation(car, road, sensing="leaky")  # type: ignore[arg-type]
    with pytest.raises(ValidationError, match="at most max_current"):
        VehicleSimulation(car, road, body_control=CornerSkyhook(high_current=1.0))
    with pytest.raises(ValidationError, match="body_control must be"):
        VehicleSimulation(car, road, body_control=HiLo(1))  # type: ignore[arg-type]


def test_stepper_with_sensing_matches_run(car: FullCar) -> None:
    """The HiL stepper carries sensing and the vehicle-level law (same step function)."""
    road = _rough(car)
    sens = Sensing(LeakyIntegrator(0.92, 1.0 / DT))
    sim = VehicleSimulation(car, road, sensing=sens, body_control=CornerSkyhook())
    res = sim.run(0.05, dt=DT, output_rate=1.0 / DT)
    n = res.time.size - 1
    t = np.arange(2 * n + 1) * (0.5 * DT)
    zr, zrd = road.displacement(t), road.velocity(t)
    st = sim.stepper(DT)
    st.reset(zr[:, 0], zrd[:, 0])
    for s in range(n):
        j = 2 * s
        out = st.step(
            zr[:, j], zrd[:, j], road_mid=(zr[:, j + 1], zrd[:, j + 1]),
            road_end=(zr[:, j + 2], zrd[:, j + 2]),
        )  # fmt: skip
    assert out["heave"] == pytest.approx(res["heave"][-1], rel=1e-9, abs=1e-15)
    assert out["i_d.rear_right"] == res["i_d.rear_right"][-1]


def test_vehicle_measures(car: FullCar) -> None:
    road = WheelRoads.bump("left", 0.05, 0.5, (car.wheelbase, car.front_track), position=1.0)
    res = VehicleSimulation(car, road, body_control=CornerSkyhook()).run(2.0, dt=DT)
    m = res.vehicle_measures()
    assert m["roll_ddot_rms"] > 0.0
    for c in car.corners:
        for k in ("DLC", "lift_off_time", "rms_travel", "peak_to_peak_travel", "coil_energy"):
            assert f"{k}.{c}" in m
    assert m["coil_energy"] == pytest.approx(sum(m[f"coil_energy.{c}"] for c in car.corners))
    # the left wheels take the bump
    assert m["DLC.front_left"] > m["DLC.front_right"]
    assert m["peak_to_peak_travel.front_left"] > m["peak_to_peak_travel.front_right"]
    for k in m:
        assert k.split(".")[0] in VEHICLE_MEASURE_UNITS
    # seat on the centre line: no roll in the vertical axis
    centre = res.vehicle_measures(seat={"y": 0.0})
    assert centre["seat_z"] != m["seat_z"]
    with pytest.raises(ValidationError, match="unknown seat coordinate 'z'"):
        res.vehicle_measures(seat={"z": 1.0})
    with pytest.raises(ValidationError, match="purpose"):
        res.vehicle_measures(purpose="fun")
