"""The semi-active optimum: the best any damper inside a force band can do on a known road.

For a road record known in advance, the optimal control problem (``docs/benchmark.md``
states it in full)::

    minimise    J = w_c <a_w^2> / S_c^2 + w_r <F_T,dyn^2> / S_r^2 + w_s <x_d^2> / S_s^2
    over        the damper force F(t), for t in [0, T]
    subject to  the quarter car's dynamics (:mod:`mrsuspension.benchmark.model`),
                F(t) in the band at v_d(t) (:mod:`mrsuspension.benchmark.band`),
                the car at rest in equilibrium on the road at t = 0

where ``<.>`` is the time average over the record, ``a_w`` the Wk-weighted body
acceleration (ISO 2631-1), ``F_T,dyn`` the dynamic tyre force (the DLC's numerator) and
``x_d`` the stroke; the scales ``S`` are by default the passive car's rms values (the band
at its passive setting, :attr:`ForceBand.passive`), so that the passive car costs
``w_c + w_r + w_s``. It is solved offline by direct transcription
(:func:`~mrsuspension.benchmark.model.trapezoidal`: the trapezoidal rule on a grid of step
``dt`` with the force held over each interval, the band met at each interval's mean
velocity) as one sparse nonlinear program for IPOPT (through CasADi), warm started from the
passive car. The optimum is the lower bound of ``J`` over every law that acts through the
same band: every control law's cost on the same road and objective is at or above it.

* :class:`BenchmarkProblem` - the discretised problem on one road: :meth:`~BenchmarkProblem.solve`,
  and the same model and objective for reference laws (:meth:`~BenchmarkProblem.passive`,
  :meth:`~BenchmarkProblem.skyhook`);
* :func:`semi_active_optimum` - build and solve in one call;
* :func:`pareto_front` - the optimum for a sweep of the comfort weight;
* :func:`replay` - the optimal force re-simulated with the toolkit's engine.

Needs CasADi (``pip install "mrsuspension[optimal]"``) for the solve only.
"""

from __future__ import annotations

import math
import time as _time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from mrsuspension.benchmark.band import ForceBand, MRBand
from mrsuspension.benchmark.model import (
    Discrete,
    LinearQuarterCar,
    linear_quarter_car,
    trapezoidal,
)
from mrsuspension.errors import MRSuspensionError, ValidationError, check_range, require_extra
from mrsuspension.vehicle import QuarterCar

if TYPE_CHECKING:
    from mrsuspension.engine.simulate import RoadInput

__all__ = [
    "TERMS",
    "BenchmarkProblem",
    "OptimumResult",
    "ParetoFront",
    "Trajectory",
    "Weights",
    "pareto_front",
    "replay",
    "semi_active_optimum",
]

#: The objective's terms, in the order of :data:`~mrsuspension.benchmark.model.OUTPUTS`.
TERMS = ("comfort", "road_holding", "rattle")
#: Grid steps the problem accepts [s]: the toolkit's Wk measure needs > 200 Hz.
DT_RANGE = (1e-4, 4e-3)


@dataclass(frozen=True)
class Weights:
    """Weights of the objective's terms (each term scaled by its passive mean square).

    Examples
    --------
    >>> Weights(comfort=0.7, road_holding=0.3, rattle=0.0).vector
    (0.7, 0.3, 0.0)
    """

    comfort: float = 1.0
    road_holding: float = 1.0
    rattle: float = 0.1

    def __post_init__(self) -> None:
        for name in TERMS:
            value = float(check_range(f"{name} weight", getattr(self, name), 0.0, 1e6))
            object.__setattr__(self, name, value)
        if not any(self.vector):
            raise ValidationError("at least one weight must be > 0; got all 0")

    @property
    def vector(self) -> tuple[float, float, float]:
        """``(comfort, road_holding, rattle)``."""
        return self.comfort, self.road_holding, self.rattle


