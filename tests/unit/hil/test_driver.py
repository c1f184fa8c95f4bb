"""PI drive-current regulator (section 7.2.2): step response, anti-windup, 12-bit D/A."""

from __future__ import annotations

import math

import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.hil import PICurrentDriver

RATE = 1000.0
TAU = 0.008  # coil + amplifier time constant [s]


def _coil_run(driver: PICurrentDriver, refs: list[float]) -> tuple[list[float], list[float]]:
    """Regulate a first-order coil (exact discretisation) through the driver."""
    a = math.exp(-1.0 / (RATE * TAU))
    i = 0.0
    currents, outputs = [], []
    for r in refs:
        u = driver.update(r, i * driver.sense_resistance)
        i = a * i + (1.0 - a) * u
        currents.append(i)
        outputs.append(u)
    return currents, outputs


def test_step_response_reaches_setpoint() -> None:
    drv = PICurrentDriver()
    drv.reset(1.0 / RATE)
    currents, _ = _coil_run(drv, [0.1] * 200)
    assert abs(currents[-1] - 0.1) < 2 * drv.da_full_scale / 4096
    # faster than the open coil: within 5 % after 3 time constants (open loop: 95 % at 3 tau)
    k = round(3 * TAU * RATE)
    assert abs(currents[k] - 0.1) < 0.05 * 0.1
    # and not much overshoot
    assert max(currents) < 0.1 * 1.3


def test_anti_windup_recovers_at_once() -> None:
    drv = PICurrentDriver()
    drv.reset(1.0 / RATE)
    _, outputs = _coil_run(drv, [0.6] * 500)  # asks for twice the limit for 0.5 s
    assert max(outputs) <= drv.current_limit + 1e-12
    assert drv.integral <= drv.current_limit + 1e-9  # no wind-up
    currents, _ = _coil_run(drv, [0.05] * 100)
    # a wound-up integrator would hold the output high for long; here it comes down fast
    assert abs(currents[40] - 0.05) < 0.01
    assert abs(currents[-1] - 0.05) < 0.002


def test_twelve_bit_output_and_limits() -> None:
    drv = PICurrentDriver()
    drv.reset(1.0 / RATE)
    lsb = drv.da_full_scale / 4096
    _, outputs = _coil_run(drv, [0.0123, 0.2, 0.07, 0.29] * 50)
    for u in outputs:
        assert 0.0 <= u <= drv.current_limit
        assert abs(u / lsb - round(u / lsb)) < 1e-9
    assert drv.direct(0.5) <= drv.current_limit
    assert drv.direct(-1.0) == 0.0
    assert drv.off() == 0.0
    assert drv.integral == 0.0


def test_unquantised_driver_is_exact() -> None:
    drv = PICurrentDriver(bits=0)
    drv.reset(1.0 / RATE)
    assert drv.direct(0.0123) == pytest.approx(0.0123, abs=0)


def test_invalid_gain_named() -> None:
    with pytest.raises(ValidationError, match="ki"):
        PICurrentDriver(ki=-1.0)
