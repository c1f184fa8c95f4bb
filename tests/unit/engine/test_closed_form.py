"""The engine against the exact frequency response of the linear quarter car, and RK4 order."""

from __future__ import annotations

import numpy as np
import pytest

from mrsuspension.dampers import LinearViscous
from mrsuspension.engine import Simulation
from mrsuspension.excitation import Harmonic, RoundedPulse, log_frequencies, two_stage_amplitude
from mrsuspension.vehicle import QuarterCar, linear_frequency_response

C = 2500.0  # N s/m, the reference model's c_0
FREQS = log_frequencies(30, 0.5, 15.0)


@pytest.fixture(scope="module")
def sweep() -> list[dict]:
    car = QuarterCar()
    out = []
    for f in FREQS:
        a = float(two_stage_amplitude(f, 0.01))  # small: no tire lift-off
        sim = Simulation(Harmonic(f, a), vehicle=car, damper=LinearViscous(damping=C))
        res = sim.run(dt=1e-4, output_rate=10_000.0)
        m = res.measures()
        assert res.F_T.min() > 0.0  # the linear model holds only without lift-off
        out.append({"f": f, "a": a, **m})
    return out


@pytest.mark.parametrize("key", ["T_as", "T_dr", "DLC", "T_au"])
def test_matches_exact_linear_response(sweep: list[dict], key: str) -> None:
    car = QuarterCar()
    exact = linear_frequency_response(car, C, FREQS)
    for row, ref in zip(sweep, exact[key], strict=True):
        expected = ref * (row["a"] if key == "DLC" else 1.0)
        assert row[key] == pytest.approx(expected, rel=5e-3), (key, row["f"])


def test_exact_response_sanity() -> None:
    """The closed form itself: static limit and undamped resonance locations."""
    car = QuarterCar()
    r = linear_frequency_response(car, 1e-9, [1e-4])
    assert r["T_as"][0] == pytest.approx(1.0, abs=1e-6)
    assert r["T_dr"][0] == pytest.approx(0.0, abs=1e-6)
    f1, f2 = car.undamped_frequencies()
    near = linear_frequency_response(car, 1.0, [f1, f2])
    assert near["T_as"][0] > 50.0  # lightly damped resonance
    assert near["T_au"][1] > 5.0


def _final_state(dt: float) -> np.ndarray:
    sim = Simulation(
        RoundedPulse(0.02, 2.0, delay=0.05),
        damper=LinearViscous(damping=C),
        vehicle=QuarterCar(tire_damping=100.0),
    )
    res = sim.run(0.4, dt=dt, output_rate=1.0 / dt)
    return np.array([res.z_s[-1], res.z_s_dot[-1], res.z_u[-1], res.z_u_dot[-1]])


def test_rk4_converges_at_fourth_order() -> None:
    dts = [4e-3, 2e-3, 1e-3, 5e-4]
    states = [_final_state(dt) for dt in dts]
    reference = _final_state(1.25e-4)
    errors = [np.max(np.abs(s - reference) / (np.abs(reference) + 1e-3)) for s in states]
    ratios = [errors[k] / errors[k + 1] for k in range(len(errors) - 1)]
    for r in ratios:
        assert 12.0 < r < 20.0, (errors, ratios)  # 2^4 = 16
    assert errors[-1] < 1e-7
