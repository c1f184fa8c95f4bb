"""Whole-vehicle semi-active MPC for the half and full car (control/vehicle_lq.py
``VehicleMPC``, issue 29).

* known answer: with the band inactive the QP's first move is the sampled-data LQR
  ``-K_d H^+ x`` of the same sampled model and cost (``scipy.linalg.solve_discrete_are``
  here), and the sampled model is the relative model's zero-order hold;
* the band: each force inside its corner's band at the first sample, and a band of zero
  width (``c_min = c_max``) gives exactly ``c v_d``; the entry the step calls (the
  buffer's layout, the plan, the next solve's time) by hand;
* on the full car over an ISO C road: the targets held over each sample, hi-lo by Dyke's
  rule; the seat comfort beside passive 0 A and ``vehicle-lq`` (printed);
* a failing solve stops the run and is raised; the quarter car is refused naming the
  per-corner law; options are checked and a scenario names them.
"""

from __future__ import annotations

import ctypes
from typing import Any

import numpy as np
import pytest

pytest.importorskip("osqp")

from mrsuspension.control import VEHICLE_LAWS
from mrsuspension.control.literature import LQ_WEIGHTS
from mrsuspension.control.vehicle_lq import (
    MB_HOLD,
    MB_PLAN,
    MB_VD,
    MB_X,
    VehicleLQ,
    VehicleMPC,
    VehicleMPCActive,
    lq_design,
    relative_model,
)
from mrsuspension.engine.vehicle import VehicleSimulation
from mrsuspension.errors import MRSuspensionError, ValidationError
from mrsuspension.excitation import Harmonic
from mrsuspension.excitation.wheels import WheelRoads
from mrsuspension.vehicle import FullCar, HalfCar


@pytest.fixture(scope="module")
def full() -> Any:
    return VehicleMPC().for_vehicle(FullCar())


def _states(car: Any, seed: int) -> list[np.ndarray]:
    """Two states of the law's layout: one the car reaches with the road at rest
    (``H x_a``) and one with the road's twist too (any ``x``)."""
    d = lq_design(car, **LQ_WEIGHTS)
    rng = np.random.default_rng(seed)
    n = len(car.corners)
    scale = np.concatenate([np.full(n, 0.01), [0.1, 0.05, 0.05], np.full(n, 0.002),
                            np.full(n, 0.3)])  # fmt: skip
    reach = d.H @ (np.linalg.pinv(d.H) @ (scale * rng.standard_normal(scale.size)))
    return [reach, scale * rng.standard_normal(scale.size)]


# -- the QP ---------------------------------------------------------------------------------
@pytest.mark.parametrize("car", [FullCar(), HalfCar()], ids=["full", "half"])
def test_with_the_band_inactive_the_first_move_is_the_sampled_data_lqr(car: Any) -> None:
    import scipy.linalg

    law = VehicleMPC().for_vehicle(car)
    pr = law.problem()
    qp = pr.qp
    d = lq_design(car, **LQ_WEIGHTS)
    ts = law.sample_time
    # the sampled model is the relative model's zero-order hold on the states it reaches
    a, b, _, _ = relative_model(car)
    np.testing.assert_allclose(d.H @ qp.a_d, scipy.linalg.expm(a * ts) @ d.H, atol=1e-10)
    # the LQR of the same sampled model and cost, solved here
    na = qp.a_d.shape[0]
    q, r, s = qp.m_d[:na, :na], qp.m_d[na:, na:], qp.m_d[:na, na:]
    p = scipy.linalg.solve_discrete_are(qp.a_d, qp.b_d, q, r, s=s)
    bp = qp.b_d.T @ p
    k_d = np.linalg.solve(r + bp @ qp.b_d, bp @ qp.a_d + s.T) @ np.linalg.pinv(d.H)
    for x in _states(car, 1):
        lqr = -(k_d @ x)
        got = pr.solve(x, -1e9, 1e9)[0]
        assert np.abs(got - lqr).max() <= 1e-6 * np.abs(lqr).max(), (got, lqr)
    # and K_d is near the continuous design's K (T_s -> 0: the whole-vehicle LQ)
    assert np.abs(k_d - d.K).max() < 0.1 * np.abs(d.K).max()
    assert b.shape[1] == len(car.corners)


