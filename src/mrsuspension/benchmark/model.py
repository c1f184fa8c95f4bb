"""The linear quarter car with the ISO 2631 Wk filter appended, and its discretisation.

State ``x`` (:data:`STATES`), positive up from static equilibrium as in
:mod:`mrsuspension.vehicle`::

    x = [z_s, z_s', z_u, z_u', w_1 .. w_8]

    m_s z_s'' = k_s (z_u - z_s) - c_sky z_s' + F
    m_u z_u'' = k_t (z_r - z_u) + c_t (z_r' - z_u') - k_s (z_u - z_s) - F
    w'        = A_w w + B_w z_s''          (the Wk weighting, a_w = C_w w)

The tyre is linear (it never lifts off): the engine's tyre, ``max(0, ...)``, is the same
while the dynamic tyre force stays above minus the static load (a DLC well below 1/3 on a
random road). The outputs ``y = [a_w, F_T - (m_s + m_u) g, x_d]`` (Wk-weighted body
acceleration, dynamic tyre force, stroke ``z_u - z_s``) are the objective's terms.

The Wk filter is the toolkit's analogue weighting (:mod:`mrsuspension.measures.iso2631`,
ISO 2631-1 Annex A, its constants :data:`~mrsuspension.measures.WK_CONSTANTS`) as one
transfer function (:func:`scipy.signal.zpk2tf` of its poles and zeros, realised with
:func:`scipy.signal.tf2ss`), brought to a balanced realisation so that its eight states
are of the size of ``a_w`` (the controllable canonical form's entries span twelve
decades).

Discretisation (:func:`trapezoidal`): the trapezoidal rule on a grid of step ``h`` with
the force held over each interval, ``F_(k+1/2)``::

    x_(k+1) = x_k + h/2 (f(x_k, F_(k+1/2), r_k) + f(x_(k+1), F_(k+1/2), r_(k+1)))

For the Wk states this is the bilinear (Tustin) map of the analogue filter driven by the
interval's mean body acceleration ``(z_s'_(k+1) - z_s'_k) / h``. Holding the force over the
interval, as the engine holds a drive current or a measured force over its tick, keeps
the discrete problem well posed: a force at the nodes enters the trapezoidal rule only
as ``F_k + F_(k+1)``, so a force alternating from node to node would change nothing.

Examples
--------
>>> from mrsuspension.vehicle import QuarterCar
>>> lin = linear_quarter_car(QuarterCar())
>>> lin.a.shape, lin.b.shape, lin.e.shape, lin.c.shape
((12, 12), (12,), (12, 2), (3, 12))
>>> bool(np.all(np.linalg.eigvals(lin.a).real < 0))
True
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from mrsuspension.measures import WK_CONSTANTS
from mrsuspension.vehicle import GRAVITY, QuarterCar

__all__ = [
    "STATES",
    "Discrete",
    "LinearQuarterCar",
    "linear_quarter_car",
    "trapezoidal",
    "wk_state_space",
]

#: Names of the state vector's entries.
STATES = ("z_s", "z_s_dot", "z_u", "z_u_dot", *(f"w{k}" for k in range(1, 9)))
#: Names of the objective's outputs.
OUTPUTS = ("a_w", "F_T_dynamic", "x_d")


def wk_state_space() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(A, B, C, D)`` of the analogue Wk weighting (8 states), balanced realisation.

    Computed once per process (copies are returned).

    The same transfer function as :func:`mrsuspension.measures.wk_weighting`'s magnitude
    (ISO 2631-1 Annex A): band-limiting high-pass (0.4 Hz) and low-pass (100 Hz),
    acceleration-velocity transition and upward step. Strictly proper (``D = 0``).

    Examples
    --------
    >>> a, b, c, d = wk_state_space()
    >>> s = 2j * np.pi * 6.3
    >>> h = (c @ np.linalg.solve(s * np.eye(8) - a, b)).item() + d.item()
    >>> round(abs(h), 3)  # |Wk(6.3 Hz)|
    1.054
    """
    return tuple(m.copy() for m in _wk_state_space())  # type: ignore[return-value]


