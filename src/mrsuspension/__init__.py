"""mrsuspension: semi-active vehicle suspensions with magneto-rheological dampers.

The curated public API; submodules hold the rest:

* :mod:`mrsuspension.dampers` - damper models, peak-velocity estimators, inverse model;
* :mod:`mrsuspension.parameters` - published parameter sets with provenance;
* :mod:`mrsuspension.shaping` - ADFG / CM current shaping and drive-current composition;
* :mod:`mrsuspension.characterisation` - the laboratory test matrix (Table 2.1) on any model.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from mrsuspension._lazy import lazy_namespace
from mrsuspension.errors import MRSuspensionError, ValidationError

if TYPE_CHECKING:
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

# the models (numpy, numba, scipy) load on first use: `import mrsuspension` and
# `mrsus --help` stay fast (docs/cli.md)
_DAMPERS = ("Bingham", "DamperModel", "LinearViscous", "SpencerBoucWen", "WangAsymmetric",
            "WangSymmetric", "make_damper")  # fmt: skip
_lazy_getattr, _lazy_dir = lazy_namespace(
    __name__,
    {
        "parameters": "mrsuspension.parameters",
        "RunSettings": "mrsuspension.engine.settings",
        **dict.fromkeys(_DAMPERS, "mrsuspension.dampers"),
    },
    globals(),
)


def __getattr__(name: str) -> Any:
    if name == "__version__":  # importlib.metadata costs ~30 ms: read on demand
        from importlib.metadata import PackageNotFoundError, version

        try:
            value = version("mrsuspension")
        except PackageNotFoundError:  # pragma: no cover - running from a source tree
            value = "0+unknown"
        globals()["__version__"] = value
        return value
    return _lazy_getattr(name)


def __dir__() -> list[str]:
    return sorted({*_lazy_dir(), "__version__"})


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
