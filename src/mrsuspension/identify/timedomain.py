"""Time-domain identification: integrate a model with internal states over any record.

Rigs (and much public MR-damper data) drive the damper with band-limited random
displacement and switch the coil at random: there are no cycles to cut, and models with
internal states (Spencer's Bouc-Wen variable, the coil's first-order lag, the
dissertation's running peak-velocity estimate) must be integrated over the record.
:func:`fit_time_domain` does that with the compiled damper kernels of
:mod:`mrsuspension.dampers.kernels` (the same physics the simulator runs), in a bounded
``scipy.optimize.least_squares`` over the first part of the record, and reports NRMSE,
RMS and R^2 on the training and the validation segments (the last 30 % by default).

Models (:data:`TIME_DOMAIN_MODELS`, one :class:`TimeDomainModel` subclass each; register
another model with internal states by adding a subclass):

``spencer``
    Spencer et al. (1997) modified Bouc-Wen with its first-order coil lag
    ``u' = -eta (u - v)`` (``eta`` is a parameter of the simulator's model). Driven by
    voltage. Unidentifiable directions are fixed or merged (see :class:`SpencerLag`).
``bingham``
    Bingham with current-linear coefficients, driven by the lagged current
    ``i_f' = -eta (i_f - i)``.
``wang``
    The dissertation's symmetric model (2.15), with the lagged current and the
    ``cycle-rms`` running peak-velocity estimate (model reference, section 2.4).

Examples
--------
>>> rec = synthetic_record(duration=2.0, noise=0.0, seed=1)
>>> res = fit_time_domain(rec, "bingham", starts=1, max_nfev=5)
>>> sorted(res.metrics)
['train', 'validation']
>>> bool(res.metrics["validation"].r2 > 0.8)
True
"""

from __future__ import annotations

import json
import math
import time as _time
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar, Literal

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension import parameters as _parameters
from mrsuspension._numba_cache import invalidate_if_changed
from mrsuspension.dampers import kernels as K
from mrsuspension.dampers.base import DamperModel
from mrsuspension.dampers.peers import Bingham, SpencerBoucWen
from mrsuspension.dampers.wang import CHARACTERISATION_VH, WangSymmetric
from mrsuspension.errors import ValidationError, check_range, unknown_name
from mrsuspension.identify.record import TimeRecord

__all__ = [
    "TIME_DOMAIN_MODELS",
    "BinghamLag",
    "SegmentMetrics",
    "SpencerLag",
    "TimeDomainModel",
    "TimeDomainResult",
    "WangLag",
    "fit_time_domain",
    "segment_metrics",
    "simulate_record",
    "synthetic_record",
    "time_domain_model",
]

FloatArray = npt.NDArray[np.float64]
Bounds = dict[str, tuple[float, float]]

# _record_series inlines the damper kernels: drop its compiled cache when they change
invalidate_if_changed(__file__, K.__file__)

#: Default share of the record (its end) kept for validation.
VALIDATION_FRACTION = 0.3


# ----------------------------------------------------------------------------------
# compiled integration over a record
@njit(cache=True, **K.NO_REFCOUNT)
def _record_series(
    kind: int,
    p: np.ndarray,
    s: np.ndarray,
    ek: int,
    ep: np.ndarray,
    es: np.ndarray,
    lag_rate: float,
    x: np.ndarray,
    v: np.ndarray,
    a: np.ndarray,
    i: np.ndarray,
    dt: float,
    substeps: int,
    force: np.ndarray,
) -> None:
    """Causal response over a record, as ``kernels.damper_series`` with three changes.

    ``lag_rate`` > 0 passes the input through a first-order lag (exact for an input held
    over each step) for models without their own coil filter; ``substeps`` splits the
    internal-state integration of each step (Spencer's RK4) into equal parts, so that the
    step count does not depend on the parameters (finite-difference Jacobians stay
    smooth); and the internal states advance with the motion's secant velocity
    ``(x[k+1] - x[k]) / dt`` (the force still uses the sampled ``v[k]``), so the
    integrated stroke meets the record at every sample. With the velocity held over the
    step instead, as a simulation step does, Spencer's force on a 3 kHz, 0-50 Hz record
    differs from ``solve_ivp``'s by 1.0 % of its range; with the secant, by 0.1 %
    (``benchmarks/bench_identify_time.py``).
    """
    n = x.shape[0]
    decay = 1.0 - math.exp(-lag_rate * dt) if lag_rate > 0.0 else 1.0
    u = i[0]
    h = dt / substeps
    for k in range(n):
        uk = u if lag_rate > 0.0 else i[k]
        K.damper_sample(kind, p, s, ek, ep, es, x[k], v[k], a[k], uk)
        force[k] = K.damper_force(kind, p, s, x[k], v[k], uk)
        vs = (x[k + 1] - x[k]) / dt if k + 1 < n else v[k]
        for j in range(substeps):
            K.damper_advance(kind, p, s, x[k] + vs * (j * h), vs, i[k], h)
        u += decay * (i[k] - u)