@functools.cache
def _wk_state_space() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    from scipy.linalg import cholesky, solve_continuous_lyapunov, svd
    from scipy.signal import tf2ss

    c = WK_CONSTANTS
    w1, w2, w3, w4, w5, w6 = (2.0 * math.pi * c[k] for k in ("f1", "f2", "f3", "f4", "f5", "f6"))

    # the four sections of Annex A, each realised with tf2ss and put in series (one
    # tf2ss of the product would span twelve decades and lose the Gramians' precision)
    sections = [
        ([1.0, 0.0, 0.0], [1.0, w1 / c["Q1"], w1 * w1]),  # high-pass
        ([w2 * w2], [1.0, w2 / c["Q2"], w2 * w2]),  # low-pass
        ([w4 * w4 / w3, w4 * w4], [1.0, w4 / c["Q4"], w4 * w4]),  # transition
        ([1.0, w5 / c["Q5"], w5 * w5], [1.0, w6 / c["Q6"], w6 * w6]),  # upward step
    ]
    a = np.zeros((0, 0))
    b = np.zeros((0, 1))
    cc = np.zeros((1, 0))
    d = np.ones((1, 1))
    for num, den in sections:
        a2, b2, c2, d2 = tf2ss(num, den)
        n1, n2 = a.shape[0], a2.shape[0]
        # series: the section's input is the chain's output so far (cc x + d u)
        a = np.block([[a, np.zeros((n1, n2))], [b2 @ cc, a2]])
        b = np.vstack([b, b2 @ d])
        cc = np.hstack([d2 @ cc, c2])
        d = d2 @ d
    # balanced realisation (square-root method): equal, diagonal Gramians
    wc = solve_continuous_lyapunov(a, -b @ b.T)
    wo = solve_continuous_lyapunov(a.T, -cc.T @ cc)
    lc = cholesky(0.5 * (wc + wc.T), lower=True)
    lo = cholesky(0.5 * (wo + wo.T), lower=True)
    u, s, vt = svd(lo.T @ lc)
    root = np.diag(s**-0.5)
    t = lc @ vt.T @ root  # x = T z
    t_inv = root @ u.T @ lo.T
    return t_inv @ a @ t, t_inv @ b, cc @ t, np.asarray(d, dtype=float)


@dataclass(frozen=True)
class LinearQuarterCar:
    """``x' = A x + b F + E r``, ``y = C x + E_y r`` (r = [z_r, z_r']), see the module."""

    vehicle: QuarterCar
    a: np.ndarray
    b: np.ndarray
    e: np.ndarray
    c: np.ndarray
    e_y: np.ndarray

    @property
    def static_load(self) -> float:
        """``(m_s + m_u) g`` [N]."""
        return self.vehicle.total_mass * GRAVITY

    def body_acceleration(self, x: np.ndarray, force: np.ndarray | float) -> np.ndarray:
        """``z_s''`` [m/s^2] at states ``x`` (columns) with force ``F`` [N]."""
        car = self.vehicle
        xd = x[2] - x[0]
        return np.asarray(
            (car.suspension_stiffness * xd - car.skyhook_damping * x[1] + force) / car.sprung_mass
        )


def linear_quarter_car(vehicle: QuarterCar) -> LinearQuarterCar:
    """The quarter car of :mod:`mrsuspension.vehicle` with a linear tyre and Wk appended."""
    ms, mu = vehicle.sprung_mass, vehicle.unsprung_mass
    ks, kt, ct = vehicle.suspension_stiffness, vehicle.tire_stiffness, vehicle.tire_damping
    csky = vehicle.skyhook_damping
    aw, bw, cw, _ = wk_state_space()
    a = np.zeros((12, 12))
    b = np.zeros(12)
    e = np.zeros((12, 2))
    # car
    a[0, 1] = 1.0
    a[1, 0], a[1, 1], a[1, 2] = -ks / ms, -csky / ms, ks / ms
    b[1] = 1.0 / ms
    a[2, 3] = 1.0
    a[3, 0], a[3, 2], a[3, 3] = ks / mu, -(ks + kt) / mu, -ct / mu
    b[3] = -1.0 / mu
    e[3] = kt / mu, ct / mu
    # Wk, driven by z_s''
    a[4:, 4:] = aw
    a[4:, :4] += np.outer(bw[:, 0], a[1, :4])
    b[4:] = bw[:, 0] * b[1]
    c = np.zeros((3, 12))
    c[0, 4:] = cw[0]
    c[1, 2], c[1, 3] = -kt, -ct  # dynamic tyre force
    c[2, 0], c[2, 2] = -1.0, 1.0  # stroke z_u - z_s
    e_y = np.zeros((3, 2))
    e_y[1] = kt, ct
    return LinearQuarterCar(vehicle, a, b, e, c, e_y)


@dataclass(frozen=True)
class Discrete:
    """The trapezoidal step: ``x_(k+1) = P x_k + q F_(k+1/2) + R r_k + S r_(k+1)``."""

    h: float
    p: np.ndarray
    q: np.ndarray
    r: np.ndarray
    s: np.ndarray


def trapezoidal(lin: LinearQuarterCar, h: float) -> Discrete:
    """The trapezoidal rule of :func:`linear_quarter_car` at step ``h`` [s], force held.

    Examples
    --------
    >>> from mrsuspension.vehicle import QuarterCar
    >>> d = trapezoidal(linear_quarter_car(QuarterCar()), 1e-3)
    >>> bool(np.max(np.abs(np.linalg.eigvals(d.p))) < 1)
    True
    """
    n = lin.a.shape[0]
    m = np.eye(n) - 0.5 * h * lin.a
    return Discrete(
        h=h,
        p=np.linalg.solve(m, np.eye(n) + 0.5 * h * lin.a),
        q=np.linalg.solve(m, h * lin.b),
        r=np.linalg.solve(m, 0.5 * h * lin.e),
        s=np.linalg.solve(m, 0.5 * h * lin.e),
    )
