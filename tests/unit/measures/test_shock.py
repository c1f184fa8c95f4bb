"""Shock measures (3.41)/(3.44) and the road-peak options (model reference, section 9)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.excitation import RoundedPulse
from mrsuspension.measures import (
    DEFAULT_ROAD_PEAK,
    ROAD_PEAKS,
    check_road_peak,
    dtr,
    peak,
    road_acceleration_peak,
    shock_ratios,
)
from mrsuspension.measures.shock import AFTER_ONSET_FACTOR, ONSET_TO_AFTER_ONSET


def test_ratios_use_peaks_of_absolute_values() -> None:
    z_r = np.array([0.0, 0.01, 0.05, 0.01, 0.0])
    acc_r = np.array([0.0, 40.0, -10.0, 5.0, 0.0])
    z_s = np.array([0.0, -0.03, 0.02, 0.01, 0.0])  # negative excursion is the peak
    acc_s = np.array([0.0, 2.0, -8.0, 1.0, 0.0])
    z_u = np.array([0.0, 0.02, 0.06, 0.0, -0.01])
    acc_u = np.array([0.0, -60.0, 20.0, 0.0, 0.0])
    x_d = z_u - z_s
    r = shock_ratios(z_s, z_u, z_r, acc_s, acc_u, acc_r, x_d, road_peak="onset")
    assert r == pytest.approx(
        {"SDR_s": 0.6, "SAR_s": 0.2, "SDR_u": 1.2, "SAR_u": 1.5, "RDR": 0.05 / 0.05}
    )
    assert list(r) == ["SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR"]
    # after the onset lobe (40 at sample 1, ending at -10): the peak is 10
    r = shock_ratios(z_s, z_u, z_r, acc_s, acc_u, acc_r, x_d)
    assert r == pytest.approx({"SDR_s": 0.6, "SAR_s": 0.8, "SDR_u": 1.2, "SAR_u": 6.0, "RDR": 1.0})


def test_ratios_of_a_pulse_passed_through_unchanged() -> None:
    p = RoundedPulse(0.035, 2.0)
    t = np.linspace(0.0, p.duration, 5001)
    z, a = p.displacement(t), p.acceleration(t)
    r = shock_ratios(z, z, z, a, a, a, 0.0 * z, road_peak="onset")
    assert r["SDR_s"] == r["SAR_s"] == r["SDR_u"] == r["SAR_u"] == 1.0
    assert r["RDR"] == 0.0
    after = shock_ratios(z, z, z, a, a, a, 0.0 * z)  # the default
    assert after == shock_ratios(z, z, z, a, a, a, 0.0 * z, road_peak="after-onset")
    # this grid misses the onset instant, so the sampled onset jump falls short of 2 c
    # (mu w0)^2 (a fragility the after-onset peak does not have): 4.78, not 4.854
    assert after["SAR_s"] == after["SAR_u"] == pytest.approx(4.777, abs=1e-3)
    assert road_acceleration_peak(a) == pytest.approx(p.after_onset_peak_acceleration, rel=1e-4)
    assert (after["SDR_s"], after["SDR_u"], after["RDR"]) == (1.0, 1.0, 0.0)


def test_after_onset_constants() -> None:
    assert abs(AFTER_ONSET_FACTOR - 0.4120101) < 1e-7
    assert abs(ONSET_TO_AFTER_ONSET - 4.85425) < 1e-5
    assert DEFAULT_ROAD_PEAK == "after-onset"
    assert set(ROAD_PEAKS) == {"onset", "after-onset"}


@pytest.mark.parametrize("mu", [1.0, 2.0, 3.0])
@pytest.mark.parametrize("speed", [50.0, 100.0])
@pytest.mark.parametrize("a", [0.02, 0.05, -0.035])
def test_sampled_road_peaks_of_the_pulse_match_the_closed_form(
    mu: float, speed: float, a: float
) -> None:
    # 0.41201 c (mu w0)^2 after the onset, 2 c (mu w0)^2 at it; c = 0.25 |a| e^2
    p = RoundedPulse(a, mu, speed_kmh=speed)
    c = 0.25 * abs(a) * math.e**2
    w = mu * 10.4 * speed / 50.0
    t = np.arange(0.0, p.duration, 1e-4)  # the onset (0.5 s) is on the grid
    acc = p.acceleration(t)
    assert road_acceleration_peak(acc, "onset") == pytest.approx(2 * c * w * w, rel=1e-12)
    assert road_acceleration_peak(acc) == pytest.approx(0.4120101 * c * w * w, rel=2e-5)
    # a 1 kHz record (the engine's default output rate): second order in the step
    t = np.arange(0.0, p.duration, 1e-3)
    assert road_acceleration_peak(p.acceleration(t)) == pytest.approx(
        p.after_onset_peak_acceleration, rel=2e-3
    )


def test_road_peak_changes_only_the_acceleration_ratios() -> None:
    p = RoundedPulse(0.035, 3.0)
    t = np.arange(0.0, p.duration, 1e-3)
    z, a = p.displacement(t), p.acceleration(t)
    rng = np.random.default_rng(1)
    sig = [rng.normal(size=t.size) * s for s in (0.02, 0.03, 5.0, 40.0, 0.01)]
    onset = shock_ratios(sig[0], sig[1], z, sig[2], sig[3], a, sig[4], road_peak="onset")
    after = shock_ratios(sig[0], sig[1], z, sig[2], sig[3], a, sig[4], road_peak="after-onset")
    for k in ("SDR_s", "SDR_u", "RDR"):  # z_r is 0 at the onset: its peak is unaffected
        assert after[k] == onset[k]
    ratio = road_acceleration_peak(a, "onset") / road_acceleration_peak(a)
    assert ratio == pytest.approx(ONSET_TO_AFTER_ONSET, rel=1e-3)
    for k in ("SAR_s", "SAR_u"):
        assert after[k] == pytest.approx(onset[k] * ratio, rel=1e-12)


def test_after_onset_on_other_records() -> None:
    t = np.arange(0.0, 4.0, 1e-3)
    # a sine from rest: only its first half-wave is left out, the peak is the same
    sine = -2.0 * np.sin(2 * np.pi * 1.5 * t)
    assert road_acceleration_peak(sine) == pytest.approx(road_acceleration_peak(sine, "onset"))
    # a quiet lead-in (round-off size) is not the onset
    lead = np.concatenate([np.full(50, 1e-14), [8.0, 3.0, -1.0, -2.5, 0.5]])
    assert road_acceleration_peak(lead) == 2.5
    assert road_acceleration_peak(lead, "onset") == 8.0
    # the lobe ends at an exact zero as well as at a sign change
    assert road_acceleration_peak([0.0, 6.0, 2.0, 0.0, 1.5, 0.2]) == 1.5
    # a pothole: the same with the signs reversed
    assert road_acceleration_peak([0.0, -6.0, -2.0, 3.0, -1.0]) == 3.0


def test_road_peak_errors() -> None:
    _raises(lambda: road_acceleration_peak(np.zeros(4)), "acc_r", "zero")
    _raises(
        lambda: road_acceleration_peak([0.0, 4.0, 3.0, 1.0]),
        "never leaves its onset lobe",
        "road_peak='onset'",
    )
    assert road_acceleration_peak([0.0, 4.0, 3.0, 1.0], "onset") == 4.0
    _raises(lambda: check_road_peak("peak"), "road_peak", "'after-onset', 'onset'", "'peak'")
    _raises(lambda: check_road_peak(None), "road_peak", "None")
    ok = np.ones(3)
    _raises(
        lambda: shock_ratios(ok, ok, ok, ok, ok, ok, ok, road_peak="after_onset"),  # type: ignore[arg-type]
        "road_peak must be one of 'after-onset', 'onset'",
        "Did you mean 'after-onset'?",
    )


def test_shock_ratio_errors() -> None:
    ok = np.ones(3)
    _raises(lambda: shock_ratios(ok, ok, np.zeros(3), ok, ok, ok, ok), "z_r", "zero")
    _raises(lambda: shock_ratios(ok, ok, ok, ok, ok, np.zeros(3), ok), "acc_r", "zero")
    _raises(lambda: shock_ratios(ok, ok, ok, ok, ok, ok, np.ones(4)), "x_d 4")
    _raises(lambda: shock_ratios(ok, ok, ok, [1.0, np.nan, 1.0], ok, ok, ok), "acc_s", "finite")


def test_dtr() -> None:
    m = 563.0 + 90.0
    load = m * 9.81
    assert dtr(1.3 * load, 1.1 * load, m) == pytest.approx(0.2)
    assert dtr(1.1 * load, 1.3 * load, m) == pytest.approx(0.2)  # magnitude of the deviation
    assert dtr(1000.0, 1000.0, m) == 0.0
    assert dtr(100.0, 0.0, 10.0, g=10.0) == pytest.approx(1.0)
    _raises(lambda: dtr(1.0, 2.0, 0.0), "nominal_total_mass", "> 0 kg")
    _raises(lambda: dtr(float("nan"), 2.0, 1.0), "peak_tire_force_nominal", "finite")
    _raises(lambda: dtr(1.0, "2", 1.0), "peak_tire_force", "number")


def test_peak() -> None:
    assert peak([0.5, -2.0, 1.0]) == 2.0
    _raises(lambda: peak([]), "empty")
