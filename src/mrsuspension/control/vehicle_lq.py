"""Whole-vehicle LQ and LQG laws for the half and full car (issue 29).

The per-corner laws of :mod:`~mrsuspension.control.literature` (``clipped-lq``,
``lq-active``, ``clipped-lqg``, ``lqg-active``) give every corner its own quarter car's
LQR. The laws here solve one LQR for the whole vehicle: the corners' damper forces from
the body's heave, pitch and roll and every wheel, coupled through the body.

**Model.** The linear half or full car of
:meth:`~mrsuspension.vehicle.body.VehicleBody.linear_matrices` (no damping at the dampers:
their forces are the input ``u``, one per corner, up on the body and down on the wheel;
springs, anti-roll bars, tires and the tire damping in it). The design runs in its own
coordinates ``q = (heave, pitch[, roll], z_u,i)`` and ``q'`` with the road at rest
(:func:`lq_design`). The law then reads the same gain in the relative state the sensors
give (:func:`relative_model`)::

    x = (e_1..e_n, v_z, q, p, d_1..d_n, z_u,1'..z_u,n')

``e_i = z_s,i - z_u,i`` (the body over the wheel at corner ``i``: minus the stroke), the
body's heave velocity and pitch and roll rates (``p`` = 0 on the half car: the layout is
the same for both cars), the tire deflections ``d_i = z_u,i - z_r,i`` and the wheels'
velocities; the disturbance is the road's velocity at every wheel. (Absolute heave, pitch
and roll are not states of the law: no sensor gives them, and under a road-velocity
disturbance they are integrators no damper force can hold, so the relative state is the
one the per-corner law uses, ``literature.quarter_car_model``, at every corner.) The
full car has one position more than velocities in this state: the road's twist (warp)
``w . (e + d)``, with ``w . T = 0``, which moves only with the road (no force changes
it); the gain is mapped with the least-squares inverse, so that the law does not respond
to it (zero gain on the warp direction).

**Cost.** ``integral(sum_i (z_s,i''^2 + w_rattle e_i^2 + w_tire d_i^2 + w_force u_i^2)) dt``:
the body's acceleration **at the corners** (not Wk-weighted), the rattle and the tire
deflection at every corner, the force: the sum of the quarter-car costs of ``lq_gain``
with the same default weights (:data:`~mrsuspension.control.literature.LQ_WEIGHTS`), so
the two are comparable, and on a decoupled half car (``HalfCar.from_quarter_car``) the
whole-vehicle gain is the quarter-car gain at every corner. (Heave, pitch and roll
accelerations would need weights in other units, m/s^2 against rad/s^2, with no
counterpart in the quarter-car cost.) Solved by :func:`scipy.linalg.solve_continuous_are`
as ``lq_gain``.

**Laws.** Each step the desired corner forces ``F = -K x_seen``: the strokes and wheel
velocities as sensed (the stroke sensor where ``[sensing]`` has one) and the body rates
as modal skyhook sees them (true, or from the corners' velocity estimates through the
distribution matrix). ``vehicle-lq`` drops the tire deflection's gain (no sensor, as
``clipped-lq``) and switches each corner hi-lo by Dyke et al.'s clipped-optimal rule, as
``clipped-lq``: high when ``(F_i - F_d) F_d > 0``, the damper's force ``F_d`` (the load
cell, the previous step's) below the desired one in magnitude and of its sign (the rule
"high when ``F_i v_d > 0``" of modal skyhook would switch high whenever the force's sign
is achievable: on ISO C it drew 0.30 A mean and rode worse than passive 0 A);
``vehicle-lq-active`` applies ``F`` by an ideal actuator at every corner (a reference,
and the closed-form check: the linear car then responds as ``A - B K``). ``vehicle-lqg``
and ``vehicle-lqg-active``: the full-state gain (tire deflection too) on a Kalman-Bucy
estimate from every corner's body and wheel accelerometers and stroke sensor, with the
dampers' forces (load cells) as the input (:func:`vehicle_kalman_gain`; the per-corner
``kalman_gain`` on the vehicle), integrated by Euler at every step. ``vehicle-lq-force``,
``vehicle-lqg-force`` (and ``vehicle-mpc-force`` below): the same forces tracked through
every corner's inverse damper model, as ``lq-force`` (``control.kernel.track_force``: the
hysteretic inverse at the stroke rate the law sees, the current clipped to
``[low_current, high_current]``; the ``wang-symmetric`` damper at every corner). The
output is one flag in the parameters (``LP_OUTPUT``: ``OUT_HILO``, ``OUT_ACTIVE``,
``OUT_FORCE``).

``vehicle-mpc`` (:class:`VehicleMPC`): the per-corner ``mpc`` over the whole car. Every
``T_s`` one QP (:class:`VehicleMPCProblem`: this module's design model and LQ cost,
sampled, ``N`` samples, a Riccati terminal cost, one force per corner per sample in the
viscous band at its predicted stroke rate) solved by OSQP in Python through a ctypes
entry the compiled step calls (:func:`mpc_forces`), the first forces held until the next
solve, hi-lo by Dyke's rule as ``vehicle-lq`` (``vehicle-mpc-force``: through the inverse
model at every step; ``vehicle-mpc-active``: by an ideal actuator).

On the quarter car these laws are the per-corner ones: ``clipped-lq``, ``lq-active``,
``clipped-lqg``, ``lqg-active``, ``mpc-hilo``, ``lq-force``, ``mpc``
(:meth:`VehicleLQ.for_vehicle` refuses a quarter car, naming its law).

Examples
--------
>>> from mrsuspension.vehicle import FullCar, HalfCar
>>> law = VehicleLQ().for_vehicle(FullCar())
>>> law.gain.shape  # 4 corners x (4 e, 3 body rates, 4 d, 4 wheel velocities)
(4, 15)
>>> VehicleLQG().for_vehicle(HalfCar()).params().size  # 7 + K 18 + A 81 + B 18 + L, C 54 + D 12
244
"""

