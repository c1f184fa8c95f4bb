"""The dissertation's hysteretic MR-damper model: symmetric (2.15) and asymmetric (2.19).

Both share one compiled kernel (:func:`~mrsuspension.dampers.kernels.wang_force`); the
symmetric model is the asymmetric one with ``k5 = k6 = 0`` and ``k1c = k1e = k1``, and
either becomes the *mean* model with ``k4 = 0`` (``hysteresis=False``).
"""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar, Literal, overload

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.dampers import kernels as K
from mrsuspension.dampers.base import DamperModel, FloatArray, ParameterSpec, flat_inputs
from mrsuspension.dampers.peak_velocity import (
    DEFAULT_ESTIMATOR,
    ESTIMATORS,
    V_LIMIT,
    CycleRms,
    InstantaneousPeak,
    KnownPeak,
    PeakVelocityEstimator,
    WindowPeak,
    make_estimator,
)
from mrsuspension.errors import ValidationError, check_finite, check_range, unknown_name

__all__ = ["CHARACTERISATION_VH", "VEHICLE_VH_VARIANT", "WangAsymmetric", "WangSymmetric"]

VhVariant = Literal["2.12", "2.13"]

#: v_h variant of the dissertation's model when none is given: the damper model on its own
#: (``WangSymmetric()``, ``mrsus damper``) and in vehicle simulations (Simulation's default
#: damper, scenarios, studies, the report, HiL) alike, so that the same name is one model.
#: The characterisation figures and the 13-parameter fit ask for (2.12)
#: (:data:`CHARACTERISATION_VH`). Chosen by evidence (docs/errata.md, "v_h in vehicle
#: studies"): (2.15) is the decoupled product C_i(i) F_h(v); the inverse model and the
#: dissertation's inverse check use (2.13); (2.12)'s H(i) is extrapolated past the 0.4 A
#: tests (x2.28 at 0.5 A) and lets policy I at 3.5 cm, 2.0-2.6 Hz reach 14.5 kN against
#: 8.0 kN with (2.13) (the HiL load cell was rated 8.8 kN).
VEHICLE_VH_VARIANT: VhVariant = "2.13"
#: ``v_h`` of the dissertation's characterisation (Chapter 2 figures, the 13-parameter
#: identification): the current-dependent (2.12)
CHARACTERISATION_VH: VhVariant = "2.12"

_COMMON_RULES = {
    "a0": "positive", "a1": "any", "a2": "nonnegative", "a3": "nonnegative",
    "a4": "nonnegative", "I0": "any", "I1": "any", "k0": "nonnegative",
}  # fmt: skip


def _estimator_class(
    estimator: str | PeakVelocityEstimator | None,
) -> type[PeakVelocityEstimator] | None:
    """The class a name (or None: the default) selects; None for an instance."""
    if isinstance(estimator, str | None):
        return ESTIMATORS.get(estimator or DEFAULT_ESTIMATOR)
    return None