def simulate_record(
    damper: DamperModel,
    record: TimeRecord,
    current: FloatArray,
    *,
    lag_rate: float = 0.0,
    substeps: int = 1,
    stop: int | None = None,
) -> FloatArray:
    """Force of ``damper`` integrated over ``record`` driven by ``current`` [A].

    Parameters
    ----------
    damper : DamperModel
        Any damper model (its compiled kernel is run).
    record : TimeRecord
        Motion (stroke, velocity, acceleration) and sampling period.
    current : ndarray
        Drive current [A] per sample (Spencer's model maps it to voltage itself).
    lag_rate : float
        Rate [1/s] of a first-order lag on the current (0: none).
    substeps : int
        Internal-state sub-steps per sample (see :func:`_record_series`).
    stop : int, optional
        Simulate samples ``0:stop`` only.

    Examples
    --------
    >>> from mrsuspension.dampers import Bingham
    >>> rec = synthetic_record(duration=0.5, noise=0.0)
    >>> f = simulate_record(Bingham(), rec, rec.coil_current(), lag_rate=100.0)
    >>> f.shape == rec.time.shape
    True
    """
    n = len(record) if stop is None else int(stop)
    kern = damper.kernel(record.dt)
    force = np.empty(n)
    _record_series(
        kern.kind, kern.params, kern.state, kern.estimator_code, kern.estimator_params,
        kern.estimator_state, float(lag_rate), record.displacement[:n], record.velocity[:n],
        record.acceleration[:n], np.ascontiguousarray(current[:n], dtype=float), record.dt,
        int(substeps), force,
    )  # fmt: skip
    return force


# ----------------------------------------------------------------------------------
# metrics
@dataclass(frozen=True)
class SegmentMetrics:
    """Agreement of model and measured force over one segment of a record.

    ``nrmse`` is the RMS error over the segment's measured force range (as for periodic
    fits), ``rms`` the RMS error [N], ``r2`` the coefficient of determination.
    """

    start: float
    stop: float
    samples: int
    nrmse: float
    rms: float
    r2: float
    force_range: float

    def to_dict(self) -> dict[str, float]:
        """Plain data."""
        return {
            "start_s": self.start, "stop_s": self.stop, "samples": self.samples,
            "nrmse": self.nrmse, "rms_N": self.rms, "r2": self.r2,
            "force_range_N": self.force_range,
        }  # fmt: skip


def segment_metrics(time: FloatArray, measured: FloatArray, model: FloatArray) -> SegmentMetrics:
    """NRMSE, RMS and R^2 of ``model`` against ``measured``.

    Examples
    --------
    >>> import numpy as np
    >>> m = segment_metrics(np.arange(4.0), np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 1.0, 2.0, 4.0]))
    >>> round(m.nrmse, 4), m.rms, round(m.r2, 3)
    (0.1667, 0.5, 0.8)
    """
    err = model - measured
    rng = float(np.ptp(measured))
    rms = float(np.sqrt(np.mean(err * err)))
    dev = measured - measured.mean()
    sst = float(dev @ dev)
    return SegmentMetrics(
        start=float(time[0]),
        stop=float(time[-1]),
        samples=int(measured.size),
        nrmse=rms / rng if rng > 0 else math.inf,
        rms=rms,
        r2=1.0 - float(err @ err) / sst if sst > 0 else math.nan,
        force_range=rng,
    )


# ----------------------------------------------------------------------------------
# models
class TimeDomainModel(ABC):
    """A damper model fitted over a record: parameters, bounds, start, simulation.

    Subclasses name the simulator's damper class (whose compiled kernel is integrated),
    its published start set, the input it is driven by, which parameters are fitted and
    which are fixed (with the reason, reported as a note). The fit works in *fit
    coordinates* (``fit_names``), which may merge unidentifiable parameters (Spencer's
    ``f0 = k1 x0``); :meth:`to_values` maps them back to the damper's parameters plus
    ``eta``.
    """

    name: ClassVar[str]
    damper: ClassVar[type[DamperModel]]
    #: keyword arguments of ``damper`` besides the parameter set (e.g. its estimator)
    damper_options: ClassVar[Mapping[str, Any]] = {}
    default_set: ClassVar[str]
    #: "voltage" (Spencer's published damper) or "current"
    driven_by: ClassVar[Literal["current", "voltage"]] = "current"
    #: the coil lag rate [1/s] used when the start set has none (Spencer et al. 1997)
    default_eta: ClassVar[float] = 190.0

    def __init__(self, start: Any = None, *, free: Sequence[str] | None = None) -> None:
        self.start_set = _parameters.resolve(
            start if start is not None else self.default_set, model=self.damper.name
        )
        self.fixed_notes: dict[str, str] = {}
        names = self.fit_names()
        if free is not None:
            for key in free:
                if key not in self.all_fit_names():
                    raise unknown_name(
                        f"parameter of {self.name!r} to free", key, self.all_fit_names()
                    )
            names = tuple(dict.fromkeys([*names, *free]))
        self.free = names

    # -- what is fitted ----------------------------------------------------------------
    @abstractmethod
    def fit_names(self) -> tuple[str, ...]:
        """Parameters fitted by default (fit coordinates); fills ``fixed_notes``."""

    def all_fit_names(self) -> tuple[str, ...]:
        """Every fit coordinate (those that ``free=`` may add)."""
        return self.fit_names()

    @abstractmethod
    def start_values(self, record: TimeRecord, current: FloatArray) -> dict[str, float]:
        """Start point in fit coordinates, adapted to the record's force level."""

    @abstractmethod
    def bounds(self, start: Mapping[str, float], record: TimeRecord) -> Bounds:
        """Box bounds of the fit coordinates."""

    @abstractmethod
    def to_values(self, fit: Mapping[str, float]) -> dict[str, float]:
        """Damper parameters (and ``eta``) from fit coordinates."""

    # -- simulation --------------------------------------------------------------------
    def input_current(self, record: TimeRecord, gain: float | None) -> FloatArray:
        """The record's coil input as the kernel's current [A]."""
        return record.coil_current(f"model {self.name!r}")

    def build(self, values: Mapping[str, float], max_current: float) -> DamperModel:
        """The simulator's damper with these parameters (``eta`` removed if not its own)."""
        vals = {k: v for k, v in values.items() if k in self.damper.parameter_rules}
        pset = _parameters.ParameterSet(
            name=f"{self.name}-fit", model=self.damper.name, values=vals,
            max_current=max(self.start_set.max_current, max_current),
            velocity_range=self.start_set.velocity_range,
        )  # fmt: skip
        return self.damper(pset, **self.damper_options)

    def lag_rate(self, values: Mapping[str, float]) -> float:
        """Rate of the current lag applied outside the kernel (0: the kernel has it)."""
        return 0.0 if "eta" in self.damper.parameter_rules else float(values["eta"])

    def substeps(
        self, values: Mapping[str, float], record: TimeRecord, current: FloatArray | None = None
    ) -> int:
        """Internal-state sub-steps per sample (1 for models without fast states)."""
        return 1

    def force(
        self,
        values: Mapping[str, float],
        record: TimeRecord,
        current: FloatArray,
        substeps: int,
        stop: int | None = None,
    ) -> FloatArray:
        """Model force over the record (samples ``0:stop``)."""
        damper = self.build(values, float(np.max(current, initial=0.0)))
        return simulate_record(
            damper, record, current, lag_rate=self.lag_rate(values), substeps=substeps, stop=stop
        )

    def parameter_set(
        self, values: Mapping[str, float], name: str, source: str, max_current: float
    ) -> tuple[_parameters.ParameterSet, list[str]]:
        """The fitted set in the simulator's format, and notes on what it cannot hold."""
        damper = self.build(values, max_current)
        keep = dict(damper.values)
        notes = []
        if "eta" not in keep and "eta" in values:
            notes.append(
                f"the simulator's {self.damper.name!r} model has no coil lag: the fitted "
                f"eta = {values['eta']:.4g} 1/s is reported in the JSON, not in the set"
            )
        base = self.start_set
        return (
            _parameters.ParameterSet(
                name=name, model=self.damper.name, values=keep,
                units={k: base.units.get(k, "") for k in keep},
                descriptions={k: base.descriptions.get(k, "") for k in keep},
                source=source, table="-",
                description=f"time-domain fit of {self.name!r} (start: {base.name})",
                max_current=max(base.max_current, max_current),
                velocity_range=base.velocity_range,
            ),
            notes,
        )  # fmt: skip


