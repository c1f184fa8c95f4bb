"""Semi-active model predictive control with OSQP (issue 29 part 1): ``mpc``, ``mpc-hilo``.

Every ``T_s`` (option ``sample``) the law solves a short-horizon quadratic programme
(Giorgetti, Bemporad, Tseng & Hrovat 2006; Canale, Milanese & Novara 2006) and holds the
first force of its solution until the next solve:

* **Prediction model**: the linear quarter car of
  :func:`~mrsuspension.control.literature.quarter_car_model`, states ``x = (z_s - z_u,
  z_s', z_u - z_r, z_u')``, input ``u`` the damper force up on the body [N], with ``u``
  held over each sample (zero-order hold: ``x_{k+1} = A_d x_k + B_d u_k``). The road is
  unknown (no preview): its velocity is zero over the horizon.
* **Cost**: the LQ cost of :func:`~mrsuspension.control.literature.lq_gain`,
  ``integral(z_s''^2 + w_rattle x_1^2 + w_tire x_3^2 + w_force u^2) dt``, integrated
  exactly over each sample with ``u`` held (Van Loan 1978), summed over the ``N`` samples
  of the horizon, plus the terminal cost ``x_N^T P x_N``, ``P`` the discrete Riccati
  solution of the same sampled cost. With the band inactive the first force is then
  exactly the sampled-data LQR's ``-K_d x``, and ``K_d`` tends to the continuous
  ``lq_gain`` as ``T_s`` tends to 0 (``tests/unit/control/test_mpc.py``: relative
  difference 3.5e-2 at 2 ms, 1.9e-4 at 10 us).
* **Constraint**: the damper's force band. A damper gives (model reference, section 1:
  up-positive, ``v_d = z_u' - z_s'``, the force up on the body has the sign of ``v_d``)
  a force between its passive force at ``i_min`` and at ``i_max``. Convexified as a
  viscous band ``c_min v_d <= F <= c_max v_d`` (``v_d > 0``; reversed for ``v_d < 0``):
  at the first sample with the measured ``v_d`` (exact for the viscous band), at the
  later samples with ``v_d`` *frozen* at its prediction from the present state and the
  previous solution's forces shifted by one sample (the last repeated). The band is then
  a box on each force: the QP is always feasible, and its constraint matrix is the
  identity, so a solve only updates the bounds and the linear cost. (Keeping ``v_d``
  a variable with its sign fixed, as Giorgetti et al.'s mode sequence does, makes the
  constraints state-dependent and the QP infeasible when the predicted sign is wrong.)
  ``c_min``, ``c_max``: the dissertation's damper's viscous range at 0 and 0.5 A, the
  Bingham fit ``bingham-wang-low`` (2043 and 2043 + 17139 x 0.5 N s/m, as
  :func:`~mrsuspension.control.literature.pdd`); its yield force is left out (the
  damper's least force lies above ``c_min v_d`` by the yield force at ``i_min``: a
  target below it gets ``i_min``).
* **State**: ``z_s - z_u = -x_d``, ``z_s'`` and ``z_u'`` as measured; the tire
  deflection ``z_u - z_r`` (not measured: the road is unknown) from the wheel's equation
  of motion, ``m_u z_u'' = k_s (z_s - z_u) - k_t (z_u - z_r) - c_t (z_u' - z_r') - F_d``,
  with the previous step's ``z_u''`` and ``F_d`` (the wheel accelerometer and the load
  cell) and ``z_r'`` taken as 0 (``c_t`` is small: 100 N s/m on the default car).

``mpc`` returns the first force as a target (``output="force"``, through the inverse model
like ``lq-force``: needs the ``wang-symmetric`` damper); ``mpc-hilo`` the current
``i_max`` when the target and ``v_d`` agree in sign and the target exceeds the present
force (``|F*| > |F_d|``), else ``i_min`` (the clipped-LQ rule of
:func:`~mrsuspension.control.literature.clipped_lq`).

How it runs. OSQP is a compiled library called from Python, not from numba: the laws run
on the :func:`~mrsuspension.control.user.law` "Python path" (a ctypes callback at every
engine step). Between solves a call returns the held force (about 8 us); the QP is set up
once per plant and options in a process (:func:`problem`: condensed, ``N`` forces as the
variables, scaled to kN) and each solve updates it (``update(q, l, u)``) and warm-starts it
from the previous solution shifted (``warm_start(x)``). The law's memory (one per corner)
holds the held force, the next solve's time and the previous solution, so the corners of
a car share a QP of the same plant and never each other's state. Measured (CPU time, a
shared 2-core machine at a load average of 10-12), ``N`` = 10, ``T_s`` = 2 ms: 80-110 us
per solve (about 34 OSQP iterations), 8 us per held step; per simulated second 0.054 s
on the quarter car at the engine's 0.5 ms step (``lq-force``: 0.0008 s) and 0.34 s on
the full car at 0.2 ms (four corners; ``lq-force``: 0.008 s), see
``docs/control-laws.md``.

Examples
--------
>>> from mrsuspension.control import make_controller
>>> make_controller("mpc", horizon=12).horizon
12.0
>>> from mrsuspension.vehicle import QuarterCar
>>> qp = problem(QuarterCar(), horizon=10, sample=2e-3)
>>> x = [0.0, 0.1, 0.0, 0.0]  # the body rising at 0.1 m/s, nothing else
>>> round(qp.first_move(x, lower=-1e6, upper=1e6) / float(-qp.gain @ x), 6)  # no band: the LQR
1.0
>>> qp.first_move(x, lower=-250.0, upper=0.0)  # a band that cannot push down enough
-250.0
"""