class WangSymmetric(DamperModel):
    """Symmetric hysteretic model, eq. (2.15), with the force gain ``k_d``.

    Parameters
    ----------
    parameters : str, path, ParameterSet or dict, optional
        Parameter set (default ``"wang-symmetric-low"``, Table 2.2, 0.5-5 Hz).
    hysteresis : bool
        ``False`` gives the mean model (``k4 = 0``, so ``v_h = 0``).
    vh_variant : {"2.13", "2.12"}
        Zero-force velocity intercept: the simplified (2.13), default, as in every
        simulation, the inverse model and the HiL loop (:data:`VEHICLE_VH_VARIANT`,
        ``docs/errata.md``), or the current-dependent (2.12) with all 13 identified
        parameters (the dissertation's characterisation figures).
    force_gain : float
        ``k_d`` multiplying the force (sections 5.3/6.2; default 1).
    estimator : str or PeakVelocityEstimator
        Peak-velocity estimator, ``"cycle-rms"`` (default), ``"window"``,
        ``"instantaneous"`` or ``"known"`` (then pass ``peak_velocity=``), see
        :mod:`mrsuspension.dampers.peak_velocity`. Its ``v_max`` defaults to the upper end
        of the parameter set's ``velocity_range`` (0.75 m/s for Tables 2.2 and 2.3).
    max_current : float, optional
        Highest accepted drive current [A] (default: the set's, 0.5 A).
    **estimator_options
        Passed to the estimator (``window=``, ``v_min=``, ``v_max=``, ``value=``).

    Examples
    --------
    >>> m = WangSymmetric(hysteresis=False)
    >>> f = m.force(0.0, [-0.2, 0.2], 0.0, 0.2, peak_velocity=0.3)
    >>> bool(f[0] < 0 < f[1]) and bool(abs(f[0] + f[1]) < 1e-9)
    True
    """

    name: ClassVar[str] = "wang-symmetric"
    kind: ClassVar[int] = K.WANG
    parameter_rules: ClassVar[dict[str, str]] = {
        **_COMMON_RULES,
        "k1": "nonnegative", "k2": "nonnegative", "k3": "any", "k4": "any", "F0": "positive",
    }  # fmt: skip
    default_parameters: ClassVar[str] = "wang-symmetric-low"
    accepts: ClassVar[tuple[str, ...]] = ("wang-symmetric",)
    #: options a scenario's ``[damper]`` table may set, with their value kind (the
    #: estimator's ``window``, ``v_min``, ``v_max`` and ``value`` are passed through)
    scenario_options: ClassVar[dict[str, str]] = {
        "hysteresis": "bool", "vh_variant": "text", "force_gain": "number",
        "estimator": "string", "window": "number", "v_min": "number", "v_max": "number",
        "value": "number",
    }  # fmt: skip

    def __init__(
        self,
        parameters: ParameterSpec = None,
        *,
        hysteresis: bool = True,
        vh_variant: VhVariant = VEHICLE_VH_VARIANT,
        force_gain: float = 1.0,
        estimator: str | PeakVelocityEstimator | None = None,
        max_current: float | None = None,
        **estimator_options: Any,
    ) -> None:
        if vh_variant not in ("2.12", "2.13"):
            raise ValidationError(f"vh_variant must be '2.12' or '2.13'; got {vh_variant!r}")
        if not isinstance(hysteresis, bool):
            raise ValidationError(f"hysteresis must be true or false; got {hysteresis!r}")
        self.hysteresis = hysteresis
        self.vh_variant: VhVariant = vh_variant
        self.force_gain = float(
            check_range("force_gain", force_gain, 0.0, 100.0, low_inclusive=False)
        )
        self._check_estimator_options(estimator, estimator_options)
        super().__init__(parameters, max_current=max_current)
        self.estimator = self._make_estimator(estimator, estimator_options)

    def _make_estimator(
        self, estimator: str | PeakVelocityEstimator | None, options: dict[str, Any]
    ) -> PeakVelocityEstimator:
        """The named estimator, its ``v_max`` by default the set's identified range."""
        cls = _estimator_class(estimator)
        vrange = self.parameters.velocity_range
        if (
            cls is not None
            and vrange is not None
            and "v_max" not in options
            and "v_max" in {f.name for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
        ):
            options = {**options, "v_max": vrange[1]}
        return make_estimator(estimator, **options)

    def _check_estimator_options(
        self, estimator: str | PeakVelocityEstimator | None, options: dict[str, Any]
    ) -> None:
        """Name a misspelled keyword as an option of this model, with a did-you-mean."""
        if not options:
            return
        own = ["parameters", "hysteresis", "vh_variant", "force_gain", "estimator", "max_current"]
        est_cls = _estimator_class(estimator)
        allowed = [f.name for f in dataclasses.fields(est_cls)] if est_cls is not None else []  # type: ignore[arg-type]
        for key in options:
            if key not in allowed:
                raise unknown_name(f"option of {type(self).__name__}", key, own + allowed)

    def _vector(self) -> FloatArray:
        v = self.values
        p = np.zeros(K.W_SIZE)
        for key, idx in (
            ("a0", K.W_A0), ("a1", K.W_A1), ("a2", K.W_A2), ("a3", K.W_A3), ("a4", K.W_A4),
            ("I0", K.W_I0), ("I1", K.W_I1), ("k0", K.W_K0), ("k2", K.W_K2), ("k3", K.W_K3),
            ("k4", K.W_K4), ("F0", K.W_F0),
        ):  # fmt: skip
            p[idx] = v[key]
        p[K.W_K1C] = v["k1c"] if "k1c" in v else v["k1"]
        p[K.W_K1E] = v["k1e"] if "k1e" in v else v["k1"]
        p[K.W_K5] = v.get("k5", 0.0)
        p[K.W_K6] = v.get("k6", 0.0)
        if not self.hysteresis:
            p[K.W_K4] = 0.0  # mean model
        p[K.W_KD] = self.force_gain
        p[K.W_VHI] = 1.0 if self.vh_variant == "2.12" else 0.0
        K.wang_derive(p)
        return p

    @property
    def stateful(self) -> bool:
        return not isinstance(self.estimator, KnownPeak)

    def _force_arrays(
        self,
        x: FloatArray,
        v: FloatArray,
        a: FloatArray,
        i: FloatArray,
        vm: FloatArray | None,
    ) -> FloatArray:
        """Eqs. (2.7)-(2.21) as numpy expressions (same equations as ``kernels.wang_force``).

        Each factor is computed on the shape of its own input (a scalar current costs
        one evaluation of C_i), and the large arrays are updated in place.
        """
        from scipy.special import expit  # overflow-free logistic, like kernels.sigmoid

        p = self._p
        if vm is None:
            vm = self._pointwise_peak_velocity(x, v, a)
        ci = 1.0 + p[K.W_K2] * (expit(p[K.W_A2] * (i + p[K.W_I0])) - p[K.W_SA2])
        if p[K.W_VHI] != 0.0:
            h = 1.0 + p[K.W_K3] * (expit(p[K.W_A3] * (i + p[K.W_I1])) - p[K.W_SA3])
        else:
            h = np.ones(())
        ft = p[K.W_F0] * (1.0 + np.exp(p[K.W_A1] * vm))  # (2.7)
        alpha = p[K.W_A0] / (1.0 + p[K.W_K0] * vm)  # (2.11)
        decay = np.exp(-p[K.W_A4] * vm)  # (2.10)
        arg = np.sign(a) * (p[K.W_K4] * vm * h)  # v_h, (2.12)/(2.13)
        arg = np.asarray(arg + v)  # allocates the broadcast shape once (0-d for scalars)
        shape = np.broadcast_shapes(arg.shape, np.shape(ci))
        if shape != arg.shape:  # (2.13) has no current factor in v_h: take i's shape now
            arg = np.broadcast_to(arg, shape).copy()
        if p[K.W_K6] != 0.0:
            arg += p[K.W_K6] * vm  # v_b, (2.20)
        arg *= 0.5 * alpha
        np.tanh(arg, out=arg)
        arg *= ft
        if p[K.W_K5] != 0.0:
            arg -= p[K.W_K5] * ci * ft  # F_b, (2.20)
        k1 = p[K.W_K1C] if p[K.W_K1C] == p[K.W_K1E] else np.where(v >= 0.0, p[K.W_K1C], p[K.W_K1E])
        rise = np.abs(v) * (k1 * decay)
        rise += 1.0
        arg *= rise
        arg *= p[K.W_KD] * ci
        return arg

    def max_damping_rate(self, max_current: float | None = None) -> float:
        """Largest pre-yield slope ``k_d C_i F_t (alpha/2 + k_v)`` over the peak velocities
        the estimator can report (model reference, section 7: about 3e5 N s/m at 0.5 A)."""
        i = self.max_current if max_current is None else max_current
        est = self.estimator
        if isinstance(est, KnownPeak):
            vms = np.array([est.value])
        else:
            vmax = getattr(est, "v_max", V_LIMIT)
            vms = np.linspace(0.0, vmax, 201)
        p = self._p
        # C_i (2.9) in plain Python: this bound only validates dt, and asking the compiled
        # kernels.current_gain here would load one more cached kernel at every start-up
        ic = float(self.check_current(min(i, self.max_current)))
        ci = 1.0 + p[K.W_K2] * (K.sigmoid.py_func(p[K.W_A2] * (ic + p[K.W_I0])) - p[K.W_SA2])
        ft = p[K.W_F0] * (1.0 + np.exp(p[K.W_A1] * vms))
        alpha = p[K.W_A0] / (1.0 + p[K.W_K0] * vms)
        kv = max(p[K.W_K1C], p[K.W_K1E]) * np.exp(-p[K.W_A4] * vms)
        return float(np.max(p[K.W_KD] * ci * ft * (0.5 * alpha + kv)))

    def _pointwise_peak_velocity(self, x: FloatArray, v: FloatArray, a: FloatArray) -> FloatArray:
        """v_m of a fresh estimator per point (vectorised ``kernels.estimator_pointwise``)."""
        est = self.estimator
        if isinstance(est, KnownPeak):
            return np.asarray(est.value)
        if isinstance(est, InstantaneousPeak | CycleRms):
            # (2.14); for cycle-rms one sample of the radicand whose cycle mean it takes
            raw, lo, hi = np.sqrt(np.maximum(v * v - a * x, 0.0)), est.v_min, est.v_max
        elif isinstance(est, WindowPeak):
            raw, lo, hi = np.abs(v), est.v_min, est.v_max
        else:  # pragma: no cover - a user-defined estimator: ask it point by point
            return np.vectorize(est.pointwise, otypes=[float])(x, v, a)
        return np.clip(raw, lo, hi)

    def _estimator_arrays(self, dt: float) -> tuple[int, FloatArray, FloatArray]:
        return self.estimator.code, self.estimator.params_for(dt), self.estimator.buffer(dt)

    def _check_peak_velocity(self, peak_velocity: npt.ArrayLike) -> FloatArray:
        return check_range("peak_velocity", peak_velocity, 0.0, V_LIMIT, unit="m/s")

    def current_gain(self, current: npt.ArrayLike) -> FloatArray:
        """C_i(i) of eq. (2.9) (1 at zero current).

        Examples
        --------
        >>> float(WangSymmetric().current_gain(0.0))
        1.0
        """
        i = self.check_current(current)
        return np.vectorize(lambda c: K.current_gain(self._p, float(c)), otypes=[float])(i)

    def passive_hysteron(
        self,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        *,
        stroke: npt.ArrayLike = 0.0,
        peak_velocity: npt.ArrayLike | None = None,
    ) -> FloatArray:
        """F_h of eq. (2.8) (zero current, v_h of (2.13)), the inverse model's reference.

        Note that ``k_d`` is not included: ``F_d = k_d C_i F_h`` for the (2.13) variant.
        """
        return self._inverse(0.0, velocity, acceleration, stroke, peak_velocity, None)[1]

    @overload
    def inverse_current(
        self,
        target_force: float,
        velocity: float,
        acceleration: float = 0.0,
        *,
        stroke: float = 0.0,
        peak_velocity: float | None = None,
        max_current: float | None = None,
    ) -> float: ...

    @overload
    def inverse_current(
        self,
        target_force: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        *,
        stroke: npt.ArrayLike = 0.0,
        peak_velocity: npt.ArrayLike | None = None,
        max_current: float | None = None,
    ) -> FloatArray: ...

    def inverse_current(
        self,
        target_force: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        *,
        stroke: npt.ArrayLike = 0.0,
        peak_velocity: npt.ArrayLike | None = None,
        max_current: float | None = None,
    ) -> Any:
        """Drive current that produces ``|target_force|`` (model reference, section 2.3).

        The damper can only produce the sign of its passive hysteron ``F_h``, so only the
        magnitude of the target is used. Targets below the passive force give 0 A,
        targets above the force at ``max_current`` give ``max_current``. The passive
        hysteron uses the (2.13) form of ``v_h``, so the inverse is exact for models with
        ``vh_variant="2.13"`` (as in the dissertation's Fig. 2.10 check).

        Examples
        --------
        >>> m = WangSymmetric(vh_variant="2.13")
        >>> f = m.force(0.0, 0.1, -1.0, 0.3, peak_velocity=0.2)
        >>> m.inverse_current(f, 0.1, -1.0, peak_velocity=0.2)  # scalars in: a float  # doctest: +ELLIPSIS
        0.3000000...
        """
        if self.values.get("k5", 0.0) != 0.0 or self.values.get("k6", 0.0) != 0.0:
            raise ValidationError(
                "the inverse model (model reference, section 2.3) is defined for the symmetric "
                "model; "
                f"this {self.name!r} model has k5={self.values.get('k5')}, "
                f"k6={self.values.get('k6')}"
            )
        if not (self._p[K.W_K2] > 0 and self._p[K.W_A2] > 0):
            raise ValidationError(
                "the inverse model needs k2 > 0 and a2 > 0 (a current-dependent damper); "
                f"got k2={self._p[K.W_K2]}, a2={self._p[K.W_A2]}"
            )
        current = self._inverse(
            target_force, velocity, acceleration, stroke, peak_velocity, max_current
        )[0]
        return float(current) if np.ndim(current) == 0 else current

    def _inverse(
        self,
        target_force: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike,
        stroke: npt.ArrayLike,
        peak_velocity: npt.ArrayLike | None,
        max_current: float | None,
    ) -> tuple[FloatArray, FloatArray]:
        i_max = self.max_current
        if max_current is not None:
            i_max = float(check_range("max_current", max_current, 0.0, self.max_current, unit="A"))
        shape, (f, x, v, a, vm) = flat_inputs(
            check_finite("target_force", target_force),
            check_finite("stroke", stroke),
            check_finite("velocity", velocity),
            check_finite("acceleration", acceleration),
            np.full((), np.nan)
            if peak_velocity is None
            else self._check_peak_velocity(peak_velocity),
            names=("target_force", "stroke", "velocity", "acceleration", "peak_velocity"),
        )
        current, hysteron = np.empty(f.shape), np.empty(f.shape)
        K.wang_inverse_array(
            self._p, self.estimator.code, self.estimator.params(), f, x, v, a, vm, i_max,
            current, hysteron,
        )  # fmt: skip
        return current.reshape(shape), hysteron.reshape(shape)

    def with_options(self, **changes: Any) -> WangSymmetric:
        """A copy with some constructor options changed (e.g. ``estimator=KnownPeak(0.2)``).

        Examples
        --------
        >>> WangSymmetric().with_options(hysteresis=False).hysteresis
        False
        """
        options: dict[str, Any] = {
            "hysteresis": self.hysteresis,
            "vh_variant": self.vh_variant,
            "force_gain": self.force_gain,
            "estimator": self.estimator,
            "max_current": self.max_current,
        }
        for key in changes:
            if key not in options:
                raise unknown_name(f"option of {type(self).__name__}", key, options)
        options.update(changes)
        return type(self)(self.parameters, **options)

    def describe(self) -> dict[str, Any]:
        d = super().describe()
        d.update(
            hysteresis=self.hysteresis,
            vh_variant=self.vh_variant,
            force_gain=self.force_gain,
            estimator=repr(self.estimator),
        )
        return d

    def __repr__(self) -> str:
        return (
            f"{type(self).__name__}(parameters={self.parameters.name!r}, "
            f"hysteresis={self.hysteresis}, vh_variant={self.vh_variant!r}, "
            f"force_gain={self.force_gain:g}, estimator={self.estimator!r})"
        )


class WangAsymmetric(WangSymmetric):
    """Asymmetric hysteretic model, eqs. (2.19)-(2.21) (default set: Table 2.3).

    Accepts symmetric sets too (``k1c = k1e = k1``, ``k5 = k6 = 0``): the reduction of
    section 2.2 of the model reference.

    Examples
    --------
    >>> m = WangAsymmetric(hysteresis=False)
    >>> f = m.force(0.0, [-0.2, 0.2], 0.0, 0.2, peak_velocity=0.3)
    >>> bool(-f[0] > f[1] > 0)  # rebound force exceeds compression force
    True
    """

    name: ClassVar[str] = "wang-asymmetric"
    parameter_rules: ClassVar[dict[str, str]] = {
        **_COMMON_RULES,
        "k1c": "nonnegative", "k1e": "nonnegative", "k2": "nonnegative", "k3": "any",
        "k4": "any", "k5": "any", "k6": "any", "F0": "positive",
    }  # fmt: skip
    default_parameters: ClassVar[str] = "wang-asymmetric"
    accepts: ClassVar[tuple[str, ...]] = ("wang-asymmetric", "wang-symmetric")

    def _convert(self, pset: _parameters.ParameterSet) -> dict[str, float]:
        values = dict(pset.values)
        if pset.model == "wang-symmetric" and "k1" in values:
            k1 = values.pop("k1")
            values.update(k1c=k1, k1e=k1, k5=0.0, k6=0.0)
        return values
