"""Modal skyhook (control/modal.py): exact modal wrench, corner equivalence, clipping."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.control.modal import (
    ModalSkyhook,
    clipped_force,
    corner_velocity,
    distribution_matrix,
    hilo_current,
    switching_condition,
)
from mrsuspension.errors import ValidationError

# an asymmetric full car: CG 1.2 m behind the front axle, 1.6 m ahead of the rear,
# front track 1.50 m, rear track 1.56 m (FL, FR, RL, RR)
X = np.array([1.2, 1.2, -1.6, -1.6])
Y = np.array([0.75, -0.75, 0.78, -0.78])
SKY = ModalSkyhook(heave=20000.0, pitch=35000.0, roll=9000.0)


def _wrench(forces: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """(F_z, M_theta, M_phi) of upward corner forces (ISO 8855: pitch nose down, roll left up)."""
    return np.array([forces.sum(), -(forces * x).sum(), (forces * y).sum()])


@pytest.mark.parametrize(
    "rates", [(0.1, 0.0, 0.0), (0.0, 0.05, 0.0), (0.0, 0.0, -0.2), (0.3, -0.04, 0.07)]
)
def test_full_car_reproduces_the_modal_wrench(rates: tuple[float, float, float]) -> None:
    vz, q, p = rates
    f = SKY.forces(distribution_matrix(X, Y), heave_velocity=vz, pitch_rate=q, roll_rate=p)
    expected = np.array([-SKY.heave * vz, -SKY.pitch * q, -SKY.roll * p])
    assert np.allclose(_wrench(f, X, Y), expected, rtol=1e-12, atol=1e-9)


def test_half_car_reproduces_the_modal_wrench() -> None:
    x = np.array([1.3, -1.5])
    f = SKY.forces(distribution_matrix(x), heave_velocity=0.2, pitch_rate=-0.1)
    assert np.allclose(_wrench(f, x, np.zeros(2))[:2], [-4000.0, 3500.0], rtol=1e-12)


def test_hand_derived_symmetric_case() -> None:
    # a = b = 1.4 m, track 1.5 m: F_i = -c_z vz/4 + c_theta q x_i/sum x^2 - c_phi p y_i/sum y^2
    x = np.array([1.4, 1.4, -1.4, -1.4])
    y = np.array([0.75, -0.75, 0.75, -0.75])
    sky = ModalSkyhook(heave=8000.0, pitch=7840.0, roll=2250.0)
    f = sky.forces(distribution_matrix(x, y), heave_velocity=0.1, pitch_rate=0.05, roll_rate=0.2)
    # heave -200 N each; pitch 7840*0.05*1.4/7.84 = +-70 N; roll 2250*0.2*0.75/2.25 = -+150 N
    assert f.tolist() == pytest.approx([-280.0, 20.0, -420.0, -120.0], abs=1e-9)


def test_corner_equivalent_is_per_corner_skyhook() -> None:
    x = np.array([1.4, 1.4, -1.4, -1.4])
    y = np.array([0.75, -0.75, 0.75, -0.75])
    sky = ModalSkyhook.corner_equivalent(x, y, skyhook_damping=6750.0)
    vz, q, p = 0.12, -0.03, 0.05
    f = sky.forces(distribution_matrix(x, y), heave_velocity=vz, pitch_rate=q, roll_rate=p)
    corner = [-6750.0 * corner_velocity(vz, q, p, xi, yi) for xi, yi in zip(x, y, strict=True)]
    assert np.allclose(f, corner, rtol=1e-12)


def test_signs_resist_the_motion() -> None:
    d = distribution_matrix(X, Y)
    nose_down = SKY.forces(d, heave_velocity=0.0, pitch_rate=0.1)
    assert nose_down[0] > 0
    assert nose_down[2] < 0
    left_up = SKY.forces(d, heave_velocity=0.0, pitch_rate=0.0, roll_rate=0.1)
    assert left_up[0] < 0
    assert left_up[1] > 0


@pytest.mark.parametrize(
    ("force", "vd", "high"),
    [
        (100.0, 0.2, True),  # up force, compression: damper pushes the body up
        (100.0, -0.2, False),  # up force, rebound: damper would pull down
        (-100.0, -0.2, True),  # down force, rebound
        (-100.0, 0.2, False),  # down force, compression
        (0.0, 0.2, False),
        (100.0, 0.0, False),
    ],
)
def test_clipping_quadrants(force: float, vd: float, high: bool) -> None:
    zc = switching_condition(force, vd)
    assert hilo_current(zc, 0.05, 0.5) == (0.5 if high else 0.05)
    assert clipped_force(force, vd) == (force if high else 0.0)
    currents, zcs = SKY.currents([force], [vd])
    assert currents[0] == (0.5 if high else 0.0)
    assert zcs[0] == zc


def test_clipping_agrees_with_skyhook_hilo() -> None:
    # skyhook F* = -c_s z_s' is on exactly when policy I's z_c = z_s' v_d < 0
    for vs in (-0.3, 0.3):
        for vd in (-0.2, 0.2):
            on = switching_condition(-6750.0 * vs, vd) < 0
            assert on == (vs * vd < 0)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: ModalSkyhook(1.0, -2.0), "pitch must be in \\[0, inf\\) N m s/rad; got -2"),
        (lambda: ModalSkyhook(1.0, 1.0, low_current=0.3, high_current=0.1), "high_current"),
        (lambda: distribution_matrix([1.0, 1.0]), "x positions must differ"),
        (lambda: distribution_matrix([1.0, 1.0, -1.0], [0.5, 0.5, 0.5]), "on one line"),
        (lambda: distribution_matrix([1.0, -1.0], [0.5, 0.5, 0.5]), "every corner"),
        (lambda: SKY.currents([1.0, 2.0], [0.1]), "one value per corner"),
    ],
)
def test_bad_input(call: object, message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        call()  # type: ignore[operator]
