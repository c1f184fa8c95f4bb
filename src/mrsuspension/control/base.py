"""The controller interface: :class:`Controller`, its declared options and their checks.

A controller is a frozen dataclass whose fields are its options. Each field declares its
unit, valid range and model-reference symbol once (:func:`option`); the constructors validate
against that declaration and :meth:`Controller.describe_options` reports it (the HiL
monitor builds its form from it), so a new law needs no table elsewhere.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from abc import ABC
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt

from mrsuspension.control import kernel as CK
from mrsuspension.errors import ValidationError, unknown_name

__all__ = ["ControlOption", "Controller", "option"]


@dataclass(frozen=True)
class ControlOption:
    """One option of a control law: its name, default, unit and valid values.

    Attributes
    ----------
    name : str
        Constructor keyword.
    default : Any
        Default value (None: derived, e.g. ``p`` from ``mode``).
    unit : str
        Unit ("" for dimensionless or text).
    low, high : float, optional
        Valid range of a number (None: unbounded).
    low_open, high_open : bool
        Whether the range excludes its ends.
    choices : tuple of str, optional
        Valid values of a text option.
    symbol : str
        The model reference's symbol (``k_c``, ``lambda``, ...).
    label : str
        Name in error messages (default: ``name``).
    shape : tuple of int or None, optional
        A vector or matrix option's shape (None: a number or a text); a ``None`` in it
        takes any length on that axis (e.g. ``(1, None)``: a gain row of the plant's
        states). Its value is held as nested tuples of floats, packed row by row into the
        law's parameter vector after the fixed slots (:meth:`Controller.params`); every
        element is checked against ``low``/``high``.

    Examples
    --------
    >>> ControlOption("gain", 3.0, low=0.0, high=1e9, label="gain k_c").check(5)
    5.0
    >>> ControlOption("K", None, unit="N/m", shape=(1, 2)).check([[1, 2]])
    ((1.0, 2.0),)
    >>> ControlOption("K", None, unit="N/m", shape=(1, 2)).check([1, 2])
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: K must be an array of shape (1, 2) [N/m]; got shape (2,)
    """

    name: str
    default: Any = None
    unit: str = ""
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: tuple[str, ...] | None = None
    symbol: str = ""
    label: str = ""
    shape: tuple[int | None, ...] | None = None

    def check(self, value: Any) -> Any:
        """``value`` validated (numbers as float); raises :class:`ValidationError`.

        Examples
        --------
        >>> ControlOption("p", 1.0, low=0.0, high=1.0).check(2.0)
        Traceback (most recent call last):
        ...
        mrsuspension.errors.ValidationError: p must be in [0, 1]; got 2
        """
        label = self.label or self.name
        if self.shape is not None:
            return self._check_array(label, value)
        if self.choices is not None:
            if value not in self.choices:
                raise unknown_name(label, str(value), self.choices)
            return value
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise ValidationError(f"{label} must be a finite number; got {value!r}")
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        below = value < lo or (self.low_open and value == lo)
        above = value > hi or (self.high_open and value == hi)
        if below or above:
            lb = "(" if self.low_open else "["
            rb = ")" if self.high_open else "]"
            raise ValidationError(f"{label} must be in {lb}{lo:g}, {hi:g}{rb}; got {value:g}")
        return float(value)

    def _check_array(self, label: str, value: Any) -> Any:
        """A vector or matrix option's value as nested tuples of floats (checked)."""
        assert self.shape is not None
        want = "(" + ", ".join("n" if d is None else str(d) for d in self.shape)
        want += ",)" if len(self.shape) == 1 else ")"
        unit = f" [{self.unit}]" if self.unit else ""
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise ValidationError(
                f"{label} must be an array of shape {want}{unit} of numbers; got {value!r}"
            ) from None
        fits = arr.ndim == len(self.shape) and all(
            d is None or d == n for d, n in zip(self.shape, arr.shape, strict=True)
        )
        if not fits:
            raise ValidationError(
                f"{label} must be an array of shape {want}{unit}; got shape {arr.shape}"
            )
        if not np.all(np.isfinite(arr)):
            raise ValidationError(f"{label} must hold finite numbers; got {arr.tolist()!r}")
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        if arr.size and (arr.min() < lo or arr.max() > hi):
            raise ValidationError(
                f"{label} elements must be in [{lo:g}, {hi:g}]{unit}; got {arr.tolist()!r}"
            )
        return _nested(arr)

    def describe(self) -> dict[str, Any]:
        """Plain data (for the monitor page).

        Examples
        --------
        >>> ControlOption("current", 0.0, unit="A", low=0.0, high=10.0).describe()["unit"]
        'A'
        """
        return dataclasses.asdict(self)


def _nested(arr: npt.NDArray[np.float64]) -> Any:
    """An array as nested tuples of floats (hashable, immutable: a frozen field's value)."""
    if arr.ndim == 0:
        return float(arr)
    return tuple(_nested(a) for a in arr)


def option(
    default: Any,
    *,
    unit: str = "",
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
    choices: tuple[str, ...] | None = None,
    symbol: str = "",
    label: str = "",
    shape: tuple[int | None, ...] | None = None,
) -> Any:
    """A dataclass field declaring a controller option (see :class:`ControlOption`).

    ``shape`` declares a vector or matrix option (its default as nested tuples, e.g.
    ``((0.0, 0.0),)`` for a 1 x 2 gain).

    Examples
    --------
    >>> from dataclasses import fields
    >>> @dataclass(frozen=True)
    ... class Demo(Controller):
    ...     current: float = option(0.1, unit="A", low=0.0, high=10.0, symbol="i")
    ...     law: ClassVar[str] = "demo"
    ...     code: ClassVar[int] = -1
    >>> Demo().current, Demo.describe_options()[0].unit
    (0.1, 'A')
    """
    spec = ControlOption(
        "", default, unit, low, high, low_open, high_open, choices, symbol, label, shape
    )
    return dataclasses.field(default=default, metadata={"option": spec})


