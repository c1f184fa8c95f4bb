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
    "ESTIMATORS",
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
    "make_damper",
    "make_estimator",
]

#: Damper models by registry name.
DAMPERS: dict[str, type[DamperModel]] = {
    "wang-symmetric": WangSymmetric,
    "wang-asymmetric": WangAsymmetric,
    "bingham": Bingham,
    "spencer": SpencerBoucWen,
    "linear": LinearViscous,
}


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