def _scale_to(measured: FloatArray, model: FloatArray) -> tuple[float, float]:
    """Least-squares ``measured ~ s model + c``: (s, c)."""
    m = model - model.mean()
    den = float(m @ m)
    s = float(m @ (measured - measured.mean())) / den if den > 0 else 1.0
    return (s if s > 0 else 1.0), float(measured.mean() - s * model.mean())


class SpencerLag(TimeDomainModel):
    """Spencer et al. (1997) modified Bouc-Wen with the first-order coil lag ``eta``.

    Driven by the command voltage ``v`` (a current record goes through the set's
    ``volts_per_amp``; a voltage record with a driver gain saves ``volts_per_amp = 1 /
    gain``). Fitted: ``c0a c0b k0 c1a c1b k1 alpha_a alpha_b gamma beta eta f0``.
    Unidentifiable directions, fixed or merged and reported:

    * ``A``: ``(alpha, A, gamma, beta) -> (s alpha, A/s, s^(n-1) gamma, s^(n-1) beta)``
      leaves the force unchanged (z rescales by 1/s), so ``A`` is held at the start set's
      value (301) and the others are identified relative to it;
    * ``x0``: the force holds ``k1 (x - x0) = k1 x - f0``; only the offset ``f0 = k1 x0``
      is identifiable, so it is fitted and ``x0 = f0 / k1`` is derived for the set;
    * ``n``: the sharpness of the loop's corners; random motion hardly identifies it, so
      it is held at the start set's value (2) unless freed (``free=["n"]``).
    """

    name: ClassVar[str] = "spencer"
    damper: ClassVar[type[DamperModel]] = SpencerBoucWen
    default_set: ClassVar[str] = "spencer-1997"
    driven_by: ClassVar[Literal["current", "voltage"]] = "voltage"
    _FORCE_SCALED = ("c0a", "c0b", "k0", "c1a", "c1b", "k1", "alpha_a", "alpha_b")
    _FITTED = (*_FORCE_SCALED, "gamma", "beta", "eta", "f0")

    def fit_names(self) -> tuple[str, ...]:
        q = self.start_set.values
        self.fixed_notes = {
            "A": f"held at {q['A']:g}: it rescales alpha, gamma, beta with z (no effect on "
            "the force), so the others are identified relative to it",
            "x0": "only f0 = k1 x0 (a force offset) is identifiable; x0 = f0 / k1 is derived",
            "n": f"held at {q['n']:g}: random motion hardly identifies the loop's corner "
            "sharpness (free it: --free n, free=['n'])",
            "volts_per_amp": "the current-to-voltage map, not a damper property",
        }
        return self._FITTED

    def all_fit_names(self) -> tuple[str, ...]:
        return (*self._FITTED, "n")

    def __init__(
        self, start: Any = None, *, free: Sequence[str] | None = None, gain: float | None = None
    ) -> None:
        super().__init__(start, free=free)
        if "n" in self.free:
            self.fixed_notes.pop("n", None)
        vpa = self.start_set.values["volts_per_amp"]
        self.volts_per_amp = float(vpa if gain is None else 1.0 / gain)
        if gain is not None:
            self.fixed_notes["volts_per_amp"] = (
                f"1 / gain = {self.volts_per_amp:.6g} V/A (the record's driver gain)"
            )

    def input_current(self, record: TimeRecord, gain: float | None) -> FloatArray:
        # the kernel multiplies the current by volts_per_amp: feed voltage / volts_per_amp
        return record.coil_voltage(self.volts_per_amp) / self.volts_per_amp

    def to_values(self, fit: Mapping[str, float]) -> dict[str, float]:
        out = dict(self.start_set.values)
        out.pop("max_voltage", None)
        out.update({k: v for k, v in fit.items() if k != "f0"})
        out["x0"] = fit["f0"] / out["k1"]
        out["volts_per_amp"] = self.volts_per_amp
        return out

    def start_values(self, record: TimeRecord, current: FloatArray) -> dict[str, float]:
        q = dict(self.start_set.values)
        fit = {k: float(q[k]) for k in self.free if k != "f0"}
        fit["f0"] = q["k1"] * q["x0"]
        # the model is homogeneous of degree 1 in the force-scaled parameters: match the
        # record's force level first (a published set of another damper is far off)
        n = min(len(record), 3 * round(1.0 / record.dt))
        vals = self.to_values(fit)
        f = self.force(vals, record, current, 2, stop=n)
        s, c = _scale_to(record.force[:n], f)
        for k in self._FORCE_SCALED:
            fit[k] *= s
        fit["f0"] = s * fit["f0"] - c
        return fit

    def bounds(self, start: Mapping[str, float], record: TimeRecord) -> Bounds:
        fmax = float(np.max(np.abs(record.force)))
        b: Bounds = {}
        for k, v in start.items():
            if k == "f0":
                b[k] = (-2.0 * fmax, 2.0 * fmax)
            elif k == "beta":
                b[k] = (-30.0 * abs(v) - 1.0, 30.0 * abs(v) + 1.0)
            elif k == "n":
                b[k] = (1.0, 4.0)
            elif k in ("c0b", "c1b", "alpha_b", "gamma"):
                b[k] = (0.0, 30.0 * abs(v) + 1.0)
            else:
                b[k] = (abs(v) / 30.0, 30.0 * abs(v))
        return b

    #: integration accuracy asked of the sub-steps: RMS change on doubling them, as a
    #: share of the force range (2 % force noise is ~0.4 % of the range: 100x below it)
    SUBSTEP_TOLERANCE: ClassVar[float] = 1e-4

    def substeps(
        self, values: Mapping[str, float], record: TimeRecord, current: FloatArray | None = None
    ) -> int:
        """Sub-steps per sample: the fewest whose doubling changes the force (first 3 s,
        start values) by less than :attr:`SUBSTEP_TOLERANCE` of its range.

        The kernel sizes its RK4 steps for stability (``h rate <= 1.5``), which at 3 kHz
        leaves an error of ~0.4 % of the force range on a 0-50 Hz record; two parts per
        sample bring it to ~3e-5. A fixed count also keeps the step count independent
        of the parameters, so finite-difference Jacobians stay smooth.
        """
        cur = self.input_current(record, record.gain) if current is None else current
        n = min(len(record), 3 * round(1.0 / record.dt))
        m = 1
        f = self.force(values, record, cur, m, stop=n)
        rng = max(float(np.ptp(f)), 1e-12)
        while m < 32:
            g = self.force(values, record, cur, 2 * m, stop=n)
            if float(np.sqrt(np.mean((g - f) ** 2))) < self.SUBSTEP_TOLERANCE * rng:
                break
            m, f = 2 * m, g
        return m


