"""The semi-active optimum of the half car: a damper in the band at each axle.

The same problem as the quarter car's (:mod:`mrsuspension.benchmark.optimum`) on
:class:`~mrsuspension.vehicle.HalfCar` (body heave and pitch, a wheel per axle, its
``linear_matrices``: the toolkit's parameters, not retyped), with:

* comfort: the Wk-weighted heave acceleration at the centre of gravity;
* road holding: the mean over the wheels of each dynamic tyre force's mean square over
  its passive value; rattle space: the same of the strokes;
* one road driven at the road's speed: the rear wheel meets the front wheel's road
  ``wheelbase / V`` later (``delay``), both wheels on the profile at ``t = 0``;
* the passive car (the band at its passive setting at both axles) solved as the same NLP
  with the band coordinates fixed: it gives the scales and the warm start.

Examples
--------
>>> from mrsuspension.excitation import iso8608
>>> problem = HalfCarProblem(iso8608("C", length=30.0, seed=2), duration=0.3, dt=2e-3)
>>> round(problem.delay, 4), problem.n  # wheelbase 2.348 m at 50 km/h; intervals
(0.1691, 150)

``problem.solve()`` gives the optimum (a :class:`HalfCarOptimum`), ``problem.passive()``
the passive car it is scaled by.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mrsuspension.benchmark.band import ForceBand, MRBand
from mrsuspension.benchmark.model import wk_state_space
from mrsuspension.benchmark.optimum import DT_RANGE, Weights, _casadi, _trapezoid_weights
from mrsuspension.errors import ValidationError, check_range
from mrsuspension.vehicle import HalfCar

if TYPE_CHECKING:
    from mrsuspension.engine.simulate import RoadInput

__all__ = ["HalfCarOptimum", "HalfCarProblem"]

#: nominal sizes of the variables for the passive solve (heave, pitch, wheels; rates)
_NOMINAL = (0.01, 0.01, 0.01, 0.01, 0.1, 0.1, 0.1, 0.1, *([1.0] * 8))


@dataclass(frozen=True)
class HalfCarOptimum:
    """A half-car trajectory (the optimum or the passive car) and its solve.

    ``states`` is ``(16, N + 1)``: heave [m], pitch [rad], ``z_u`` front and rear [m],
    their rates, then the Wk states; ``force`` and ``u`` are ``(2, N)`` (front, rear);
    ``mean_squares`` has ``comfort`` [m^2/s^4], ``road_holding`` and ``rattle`` per wheel
    [N^2, m^2]; ``measures`` the toolkit's: ``wk_rms_heave_acceleration`` [m/s^2] and
    ``DLC.front``, ``DLC.rear``, ``rms_stroke.front``, ``rms_stroke.rear``.
    """

    label: str
    time: np.ndarray
    states: np.ndarray
    force: np.ndarray
    u: np.ndarray
    mean_squares: dict[str, Any]
    cost: float
    passive_cost: float
    measures: dict[str, float]
    status: str
    success: bool
    iterations: int
    wall_time: float
    stroke_matrix: np.ndarray  # D: x_d = D q (2 x 4)

    @property
    def interval_velocity(self) -> np.ndarray:
        """``(2, N)``: each damper's mean velocity over each interval [m/s]."""
        v = self.damper_velocity
        return np.asarray(0.5 * (v[:, :-1] + v[:, 1:]))

    @property
    def damper_velocity(self) -> np.ndarray:
        """``(2, N + 1)``: ``v_d`` of each damper at the nodes [m/s]."""
        return np.asarray(self.stroke_matrix @ self.states[4:8])

    def band_violation(self, band: ForceBand) -> float:
        """Largest distance [N] of either force outside ``band`` over the intervals."""
        worst = 0.0
        for j in range(2):
            lo, hi = band.edges(self.interval_velocity[j])
            f = self.force[j]
            worst = max(worst, float(np.max(np.maximum(np.maximum(lo - f, f - hi), 0.0))))
        return worst

    def ratios(self, other: HalfCarOptimum) -> dict[str, float]:
        """rms of each term over ``other``'s (road holding and rattle: per wheel)."""
        out = {"comfort": math.sqrt(self.mean_squares["comfort"] / other.mean_squares["comfort"])}
        for term in ("road_holding", "rattle"):
            for j, corner in enumerate(HalfCar.corners):
                out[f"{term}.{corner}"] = math.sqrt(
                    self.mean_squares[term][j] / other.mean_squares[term][j]
                )
        return out


