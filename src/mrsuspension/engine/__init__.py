"""The simulation engine (MODEL_SPEC section 7): fixed-step RK4 with zero-order-hold
controller outputs, compiled with numba.

* :class:`Simulation` - one run (``Simulation(excitation, ...).run()``);
* :class:`Stepper` - the same compiled step, tick by tick (real-time / HiL loops);
* :func:`run_many` - batches across processes (one per core by default).
"""

from __future__ import annotations

from mrsuspension.engine.result import SIGNALS, SimulationResult
from mrsuspension.engine.simulate import (
    DEFAULT_DT,
    RoadInput,
    Simulation,
    SimulationDiverged,
    Stepper,
    run_many,
)

__all__ = [
    "DEFAULT_DT",
    "SIGNALS",
    "RoadInput",
    "Simulation",
    "SimulationDiverged",
    "SimulationResult",
    "Stepper",
    "run_many",
]