class BinghamLag(TimeDomainModel):
    """Bingham with current-linear coefficients driven by the lagged current.

    ``F = (fc_a + fc_b i_f) sgn(v) + (c0_a + c0_b i_f) v + f0``, ``i_f' = -eta (i_f - i)``.
    The start is the linear least-squares solution at the start set's ``eta`` (190 1/s,
    Spencer et al.'s coil filter); ``fc_b`` and ``c0_b`` are kept >= 0 (force rising with
    current), which the simulator's model requires over its current range anyway.
    """

    name: ClassVar[str] = "bingham"
    damper: ClassVar[type[DamperModel]] = Bingham
    default_set: ClassVar[str] = "bingham-wang-low"

    def fit_names(self) -> tuple[str, ...]:
        self.fixed_notes = {}
        return ("fc_a", "fc_b", "c0_a", "c0_b", "f0", "eta")

    def to_values(self, fit: Mapping[str, float]) -> dict[str, float]:
        out = {k: float(v) for k, v in self.start_set.values.items()}
        out.setdefault("eta", self.default_eta)
        out.update(fit)
        return out

    def start_values(self, record: TimeRecord, current: FloatArray) -> dict[str, float]:
        from scipy.optimize import lsq_linear

        eta = float(self.start_set.values.get("eta", self.default_eta))
        decay = 1.0 - math.exp(-eta * record.dt)
        filt = np.empty_like(current)
        u = current[0]
        for k in range(current.size):  # numpy-free recursion is fine: once per fit
            filt[k] = u
            u += decay * (current[k] - u)
        v = record.velocity
        sg = np.sign(v)
        basis = np.column_stack([sg, sg * filt, v, v * filt, np.ones_like(v)])
        res = lsq_linear(
            basis, record.force, bounds=([0, 0, 0, 0, -np.inf], [np.inf] * 5), method="bvls"
        )
        fca, fcb, c0a, c0b, f0 = (float(c) for c in res.x)
        return {"fc_a": fca, "fc_b": fcb, "c0_a": c0a, "c0_b": c0b, "f0": f0, "eta": eta}

    def bounds(self, start: Mapping[str, float], record: TimeRecord) -> Bounds:
        fmax = float(np.max(np.abs(record.force)))
        imax = max(float(np.max(np.abs(self.input_current(record, None)))), 1e-6)
        vmax = max(float(np.max(np.abs(record.velocity))), 1e-6)
        return {
            "fc_a": (0.0, 2 * fmax), "fc_b": (0.0, 4 * fmax / imax),
            "c0_a": (0.0, 4 * fmax / vmax), "c0_b": (0.0, 8 * fmax / (vmax * imax)),
            "f0": (-fmax, fmax), "eta": (1.0, 5000.0),
        }  # fmt: skip