class HalfCarProblem:
    """The half car's optimal control problem on one road (see the module docstring).

    Parameters
    ----------
    road : RoadInput
        The road under the front wheel (with a ``speed`` [m/s] unless ``delay`` is given).
    vehicle : HalfCar, optional
        The half car (default: one side of the published full car).
    band : ForceBand, optional
        Every damper's band (default :class:`MRBand`).
    weights : Weights, optional
    dt, duration : float
        Grid step [s] and record length [s], as :class:`~mrsuspension.benchmark.BenchmarkProblem`.
    delay : float, optional
        Rear wheel's delay [s] (default ``wheelbase / speed``).
    """

    n_corners = 2

    def __init__(
        self,
        road: RoadInput,
        *,
        vehicle: HalfCar | None = None,
        band: ForceBand | None = None,
        weights: Weights | None = None,
        dt: float = 1e-3,
        duration: float | None = None,
        delay: float | None = None,
    ) -> None:
        from mrsuspension.engine.simulate import road_grid

        self.vehicle = HalfCar() if vehicle is None else vehicle
        if not isinstance(self.vehicle, HalfCar):
            raise ValidationError(f"vehicle must be a HalfCar; got {type(self.vehicle).__name__}")
        self.band: ForceBand = MRBand() if band is None else band
        self.weights = Weights() if weights is None else weights
        self.dt = float(check_range("dt", dt, DT_RANGE[0], DT_RANGE[1], unit="s"))
        if delay is None:
            speed = getattr(road, "speed", None)
            if speed is None:
                raise ValidationError("give delay [s]: the road has no speed to derive it from")
            delay = self.vehicle.wheelbase / float(speed)
        self.delay = float(check_range("delay", delay, 0.0, 60.0, unit="s"))
        total = float(getattr(road, "duration", math.inf)) - self.delay
        total = total if duration is None else float(duration)
        total = float(check_range("duration", total, 10 * self.dt, 3600.0, unit="s"))
        self.n = math.floor(total / self.dt + 1e-9)
        front = road_grid(road, self.n + 1, self.dt, start=self.delay)
        rear = road_grid(road, self.n + 1, self.dt)
        # r = [z_r front, z_r rear, z_r' front, z_r' rear]
        self.road_samples = np.vstack([front[0], rear[0], front[1], rear[1]])
        self.time = np.arange(self.n + 1) * self.dt
        self._model()
        self._q = _trapezoid_weights(self.n, self.dt)
        self._solver: dict[str, Any] | None = None
        self._passive: HalfCarOptimum | None = None

    # -- model ----------------------------------------------------------------------------
    def _model(self) -> None:
        car = self.vehicle
        lin = car.linear_matrices(0.0)  # M, C (tyre damping), K, K_road, C_road
        t = car.body_transform()
        d = np.hstack([-t, np.eye(2)])  # x_d = D q
        minv = np.linalg.inv(lin.M)
        aw, bw, cw, _ = wk_state_space()
        a = np.zeros((16, 16))
        b = np.zeros((16, 2))
        e = np.zeros((16, 4))
        a[0:4, 4:8] = np.eye(4)
        a[4:8, 0:4] = -minv @ lin.K
        a[4:8, 4:8] = -minv @ lin.C
        b[4:8] = -minv @ d.T  # a positive force pushes the body up and the wheel down
        e[4:8, 0:2] = minv @ lin.K_road
        e[4:8, 2:4] = minv @ lin.C_road
        a[8:, 8:] = aw
        a[8:, :8] += np.outer(bw[:, 0], a[4, :8])  # driven by the heave acceleration
        b[8:] = np.outer(bw[:, 0], b[4])
        e[8:] = np.outer(bw[:, 0], e[4])
        kt, ct = car.tire_stiffnesses, car.tire_dampings
        c = np.zeros((5, 16))  # a_w, F_T front/rear (dynamic), x_d front/rear
        c[0, 8:] = cw[0]
        e_y = np.zeros((5, 4))
        for j in range(2):
            c[1 + j, 2 + j], c[1 + j, 6 + j] = -kt[j], -ct[j]
            e_y[1 + j, j], e_y[1 + j, 2 + j] = kt[j], ct[j]
            c[3 + j, 0:4] = d[j]
        h = self.dt
        m = np.eye(16) - 0.5 * h * a
        self._p = np.linalg.solve(m, np.eye(16) + 0.5 * h * a)
        self._qf = np.linalg.solve(m, h * b)
        self._rs = np.linalg.solve(m, 0.5 * h * e)
        self._c, self._e_y, self._d = c, e_y, d
        self.x0 = np.zeros(16)
        zr0 = self.road_samples[0:2, 0]
        self.x0[0:2] = np.linalg.solve(t, zr0)  # the body on the wheels, at rest
        self.x0[2:4] = zr0

    # -- NLP ------------------------------------------------------------------------------
    def _nlp(self) -> dict[str, Any]:
        if self._solver is not None:
            return self._solver
        ca = _casadi()
        import scipy.sparse as sparse

        n = self.n
        sx = np.array(_NOMINAL)
        sf = 1000.0
        nx = 16 * (n + 1)
        nz = nx + 4 * n
        k = np.arange(n)
        p_s = self._p * sx[None, :] / sx[:, None]
        q_s = self._qf * sf / sx[:, None]
        pi, pj = np.nonzero(p_s)
        eye = np.arange(16)
        rows = [(16 * k[:, None] + eye).ravel(), (16 * k[:, None] + pi).ravel()]
        cols = [(16 * (k[:, None] + 1) + eye).ravel(), (16 * k[:, None] + pj).ravel()]
        vals = [np.ones(16 * n), np.tile(-p_s[pi, pj], n)]
        for j in range(2):  # forces F[j, k] at nx + 2 k + j
            qi = np.nonzero(q_s[:, j])[0]
            rows.append((16 * k[:, None] + qi).ravel())
            cols.append(np.repeat(nx + 2 * k + j, qi.size))
            vals.append(np.tile(-q_s[qi, j], n))
        a_def = sparse.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(16 * n, nz),
        )
        r = self.road_samples
        b_def = ((self._rs @ (r[:, :-1] + r[:, 1:])) / sx[:, None]).ravel(order="F")
        z = ca.MX.sym("z", nz)
        g = [ca.mtimes(ca.DM(a_def), z) - ca.DM(b_def)]
        for j in range(2):
            # mean damper velocity of corner j over each interval: D_j q' at both nodes
            dv = self._d[j] * sx[4:8]
            cols_v = (
                16 * k[:, None] + np.concatenate([4 + np.arange(4), 20 + np.arange(4)])
            ).ravel()
            l_v = sparse.csc_matrix(
                (np.tile(0.5 * np.concatenate([dv, dv]), n), (np.repeat(k, 8), cols_v)),
                shape=(n, nz),
            )
            force = sf * z[nx + j : nx + 2 * n : 2]
            u = z[nx + 2 * n + j :: 2]
            v_mid = ca.mtimes(ca.DM(l_v), z)
            g.append((force - self.band.force(v_mid, u, ca)) / sf)
        coeff = ca.MX.sym("c", 5)
        root_q = np.sqrt(self._q)
        cost = 0
        for j in range(5):
            w_j = sparse.kron(sparse.diags(root_q), sparse.csr_matrix((self._c[j] * sx)[None, :]))
            w_j = sparse.hstack([w_j, sparse.csc_matrix((n + 1, 4 * n))]).tocsc()
            y = ca.mtimes(ca.DM(w_j), z) + ca.DM(root_q * (self._e_y[j] @ r))
            cost = cost + coeff[j] * ca.dot(y, y)
        opts = {
            "ipopt.linear_solver": "mumps",
            "ipopt.tol": 1e-8,
            "ipopt.acceptable_tol": 1e-6,
            "ipopt.max_iter": 1000,
            "ipopt.mu_strategy": "adaptive",
            "ipopt.print_level": 0,
            "ipopt.sb": "yes",
            "print_time": False,
        }
        solver = ca.nlpsol(
            "halfcar", "ipopt", {"x": z, "f": cost, "g": ca.vertcat(*g), "p": coeff}, opts
        )
        lo, hi = self.band.bounds
        lbx = np.concatenate([np.full(nx + 2 * n, -np.inf), np.full(2 * n, lo)])
        ubx = np.concatenate([np.full(nx + 2 * n, np.inf), np.full(2 * n, hi)])
        lbx[:16] = ubx[:16] = self.x0 / sx
        self._solver = {"solver": solver, "sx": sx, "sf": sf, "lbx": lbx, "ubx": ubx, "nx": nx}
        return self._solver

    def _run(
        self, coeff: npt.ArrayLike, z0: np.ndarray, fixed_u: float | None, label: str
    ) -> tuple[np.ndarray, dict[str, Any], float]:
        nlp = self._nlp()
        lbx, ubx = nlp["lbx"].copy(), nlp["ubx"].copy()
        if fixed_u is not None:
            lbx[nlp["nx"] + 2 * self.n :] = fixed_u
            ubx[nlp["nx"] + 2 * self.n :] = fixed_u
        t0 = _time.perf_counter()
        sol = nlp["solver"](
            x0=z0, p=np.asarray(coeff, dtype=float), lbx=lbx, ubx=ubx, lbg=0.0, ubg=0.0
        )
        wall = _time.perf_counter() - t0
        return np.asarray(sol["x"]).ravel(), nlp["solver"].stats(), wall

    def _result(
        self, zz: np.ndarray, stats: dict[str, Any], wall: float, label: str, scales: Any
    ) -> HalfCarOptimum:
        from mrsuspension import measures as M

        nlp = self._nlp()
        n, nx, sx, sf = self.n, nlp["nx"], nlp["sx"], nlp["sf"]
        x = zz[:nx].reshape(n + 1, 16).T * sx[:, None]
        force = zz[nx : nx + 2 * n].reshape(n, 2).T * sf
        u = zz[nx + 2 * n :].reshape(n, 2).T
        y = self._c @ x + self._e_y @ self.road_samples
        ms = {
            "comfort": float(self._q @ y[0] ** 2),
            "road_holding": [float(self._q @ y[1 + j] ** 2) for j in range(2)],
            "rattle": [float(self._q @ y[3 + j] ** 2) for j in range(2)],
        }
        heave_acc = np.diff(x[4]) / self.dt
        loads = self.vehicle.static_tire_loads()
        measures = {"wk_rms_heave_acceleration": M.weighted_rms(heave_acc, 1.0 / self.dt)}
        for j, corner in enumerate(self.vehicle.corners):
            measures[f"DLC.{corner}"] = M.dlc(loads[j] + y[1 + j])
            measures[f"rms_stroke.{corner}"] = float(np.std(y[3 + j]))
        cost, passive_cost = math.nan, math.nan
        if scales is not None:
            cost = float(np.dot(self._coeff(scales), self._flat(ms)))
            passive_cost = float(sum(self.weights.vector))
        status = str(stats.get("return_status", "unknown"))
        return HalfCarOptimum(
            label=label,
            time=self.time,
            states=x,
            force=force,
            u=u,
            mean_squares=ms,
            cost=cost,
            passive_cost=passive_cost,
            measures=measures,
            status=status,
            success=status in ("Solve_Succeeded", "Solved_To_Acceptable_Level"),
            iterations=int(stats.get("iter_count", -1)),
            wall_time=wall,
            stroke_matrix=self._d,
        )

    @staticmethod
    def _flat(ms: dict[str, Any]) -> np.ndarray:
        return np.array([ms["comfort"], *ms["road_holding"], *ms["rattle"]])

    def _coeff(self, scales: np.ndarray) -> np.ndarray:
        """Objective coefficients: weight over scale^2, the wheels' terms averaged."""
        w_c, w_r, w_s = self.weights.vector
        per = np.array([w_c, w_r / 2, w_r / 2, w_s / 2, w_s / 2])
        return np.asarray(per / scales**2)

    def passive(self) -> HalfCarOptimum:
        """Both dampers at the band's passive setting (the NLP with ``u`` fixed)."""
        if self._passive is None:
            nlp = self._nlp()
            z0 = np.concatenate(
                [np.tile(self.x0 / nlp["sx"], self.n + 1), np.zeros(2 * self.n),
                 np.full(2 * self.n, self.band.passive)]
            )  # fmt: skip
            zz, stats, wall = self._run(np.ones(5), z0, self.band.passive, "passive")
            run = self._result(zz, stats, wall, "passive", None)
            if not run.success:  # pragma: no cover - a square system IPOPT did not solve
                raise ValidationError(f"the passive half car did not solve: {run.status}")
            flat = self._flat(run.mean_squares)
            self._scales = np.where(flat > 0, np.sqrt(flat), 1.0)
            self._z_passive = zz
            self._passive = self._result(zz, stats, wall, "passive", self._scales)
        return self._passive

    def solve(self) -> HalfCarOptimum:
        """The optimum, warm started from the passive car."""
        self.passive()
        zz, stats, wall = self._run(self._coeff(self._scales), self._z_passive, None, "optimum")
        return self._result(zz, stats, wall, "optimum", self._scales)
