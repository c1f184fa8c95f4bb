"""ISO 2631-1 Wk weighting, weighted RMS and VDV against the spec's |Wk| and hand values."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import sosfreqz

from mrsuspension.errors import ValidationError
from mrsuspension.measures import vdv, weighted_rms, wk_filter, wk_sos, wk_weighting

# MODEL_SPEC section 9 (ISO 2631-1 Table 3 values)
SPEC_WK = {1.0: 0.482, 4.0: 0.967, 6.3: 1.054, 20.0: 0.636}


def test_wk_magnitude_matches_the_spec_values():
    f = np.array(list(SPEC_WK))
    np.testing.assert_allclose(wk_weighting(f), list(SPEC_WK.values()), rtol=0.01)
    np.testing.assert_allclose(wk_weighting(f), list(SPEC_WK.values()), atol=6e-4)


def test_wk_shape():
    assert float(wk_weighting(0.0)) == 0.0
    assert float(wk_weighting(0.01)) < 1e-3  # band-limited below 0.4 Hz
    assert float(wk_weighting(400.0)) < 0.05  # and above 100 Hz
    with pytest.raises(ValidationError, match="freq"):
        wk_weighting([-1.0])


@pytest.mark.parametrize("fs", [512.0, 1000.0, 10000.0])
def test_digital_filter_follows_the_analog_weighting(fs):
    f = np.array([0.5, 1.0, 2.0, 4.0, 6.3, 10.0, 16.0])
    _, h = sosfreqz(wk_sos(fs), worN=f, fs=fs)
    np.testing.assert_allclose(np.abs(h), wk_weighting(f), rtol=0.005)


@pytest.mark.parametrize("f0", [1.0, 4.0, 6.3])
def test_filtered_sinusoid_has_the_weighted_amplitude(f0):
    fs = 1000.0
    t = np.arange(0.0, 40.0, 1 / fs)
    aw = wk_filter(1.5 * np.sin(2 * np.pi * f0 * t), fs)
    tail = aw[-int(10 * fs) :]  # after the start transient
    assert np.sqrt(2) * np.sqrt(np.mean(tail**2)) == pytest.approx(1.5 * SPEC_WK[f0], rel=0.01)


def test_weighted_rms_of_a_sinusoid():
    fs, f0, amp = 1000.0, 4.0, 2.0
    t = np.arange(0.0, 120.0, 1 / fs)
    expected = amp / math.sqrt(2) * SPEC_WK[f0]
    assert weighted_rms(amp * np.sin(2 * np.pi * f0 * t), fs) == pytest.approx(expected, rel=0.01)


@pytest.mark.parametrize("f0", [4.0, 6.3])
def test_vdv_of_a_sinusoid(f0):
    fs, amp, duration = 2000.0, 1.2, 60.0
    t = np.arange(0.0, duration, 1 / fs)
    x = amp * np.sin(2 * np.pi * f0 * t)
    raw = (3 / 8 * amp**4 * duration) ** 0.25
    assert vdv(x, fs, weighted=False) == pytest.approx(raw, rel=1e-6)
    assert vdv(x, fs) == pytest.approx(raw * SPEC_WK[f0], rel=0.01)


def test_input_checks():
    _raises = pytest.raises
    with _raises(ValidationError, match=r"fs must be > 200 Hz"):
        wk_sos(100.0)
    with _raises(ValidationError, match="fs"):
        weighted_rms(np.zeros(10), 0.0)
    with _raises(ValidationError, match="acc must be finite"):
        wk_filter([0.0, np.inf], 1000.0)
    with _raises(ValidationError, match="acc must not be empty"):
        vdv([], 1000.0)
    with _raises(ValidationError, match="fs"):
        vdv([1.0], -1.0, weighted=False)
