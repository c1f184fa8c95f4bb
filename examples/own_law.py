"""Your own control law in plain Python, against passive, on a quarter car and a full car.

The law reads the measured signals by name (``z_s_dot``, ``v_d``, ...: the table in
``docs/control-laws.md``) and returns the drive current [A]; its options are the
parameters with defaults. Decorated with ``mrsuspension.control.law`` it runs inside the
compiled engine (numba) wherever a built-in law runs: ``Simulation``,
``VehicleSimulation`` at every corner, sweeps, the optimiser and the HiL loop. A scenario
names it ``[controller] law = "own_law.py:groundhook_skyhook"``.

Here: a hybrid skyhook-groundhook on-off law (the literature's laws are built in as well:
``mrsuspension.control.literature``), at 1.5 Hz on the quarter car and on an ISO class C
road on the full car.
"""

from __future__ import annotations

import numpy as np

from mrsuspension.control import Passive, law
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.measures import rms
from mrsuspension.vehicle import FullCar


@law
def groundhook_skyhook(z_s_dot, z_u_dot, v_d, alpha=0.8, high=0.5):
    """On-off hybrid: high current when the desired force opposes the stroke rate.

    Desired force (up on the body) ``F = -(alpha z_s' - (1 - alpha) z_u')`` [per N s/m]:
    skyhook at ``alpha = 1``, groundhook at 0.
    """
    desired = -(alpha * z_s_dot - (1.0 - alpha) * z_u_dot)
    return high if desired * v_d > 0.0 else 0.0


def main() -> None:
    print(f"law {groundhook_skyhook.law}: runs on the {groundhook_skyhook.path()} path")
    laws = {"passive 0.1 A": Passive(0.1), "hybrid on-off": groundhook_skyhook(alpha=0.8)}
    print("quarter car, 1.5 Hz, 20 mm:")
    for name, controller in laws.items():
        res = Simulation(Harmonic(1.5, 0.02), controller=controller).run(6.0)
        steady = res.time >= 3.0
        print(f"  {name:14s} rms z_s'' {rms(res['z_s_ddot'][steady]):.3f} m/s^2, "
              f"rms F_T {rms(res['F_T'][steady] - res['F_T'].mean()):.0f} N")  # fmt: skip
    car = FullCar()
    road = WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=72.0, length=60.0, seed=1
    )
    print("full car, ISO class C road, 72 km/h (the law at every corner):")
    for name, controller in laws.items():
        res = VehicleSimulation(car, road, controllers=controller).run(2.0)
        print(f"  {name:14s} rms heave'' {rms(res['heave_ddot']):.3f} m/s^2, "
              f"rms pitch'' {rms(res['pitch_ddot']):.3f} rad/s^2, "
              f"mean i_d {np.mean(res['i_d.front_left']):.3f} A")  # fmt: skip


if __name__ == "__main__":
    main()
