"""ISO 2631-1 frequency weightings Wk, Wd and We, weighted RMS and VDV.

Beyond the dissertation (model reference, section 9). The Wk weighting (vertical, seat surface) is
the product of four analog filters (ISO 2631-1:1997, Annex A), with ``s = j 2 pi f`` and
``w_i = 2 pi f_i``:

* band limiting, high-pass ``s^2 / (s^2 + s w1/Q1 + w1^2)``, f1 = 0.4 Hz, Q1 = 1/sqrt(2);
* band limiting, low-pass ``w2^2 / (s^2 + s w2/Q2 + w2^2)``, f2 = 100 Hz, Q2 = 1/sqrt(2);
* acceleration-velocity transition ``(1 + s/w3) / (1 + s/(Q4 w4) + s^2/w4^2)``,
  f3 = f4 = 12.5 Hz, Q4 = 0.63;
* upward step ``(1 + s/(Q5 w5) + s^2/w5^2) / (1 + s/(Q6 w6) + s^2/w6^2) (w5/w6)^2``,
  f5 = 2.37 Hz, Q5 = 0.91, f6 = 3.35 Hz, Q6 = 0.91.

Wd (horizontal x/y, seat surface; Table 1) and We (rotational rx/ry/rz; Table 2) have the
same band limits and no upward step (f5 = f6 = infinity in Table A.2): Wd has
f3 = f4 = 2 Hz, Q4 = 0.63; We has f3 = f4 = 1 Hz, Q4 = 0.63. Every function below takes
``weighting="Wk"`` (default), ``"Wd"`` or ``"We"`` (:data:`WEIGHTINGS`).

In the time domain each section is mapped by the bilinear transform with its corner
frequencies pre-warped, so every corner sits at its analog frequency for any sampling
rate above 200 Hz (twice f2). Between the corners the bilinear map still compresses the
response near ``fs/2``: at 512 Hz the filter reads -1.19 dB at 100 Hz and -0.48 dB at
80 Hz, at 1 kHz -0.29 and -0.12 dB, at 2 kHz -0.07 and -0.03 dB. :func:`wk_filter`,
:func:`weighted_rms` and :func:`vdv` therefore filter at :data:`WK_FILTER_RATE` (2 kHz)
or more: a record sampled slower is first upsampled by the integer factor
``ceil(2000 / fs)`` with :func:`scipy.signal.resample_poly` (an anti-imaging FIR, flat
to 0.01 dB over the Wk band). The whole path (resample, filter, back to ``fs``) is then
within 0.03 dB of ``|Wk|`` over 0.5-80 Hz and 0.07 dB at 100 Hz, for 512 Hz and 1 kHz
records alike (:func:`wk_response`).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError, check_finite, check_range
from mrsuspension.measures._checks import FloatArray, rate, signal

__all__ = [
    "WD_CONSTANTS",
    "WEIGHTINGS",
    "WE_CONSTANTS",
    "WK_CONSTANTS",
    "WK_FILTER_RATE",
    "check_weighting",
    "frequency_weighting",
    "vdv",
    "weighted_rms",
    "weighting_filter",
    "weighting_sos",
    "wk_filter",
    "wk_response",
    "wk_sos",
    "wk_weighting",
]

#: Wk filter constants, ISO 2631-1 Table A.2 (frequencies in Hz; model reference, section 9)
WK_CONSTANTS: dict[str, float] = {
    "f1": 0.4,
    "f2": 100.0,
    "Q1": 1.0 / math.sqrt(2.0),
    "Q2": 1.0 / math.sqrt(2.0),
    "f3": 12.5,
    "f4": 12.5,
    "Q4": 0.63,
    "f5": 2.37,
    "Q5": 0.91,
    "f6": 3.35,
    "Q6": 0.91,
}

#: Wd filter constants (horizontal x/y, seat surface), ISO 2631-1 Table A.2: no upward
#: step (f5 = f6 = infinity). |Wd| = 1.011 @1 Hz, 0.890 @2 Hz, 0.512 @4 Hz (Table 3).
WD_CONSTANTS: dict[str, float] = {
    "f1": 0.4,
    "f2": 100.0,
    "Q1": 1.0 / math.sqrt(2.0),
    "Q2": 1.0 / math.sqrt(2.0),
    "f3": 2.0,
    "f4": 2.0,
    "Q4": 0.63,
}

#: We filter constants (rotational rx/ry/rz, seat surface), ISO 2631-1 Table A.2: no
#: upward step (f5 = f6 = infinity).
WE_CONSTANTS: dict[str, float] = {
    "f1": 0.4,
    "f2": 100.0,
    "Q1": 1.0 / math.sqrt(2.0),
    "Q2": 1.0 / math.sqrt(2.0),
    "f3": 1.0,
    "f4": 1.0,
    "Q4": 0.63,
}

#: weighting name -> its Table A.2 constants (a table without ``f5`` has no upward step)
WEIGHTINGS: dict[str, dict[str, float]] = {
    "Wk": WK_CONSTANTS,
    "Wd": WD_CONSTANTS,
    "We": WE_CONSTANTS,
}


def check_weighting(weighting: object) -> str:
    """``weighting`` if it names one of :data:`WEIGHTINGS`, else a :class:`ValidationError`.

    Examples
    --------
    >>> check_weighting("Wd")
    'Wd'
    """
    if not isinstance(weighting, str) or weighting not in WEIGHTINGS:
        raise ValidationError(
            f"weighting must be one of {', '.join(WEIGHTINGS)}; got {weighting!r}"
        )
    return weighting


#: Lowest rate [Hz] the weighted measures filter at: slower records are upsampled to it
#: (by an integer factor). At 2 kHz the digital Wk is within 0.03 dB of the analog one
#: up to 80 Hz (0.07 dB at 100 Hz); at 1 kHz it is 0.12 dB low at 80 Hz.
WK_FILTER_RATE = 2000.0


def wk_weighting(freq: npt.ArrayLike) -> FloatArray:
    """Magnitude ``|Wk(f)|`` of the ISO 2631-1 Wk weighting at frequencies ``freq`` [Hz].

    Examples
    --------
    >>> np.round(wk_weighting([1.0, 4.0, 6.3, 20.0]), 3)
    array([0.482, 0.967, 1.054, 0.636])
    """
    return frequency_weighting(freq, "Wk")


def frequency_weighting(freq: npt.ArrayLike, weighting: str = "Wk") -> FloatArray:
    """Magnitude ``|W(f)|`` of an ISO 2631-1 weighting (Annex A) at ``freq`` [Hz].

    Parameters
    ----------
    freq : array_like
        Frequencies [Hz], >= 0.
    weighting : {"Wk", "Wd", "We"}
        Wk vertical, Wd horizontal (x, y), We rotational (:data:`WEIGHTINGS`).

    Examples
    --------
    >>> np.round(frequency_weighting([1.0, 2.0, 4.0, 8.0], "Wd"), 3)  # Table 3
    array([1.011, 0.89 , 0.512, 0.253])
    """
    c = WEIGHTINGS[check_weighting(weighting)]
    f = check_finite("freq", freq)
    if np.any(f < 0):
        raise ValidationError("freq must be >= 0 Hz")
    s = 2j * np.pi * f
    w1, w2, w3, w4 = (2 * np.pi * c[k] for k in ("f1", "f2", "f3", "f4"))
    high = s**2 / (s**2 + s * w1 / c["Q1"] + w1**2)
    low = w2**2 / (s**2 + s * w2 / c["Q2"] + w2**2)
    transition = (1 + s / w3) / (1 + s / (c["Q4"] * w4) + (s / w4) ** 2)
    if "f5" not in c:
        return np.asarray(np.abs(high * low * transition), dtype=float)
    w5, w6 = (2 * np.pi * c[k] for k in ("f5", "f6"))
    step = (1 + s / (c["Q5"] * w5) + (s / w5) ** 2) / (1 + s / (c["Q6"] * w6) + (s / w6) ** 2)
    return np.asarray(np.abs(high * low * transition * step * (w5 / w6) ** 2), dtype=float)


def _min_fs() -> float:
    return 2.0 * WK_CONSTANTS["f2"]


def wk_sos(fs: float) -> FloatArray:
    """Second-order sections of the digital Wk filter at sampling rate ``fs`` [Hz] (> 200 Hz).

    The filter at ``fs`` itself, whatever its accuracy there (-1.19 dB at 100 Hz when
    ``fs`` is 512 Hz); :func:`wk_filter` runs it at :data:`WK_FILTER_RATE` or more.

    Examples
    --------
    >>> wk_sos(1000.0).shape
    (4, 6)
    """
    return weighting_sos(fs, "Wk")


def weighting_sos(fs: float, weighting: str = "Wk") -> FloatArray:
    """Second-order sections of a digital ISO 2631-1 weighting at ``fs`` [Hz] (> 200 Hz).

    As :func:`wk_sos` for ``weighting`` in :data:`WEIGHTINGS` (Wd and We: 3 sections).

    Examples
    --------
    >>> weighting_sos(1000.0, "Wd").shape
    (3, 6)
    """
    c = WEIGHTINGS[check_weighting(weighting)]
    rate_hz = rate("fs", fs)
    if rate_hz <= _min_fs():
        raise ValidationError(
            f"fs must be > {_min_fs():g} Hz (twice the Wk band limit f2 = "
            f"{WK_CONSTANTS['f2']:g} Hz) for the Wk filter; got {rate_hz:g} Hz: resample first"
        )

    def warp(f_hz: float) -> float:  # pre-warped analog corner [rad/s]
        return 2.0 * rate_hz * math.tan(math.pi * f_hz / rate_hz)

    def poles(w: float, q: float) -> list[complex]:  # roots of s^2 + s w/q + w^2
        return [complex(r) for r in np.roots([1.0, w / q, w * w])]

    w1, w2, w3, w4 = (warp(c[k]) for k in ("f1", "f2", "f3", "f4"))
    zeros: list[complex] = [0j, 0j]  # high-pass
    pole_list = poles(w1, c["Q1"]) + poles(w2, c["Q2"]) + poles(w4, c["Q4"])
    zeros += [complex(-w3)]
    if "f5" in c:  # the upward step (Wk)
        w5, w6 = warp(c["f5"]), warp(c["f6"])
        pole_list += poles(w6, c["Q6"])
        zeros += poles(w5, c["Q5"])
    # gains of the monic forms: high-pass 1, low-pass w2^2, transition w4^2/w3, and the
    # step (1 + s/(Q5 w5) + s^2/w5^2)/(1 + s/(Q6 w6) + s^2/w6^2) (w5/w6)^2 is monic/monic
    gain = w2**2 * w4**2 / w3
    from scipy.signal import bilinear_zpk, zpk2sos  # scipy loads on first use

    z_d, p_d, k_d = bilinear_zpk(np.array(zeros), np.array(pole_list), gain, rate_hz)
    return np.asarray(zpk2sos(z_d, p_d, k_d), dtype=float)


def _upsampling(fs: float) -> int:
    """The integer factor that brings ``fs`` [Hz] to :data:`WK_FILTER_RATE` or more."""
    rate_hz = rate("fs", fs)
    if rate_hz <= _min_fs():
        raise ValidationError(
            f"fs must be > {_min_fs():g} Hz (twice the Wk band limit f2 = "
            f"{WK_CONSTANTS['f2']:g} Hz) for the Wk filter; got {rate_hz:g} Hz: resample first"
        )
    return max(1, math.ceil(WK_FILTER_RATE / rate_hz - 1e-9))


def _weighted(
    acc: npt.ArrayLike, fs: float, weighting: str = "Wk"
) -> tuple[FloatArray, float, int]:
    """``(a_w, rate, factor)``: the weighted signal at ``rate = factor fs`` >= 2 kHz."""
    from scipy.signal import resample_poly, sosfilt  # scipy loads on first use

    check_weighting(weighting)
    a = signal("acc", acc)
    factor = _upsampling(fs)
    if factor > 1:
        a = np.asarray(resample_poly(a, factor, 1), dtype=float)
    high = float(fs) * factor
    return np.asarray(sosfilt(weighting_sos(high, weighting), a), dtype=float), high, factor


def wk_filter(acc: npt.ArrayLike, fs: float) -> FloatArray:
    """Wk-weighted acceleration: ``acc`` [m/s^2] sampled at ``fs`` [Hz] through the Wk filter.

    A causal filter starting from rest (as a measuring instrument does): the first
    seconds carry the start transient of the 0.4 Hz high-pass. Below
    :data:`WK_FILTER_RATE` the record is upsampled by ``ceil(2000 / fs)`` (polyphase
    FIR), filtered there and returned at ``fs`` (every ``factor``-th sample: exact, the
    upsampled record holds nothing above the original Nyquist frequency), so a 512 Hz
    record is weighted within 0.03 dB of ``|Wk|`` up to 80 Hz.

    Examples
    --------
    >>> fs = 1000.0
    >>> t = np.arange(0.0, 30.0, 1 / fs)
    >>> aw = wk_filter(np.sin(2 * np.pi * 4.0 * t), fs)
    >>> round(float(np.max(np.abs(aw[-2000:]))), 2)  # |Wk(4 Hz)| = 0.967
    0.97
    """
    aw, _, factor = _weighted(acc, fs)
    return np.ascontiguousarray(aw[::factor])


def weighting_filter(acc: npt.ArrayLike, fs: float, weighting: str = "Wk") -> FloatArray:
    """``acc`` [m/s^2 or rad/s^2] at ``fs`` [Hz] through an ISO 2631-1 weighting.

    As :func:`wk_filter` (same upsampling to :data:`WK_FILTER_RATE`) for ``weighting``
    in :data:`WEIGHTINGS`; the output has the input's unit.

    Examples
    --------
    >>> fs = 1000.0
    >>> t = np.arange(0.0, 30.0, 1 / fs)
    >>> aw = weighting_filter(np.sin(2 * np.pi * 2.0 * t), fs, "Wd")
    >>> round(float(np.max(np.abs(aw[-2000:]))), 2)  # |Wd(2 Hz)| = 0.890
    0.89
    """
    aw, _, factor = _weighted(acc, fs, weighting)
    return np.ascontiguousarray(aw[::factor])


def wk_response(freq: npt.ArrayLike, fs: float) -> FloatArray:
    """Magnitude of the weighting :func:`wk_filter` applies to a record sampled at ``fs``.

    The whole path (upsampling to :data:`WK_FILTER_RATE` or more, the digital Wk
    filter, back to ``fs``), measured from its impulse response over 2^18 samples (the
    0.4 Hz high-pass has decayed by then); compare with the analog :func:`wk_weighting`.

    Parameters
    ----------
    freq : array_like
        Frequencies [Hz], in ``[0, fs/2]``.
    fs : float
        Sampling rate of the records [Hz] (> 200 Hz).

    Examples
    --------
    >>> f = np.array([4.0, 80.0, 100.0])
    >>> db = 20 * np.log10(wk_response(f, 512.0) / wk_weighting(f))
    >>> bool(np.all(np.abs(db) < 0.1))
    True
    """
    rate_hz = rate("fs", fs)
    f = check_range("freq", freq, 0.0, rate_hz / 2, unit="Hz")
    n = 2**18
    impulse = np.zeros(n)
    impulse[64] = 1.0  # away from the start: the upsampling FIR reaches back ~10 samples
    h = wk_filter(impulse, rate_hz)
    spectrum = np.abs(np.fft.rfft(h))
    return np.asarray(np.interp(f, np.fft.rfftfreq(n, 1.0 / rate_hz), spectrum), dtype=float)


def weighted_rms(acc: npt.ArrayLike, fs: float, *, weighting: str = "Wk") -> float:
    """Weighted RMS acceleration ``a_w`` [m/s^2] over the whole record (ISO 2631-1 6.4.2).

    Filtered at :data:`WK_FILTER_RATE` or more (see :func:`wk_filter`), so a 512 Hz
    record gives the same ``a_w`` as a 1 kHz one. ``weighting`` is ``"Wk"`` (default),
    ``"Wd"`` or ``"We"`` (a rotational acceleration [rad/s^2] gives ``a_w`` in rad/s^2).

    Examples
    --------
    >>> fs = 1000.0
    >>> t = np.arange(0.0, 60.0, 1 / fs)
    >>> round(weighted_rms(np.sin(2 * np.pi * 6.3 * t), fs) * math.sqrt(2), 2)  # |Wk(6.3)|
    1.05
    """
    aw, _, _ = _weighted(acc, fs, weighting)
    return float(np.sqrt(np.mean(aw * aw)))


def vdv(acc: npt.ArrayLike, fs: float, *, weighted: bool = True) -> float:
    """Fourth-power vibration dose value ``(integral a_w^4 dt)^(1/4)`` [m/s^1.75] (ISO 2631-1 6.3.2).

    ``weighted=False`` skips the Wk filter (the raw acceleration's dose). The weighted
    dose is integrated at the filter's rate, :data:`WK_FILTER_RATE` or more (see
    :func:`wk_filter`).

    Examples
    --------
    >>> fs = 1000.0
    >>> t = np.arange(0.0, 8.0, 1 / fs)
    >>> round(vdv(2.0 * np.sin(2 * np.pi * 5 * t), fs, weighted=False), 4)  # (3/8 A^4 T)^(1/4)
    2.6321
    """
    rate_hz = rate("fs", fs)
    if weighted:
        a, rate_hz, _ = _weighted(acc, fs)
    else:
        a = signal("acc", acc)
    return float((np.sum(a**4) / rate_hz) ** 0.25)
