"""What the fit needs to know about each damper model: bounds, scaling, Jacobians.

The residuals always come from the package's own models (:meth:`DamperModel.force`
with the known peak velocity of each test, or :meth:`DamperModel.response` over
repeated cycles for a model with internal states), so the fit uses the same physics as
the simulator. For the memoryless models this module adds the analytic derivatives of
the force with respect to the parameters (the chain rule through eqs. (2.7)-(2.21) for
the dissertation's models); a test holds them against finite differences of the
models' forces.

Default bounds scale with the campaign (largest force, current and velocity) so that a
damper of another size fits from the same defaults; they are listed in
``docs/identification.md``.

Examples
--------
>>> spec = FIT_MODELS["bingham"]()
>>> spec.damper.name, spec.force_scale
('bingham', ('fc_a', 'fc_b', 'c0_a', 'c0_b', 'f0'))
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from scipy.special import expit

from mrsuspension import parameters as _parameters
from mrsuspension.dampers import (
    Bingham,
    DamperModel,
    LinearViscous,
    SpencerBoucWen,
    WangAsymmetric,
    WangSymmetric,
)
from mrsuspension.dampers.wang import (
    CHARACTERISATION_VH,
)
from mrsuspension.errors import ValidationError, unknown_name
from mrsuspension.identify.preprocess import Loop

__all__ = ["FIT_MODELS", "FitData", "FitModel"]

FloatArray = npt.NDArray[np.float64]
Bounds = dict[str, tuple[float, float]]


@dataclass(frozen=True)
class FitData:
    """The loops of a fit, concatenated, with a residual weight per point.

    ``weight`` is ``1 / (force range of the test * sqrt(points of the test))``, so the
    sum of squared weighted residuals is the sum over tests of NRMSE^2 (the cost
    (2.22) with every test normalised by its force range; model reference, section 10). ``centred``
    marks loops whose mean force was removed: their model force loses its mean too.
    """

    loops: tuple[Loop, ...]
    stroke: FloatArray
    velocity: FloatArray
    acceleration: FloatArray
    current: FloatArray
    peak_velocity: FloatArray
    force: FloatArray
    weight: FloatArray
    slices: tuple[slice, ...]
    centred: tuple[bool, ...] = ()

    @classmethod
    def from_loops(cls, loops: Sequence[Loop]) -> FitData:
        """Concatenate ``loops`` (at least one)."""
        if not loops:
            raise ValidationError("no loops to fit")
        slices = []
        start = 0
        for loop in loops:
            slices.append(slice(start, start + loop.force.size))
            start += loop.force.size

        def cat(name: str) -> FloatArray:
            return np.ascontiguousarray(np.concatenate([getattr(lp, name) for lp in loops]))

        return cls(
            loops=tuple(loops),
            stroke=cat("stroke"),
            velocity=cat("velocity"),
            acceleration=cat("acceleration"),
            current=cat("current"),
            peak_velocity=np.concatenate(
                [np.full(lp.force.size, lp.peak_velocity) for lp in loops]
            ),
            force=cat("force"),
            weight=np.concatenate(
                [
                    np.full(lp.force.size, 1.0 / (lp.force_range * math.sqrt(lp.force.size)))
                    for lp in loops
                ]
            ),
            slices=tuple(slices),
            centred=tuple(lp.offset_removed for lp in loops),
        )

    @cached_property
    def sign_acceleration(self) -> FloatArray:
        """sgn(a_d) at every point (the hysteresis branch of the dissertation's models)."""
        return np.sign(self.acceleration)

    @cached_property
    def abs_velocity(self) -> FloatArray:
        """|v_d| at every point."""
        return np.abs(self.velocity)

    @cached_property
    def compression(self) -> npt.NDArray[np.bool_]:
        """v_d >= 0 (compression side of the asymmetric model)."""
        return self.velocity >= 0.0

    def centre(self, values: FloatArray) -> FloatArray:
        """Subtract, in place, the per-loop mean of ``values`` (rows) for loops whose
        measured offset was removed; returns ``values``."""
        for sl, c in zip(self.slices, self.centred, strict=True):
            if c:
                values[sl] -= values[sl].mean(axis=0)
        return values

    @property
    def max_force(self) -> float:
        """Largest force magnitude [N]."""
        return float(np.max(np.abs(self.force)))

    @property
    def max_current(self) -> float:
        """Largest drive current [A]."""
        return float(np.max(self.current))

    @property
    def max_velocity(self) -> float:
        """Largest velocity magnitude [m/s]."""
        return float(np.max(np.abs(self.velocity)))

    @property
    def max_stroke(self) -> float:
        """Largest stroke magnitude [m]."""
        return float(np.max(np.abs(self.stroke)))


class FitModel:
    """Fit-side description of one damper model (subclass per model family).

    Parameters
    ----------
    options : mapping, optional
        Constructor options of the damper model (e.g. ``hysteresis``, ``vh_variant``
        for the dissertation's models); the estimator is always ``known`` v_m per test.
    """

    #: damper model class
    damper: ClassVar[type[DamperModel]]
    #: parameters that scale the force together (one common factor scales F exactly)
    force_scale: ClassVar[tuple[str, ...]] = ()
    #: parameters held at their start value unless the user frees them
    default_fixed: ClassVar[tuple[str, ...]] = ()
    #: whether :meth:`jacobian` is analytic
    analytic: ClassVar[bool] = False
    #: default number of starts of the multi-start fit
    default_starts: ClassVar[int] = 1
    #: constructor options accepted
    option_names: ClassVar[tuple[str, ...]] = ()
    #: default evaluation budget per start (None: scipy's default, 100 per parameter)
    default_max_nfev: ClassVar[int | None] = None

    def __init__(self, options: Mapping[str, Any] | None = None) -> None:
        opts = dict(options or {})
        for key in opts:
            if key not in self.option_names:
                raise unknown_name(
                    f"option of model {self.damper.name!r} for identification",
                    key,
                    self.option_names or ("(none)",),
                )
        self.options = opts

    @property
    def name(self) -> str:
        """Registry name of the model."""
        return self.damper.name

    def fixed_by_options(self) -> tuple[str, ...]:
        """Parameters that have no effect with the chosen options."""
        return ()

    def construct(self, parameters: _parameters.ParameterSet, max_current: float) -> DamperModel:
        """The damper model with a parameter set and the model options."""
        return self.damper(parameters, max_current=max_current, **self.options)

    def build(self, values: Mapping[str, float], max_current: float) -> DamperModel:
        """The damper model with these parameter values."""
        pset = _parameters.ParameterSet(name="fit", model=self.damper.name, values=dict(values))
        return self.construct(pset, max_current)

    def forces(self, model: DamperModel, data: FitData) -> FloatArray:
        """Model force at every point of ``data``."""
        return model.force(data.stroke, data.velocity, data.acceleration, data.current)

    def jacobian(
        self,
        values: Mapping[str, float],
        free: Sequence[str],
        data: FitData,
        weight: FloatArray | None = None,
    ) -> FloatArray | None:
        """d force / d parameter for the ``free`` parameters, rows times ``weight``
        (``None``: not analytic)."""
        return None

    def default_bounds(self, data: FitData, start: Mapping[str, float]) -> Bounds:
        """Bounds of every parameter, scaled to the campaign."""
        raise NotImplementedError  # pragma: no cover


# ----------------------------------------------------------------------------------
class WangFit(FitModel):
    """The dissertation's symmetric model (2.15), evaluated with the known v_m per test."""

    damper: ClassVar[type[DamperModel]] = WangSymmetric
    force_scale = ("F0",)
    analytic = True
    default_starts = 8
    option_names = ("hysteresis", "vh_variant", "force_gain")
    # starts from the global stage that head for a poor local minimum otherwise run to
    # scipy's 1300 evaluations; the best start of a 30-test campaign needs ~150
    default_max_nfev: ClassVar[int | None] = 400

    def __init__(self, options: Mapping[str, Any] | None = None) -> None:
        # all 13 identified parameters: the current-dependent v_h (2.12) unless asked
        super().__init__({"vh_variant": CHARACTERISATION_VH, **(options or {})})

    def fixed_by_options(self) -> tuple[str, ...]:
        fixed: list[str] = []
        if self.options.get("vh_variant", "2.12") == "2.13":
            fixed += ["a3", "k3", "I1"]  # H(i) = 1
        if self.options.get("hysteresis", True) is False:
            fixed.append("k4")  # mean model
        return tuple(fixed)

    def forces(self, model: DamperModel, data: FitData) -> FloatArray:
        return model.force(
            data.stroke, data.velocity, data.acceleration, data.current,
            peak_velocity=data.peak_velocity,
        )  # fmt: skip

    def default_bounds(self, data: FitData, start: Mapping[str, float]) -> Bounds:
        i_ref = max(data.max_current, 0.1)
        f_ref = data.max_force
        b: Bounds = {
            "a0": (1.0, 1e5),  # s/m: tanh slope (Table 2.2: ~990)
            "a1": (-20.0, 20.0),  # s/m: exp(a1 v_m) in F_t; |a1| <= 20 keeps F_t sane to 1 m/s
            "a2": (0.0, 100.0 / i_ref),  # 1/A: sigmoid slopes, |a (i + I)| < 400
            "a3": (0.0, 100.0 / i_ref),
            "a4": (0.0, 50.0),  # s/m
            "I0": (-3.0 * i_ref, 3.0 * i_ref),  # A
            "I1": (-3.0 * i_ref, 3.0 * i_ref),
            "k0": (0.0, 5000.0),  # s/m
            "k1": (0.0, 500.0),  # s/m
            "k1c": (0.0, 500.0),
            "k1e": (0.0, 500.0),
            "k2": (0.0, 200.0),
            "k3": (-200.0, 200.0),
            "k4": (-2.0, 2.0),
            "k5": (-2.0, 2.0),
            "k6": (-2.0, 2.0),
            "F0": (1e-4 * f_ref, 10.0 * f_ref),  # N
        }
        return {k: b[k] for k in self.damper.parameter_rules}

    def jacobian(
        self,
        values: Mapping[str, float],
        free: Sequence[str],
        data: FitData,
        weight: FloatArray | None = None,
    ) -> FloatArray:
        """Chain rule through eqs. (2.7)-(2.21) (symbols: model reference, sections 2.1-2.2).

        Only the requested columns are formed; ``weight`` (per point) multiplies the
        rows, folded into the common factors so it costs nothing extra.
        """
        p = values
        v, i, vm = data.velocity, data.current, data.peak_velocity
        s = data.sign_acceleration
        av = data.abs_velocity
        kd = float(self.options.get("force_gain", 1.0))
        hysteresis = self.options.get("hysteresis", True)
        vh212 = self.options.get("vh_variant", "2.12") == "2.12"
        k4 = p["k4"] if hysteresis else 0.0
        k1c = p.get("k1c", p.get("k1", 0.0))
        k1e = p.get("k1e", p.get("k1", 0.0))
        k5, k6 = p.get("k5", 0.0), p.get("k6", 0.0)
        # C_i, eq. (2.9)
        s2, s20 = expit(p["a2"] * (i + p["I0"])), float(expit(p["a2"] * p["I0"]))
        c = 1.0 + p["k2"] * (s2 - s20)
        # H(i), eq. (2.12); 1 for (2.13)
        if vh212:
            s3, s30 = expit(p["a3"] * (i + p["I1"])), float(expit(p["a3"] * p["I1"]))
            h: Any = 1.0 + p["k3"] * (s3 - s30)
        else:
            s3, s30, h = np.zeros(()), 0.0, 1.0
        e1 = np.exp(p["a1"] * vm)
        ft = p["F0"] * (1.0 + e1)  # (2.7)
        den = 1.0 + p["k0"] * vm
        alpha = p["a0"] / den  # (2.11)
        dec = np.exp(-p["a4"] * vm)  # (2.10)
        if k1c == k1e:
            k1v: Any = k1c
        else:
            k1v = np.where(data.compression, k1c, k1e)
        dec_av = dec * av
        r = 1.0 + k1v * dec_av  # linear rise
        u = v + s * (k4 * vm * h) + k6 * vm  # v + v_h + v_b
        th = np.tanh(0.5 * alpha * u)
        sech2 = 1.0 - th * th
        w = kd if weight is None else kd * weight
        wcr = w * c * r
        g_t = th - k5 * c  # (F_t tanh - F_b) / F_t
        dF_dft = wcr * g_t
        dF_du = wcr * ft * sech2 * (0.5 * alpha)
        dF_dalpha = wcr * ft * sech2 * (0.5 * u)
        dF_dc = (w * r) * ft * (g_t - k5 * c)
        dF_dr = (w * c) * ft * g_t

        def du_dh() -> FloatArray:
            return np.asarray(dF_du * s * (k4 * vm))

        cols: dict[str, Callable[[], Any]] = {
            "a0": lambda: dF_dalpha / den,
            "k0": lambda: dF_dalpha * (-p["a0"] * vm / (den * den)),
            "a1": lambda: dF_dft * (p["F0"] * vm * e1),
            "F0": lambda: dF_dft * (1.0 + e1),
            "a4": lambda: dF_dr * (-vm * k1v * dec_av),
            "k2": lambda: dF_dc * (s2 - s20),
            "a2": lambda: (
                dF_dc * (p["k2"] * (s2 * (1 - s2) * (i + p["I0"]) - s20 * (1 - s20) * p["I0"]))
            ),
            "I0": lambda: dF_dc * (p["k2"] * p["a2"] * (s2 * (1 - s2) - s20 * (1 - s20))),
            "k4": lambda: dF_du * s * (vm * h) if hysteresis else 0.0,
            "k6": lambda: dF_du * vm,
            "k5": lambda: -(w * c * c) * r * ft,
            "k3": lambda: du_dh() * (s3 - s30),
            "a3": lambda: (
                du_dh()
                * (
                    p.get("k3", 0.0)
                    * (s3 * (1 - s3) * (i + p.get("I1", 0.0)) - s30 * (1 - s30) * p.get("I1", 0.0))
                )
            ),
            "I1": lambda: (
                du_dh() * (p.get("k3", 0.0) * p.get("a3", 0.0) * (s3 * (1 - s3) - s30 * (1 - s30)))
            ),
            "k1": lambda: dF_dr * dec_av,
            "k1c": lambda: dF_dr * np.where(data.compression, dec_av, 0.0),
            "k1e": lambda: dF_dr * np.where(data.compression, 0.0, dec_av),
        }
        out = np.empty((v.size, len(free)), order="F")
        for j, name in enumerate(free):
            out[:, j] = cols[name]()
        return out


class WangAsymmetricFit(WangFit):
    """The dissertation's asymmetric model (2.19)-(2.21) (16 parameters)."""

    damper: ClassVar[type[DamperModel]] = WangAsymmetric


class BinghamFit(FitModel):
    """Current-dependent Bingham model (linear in its parameters)."""

    damper: ClassVar[type[DamperModel]] = Bingham
    force_scale = ("fc_a", "fc_b", "c0_a", "c0_b", "f0")
    analytic = True
    default_starts = 1

    def default_bounds(self, data: FitData, start: Mapping[str, float]) -> Bounds:
        f, i, v = data.max_force, max(data.max_current, 0.1), max(data.max_velocity, 1e-3)
        return {
            "fc_a": (0.0, 10.0 * f),
            "fc_b": (0.0, 10.0 * f / i),  # >= 0 keeps the yield force positive at any current
            "c0_a": (0.0, 10.0 * f / v),
            "c0_b": (0.0, 10.0 * f / (v * i)),
            "f0": (-f, f),
        }

    def jacobian(
        self,
        values: Mapping[str, float],
        free: Sequence[str],
        data: FitData,
        weight: FloatArray | None = None,
    ) -> FloatArray:
        sg, v, i = np.sign(data.velocity), data.velocity, data.current
        cols = {"fc_a": sg, "fc_b": i * sg, "c0_a": v, "c0_b": i * v, "f0": np.ones_like(v)}
        out = np.column_stack([cols[n] for n in free])
        return out if weight is None else out * weight[:, None]


class LinearFit(FitModel):
    """Linear viscous damper ``F = c v``."""

    damper: ClassVar[type[DamperModel]] = LinearViscous
    force_scale = ("c",)
    analytic = True

    def default_bounds(self, data: FitData, start: Mapping[str, float]) -> Bounds:
        return {"c": (0.0, 10.0 * data.max_force / max(data.max_velocity, 1e-3))}

    def jacobian(
        self,
        values: Mapping[str, float],
        free: Sequence[str],
        data: FitData,
        weight: FloatArray | None = None,
    ) -> FloatArray:
        out = data.velocity[:, None].copy()
        return out if weight is None else out * weight[:, None]


class SpencerFit(FitModel):
    """Spencer et al. (1997) modified Bouc-Wen: stateful, run over repeated cycles.

    Each loop is repeated ``cycles`` times (default 3) as a periodic record and the
    model's causal :meth:`~DamperModel.response` is run over it, ``substeps`` samples
    per loop point (default 1; linear interpolation in between); the last cycle is
    compared. The model's slow mode ``k0 / (c0 + c1)`` (a time constant of seconds)
    makes the force offset depend on the run length: fit such data with the offsets
    removed. The Jacobian is by finite differences (slow: fit few tests, or few
    parameters). ``n`` (Bouc-Wen exponent) and ``volts_per_amp`` are held fixed.
    """

    damper: ClassVar[type[DamperModel]] = SpencerBoucWen
    force_scale = ("c0a", "c0b", "k0", "c1a", "c1b", "k1", "alpha_a", "alpha_b")
    default_fixed = ("n", "volts_per_amp")
    option_names = ("cycles", "substeps")

    default_max_nfev: ClassVar[int | None] = 40

    def construct(self, parameters: _parameters.ParameterSet, max_current: float) -> DamperModel:
        return self.damper(parameters, max_current=max_current)  # `cycles` is a fit option

    def forces(self, model: DamperModel, data: FitData) -> FloatArray:
        reps = int(self.options.get("cycles", 3))
        sub = int(self.options.get("substeps", 1))
        if reps < 1 or sub < 1:
            raise ValidationError(f"cycles and substeps must be >= 1; got {reps}, {sub}")
        out = np.empty(data.force.size)
        for loop, sl in zip(data.loops, data.slices, strict=True):
            n = loop.force.size
            m = n * sub
            dt = 1.0 / (loop.frequency * m)
            phase = np.arange(m) / sub  # in loop points

            def periodic(y: FloatArray, phase: FloatArray = phase, n: int = n) -> FloatArray:
                return np.tile(np.interp(phase, np.arange(n + 1), np.append(y, y[0])), reps)

            r = model.response(
                dt * np.arange(reps * m),
                periodic(loop.stroke),
                periodic(loop.velocity),
                periodic(loop.acceleration),
                periodic(loop.current),
            )
            out[sl] = r.force[-m::sub]
        return out

    def default_bounds(self, data: FitData, start: Mapping[str, float]) -> Bounds:
        b: Bounds = {}
        for key, value in start.items():
            rule = self.damper.parameter_rules[key]
            if key == "x0":
                b[key] = (-1.0, 1.0)  # m
            elif value > 0:
                b[key] = (value / 100.0, value * 100.0)
            elif rule == "any":
                b[key] = (-100.0 * abs(value) - 1.0, 100.0 * abs(value) + 1.0)
            else:
                b[key] = (0.0, 1.0)
        return b


#: Fit descriptions by damper model name.
FIT_MODELS: dict[str, type[FitModel]] = {
    "wang-symmetric": WangFit,
    "wang-asymmetric": WangAsymmetricFit,
    "bingham": BinghamFit,
    "spencer": SpencerFit,
    "linear": LinearFit,
}


def fit_model(name: str, options: Mapping[str, Any] | None = None) -> FitModel:
    """The fit description of a model by name (did-you-mean on a typo)."""
    if name not in FIT_MODELS:
        raise unknown_name("damper model", name, FIT_MODELS)
    return FIT_MODELS[name](options)