@dataclass(frozen=True)
class Trajectory:
    """A run of the discretised model: states at the nodes, force over the intervals.

    Attributes
    ----------
    label : str
        What produced it (``"optimum"``, ``"passive"``, ``"skyhook 6750 N s/m"``).
    time : ndarray
        Nodes ``k dt`` [s], ``N + 1`` of them.
    states : ndarray
        ``(12, N + 1)``: :data:`~mrsuspension.benchmark.model.STATES` [SI].
    force : ndarray
        Damper force held over each interval [N], ``N`` values.
    u : ndarray
        Band coordinate of each interval.
    road : ndarray
        ``(2, N + 1)``: ``z_r`` [m], ``z_r'`` [m/s] at the nodes.
    outputs : ndarray
        ``(3, N + 1)``: ``a_w`` [m/s^2], dynamic tyre force [N], stroke ``x_d`` [m].
    mean_squares : dict
        Time averages (trapezoidal) of the outputs' squares by term (:data:`TERMS`).
    terms : dict
        Each term's share of the cost: ``w mean_square / S^2``.
    cost : float
        ``sum(terms)``.
    measures : dict
        The toolkit's road measures of the run
        (:func:`~mrsuspension.engine.result.road_measures`: ``DLC``,
        ``wk_rms_body_acceleration``, ``rms_stroke``, ...), body acceleration taken as each
        interval's mean ``(z_s'_(k+1) - z_s'_k) / dt``.
    current : ndarray or None
        Drive current of each interval [A] for an :class:`MRBand` (``nan`` at ``v_d = 0``).
    """

    label: str
    time: np.ndarray
    states: np.ndarray
    force: np.ndarray
    u: np.ndarray
    road: np.ndarray
    outputs: np.ndarray
    mean_squares: dict[str, float]
    terms: dict[str, float]
    cost: float
    measures: dict[str, float]
    current: np.ndarray | None

    @property
    def dt(self) -> float:
        """Grid step [s]."""
        return float(self.time[1] - self.time[0])

    @property
    def damper_velocity(self) -> np.ndarray:
        """``v_d = z_u' - z_s'`` at the nodes [m/s]."""
        return np.asarray(self.states[3] - self.states[1])

    @property
    def interval_velocity(self) -> np.ndarray:
        """``v_d`` at each interval's middle (mean of its nodes) [m/s]: the band's argument."""
        v = self.damper_velocity
        return np.asarray(0.5 * (v[:-1] + v[1:]))

    @property
    def body_acceleration(self) -> np.ndarray:
        """Mean ``z_s''`` over each interval [m/s^2]."""
        return np.asarray(np.diff(self.states[1]) / self.dt)

    @property
    def stroke(self) -> np.ndarray:
        """``x_d = z_u - z_s`` at the nodes [m]."""
        return np.asarray(self.outputs[2])

    def band_violation(self, band: ForceBand) -> float:
        """Largest distance [N] of the force outside ``band`` at the interval velocities."""
        lo, hi = band.edges(self.interval_velocity)
        return float(np.max(np.maximum(np.maximum(lo - self.force, self.force - hi), 0.0)))

    def ratios(self, other: Trajectory) -> dict[str, float]:
        """This run's rms of each term over ``other``'s (e.g. over the passive car's)."""
        return {
            k: math.sqrt(self.mean_squares[k] / other.mean_squares[k])
            if other.mean_squares[k] > 0
            else math.nan
            for k in TERMS
        }


@dataclass(frozen=True)
class OptimumResult(Trajectory):
    """The optimum (a :class:`Trajectory`) with its solver's report.

    Attributes
    ----------
    status : str
        IPOPT's return status (``"Solve_Succeeded"``, ...).
    success : bool
        IPOPT converged (to ``tol``, or to its acceptable level).
    iterations : int
        IPOPT iterations.
    wall_time : float
        Seconds in the solver (the problem's construction not included).
    build_time : float
        Seconds to build the NLP.
    passive : Trajectory
        The passive car on the same model and objective (the scales' reference).
    weights : Weights
    scales : tuple of float
        ``(S_c [m/s^2], S_r [N], S_s [m])``.
    """

    status: str = ""
    success: bool = False
    iterations: int = 0
    wall_time: float = 0.0
    build_time: float = 0.0
    passive: Trajectory | None = None
    weights: Weights = field(default_factory=Weights)
    scales: tuple[float, float, float] = (1.0, 1.0, 1.0)

    def summary(self) -> str:
        """A few lines: status, cost against the passive car's, ratios, band violation."""
        lines = [
            f"semi-active optimum: {self.status} in {self.iterations} iterations, "
            f"{self.wall_time:.1f} s (NLP built in {self.build_time:.1f} s)",
            f"cost {self.cost:.6g} (passive {self.passive.cost:.6g})"
            if self.passive is not None
            else f"cost {self.cost:.6g}",
        ]
        if self.passive is not None:
            r = self.ratios(self.passive)
            lines.append("rms over passive: " + ", ".join(f"{k} {v:.3f}" for k, v in r.items()))
        return "\n".join(lines)


def _casadi() -> Any:
    require_extra("optimal", "the semi-active optimum (mrsuspension.benchmark)")
    import casadi

    return casadi