from __future__ import annotations

import ctypes
import math
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.control import kernel as CK
from mrsuspension.control.literature import LQ_WEIGHTS, LQG_NOISE
from mrsuspension.control.modal import (
    LAW_LQ,
    LAW_LQG,
    LAW_MPC,
    MP_IHIGH,
    MP_ILOW,
    MP_SIZE,
    VehicleLaw,
)
from mrsuspension.errors import ValidationError, check_range

__all__ = [
    "LP_K",
    "LP_NX",
    "LP_OUTPUT",
    "MB_DX",
    "MB_HOLD",
    "MB_PLAN",
    "MB_ROWS",
    "MB_U",
    "MB_VD",
    "MB_X",
    "MB_Y",
    "NB",
    "OUT_ACTIVE",
    "OUT_FORCE",
    "OUT_HILO",
    "LQDesign",
    "VehicleLQ",
    "VehicleLQActive",
    "VehicleLQForce",
    "VehicleLQG",
    "VehicleLQGActive",
    "VehicleLQGForce",
    "VehicleMPC",
    "VehicleMPCActive",
    "VehicleMPCForce",
    "VehicleMPCProblem",
    "lq_design",
    "lq_forces",
    "mpc_forces",
    "relative_model",
    "vehicle_kalman_gain",
    "vehicle_lq_gain",
]

FloatArray = npt.NDArray[np.float64]

#: body rates in the law's state: heave velocity, pitch and roll rates (roll 0 on the
#: half car)
NB = 3
# the kernel parameters after the MP_* layout (control.modal): output (OUT_*), the state
# size nx, then K (corners x nx, row-major) and, for the LQG, A (nx x nx), B (nx x
# corners), L (nx x 3 corners), C (3 corners x nx), D (3 corners x corners)
LP_OUTPUT, LP_NX, LP_K = MP_SIZE, MP_SIZE + 1, MP_SIZE + 2
#: the output (``params()[LP_OUTPUT]``): hi-lo by Dyke's rule, an ideal actuator (the
#: ``-active`` laws), or the force tracked through every corner's inverse model (the
#: ``-force`` laws: a continuous current)
OUT_HILO, OUT_ACTIVE, OUT_FORCE = 0.0, 1.0, 2.0
#: the vehicle-law buffer's rows (``mbuf``) the LQ laws use beside the 4 of control.modal:
#: the state the gain multiplies (LQ: as seen; LQG: the estimate), the measurements (then
#: the innovation), the dampers' forces, the estimate's rates
MB_X, MB_Y, MB_U, MB_DX = 4, 5, 6, 7
MB_ROWS = 8
#: ``vehicle-mpc``'s use of the buffer (:func:`mpc_forces`): ``mbuf[MB_X, nx]`` the time
#: [s]; ``mbuf[MB_HOLD, 0]`` the next solve's time [s]; ``mbuf[MB_VD]`` the corners' stroke
#: rates as seen [m/s]; ``mbuf[MB_PLAN + k]`` the previous solution's forces [N] at
#: sample ``k`` (``N`` rows)
MB_HOLD, MB_VD, MB_PLAN = MB_Y, MB_U, MB_ROWS


# --- models ----------------------------------------------------------------------------


def _body_and_wheels(vehicle: Any) -> tuple[Any, FloatArray, FloatArray, int, int]:
    """``(linear model, T, D, nb, n)``: ``z_s = T q_b``, ``x_d = D q``."""
    lin = vehicle.linear_matrices(0.0)
    t = vehicle.body_transform()
    n, nb = t.shape
    d = np.hstack([-t, np.eye(n)])
    return lin, t, d, nb, n


def relative_model(vehicle: Any) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """``(A, B, E, T)`` of the vehicle in the law's relative state ``x' = A x + B u + E z_r'``.

    ``x = (e_i, v_z, q, p, d_i, z_u,i')`` (module docstring; ``3 n + 3`` values for ``n``
    corners, the roll rate's row and column zero on the half car), ``u`` the corners'
    damper forces (up on the body) [N], ``z_r'`` every wheel's road velocity [m/s];
    ``T`` (corners x 3) the body's motion at the corners, ``z_s,i' = T_i (v_z, q, p)``.
    Built from :meth:`~mrsuspension.vehicle.body.VehicleBody.linear_matrices`: with
    ``x_d = D q``, ``K = D^T S D + K_tire``, the forces on ``q`` are ``D^T S e - K_road d
    - C q' + C_road z_r' - D^T u``.

    Examples
    --------
    >>> from mrsuspension.vehicle import HalfCar
    >>> a, b, e, t = relative_model(HalfCar())
    >>> a.shape, b.shape, e.shape, t.shape
    ((9, 9), (9, 2), (9, 2), (2, 3))
    """
    lin, t, d, nb, n = _body_and_wheels(vehicle)
    minv = np.linalg.inv(lin.M)
    # D^T S from K - K_tire = D^T S D (D has full row rank)
    k_susp = lin.K - np.pad(np.diag(vehicle.tire_stiffnesses), ((nb, 0), (nb, 0)))
    dts = k_susp @ d.T @ np.linalg.inv(d @ d.T)
    nx = 3 * n + NB
    ie = np.arange(n)  # e
    iv = np.concatenate([n + np.arange(nb), n + NB + n + np.arange(n)])  # q' = (v_b, v_u)
    idd = n + NB + np.arange(n)  # d
    a = np.zeros((nx, nx))
    b = np.zeros((nx, n))
    e = np.zeros((nx, n))
    a[np.ix_(ie, iv)] = -d  # e' = z_s' - z_u' = -x_d'
    a[np.ix_(idd, iv[nb:])] = np.eye(n)  # d' = z_u' - z_r'
    e[idd] = -np.eye(n)
    a[np.ix_(iv, ie)] = minv @ dts
    a[np.ix_(iv, idd)] = -minv @ lin.K_road
    a[np.ix_(iv, iv)] = -minv @ lin.C
    b[iv] = -minv @ d.T
    e[iv] = minv @ lin.C_road
    t3 = np.zeros((n, NB))
    t3[:, :nb] = t
    return a, b, e, t3


