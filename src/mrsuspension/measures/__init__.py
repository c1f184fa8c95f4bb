"""Performance measures (MODEL_SPEC section 9): pure functions on arrays.

Every function takes plain numpy arrays in SI units, with an explicit sampling rate
(``fs``) or time array where it needs one; nothing here knows about the engine.

==========================  =====================================================
harmonic, steady state      :func:`steady_window`, :func:`rms`,
                            :func:`transmissibility`, :func:`T_as`, :func:`T_au`,
                            :func:`T_dr`, :func:`T_ds`, :func:`T_du`, :func:`dlc`,
                            :func:`asymmetry_ratio`, :func:`current_statistics`,
                            :func:`force_tracking_error`, :func:`harmonic_measures`
shock (rounded pulse)       :func:`shock_ratios`, :func:`road_acceleration_peak`
                            (``road_peak``: after-onset or onset), :func:`dtr`,
                            :func:`peak`
random road                 :func:`psd` (Welch, 512 Hz, 8192, Hann, 50 %),
                            :func:`dlc` (mean load), :func:`rms`
ISO 2631-1 (beyond seed)    :func:`wk_weighting`, :func:`wk_filter`,
                            :func:`weighted_rms`, :func:`vdv`,
                            :func:`wk_response`; Wd/We: :func:`frequency_weighting`,
                            :func:`weighting_filter`, :func:`weighting_sos`
==========================  =====================================================

Examples
--------
>>> import numpy as np
>>> from mrsuspension import measures
>>> t = np.arange(0.0, 14.0, 1e-3)
>>> z_r = 0.025 * np.sin(2 * np.pi * 1.5 * t)
>>> w = measures.steady_window(t, 1.5)
>>> measures.T_dr(0.4 * z_r, z_r, window=w)
0.4
"""

from __future__ import annotations

from mrsuspension.measures._checks import Window
from mrsuspension.measures.iso2631 import (
    WD_CONSTANTS,
    WE_CONSTANTS,
    WEIGHTINGS,
    WK_CONSTANTS,
    WK_FILTER_RATE,
    check_weighting,
    frequency_weighting,
    vdv,
    weighted_rms,
    weighting_filter,
    weighting_sos,
    wk_filter,
    wk_response,
    wk_sos,
    wk_weighting,
)
from mrsuspension.measures.shock import (
    DEFAULT_ROAD_PEAK,
    ROAD_PEAKS,
    RoadPeak,
    check_road_peak,
    dtr,
    peak,
    road_acceleration_peak,
    shock_ratios,
)
from mrsuspension.measures.spectral import (
    PSD_FS,
    PSD_NPERSEG,
    PowerSpectrum,
    ShortRecordWarning,
    psd,
)
from mrsuspension.measures.steady import (
    G,
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

__all__ = [
    "DEFAULT_ROAD_PEAK",
    "PSD_FS",
    "PSD_NPERSEG",
    "ROAD_PEAKS",
    "WD_CONSTANTS",
    "WEIGHTINGS",
    "WE_CONSTANTS",
    "WK_CONSTANTS",
    "WK_FILTER_RATE",
    "G",
    "PowerSpectrum",
    "RoadPeak",
    "ShortRecordWarning",
    "T_as",
    "T_au",
    "T_dr",
    "T_ds",
    "T_du",
    "Window",
    "asymmetry_ratio",
    "check_road_peak",
    "check_weighting",
    "current_statistics",
    "dlc",
    "dtr",
    "force_tracking_error",
    "frequency_weighting",
    "harmonic_measures",
    "peak",
    "psd",
    "rms",
    "road_acceleration_peak",
    "shock_ratios",
    "steady_window",
    "transmissibility",
    "vdv",
    "weighted_rms",
    "weighting_filter",
    "weighting_sos",
    "wk_filter",
    "wk_response",
    "wk_sos",
    "wk_weighting",
]
