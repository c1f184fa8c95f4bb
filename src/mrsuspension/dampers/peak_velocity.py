"""Peak-velocity estimators v_m (model reference, section 2.4).

The dissertation's model needs the peak piston velocity ``v_m`` of the current excitation.
It is known in a harmonic characterisation test (``2 pi f a_m``) but has to be estimated
on line otherwise. Four estimators are provided, selectable by name:

``"cycle-rms"`` (default)
    ``sqrt(2 mean(v_d^2))`` over the last ``window`` seconds (1 s), clamped to
    ``[v_min, v_max]``: the cycle average of (2.14) (for any periodic motion the cycle
    mean of ``v^2 - a x`` is ``2 mean(v^2)``), exact for a sinusoid, free of ``a_d`` and
    insensitive to spikes, so it cannot run away in closed loop (model reference, section 2.4,
    revised 2026-11-24). The dissertation's model sets carry their identified velocity range;
    ``v_max`` defaults to its upper end (0.75 m/s for Tables 2.2 and 2.3).
``"window"``
    the peak of ``|v_d|`` over the last ``window`` seconds, clamped (the old default).
    In closed loop the peak reads 1.2-2.4x above ``2 pi f a_m`` (wheel-hop and switching
    spikes), and through ``F_t = F0 (1 + exp(a1 v_m))`` that feeds back up to the clamp:
    policy I ran away near 2.3 Hz (erratum 7). Kept for comparison.
``"instantaneous"``
    eq. (2.14), ``sqrt(max(v_d^2 - a_d x_d, 0))``, clamped. Exact for a sinusoid, but
    unsafe in closed loop: wheel-hop acceleration inflates it (erratum 7).
``"known"``
    a given value, e.g. ``2 pi f a_m`` for a harmonic test.

Examples
--------
>>> make_estimator()
CycleRms(window=1.0, v_min=0.001, v_max=0.75)
>>> est = make_estimator("window", window=0.5)
>>> est
WindowPeak(window=0.5, v_min=0.001, v_max=0.75)
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
    "DEFAULT_ESTIMATOR",
    "ESTIMATORS",
    "V_MAX_DEFAULT",
    "CycleRms",
    "InstantaneousPeak",
    "KnownPeak",
    "PeakVelocityEstimator",
    "WindowPeak",
    "make_estimator",
]

#: Highest peak velocity accepted anywhere [m/s]: three times the fastest test of
#: Table 2.1 (1.57 m/s); ``exp(a1 v_m)`` makes the model meaningless far beyond it.
V_LIMIT = 5.0
#: Default upper clamp [m/s]: the identified velocity range of Tables 2.2/2.3 (model
#: reference, section 2.4; the dissertation reports peak steady relative velocities of
#: about 0.75 m/s with the hysteretic model, section 5.2). A parameter set's
#: ``velocity_range`` overrides it.
V_MAX_DEFAULT = 0.75
#: Name of the default estimator (model reference, section 2.4, revised 2026-11-24).
DEFAULT_ESTIMATOR = "cycle-rms"


def _check_window(window: float) -> None:
    if not (math.isfinite(window) and 0.0 < window <= 600.0):
        raise ValidationError(f"window must be in (0, 600] s; got {window}")


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
class _Windowed(PeakVelocityEstimator):
    """Shared parts of the estimators over a sliding window of ``window`` seconds."""

    window: float = 1.0
    v_min: float = 1e-3
    v_max: float = V_MAX_DEFAULT

    def __post_init__(self) -> None:
        _check_window(self.window)
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


@dataclass(frozen=True)
class CycleRms(_Windowed):
    """``sqrt(2 mean(v_d^2))`` over the last ``window`` seconds, clamped (default estimator).

    The cycle average of (2.14): for any periodic motion the cycle mean of its radicand
    ``v^2 - a x`` equals ``2 mean(v^2)``. Exact for a sinusoid when the window holds a whole
    number of half periods (1 s: any multiple of 0.5 Hz); otherwise it ripples by at most
    ``1 - sqrt(1 - |sin(w T_w)| / (w T_w))`` relative, ``w = 2 pi f`` (11 % at 0.75 Hz,
    6.6 % at 1.25 Hz, 1.6 % at 2.9 Hz);
    free of ``a_d``, so there is no loop through the damper force; a spike of ``v_d`` moves
    it by its energy share of the window, not to its peak. A running sum, O(1) per sample.

    Parameters
    ----------
    window : float
        Length of the sliding window T_w [s] (model reference, section 2.4: 1.0 s).
    v_min, v_max : float
        Clamp [m/s]; ``v_max`` is the identified velocity range (0.75 m/s for Table 2.2;
        the damper model passes its parameter set's ``velocity_range``).

    Examples
    --------
    >>> import numpy as np
    >>> from mrsuspension.dampers import kernels as K
    >>> est, dt = CycleRms(window=1.0), 1e-3
    >>> ep, es = est.params_for(dt), est.buffer(dt)
    >>> t = np.arange(3000) * dt                        # 3 s of 0.25 sin(2 pi 1.5 t) m/s
    >>> vm = [K.estimator_update(est.code, ep, es, 0.0, 0.25 * np.sin(3 * np.pi * s), 0.0)
    ...       for s in t]
    >>> round(vm[-1], 6)                                # 2 pi f a_m = 0.25 m/s
    0.25
    """

    name: ClassVar[str] = "cycle-rms"
    code: ClassVar[int] = K.EST_CYCLE_RMS

    def buffer(self, dt: float) -> np.ndarray:
        return np.zeros(K.CR_RING + self.samples(dt))


@dataclass(frozen=True)
class WindowPeak(_Windowed):
    """Peak of ``|v_d|`` over the last ``window`` seconds, clamped (the old default).

    Reads 1.2-2.4x above ``2 pi f a_m`` in closed loop and can run away up to the clamp
    through ``F_t`` (model reference, section 2.4, erratum 7); kept for comparison.

    Parameters
    ----------
    window : float
        Length of the sliding window T_w [s] (model reference, section 2.4: 1.0 s).
    v_min, v_max : float
        Clamp [m/s] (identified range of Table 2.2: up to 0.75 m/s).
    """

    name: ClassVar[str] = "window"
    code: ClassVar[int] = K.EST_WINDOW

    def buffer(self, dt: float) -> np.ndarray:
        return np.zeros(3 + 2 * (self.samples(dt) + 1))


@dataclass(frozen=True)
class InstantaneousPeak(PeakVelocityEstimator):
    """Eq. (2.14), ``sqrt(max(v_d^2 - a_d x_d, 0))``, clamped to ``[v_min, v_max]``.

    Exact for a pure sinusoid; **unsafe in closed loop** (model reference, section 2.4, erratum 7).
    """

    v_min: float = 1e-3
    v_max: float = V_MAX_DEFAULT
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
    "cycle-rms": CycleRms,
    "window": WindowPeak,
    "instantaneous": InstantaneousPeak,
    "known": KnownPeak,
}


def make_estimator(
    spec: str | PeakVelocityEstimator | None = None, **options: Any
) -> PeakVelocityEstimator:
    """Build an estimator from its name (``"cycle-rms"``, ``"window"``, ``"instantaneous"``,
    ``"known"``).

    ``None`` gives the default, :class:`CycleRms`. Options are passed to the class.
    """
    if spec is None:
        spec = DEFAULT_ESTIMATOR
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
