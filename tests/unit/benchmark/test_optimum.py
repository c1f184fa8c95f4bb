"""The semi-active optimum: a known answer, the band, the bound on other laws, the front.

One short road (0.6 s of ISO 8608 class C at 50 km/h, 2 ms grid) serves every test; the
MR-band problem is built once (its NLP too: the weights are parameters).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.benchmark import (
    ActiveBand,
    BenchmarkProblem,
    LinearBand,
    MRBand,
    OptimumResult,
    Weights,
    pareto_front,
    replay,
)
from mrsuspension.benchmark.model import linear_quarter_car
from mrsuspension.control import Passive
from mrsuspension.dampers import WangSymmetric
from mrsuspension.engine import Simulation
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import iso8608
from mrsuspension.vehicle import QuarterCar

DURATION = 0.6
DT = 2e-3


@pytest.fixture(scope="module")
def road():  # type: ignore[no-untyped-def]
    return iso8608("C", length=20.0, seed=5, speed_kmh=50.0)


@pytest.fixture(scope="module")
def problem(road) -> BenchmarkProblem:  # type: ignore[no-untyped-def]
    return BenchmarkProblem(road, band=MRBand(), dt=DT, duration=DURATION)


@pytest.fixture(scope="module")
def optimum(problem: BenchmarkProblem) -> OptimumResult:
    return problem.solve(tol=1e-9)


def _lq_by_least_squares(problem: BenchmarkProblem, coeff: np.ndarray) -> tuple[np.ndarray, float]:
    """The same discrete LQ problem solved independently: condensed, dense least squares.

    Discretised here from the continuous matrices (trapezoidal rule, force held over the
    interval), every output written as an affine function of the N forces, then
    ``min sum_k q_k sum_j c_j y_jk^2`` by its normal equations.
    """
    lin = linear_quarter_car(problem.vehicle)
    h, n = problem.dt, problem.n
    m = np.eye(12) - 0.5 * h * lin.a
    phi = np.linalg.solve(m, np.eye(12) + 0.5 * h * lin.a)
    gam = np.linalg.solve(m, h * lin.b)
    lam = np.linalg.solve(m, 0.5 * h * lin.e)
    r = problem.road_samples
    # free response (zero force) and the response to a unit force in each interval
    x = np.zeros((12, n + 1))
    x[0, 0] = x[2, 0] = r[0, 0]
    for k in range(n):
        x[:, k + 1] = phi @ x[:, k] + lam @ (r[:, k] + r[:, k + 1])
    y0 = lin.c @ x + lin.e_y @ r  # (3, n+1)
    g = np.zeros((3, n + 1, n))
    xs = np.zeros((12, n))  # state response to each column's unit force
    for k in range(n):
        xs = phi @ xs
        xs[:, k] += gam
        g[:, k + 1, :] = lin.c @ xs
    q = np.full(n + 1, h)
    q[0] = q[-1] = 0.5 * h
    q /= n * h
    wsq = np.sqrt(coeff[:, None] * q[None, :])  # (3, n+1)
    a = (wsq[:, :, None] * g).reshape(-1, n)
    b = -(wsq * y0).ravel()
    # normal equations (square, 400 x 400): a QR or SVD of the tall matrix takes seconds
    # when OpenBLAS's threads share two loaded cores
    force = np.linalg.solve(a.T @ a, a.T @ b)
    resid = a @ force - b
    return force, float(resid @ resid)


def test_wide_band_gives_the_linear_quadratic_optimum(road) -> None:  # type: ignore[no-untyped-def]
    car = QuarterCar()
    scales = (1.0, 0.1 * car.static_load, 0.01)
    weights = Weights(comfort=1.0, road_holding=0.5, rattle=0.2)
    lq = BenchmarkProblem(
        road, band=ActiveBand(), weights=weights, dt=DT, duration=DURATION, scales=scales
    )
    best = lq.solve(tol=1e-10)
    assert best.success, best.status
    coeff = np.array([w / s**2 for w, s in zip(weights.vector, scales, strict=True)])
    force, cost = _lq_by_least_squares(lq, coeff)
    assert np.linalg.norm(best.force - force) <= 1e-4 * np.linalg.norm(force)
    assert best.cost == pytest.approx(cost, rel=1e-4)
    # the cost of the LQ force on the optimum's own model is the least-squares cost
    assert lq.evaluate(force).cost == pytest.approx(cost, rel=1e-9)


def test_a_band_of_one_damper_gives_that_damper(road) -> None:  # type: ignore[no-untyped-def]
    """``c_min = c_max``: the only feasible law is the linear damper; the optimum is it."""
    one = BenchmarkProblem(
        road, band=LinearBand(2500.0, 2500.0), dt=DT, duration=0.4, scales=(1.0, 600.0, 0.01)
    )
    best = one.solve()
    assert best.success, best.status
    passive = one.passive()
    assert np.allclose(best.force, passive.force, rtol=0, atol=1e-6 * np.max(np.abs(passive.force)))
    assert np.allclose(best.force, 2500.0 * best.interval_velocity, rtol=1e-9, atol=1e-6)
    assert best.cost == pytest.approx(passive.cost, rel=1e-8)


def test_the_optimal_force_stays_inside_the_band(
    problem: BenchmarkProblem, optimum: OptimumResult
) -> None:
    assert optimum.success, optimum.status
    assert optimum.iterations > 0
    assert optimum.wall_time > 0
    band = problem.band
    assert isinstance(band, MRBand)
    # every interval: inside [F_min(v), F_max(v)] to the solver's tolerance, dissipative
    scale = float(np.max(np.abs(optimum.force)))
    assert optimum.band_violation(band) <= 1e-6 * scale
    v = optimum.interval_velocity
    assert np.all(optimum.force * v >= -1e-6 * scale * np.abs(v))
    assert np.all((optimum.u >= -1e-8) & (optimum.u <= 1 + 1e-8))
    # and it is the damper model's own force at the current the band reports
    moving = np.abs(v) > 1e-3
    assert optimum.current is not None
    model = WangSymmetric(hysteresis=False).force(
        0.0, v[moving], 0.0, optimum.current[moving], peak_velocity=band.peak_velocity
    )
    assert np.allclose(model, optimum.force[moving], rtol=1e-6, atol=1e-3)
    assert 0.0 <= optimum.measures["mean_current"] <= band.max_current
    # the optimum uses the band: neither edge all the time
    assert 0.05 < float(np.mean(optimum.u)) < 0.95


def test_optimum_costs_no_more_than_passive_or_skyhook(
    problem: BenchmarkProblem, optimum: OptimumResult
) -> None:
    others = [
        problem.passive(),
        problem.passive(u=1.0),
        problem.passive(u=0.3),
        problem.skyhook(),
        problem.skyhook(2000.0),
    ]
    for other in others:
        assert optimum.cost <= other.cost, other.label
    assert optimum.cost < 0.95 * problem.passive().cost
    assert problem.passive().cost == pytest.approx(sum(problem.weights.vector))


def test_engine_agrees_with_the_discretised_model(
    road,  # type: ignore[no-untyped-def]
    problem: BenchmarkProblem,
    optimum: OptimumResult,
) -> None:
    """Re-simulated with the toolkit's engine (RK4 at 0.1 ms, nonlinear tyre): within 3 %."""
    band = problem.band
    assert isinstance(band, MRBand)
    damper = WangSymmetric(hysteresis=False, estimator="known", value=band.peak_velocity)
    engine = Simulation(road, damper=damper, controller=Passive(0.0)).run(duration=DURATION)
    mine = problem.passive().measures
    theirs = engine.measures()
    for name in ("DLC", "wk_rms_body_acceleration", "rms_stroke"):
        assert mine[name] == pytest.approx(theirs[name], rel=0.03), name
    replayed = replay(optimum, road, vehicle=problem.vehicle)
    for name in ("DLC", "wk_rms_body_acceleration", "rms_stroke"):
        assert optimum.measures[name] == pytest.approx(replayed[name], rel=0.03), name