class WangLag(TimeDomainModel):
    """The dissertation's symmetric model (2.15) with the lagged current and ``cycle-rms``.

    The peak velocity ``v_m`` is the running ``sqrt(2 mean(v^2))`` over the last second
    (model reference, section 2.4), clamped to the start set's velocity range; ``sgn(a_d)`` comes
    from the record's derived acceleration. All 13 parameters of Table 2.2 and ``eta`` are
    fitted; ``F0`` (and the current gain) are first scaled to the record's force level.
    """

    name: ClassVar[str] = "wang"
    damper: ClassVar[type[DamperModel]] = WangSymmetric
    damper_options: ClassVar[Mapping[str, Any]] = {
        "estimator": "cycle-rms",
        "vh_variant": CHARACTERISATION_VH,  # all 13 identified parameters
    }
    default_set: ClassVar[str] = "wang-symmetric-low"
    _NAMES = ("a0", "a1", "a2", "a3", "a4", "I0", "I1", "k0", "k1", "k2", "k3", "k4", "F0")

    def fit_names(self) -> tuple[str, ...]:
        self.fixed_notes = {}
        return (*self._NAMES, "eta")

    def to_values(self, fit: Mapping[str, float]) -> dict[str, float]:
        out = {k: float(v) for k, v in self.start_set.values.items()}
        out.setdefault("eta", self.default_eta)
        out.update(fit)
        return out

    def start_values(self, record: TimeRecord, current: FloatArray) -> dict[str, float]:
        fit = {k: v for k, v in self.to_values({}).items() if k in self.free}
        n = min(len(record), 3 * round(1.0 / record.dt))
        f = self.force(self.to_values(fit), record, current, 1, stop=n)
        s, _ = _scale_to(record.force[:n], f)
        fit["F0"] *= s
        return fit

    def bounds(self, start: Mapping[str, float], record: TimeRecord) -> Bounds:
        rules = self.damper.parameter_rules
        b: Bounds = {}
        for k, v in start.items():
            if k == "eta":
                b[k] = (1.0, 5000.0)
            elif rules.get(k) == "any":
                b[k] = (-10.0 * abs(v) - 1.0, 10.0 * abs(v) + 1.0)
            elif rules.get(k) == "positive":
                b[k] = (abs(v) / 30.0 if v else 1e-6, 30.0 * abs(v) + 1e-3)
            else:
                b[k] = (0.0, 30.0 * abs(v) + 1.0)
        return b


#: Time-domain models by name (add a :class:`TimeDomainModel` subclass to register one).
TIME_DOMAIN_MODELS: dict[str, type[TimeDomainModel]] = {
    "spencer": SpencerLag,
    "bingham": BinghamLag,
    "wang": WangLag,
}


def time_domain_model(
    name: str | TimeDomainModel, start: Any = None, **options: Any
) -> TimeDomainModel:
    """A time-domain model by name (did-you-mean on a typo).

    Examples
    --------
    >>> time_domain_model("spencer").free[-2:]
    ('eta', 'f0')
    """
    if isinstance(name, TimeDomainModel):
        return name
    if name not in TIME_DOMAIN_MODELS:
        raise unknown_name("time-domain model", str(name), TIME_DOMAIN_MODELS)
    cls = TIME_DOMAIN_MODELS[name]
    if cls is not SpencerLag:
        options.pop("gain", None)
    return cls(start, **options)


