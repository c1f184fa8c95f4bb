"""The damper-model interface shared by every model, and its time-series result."""

from __future__ import annotations

from abc import ABC
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, overload

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.dampers import kernels as K
from mrsuspension.errors import ValidationError, check_finite, check_range, unknown_name

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes

__all__ = ["DamperKernel", "DamperModel", "DamperResponse"]

FloatArray = npt.NDArray[np.float64]
ParameterSpec = str | Path | _parameters.ParameterSet | Mapping[str, float] | None


def broadcast_shape(arrays: Sequence[FloatArray], names: Sequence[str]) -> tuple[int, ...]:
    """Common shape of ``arrays``, or an error naming each input's shape."""
    try:
        return np.broadcast_shapes(*(q.shape for q in arrays))
    except ValueError:
        shapes = ", ".join(f"{n} {q.shape}" for n, q in zip(names, arrays, strict=False))
        raise ValidationError(f"input shapes do not broadcast: {shapes}") from None


def flat_inputs(
    *arrays: npt.ArrayLike, names: tuple[str, ...]
) -> tuple[tuple[int, ...], list[FloatArray]]:
    """Broadcast arrays together; return the shape and contiguous, writeable 1-D arrays."""
    given = [np.asarray(a, dtype=float) for a in arrays]
    shape = broadcast_shape(given, names)
    flat = []
    for q in given:
        if q.shape == shape and q.flags.c_contiguous and q.flags.writeable:
            flat.append(q.ravel())
        else:  # materialise the broadcast (a copy the compiled loop may read and write)
            flat.append(np.array(np.broadcast_to(q, shape), dtype=float).ravel())
    return shape, flat


@dataclass(frozen=True)
class DamperKernel:
    """Flat, compiled-kernel view of a damper with a fresh internal state.

    The simulation engine and the hardware-in-the-loop loop drive a damper through
    :func:`~mrsuspension.dampers.kernels.damper_sample`,
    :func:`~mrsuspension.dampers.kernels.damper_force` and
    :func:`~mrsuspension.dampers.kernels.damper_advance` with these arrays.
    """

    kind: int
    params: FloatArray
    state: FloatArray
    estimator_code: int
    estimator_params: FloatArray
    estimator_state: FloatArray
    max_current: float

    def __post_init__(self) -> None:
        if self.kind not in K.MODEL_CODES.values():
            raise ValidationError(
                f"unknown damper model code {self.kind!r}: the compiled kernels know "
                f"{', '.join(f'{n} = {c}' for n, c in K.MODEL_CODES.items())} "
                "(a new model needs its code and branches in dampers/kernels.py)"
            )


@dataclass(frozen=True)
class DamperResponse:
    """Causal response of a damper to a sampled motion and drive current.

    Attributes are arrays over ``time`` [s]: ``stroke`` x_d [m], ``velocity`` v_d [m/s],
    ``acceleration`` a_d [m/s^2], ``current`` i_d [A], ``force`` F_d [N] and
    ``peak_velocity`` v_m [m/s] (NaN for models without it).
    """

    time: FloatArray
    stroke: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    current: FloatArray
    force: FloatArray
    peak_velocity: FloatArray

    units: ClassVar[dict[str, str]] = {
        "time": "s",
        "stroke": "m",
        "velocity": "m/s",
        "acceleration": "m/s^2",
        "current": "A",
        "force": "N",
        "peak_velocity": "m/s",
    }

    def dissipated_energy(self) -> float:
        """Energy absorbed by the damper over the record, ``integral F_d v_d dt`` [J]."""
        return float(np.trapezoid(self.force * self.velocity, self.time))

    def to_pandas(self) -> pd.DataFrame:
        """The signals as a DataFrame indexed by ``time``, columns by plain name
        (``df["force"]``), units in ``df.attrs["units"]``."""
        import pandas as pd

        df = pd.DataFrame(
            {k: getattr(self, k) for k in self.units if k != "time"},
            index=pd.Index(self.time, name="time"),
        )
        df.attrs["units"] = dict(self.units)
        return df

    def plot(self, kind: str = "F-v", ax: Axes | None = None, **style: Any) -> Axes:
        """Plot the force loop against velocity (``"F-v"``) or stroke (``"F-x"``).

        Draws into ``ax`` when given, else into a new figure made without pyplot
        (:func:`~mrsuspension._notebook.new_figure`; ``ax.figure``); returns the Axes.
        """
        if kind not in ("F-v", "F-x"):
            raise ValidationError(f"plot kind must be 'F-v' or 'F-x'; got {kind!r}")
        if ax is None:
            from mrsuspension._notebook import new_figure

            ax = new_figure(6.4, 4.8).subplots()
        if kind == "F-v":
            ax.plot(self.velocity, self.force, **style)
            ax.set_xlabel("damper velocity $v_d$ [m/s]")
        else:
            ax.plot(self.stroke * 1e3, self.force, **style)
            ax.set_xlabel("damper stroke $x_d$ [mm]")
        ax.set_ylabel("damper force $F_d$ [N]")
        return ax