def test_every_force_lies_in_its_corners_band_and_a_zero_width_band_is_c_v_d(full: Any) -> None:
    pr = full.problem()
    n, nh = 4, pr.horizon
    x = _states(FullCar(), 2)[1]
    vd = np.array([0.2, -0.1, 0.05, -0.3])  # m/s: compression at 0 and 2, rebound at 1 and 3
    plan = np.zeros((nh, n))
    lower, upper = pr.band(x, vd, plan)
    # the first sample's band from the measured v_d: [2043, 10613] N s/m times v_d
    np.testing.assert_allclose(lower[0], np.minimum(2043.0 * vd, 10613.0 * vd))
    np.testing.assert_allclose(upper[0], np.maximum(2043.0 * vd, 10613.0 * vd))
    assert np.all(lower[1:] <= upper[1:])
    u = pr.solve(x, lower, upper)
    assert np.all(lower - 1e-9 <= u)
    assert np.all(u <= upper + 1e-9)
    assert np.all(u[0] * vd > 0.0)  # dissipative: the sign of v_d
    unconstrained = pr.solve(x, -1e9, 1e9)[0]
    assert not np.allclose(unconstrained, u[0], rtol=0.01)  # the band is active
    # a band of zero width: the force is c v_d exactly
    narrow = VehicleMPC(band_low=5000.0, band_high=5000.0).for_vehicle(FullCar()).problem()
    first = narrow.step(x, vd, np.zeros((nh, n)))
    np.testing.assert_allclose(first, 5000.0 * vd, rtol=1e-9)


def test_the_entry_reads_the_buffer_and_writes_forces_plan_and_next_solve(full: Any) -> None:
    """The entry as the compiled step calls it (its address in ``params()``)."""
    pr = full.problem()
    rows, width = full.buffer_shape(4)
    assert (rows, width) == (MB_PLAN + 10, 16)
    mbuf = np.zeros((rows, width))
    x = _states(FullCar(), 3)[0]
    vd = np.array([0.2, -0.1, 0.05, -0.3])
    mbuf[MB_X, :15] = x
    mbuf[MB_X, 15] = 0.0042  # the time [s]
    mbuf[MB_VD, :4] = vd
    assert full.params()[-2] == pr.address
    fn = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_int64)(
        pr.address
    )
    forces = np.zeros(16)
    out = fn(mbuf[MB_X:].ctypes.data, forces.ctypes.data, 4)
    assert out == 0.0
    expected = pr.step(x, vd, np.zeros((10, 4)))
    np.testing.assert_allclose(forces[:4], expected, rtol=1e-6, atol=1e-6)
    assert np.all(forces[4:] == 0.0)
    np.testing.assert_allclose(mbuf[MB_PLAN, :4], forces[:4])  # the plan kept in the buffer
    assert mbuf[MB_HOLD, 0] == pytest.approx(0.006)  # the next 2 ms sample


