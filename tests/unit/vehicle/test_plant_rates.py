"""The quarter car's compiled rates (model reference, section 4) against hand-derived values."""

from __future__ import annotations

import math

import pytest

from mrsuspension.vehicle import GRAVITY, QuarterCar
from mrsuspension.vehicle import kernel as VK

CAR = QuarterCar()


def rates(
    zs: float = 0.0,
    vs: float = 0.0,
    zu: float = 0.0,
    vu: float = 0.0,
    zr: float = 0.0,
    zrd: float = 0.0,
    fd: float = 0.0,
    car: QuarterCar = CAR,
    reference: tuple[float, float, float, float, float] | None = None,
) -> tuple[float, float, float, float]:
    """:func:`plant_rates` from the car's parameter vector, as the engine calls it."""
    vp = car.params()
    z0, v0, c0, cs, ms0 = reference if reference is not None else (0.0, 0.0, 0.0, 0.0, 1.0)
    return VK.plant_rates(
        zs, vs, zu, vu, z0, v0, zr, zrd, fd, vp[VK.V_KS], vp[VK.V_CSKY], 1.0 / vp[VK.V_MS],
        1.0 / vp[VK.V_MU], (vp[VK.V_MS] + vp[VK.V_MU]) * vp[VK.V_G], vp[VK.V_KT], vp[VK.V_CT],
        vp[VK.V_DXU], reference is not None, c0, cs, 1.0 / ms0,
    )  # fmt: skip


def test_at_rest_on_a_static_road_nothing_accelerates() -> None:
    a_s, a_u, a_0, ft = rates()
    assert a_s == 0.0
    assert abs(a_u) < 1e-12
    assert a_0 == 0.0
    assert ft == pytest.approx(CAR.total_mass * GRAVITY, rel=1e-15)


def test_a_suspension_displacement_gives_the_spring_force_over_the_mass() -> None:
    x = 0.02  # body 2 cm down, wheel and road at rest: spring compressed by 2 cm
    a_s, a_u, _, ft = rates(zs=-x)
    assert a_s == pytest.approx(CAR.suspension_stiffness * x / CAR.sprung_mass, rel=1e-14)
    # the wheel feels the spring pushing it down; the tire still carries the weight
    assert a_u == pytest.approx(-CAR.suspension_stiffness * x / CAR.unsprung_mass, rel=1e-12)
    assert ft == pytest.approx(CAR.static_load, rel=1e-15)


def test_damper_and_tire_forces() -> None:
    fd, dz, dv = 500.0, 0.005, 0.1  # damper force; wheel 5 mm up, moving up at 0.1 m/s
    a_s, a_u, _, ft = rates(zu=dz, vu=dv, zs=dz, fd=fd)
    tire = CAR.tire_stiffness * (CAR.static_tire_deflection - dz) - CAR.tire_damping * dv
    assert ft == pytest.approx(tire, rel=1e-14)
    assert a_s == pytest.approx(fd / CAR.sprung_mass, rel=1e-14)
    assert a_u == pytest.approx((tire - CAR.static_load - fd) / CAR.unsprung_mass, rel=1e-10)


def test_the_tire_lifts_off_and_never_pulls() -> None:
    up = CAR.static_tire_deflection + 1e-3  # the whole car 1 mm above the free tire
    lifted = rates(zs=up, zu=up)
    assert lifted[3] == 0.0
    assert lifted[1] == pytest.approx(-GRAVITY * CAR.total_mass / CAR.unsprung_mass)
    pulling = rates(vu=100.0)  # in contact, but the tire's damping would pull
    assert pulling[3] == 0.0


def test_skyhook_damping_and_the_reference_model() -> None:
    sky = QuarterCar.reference()
    a_s, _, _, _ = rates(vs=0.2, car=sky)
    assert a_s == pytest.approx(-sky.skyhook_damping * 0.2 / sky.sprung_mass, rel=1e-14)
    z0, v0, c0, cs, ms0 = 0.01, -0.1, 2500.0, 6750.0, 563.0
    zu, vu = 0.002, 0.05
    _, _, a_0, _ = rates(zu=zu, vu=vu, zs=zu, reference=(z0, v0, c0, cs, ms0))
    # (3.18): m_s0 z_s0'' = -c_0 (z_s0' - z_u') - c_s z_s0' - k_s (z_s0 - z_u)
    expected = (-c0 * (v0 - vu) - cs * v0 - CAR.suspension_stiffness * (z0 - zu)) / ms0
    assert math.isclose(a_0, expected, rel_tol=1e-14)