class DamperModel(ABC):
    """One interface for every damper model.

    A damper model maps stroke ``x_d`` [m], velocity ``v_d`` [m/s], acceleration
    ``a_d`` [m/s^2] and drive current ``i`` [A] to force ``F_d`` [N], with the damper's
    sign convention (model reference, section 1): positive quantities are compression, and a
    positive force resists compression.

    * :meth:`force` evaluates the model pointwise over broadcast arrays (the exact map for
      memoryless models; for models with internal state, the force of a freshly reset
      damper);
    * :meth:`response` runs the causal model over a sampled time series (peak-velocity
      windows, Bouc-Wen states, coil filter);
    * :meth:`kernel` exposes the compiled scalar path for the simulation engine.
    """

    #: registry name of the model family
    name: ClassVar[str]
    #: compiled-kernel model code
    kind: ClassVar[int]
    #: parameter names and a predicate name for each ("any", "positive", "nonnegative")
    parameter_rules: ClassVar[dict[str, str]]
    #: registered parameter set used when none is given
    default_parameters: ClassVar[str]
    #: parameter-set families this model accepts
    accepts: ClassVar[tuple[str, ...]]
    #: whether the drive current changes the force (False: a passive model such as the
    #: linear damper; the measures of its runs then report no current)
    takes_current: ClassVar[bool] = True

    def __init__(self, parameters: ParameterSpec = None, *, max_current: float | None = None):
        pset = _parameters.resolve(
            parameters if parameters is not None else self.default_parameters, model=self.name
        )
        if pset.model not in self.accepts:
            raise ValidationError(
                f"parameter set {pset.name!r} is for model {pset.model!r}; "
                f"model {self.name!r} accepts sets of: {', '.join(self.accepts)}"
            )
        # the limit first: some models check their parameters over 0..max_current
        self.max_current = float(
            check_range("max_current", pset.max_current if max_current is None else max_current,
                        0.0, 10.0, unit="A", low_inclusive=False)
        )  # fmt: skip
        values = self._convert(pset)
        self._check_values(pset.name, values)
        self.parameters = pset
        self.values: dict[str, float] = values
        self._p = self._vector()

    # -- subclass hooks --------------------------------------------------------------
    def _convert(self, pset: _parameters.ParameterSet) -> dict[str, float]:
        """Map a set of an accepted family onto this model's parameter names."""
        return dict(pset.values)

    def _vector(self) -> FloatArray:
        """The parameter vector of the compiled kernel."""
        return np.array([self.values[k] for k in self.parameter_rules], dtype=float)

    def _estimator_arrays(self, dt: float) -> tuple[int, FloatArray, FloatArray]:
        return K.EST_KNOWN, np.zeros(1), np.zeros(1)

    # -- validation ------------------------------------------------------------------
    def _check_values(self, set_name: str, values: Mapping[str, float]) -> None:
        for key in values:
            if key not in self.parameter_rules:
                raise unknown_name(
                    f"parameter for model {self.name!r} in set {set_name!r}:",
                    key,
                    self.parameter_rules,
                )
        for key, rule in self.parameter_rules.items():
            if key not in values:
                raise ValidationError(
                    f"parameter set {set_name!r} lacks {key!r}, needed by model {self.name!r} "
                    f"(needs: {', '.join(self.parameter_rules)})"
                )
            v = values[key]
            if (rule == "positive" and not v > 0) or (rule == "nonnegative" and not v >= 0):
                sign = "> 0" if rule == "positive" else ">= 0"
                raise ValidationError(
                    f"parameter {key!r} of set {set_name!r} must be {sign} for model "
                    f"{self.name!r}; got {v}"
                )

    def check_current(self, current: object) -> FloatArray:
        """Validate drive currents against ``[0, max_current]``."""
        return check_range("drive current", current, 0.0, self.max_current, unit="A")

    # -- public API ------------------------------------------------------------------
    @overload
    def force(
        self,
        stroke: float,
        velocity: float,
        acceleration: float = 0.0,
        current: float = 0.0,
        *,
        peak_velocity: float | None = None,
    ) -> float: ...

    @overload
    def force(
        self,
        stroke: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        current: npt.ArrayLike = 0.0,
        *,
        peak_velocity: npt.ArrayLike | None = None,
    ) -> FloatArray: ...

    def force(
        self,
        stroke: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        current: npt.ArrayLike = 0.0,
        *,
        peak_velocity: npt.ArrayLike | None = None,
    ) -> Any:
        """Damper force [N] at each point of the broadcast inputs.

        Parameters
        ----------
        stroke, velocity, acceleration : array_like
            x_d [m], v_d [m/s], a_d [m/s^2], compression positive.
        current : array_like
            Drive current [A], within ``[0, max_current]``.
        peak_velocity : array_like, optional
            v_m [m/s] for models that use it; by default the model's estimator is asked
            with only this one sample (``cycle-rms``: (2.14), ``window``: ``|v_d|``; clamped).

        Returns
        -------
        numpy.ndarray or float
            Force [N] with the broadcast shape of the inputs; a ``float`` when every
            input is a scalar.

        Examples
        --------
        >>> from mrsuspension.dampers import WangSymmetric
        >>> round(WangSymmetric().force(0.01, 0.1, 0.0, 0.2), 1)  # scalars in, a scalar out
        912.7
        >>> WangSymmetric().force([0.01, 0.0], 0.1, 0.0, 0.2).shape
        (2,)
        """
        x, v, a, i, vm, shape = self._validated(
            stroke, velocity, acceleration, current, peak_velocity
        )
        out = np.asarray(self._force_arrays(x, v, a, i, vm), dtype=float)
        if out.shape != shape:
            out = np.broadcast_to(out, shape).copy()
        return float(out) if out.ndim == 0 else out

    def _validated(
        self,
        stroke: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike,
        current: npt.ArrayLike,
        peak_velocity: npt.ArrayLike | None,
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray | None, tuple[int, ...]]:
        """Check the inputs of :meth:`force`; return them and their broadcast shape."""
        x = check_finite("stroke", stroke)
        v = check_finite("velocity", velocity)
        a = check_finite("acceleration", acceleration)
        i = self.check_current(current)
        vm = None if peak_velocity is None else self._check_peak_velocity(peak_velocity)
        arrays = (x, v, a, i) if vm is None else (x, v, a, i, vm)
        names = ("stroke", "velocity", "acceleration", "current", "peak_velocity")
        return x, v, a, i, vm, broadcast_shape(arrays, names)

    def _force_arrays(
        self,
        x: FloatArray,
        v: FloatArray,
        a: FloatArray,
        i: FloatArray,
        vm: FloatArray | None,
    ) -> FloatArray:
        """Force over validated, broadcastable arrays (default: the compiled kernel loop).

        Memoryless models override this with numpy expressions of the same equations,
        which numpy evaluates with SIMD; a test keeps both paths equal to round-off.
        """
        shape, (x1, v1, a1, i1, vm1) = flat_inputs(
            x, v, a, i, np.full((), np.nan) if vm is None else vm,
            names=("stroke", "velocity", "acceleration", "current", "peak_velocity"),
        )  # fmt: skip
        out = np.empty(x1.shape)
        ek, ep, _ = self._estimator_arrays(1.0)
        K.damper_pointwise(
            self.kind, self._p, ek, ep, x1, v1, a1, i1, vm1, out, np.zeros(K.STATE_SIZE)
        )
        return out.reshape(shape)

    def kernel_force(
        self,
        stroke: npt.ArrayLike,
        velocity: npt.ArrayLike,
        acceleration: npt.ArrayLike = 0.0,
        current: npt.ArrayLike = 0.0,
        *,
        peak_velocity: npt.ArrayLike | None = None,
    ) -> FloatArray:
        """:meth:`force` evaluated point by point by the compiled scalar kernel.

        The simulation engine uses this path; it exists publicly so that tests and
        benchmarks can hold the two paths against each other.
        """
        x, v, a, i, vm, _ = self._validated(stroke, velocity, acceleration, current, peak_velocity)
        return DamperModel._force_arrays(self, x, v, a, i, vm)

    def _check_peak_velocity(self, peak_velocity: npt.ArrayLike) -> FloatArray:
        raise ValidationError(f"model {self.name!r} has no peak-velocity input")

    def response(
        self,
        time: npt.ArrayLike,
        stroke: npt.ArrayLike,
        velocity: npt.ArrayLike | None = None,
        acceleration: npt.ArrayLike | None = None,
        current: npt.ArrayLike = 0.0,
    ) -> DamperResponse:
        """Causal response to a uniformly sampled motion (and current) history.

        Velocity and acceleration, when not given, are derived from the stroke by
        second-order central differences (:func:`numpy.gradient`).

        Examples
        --------
        >>> import numpy as np
        >>> from mrsuspension.dampers import LinearViscous
        >>> t = np.linspace(0.0, 1.0, 1001)
        >>> r = LinearViscous(damping=1000.0).response(t, 0.01 * np.sin(2 * np.pi * t))
        >>> round(r.dissipated_energy(), 3)  # pi c omega a^2 per cycle
        1.974
        """
        t = check_finite("time", time)
        if t.ndim != 1 or t.size < 2:
            raise ValidationError(
                f"time must be a 1-D array of at least 2 samples; got shape {t.shape}"
            )
        steps = np.diff(t)
        dt = float(steps.mean())
        if dt <= 0 or np.max(np.abs(steps - dt)) > 1e-6 * dt + 1e-12:
            raise ValidationError(
                "time must be increasing and uniformly sampled; "
                f"steps range from {steps.min():g} to {steps.max():g} s"
            )
        n = t.size

        def series(name: str, value: npt.ArrayLike) -> FloatArray:
            arr = check_finite(name, value)
            if arr.ndim == 0:
                return np.full(n, float(arr))
            if arr.shape != (n,):
                raise ValidationError(f"{name} must have the shape of time {(n,)}; got {arr.shape}")
            return np.ascontiguousarray(arr, dtype=float)

        x = series("stroke", stroke)
        v = series("velocity", velocity) if velocity is not None else np.gradient(x, dt)
        a = series("acceleration", acceleration) if acceleration is not None else np.gradient(v, dt)
        i = series("drive current", self.check_current(current))  # NaN: say the range too
        kern = self.kernel(dt)
        f = np.empty(n)
        vm = np.empty(n)
        K.damper_series(
            kern.kind, kern.params, kern.state, kern.estimator_code, kern.estimator_params,
            kern.estimator_state, x, v, a, i, dt, f, vm,
        )  # fmt: skip
        return DamperResponse(t, x, v, a, i, f, vm)

    def kernel(self, dt: float) -> DamperKernel:
        """Compiled-path view with a fresh internal state, for sampling period ``dt``."""
        ek, ep, es = self._estimator_arrays(dt)
        return DamperKernel(
            kind=self.kind,
            params=self._p.copy(),
            state=np.zeros(K.STATE_SIZE),
            estimator_code=ek,
            estimator_params=ep,
            estimator_state=es,
            max_current=self.max_current,
        )

    def max_damping_rate(self, max_current: float | None = None) -> float:
        """Upper bound of ``dF_d/dv_d`` [N s/m] up to ``max_current``: the stiffness a
        time-stepper must resolve (used for the engine's step-size check)."""
        raise NotImplementedError

    @property
    def stateful(self) -> bool:
        """Whether the force depends on past inputs (internal states or estimator memory)."""
        return False

    def describe(self) -> dict[str, Any]:
        """Plain-data description (model, parameter set, provenance, options)."""
        return {
            "model": self.name,
            "parameter_set": self.parameters.name,
            "source": self.parameters.source,
            "max_current": self.max_current,
            "parameters": dict(self.values),
        }

    def __repr__(self) -> str:
        return f"{type(self).__name__}(parameters={self.parameters.name!r})"