# -- closed loop on the full car ---------------------------------------------------------------
def test_on_an_iso_c_road_the_targets_are_held_and_switched_by_dykes_rule() -> None:
    car = FullCar()
    road = WheelRoads.two_track("C", (car.wheelbase, car.front_track), 72.0, length=60.0, seed=3)
    comfort = {}
    runs = {}
    for name, law in {"passive 0 A": None, "vehicle-lq": VehicleLQ(),
                      "vehicle-mpc": VehicleMPC(),
                      "vehicle-mpc-active": VehicleMPCActive()}.items():  # fmt: skip
        sim = VehicleSimulation(car, road, body_control=law)
        res = sim.run(3.0, dt=2e-4, output_rate=5000.0)
        for key in ("heave_ddot", "pitch_ddot", "roll_ddot"):
            assert np.all(np.isfinite(np.asarray(res[key]))), (name, key)
        comfort[name] = float(res.vehicle_measures()["seat_total"])
        runs[name] = (sim, res)
    print("seat total [m/s^2]:", {k: round(v, 4) for k, v in comfort.items()})
    assert all(0.1 < v < 10.0 for v in comfort.values()), comfort
    sim, res = runs["vehicle-mpc"]
    qp = sim.body_control.problem().qp
    assert qp.unfinished == 0
    high = 0
    for c in car.corners:
        target = np.asarray(res[f"F_target.{c}"])[1:]  # row r: step r's target
        steps = np.arange(target.size)
        new = steps % 10 == 0  # a solve every 2 ms = 10 steps of 0.2 ms
        held = np.diff(target)[~new[1:]]
        assert np.all(held == 0.0)  # held between solves
        assert np.count_nonzero(np.diff(target)[new[1:]]) > 0.9 * new[1:].sum()
        # the band at the solve: the sign of the stroke rate the law saw (v_d = z_u' - z_s')
        i_d = np.asarray(res[f"i_d.{c}"])[1:]
        f_d = np.asarray(res[f"F_d.{c}"])[:-1]  # the load cell: the step before's force
        achievable = (target - f_d) * f_d > 0.0  # Dyke et al.'s clipped-optimal rule
        assert np.array_equal(i_d == 0.5, achievable)
        high += int(achievable.sum())
    assert 0.02 < high / (4 * res.time.size) < 0.6
    # the ideal actuator applies the held target itself, inside the band: no current
    _, res = runs["vehicle-mpc-active"]
    pushes = []
    for c in car.corners:
        target = np.asarray(res[f"F_target.{c}"])[1:]
        assert np.array_equal(np.asarray(res[f"F_d.{c}"])[1:], target)
        assert np.all(np.asarray(res[f"i_d.{c}"]) == 0.0)
        v_d = np.asarray(res[f"z_u_dot.{c}"]) - np.asarray(res[f"z_s_dot.{c}"])
        solve = np.arange(target.size) % 10 == 0
        # dissipative where solved (the band on the stroke rate then); held over T_s, the
        # force can push where v_d changes sign within the sample
        assert np.all(target[solve] * v_d[:-1][solve] >= 0.0)
        pushes.append(round(100 * float(np.mean(target * v_d[:-1] < 0.0)), 1))
    print("vehicle-mpc-active: share of steps its held force pushes [%]:", pushes)
    assert max(pushes) < 10.0


def test_a_failing_solve_stops_the_run_and_is_raised(monkeypatch: pytest.MonkeyPatch) -> None:
    car = HalfCar()
    law = VehicleMPC(sample_time=3e-3).for_vehicle(car)  # its own problem: not shared

    def broken(*args: Any) -> Any:
        raise RuntimeError("the QP broke")

    monkeypatch.setattr(law.problem(), "step", broken)
    sim = VehicleSimulation(car, WheelRoads.in_phase(Harmonic(2.0, 0.01), car), body_control=law)
    with pytest.raises(MRSuspensionError, match="'vehicle-mpc' raised RuntimeError: the QP broke"):
        sim.run(0.05, dt=2e-4)


# -- options, scenarios (the quarter car: test_vehicle_lq.py) ------------------------------------------------------
@pytest.mark.parametrize(
    ("options", "words"),
    [({"horizon_samples": 2.5}, "horizon_samples N must be a whole number"),
     ({"horizon_samples": 0.0}, "horizon_samples must be in"),
     ({"sample_time": 1.0}, "sample_time must be in"),
     ({"band_low": 2e4}, "band_low must be <= band_high"),
     ({"force_weight": 0.0}, "force_weight must be in")],
)  # fmt: skip
def test_bad_options_are_refused_naming_them(options: dict[str, float], words: str) -> None:
    with pytest.raises(ValidationError, match=words):
        VehicleMPC(**options)


def test_a_scenario_names_the_law_with_its_options() -> None:
    from mrsuspension.scenario import Scenario

    assert VEHICLE_LAWS["vehicle-mpc"] is VehicleMPC
    tables = {
        "vehicle": {"model": "half-car"},
        "excitation": {"kind": "harmonic", "frequency": 1.5, "amplitude": 0.01},
        "controller": {"law": "vehicle-mpc", "horizon_samples": 5, "sample_time": 1e-3},
    }
    law = Scenario.from_dict(tables).body_control
    assert isinstance(law, VehicleMPC)
    assert (law.horizon_samples, law.sample_time) == (5, 1e-3)
    assert law.problem().horizon == 5
    assert isinstance(law.problem().entry.address, int)
