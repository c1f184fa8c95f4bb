"""Semi-active MPC with OSQP (control/mpc.py, issue 29 part 1).

The QP against the sampled-data LQR with the band inactive (1e-6) and the LQR against
``lq_gain`` as the sample shrinks; the band on hand-computed states (the law's function,
its first solve); the hold between solves and the hi-lo rule; a closed loop on an ISO C
road better than the passive car at 0 A; every corner of the full car; the options'
errors and the missing ``osqp``.
"""

from __future__ import annotations

import functools
import importlib.util
import itertools
from typing import Any

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg

from mrsuspension.control import Passive, make_controller
from mrsuspension.control import literature as L
from mrsuspension.control import mpc as M
from mrsuspension.engine import Simulation
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation.road import iso8608
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.measures.iso2631 import weighted_rms
from mrsuspension.vehicle import FullCar, QuarterCar

pytest.importorskip("osqp")

C_MIN, C_MAX = 2043.0, 10613.0  # the laws' default band [N s/m]
#: states x = (z_s - z_u, z_s', z_u - z_r, z_u') [m, m/s]
STATES = [
    (0.0, 0.1, 0.0, 0.0),
    (0.01, -0.2, 0.002, 0.4),
    (-0.02, 0.05, -0.003, -0.3),
    (0.005, 0.3, 0.001, 0.25),
]


# -- the QP ------------------------------------------------------------------------------
def test_with_the_band_inactive_the_first_move_is_the_sampled_data_lqr() -> None:
    """``-K_d x`` within 1e-6 (measured 5e-9 to 1e-8), ``K_d`` from scipy's discrete
    Riccati solve of the QP's own sampled model and cost; that model is the zero-order
    hold of ``quarter_car_model`` and that cost the LQ cost integrated over a sample."""
    car = QuarterCar()
    qp = M.problem(car, horizon=10, sample=2e-3)
    a, b, _ = L.quarter_car_model(car)
    # the sampled model: exp(A T) and int_0^T exp(A t) dt B
    np.testing.assert_allclose(qp.a_d, scipy.linalg.expm(a * 2e-3), rtol=1e-12, atol=1e-14)
    t = np.linspace(0.0, 2e-3, 201)  # exp(A t) on a 10 us grid, integrated by Simpson
    step = scipy.linalg.expm(a * 1e-5)
    phi = np.array(list(itertools.accumulate([np.eye(4)] * 201, lambda m, _: step @ m)))
    gamma = np.array([scipy.integrate.simpson(phi[: k + 1], x=t[: k + 1], axis=0) for k in
                      range(1, 201)]) @ b  # fmt: skip
    gamma = np.r_[np.zeros((1, 4, 1)), gamma]
    np.testing.assert_allclose(qp.b_d, gamma[-1], rtol=1e-7, atol=1e-14)
    # the sampled cost: z_s''^2 + w_r x_1^2 + w_t x_3^2 + w_f u^2 along x(t), u held
    x0, u = np.array(STATES[1]), 300.0
    xt = phi @ x0 + gamma[:, :, 0] * u
    acc = xt @ a[1] + b[1, 0] * u
    w = L.LQ_WEIGHTS
    integrand = acc**2 + w["w_rattle"] * xt[:, 0] ** 2 + w["w_tire"] * xt[:, 2] ** 2
    integrand += w["w_force"] * u**2
    z = np.r_[x0, u]
    assert z @ qp.m_d @ z == pytest.approx(scipy.integrate.simpson(integrand, x=t), rel=1e-7)
    # the first move against the discrete LQR of that model and cost
    q, r, s = qp.m_d[:4, :4], qp.m_d[4:, 4:], qp.m_d[:4, 4:]
    p = scipy.linalg.solve_discrete_are(qp.a_d, qp.b_d, q, r, s=s)
    k_d = np.linalg.solve(r + qp.b_d.T @ p @ qp.b_d, qp.b_d.T @ p @ qp.a_d + s.T)[0]
    for x in STATES:
        lqr = -float(k_d @ x)
        assert qp.first_move(x, lower=-1e9, upper=1e9) == pytest.approx(lqr, rel=1e-6), x