from __future__ import annotations

import functools
import importlib.util
import math
from typing import Any

import numpy as np
import numpy.typing as npt

from mrsuspension.control.base import Controller
from mrsuspension.control.literature import LQ_WEIGHTS, quarter_car_model
from mrsuspension.control.user import law
from mrsuspension.errors import ValidationError

__all__ = [
    "HORIZON_MAX",
    "LAWS",
    "MEMORY",
    "CondensedMPC",
    "MPCProblem",
    "mpc",
    "mpc_hilo",
    "problem",
]

#: the longest horizon [samples] (the law's memory holds a solution of this length)
HORIZON_MAX = 50
#: the QP's force unit [N] (the variables are kN: the cost's scale near 1)
_FORCE_UNIT = 1000.0
#: OSQP's settings: tolerances well below a newton, warm start, no polishing (the box is
#: simple and polishing costs a second solve); ``max_iter`` bounds the worst solve
_SETTINGS: dict[str, Any] = {
    "eps_abs": 1e-6,
    "eps_rel": 1e-6,
    "max_iter": 400,
    "polishing": False,
    "warm_starting": True,
    "verbose": False,
}


def _require_osqp() -> None:
    """Raise a one-line :class:`ValidationError` when ``osqp`` is not installed."""
    if importlib.util.find_spec("osqp") is None:
        raise ValidationError(
            "the MPC laws (mpc, mpc-hilo) need osqp, which is not installed: "
            'pip install "mrsuspension[optimal]"'
        )


