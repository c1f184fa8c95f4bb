"""Shock measures of rounded-pulse runs, eqs. (3.41) and (3.44) (spec section 9).

All peaks are maxima of absolute values over the whole record.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mrsuspension.errors import ValidationError
from mrsuspension.measures._checks import rate, same_length, signal
from mrsuspension.measures.steady import G

__all__ = ["dtr", "peak", "shock_ratios"]


def peak(x: npt.ArrayLike) -> float:
    """Largest absolute value of a signal, ``max |x|``.

    Examples
    --------
    >>> peak([0.1, -0.4, 0.3])
    0.4
    """
    return float(np.max(np.abs(signal("x", x))))


def shock_ratios(
    z_s: npt.ArrayLike,
    z_u: npt.ArrayLike,
    z_r: npt.ArrayLike,
    acc_s: npt.ArrayLike,
    acc_u: npt.ArrayLike,
    acc_r: npt.ArrayLike,
    x_d: npt.ArrayLike,
) -> dict[str, float]:
    """Shock displacement and acceleration ratios over the whole record.

    ``SDR_s = max|z_s|/max|z_r|``, ``SAR_s = max|z_s''|/max|z_r''|``, ``SDR_u``,
    ``SAR_u`` likewise for the unsprung mass, and ``RDR = max|x_d|/max|z_r|``.

    Parameters
    ----------
    z_s, z_u, z_r : array_like
        Sprung, unsprung and road displacement [m], equal lengths.
    acc_s, acc_u, acc_r : array_like
        Their accelerations [m/s^2].
    x_d : array_like
        Suspension stroke ``z_u - z_s`` [m].

    Returns
    -------
    dict
        ``{"SDR_s", "SAR_s", "SDR_u", "SAR_u", "RDR"}``, dimensionless.

    Examples
    --------
    >>> zr = np.array([0.0, 0.02, 0.05, 0.02, 0.0])
    >>> ar = np.array([10.0, 0.0, -5.0, 0.0, 1.0])
    >>> r = shock_ratios(0.6 * zr, zr, zr, 0.3 * ar, -2 * ar, ar, [0.0, -0.01, 0.02, 0.0, 0.0])
    >>> {k: round(v, 6) for k, v in r.items()}
    {'SDR_s': 0.6, 'SAR_s': 0.3, 'SDR_u': 1.0, 'SAR_u': 2.0, 'RDR': 0.4}
    """
    names = ("z_s", "z_u", "z_r", "acc_s", "acc_u", "acc_r", "x_d")
    arrays = {
        k: signal(k, v)
        for k, v in zip(names, (z_s, z_u, z_r, acc_s, acc_u, acc_r, x_d), strict=True)
    }
    same_length(**arrays)
    pk = {k: float(np.max(np.abs(v))) for k, v in arrays.items()}
    for k in ("z_r", "acc_r"):
        if pk[k] == 0.0:
            raise ValidationError(f"{k} is zero over the whole record: shock ratios undefined")
    return {
        "SDR_s": pk["z_s"] / pk["z_r"],
        "SAR_s": pk["acc_s"] / pk["acc_r"],
        "SDR_u": pk["z_u"] / pk["z_r"],
        "SAR_u": pk["acc_u"] / pk["acc_r"],
        "RDR": pk["x_d"] / pk["z_r"],
    }


def dtr(
    peak_tire_force_nominal: float,
    peak_tire_force: float,
    nominal_total_mass: float,
    g: float = G,
) -> float:
    """Deviation in peak tire force ratio ``|F_T0,peak - F_T,peak| / ((m_s0 + m_u) g)``, (3.44).

    Parameters
    ----------
    peak_tire_force_nominal : float
        Peak tire force [N] of the run with the nominal sprung mass ``m_s0``.
    peak_tire_force : float
        Peak tire force [N] of the run being assessed.
    nominal_total_mass : float
        ``m_s0 + m_u`` [kg] (563 + 90 kg nominally).
    g : float, optional
        Gravitational acceleration [m/s^2], 9.81.

    Examples
    --------
    >>> round(dtr(9000.0, 8359.407, 653.0), 6)  # 640.593 N / 6405.93 N
    0.1
    """
    values = {}
    for name, value in (
        ("peak_tire_force_nominal", peak_tire_force_nominal),
        ("peak_tire_force", peak_tire_force),
    ):
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            raise ValidationError(f"{name} must be a number [N]; got {value!r}")
        if not np.isfinite(value):
            raise ValidationError(f"{name} must be finite [N]; got {value}")
        values[name] = float(value)
    mass = rate("nominal_total_mass", nominal_total_mass, "kg")
    gravity = rate("g", g, "m/s^2")
    return abs(values["peak_tire_force_nominal"] - values["peak_tire_force"]) / (mass * gravity)
