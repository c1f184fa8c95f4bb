"""Global least-squares fit of a damper model to many loops, eq. (2.22).

The dissertation minimised the summed squared force error over all points, currents and
frequencies with MATLAB's ``fminunc``. Here (model reference, section 10) every test is
normalised by its force range and its number of points, so the cost is the sum over
tests of NRMSE^2 and a 1 kN test counts as much as a 100 N one; the problem is solved
by :func:`scipy.optimize.least_squares` (trust-region reflective, with bounds) from
several starts, with analytic Jacobians for the memoryless models.

Examples
--------
>>> import numpy as np
>>> from mrsuspension.characterisation import harmonic_loop
>>> from mrsuspension.dampers import Bingham
>>> from mrsuspension.identify.preprocess import Loop
>>> def as_loop(h):
...     th = 2 * np.pi * np.arange(360) / 360
...     acc = -h.stroke * (2 * np.pi * h.condition.frequency) ** 2
...     return Loop("demo", h.time, h.stroke, h.velocity, acc, h.force, h.current,
...                 h.condition.frequency, h.condition.amplitude, h.peak_velocity)
>>> loops = [as_loop(harmonic_loop(Bingham(), 1.5, 0.0125, i)) for i in (0.0, 0.2, 0.4)]
>>> result = fit_loops(loops, "bingham", start={"fc_a": 50, "fc_b": 500, "c0_a": 1000,
...                                               "c0_b": 10000, "f0": 1.0})
>>> round(result.parameters["fc_b"], 1), bool(result.nrmse.max() < 1e-6)
(798.2, True)
"""

from __future__ import annotations

import datetime as _dt
import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension import parameters as _parameters
from mrsuspension.dampers import DamperModel
from mrsuspension.errors import MRSuspensionError, ValidationError, unknown_name
from mrsuspension.identify._threads import blas_threads
from mrsuspension.identify.models import FitData, FitModel, fit_model
from mrsuspension.identify.preprocess import Loop

__all__ = ["FitError", "FitProblem", "FitResult", "StartRecord", "fit_loops"]

FloatArray = npt.NDArray[np.float64]
BoundsSpec = Mapping[str, tuple[float, float]]
FixedSpec = Mapping[str, float | None] | Sequence[str]

JACOBIANS = ("analytic", "2-point", "3-point")
TRUST_SOLVERS = ("lsmr", "exact")


class FitError(MRSuspensionError):
    """The fit could not run (every start failed); the message says why."""


@dataclass(frozen=True)
class StartRecord:
    """Outcome of one start of the multi-start fit."""

    index: int
    rms_nrmse: float
    nfev: int
    status: int
    message: str
    origin: str = ""  # "start set" (the published/given set) or "sobol" (global stage)


@dataclass(frozen=True)
class FitResult:
    """A fitted model and how the fit went.

    ``parameters`` is a :class:`~mrsuspension.parameters.ParameterSet` the simulator
    loads (``make_damper(model, result.parameters)`` or ``.save("fit.toml")``);
    ``nrmse`` and ``model_forces`` are per fitted loop (``loops``); ``excluded`` names
    loops left out because the model force was not finite for them.
    """

    model: str
    parameters: _parameters.ParameterSet
    start: _parameters.ParameterSet
    free: tuple[str, ...]
    bounds: Mapping[str, tuple[float, float]]
    rms_nrmse: float
    nfev: int
    status: int
    converged: bool
    message: str
    starts: tuple[StartRecord, ...]
    seconds: float
    loops: tuple[Loop, ...]
    loop_index: tuple[int, ...]
    model_forces: tuple[FloatArray, ...]
    nrmse: FloatArray
    options: Mapping[str, Any] = field(default_factory=dict)
    at_bounds: tuple[str, ...] = ()
    excluded: Mapping[int, str] = field(default_factory=dict)
    jacobian: str = "analytic"
    starts_within: int = 1
    correlated: tuple[tuple[str, str, float], ...] = ()
    condition: float = math.nan

    @property
    def evidence(self) -> dict[str, Any]:
        """How trustworthy the optimum is: best of N starts, how many starts reached
        within 1 % of the best cost, parameters at bounds, strongly correlated pairs
        (|corr| > 0.98 from the Jacobian at the optimum) and the condition number of the
        column-scaled J^T J (above 1e10: near singular, some parameters not identifiable).
        """
        return {
            "starts": len(self.starts),
            "starts_within_1pct": self.starts_within,
            "best_start": min(self.starts, key=lambda r: r.rms_nrmse).index + 1
            if self.starts
            else None,
            "start_rms_nrmse": [r.rms_nrmse for r in self.starts],
            "at_bounds": list(self.at_bounds),
            "correlated": [[a, b, c] for a, b, c in self.correlated],
            "condition": self.condition,
        }

    def damper(self) -> DamperModel:
        """The fitted damper model (with the fit's model options)."""
        return fit_model(self.model, self.options).construct(
            self.parameters, self.parameters.max_current
        )


