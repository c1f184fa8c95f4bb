"""The simulation engine (MODEL_SPEC section 7): fixed-step RK4 with zero-order-hold
controller outputs, compiled with numba.

* :class:`Simulation` - one run (``Simulation(excitation, ...).run()``);
* :class:`Stepper` - the same compiled step, tick by tick (real-time / HiL loops);
* :func:`run_many` - batches across processes (one per core by default);
* :class:`RunSettings` - ``dt``, ``duration`` and ``output_rate`` of a run;
* :class:`KernelArrays` - the compiled step's arrays by name
  (:meth:`Simulation.kernel_arrays`).

The engine inlines the laws and layouts of :mod:`mrsuspension.control.kernel` and
:mod:`mrsuspension.vehicle.kernel`; neither imports the engine.
"""

from __future__ import annotations

from mrsuspension.engine.arrays import KernelArrays, RunPlan
from mrsuspension.engine.result import SIGNALS, SimulationDiverged, SimulationResult
from mrsuspension.engine.settings import RunSettings
from mrsuspension.engine.simulate import (
    DEFAULT_DT,
    RoadInput,
    Simulation,
    Stepper,
    measures_of,
    run_many,
)

__all__ = [
    "DEFAULT_DT",
    "SIGNALS",
    "KernelArrays",
    "RoadInput",
    "RunPlan",
    "RunSettings",
    "Simulation",
    "SimulationDiverged",
    "SimulationResult",
    "Stepper",
    "measures_of",
    "run_many",
]