def _trapezoid_weights(n: int, h: float) -> np.ndarray:
    q = np.full(n + 1, h)
    q[0] = q[-1] = 0.5 * h
    return q / (n * h)


class BenchmarkProblem:
    """The discretised optimal control problem on one road (see the module docstring).

    Parameters
    ----------
    road : RoadInput
        The road (any excitation: :func:`~mrsuspension.excitation.iso8608`, ...), sampled
        on the grid as the engine samples it.
    vehicle : QuarterCar, optional
        The quarter car (nominal by default); its parameters give the linear model.
    band : ForceBand, optional
        The damper's force band (default :class:`MRBand`: the dissertation's damper,
        0-0.5 A).
    weights : Weights, optional
        The objective's weights.
    dt : float
        Grid step [s] (1e-4 to 4e-3; 1 ms by default).
    duration : float, optional
        Record length [s] (default: the road's duration), a whole number of ``dt``.
    scales : (float, float, float), optional
        ``(S_c [m/s^2], S_r [N], S_s [m])``; default: the passive car's rms values.

    Examples
    --------
    >>> from mrsuspension.excitation import iso8608
    >>> problem = BenchmarkProblem(iso8608("C", length=20.0, seed=1), duration=0.5)
    >>> passive = problem.passive()
    >>> round(passive.cost, 6)  # the scales are the passive car's: w_c + w_r + w_s
    2.1
    >>> round(problem.skyhook(3000.0).cost, 3)  # skyhook through the band, c_s = 3000 N s/m
    2.097
    """

    def __init__(
        self,
        road: RoadInput,
        *,
        vehicle: QuarterCar | None = None,
        band: ForceBand | None = None,
        weights: Weights | None = None,
        dt: float = 1e-3,
        duration: float | None = None,
        scales: Sequence[float] | None = None,
    ) -> None:
        from mrsuspension.engine.simulate import road_grid

        self.vehicle = QuarterCar() if vehicle is None else vehicle
        if not isinstance(self.vehicle, QuarterCar):
            raise ValidationError(
                f"vehicle must be a QuarterCar; got {type(self.vehicle).__name__}"
            )
        self.band: ForceBand = MRBand() if band is None else band
        self.weights = Weights() if weights is None else weights
        self.dt = float(check_range("dt", dt, DT_RANGE[0], DT_RANGE[1], unit="s"))
        total = float(getattr(road, "duration", math.inf)) if duration is None else duration
        total = float(check_range("duration", total, 10 * self.dt, 3600.0, unit="s"))
        self.n = math.floor(total / self.dt + 1e-9)
        self.road = road
        zr, zrd = road_grid(road, self.n + 1, self.dt)
        self.road_samples = np.vstack([zr, zrd])
        self.time = np.arange(self.n + 1) * self.dt
        self.linear: LinearQuarterCar = linear_quarter_car(self.vehicle)
        self.discrete: Discrete = trapezoidal(self.linear, self.dt)
        self.x0 = np.zeros(12)
        self.x0[0] = self.x0[2] = zr[0]
        self._q = _trapezoid_weights(self.n, self.dt)
        if scales is not None:
            s = check_range("scales", scales, 0.0, 1e9, low_inclusive=False)
            if s.shape != (3,):
                raise ValidationError(
                    f"scales must be three numbers (S_c m/s^2, S_r N, S_s m); got {s.shape}"
                )
            self._scales: tuple[float, float, float] | None = (
                float(s[0]),
                float(s[1]),
                float(s[2]),
            )
        else:
            self._scales = None
        self._passive: Trajectory | None = None
        self._solvers: dict[Any, dict[str, Any]] = {}  # shared by with_weights copies

    # -- the objective ------------------------------------------------------------------
    @property
    def scales(self) -> tuple[float, float, float]:
        """``(S_c, S_r, S_s)``: given, or the passive car's rms values."""
        if self._scales is None:
            self.passive()
        assert self._scales is not None
        return self._scales

    def with_weights(self, weights: Weights) -> BenchmarkProblem:
        """The same road, car, band, grid and scales with other weights."""
        new = object.__new__(BenchmarkProblem)
        new.__dict__.update(self.__dict__)
        new._scales = self.scales
        new.weights = weights
        new._passive = None if self._passive is None else new._rescored(self._passive)
        return new

    def _rescored(self, run: Trajectory) -> Trajectory:
        """``run`` with its terms and cost under this problem's weights and scales."""
        s = self.scales
        terms = {
            k: w * run.mean_squares[k] / (s[j] * s[j])
            for j, (k, w) in enumerate(zip(TERMS, self.weights.vector, strict=True))
        }
        return replace(run, terms=terms, cost=float(sum(terms.values())))

    def _outputs(self, x: np.ndarray) -> np.ndarray:
        return np.asarray(self.linear.c @ x + self.linear.e_y @ self.road_samples)

    def _trajectory(self, label: str, x: np.ndarray, force: np.ndarray, u: np.ndarray,
                    scaled: bool = True) -> Trajectory:  # fmt: skip
        from mrsuspension.engine.result import road_measures

        y = self._outputs(x)
        ms = {k: float(self._q @ (y[j] * y[j])) for j, k in enumerate(TERMS)}
        terms = dict.fromkeys(TERMS, math.nan)
        current = None
        if isinstance(self.band, MRBand):
            v_mid = 0.5 * ((x[3] - x[1])[:-1] + (x[3] - x[1])[1:])
            current = self.band.current(force, v_mid)
        tire = self.linear.static_load + y[1]
        acc = np.diff(x[1]) / self.dt
        with np.errstate(invalid="ignore"):
            mean_current = float(np.nanmean(current)) if current is not None else math.nan
        measures = road_measures(
            tire_force_mean=float(np.mean(tire)),
            tire_force_variance=float(np.var(tire)),
            body_acceleration=acc,
            fs=1.0 / self.dt,
            stroke_variance=float(np.var(y[2])),
            mean_current=mean_current,
        )
        run = Trajectory(
            label=label,
            time=self.time,
            states=x,
            force=np.asarray(force, dtype=float),
            u=np.asarray(u, dtype=float),
            road=self.road_samples,
            outputs=y,
            mean_squares=ms,
            terms=terms,
            cost=float(sum(terms.values())),
            measures=measures,
            current=current,
        )
        return self._rescored(run) if scaled else run

    # -- reference laws on the same discretised model -------------------------------------
    def _simulate(
        self,
        target: Callable[[float, float], float] | None,
        u: float,
        label: str,
        scaled: bool = True,
        band: ForceBand | None = None,
    ) -> Trajectory:
        """March the trapezoidal rule; the force of each interval solves ``F = g(F)``.

        With ``target`` None the band at coordinate ``u``; else the band's force nearest
        to ``target(z_s'_mid, v_mid)`` (the request clipped into the band). ``band``:
        another band than the problem's.
        """
        from scipy.optimize import brentq

        d, n = self.discrete, self.n
        band = self.band if band is None else band
        r = self.road_samples
        x = np.empty((12, n + 1))
        x[:, 0] = self.x0
        forces = np.empty(n)
        us = np.empty(n)
        lo_u, hi_u = band.bounds
        for k in range(n):
            base = d.p @ x[:, k] + d.r @ r[:, k] + d.s @ r[:, k + 1]
            v_a = 0.5 * (x[3, k] - x[1, k] + base[3] - base[1])
            v_b = 0.5 * (d.q[3] - d.q[1])
            s_a = 0.5 * (x[1, k] + base[1])
            s_b = 0.5 * d.q[1]

            g = _step_law(band, u, target, v_a, v_b, s_a, s_b)
            span = 1e4
            while f_minus_g(g, -span) > 0.0 or f_minus_g(g, span) < 0.0:
                span *= 10.0
                if span > 1e10:  # pragma: no cover - a band of no physical size
                    raise MRSuspensionError(
                        f"{label}: no force solves the step at t = {k * self.dt:g} s"
                    )
            f = float(brentq(_residual, -span, span, args=(g,), xtol=1e-9, rtol=1e-13))
            forces[k] = f
            v = v_a + v_b * f
            if target is None:
                us[k] = u
            else:  # every band is affine in u (an ActiveBand's u is the force: f0 0, f1 1)
                f0, f1 = float(band.force(v, 0.0)), float(band.force(v, 1.0))
                us[k] = (f - f0) / (f1 - f0) if f1 != f0 else lo_u
                us[k] = min(max(us[k], lo_u), hi_u)
            x[:, k + 1] = base + d.q * f
        return self._trajectory(label, x, forces, us, scaled=scaled)

    def passive(self, u: float | None = None) -> Trajectory:
        """The band at a fixed coordinate ``u`` (default: its passive setting).

        For an :class:`MRBand` ``u = 0`` is the damper at ``i_min``, ``u = 1`` at ``i_max``.
        A band with a ``passive_band`` (:class:`~mrsuspension.benchmark.band.MREnvelopeBand`)
        takes the passive car (``u`` None: the scales' reference) from that band.
        """
        if u is None:
            if self._passive is None:
                ref = getattr(self.band, "passive_band", self.band)
                run = self._simulate(None, ref.passive, "passive", scaled=False, band=ref)
                if self._scales is None:
                    ms = run.mean_squares
                    self._scales = (
                        math.sqrt(ms["comfort"]) or 1.0,
                        math.sqrt(ms["road_holding"]) or 1.0,
                        math.sqrt(ms["rattle"]) or 1.0,
                    )
                self._passive = self._rescored(run)
            return self._passive
        lo, hi = self.band.bounds
        uu = float(check_range("u", u, lo, hi))
        return self._simulate(None, uu, f"band at u = {uu:g}")

    def skyhook(self, damping: float = 6750.0) -> Trajectory:
        """Skyhook through the band: the band's force nearest to ``-c_s z_s'``.

        A law any semi-active damper can follow (it needs no force outside the band), so
        the optimum costs no more; the ideal skyhook of :class:`~mrsuspension.control.IdealSkyhook`
        (zero force when not dissipative) is outside an MR band, whose soft edge is not 0.
        """
        c = float(check_range("damping", damping, 0.0, 1e7, unit="N s/m"))
        return self._simulate(lambda zs_dot, _v: -c * zs_dot, 0.0, f"skyhook {c:g} N s/m")

    def evaluate(self, force: np.ndarray, label: str = "given force") -> Trajectory:
        """The discretised model driven by a force per interval (``N`` values) [N].

        Its cost is comparable with the optimum's whatever the force; the force's band
        coordinate is not computed (``u`` is ``nan``).
        """
        f = np.asarray(force, dtype=float)
        if f.shape != (self.n,):
            raise ValidationError(
                f"force must have {self.n} values (one per interval); got {f.shape}"
            )
        d, r = self.discrete, self.road_samples
        x = np.empty((12, self.n + 1))
        x[:, 0] = self.x0
        for k in range(self.n):
            x[:, k + 1] = d.p @ x[:, k] + d.q * f[k] + d.r @ r[:, k] + d.s @ r[:, k + 1]
        return self._trajectory(label, x, f, np.full(self.n, np.nan))

    # -- the optimum --------------------------------------------------------------------
    def _nlp(self, progress: bool, tol: float, max_iter: int) -> dict[str, Any]:
        """The NLP and its IPOPT solver, built once per problem (weights are parameters).

        Variables ``z`` (scaled by the passive car's rms sizes): the states at the nodes
        (node by node), the force of each interval, the band coordinate of each interval.
        Constraints: the trapezoidal defects, linear in ``z`` and written as one constant
        sparse matrix, and the band equations ``F = F_band(v_mid, u)``, elementwise on
        vectors. Objective: ``sum_j c_j |W_j z + w_j|^2`` with constant sparse ``W_j`` and
        the parameters ``c_j = w_j / S_j^2``. As a CasADi MX graph of a few nodes, its
        derivatives are built in a second for any grid (an SX graph of every operation
        took minutes for 10 000 intervals).
        """
        key = (progress, tol, max_iter)
        cache: dict[Any, dict[str, Any]] = self._solvers
        if key in cache:
            return cache[key]
        ca = _casadi()
        import scipy.sparse as sparse

        passive = self.passive()
        n, d, lin = self.n, self.discrete, self.linear
        sx = np.sqrt(np.mean(passive.states**2, axis=1))
        sx = np.maximum(sx, 1e-3 * np.max(sx[:4]))
        sf = max(float(np.sqrt(np.mean(passive.force**2))), 1.0)
        nx = 12 * (n + 1)
        nz = nx + 2 * n
        k = np.arange(n)
        # defects, scaled by the state scales: x_(k+1) - P x_k - q f_k - (R r_k + S r_(k+1))
        p_s = d.p * sx[None, :] / sx[:, None]
        q_s = d.q * sf / sx
        pi, pj = np.nonzero(p_s)
        qi = np.nonzero(q_s)[0]
        eye = np.arange(12)
        rows = np.concatenate(
            [
                (12 * k[:, None] + eye).ravel(),
                (12 * k[:, None] + pi).ravel(),
                (12 * k[:, None] + qi).ravel(),
            ]
        )
        cols = np.concatenate(
            [
                (12 * (k[:, None] + 1) + eye).ravel(),
                (12 * k[:, None] + pj).ravel(),
                np.repeat(nx + k, qi.size),
            ]
        )
        vals = np.concatenate([np.ones(12 * n), np.tile(-p_s[pi, pj], n), np.tile(-q_s[qi], n)])
        a_def = sparse.csc_matrix((vals, (rows, cols)), shape=(12 * n, nz))
        road = self.road_samples
        b_def = ((d.r @ road[:, :-1] + d.s @ road[:, 1:]) / sx[:, None]).ravel(order="F")
        # the band's velocity: the interval's mean v_d = z_u' - z_s'
        mid = 0.5 * np.array([-sx[1], sx[3], -sx[1], sx[3]])
        l_v = sparse.csc_matrix(
            (np.tile(mid, n), (np.repeat(k, 4), (12 * k[:, None] + [1, 3, 13, 15]).ravel())),
            shape=(n, nz),
        )
        z = ca.MX.sym("z", nz)
        force = sf * z[nx : nx + n]
        v_mid = ca.mtimes(ca.DM(l_v), z)
        band_res = (force - self.band.force(v_mid, z[nx + n :], ca)) / sf
        g = ca.vertcat(ca.mtimes(ca.DM(a_def), z) - ca.DM(b_def), band_res)
        coeff = ca.MX.sym("c", 3)
        root_q = np.sqrt(self._q)
        cost = 0
        for j in range(3):
            w_j = sparse.kron(sparse.diags(root_q), sparse.csr_matrix((lin.c[j] * sx)[None, :]))
            w_j = sparse.hstack([w_j, sparse.csc_matrix((n + 1, 2 * n))]).tocsc()
            y = ca.mtimes(ca.DM(w_j), z) + ca.DM(root_q * (lin.e_y[j] @ road))
            cost = cost + coeff[j] * ca.dot(y, y)
        opts: dict[str, Any] = {
            "ipopt.linear_solver": "mumps",
            "ipopt.tol": tol,
            "ipopt.acceptable_tol": 100 * tol,
            "ipopt.max_iter": int(max_iter),
            "ipopt.mu_strategy": "adaptive",
            "ipopt.print_level": 5 if progress else 0,
            "ipopt.print_frequency_iter": 10 if n > 2000 else 1,
            "ipopt.sb": "yes",
            "print_time": False,
        }
        solver = ca.nlpsol("optimum", "ipopt", {"x": z, "f": cost, "g": g, "p": coeff}, opts)
        ulo, uhi = self.band.bounds
        lbx = np.concatenate([np.full(nx, -np.inf), np.full(n, -np.inf), np.full(n, ulo)])
        ubx = np.concatenate([np.full(nx, np.inf), np.full(n, np.inf), np.full(n, uhi)])
        lbx[:12] = ubx[:12] = self.x0 / sx
        cache[key] = {"solver": solver, "sx": sx, "sf": sf, "lbx": lbx, "ubx": ubx}
        return cache[key]

    def solve(
        self,
        *,
        warm_start: Trajectory | None = None,
        progress: bool = False,
        tol: float = 1e-8,
        max_iter: int = 1000,
    ) -> OptimumResult:
        """Solve the NLP with IPOPT (MUMPS); warm start: the passive car by default.

        Parameters
        ----------
        warm_start : Trajectory, optional
            Initial guess (e.g. a neighbouring optimum of a weight sweep).
        progress : bool
            Print IPOPT's iteration lines (every 10th past the first 10 on grids of more
            than 2000 intervals).
        tol : float
            IPOPT's ``tol`` (its scaled NLP error: the largest of the scaled dual
            infeasibility, constraint violation and complementarity); the acceptable
            level is ``100 tol``.
        max_iter : int
            IPOPT's ``max_iter``.
        """
        t0 = _time.perf_counter()
        nlp = self._nlp(progress, float(tol), int(max_iter))
        passive = self.passive()
        start = passive if warm_start is None else warm_start
        if start.states.shape != (12, self.n + 1):
            raise ValidationError(
                f"warm_start must have {self.n + 1} nodes; got {start.states.shape[1]}"
            )
        n = self.n
        sx, sf = nlp["sx"], nlp["sf"]
        ulo, uhi = self.band.bounds
        if hasattr(self.band, "coordinate"):  # the start's force in this band's coordinate
            u0 = self.band.coordinate(start.force, start.interval_velocity)
        else:
            u0 = np.clip(np.nan_to_num(start.u, nan=self.band.passive), ulo, uhi)
        z0 = np.concatenate([(start.states / sx[:, None]).ravel(order="F"), start.force / sf, u0])
        s = self.scales
        coeff = [w / (s[j] * s[j]) for j, w in enumerate(self.weights.vector)]
        build = _time.perf_counter() - t0
        t1 = _time.perf_counter()
        solver = nlp["solver"]
        sol = solver(x0=z0, p=coeff, lbx=nlp["lbx"], ubx=nlp["ubx"], lbg=0.0, ubg=0.0)
        wall = _time.perf_counter() - t1
        stats = solver.stats()
        zz = np.asarray(sol["x"]).ravel()
        nx = 12 * (n + 1)
        x = zz[:nx].reshape(n + 1, 12).T * sx[:, None]
        f = zz[nx : nx + n] * sf
        u = zz[nx + n :]
        traj = self._trajectory("optimum", x, f, u)
        status = str(stats.get("return_status", "unknown"))
        return OptimumResult(
            **{k: getattr(traj, k) for k in Trajectory.__dataclass_fields__},
            status=status,
            success=status in ("Solve_Succeeded", "Solved_To_Acceptable_Level"),
            iterations=int(stats.get("iter_count", -1)),
            wall_time=wall,
            build_time=build,
            passive=passive,
            weights=self.weights,
            scales=self.scales,
        )


