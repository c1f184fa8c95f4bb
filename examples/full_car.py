"""A full car with an MR damper at every corner: passive against per-corner skyhook.

Runs in a few seconds: the published passenger car (``FullCar()``) at 72 km/h on an
ISO 8608 class C road reaching the rear wheels wheelbase/speed later, then over a bump
under the left wheels only (which rolls the body). Prints the body's heave, pitch and roll
and every wheel's dynamic load coefficient (DLC).
"""

from __future__ import annotations

import numpy as np

from mrsuspension.control import HiLo, Passive
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.excitation import RoundedPulse, WheelRoads, iso8608
from mrsuspension.measures import dlc, rms
from mrsuspension.vehicle import FullCar

SPEED_KMH = 72.0
CONTROLLERS = {"passive 0 A": Passive(0.0), "skyhook hi-lo (ACM)": HiLo(1, mode="ACM")}


def main() -> None:
    car = FullCar()
    print(f"{car.model_name}: m_s = {car.sprung_mass:g} kg, wheelbase {car.wheelbase:.3f} m, "
          f"natural frequencies {np.round(car.natural_frequencies(), 2).tolist()} Hz")  # fmt: skip
    road = WheelRoads.from_excitation(iso8608("C", speed_kmh=SPEED_KMH), car)
    print(f"\nISO 8608 class C road, rear wheels {road.rear_delay * 1e3:.0f} ms late, 10 s:")
    for name, controller in CONTROLLERS.items():
        res = VehicleSimulation(car, road, controllers=controller).run(10.0)
        wheels = ", ".join(f"{c} {dlc(res[f'F_T.{c}']):.3f}" for c in car.corners)
        print(f"  {name:<20} rms heave acc {rms(res.heave_ddot):.3f} m/s^2, "
              f"pitch acc {rms(res.pitch_ddot):.3f} rad/s^2; DLC {wheels}")  # fmt: skip
    # the left wheel track only (the rear wheel L/V later); the right one stays flat
    pulse = RoundedPulse(0.035, 3.0)  # the pulse of eq. (3.38), its w0 as at 50 km/h
    bump = WheelRoads(pulse, None, car.wheelbase, SPEED_KMH, car.track, source="left bump")
    print("\n35 mm bump under the left wheels only, 3 s:")
    for name, controller in CONTROLLERS.items():
        res = VehicleSimulation(car, bump, controllers=controller).run(3.0)
        print(f"  {name:<20} peak roll {np.degrees(np.abs(res.roll).max()):.2f} deg, "
              f"peak roll rate {np.degrees(np.abs(res.roll_dot).max()):.1f} deg/s, "
              f"peak pitch {np.degrees(np.abs(res.pitch).max()):.2f} deg")  # fmt: skip


if __name__ == "__main__":
    main()
