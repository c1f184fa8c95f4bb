"""Steady-state measures (model reference, section 9) on hand-made arrays with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.excitation import Harmonic
from mrsuspension.measures import (
    T_as,
    T_au,
    T_dr,
    T_ds,
    T_du,
    asymmetry_ratio,
    current_statistics,
    dlc,
    force_tracking_error,
    harmonic_measures,
    rms,
    steady_window,
    transmissibility,
)

DT = 1e-3


def _record(f: float, duration: float):
    t = np.arange(0.0, duration + DT / 2, DT)
    return t, np.sin(2 * np.pi * f * t)


# -- rms and transmissibility ---------------------------------------------------------------
def test_rms_of_a_sinusoid_over_whole_cycles():
    t = np.arange(0.0, 2.0, 1e-4)
    assert rms(0.03 * np.sin(2 * np.pi * 3.0 * t + 0.4)) == pytest.approx(
        0.03 / math.sqrt(2), rel=1e-10
    )
    assert rms([3.0, 4.0]) == pytest.approx(math.sqrt(12.5))


@pytest.mark.parametrize("gain", [0.2, 1.0, 3.5])
def test_transmissibility_of_scaled_and_shifted_signals(gain):
    t = np.arange(0.0, 4.0, 1e-3)
    ref = np.sin(2 * np.pi * 2.0 * t)
    resp = -gain * np.sin(2 * np.pi * 2.0 * t + 1.1)  # phase does not change an rms ratio
    assert transmissibility(resp, ref) == pytest.approx(gain, rel=1e-10)
    for fun in (T_as, T_au, T_dr, T_ds, T_du):
        assert fun(resp, ref) == pytest.approx(gain, rel=1e-10)


def test_windows_as_slice_time_limits_and_mask():
    t = np.arange(0.0, 10.0, 0.01)
    ref = np.ones_like(t)
    resp = np.where(t < 5.0, 10.0, 2.0)
    assert T_as(resp, ref) == pytest.approx(math.sqrt((100 + 4) / 2))
    assert T_as(resp, ref, window=slice(500, None)) == pytest.approx(2.0)
    assert T_dr(resp, ref, window=(5.0, 10.0), time=t) == pytest.approx(2.0)
    assert T_dr(resp, ref, window=(0.0, 5.0), time=t) == pytest.approx(10.0)  # half-open
    assert T_au(resp, ref, window=t >= 5.0) == pytest.approx(2.0)
    assert rms(resp, window=(5.0, 20.0), time=t) == pytest.approx(2.0)


@pytest.mark.parametrize(
    ("call", "fragments"),
    [
        (lambda: rms([]), ("x", "empty")),
        (lambda: rms([1.0, np.nan]), ("x", "finite", "index 1")),
        (lambda: rms([[1.0, 2.0]]), ("one-dimensional",)),
        (lambda: rms("abc"), ("array of numbers",)),
        (lambda: T_as([1.0, 2.0], [1.0]), ("acc_s 2", "acc_r 1")),
        (lambda: T_dr([1.0, 2.0], [0.0, 0.0]), ("z_r", "zero rms")),
        (lambda: transmissibility([1.0], [0.0]), ("reference", "zero rms")),
        (lambda: rms([1.0, 2.0], window=(0.0, 1.0)), ("needs time",)),
        (lambda: rms([1.0, 2.0], window=(5.0, 6.0), time=[0.0, 1.0]), ("no samples", "0-1 s")),
        (lambda: rms([1.0, 2.0], window=(1.0, 0.0), time=[0.0, 1.0]), ("t_end > t_start",)),
        (
            lambda: rms([1.0, 2.0], window=(0.0, 1.0), time=[1.0, 0.0]),
            ("time", "strictly increasing"),
        ),
        (lambda: rms([1.0, 2.0], window=(0.0, 1.0), time=[0.0, 1.0, 2.0]), ("time", "length 2")),
        (lambda: rms([1.0, 2.0], window=[True]), ("boolean mask of length 2",)),
        (lambda: rms([1.0, 2.0], window=[False, False]), ("selects no samples",)),
        (lambda: rms([1.0, 2.0], window=slice(5, None)), ("selects no samples",)),
    ],
)
def test_bad_inputs(call, fragments):
    _raises(call, *fragments)


# -- the steady-state window ------------------------------------------------------------------
@pytest.mark.parametrize("f", [0.5, 0.75, 1.5, 1.75, 3.0, 7.3, 15.0])
def test_steady_window_is_a_whole_number_of_cycles_at_the_end(f):
    h = Harmonic(f, 0.01)
    t, x = _record(f, h.duration)
    w = steady_window(t, f)
    samples = w.stop - w.start
    cycles = samples * DT * f
    assert w.stop == t.size
    assert cycles == pytest.approx(round(cycles), abs=DT * f)  # whole cycles to one sample
    assert round(cycles) >= 10
    assert samples * DT >= 2.0 - DT
    assert t[w.start] >= max(5.0, 10 / f) - DT  # settled (model reference, section 9)
    # a whole number of cycles gives the exact rms of a sinusoid (up to the sub-sample rest)
    assert rms(x, window=w) == pytest.approx(1 / math.sqrt(2), rel=1e-3)


def test_steady_window_agrees_with_the_harmonic_measure_window():
    for f in (0.6, 2.0, 4.4, 12.0):
        h = Harmonic(f, 0.01)
        t, _ = _record(f, h.duration)
        w = steady_window(t, f)
        t0, t1 = h.measure_window()
        assert t[w.start] == pytest.approx(t0, abs=1.5 * DT)
        assert t[w.stop - 1] == pytest.approx(t1, abs=1.5 * DT)


def test_steady_window_uses_all_whole_cycles_available():
    t, _ = _record(2.0, 30.0)
    w = steady_window(t, 2.0)
    assert (w.stop - w.start) * DT == pytest.approx(25.0)  # settle 5 s, then 50 cycles


def test_steady_window_rejects_short_records():
    t, _ = _record(1.5, 12.0)
    _raises(lambda: steady_window(t, 1.5), "too short", "1.5 Hz", "got 12 s")
    _raises(lambda: steady_window(t, 0.0), "frequency", "> 0")
    _raises(lambda: steady_window(t, 1.5, min_cycles=0), "min_cycles")
    _raises(lambda: steady_window([0.0], 1.5), "at least 2")


def test_steady_window_options():
    t, _ = _record(1.0, 8.0)
    w = steady_window(t, 1.0, settle=2.0, min_cycles=3, min_time=1.0)
    assert (w.stop - w.start) * DT == pytest.approx(5.0)


# -- tire force, asymmetry, current, tracking -------------------------------------------------
def test_dlc_against_static_load_and_mean_load():
    static = (563.0 + 90.0) * 9.81
    t = np.arange(0.0, 1.0, 1e-4)
    force = static + 0.2 * static * np.sin(2 * np.pi * 5.0 * t)
    assert dlc(force, static_load=static) == pytest.approx(0.2 / math.sqrt(2), rel=1e-9)
    assert dlc(force) == pytest.approx(0.2 / math.sqrt(2), rel=1e-9)  # mean load = static here
    assert dlc([90.0, 110.0, 90.0, 110.0]) == pytest.approx(0.1)
    assert dlc([90.0, 110.0, 90.0, 110.0], static_load=50.0) == pytest.approx(0.2)
    _raises(lambda: dlc([1.0, 2.0], static_load=0.0), "static_load", "> 0 N")
    _raises(lambda: dlc([-1.0, -2.0]), "mean tire force", "static_load")


def test_asymmetry_ratio_sign_convention():
    # rebound is negative F_d: 1200 N rebound against 500 N compression
    assert asymmetry_ratio([500.0, -1200.0, 100.0]) == pytest.approx(2.4)
    t = np.linspace(0.0, 1.0, 1001)
    force = np.where(np.sin(2 * np.pi * t) > 0, 300.0, 750.0) * np.sin(2 * np.pi * t)
    assert asymmetry_ratio(force) == pytest.approx(2.5, rel=1e-3)
    assert asymmetry_ratio([100.0, 50.0]) == 0.0
    _raises(lambda: asymmetry_ratio([-100.0, -50.0]), "no compression")


def test_current_statistics():
    stats = current_statistics([0.0, 0.5, 0.5, 0.0, 0.25, 0.25])
    assert stats["mean_current"] == pytest.approx(0.25)
    assert stats["mean_square_current"] == pytest.approx((0.25 + 0.25 + 0.0625 * 2) / 6)
    assert current_statistics([0.0, 1.0], window=slice(1, None))["mean_current"] == 1.0


def test_force_tracking_error_only_where_switching_is_negative():
    force = np.array([100.0, -90.0, 500.0, 40.0])
    target = np.array([110.0, 100.0, 0.0, -60.0])
    switching = np.array([-1.0, -0.5, 2.0, -3.0])
    # samples 0, 1, 3: |F| - |F*| = -10, -10, -20
    expected = math.sqrt((100 + 100 + 400) / 3)
    assert force_tracking_error(force, target, switching) == pytest.approx(expected)
    assert force_tracking_error(force, target, switching, window=slice(0, 2)) == pytest.approx(10.0)
    _raises(lambda: force_tracking_error(force, target, np.ones(4)), "never negative")
    _raises(lambda: force_tracking_error(force, target[:3], switching), "target 3")


def test_harmonic_measures_bundle():
    f = 2.5
    h = Harmonic(f, 0.02)
    t, _ = _record(f, h.duration)
    zr, ar = h.displacement(t), h.acceleration(t)
    phase = 2 * np.pi * f * t + 0.7
    zs = 0.5 * 0.02 * np.sin(phase)
    static = 6405.93
    out = harmonic_measures(
        t, f,
        z_s=zs, z_u=1.2 * zr, z_r=zr, acc_s=-((2 * np.pi * f) ** 2) * zs, acc_u=1.2 * ar,
        acc_r=ar, x_d=1.2 * zr - zs, F_d=np.where(zr > 0, 1.0, 2.0) * 400 * np.sin(phase),
        F_T=static + 640.593 * np.sin(phase), static_load=static, i_d=np.full(t.size, 0.3),
    )  # fmt: skip
    assert out["T_as"] == pytest.approx(0.5, rel=1e-3)
    assert out["T_ds"] == pytest.approx(0.5, rel=1e-3)
    assert out["T_au"] == pytest.approx(1.2, rel=1e-9)
    assert out["T_du"] == pytest.approx(1.2, rel=1e-9)
    assert out["DLC"] == pytest.approx(0.1 / math.sqrt(2), rel=1e-3)
    assert out["mean_current"] == pytest.approx(0.3)
    assert out["mean_square_current"] == pytest.approx(0.09)
    assert set(out) == {
        "T_as", "T_au", "T_dr", "T_ds", "T_du", "DLC", "gamma", "mean_current", "mean_square_current",
    }  # fmt: skip
    passive = harmonic_measures(
        t, f, z_s=zs, z_u=zr, z_r=zr, acc_s=ar, acc_u=ar, acc_r=ar, x_d=zr,
        F_d=-np.abs(zr), F_T=static + zr, static_load=static,
    )  # fmt: skip
    assert passive["gamma"] is None
    assert "mean_current" not in passive