class FitProblem:
    """The weighted residuals of one model over a set of loops, and their Jacobian.

    Parameters
    ----------
    loops : sequence of Loop
        Pre-processed loops (:func:`~mrsuspension.identify.preprocess.preprocess`).
    model : str
        ``"wang-symmetric"``, ``"wang-asymmetric"``, ``"bingham"``, ``"spencer"`` or
        ``"linear"``.
    start : set name, path, ParameterSet or dict, optional
        Starting values (default: the model's published set); accepted sets of other
        families are converted as the model does (a symmetric set starts the
        asymmetric model).
    bounds : mapping, optional
        ``{name: (low, high)}`` overriding the default bounds.
    fixed : sequence of names or mapping, optional
        Parameters held fixed, at their start value or at a given value.
    model_options : mapping, optional
        Options of the model (``hysteresis``, ``vh_variant``, ``force_gain`` for the
        dissertation's models; ``cycles`` for Spencer's).
    """

    def __init__(
        self,
        loops: Sequence[Loop],
        model: str = "wang-symmetric",
        *,
        start: Any = None,
        bounds: BoundsSpec | None = None,
        fixed: FixedSpec | None = None,
        model_options: Mapping[str, Any] | None = None,
    ) -> None:
        self.spec: FitModel = fit_model(model, model_options)
        self.data = FitData.from_loops(loops)
        damper_cls = self.spec.damper
        start_set = _parameters.resolve(
            start if start is not None else damper_cls.default_parameters, model=damper_cls.name
        )
        self.max_current = float(min(10.0, max(start_set.max_current, self.data.max_current)))
        start_model = self.spec.construct(start_set, self.max_current)
        self.start_set = start_set
        self.start_values: dict[str, float] = dict(start_model.values)
        self.names = list(damper_cls.parameter_rules)
        self.notes: list[str] = []
        fixed_values: dict[str, float] = {}
        fixed_names = set(self.spec.default_fixed) | set(self.spec.fixed_by_options())
        if fixed is not None:
            items = fixed.items() if isinstance(fixed, Mapping) else ((n, None) for n in fixed)
            for key, value in items:
                if key not in self.names:
                    raise unknown_name(f"parameter of model {model!r} to fix", key, self.names)
                fixed_names.add(key)
                if value is not None:
                    fixed_values[key] = float(value)
        self.start_values.update(fixed_values)
        self.free = [n for n in self.names if n not in fixed_names]
        if not self.free:
            raise ValidationError(f"every parameter of model {model!r} is fixed; nothing to fit")
        b = self.spec.default_bounds(self.data, self.start_values)
        for key, pair in (bounds or {}).items():
            if key not in self.names:
                raise unknown_name(f"parameter of model {model!r} in bounds", key, self.names)
            try:
                lo, hi = (float(q) for q in pair)
            except (TypeError, ValueError):
                raise ValidationError(
                    f"bounds of {key!r} must be (low, high); got {pair!r}"
                ) from None
            if not lo < hi:
                raise ValidationError(f"bounds of {key!r} must have low < high; got {pair!r}")
            b[key] = (lo, hi)
        for key in self.free:
            lo, hi = b[key]
            value = self.start_values[key]
            if not lo <= value <= hi:
                pad = 0.1 * abs(value) + 1e-12
                b[key] = (min(lo, value - pad), max(hi, value + pad))
                self.notes.append(f"bounds of {key} widened to include its start value {value:g}")
        self.bounds = b
        self.lower = np.array([b[k][0] for k in self.free])
        self.upper = np.array([b[k][1] for k in self.free])
        self.x_start = np.array([self.start_values[k] for k in self.free])

    # -- evaluation -------------------------------------------------------------------
    def values(self, theta: npt.ArrayLike) -> dict[str, float]:
        """All parameter values with the free ones taken from ``theta``."""
        out = dict(self.start_values)
        out.update(zip(self.free, (float(q) for q in np.asarray(theta)), strict=True))
        return out

    def model_force(self, theta: npt.ArrayLike) -> FloatArray:
        """Model force over all points (NaN where the parameters are not accepted)."""
        with np.errstate(all="ignore"):
            try:
                damper = self.spec.build(self.values(theta), self.max_current)
                force = np.array(self.spec.forces(damper, self.data), dtype=float)
                return self.data.centre(force)
            except ValidationError:
                return np.full(self.data.force.size, np.nan)

    def residuals(self, theta: npt.ArrayLike) -> FloatArray:
        """Weighted residuals; their sum of squares is the sum over loops of NRMSE^2."""
        return (self.model_force(theta) - self.data.force) * self.data.weight

    def jacobian(self, theta: npt.ArrayLike) -> FloatArray:
        """Analytic Jacobian of :meth:`residuals` (for models that have one)."""
        with np.errstate(all="ignore"):
            jac = self.spec.jacobian(self.values(theta), self.free, self.data, self.data.weight)
        if jac is None:
            raise ValidationError(f"model {self.spec.name!r} has no analytic Jacobian")
        # the weight is constant over each loop, so centring after weighting is the same
        jac = self.data.centre(jac)
        if not np.isfinite(jac).all():
            jac[~np.isfinite(jac)] = 0.0
        return jac

    def nrmse(self, forces: FloatArray) -> FloatArray:
        """NRMSE of each loop for model forces over all points."""
        out = []
        for loop, sl in zip(self.data.loops, self.data.slices, strict=True):
            err = forces[sl] - loop.force
            out.append(math.sqrt(float(np.mean(err * err))) / loop.force_range)
        return np.array(out)

    # -- starts ---------------------------------------------------------------------------
    def _inside(self, theta: FloatArray) -> FloatArray:
        span = self.upper - self.lower
        return np.clip(theta, self.lower + 1e-9 * span, self.upper - 1e-9 * span)

    def scaled(self, theta: npt.ArrayLike) -> FloatArray:
        """``theta`` with its force-scale parameters scaled to match the measured forces.

        The force is proportional to these parameters together (``F0`` for the
        dissertation's models), so one linear least-squares factor brings a start set
        of another damper size to the campaign's force level.
        """
        theta = np.array(theta, dtype=float)
        idx = [self.free.index(k) for k in self.spec.force_scale if k in self.free]
        if not idx or len(idx) != len(self.spec.force_scale):
            return self._inside(theta)
        f = self.model_force(theta)
        w2 = self.data.weight**2
        if not np.all(np.isfinite(f)):
            return self._inside(theta)
        den = float(np.sum(w2 * f * f))
        s = float(np.sum(w2 * f * self.data.force)) / den if den > 0 else 1.0
        if math.isfinite(s) and s > 0:
            theta[idx] *= s
        return self._inside(theta)

    def _unit_to_theta(self, u: FloatArray) -> FloatArray:
        """Map points of the unit cube onto the bounds: log-uniform where the bounds are
        positive and span more than a decade (``a0`` in 1-1e5 s/m), uniform elsewhere."""
        lo, hi = self.lower, self.upper
        logs = (lo > 0) & (hi > 10 * lo)
        theta = lo + u * (hi - lo)
        if logs.any():
            llo, lhi = np.log(lo[logs]), np.log(hi[logs])
            theta[:, logs] = np.exp(llo + u[:, logs] * (lhi - llo))
        return theta

    def cost(self, theta: npt.ArrayLike) -> float:
        """Sum over loops of NRMSE^2 (inf where the model force is not finite)."""
        r = self.residuals(theta)
        c = float(r @ r)
        return c if math.isfinite(c) else math.inf

    def starts(self, count: int, seed: int = 0, *, screen: int | None = None) -> list[FloatArray]:
        """The scaled start set first, then the ``count - 1`` best of a global stage.

        The global stage draws ``screen`` points (default ``max(64, 16 count)``) of a
        scrambled Sobol sequence over the bounds (:meth:`_unit_to_theta`), brings each
        to the campaign's force level (:meth:`scaled`) and keeps the ``count - 1`` of
        lowest cost; the local polish (:meth:`solve`) starts from them. Starts from the
        whole box, not perturbations of the start set, so a campaign whose damper is
        far from the published one is still searched (issue 15).
        """
        out = [self.scaled(self.x_start)]
        if count <= 1:
            return out
        from scipy.stats import qmc

        n = int(screen) if screen is not None else max(64, 16 * count)
        m = max(1, math.ceil(math.log2(max(n, count))))
        u = qmc.Sobol(self.x_start.size, scramble=True, seed=seed).random_base2(m)[:n]
        cands = [self.scaled(theta) for theta in self._unit_to_theta(u)]
        costs = np.array([self.cost(c) for c in cands])
        order = np.argsort(costs, kind="stable")
        out.extend(cands[k] for k in order[: count - 1] if math.isfinite(costs[k]))
        return out

    def identifiability(
        self, theta: npt.ArrayLike, jac: FloatArray | None = None, threshold: float = 0.98
    ) -> tuple[tuple[tuple[str, str, float], ...], float]:
        """Correlated parameter pairs and the condition number at ``theta``.

        From the Jacobian of the residuals (columns scaled to unit norm), the
        correlation matrix of the Gauss-Newton covariance ``(J^T J)^-1`` gives the pairs
        with ``|corr| > threshold``; the condition number of the scaled ``J^T J`` above
        1e10 says the data cannot tell some parameters apart.
        """
        j = np.asarray(self.jacobian(theta) if jac is None else jac, dtype=float)
        norms = np.linalg.norm(j, axis=0)
        live = norms > 0
        if not live.any():
            return (), math.inf
        js = j[:, live] / norms[live]
        jtj = js.T @ js
        cond = float(np.linalg.cond(jtj)) if live.all() else math.inf
        cov = np.linalg.pinv(jtj)
        d = np.sqrt(np.clip(np.diag(cov), 1e-300, None))
        corr = cov / np.outer(d, d)
        names = [n for n, ok in zip(self.free, live, strict=True) if ok]
        pairs = []
        for a in range(len(names)):
            for b in range(a + 1, len(names)):
                if abs(corr[a, b]) > threshold:
                    pairs.append((names[a], names[b], float(round(corr[a, b], 4))))
        pairs.sort(key=lambda p: -abs(p[2]))
        return tuple(pairs), cond

    # -- solving --------------------------------------------------------------------------
    def solve(
        self,
        *,
        multistart: int | None = None,
        seed: int = 0,
        max_nfev: int | None = None,
        jacobian: str = "analytic",
        trust_solver: str = "lsmr",
        name: str | None = None,
        source: str | None = None,
        loop_index: Sequence[int] | None = None,
        excluded: Mapping[int, str] | None = None,
    ) -> FitResult:
        """Run the multi-start least-squares fit and package the best result.

        ``trust_solver="lsmr"`` (default) solves the trust-region subproblems with LSMR,
        which needs only products with the Jacobian; ``"exact"`` takes a dense SVD of the
        tall Jacobian every iteration, which multi-threaded LAPACK makes 10-50 times
        slower on a busy machine (measured on the 2-core CI box) for the same result.
        BLAS runs single-threaded during the fit
        (:func:`~mrsuspension.identify._threads.blas_threads`).
        """
        from scipy.optimize import least_squares

        if trust_solver not in TRUST_SOLVERS:
            raise ValidationError(
                f"trust_solver must be one of {', '.join(TRUST_SOLVERS)}; got {trust_solver!r}"
            )
        if jacobian not in JACOBIANS:
            raise ValidationError(
                f"jacobian must be one of {', '.join(JACOBIANS)}; got {jacobian!r}"
            )
        count = self.spec.default_starts if multistart is None else int(multistart)
        if count < 1:
            raise ValidationError(f"multistart must be >= 1; got {multistart!r}")
        budget = self.spec.default_max_nfev if max_nfev is None else int(max_nfev)
        jac: Any = (
            self.jacobian
            if (jacobian == "analytic" and self.spec.analytic)
            else ("2-point" if jacobian == "analytic" else jacobian)
        )
        t0 = time.perf_counter()
        records = []
        costs: list[float] = []
        best: Any = None
        failures = []
        n_loops = len(self.data.loops)
        with blas_threads(1):
            for k, x0 in enumerate(self.starts(count, seed)):
                try:
                    sol = least_squares(
                        self.residuals, x0, jac=jac, bounds=(self.lower, self.upper),
                        x_scale="jac", max_nfev=budget, method="trf", tr_solver=trust_solver,
                    )  # fmt: skip
                except (ValueError, FloatingPointError, np.linalg.LinAlgError) as exc:
                    failures.append(f"start {k + 1}: {exc}")
                    continue
                records.append(
                    StartRecord(k, math.sqrt(2 * sol.cost / n_loops), sol.nfev, sol.status,
                                sol.message, "start set" if k == 0 else "sobol")
                )  # fmt: skip
                costs.append(float(sol.cost))
                if best is None or sol.cost < best.cost:
                    best = sol
        if best is None:
            raise FitError(f"every start of the {self.spec.name} fit failed: {'; '.join(failures)}")
        forces = self.model_force(best.x)
        nrmse = self.nrmse(forces)
        values = self.values(best.x)
        span = self.upper - self.lower
        at_bounds = tuple(
            k for k, x, lo, hi, s in zip(self.free, best.x, self.lower, self.upper, span, strict=True)
            if min(x - lo, hi - x) <= 1e-6 * s
        )  # fmt: skip
        pset = self._parameter_set(values, nrmse, name, source)
        within = sum(1 for c in costs if c <= best.cost * 1.01 + 1e-300)
        with np.errstate(all="ignore"):
            try:
                correlated, condition = self.identifiability(
                    best.x, best.jac if not callable(jac) else None
                )
            except (ValueError, np.linalg.LinAlgError, ValidationError):
                correlated, condition = (), math.nan
        return FitResult(
            model=self.spec.name,
            parameters=pset,
            start=self.start_set,
            free=tuple(self.free),
            bounds={k: self.bounds[k] for k in self.free},
            rms_nrmse=math.sqrt(2 * best.cost / n_loops),
            nfev=int(best.nfev),
            status=int(best.status),
            converged=bool(best.status > 0),
            message=str(best.message),
            starts=tuple(records),
            seconds=time.perf_counter() - t0,
            loops=self.data.loops,
            loop_index=tuple(range(n_loops) if loop_index is None else loop_index),
            model_forces=tuple(forces[sl].copy() for sl in self.data.slices),
            nrmse=nrmse,
            options=dict(self.spec.options),
            at_bounds=at_bounds,
            excluded=dict(excluded or {}),
            jacobian="analytic" if callable(jac) else str(jac),
            starts_within=within,
            correlated=correlated,
            condition=condition,
        )

    def _parameter_set(
        self,
        values: Mapping[str, float],
        nrmse: FloatArray,
        name: str | None,
        source: str | None,
    ) -> _parameters.ParameterSet:
        ref = _parameters.get(self.spec.damper.default_parameters)
        loops = self.data.loops
        freqs = [lp.nominal_frequency or lp.frequency for lp in loops]
        currents = [lp.mean_current for lp in loops]
        opts = ", ".join(f"{k}={v!r}" for k, v in self.spec.options.items())
        today = _dt.date.today().isoformat()
        return _parameters.ParameterSet(
            name=name or f"{self.spec.name}-fitted",
            model=self.spec.name,
            values=dict(values),
            units={k: self.start_set.units.get(k) or ref.units.get(k, "") for k in values},
            descriptions={
                k: self.start_set.descriptions.get(k) or ref.descriptions.get(k, "") for k in values
            },
            source=source or f"fitted by mrsuspension identify on {today}",
            table="-",
            description=(
                f"least-squares fit (eq. 2.22, each test normalised by its force range) to "
                f"{len(loops)} tests, {min(freqs):g}-{max(freqs):g} Hz, "
                f"{min(currents):.3g}-{max(currents):.3g} A; mean NRMSE "
                f"{100 * float(np.mean(nrmse)):.2f} %, max {100 * float(np.max(nrmse)):.2f} %; "
                f"free: {', '.join(self.free)}; started from {self.start_set.name!r}"
                + (f"; model options {opts}" if opts else "")
            ),
            frequency_range=(float(min(freqs)), float(max(freqs))),
            max_current=self.max_current,
        )