def _sampled(
    a: npt.NDArray[np.float64], b: npt.NDArray[np.float64], m: npt.NDArray[np.float64], ts: float
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``(A_d, B_d, M_d)``: the zero-order-hold model of ``x' = A x + B u`` (``n`` states,
    ``m`` inputs) and the cost weight ``M`` (``n + m`` square, on ``(x, u)``) integrated
    over one sample with ``u`` held (Van Loan 1978)."""
    import scipy.linalg

    n = a.shape[0]
    nu = b.shape[1]
    f = np.zeros((n + nu, n + nu))
    f[:n, :n] = a
    f[:n, n:] = b
    w = n + nu
    big = np.zeros((2 * w, 2 * w))
    big[:w, :w] = -f.T
    big[:w, w:] = m
    big[w:, w:] = f
    e = scipy.linalg.expm(big * ts)
    phi = e[w:, w:]
    md = phi.T @ e[:w, w:]
    return phi[:n, :n], phi[:n, n:], 0.5 * (md + md.T)


class CondensedMPC:
    """The condensed QP of a sampled linear plant's MPC with boxes on the inputs, set up
    once in OSQP: the per-corner :class:`MPCProblem` and the whole-vehicle law
    (:class:`~mrsuspension.control.vehicle_lq.VehicleMPC`).

    ``x_{k+1} = A_d x_k + B_d u_k`` (``n`` states, ``m`` inputs), the cost
    ``sum_{k<N} (x_k, u_k)^T M_d (x_k, u_k) + x_N^T P x_N`` with ``P`` the discrete
    Riccati solution of the same stage cost: with the boxes inactive the first move is the
    sampled-data LQR's ``-K_d x``. The variables are the ``N m`` inputs (sample by sample,
    in kN); the constraint matrix is the identity, so a solve updates only the linear cost
    and the bounds.

    Parameters
    ----------
    a_d, b_d : ndarray
        The sampled model (``n x n``, ``n x m``).
    m_d : ndarray
        The sampled stage cost's weight on ``(x, u)`` (``n + m`` square).
    horizon : int
        ``N``, samples in the horizon.
    rates : ndarray
        The rows ``S`` (``r x n``) of the outputs :meth:`stroke_rates` predicts,
        ``S x_k`` [m/s] (the dampers' stroke rates).

    Attributes
    ----------
    a_d, b_d, m_d : ndarray
        As given.
    p : ndarray
        The terminal weight: the discrete Riccati solution (``n x n``).
    gain_matrix : ndarray
        ``K_d`` (``m x n``): the sampled-data LQR, the first move with the boxes inactive.
    solves, iterations, unfinished : int
        Solves so far, OSQP's iterations in them, and the solves it stopped at
        ``max_iter`` (their last iterate, clipped to the bounds, is used).
    """

    def __init__(
        self,
        a_d: npt.NDArray[np.float64],
        b_d: npt.NDArray[np.float64],
        m_d: npt.NDArray[np.float64],
        horizon: int,
        rates: npt.NDArray[np.float64],
    ) -> None:
        import scipy.linalg
        import scipy.sparse

        _require_osqp()
        import osqp

        self.a_d, self.b_d, self.m_d = a_d, b_d, m_d
        nx, nu = b_d.shape
        n = int(horizon)
        self.horizon, self.inputs = n, nu
        q, r, s = m_d[:nx, :nx], m_d[nx:, nx:], m_d[:nx, nx:]
        self.p = scipy.linalg.solve_discrete_are(a_d, b_d, q, r, s=s)
        bp = b_d.T @ self.p
        self.gain_matrix = np.linalg.solve(r + bp @ b_d, bp @ a_d + s.T)
        # x_k = Sx[k] x_0 + Su[k] U, k = 0..N (U: u_0, u_1, ... each m values)
        nv = n * nu
        sx = np.zeros((n + 1, nx, nx))
        su = np.zeros((n + 1, nx, nv))
        sx[0] = np.eye(nx)
        for k in range(n):
            sx[k + 1] = a_d @ sx[k]
            su[k + 1] = a_d @ su[k]
            su[k + 1][:, k * nu : (k + 1) * nu] = b_d
        # J = sum_k (x_k, u_k)^T M_d (x_k, u_k) + x_N^T P x_N = U^T H U + 2 x_0^T F U + c
        h = np.zeros((nv, nv))
        f = np.zeros((nx, nv))
        for k in range(n):
            ek = np.zeros((nu, nv))
            ek[:, k * nu : (k + 1) * nu] = np.eye(nu)
            zu = np.vstack([su[k], ek])  # (x_k, u_k) = Zx x_0 + Zu U
            zx = np.vstack([sx[k], np.zeros((nu, nx))])
            h += zu.T @ m_d @ zu
            f += zx.T @ m_d @ zu
        h += su[n].T @ self.p @ su[n]
        f += sx[n].T @ self.p @ su[n]
        h = 0.5 * (h + h.T) * _FORCE_UNIT**2
        f = f * _FORCE_UNIT
        scale = 1.0 / float(np.mean(np.diag(h)))  # the cost's scale near 1
        self._q_of_x = 2.0 * scale * f.T  # q = G x_0 (N m x n)
        # the rates S x_k at k = 0..N-1: Vx x_0 + Vu U [m/s], U in kN
        sel = np.atleast_2d(np.asarray(rates, dtype=float))
        nr = sel.shape[0]
        self._vx = np.einsum("ij,kjl->kil", sel, sx[:n]).reshape(n * nr, nx)
        self._vu = np.einsum("ij,kjl->kil", sel, su[:n]).reshape(n * nr, nv) * _FORCE_UNIT
        self._solver = osqp.OSQP()
        self._solver.setup(
            scipy.sparse.csc_matrix(np.triu(2.0 * scale * h)),
            np.zeros(nv),
            scipy.sparse.identity(nv, format="csc"),
            np.zeros(nv),
            np.zeros(nv),
            **_SETTINGS,
        )
        self.solves = self.iterations = self.unfinished = 0

    def stroke_rates(self, x: npt.ArrayLike, forces: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The predicted rates ``S x_k`` [m/s] at the horizon's samples ``k = 0..N-1``
        (sample by sample, ``r`` values each) from the state ``x`` and the inputs
        ``forces`` [N] (``N m`` values, sample by sample)."""
        out: npt.NDArray[np.float64] = self._vx @ np.asarray(x, dtype=float)
        out += self._vu @ (np.ravel(np.asarray(forces, dtype=float)) / _FORCE_UNIT)
        return out

    def solve(
        self,
        x: npt.ArrayLike,
        lower: npt.ArrayLike,
        upper: npt.ArrayLike,
        warm: npt.ArrayLike | None = None,
    ) -> npt.NDArray[np.float64]:
        """The optimal inputs [N] over the horizon from state ``x`` (``N m`` values, sample
        by sample), each within its bounds ``lower <= u <= upper`` [N] (numbers or ``N m``
        values).

        ``warm``: inputs [N] to start OSQP from (default: its previous solution). A solve
        OSQP does not finish (``max_iter``) returns its last iterate clipped to the bounds.
        """
        nv = self.horizon * self.inputs
        lo = np.ravel(np.asarray(lower, dtype=float)) / _FORCE_UNIT
        hi = np.ravel(np.asarray(upper, dtype=float)) / _FORCE_UNIT
        if lo.size == 1:
            lo = np.full(nv, float(lo[0]))
        if hi.size == 1:
            hi = np.full(nv, float(hi[0]))
        self._solver.update(q=self._q_of_x @ np.asarray(x, dtype=float), l=lo, u=hi)
        if warm is not None:
            self._solver.warm_start(x=np.ravel(np.asarray(warm, dtype=float)) / _FORCE_UNIT)
        res = self._solver.solve(raise_error=False)
        self.solves += 1
        self.iterations += int(res.info.iter)
        u = res.x
        if res.info.status_val != 1:  # OSQP_SOLVED
            self.unfinished += 1
            if u is None or not np.all(np.isfinite(u)):
                u = np.zeros(nv)
        out: npt.NDArray[np.float64] = np.minimum(np.maximum(u, lo), hi) * _FORCE_UNIT
        return out


class MPCProblem(CondensedMPC):
    """The condensed QP of one quarter car's semi-active MPC, set up once in OSQP.

    Parameters
    ----------
    a, b : ndarray
        The continuous model (4 x 4, 4 x 1) of
        :func:`~mrsuspension.control.literature.quarter_car_model`.
    horizon : int
        ``N``, samples in the horizon (1 to :data:`HORIZON_MAX`).
    sample : float
        ``T_s`` [s], the MPC's sample (the force is held over it).
    w_rattle, w_tire, w_force : float
        The LQ weights of :func:`~mrsuspension.control.literature.lq_gain`.

    Attributes
    ----------
    a_d, b_d : ndarray
        The sampled model (4 x 4, 4 x 1).
    m_d : ndarray
        The sampled stage cost's weight on ``(x, u)`` (5 x 5).
    p : ndarray
        The terminal weight: the discrete Riccati solution (4 x 4).
    gain : ndarray
        ``K_d`` (4,): the sampled-data LQR, the first move with the band inactive.
    solves, iterations, unfinished : int
        As :class:`CondensedMPC`.
    """

    def __init__(
        self,
        a: npt.ArrayLike,
        b: npt.ArrayLike,
        horizon: int,
        sample: float,
        w_rattle: float = LQ_WEIGHTS["w_rattle"],
        w_tire: float = LQ_WEIGHTS["w_tire"],
        w_force: float = LQ_WEIGHTS["w_force"],
    ) -> None:
        a = np.asarray(a, dtype=float).reshape(4, 4)
        b = np.asarray(b, dtype=float).reshape(4, 1)
        self.sample = float(sample)
        # the continuous cost z_s''^2 + w_r x_1^2 + w_t x_3^2 + w_f u^2 on (x, u)
        cd = np.concatenate([a[1], b[1]])
        m = np.outer(cd, cd) + np.diag([w_rattle, 0.0, w_tire, 0.0, w_force])
        a_d, b_d, m_d = _sampled(a, b, m, self.sample)
        # v_d = z_u' - z_s'
        super().__init__(a_d, b_d, m_d, horizon, np.array([[0.0, -1.0, 0.0, 1.0]]))
        self.gain = self.gain_matrix[0]

    def first_move(self, x: npt.ArrayLike, lower: float, upper: float) -> float:
        """The first force [N] of :meth:`solve` with the same bounds at every sample."""
        return float(self.solve(x, lower, upper)[0])


_PROBLEMS: dict[tuple[Any, ...], MPCProblem] = {}


def problem(
    plant: Any,
    horizon: int = 10,
    sample: float = 2e-3,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
) -> MPCProblem:
    """The :class:`MPCProblem` of a quarter car (or a vehicle's corner), ``plant``."""
    a, b, _ = quarter_car_model(plant)
    return _cached(a, b[:, 0], int(horizon), float(sample), w_rattle, w_tire, w_force)


def _cached(
    a: npt.NDArray[np.float64],
    b: npt.NDArray[np.float64],
    horizon: int,
    sample: float,
    w_rattle: float,
    w_tire: float,
    w_force: float,
) -> MPCProblem:
    """One QP per plant and options in this process (the corners of a car with the same
    plant share it; each corner warm-starts it from its own memory)."""
    key = (a.tobytes(), b.tobytes(), horizon, sample, w_rattle, w_tire, w_force)
    got = _PROBLEMS.get(key)
    if got is None:
        if len(_PROBLEMS) >= 64:  # a sweep over options: keep the newest
            _PROBLEMS.clear()
        got = MPCProblem(a, b, horizon, sample, w_rattle, w_tire, w_force)
        _PROBLEMS[key] = got
    return got


# -- the laws ------------------------------------------------------------------------------
_MPC: dict[str, dict[str, Any]] = {
    "horizon": {"unit": "samples", "low": 1.0, "high": float(HORIZON_MAX), "symbol": "N"},
    "sample": {"unit": "s", "low": 1e-4, "high": 0.05, "symbol": "T_s"},
    "w_rattle": {"unit": "1/s^4", "low": 0.0, "high": 1e12, "symbol": "q_x"},
    "w_tire": {"unit": "1/s^4", "low": 0.0, "high": 1e12, "symbol": "q_t"},
    "w_force": {"unit": "1/kg^2", "low": 0.0, "high": 1e3, "low_open": True, "symbol": "r"},
    "c_min": {"unit": "N s/m", "low": 0.0, "high": 1e7, "symbol": "c_min"},
    "c_max": {"unit": "N s/m", "low": 0.0, "high": 1e7, "symbol": "c_max"},
    "A": {"unit": "1/s, 1/s^2", "low": -1e12, "high": 1e12, "symbol": "A"},
    "B": {"unit": "1/kg", "low": -1e6, "high": 1e6, "symbol": "B"},
}
_HILO: dict[str, dict[str, Any]] = {
    "i_min": {"unit": "A", "low": 0.0, "high": 10.0, "symbol": "i_min"},
    "i_max": {"unit": "A", "low": 0.0, "high": 10.0, "symbol": "i_max"},
}
#: the memory: the held force [N], the next solve's time [s], the previous solution [N]
MEMORY = 2 + HORIZON_MAX
_Z44 = tuple((0.0, 0.0, 0.0, 0.0) for _ in range(4))
_Z4 = (0.0, 0.0, 0.0, 0.0)


@functools.cache
def _default_model() -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``A``, ``B`` of the default :class:`~mrsuspension.vehicle.QuarterCar`."""
    from mrsuspension.vehicle import QuarterCar

    a, b, _ = quarter_car_model(QuarterCar())
    return a, b[:, 0]


def _mpc_for_plant(plant: Any, **options: Any) -> dict[str, Any]:
    """The model ``A``, ``B`` (:func:`~mrsuspension.control.literature.quarter_car_model`)
    from the plant where both are zeros (their defaults); checks that OSQP is installed
    (before a run, not in it)."""
    _require_osqp()
    if np.any(np.asarray(options["A"]) != 0.0) or np.any(np.asarray(options["B"]) != 0.0):
        return {}
    a, b, _ = quarter_car_model(plant)
    return {"A": a, "B": b[:, 0]}


def _target(
    x_d: float,
    v_d: float,
    z_s_dot: float,
    z_u_dot: float,
    z_u_ddot: float,
    F_d: float,
    time: float,
    memory: Any,
    o: tuple[float, ...],
    A: Any,
    B: Any,
) -> float:
    """The MPC's force [N] at ``time``: the held one, or a new solve's first force."""
    if time < memory[1]:
        return float(memory[0])
    horizon, sample, w_rattle, w_tire, w_force, c_min, c_max = o
    if not np.any(B):  # not attached to a plant (UserLaw.cost()): the default quarter car
        A, B = _default_model()
    n = int(horizon)
    qp = _cached(A, B, n, sample, w_rattle, w_tire, w_force)
    # the tire deflection from the wheel's row of the model, z_u'' = A_3 x + B_3 F_d
    # (z_r' taken as 0): A[3, 2] = -k_t / m_u
    tire = 0.0
    if A[3, 2] != 0.0:
        tire = (z_u_ddot + A[3, 0] * x_d - A[3, 3] * z_u_dot - B[3] * F_d) / A[3, 2]
    x = np.array([-x_d, z_s_dot, tire, z_u_dot])
    previous = np.asarray(memory[2 : 2 + n])
    shifted = np.empty(n)
    shifted[:-1] = previous[1:]
    shifted[-1] = previous[-1]
    v = qp.stroke_rates(x, shifted)
    v[0] = v_d  # the first sample's band: the measured stroke rate
    a, b = c_min * v, c_max * v
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    u = qp.solve(x, lo, hi, warm=shifted)
    memory[2 : 2 + n] = u
    memory[0] = u[0]
    memory[1] = (math.floor(time / sample + 1e-9) + 1.0) * sample
    return float(u[0])


@law(output="force", numba=False, for_plant=_mpc_for_plant, options=_MPC, memory=MEMORY)
def mpc(
    x_d: float,
    v_d: float,
    z_s_dot: float,
    z_u_dot: float,
    z_u_ddot: float,
    F_d: float,
    time: float,
    memory: Any,
    horizon: float = 10.0,
    sample: float = 2e-3,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
    c_min: float = 2043.0,
    c_max: float = 10613.0,
    A: Any = _Z44,
    B: Any = _Z4,
) -> float:
    """Semi-active MPC (Giorgetti et al. 2006; Canale et al. 2006): every ``T_s`` the first
    force of the LQ cost's ``N``-sample QP within the viscous band ``[c_min, c_max] v_d``
    (the module docstring), held until the next solve; a target force through the
    inverse model.

    ``A``, ``B``: the plant's model (``for_plant``: each corner its own) unless given
    (zeros, the law not attached to a plant, as in
    :meth:`~mrsuspension.control.user.UserLaw.cost`: the default
    :class:`~mrsuspension.vehicle.QuarterCar`'s). Defaults: ``N`` = 10, ``T_s`` = 2 ms
    (a 20 ms horizon; the terminal cost carries the rest), the LQ weights of
    :data:`~mrsuspension.control.literature.LQ_WEIGHTS`, the band of
    :func:`~mrsuspension.control.literature.pdd`.
    """
    o = (horizon, sample, w_rattle, w_tire, w_force, c_min, c_max)
    return _target(x_d, v_d, z_s_dot, z_u_dot, z_u_ddot, F_d, time, memory, o, A, B)


@law(
    numba=False, for_plant=_mpc_for_plant, options={**_MPC, **_HILO}, memory=MEMORY
)  # fmt: skip
def mpc_hilo(
    x_d: float,
    v_d: float,
    z_s_dot: float,
    z_u_dot: float,
    z_u_ddot: float,
    F_d: float,
    time: float,
    memory: Any,
    horizon: float = 10.0,
    sample: float = 2e-3,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
    c_min: float = 2043.0,
    c_max: float = 10613.0,
    A: Any = _Z44,
    B: Any = _Z4,
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """:func:`mpc`'s force as two currents: ``i_max`` when the target ``F*`` and ``v_d``
    agree in sign and ``|F*| > |F_d|`` (more force of the right sign is wanted), else
    ``i_min`` (the rule of :func:`~mrsuspension.control.literature.clipped_lq`, checked at
    every step against the held target)."""
    o = (horizon, sample, w_rattle, w_tire, w_force, c_min, c_max)
    f = _target(x_d, v_d, z_s_dot, z_u_dot, z_u_ddot, F_d, time, memory, o, A, B)
    return i_max if f * v_d > 0.0 and abs(f) > abs(F_d) else i_min


def _validate_mpc(self: Any) -> None:
    """The declared ranges, then: a whole ``N``, ``c_min <= c_max``."""
    Controller._validate(self)
    if self.horizon != math.floor(self.horizon):
        raise ValidationError(
            f"horizon N must be a whole number of samples in [1, {HORIZON_MAX}]; "
            f"got {self.horizon:g}"
        )
    if self.c_min > self.c_max:
        raise ValidationError(
            f"c_min must be <= c_max (the band's damping at i_min and i_max) [N s/m]; "
            f"got c_min {self.c_min:g}, c_max {self.c_max:g}"
        )


#: the laws by registry name
LAWS = {"mpc": mpc, "mpc-hilo": mpc_hilo}
for _name, _cls in LAWS.items():
    _cls.law = _name
    _cls._validate = _validate_mpc
