"""ISO 2631-1 and ISO 8608 against the standards' own tables (issue 27).

ISO 2631-1:1997 Table 3 gives the principal frequency weightings at the nominal
one-third-octave frequencies 0.1-400 Hz (bands x = -10 ... 26), as factors (x 1000, three
significant figures) and in decibels (two decimals). The weightings here are the
package's analog ``|W(f)|`` (Annex A's formulas, :func:`frequency_weighting`) and its
digital filters (:func:`weighting_sos`). ISO 8608:2016 Table F.1 classes roads by
``Gd(n0)`` at ``n0 = 0.1 cycle/m`` (and ``Gd(Omega0)`` at ``Omega0 = 1 rad/m``): class
limits a factor 4 apart, each class's value the geometric mean of its limits.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import sosfreqz

from mrsuspension.excitation import ISO8608_BAND, ISO8608_CLASSES, ISO8608_N0, iso8608_psd
from mrsuspension.measures import frequency_weighting, weighting_sos

#: ISO 2631-1:1997 Table 3: f [Hz], Wk factor x 1000, Wk [dB], Wd factor x 1000, Wd [dB]
TABLE_3 = """
0.1     31.2  -30.11   62.4  -24.09
0.125   48.6  -26.26   97.3  -20.24
0.16    79.0  -22.05  158    -16.01
0.2    121    -18.33  243    -12.28
0.25   182    -14.81  365     -8.75
0.315  263    -11.60  530     -5.52
0.4    352     -9.07  713     -2.94
0.5    418     -7.57  853     -1.38
0.63   459     -6.77  944     -0.50
0.8    477     -6.43  992     -0.07
1      482     -6.33 1011      0.10
1.25   484     -6.29 1008      0.07
1.6    494     -6.12  968     -0.28
2      531     -5.49  890     -1.01
2.5    631     -4.01  776     -2.20
3.15   804     -1.90  642     -3.85
4      967     -0.29  512     -5.82
5     1039      0.33  409     -7.76
6.3   1054      0.46  323     -9.81
8     1036      0.31  253    -11.93
10     988     -0.10  202    -13.91
12.5   902     -0.89  161    -15.87
16     768     -2.29  125    -18.03
20     636     -3.93  100    -19.99
25     513     -5.80   80.0  -21.94
31.5   405     -7.86   63.2  -23.98
40     314    -10.05   49.4  -26.13
50     246    -12.19   38.8  -28.22
63     186    -14.61   29.5  -30.60
80     132    -17.56   21.1  -33.53
100     88.7  -21.04   14.1  -36.99
125     54.0  -25.35    8.63 -41.28
160     28.5  -30.91    4.55 -46.84
200     15.2  -36.38    2.43 -52.30
250      7.90 -42.04    1.26 -57.97
315      3.98 -48.00    0.64 -63.92
400      1.95 -54.20    0.31 -70.12
"""
ROWS = np.array([[float(v) for v in line.split()] for line in TABLE_3.strip().splitlines()])
FREQ = ROWS[:, 0]
COLUMNS = {"Wk": (ROWS[:, 1], ROWS[:, 2]), "Wd": (ROWS[:, 3], ROWS[:, 4])}


def _db(x: np.ndarray) -> np.ndarray:
    return np.asarray(20.0 * np.log10(x))


def test_table_is_every_third_octave_band_from_0_1_to_400_hz() -> None:
    assert FREQ.size == 37  # bands x = -10 ... 26
    exact = 10.0 ** (np.arange(-10, 27) / 10.0)
    assert np.allclose(FREQ / exact, 1.0, atol=0.03)  # the nominal (rounded) frequencies
    for factor, db in COLUMNS.values():  # the table agrees with itself, to its rounding
        assert np.max(np.abs(_db(factor / 1000.0) - db)) < 0.06


@pytest.mark.audit("closed form")
@pytest.mark.parametrize("weighting", ["Wk", "Wd"])
def test_weighting_matches_table_3_in_every_band(weighting: str) -> None:
    """Within 0.05 dB of the dB column at each nominal frequency (measured: 0.005 dB)."""
    factor, db = COLUMNS[weighting]
    ours = frequency_weighting(FREQ, weighting)
    error = _db(ours) - db
    worst = int(np.argmax(np.abs(error)))
    print(f"{weighting}: worst {error[worst]:+.4f} dB at {FREQ[worst]:g} Hz")
    assert np.max(np.abs(error)) < 0.05
    # and the factor column within a unit of its last digit (three significant figures, at
    # most two decimals; two factors, Wk at 1.25 and 16 Hz, read 0.55 and 0.7 units below
    # both the formula and the table's own dB column: the table truncated them)
    last = np.maximum(10.0 ** (np.floor(np.log10(factor)) - 2), 0.01)
    assert np.all(np.abs(1000.0 * ours - factor) <= last)


@pytest.mark.parametrize("weighting", ["Wk", "Wd"])
def test_digital_filter_matches_table_3_to_400_hz_at_20_khz(weighting: str) -> None:
    """The bilinear filters at a rate that resolves 400 Hz (measured: 0.033 dB there)."""
    _, h = sosfreqz(weighting_sos(20_000.0, weighting), worN=FREQ, fs=20_000.0)
    assert np.max(np.abs(_db(np.abs(h)) - COLUMNS[weighting][1])) < 0.05


#: ISO 8608:2016 Table F.1: class, lower and upper limit of Gd(n0) [1e-6 m^3], Gd(Omega0)
#: geometric mean [1e-6 m^3] at Omega0 = 1 rad/m (class A starts at 0, class H is open)
ISO8608_TABLE = {
    "A": (None, 32.0, 1.0), "B": (32.0, 128.0, 4.0), "C": (128.0, 512.0, 16.0),
    "D": (512.0, 2048.0, 64.0), "E": (2048.0, 8192.0, 256.0), "F": (8192.0, 32768.0, 1024.0),
    "G": (32768.0, 131072.0, 4096.0), "H": (131072.0, None, 16384.0),
}  # fmt: skip


@pytest.mark.audit("closed form")
def test_iso8608_class_levels_are_the_geometric_means_of_the_class_limits() -> None:
    assert list(ISO8608_CLASSES) == list(ISO8608_TABLE)
    assert ISO8608_N0 == 0.1
    assert ISO8608_BAND == (0.011, 2.83)
    for key, (lo, hi, omega_level) in ISO8608_TABLE.items():
        level = ISO8608_CLASSES[key] / 1e-6
        # the open ends: a factor of 4, as between the other limits
        low = hi / 4.0 if lo is None and hi is not None else lo
        high = low * 4.0 if hi is None and low is not None else hi
        assert low is not None
        assert high is not None
        assert high == 4.0 * low
        assert level == pytest.approx(math.sqrt(low * high), rel=1e-12), key
        # Gd(Omega) = Gd(n) / (2 pi) at Omega = 2 pi n; at Omega0 = 1 rad/m, n = 1/(2 pi)
        n = 1.0 / (2.0 * math.pi)
        gd_omega = float(iso8608_psd(key, [n])[0]) / (2.0 * math.pi) / 1e-6
        assert gd_omega == pytest.approx(omega_level, rel=0.006), key  # the table rounds
