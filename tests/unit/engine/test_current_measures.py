"""Currents are reported only where a damper takes one (issue 31, item 5).

A linear damper ignores the current its controller commands: its runs report no
``mean_current`` / ``mean_square_current`` (quarter car, a vehicle's corners, the in-kernel
reduction alike), its corner no ``coil_energy``; an MR damper's runs keep them.
"""

from __future__ import annotations

import math

import pytest

from mrsuspension.control import HiLo, Passive
from mrsuspension.dampers import DAMPERS, LinearViscous, WangSymmetric, takes_current
from mrsuspension.engine import Simulation
from mrsuspension.engine.reduced import run_measures
from mrsuspension.engine.result import CURRENT_MEASURES
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import Harmonic, RoadProfile, WheelRoads
from mrsuspension.vehicle import HalfCar

DT = 2e-4
EXC = Harmonic(5.0, 0.005)  # its own duration: 10 settled cycles (steady-state rule)


def test_only_the_linear_model_takes_no_current() -> None:
    assert {name for name, cls in DAMPERS.items() if not cls.takes_current} == {"linear"}
    assert not takes_current(LinearViscous().describe())
    assert takes_current(WangSymmetric().describe())


@pytest.mark.parametrize("damper", [LinearViscous(), WangSymmetric()], ids=["linear", "wang"])
def test_quarter_car_reports_current_only_for_an_mr_damper(damper: object) -> None:
    sim = Simulation(EXC, damper=damper, controller=HiLo(1, mode="ACM"))
    post = sim.run(dt=DT).measures()
    kernel = run_measures(sim, dt=DT)
    for m in (post, kernel):
        has = [k for k in CURRENT_MEASURES if k in m]
        if isinstance(damper, LinearViscous):
            assert has == []
            assert math.isfinite(m["T_as"])
        else:
            assert has == list(CURRENT_MEASURES)
            assert 0.0 < m["mean_current"] <= 0.5


def test_vehicle_corner_with_a_linear_damper_has_no_current() -> None:
    car = HalfCar()
    track = RoadProfile.from_options({"iso_class": "C", "length": 12.0, "seed": 1})
    road = WheelRoads.from_excitation(track, car, speed_kmh=50.0)  # a road: any duration
    sim = VehicleSimulation(
        car,
        road,
        dampers={"front": LinearViscous(), "rear": WangSymmetric()},
        controllers={c: Passive(0.2) for c in car.corners},
    )
    res = sim.run(0.6, dt=DT)
    # the controller does command a current at the linear corner: it must not be reported
    assert float(res["i_d.front"].mean()) == pytest.approx(0.2, rel=0.01)
    for m in (res.measures(), sim.run_measures(0.6, dt=DT)):
        assert "mean_current.front" not in m
        assert "mean_square_current.front" not in m
        assert m["mean_current.rear"] == pytest.approx(0.2, rel=0.01)
        assert "DLC.front" in m
    vm = res.vehicle_measures()
    assert "coil_energy.front" not in vm
    assert vm["coil_energy"] == pytest.approx(vm["coil_energy.rear"])
    assert vm["coil_energy.rear"] > 0.0
