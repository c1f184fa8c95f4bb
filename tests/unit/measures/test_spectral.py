"""Welch PSDs with the dissertation's settings: resampling, resolution, Parseval, short records."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from _helpers import raises_validation as _raises
from mrsuspension.measures import PowerSpectrum, ShortRecordWarning, psd


@pytest.mark.parametrize("fs_in", [512.0, 1000.0, 10000.0])
@pytest.mark.parametrize(("f0", "amp"), [(1.5, 0.8), (11.0, 2.0)])
def test_sinusoid_peaks_at_its_frequency_with_its_power(fs_in, f0, amp):
    t = np.arange(0.0, 40.0, 1 / fs_in)
    spec = psd(amp * np.sin(2 * np.pi * f0 * t) + 3.0, fs_in)  # the mean is removed
    assert isinstance(spec, PowerSpectrum)
    assert spec.fs == pytest.approx(512.0)
    assert spec.nperseg == 8192
    assert spec.resolution == pytest.approx(0.0625)
    assert not spec.short_record
    assert spec.frequency[np.argmax(spec.density)] == pytest.approx(f0, abs=0.0625)
    power = np.sum(spec.density) * spec.resolution  # Parseval: mean square = A^2/2
    assert power == pytest.approx(amp**2 / 2, rel=0.01)
    f, p = spec  # unpacks like scipy's (f, Pxx)
    assert f is spec.frequency
    assert p is spec.density


def test_white_noise_level():
    rng = np.random.default_rng(0)
    x = rng.normal(0.0, 1.0, 512 * 200)
    _, p = psd(x, 512.0)
    # one-sided density of unit white noise at 512 Hz: 2/512 per Hz
    assert np.mean(p[5:-5]) == pytest.approx(2 / 512, rel=0.02)


def test_anti_aliasing_when_resampling():
    fs_in = 2000.0
    t = np.arange(0.0, 40.0, 1 / fs_in)
    alias = np.sin(2 * np.pi * 400.0 * t)  # above the 256 Hz Nyquist of 512 Hz: must vanish
    spec = psd(np.sin(2 * np.pi * 3.0 * t) + alias, fs_in)
    power = np.sum(spec.density) * spec.resolution
    assert power == pytest.approx(0.5, rel=0.01)
    assert spec.frequency[np.argmax(spec.density)] == pytest.approx(3.0)


def test_short_record_uses_the_whole_record_and_says_so():
    t = np.arange(0.0, 5.0, 1e-3)  # 5 s: 2560 samples at 512 Hz < 8192
    with pytest.warns(ShortRecordWarning, match="shorter than one Welch segment"):
        spec = psd(np.sin(2 * np.pi * 4.0 * t), 1000.0)
    assert spec.short_record
    assert spec.nperseg == 2560
    assert spec.resolution == pytest.approx(0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        quiet = psd(np.sin(2 * np.pi * 4.0 * t), 1000.0, warn=False)
    assert quiet.short_record


def test_options_and_errors():
    x = np.zeros(4096)
    assert psd(x, 512.0, nperseg=1024).nperseg == 1024
    _raises(lambda: psd(x, 0.0), "fs_in", "> 0")
    _raises(lambda: psd(x, -5.0), "fs_in")
    _raises(lambda: psd(x, 512.0, nperseg=3), "nperseg")
    _raises(lambda: psd([1.0, 2.0], 512.0), "at least 16")
    _raises(lambda: psd(np.full(100, np.nan), 512.0), "x", "finite")
    _raises(lambda: psd(np.zeros(20), 10000.0), "too short")
