"""The run contract: what every plant's run offers the engine's callers.

One home for the protocol that :class:`~mrsuspension.engine.simulate.Simulation`,
:class:`~mrsuspension.engine.vehicle.VehicleSimulation` and any registered model's runs
keep (:mod:`mrsuspension.engine.plants` registers the models; :mod:`mrsuspension.engine.batch`
runs many). It imports nothing of the models, so every model module may name it.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

from mrsuspension.engine.settings import RunPlan

__all__ = ["RunModel"]


@runtime_checkable
class RunModel(Protocol):
    """The run contract: what every plant's run offers its callers.

    ``model_name`` names its :class:`Plant` (the ``[vehicle] model``); ``excitation`` is
    its road input (it sets the default duration,
    :meth:`RunSettings.duration_for <mrsuspension.engine.settings.RunSettings.duration_for>`);
    ``describe()`` is plain data naming the run; ``max_stable_dt()`` the RK4 stability
    limit [s] and ``check_dt(dt)`` its refusal; ``record_values(plan)`` the values a
    recorded run keeps (the memory check); ``run(...)`` the result (with
    ``measures(**kwargs)``); ``stepper(dt)`` a step-by-step driver (the HiL loop).
    """

    @property
    def model_name(self) -> str: ...

    @property
    def excitation(self) -> Any: ...

    def describe(self) -> dict[str, Any]: ...

    def max_stable_dt(self) -> float: ...

    def check_dt(self, dt: float) -> float: ...

    def record_values(self, plan: RunPlan) -> float: ...

    def run(
        self,
        duration: float | None = None,
        *,
        dt: float | None = None,
        output_rate: float | None = None,
        settings: Any = None,
    ) -> Any: ...

    def stepper(self, dt: float = ...) -> Any: ...