def test_pareto_front_is_monotone(problem: BenchmarkProblem) -> None:
    front = pareto_front(problem, (0.15, 0.5, 0.85), rattle=0.0, tol=1e-9)
    assert [r.success for r in front.results] == [True] * 3
    # more weight on comfort: never worse comfort, never better road holding
    assert np.all(np.diff(front.comfort) <= 1e-9 * front.comfort[0])
    assert np.all(np.diff(front.road_holding) >= -1e-9 * front.road_holding[0])
    assert front.comfort[-1] < front.comfort[0]
    assert front.road_holding[-1] > front.road_holding[0]
    # every point of the front beats the passive car on its own weighted cost
    for r in front.results:
        assert r.passive is not None
        assert r.cost <= r.passive.cost


def test_inputs_are_checked(road) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(ValidationError, match="dt must be in"):
        BenchmarkProblem(road, dt=0.01)
    with pytest.raises(ValidationError, match="at least one weight must be > 0"):
        Weights(0.0, 0.0, 0.0)
    with pytest.raises(ValidationError, match="scales must be three numbers"):
        BenchmarkProblem(road, duration=0.1, scales=(1.0, 2.0))
    p = BenchmarkProblem(road, duration=0.1, dt=2e-3)
    with pytest.raises(ValidationError, match="force must have 50 values"):
        p.evaluate(np.zeros(3))


def test_missing_casadi_names_the_extra(monkeypatch: pytest.MonkeyPatch, road) -> None:  # type: ignore[no-untyped-def]
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "casadi" else real(name, *a)
    )
    with pytest.raises(ValidationError, match=r'pip install "mrsuspension\[optimal\]"'):
        BenchmarkProblem(road, duration=0.1).solve()
    assert math.isfinite(BenchmarkProblem(road, duration=0.1).passive().cost)  # no CasADi needed