def _declared(cls: type) -> dict[str, ControlOption]:
    """The options declared by ``cls``'s fields, by name."""
    out: dict[str, ControlOption] = {}
    for f in dataclasses.fields(cls):
        spec = f.metadata.get("option")
        if spec is not None:
            out[f.name] = dataclasses.replace(spec, name=f.name)
    return out


@dataclass(frozen=True)
class Controller(ABC):
    """Common interface: a kernel code, a parameter vector and declared options.

    Subclasses declare their options as fields with :func:`option`; the fields are
    checked after construction (:meth:`_validate`) and reported by
    :meth:`describe_options`.
    """

    law: ClassVar[str]
    code: ClassVar[int]
    #: force source of the engine (a damper model, or an ideal dissipative damper)
    force_source: ClassVar[int] = CK.F_MODEL
    #: whether the controller needs the inverse of the dissertation's damper model
    needs_inverse: ClassVar[bool] = False
    #: constructor-only options (not fields), e.g. ``mode`` of the shaped laws
    extra_options: ClassVar[tuple[ControlOption, ...]] = ()

    def __post_init__(self) -> None:
        self._validate()

    def _validate(self) -> None:
        """Check every declared option field (numbers become floats)."""
        for name, spec in _declared(type(self)).items():
            object.__setattr__(self, name, spec.check(getattr(self, name)))

    @property
    def drives_damper(self) -> bool:
        """Whether the law acts through the MR damper's drive current (not an ideal force)."""
        return self.force_source == CK.F_MODEL

    @classmethod
    def describe_options(cls) -> list[ControlOption]:
        """The constructor's options: name, default, unit and valid values.

        Defaults come from the constructor's signature, units and ranges from the
        field declarations (:func:`option`).

        Examples
        --------
        >>> from mrsuspension.control import Passive
        >>> [(o.name, o.default, o.unit, o.high) for o in Passive.describe_options()]
        [('current', 0.0, 'A', 10.0)]
        """
        declared = _declared(cls)
        declared.update({o.name: o for o in cls.extra_options})
        out = []
        for name, param in inspect.signature(cls).parameters.items():
            if param.kind in (param.VAR_KEYWORD, param.VAR_POSITIONAL) or name not in declared:
                continue
            default = None if param.default is param.empty else param.default
            out.append(dataclasses.replace(declared[name], default=default))
        return out

    def params(self, max_current: float) -> npt.NDArray[np.float64]:
        """Parameter vector of the compiled controller (layout ``control.kernel.P_*``).

        Examples
        --------
        >>> from mrsuspension.control import Passive
        >>> p = Passive(0.2).params(0.5)
        >>> p.size == CK.CP_SIZE, float(p[CK.P_CURRENT]), float(p[CK.P_IMAX])
        (True, 0.2, 0.5)
        """
        p = np.zeros(CK.CP_SIZE)
        p[CK.P_P] = 1.0
        p[CK.P_XI] = 1.0
        p[CK.P_XIC] = 1.0
        p[CK.P_EPS] = 1.0
        p[CK.P_MS0] = 1.0
        p[CK.P_BETA] = 1.0
        p[CK.P_INV_HYST] = 1.0
        p[CK.P_IMAX] = max_current
        self._fill(p)
        tail = self._tail()
        return np.concatenate([p, tail]) if tail.size else p

    def _tail(self) -> npt.NDArray[np.float64]:
        """The parameters after the fixed slots: the vector and matrix options, row by row,
        in declaration order (:meth:`option_slots` says where each starts)."""
        parts = [
            np.asarray(getattr(self, name), dtype=float).ravel()
            for name, spec in _declared(type(self)).items()
            if spec.shape is not None
        ]
        return np.concatenate(parts) if parts else np.zeros(0)

    def option_slots(self) -> dict[str, slice]:
        """Where each vector or matrix option lies in :meth:`params` (slices).

        Examples
        --------
        >>> from mrsuspension.control import Passive
        >>> Passive().option_slots()
        {}
        """
        out: dict[str, slice] = {}
        at = CK.CP_SIZE
        for name, spec in _declared(type(self)).items():
            if spec.shape is not None:
                n = int(np.asarray(getattr(self, name), dtype=float).size)
                out[name] = slice(at, at + n)
                at += n
        return out

    def for_plant(self, plant: Any) -> Controller:
        """This law attached to ``plant``, the quarter car it drives (a half or full car's
        corner: the corner's :meth:`~mrsuspension.vehicle.VehicleBody.corner_quarter_car`).

        Called by :class:`~mrsuspension.engine.Simulation` (and so at every corner of a
        :class:`~mrsuspension.engine.vehicle.VehicleSimulation`) when it is built: a law
        may derive gains from the plant's masses and stiffnesses (a Riccati solve...) and
        return a copy holding them. By default the law itself. It may be called again on
        the attached law (e.g. ``dataclasses.replace`` of a simulation): return the same
        gains for the same plant.
        """
        return self

    def _fill(self, p: npt.NDArray[np.float64]) -> None:  # noqa: B027 - optional hook
        """Write this controller's fields into the parameter vector (default: nothing)."""

    def describe(self) -> dict[str, Any]:
        """Plain data: the law and every parameter (``make_controller(**describe())``).

        Examples
        --------
        >>> from mrsuspension.control import Passive
        >>> Passive(0.1).describe()
        {'law': 'passive', 'current': 0.1}
        """
        return {"law": self.law, **dataclasses.asdict(self)}
