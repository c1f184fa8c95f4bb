"""Half and full car: validation, geometry, static loads and the closed-form response."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.vehicle import GRAVITY, QuarterCar, linear_frequency_response
from mrsuspension.vehicle.body import (
    CORNERS_FULL,
    CORNERS_HALF,
    FullCar,
    HalfCar,
    available_sets,
    delay_phasors,
)


@pytest.mark.parametrize(
    ("cls", "changes", "message"),
    [
        (FullCar, {"roll_inertia": -5.0}, "roll_inertia must be in (0, 1e+07] kg m^2; got -5 kg m^2"),
        (HalfCar, {"pitch_inertia": -1.0}, "pitch_inertia must be in (0, 1e+07] kg m^2; got -1 kg m^2"),
        (HalfCar, {"cg_to_front": 0.0, "cg_to_rear": 0.0},
         "wheelbase cg_to_front + cg_to_rear must be > 0 m; got 0 + 0 = 0 m"),
        (FullCar, {"front_track": 0.0}, "front_track must be in (0, 20] m; got 0 m"),
        (FullCar, {"sprung_mass": float("nan")}, "sprung_mass must be finite and in [1, 100000] kg; got nan"),
    ],
)  # fmt: skip
def test_bad_parameters_say_field_value_and_range(cls, changes, message) -> None:
    with pytest.raises(ValidationError) as info:
        cls(**changes)
    assert str(info.value) == message
    assert "\n" not in str(info.value)


def test_unknown_names_suggest_the_closest() -> None:
    with pytest.raises(ValidationError, match="Did you mean 'rear_right'"):
        FullCar().corner_index("rear_rigth")
    with pytest.raises(ValidationError, match="Did you mean 'roll_inertia'"):
        FullCar().with_(rol_inertia=3.0)
    with pytest.raises(ValidationError, match="unknown vehicle parameter set"):
        FullCar.from_set("no-such-car")


def test_published_set_and_geometry() -> None:
    assert available_sets() == ["full-car-kalman-2023"]
    car = FullCar.from_set("full-car-kalman-2023")
    assert car == FullCar()
    assert car.corners == CORNERS_FULL
    assert HalfCar.corners == CORNERS_HALF
    x, y = car.corner_positions()
    assert x.tolist() == [1.116, 1.116, -1.232, -1.232]
    assert y.tolist() == [0.621, -0.621, 0.621, -0.621]
    # the static loads carry the car and balance its pitch and roll moments
    w = car.static_sprung_loads()
    assert w.sum() == pytest.approx(car.sprung_mass * GRAVITY, rel=1e-14)
    assert (x * w).sum() == pytest.approx(0.0, abs=1e-9)
    assert (y * w).sum() == pytest.approx(0.0, abs=1e-9)
    assert car.static_tire_loads() == pytest.approx(w + car.unsprung_masses * GRAVITY)
    assert HalfCar.from_set() == HalfCar()


def test_quarter_car_corner_is_a_special_case() -> None:
    qc = QuarterCar()
    for car in (HalfCar.from_quarter_car(qc), FullCar.from_quarter_car(qc)):
        for c in car.corners:
            assert car.corner_quarter_car(c) == qc
        assert car.pitch_inertia == pytest.approx(
            car.sprung_mass * car.cg_to_front * car.cg_to_rear
        )


def test_linear_matrices_are_symmetric_and_carry_the_car() -> None:
    car = FullCar(front_anti_roll_stiffness=20_000.0, rear_anti_roll_stiffness=8000.0)
    lin = car.linear_matrices({c: 1500.0 for c in car.corners})
    assert np.allclose(lin.K, lin.K.T)
    assert np.allclose(lin.C, lin.C.T)
    assert np.all(np.linalg.eigvalsh(lin.K) > 0.0)
    # a static road lift of every wheel lifts the whole car: K q = K_road 1
    q = np.linalg.solve(lin.K, lin.K_road @ np.ones(4))
    assert q == pytest.approx([1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], abs=1e-12)
    # the anti-roll bars stiffen roll only: same heave and pitch stiffness
    plain = FullCar().linear_matrices(1500.0)
    assert lin.K[:2, :2] == pytest.approx(plain.K[:2, :2])
    assert lin.K[2, 2] > plain.K[2, 2]


@pytest.mark.parametrize("cls", [HalfCar, FullCar])
def test_decoupled_frequency_response_is_the_quarter_cars(cls) -> None:
    """Hand-derived case: with I_y = m a b (and I_x = m t^2/4) and the same road at every
    wheel, the corners are independent quarter cars: body and wheel at each corner follow
    the quarter car's closed-form transmissibility (and the body only heaves)."""
    qc = QuarterCar()
    car = cls.from_quarter_car(qc)
    f = np.geomspace(0.5, 20.0, 30)
    r = car.frequency_response(f, qc_damping := 2500.0)
    q = linear_frequency_response(qc, qc_damping, f)
    for c in car.corners:
        assert np.abs(r[f"z_s.{c}"]) == pytest.approx(q["T_as"], rel=1e-12)
        assert np.abs(r[f"z_u.{c}"]) == pytest.approx(q["T_au"], rel=1e-12)
        assert np.abs(r[f"x_d.{c}"]) == pytest.approx(q["T_dr"], rel=1e-12)
        dlc = np.abs(r[f"F_T.{c}"]) / math.sqrt(2.0) / qc.static_load
        assert dlc == pytest.approx(q["DLC"], rel=1e-12)
    assert np.abs(r["pitch"]).max() < 1e-12


def test_half_car_pitch_closed_form_at_zero_frequency_limit() -> None:
    """Quasi-static road with a delay: the body follows the road's heave and slope."""
    car = HalfCar()
    f = np.array([1e-3])
    tau = 0.1
    road = delay_phasors(f, [0.0, tau])
    r = car.frequency_response(f, 1500.0, road)
    zf, zr = road[0]
    heave = (car.cg_to_rear * zf + car.cg_to_front * zr) / car.wheelbase
    pitch = (zr - zf) / car.wheelbase  # z - a theta = z_r,front, z + b theta = z_r,rear
    assert abs(r["heave"][0] - heave) < 1e-4 * abs(heave)
    assert abs(r["pitch"][0] - pitch) < 1e-3 * abs(pitch)


def test_frequency_response_checks_its_road() -> None:
    with pytest.raises(ValidationError, match=r"one phasor per corner \(4\)"):
        FullCar().frequency_response([1.0], 1500.0, road=[1.0, 1.0])
    with pytest.raises(ValidationError, match="frequency must be > 0 Hz"):
        FullCar().frequency_response([0.0], 1500.0)
    with pytest.raises(ValidationError, match="damping must be in"):
        FullCar().frequency_response([1.0], -5.0)
