"""Peak-velocity estimators v_m (MODEL_SPEC section 2.4).

The dissertation's model needs the peak piston velocity ``v_m`` of the current excitation.
It is known in a harmonic characterisation test (``2 pi f a_m``) but has to be estimated
on line otherwise. Three estimators are provided, selectable by name:

``"window"`` (default)
    the peak of ``|v_d|`` over the last ``window`` seconds (1 s), clamped to
    ``[v_min, v_max]``. It can never exceed ``v_max``, so the transition force
    ``F_t = F0 (1 + exp(a1 v_m))`` stays bounded in closed loop.
``"instantaneous"``
    eq. (2.14), ``sqrt(max(v_d^2 - a_d x_d, 0))``, clamped. Exact for a sinusoid, but
    unsafe in closed loop: wheel-hop acceleration inflates it (erratum 7).
``"known"``
    a given value, e.g. ``2 pi f a_m`` for a harmonic test.

Examples
--------
>>> est = make_estimator("window", window=0.5)
>>> est
WindowPeak(window=0.5, v_min=0.001, v_max=1.0)
>>> make_estimator("known", value=0.2).pointwise(0.0, 0.05, 0.0)
0.2
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from mrsuspension.dampers import kernels as K
from mrsuspension.errors import ValidationError, unknown_name

__all__ = [
    "ESTIMATORS",
    "InstantaneousPeak",
    "KnownPeak",
    "PeakVelocityEstimator",
    "WindowPeak",
    "make_estimator",
]

#: Highest peak velocity accepted anywhere [m/s]: three times the fastest test of
#: Table 2.1 (1.57 m/s); ``exp(a1 v_m)`` makes the model meaningless far beyond it.
V_LIMIT = 5.0


def _check_clamp(v_min: float, v_max: float) -> None:
    if not (math.isfinite(v_min) and math.isfinite(v_max) and 0.0 < v_min < v_max <= V_LIMIT):
        raise ValidationError(
            f"peak-velocity clamp must satisfy 0 < v_min < v_max <= {V_LIMIT:g} m/s; "
            f"got v_min={v_min}, v_max={v_max}"
        )


class PeakVelocityEstimator(ABC):
    """Common interface: a code and parameter vector for the compiled kernels."""

    name: ClassVar[str]
    code: ClassVar[int]

    @abstractmethod
    def params(self) -> np.ndarray:
        """Parameter vector ``ep`` of the compiled estimator."""

    def buffer(self, dt: float) -> np.ndarray:
        """A fresh state buffer ``es`` for sampling period ``dt`` [s]."""
        return np.zeros(1)

    def params_for(self, dt: float) -> np.ndarray:
        """Parameter vector for sampling period ``dt`` (the window needs its length)."""
        return self.params()

    def pointwise(self, stroke: float, velocity: float, acceleration: float) -> float:
        """v_m of a fresh estimator that has seen this one sample."""
        return float(
            K.estimator_pointwise(self.code, self.params(), stroke, velocity, acceleration)
        )


@dataclass(frozen=True)
class WindowPeak(PeakVelocityEstimator):
    """Peak of ``|v_d|`` over the last ``window`` seconds, clamped (default estimator).

    Parameters
    ----------
    window : float
        Length of the sliding window T_w [s] (spec section 2.4: 1.0 s).
    v_min, v_max : float
        Clamp [m/s] (spec: 1e-3 and 1.0; identified range about 0.05-0.75 m/s).
    """

    window: float = 1.0
    v_min: float = 1e-3
    v_max: float = 1.0
    name: ClassVar[str] = "window"
    code: ClassVar[int] = K.EST_WINDOW

    def __post_init__(self) -> None:
        if not (math.isfinite(self.window) and 0.0 < self.window <= 600.0):
            raise ValidationError(f"window must be in (0, 600] s; got {self.window}")
        _check_clamp(self.v_min, self.v_max)

    def params(self) -> np.ndarray:
        return np.array([self.v_min, self.v_max, 1.0])

    def samples(self, dt: float) -> int:
        """Number of samples in the window at sampling period ``dt``."""
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValidationError(f"sampling period dt must be > 0 s; got {dt}")
        n = max(1, round(self.window / dt))
        if n > 50_000_000:
            raise ValidationError(
                f"a {self.window} s window at dt = {dt} s needs {n} samples; use a larger dt"
            )
        return n

    def params_for(self, dt: float) -> np.ndarray:
        return np.array([self.v_min, self.v_max, float(self.samples(dt))])

    def buffer(self, dt: float) -> np.ndarray:
        return np.zeros(3 + 2 * (self.samples(dt) + 1))


@dataclass(frozen=True)
class InstantaneousPeak(PeakVelocityEstimator):
    """Eq. (2.14), ``sqrt(max(v_d^2 - a_d x_d, 0))``, clamped to ``[v_min, v_max]``.

    Exact for a pure sinusoid; **unsafe in closed loop** (spec section 2.4, erratum 7).
    """

    v_min: float = 1e-3
    v_max: float = 1.0
    name: ClassVar[str] = "instantaneous"
    code: ClassVar[int] = K.EST_INSTANT

    def __post_init__(self) -> None:
        _check_clamp(self.v_min, self.v_max)

    def params(self) -> np.ndarray:
        return np.array([self.v_min, self.v_max])


@dataclass(frozen=True)
class KnownPeak(PeakVelocityEstimator):
    """A given peak velocity ``value`` [m/s], e.g. ``2 pi f a_m`` in a harmonic test."""

    value: float
    name: ClassVar[str] = "known"
    code: ClassVar[int] = K.EST_KNOWN

    def __post_init__(self) -> None:
        if not (math.isfinite(self.value) and 0.0 <= self.value <= V_LIMIT):
            raise ValidationError(
                f"known peak velocity must be in [0, {V_LIMIT:g}] m/s; got {self.value:g} m/s"
            )

    def params(self) -> np.ndarray:
        return np.array([self.value])


ESTIMATORS: dict[str, type[PeakVelocityEstimator]] = {
    "window": WindowPeak,
    "instantaneous": InstantaneousPeak,
    "known": KnownPeak,
}


def make_estimator(
    spec: str | PeakVelocityEstimator | None = None, **options: Any
) -> PeakVelocityEstimator:
    """Build an estimator from its name (``"window"``, ``"instantaneous"``, ``"known"``).

    ``None`` gives the default :class:`WindowPeak`. Options are passed to the class.
    """
    if spec is None:
        spec = "window"
    if isinstance(spec, PeakVelocityEstimator):
        if options:
            raise ValidationError("options can only be given with an estimator name")
        return spec
    if spec not in ESTIMATORS:
        raise unknown_name("peak-velocity estimator", str(spec), ESTIMATORS)
    try:
        return ESTIMATORS[spec](**options)
    except TypeError as exc:
        raise ValidationError(f"peak-velocity estimator {spec!r}: {exc}") from None
