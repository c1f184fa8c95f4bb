"""MR-damper models behind one interface.

========================  =============================================================
``"wang-symmetric"``      :class:`WangSymmetric`, the dissertation's model (2.15)
``"wang-asymmetric"``     :class:`WangAsymmetric`, eqs. (2.19)-(2.21)
``"bingham"``             :class:`Bingham`, current-dependent Bingham plastic
``"spencer"``             :class:`SpencerBoucWen`, Spencer et al. (1997)
``"linear"``              :class:`LinearViscous`, ``F = c v``
========================  =============================================================

Examples
--------
>>> from mrsuspension.dampers import make_damper
>>> damper = make_damper("wang-symmetric", "wang-symmetric-low", hysteresis=False)
>>> round(float(damper.force(0.0, 0.1, 0.0, 0.2, peak_velocity=0.25)), 1)
1109.2
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from mrsuspension.dampers.base import DamperKernel, DamperModel, DamperResponse, ParameterSpec
from mrsuspension.dampers.peak_velocity import (
    ESTIMATORS,
    CycleRms,
    InstantaneousPeak,
    KnownPeak,
    PeakVelocityEstimator,
    WindowPeak,
    make_estimator,
)
from mrsuspension.dampers.peers import Bingham, LinearViscous, SpencerBoucWen
from mrsuspension.dampers.wang import WangAsymmetric, WangSymmetric
from mrsuspension.errors import ValidationError, unknown_name

__all__ = [
    "DAMPERS",
    "DAMPER_OPTIONS",
    "ESTIMATORS",
    "SCENARIO_COMMON_OPTIONS",
    "Bingham",
    "CycleRms",
    "DamperKernel",
    "DamperModel",
    "DamperResponse",
    "InstantaneousPeak",
    "KnownPeak",
    "LinearViscous",
    "PeakVelocityEstimator",
    "SpencerBoucWen",
    "WangAsymmetric",
    "WangSymmetric",
    "WindowPeak",
    "damper_options",
    "make_damper",
    "make_estimator",
    "takes_current",
]

#: Damper models by registry name.
DAMPERS: dict[str, type[DamperModel]] = {
    "wang-symmetric": WangSymmetric,
    "wang-asymmetric": WangAsymmetric,
    "bingham": Bingham,
    "spencer": SpencerBoucWen,
    "linear": LinearViscous,
}


#: ``[damper]`` keys every model accepts: the registry name, the parameter set and the
#: simulation's drive-current limit i_max
SCENARIO_COMMON_OPTIONS: dict[str, str] = {
    "model": "string",
    "parameters": "string",
    "max_current": "number",
}


def damper_options(model: str) -> dict[str, str]:
    """The ``[damper]`` keys a scenario may set for ``model``, with their value kind.

    The common keys (:data:`SCENARIO_COMMON_OPTIONS`) and the model class's own
    ``scenario_options`` (none when a model declares none).

    Raises
    ------
    ValidationError
        An unregistered model, naming it and the valid ones.

    Examples
    --------
    >>> sorted(damper_options("linear"))
    ['damping', 'max_current', 'model', 'parameters']
    >>> damper_options("lineer")
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: unknown damper model 'lineer'. Did you mean 'linear'? Valid: bingham, linear, spencer, wang-asymmetric, wang-symmetric.
    """
    if model not in DAMPERS:
        raise unknown_name("damper model", str(model), DAMPERS)
    own: dict[str, str] = getattr(DAMPERS[model], "scenario_options", {})
    return {**SCENARIO_COMMON_OPTIONS, **own}


#: ``[damper]`` keys by model, derived from the classes (see :func:`damper_options`).
DAMPER_OPTIONS: dict[str, dict[str, str]] = {m: damper_options(m) for m in DAMPERS}


def make_damper(model: str, parameters: ParameterSpec = None, **options: Any) -> DamperModel:
    """Build a damper model by name, with a parameter set (name, path, set or dict).

    Options are passed to the model class (e.g. ``hysteresis``, ``force_gain``,
    ``estimator`` for the dissertation's models; ``damping`` for ``"linear"``).
    """
    if model not in DAMPERS:
        raise unknown_name("damper model", model, DAMPERS)
    try:
        return DAMPERS[model](parameters, **options)
    except TypeError as exc:
        raise ValidationError(f"damper model {model!r}: {exc}") from None


def takes_current(damper: Mapping[str, Any] | None) -> bool:
    """Whether the damper a run describes takes a drive current (``describe()["damper"]``).

    False for a model whose force does not depend on the current
    (:attr:`DamperModel.takes_current`, e.g. ``"linear"``): the measures of its runs
    report no ``mean_current``. A description without a registered model counts as
    taking one.

    Examples
    --------
    >>> takes_current({"model": "linear"}), takes_current({"model": "wang-symmetric"})
    (False, True)
    >>> takes_current(None)
    True
    """
    model = DAMPERS.get(str((damper or {}).get("model")))
    return True if model is None else bool(model.takes_current)
