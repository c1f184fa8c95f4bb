"""Welch power spectral densities with the dissertation's settings (model reference, section 9).

Signals are resampled to 512 Hz (polyphase FIR with anti-aliasing), then analysed with
one-sided Welch averaging: Hann window, 8192-sample segments (0.0625 Hz resolution),
50 % overlap, the mean removed from every segment.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError
from mrsuspension.measures._checks import FloatArray, rate, signal

__all__ = ["PSD_FS", "PSD_NPERSEG", "PowerSpectrum", "ShortRecordWarning", "psd"]

#: analysis sampling rate [Hz] of the random-road PSDs (model reference, section 9)
PSD_FS = 512.0
#: Welch segment length: 8192 samples at 512 Hz = 0.0625 Hz resolution (model reference, section 9)
PSD_NPERSEG = 8192


class ShortRecordWarning(UserWarning):
    """The record is shorter than one Welch segment; the whole record was used instead."""


@dataclass(frozen=True)
class PowerSpectrum:
    """A one-sided PSD; unpacks as ``f, p = psd(x, fs_in)``.

    Attributes
    ----------
    frequency : ndarray
        Frequencies [Hz], 0 to ``fs/2``.
    density : ndarray
        Power spectral density [unit^2/Hz].
    fs : float
        Sampling rate [Hz] the spectrum was computed at.
    nperseg : int
        Segment length used (samples).
    short_record : bool
        True when the record was shorter than the requested segment, so one segment
        of the whole record was used (coarser resolution, no averaging).
    """

    frequency: FloatArray
    density: FloatArray
    fs: float
    nperseg: int
    short_record: bool

    @property
    def resolution(self) -> float:
        """Frequency resolution ``fs / nperseg`` [Hz]."""
        return self.fs / self.nperseg

    def __iter__(self) -> Iterator[FloatArray]:
        yield self.frequency
        yield self.density


def psd(
    x: npt.ArrayLike,
    fs_in: float,
    *,
    fs: float = PSD_FS,
    nperseg: int = PSD_NPERSEG,
    warn: bool = True,
) -> PowerSpectrum:
    """One-sided Welch PSD of ``x`` sampled at ``fs_in``, with the dissertation's settings.

    The signal is resampled to ``fs`` (512 Hz) with :func:`scipy.signal.resample_poly`
    (anti-aliasing FIR, ends padded by a fitted line) unless ``fs_in`` already equals
    it, then Welch-averaged with a Hann window, ``nperseg`` (8192) samples per segment
    and 50 % overlap. When the resampled record is shorter than ``nperseg``, the whole
    record forms a single segment: the result says so (``short_record``) and a
    :class:`ShortRecordWarning` is issued (unless ``warn=False``).

    Parameters
    ----------
    x : array_like
        The signal (any unit), at least 16 samples.
    fs_in : float
        Its sampling rate [Hz].
    fs : float, optional
        Analysis rate [Hz], 512 Hz. The resampling ratio is a fraction with denominator
        at most 10000; the rate actually used is reported in ``fs``.
    nperseg : int, optional
        Samples per segment, 8192.
    warn : bool, optional
        Issue :class:`ShortRecordWarning` for a short record (the flag is set anyway).

    Examples
    --------
    >>> t = np.arange(0.0, 64.0, 1e-3)  # 64 s at 1 kHz
    >>> spec = psd(np.sin(2 * np.pi * 4.0 * t), 1000.0)
    >>> spec.fs, spec.resolution, float(spec.frequency[np.argmax(spec.density)])
    (512.0, 0.0625, 4.0)
    >>> round(float(np.sum(spec.density) * spec.resolution), 3)  # power = 1/2
    0.5
    """
    from scipy.signal import resample_poly, welch  # scipy loads on first use

    data = signal("x", x)
    f_in = rate("fs_in", fs_in)
    f_out = rate("fs", fs)
    if isinstance(nperseg, bool) or not isinstance(nperseg, int | np.integer) or nperseg < 16:
        raise ValidationError(f"nperseg must be an integer >= 16; got {nperseg!r}")
    if data.size < 16:
        raise ValidationError(f"x must hold at least 16 samples for a PSD; got {data.size}")
    if f_in == f_out:
        y, f_used = data, f_out
    else:
        ratio = Fraction(f_out / f_in).limit_denominator(10000)
        if ratio.numerator == 0 or ratio.numerator > 10000:
            raise ValidationError(
                f"cannot resample from fs_in = {f_in:g} Hz to {f_out:g} Hz (ratio {f_out / f_in:g} "
                "out of range); resample the signal first"
            )
        y = resample_poly(data, ratio.numerator, ratio.denominator, padtype="line")
        f_used = f_in * ratio.numerator / ratio.denominator
    seg = int(nperseg)
    short = y.size < seg
    if short:
        if y.size < 16:
            raise ValidationError(
                f"x is too short for a PSD: {data.size} samples at {f_in:g} Hz give {y.size} at "
                f"{f_used:g} Hz; need at least 16"
            )
        if warn:
            warnings.warn(
                f"record of {y.size} samples at {f_used:g} Hz ({y.size / f_used:.3g} s) is shorter "
                f"than one Welch segment ({seg} samples, {seg / f_used:.3g} s): using the whole "
                f"record as one segment (resolution {f_used / y.size:.3g} Hz, no averaging)",
                ShortRecordWarning,
                stacklevel=2,
            )
        seg = y.size
    freq, density = welch(
        y, fs=f_used, window="hann", nperseg=seg, noverlap=seg // 2, detrend="constant"
    )
    return PowerSpectrum(
        np.asarray(freq, dtype=float), np.asarray(density, dtype=float), f_used, seg, short
    )
