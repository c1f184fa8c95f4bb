"""The half car's optimum: two decoupled quarter cars are the quarter car; the band holds."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.benchmark import BenchmarkProblem, HalfCarProblem, MRBand
from mrsuspension.errors import ValidationError
from mrsuspension.excitation import iso8608
from mrsuspension.vehicle import HalfCar, QuarterCar


@pytest.fixture(scope="module")
def road():  # type: ignore[no-untyped-def]
    return iso8608("C", length=30.0, seed=5, speed_kmh=50.0)


def test_decoupled_half_car_on_one_road_is_the_quarter_car(road) -> None:  # type: ignore[no-untyped-def]
    """Corners of the quarter car, I_y = m_s a b, no delay: each axle is the quarter car,
    the heave acceleration its body acceleration, so the optimum is the quarter car's."""
    half = HalfCarProblem(
        road, vehicle=HalfCar.from_quarter_car(QuarterCar()), delay=0.0, dt=2e-3, duration=0.3
    )
    quarter = BenchmarkProblem(road, dt=2e-3, duration=0.3)
    hp, qp = half.passive(), quarter.passive()
    assert np.allclose(hp.force, qp.force[None, :], rtol=0, atol=1e-6 * np.max(np.abs(qp.force)))
    assert hp.measures["DLC.rear"] == pytest.approx(qp.measures["DLC"], rel=1e-6)
    assert hp.measures["wk_rms_heave_acceleration"] == pytest.approx(
        qp.measures["wk_rms_body_acceleration"], rel=1e-6
    )
    hb, qb = half.solve(), quarter.solve()
    assert hb.success, hb.status
    assert hb.cost == pytest.approx(qb.cost, rel=1e-6)
    for j in range(2):
        assert np.linalg.norm(hb.force[j] - qb.force) <= 1e-4 * np.linalg.norm(qb.force)


def test_half_car_optimum_stays_in_the_band_and_beats_passive(road) -> None:  # type: ignore[no-untyped-def]
    problem = HalfCarProblem(road, dt=2e-3, duration=0.4)
    assert problem.delay == pytest.approx(HalfCar().wheelbase / (50.0 / 3.6))
    passive = problem.passive()
    best = problem.solve()
    assert best.success, best.status
    assert best.cost < 0.95 * passive.cost
    assert passive.cost == pytest.approx(2.1)
    band = problem.band
    assert isinstance(band, MRBand)
    assert best.band_violation(band) <= 1e-6 * float(np.max(np.abs(best.force)))
    assert np.all(best.force * best.interval_velocity >= -1e-3)
    assert passive.band_violation(band) <= 1e-6 * float(np.max(np.abs(passive.force)))
    # the rear axle's road is the front's, later: the front reaches it first
    r, t = problem.road_samples, problem.time
    late = t >= problem.delay
    front_then = np.interp(t[late] - problem.delay, t, r[0])
    assert np.allclose(r[1, late], front_then, atol=2e-4)  # linear interpolation of 2 ms
    assert not np.allclose(r[1], r[0], atol=2e-4)


def test_half_car_needs_a_delay_or_a_speed() -> None:
    from mrsuspension.excitation import Harmonic

    with pytest.raises(ValidationError, match="give delay"):
        HalfCarProblem(Harmonic(1.5, 0.01), duration=0.5)