# ----------------------------------------------------------------------------------
# the result
@dataclass
class TimeDomainResult:
    """Outcome of :func:`fit_time_domain`.

    Attributes
    ----------
    model : str
        Time-domain model name.
    parameters : dict
        Fitted values in the damper's parameter names, plus ``eta`` (and ``f0`` for
        Spencer's offset).
    parameter_set : ParameterSet
        The set in the simulator's format (loadable by the damper class).
    metrics : dict
        ``"train"`` and ``"validation"`` :class:`SegmentMetrics`.
    start_metrics : dict
        The same for the start point (e.g. the published set, scaled).
    fit_seconds : float
        Wall time of the fit (start search and polish) [s].
    fixed : dict
        Parameters held fixed or merged, with the reason.
    notes : list of str
        What the reader and the fit did.
    record : TimeRecord
        The record fitted.
    model_force : ndarray
        Model force over the whole record [N].
    split : int
        Index of the first validation sample.
    """

    model: str
    parameters: dict[str, float]
    parameter_set: _parameters.ParameterSet
    metrics: dict[str, SegmentMetrics]
    start_metrics: dict[str, SegmentMetrics]
    fit_seconds: float
    fixed: dict[str, str]
    notes: list[str]
    record: TimeRecord
    model_force: FloatArray
    split: int
    evaluations: int = 0
    starts: list[dict[str, float]] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """Plain data (the ``--json`` output)."""
        return {
            "model": self.model,
            "record": self.record.source,
            "samples": len(self.record),
            "sample_rate_Hz": self.record.sample_rate,
            "parameters": dict(self.parameters),
            "parameter_set": self.parameter_set.to_dict(),
            "train_nrmse": self.metrics["train"].nrmse,
            "validation_nrmse": self.metrics["validation"].nrmse,
            "train_r2": self.metrics["train"].r2,
            "validation_r2": self.metrics["validation"].r2,
            "train_rms_N": self.metrics["train"].rms,
            "validation_rms_N": self.metrics["validation"].rms,
            "start_train_nrmse": self.start_metrics["train"].nrmse,
            "start_validation_nrmse": self.start_metrics["validation"].nrmse,
            "metrics": {k: m.to_dict() for k, m in self.metrics.items()},
            "fit_seconds": self.fit_seconds,
            "evaluations": self.evaluations,
            "fixed": dict(self.fixed),
            "notes": list(self.notes),
            "starts": self.starts,
        }

    def summary_text(self) -> str:
        """A few lines for the terminal."""
        m, s = self.metrics, self.start_metrics
        lines = [
            f"time-domain fit of {self.model!r} to {Path(self.record.source).name}: "
            f"{len(self.record)} samples at {self.record.sample_rate:g} Hz, "
            f"validation from t = {self.record.time[self.split]:.4g} s",
            f"  NRMSE train {100 * m['train'].nrmse:.2f} %, validation "
            f"{100 * m['validation'].nrmse:.2f} % (R^2 {m['train'].r2:.4f} / "
            f"{m['validation'].r2:.4f}); start {100 * s['train'].nrmse:.2f} / "
            f"{100 * s['validation'].nrmse:.2f} %",
            f"  fit {self.fit_seconds:.1f} s ({self.evaluations} model runs)",
            "  parameters: " + ", ".join(f"{k}={v:.5g}" for k, v in self.parameters.items()),
        ]
        lines += [f"  fixed {k}: {why}" for k, why in self.fixed.items()]
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)

    def save(self, folder: str | Path, *, plots: bool = True) -> list[Path]:
        """Write ``parameters.toml`` (the simulator's format), ``result.json`` and plots.

        Plots (needs matplotlib): a time window of measured and model force, force
        against velocity, and the residual spectrum.
        """
        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        files = [self.parameter_set.save(out / "parameters.toml")]
        path = out / "result.json"
        path.write_text(json.dumps(self.to_dict(), indent=2) + "\n")
        files.append(path)
        if plots:
            files += _plots(self, out)
        return files


