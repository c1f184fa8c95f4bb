"""The whole-vehicle laws through every corner's inverse damper model (control/vehicle_lq.py,
issue 29): ``vehicle-lq-force``, ``vehicle-lqg-force``, ``vehicle-mpc-force``.

* at recorded steps of a full-car run on an ISO C road, every corner's current is the
  inverse model's (``wang_inverse_from`` at the passive hysteron of the step's stroke
  rate, acceleration sign and v_m) of the corner's recorded target force, clipped to
  ``[low_current, high_current]``, and ``z_c = F_h F*`` (1e-9);
* the closed loop is finite, its current continuous (many levels strictly between the
  low and high currents), its comfort printed beside ``vehicle-lq`` and passive 0 A;
* a damper other than the symmetric ``wang-symmetric`` at any corner is refused in one
  line, as for the per-corner inverse-model laws; the quarter car names the per-corner law (tests/unit/control/test_vehicle_lq.py).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from mrsuspension.control import VEHICLE_LAWS
from mrsuspension.control.vehicle_lq import (
    LP_OUTPUT,
    OUT_FORCE,
    VehicleLQ,
    VehicleLQForce,
    VehicleLQGForce,
    VehicleMPCForce,
)
from mrsuspension.dampers import kernels as DK
from mrsuspension.dampers import make_damper
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar

DT = 2e-4  # s; every step recorded (the inputs of step r's law are row r - 1's)
FORCE_LAWS = ("vehicle-lq-force", "vehicle-lqg-force", "vehicle-mpc-force")


@pytest.fixture(scope="module")
def runs() -> dict[str, Any]:
    car = FullCar()
    road = WheelRoads.two_track("C", (car.wheelbase, car.front_track), 72.0, length=60.0, seed=3)
    out: dict[str, Any] = {"car": car}
    laws = {"passive 0 A": None, "vehicle-lq": VehicleLQ(), "vehicle-lq-force": VehicleLQForce(),
            "vehicle-lqg-force": VehicleLQGForce(),
            "vehicle-mpc-force": VehicleMPCForce()}  # fmt: skip
    for name, law in laws.items():
        sim = VehicleSimulation(car, road, body_control=law)
        out[name] = (sim, sim.run(2.5, dt=DT, output_rate=1.0 / DT))
    return out


@pytest.mark.parametrize("law", FORCE_LAWS)
def test_every_corners_current_is_the_inverse_model_of_its_target(
    runs: dict[str, Any], law: str
) -> None:
    """Row ``r`` records step ``r - 1``'s law, run on the state of row ``r - 1``: the
    stroke rate ``v_d = z_u' - z_s'`` and ``a_d = z_u'' - z_s''`` there (ideal sensing),
    the v_m the step latched (row ``r``); the hysteretic inverse (the branch from
    ``sgn(a_d)``), as the per-corner ``lq-force``."""
    car = runs["car"]
    sim, res = runs[law]
    body = sim.body_control
    assert body.params()[LP_OUTPUT] == OUT_FORCE
    low, high = body.low_current, body.high_current
    dp = sim.arrays(DT).damper_params
    inside = 0
    for k, c in enumerate(car.corners):
        col = {key: np.asarray(res[f"{key}.{c}"]) for key in
               ("z_s_dot", "z_u_dot", "z_s_ddot", "z_u_ddot", "v_m", "F_target", "i_d", "z_c")}  # fmt: skip
        for r in range(1, res.time.size, 23):
            target = col["F_target"][r]
            v_d = col["z_u_dot"][r - 1] - col["z_s_dot"][r - 1]
            a_d = col["z_u_ddot"][r - 1] - col["z_s_ddot"][r - 1]
            fh = DK.passive_hysteron(dp[k], v_d, DK.sign(a_d), col["v_m"][r])
            i = min(max(DK.wang_inverse_from(dp[k], target, fh, high), low), high)
            assert abs(col["i_d"][r] - i) <= 1e-9, (c, r, col["i_d"][r], i)
            assert abs(col["z_c"][r] - fh * target) <= 1e-9 * max(1.0, abs(fh * target)), (c, r)
            inside += low < i < high
    assert inside > 50  # the inverse's continuous range, not only its ends, was checked


def test_the_closed_loop_is_finite_and_its_current_continuous(runs: dict[str, Any]) -> None:
    """ISO C, full car, 72 km/h, 2.5 s: finite body accelerations; every ``-force`` law's
    current takes many levels strictly between the low and high currents (hi-lo takes
    two); the seat comfort (ISO 2631 total) printed beside ``vehicle-lq`` and passive
    0 A (which wins is not asserted)."""
    car = runs["car"]
    comfort = {}
    for name in ("passive 0 A", "vehicle-lq", *FORCE_LAWS):
        sim, res = runs[name]
        for key in ("heave_ddot", "pitch_ddot", "roll_ddot"):
            assert np.all(np.isfinite(np.asarray(res[key]))), (name, key)
        comfort[name] = float(res.vehicle_measures()["seat_total"])
        i_d = np.concatenate([np.asarray(res[f"i_d.{c}"]) for c in car.corners])
        if name in FORCE_LAWS:
            law = sim.body_control
            assert np.all((i_d >= law.low_current) & (i_d <= law.high_current)), name
            between = np.unique(i_d[(i_d > law.low_current) & (i_d < law.high_current)])
            assert between.size > 2, (name, between)
        elif name == "vehicle-lq":
            assert set(np.unique(i_d)) <= {0.0, 0.5}
    print("seat total [m/s^2]:", {k: round(v, 4) for k, v in comfort.items()})
    assert all(0.1 < v < 10.0 for v in comfort.values()), comfort


@pytest.mark.parametrize("law", FORCE_LAWS)
@pytest.mark.parametrize(
    ("dampers", "got"),
    [("linear", "got 'linear' at corner front_left"),
     ({"rear_right": "wang-asymmetric"}, "got 'wang-asymmetric' at corner rear_right")],
    ids=["linear everywhere", "asymmetric at the rear right"],
)  # fmt: skip
def test_a_damper_without_the_inverse_model_is_refused_in_one_line(
    law: str, dampers: Any, got: str
) -> None:
    car = FullCar()
    road = WheelRoads.two_track("C", (car.wheelbase, car.front_track), 72.0, length=5.0, seed=3)
    if isinstance(dampers, str):
        given: Any = make_damper(dampers)
    else:
        given = {c: make_damper(m) for c, m in dampers.items()}
    with pytest.raises(ValidationError) as err:
        VehicleSimulation(car, road, dampers=given, body_control=VEHICLE_LAWS[law]())
    text = str(err.value)
    assert "\n" not in text
    assert text.startswith(
        f"controller '{law}' uses the inverse model (model reference, section 2.3) and needs "
        "the 'wang-symmetric' damper model;"
    ), text
    assert text.endswith(got), text
    # the hi-lo law of the same kind drives any damper
    hilo = law.removesuffix("-force")
    VehicleSimulation(car, road, dampers=given, body_control=VEHICLE_LAWS[hilo]())