def test_the_sampled_data_lqr_tends_to_lq_gain_as_the_sample_shrinks() -> None:
    """The force is held over ``T_s``, so the sampled optimum differs from the continuous
    one by O(T_s): measured (max over the gains, relative) 3.5e-2 at 2 ms, 1.9e-3 at
    100 us, 1.9e-4 at 10 us; and the MPC's first move follows."""
    car = QuarterCar()
    k = L.lq_gain(car, **L.LQ_WEIGHTS)[0]
    errors = []
    for ts in (2e-3, 1e-4, 1e-5):
        qp = M.problem(car, horizon=4, sample=ts)
        errors.append(np.abs(qp.gain - k).max() / np.abs(k).max())
    assert errors[0] < 0.05, errors
    assert errors[1] < 3e-3, errors
    assert errors[2] < 3e-4, errors
    assert errors[2] < errors[1] / 5.0 < errors[0] / 25.0, errors
    for x in STATES:
        got = qp.first_move(x, lower=-1e9, upper=1e9)
        assert got == pytest.approx(-float(k @ x), rel=1e-3, abs=1e-3), x


# -- the law's function: the band, the hold, the hi-lo rule -------------------------------
@functools.cache
def _model() -> tuple[np.ndarray, np.ndarray]:
    ctl = make_controller("mpc").for_plant(QuarterCar())
    return np.array(ctl.A), np.array(ctl.B)


def _call(
    fn: Any, z_s_dot: float, z_u_dot: float, F_d: float = 0.0, memory: Any = None, **kw: Any
) -> tuple[float, np.ndarray]:
    """The law's function at the first sample of a run (``time`` 0, its memory zero),
    ``x_d`` = 0 and the tire deflection 0 (``z_u''`` from the wheel's equation)."""
    a, b = _model()
    memory = np.zeros(M.MEMORY) if memory is None else memory
    z_u_ddot = a[3, 1] * z_s_dot + a[3, 3] * z_u_dot + b[3] * F_d
    out = fn(
        x_d=0.0, v_d=z_u_dot - z_s_dot, z_s_dot=z_s_dot, z_u_dot=z_u_dot, z_u_ddot=z_u_ddot,
        F_d=F_d, time=kw.pop("time", 0.0), memory=memory, A=a, B=b, **kw,
    )  # fmt: skip
    return float(out), memory


def test_the_force_lies_in_the_band_with_the_sign_of_v_d() -> None:
    """Hand-picked: the body rising at 0.1 m/s, the wheel at 0.3 m/s, so ``v_d`` = +0.2
    m/s (the damper can only push the body up) while the LQR pulls it down (-K x =
    -281 N): the force is the band's least, ``c_min v_d`` = 2043 x 0.2 = 408.6 N, or 0
    with ``c_min`` = 0. The wheel at 0.09 m/s: ``v_d`` = -0.01 m/s, the LQR's -353 N is
    beyond the band's most, ``c_max v_d`` = -106.13 N. The wheel still: ``v_d`` = -0.1,
    the LQR's -384 N is inside the band: the force is the LQR's."""
    qp = M.problem(QuarterCar())
    lqr = -float(qp.gain @ [0.0, 0.1, 0.0, 0.3])
    assert lqr < -250.0  # the LQ force pushes against v_d > 0
    got, memory = _call(M.mpc.function, 0.1, 0.3)
    assert got == pytest.approx(C_MIN * 0.2, abs=1e-3)
    assert memory[0] == got
    assert memory[1] == pytest.approx(2e-3)  # held until 2 ms
    assert _call(M.mpc.function, 0.1, 0.3, c_min=0.0)[0] == pytest.approx(0.0, abs=1e-3)
    assert _call(M.mpc.function, 0.1, 0.09)[0] == pytest.approx(-C_MAX * 0.01, abs=1e-3)
    inside = _call(M.mpc.function, 0.1, 0.0)[0]
    assert inside == pytest.approx(-float(qp.gain @ [0.0, 0.1, 0.0, 0.0]), rel=1e-5)
    assert -C_MAX * 0.1 < inside < -C_MIN * 0.1