def _step_law(
    band: ForceBand,
    u: float,
    target: Callable[[float, float], float] | None,
    v_a: float,
    v_b: float,
    s_a: float,
    s_b: float,
) -> Callable[[float], float]:
    """``g(F)``: the force a law gives when the interval's force is ``F``.

    The interval's mean damper velocity is ``v_a + v_b F`` and body velocity
    ``s_a + s_b F``; without ``target`` the band at coordinate ``u``, else the request
    ``target(z_s', v_d)`` clipped into the band.
    """
    if target is None:

        def fixed(f: float) -> float:
            return float(band.force(v_a + v_b * f, u))

        return fixed

    def clipped(f: float) -> float:
        v = v_a + v_b * f
        lo, hi = band.edges(np.array([v]))
        return float(min(max(target(s_a + s_b * f, v), lo[0]), hi[0]))

    return clipped


def _residual(f: float, g: Callable[[float], float]) -> float:
    """``f - g(f)`` (for :func:`scipy.optimize.brentq`)."""
    return f - g(f)


def f_minus_g(g: Callable[[float], float], f: float) -> float:
    """``f - g(f)``: increasing in ``f`` for a band and a law of the sign conventions."""
    return f - g(f)


def semi_active_optimum(
    road: RoadInput,
    *,
    vehicle: QuarterCar | None = None,
    band: ForceBand | None = None,
    weights: Weights | None = None,
    dt: float = 1e-3,
    duration: float | None = None,
    scales: Sequence[float] | None = None,
    progress: bool = False,
    tol: float = 1e-8,
) -> OptimumResult:
    """The semi-active optimum on ``road`` (:class:`BenchmarkProblem` and its ``solve``).

    Examples
    --------
    >>> from mrsuspension.excitation import iso8608
    >>> best = semi_active_optimum(iso8608("C", length=20.0, seed=1), duration=0.3, dt=2e-3)
    >>> best.success, round(best.cost, 3), best.passive.cost
    (True, 1.817, 2.1)
    >>> bool(best.band_violation(MRBand()) < 1e-6 * abs(best.force).max())  # [N]
    True
    """
    problem = BenchmarkProblem(
        road, vehicle=vehicle, band=band, weights=weights, dt=dt, duration=duration, scales=scales
    )
    return problem.solve(progress=progress, tol=tol)


