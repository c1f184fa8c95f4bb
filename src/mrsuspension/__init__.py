"""mrsuspension: semi-active vehicle suspensions with magneto-rheological dampers.

The curated public API; submodules hold the rest:

* :mod:`mrsuspension.dampers` - damper models, peak-velocity estimators, inverse model;
* :mod:`mrsuspension.parameters` - published parameter sets with provenance;
* :mod:`mrsuspension.shaping` - ADFG / CM current shaping and drive-current composition;
* :mod:`mrsuspension.characterisation` - the laboratory test matrix (Table 2.1) on any model.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from mrsuspension import parameters
from mrsuspension.dampers import (
    Bingham,
    DamperModel,
    LinearViscous,
    SpencerBoucWen,
    WangAsymmetric,
    WangSymmetric,
    make_damper,
)
from mrsuspension.engine.settings import RunSettings
from mrsuspension.errors import MRSuspensionError, ValidationError

try:
    __version__ = version("mrsuspension")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

__all__ = [
    "Bingham",
    "DamperModel",
    "LinearViscous",
    "MRSuspensionError",
    "RunSettings",
    "SpencerBoucWen",
    "ValidationError",
    "WangAsymmetric",
    "WangSymmetric",
    "__version__",
    "make_damper",
    "parameters",
]
