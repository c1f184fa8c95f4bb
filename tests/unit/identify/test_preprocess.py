"""Pre-processing: frequency, derivatives, whole steady cycles, and clear refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.characterisation import harmonic_loop
from mrsuspension.dampers import WangSymmetric
from mrsuspension.errors import ValidationError
from mrsuspension.identify.preprocess import (
    PreprocessOptions,
    detect_frequency,
    preprocess,
    smooth_derivative,
)
from mrsuspension.identify.readers import RawTest, TestDataError

FS = 1000.0
DAMPER = WangSymmetric()


def record(
    f: float = 1.5,
    a: float = 0.0125,
    i: float = 0.2,
    cycles: float = 3.4,
    phase: float = 0.7,
    with_velocity: bool = True,
    noise: float = 0.0,
    seed: int = 0,
) -> RawTest:
    t = np.arange(int(cycles / f * FS)) / FS
    w = 2 * math.pi * f
    x = a * np.sin(w * t + phase)
    v = a * w * np.cos(w * t + phase)
    acc = -a * w * w * np.sin(w * t + phase)
    force = DAMPER.force(x, v, acc, i, peak_velocity=a * w)
    force = force + np.random.default_rng(seed).normal(0, noise, t.size)
    return RawTest("rec", t, x, v if with_velocity else None, force)


def test_detect_frequency_is_exact_for_a_sine_with_drift_and_noise() -> None:
    t = np.arange(0.0, 2.3, 1e-3)
    y = 0.01 * np.sin(2 * np.pi * 2.37 * t - 0.4) + 0.003 + 0.001 * t
    y += np.random.default_rng(1).normal(0.0, 2e-4, t.size)
    fit = detect_frequency(t, y)
    assert fit.frequency == pytest.approx(2.37, rel=2e-4)
    assert fit.amplitude == pytest.approx(0.01, rel=1e-2)
    assert fit.phase == pytest.approx(-0.4, abs=1e-2)
    assert fit.explained > 0.99


def test_smooth_derivative_of_noisy_sine() -> None:
    t = np.arange(0.0, 2.0, 1e-3)
    x = 0.01 * np.sin(2 * np.pi * t) + np.random.default_rng(0).normal(0, 1e-6, t.size)
    v = smooth_derivative(x, 1e-3, 51)
    exact = 0.02 * np.pi * np.cos(2 * np.pi * t)
    assert np.max(np.abs(v - exact)) < 0.01 * np.max(np.abs(exact))


def test_loop_matches_the_characterisation_loop() -> None:
    """From an arbitrary start phase, the loop starts at phase 0 like harmonic_loop."""
    loop = preprocess(record(), current=0.2, frequency=1.5, amplitude=0.0125)
    ref = harmonic_loop(DAMPER, 1.5, 0.0125, 0.2)
    assert loop.frequency == pytest.approx(1.5, rel=1e-9)
    assert loop.cycles_found == 3
    assert loop.cycles_used == 3
    # linear interpolation of 1 kHz samples: (omega dt)^2 / 8 ~ 1e-5 of the amplitude
    np.testing.assert_allclose(loop.stroke, ref.stroke, atol=2e-5 * 0.0125)
    np.testing.assert_allclose(loop.velocity, ref.velocity, atol=2e-5 * ref.peak_velocity)
    # linear interpolation of 1 kHz samples near the steep yield: small differences only
    assert np.sqrt(np.mean((loop.force - ref.force) ** 2)) < 2e-3 * np.ptp(ref.force)
    assert loop.peak_velocity == pytest.approx(2 * math.pi * 1.5 * 0.0125)
    assert any("v_m = 2 pi f a_m" in n for n in loop.notes)


def test_velocity_and_acceleration_are_derived_and_noted() -> None:
    loop = preprocess(record(with_velocity=False), current=0.2)
    ref = harmonic_loop(DAMPER, 1.5, 0.0125, 0.2)
    np.testing.assert_allclose(loop.velocity, ref.velocity, atol=1e-4 * ref.peak_velocity)
    assert any(
        n.startswith("velocity derived from displacement (Savitzky-Golay") for n in loop.notes
    )
    assert any(n.startswith("acceleration derived from displacement") for n in loop.notes)
    # measured v_m (no nominal amplitude) is the fundamental of the velocity
    assert loop.peak_velocity == pytest.approx(ref.peak_velocity, rel=1e-4)


def test_displacement_integrated_from_velocity() -> None:
    raw = record()
    raw = RawTest(raw.source, raw.time, None, raw.velocity, raw.force)
    loop = preprocess(raw, current=0.2)
    assert np.ptp(loop.stroke) / 2 == pytest.approx(0.0125, rel=1e-3)
    assert any("integrated from velocity" in n for n in loop.notes)


def test_transient_cycles_are_dropped() -> None:
    raw = record(cycles=5.2)
    ramp = np.clip(raw.time / 1.2, 0.3, 1.0)  # amplitude ramps up over the first cycles
    raw = RawTest("r", raw.time, raw.displacement * ramp, raw.velocity * ramp, raw.force * ramp)
    loop = preprocess(raw, current=0.2)
    assert loop.cycles_found == 5
    assert loop.cycles_used < 5
    assert any("dropped as not steady" in n for n in loop.notes)
    # frequency and amplitude come from the steady part, not biased by the ramp
    assert loop.frequency == pytest.approx(1.5, rel=1e-5)
    assert loop.amplitude == pytest.approx(0.0125, rel=1e-4)
    assert preprocess(raw, PreprocessOptions(max_cycles=1), current=0.2).cycles_used == 1


def test_irregular_time_base_is_resampled_with_a_note() -> None:
    raw = record()
    t = raw.time + np.random.default_rng(0).uniform(-2e-4, 2e-4, raw.time.size)
    loop = preprocess(
        RawTest("r", np.sort(t), raw.displacement, raw.velocity, raw.force), current=0.2
    )
    assert any("resampled onto a uniform" in n for n in loop.notes)
    assert loop.frequency == pytest.approx(1.5, rel=1e-3)


def test_offset_removal_and_frequency_warning() -> None:
    raw = record()
    raw = RawTest("r", raw.time, raw.displacement, raw.velocity, raw.force + 150.0)
    loop = preprocess(raw, PreprocessOptions(remove_offset=True), current=0.2, frequency=1.6)
    assert loop.force_offset == pytest.approx(150.0, abs=1.0)
    assert any(
        n.startswith("warning: detected 1.5 Hz but the manifest says 1.6 Hz") for n in loop.notes
    )


def test_current_from_the_file_and_points_per_cycle() -> None:
    raw = record()
    raw = RawTest("r", raw.time, raw.displacement, raw.velocity, raw.force,
                  current=np.full(raw.time.size, 0.2) + 1e-3)  # fmt: skip
    loop = preprocess(raw, PreprocessOptions(points_per_cycle=720))
    assert loop.force.size == 720
    assert loop.mean_current == pytest.approx(0.201)
    with pytest.raises(TestDataError, match="no drive current"):
        preprocess(record())


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda r: RawTest("r", r.time, r.displacement, r.velocity,
                           np.where(np.arange(r.time.size) % 20 == 7, np.nan, r.force)),
         r"hold NaN or infinite values in force \(first at data row 8, t = 0.007 s\); more "
         r"than 2 % cannot be bridged"),
        (lambda r: RawTest("r", np.concatenate([r.time[:100], r.time[99:-1]]), r.displacement,
                           r.velocity, r.force),
         r"time is not increasing at data row 101"),
        (lambda r: RawTest("r", r.time[:500], r.displacement[:500], r.velocity[:500],
                           r.force[:500]),
         r"no whole cycle: the record lasts 0.499 s, 0.75 periods"),
        (lambda r: RawTest("r", r.time, r.displacement, r.velocity, np.full(r.time.size, 5.0)),
         r"the force is constant over the record"),
        (lambda r: RawTest("r", r.time, np.zeros(r.time.size), None, r.force),
         r"no excitation found"),
    ],
)  # fmt: skip
def test_bad_records_are_refused_with_a_clear_message(mutate, message: str) -> None:
    with pytest.raises(TestDataError, match=message):
        preprocess(mutate(record()), current=0.2, frequency=1.5)


def test_options_are_validated() -> None:
    with pytest.raises(ValidationError, match="points per cycle"):
        PreprocessOptions(points_per_cycle=4)
    with pytest.raises(ValidationError, match="peak_velocity must be one of"):
        PreprocessOptions(peak_velocity="guess")
    with pytest.raises(TestDataError, match="'nominal' needs the frequency and amplitude"):
        preprocess(record(), PreprocessOptions(peak_velocity="nominal"), current=0.2)