@dataclass(frozen=True)
class ParetoFront:
    """The optimum for each comfort weight ``lambda`` (road holding ``1 - lambda``).

    Attributes
    ----------
    comfort_weights : ndarray
        The sweep's ``lambda``.
    results : list of OptimumResult
    comfort : ndarray
        rms ``a_w`` of each optimum [m/s^2].
    road_holding : ndarray
        rms dynamic tyre force over the static load of each optimum (the DLC about the
        static load).
    passive : Trajectory
        The passive car (a point off the front).
    """

    comfort_weights: np.ndarray
    results: list[OptimumResult]
    comfort: np.ndarray
    road_holding: np.ndarray
    passive: Trajectory


def pareto_front(
    road: RoadInput | BenchmarkProblem,
    comfort_weights: Sequence[float] = (0.1, 0.3, 0.5, 0.7, 0.9),
    *,
    rattle: float = 0.0,
    progress: bool = False,
    tol: float = 1e-8,
    **problem: Any,
) -> ParetoFront:
    """Sweep the comfort weight: the optimum's comfort/road-holding Pareto front.

    Each ``lambda`` gives ``Weights(comfort=lambda, road_holding=1 - lambda, rattle)``; the
    scales are the passive car's for all (so the points are comparable), one NLP serves
    the whole sweep (the weights are its parameters) and each solve is warm started from
    the previous optimum. ``road`` is a road, with ``problem`` the keywords of
    :class:`BenchmarkProblem` (``vehicle``, ``band``, ``dt``, ``duration``, ``scales``),
    or a :class:`BenchmarkProblem` itself.

    Examples
    --------
    >>> from mrsuspension.excitation import iso8608
    >>> front = pareto_front(iso8608("C", length=20.0, seed=1), (0.2, 0.8), duration=0.2,
    ...                      dt=2e-3)
    >>> bool(front.comfort[1] <= front.comfort[0] and front.road_holding[1] >= front.road_holding[0])
    True
    """
    lams = check_range("comfort_weights", comfort_weights, 0.0, 1.0)
    if lams.ndim != 1 or lams.size < 2:
        raise ValidationError(f"comfort_weights must be at least two values; got {lams!r}")
    if isinstance(road, BenchmarkProblem):
        if problem:
            raise ValidationError(
                f"give the problem's settings to BenchmarkProblem, not pareto_front: {sorted(problem)}"
            )
        base = road
    else:
        base = BenchmarkProblem(road, **problem)
    results: list[OptimumResult] = []
    warm: Trajectory | None = None
    for lam in lams:
        w = Weights(comfort=float(lam), road_holding=1.0 - float(lam), rattle=rattle)
        best = base.with_weights(w).solve(warm_start=warm, progress=progress, tol=tol)
        if not best.success:
            raise MRSuspensionError(
                f"the optimum for comfort weight {lam:g} did not converge: {best.status}"
            )
        results.append(best)
        warm = best
    load = base.linear.static_load
    return ParetoFront(
        comfort_weights=lams,
        results=results,
        comfort=np.array([math.sqrt(r.mean_squares["comfort"]) for r in results]),
        road_holding=np.array([math.sqrt(r.mean_squares["road_holding"]) / load for r in results]),
        passive=base.passive(),
    )


