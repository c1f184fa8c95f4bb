"""Contract every fit model passes (like the damper contract test): parameter vector
round trip, bounds containing the start, finite force on a loop, analytic Jacobian equal
to finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import make_damper
from mrsuspension.identify.fit import FitProblem
from mrsuspension.identify.models import FIT_MODELS
from mrsuspension.identify.preprocess import Loop

# Spencer's causal response over repeated cycles is slow: one loop, one cycle
OPTIONS = {"spencer": {"cycles": 1}}


def loops(model: str) -> list[Loop]:
    damper = make_damper(model)
    out = []
    for f, a, i in [(1.5, 0.0125, 0.0), (2.5, 0.0125, 0.2)][: 1 if model == "spencer" else 2]:
        h = harmonic_loop(damper, f, a, i)
        w = 2 * math.pi * f
        out.append(
            Loop("t", h.time, h.stroke, h.velocity, -h.stroke * w * w, h.force, h.current,
                 f, a, h.peak_velocity)
        )  # fmt: skip
    return out


@pytest.fixture(params=sorted(FIT_MODELS), scope="module")
def problem(request: pytest.FixtureRequest) -> FitProblem:
    model = request.param
    return FitProblem(loops(model), model, model_options=OPTIONS.get(model))


def test_parameter_vector_round_trip(problem: FitProblem) -> None:
    values = problem.values(problem.x_start)
    assert list(values) == problem.names
    back = np.array([values[k] for k in problem.free])
    np.testing.assert_array_equal(back, problem.x_start)
    pset = problem.spec.build(values, problem.max_current)
    assert dict(pset.values) == pytest.approx(values)


def test_bounds_contain_the_start(problem: FitProblem) -> None:
    assert np.all(problem.lower < problem.upper)
    assert np.all(problem.lower <= problem.x_start)
    assert np.all(problem.x_start <= problem.upper)
    for theta in problem.starts(3, seed=1, screen=8):
        assert np.all((problem.lower <= theta) & (theta <= problem.upper))


def test_force_is_finite_on_a_loop(problem: FitProblem) -> None:
    force = problem.model_force(problem.x_start)
    assert force.shape == problem.data.force.shape
    assert np.all(np.isfinite(force))


def test_analytic_jacobian_matches_finite_differences(problem: FitProblem) -> None:
    if not problem.spec.analytic:
        pytest.skip(f"{problem.spec.name}: no analytic Jacobian (finite differences)")
    x = problem.x_start
    jac = problem.jacobian(x)
    num = np.empty_like(jac)
    for j in range(x.size):
        h = 1e-6 * max(abs(x[j]), 1e-2)
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        num[:, j] = (problem.residuals(xp) - problem.residuals(xm)) / (2 * h)
    scale = np.maximum(np.abs(num).max(axis=0), 1e-12)
    assert np.max(np.abs(jac - num) / scale) < 1e-4
