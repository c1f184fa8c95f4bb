"""The simulation engine (model reference, section 7): fixed-step RK4 with zero-order-hold
controller outputs, compiled with numba.

* :class:`Simulation` - one run (``Simulation(excitation, ...).run()``);
* :class:`Stepper` - the same compiled step, tick by tick (real-time / HiL loops);
* :func:`run_many` - batches across processes (one per core by default);
* :class:`RunSettings` - ``dt``, ``duration`` and ``output_rate`` of a run;
* :class:`KernelArrays` - the compiled step's arrays by name
  (:meth:`Simulation.kernel_arrays`);
* :class:`Measures` - a run's measures: a ``dict`` that carries their units
  (``result.measures().units``);
* :class:`VehicleSimulation` - a half or full car with a damper and a controller at every
  corner on a :class:`WheelInput` (e.g. :class:`~mrsuspension.excitation.WheelRoads`), and
  :func:`run_vehicles` for batches, loaded on first use (:mod:`mrsuspension.engine.vehicle`).

The engine inlines the laws and layouts of :mod:`mrsuspension.control.kernel` and
:mod:`mrsuspension.vehicle.kernel`; neither imports the engine.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from mrsuspension._lazy import lazy_namespace
from mrsuspension._notebook import Measures
from mrsuspension.engine.arrays import KernelArrays
from mrsuspension.engine.result import SIGNALS, SimulationDiverged, SimulationResult
from mrsuspension.engine.settings import RunPlan, RunSettings
from mrsuspension.engine.simulate import (
    DEFAULT_DT,
    RoadInput,
    Simulation,
    Stepper,
    measures_of,
    run_many,
)

if TYPE_CHECKING:
    from mrsuspension.engine.vehicle import (
        VehicleSimulation,
        WheelInput,
        run_vehicles,
    )
    from mrsuspension.engine.vehicle_result import VehicleResult

# the vehicle models compile their own step: load them on first use
_VEHICLE = (
    "VehicleResult",
    "VehicleSimulation",
    "WheelInput",
    "run_vehicles",
)
__getattr__, __dir__ = lazy_namespace(
    __name__,
    {
        **dict.fromkeys(_VEHICLE, "mrsuspension.engine.vehicle"),
        "VehicleResult": "mrsuspension.engine.vehicle_result",
    },
    globals(),
)

__all__ = [
    "DEFAULT_DT",
    "SIGNALS",
    "KernelArrays",
    "Measures",
    "RoadInput",
    "RunPlan",
    "RunSettings",
    "Simulation",
    "SimulationDiverged",
    "SimulationResult",
    "Stepper",
    "VehicleResult",
    "VehicleSimulation",
    "WheelInput",
    "measures_of",
    "run_many",
    "run_vehicles",
]
