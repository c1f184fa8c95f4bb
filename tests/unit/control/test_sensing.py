"""Body-velocity estimators and the stroke sensor (control/sensing.py)."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from mrsuspension.control.sensing import (
    BandPassObserver,
    LeakyIntegrator,
    StrokeSensor,
    band_pass_corner,
    band_pass_response,
    leaky_integrator_response,
    leaky_integrator_tau,
    phase_error,
)
from mrsuspension.errors import ValidationError

FS = 1000.0
FREQS = [0.5, 1.0, 1.5, 4.0, 10.0]


def _measured_response(estimate: np.ndarray, freq: float, fs: float, settle: float) -> complex:
    """``V_hat / A`` from a steady sine response: least squares on whole cycles after ``settle``."""
    k = np.arange(estimate.size)
    start = int(settle * fs)
    cycles = math.floor((estimate.size - start) * freq / fs)
    stop = start + round(cycles * fs / freq)
    theta = 2 * np.pi * freq * k[start:stop] / fs
    basis = np.column_stack([np.sin(theta), np.cos(theta)])
    (re, im), *_ = np.linalg.lstsq(basis, estimate[start:stop], rcond=None)
    return complex(re, im)


def _sine(freq: float, seconds: float, fs: float = FS) -> np.ndarray:
    return np.sin(2 * np.pi * freq * np.arange(int(seconds * fs)) / fs)


@pytest.mark.parametrize("freq", FREQS)
def test_leaky_sine_response_matches_exact(freq: float) -> None:
    est = LeakyIntegrator(tau=0.919, fs=FS)
    h_sim = _measured_response(est.estimate(_sine(freq, 40.0)), freq, FS, settle=25.0)
    h = complex(est.response([freq])[0])
    assert abs(abs(h_sim) / abs(h) - 1.0) < 0.005
    assert abs(math.degrees(np.angle(h_sim / h))) < 0.005 * abs(math.degrees(np.angle(h)))
    assert abs(h_sim - h) / abs(h) < 1e-6  # exact discretisation: round-off only


@pytest.mark.parametrize("freq", FREQS)
def test_band_pass_sine_response_matches_exact(freq: float) -> None:
    est = BandPassObserver(corner=0.1228, fs=FS)
    h_sim = _measured_response(est.estimate(_sine(freq, 80.0)), freq, FS, settle=60.0)
    h = complex(est.response([freq])[0])
    assert abs(abs(h_sim) / abs(h) - 1.0) < 0.005
    assert abs(math.degrees(np.angle(h_sim / h))) < 0.005 * abs(math.degrees(np.angle(h)))
    assert abs(h_sim - h) / abs(h) < 1e-6


def test_dc_offset_gives_a_bounded_estimate() -> None:
    a0 = 0.3  # m/s^2, e.g. a tilted accelerometer
    offset = np.full(int(60 * FS), a0)
    leaky = LeakyIntegrator(tau=0.919, fs=FS).estimate(offset)
    assert np.max(np.abs(leaky)) <= a0 * 0.919 * (1 + 1e-12)
    assert leaky[-1] == pytest.approx(a0 * 0.919, rel=1e-9)
    band = BandPassObserver(corner=0.1228, fs=FS).estimate(offset)
    wc = 2 * np.pi * 0.1228
    assert np.max(np.abs(band)) < a0 / wc  # peak of the step response s/(...) * a0/s
    assert abs(band[-1]) < 1e-4 * a0 / wc  # rejected: back to zero


@pytest.mark.parametrize("kind", ["leaky", "band-pass"])
def test_discrete_response_converges_to_continuous(kind: str) -> None:
    f = np.array(FREQS)

    def response(fs: float | None) -> np.ndarray:
        if kind == "leaky":
            return leaky_integrator_response(f, 0.919, fs)
        return band_pass_response(f, 0.1228, fs)

    cont = response(None)
    errors = [float(np.max(np.abs(response(fs) / cont - 1.0))) for fs in (1e2, 1e3, 1e4, 1e5)]
    assert all(b < a / 8 for a, b in itertools.pairwise(errors))  # first order in T
    assert errors[-1] < 1e-3


def test_tau_for_ten_degrees_over_the_body_mode() -> None:
    tau = leaky_integrator_tau(1.0, max_phase_error=10.0, fs=FS)
    band = phase_error([1.0, 1.25, 1.5], leaky_integrator_response([1.0, 1.25, 1.5], tau, FS))
    assert band[0] == pytest.approx(10.0, abs=1e-8)
    assert np.all(band <= 10.0 + 1e-8)
    assert np.all(np.diff(band) < 0)
    assert leaky_integrator_tau(1.0, 10.0) == pytest.approx(
        1 / (2 * np.pi * math.tan(math.radians(10.0)))
    )


def test_corner_for_ten_degrees_over_the_body_mode() -> None:
    fc = band_pass_corner(1.0, max_phase_error=10.0, fs=FS)
    band = phase_error([1.0, 1.5], band_pass_response([1.0, 1.5], fc, FS))
    assert band[0] == pytest.approx(10.0, abs=1e-8)
    assert band[1] < band[0]


def test_phase_error_continuous_closed_form() -> None:
    tau = 0.5
    for f in (0.2, 1.0, 3.0):
        expected = math.degrees(math.atan(1 / (2 * math.pi * f * tau)))
        assert phase_error(f, leaky_integrator_response(f, tau)) == pytest.approx(expected)


def test_stroke_sensor_quantises_holds_and_differences() -> None:
    sensor = StrokeSensor(fs=100.0, resolution=1e-3)
    t = np.arange(0.0, 0.05, 1e-3)  # 1 kHz record, sensor every 10th sample
    x, v = sensor.measure(0.1 * t + 0.0004, 1000.0)
    assert x[0] == 0.0
    assert x[9] == 0.0
    assert x[10] == pytest.approx(0.001)  # 1.4 mm -> 1 mm
    assert v[10] == pytest.approx(0.1)  # (1 mm - 0) * 100 Hz
    assert np.all(x[10:20] == x[10])


def test_stroke_sensor_noise_is_seeded_white() -> None:
    a = StrokeSensor(fs=500.0, noise_std=2e-4, seed=7)
    noise = a.noise(50000)
    assert np.array_equal(noise, StrokeSensor(fs=500.0, noise_std=2e-4, seed=7).noise(50000))
    assert np.std(noise) == pytest.approx(2e-4, rel=0.02)
    assert abs(np.corrcoef(noise[:-1], noise[1:])[0, 1]) < 0.02
    x, v = a.measure(np.zeros(1000), 500.0)
    assert np.array_equal(x, noise[:1000])
    assert v[1] == pytest.approx((noise[1] - noise[0]) * 500.0)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: LeakyIntegrator(tau=0.0, fs=FS), "tau must be in \\(0, inf\\) s; got 0 s"),
        (lambda: BandPassObserver(corner=600.0, fs=FS), "corner must be below fs/2"),
        (
            lambda: StrokeSensor(fs=100.0, resolution=-1.0),
            "resolution must be in \\[0, inf\\) m; got -1 m",
        ),
        (lambda: StrokeSensor(fs=300.0).measure([0.0], 1000.0), "integer multiple"),
        (lambda: leaky_integrator_tau(1.0, 95.0), "max_phase_error must be in \\(0, 90\\) deg"),
        (lambda: leaky_integrator_tau(100.0, 10.0, fs=200.0), "freq must be below fs/2"),
        (lambda: leaky_integrator_tau(40.0, 5.0, fs=1000.0), "sampling lead"),
    ],
)
def test_bad_input(call: object, message: str) -> None:
    with pytest.raises(ValidationError, match=message):
        call()  # type: ignore[operator]