class LQDesign(NamedTuple):
    """The whole-vehicle LQR (:func:`lq_design`): the problem in the design coordinates
    ``(q, q')`` (road at rest), its solution, and the gain in the law's state."""

    #: ``x_a' = A x_a + B u``, ``x_a = (q, q')``
    A: FloatArray
    B: FloatArray
    #: the cost ``x^T Q x + 2 x^T N u + u^T R u``
    Q: FloatArray
    R: FloatArray
    N: FloatArray
    #: the Riccati solution and the gain ``u = -K_a x_a``
    P: FloatArray
    K_design: FloatArray
    #: ``x = H x_a`` (the law's state with the road at rest) and the gain ``K = K_a H^+``
    H: FloatArray
    K: FloatArray


def lq_design(vehicle: Any, w_rattle: float, w_tire: float, w_force: float) -> LQDesign:
    """The whole-vehicle LQR of ``vehicle`` (module docstring: model, cost, mapping).

    In ``x_a = (q, q')``, ``q = (heave, pitch[, roll], z_u,i)`` of
    :meth:`~mrsuspension.vehicle.body.VehicleBody.linear_matrices` with the road at rest:
    the corners' body accelerations ``T q_b'' = C x_a + D u`` give ``Q = C^T C +
    w_rattle (D_x^T D_x) + w_tire (S^T S)``, ``N = C^T D``, ``R = D^T D + w_force I``
    (``x_d = D_x q``, ``z_u = S q``), solved by :func:`scipy.linalg.solve_continuous_are`.
    The gain in the law's state ``x`` (:func:`relative_model`) is ``K = K_a H^+`` with
    ``x = H x_a``: exact on the half car (``H`` square), the least-squares inverse on the
    full car (no gain on the road's twist).

    Examples
    --------
    >>> from mrsuspension.vehicle import HalfCar
    >>> d = lq_design(HalfCar(), **LQ_WEIGHTS)
    >>> d.K_design.shape, d.K.shape
    ((2, 8), (2, 9))
    """
    import scipy.linalg  # (not at import: the CLI starts without scipy)

    lin, t, dx, nb, n = _body_and_wheels(vehicle)
    nq = nb + n
    minv = np.linalg.inv(lin.M)
    a = np.zeros((2 * nq, 2 * nq))
    a[:nq, nq:] = np.eye(nq)
    a[nq:, :nq] = -minv @ lin.K
    a[nq:, nq:] = -minv @ lin.C
    b = np.zeros((2 * nq, n))
    b[nq:] = -minv @ dx.T
    c = t @ a[nq : nq + nb]  # the corners' body accelerations
    dd = t @ b[nq : nq + nb]
    sel = np.hstack([np.zeros((n, nb)), np.eye(n)])  # z_u = tire deflection (road at rest)
    q = c.T @ c
    q[:nq, :nq] += w_rattle * dx.T @ dx + w_tire * sel.T @ sel
    r = dd.T @ dd + w_force * np.eye(n)
    nn = c.T @ dd
    p = scipy.linalg.solve_continuous_are(a, b, q, r, s=nn)
    k_a = np.linalg.solve(r, b.T @ p + nn.T)
    # x = H x_a: e = -x_d, body rates, d = z_u, wheel velocities (the law's layout)
    nx = 3 * n + NB
    h = np.zeros((nx, 2 * nq))
    h[:n, :nq] = -dx
    h[n : n + nb, nq : nq + nb] = np.eye(nb)
    h[n + NB : n + NB + n, :nq] = sel
    h[n + NB + n :, nq + nb :] = np.eye(n)
    k = k_a @ np.linalg.pinv(h)
    k[:, n + nb : n + NB] = 0.0  # the half car's roll rate: none
    return LQDesign(a, b, q, r, nn, p, k_a, h, k)


def vehicle_lq_gain(
    vehicle: Any,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
) -> FloatArray:
    """The whole-vehicle LQ gain ``K`` (corners x ``3 n + 3``) in the law's state:
    :func:`lq_design`'s ``K``.

    Examples
    --------
    >>> from mrsuspension.vehicle import HalfCar
    >>> k = vehicle_lq_gain(HalfCar())
    >>> bool(k[0, 2] > 0.0)  # a positive gain on the heave velocity: skyhook-like
    True
    """
    return lq_design(vehicle, w_rattle, w_tire, w_force).K