def fit_loops(
    loops: Sequence[Loop],
    model: str = "wang-symmetric",
    *,
    start: Any = None,
    bounds: BoundsSpec | None = None,
    fixed: FixedSpec | None = None,
    model_options: Mapping[str, Any] | None = None,
    multistart: int | None = None,
    seed: int = 0,
    max_nfev: int | None = None,
    jacobian: str = "analytic",
    trust_solver: str = "lsmr",
    name: str | None = None,
    source: str | None = None,
) -> FitResult:
    """Fit ``model`` to ``loops`` (global least squares, eq. 2.22, multi-start).

    Loops for which the model force is not finite at the start are left out and named
    in :attr:`FitResult.excluded`; the others are fitted. See :class:`FitProblem` for
    the parameters; ``multistart`` defaults to 4 for the dissertation's models and 1 for
    the others, ``jacobian="2-point"`` forces finite differences, ``trust_solver`` is
    explained in :meth:`FitProblem.solve`.
    """
    problem = FitProblem(
        loops, model, start=start, bounds=bounds, fixed=fixed, model_options=model_options
    )
    f0 = problem.model_force(problem.scaled(problem.x_start))
    bad = [k for k, sl in enumerate(problem.data.slices) if not np.all(np.isfinite(f0[sl]))]
    index = list(range(len(loops)))
    excluded: dict[int, str] = {}
    if bad:
        if len(bad) == len(loops):
            raise FitError(
                f"the {problem.spec.name} model force is not finite for any test at the start "
                "parameters; give other start values"
            )
        excluded = {k: "model force not finite at the start parameters" for k in bad}
        index = [k for k in index if k not in excluded]
        problem = FitProblem(
            [loops[k] for k in index], model, start=start, bounds=bounds, fixed=fixed,
            model_options=model_options,
        )  # fmt: skip
    return problem.solve(
        multistart=multistart, seed=seed, max_nfev=max_nfev, jacobian=jacobian,
        trust_solver=trust_solver, name=name, source=source, loop_index=index, excluded=excluded,
    )  # fmt: skip