def replay(
    trajectory: Trajectory,
    road: RoadInput,
    *,
    vehicle: QuarterCar | None = None,
    dt: float = 1e-4,
) -> dict[str, float]:
    """The toolkit's engine driven by ``trajectory``'s force: its road measures.

    A :class:`~mrsuspension.engine.Stepper` with an external force (as the HiL loop gives
    a measured force) steps the nonlinear quarter car (RK4, the tyre may lift off) at
    ``dt``, holding each interval's force; the road is the excitation itself at each
    tick's start, middle and end. The measures are taken on the trajectory's grid, as a
    :class:`~mrsuspension.engine.Simulation` records them. A sanity check of the
    transcription: open loop, the two agree within a few per cent.
    """
    from mrsuspension.engine import Simulation
    from mrsuspension.engine.result import road_measures

    h = trajectory.dt
    sub = round(h / dt)
    if sub < 1 or abs(sub * dt - h) > 1e-9 * h:
        raise ValidationError(f"dt must divide the trajectory's step {h:g} s; got {dt:g} s")
    car = QuarterCar() if vehicle is None else vehicle
    stepper = Simulation(road, vehicle=car).stepper(dt, external_force=True)
    zr0 = float(np.asarray(road.displacement(0.0)))
    stepper.reset(zr0, float(np.asarray(road.velocity(0.0))))
    n = trajectory.force.size
    ticks = np.arange(n * sub + 1) * dt
    zr = np.asarray(road.displacement(ticks), dtype=float)
    zrd = np.asarray(road.velocity(ticks), dtype=float)
    mid = ticks[:-1] + 0.5 * dt
    zrm = np.asarray(road.displacement(mid), dtype=float)
    zrdm = np.asarray(road.velocity(mid), dtype=float)
    acc = np.empty(n)
    tire = np.empty(n + 1)
    stroke = np.empty(n + 1)
    tire[0], stroke[0] = car.static_load, 0.0
    vs_prev = 0.0
    for k in range(n):
        for j in range(sub):
            m = k * sub + j
            out = stepper.step(
                zr[m],
                zrd[m],
                road_mid=(zrm[m], zrdm[m]),
                road_end=(zr[m + 1], zrd[m + 1]),
                damper_force=float(trajectory.force[k]),
            )
        acc[k] = (out["z_s_dot"] - vs_prev) / h
        vs_prev = out["z_s_dot"]
        tire[k + 1], stroke[k + 1] = out["F_T"], out["x_d"]
    return road_measures(
        tire_force_mean=float(np.mean(tire)),
        tire_force_variance=float(np.var(tire)),
        body_acceleration=acc,
        fs=1.0 / h,
        stroke_variance=float(np.var(stroke)),
        mean_current=math.nan,
    )
