"""The simulation engine (MODEL_SPEC section 7): fixed-step RK4 with zero-order-hold
controller outputs, compiled with numba.

* :class:`Simulation` - one run (``Simulation(excitation, ...).run()``);
* :class:`Stepper` - the same compiled step, tick by tick (real-time / HiL loops);
* :func:`run_many` - batches across processes (one per core by default);
* :class:`RunSettings` - ``dt``, ``duration`` and ``output_rate`` of a run.

The names are loaded on first use, so that :mod:`mrsuspension.control` can use the
kernel constants of :mod:`mrsuspension.engine.kernel` without a circular import.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from mrsuspension.engine.result import SIGNALS, SimulationResult
    from mrsuspension.engine.settings import RunSettings
    from mrsuspension.engine.simulate import (
        DEFAULT_DT,
        RoadInput,
        Simulation,
        SimulationDiverged,
        Stepper,
        measures_of,
        run_many,
    )

_WHERE = {
    "SIGNALS": "result",
    "SimulationResult": "result",
    "DEFAULT_DT": "simulate",
    "RoadInput": "simulate",
    "RunSettings": "settings",
    "Simulation": "simulate",
    "SimulationDiverged": "simulate",
    "Stepper": "simulate",
    "measures_of": "simulate",
    "run_many": "simulate",
}

__all__ = [
    "DEFAULT_DT",
    "SIGNALS",
    "RoadInput",
    "RunSettings",
    "Simulation",
    "SimulationDiverged",
    "SimulationResult",
    "Stepper",
    "measures_of",
    "run_many",
]


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        module = importlib.import_module(f"mrsuspension.engine.{_WHERE[name]}")
        return getattr(module, name)
    raise AttributeError(f"module 'mrsuspension.engine' has no attribute {name!r}")
