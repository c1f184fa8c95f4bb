"""ISO 2631-1 Wd and We weightings beside Wk (Annex A, Table A.2; Table 3 values)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mrsuspension.errors import ValidationError
from mrsuspension.measures import (
    WEIGHTINGS,
    frequency_weighting,
    weighted_rms,
    weighting_filter,
    weighting_sos,
    wk_sos,
    wk_weighting,
)

#: ISO 2631-1:1997 Table 3, Wd column (factor x 1000) at one-third-octave frequencies
WD_TABLE = {
    0.5: 853,
    0.63: 944,
    0.8: 992,
    1.0: 1011,
    1.25: 1008,
    1.6: 968,
    2.0: 890,
    2.5: 776,
    3.15: 642,
    4.0: 512,
    5.0: 409,
    6.3: 323,
    8.0: 253,
    12.5: 161,
    16.0: 125,
    20.0: 100,
}


def test_wd_matches_table_3() -> None:
    f = np.array(list(WD_TABLE))
    table = np.array(list(WD_TABLE.values())) / 1000.0
    assert np.allclose(frequency_weighting(f, "Wd"), table, atol=0.0006)


def test_we_is_a_velocity_weighting_above_1_hz() -> None:
    # We = band limits x (1 + s/w3)/(1 + s/(Q4 w4) + s^2/w4^2), f3 = f4 = 1 Hz: ~1/f above
    f = np.array([4.0, 8.0, 16.0])
    w = frequency_weighting(f, "We")
    assert np.allclose(w * f, w[0] * f[0], rtol=0.02)
    assert frequency_weighting([1.0], "We")[0] == pytest.approx(0.880, abs=0.001)


def test_wk_unchanged_and_has_the_step() -> None:
    assert np.array_equal(frequency_weighting([1.0, 4.0], "Wk"), wk_weighting([1.0, 4.0]))
    assert np.array_equal(weighting_sos(1000.0, "Wk"), wk_sos(1000.0))
    assert weighting_sos(1000.0, "Wd").shape == (3, 6)
    assert set(WEIGHTINGS) == {"Wk", "Wd", "We"}


@pytest.mark.parametrize("freq", [1.0, 2.0, 4.0, 8.0])
def test_sine_through_wd_at_table_frequencies(freq: float) -> None:
    fs = 1000.0
    t = np.arange(0.0, 40.0, 1 / fs)
    acc = np.sin(2 * np.pi * freq * t)
    aw = weighting_filter(acc, fs, "Wd")
    steady = aw[int(20 * fs) :]
    amplitude = math.sqrt(2.0) * float(np.sqrt(np.mean(steady**2)))
    assert amplitude == pytest.approx(WD_TABLE[freq] / 1000.0, abs=0.002)


def test_weighted_rms_with_wd() -> None:
    fs = 512.0
    t = np.arange(0.0, 120.0, 1 / fs)
    a_w = weighted_rms(np.sin(2 * np.pi * 4.0 * t), fs, weighting="Wd")
    assert a_w * math.sqrt(2.0) == pytest.approx(0.512, abs=0.005)


def test_unknown_weighting() -> None:
    with pytest.raises(ValidationError, match="weighting must be one of Wk, Wd, We; got 'Wx'"):
        frequency_weighting([1.0], "Wx")
    with pytest.raises(ValidationError, match="weighting"):
        weighted_rms(np.zeros(1000), 1000.0, weighting="wd")
