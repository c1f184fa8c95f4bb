"""Shock measures (3.41)/(3.44) on hand-made records."""

from __future__ import annotations

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.excitation import RoundedPulse
from mrsuspension.measures import dtr, peak, shock_ratios


def test_ratios_use_peaks_of_absolute_values():
    z_r = np.array([0.0, 0.01, 0.05, 0.01, 0.0])
    acc_r = np.array([0.0, 40.0, -10.0, 5.0, 0.0])
    z_s = np.array([0.0, -0.03, 0.02, 0.01, 0.0])  # negative excursion is the peak
    acc_s = np.array([0.0, 2.0, -8.0, 1.0, 0.0])
    z_u = np.array([0.0, 0.02, 0.06, 0.0, -0.01])
    acc_u = np.array([0.0, -60.0, 20.0, 0.0, 0.0])
    x_d = z_u - z_s
    r = shock_ratios(z_s, z_u, z_r, acc_s, acc_u, acc_r, x_d)
    assert r == pytest.approx(
        {"SDR_s": 0.6, "SAR_s": 0.2, "SDR_u": 1.2, "SAR_u": 1.5, "RDR": 0.05 / 0.05}
    )
    assert list(r) == ["SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR"]


def test_ratios_of_a_pulse_passed_through_unchanged_are_one():
    p = RoundedPulse(0.035, 2.0)
    t = np.linspace(0.0, p.duration, 5001)
    z, a = p.displacement(t), p.acceleration(t)
    r = shock_ratios(z, z, z, a, a, a, 0.0 * z)
    assert r["SDR_s"] == r["SAR_s"] == r["SDR_u"] == r["SAR_u"] == 1.0
    assert r["RDR"] == 0.0


def test_shock_ratio_errors():
    ok = np.ones(3)
    _raises(lambda: shock_ratios(ok, ok, np.zeros(3), ok, ok, ok, ok), "z_r", "zero")
    _raises(lambda: shock_ratios(ok, ok, ok, ok, ok, np.zeros(3), ok), "acc_r", "zero")
    _raises(lambda: shock_ratios(ok, ok, ok, ok, ok, ok, np.ones(4)), "x_d 4")
    _raises(lambda: shock_ratios(ok, ok, ok, [1.0, np.nan, 1.0], ok, ok, ok), "acc_s", "finite")


def test_dtr():
    m = 563.0 + 90.0
    load = m * 9.81
    assert dtr(1.3 * load, 1.1 * load, m) == pytest.approx(0.2)
    assert dtr(1.1 * load, 1.3 * load, m) == pytest.approx(0.2)  # magnitude of the deviation
    assert dtr(1000.0, 1000.0, m) == 0.0
    assert dtr(100.0, 0.0, 10.0, g=10.0) == pytest.approx(1.0)
    _raises(lambda: dtr(1.0, 2.0, 0.0), "nominal_total_mass", "> 0 kg")
    _raises(lambda: dtr(float("nan"), 2.0, 1.0), "peak_tire_force_nominal", "finite")
    _raises(lambda: dtr(1.0, "2", 1.0), "peak_tire_force", "number")


def test_peak():
    assert peak([0.5, -2.0, 1.0]) == 2.0
    _raises(lambda: peak([]), "empty")
