"""The excitation interface: road input ``z_r(t)`` [m], positive up (model reference, section 1)."""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar, TypeVar

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_finite, check_range

__all__ = ["Configurable", "Excitation", "FloatArray", "Option"]

FloatArray = npt.NDArray[np.float64]

_C = TypeVar("_C", bound="Configurable")

#: value kinds of an option, as a scenario file checks them
OPTION_KINDS = ("number", "integer", "string", "numbers")


@dataclass(frozen=True)
class Option:
    """One option of an excitation kind: a key of a scenario's ``[excitation]`` table.

    Parameters
    ----------
    name : str
        The key (``"frequency"``).
    kind : {"number", "integer", "string", "numbers"}
        Its value kind in a scenario file (``"numbers"``: a list of numbers).
    unit : str
        Unit of a number (``""`` for none).
    doc : str
        What it means, with its default (shown in help and in errors).
    required : bool
        The excitation cannot be built without it.
    default : object, optional
        Passed to the constructor when the option is not given (None: the
        constructor's own default).
    low, high : float, optional
        Valid range of a number (None: unbounded on that side).
    low_inclusive : bool
        Whether ``low`` itself is valid.
    choices : tuple of str, optional
        The valid values of a string option (None: free text, e.g. a file path).
    keyword : str, optional
        The constructor keyword, when it differs from ``name`` (``speed`` ->
        ``speed_kmh``).

    Examples
    --------
    >>> Option("delay", "number", "s", "time before the pulse [s]", default=0.5, low=0.0).argument
    'delay'
    """

    name: str
    kind: str
    unit: str
    doc: str
    required: bool = False
    default: Any = None
    low: float | None = None
    high: float | None = None
    low_inclusive: bool = True
    choices: tuple[str, ...] | None = None
    keyword: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in OPTION_KINDS:
            raise ValidationError(
                f"option {self.name!r}: kind must be one of {', '.join(OPTION_KINDS)}; "
                f"got {self.kind!r}"
            )

    @property
    def argument(self) -> str:
        """The constructor keyword the option sets."""
        return self.keyword or self.name


class Configurable:
    """What a registered excitation kind declares (see :mod:`mrsuspension.excitation`).

    ``name`` is the registry name (``[excitation] kind``), ``options`` the keys its
    scenario table accepts, ``measures_kind`` the family of measures
    :meth:`~mrsuspension.engine.result.SimulationResult.measures` computes for its runs
    (see :data:`~mrsuspension.engine.result.MEASURES_BY_KIND`), ``example_options`` a
    valid set of options (for the docs and the contract tests) and ``internal_parameters``
    the constructor parameters that no option sets directly (a road's sampled profile).
    The registry, the option tables of the scenario files and the studies' measure lists
    are derived from these declarations.
    """

    name: ClassVar[str]
    options: ClassVar[tuple[Option, ...]] = ()
    measures_kind: ClassVar[str]
    example_options: ClassVar[dict[str, Any]] = {}
    internal_parameters: ClassVar[tuple[str, ...]] = ()

    @classmethod
    def option_table(cls) -> dict[str, Option]:
        """The declared options by name."""
        return {o.name: o for o in cls.options}

    @classmethod
    def from_options(
        cls: type[_C], options: Mapping[str, Any], *, base_dir: str | Path | None = None
    ) -> _C:
        """Build from scenario options (checked names, required ones present).

        Each declared option given sets its constructor keyword; an option not given
        takes its declared ``default`` (if any), else the constructor's. ``base_dir`` is
        for kinds that read files. Called by
        :func:`~mrsuspension.excitation.make_excitation`, which checks the names first.
        """
        kwargs: dict[str, Any] = {}
        for opt in cls.options:
            if opt.name in options:
                kwargs[opt.argument] = options[opt.name]
            elif opt.default is not None:
                kwargs[opt.argument] = opt.default
        return cls(**kwargs)

    def to_options(self) -> dict[str, Any] | None:
        """Scenario options that rebuild this excitation; None when there are none.

        The declared options read back from the attributes their keywords set (those
        left at None are left out); kinds built from data no option holds (a road
        profile) return None.
        """
        out: dict[str, Any] = {}
        for opt in self.options:
            value = getattr(self, opt.argument, None)
            if value is None:
                continue
            out[opt.name] = list(value) if isinstance(value, tuple) else value
        return out


class Excitation(Configurable, ABC):
    """A road displacement input ``z_r(t)`` with exact derivatives.

    Every excitation is a function of time [s] that accepts scalars or numpy arrays and
    returns a float array of the same shape: :meth:`displacement` ``z_r`` [m],
    :meth:`velocity` ``dz_r/dt`` [m/s] and :meth:`acceleration` ``d2z_r/dt2`` [m/s^2]
    (analytic, or from a C2 cubic spline for sampled roads). :attr:`duration` is a
    sensible simulation length [s] and :meth:`measure_window` the part of the record
    the measures are computed over (model reference, section 9).

    Subclasses are frozen dataclasses that validate their parameters on construction,
    and declare their registry name, options and measures (:class:`Configurable`).
    """

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

        The whole record by default (shock and random-road measures, model reference, section 9).
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
