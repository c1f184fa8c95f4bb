"""The excitation interface: a road input ``z_r(t)`` [m], positive up (MODEL_SPEC section 1)."""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_finite, check_range

__all__ = ["Excitation", "FloatArray"]

FloatArray = npt.NDArray[np.float64]


class Excitation(ABC):
    """A road displacement input ``z_r(t)`` with exact derivatives.

    Every excitation is a function of time [s] that accepts scalars or numpy arrays and
    returns a float array of the same shape: :meth:`displacement` ``z_r`` [m],
    :meth:`velocity` ``dz_r/dt`` [m/s] and :meth:`acceleration` ``d2z_r/dt2`` [m/s^2]
    (analytic, or from a C2 cubic spline for sampled roads). :attr:`duration` is a
    sensible simulation length [s] and :meth:`measure_window` the part of the record
    the spec section 9 measures are computed over.

    Subclasses are frozen dataclasses that validate their parameters on construction.
    """

    #: registry name of the excitation kind (``"harmonic"``, ``"pulse"``, ``"road"``)
    name: ClassVar[str]

    @abstractmethod
    def displacement(self, t: npt.ArrayLike) -> FloatArray:
        """Road displacement ``z_r`` [m] at times ``t`` [s]."""

    @abstractmethod
    def velocity(self, t: npt.ArrayLike) -> FloatArray:
        """Road velocity ``dz_r/dt`` [m/s] at times ``t`` [s]."""

    @abstractmethod
    def acceleration(self, t: npt.ArrayLike) -> FloatArray:
        """Road acceleration ``d2z_r/dt2`` [m/s^2] at times ``t`` [s]."""

    @property
    @abstractmethod
    def duration(self) -> float:
        """A sensible default simulation length [s]."""

    @abstractmethod
    def describe(self) -> dict[str, Any]:
        """The excitation as plain data: ``kind``, its parameters and derived values."""

    def measure_window(self) -> tuple[float, float]:
        """Time limits ``(t_start, t_end)`` [s] of the part of the record to measure.

        The whole record by default (shock and random-road measures, spec section 9).
        """
        return (0.0, self.duration)

    def sample_grid(self, n: int, step: float, start: float = 0.0) -> tuple[FloatArray, FloatArray]:
        """``(z_r, dz_r/dt)`` at the ``n`` times ``start + k * step``, ``k = 0 .. n-1``.

        What the simulation engine asks for (the road at every half step from 0) and the
        HiL loop's live road (a tick's half steps from the tick's time). The default
        evaluates :meth:`displacement` and :meth:`velocity` on the grid; excitations with
        a faster exact way to fill a uniform grid override it (with the same arguments).

        Examples
        --------
        >>> from mrsuspension.excitation import Harmonic
        >>> z, v = Harmonic(1.0, 0.01).sample_grid(3, 0.25)
        >>> z.round(12).tolist(), v.round(12).tolist()
        ([0.0, 0.01, 0.0], [0.062831853072, 0.0, -0.062831853072])
        >>> z, v = Harmonic(1.0, 0.01).sample_grid(2, 0.25, start=0.5)
        >>> z.round(12).tolist()
        [0.0, -0.01]
        """
        n, step, start = grid_args(n, step, start)
        t = start + np.arange(n) * step
        return self.displacement(t), self.velocity(t)


def grid_args(n: object, step: object, start: object = 0.0) -> tuple[int, float, float]:
    """The checked ``(n, step, start)`` of :meth:`Excitation.sample_grid`.

    ``n >= 1`` points, ``step > 0`` [s], ``start`` finite [s]. Plain valid numbers pass
    in about a microsecond (the live HiL road asks every tick); anything else goes
    through :func:`~mrsuspension.errors.check_range` and its messages.

    Examples
    --------
    >>> grid_args(3, 1e-4)
    (3, 0.0001, 0.0)
    >>> grid_args(0, 1e-4)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: n must be in [1, inf); got 0
    """
    if (
        type(n) is int
        and n >= 1
        and type(step) is float
        and 0.0 < step < math.inf
        and type(start) is float
        and math.isfinite(start)
    ):
        return n, step, start
    n = int(check_range("n", n, 1, None))
    step = float(check_range("step", step, 0.0, None, unit="s", low_inclusive=False))
    start = float(check_range("start", number("start", start), unit="s"))
    return n, step, start


def time_array(t: npt.ArrayLike) -> FloatArray:
    """``t`` as a float array, checked finite (named ``time`` in the error)."""
    return check_finite("time", t)


def number(name: str, value: object) -> float:
    """``value`` as a float, or an error if it is not a single real number (bools excluded)."""
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise ValidationError(f"{name} must be a number; got {value!r}")
    return float(value)


def positive(name: str, value: object, unit: str, high: float | None = None) -> float:
    """A finite number in ``(0, high]``, as a float."""
    v = number(name, value)
    check_range(name, v, 0.0, high, unit=unit, low_inclusive=False)
    return v


def non_negative(name: str, value: object, unit: str, high: float | None = None) -> float:
    """A finite number in ``[0, high]``, as a float."""
    v = number(name, value)
    check_range(name, v, 0.0, high, unit=unit)
    return v