def _plots(result: TimeDomainResult, out: Path) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from scipy.signal import welch

    rec, f = result.record, result.model_force
    files = []
    # a window of the validation segment: 1 s or what there is
    k0 = result.split
    k1 = min(len(rec), k0 + round(1.0 / rec.dt))
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.plot(rec.time[k0:k1], rec.force[k0:k1], lw=0.8, label="measured")
    ax.plot(rec.time[k0:k1], f[k0:k1], lw=0.8, label=f"{result.model} (fitted)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("force [N]")
    ax.set_title("validation segment")
    ax.legend(loc="upper right")
    fig.tight_layout()
    files.append(out / "time_window.png")
    fig.savefig(files[-1], dpi=110)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot(rec.velocity[k0:], rec.force[k0:], ",", alpha=0.4, label="measured")
    ax.plot(rec.velocity[k0:], f[k0:], ",", alpha=0.4, label="model")
    ax.set_xlabel("velocity [m/s]")
    ax.set_ylabel("force [N]")
    ax.legend(loc="upper left", markerscale=20)
    fig.tight_layout()
    files.append(out / "force_velocity.png")
    fig.savefig(files[-1], dpi=110)
    plt.close(fig)
    fs = 1.0 / rec.dt
    freq, p_res = welch(f - rec.force, fs=fs, nperseg=min(4096, len(rec)))
    _, p_meas = welch(rec.force - rec.force.mean(), fs=fs, nperseg=min(4096, len(rec)))
    fig, ax = plt.subplots(figsize=(6, 3.5))
    ax.semilogy(freq, p_meas, lw=0.8, label="measured force")
    ax.semilogy(freq, p_res, lw=0.8, label="residual")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("PSD [N^2/Hz]")
    ax.legend(loc="upper right")
    fig.tight_layout()
    files.append(out / "residual_spectrum.png")
    fig.savefig(files[-1], dpi=110)
    plt.close(fig)
    return files


# ----------------------------------------------------------------------------------
# the fit
def _check_fit_memory(samples: int, free: int, dt: float) -> None:
    """Refuse, before the first evaluation, a fit whose finite-difference Jacobian
    (training samples x free parameters) and work arrays exceed the memory limit."""
    from mrsuspension.engine.settings import check_memory

    check_memory(
        samples * dt,
        float(samples) * (free + 8),
        subject=f"a time-domain fit of {samples} training samples with {free} free parameters",
        hint="fit a shorter stretch of the record or resample it to a lower rate",
    )


def fit_time_domain(
    record: TimeRecord,
    model: str | TimeDomainModel = "spencer",
    *,
    start: Any = None,
    validation_fraction: float = VALIDATION_FRACTION,
    free: Sequence[str] | None = None,
    starts: int = 3,
    seed: int = 0,
    max_nfev: int | None = None,
    name: str | None = None,
    progress: Callable[[str], None] | None = None,
) -> TimeDomainResult:
    """Fit a model with internal states to a time-domain record.

    The model is integrated over the training segment (the record's start) by its
    compiled kernel; a bounded ``least_squares`` (trust-region reflective,
    finite-difference Jacobian) minimises the force error normalised by the segment's
    force range. ``starts`` starts (the start set scaled to the record's force level,
    then random log-perturbations of it) each get a short run; the best is polished.

    Parameters
    ----------
    record : TimeRecord
        The record (see :func:`~mrsuspension.identify.record.read_record`).
    model : str or TimeDomainModel
        ``"spencer"``, ``"bingham"``, ``"wang"`` (:data:`TIME_DOMAIN_MODELS`).
    start : str, path or ParameterSet, optional
        Start set (default: the model's published set).
    validation_fraction : float
        Share of the record, at its end, kept for validation (0.3; 0 < f < 0.9).
    free : sequence of str, optional
        Parameters held fixed by default to fit anyway (Spencer: ``"n"``).
    starts : int
        Number of starts (1-20).
    seed : int
        Seed of the random starts.
    max_nfev : int, optional
        Budget of the polish run (function evaluations, Jacobians not counted; 60).
    name : str, optional
        Name of the fitted parameter set.
    progress : callable, optional
        Called with a short message at each stage.

    Returns
    -------
    TimeDomainResult

    Examples
    --------
    >>> rec = synthetic_record(duration=2.0, noise=0.02, seed=2)
    >>> res = fit_time_domain(rec, "spencer", starts=1, max_nfev=3)
    >>> res.parameter_set.model, "A" in res.fixed
    ('spencer', True)
    """
    from scipy.optimize import least_squares

    from mrsuspension.identify._threads import blas_threads

    frac = float(
        check_range("validation_fraction", validation_fraction, 0.0, 0.9, low_inclusive=False)
    )
    if not (isinstance(starts, int) and 1 <= starts <= 20):
        raise ValidationError(f"starts must be an integer in 1-20; got {starts!r}")
    if max_nfev is not None and not (isinstance(max_nfev, int) and 1 <= max_nfev <= 100_000):
        raise ValidationError(
            f"max_nfev must be an integer in [1, 100000] (one model integration each); "
            f"got {max_nfev!r}"
        )
    tdm = time_domain_model(model, start, free=free, gain=record.gain)
    say = progress or (lambda _msg: None)
    t_begin = _time.perf_counter()
    current = np.ascontiguousarray(tdm.input_current(record, record.gain))
    n = len(record)
    split = round(n * (1.0 - frac))
    if split < 64 or n - split < 64:
        raise ValidationError(
            f"validation_fraction {frac:g} leaves {split} training and {n - split} validation "
            "samples; each needs at least 64"
        )
    train = record.force[:split]
    scale_f = float(np.ptp(train)) * math.sqrt(split)
    if not scale_f > 0:
        raise ValidationError("the training segment's force is constant; nothing to fit")
    say("start point")
    start_fit = tdm.start_values(record, current)
    names = list(tdm.free)
    _check_fit_memory(split, len(names), record.dt)
    bounds = tdm.bounds(start_fit, record)
    lo = np.array([bounds[k][0] for k in names])
    hi = np.array([bounds[k][1] for k in names])
    x_start = np.clip(np.array([start_fit[k] for k in names]), lo, hi)
    scale = np.maximum(np.abs(x_start), 1e-3 * (hi - lo))
    scale = np.where(scale > 0, scale, 1.0)
    substeps = tdm.substeps(tdm.to_values(dict(zip(names, x_start, strict=True))), record, current)
    evaluations = 0

    def values(theta: FloatArray) -> dict[str, float]:
        return tdm.to_values(dict(zip(names, (theta * scale).tolist(), strict=True)))

    def residuals(theta: FloatArray) -> FloatArray:
        nonlocal evaluations
        evaluations += 1
        f = tdm.force(values(theta), record, current, substeps, stop=split)
        r = (f - train) / scale_f
        return np.where(np.isfinite(r), r, 1e3)

    lo_s, hi_s = lo / scale, hi / scale
    theta0 = x_start / scale
    rng = np.random.default_rng(seed)
    candidates = [theta0]
    for _ in range(starts - 1):
        # log-normal perturbations (factor e^0.5 = 1.6 typical) of the positive values
        pert = theta0 * np.exp(rng.normal(0.0, 0.5, theta0.size))
        pert = np.where(theta0 > 0, pert, theta0 + rng.normal(0.0, 0.5, theta0.size))
        candidates.append(np.clip(pert, lo_s, hi_s))
    opts: dict[str, Any] = {"jac": "2-point", "diff_step": 1e-6, "x_scale": 1.0,
                            "method": "trf", "bounds": (lo_s, hi_s)}  # fmt: skip
    record_starts: list[dict[str, float]] = []
    with blas_threads(1):
        best = None
        if starts > 1:
            for j, c in enumerate(candidates):
                say(f"start {j + 1}/{starts}")
                r = least_squares(residuals, c, max_nfev=6, **opts)
                record_starts.append({"start": j, "cost": float(r.cost), "nfev": int(r.nfev)})
                if best is None or r.cost < best.cost:
                    best = r
            theta_best = best.x if best is not None else theta0
        else:
            theta_best = theta0
        say("polish")
        res = least_squares(
            residuals, theta_best, max_nfev=60 if max_nfev is None else max_nfev,
            ftol=1e-10, xtol=1e-10, gtol=1e-10, **opts,
        )  # fmt: skip
    fitted = values(res.x)
    fit_seconds = _time.perf_counter() - t_begin
    say("metrics")
    full = tdm.force(fitted, record, current, substeps)
    start_force = tdm.force(values(theta0), record, current, substeps)
    t = record.time

    def segs(f: FloatArray) -> dict[str, SegmentMetrics]:
        return {
            "train": segment_metrics(t[:split], record.force[:split], f[:split]),
            "validation": segment_metrics(t[split:], record.force[split:], f[split:]),
        }

    fixed = dict(tdm.fixed_notes)
    notes = list(record.notes)
    at_bound = [k for k, x, a, b in zip(names, res.x, lo_s, hi_s, strict=True)
                if min(x - a, b - x) <= 1e-6 * (b - a)]  # fmt: skip
    if at_bound:
        notes.append(f"at a bound of the fit: {', '.join(at_bound)} (widen or fix them)")
    if not res.success:
        notes.append(f"the polish stopped at its budget ({res.nfev} evaluations): {res.message}")
    if substeps > 1:
        notes.append(f"{substeps} internal-state sub-steps per sample (stable RK4)")
    params = {k: v for k, v in fitted.items() if k != "max_voltage"}
    if "f0" in names:
        params["f0"] = float(res.x[names.index("f0")] * scale[names.index("f0")])
    imax = float(np.max(current, initial=0.0))
    pset, set_notes = tdm.parameter_set(
        fitted,
        name or f"{tdm.name}-time-domain-fit",
        f"time-domain fit to {Path(record.source).name} ({len(record)} samples, "
        f"{record.sample_rate:g} Hz, validation last {100 * frac:g} %)",
        imax,
    )
    notes += set_notes
    return TimeDomainResult(
        model=tdm.name,
        parameters=params,
        parameter_set=pset,
        metrics=segs(full),
        start_metrics=segs(start_force),
        fit_seconds=fit_seconds,
        fixed=fixed,
        notes=notes,
        record=record,
        model_force=full,
        split=split,
        evaluations=evaluations,
        starts=record_starts,
    )


# ----------------------------------------------------------------------------------
# a public-style synthetic record
def synthetic_record(
    duration: float = 20.0,
    sample_rate: float = 3000.0,
    *,
    parameters: Any = "spencer-1997",
    eta: float | None = 118.0,
    band: tuple[float, float] = (0.1, 50.0),
    stroke_rms: float = 0.001,
    levels: Sequence[float] = (0.0, 2.25),
    mean_hold: float = 0.2,
    noise: float = 0.02,
    seed: int = 0,
    substeps: int = 8,
) -> TimeRecord:
    """A rig-like random record through Spencer's model with its coil lag.

    Band-limited random displacement (flat spectrum over ``band`` [Hz], random phases,
    ``stroke_rms`` [m]; velocity exact), command voltage switched at random among
    ``levels`` [V] (exponential hold times, mean ``mean_hold`` [s]), force of the
    Spencer model (``parameters``, with ``eta`` [1/s] when given: 118 is what a careful
    fit of a public 3 kHz record found, against the published 190) integrated with
    ``substeps`` RK4 sub-steps per sample, plus Gaussian noise of ``noise`` times the
    force's standard deviation. The coil input is the voltage [V]; the driver gain is
    ``1 / volts_per_amp`` (0.222 A/V: 2.25 V -> 0.5 A).

    Examples
    --------
    >>> rec = synthetic_record(duration=1.0, seed=3)
    >>> len(rec), rec.coil_unit, sorted(set(rec.coil.tolist()))
    (3000, 'V', [0.0, 2.25])
    """
    duration = float(check_range("duration", duration, 0.1, 3600.0, unit="s"))
    fs = float(check_range("sample_rate", sample_rate, 100.0, 1e6, unit="Hz"))
    check_range("noise", noise, 0.0, 1.0)
    check_range("stroke_rms", stroke_rms, 1e-6, 0.5, unit="m")
    if not (0.0 <= band[0] < band[1] <= fs / 2):
        raise ValidationError(f"band must satisfy 0 <= low < high <= {fs / 2:g} Hz; got {band}")
    rng = np.random.default_rng(seed)
    n = round(duration * fs)
    t = np.arange(n) / fs
    freqs = np.fft.rfftfreq(n, 1.0 / fs)
    spec = np.where((freqs >= max(band[0], 1e-9)) & (freqs <= band[1]), 1.0, 0.0).astype(complex)
    spec *= np.exp(2j * np.pi * rng.random(freqs.size))
    x = np.fft.irfft(spec, n)
    v = np.fft.irfft(spec * (2j * np.pi * freqs), n)
    k = stroke_rms / float(np.std(x))
    x, v = x * k, v * k
    volts = np.empty(n)
    pos = 0
    while pos < n:
        hold = max(1, round(rng.exponential(mean_hold) * fs))
        volts[pos : pos + hold] = rng.choice(np.asarray(levels, dtype=float))
        pos += hold
    pset = _parameters.resolve(parameters, model="spencer")
    if eta is not None:
        pset = pset.replace(eta=float(eta))
    damper = SpencerBoucWen(pset)
    vpa = damper.values["volts_per_amp"]
    motion = TimeRecord(
        time=t, displacement=x, velocity=v, force=np.zeros(n), coil=volts, coil_unit="V",
        acceleration=np.gradient(v, 1.0 / fs), gain=1.0 / vpa, source="synthetic",
    )  # fmt: skip
    f = simulate_record(damper, motion, volts / vpa, substeps=substeps)
    if noise > 0:
        f = f + rng.normal(0.0, noise * float(np.std(f)), n)
    return TimeRecord.from_arrays(
        t, x, f, volts, velocity=v, coil_unit="V", gain=1.0 / vpa,
        source=f"synthetic-spencer-eta{pset['eta']:g}-seed{seed}",
        notes=(
            f"synthetic: {pset.name}, eta {pset['eta']:g} 1/s, {band[0]:g}-{band[1]:g} Hz "
            f"displacement ({stroke_rms * 1e3:g} mm rms), {len(levels)}-level random "
            f"switching, noise {100 * noise:g} % of the force std",
        ),
    )  # fmt: skip