def test_the_force_is_held_between_solves_and_the_hilo_rule_compares_it_with_f_d() -> None:
    memory = np.zeros(M.MEMORY)
    memory[0], memory[1] = -500.0, 4e-3  # a target of -500 N held until 4 ms
    hold = functools.partial(_call, M.mpc_hilo.function, memory=memory, time=3.9e-3)
    assert hold(0.1, 0.0, F_d=-300.0)[0] == 0.5  # v_d < 0, |F*| above |F_d|: more
    assert hold(0.1, 0.0, F_d=-600.0)[0] == 0.0  # above F*: less
    assert hold(-0.1, 0.0, F_d=300.0)[0] == 0.0  # F* against v_d > 0: less
    assert _call(M.mpc.function, 0.1, 0.0, memory=memory, time=3.9e-3)[0] == -500.0
    assert memory[1] == 4e-3  # no solve before 4 ms


# -- closed loop ------------------------------------------------------------------------
def test_on_an_iso_c_road_the_mpc_beats_the_passive_car_at_0_a() -> None:
    """Quarter car, ISO 8608 class C at 72 km/h, 6 s (the first second left out):
    Wk-weighted rms body acceleration 1.223 m/s^2 against passive 0 A's 1.304 (lq-force
    1.257, clipped-lq 1.215, mpc-hilo 1.376, passive 0.5 A 1.883); the target held over
    every 2 ms (2999 changes in 6 s) and finite, the current within [0, 0.5] A."""
    road = iso8608("C", length=140.0, seed=1, speed_kmh=72.0)

    def run(controller: Any) -> tuple[float, Any]:
        r = Simulation(road, controller=controller).run(6.0, dt=5e-4, output_rate=2000.0)
        t = np.asarray(r.time)
        return weighted_rms(np.asarray(r["z_s_ddot"])[t >= 1.0], 2000.0), r

    got, r = run(make_controller("mpc"))
    passive, _ = run(Passive(0.0))
    assert got < 0.97 * passive, (got, passive)
    target, i_d = np.asarray(r["F_target"]), np.asarray(r["i_d"])
    assert np.all(np.isfinite(target))
    assert np.abs(target).max() < 2e4
    assert np.all((i_d >= 0.0) & (i_d <= 0.5))
    changes = np.count_nonzero(np.diff(target[1:]))  # one new force per 2 ms solve
    assert 2990 <= changes <= 3000, changes


def test_every_corner_of_the_full_car_runs_its_own_mpc() -> None:
    car = FullCar()
    road = WheelRoads.two_track(
        "C", (car.wheelbase, car.front_track), speed_kmh=72.0, length=20.0, seed=1
    )
    for law in ("mpc", "mpc-hilo"):
        res = VehicleSimulation(car, road, controllers=make_controller(law)).run(0.2, dt=2e-4)
        for c in car.corners:
            i_d = np.asarray(res[f"i_d.{c}"])
            assert np.all(np.isfinite(i_d)), (law, c)
            assert i_d.max() > 0.0, (law, c)
            assert np.all((i_d >= 0.0) & (i_d <= 0.5)), (law, c)
    models = [make_controller("mpc").for_plant(car.corner_quarter_car(c)).A for c in car.corners]
    assert models[0] != models[-1]  # front and rear: each corner's own model


# -- options and errors -------------------------------------------------------------------
@pytest.mark.parametrize(
    ("options", "words"),
    [
        ({"horizon": 10.5}, "horizon N must be a whole number of samples in [1, 50]; got 10.5"),
        ({"horizon": 0.0}, "horizon"),
        ({"horizon": 60.0}, "got 60"),
        ({"sample": 0.0}, "sample must be in [0.0001, 0.05]; got 0"),
        ({"w_force": 0.0}, "w_force"),
        ({"w_tire": -1.0}, "w_tire"),
        ({"c_min": 5000.0, "c_max": 3000.0}, "c_min must be <= c_max"),
    ],
)
def test_bad_options_are_refused_naming_them(options: dict[str, float], words: str) -> None:
    for law in ("mpc", "mpc-hilo"):
        with pytest.raises(ValidationError) as err:
            make_controller(law, **options)
        assert words in str(err.value), str(err.value)


def test_without_osqp_the_error_names_the_extra(monkeypatch: pytest.MonkeyPatch) -> None:
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "osqp" else real(name, *a)
    )
    with pytest.raises(ValidationError, match=r'need osqp.*pip install "mrsuspension\[optimal\]"'):
        Simulation(iso8608("C", length=50.0), controller=make_controller("mpc"))