def _measurements(a: FloatArray, b: FloatArray, t3: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(C, D)`` of ``y = (z_s,i'', z_u,i'', x_d,i) = C x + D u`` (3 n rows)."""
    n = t3.shape[0]
    vb = slice(n, n + NB)
    vu = slice(2 * n + NB, 3 * n + NB)
    c = np.vstack([t3 @ a[vb], a[vu], np.hstack([-np.eye(n), np.zeros((n, 2 * n + NB))])])
    d = np.vstack([t3 @ b[vb], b[vu], np.zeros((n, n))])
    return c, d


def vehicle_kalman_gain(
    vehicle: Any,
    road_intensity: float = LQG_NOISE["road_intensity"],
    noise_acc: float = LQG_NOISE["noise_acc"],
    noise_stroke: float = LQG_NOISE["noise_stroke"],
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(L, C, D)``: the steady Kalman-Bucy gain of :func:`relative_model` measured by
    every corner's body and wheel accelerometers and stroke sensor, and the measurement
    model ``y = (z_s,i'', z_u,i'', x_d,i) = C x + D u``.

    As :func:`~mrsuspension.control.literature.kalman_gain` at every corner: the road's
    velocity at every wheel white and independent (intensity ``road_intensity``),
    measurement noise ``noise_acc`` (both accelerometers) and ``noise_stroke``; the
    roll-rate state of the half car (no roll) is left out of the solve.

    Examples
    --------
    >>> from mrsuspension.vehicle import FullCar
    >>> gain, c, d = vehicle_kalman_gain(FullCar())
    >>> gain.shape, c.shape, d.shape
    ((15, 12), (12, 15), (12, 4))
    """
    import scipy.linalg  # (not at import: the CLI starts without scipy)

    a, b, e, t3 = relative_model(vehicle)
    c, d = _measurements(a, b, t3)
    n = t3.shape[0]
    keep = np.ones(a.shape[0], dtype=bool)
    if not np.any(t3[:, 2]):  # no roll: its state is neither driven nor seen
        keep[n + 2] = False
    ak, ck, ek = a[np.ix_(keep, keep)], c[:, keep], e[keep]
    v = np.diag([noise_acc] * (2 * n) + [noise_stroke] * n)
    p = scipy.linalg.solve_continuous_are(ak.T, ck.T, road_intensity * (ek @ ek.T), v)
    gain = np.zeros((a.shape[0], 3 * n))
    gain[keep] = p @ ck.T @ np.linalg.inv(v)
    return gain, c, d


# --- the laws ------------------------------------------------------------------------


def _quarter_car_refused(law: str, per_corner: str) -> ValidationError:
    return ValidationError(
        f"law {law!r} drives a half or full car (its body's heave, pitch and roll); on the "
        f"quarter car it is the per-corner law {per_corner!r}"
    )


@dataclass(frozen=True)
class VehicleLQ(VehicleLaw):
    """Whole-vehicle clipped LQ: ``F = -K x_seen`` (tire deflection's gain dropped), hi-lo
    per corner (high when ``(F_i - F_d) F_d > 0``, Dyke et al.'s rule).

    Parameters
    ----------
    rattle_weight, tire_weight, force_weight : float
        The cost's weights per corner (module docstring): rattle [1/s^4] and tire
        deflection [1/s^4] (>= 0), force [1/kg^2] (> 0); defaults ``w_rattle``, ``w_tire``,
        ``w_force`` of :data:`~mrsuspension.control.literature.LQ_WEIGHTS` (the names
        differ from the per-corner laws' options: one field per name on the monitor's
        page).
    low_current, high_current : float
        Currents [A] as :class:`~mrsuspension.control.modal.ModalSkyhook` (0 and 0.5 A).

    Notes
    -----
    :meth:`for_vehicle` solves the gain for the car it drives (:attr:`gain`, not an
    option); :meth:`params` needs it.

    Examples
    --------
    >>> VehicleLQ.options()
    ('rattle_weight', 'tire_weight', 'force_weight', 'low_current', 'high_current')
    >>> VehicleLQ(force_weight=0.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: force_weight must be in (0, 1000] 1/kg^2; got 0 1/kg^2
    """

    law: ClassVar[str] = "vehicle-lq"
    kernel_code: ClassVar[int] = LAW_LQ
    uses_body_rates: ClassVar[bool] = True
    #: an ideal actuator at every corner instead of the damper (the ``-active`` laws)
    active: ClassVar[bool] = False
    #: the quarter car's per-corner law of the same kind
    per_corner: ClassVar[str] = "clipped-lq"

    rattle_weight: float = LQ_WEIGHTS["w_rattle"]
    tire_weight: float = LQ_WEIGHTS["w_tire"]
    force_weight: float = LQ_WEIGHTS["w_force"]
    low_current: float = 0.0
    high_current: float = 0.5

    def __post_init__(self) -> None:
        check_range("rattle_weight", self.rattle_weight, 0.0, 1e12, unit="1/s^4")
        check_range("tire_weight", self.tire_weight, 0.0, 1e12, unit="1/s^4")
        check_range("force_weight", self.force_weight, 0.0, 1e3, unit="1/kg^2", low_inclusive=False)
        check_range("low_current", self.low_current, 0.0, None, unit="A")
        check_range("high_current", self.high_current, float(self.low_current), None, unit="A")
        self._check_noise()

    def _check_noise(self) -> None:
        """(The LQG's noise intensities.)"""

    @property
    def gain(self) -> FloatArray:
        """The applied gain ``K`` (corners x ``3 n + 3``; :meth:`for_vehicle` sets it)."""
        k = self.__dict__.get("_gain")
        if k is None:
            raise ValidationError(
                f"law {self.law!r} has no gain yet: attach it to a half or full car "
                "(for_vehicle) for its Riccati solve"
            )
        return np.asarray(k)

    def for_vehicle(self, vehicle: Any) -> VehicleLQ:
        """This law with its gain for ``vehicle`` (a half or full car)."""
        if not hasattr(vehicle, "body_transform"):
            raise _quarter_car_refused(self.law, self.per_corner)
        out = type(self)(**{k: getattr(self, k) for k in self.options()})
        for key, value in out._design(vehicle).items():
            object.__setattr__(out, key, value)
        return out

    def _design(self, vehicle: Any) -> dict[str, FloatArray]:
        k = vehicle_lq_gain(vehicle, self.rattle_weight, self.tire_weight, self.force_weight)
        n = k.shape[0]
        k[:, n + NB : 2 * n + NB] = 0.0  # the tire deflection is not measured
        return {"_gain": k}

    def state_size(self) -> int:
        """Values of the law's state in the kernel (``nx = 3 n + 3``)."""
        return int(self.gain.shape[1])

    def buffer_shape(self, corners: int) -> tuple[int, int]:
        """The shape of the vehicle kernel's law buffer (``mbuf``) for this law."""
        return MB_ROWS, max(corners, self.state_size())

    def _tail(self) -> list[FloatArray]:
        return [self.gain]

    def params(self) -> FloatArray:
        """The kernel parameter vector: the ``MP_*`` layout (currents), then ``LP_*``.

        Examples
        --------
        >>> from mrsuspension.vehicle import HalfCar
        >>> p = VehicleLQ().for_vehicle(HalfCar()).params()
        >>> p.size, float(p[LP_NX])  # 5 + 2 + 2 x 9
        (25, 9.0)
        """
        head = np.zeros(LP_K)
        head[MP_ILOW], head[MP_IHIGH] = self.low_current, self.high_current
        head[LP_OUTPUT] = (
            OUT_ACTIVE if self.active else OUT_FORCE if self.needs_inverse else OUT_HILO
        )
        head[LP_NX] = self.state_size()
        return np.concatenate([head, *(np.ravel(m) for m in self._tail())])


@dataclass(frozen=True)
class VehicleLQActive(VehicleLQ):
    """:class:`VehicleLQ`'s force ``F = -K x_seen`` applied by an ideal actuator at every
    corner (a reference, not a damper; no current): the linear car responds as ``A - B
    K``.

    Examples
    --------
    >>> VehicleLQActive().law
    'vehicle-lq-active'
    """

    law: ClassVar[str] = "vehicle-lq-active"
    active: ClassVar[bool] = True
    per_corner: ClassVar[str] = "lq-active"


@dataclass(frozen=True)
class VehicleLQForce(VehicleLQ):
    """:class:`VehicleLQ`'s force ``F = -K x_seen`` tracked through every corner's inverse
    damper model, as the per-corner ``lq-force``: the continuous current at which the
    corner's damper gives ``F_i`` at its stroke rate (the hysteretic inverse, the branch
    from the sign of the previous step's damper acceleration), clipped to
    ``[low_current, high_current]``; needs the ``wang-symmetric`` damper at every corner.

    Examples
    --------
    >>> VehicleLQForce().law, VehicleLQForce.per_corner, VehicleLQForce.needs_inverse
    ('vehicle-lq-force', 'lq-force', True)
    """

    law: ClassVar[str] = "vehicle-lq-force"
    needs_inverse: ClassVar[bool] = True
    per_corner: ClassVar[str] = "lq-force"


@dataclass(frozen=True)
class VehicleLQG(VehicleLQ):
    """Whole-vehicle clipped LQG: the full-state gain (tire deflection too) on a
    Kalman-Bucy estimate from every corner's body and wheel accelerometers and stroke
    sensor, the dampers' forces as the input; hi-lo per corner as :class:`VehicleLQ`.

    Parameters
    ----------
    rattle_weight, tire_weight, force_weight, low_current, high_current
        As :class:`VehicleLQ`.
    road_noise, accelerometer_noise, stroke_sensor_noise : float
        The road velocity's intensity [m^2/s] and the accelerometers' [(m/s^2)^2 s] and
        stroke sensors' [m^2 s] noise intensities (> 0; defaults ``road_intensity``,
        ``noise_acc``, ``noise_stroke`` of :data:`~mrsuspension.control.literature.LQG_NOISE`).

    Examples
    --------
    >>> VehicleLQG(accelerometer_noise=-1.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: accelerometer_noise must be in (0, 1e+06] (m/s^2)^2 s; got -1 (m/s^2)^2 s
    """

    law: ClassVar[str] = "vehicle-lqg"
    kernel_code: ClassVar[int] = LAW_LQG
    per_corner: ClassVar[str] = "clipped-lqg"

    road_noise: float = LQG_NOISE["road_intensity"]
    accelerometer_noise: float = LQG_NOISE["noise_acc"]
    stroke_sensor_noise: float = LQG_NOISE["noise_stroke"]

    def _check_noise(self) -> None:
        check_range("road_noise", self.road_noise, 0.0, 1.0, unit="m^2/s",
                    low_inclusive=False)  # fmt: skip
        check_range("accelerometer_noise", self.accelerometer_noise, 0.0, 1e6, unit="(m/s^2)^2 s",
                    low_inclusive=False)  # fmt: skip
        check_range("stroke_sensor_noise", self.stroke_sensor_noise, 0.0, 1.0, unit="m^2 s",
                    low_inclusive=False)  # fmt: skip

    def _design(self, vehicle: Any) -> dict[str, FloatArray]:
        k = vehicle_lq_gain(vehicle, self.rattle_weight, self.tire_weight, self.force_weight)
        a, b, _, _ = relative_model(vehicle)
        gain, c, d = vehicle_kalman_gain(
            vehicle, self.road_noise, self.accelerometer_noise, self.stroke_sensor_noise
        )
        return {
            "_gain": k,
            "_model": np.hstack([a, b]),
            "_kalman": gain,
            "_sensors": np.hstack([c, d]),
        }

    @property
    def estimator(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        """``(A, B, L, C, D)`` of the estimate (:func:`relative_model`,
        :func:`vehicle_kalman_gain`)."""
        self.gain  # noqa: B018 (raises without a vehicle)
        nx = self.state_size()
        model, sensors = self.__dict__["_model"], self.__dict__["_sensors"]
        return (model[:, :nx], model[:, nx:], self.__dict__["_kalman"], sensors[:, :nx],
                sensors[:, nx:])  # fmt: skip

    def _tail(self) -> list[FloatArray]:
        return [self.gain, *self.estimator]


@dataclass(frozen=True)
class VehicleLQGActive(VehicleLQG):
    """:class:`VehicleLQG`'s force ``-K x_hat`` by an ideal actuator at every corner (a
    reference, and the check that the estimate converges).

    Examples
    --------
    >>> VehicleLQGActive().law
    'vehicle-lqg-active'
    """

    law: ClassVar[str] = "vehicle-lqg-active"
    active: ClassVar[bool] = True
    per_corner: ClassVar[str] = "lqg-active"


@dataclass(frozen=True)
class VehicleLQGForce(VehicleLQG):
    """:class:`VehicleLQG`'s force ``-K x_hat`` tracked through every corner's inverse
    damper model, as :class:`VehicleLQForce` (the per-corner laws have no LQG through the
    inverse: ``per_corner`` names ``lq-force``).

    Examples
    --------
    >>> VehicleLQGForce().law, VehicleLQGForce.per_corner
    ('vehicle-lqg-force', 'lq-force')
    """

    law: ClassVar[str] = "vehicle-lqg-force"
    needs_inverse: ClassVar[bool] = True
    per_corner: ClassVar[str] = "lq-force"


class VehicleMPCProblem:
    """The whole-vehicle semi-active MPC's QP in this process, and its entry.

    The model is :func:`lq_design`'s ``(A, B)`` in ``x_a = (q, q')`` (the relative model
    of :func:`relative_model` on the states it can reach, ``A H = H A_a``, ``B = H B_a``;
    the state the law reads is mapped by ``x_a = H^+ x`` as the LQ law's gain, so the twist
    of the road gets no response), zero-order-hold sampled at ``T_s`` with the LQ cost
    ``[[Q, N], [N^T, R]]`` integrated exactly over the sample (Van Loan), the terminal
    weight the discrete Riccati solution: :class:`~mrsuspension.control.mpc.CondensedMPC`
    with one force per corner per sample. The band on each force is the viscous band of
    :mod:`~mrsuspension.control.mpc` at the corner's stroke rate (``v_d = x_d' = D_x
    q'``): measured at the first sample, predicted at the later ones from the state and
    the previous solution shifted by a sample.

    ``address`` is a C entry ``double f(double *buffer, double *forces, int64 corners)``
    (a ctypes callback into Python, as a user law's Python path,
    :mod:`~mrsuspension.control.user`) that :func:`mpc_forces` calls with the law's
    buffer from row ``MB_X`` on and the forces' row.

    Parameters
    ----------
    design : LQDesign
        :func:`lq_design` of the car.
    horizon : int
        ``N`` [samples].
    sample : float
        ``T_s`` [s].
    c_min, c_max : float
        The band's damping [N s/m] (``c_min v_d <= F <= c_max v_d`` for ``v_d > 0``).
    law : str
        The law's name (for a failure's report).

    Attributes
    ----------
    qp : CondensedMPC
        The QP in ``x_a`` (``qp.gain_matrix``: the sampled-data LQR ``K_d`` in ``x_a``).
    gain : ndarray
        ``K_d H^+`` (corners x ``nx``): the first move with the band inactive.
    """

    def __init__(
        self, design: LQDesign, horizon: int, sample: float, c_min: float, c_max: float,
        law: str = "vehicle-mpc",
    ) -> None:  # fmt: skip
        from mrsuspension.control import mpc
        from mrsuspension.control.user import _CTYPES_ENTRY, LawEntry, _checked

        n = design.B.shape[1]
        nq = design.A.shape[0] // 2
        self.corners, self.horizon, self.sample = n, int(horizon), float(sample)
        self.c_min, self.c_max, self.law = float(c_min), float(c_max), law
        self.nx = design.H.shape[0]
        cost = np.block([[design.Q, design.N], [design.N.T, design.R]])
        a_d, b_d, m_d = mpc._sampled(design.A, design.B, cost, self.sample)
        # the strokes x_d = D_x q: their rates D_x q' (D_x = -H's first n rows)
        rates = np.hstack([np.zeros((n, nq)), -design.H[:n, :nq]])
        self.qp = mpc.CondensedMPC(a_d, b_d, m_d, self.horizon, rates)
        self.h_pinv = np.linalg.pinv(design.H)
        self.gain = self.qp.gain_matrix @ self.h_pinv
        self._entry = _CTYPES_ENTRY(self._call)
        self.entry = _checked(
            LawEntry(int(ctypes.cast(self._entry, ctypes.c_void_p).value or 0), "python", 0.0,
                     "", self._entry)
        )  # fmt: skip
        self.address = self.entry.address

    def band(
        self, x: npt.ArrayLike, stroke_rates: npt.ArrayLike, previous: npt.ArrayLike
    ) -> tuple[FloatArray, FloatArray]:
        """``(lower, upper)`` [N] (``N x n``): the viscous band at every sample and corner,
        ``v_d`` the measured ``stroke_rates`` at the first sample and predicted from ``x``
        and ``previous`` (``N x n`` forces [N], already shifted) at the later ones."""
        xa = self.h_pinv @ np.asarray(x, dtype=float)
        v = self.qp.stroke_rates(xa, previous).reshape(self.horizon, self.corners)
        v[0] = stroke_rates
        a, b = self.c_min * v, self.c_max * v
        return np.minimum(a, b), np.maximum(a, b)

    def solve(
        self,
        x: npt.ArrayLike,
        lower: npt.ArrayLike,
        upper: npt.ArrayLike,
        warm: npt.ArrayLike | None = None,
    ) -> FloatArray:
        """The optimal forces [N] (``N x n``: sample by sample, corner by corner) from the
        law's state ``x`` (``nx`` values, mapped by ``H^+``) within ``lower <= F <= upper``
        [N] (numbers or ``N x n``)."""
        xa = self.h_pinv @ np.asarray(x, dtype=float)
        u = self.qp.solve(xa, lower, upper, warm=warm)
        return u.reshape(self.horizon, self.corners)

    def step(self, x: npt.ArrayLike, stroke_rates: npt.ArrayLike, plan: FloatArray) -> FloatArray:
        """One solve from ``x`` with the band at ``stroke_rates`` [m/s]; ``plan`` (``N x
        n``, the previous solution [N]) is replaced by the new one; returns its first
        forces [N]."""
        shifted = np.empty_like(plan)
        shifted[:-1] = plan[1:]
        shifted[-1] = plan[-1]
        lower, upper = self.band(x, stroke_rates, shifted)
        plan[:] = self.solve(x, lower, upper, warm=shifted)
        return plan[0]

    def _call(self, s: Any, o: Any, n: int) -> float:
        """The entry: read the buffer (rows ``MB_X`` on), solve, write the forces and the
        next solve's time. An exception is kept for the engine (the forces NaN)."""
        from mrsuspension.control.user import FAILED

        try:
            nx, nc, nh = self.nx, self.corners, self.horizon
            rows = MB_PLAN - MB_X + nh
            buf = np.ctypeslib.as_array(s, (rows, nx + 1))
            forces = np.ctypeslib.as_array(o, (n,))
            t = float(buf[0, nx])
            plan = buf[MB_PLAN - MB_X :, :nc]
            if t == 0.0:  # a new run: no previous solution
                plan[:] = 0.0
            forces[:nc] = self.step(buf[0, :nx], buf[MB_VD - MB_X, :nc], plan)
            buf[MB_HOLD - MB_X, 0] = (math.floor(t / self.sample + 1e-9) + 1.0) * self.sample
            return 0.0
        except BaseException as exc:
            FAILED.append((self.law, exc))
            return math.nan


#: one QP and entry per car and options in this process (kept: a run holds its address)
_MPC_PROBLEMS: dict[tuple[Any, ...], VehicleMPCProblem] = {}


@dataclass(frozen=True)
class VehicleMPC(VehicleLQ):
    """Whole-vehicle semi-active MPC: every ``T_s`` the first forces of the whole car's QP
    (:class:`VehicleMPCProblem`: the LQ cost of :func:`lq_design`, ``N`` samples, one
    force per corner per sample in the viscous band at its predicted stroke rate), held
    until the next solve; hi-lo per corner by Dyke's rule as :class:`VehicleLQ`.

    Parameters
    ----------
    rattle_weight, tire_weight, force_weight, low_current, high_current
        As :class:`VehicleLQ`.
    horizon_samples : float
        ``N``, a whole number in 1 to :data:`~mrsuspension.control.mpc.HORIZON_MAX`
        (default 10).
    sample_time : float
        ``T_s`` [s] in [1e-4, 0.05] (default 2 ms).
    band_low, band_high : float
        The band's damping ``c_min``, ``c_max`` [N s/m] (defaults those of ``mpc``: the
        dissertation's damper at 0 and 0.5 A, 2043 and 10613 N s/m). (The names differ
        from the per-corner ``mpc``'s ``horizon``, ``sample``, ``c_min``, ``c_max``: one
        field per name on the monitor's page.)

    Notes
    -----
    The state is :class:`VehicleLQ`'s as seen (the tire deflection 0: not measured). The
    QP runs in Python (OSQP) through a ctypes entry the compiled step calls at each
    solve; between solves the step holds the forces without calling it.

    Examples
    --------
    >>> VehicleMPC(band_low=3000.0, band_high=2000.0)
    Traceback (most recent call last):
    ...
    mrsuspension.errors.ValidationError: band_low must be <= band_high (the band's damping at i_min and i_max) [N s/m]; got band_low 3000, band_high 2000
    >>> from mrsuspension.vehicle import FullCar
    >>> law = VehicleMPC().for_vehicle(FullCar())
    >>> law.problem().gain.shape  # the sampled-data LQR: 4 corners x 15
    (4, 15)
    """

    law: ClassVar[str] = "vehicle-mpc"
    kernel_code: ClassVar[int] = LAW_MPC
    per_corner: ClassVar[str] = "mpc-hilo"

    horizon_samples: float = 10.0
    sample_time: float = 2e-3
    band_low: float = 2043.0
    band_high: float = 10613.0

    def __post_init__(self) -> None:
        from mrsuspension.control.mpc import HORIZON_MAX

        super().__post_init__()
        check_range("horizon_samples", self.horizon_samples, 1.0, float(HORIZON_MAX),
                    unit="samples")  # fmt: skip
        if self.horizon_samples != math.floor(self.horizon_samples):
            raise ValidationError(
                f"horizon_samples N must be a whole number of samples in [1, {HORIZON_MAX}]; "
                f"got {self.horizon_samples:g}"
            )
        check_range("sample_time", self.sample_time, 1e-4, 0.05, unit="s")
        check_range("band_low", self.band_low, 0.0, 1e7, unit="N s/m")
        check_range("band_high", self.band_high, 0.0, 1e7, unit="N s/m")
        if self.band_low > self.band_high:
            raise ValidationError(
                "band_low must be <= band_high (the band's damping at i_min and i_max) "
                f"[N s/m]; got band_low {self.band_low:g}, band_high {self.band_high:g}"
            )

    def _design(self, vehicle: Any) -> dict[str, FloatArray]:
        from mrsuspension.control.mpc import _require_osqp

        _require_osqp()  # before a run, not in it
        d = lq_design(vehicle, self.rattle_weight, self.tire_weight, self.force_weight)
        return {"_gain": d.K, "_lq": np.concatenate([np.ravel(m) for m in d]),
                "_lq_shape": np.array([d.A.shape[0], d.B.shape[1], d.H.shape[0]], float)}  # fmt: skip

    def design(self) -> LQDesign:
        """The attached car's :func:`lq_design` (kept flat in the law: it pickles)."""
        self.gain  # noqa: B018 (raises without a vehicle)
        na, nc, nx = (int(v) for v in self.__dict__["_lq_shape"])
        shapes = [(na, na), (na, nc), (na, na), (nc, nc), (na, nc), (na, na), (nc, na),
                  (nx, na), (nc, nx)]  # fmt: skip
        flat, out, at = self.__dict__["_lq"], [], 0
        for shape in shapes:
            size = shape[0] * shape[1]
            out.append(flat[at : at + size].reshape(shape))
            at += size
        return LQDesign(*out)

    def problem(self) -> VehicleMPCProblem:
        """The QP and its entry in this process (built once per car and options)."""
        d = self.design()
        key = (self.__dict__["_lq"].tobytes(), self.horizon_samples, self.sample_time,
               self.band_low, self.band_high, self.law)  # fmt: skip
        got = _MPC_PROBLEMS.get(key)
        if got is None:
            got = VehicleMPCProblem(d, int(self.horizon_samples), self.sample_time,
                                    self.band_low, self.band_high, self.law)  # fmt: skip
            _MPC_PROBLEMS[key] = got
        return got

    def buffer_shape(self, corners: int) -> tuple[int, int]:
        """The law buffer: :class:`VehicleLQ`'s rows, the time after the state, and
        ``N`` rows of the previous solution (``MB_PLAN``)."""
        return MB_PLAN + int(self.horizon_samples), self.state_size() + 1

    def _tail(self) -> list[FloatArray]:
        qp = self.problem()
        return [self.gain, np.array([float(qp.address), self.sample_time])]


@dataclass(frozen=True)
class VehicleMPCActive(VehicleMPC):
    """:class:`VehicleMPC`'s forces applied by an ideal actuator at every corner (no
    current): the QP's forces as they are. With the band (default: the damper's viscous
    range) that is an ideal semi-active damper following the MPC, the reference of what
    force tracking could give; with ``band_low`` = ``band_high`` = 0 no force at all.

    Examples
    --------
    >>> VehicleMPCActive().law, VehicleMPCActive.per_corner
    ('vehicle-mpc-active', 'mpc')
    """

    law: ClassVar[str] = "vehicle-mpc-active"
    active: ClassVar[bool] = True
    per_corner: ClassVar[str] = "mpc"


@dataclass(frozen=True)
class VehicleMPCForce(VehicleMPC):
    """:class:`VehicleMPC`'s held forces tracked through every corner's inverse damper
    model, as :class:`VehicleLQForce` (the per-corner ``mpc``: its first force through the
    inverse model). The inverse runs at every step on the held force.

    Examples
    --------
    >>> VehicleMPCForce().law, VehicleMPCForce.per_corner
    ('vehicle-mpc-force', 'mpc')
    """

    law: ClassVar[str] = "vehicle-mpc-force"
    needs_inverse: ClassVar[bool] = True
    per_corner: ClassVar[str] = "mpc"


# --- kernel ----------------------------------------------------------------------------


@njit(cache=True, inline="always")
def _seen_rates(x: np.ndarray, nc: int, vz: float, q: float, p: float) -> None:
    """The body's rates as seen into the state ``x`` (after the ``nc`` strokes)."""
    x[nc] = vz
    x[nc + 1] = q
    x[nc + 2] = p


@njit(cache=True, inline="always")
def lq_forces(
    forces: np.ndarray,
    mbuf: np.ndarray,
    mp: np.ndarray,
    nc: int,
    vz: float,
    q: float,
    p: float,
    estimate: bool,
    dt: float,
) -> None:
    """Write the corners' desired forces ``F = -K x`` [N] into ``forces``.

    ``mbuf[MB_X]`` holds the state: as seen (the strokes and wheel velocities written by
    the vehicle step; the body rates ``vz, q, p`` here), or with ``estimate`` the Kalman
    estimate, advanced by Euler over ``dt`` [s] from the measurements ``mbuf[MB_Y]`` and
    the dampers' forces ``mbuf[MB_U]``: ``x' = A x + B u + L (y - C x - D u)`` (the
    innovation replaces ``y``, the rates go to ``mbuf[MB_DX]``). ``mp``:
    :meth:`VehicleLQ.params`.
    """
    nx = int(mp[LP_NX])
    x = mbuf[MB_X]
    if estimate:
        y = mbuf[MB_Y]
        u = mbuf[MB_U]
        rate = mbuf[MB_DX]
        ny = 3 * nc
        oa = LP_K + nc * nx
        ob = oa + nx * nx
        ol = ob + nx * nc
        oc = ol + nx * ny
        od = oc + ny * nx
        for i in range(ny):  # the innovation y - C x - D u
            v = y[i]
            for j in range(nx):
                v -= mp[oc + i * nx + j] * x[j]
            for j in range(nc):
                v -= mp[od + i * nc + j] * u[j]
            y[i] = v
        for i in range(nx):
            v = 0.0
            for j in range(nx):
                v += mp[oa + i * nx + j] * x[j]
            for j in range(nc):
                v += mp[ob + i * nc + j] * u[j]
            for j in range(ny):
                v += mp[ol + i * ny + j] * y[j]
            rate[i] = v
        for i in range(nx):
            x[i] += dt * rate[i]
    else:
        _seen_rates(x, nc, vz, q, p)
    for c in range(nc):
        f = 0.0
        for j in range(nx):
            f -= mp[LP_K + c * nx + j] * x[j]
        forces[c] = f


@njit(cache=True, inline="always")
def mpc_forces(
    forces: np.ndarray,
    mbuf: np.ndarray,
    mp: np.ndarray,
    nc: int,
    vz: float,
    q: float,
    p: float,
    vd: np.ndarray,
    t: float,
) -> None:
    """``vehicle-mpc``'s forces [N] into ``forces``: held, or at a solve (``t`` [s] at or
    past the next solve's time ``mbuf[MB_HOLD, 0]``) from the law's entry.

    The state ``mbuf[MB_X]`` as :func:`lq_forces` sees it (the strokes and wheel
    velocities written by the vehicle step, the body rates here), the time after it, the
    corners' stroke rates ``vd`` [m/s] into ``mbuf[MB_VD]``; the entry (its address after
    ``K`` in ``mp``: :meth:`VehicleMPC.params`) solves and writes the forces, the plan
    and the next solve's time (:class:`VehicleMPCProblem`). An entry that failed (not a
    finite return) leaves the forces NaN.
    """
    nx = int(mp[LP_NX])
    x = mbuf[MB_X]
    _seen_rates(x, nc, vz, q, p)
    if t < mbuf[MB_HOLD, 0]:
        return
    x[nx] = t
    for c in range(nc):
        mbuf[MB_VD, c] = vd[c]
    addr = np.int64(mp[LP_K + nc * nx])
    out: float = CK.call_law(addr, mbuf[MB_X:], forces[:nc])  # type: ignore[call-arg]
    if not math.isfinite(out):
        for c in range(nc):
            forces[c] = math.nan
