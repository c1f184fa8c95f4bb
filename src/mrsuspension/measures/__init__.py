"""Performance measures (model reference, section 9): pure functions on arrays.

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
                            :func:`dtr_ratio`, :func:`peak`
random road                 :func:`psd` (Welch, 512 Hz, 8192, Hann, 50 %),
                            :func:`dlc` (mean load), :func:`rms`
ISO 2631-1 (beyond seed)    :func:`wk_weighting`, :func:`wk_filter`,
                            :func:`weighted_rms`, :func:`vdv`,
                            :func:`wk_response`; Wd/We: :func:`frequency_weighting`,
                            :func:`weighting_filter`, :func:`weighting_sos`
vehicle (half/full car)     :func:`seat_acceleration`, :func:`seat_vibration`
                            (ISO 2631-1 axes, factors, total value),
                            :func:`wheel_dlc`, :func:`wheel_lift_off_time`,
                            :func:`wheel_suspension_travel`,
                            :func:`wheel_coil_energy` (``R i^2``) and their
                            single-corner forms
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
    dtr_ratio,
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
from mrsuspension.measures.vehicle import (
    AXIS_FACTORS,
    AXIS_WEIGHTINGS,
    COIL_RESISTANCE,
    PURPOSES,
    SeatVibration,
    SuspensionTravel,
    coil_energy,
    lift_off_time,
    seat_acceleration,
    seat_vibration,
    suspension_travel,
    wheel_coil_energy,
    wheel_dlc,
    wheel_lift_off_time,
    wheel_suspension_travel,
)

__all__ = [
    "AXIS_FACTORS",
    "AXIS_WEIGHTINGS",
    "COIL_RESISTANCE",
    "DEFAULT_ROAD_PEAK",
    "PSD_FS",
    "PSD_NPERSEG",
    "PURPOSES",
    "ROAD_PEAKS",
    "WD_CONSTANTS",
    "WEIGHTINGS",
    "WE_CONSTANTS",
    "WK_CONSTANTS",
    "WK_FILTER_RATE",
    "G",
    "PowerSpectrum",
    "RoadPeak",
    "SeatVibration",
    "ShortRecordWarning",
    "SuspensionTravel",
    "T_as",
    "T_au",
    "T_dr",
    "T_ds",
    "T_du",
    "Window",
    "asymmetry_ratio",
    "check_road_peak",
    "check_weighting",
    "coil_energy",
    "current_statistics",
    "dlc",
    "dtr",
    "dtr_ratio",
    "force_tracking_error",
    "frequency_weighting",
    "harmonic_measures",
    "lift_off_time",
    "peak",
    "psd",
    "rms",
    "road_acceleration_peak",
    "seat_acceleration",
    "seat_vibration",
    "shock_ratios",
    "steady_window",
    "suspension_travel",
    "transmissibility",
    "vdv",
    "weighted_rms",
    "weighting_filter",
    "weighting_sos",
    "wheel_coil_energy",
    "wheel_dlc",
    "wheel_lift_off_time",
    "wheel_suspension_travel",
    "wk_filter",
    "wk_response",
    "wk_sos",
    "wk_weighting",
]
