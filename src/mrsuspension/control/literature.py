"""The literature's benchmark laws as ``control/`` plug-ins (issue 29 part 1).

Each law is a plain function of the measured signals (:mod:`~mrsuspension.control.signals`)
made a controller by :func:`~mrsuspension.control.user.law` (the numba path: no change
to the compiled kernels) and registered in :data:`~mrsuspension.control.CONTROLLERS`, so
it runs on the quarter car and at every corner of a half or full car, in scenarios,
sweeps, studies and the HiL loop, and is covered by the controllers' contract test.

Signs. The papers write the stroke rate ``v = z_s' - z_u'`` (body minus wheel); this
toolkit's frame is up-positive with ``v_d = z_u' - z_s'`` and ``x_d = z_u - z_s``
(``docs/control-laws.md``), and the damper force ``F_d = c v_d`` is **up on the body**.
Every rule below is written in the toolkit's signs: a paper's ``v`` is ``-v_d`` here.

=======================  =================================================  ==========
law                      rule (this toolkit's signs)                        output
=======================  =================================================  ==========
``skyhook-onoff``        high when ``z_s' v_d < 0`` (Karnopp et al. 1974)   hi-lo
``groundhook``           high when ``z_u' v_d > 0`` (Valasek et al. 1997)   hi-lo
``groundhook-continuous``  ``F* = c_g z_u'`` where ``z_u' v_d > 0``, else 0  force
``hybrid-skyhook-groundhook``  ``i = g (a s_sky + (1 - a) s_gnd)``,         current
                         ``s_sky = |z_s'|`` where ``z_s' v_d < 0``,
                         ``s_gnd = |z_u'|`` where ``z_u' v_d > 0``
                         (Goncalves & Ahmadian 2003)
``add``                  high when ``z_s'' v_d < 0`` (Savaresi et al. 2005) hi-lo
``sh-add``               skyhook where ``z_s''^2 <= alpha^2 z_s'^2``, ADD   hi-lo
                         elsewhere (Savaresi & Spelta 2007)
``pdd``                  ``F* = c v_d``, ``c = clip(-k x_d / v_d, c_min,    force
                         c_max)`` (Morselli & Zanasi 2008)
``pdd-current``          the same ``c`` as a current of a damper linear in  current
                         current
``clipped-lq``           high when ``(f_c - F_d) F_d > 0``, ``f_c = -K x``  hi-lo
                         (Dyke et al. 1996)
``lq-force``             ``F* = f_c`` through the inverse model             force
``lq-active``            ``f_c`` applied by an ideal actuator (a reference) active
``clipped-lqg``          Dyke's rule with ``f_c = -K x_hat``, ``x_hat`` a    hi-lo
                         Kalman estimate (the law's memory)
``lqg-active``           ``-K x_hat`` by an ideal actuator                  active
=======================  =================================================  ==========

"hi-lo": ``i_max`` when the rule says high, else ``i_min``; "force": a target force
tracked through the dissertation's damper's inverse model (``output="force"``: needs
the ``wang-symmetric`` damper); "active": the force itself, by an ideal actuator in place
of the damper (``output="active"``, for the closed-form check of the LQR).

What was checked against what. The papers' full texts were not reachable from this
workplace (only their abstracts: Savaresi et al. 2005 -- ADD minimises the body
acceleration with a two-state damper and no preview; Savaresi & Spelta 2007 -- SH good
around the body resonance, ADD beyond it, the mix quasi-optimal; Goncalves & Ahmadian
2003 -- hybrid merges skyhook and groundhook; Dyke et al. 1996 -- clipped-optimal from
acceleration feedback). Each rule is therefore derived here from first principles, in
its docstring, and its sign checked by a hand-computed case
(``tests/unit/control/test_literature.py``) and by the closed-loop ranking of
``docs/control-laws.md`` ("The literature's benchmark laws").

Examples
--------
>>> from mrsuspension.control import make_controller
>>> make_controller("add", i_max=0.4).i_max
0.4
>>> add.function(z_s_ddot=1.0, v_d=-0.1, i_min=0.0, i_max=0.5)  # z_s'' v_d < 0: high
0.5
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
from numba import njit

from mrsuspension.control.modal import clipped_optimal_condition
from mrsuspension.control.user import law

__all__ = [
    "LQG_NOISE",
    "LQ_WEIGHTS",
    "add",
    "clipped_lq",
    "clipped_lqg",
    "groundhook",
    "groundhook_continuous",
    "hybrid_skyhook_groundhook",
    "kalman_gain",
    "lq_active",
    "lq_force",
    "lq_gain",
    "lqg_active",
    "pdd",
    "pdd_current",
    "quarter_car_model",
    "sh_add",
    "skyhook_onoff",
]

#: the two currents of a hi-lo law: 0 A and the engine's default ``max_current`` (0.5 A,
#: the dissertation's damper's range)
_HILO: dict[str, dict[str, Any]] = {
    "i_min": {"unit": "A", "low": 0.0, "high": 10.0, "symbol": "i_min"},
    "i_max": {"unit": "A", "low": 0.0, "high": 10.0, "symbol": "i_max"},
}


# -- on-off laws -------------------------------------------------------------------------
@law(options=_HILO)
def skyhook_onoff(z_s_dot: float, v_d: float, i_min: float = 0.0, i_max: float = 0.5) -> float:
    """Two-state skyhook (Karnopp, Crosby & Harwood 1974): high when ``z_s' v_d < 0``.

    The damper's force ``c v_d`` (up on the body) opposes the body's velocity, as the
    skyhook force ``-c_sky z_s'`` would, exactly when ``z_s' v_d < 0`` (papers:
    ``z_s' (z_s' - z_u') > 0``). The built-in ``skyhook-hilo`` is the continuous policy I
    of the dissertation; this is the two-state reference of the benchmark.
    """
    return i_max if z_s_dot * v_d < 0.0 else i_min


@law(options=_HILO)
def groundhook(z_u_dot: float, v_d: float, i_min: float = 0.0, i_max: float = 0.5) -> float:
    """On-off groundhook (Valasek et al. 1997): high when ``z_u' v_d > 0``.

    Groundhook wants the force ``-c_g z_u'`` on the wheel (a damper to the ground). The
    damper pushes the wheel with ``-c v_d``, so it can when ``z_u' v_d > 0`` (papers:
    ``-z_u' (z_s' - z_u') > 0``).
    """
    return i_max if z_u_dot * v_d > 0.0 else i_min


@law(
    output="force",
    options={"groundhook_damping": {"unit": "N s/m", "low": 0.0, "high": 1e7, "symbol": "c_g"}},
)
def groundhook_continuous(z_u_dot: float, v_d: float, groundhook_damping: float = 6750.0) -> float:
    """Continuous groundhook (Valasek et al. 1997): target ``F* = c_g z_u'`` where the
    damper can give it (``z_u' v_d > 0``), else 0; tracked through the inverse model.

    ``F*`` is up on the body, so ``-F* = -c_g z_u'`` on the wheel. Default ``c_g`` =
    6750 N s/m, the dissertation's skyhook damping ``c_s`` (a comparable scale; Valasek et
    al.'s gains are for a heavy truck).
    """
    return groundhook_damping * z_u_dot if z_u_dot * v_d > 0.0 else 0.0


@law(
    options={
        "alpha": {"low": 0.0, "high": 1.0, "symbol": "alpha", "label": "alpha (skyhook share)"},
        "gain": {"unit": "A s/m", "low": 0.0, "high": 1e6, "symbol": "G"},
        **_HILO,
    }
)
def hybrid_skyhook_groundhook(
    z_s_dot: float,
    z_u_dot: float,
    v_d: float,
    alpha: float = 0.5,
    gain: float = 10.0,
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """Hybrid skyhook-groundhook (Goncalves & Ahmadian 2003): the current
    ``i = clip(G (alpha s_sky + (1 - alpha) s_gnd), i_min, i_max)``.

    ``s_sky = |z_s'|`` where skyhook can act (``z_s' v_d < 0``), else 0; ``s_gnd = |z_u'|``
    where groundhook can (``z_u' v_d > 0``), else 0: each part is gated by its own rule,
    so ``alpha = 1`` is skyhook and ``alpha = 0`` groundhook, and the commanded force is
    always dissipative. The current stands for the force magnitude (an MR damper's force
    grows with its current). Defaults: ``alpha = 0.5`` (the middle of the blend), ``G =
    10 A s/m`` (``i_max`` = 0.5 A at 5 cm/s, so mostly two-state on a road); neither is
    a value taken from the paper.
    """
    s_sky = abs(z_s_dot) if z_s_dot * v_d < 0.0 else 0.0
    s_gnd = abs(z_u_dot) if z_u_dot * v_d > 0.0 else 0.0
    i = gain * (alpha * s_sky + (1.0 - alpha) * s_gnd)
    return min(max(i, i_min), i_max)


@law(options=_HILO)
def add(z_s_ddot: float, v_d: float, i_min: float = 0.0, i_max: float = 0.5) -> float:
    """Acceleration-driven damper, ADD (Savaresi, Silani & Bittanti 2005): high when
    ``z_s'' v_d < 0``.

    From first principles: the damper's force ``c v_d`` is up on the body, so it lowers
    the body's acceleration magnitude at this instant when it opposes it, ``z_s'' c v_d <
    0``; with two states, ``c_max`` then and ``c_min`` otherwise (papers: ``z_s'' (z_s' -
    z_u') > 0``). ``z_s''`` is the previous step's (one ``dt`` late, as a sampled
    controller sees it).
    """
    return i_max if z_s_ddot * v_d < 0.0 else i_min


@law(
    options={
        "alpha": {"unit": "rad/s", "low": 0.0, "high": 1e4, "symbol": "alpha"},
        **_HILO,
    }
)
def sh_add(
    z_s_dot: float,
    z_s_ddot: float,
    v_d: float,
    alpha: float = 12.0,
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """Mixed skyhook-ADD, SH-ADD (Savaresi & Spelta 2007): the skyhook rule where
    ``z_s''^2 - alpha^2 z_s'^2 <= 0``, the ADD rule elsewhere.

    For a body moving as a sine at ``w``, ``|z_s''| = w |z_s'|``: the test picks skyhook
    below ``w = alpha`` and ADD above it, the frequency split of the abstract (SH best
    around the body resonance, ADD beyond). Default ``alpha`` = 12 rad/s (1.9 Hz), where
    the two-state skyhook's and ADD's transmissibilities cross on the default quarter car
    with the ideal two-state damper of the benchmark (``docs/control-laws.md``).
    """
    if z_s_ddot * z_s_ddot - alpha * alpha * z_s_dot * z_s_dot <= 0.0:
        return i_max if z_s_dot * v_d < 0.0 else i_min
    return i_max if z_s_ddot * v_d < 0.0 else i_min


# -- power-driven damper ---------------------------------------------------------------
_PDD = {
    "stiffness": {"unit": "N/m", "low": 0.0, "high": 1e8, "symbol": "k"},
    "c_min": {"unit": "N s/m", "low": 0.0, "high": 1e7, "symbol": "c_min"},
    "c_max": {"unit": "N s/m", "low": 0.0, "high": 1e7, "symbol": "c_max"},
}


def _pdd_stiffness(plant: Any, **options: Any) -> dict[str, Any]:
    """``k`` = the plant's suspension stiffness where the option is 0 (its default)."""
    if options["stiffness"] != 0.0:
        return {}
    return {"stiffness": float(plant.suspension_stiffness)}


@law(output="force", for_plant=_pdd_stiffness, options=_PDD)
def pdd(
    x_d: float,
    v_d: float,
    stiffness: float = 0.0,
    c_min: float = 2043.0,
    c_max: float = 10613.0,
) -> float:
    """Power-driven damper, PDD (Morselli & Zanasi 2008): ``F* = c v_d`` with
    ``c = clip(-k x_d / v_d, c_min, c_max)``, tracked through the inverse model.

    From first principles: the spring pushes the body with ``k x_d``; the damper's
    ``c v_d`` cancels it (no suspension force on the body, none of the spring's power
    into it) with ``c = -k x_d / v_d`` when that is a damping it can give, else the
    nearest bound. The ratio is the same in the papers' signs (``x = -x_d``, ``v =
    -v_d``). ``k`` = 0 (default): the plant's suspension stiffness. ``c_min``, ``c_max``:
    the viscous range of the dissertation's damper at 0 and 0.5 A (the Bingham fit
    ``bingham-wang-low``: 2043 and 2043 + 17139 x 0.5 N s/m).
    """
    if v_d == 0.0:
        return 0.0
    c = min(max(-stiffness * x_d / v_d, c_min), c_max)
    return c * v_d


@law(for_plant=_pdd_stiffness, options={**_PDD, **_HILO})
def pdd_current(
    x_d: float,
    v_d: float,
    stiffness: float = 0.0,
    c_min: float = 2043.0,
    c_max: float = 10613.0,
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """PDD's damping as a current: ``i = i_min + (i_max - i_min) (c - c_min) / (c_max -
    c_min)``, ``c`` as :func:`pdd` (for a damper linear in current, ``c = c_min + (c_max -
    c_min) i / i_max``: the benchmark's ideal damper)."""
    if v_d == 0.0 or c_max <= c_min:
        return i_min
    c = min(max(-stiffness * x_d / v_d, c_min), c_max)
    return i_min + (i_max - i_min) * (c - c_min) / (c_max - c_min)


# -- linear-quadratic ------------------------------------------------------------------
#: default LQ weights: body acceleration 1, rattle 1e2 1/s^4, tire deflection 1e3 1/s^4,
#: force 1e-6 1/kg^2 (the Riccati example of ``docs/control-laws.md``)
LQ_WEIGHTS = {"w_rattle": 1e2, "w_tire": 1e3, "w_force": 1e-6}


def quarter_car_model(
    plant: Any,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``(A, B, E)`` of the linear quarter car ``x' = A x + B u + E z_r'``.

    States ``x = (z_s - z_u, z_s', z_u - z_r, z_u')``, input ``u`` the damper force up on
    the body [N], disturbance the road's velocity ``z_r'``; the plant's tire damping and
    skyhook damping (a passive force ``-c_sky z_s'``) are in ``A``.

    Examples
    --------
    >>> from mrsuspension.vehicle import QuarterCar
    >>> a, b, e = quarter_car_model(QuarterCar())
    >>> a.shape, float(b[1, 0] * 563.0), e.ravel().tolist()[:3]
    ((4, 4), 1.0, [0.0, 0.0, -1.0])
    """
    ms, mu = plant.sprung_mass, plant.unsprung_mass
    ks, kt = plant.suspension_stiffness, plant.tire_stiffness
    ct, csky = plant.tire_damping, getattr(plant, "skyhook_damping", 0.0)
    a = np.array(
        [
            [0.0, 1.0, 0.0, -1.0],
            [-ks / ms, -csky / ms, 0.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
            [ks / mu, 0.0, -kt / mu, -ct / mu],
        ]
    )
    b = np.array([[0.0], [1.0 / ms], [0.0], [-1.0 / mu]])
    e = np.array([[0.0], [0.0], [-1.0], [ct / mu]])
    return a, b, e


def lq_gain(plant: Any, w_rattle: float, w_tire: float, w_force: float) -> npt.NDArray[np.float64]:
    """The LQR gain ``K`` (1 x 4) of :func:`quarter_car_model`: ``u = -K x`` minimises
    ``integral(z_s''^2 + w_rattle x_1^2 + w_tire x_3^2 + w_force u^2) dt``.

    ``z_s'' = C x + D u`` (the second row of ``A`` and ``B``) gives the cross weight
    ``N = C^T D``; solved by :func:`scipy.linalg.solve_continuous_are`.

    Examples
    --------
    >>> from mrsuspension.vehicle import QuarterCar
    >>> k = lq_gain(QuarterCar(), **LQ_WEIGHTS)
    >>> k.shape, bool(k[0, 1] > 0.0)  # a positive gain on z_s': skyhook-like
    ((1, 4), True)
    """
    import scipy.linalg  # (not at import: the CLI starts without scipy)

    a, b, _ = quarter_car_model(plant)
    c = a[1:2, :]
    d = b[1:2, :]
    q = c.T @ c + np.diag([w_rattle, 0.0, w_tire, 0.0])
    r = d.T @ d + np.array([[w_force]])
    n = c.T @ d
    p = scipy.linalg.solve_continuous_are(a, b, q, r, s=n)
    gain: npt.NDArray[np.float64] = np.linalg.solve(r, b.T @ p + n.T)
    return gain


_LQ = {
    "K": {"unit": "N/m, N s/m", "low": -1e9, "high": 1e9, "symbol": "K"},
    "w_rattle": {"unit": "1/s^4", "low": 0.0, "high": 1e12, "symbol": "q_x"},
    "w_tire": {"unit": "1/s^4", "low": 0.0, "high": 1e12, "symbol": "q_t"},
    "w_force": {"unit": "1/kg^2", "low": 0.0, "high": 1e3, "low_open": True, "symbol": "r"},
}


def _lq_for_plant(plant: Any, **options: Any) -> dict[str, Any]:
    """``K`` from the plant's Riccati solve where ``K`` is all zeros (its default)."""
    if np.any(np.asarray(options["K"]) != 0.0):
        return {}
    k = lq_gain(plant, options["w_rattle"], options["w_tire"], options["w_force"])
    return {"K": k}


_K0 = ((0.0, 0.0, 0.0, 0.0),)


@law(for_plant=_lq_for_plant, options={**_LQ, **_HILO})
def clipped_lq(
    z_s_dot: float,
    z_u_dot: float,
    x_d: float,
    F_d: float,
    K: Any = _K0,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """Clipped-optimal LQ (Dyke, Spencer, Sain & Carlson 1996): high when
    ``(f_c - F_d) F_d > 0``, ``f_c = -K x``.

    ``K``: the LQR gain of :func:`lq_gain` for the plant the law drives (each corner its
    own), from the weights, unless given. ``x = (z_s - z_u, z_s', z_u - z_r, z_u')``; the
    tire deflection ``z_u - z_r`` is not measured (the road is unknown), so its gain is not
    applied (an LQG would estimate it). ``F_d`` is the previous step's damper force (the
    load cell): more current when the damper's force is below the optimal one in
    magnitude and of its sign, else ``i_min`` (Dyke et al.'s voltage rule).
    """
    fc = -(K[0, 0] * (-x_d) + K[0, 1] * z_s_dot + K[0, 3] * z_u_dot)
    return i_max if clipped_optimal_condition(fc, F_d) < 0.0 else i_min


@law(output="force", for_plant=_lq_for_plant, options=_LQ)
def lq_force(
    z_s_dot: float,
    z_u_dot: float,
    x_d: float,
    K: Any = _K0,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
) -> float:
    """LQ tracked through the inverse model: ``F* = f_c = -K x`` (as :func:`clipped_lq`;
    the inverse gives the current nearest to it, the least where ``f_c`` is not
    dissipative)."""
    return -(K[0, 0] * (-x_d) + K[0, 1] * z_s_dot + K[0, 3] * z_u_dot)


@law(output="active", for_plant=_lq_for_plant, options=_LQ)
def lq_active(
    z_s_dot: float,
    z_u_dot: float,
    x_d: float,
    K: Any = _K0,
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
) -> float:
    """The LQ force ``f_c = -K x`` applied by an ideal actuator (a reference, not a
    damper): the linear quarter car then responds as ``A - B K`` (the closed-form check
    of ``tests/unit/control/test_literature.py``)."""
    return -(K[0, 0] * (-x_d) + K[0, 1] * z_s_dot + K[0, 3] * z_u_dot)


# -- LQG: the LQ gain on a Kalman estimate ----------------------------------------------
#: default LQG noise intensities: the road's velocity 1e-3 m^2/s (ISO 8608 class C at 72
#: km/h: one-sided velocity PSD (2 pi n0)^2 Gd(n0) V = 2.0e-3 m^2/s, n0 = 0.1 cycle/m,
#: Gd(n0) = 256e-6 m^3, V = 20 m/s), the accelerometers 1e-2 (m/s^2)^2 s, the stroke
#: sensor 1e-8 m^2 s (assumed sensor grades, not values from a paper)
LQG_NOISE = {"road_intensity": 1e-3, "noise_acc": 1e-2, "noise_stroke": 1e-8}


def _measurements(
    plant: Any,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """``(C, D)`` of the measurements ``y = (z_s'', z_u'', z_s - z_u) = C x + D u``."""
    a, b, _ = quarter_car_model(plant)
    c = np.vstack([a[1], a[3], [1.0, 0.0, 0.0, 0.0]])
    d = np.array([b[1, 0], b[3, 0], 0.0])
    return c, d


def kalman_gain(
    plant: Any, road_intensity: float, noise_acc: float, noise_stroke: float
) -> npt.NDArray[np.float64]:
    """The steady Kalman-Bucy gain ``L`` (4 x 3) of :func:`quarter_car_model` measured by
    the body and wheel accelerometers and the stroke sensor.

    Process noise: the road's velocity (white, intensity ``road_intensity``) through
    ``E``; measurement noise: ``diag(noise_acc, noise_acc, noise_stroke)``. The wheel
    accelerometer also sees the road through the tire's damping (``c_t z_r' / m_u``);
    that correlation is left out (``c_t`` is small). Solved by
    :func:`scipy.linalg.solve_continuous_are` on the dual problem.

    Examples
    --------
    >>> from mrsuspension.vehicle import QuarterCar
    >>> kalman_gain(QuarterCar(), **LQG_NOISE).shape
    (4, 3)
    """
    import scipy.linalg  # (not at import: the CLI starts without scipy)

    a, _, e = quarter_car_model(plant)
    c, _ = _measurements(plant)
    v = np.diag([noise_acc, noise_acc, noise_stroke])
    p = scipy.linalg.solve_continuous_are(a.T, c.T, road_intensity * (e @ e.T), v)
    gain: npt.NDArray[np.float64] = p @ c.T @ np.linalg.inv(v)
    return gain


_LQG = {
    "K": _LQ["K"],
    "L": {"unit": "1/s, s, ...", "low": -1e12, "high": 1e12, "symbol": "L"},
    "A": {"unit": "1/s, 1/s^2", "low": -1e12, "high": 1e12, "symbol": "A"},
    "B": {"unit": "1/kg", "low": -1e6, "high": 1e6, "symbol": "B"},
    "w_rattle": _LQ["w_rattle"],
    "w_tire": _LQ["w_tire"],
    "w_force": _LQ["w_force"],
    "road_intensity": {"unit": "m^2/s", "low": 0.0, "high": 1.0, "low_open": True, "symbol": "W"},
    "noise_acc": {"unit": "(m/s^2)^2 s", "low": 0.0, "high": 1e6, "low_open": True},
    "noise_stroke": {"unit": "m^2 s", "low": 0.0, "high": 1.0, "low_open": True},
}


def _lqg_for_plant(plant: Any, **options: Any) -> dict[str, Any]:
    """``K``, ``L``, ``A``, ``B`` from the plant where all of them are zeros (their
    defaults); given ones are kept."""
    given = [np.any(np.asarray(options[n]) != 0.0) for n in ("K", "L", "A", "B")]
    if any(given):
        return {}
    a, b, _ = quarter_car_model(plant)
    k = lq_gain(plant, options["w_rattle"], options["w_tire"], options["w_force"])
    gain = kalman_gain(
        plant, options["road_intensity"], options["noise_acc"], options["noise_stroke"]
    )
    return {"K": k, "L": gain, "A": a, "B": b[:, 0]}


_Z44 = tuple((0.0, 0.0, 0.0, 0.0) for _ in range(4))
_Z43 = tuple((0.0, 0.0, 0.0) for _ in range(4))


@njit(error_model="numpy")  # (compiled on first use; the laws calling it compile with it)
def _lqg_force(
    z_s_ddot: float,
    z_u_ddot: float,
    x_d: float,
    F_d: float,
    time: float,
    memory: Any,
    K: Any,
    L: Any,
    A: Any,
    B: Any,
) -> float:
    """Advance the estimate in ``memory`` (``x_hat``, then the last sample's time) to
    ``time`` by an Euler step and return ``f_c = -K x_hat``."""
    dt = time - memory[4]
    memory[4] = time
    u = F_d
    # the innovation y - C x_hat - D u; C and D are rows of A and B (_measurements)
    r0 = z_s_ddot - u * B[1]
    r1 = z_u_ddot - u * B[3]
    for j in range(4):
        r0 -= A[1, j] * memory[j]
        r1 -= A[3, j] * memory[j]
    r2 = -x_d - memory[0]
    d0 = d1 = d2 = d3 = 0.0
    for i in range(4):
        rate = B[i] * u + L[i, 0] * r0 + L[i, 1] * r1 + L[i, 2] * r2
        for j in range(4):
            rate += A[i, j] * memory[j]
        if i == 0:
            d0 = rate
        elif i == 1:
            d1 = rate
        elif i == 2:
            d2 = rate
        else:
            d3 = rate
    memory[0] += dt * d0
    memory[1] += dt * d1
    memory[2] += dt * d2
    memory[3] += dt * d3
    return -(K[0, 0] * memory[0] + K[0, 1] * memory[1] + K[0, 2] * memory[2] + K[0, 3] * memory[3])


@law(for_plant=_lqg_for_plant, options={**_LQG, **_HILO}, memory=5)
def clipped_lqg(
    z_s_ddot: float,
    z_u_ddot: float,
    x_d: float,
    F_d: float,
    time: float,
    memory: Any,
    K: Any = _K0,
    L: Any = _Z43,
    A: Any = _Z44,
    B: Any = (0.0, 0.0, 0.0, 0.0),
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
    road_intensity: float = LQG_NOISE["road_intensity"],
    noise_acc: float = LQG_NOISE["noise_acc"],
    noise_stroke: float = LQG_NOISE["noise_stroke"],
    i_min: float = 0.0,
    i_max: float = 0.5,
) -> float:
    """Clipped-optimal LQG (Dyke et al. 1996: LQG from acceleration feedback): Dyke's rule
    (high when ``(f_c - F_d) F_d > 0``) with ``f_c = -K x_hat``, the full-state LQ gain
    (:func:`lq_gain`, the tire deflection's gain too) on a Kalman-Bucy estimate
    (:func:`kalman_gain`) from the body and wheel accelerometers (``z_s''``, ``z_u''``)
    and the stroke sensor, with the load cell's ``F_d`` as the input.

    The estimate is the law's memory (``law(memory=5)``: ``x_hat`` and the last sample's
    time), integrated by Euler over the time since the last sample; ``A``, ``B`` (the
    plant's model), ``K`` and ``L`` come from the plant (``for_plant``), each corner its
    own, unless given.
    """
    fc = _lqg_force(z_s_ddot, z_u_ddot, x_d, F_d, time, memory, K, L, A, B)
    return i_max if clipped_optimal_condition(fc, F_d) < 0.0 else i_min


@law(output="active", for_plant=_lqg_for_plant, options=_LQG, memory=5)
def lqg_active(
    z_s_ddot: float,
    z_u_ddot: float,
    x_d: float,
    F_d: float,
    time: float,
    memory: Any,
    K: Any = _K0,
    L: Any = _Z43,
    A: Any = _Z44,
    B: Any = (0.0, 0.0, 0.0, 0.0),
    w_rattle: float = LQ_WEIGHTS["w_rattle"],
    w_tire: float = LQ_WEIGHTS["w_tire"],
    w_force: float = LQ_WEIGHTS["w_force"],
    road_intensity: float = LQG_NOISE["road_intensity"],
    noise_acc: float = LQG_NOISE["noise_acc"],
    noise_stroke: float = LQG_NOISE["noise_stroke"],
) -> float:
    """The LQG force ``f_c = -K x_hat`` (as :func:`clipped_lqg`) by an ideal actuator: a
    reference, and the check that the estimate converges (the recorded ``F_target``
    against ``-K x`` of the true states)."""
    return _lqg_force(z_s_ddot, z_u_ddot, x_d, F_d, time, memory, K, L, A, B)


#: the laws by registry name
LAWS = {
    "skyhook-onoff": skyhook_onoff,
    "groundhook": groundhook,
    "groundhook-continuous": groundhook_continuous,
    "hybrid-skyhook-groundhook": hybrid_skyhook_groundhook,
    "add": add,
    "sh-add": sh_add,
    "pdd": pdd,
    "pdd-current": pdd_current,
    "clipped-lq": clipped_lq,
    "lq-force": lq_force,
    "lq-active": lq_active,
    "clipped-lqg": clipped_lqg,
    "lqg-active": lqg_active,
}
for _name, _cls in LAWS.items():
    _cls.law = _name
