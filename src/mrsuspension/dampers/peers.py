"""Peer damper models under the same interface: linear viscous, Bingham, Spencer Bouc-Wen."""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from mrsuspension import parameters as _parameters
from mrsuspension.dampers import kernels as K
from mrsuspension.dampers.base import DamperModel, FloatArray, ParameterSpec
from mrsuspension.errors import ValidationError, check_range

__all__ = ["Bingham", "LinearViscous", "SpencerBoucWen"]


class LinearViscous(DamperModel):
    """Linear viscous damper ``F = c v`` (current has no effect).

    Used to validate the vehicle code against the exact linear quarter-car response.

    Parameters
    ----------
    parameters : str, path, ParameterSet or dict, optional
        A set with ``c`` [N s/m] (default ``"linear-2500"``).
    damping : float, optional
        Shortcut for ``parameters={"c": damping}``.

    Examples
    --------
    >>> float(LinearViscous(damping=1500.0).force(0.0, 0.2))
    300.0
    """

    name: ClassVar[str] = "linear"
    kind: ClassVar[int] = K.LINEAR
    parameter_rules: ClassVar[dict[str, str]] = {"c": "nonnegative"}
    default_parameters: ClassVar[str] = "linear-2500"
    accepts: ClassVar[tuple[str, ...]] = ("linear",)
    takes_current: ClassVar[bool] = False
    #: options a scenario's ``[damper]`` table may set, with their value kind
    scenario_options: ClassVar[dict[str, str]] = {"damping": "number"}

    def __init__(
        self,
        parameters: ParameterSpec = None,
        *,
        damping: float | None = None,
        max_current: float | None = None,
    ) -> None:
        if damping is not None:
            if parameters is not None:
                raise ValidationError("give either parameters or damping, not both")
            c = float(check_range("damping", damping, 0.0, 1e7, unit="N s/m"))
            parameters = _parameters.ParameterSet(
                name=f"linear-{c:g}",
                model="linear",
                values={"c": c},
                units={"c": "N s/m"},
                source="given damping coefficient",
            )
        super().__init__(parameters, max_current=max_current)

    def _force_arrays(
        self, x: FloatArray, v: FloatArray, a: FloatArray, i: FloatArray, vm: FloatArray | None
    ) -> FloatArray:
        return self.values["c"] * v

    def max_damping_rate(self, max_current: float | None = None) -> float:
        return self.values["c"]


class Bingham(DamperModel):
    """Bingham plastic model with current-dependent yield force and viscosity.

    ``F = (fc_a + fc_b i) sgn(v) + (c0_a + c0_b i) v + f0`` (model reference, section 2.5,
    made current dependent by the common linear-in-current extension). The default set
    ``"bingham-wang-low"`` is a least-squares fit of this form to the dissertation's
    symmetric model (Table 2.2, 0.5-5 Hz), see its provenance.

    Examples
    --------
    >>> m = Bingham()
    >>> bool(m.force(0.0, 0.1, 0.0, 0.4) > m.force(0.0, 0.1, 0.0, 0.0) > 0)
    True
    """

    name: ClassVar[str] = "bingham"
    kind: ClassVar[int] = K.BINGHAM
    parameter_rules: ClassVar[dict[str, str]] = {
        "fc_a": "nonnegative", "fc_b": "any", "c0_a": "nonnegative", "c0_b": "any", "f0": "any",
    }  # fmt: skip
    default_parameters: ClassVar[str] = "bingham-wang-low"
    accepts: ClassVar[tuple[str, ...]] = ("bingham",)
    #: options a scenario's ``[damper]`` table may set, with their value kind
    scenario_options: ClassVar[dict[str, str]] = {}

    def _force_arrays(
        self, x: FloatArray, v: FloatArray, a: FloatArray, i: FloatArray, vm: FloatArray | None
    ) -> FloatArray:
        q = self.values
        return (q["fc_a"] + q["fc_b"] * i) * np.sign(v) + (q["c0_a"] + q["c0_b"] * i) * v + q["f0"]

    def max_damping_rate(self, max_current: float | None = None) -> float:
        i = self.max_current if max_current is None else max_current
        return self.values["c0_a"] + max(self.values["c0_b"] * i, 0.0)

    def _check_values(self, set_name: str, values: Any) -> None:
        super()._check_values(set_name, values)
        imax = self.max_current
        for a, b, what in (("fc_a", "fc_b", "yield force"), ("c0_a", "c0_b", "viscosity")):
            if values[a] + values[b] * imax < 0:
                raise ValidationError(
                    f"set {set_name!r}: the {what} {a} + {b} i becomes negative within "
                    f"0-{imax} A ({values[a]} + {values[b]} i)"
                )


class SpencerBoucWen(DamperModel):
    """Modified Bouc-Wen model of Spencer et al. (1997), with its coil filter.

    Internal states: the inner displacement ``y``, the evolutionary variable ``z`` and
    the filtered command voltage ``u`` (``u' = -eta (u - v)``). The published damper is
    voltage driven (0-2.25 V); mrsuspension drives it with current through the linear
    map ``v = volts_per_amp * i`` (4.5 V/A, so 0.5 A -> 2.25 V). Parameters are in SI,
    converted from the paper's cgs values (set ``"spencer-1997"``).

    :meth:`force` gives the force of a freshly reset damper (``y = x``, ``z = 0``,
    ``u`` settled); use :meth:`response` for loops.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(0.0, 2.0, 1e-4)
    >>> r = SpencerBoucWen().response(t, 0.01 * np.sin(2 * np.pi * t), current=0.25)
    >>> bool(r.dissipated_energy() > 0)
    True
    """

    name: ClassVar[str] = "spencer"
    kind: ClassVar[int] = K.SPENCER
    parameter_rules: ClassVar[dict[str, str]] = {
        "c0a": "positive", "c0b": "nonnegative", "k0": "nonnegative", "c1a": "positive",
        "c1b": "nonnegative", "k1": "nonnegative", "x0": "any", "alpha_a": "nonnegative",
        "alpha_b": "nonnegative", "gamma": "nonnegative", "beta": "any", "A": "any",
        "n": "positive", "eta": "positive", "volts_per_amp": "positive",
    }  # fmt: skip
    default_parameters: ClassVar[str] = "spencer-1997"
    accepts: ClassVar[tuple[str, ...]] = ("spencer",)
    #: options a scenario's ``[damper]`` table may set, with their value kind
    scenario_options: ClassVar[dict[str, str]] = {}

    @property
    def stateful(self) -> bool:
        return True

    def max_damping_rate(self, max_current: float | None = None) -> float:
        # F = c1 y' with y' following x' through c0/(c0 + c1) and the fast Bouc-Wen
        # state: bounded by c1 at the highest command voltage
        i = self.max_current if max_current is None else max_current
        return self.values["c1a"] + self.values["c1b"] * self.values["volts_per_amp"] * i

    def _convert(self, pset: _parameters.ParameterSet) -> dict[str, float]:
        values = dict(pset.values)
        values.pop("max_voltage", None)  # informative only
        return values

    def _check_values(self, set_name: str, values: Any) -> None:
        super()._check_values(set_name, values)
        if values["n"] < 1:
            raise ValidationError(
                f"set {set_name!r}: Bouc-Wen exponent n must be >= 1; got {values['n']}"
            )
